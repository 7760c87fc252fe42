//! The rasterizer: panels of flat-shaded meshes on a z-buffer, with an optional wireframe,
//! per-vertex colours through the viridis ramp with a colour bar, and a caption; several
//! panels side by side make a strip.
//!
//! Every step is sequential and in face order, so the same input gives the same pixels.
//! Meshes are drawn at twice the resolution and averaged down (anti-aliasing); text is drawn
//! at the final resolution, so it stays sharp.

use envelope_mesh::TriangleSoup;
use glam::DVec3;

use crate::camera::{Camera, Projected, View};
use crate::canvas::{Canvas, Size};
use crate::error::RenderError;
use crate::limits::MAX_PIXELS;
use crate::ramp::{normalize, viridis};
use crate::text::{self, GLYPH};

/// The page colour.
const BACKGROUND: [u8; 3] = [255, 255, 255];
/// Caption and label colour.
const INK: [u8; 3] = [40, 40, 48];
/// Front faces: a light blue-grey.
const FRONT: DVec3 = DVec3::new(0.80, 0.83, 0.88);
/// Back faces: a warm tint, so the inside of an open mesh reads as inside.
const BACK: DVec3 = DVec3::new(0.90, 0.72, 0.55);
/// Wireframe colour.
const WIRE: [u8; 3] = [35, 38, 52];
/// Light that reaches faces turned away from the lamp.
const AMBIENT: f64 = 0.18;
/// Empty border around the mesh, as a fraction of the smaller side of its area.
const MARGIN: f64 = 0.05;
/// Meshes are drawn at this many samples per pixel side, unless the panel is large.
const SUPERSAMPLE: u32 = 2;
/// Above this many pixels a panel is drawn without supersampling (memory).
const SUPERSAMPLE_MAX_PIXELS: u64 = 1 << 22;

/// One mesh to draw, with its caption and, optionally, one value per vertex to colour by.
#[derive(Clone, Copy, Debug)]
pub struct Panel<'a> {
    /// The mesh.
    pub mesh: &'a TriangleSoup,
    /// One line under the mesh (e.g. `bunny.off  4,012 faces  eps 1%`); may be empty.
    pub caption: &'a str,
    /// One value per vertex, drawn through [`viridis`](crate::ramp::viridis) from the
    /// smallest (dark) to the largest (yellow), with a colour bar; non-finite values take the
    /// low end and are left out of the bar's range.
    pub scalars: Option<&'a [f64]>,
}

/// How panels are drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Style {
    /// Where the camera looks from and how it projects.
    pub view: View,
    /// Draw the edges over the faces (depth-tested, so hidden edges stay hidden).
    pub wireframe: bool,
    /// One camera for every panel of a strip (fitted to all meshes), so that levels of
    /// detail line up; otherwise each panel is fitted to its own mesh.
    pub same_scale: bool,
}

/// One panel of `size`.
///
/// ```
/// use envelope_render::{Panel, Size, Style, render};
/// let mesh = envelope_mesh::generate::tetrahedron();
/// let panel = Panel { mesh: &mesh, caption: "tetrahedron", scalars: None };
/// let picture = render(&panel, &Style::default(), Size::new(64, 64).unwrap()).unwrap();
/// assert_eq!((picture.width(), picture.height()), (64, 64));
/// ```
pub fn render(panel: &Panel<'_>, style: &Style, size: Size) -> Result<Canvas, RenderError> {
    render_strip(std::slice::from_ref(panel), style, size)
}

/// Panels side by side, each of `size` (the picture is `n * width` x `height`).
///
/// ```
/// use envelope_render::{Panel, Size, Style, render_strip};
/// use envelope_mesh::generate::{icosphere, tetrahedron};
/// let (a, b) = (tetrahedron(), icosphere(1, 1.0));
/// let panels = [
///     Panel { mesh: &a, caption: "a", scalars: None },
///     Panel { mesh: &b, caption: "b", scalars: None },
/// ];
/// let style = Style { same_scale: true, ..Style::default() };
/// let picture = render_strip(&panels, &style, Size::new(48, 32).unwrap()).unwrap();
/// assert_eq!((picture.width(), picture.height()), (96, 32));
/// ```
pub fn render_strip(
    panels: &[Panel<'_>],
    style: &Style,
    size: Size,
) -> Result<Canvas, RenderError> {
    if panels.is_empty() {
        return Err(RenderError::NoPanels);
    }
    let (width, height) = (
        u64::from(size.width()) * panels.len() as u64,
        u64::from(size.height()),
    );
    if width * height > MAX_PIXELS || width > u64::from(u32::MAX) {
        return Err(RenderError::TooLarge { width, height });
    }
    for panel in panels {
        check(panel)?;
    }
    let shared = style.same_scale.then(|| {
        Camera::fit(
            &style.view,
            &panels.iter().map(|p| p.mesh).collect::<Vec<_>>(),
        )
    });
    let ts = text_scale(size);
    let bars: Vec<u32> = panels.iter().map(|p| bar_column(p, ts)).collect();
    // Under one camera every mesh area has the same size, so that the meshes line up.
    let widest = bars.iter().copied().max().unwrap_or(0);
    let mut picture = Canvas::blank(width as u32, size.height(), BACKGROUND);
    for (i, panel) in panels.iter().enumerate() {
        let camera = shared.unwrap_or_else(|| Camera::fit(&style.view, &[panel.mesh]));
        let bar = if style.same_scale { widest } else { bars[i] };
        let left = i as i64 * i64::from(size.width());
        picture.blit(&draw_panel(panel, style, &camera, size, bar), left, 0);
        if i > 0 {
            // A hairline between panels.
            picture.fill_rect(left, 0, 1, i64::from(size.height()), [220, 220, 224]);
        }
    }
    Ok(picture)
}

/// Refuses what cannot be drawn: out-of-range indices, non-finite coordinates, a wrong
/// number of values.
fn check(panel: &Panel<'_>) -> Result<(), RenderError> {
    let mesh = panel.mesh;
    let n = mesh.num_vertices();
    for (face, corners) in mesh.faces.iter().enumerate() {
        if let Some(v) = corners.iter().find(|v| v.index() >= n) {
            return Err(RenderError::Index {
                face,
                vertex: v.0,
                vertices: n,
            });
        }
    }
    if let Some(vertex) = mesh.positions.iter().position(|p| !p.is_finite()) {
        return Err(RenderError::NotFinite { vertex });
    }
    if let Some(s) = panel.scalars
        && s.len() != n
    {
        return Err(RenderError::Scalars {
            got: s.len(),
            vertices: n,
        });
    }
    Ok(())
}

/// The text scale for a panel: 2 on large panels, where 8-pixel text would be too small.
fn text_scale(size: Size) -> u32 {
    if size.width().min(size.height()) >= 480 {
        2
    } else {
        1
    }
}

/// The labels of a panel's colour bar, `(top, bottom)`, when it has one.
fn bar_labels(panel: &Panel<'_>) -> Option<(String, String)> {
    let (lo, hi) = panel.scalars.and_then(finite_range)?;
    Some((text::short(hi), text::short(lo)))
}

/// The width of a panel's colour-bar column (bar, gap, labels, margin); 0 without one.
fn bar_column(panel: &Panel<'_>, ts: u32) -> u32 {
    bar_labels(panel).map_or(0, |(a, b)| {
        let label = text::width(&a, ts).max(text::width(&b, ts));
        (10 + 3 + 4) * ts + label
    })
}

/// One panel: the mesh area, the colour bar (with values) in the right `bar_column` pixels,
/// and the caption.
fn draw_panel(
    panel: &Panel<'_>,
    style: &Style,
    camera: &Camera,
    size: Size,
    bar_column: u32,
) -> Canvas {
    let ts = text_scale(size);
    let (w, h) = (size.width(), size.height());
    let mut canvas = Canvas::blank(w, h, BACKGROUND);
    let caption_band = if panel.caption.is_empty() {
        0
    } else {
        (GLYPH + 6) * ts
    };
    let range = panel.scalars.and_then(finite_range);
    let labels = bar_labels(panel);
    // The mesh keeps at least a quarter of the panel when the labels are long.
    let mesh_w = w.saturating_sub(bar_column).max(w / 4).max(1);
    let mesh_h = h.saturating_sub(caption_band).max(h / 4).max(1);
    let area = draw_mesh(panel, style, camera, mesh_w, mesh_h, range);
    canvas.blit(&area, 0, 0);

    if let Some((top, bottom)) = labels {
        let s = i64::from(ts);
        let (x, y0, y1) = (i64::from(mesh_w), 6 * s, i64::from(mesh_h) - 6 * s);
        let bar_h = (y1 - y0).max(1);
        for y in y0..y1 {
            let t = 1.0 - (y - y0) as f64 / bar_h as f64;
            canvas.fill_rect(x, y, 10 * s, 1, viridis(t));
        }
        let label_x = x + 13 * s;
        canvas.text(label_x, y0, &top, ts, INK);
        canvas.text(label_x, y1 - i64::from(GLYPH * ts), &bottom, ts, INK);
    }
    if caption_band > 0 {
        let tw = i64::from(text::width(panel.caption, ts));
        // Centred when it fits, else from the left edge (the rest is clipped).
        let x = ((i64::from(w) - tw) / 2).max(i64::from(2 * ts));
        let y = i64::from(h - caption_band + 3 * ts);
        canvas.text(x, y, panel.caption, ts, INK);
    }
    canvas
}

/// The smallest and largest finite value, `None` when there is none.
fn finite_range(values: &[f64]) -> Option<(f64, f64)> {
    values
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(None, |r, v| match r {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// A z-buffered colour target.
struct Target {
    width: usize,
    height: usize,
    color: Vec<[u8; 3]>,
    depth: Vec<f64>,
}

/// The mesh on a `width` x `height` area, supersampled and averaged down.
fn draw_mesh(
    panel: &Panel<'_>,
    style: &Style,
    camera: &Camera,
    width: u32,
    height: u32,
    range: Option<(f64, f64)>,
) -> Canvas {
    let ss = if u64::from(width) * u64::from(height) <= SUPERSAMPLE_MAX_PIXELS {
        SUPERSAMPLE
    } else {
        1
    };
    let (tw, th) = ((width * ss) as usize, (height * ss) as usize);
    let mut target = Target {
        width: tw,
        height: th,
        color: vec![BACKGROUND; tw * th],
        depth: vec![f64::INFINITY; tw * th],
    };
    let mesh = panel.mesh;
    let screen: Vec<Projected> = mesh
        .positions
        .iter()
        .map(|&p| camera.project(p, tw as f64, th as f64, MARGIN))
        .collect();
    let light = camera.light();
    for face in &mesh.faces {
        let [a, b, c] = face.map(|v| v.index());
        let [pa, pb, pc] = [a, b, c].map(|i| mesh.positions[i]);
        let n = (pb - pa).cross(pc - pa);
        let Some(unit) = n.try_normalize() else {
            continue; // No area, nothing to see.
        };
        let front = camera.faces_eye(n, pa);
        let facing = if front { unit } else { -unit };
        let shade = AMBIENT + (1.0 - AMBIENT) * facing.dot(light).max(0.0);
        let values = panel.scalars.map(|s| [s[a], s[b], s[c]]);
        fill_triangle(
            &mut target,
            [screen[a], screen[b], screen[c]],
            values,
            |v| surface(v, front, shade, range),
        );
    }
    if style.wireframe {
        let (lo, hi) = screen.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
            (lo.min(p.key), hi.max(p.key))
        });
        // Lets an edge win over its own faces, whose depths it shares up to rounding.
        let bias = 2e-3 * (hi - lo).max(0.0);
        for face in &mesh.faces {
            let [a, b, c] = face.map(|v| screen[v.index()]);
            for (p, q) in [(a, b), (b, c), (c, a)] {
                draw_edge(&mut target, p, q, bias);
            }
        }
    }
    downsample(&target, ss)
}

/// The colour of a surface point: the face's tint (or the ramp at the interpolated value),
/// times its light.
fn surface(value: Option<f64>, front: bool, shade: f64, range: Option<(f64, f64)>) -> [u8; 3] {
    let tint = if front { FRONT } else { BACK };
    let base = match (value, range) {
        (Some(v), Some((lo, hi))) => {
            let c = viridis(normalize(v, lo, hi));
            let c = DVec3::new(f64::from(c[0]), f64::from(c[1]), f64::from(c[2])) / 255.0;
            // Back faces keep the ramp with a little of the back tint mixed in.
            if front { c } else { c.lerp(BACK, 0.25) }
        }
        _ => tint,
    };
    let c = base * shade * 255.0;
    [c.x, c.y, c.z].map(|v| v.round().clamp(0.0, 255.0) as u8)
}

/// Twice the signed area of `(a, b, p)` in screen coordinates.
fn edge(a: (f64, f64), b: (f64, f64), p: (f64, f64)) -> f64 {
    (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0)
}

/// Fills a triangle, depth-tested, colouring each covered sample with `color(value)` where
/// `value` is the corner `values` interpolated perspective-correctly (when there are any).
fn fill_triangle(
    target: &mut Target,
    v: [Projected; 3],
    values: Option<[f64; 3]>,
    color: impl Fn(Option<f64>) -> [u8; 3],
) {
    let p = v.map(|q| (q.x, q.y));
    let area = edge(p[0], p[1], p[2]);
    if area == 0.0 || !area.is_finite() {
        return;
    }
    let min_x = p
        .iter()
        .map(|q| q.0)
        .fold(f64::MAX, f64::min)
        .floor()
        .max(0.0) as usize;
    let min_y = p
        .iter()
        .map(|q| q.1)
        .fold(f64::MAX, f64::min)
        .floor()
        .max(0.0) as usize;
    let max_x = (p.iter().map(|q| q.0).fold(f64::MIN, f64::max).ceil() as usize).min(target.width);
    let max_y = (p.iter().map(|q| q.1).fold(f64::MIN, f64::max).ceil() as usize).min(target.height);
    for y in min_y..max_y {
        for x in min_x..max_x {
            let c = (x as f64 + 0.5, y as f64 + 0.5);
            let b = [
                edge(p[1], p[2], c) / area,
                edge(p[2], p[0], c) / area,
                edge(p[0], p[1], c) / area,
            ];
            if b.iter().any(|&t| t < 0.0) {
                continue;
            }
            let key = b[0] * v[0].key + b[1] * v[1].key + b[2] * v[2].key;
            let i = y * target.width + x;
            if key < target.depth[i] {
                target.depth[i] = key;
                let value = values.map(|s| {
                    let w = [b[0] * v[0].w, b[1] * v[1].w, b[2] * v[2].w];
                    (w[0] * s[0] + w[1] * s[1] + w[2] * s[2]) / (w[0] + w[1] + w[2])
                });
                target.color[i] = color(value);
            }
        }
    }
}

/// Draws the segment `p`-`q` where it is not behind the surface by more than `bias`.
fn draw_edge(target: &mut Target, p: Projected, q: Projected, bias: f64) {
    let length = (q.x - p.x).hypot(q.y - p.y);
    if !length.is_finite() {
        return;
    }
    // Half-sample steps: no gaps, and each sample set at most twice.
    let steps = (2.0 * length).ceil().max(1.0) as usize;
    for k in 0..=steps {
        let t = k as f64 / steps as f64;
        let (x, y) = (p.x + t * (q.x - p.x), p.y + t * (q.y - p.y));
        if x < 0.0 || y < 0.0 {
            continue;
        }
        let (x, y) = (x as usize, y as usize);
        if x >= target.width || y >= target.height {
            continue;
        }
        let key = p.key + t * (q.key - p.key);
        let i = y * target.width + x;
        if key <= target.depth[i] + bias {
            target.color[i] = WIRE;
        }
    }
}

/// Averages each `ss` x `ss` block of samples into one pixel.
fn downsample(target: &Target, ss: u32) -> Canvas {
    let ss = ss as usize;
    let (w, h) = (target.width / ss, target.height / ss);
    let mut out = Canvas::blank(w as u32, h as u32, BACKGROUND);
    let n = (ss * ss) as u32;
    for y in 0..h {
        for x in 0..w {
            let mut sum = [0u32; 3];
            for dy in 0..ss {
                for dx in 0..ss {
                    let c = target.color[(y * ss + dy) * target.width + x * ss + dx];
                    for k in 0..3 {
                        sum[k] += u32::from(c[k]);
                    }
                }
            }
            let c = sum.map(|s| ((s + n / 2) / n) as u8);
            out.set(x as i64, y as i64, c);
        }
    }
    out
}

//! `envelope render MESH... OUT.png`: pictures of meshes side by side, drawn on the CPU
//! (`envelope-render`), and the pictures of `lod --picture` and `demo`.
//!
//! Exit codes: 0 written, 2 bad arguments or unreadable input (OUT untouched). OUT is
//! checked before any mesh is read and written atomically (`crate::outputs`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use envelope::advanced::mesh::TriangleSoup;
use envelope::{Level, Mesh};
use envelope_render::plot::{Series, faces_vs_epsilon_png, faces_vs_epsilon_svg};
use envelope_render::text::{short, thousands};
use envelope_render::{Panel, Projection, Size, Style, Up, View, render_strip};

use crate::outputs::{Plan, Staging};
use crate::ranges;

/// What `lod --picture` (and `demo`) write beside the levels.
pub(crate) const LOD_PICTURES: [&str; 3] =
    ["lod.png", "faces-vs-epsilon.svg", "faces-vs-epsilon.png"];

/// The up axis of the meshes.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub(crate) enum UpArg {
    /// +Y up, front seen from +Z (most scanned models).
    Y,
    /// +Z up, front seen from -Y (CAD models).
    Z,
}

/// What colours the surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum ColorBy {
    /// A plain tint (back faces a warmer one).
    None,
    /// The per-vertex `quality` of a PLY file, through the viridis ramp with a colour bar.
    Quality,
}

/// Arguments of `envelope render`.
#[derive(clap::Args)]
#[command(override_usage = "envelope render [OPTIONS] MESH... OUT.png")]
pub(crate) struct Args {
    /// Mesh files (OBJ, OFF, PLY, STL), one panel each, left to right; the last path is the
    /// picture to write (.png).
    #[arg(required = true, num_args = 2.., value_name = "PATH")]
    paths: Vec<PathBuf>,
    /// Camera direction AZ,EL in degrees: azimuth in [-360, 360] (positive turns toward the
    /// mesh's right), elevation in [-90, 90] (positive looks from above); 0,0 is the front.
    #[arg(long, default_value = "30,20", value_parser = ranges::view, allow_hyphen_values = true)]
    view: View,
    /// Size of each panel in pixels, WxH, each side in 16..=8192; the picture is N*W x H
    /// for N meshes (64 Mi pixels at most).
    #[arg(long, default_value = "640x480", value_parser = ranges::size)]
    size: Size,
    /// The axis that points up in the picture.
    #[arg(long, value_enum, default_value_t = UpArg::Y)]
    up: UpArg,
    /// A perspective camera with this vertical field of view in degrees, (0, 180)
    /// (default: orthographic).
    #[arg(long, value_parser = ranges::fov, allow_hyphen_values = true)]
    perspective: Option<f64>,
    /// Draw the edges over the faces.
    #[arg(long)]
    wire: bool,
    /// Colour the surface by a per-vertex value.
    #[arg(long, value_enum, default_value_t = ColorBy::None)]
    color_by: ColorBy,
    /// A caption under a panel; give it once per mesh, in order (default: the file name and
    /// the number of faces).
    #[arg(long)]
    caption: Vec<String>,
    /// One camera scale for every panel (fitted to all meshes), so that panels line up.
    #[arg(long)]
    same_scale: bool,
}

/// The per-vertex quality of `mesh` (PLY vertex property `quality`, such as the bound of
/// `envelope verify --map`), one value per vertex, when its file has one: a vertex's largest
/// corner value, NaN (drawn uncoloured, outside the ramp's range) where no face uses it.
fn quality(mesh: &Mesh) -> Option<Vec<f64>> {
    let q = mesh.attributes().quality.as_ref()?;
    let mut out = vec![f64::NAN; mesh.num_vertices()];
    for (f, tri) in mesh.triangles().enumerate() {
        for (k, &v) in tri.iter().enumerate() {
            let [x] = q.value(f, k);
            let slot = &mut out[v as usize];
            *slot = if slot.is_nan() { x } else { slot.max(x) };
        }
    }
    Some(out)
}

pub(crate) fn run(args: &Args) -> Result<ExitCode, String> {
    let (out, inputs) = args
        .paths
        .split_last()
        .ok_or("give at least one mesh and the picture OUT.png")?;
    let is_png = out
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png {
        return Err(format!(
            "OUT {}: pictures are written as PNG: use .png",
            out.display()
        ));
    }
    if args.caption.len() > inputs.len() {
        return Err(format!(
            "--caption given {} times for {} meshes: give it at most once per mesh",
            args.caption.len(),
            inputs.len()
        ));
    }
    let pixels = inputs.len() as u64 * u64::from(args.size.width()) * u64::from(args.size.height());
    if pixels > envelope_render::MAX_PIXELS {
        return Err(format!(
            "--size {}x{}: {} panels of it make {pixels} pixels, more than {}; use a smaller --size",
            args.size.width(),
            args.size.height(),
            inputs.len(),
            envelope_render::MAX_PIXELS
        ));
    }
    let labels: Vec<String> = (1..=inputs.len()).map(|i| format!("MESH {i}")).collect();
    let named: Vec<(&str, &Path)> = labels
        .iter()
        .zip(inputs)
        .map(|(l, p)| (l.as_str(), p.as_path()))
        .collect();
    let mut plan = Plan::new(&named);
    plan.file("OUT", out)?;

    let mut view = args.view.with_up(match args.up {
        UpArg::Y => Up::Y,
        UpArg::Z => Up::Z,
    });
    if let Some(fov_degrees) = args.perspective {
        view = view
            .with_projection(Projection::Perspective { fov_degrees })
            .map_err(|e| format!("--perspective: {e}"))?;
    }
    let mut meshes = Vec::new();
    let mut values = Vec::new();
    for path in inputs {
        let mesh = envelope::load(path).map_err(|e| e.to_string())?;
        if args.color_by == ColorBy::Quality {
            let q = quality(&mesh).ok_or_else(|| {
                format!(
                    "{}: --color-by quality: this file has no per-vertex quality",
                    path.display()
                )
            })?;
            values.push(Some(q));
        } else {
            values.push(None);
        }
        meshes.push(mesh);
    }
    let captions: Vec<String> = inputs
        .iter()
        .zip(&meshes)
        .enumerate()
        .map(|(i, (path, mesh))| {
            args.caption.get(i).cloned().unwrap_or_else(|| {
                let name = path.file_name().map_or_else(
                    || path.display().to_string(),
                    |n| n.to_string_lossy().into_owned(),
                );
                format!("{name}  {} faces", thousands(mesh.num_faces()))
            })
        })
        .collect();
    let panels: Vec<Panel<'_>> = meshes
        .iter()
        .zip(&captions)
        .zip(&values)
        .map(|((mesh, caption), v)| Panel {
            mesh: mesh.soup(),
            caption,
            scalars: v.as_deref(),
        })
        .collect();
    let style = Style {
        view,
        wireframe: args.wire,
        same_scale: args.same_scale,
    };
    let picture = render_strip(&panels, &style, args.size).map_err(|e| e.to_string())?;
    let png = picture.to_png().map_err(|e| e.to_string())?;
    let mut staging = Staging::new();
    staging.bytes(out, &png)?;
    staging.commit()?;
    println!(
        "{}: {}x{} pixels, {} panel{}",
        out.display(),
        picture.width(),
        picture.height(),
        panels.len(),
        if panels.len() == 1 { "" } else { "s" }
    );
    Ok(ExitCode::SUCCESS)
}

/// Stages `OUTDIR/lod.png` (level 0 and every level under one camera, so they line up)
/// and the faces-against-epsilon plot of the chain as `faces-vs-epsilon.svg` and `.png`.
pub(crate) fn stage_lod_pictures(
    staging: &mut Staging,
    dir: &Path,
    label: &str,
    original: &TriangleSoup,
    levels: &[Level],
    up: Up,
) -> Result<(), String> {
    let diagonal = original.diagonal();
    let percent = |e: f64| 100.0 * e / diagonal;
    // Short enough for a 240-pixel panel: the levels' order is the strip's.
    let mut captions = vec![format!("input  {} faces", thousands(original.num_faces()))];
    captions.extend(levels.iter().map(|l| {
        format!(
            "{} faces  eps {}%",
            thousands(l.mesh.num_faces()),
            short(percent(l.cumulative))
        )
    }));
    let meshes: Vec<&TriangleSoup> = std::iter::once(original)
        .chain(levels.iter().map(|l| &l.mesh))
        .collect();
    let panels: Vec<Panel<'_>> = meshes
        .iter()
        .zip(&captions)
        .map(|(mesh, caption)| Panel {
            mesh,
            caption,
            scalars: None,
        })
        .collect();
    let style = Style {
        view: View::default().with_up(up),
        wireframe: true,
        same_scale: true,
    };
    let fail = |e: envelope_render::RenderError| format!("{}: picture: {e}", dir.display());
    let panel = Size::new(240, 240).map_err(fail)?;
    let strip = render_strip(&panels, &style, panel).map_err(fail)?;
    staging.bytes(&dir.join(LOD_PICTURES[0]), &strip.to_png().map_err(fail)?)?;

    let name = Path::new(label)
        .file_name()
        .map_or_else(|| label.to_string(), |n| n.to_string_lossy().into_owned());
    let series = [Series {
        name,
        points: levels
            .iter()
            .map(|l| (percent(l.cumulative), l.mesh.num_faces() as f64))
            .collect(),
    }];
    let title = "faces against epsilon";
    let plot = Size::new(720, 480).map_err(fail)?;
    let svg = faces_vs_epsilon_svg(title, &series, plot).map_err(fail)?;
    staging.text(&dir.join(LOD_PICTURES[1]), &svg)?;
    let png = faces_vs_epsilon_png(title, &series, plot).map_err(fail)?;
    staging.bytes(&dir.join(LOD_PICTURES[2]), &png)
}

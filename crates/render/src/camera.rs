//! Views and cameras: where the eye is (azimuth and elevation around the mesh), how it
//! projects, and the fit that puts every vertex in frame.

use envelope_mesh::TriangleSoup;
use glam::DVec3;

use crate::error::RenderError;

/// How the camera projects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Parallel rays: sizes do not change with depth (the default; levels line up).
    Orthographic,
    /// A pinhole with this vertical field of view in degrees, in (0, 180).
    Perspective {
        /// Field of view in degrees.
        fov_degrees: f64,
    },
}

/// Which axis of the mesh points up in the picture.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Up {
    /// +Y up, the front seen from +Z (most scanned models: bunny, armadillo).
    #[default]
    Y,
    /// +Z up, the front seen from -Y (CAD models, the built-in cup).
    Z,
}

/// Where the camera looks from: azimuth around the up axis and elevation above the horizon,
/// in degrees; `(0, 0)` is the front view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    azimuth: f64,
    elevation: f64,
    projection: Projection,
    up: Up,
}

impl Default for View {
    /// From the front-right and a little above, orthographic, +Y up.
    fn default() -> Self {
        View {
            azimuth: 30.0,
            elevation: 20.0,
            projection: Projection::Orthographic,
            up: Up::Y,
        }
    }
}

impl View {
    /// A view from `azimuth` (any finite angle; positive turns the eye to the mesh's right)
    /// and `elevation` (in -90..=90; positive looks from above), orthographic, +Y up.
    ///
    /// ```
    /// use envelope_render::View;
    /// assert!(View::new(30.0, 20.0).is_ok());
    /// assert!(View::new(0.0, 91.0).is_err());
    /// assert!(View::new(f64::NAN, 0.0).is_err());
    /// ```
    pub fn new(azimuth: f64, elevation: f64) -> Result<View, RenderError> {
        if !azimuth.is_finite() || !(-90.0..=90.0).contains(&elevation) {
            return Err(RenderError::View);
        }
        Ok(View {
            azimuth,
            elevation,
            ..View::default()
        })
    }

    /// The same view with another projection (a perspective's field of view must be in
    /// (0, 180) degrees).
    ///
    /// ```
    /// use envelope_render::{Projection, View};
    /// let v = View::default();
    /// assert!(v.with_projection(Projection::Perspective { fov_degrees: 30.0 }).is_ok());
    /// assert!(v.with_projection(Projection::Perspective { fov_degrees: 180.0 }).is_err());
    /// ```
    pub fn with_projection(self, projection: Projection) -> Result<View, RenderError> {
        if let Projection::Perspective { fov_degrees } = projection
            && !(fov_degrees > 0.0 && fov_degrees < 180.0)
        {
            return Err(RenderError::View);
        }
        Ok(View { projection, ..self })
    }

    /// The same view with another up axis.
    ///
    /// ```
    /// use envelope_render::{Up, View};
    /// assert_eq!(View::default().with_up(Up::Z).up(), Up::Z);
    /// ```
    #[must_use]
    pub fn with_up(self, up: Up) -> View {
        View { up, ..self }
    }

    /// The up axis.
    #[must_use]
    pub fn up(&self) -> Up {
        self.up
    }

    /// Unit vectors `(right, up, toward the eye)` of the camera, in mesh coordinates.
    fn basis(&self) -> (DVec3, DVec3, DVec3) {
        let (front, right, up) = match self.up {
            Up::Y => (DVec3::Z, DVec3::X, DVec3::Y),
            Up::Z => (DVec3::NEG_Y, DVec3::X, DVec3::Z),
        };
        let (a, e) = (self.azimuth.to_radians(), self.elevation.to_radians());
        let eye = e.cos() * (a.cos() * front + a.sin() * right) + e.sin() * up;
        // Horizontal and perpendicular to the eye's direction, even looking straight down.
        let r = a.cos() * right - a.sin() * front;
        (r, eye.cross(r), eye)
    }
}

/// A vertex on screen: position in pixels (y down), a depth key (smaller is nearer) and the
/// perspective weight (1 for orthographic) for interpolating values across a triangle.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Projected {
    pub(crate) x: f64,
    pub(crate) y: f64,
    pub(crate) key: f64,
    pub(crate) w: f64,
}

/// A camera fitted to some meshes: every vertex of them is in frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Camera {
    center: DVec3,
    right: DVec3,
    up: DVec3,
    /// Unit vector toward the eye.
    pub(crate) toward_eye: DVec3,
    /// Perspective: eye distance from `center` and `1 / tan(fov / 2)`.
    perspective: Option<(f64, f64)>,
    /// Centre of the projected extent, in view units.
    mid: (f64, f64),
    /// Width and height of the projected extent, in view units.
    extent: (f64, f64),
}

impl Camera {
    /// Fits a camera for `view` to the union of `meshes` (their bounding box and their
    /// projected extent).
    pub(crate) fn fit(view: &View, meshes: &[&TriangleSoup]) -> Camera {
        let boxes: Vec<(DVec3, DVec3)> = meshes.iter().filter_map(|m| m.bounding_box()).collect();
        let (lo, hi) = boxes
            .iter()
            .copied()
            .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)))
            .unwrap_or((DVec3::splat(-1.0), DVec3::ONE));
        let (right, up, toward_eye) = view.basis();
        let radius = 0.5 * (hi - lo).length();
        let perspective = match view.projection {
            Projection::Orthographic => None,
            Projection::Perspective { fov_degrees } => {
                let half = 0.5 * fov_degrees.to_radians();
                // Far enough that the bounding sphere is in front of the eye and in view.
                let distance = radius.max(f64::MIN_POSITIVE) / half.sin() * 1.05;
                Some((distance, 1.0 / half.tan()))
            }
        };
        let mut camera = Camera {
            center: 0.5 * (lo + hi),
            right,
            up,
            toward_eye,
            perspective,
            mid: (0.0, 0.0),
            extent: (0.0, 0.0),
        };
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for p in meshes.iter().flat_map(|m| m.positions.iter()) {
            let (x, y, _, _) = camera.view_coordinates(*p);
            (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
        }
        if x0 <= x1 && y0 <= y1 {
            camera.mid = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
            camera.extent = (x1 - x0, y1 - y0);
        }
        camera
    }

    /// View-plane coordinates (x right, y up), depth key and perspective weight of `p`.
    fn view_coordinates(&self, p: DVec3) -> (f64, f64, f64, f64) {
        let q = p - self.center;
        let (x, y, z) = (q.dot(self.right), q.dot(self.up), q.dot(self.toward_eye));
        match self.perspective {
            None => (x, y, -z, 1.0),
            Some((distance, focal)) => {
                let depth = (distance - z).max(f64::MIN_POSITIVE);
                // 1/depth is affine in screen space, so the z-buffer interpolates it exactly.
                (
                    focal * x / depth,
                    focal * y / depth,
                    -1.0 / depth,
                    1.0 / depth,
                )
            }
        }
    }

    /// `p` on a screen of `width` x `height` pixels with a margin of `margin` (a fraction
    /// of the smaller side) around the fitted extent.
    pub(crate) fn project(&self, p: DVec3, width: f64, height: f64, margin: f64) -> Projected {
        let (x, y, key, w) = self.view_coordinates(p);
        let m = margin * width.min(height);
        let sx = (width - 2.0 * m) / self.extent.0;
        let sy = (height - 2.0 * m) / self.extent.1;
        let scale = match (sx.is_finite(), sy.is_finite()) {
            (true, true) => sx.min(sy),
            (true, false) => sx,
            (false, true) => sy,
            (false, false) => 1.0,
        };
        Projected {
            x: 0.5 * width + (x - self.mid.0) * scale,
            // Screen rows grow downwards; view y grows upwards.
            y: 0.5 * height - (y - self.mid.1) * scale,
            key,
            w,
        }
    }

    /// Whether the face with (unnormalised) normal `n` through `p` faces the eye.
    pub(crate) fn faces_eye(&self, n: DVec3, p: DVec3) -> bool {
        match self.perspective {
            None => n.dot(self.toward_eye) > 0.0,
            Some((distance, _)) => n.dot(self.center + distance * self.toward_eye - p) > 0.0,
        }
    }

    /// The light's direction: a headlight from a little above and to the left of the eye,
    /// so faces square to the view still differ from their neighbours.
    pub(crate) fn light(&self) -> DVec3 {
        (self.toward_eye + 0.35 * self.up - 0.25 * self.right).normalize()
    }
}

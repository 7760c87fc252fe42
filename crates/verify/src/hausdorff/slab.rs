//! A cheap f64 filter of the candidates of a face or sub-triangle: the triangles beyond
//! `eps` along one of its separating axes (module docs of `hausdorff`, "Cells").

use glam::DVec3;

/// A triangle's separating axes (its unit normal and unit edge normals in its plane) and its
/// extent along each widened by a reach: a triangle whose extent along one axis lies
/// beyond is farther than the reach from every point of it. In f64, widened a little more
/// for roundings: a triangle dropped in error costs a proof, never a wrong one (witnesses
/// and bounds ask the tree). Axes that do not normalise are skipped.
pub(super) struct Slab {
    axes: [DVec3; 4],
    lo: [f64; 4],
    hi: [f64; 4],
}

impl Slab {
    pub(super) fn new(t: [DVec3; 3], reach: f64) -> Slab {
        let n = (t[1] - t[0]).cross(t[2] - t[0]);
        let axes = [
            n,
            n.cross(t[1] - t[0]),
            n.cross(t[2] - t[1]),
            n.cross(t[0] - t[2]),
        ]
        .map(DVec3::normalize_or_zero);
        let mag = t.iter().map(|p| p.abs().max_element()).fold(0.0, f64::max);
        let wide = reach * (1.0 + 1e-6) + mag * 1e-12;
        let mut slab = Slab {
            axes,
            lo: [f64::NEG_INFINITY; 4],
            hi: [f64::INFINITY; 4],
        };
        for k in 0..4 {
            if axes[k] != DVec3::ZERO && wide.is_finite() {
                let d = t.map(|p| axes[k].dot(p));
                slab.lo[k] = d[0].min(d[1]).min(d[2]) - wide;
                slab.hi[k] = d[0].max(d[1]).max(d[2]) + wide;
            }
        }
        slab
    }

    /// Whether `u` lies beyond the reach along one axis (then it is farther than the reach
    /// from every point of the triangle, up to the roundings the widening covers).
    pub(super) fn apart(&self, u: &[DVec3; 3]) -> bool {
        (0..4).any(|k| {
            let d = u.map(|p| self.axes[k].dot(p));
            d[0].min(d[1]).min(d[2]) > self.hi[k] || d[0].max(d[1]).max(d[2]) < self.lo[k]
        })
    }
}

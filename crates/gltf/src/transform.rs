//! Node transforms: how far a world matrix stretches lengths, and the scene's world box.

use glam::{DMat3, DMat4, DVec3};

use crate::Scene;

/// An upper bound on the spectral norm of the matrix's linear part: the largest eigenvalue of
/// `M^T M` in closed form, plus a margin far above its rounding error, and never above the
/// Frobenius norm (itself an upper bound).
pub(crate) fn max_stretch(world: &[[f64; 4]; 4]) -> f64 {
    let m = DMat3::from_mat4(DMat4::from_cols_array_2d(world));
    let a = m.transpose() * m;
    let frob2 = a.x_axis.x + a.y_axis.y + a.z_axis.z;
    if !(frob2.is_finite() && frob2 > 0.0) {
        return if frob2.is_finite() {
            0.0
        } else {
            f64::INFINITY
        };
    }
    let lambda = largest_eigenvalue(&a);
    let bound = (lambda + 1e-9 * frob2).sqrt();
    bound.min(frob2.sqrt() * (1.0 + 1e-12))
}

/// The largest eigenvalue of a symmetric 3x3 matrix (trigonometric closed form).
fn largest_eigenvalue(a: &DMat3) -> f64 {
    let (a00, a11, a22) = (a.x_axis.x, a.y_axis.y, a.z_axis.z);
    let (a01, a02, a12) = (a.y_axis.x, a.z_axis.x, a.z_axis.y);
    let p1 = a01 * a01 + a02 * a02 + a12 * a12;
    let q = (a00 + a11 + a22) / 3.0;
    if p1 == 0.0 {
        return a00.max(a11).max(a22);
    }
    let p2 = (a00 - q).powi(2) + (a11 - q).powi(2) + (a22 - q).powi(2) + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    let b = (*a - DMat3::from_diagonal(DVec3::splat(q))) * (1.0 / p);
    let r = (b.determinant() / 2.0).clamp(-1.0, 1.0);
    let phi = r.acos() / 3.0;
    q + 2.0 * p * phi.cos()
}

pub(crate) fn world_diagonal(scene: &Scene) -> f64 {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for p in scene.primitives().iter().filter(|p| p.is_triangles()) {
        let mut mats: Vec<DMat4> = scene
            .instances()
            .iter()
            .filter(|i| i.mesh == p.mesh())
            .map(|i| DMat4::from_cols_array_2d(&i.world))
            .collect();
        if mats.is_empty() {
            mats.push(DMat4::IDENTITY);
        }
        for m in mats {
            for &v in &p.soup().positions {
                let w = m.transform_point3(v);
                lo = lo.min(w);
                hi = hi.max(w);
            }
        }
    }
    if lo.x <= hi.x {
        (hi - lo).length()
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    #[test]
    fn stretch_of_scale_and_rotation() {
        let m = DMat4::from_scale_rotation_translation(
            DVec3::new(2.0, 3.0, 0.5),
            DQuat::from_rotation_y(0.7),
            DVec3::new(5.0, 0.0, 1.0),
        );
        let s = max_stretch(&m.to_cols_array_2d());
        assert!((3.0..3.0 + 1e-6).contains(&s), "{s}");
        let r = DMat4::from_quat(DQuat::from_rotation_x(1.1));
        let s = max_stretch(&r.to_cols_array_2d());
        assert!((1.0..1.0 + 1e-6).contains(&s), "{s}");
        // Shear: the closed form against a sampled maximum.
        let shear = DMat4::from_cols_array(&[
            1.0, 0.0, 0.0, 0.0, 2.0, 1.0, 0.0, 0.0, 0.0, 0.5, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
        ]);
        let s = max_stretch(&shear.to_cols_array_2d());
        let m3 = DMat3::from_mat4(shear);
        let mut best: f64 = 0.0;
        for i in 0..200 {
            for j in 0..100 {
                let (t, f) = (i as f64 * 0.0314159, j as f64 * 0.0314159);
                let v = DVec3::new(f.sin() * t.cos(), f.sin() * t.sin(), f.cos());
                best = best.max((m3 * v).length());
            }
        }
        assert!(s >= best && s < best * 1.01, "{s} {best}");
    }
}

//! Morton (Z-order) keys: the numerical method's renumbering (close in space, close in
//! memory).
use envelope_predicates::bvh::Aabb;
use glam::DVec3;

/// Morton (Z-order) key of `p` in the box `b`, 21 bits per axis.
pub(crate) fn morton(p: DVec3, b: &Aabb) -> u64 {
    let spread = |x: u64| {
        let mut x = x & 0x1f_ffff;
        x = (x | x << 32) & 0x1f_0000_0000_ffff;
        x = (x | x << 16) & 0x1f_0000_ff00_00ff;
        x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
        x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
        (x | x << 2) & 0x1249_2492_4924_9249
    };
    let ext = (b.max - b.min).max(DVec3::splat(f64::MIN_POSITIVE));
    let q = ((p - b.min) / ext * 2_097_151.0).clamp(DVec3::ZERO, DVec3::splat(2_097_151.0));
    spread(q.x as u64) | spread(q.y as u64) << 1 | spread(q.z as u64) << 2
}

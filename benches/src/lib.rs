//! Shared helpers for the benchmarks.
#![forbid(unsafe_code)]

use glam::DVec3;

/// xorshift64*: deterministic inputs without extra dependencies.
pub struct Rng(pub u64);

impl Rng {
    /// A double in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A point in the unit cube.
    pub fn point(&mut self) -> DVec3 {
        DVec3::new(self.unit(), self.unit(), self.unit())
    }
}

/// An epsilon given as a percentage of the bounding-box diagonal (`1/64%`, `0.5%`): the
/// label as given and the fraction (`0.5%` is `0.005`); `None` unless finite and positive.
///
/// ```
/// assert_eq!(envelope_benches::parse_epsilon("1/4%"), Some(("1/4%".into(), 0.0025)));
/// assert_eq!(envelope_benches::parse_epsilon("0.5"), None);
/// ```
#[must_use]
pub fn parse_epsilon(s: &str) -> Option<(String, f64)> {
    let p = s.strip_suffix('%')?;
    let v = match p.split_once('/') {
        Some((a, b)) => a.parse::<f64>().ok()? / b.parse::<f64>().ok()?,
        None => p.parse::<f64>().ok()?,
    };
    (v.is_finite() && v > 0.0).then(|| (s.to_string(), v / 100.0))
}

/// What meshoptimizer's `simplify` gave: its f32 positions (as it takes them), the kept
/// triangles' indices into them, the seconds of the call alone and the error it reports.
pub struct MeshoptRun {
    /// The input's positions rounded to f32.
    pub positions: Vec<[f32; 3]>,
    /// Three indices per kept triangle.
    pub indices: Vec<u32>,
    /// Seconds of the `simplify` call alone.
    pub seconds: f64,
    /// meshoptimizer's own error estimate (absolute).
    pub error: f32,
}

/// meshoptimizer's `simplify` of `soup` to 0 triangles under absolute error `eps`
/// (`SimplifyOptions::ErrorAbsolute`): the speed ceiling the peers and scale benches
/// measure, with no guarantee.
///
/// # Errors
/// meshoptimizer's refusal of the vertex data, as text.
pub fn meshopt_simplify(
    soup: &envelope_mesh::TriangleSoup,
    eps: f64,
) -> Result<MeshoptRun, String> {
    #[allow(clippy::cast_possible_truncation)]
    let positions: Vec<[f32; 3]> = soup
        .positions
        .iter()
        .map(|p| [p.x as f32, p.y as f32, p.z as f32])
        .collect();
    let input: Vec<u32> = soup.faces.iter().flat_map(|f| f.map(|v| v.0)).collect();
    let bytes = meshopt::utilities::typed_to_bytes(&positions);
    let adapter = meshopt::VertexDataAdapter::new(bytes, 12, 0).map_err(|e| e.to_string())?;
    let t = std::time::Instant::now();
    let mut error = 0f32;
    #[allow(clippy::cast_possible_truncation)]
    let indices = meshopt::simplify(
        &input,
        &adapter,
        0,
        eps as f32,
        meshopt::SimplifyOptions::ErrorAbsolute,
        Some(&mut error),
    );
    let seconds = t.elapsed().as_secs_f64();
    Ok(MeshoptRun {
        positions,
        indices,
        seconds,
        error,
    })
}

/// One step of Loop subdivision (Loop 1987): every face split in four, new edge points at
/// 3/8 of the edge's ends and 1/8 of the two opposite corners, old vertices moved to
/// `(1 - n beta) v + beta * sum(neighbours)` with Warren's `beta = 3 / (8 n)` (`3/16` at
/// valence 3). Border edges take their midpoint and border vertices `3/4 v + 1/8` of their two
/// border neighbours (the border stays a cubic B-spline curve). Edges with more than two
/// faces count as borders. Used to make the scale series' large inputs from corpus meshes,
/// as the 1,074,744-face head of issue 36 was made (a scan, subdivided once).
#[must_use]
pub fn loop_subdivide(soup: &envelope_mesh::TriangleSoup) -> envelope_mesh::TriangleSoup {
    use envelope_mesh::VertexId;
    use std::collections::HashMap;
    let nv = soup.positions.len();
    // Edge -> (new vertex index, opposite corners, face count).
    // In first-seen order, so the sums below are the same on every run.
    let mut order: Vec<(u32, u32)> = Vec::with_capacity(soup.faces.len() * 3 / 2 + 16);
    let mut edges: HashMap<(u32, u32), (u32, [u32; 2], u32)> =
        HashMap::with_capacity(soup.faces.len() * 3 / 2 + 16);
    let mut next = u32::try_from(nv).expect("fewer than 2^32 vertices");
    for f in &soup.faces {
        let v = f.map(|x| x.0);
        for k in 0..3 {
            let (a, b, c) = (v[k], v[(k + 1) % 3], v[(k + 2) % 3]);
            let key = (a.min(b), a.max(b));
            let e = edges.entry(key).or_insert_with(|| {
                order.push(key);
                next += 1;
                (next - 1, [u32::MAX; 2], 0)
            });
            if e.2 < 2 {
                e.1[e.2 as usize] = c;
            }
            e.2 += 1;
        }
    }
    let p = &soup.positions;
    let mut positions = vec![DVec3::ZERO; next as usize];
    // Old vertices: interior neighbour sums and border neighbours.
    let mut sum = vec![DVec3::ZERO; nv];
    let mut valence = vec![0u32; nv];
    let mut border: Vec<Vec<u32>> = vec![Vec::new(); nv];
    for &(a, b) in &order {
        let (new, opp, count) = edges[&(a, b)];
        let (pa, pb) = (p[a as usize], p[b as usize]);
        sum[a as usize] += pb;
        sum[b as usize] += pa;
        valence[a as usize] += 1;
        valence[b as usize] += 1;
        positions[new as usize] = if count == 2 {
            (pa + pb) * 0.375 + (p[opp[0] as usize] + p[opp[1] as usize]) * 0.125
        } else {
            border[a as usize].push(b);
            border[b as usize].push(a);
            (pa + pb) * 0.5
        };
    }
    for i in 0..nv {
        positions[i] = match border[i].as_slice() {
            [] if valence[i] > 0 => {
                let n = f64::from(valence[i]);
                let beta = if valence[i] == 3 {
                    3.0 / 16.0
                } else {
                    3.0 / (8.0 * n)
                };
                p[i] * (1.0 - n * beta) + sum[i] * beta
            }
            [a, b] => p[i] * 0.75 + (p[*a as usize] + p[*b as usize]) * 0.125,
            // Isolated, or a corner of several borders: kept in place.
            _ => p[i],
        };
    }
    let mut faces = Vec::with_capacity(soup.faces.len() * 4);
    for f in &soup.faces {
        let v = f.map(|x| x.0);
        let m = |a: u32, b: u32| edges[&(a.min(b), a.max(b))].0;
        let (ab, bc, ca) = (m(v[0], v[1]), m(v[1], v[2]), m(v[2], v[0]));
        for t in [[v[0], ab, ca], [ab, v[1], bc], [ca, bc, v[2]], [ab, bc, ca]] {
            faces.push(t.map(VertexId));
        }
    }
    envelope_mesh::TriangleSoup::new(positions, faces)
}

#[cfg(test)]
mod tests {
    use super::loop_subdivide;
    use envelope_mesh::{analyze, generate};

    #[test]
    fn loop_subdivision_quadruples_faces_and_keeps_the_topology() {
        for soup in [
            generate::icosphere(1, 1.0),
            generate::torus(1.0, 0.3, 12, 8),
        ] {
            let t0 = analyze(&soup);
            let fine = loop_subdivide(&soup);
            let t1 = analyze(&fine);
            assert_eq!(fine.faces.len(), 4 * soup.faces.len());
            // V' = V + E, and E = 3F/2 on a closed mesh.
            assert_eq!(
                fine.positions.len(),
                soup.positions.len() + 3 * soup.faces.len() / 2
            );
            assert_eq!((t1.genus, t1.manifold), (t0.genus, true));
        }
        // On a sphere the limit surface shrinks inside: every new point is within the
        // unit ball and none at its centre.
        let fine = loop_subdivide(&generate::icosphere(2, 1.0));
        for p in &fine.positions {
            assert!(p.length() <= 1.0 + 1e-12 && p.length() > 0.9, "{p}");
        }
    }

    #[test]
    fn loop_subdivision_smooths_an_open_border_along_itself() {
        let cyl = generate::open_cylinder(1.0, 1.0, 16, 4);
        let fine = loop_subdivide(&cyl);
        assert_eq!(fine.faces.len(), 4 * cyl.faces.len());
        let t = analyze(&fine);
        assert_eq!(t.num_border_loops(), 2);
        // Border points stay on their rim's plane (z = 0 or z = 1).
        let on_rim = fine
            .positions
            .iter()
            .filter(|p| p.z.abs() < 1e-12 || (p.z - 1.0).abs() < 1e-12)
            .count();
        assert_eq!(on_rim, 2 * 2 * 16);
    }
}

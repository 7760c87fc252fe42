//! Filling what the L-infinity closing swallows (issue 37): the driver of
//! [`crate::TessellationSource::Closing`], run after the sharp-edge step on inputs without
//! borders (the closing needs a solid).
//!
//! El-Sana and Varshney fill what the cube of side `2 alpha` cannot reach. [`crate::closing`]
//! estimates, on voxels, which faces that is; here the swallowed faces are cut into regions
//! (connected across edges) and each region with two or more boundary loops (a tunnel, a
//! network of tunnels) is replaced by caps over its loops. What keeps the guarantees is
//! exact and shared with [`crate::reduce_genus`]: every cap passes the alpha test (diagonals
//! within the cube, triangles inside their corners' cubes, no fold over the kept face), and
//! the output is validated with `envelope-check` against the input's counts. A cap takes no
//! diagonal on an edge a kept face still uses (non-manifold: the validation would refuse
//! it after the whole round was assembled). A loop refused as wider than the cube is tried
//! again with points on its long edges ([`crate::steiner`]), its input faces there split.
//!
//! **Peeling (our choice; the paper has one region per rim).** On real parts the closing's
//! boundary is ragged where a pocket or a groove wider than a tunnel meets the network, and
//! one region can hold a whole network of tunnels. A region is filled only if every one of
//! its loops gets a cap, so where a loop is refused (by the alpha test, or by the validation
//! for a cap that crosses or duplicates something) the region's faces at that loop go back to
//! the kept side and its new loops are tried, up to [`PEEL_ROUNDS`] times; at the last round
//! a region still refused is kept whole. A tunnel whose mouth cannot be capped is so kept up
//! to where it joins the rest of its network, which is capped there.
//!
//! **Cells (our choice).** The voxels' answer is ragged where it changes: strips of a tunnel
//! wall near a wide opening come out kept; and peeling a layer of faces at a time from a
//! refused loop merges the fronts of neighbouring tunnels, whose walls are single long
//! triangles, into ever longer loops until whole networks go back. So the surface is also cut along its edges sharper than an angle
//! into *cells* (a tunnel's wall between its junctions, a flat face): a cell at least
//! [`CELL_SNAP`] swallowed (by area) at the first of [`CELL_BETAS`] is swallowed whole, and
//! peeling gives back, with each face at a refused loop, its cell at the first angle where
//! that cell is at most half of its region (finer angles split the walls of a coarse,
//! simplified tunnel network that a coarser one leaves joined). The new loops are then the
//! cells' sharp junction curves, which cap. A face whose cell is more than half its region at
//! every angle (a smooth part) peels alone, as before.
//!
//! **Levels.** The closing is taken at `alpha`, then at [`LEVELS`] of it on the result: a
//! region refused at the full radius (its loops too wide) often fills at a smaller one, where
//! the closing's boundary runs deeper inside the tunnels. Every cap's corners are input
//! vertices or points on input edges (split faces are never split again), so every cap of
//! every level lies in the union of the input's alpha-prisms.

use std::cell::OnceCell;
use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};

use envelope_check::DegeneracyClass;
use envelope_mesh::{FaceId, TriangleSoup, VertexId};
use glam::DVec3;

use crate::rim::{Candidate, Capped, Edge, cap_avoiding, split_simple};
use crate::steiner::{Refined, refine};
use crate::tessellation::{EdgeMap, border_edges, face_normals, patches, tessellation_edges};
use crate::union::{cut_edges, fill_islands, patch_rims};
use crate::validation::{Fill, class_counts, new_findings};

/// Fractions of `alpha` at which the closing is taken, in order, each on the previous result.
pub(crate) const LEVELS: [f64; 3] = [1.0, 0.75, 0.5];

/// Dihedral angles, in degrees, past which an edge bounds a cell, coarsest first (see the
/// module docs): low enough that the walls of two crossing tunnels part at their junction.
pub(crate) const CELL_BETAS: [f64; 5] = [40.0, 35.0, 30.0, 25.0, 20.0];

/// Fraction of its area past which the closing's answer for most of a cell is taken for all
/// of it (see the module docs).
pub(crate) const CELL_SNAP: f64 = 0.8;

/// Where a face of the step's current surface comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Origin {
    /// An input face.
    Input,
    /// A cap, of this step or already of its input.
    Cap,
    /// A piece of an input face split at points of a cap's loop ([`crate::steiner`]).
    Piece,
}

/// Rounds of peeling per level.
pub(crate) const PEEL_ROUNDS: usize = 48;

/// What [`fill_closing`] did.
#[derive(Debug, Default)]
pub(crate) struct Filled {
    /// The result: the input's positions, the kept faces in order, then the caps.
    pub soup: TriangleSoup,
    /// Which faces of `soup` are caps, of this step or already of the input (`added_in`).
    pub added: Vec<usize>,
    /// Which faces of `soup` are pieces of input faces split at points of a cap's loop
    /// ([`crate::steiner`]).
    pub pieces: Vec<usize>,
    /// Input faces split into pieces (some of them may be gone since, swallowed at a later
    /// level).
    pub split_faces: usize,
    /// Caps over the closing's loops.
    pub caps: usize,
    /// Faces swallowed by the closing at the full radius, before peeling.
    pub swallowed: usize,
    /// Distinct loops tried.
    pub loops_tried: usize,
    /// Distinct loops refused by the alpha test for their shape, or as wider than the cube.
    pub refused_shape: usize,
    /// See `refused_shape`.
    pub refused_wide: usize,
    /// Caps refused by the validation.
    pub refused_validation: usize,
}

/// Fills the regions the closing of `soup` swallows at each of [`LEVELS`] (see the module
/// docs). `added_in` marks the faces of `soup` that are already caps; `baseline` holds (or
/// takes, when a first output is validated) the original input's counts of the validated
/// classes; `outward` is the input's orientation (the sign of its signed volume).
pub(crate) fn fill_closing(
    soup: &TriangleSoup,
    added_in: &[bool],
    alpha: f64,
    baseline: &OnceCell<HashMap<DegeneracyClass, usize>>,
    input: &TriangleSoup,
    outward: bool,
) -> Filled {
    let border_edges = border_edges(&EdgeMap::new(soup)).len();
    let sign = if outward { 1.0 } else { -1.0 };
    let mut cur = soup.clone();
    let mut origin: Vec<Origin> = added_in
        .iter()
        .map(|&cap| if cap { Origin::Cap } else { Origin::Input })
        .collect();
    let mut done = Filled::default();
    let mut tried: HashMap<Vec<(VertexId, VertexId)>, Option<bool>> = HashMap::new();
    for (level, &frac) in LEVELS.iter().enumerate() {
        let Some(mut swallowed) = crate::closing::swallowed_faces(&cur, alpha * frac, outward)
        else {
            break;
        };
        if !swallowed.contains(&true) {
            continue; // nothing the cube cannot reach at this radius
        }
        let edges = EdgeMap::new(&cur);
        let normals = face_normals(&cur);
        // The cells at the first angle; the finer ones when peeling first needs them.
        let mut cells: Vec<Vec<usize>> = vec![cells_of(&cur, &edges, &normals, CELL_BETAS[0])];
        snap_to_cells(&cur, &cells[0], &mut swallowed);
        fill_islands(&cur, &edges, &mut swallowed, true);
        if level == 0 {
            done.swallowed = swallowed.iter().filter(|&&s| s).count();
        }
        // Cap or refusal of each loop (vertices, kept faces) met at this level.
        let mut memo: HashMap<(Vec<VertexId>, Vec<FaceId>), Capped> = HashMap::new();
        let mut memo_refined: HashMap<(Vec<VertexId>, Vec<FaceId>), Option<Refined>> =
            HashMap::new();
        for round in 0..PEEL_ROUNDS {
            let last = round + 1 == PEEL_ROUNDS;
            let cut = cut_edges(&edges, &swallowed);
            let pat = patches(&cur, &edges, &cut);
            // A region with fewer than two loops (a pocket, or a whole shell) is not filled:
            // it goes back whole (no other region shares an edge with it, so theirs stay).
            let mut open = vec![false; pat.count];
            for (p, loops) in pat.loops.iter().enumerate() {
                open[p] = loops.len() < 2;
            }
            for (f, s) in swallowed.iter_mut().enumerate() {
                let p = pat.of_face[f];
                if *s && p != usize::MAX && open[p] {
                    *s = false;
                }
            }
            // Per region refused, the vertices of its refused loops.
            let mut give_back: HashMap<usize, HashSet<VertexId>> = HashMap::new();
            let mut caps: Vec<(usize, Candidate)> = Vec::new();
            // The refined caps of this round (by index in `caps`), their points (numbered
            // after `cur`'s positions) and the faces they split.
            let mut refined: HashMap<usize, Refined> = HashMap::new();
            let mut points: Vec<DVec3> = Vec::new();
            let mut split: HashSet<FaceId> = HashSet::new();
            // An edge with a face that stays: no cap may take it as a diagonal.
            let kept_edge = |a: VertexId, b: VertexId| {
                edges
                    .faces
                    .get(&(a.min(b), a.max(b)))
                    .is_some_and(|fs| fs.iter().any(|(f, _)| !swallowed[f.index()]))
            };
            for (p, lp, rim) in patch_rims(&edges, &swallowed, &pat) {
                let pieces = rim.map(|(v, f)| split_simple(&v, &f)).unwrap_or_default();
                // A piece dropped by the split (a slit) would leave its edges open.
                let mut fine = pieces.iter().map(|(v, _)| v.len()).sum::<usize>() == lp.len();
                for (mut v, mut f) in pieces {
                    // Rotated to start at the least vertex, so a loop met again is cached.
                    let first = (0..v.len()).min_by_key(|&i| v[i]).unwrap_or(0);
                    v.rotate_left(first);
                    f.rotate_left(first);
                    let mut c = Candidate::rim(v, f);
                    let result = memo
                        .entry((c.vertices.clone(), c.keep.clone()))
                        .or_insert_with(|| cap_avoiding(&cur, &c, alpha, &kept_edge))
                        .clone();
                    match result {
                        Ok(cap) => {
                            tried.entry(c.key.clone()).or_insert(None);
                            c.cap = cap;
                            caps.push((p, c));
                        }
                        Err((_, shape)) => {
                            // Wider than the cube along long edges: points on them may
                            // let a cap pass ([`crate::steiner`]); only input faces split,
                            // each by one cap.
                            let splittable = |f: FaceId| {
                                origin[f.index()] == Origin::Input && !split.contains(&f)
                            };
                            let r = if shape {
                                None
                            } else {
                                memo_refined
                                    .entry((c.vertices.clone(), c.keep.clone()))
                                    .or_insert_with(|| {
                                        refine(&cur, &c, alpha, splittable, &kept_edge)
                                    })
                                    .as_ref()
                                    .filter(|r| r.split.iter().all(|(f, _)| splittable(*f)))
                                    .map(|r| r.shifted(points.len()))
                            };
                            if let Some(r) = r {
                                tried.entry(c.key.clone()).or_insert(None);
                                points.extend(&r.points);
                                split.extend(r.split.iter().map(|(f, _)| *f));
                                c.cap.clone_from(&r.cap);
                                refined.insert(caps.len(), r);
                                caps.push((p, c));
                            } else {
                                tried.insert(c.key.clone(), Some(shape));
                                fine = false;
                            }
                        }
                    }
                }
                if !fine {
                    give_back.entry(p).or_default().extend(lp);
                }
            }
            let mut whole: HashSet<usize> = HashSet::new();
            // A region whose caps would take material away goes back whole.
            let n_old = cur.positions.len();
            let position = |v: VertexId| {
                if v.index() < n_old {
                    cur.position(v)
                } else {
                    points[v.index() - n_old]
                }
            };
            for p in shrinking_regions(&cur, &swallowed, &pat.of_face, &caps, sign, &position) {
                give_back.entry(p).or_default();
                whole.insert(p);
            }
            if give_back.is_empty() {
                if caps.is_empty() {
                    break;
                }
                let cands: Vec<Candidate> = caps.iter().map(|(_, c)| c.clone()).collect();
                let (out, out_origin, cap_of_face) =
                    assemble(&cur, &origin, &swallowed, &split, &cands, &refined, &points);
                let base = baseline.get_or_init(|| class_counts(input));
                match blame(&out, &cap_of_face, base, border_edges) {
                    None => {
                        origin = out_origin;
                        done.caps += cands.len();
                        done.split_faces += split.len();
                        cur = out;
                        break;
                    }
                    Some((bad, at)) => {
                        done.refused_validation += bad.len();
                        // A finding on kept faces only (a vertex pinched between two
                        // regions): the regions at its vertices give way there.
                        for (f, &p) in pat.of_face.iter().enumerate() {
                            if swallowed[f] && cur.faces[f].iter().any(|v| at.contains(v)) {
                                give_back.entry(p).or_default().extend(at.iter().copied());
                                if last {
                                    whole.insert(p);
                                }
                            }
                        }
                        for &i in &bad {
                            let (p, c) = &caps[i];
                            give_back
                                .entry(*p)
                                .or_default()
                                .extend(c.vertices.iter().copied());
                            if last {
                                whole.insert(*p);
                            }
                        }
                        if give_back.is_empty() {
                            break; // nothing to give way: leave this level's regions as they are
                        }
                    }
                }
            } else if last {
                whole.extend(give_back.keys().copied());
            }
            // The regions' faces at their refused loops go back to the kept side, each with
            // its coarsest cell that is at most half its region (whole regions at the last
            // round).
            if cells.len() < CELL_BETAS.len() {
                cells.extend(
                    CELL_BETAS[1..]
                        .iter()
                        .map(|&b| cells_of(&cur, &edges, &normals, b)),
                );
            }
            let at_loop = |f: FaceId| {
                let p = pat.of_face[f.index()];
                swallowed[f.index()]
                    && give_back
                        .get(&p)
                        .is_some_and(|vs| cur.faces[f.index()].iter().any(|v| vs.contains(v)))
            };
            let mut region_size: HashMap<usize, usize> = HashMap::new();
            let mut cell_size: HashMap<(usize, usize), usize> = HashMap::new();
            for f in cur.face_ids().filter(|f| swallowed[f.index()]) {
                *region_size.entry(pat.of_face[f.index()]).or_default() += 1;
                for (l, of) in cells.iter().enumerate() {
                    *cell_size.entry((l, of[f.index()])).or_default() += 1;
                }
            }
            let mut back_cells: HashSet<(usize, usize)> = HashSet::new();
            for f in cur.face_ids().filter(|&f| at_loop(f)) {
                let half = region_size[&pat.of_face[f.index()]] / 2;
                let small = (0..cells.len())
                    .map(|l| (l, cells[l][f.index()]))
                    .find(|&(l, c)| c != usize::MAX && cell_size[&(l, c)] <= half);
                back_cells.extend(small);
            }
            let back: Vec<FaceId> = cur
                .face_ids()
                .filter(|&f| {
                    let p = pat.of_face[f.index()];
                    swallowed[f.index()]
                        && (at_loop(f)
                            || whole.contains(&p)
                            || (0..cells.len())
                                .any(|l| back_cells.contains(&(l, cells[l][f.index()]))))
                })
                .collect();
            for f in back {
                swallowed[f.index()] = false;
            }
        }
    }
    done.loops_tried = tried.len();
    for refusal in tried.values().flatten() {
        if *refusal {
            done.refused_shape += 1;
        } else {
            done.refused_wide += 1;
        }
    }
    let of = |o: Origin| (0..cur.num_faces()).filter(|&f| origin[f] == o).collect();
    done.added = of(Origin::Cap);
    done.pieces = of(Origin::Piece);
    done.soup = cur;
    done
}

/// The cell of every face (`usize::MAX` for a face with a repeated vertex): the surface cut
/// along its edges sharper than `beta` degrees (between the faces' `normals`) and its
/// border edges.
fn cells_of(
    soup: &TriangleSoup,
    edges: &EdgeMap,
    normals: &[Option<DVec3>],
    beta: f64,
) -> Vec<usize> {
    let sharp: HashSet<Edge> = tessellation_edges(edges, normals, beta)
        .into_iter()
        .collect();
    patches(soup, edges, &sharp).of_face
}

/// Takes the closing's answer for most of a cell for all of it (see the module docs); the
/// areas are f64 and only weigh a proposal.
fn snap_to_cells(soup: &TriangleSoup, cells: &[usize], swallowed: &mut [bool]) {
    let mut area: HashMap<usize, [f64; 2]> = HashMap::new();
    for f in soup.face_ids() {
        let [a, b, c] = soup.triangle(f);
        area.entry(cells[f.index()]).or_default()[usize::from(swallowed[f.index()])] +=
            (b - a).cross(c - a).length();
    }
    for (f, s) in swallowed.iter_mut().enumerate() {
        let c = cells[f];
        let [kept, gone] = area[&c];
        if c == usize::MAX || kept + gone <= 0.0 {
            continue;
        }
        if gone >= CELL_SNAP * (kept + gone) {
            *s = true;
        }
    }
}

/// The regions whose caps in `caps` would take material away from the solid (see
/// [`Fill::takes_material`]); `sign` is the input's orientation.
fn shrinking_regions(
    soup: &TriangleSoup,
    swallowed: &[bool],
    region_of: &[usize],
    caps: &[(usize, Candidate)],
    sign: f64,
    position: &dyn Fn(VertexId) -> DVec3,
) -> BTreeSet<usize> {
    let mut fills: BTreeMap<usize, Fill> = BTreeMap::new();
    for (p, c) in caps {
        let added = &mut fills.entry(*p).or_default().caps;
        added.extend(c.cap.iter().map(|t| t.map(position)));
    }
    for f in soup.face_ids().filter(|f| swallowed[f.index()]) {
        if let Some(fill) = fills.get_mut(&region_of[f.index()]) {
            fill.removed.push(soup.triangle(f));
        }
    }
    fills
        .into_iter()
        .filter(|(_, fill)| fill.takes_material(sign))
        .map(|(p, _)| p)
        .collect()
}

/// `None` when `out` has no more findings of the validated classes than `baseline`;
/// otherwise the caps involved in new findings and the vertices of the findings that involve
/// no cap.
fn blame(
    out: &TriangleSoup,
    cap_of_face: &HashMap<usize, usize>,
    baseline: &HashMap<DegeneracyClass, usize>,
    baseline_borders: usize,
) -> Option<(HashSet<usize>, HashSet<VertexId>)> {
    let found = new_findings(out, baseline);
    let (mut caps, mut at) = (HashSet::new(), HashSet::new());
    let mut any = found.is_some();
    for e in found.iter().flatten() {
        at.extend(e.vertex);
        let blamed: Vec<usize> = e
            .faces
            .iter()
            .filter_map(|f| cap_of_face.get(&f.index()).copied())
            .collect();
        if blamed.is_empty() {
            at.extend(e.faces.iter().flat_map(|f| out.faces[f.index()]));
        }
        caps.extend(blamed);
    }
    let open = border_edges(&EdgeMap::new(out));
    if open.len() > baseline_borders {
        any = true;
        at.extend(open.iter().flat_map(|&(a, b)| [a, b]));
    }
    any.then_some((caps, at))
}

/// `soup` without its swallowed faces and the faces in `split`, with after the kept faces
/// each candidate's pieces of split faces (from `refined`, by candidate) and its caps; the
/// origin of every face of the result (`origin`: of `soup`'s), and the candidate of each new
/// one. `points` are the refined caps' points, numbered after `soup`'s positions.
fn assemble(
    soup: &TriangleSoup,
    origin: &[Origin],
    swallowed: &[bool],
    split: &HashSet<FaceId>,
    cands: &[Candidate],
    refined: &HashMap<usize, Refined>,
    points: &[DVec3],
) -> (TriangleSoup, Vec<Origin>, HashMap<usize, usize>) {
    let (mut faces, mut out_origin): (Vec<[VertexId; 3]>, Vec<Origin>) = soup
        .face_ids()
        .filter(|f| !swallowed[f.index()] && !split.contains(f))
        .map(|f| (soup.faces[f.index()], origin[f.index()]))
        .unzip();
    let mut cap_of_face = HashMap::new();
    for (i, c) in cands.iter().enumerate() {
        let fans = refined.get(&i).map_or(&[][..], |r| &r.split[..]);
        let pieces = fans
            .iter()
            .flat_map(|(_, fan)| fan)
            .map(|t| (t, Origin::Piece));
        for (t, o) in pieces.chain(c.cap.iter().map(|t| (t, Origin::Cap))) {
            cap_of_face.insert(faces.len(), i);
            faces.push(*t);
            out_origin.push(o);
        }
    }
    let mut positions = soup.positions.clone();
    positions.extend_from_slice(points);
    (TriangleSoup::new(positions, faces), out_origin, cap_of_face)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cell_mostly_swallowed_is_swallowed_whole_and_no_cell_is_kept_for_its_majority() {
        // A plate with one hole: its flat top is one cell of several faces.
        let plate = crate::testmeshes::plate_with_square_holes(&[1], 1, 1.0);
        let edges = EdgeMap::new(&plate);
        let cells = cells_of(&plate, &edges, &face_normals(&plate), CELL_BETAS[0]);
        let top = cells[0];
        let in_top: Vec<usize> = (0..cells.len()).filter(|&f| cells[f] == top).collect();
        assert!(
            in_top.len() >= 6,
            "{} faces in the first cell",
            in_top.len()
        );
        assert!(
            in_top.len() < cells.len(),
            "the plate is more than one cell"
        );
        // All but one face of the cell swallowed: the cell is swallowed whole, nothing else.
        let mut swallowed = vec![false; cells.len()];
        for &f in &in_top[1..] {
            swallowed[f] = true;
        }
        snap_to_cells(&plate, &cells, &mut swallowed);
        for (f, &s) in swallowed.iter().enumerate() {
            assert_eq!(s, cells[f] == top, "face {f}");
        }
        // One face of it: nothing changes (the closing may swallow a minority of a smooth
        // cell, as the inner band of a torus).
        let mut swallowed = vec![false; cells.len()];
        swallowed[in_top[0]] = true;
        let before = swallowed.clone();
        snap_to_cells(&plate, &cells, &mut swallowed);
        assert_eq!(swallowed, before);
    }
}

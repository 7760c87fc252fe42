//! A bounding-volume hierarchy over axis-aligned boxes, with conservative box arithmetic.
//!
//! Boxes built from input points are exact (their bounds are input coordinates). Constructed
//! boxes (inflated by a tolerance) are rounded outward, and distance bounds are rounded down,
//! so every box test is conservative: it may report extra candidates, never miss one.
//!
//! Build: median split of item-box centres along the widest axis, `O(n log n)`, the top levels
//! in parallel (rayon). Leaves hold up to [`LEAF_SIZE`] items. Item ids are `u32` indices into
//! the slice of boxes the tree was built from.

use glam::DVec3;

use crate::range::{next_down, next_up};

/// Maximum number of items per leaf. 8 rather than 4: fewer node pairs walked for as many
/// box tests at the leaves. Same outputs: a tree's shape decides where to look, never what
/// is found.
pub const LEAF_SIZE: usize = 8;

/// A closed axis-aligned box `[min, max]`. An empty box has `min > max`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Lower corner.
    pub min: DVec3,
    /// Upper corner.
    pub max: DVec3,
}

impl Aabb {
    /// The empty box (union identity).
    pub const EMPTY: Aabb = Aabb {
        min: DVec3::INFINITY,
        max: DVec3::NEG_INFINITY,
    };

    /// The smallest box containing the points (exact).
    ///
    /// ```
    /// use envelope_predicates::bvh::Aabb;
    /// use glam::DVec3;
    /// let b = Aabb::from_points(&[DVec3::ZERO, DVec3::new(1.0, -2.0, 3.0)]);
    /// assert_eq!(b.min, DVec3::new(0.0, -2.0, 0.0));
    /// assert!(b.overlaps(&Aabb::from_points(&[DVec3::new(1.0, 0.0, 3.0)])));
    /// ```
    #[must_use]
    pub fn from_points(points: &[DVec3]) -> Aabb {
        points.iter().fold(Aabb::EMPTY, |b, &p| Aabb {
            min: b.min.min(p),
            max: b.max.max(p),
        })
    }

    /// The box of a triangle (exact).
    #[inline]
    #[must_use]
    pub fn from_triangle(t: [DVec3; 3]) -> Aabb {
        Aabb {
            min: t[0].min(t[1]).min(t[2]),
            max: t[0].max(t[1]).max(t[2]),
        }
    }

    /// The smallest box containing both (exact).
    #[inline]
    #[must_use]
    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    /// True when the closed boxes share a point (exact).
    #[inline]
    #[must_use]
    pub fn overlaps(&self, o: &Aabb) -> bool {
        // Without short-circuits: one branch for the caller instead of up to six.
        (self.min.x <= o.max.x)
            & (o.min.x <= self.max.x)
            & (self.min.y <= o.max.y)
            & (o.min.y <= self.max.y)
            & (self.min.z <= o.max.z)
            & (o.min.z <= self.max.z)
    }

    /// True when `p` is in the closed box (exact).
    #[inline]
    #[must_use]
    pub fn contains(&self, p: DVec3) -> bool {
        self.min.cmple(p).all() && p.cmple(self.max).all()
    }

    /// True for the empty box.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        !self.min.cmple(self.max).all()
    }

    /// A box containing every point within distance `eps` (>= 0) of this box, rounded outward.
    ///
    /// ```
    /// use envelope_predicates::bvh::Aabb;
    /// use glam::DVec3;
    /// let b = Aabb::from_points(&[DVec3::splat(0.1)]).inflated(0.2);
    /// assert!(b.min.x <= 0.1 - 0.2 && b.max.x >= 0.1 + 0.2);
    /// assert!(b.contains(DVec3::new(-0.1, 0.3, 0.3)));
    /// ```
    #[must_use]
    pub fn inflated(&self, eps: f64) -> Aabb {
        let down = |x: f64| next_down(x - eps);
        let up = |x: f64| next_up(x + eps);
        Aabb {
            min: DVec3::new(down(self.min.x), down(self.min.y), down(self.min.z)),
            max: DVec3::new(up(self.max.x), up(self.max.y), up(self.max.z)),
        }
    }

    /// A lower bound of the squared distance from `p` to the box (0 inside); never larger than
    /// the exact value.
    ///
    /// ```
    /// use envelope_predicates::bvh::Aabb;
    /// use glam::DVec3;
    /// let b = Aabb::from_points(&[DVec3::ZERO, DVec3::ONE]);
    /// let d2 = b.sq_distance_lower_bound(DVec3::new(4.0, 0.5, -3.0));
    /// assert!(d2 <= 18.0 && d2 > 17.99);
    /// ```
    #[must_use]
    pub fn sq_distance_lower_bound(&self, p: DVec3) -> f64 {
        let axis = |lo: f64, hi: f64, x: f64| {
            // Each gap is rounded down, so its square is a lower bound before rounding.
            if x < lo {
                next_down(lo - x).max(0.0)
            } else if x > hi {
                next_down(x - hi).max(0.0)
            } else {
                0.0
            }
        };
        let d = DVec3::new(
            axis(self.min.x, self.max.x, p.x),
            axis(self.min.y, self.max.y, p.y),
            axis(self.min.z, self.max.z, p.z),
        );
        // Three squares and two sums: relative error below 5u; subtract generously.
        let s = d.x * d.x + d.y * d.y + d.z * d.z;
        (s * (1.0 - 8.0 * f64::EPSILON) - 1e-300).max(0.0)
    }

    /// A lower bound of the distance from `p` to the box.
    #[must_use]
    pub fn distance_lower_bound(&self, p: DVec3) -> f64 {
        next_down(self.sq_distance_lower_bound(p).sqrt()).max(0.0)
    }

    #[inline]
    fn center(&self) -> DVec3 {
        (self.min + self.max) * 0.5
    }
}

/// A node of a [`Bvh`], by index.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct NodeId(u32);

/// What a node holds.
#[derive(Clone, Copy, Debug)]
pub enum NodeKind<'a> {
    /// A leaf with these item ids.
    Leaf(&'a [u32]),
    /// An interior node with two children.
    Interior(NodeId, NodeId),
}

#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    /// Leaf: first item position; interior: left child.
    a: u32,
    /// Leaf: item count (> 0); interior: right child.
    b: u32,
    /// Number of items below.
    count: u32,
    leaf: bool,
}

impl Node {
    /// This node in a tree whose nodes of its own tree start at `links` and whose items at
    /// `first` (the children's links, or a leaf's first item position, shifted).
    fn moved(&self, links: u32, first: u32) -> Node {
        if self.leaf {
            Node {
                a: self.a + first,
                ..*self
            }
        } else {
            Node {
                a: self.a + links,
                b: self.b + links,
                ..*self
            }
        }
    }
}

/// A bounding-volume hierarchy over item boxes.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// Item ids in leaf order.
    items: Vec<u32>,
    /// Item boxes in leaf order (`boxes[k]` is the box of `items[k]`).
    boxes: Vec<Aabb>,
}

/// How many overlapping pairs a self-pair walk over `items` items may take before a caller
/// calls the input too dense to test every pair: 48 per item (a manifold mesh has about a
/// dozen per face) plus 2^22. The input checker and the certificate share it, so that time
/// and memory stay linear in the input (a stack of coincident faces has quadratically many).
#[must_use]
pub const fn pair_budget(items: usize) -> usize {
    48 * items + (1 << 22)
}

/// Subtrees larger than this are built / traversed with rayon.
const PAR_THRESHOLD: usize = 4096;

impl Bvh {
    /// Builds a tree over `boxes` (item id `i` is `boxes[i]`).
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let boxes: Vec<Aabb> = (0..10)
    ///     .map(|i| Aabb::from_points(&[DVec3::splat(i as f64), DVec3::splat(i as f64 + 1.5)]))
    ///     .collect();
    /// let bvh = Bvh::new(&boxes);
    /// assert_eq!(bvh.self_pairs(), (0..9).map(|i| (i, i + 1)).collect::<Vec<_>>());
    /// assert_eq!(bvh.overlapping(&Aabb::from_points(&[DVec3::splat(0.5)])), vec![0]);
    /// ```
    #[must_use]
    pub fn new(boxes: &[Aabb]) -> Bvh {
        let (nodes, items) = shape(boxes);
        let ordered = items.iter().map(|&i| boxes[i as usize]).collect();
        Bvh {
            nodes,
            items,
            boxes: ordered,
        }
    }

    /// [`Bvh::new`] over boxes the caller gives up: the same tree, whose boxes in leaf order
    /// are `boxes` permuted in place instead of a copy (one array of boxes less at the peak,
    /// for a tree over millions of items).
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let boxes: Vec<Aabb> = [5.0, 0.0, 9.0, 1.0, 4.5]
    ///     .map(|x| Aabb::from_points(&[DVec3::splat(x), DVec3::splat(x + 0.7)]))
    ///     .to_vec();
    /// let copied = Bvh::new(&boxes);
    /// let owned = Bvh::from_boxes(boxes);
    /// assert_eq!(owned.leaf_order(), copied.leaf_order());
    /// assert_eq!(owned.leaf_boxes(), copied.leaf_boxes());
    /// assert_eq!(owned.self_pairs(), copied.self_pairs());
    /// ```
    #[must_use]
    pub fn from_boxes(mut boxes: Vec<Aabb>) -> Bvh {
        let (nodes, items) = shape(&boxes);
        // Leaf position `k` takes the box of item `items[k]`: follow each cycle of that
        // permutation once.
        let mut placed = vec![false; boxes.len()];
        for start in 0..boxes.len() {
            if placed[start] {
                continue;
            }
            let first = boxes[start];
            let mut k = start;
            loop {
                placed[k] = true;
                let from = items[k] as usize;
                if from == start {
                    boxes[k] = first;
                    break;
                }
                boxes[k] = boxes[from];
                k = from;
            }
        }
        Bvh {
            nodes,
            items,
            boxes,
        }
    }

    /// Builds a tree over the boxes of the triangles `faces` of `positions` (item id = face index).
    #[must_use]
    pub fn from_triangles(positions: &[DVec3], faces: &[[u32; 3]]) -> Bvh {
        let boxes: Vec<Aabb> = faces
            .iter()
            .map(|f| Aabb::from_triangle(f.map(|i| positions[i as usize])))
            .collect();
        Bvh::new(&boxes)
    }

    /// One tree over the items of `a` then those of `b`: item `i` of `b` becomes item
    /// `a.len() + i`. The root's children are the two trees as they are (no rebuild), so a
    /// query or pair search answers exactly what it would on the two separately, and the
    /// pairs of [`Bvh::self_pairs`] are those of `a`, of `b`, and between them. Both are
    /// borrowed: their nodes, items and boxes are copied once into vectors of the joined
    /// sizes (the trees joined are often kept: the proof's, the input's).
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let unit = |x: f64| Aabb::from_points(&[DVec3::splat(x), DVec3::splat(x + 1.0)]);
    /// let a = Bvh::new(&[unit(0.0), unit(5.0)]);
    /// let b = Bvh::new(&[unit(0.5), unit(9.0)]);
    /// let ab = Bvh::join(&a, &b);
    /// assert_eq!(ab.len(), 4);
    /// assert_eq!(ab.self_pairs(), vec![(0, 2)]);
    /// assert_eq!(ab.overlapping(&unit(8.5)), vec![3]);
    /// ```
    #[must_use]
    pub fn join(a: &Bvh, b: &Bvh) -> Bvh {
        // `a` copied once, into vectors with room for `b`.
        fn with_room<T: Clone>(from: &[T], more: usize) -> Vec<T> {
            let mut v = Vec::with_capacity(from.len() + more);
            v.extend_from_slice(from);
            v
        }
        Bvh {
            nodes: with_room(&a.nodes, 1 + b.nodes.len()),
            items: with_room(&a.items, b.items.len()),
            boxes: with_room(&a.boxes, b.boxes.len()),
        }
        .joined(b)
    }

    /// [`Bvh::join`] that takes `self` and grows its own vectors instead of copying them:
    /// the new root goes in front of `self`'s nodes (moved one place up, their links with
    /// them) and `b`'s follow, so children still come after their parent (what
    /// [`Bvh::refit`] walks backwards on). The same tree as [`Bvh::join`]'s, node for node.
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let unit = |x: f64| Aabb::from_points(&[DVec3::splat(x), DVec3::splat(x + 1.0)]);
    /// let (a, b) = (Bvh::new(&[unit(0.0), unit(5.0)]), Bvh::new(&[unit(0.5), unit(9.0)]));
    /// let joined = Bvh::join(&a, &b);
    /// let grown = a.joined(&b);
    /// assert_eq!(grown.self_pairs(), joined.self_pairs());
    /// assert_eq!(grown.leaf_order(), joined.leaf_order());
    /// assert_eq!(grown.overlapping(&unit(8.5)), vec![3]);
    /// ```
    #[must_use]
    pub fn joined(mut self, b: &Bvh) -> Bvh {
        let shift = self.items.len() as u32;
        assert!(
            (shift as usize + b.items.len()) < u32::MAX as usize,
            "too many items for u32 ids"
        );
        if b.nodes.is_empty() {
            return self;
        }
        if self.nodes.is_empty() {
            // No nodes, no items: `b`'s ids stay as they are.
            return b.clone();
        }
        let (ra, rb) = (self.nodes[0], b.nodes[0]);
        let lb = 1 + self.nodes.len() as u32;
        self.nodes.reserve(1 + b.nodes.len());
        self.nodes.insert(
            0,
            Node {
                bounds: ra.bounds.union(&rb.bounds),
                a: 1,
                b: lb,
                count: ra.count + rb.count,
                leaf: false,
            },
        );
        for n in &mut self.nodes[1..] {
            *n = n.moved(1, 0);
        }
        self.nodes
            .extend(b.nodes.iter().map(|n| n.moved(lb, shift)));
        self.items.extend(b.items.iter().map(|&i| i + shift));
        self.boxes.extend_from_slice(&b.boxes);
        self
    }

    /// Every item once, in the order of the leaves that hold them (depth first): a spatially
    /// coherent order. Work done item by item in it reads nearby data one after another (and
    /// a query per item walks the tree's nodes near the previous one's).
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let unit = |x: f64| Aabb::from_points(&[DVec3::splat(x), DVec3::splat(x + 1.0)]);
    /// let tree = Bvh::new(&[unit(9.0), unit(0.0), unit(8.0), unit(1.0)]);
    /// let mut order = tree.leaf_order().to_vec();
    /// assert_eq!(order.len(), 4);
    /// order.sort_unstable();
    /// assert_eq!(order, vec![0, 1, 2, 3]);
    /// ```
    #[must_use]
    pub fn leaf_order(&self) -> &[u32] {
        &self.items
    }

    /// Number of items.
    #[must_use]
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// True when the tree has no items.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// The same tree with its items renumbered in leaf order (a depth-first walk of the
    /// leaves, so items close in space get close ids), and the old id of each new one. A
    /// caller that stores its items in that order visits memory coherently.
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let boxes: Vec<Aabb> = [5.0, 0.0, 9.0, 1.0]
    ///     .map(|x| Aabb::from_points(&[DVec3::splat(x), DVec3::splat(x + 0.5)]))
    ///     .to_vec();
    /// let (tree, old) = Bvh::new(&boxes).into_leaf_order();
    /// let renumbered: Vec<Aabb> = old.iter().map(|&i| boxes[i as usize]).collect();
    /// let q = Aabb::from_points(&[DVec3::splat(9.2)]);
    /// assert_eq!(tree.overlapping(&q).len(), 1);
    /// assert_eq!(renumbered[tree.overlapping(&q)[0] as usize], boxes[2]);
    /// ```
    #[must_use]
    pub fn into_leaf_order(mut self) -> (Bvh, Vec<u32>) {
        let n = self.items.len() as u32;
        let old = std::mem::replace(&mut self.items, (0..n).collect());
        (self, old)
    }

    /// The root node, if any.
    #[must_use]
    pub fn root(&self) -> Option<NodeId> {
        (!self.nodes.is_empty()).then_some(NodeId(0))
    }

    /// The box of a node (contains the boxes of all items below it).
    #[must_use]
    pub fn bounds(&self, n: NodeId) -> Aabb {
        self.nodes[n.0 as usize].bounds
    }

    /// The children or items of a node.
    #[must_use]
    pub fn kind(&self, n: NodeId) -> NodeKind<'_> {
        let node = &self.nodes[n.0 as usize];
        if node.leaf {
            NodeKind::Leaf(&self.items[node.a as usize..(node.a + node.b) as usize])
        } else {
            NodeKind::Interior(NodeId(node.a), NodeId(node.b))
        }
    }

    /// Calls `f` with every item whose box overlaps `query`.
    pub fn for_each_overlapping(&self, query: &Aabb, mut f: impl FnMut(u32)) {
        self.for_each_overlapping_while(query, |i| {
            f(i);
            true
        });
    }

    /// Whether some item's box overlaps `query` (the walk stops at the first).
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let at = |x: f64| Aabb::from_points(&[DVec3::splat(x), DVec3::splat(x + 1.0)]);
    /// let tree = Bvh::new(&[at(0.0), at(5.0)]);
    /// assert!(tree.any_overlapping(&at(5.5)) && !tree.any_overlapping(&at(2.5)));
    /// ```
    #[must_use]
    pub fn any_overlapping(&self, query: &Aabb) -> bool {
        let mut hit = false;
        self.for_each_overlapping_while(query, |_| {
            hit = true;
            false
        });
        hit
    }

    /// Calls `f` with the items whose boxes overlap `query` until it returns `false`.
    pub fn for_each_overlapping_while(&self, query: &Aabb, f: impl FnMut(u32) -> bool) {
        self.for_each_entering(|b| b.overlaps(query), f);
    }

    /// Walks the tree into the nodes, and calls `f` with the items, whose boxes `enter`
    /// accepts, until `f` returns `false`: depth first, each node's first child first (for
    /// trees up to 64 deep, as median splits make them), so an `enter` that turns away more
    /// nodes leaves the other items in the same order.
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let at = |x: f64| Aabb::from_points(&[DVec3::splat(x), DVec3::splat(x + 1.0)]);
    /// let tree = Bvh::new(&[at(0.0), at(5.0), at(9.0)]);
    /// let mut got = Vec::new();
    /// tree.for_each_entering(|b| b.max.x > 3.0, |i| { got.push(i); true });
    /// got.sort_unstable();
    /// assert_eq!(got, [1, 2]);
    /// ```
    pub fn for_each_entering(
        &self,
        mut enter: impl FnMut(&Aabb) -> bool,
        mut f: impl FnMut(u32) -> bool,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        // A fixed stack for the usual depths, spilling to the heap beyond (no allocation
        // per query).
        let mut stack = [0u32; 64];
        let mut len = 1;
        let mut spill = Vec::new();
        loop {
            let n = if len > 0 {
                len -= 1;
                stack[len]
            } else if let Some(n) = spill.pop() {
                n
            } else {
                break;
            };
            let node = &self.nodes[n as usize];
            if !enter(&node.bounds) {
                continue;
            }
            if node.leaf {
                for k in node.a as usize..(node.a + node.b) as usize {
                    if enter(&self.boxes[k]) && !f(self.items[k]) {
                        return;
                    }
                }
            } else if len + 2 <= stack.len() {
                stack[len] = node.b;
                stack[len + 1] = node.a;
                len += 2;
            } else {
                spill.push(node.b);
                spill.push(node.a);
            }
        }
    }

    /// The sorted ids of the items whose boxes overlap `query`.
    #[must_use]
    pub fn overlapping(&self, query: &Aabb) -> Vec<u32> {
        let mut out = Vec::new();
        self.for_each_overlapping(query, |i| out.push(i));
        out.sort_unstable();
        out
    }

    /// All pairs `(i, j)`, `i < j`, of items with overlapping boxes, for which `keep(i, j)` holds;
    /// sorted. Runs in parallel (rayon); `keep` is called once per overlapping pair.
    pub fn self_pairs_where<F: Fn(u32, u32) -> bool + Sync>(&self, keep: F) -> Vec<(u32, u32)> {
        self.self_pairs_emit(|i, j, out| {
            if keep(i, j) {
                out.push((i, j));
            }
        })
    }

    /// Calls `emit(i, j, out)` once for every pair `i < j` of items with overlapping boxes
    /// and returns everything the calls pushed onto `out`, sorted: for a caller that turns
    /// one pair of items into several answers (the envelope proof: one pair of input faces,
    /// up to nine pairs of triangles of three surfaces). Runs in parallel.
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let boxes: Vec<Aabb> = (0..4)
    ///     .map(|i| Aabb::from_points(&[DVec3::splat(i as f64), DVec3::splat(i as f64 + 1.5)]))
    ///     .collect();
    /// let tree = Bvh::new(&boxes);
    /// let both_ways = tree.self_pairs_emit(|i, j, out| out.extend([(i, j), (j + 10, i)]));
    /// assert_eq!(both_ways, vec![(0, 1), (1, 2), (2, 3), (11, 0), (12, 1), (13, 2)]);
    /// ```
    pub fn self_pairs_emit<F: Fn(u32, u32, &mut Vec<(u32, u32)>) + Sync>(
        &self,
        emit: F,
    ) -> Vec<(u32, u32)> {
        if self.nodes.is_empty() {
            return Vec::new();
        }
        let mut out = collect(|o| self.self_rec(0, &emit, o));
        out.sort_unstable();
        out
    }

    /// The same tree shape over `copies` times as many items: every leaf that holds item
    /// `i` holds the items `i`, `i + n`, ..., `i + (copies - 1) n` instead (`n` = this
    /// tree's length), keeping this tree's boxes; [`Bvh::refit`] it to the boxes of the new
    /// items. For surfaces that follow one another face by face (an input and its
    /// offsets): one tree over all of them whose leaves, and so a caller's storage in leaf
    /// order, keep the copies of a face together.
    ///
    /// # Panics
    /// When `copies` is zero or the new items do not fit in `u32` ids.
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let at = |x: f64| Aabb::from_points(&[DVec3::splat(x), DVec3::splat(x + 1.0)]);
    /// let tree = Bvh::new(&[at(0.0), at(5.0)]);
    /// let both = tree.interleaved(2).refit(&[at(0.0), at(5.0), at(0.5), at(9.0)]);
    /// assert_eq!(both.len(), 4);
    /// assert_eq!(both.self_pairs(), vec![(0, 2)]);
    /// ```
    #[must_use]
    pub fn interleaved(&self, copies: usize) -> Bvh {
        self.interleaved_nodes(copies, true)
    }

    /// `self.interleaved(copies).refit(boxes)`, without the copies' boxes that the refit
    /// replaces at once.
    ///
    /// # Panics
    /// As [`Bvh::interleaved`] and [`Bvh::refit`].
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let at = |x: f64| Aabb::from_points(&[DVec3::splat(x), DVec3::splat(x + 1.0)]);
    /// let tree = Bvh::new(&[at(0.0), at(5.0)]);
    /// let boxes = [at(0.0), at(5.0), at(0.5), at(9.0)];
    /// let both = tree.interleaved_refit(2, &boxes);
    /// assert_eq!(both.self_pairs(), tree.interleaved(2).refit(&boxes).self_pairs());
    /// ```
    #[must_use]
    pub fn interleaved_refit(&self, copies: usize, boxes: &[Aabb]) -> Bvh {
        self.interleaved_nodes(copies, false).into_refit(boxes)
    }

    /// [`Bvh::interleaved`]; without its boxes (none yet) unless `with_boxes`.
    fn interleaved_nodes(&self, copies: usize, with_boxes: bool) -> Bvh {
        assert!(copies > 0, "at least one copy");
        let n = self.items.len();
        assert!(
            (n as u64) * (copies as u64) < u64::from(u32::MAX),
            "too many items for u32 ids"
        );
        let mut items = Vec::with_capacity(n * copies);
        let mut boxes = Vec::with_capacity(if with_boxes { n * copies } else { 0 });
        let mut nodes = self.nodes.clone();
        for node in nodes.iter_mut() {
            node.count *= copies as u32;
            if node.leaf {
                let first = items.len() as u32;
                for k in node.a as usize..(node.a + node.b) as usize {
                    for c in 0..copies {
                        items.push(self.items[k] + (c * n) as u32);
                        if with_boxes {
                            boxes.push(self.boxes[k]);
                        }
                    }
                }
                node.a = first;
                node.b *= copies as u32;
            }
        }
        Bvh {
            nodes,
            items,
            boxes,
        }
    }

    /// Whether this is a tree over exactly `boxes`: one item per box, each item once, with
    /// the box it has there (as [`Bvh::new`]`(boxes)` or a [`Bvh::refit`] to them makes it).
    /// For a caller handed a tree built elsewhere. Linear time.
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let at = |x: f64| Aabb::from_points(&[DVec3::splat(x), DVec3::splat(x + 1.0)]);
    /// let tree = Bvh::new(&[at(0.0), at(5.0)]);
    /// assert!(tree.has_item_boxes(&[at(0.0), at(5.0)]));
    /// assert!(!tree.has_item_boxes(&[at(5.0), at(0.0)]));
    /// assert!(!tree.has_item_boxes(&[at(0.0)]));
    /// ```
    #[must_use]
    pub fn has_item_boxes(&self, boxes: &[Aabb]) -> bool {
        self.has_item_boxes_of(boxes.len(), |i| boxes[i as usize])
    }

    /// [`Bvh::has_item_boxes`] with the boxes given by a function: whether this is a tree
    /// over items `0..n`, each once, item `i` with the box `box_of(i)` (called only for
    /// `i < n`, once per item). For boxes a caller would otherwise gather only to compare.
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let at = |x: f64| Aabb::from_points(&[DVec3::splat(x), DVec3::splat(x + 1.0)]);
    /// let tree = Bvh::new(&[at(0.0), at(5.0)]);
    /// assert!(tree.has_item_boxes_of(2, |i| at(5.0 * f64::from(i))));
    /// assert!(!tree.has_item_boxes_of(2, |i| at(f64::from(i))));
    /// assert!(!tree.has_item_boxes_of(3, |i| at(5.0 * f64::from(i))));
    /// ```
    #[must_use]
    pub fn has_item_boxes_of(&self, n: usize, box_of: impl Fn(u32) -> Aabb) -> bool {
        if n != self.items.len() {
            return false;
        }
        let mut seen = vec![false; n];
        self.items.iter().zip(&self.boxes).all(|(&i, b)| {
            (i as usize) < n && !std::mem::replace(&mut seen[i as usize], true) && box_of(i) == *b
        })
    }

    /// The item boxes in leaf order: entry `k` is the box of item [`Bvh::leaf_order`]`()[k]`
    /// (after [`Bvh::into_leaf_order`], the box of item `k`).
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let unit = |x: f64| Aabb::from_points(&[DVec3::splat(x), DVec3::splat(x + 1.0)]);
    /// let boxes = [unit(9.0), unit(0.0), unit(8.0)];
    /// let tree = Bvh::new(&boxes);
    /// for (k, &i) in tree.leaf_order().iter().enumerate() {
    ///     assert_eq!(tree.leaf_boxes()[k], boxes[i as usize]);
    /// }
    /// ```
    #[must_use]
    pub fn leaf_boxes(&self) -> &[Aabb] {
        &self.boxes
    }

    /// The same tree shape over other boxes: item `i` gets `boxes[i]`, and every node the
    /// union of its items' new boxes. Every query and pair search answers exactly what it
    /// would on [`Bvh::new`]`(boxes)` (the sets of items whose boxes overlap do not depend
    /// on the shape); only the speed does, so a refit suits boxes that moved little against
    /// the ones the tree was built for (an envelope face against its input face, at small
    /// offsets). Linear time, no sorting.
    ///
    /// # Panics
    /// When `boxes` does not have one box per item.
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let at = |x: f64| Aabb::from_points(&[DVec3::splat(x), DVec3::splat(x + 1.0)]);
    /// let tree = Bvh::new(&[at(0.0), at(5.0), at(9.0)]);
    /// let moved = tree.refit(&[at(0.0), at(8.5), at(9.0)]);
    /// assert_eq!(moved.self_pairs(), vec![(1, 2)]);
    /// assert_eq!(moved.overlapping(&at(4.0)), Vec::<u32>::new());
    /// ```
    #[must_use]
    pub fn refit(&self, boxes: &[Aabb]) -> Bvh {
        Bvh {
            nodes: self.nodes.clone(),
            items: self.items.clone(),
            boxes: Vec::new(),
        }
        .into_refit(boxes)
    }

    /// [`Bvh::refit`] where only a few items moved: the same tree with each item of `moved`
    /// given its new box, and the nodes above refitted. The same tree as a refit to every
    /// item's box (the boxes of the other items are this tree's; a leaf with no moved item
    /// keeps its box, the union of the same boxes), for the work of a copy and one pass over
    /// the nodes instead of a gather of every box.
    ///
    /// # Panics
    /// When an item of `moved` is not in the tree.
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let at = |x: f64| Aabb::from_points(&[DVec3::splat(x), DVec3::splat(x + 1.0)]);
    /// let tree = Bvh::new(&[at(0.0), at(5.0), at(9.0)]);
    /// let moved = tree.refit_items(&[(1, at(8.5))]);
    /// assert_eq!(moved.self_pairs(), vec![(1, 2)]);
    /// assert_eq!(moved.leaf_boxes(), tree.refit(&[at(0.0), at(8.5), at(9.0)]).leaf_boxes());
    /// ```
    #[must_use]
    pub fn refit_items(&self, moved: &[(u32, Aabb)]) -> Bvh {
        let mut tree = self.clone();
        if moved.is_empty() {
            return tree;
        }
        let mut sorted = moved.to_vec();
        sorted.sort_unstable_by_key(|m| m.0);
        // Each moved item's leaf position, and its new box there.
        let mut dirty = vec![false; tree.items.len()];
        let mut found = 0;
        for (k, &i) in tree.items.iter().enumerate() {
            if let Ok(j) = sorted.binary_search_by_key(&i, |m| m.0) {
                tree.boxes[k] = sorted[j].1;
                dirty[k] = true;
                found += 1;
            }
        }
        assert!(
            found == sorted.len() && sorted.windows(2).all(|w| w[0].0 < w[1].0),
            "each moved item once, and in the tree"
        );
        tree.refit_nodes(|leaf| dirty[leaf].iter().any(|&d| d));
        tree
    }

    /// [`Bvh::refit`] in place: this tree's nodes and items with the new boxes.
    fn into_refit(mut self, boxes: &[Aabb]) -> Bvh {
        assert_eq!(boxes.len(), self.items.len(), "one box per item");
        self.boxes = self.items.iter().map(|&i| boxes[i as usize]).collect();
        self.refit_nodes(|_| true);
        self
    }

    /// Every node's bounds from the item boxes in leaf order: each leaf for which `changed`
    /// says so (given its range of leaf positions) the union of its boxes, every interior node
    /// the union of its children's. Children come after their parent in every tree this type
    /// builds (pre-order builds, `join` putting the new root first), so one backward pass
    /// sees every child's new box before its parent's.
    fn refit_nodes(&mut self, changed: impl Fn(std::ops::Range<usize>) -> bool) {
        let (nodes, ordered) = (&mut self.nodes, &self.boxes);
        for n in (0..nodes.len()).rev() {
            let node = nodes[n];
            if node.leaf {
                let range = node.a as usize..(node.a + node.b) as usize;
                if changed(range.clone()) {
                    nodes[n].bounds = ordered[range].iter().fold(Aabb::EMPTY, |b, x| b.union(x));
                }
            } else {
                assert!(
                    node.a as usize > n && node.b as usize > n,
                    "children after the parent"
                );
                nodes[n].bounds = nodes[node.a as usize]
                    .bounds
                    .union(&nodes[node.b as usize].bounds);
            }
        }
    }

    /// All pairs `(i, j)`, `i < j`, of items with overlapping boxes; sorted.
    #[must_use]
    pub fn self_pairs(&self) -> Vec<(u32, u32)> {
        self.self_pairs_where(|_, _| true)
    }

    /// All pairs `(i, j)` with `i` an item of `self` and `j` an item of `other` whose boxes
    /// overlap and for which `keep(i, j)` holds; sorted. Runs in parallel.
    pub fn pairs_with_where<F: Fn(u32, u32) -> bool + Sync>(
        &self,
        other: &Bvh,
        keep: F,
    ) -> Vec<(u32, u32)> {
        if self.nodes.is_empty() || other.nodes.is_empty() {
            return Vec::new();
        }
        let pair = |a: u32, b: u32, out: &mut Vec<(u32, u32)>| {
            if keep(a, b) {
                out.push((a, b));
            }
        };
        let mut out = collect(|o| cross_rec(self, 0, other, 0, &pair, o));
        out.sort_unstable();
        out
    }

    /// All overlapping pairs between two trees (`(id in self, id in other)`), sorted.
    #[must_use]
    pub fn pairs_with(&self, other: &Bvh) -> Vec<(u32, u32)> {
        self.pairs_with_where(other, |_, _| true)
    }

    #[inline]
    /// The number of pairs `i < j` of items with overlapping boxes, counted up to `limit`:
    /// `limit` when there are at least that many. The cost of a self-pair walk, found in time
    /// bounded by `limit` and the tree's size (a walk over a stack of coincident faces has
    /// quadratically many pairs). Sequential and deterministic.
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let boxes = vec![Aabb::from_points(&[DVec3::ZERO, DVec3::ONE]); 100];
    /// let tree = Bvh::new(&boxes);
    /// assert_eq!(tree.self_pair_count_up_to(10_000), 4950);
    /// assert_eq!(tree.self_pair_count_up_to(1000), 1000);
    /// ```
    #[must_use]
    pub fn self_pair_count_up_to(&self, limit: usize) -> usize {
        let mut count = 0usize;
        if limit > 0 {
            self.self_pairs_while(|_, _| {
                count += 1;
                count < limit
            });
        }
        count
    }

    /// Calls `f(i, j)`, `i < j`, for the pairs of items with overlapping boxes, one at a
    /// time in a fixed order, until it returns false: a walk a caller can stop (the
    /// self-pair walks of [`Bvh::self_pairs_where`] run to the end, in parallel).
    ///
    /// ```
    /// use envelope_predicates::bvh::{Aabb, Bvh};
    /// use glam::DVec3;
    /// let boxes = vec![Aabb::from_points(&[DVec3::ZERO, DVec3::ONE]); 10];
    /// let mut seen = 0;
    /// Bvh::new(&boxes).self_pairs_while(|i, j| {
    ///     assert!(i < j);
    ///     seen += 1;
    ///     seen < 7
    /// });
    /// assert_eq!(seen, 7);
    /// ```
    pub fn self_pairs_while(&self, mut f: impl FnMut(u32, u32) -> bool) {
        if self.nodes.is_empty() {
            return;
        }
        let mut visit = |k: usize, l: usize| {
            !self.boxes[k].overlaps(&self.boxes[l]) || {
                let (i, j) = ordered(self.items[k], self.items[l]);
                f(i, j)
            }
        };
        // (a, b): the pairs within `a` when `a == b`, else the pairs across them.
        let mut stack = vec![(0u32, 0u32)];
        while let Some((na, nb)) = stack.pop() {
            let (a, b) = (&self.nodes[na as usize], &self.nodes[nb as usize]);
            if na == nb {
                if a.leaf {
                    let (s, e) = (a.a as usize, (a.a + a.b) as usize);
                    for k in s..e {
                        for l in k + 1..e {
                            if !visit(k, l) {
                                return;
                            }
                        }
                    }
                } else {
                    stack.extend([(a.a, a.a), (a.b, a.b), (a.a, a.b)]);
                }
            } else if a.bounds.overlaps(&b.bounds) {
                if a.leaf && b.leaf {
                    for k in a.a as usize..(a.a + a.b) as usize {
                        for l in b.a as usize..(b.a + b.b) as usize {
                            if !visit(k, l) {
                                return;
                            }
                        }
                    }
                } else if !a.leaf && (b.leaf || a.count >= b.count) {
                    stack.extend([(a.a, nb), (a.b, nb)]);
                } else {
                    stack.extend([(na, b.a), (na, b.b)]);
                }
            }
        }
    }

    fn size(&self, n: u32) -> usize {
        self.nodes[n as usize].count as usize
    }

    /// Calls `emit(i, j, out)`, `i < j`, for every overlapping pair within the subtree `n`.
    fn self_rec<F: Fn(u32, u32, &mut Vec<(u32, u32)>) + Sync>(
        &self,
        n: u32,
        emit: &F,
        out: &mut Vec<(u32, u32)>,
    ) {
        let node = &self.nodes[n as usize];
        if node.leaf {
            let (s, e) = (node.a as usize, (node.a + node.b) as usize);
            for k in s..e {
                for l in k + 1..e {
                    if self.boxes[k].overlaps(&self.boxes[l]) {
                        let (i, j) = ordered(self.items[k], self.items[l]);
                        emit(i, j, out);
                    }
                }
            }
            return;
        }
        let (l, r) = (node.a, node.b);
        let pair = |a: u32, b: u32, out: &mut Vec<(u32, u32)>| {
            let (i, j) = ordered(a, b);
            emit(i, j, out);
        };
        if self.size(n) > PAR_THRESHOLD {
            let ((x, y), z) = rayon::join(
                || {
                    rayon::join(
                        || collect(|o| self.self_rec(l, emit, o)),
                        || collect(|o| self.self_rec(r, emit, o)),
                    )
                },
                || collect(|o| cross_rec(self, l, self, r, &pair, o)),
            );
            out.extend(x);
            out.extend(y);
            out.extend(z);
        } else {
            self.self_rec(l, emit, out);
            self.self_rec(r, emit, out);
            cross_rec(self, l, self, r, &pair, out);
        }
    }
}

#[inline]
fn ordered(a: u32, b: u32) -> (u32, u32) {
    if a < b { (a, b) } else { (b, a) }
}

/// What `fill` appends to a new vector.
fn collect<T>(fill: impl FnOnce(&mut Vec<T>)) -> Vec<T> {
    let mut out = Vec::new();
    fill(&mut out);
    out
}

/// Calls `f(i, j, out)` for every overlapping pair of an item `i` under the node `na` of `ta`
/// and an item `j` under `nb` of `tb` (one vector for a whole sequential subtree pair: no
/// allocation per node pair).
fn cross_rec<F: Fn(u32, u32, &mut Vec<(u32, u32)>) + Sync>(
    ta: &Bvh,
    na: u32,
    tb: &Bvh,
    nb: u32,
    f: &F,
    out: &mut Vec<(u32, u32)>,
) {
    let (a, b) = (&ta.nodes[na as usize], &tb.nodes[nb as usize]);
    if !a.bounds.overlaps(&b.bounds) {
        return;
    }
    if a.leaf && b.leaf {
        for k in a.a as usize..(a.a + a.b) as usize {
            for l in b.a as usize..(b.a + b.b) as usize {
                if ta.boxes[k].overlaps(&tb.boxes[l]) {
                    f(ta.items[k], tb.items[l], out);
                }
            }
        }
        return;
    }
    let (sa, sb) = (ta.size(na), tb.size(nb));
    // Descend the larger side (or the only interior one).
    let descend_a = !a.leaf && (b.leaf || sa >= sb);
    let (x, y) = if descend_a {
        ((a.a, nb), (a.b, nb))
    } else {
        ((na, b.a), (na, b.b))
    };
    if sa + sb > PAR_THRESHOLD {
        let (l, r) = rayon::join(
            || collect(|o| cross_rec(ta, x.0, tb, x.1, f, o)),
            || collect(|o| cross_rec(ta, y.0, tb, y.1, f, o)),
        );
        out.extend(l);
        out.extend(r);
    } else {
        cross_rec(ta, x.0, tb, x.1, f, out);
        cross_rec(ta, y.0, tb, y.1, f, out);
    }
}

/// The nodes of the tree over `boxes` and its items in leaf order (no boxes yet).
fn shape(boxes: &[Aabb]) -> (Vec<Node>, Vec<u32>) {
    assert!(
        boxes.len() < u32::MAX as usize,
        "too many items for u32 ids"
    );
    if boxes.is_empty() {
        return (Vec::new(), Vec::new());
    }
    // Each item with its centre, so the partitions read contiguous memory (the same
    // comparisons in the same places as on bare ids: the same tree).
    let mut entries: Vec<Entry> = boxes
        .iter()
        .zip(0u32..)
        .map(|(b, i)| Entry {
            c: b.center().to_array(),
            i,
        })
        .collect();
    let nodes = build(boxes, &mut entries, 0);
    (nodes, entries.iter().map(|e| e.i).collect())
}

/// Builds the subtree over `items` (positions `offset..` in the global item order); node 0 of
/// the returned vector is its root, child links are relative to the vector. Large subtrees are
/// split in parallel and relocated; small ones are built sequentially in place. A node's box
/// is the union of its children's (the same box as the union of its items', min and max
/// being exact).
fn build(boxes: &[Aabb], items: &mut [Entry], offset: u32) -> Vec<Node> {
    if items.len() <= 16 * PAR_THRESHOLD {
        let mut nodes = Vec::with_capacity(items.len() / 2 + 1);
        build_into(&mut nodes, boxes, items, offset);
        return nodes;
    }
    let mid = split(items);
    let (li, ri) = items.split_at_mut(mid);
    let (left, right) = rayon::join(
        || build(boxes, li, offset),
        || build(boxes, ri, offset + mid as u32),
    );
    let mut nodes = Vec::with_capacity(1 + left.len() + right.len());
    let (lo, ro) = (1u32, 1 + left.len() as u32);
    nodes.push(Node {
        bounds: left[0].bounds.union(&right[0].bounds),
        a: lo,
        b: ro,
        count: (li.len() + ri.len()) as u32,
        leaf: false,
    });
    let shift = |n: &Node, by: u32| {
        if n.leaf {
            *n
        } else {
            Node {
                a: n.a + by,
                b: n.b + by,
                ..*n
            }
        }
    };
    nodes.extend(left.iter().map(|n| shift(n, lo)));
    nodes.extend(right.iter().map(|n| shift(n, ro)));
    nodes
}

/// Sequential pre-order build appending to `nodes`; returns the index of the subtree root.
fn build_into(nodes: &mut Vec<Node>, boxes: &[Aabb], items: &mut [Entry], offset: u32) -> u32 {
    let me = nodes.len() as u32;
    if items.len() <= LEAF_SIZE {
        let bounds = items
            .iter()
            .fold(Aabb::EMPTY, |b, e| b.union(&boxes[e.i as usize]));
        let n = items.len() as u32;
        nodes.push(Node {
            bounds,
            a: offset,
            b: n,
            count: n,
            leaf: true,
        });
        return me;
    }
    let mid = split(items);
    nodes.push(Node {
        bounds: Aabb::EMPTY,
        a: 0,
        b: 0,
        count: items.len() as u32,
        leaf: false,
    });
    let (li, ri) = items.split_at_mut(mid);
    let l = build_into(nodes, boxes, li, offset);
    let r = build_into(nodes, boxes, ri, offset + mid as u32);
    let bounds = nodes[l as usize].bounds.union(&nodes[r as usize].bounds);
    let node = &mut nodes[me as usize];
    node.a = l;
    node.b = r;
    node.bounds = bounds;
    me
}

/// An item id with its box's centre.
#[derive(Clone, Copy)]
struct Entry {
    c: [f64; 3],
    i: u32,
}

/// A median partition of the items along the widest axis of their centres; returns the
/// position of the median.
fn split(items: &mut [Entry]) -> usize {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for e in items.iter() {
        let c = e.c;
        for k in 0..3 {
            lo[k] = lo[k].min(c[k]);
            hi[k] = hi[k].max(c[k]);
        }
    }
    let ext = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    let axis = if ext[0] >= ext[1] && ext[0] >= ext[2] {
        0
    } else if ext[1] >= ext[2] {
        1
    } else {
        2
    };
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |a, b| a.c[axis].total_cmp(&b.c[axis]));
    mid
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The partition on entries (id and centre together) makes the tree the partition on
    /// bare ids reading the centres made: the same comparisons at the same places give the
    /// same permutation. Reference: that build, on random boxes with repeated centres.
    #[test]
    fn entries_build_the_tree_bare_ids_built() {
        fn reference(centers: &[[f64; 3]], items: &mut [u32]) {
            if items.len() <= LEAF_SIZE {
                return;
            }
            let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            for &i in items.iter() {
                for k in 0..3 {
                    lo[k] = lo[k].min(centers[i as usize][k]);
                    hi[k] = hi[k].max(centers[i as usize][k]);
                }
            }
            let ext = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
            let axis = if ext[0] >= ext[1] && ext[0] >= ext[2] {
                0
            } else if ext[1] >= ext[2] {
                1
            } else {
                2
            };
            let mid = items.len() / 2;
            items.select_nth_unstable_by(mid, |&i, &j| {
                centers[i as usize][axis].total_cmp(&centers[j as usize][axis])
            });
            let (l, r) = items.split_at_mut(mid);
            reference(centers, l);
            reference(centers, r);
        }
        let mut next = crate::xorshift(0x9E37_79B9_7F4A_7C15);
        let mut unit = || (next() >> 11) as f64 / (1u64 << 53) as f64;
        // Below the parallel threshold and above it; coarse grids repeat centres.
        for (n, grid) in [(1000usize, 0.0), (3000, 8.0), (40_000, 0.0), (40_000, 16.0)] {
            let boxes: Vec<Aabb> = (0..n)
                .map(|_| {
                    let mut p = DVec3::new(unit(), unit(), unit()) * 10.0;
                    if grid > 0.0 {
                        p = (p * grid).round() / grid;
                    }
                    Aabb::from_points(&[p, p + DVec3::splat(0.1 * unit())])
                })
                .collect();
            let centers: Vec<[f64; 3]> = boxes.iter().map(|b| b.center().to_array()).collect();
            let mut expected: Vec<u32> = (0..n as u32).collect();
            reference(&centers, &mut expected);
            assert_eq!(Bvh::new(&boxes).items, expected, "{n} boxes, grid {grid}");
        }
    }
}

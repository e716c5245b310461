//! Back-face culling of single strips with a segment tree (the constrained single-strip
//! paper, sections 4.2 to 4.4): cut a strip into a few long segments per view, drawing
//! the front-facing ones and skipping the back-facing ones.
//!
//! * [`SegmentTree::build`] builds the tree bottom-up over the strips of a [`StripSet`]:
//!   neighbouring segments whose normals deviate least are merged first (a priority
//!   queue over adjacent pairs keyed by the merged normal cone, neighbours in a linked
//!   list, `O(n log n)`), so flat regions join early and sharp features stay near the
//!   root. The tree is not balanced. Each [`Node`] holds its index range in the strip
//!   buffer, its average normal and conservative [`Bounds`]: a normal cone that holds
//!   its children's cones and a bounding sphere around the centroid of its vertices.
//! * [`SegmentTree::cull`] classifies nodes for an eye point from the roots down
//!   ([`Bounds::classify`]: wholly front-facing, wholly back-facing, or split) and
//!   returns the index ranges to draw ([`Culled`]), for one multi-draw call.
//! * [`RenderFront`] does the same, starting at the lowest nodes tested in the last
//!   frame and merging or splitting them; it gives exactly the ranges of
//!   [`SegmentTree::cull`].
//! * [`helix_eyes`]: the eye points of the helix camera path the figures use;
//!   [`FacingCounter`] counts, by brute force, the triangles a view's ranges draw
//!   facing the eye and facing away.
//!
//! **Parity.** A leaf of the tree is a *pair* of strip triangles, `2k` and `2k + 1`
//! counted from the start of their strip (pairs made only of swaps are dropped), so
//! every node, and every range drawn, starts at an even triangle of its strip: decoded
//! from its first index with the rule of [`decode`](crate::decode), each triangle keeps
//! the winding it has in the strip, without an extra index. The price is that a pair
//! across the silhouette is drawn whole (its back-facing triangle is a *leak*, counted
//! by the callers).
//!
//! ```
//! use stripkit::cull::{helix_eyes, RenderFront, SegmentTree, Culled, CullOptions, HELIX_VIEWS};
//! use stripkit::{gen, stripify, Algorithm, SingleOptions, StripOptions, Weights};
//!
//! let mesh = gen::icosphere(3);
//! let single = Algorithm::Single(SingleOptions::new(Weights::Cull));
//! let strips = stripify(&mesh, &StripOptions::default().algorithm(single))?;
//! let positions = strips.with_added_vertices(&mesh.positions);
//! let tree = SegmentTree::build(&strips.strips, &positions);
//! let mut front = RenderFront::new(&tree);
//! let (mut a, mut b) = (Culled::default(), Culled::default());
//! for eye in helix_eyes([0.0; 3], 1.0, HELIX_VIEWS) {
//!     tree.cull(eye, &CullOptions::default(), &mut a);
//!     front.cull(&tree, eye, &CullOptions::default(), &mut b);
//!     assert_eq!(a.ranges, b.ranges);
//!     // About half the sphere faces away from the eye.
//!     assert!(a.culled_triangles > mesh.triangle_count() / 4);
//! }
//! # Ok::<(), stripkit::Error>(())
//! ```

mod count;
mod frustum;
mod path;

pub use count::{FacingCounter, FacingCounts};
pub use frustum::{Frustum, Side};
pub use path::{bounding_sphere, helix_eyes, HELIX_VIEWS};

use crate::vec3::{add, cross, dot, norm, sub, tri_normal, unit};
use crate::StripSet;
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::ops::Range;

/// "No node": the children of a leaf, the parent of a root.
pub const NONE: u32 = u32::MAX;

/// How a segment faces an eye point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Facing {
    /// Every triangle faces the eye: draw it.
    Front,
    /// Every triangle faces away (or is seen edge-on): skip it.
    Back,
    /// The test cannot tell: test the children (a leaf is drawn).
    Split,
}

/// Conservative bounds of a set of triangles: a cone around `axis` of half-angle
/// `angle` that holds every triangle's unit normal, and a sphere that holds every
/// vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// Unit axis of the cone ([`Bounds::of_triangles`]: the area-weighted average
    /// normal).
    pub axis: [f32; 3],
    /// Half-angle of the normal cone, radians, in `[0, pi]`; negative for an empty
    /// cone (only zero-area triangles, which draw nothing): such bounds face away.
    pub angle: f32,
    /// `cos(angle)`, for [`Bounds::classify`].
    pub cos_angle: f32,
    /// `sin(angle)`.
    pub sin_angle: f32,
    /// Centroid of the vertices.
    pub center: [f32; 3],
    /// Radius of the sphere around `center` that holds every vertex.
    pub radius: f32,
}

impl Bounds {
    /// Bounds from an axis, a half-angle and a sphere (the angle is clamped to `pi`).
    pub fn new(axis: [f32; 3], angle: f32, center: [f32; 3], radius: f32) -> Self {
        let a = angle.min(std::f32::consts::PI);
        Bounds { axis, angle: a, cos_angle: a.cos(), sin_angle: a.sin().max(0.0), center, radius }
    }

    /// The tightest bounds of `triangles` (indices into `positions`) around their
    /// average normal and centroid, widened by `slack` (radians and length) against
    /// rounding.
    pub fn of_triangles(triangles: &[[u32; 3]], positions: &[[f32; 3]], slack: [f64; 2]) -> Self {
        let mut acc = Acc::default();
        for t in triangles {
            acc.add(t, positions);
        }
        acc.finish(triangles, positions, slack)
    }

    /// How the triangles these bounds hold face the eye point `eye` (perspective).
    ///
    /// With `d = center - eye`, `D = |d|`, `b` the angle between `axis` and `d`, `a`
    /// the cone's half-angle and `r` the radius: a triangle with unit normal `m` in the
    /// cone and a point `p` in the sphere faces away when `m . (p - eye) >= 0`. Over
    /// the sphere, `min m . (p - eye) = m . d - r`; over the cone, `min m . d =
    /// D cos(b + a)` when `b + a <= pi` (else `-D`). So every triangle faces away when
    ///
    /// `B = D cos(b + a) - r = (axis . d) cos a - sqrt(D^2 - (axis . d)^2) sin a - r >= 0`
    ///
    /// (and `cos a * D >= -(axis . d)`, i.e. `b + a <= pi`), and every triangle faces
    /// the eye when `F`, the same with `-d`, is `> 0`; otherwise [`Facing::Split`]. This
    /// is exact for the cone and the sphere (it misclassifies no triangle they could
    /// hold) and looser than meshoptimizer's apex-free test `axis . d >= D sin a + r`,
    /// which implies it. It is monotone: bounds that hold other bounds face the same way
    /// or are split. `B` and `F` are minima of functions of the eye that are
    /// 1-Lipschitz, so the answer holds while the eye moves less than `|B|` (`|F|`, or
    /// `min(-B, -F)` for a split): [`RenderFront`] skips the test then.
    #[inline]
    pub fn classify(&self, eye: [f32; 3]) -> Facing {
        if self.angle < 0.0 {
            return Facing::Back;
        }
        classify(self.center, self.radius, self.axis, self.cos_angle, self.sin_angle, eye).0
    }
}

/// [`Bounds::classify`] on the parts of non-empty bounds, with the distance the eye may
/// move (exactly; before rounding) without changing the answer.
#[inline(always)]
fn classify(center: [f32; 3], r: f32, axis: [f32; 3], cos_a: f32, sin_a: f32, eye: [f32; 3]) -> (Facing, f32) {
    let d = [center[0] - eye[0], center[1] - eye[1], center[2] - eye[2]];
    let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let dn = axis[0] * d[0] + axis[1] * d[1] + axis[2] * d[2];
    let dd = d2.sqrt();
    // D sin(b) sin(a), and the value of either side where b + a passes pi.
    let s = (d2 - dn * dn).max(0.0).sqrt() * sin_a;
    let far = -dd - r;
    let back = if cos_a * dd >= -dn { dn * cos_a - s - r } else { far };
    let front = if cos_a * dd >= dn { -dn * cos_a - s - r } else { far };
    if back >= 0.0 {
        (Facing::Back, back)
    } else if front > 0.0 {
        (Facing::Front, front)
    } else {
        (Facing::Split, (-back).min(-front))
    }
}

/// A margin of [`classify`] less a bound on its rounding error: how far the eye may move
/// with the f32 test still giving the same answer (negative: no distance).
#[inline(always)]
fn safe_reach(margin: f32, center: [f32; 3], r: f32, eye: [f32; 3]) -> f32 {
    let d = [center[0] - eye[0], center[1] - eye[1], center[2] - eye[2]];
    let scale = d[0].abs() + d[1].abs() + d[2].abs() + r;
    margin - 1e-5 * scale - f32::MIN_POSITIVE
}

/// What the traversal reads of a node: one cache line (the rest is in [`Node`]).
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(64))]
struct Hot {
    center: [f32; 3],
    radius: f32,
    axis: [f32; 3],
    /// `cos(angle)`; 2 for an empty cone (faces away).
    cos: f32,
    sin: f32,
    /// The right child ([`NONE`] for a leaf); the left one is the next node.
    right: u32,
    triangles: u32,
    start: u32,
    end: u32,
    strip: u32,
    parent: u32,
    /// The first node after this node's subtree.
    subtree_end: u32,
}

impl Hot {
    /// [`Hot::classify`] combined with the options' frustum: a node outside it faces
    /// "back" (is skipped; the flag says it was the frustum). With a frustum the reach
    /// is negative (no reuse).
    #[inline(always)]
    fn classify_in(&self, eye: [f32; 3], options: &CullOptions) -> (Facing, f32, bool) {
        let (facing, reach) = self.classify(eye);
        let Some(frustum) = &options.frustum else { return (facing, reach, false) };
        // A back-facing node is skipped anyway: only the others meet the planes.
        let outside = facing != Facing::Back && frustum.side(self.center, self.radius) == Side::Outside;
        (if outside { Facing::Back } else { facing }, -1.0, outside)
    }

    /// The facing and how far the eye may move keeping it (after rounding).
    #[inline(always)]
    fn classify(&self, eye: [f32; 3]) -> (Facing, f32) {
        if self.cos > 1.5 {
            return (Facing::Back, f32::INFINITY);
        }
        let (f, m) = classify(self.center, self.radius, self.axis, self.cos, self.sin, eye);
        (f, safe_reach(m, self.center, self.radius, eye))
    }
}

/// One segment of a strip: a node of the [`SegmentTree`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node {
    /// Conservative normal cone and bounding sphere of the node's triangles. For a
    /// leaf, the cone is around the average normal; for a merged node, it is the
    /// smallest cone that holds both children's cones (axis on the arc between
    /// theirs), which is never wider than the cone around the average normal that
    /// holds them and tests about 15% fewer nodes per view (horse, dragon).
    pub bounds: Bounds,
    /// Unit average (area-weighted) normal of the node's triangles (`[0, 0, 0]` when
    /// they all have zero area).
    pub normal: [f32; 3],
    /// First index of the node's range in [`StripSet::indices`]: an even triangle of
    /// its strip.
    pub start: u32,
    /// One past the last index of the range: `indices[start..end]` drawn as a strip
    /// draws the node's triangles (and swaps, which draw nothing).
    pub end: u32,
    /// The node's leaves are `first_leaf..end_leaf`, counting the leaves of the whole
    /// tree in strip order from 0 ([`SegmentTree::leaves`]).
    pub first_leaf: u32,
    /// One past the node's last leaf.
    pub end_leaf: u32,
    /// Triangles drawn by the range (swaps not counted).
    pub triangles: u32,
    /// The strip of the [`StripSet`] the node lies in.
    pub strip: u32,
    /// The two children, left (earlier in the strip) first; [`NONE`] for a leaf.
    pub children: [u32; 2],
    /// The parent; [`NONE`] for a root.
    pub parent: u32,
}

impl Node {
    /// Whether the node is a leaf (a pair of strip triangles).
    pub fn is_leaf(&self) -> bool {
        self.children[0] == NONE
    }
}

/// Settings of a traversal.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CullOptions {
    /// A split node of at most this many triangles is drawn without testing its
    /// children (0: descend to the leaves, pairs of triangles).
    pub min_triangles: u32,
    /// Two drawn ranges of one strip separated by at most this many culled triangles
    /// are drawn as one range, the back-facing triangles between them included (fewer
    /// draws for a few more triangles; 0: only neighbouring drawn nodes are joined).
    pub max_gap: u32,
    /// Frustum culling with the nodes' bounding spheres: a node wholly outside one
    /// plane is skipped ([`Culled::outside_triangles`]); one that crosses a plane is
    /// classified as without a frustum (a front-facing one is drawn whole and clipped
    /// by the GPU, so the ranges do not multiply at the frustum's edges). The frustum turns with the camera, which the eye
    /// point alone does not tell, so [`RenderFront`] tests every front node again
    /// when a frustum is given (no reuse).
    pub frustum: Option<Frustum>,
}

/// What one view draws: the output of [`SegmentTree::cull`] and [`RenderFront::cull`].
/// Reused between views to keep its buffers.
#[derive(Clone, Debug, Default)]
pub struct Culled {
    /// Index ranges into [`StripSet::indices`], in strip order, each drawn as its own
    /// strip (a multi-draw); neighbouring drawn nodes are merged into one range.
    pub ranges: Vec<Range<u32>>,
    /// Triangles in the drawn ranges (swaps not counted).
    pub drawn_triangles: usize,
    /// Triangles in the skipped nodes (all of them back-facing or edge-on, or outside
    /// the frustum).
    pub culled_triangles: usize,
    /// Of those, triangles in nodes skipped only because they lie outside the
    /// [`CullOptions::frustum`].
    pub outside_triangles: usize,
    /// Nodes classified.
    pub visited: usize,
    /// Drawn nodes that were split (leaves or small nodes across the silhouette).
    pub split_drawn: usize,
    /// The last drawn node's strip, for merging ranges.
    last_strip: u32,
    /// Triangles culled since the last drawn node of its strip.
    gap: usize,
    /// [`CullOptions::max_gap`] of the traversal.
    max_gap: usize,
    /// Front nodes kept by [`RenderFront::cull`] without a test (the eye moved less
    /// than their margin since they were tested).
    pub reused: usize,
    /// The traversal's stack (node, its parent's reach), kept between views.
    stack: Vec<(u32, f32)>,
}

impl Culled {
    fn clear(&mut self, options: &CullOptions) {
        self.gap = 0;
        self.max_gap = options.max_gap as usize;
        self.ranges.clear();
        self.drawn_triangles = 0;
        self.culled_triangles = 0;
        self.outside_triangles = 0;
        self.visited = 0;
        self.split_drawn = 0;
        self.reused = 0;
        self.last_strip = NONE;
    }

    #[inline]
    fn emit_back(&mut self, triangles: u32) {
        self.culled_triangles += triangles as usize;
        self.gap += triangles as usize;
    }

    #[inline]
    fn emit(&mut self, node: &Hot, facing: Facing) {
        self.emit_parts(node.start, node.end, node.strip, node.triangles, facing);
    }

    #[inline]
    fn emit_parts(&mut self, start: u32, end: u32, strip: u32, triangles: u32, facing: Facing) {
        if facing == Facing::Back {
            self.emit_back(triangles);
            return;
        }
        if facing == Facing::Split {
            self.split_drawn += 1;
        }
        self.drawn_triangles += triangles as usize;
        // The nodes between the last drawn one of this strip and this one were all
        // culled: `gap` triangles (none when the leaves are neighbours, as every node
        // has a triangle).
        match self.ranges.last_mut() {
            Some(r) if self.last_strip == strip && self.gap <= self.max_gap => {
                r.end = end;
                self.drawn_triangles += self.gap;
                self.culled_triangles -= self.gap;
            }
            _ => self.ranges.push(start..end),
        }
        self.gap = 0;
        self.last_strip = strip;
    }
}

/// The segment tree of a [`StripSet`]: one binary tree per strip (a forest), nodes in
/// one `Vec` in depth-first pre-order (a node, its left subtree, its right subtree; the
/// trees in strip order).
#[derive(Clone, Debug, Default)]
pub struct SegmentTree {
    /// The nodes, depth-first (a left child right after its parent).
    pub nodes: Vec<Node>,
    /// The root of each strip with a drawable triangle, in strip order.
    pub roots: Vec<u32>,
    /// Number of leaves.
    pub leaf_count: u32,
    /// The traversal's compact copy of the nodes.
    hot: Vec<Hot>,
}

/// Running sums for the bounds of a set of triangles.
#[derive(Clone, Copy, Default)]
struct Acc {
    normal: [f64; 3],
    vertex_sum: [f64; 3],
    vertices: f64,
    area: f64,
}

fn angle_between(a: [f64; 3], b: [f64; 3]) -> f64 {
    // atan2 of |a x b| and a . b: accurate at small angles.
    norm(cross(a, b)).atan2(dot(a, b))
}
fn p64(p: [f32; 3]) -> [f64; 3] {
    [p[0] as f64, p[1] as f64, p[2] as f64]
}
fn f32s(a: [f64; 3]) -> [f32; 3] {
    [a[0] as f32, a[1] as f32, a[2] as f32]
}

/// The (area-scaled) normal of a triangle: `(b - a) x (c - a)`.
pub(crate) fn triangle_normal(t: &[u32; 3], positions: &[[f32; 3]]) -> [f64; 3] {
    let [a, b, c] = t.map(|v| p64(positions[v as usize]));
    tri_normal(a, b, c)
}

impl Acc {
    fn add(&mut self, t: &[u32; 3], positions: &[[f32; 3]]) {
        let n = triangle_normal(t, positions);
        self.normal = add(self.normal, n);
        self.area += norm(n);
        for &v in t {
            self.vertex_sum = add(self.vertex_sum, p64(positions[v as usize]));
            self.vertices += 1.0;
        }
    }

    fn center(&self) -> [f64; 3] {
        let n = self.vertices.max(1.0);
        [self.vertex_sum[0] / n, self.vertex_sum[1] / n, self.vertex_sum[2] / n]
    }

    /// Exact bounds of `triangles` around the average normal and the centroid.
    fn finish(&self, triangles: &[[u32; 3]], positions: &[[f32; 3]], slack: [f64; 2]) -> Bounds {
        let c = self.center();
        let mut radius = 0.0f64;
        let mut normals = triangles.iter().filter_map(|t| unit(triangle_normal(t, positions))).peekable();
        let axis = unit(self.normal).or_else(|| normals.peek().copied());
        let mut angle = -1.0f64;
        if let Some(axis) = axis {
            for m in normals {
                angle = angle.max(angle_between(axis, m));
            }
        }
        for t in triangles {
            for &v in t {
                radius = radius.max(norm(sub(p64(positions[v as usize]), c)));
            }
        }
        let axis = axis.unwrap_or([0.0, 0.0, 1.0]);
        let angle = if angle < 0.0 { -1.0 } else { angle + slack[0] };
        let b = Bounds::new(f32s(axis), angle as f32, f32s(c), (radius + slack[1]) as f32);
        if angle < 0.0 {
            Bounds { angle: -1.0, ..b }
        } else {
            b
        }
    }
}

/// Build state of a node: its sums and its exact-in-f64 bounds.
#[derive(Clone, Copy)]
struct Work {
    acc: Acc,
    axis: [f64; 3],
    angle: f64, // < 0: empty cone
    center: [f64; 3],
    radius: f64,
}

impl Work {
    fn merge(a: &Work, b: &Work, slack: [f64; 2]) -> Work {
        let mut acc = a.acc;
        acc.normal = add(acc.normal, b.acc.normal);
        acc.vertex_sum = add(acc.vertex_sum, b.acc.vertex_sum);
        acc.vertices += b.acc.vertices;
        acc.area += b.acc.area;
        let (axis, angle) = match (a.angle >= 0.0, b.angle >= 0.0) {
            (false, false) => (a.axis, -1.0),
            (true, false) => (a.axis, a.angle),
            (false, true) => (b.axis, b.angle),
            (true, true) => {
                let (axis, angle) = enclosing_cone(a.axis, a.angle, b.axis, b.angle);
                (axis, (angle + slack[0]).min(std::f64::consts::PI))
            }
        };
        let center = acc.center();
        let radius = (norm(sub(center, a.center)) + a.radius).max(norm(sub(center, b.center)) + b.radius) + slack[1];
        Work { acc, axis, angle, center, radius }
    }

    fn bounds(&self) -> Bounds {
        let b = Bounds::new(f32s(self.axis), self.angle as f32, f32s(self.center), self.radius as f32);
        if self.angle < 0.0 {
            Bounds { angle: -1.0, ..b }
        } else {
            b
        }
    }
}

/// The smallest cone that holds the cones `(a, x)` and `(b, y)` (unit axes,
/// half-angles): its axis on the arc from `a` to `b`, half-angle `(t + x + y) / 2` for
/// the angle `t` between the axes, unless one cone holds the other.
fn enclosing_cone(a: [f64; 3], x: f64, b: [f64; 3], y: f64) -> ([f64; 3], f64) {
    let t = angle_between(a, b);
    if t + y <= x {
        return (a, x);
    }
    if t + x <= y {
        return (b, y);
    }
    let angle = (t + x + y) / 2.0;
    if angle >= std::f64::consts::PI || t.sin() < 1e-9 {
        // Opposite axes (or nearly): keep the one and cover the other.
        return (a, (t + y).max(x).min(std::f64::consts::PI));
    }
    // Rotate a towards b by angle - x.
    let u = angle - x;
    let (su, sr, st) = (u.sin(), (t - u).sin(), t.sin());
    let axis = unit([(sr * a[0] + su * b[0]) / st, (sr * a[1] + su * b[1]) / st, (sr * a[2] + su * b[2]) / st]).unwrap_or(a);
    // Rounding: make sure both cones are held.
    let angle = angle.max(angle_between(axis, a) + x).max(angle_between(axis, b) + y);
    (axis, angle)
}

/// The merge priority of a pair: the merged cone's half-angle in steps of a quarter
/// degree, then the merged triangle count (so that nearly flat regions merge as
/// balanced subtrees rather than chains).
fn merge_key(w: &Work, triangles: u32) -> u64 {
    let steps = if w.angle < 0.0 { 0 } else { (w.angle.to_degrees() * 4.0).ceil() as u64 + 1 };
    (steps << 32) | triangles as u64
}


impl SegmentTree {
    /// The slack [`SegmentTree::build`] widens cones and spheres by: `1e-5` radians,
    /// and `1e-5` times the diagonal of the bounding box of the strips' vertices (for
    /// [`Bounds::of_triangles`] on bounds of one's own).
    pub fn slack(strips: &StripSet, positions: &[[f32; 3]]) -> [f64; 2] {
        let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
        for &v in &strips.indices {
            let p = p64(positions[v as usize]);
            lo = std::array::from_fn(|k| lo[k].min(p[k]));
            hi = std::array::from_fn(|k| hi[k].max(p[k]));
        }
        let size = if strips.indices.is_empty() { 1.0 } else { norm(sub(hi, lo)).max(1e-30) };
        [1e-5, 1e-5 * size]
    }

    /// Builds the tree of every strip of `strips` (indices into `positions`).
    ///
    /// Leaves are pairs of strip triangles `2k, 2k + 1` (from the strip's start) with at
    /// least one drawable triangle (see the module docs on parity). Adjacent segments of
    /// one strip are merged, smallest merged normal cone first (ties: fewest
    /// triangles). A merged node's cone is the smallest that holds both children's
    /// cones; its sphere is centred at the centroid of its
    /// vertices and holds both children's spheres; both are widened by a slack of
    /// `1e-5` (radians, and times the size of the positions' bounding box) so that the
    /// f32 test stays monotone down the tree. `O(n log n)` in the triangles.
    pub fn build(strips: &StripSet, positions: &[[f32; 3]]) -> SegmentTree {
        let slack = Self::slack(strips, positions);

        let mut nodes: Vec<Node> = Vec::new();
        let mut work: Vec<Work> = Vec::new();
        let mut strip_leaves: Vec<Range<u32>> = Vec::new();
        let mut tris: Vec<[u32; 3]> = Vec::with_capacity(2);
        for (s, strip) in strips.iter().enumerate() {
            let base = strips.offsets[s];
            let first = nodes.len() as u32;
            let count = strip.len().saturating_sub(2);
            for k in (0..count).step_by(2) {
                tris.clear();
                let mut last = 0;
                for i in k..(k + 2).min(count) {
                    let t = if i % 2 == 0 {
                        [strip[i], strip[i + 1], strip[i + 2]]
                    } else {
                        [strip[i + 1], strip[i], strip[i + 2]]
                    };
                    if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                        tris.push(t);
                        last = i;
                    }
                }
                if tris.is_empty() {
                    continue;
                }
                let mut acc = Acc::default();
                for t in &tris {
                    acc.add(t, positions);
                }
                let b = acc.finish(&tris, positions, slack);
                let id = nodes.len() as u32;
                work.push(Work {
                    acc,
                    axis: p64(b.axis),
                    angle: b.angle as f64,
                    center: p64(b.center),
                    radius: b.radius as f64,
                });
                nodes.push(Node {
                    bounds: b,
                    normal: f32s(unit(acc.normal).unwrap_or([0.0; 3])),
                    start: base + k as u32,
                    end: base + last as u32 + 3,
                    first_leaf: id,
                    end_leaf: id + 1,
                    triangles: tris.len() as u32,
                    strip: s as u32,
                    children: [NONE; 2],
                    parent: NONE,
                });
            }
            strip_leaves.push(first..nodes.len() as u32);
        }
        let leaf_count = nodes.len() as u32;

        // Linked list of the current segments of each strip, and a heap of adjacent
        // pairs (stale entries skipped: a pair is live while both are unmerged and
        // still neighbours).
        let cap = 2 * nodes.len();
        let mut next: Vec<u32> = Vec::with_capacity(cap);
        let mut prev: Vec<u32> = Vec::with_capacity(cap);
        for range in &strip_leaves {
            for id in range.clone() {
                prev.push(if id > range.start { id - 1 } else { NONE });
                next.push(if id + 1 < range.end { id + 1 } else { NONE });
            }
        }
        let mut heap: BinaryHeap<Reverse<(u64, u32, u32)>> = BinaryHeap::with_capacity(nodes.len());
        let pair_key = |work: &[Work], nodes: &[Node], a: u32, b: u32| {
            let w = Work::merge(&work[a as usize], &work[b as usize], slack);
            merge_key(&w, nodes[a as usize].triangles + nodes[b as usize].triangles)
        };
        for a in 0..leaf_count {
            let b = next[a as usize];
            if b != NONE {
                heap.push(Reverse((pair_key(&work, &nodes, a, b), a, b)));
            }
        }
        while let Some(Reverse((_, a, b))) = heap.pop() {
            let (ai, bi) = (a as usize, b as usize);
            if nodes[ai].parent != NONE || nodes[bi].parent != NONE || next[ai] != b {
                continue;
            }
            let w = Work::merge(&work[ai], &work[bi], slack);
            let id = nodes.len() as u32;
            let (na, nb) = (nodes[ai], nodes[bi]);
            nodes.push(Node {
                bounds: w.bounds(),
                normal: f32s(unit(w.acc.normal).unwrap_or([0.0; 3])),
                start: na.start,
                end: nb.end,
                first_leaf: na.first_leaf,
                end_leaf: nb.end_leaf,
                triangles: na.triangles + nb.triangles,
                strip: na.strip,
                children: [a, b],
                parent: NONE,
            });
            work.push(w);
            nodes[ai].parent = id;
            nodes[bi].parent = id;
            let (p, n) = (prev[ai], next[bi]);
            prev.push(p);
            next.push(n);
            if p != NONE {
                next[p as usize] = id;
                heap.push(Reverse((pair_key(&work, &nodes, p, id), p, id)));
            }
            if n != NONE {
                prev[n as usize] = id;
                heap.push(Reverse((pair_key(&work, &nodes, id, n), id, n)));
            }
        }
        let mut roots: Vec<u32> = (0..nodes.len() as u32).filter(|&i| nodes[i as usize].parent == NONE).collect();
        roots.sort_by_key(|&r| nodes[r as usize].first_leaf);
        // Depth-first pre-order, left child first: a subtree is one block of memory,
        // a left child follows its parent, the leaves come in strip order.
        let mut order: Vec<u32> = Vec::with_capacity(nodes.len());
        let mut stack: Vec<u32> = Vec::new();
        for &r in &roots {
            stack.push(r);
            while let Some(id) = stack.pop() {
                order.push(id);
                let n = &nodes[id as usize];
                if !n.is_leaf() {
                    stack.push(n.children[1]);
                    stack.push(n.children[0]);
                }
            }
        }
        let mut new_id = vec![NONE; nodes.len()];
        for (i, &old) in order.iter().enumerate() {
            new_id[old as usize] = i as u32;
        }
        let map = |id: u32| if id == NONE { NONE } else { new_id[id as usize] };
        let nodes: Vec<Node> = order
            .iter()
            .map(|&old| {
                let n = nodes[old as usize];
                Node { children: n.children.map(map), parent: map(n.parent), ..n }
            })
            .collect();
        let roots = roots.into_iter().map(map).collect();
        let mut hot: Vec<Hot> = nodes
            .iter()
            .enumerate()
            .map(|(i, n)| {
                let b = &n.bounds;
                debug_assert!(n.is_leaf() || n.children[0] == i as u32 + 1);
                Hot {
                    center: b.center,
                    radius: b.radius,
                    axis: b.axis,
                    cos: if b.angle < 0.0 { 2.0 } else { b.cos_angle },
                    sin: b.sin_angle,
                    right: n.children[1],
                    triangles: n.triangles,
                    start: n.start,
                    end: n.end,
                    strip: n.strip,
                    parent: n.parent,
                    subtree_end: i as u32 + 1,
                }
            })
            .collect();
        // Children come after their parent: the right child's subtree ends last.
        for i in (0..hot.len()).rev() {
            if hot[i].right != NONE {
                hot[i].subtree_end = hot[hot[i].right as usize].subtree_end;
            }
        }
        SegmentTree { nodes, roots, leaf_count, hot }
    }

    /// The leaves (node ids), in strip order.
    pub fn leaves(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.nodes.len() as u32).filter(|&i| self.nodes[i as usize].is_leaf())
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the tree has no node (no drawable triangle).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Depth of the deepest leaf (a root alone: 0).
    pub fn depth(&self) -> usize {
        let mut depth = vec![0u32; self.nodes.len()];
        let mut max = 0;
        // Parents come before their children.
        for i in 0..self.nodes.len() {
            let p = self.nodes[i].parent;
            if p != NONE {
                depth[i] = depth[p as usize] + 1;
                max = max.max(depth[i]);
            }
        }
        max as usize
    }

    /// Descends from `id` (whose ancestors are all split; `reach`: how far the eye
    /// may move keeping its parent split), emitting the stopping nodes in strip order;
    /// `front`, when given, receives them with how far the eye may move keeping them.
    fn descend(
        &self,
        id: u32,
        reach: f32,
        eye: [f32; 3],
        options: &CullOptions,
        out: &mut Culled,
        mut front: Option<&mut Vec<Entry>>,
    ) {
        let mut stack = std::mem::take(&mut out.stack);
        stack.clear();
        let mut next = Some((id, reach));
        // The left child is visited right after its parent (the next node in memory);
        // the right one waits on the stack.
        while let Some((id, parent_reach)) = next.or_else(|| stack.pop()) {
            let h = &self.hot[id as usize];
            let (facing, reach, outside) = h.classify_in(eye, options);
            out.visited += 1;
            if facing != Facing::Split || h.right == NONE || h.triangles <= options.min_triangles {
                if outside {
                    out.outside_triangles += h.triangles as usize;
                }
                out.emit(h, facing);
                if let Some(f) = front.as_deref_mut() {
                    f.push(Entry::new(id, h, facing, eye, reach.min(parent_reach)));
                }
                next = None;
            } else {
                stack.push((h.right, reach));
                next = Some((id + 1, reach));
            }
        }
        out.stack = stack;
    }

    /// The ranges to draw for the eye point `eye`, traversing from the roots.
    pub fn cull(&self, eye: [f32; 3], options: &CullOptions, out: &mut Culled) {
        out.clear(options);
        for &r in &self.roots {
            self.descend(r, f32::INFINITY, eye, options, out, None);
        }
    }
}

/// A node of the render front and what drawing it needs, with the eye it was tested
/// from and the squared distance the eye may move from there keeping it.
#[derive(Clone, Copy, Debug)]
struct Entry {
    node: u32,
    subtree_end: u32,
    start: u32,
    end: u32,
    strip: u32,
    triangles: u32,
    facing: Facing,
    eye: [f32; 3],
    reach2: f32,
}

impl Entry {
    fn new(node: u32, h: &Hot, facing: Facing, eye: [f32; 3], reach: f32) -> Self {
        Entry {
            node,
            subtree_end: h.subtree_end,
            start: h.start,
            end: h.end,
            strip: h.strip,
            triangles: h.triangles,
            facing,
            eye,
            reach2: if reach > 0.0 { reach * reach } else { -1.0 },
        }
    }
}

/// The render front: the lowest nodes tested in the last frame (those where the
/// traversal stopped), in strip order. The next frame starts there: a node whose parent
/// now stops the traversal is merged up (as far as its ancestors stop it), a node that
/// is now split is split, the others stay. The classification is monotone down the
/// tree (a node's bounds hold its children's), so this gives exactly the ranges of
/// [`SegmentTree::cull`] from the roots.
///
/// Each node of the front keeps the eye it was tested from and the smaller of its own
/// margin and its parent's ([`Bounds::classify`], less a bound on rounding): while the
/// eye stays that close, the node still stops the traversal with the same answer and
/// its parent is still split, so it is kept without a test ([`Culled::reused`]).
#[derive(Clone, Debug, Default)]
pub struct RenderFront {
    nodes: Vec<Entry>,
    scratch: Vec<Entry>,
}

impl RenderFront {
    /// A front at the roots (the first frame then traverses from the roots).
    pub fn new(tree: &SegmentTree) -> Self {
        let nodes = tree
            .roots
            .iter()
            .map(|&r| Entry::new(r, &tree.hot[r as usize], Facing::Split, [0.0; 3], -1.0))
            .collect();
        RenderFront { nodes, scratch: Vec::new() }
    }

    /// The nodes of the front, in strip order.
    pub fn nodes(&self) -> Vec<u32> {
        self.nodes.iter().map(|e| e.node).collect()
    }

    /// The ranges to draw for `eye`, starting at the front, which moves to this
    /// view's stopping nodes. `tree` must be the tree the front was made for.
    pub fn cull(&mut self, tree: &SegmentTree, eye: [f32; 3], options: &CullOptions, out: &mut Culled) {
        out.clear(options);
        let mut new = std::mem::take(&mut self.scratch);
        new.clear();
        // Nodes below a node already emitted are skipped: the end of its subtree.
        let mut covered_to = 0u32;
        // The last parent tested: whether it stopped, its facing and reach (siblings
        // share it).
        let mut tested: (u32, bool, Facing, f32, bool) = (NONE, false, Facing::Split, 0.0, false);
        for e in &self.nodes {
            let x = e.node;
            if x < covered_to {
                continue;
            }
            let m = [eye[0] - e.eye[0], eye[1] - e.eye[1], eye[2] - e.eye[2]];
            if m[0] * m[0] + m[1] * m[1] + m[2] * m[2] < e.reach2 {
                out.emit_parts(e.start, e.end, e.strip, e.triangles, e.facing);
                out.reused += 1;
                new.push(*e);
                covered_to = e.subtree_end;
                continue;
            }
            // Merge up while the parent stops the traversal.
            let (mut top, mut top_facing, mut top_reach, mut top_outside) = (x, None, f32::INFINITY, false);
            let mut parent_reach = f32::INFINITY;
            loop {
                let p = tree.hot[top as usize].parent;
                if p == NONE {
                    break;
                }
                let (stops, facing, reach, outside) = if tested.0 == p {
                    (tested.1, tested.2, tested.3, tested.4)
                } else {
                    let h = &tree.hot[p as usize];
                    let (facing, reach, outside) = h.classify_in(eye, options);
                    out.visited += 1;
                    // A parent is never a leaf.
                    let stops = facing != Facing::Split || h.triangles <= options.min_triangles;
                    tested = (p, stops, facing, reach, outside);
                    (stops, facing, reach, outside)
                };
                if !stops {
                    parent_reach = reach;
                    break;
                }
                top = p;
                top_facing = Some(facing);
                top_reach = reach;
                top_outside = outside;
            }
            match top_facing {
                Some(facing) => {
                    let t = &tree.hot[top as usize];
                    if top_outside {
                        out.outside_triangles += t.triangles as usize;
                    }
                    out.emit(t, facing);
                    new.push(Entry::new(top, t, facing, eye, top_reach.min(parent_reach)));
                    covered_to = t.subtree_end;
                }
                None => {
                    tree.descend(x, parent_reach, eye, options, out, Some(&mut new));
                    covered_to = tree.hot[x as usize].subtree_end;
                }
            }
        }
        self.scratch = std::mem::replace(&mut self.nodes, new);
    }
}

//! The segment tree: its nodes, and its bottom-up build over the strips.

use super::bounds::{classify, f32s, p64, safe_reach, Acc, Bounds, Work};
use super::{Facing, NONE};
use crate::vec3::{norm, sub, unit};
use crate::strip::StripSet;
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::ops::Range;

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
    /// The two children, left (earlier in the strip) first; `u32::MAX` for a leaf
    /// ([`Node::is_leaf`]).
    pub children: [u32; 2],
    /// The parent; `u32::MAX` for a root ([`Node::is_root`]).
    pub parent: u32,
}

impl Node {
    /// Whether the node is a leaf (a pair of strip triangles).
    pub fn is_leaf(&self) -> bool {
        self.children[0] == NONE
    }

    /// Whether the node is a root (the top of its strip's tree).
    pub fn is_root(&self) -> bool {
        self.parent == NONE
    }
}

/// What the traversal reads of a node: one cache line (the rest is in [`Node`]).
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(64))]
pub(super) struct Hot {
    pub(super) center: [f32; 3],
    pub(super) radius: f32,
    pub(super) axis: [f32; 3],
    /// `cos(angle)`; 2 for an empty cone (faces away).
    pub(super) cos: f32,
    pub(super) sin: f32,
    /// The right child ([`NONE`] for a leaf); the left one is the next node.
    pub(super) right: u32,
    pub(super) triangles: u32,
    pub(super) start: u32,
    pub(super) end: u32,
    pub(super) strip: u32,
    pub(super) parent: u32,
    /// The first node after this node's subtree.
    pub(super) subtree_end: u32,
}

impl Hot {
    /// The facing and how far the eye may move keeping it (after rounding).
    #[inline(always)]
    pub(super) fn classify(&self, eye: [f32; 3]) -> (Facing, f32) {
        if self.cos > 1.5 {
            return (Facing::Back, f32::INFINITY);
        }
        let (f, m) = classify(self.center, self.radius, self.axis, self.cos, self.sin, eye);
        (f, safe_reach(m, self.center, self.radius, eye))
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
    pub(super) hot: Vec<Hot>,
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
        let (mut nodes, mut work, strip_leaves) = leaves(strips, positions, slack);
        let leaf_count = nodes.len() as u32;
        merge_neighbours(&mut nodes, &mut work, &strip_leaves, slack);
        let (nodes, roots) = preorder(nodes);
        let hot = hot_copy(&nodes);
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
}

/// The leaves of every strip, with their build state, and the range of leaf ids of
/// each strip: a leaf per pair of strip triangles `2k, 2k + 1` with at least one
/// drawable triangle.
fn leaves(strips: &StripSet, positions: &[[f32; 3]], slack: [f64; 2]) -> (Vec<Node>, Vec<Work>, Vec<Range<u32>>) {
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
    (nodes, work, strip_leaves)
}

/// Merges neighbouring segments of each strip (`strip_leaves`: the leaves of each),
/// the pair with the smallest merged cone first (ties: fewest triangles), until each
/// strip is one tree; the parents are appended to `nodes` and `work`.
fn merge_neighbours(nodes: &mut Vec<Node>, work: &mut Vec<Work>, strip_leaves: &[Range<u32>], slack: [f64; 2]) {
    let leaf_count = nodes.len() as u32;
    // Linked list of the current segments of each strip, and a heap of adjacent
    // pairs (stale entries skipped: a pair is live while both are unmerged and
    // still neighbours).
    let cap = 2 * nodes.len();
    let mut next: Vec<u32> = Vec::with_capacity(cap);
    let mut prev: Vec<u32> = Vec::with_capacity(cap);
    for range in strip_leaves {
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
            heap.push(Reverse((pair_key(work, nodes, a, b), a, b)));
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
            heap.push(Reverse((pair_key(work, nodes, p, id), p, id)));
        }
        if n != NONE {
            prev[n as usize] = id;
            heap.push(Reverse((pair_key(work, nodes, id, n), id, n)));
        }
    }
}

/// The nodes renumbered depth-first in pre-order, left child first (a subtree is one
/// block of memory, a left child follows its parent, the leaves come in strip order),
/// and the roots in strip order.
fn preorder(nodes: Vec<Node>) -> (Vec<Node>, Vec<u32>) {
    let mut roots: Vec<u32> = (0..nodes.len() as u32).filter(|&i| nodes[i as usize].parent == NONE).collect();
    roots.sort_by_key(|&r| nodes[r as usize].first_leaf);
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
    (nodes, roots)
}

/// The traversal's compact copy of the (pre-ordered) nodes.
fn hot_copy(nodes: &[Node]) -> Vec<Hot> {
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
    hot
}

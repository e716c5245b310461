//! Traversals of the [`SegmentTree`] for an eye point: from the roots
//! ([`SegmentTree::cull`]) or from the last frame's render front ([`RenderFront`]),
//! with the ranges they draw ([`Culled`]).

use super::frustum::{Frustum, Side};
use super::tree::{Hot, SegmentTree};
use super::{Facing, NONE};
use std::ops::Range;

/// Settings of a traversal. The default descends to the leaves, joins only
/// neighbouring drawn nodes and culls no frustum; change it with the builder methods.
///
/// ```
/// use stripkit::cull::CullOptions;
/// let options = CullOptions::default().min_triangles(64).max_gap(16);
/// assert_eq!((options.min_triangles, options.max_gap, options.frustum), (64, 16, None));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct CullOptions {
    /// A split node of at most this many triangles is drawn without testing its
    /// children (0, the default: descend to the leaves, pairs of triangles).
    pub min_triangles: u32,
    /// Two drawn ranges of one strip separated by at most this many culled triangles
    /// are drawn as one range, the back-facing triangles between them included (fewer
    /// draws for a few more triangles; 0, the default: only neighbouring drawn nodes
    /// are joined).
    pub max_gap: u32,
    /// Frustum culling with the nodes' bounding spheres (default `None`: none): a node
    /// wholly outside one plane is skipped ([`Culled::outside_triangles`]); one that
    /// crosses a plane is classified as without a frustum (a front-facing one is drawn
    /// whole and clipped by the GPU, so the ranges do not multiply at the frustum's
    /// edges). The frustum turns with the camera, which the eye point alone does not
    /// tell, so [`RenderFront`] tests every front node again when a frustum is given
    /// (no reuse).
    pub frustum: Option<Frustum>,
}

impl CullOptions {
    /// Sets [`CullOptions::min_triangles`].
    pub fn min_triangles(mut self, triangles: u32) -> Self {
        self.min_triangles = triangles;
        self
    }

    /// Sets [`CullOptions::max_gap`].
    pub fn max_gap(mut self, triangles: u32) -> Self {
        self.max_gap = triangles;
        self
    }

    /// Sets [`CullOptions::frustum`].
    pub fn frustum(mut self, frustum: Option<Frustum>) -> Self {
        self.frustum = frustum;
        self
    }
}

/// What one view draws: the output of [`SegmentTree::cull`] and [`RenderFront::cull`].
/// Reused between views to keep its buffers.
#[derive(Clone, Debug, Default)]
pub struct Culled {
    /// Index ranges into [`StripSet::indices`](crate::StripSet::indices), in strip order, each drawn as its own
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

}

impl SegmentTree {
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
/// margin and its parent's ([`Bounds::classify`](super::bounds::Bounds::classify), less a bound on rounding): while the
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

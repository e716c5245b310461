//! Walks through the [`DualGraph`] and their encoding as strips.
//!
//! A *walk* is a sequence of triangles, each a [`DualGraph`] neighbour of the one
//! before: what every stripifier builds and every local search of [`crate::improve`]
//! rewrites. [`Walks`] holds a list of them, flat (triangle ids and offsets), in output
//! order. [`encode_path`] turns one walk into one strip with the fewest swaps for that
//! walk. Because dual neighbours share an edge traversed in opposite directions, the
//! strip rule then gives every triangle its input winding.
//!
//! In a walk `t0, t1, .., tk` call the edge shared by `t(i-1)` and `t(i)` `E(i)`, and the
//! vertex shared by `E(i)` and `E(i+1)` the *pivot* of `t(i)`. A strip alternates its
//! turns by itself; it needs a swap (one repeated index) exactly at an inner triangle
//! whose pivot equals the pivot of the triangle before it (three consecutive shared
//! edges around one vertex). The first triangle has no pivot: reading the walk from
//! `t0`, `t1` needs a swap when its pivot is the *tail* of `E(1)` as `t0` runs it.
//! [`encode_path`] therefore reads a walk from whichever end needs fewer swaps.

use crate::strip::StripSet;
use crate::topology::{DualGraph, NO_NEIGHBOR};

/// Walks through a [`DualGraph`] (each a sequence of triangle ids, each a neighbour of
/// the one before), stored flat: walk `i` is `triangles()[offsets[i]..offsets[i + 1]]`.
/// The triangles after the last offset form the walk being built (see
/// [`Walks::push_triangle`] and [`Walks::end_walk`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Walks {
    tris: Vec<u32>,
    /// Always holds the leading 0.
    offsets: Vec<u32>,
}

impl Default for Walks {
    fn default() -> Self {
        Walks::new()
    }
}

impl Walks {
    /// No walks.
    pub fn new() -> Self {
        Walks { tris: Vec::new(), offsets: vec![0] }
    }

    /// No walks, room for `triangles` triangle ids.
    pub fn with_capacity(triangles: usize) -> Self {
        Walks { tris: Vec::with_capacity(triangles), offsets: vec![0] }
    }

    /// Appends a walk.
    #[cfg(test)]
    pub fn push(&mut self, walk: &[u32]) {
        self.tris.extend_from_slice(walk);
        self.end_walk();
    }

    /// Appends the triangles of `walk` as one walk.
    pub fn push_iter(&mut self, walk: impl IntoIterator<Item = u32>) {
        self.tris.extend(walk);
        self.end_walk();
    }

    /// Appends triangle `t` to the walk being built.
    #[inline]
    pub fn push_triangle(&mut self, t: u32) {
        self.tris.push(t);
    }

    /// Ends the walk being built (a walk of the triangles pushed since the last end).
    #[inline]
    pub fn end_walk(&mut self) {
        self.offsets.push(self.tris.len() as u32);
    }

    /// Opens the last walk again, so that [`Walks::push_triangle`] goes on with it.
    pub fn reopen_last(&mut self) {
        if self.offsets.len() > 1 {
            self.offsets.pop();
        }
    }

    /// Number of (ended) walks.
    #[cfg(test)]
    pub fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    /// True when there is no walk.
    #[cfg(test)]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Walk `i`.
    #[cfg(test)]
    pub fn walk(&self, i: usize) -> &[u32] {
        &self.tris[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }

    /// The walks in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        self.offsets.windows(2).map(move |w| &self.tris[w[0] as usize..w[1] as usize])
    }

    /// Every triangle of every walk, in order.
    pub fn triangles(&self) -> &[u32] {
        &self.tris
    }

    /// The walks held as strips of triangle ids (for the tests of `improve::tunnel`, written
    /// on strips of triangle ids).
    #[cfg(test)]
    pub(crate) fn from_strip_set(set: &StripSet) -> Walks {
        let mut offsets = set.offsets.clone();
        if offsets.is_empty() {
            offsets.push(0);
        }
        Walks { tris: set.indices.clone(), offsets }
    }

    /// The walks as a [`StripSet`] of triangle ids (see [`Walks::from_strip_set`]).
    #[cfg(test)]
    pub(crate) fn into_strip_set(self) -> StripSet {
        StripSet { indices: self.tris, offsets: self.offsets }
    }

    /// Every walk encoded as one strip with [`encode_path`], in order.
    pub fn encode(&self, tris: &[[u32; 3]], graph: &DualGraph) -> StripSet {
        let mut out = StripSet::new();
        out.indices.reserve(self.tris.len() + self.tris.len() / 4);
        for w in self.iter() {
            encode_path(tris, graph, w, &mut out);
        }
        out
    }
}

/// The slot `j` of triangle `t` (edge `(t[j], t[j+1])`) across which `next` lies,
/// other than the edge `{avoid.0, avoid.1}`.
#[inline]
fn link_slot(tri: &[u32; 3], nbr: &[u32; 3], next: u32, avoid: (u32, u32)) -> Option<usize> {
    (0..3).find(|&j| {
        let (u, v) = (tri[j], tri[(j + 1) % 3]);
        nbr[j] == next && !((u == avoid.0 && v == avoid.1) || (u == avoid.1 && v == avoid.0))
    })
}

/// Walks a path in the order `at(0), at(1), ..`, emitting the strip's indices; returns
/// the number of swaps. Panics when two consecutive triangles are not dual neighbours.
pub(crate) fn walk(
    tris: &[[u32; 3]],
    graph: &DualGraph,
    len: usize,
    at: impl Fn(usize) -> u32,
    mut emit: impl FnMut(u32),
) -> usize {
    if len == 0 {
        return 0;
    }
    let t0 = at(0) as usize;
    let tri = &tris[t0];
    if len == 1 {
        tri.iter().for_each(|&v| emit(v));
        return 0;
    }
    let j = link_slot(tri, &graph.neighbors[t0], at(1), (NO_NEIGHBOR, NO_NEIGHBOR))
        .expect("encode_path: consecutive triangles are not dual neighbours");
    let (x, y, a) = (tri[j], tri[(j + 1) % 3], tri[(j + 2) % 3]);
    emit(a);
    emit(x);
    emit(y);
    let (mut p, mut q) = (x, y);
    let mut swaps = 0;
    for i in 1..len {
        let t = at(i) as usize;
        let tri = &tris[t];
        let r = *tri
            .iter()
            .find(|&&v| v != p && v != q)
            .expect("walk: triangle lost its entry edge");
        if i + 1 < len {
            let k = link_slot(tri, &graph.neighbors[t], at(i + 1), (p, q))
                .expect("encode_path: consecutive triangles are not dual neighbours");
            let (u, v) = (tri[k], tri[(k + 1) % 3]);
            if u == q || v == q {
                emit(r);
                p = q;
            } else {
                emit(p);
                emit(r);
                swaps += 1;
            }
            q = r;
        } else {
            emit(r);
        }
    }
    swaps
}

/// True when a strip read from `a` through `b` to `c` needs a swap at `b`: the pivot
/// of `b` is the tail of the edge `a -> b` as `a` runs it.
fn start_swap(tris: &[[u32; 3]], graph: &DualGraph, a: u32, b: u32, c: u32) -> bool {
    let ta = &tris[a as usize];
    let Some(j) = link_slot(
        ta,
        &graph.neighbors[a as usize],
        b,
        (NO_NEIGHBOR, NO_NEIGHBOR),
    ) else {
        return false;
    };
    let (x, y) = (ta[j], ta[(j + 1) % 3]);
    let tb = &tris[b as usize];
    match link_slot(tb, &graph.neighbors[b as usize], c, (x, y)) {
        Some(k) => {
            let (u, v) = (tb[k], tb[(k + 1) % 3]);
            !(u == y || v == y)
        }
        None => false,
    }
}

/// Appends the walk `path` (triangle ids into `tris`, each a `graph` neighbour of the
/// one before) to `out` as one strip, read from whichever end needs fewer swaps, and
/// returns the swaps used. Every triangle keeps its winding. O(path length).
///
/// # Panics
/// When two consecutive triangles of `path` are not neighbours in `graph` (a bug in
/// the caller, never a property of the input mesh).
pub fn encode_path(
    tris: &[[u32; 3]],
    graph: &DualGraph,
    path: &[u32],
    out: &mut StripSet,
) -> usize {
    let n = path.len();
    if out.offsets.is_empty() {
        out.offsets.push(0);
    }
    let mark = out.indices.len();
    let mut swaps = walk(tris, graph, n, |i| path[i], |v| out.indices.push(v));
    // Both readings share their inner swaps; only the first step can differ.
    if n >= 3
        && start_swap(tris, graph, path[0], path[1], path[2])
        && !start_swap(tris, graph, path[n - 1], path[n - 2], path[n - 3])
    {
        out.indices.truncate(mark);
        swaps = walk(tris, graph, n, |i| path[n - 1 - i], |v| out.indices.push(v));
    }
    out.offsets.push(out.indices.len() as u32);
    swaps
}


/// Swaps of the walk `w` as [`walk`] encodes it (read from `w[0]`).
pub(crate) fn walk_swaps(tris: &[[u32; 3]], graph: &DualGraph, w: &[u32]) -> u32 {
    walk(tris, graph, w.len(), |j| w[j], |_| {}) as u32
}

/// The swaps a walk needs at `w[2]` of four consecutive triangles `w` (a swap at an
/// inner triangle depends only on it, the one after it and the two before): those of
/// the four less those of the first three.
pub(crate) fn inner_swap(tris: &[[u32; 3]], graph: &DualGraph, w: &[u32]) -> u32 {
    walk_swaps(tris, graph, w) - walk_swaps(tris, graph, &w[..3])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strip::verify;

    #[test]
    fn a_fan_needs_swaps_and_keeps_winding() {
        // A fan of 4 triangles around vertex 0: every inner triangle pivots on 0.
        let tris = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]];
        let g = DualGraph::from_triangles(&tris, 6);
        let mut out = StripSet::new();
        let swaps = encode_path(&tris, &g, &[0, 1, 2, 3], &mut out);
        // Pivots of the two inner triangles are both 0: one swap there; the start can
        // always be read from the end where it costs nothing.
        assert_eq!(swaps, 1);
        assert_eq!(out.indices.len(), 4 + 2 + swaps);
        assert!(verify(&tris, &out).ok());
    }

    #[test]
    fn a_band_needs_no_swap() {
        // Quad band 0-1-2-3 over 4-5-6-7, triangles alternating.
        let tris = [
            [0, 4, 1],
            [1, 4, 5],
            [1, 5, 2],
            [2, 5, 6],
            [2, 6, 3],
            [3, 6, 7],
        ];
        let g = DualGraph::from_triangles(&tris, 8);
        let mut out = StripSet::new();
        assert_eq!(encode_path(&tris, &g, &[0, 1, 2, 3, 4, 5], &mut out), 0);
        assert_eq!(out.indices.len(), 8);
        assert!(verify(&tris, &out).ok());
        let mut out = StripSet::new();
        assert_eq!(encode_path(&tris, &g, &[5, 4, 3, 2, 1, 0], &mut out), 0);
        assert!(verify(&tris, &out).ok());
    }
}

//! Stripifiers: one file per algorithm. Each takes triangles (or a mesh) and returns a
//! [`crate::strip::StripSet`] that [`crate::strip::verify`] accepts.
//!
//! Shared here: [`encode_path`], which turns a walk through the dual graph (a sequence
//! of triangles, each a [`DualGraph`] neighbour of the one before) into one strip with
//! the fewest swaps for that walk. Because dual neighbours share an edge traversed in
//! opposite directions, the strip rule then gives every triangle its input winding.
//!
//! In a walk `t0, t1, .., tk` call the edge shared by `t(i-1)` and `t(i)` `E(i)`, and the
//! vertex shared by `E(i)` and `E(i+1)` the *pivot* of `t(i)`. A strip alternates its
//! turns by itself; it needs a swap (one repeated index) exactly at an inner triangle
//! whose pivot equals the pivot of the triangle before it (three consecutive shared
//! edges around one vertex). The first triangle has no pivot: reading the walk from
//! `t0`, `t1` needs a swap when its pivot is the *tail* of `E(1)` as `t0` runs it.
//! [`encode_path`] therefore reads a walk from whichever end needs fewer swaps.

pub mod cache;
pub mod greedy;
pub mod quad;
pub mod quad_single;
pub mod quad_verify;
pub use crate::improve::tunnel;

use crate::strip::StripSet;
use crate::topology::{DualGraph, NO_NEIGHBOR};

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

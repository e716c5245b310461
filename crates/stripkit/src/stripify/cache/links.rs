//! The stripifier's links between triangles, in 12 bytes per triangle: for each edge
//! slot, the neighbour across it (the dual graph of [`DualGraph`], the same pairing on
//! non-manifold edges) in the low 30 bits and the slot of the shared edge in that
//! neighbour in the top 2 bits. A missing neighbour is the sentinel triangle
//! `tris.len()` (always taken).
//!
//! Built from the vertex-to-triangle lists the stripifier keeps anyway, one vertex at a
//! time, instead of the dual graph's table of every corner (8 bytes per corner) and
//! separate twin slots: on the 4.4M-triangle mesh the links take 53 MB where the graph,
//! its twins and the 32-byte records made from them took 208 MB.
//!
//! [`DualGraph`]: crate::topology::DualGraph

use crate::topology::{sort_bucket, Csr};

/// The neighbour bits of a link.
pub(super) const MASK: u32 = (1 << 30) - 1;

/// The neighbour of a link.
#[inline(always)]
pub(super) fn nbr(link: u32) -> u32 {
    link & MASK
}

/// The slot of the shared edge in the neighbour.
#[inline(always)]
pub(super) fn twin(link: u32) -> usize {
    (link >> 30) as usize
}

/// The neighbour's vertex opposite the shared edge (the link must have a neighbour).
#[inline(always)]
pub(super) fn opp(tris: &[[u32; 3]], link: u32) -> u32 {
    // The slot before the shared edge's slot holds the vertex opposite it.
    const PREV: [usize; 3] = [2, 0, 1];
    tris[nbr(link) as usize][PREV[twin(link)]]
}

/// The links of `tris`, whose non-degenerate triangles around each vertex are listed
/// in `vtris` (in triangle order, as [`crate::topology::vertex_triangles`] gives them).
///
/// The same neighbours and twin slots as
/// [`DualGraph::from_triangles_with_twins`](crate::topology::DualGraph::from_triangles_with_twins):
/// each edge's corners are gathered at its lower vertex, keyed by the higher vertex,
/// then the corner id and its direction, sorted, and on each edge the j-th corner
/// running it one way is linked with the j-th running it the other way.
///
/// # Panics
///
/// With `u32::MAX / 6` (715,827,882) triangles or more (a corner id, doubled, must
/// fit in 32 bits; such a mesh takes more than 8 GB for its triangles alone).
pub(super) fn links(tris: &[[u32; 3]], vtris: &Csr<u32>) -> Vec<[u32; 3]> {
    let n = tris.len();
    assert!(n < (u32::MAX / 6) as usize, "{n} triangles: the cache stripifier takes fewer than u32::MAX / 6");
    let none = n as u32;
    let mut links = vec![[none; 3]; n];
    // One vertex's corners: higher vertex in the top 32 bits, then corner * 2 + 1 when
    // the corner runs its edge low -> high (below 2^32 by the bound above).
    let mut bucket: Vec<u64> = Vec::with_capacity(32);
    for v in 0..vtris.offsets().len().saturating_sub(1) {
        bucket.clear();
        for &t in vtris.bucket(v) {
            let tri = tris[t as usize];
            for j in 0..3 {
                let (a, b) = (tri[j], tri[(j + 1) % 3]);
                if a.min(b) as usize == v {
                    let corner = u64::from(t) * 3 + j as u64;
                    bucket.push(u64::from(a.max(b)) << 32 | (corner * 2 + u64::from(a < b)));
                }
            }
        }
        sort_bucket(&mut bucket);
        let hi = |e: u64| (e >> 32) as u32;
        let mut link = |eu: u64, ed: u64| {
            let c = (eu & 0xFFFF_FFFF) >> 1;
            let d = (ed & 0xFFFF_FFFF) >> 1;
            let (ct, cs, dt, ds) = ((c / 3) as usize, (c % 3) as usize, (d / 3) as usize, (d % 3) as u32);
            links[ct][cs] = dt as u32 | ds << 30;
            links[dt][ds as usize] = ct as u32 | (cs as u32) << 30;
        };
        let mut i = 0;
        while i < bucket.len() {
            let mut k = i + 1;
            while k < bucket.len() && hi(bucket[k]) == hi(bucket[i]) {
                k += 1;
            }
            // Two corners: linked when they run the edge in opposite directions; more:
            // the j-th up (by corner id) with the j-th down.
            let group = &bucket[i..k];
            let mut up = group.iter().filter(|&&e| e & 1 == 1);
            let mut down = group.iter().filter(|&&e| e & 1 == 0);
            while let (Some(&eu), Some(&ed)) = (up.next(), down.next()) {
                link(eu, ed);
            }
            i = k;
        }
    }
    links
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topology::{vertex_triangles, DualGraph, NO_NEIGHBOR};

    /// The links against the dual graph and its twins, slot by slot.
    fn check(tris: &[[u32; 3]], vc: usize) {
        let (graph, twins) = DualGraph::from_triangles_with_twins(tris, vc);
        let l = links(tris, &vertex_triangles(tris, vc));
        for t in 0..tris.len() {
            for k in 0..3 {
                let m = graph.neighbors[t][k];
                if m == NO_NEIGHBOR {
                    assert_eq!(l[t][k], tris.len() as u32, "{t}/{k}");
                } else {
                    assert_eq!((nbr(l[t][k]), twin(l[t][k])), (m, twins[t][k] as usize), "{t}/{k}");
                }
            }
        }
    }

    #[test]
    fn the_links_are_the_dual_graph_with_its_twins() {
        let (tris, vc) = crate::test_support::random_diagonals(23, 17, 5);
        check(&tris, vc);
        // Non-manifold edges (three and four triangles on one edge, both ways),
        // degenerate triangles, a flipped one and an isolated one, shuffled.
        let mut odd = vec![
            [0, 1, 2],
            [1, 0, 3],
            [0, 1, 4],
            [1, 0, 5],
            [0, 1, 6],
            [2, 1, 7],
            [7, 7, 1],
            [1, 2, 8],
            [9, 10, 11],
            [2, 0, 12],
        ];
        check(&odd, 13);
        odd.reverse();
        odd.swap(2, 7);
        check(&odd, 13);
        check(&[], 0);
    }
}

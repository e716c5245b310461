//! The dual graph every stripifier walks, against its definition by brute force
//! (moved from `tests/greedy_meshes.rs`).

use proptest::prelude::*;
use crate::topology::{DualGraph, NO_NEIGHBOR};

/// The definition, by brute force: `t` and `u` are neighbours across `t`'s edge
/// `j` when `u` runs that edge the opposite way and the two have the same rank
/// (by triangle id) among the non-degenerate triangles running the edge their
/// own way (a manifold edge: both rank 0; a non-manifold edge pairs up in order).
fn brute(tris: &[[u32; 3]]) -> DualGraph {
    let deg = |t: &[u32; 3]| t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
    let runs = |u: &[u32; 3], a: u32, b: u32| (0..3).any(|k| (u[k], u[(k + 1) % 3]) == (a, b));
    let mut neighbors = vec![[NO_NEIGHBOR; 3]; tris.len()];
    for (ti, t) in tris.iter().enumerate() {
        if deg(t) {
            continue;
        }
        for j in 0..3 {
            let (a, b) = (t[j], t[(j + 1) % 3]);
            let same: Vec<usize> = (0..tris.len()).filter(|&u| !deg(&tris[u]) && runs(&tris[u], a, b)).collect();
            let other: Vec<usize> = (0..tris.len()).filter(|&u| !deg(&tris[u]) && runs(&tris[u], b, a)).collect();
            let rank = same.iter().position(|&u| u == ti).expect("t runs its own edge");
            if let Some(&u) = other.get(rank) {
                neighbors[ti][j] = u as u32;
            }
        }
    }
    DualGraph { neighbors }
}

proptest! {
    // Random soups over few vertices: many shared, non-manifold, flipped and
    // degenerate edges.
    #[test]
    fn matches_the_definition(tris in prop::collection::vec([0u32..9, 0u32..9, 0u32..9], 0..40)) {
        prop_assert_eq!(DualGraph::from_triangles(&tris, 9), brute(&tris));
    }
}

#[test]
fn icosphere_and_a_high_valence_fan() {
    let (tris, n) = super::support::icosphere(2);
    assert_eq!(DualGraph::from_triangles(&tris, n), brute(&tris));
    // Indices beyond the stated count are tolerated.
    assert_eq!(DualGraph::from_triangles(&tris, 0), brute(&tris));
    // A closed fan of 200 triangles around vertex 0 (buckets far over 16).
    let fan: Vec<[u32; 3]> = (0..200u32).map(|i| [0, 1 + i, 1 + (i + 1) % 200]).collect();
    let g = DualGraph::from_triangles(&fan, 201);
    assert_eq!(g, brute(&fan));
    assert!(g.neighbors.iter().all(|n| n[0] != NO_NEIGHBOR && n[2] != NO_NEIGHBOR));
}

//! Matching graphs from meshes: the dual graph (one node per triangle, one edge per
//! pair of triangles across a manifold, consistently oriented edge) with a choice of
//! weights.

use crate::error::Result;
use crate::mesh::Mesh;
use crate::topology::{DualGraph, NO_NEIGHBOR};
use stripkit_matching::Graph;

/// How to weight the dual edges. Default: [`DualWeights::Random`] with
/// [`DualWeights::DEFAULT_SEED`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DualWeights {
    /// Every edge weighs 1.
    Uniform,
    /// Independent uniform integers in `1..=1000` from a seeded generator.
    Random {
        /// Generator seed: the same seed gives the same weights.
        seed: u64,
    },
    /// The dihedral angle between the two triangles' normals, scaled to integers:
    /// `round(angle / pi * 1000)`, so 0 for coplanar neighbours and 1000 for folded
    /// back ones. A degenerate (zero-area) triangle counts as angle 0.
    NormalAngle,
}

impl DualWeights {
    /// The seed of the default weights, and of `Random` when no seed is asked for: 1.
    pub const DEFAULT_SEED: u64 = 1;

    /// These weights drawn from `seed`: `Some` for [`DualWeights::Random`], `None` for
    /// the weights that take no seed.
    pub fn with_seed(self, seed: u64) -> Option<DualWeights> {
        match self {
            DualWeights::Random { .. } => Some(DualWeights::Random { seed }),
            DualWeights::Uniform | DualWeights::NormalAngle => None,
        }
    }
}

impl Default for DualWeights {
    /// Random weights with [`DualWeights::DEFAULT_SEED`].
    fn default() -> Self {
        DualWeights::Random { seed: DualWeights::DEFAULT_SEED }
    }
}

/// splitmix64: deterministic, seedable, good enough for test weights.
pub(crate) fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E3779B97F4A7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D049BB133111EB);
    z ^ (z >> 31)
}

/// The dual graph of a mesh as a matching graph: one node per triangle, one edge per
/// pair of dual neighbours, weighted by `weight(t, j, u)` for the edge from triangle
/// `t` across its edge `j` to triangle `u` (called once per edge, with `t < u`).
pub(crate) fn graph_from_dual(dual: &DualGraph, mut weight: impl FnMut(usize, usize, usize) -> i64) -> Result<Graph> {
    let mut edges = Vec::with_capacity(dual.len() * 3 / 2);
    let mut weights = Vec::with_capacity(dual.len() * 3 / 2);
    for (t, nb) in dual.neighbors.iter().enumerate() {
        for (j, &u) in nb.iter().enumerate() {
            if u != NO_NEIGHBOR && (t as u32) < u {
                edges.push([t as u32, u]);
                weights.push(weight(t, j, u as usize));
            }
        }
    }
    Ok(Graph::new(dual.len(), edges, weights)?)
}

/// The weighted dual graph of a mesh's triangles (faces fanned by
/// [`Mesh::triangulate`]; node `t` is triangle `t`). O(triangles + vertices).
pub fn mesh_dual_graph(mesh: &Mesh, weights: DualWeights) -> Result<Graph> {
    let tris = mesh.triangulate().tris;
    let dual = DualGraph::from_triangles(&tris, mesh.vertex_count());
    match weights {
        DualWeights::Uniform => graph_from_dual(&dual, |_, _, _| 1),
        DualWeights::Random { seed } => {
            let mut s = seed;
            graph_from_dual(&dual, |_, _, _| 1 + (splitmix(&mut s) % 1000) as i64)
        }
        DualWeights::NormalAngle => {
            let normal = |t: usize| -> [f64; 3] {
                let p = |i: u32| {
                    let q = mesh.positions[i as usize];
                    [q[0] as f64, q[1] as f64, q[2] as f64]
                };
                let [a, b, c] = tris[t].map(p);
                let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
                let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
                let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
                let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                if len > 0.0 && len.is_finite() {
                    [n[0] / len, n[1] / len, n[2] / len]
                } else {
                    [0.0; 3]
                }
            };
            graph_from_dual(&dual, |t, _, u| {
                let (a, b) = (normal(t), normal(u));
                if a == [0.0; 3] || b == [0.0; 3] {
                    return 0;
                }
                let dot = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]).clamp(-1.0, 1.0);
                (dot.acos() / std::f64::consts::PI * 1000.0).round() as i64
            })
        }
    }
}

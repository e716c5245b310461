//! Matching graphs from meshes: the dual graph (one node per triangle, one edge per
//! pair of triangles across a manifold, consistently oriented edge) with a choice of
//! weights.

use crate::error::Result;
use crate::mesh::Mesh;
use crate::topology::{DualGraph, NO_NEIGHBOR};
use crate::vec3;
use stripkit_matching::Graph;

/// How to weight the dual edges.
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

impl Default for DualWeights {
    /// [`DualWeights::Random`] with seed 1.
    fn default() -> Self {
        DualWeights::Random { seed: 1 }
    }
}

impl DualWeights {
    /// Every kind's name, in the order of the variants.
    pub const NAMES: &'static [&'static str] = &["uniform", "random", "normal-angle"];
    /// The lowercase name of this kind (one of [`DualWeights::NAMES`]).
    pub fn name(&self) -> &'static str {
        match self {
            DualWeights::Uniform => "uniform",
            DualWeights::Random { .. } => "random",
            DualWeights::NormalAngle => "normal-angle",
        }
    }
}

impl std::str::FromStr for DualWeights {
    type Err = crate::error::Error;
    /// The kind of this name ([`DualWeights::NAMES`]); `random` with the default seed.
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "uniform" => Ok(DualWeights::Uniform),
            "random" => Ok(DualWeights::default()),
            "normal-angle" => Ok(DualWeights::NormalAngle),
            _ => Err(crate::error::unknown("dual weights", s, DualWeights::NAMES)),
        }
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
                vec3::unit(vec3::tri_normal(a, b, c)).unwrap_or([0.0; 3])
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

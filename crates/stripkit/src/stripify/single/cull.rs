//! Weights for back-face culling (section 4.1 of the paper).
//!
//! Placeholder until the clustering lands: the normalized dihedral angle of each edge.

use super::work::{dot, WorkMesh};
use crate::topology::NO_NEIGHBOR;

/// Per-slot weights in `[0, 1]` for back-face culling; may split triangles of `w`
/// first (symmetric: both sides of a dual edge get the same weight).
pub(crate) fn cull_weights(w: &mut WorkMesh, _max_angle: f64, _seed: u64) -> Vec<[f64; 3]> {
    let normals: Vec<[f64; 3]> = (0..w.len()).map(|t| w.normal(t)).collect();
    (0..w.len())
        .map(|t| {
            std::array::from_fn(|j| {
                let u = w.nbr[t][j];
                if u == NO_NEIGHBOR {
                    return 0.0;
                }
                dot(normals[t], normals[u as usize]).clamp(-1.0, 1.0).acos() / std::f64::consts::PI
            })
        })
        .collect()
}

//! The optimality certificate of a weighted perfect matching and its checker.
//!
//! A perfect matching `M` is maximum-weight when there are vertex duals `y` and
//! blossom duals `z_B >= 0` on a laminar family of odd vertex sets such that
//!
//! * every edge `uv` has slack `y_u + y_v + sum(z_B : u, v in B) - w_uv >= 0`;
//! * every edge of `M` has slack 0;
//! * every blossom with `z_B > 0` is full: `M` has `(|B| - 1) / 2` edges inside it.
//!
//! Then `w(M) = sum y + sum z_B (|B| - 1) / 2`, the dual bound, so no perfect matching
//! is heavier. The checker below verifies all of it from scratch in
//! O(edges * blossom depth), trusting nothing the solver computed.
//!
//! Scale: the certificate is stated for the *internal* weights `2w` (maximising) or
//! `-2w` (minimising cost `w`), so that every dual is an integer.

use crate::blossom::NONE;
use crate::error::{Error, Result};

/// One blossom of the dual solution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DualBlossom {
    /// Its dual `z_B` (positive; blossoms with zero dual are left out).
    pub z: i64,
    /// Index of the smallest listed blossom strictly containing it, or `u32::MAX`.
    /// Always greater than the blossom's own index.
    pub parent: u32,
}

/// Dual solution proving a perfect matching optimal: vertex duals `y`, and blossom
/// duals `z_B` on a laminar family (see the [crate docs](crate#the-certificate)).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Certificate {
    /// Vertex duals, one per vertex, for the internal weights (`2w` or `-2w`).
    pub y: Vec<i64>,
    /// The laminar family: blossoms with positive dual, children before parents.
    pub blossoms: Vec<DualBlossom>,
    /// The smallest listed blossom containing each vertex, or `u32::MAX`. A blossom's
    /// member set is the vertices whose chain of parents reaches it.
    pub vertex_blossom: Vec<u32>,
}

/// What the checker found: the primal weight and the dual bound (equal when it passes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CheckReport {
    /// Sum of the internal weights of the matched edges.
    pub primal: i128,
    /// `sum y + sum z_B (|B| - 1) / 2`.
    pub dual: i128,
}

fn fail(what: String) -> Error {
    Error::Verification(what)
}

/// Checks that `matched` (edge ids) is a perfect matching of the graph with `n`
/// vertices, edges `ends` and internal weights `w`, and that `cert` proves it
/// maximum-weight. Self-loops in `ends` are ignored; parallel edges are all checked.
///
/// The weights are *internal* ones (`2w` to maximise `w`, `-2w` to minimise it, see
/// [`Objective::internal`](crate::Objective::internal)); [`verify`](crate::verify)
/// does the conversion for a [`Graph`](crate::Graph). Checks every condition of the
/// [crate docs](crate#the-certificate) from scratch in O(edges * blossom depth).
/// Returns the primal weight and the dual bound, which are equal when it passes; fails
/// with [`Error::Verification`] naming the first violated condition.
pub fn check_certificate(
    n: usize,
    ends: &[[u32; 2]],
    w: &[i64],
    matched: &[u32],
    cert: &Certificate,
) -> Result<CheckReport> {
    if cert.y.len() != n || cert.vertex_blossom.len() != n {
        return Err(fail(format!(
            "certificate has {} vertex duals and {} blossom links for {n} vertices",
            cert.y.len(),
            cert.vertex_blossom.len()
        )));
    }
    // The matching.
    let mut mate = vec![NONE; n];
    let mut primal: i128 = 0;
    for &e in matched {
        let Some(&[a, b]) = ends.get(e as usize) else {
            return Err(fail(format!("matched edge {e} does not exist")));
        };
        if a == b {
            return Err(fail(format!("matched edge {e} is a self-loop")));
        }
        for v in [a, b] {
            if mate[v as usize] != NONE {
                return Err(fail(format!("vertex {v} is matched twice")));
            }
            mate[v as usize] = e;
        }
        primal += w[e as usize] as i128;
    }
    if let Some(v) = mate.iter().position(|&m| m == NONE) {
        return Err(fail(format!("vertex {v} is not matched: the matching is not perfect")));
    }
    // The laminar family.
    let nb = cert.blossoms.len();
    for (i, b) in cert.blossoms.iter().enumerate() {
        if b.z < 0 {
            return Err(fail(format!("blossom {i} has negative dual {}", b.z)));
        }
        if b.parent != NONE && (b.parent as usize >= nb || b.parent as usize <= i) {
            return Err(fail(format!("blossom {i} has invalid parent {}", b.parent)));
        }
    }
    let mut depth = vec![0u32; nb];
    let mut zsum = vec![0i128; nb];
    for i in (0..nb).rev() {
        let p = cert.blossoms[i].parent;
        if p != NONE {
            depth[i] = depth[p as usize] + 1;
            zsum[i] = zsum[p as usize];
        }
        zsum[i] += cert.blossoms[i].z as i128;
    }
    let mut size = vec![0u64; nb];
    for (v, &b) in cert.vertex_blossom.iter().enumerate() {
        if b != NONE && b as usize >= nb {
            return Err(fail(format!("vertex {v} refers to blossom {b} of {nb}")));
        }
        let mut x = b;
        while x != NONE {
            size[x as usize] += 1;
            x = cert.blossoms[x as usize].parent;
        }
    }
    let lca = |a: u32, b: u32| -> u32 {
        let (mut a, mut b) = (a, b);
        while a != b {
            if a == NONE || b == NONE {
                return NONE;
            }
            if depth[a as usize] >= depth[b as usize] {
                a = cert.blossoms[a as usize].parent;
            } else {
                b = cert.blossoms[b as usize].parent;
            }
        }
        a
    };
    // Edges inside each blossom that are matched.
    let mut inside = vec![0u64; nb];
    for &e in matched {
        let [a, b] = ends[e as usize];
        let mut x = lca(cert.vertex_blossom[a as usize], cert.vertex_blossom[b as usize]);
        while x != NONE {
            inside[x as usize] += 1;
            x = cert.blossoms[x as usize].parent;
        }
    }
    let mut dual: i128 = cert.y.iter().map(|&y| y as i128).sum();
    for i in 0..nb {
        if size[i] < 3 || size[i] % 2 == 0 {
            return Err(fail(format!("blossom {i} has {} vertices (needs an odd number >= 3)", size[i])));
        }
        if cert.blossoms[i].z > 0 && inside[i] != (size[i] - 1) / 2 {
            return Err(fail(format!(
                "blossom {i} (dual {}) holds {} matched edges, not {}",
                cert.blossoms[i].z,
                inside[i],
                (size[i] - 1) / 2
            )));
        }
        dual += cert.blossoms[i].z as i128 * ((size[i] - 1) / 2) as i128;
    }
    // Feasibility and tightness, edge by edge.
    for (e, &[a, b]) in ends.iter().enumerate() {
        if a == b {
            continue;
        }
        let l = lca(cert.vertex_blossom[a as usize], cert.vertex_blossom[b as usize]);
        let z = if l == NONE { 0 } else { zsum[l as usize] };
        let slack = cert.y[a as usize] as i128 + cert.y[b as usize] as i128 + z - w[e] as i128;
        if slack < 0 {
            return Err(fail(format!("edge {e} ({a}, {b}) violates its dual constraint by {}", -slack)));
        }
        if slack != 0 && mate[a as usize] == e as u32 {
            return Err(fail(format!("matched edge {e} ({a}, {b}) has slack {slack}")));
        }
    }
    if primal != dual {
        return Err(fail(format!("primal {primal} differs from dual {dual}")));
    }
    Ok(CheckReport { primal, dual })
}

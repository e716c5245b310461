//! Quad-level verification of strips for quad and mixed meshes.
//!
//! A quad may be split along either diagonal, so the triangle-level check (one output
//! triangle per input fan triangle) does not apply to it. Here:
//!
//! * every quad (a face of four distinct vertices, [`is_quad`]) must be covered by
//!   exactly two output triangles that together form it: `(a,b,c)+(a,c,d)` or
//!   `(a,b,d)+(b,c,d)` up to rotation, with the quad's orientation;
//! * every other face must be covered by exactly its fan triangles (`(v0,vi,vi+1)`),
//!   with its orientation, as the triangle-level check demands;
//! * no output triangle is left over;
//! * no two triangles that come from quads lie on the same three vertices (the
//!   "incorrect triangle" two quads sharing two edges can produce), unless every
//!   choice of diagonals for that pair of quads clashes (the input forces it), the
//!   two quads are one face listed twice (same vertices in the same cyclic order: the
//!   duplicate is the input's, and each copy is covered on its own; any two quads that
//!   could give that triangle count, since where quads share all four vertices the
//!   drawn triangles can be assigned to them in more than one way), or no choice of
//!   diagonals for all the quads at once avoids every coincidence (a cluster of quads
//!   on a few vertices, checked only when a coincidence is found, and taken as so
//!   beyond 2^20 candidate pairs: thousands of quads on the same three vertices;
//!   QSTRIP solves exactly the same pairs, so the two agree).
//!
//! Independent of how the strips were built: it only decodes them by the docs/metrics.md
//! rule. O(T) expected time with hashing.

use super::quad_adjacency::{candidate_pairs, coincide, is_quad, same_quad, solve_diagonals, split, split_sets};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::strip::{canonical, for_each_triangle, StripSet};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// Figures from a successful [`verify_quads`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QuadCheck {
    /// Quads covered by two triangles each.
    pub quads: usize,
    /// Quads split along diagonal v0-v2 (the rest along v1-v3).
    pub split_02: usize,
    /// Other faces' triangles matched one to one.
    pub other_triangles: usize,
    /// Degenerate triangles (swaps) seen in the strips.
    pub degenerate: usize,
}

/// A small multiplicative hasher for vertex-triple keys (std's SipHash is several
/// times slower here and the keys are not attacker-chosen in a way that matters for a
/// one-off check).
#[derive(Default)]
struct TripleHasher(u64);

impl Hasher for TripleHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    fn write_u32(&mut self, n: u32) {
        self.write_u64(n as u64);
    }
    fn write_u64(&mut self, n: u64) {
        self.0 = (self.0.rotate_left(5) ^ n).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
}

type Counts = HashMap<[u32; 3], u32, BuildHasherDefault<TripleHasher>>;

fn take(counts: &mut Counts, t: [u32; 3]) -> bool {
    match counts.get_mut(&canonical(t)) {
        Some(c) if *c > 0 => {
            *c -= 1;
            true
        }
        _ => false,
    }
}

fn has(counts: &Counts, t: [u32; 3]) -> bool {
    counts.get(&canonical(t)).is_some_and(|&c| c > 0)
}

/// Checks that `strips` cover `mesh` exactly: quads by two triangles forming them
/// (either diagonal), other faces by their fan triangles, orientation kept, nothing
/// added, no coincident triangles from quads. A failure is an
/// [`Error::Verification`] naming the first offending face or triangle.
pub fn verify_quads(mesh: &Mesh, strips: &StripSet) -> Result<QuadCheck> {
    let mut check = QuadCheck::default();
    let mut counts = Counts::default();
    let vcount = mesh.vertex_count() as u32;
    let mut bad_index = None;
    check.degenerate = crate::metrics::swaps(strips);
    for s in strips.iter() {
        if let Some(&v) = s.iter().find(|&&v| v >= vcount) {
            bad_index = Some(v);
        }
        for_each_triangle(s, |t| *counts.entry(canonical(t)).or_insert(0) += 1);
    }
    if let Some(v) = bad_index {
        return Err(Error::Verification(format!(
            "strips refer to vertex {v} but the mesh has {vcount} vertices"
        )));
    }
    // Other faces first: their triangles are fixed.
    for (f, face) in mesh.faces().enumerate() {
        if is_quad(face) || face.len() < 3 {
            continue;
        }
        for i in 1..face.len() - 1 {
            let t = [face[0], face[i], face[i + 1]];
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                continue;
            }
            if !take(&mut counts, t) {
                return Err(Error::Verification(format!(
                    "face {f}: triangle ({}, {}, {}) is missing from the strips (or flipped)",
                    t[0], t[1], t[2]
                )));
            }
            check.other_triangles += 1;
        }
    }
    // Quads: take the unambiguous ones first (only one diagonal's pair present), then
    // the rest, so that a neighbouring pillow cannot steal a triangle.
    let not_covered = |f: usize| {
        let v = mesh.face(f);
        Error::Verification(format!(
            "quad face {f} ({}, {}, {}, {}) is not covered by two triangles forming it \
             with its orientation",
            v[0], v[1], v[2], v[3]
        ))
    };
    let mut chosen: Vec<(usize, u8)> = Vec::new();
    let mut deferred = Vec::new();
    for f in (0..mesh.face_count()).filter(|&f| is_quad(mesh.face(f))) {
        let v = mesh.face(f);
        let ok = [0, 1].map(|d| split(v, d).iter().all(|&t| has(&counts, t)));
        let d = match ok {
            [true, true] => {
                deferred.push(f);
                continue;
            }
            [true, false] => 0,
            [false, true] => 1,
            [false, false] => return Err(not_covered(f)),
        };
        split(v, d).iter().for_each(|&t| {
            take(&mut counts, t);
        });
        chosen.push((f, d));
    }
    // The rest could take either diagonal's pair: a depth-first search, diagonal 0
    // first, so that where taking greedily works (every real mesh) it is what
    // happens, and where quads share all four vertices (a face, its copies and its
    // flips) a triangle one quad took too early is given back.
    let mut pick = vec![0u8; deferred.len()];
    let (mut i, mut steps, mut deepest) = (0usize, 0usize, 0usize);
    while i < deferred.len() {
        steps += 1;
        if steps > ASSIGN_BUDGET {
            return Err(Error::Verification(format!(
                "the triangles of {} quads sharing vertices could not be matched to them within \
                 {ASSIGN_BUDGET} steps",
                deferred.len()
            )));
        }
        let v = mesh.face(deferred[i]);
        let next = (pick[i]..2).find(|&d| split(v, d).iter().all(|&t| has(&counts, t)));
        if let Some(d) = next {
            split(v, d).iter().for_each(|&t| {
                take(&mut counts, t);
            });
            pick[i] = d;
            i += 1;
            deepest = deepest.max(i);
            if i < deferred.len() {
                pick[i] = 0;
            }
            continue;
        }
        // No diagonal left for quad i: give back quad i - 1's and try its next.
        if i == 0 {
            return Err(not_covered(deferred[deepest.min(deferred.len() - 1)]));
        }
        i -= 1;
        let u = mesh.face(deferred[i]);
        for t in split(u, pick[i]) {
            *counts.entry(canonical(t)).or_insert(0) += 1;
        }
        pick[i] += 1;
    }
    chosen.extend(deferred.iter().copied().zip(pick));
    let mut quad_sets: Vec<([u32; 3], u32)> = Vec::with_capacity(2 * chosen.len());
    for &(f, d) in &chosen {
        quad_sets.extend(split_sets(mesh.face(f), d).map(|t| (t, f as u32)));
        check.quads += 1;
        if d == 0 {
            check.split_02 += 1;
        }
    }
    if let Some((t, _)) = counts.iter().find(|(_, &c)| c > 0) {
        return Err(Error::Verification(format!(
            "triangle ({}, {}, {}) in the strips belongs to no face (added or flipped)",
            t[0], t[1], t[2]
        )));
    }
    quad_sets.sort_unstable();
    for w in quad_sets.windows(2) {
        let ((t, f1), (u, f2)) = (w[0], w[1]);
        let (a, b) = (mesh.face(f1 as usize), mesh.face(f2 as usize));
        if t == u && f1 != f2 && !same_quad(a, b) && avoidable(a, b) && !explained(mesh, t) && solvable(mesh) {
            return Err(Error::Verification(format!(
                "quad faces {f1} and {f2} give coincident triangles on vertices ({}, {}, {}); \
                 another choice of diagonals avoids it",
                t[0], t[1], t[2]
            )));
        }
    }
    Ok(check)
}

/// Steps of the search that matches drawn triangles to quads able to take either
/// diagonal before the check gives up.
const ASSIGN_BUDGET: usize = 1 << 20;

/// True when two quads that can both give triangle `t` (sorted) are one face listed
/// twice or clash whatever their diagonals: then `t` may rightly be drawn twice. The
/// assignment of drawn triangles to quads above is one of several where quads share
/// their four vertices (a face, its copies and its flips), so the pair it names is not
/// always the pair that drew them; this looks at every quad that could have.
fn explained(mesh: &Mesh, t: [u32; 3]) -> bool {
    let able: Vec<&[u32]> = mesh
        .faces()
        .filter(|f| is_quad(f) && (0..2).any(|d| split_sets(f, d).contains(&t)))
        .collect();
    (0..able.len()).any(|i| able[i + 1..].iter().any(|b| same_quad(able[i], b) || !avoidable(able[i], b)))
}

/// True when some choice of diagonals for all quads of `mesh` at once gives no
/// avoidable coincidence (the pairs of [`candidate_pairs`]; past its budget, false).
fn solvable(mesh: &Mesh) -> bool {
    let quads: Vec<&[u32]> = mesh.faces().filter(|f| is_quad(f)).collect();
    candidate_pairs(&quads).is_some_and(|pairs| solve_diagonals(&quads, &pairs, &[]).is_some())
}

/// True when some choice of diagonals for quads `a` and `b` gives no two triangles on
/// the same three vertices (false only for pairs on the same four vertices whose every
/// split clashes, which the input forces).
fn avoidable(a: &[u32], b: &[u32]) -> bool {
    (0..2).any(|da| (0..2).any(|db| !coincide(a, da, b, db)))
}

//! The second check of single strips: the changed triangles cover exactly the input
//! triangles. It trusts nothing of the builder but its record of which input triangles
//! each output triangle came from, which edges the Steiner vertices split and which
//! pairs were swapped; each claim is checked against the geometry and the topology.
//!
//! Input triangles are grouped by the swaps (a swapped pair, and anything later swapped
//! with one of its pieces, is one group). For every group:
//! * the oriented boundary of its output pieces, with every Steiner vertex on it
//!   removed (`a -> m -> b` read as `a -> b` for the edge `m` split), equals the
//!   oriented boundary of its input triangles: the pieces tile the same region with
//!   the same winding, nothing lost or added at its rim;
//! * every Steiner vertex lies at the midpoint of the edge it split;
//! * without swaps, every piece lies in its input triangle's plane and faces its way:
//!   the pieces are exactly a subdivision of the triangle.
//!
//! Swapped groups cover the same quad; how far a swap moves the surface is reported
//! ([`max_swap_deviation`]).

use super::work::WorkMesh;
use crate::vec3::{dot, sub, tri_normal};
use crate::topology::UnionFind;
use std::collections::HashMap;

/// What the cover check saw.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Cover {
    /// Input triangles split into pieces (not swapped).
    pub split_triangles: usize,
    /// Groups joined by swaps.
    pub swap_groups: usize,
}

/// Checks that the triangles of `w` cover `input` (triangles over the first
/// `w.input_vertices` positions of `w`) as the module docs say; `Err` names the first
/// input triangle whose cover is wrong.
pub(crate) fn cover(input: &[[u32; 3]], w: &WorkMesh) -> Result<Cover, String> {
    let n = input.len();
    if w.origin.len() != w.tris.len() || w.origin.iter().any(|&o| o as usize >= n) {
        return Err("an output triangle names no input triangle".into());
    }
    let mut joined = UnionFind::new(n);
    for &[a, b] in &w.swaps {
        joined.union(a, b);
    }
    let group: Vec<u32> = (0..n as u32).map(|t| joined.find(t)).collect();
    let swapped: Vec<bool> = {
        let mut s = vec![false; n];
        for &[a, b] in &w.swaps {
            s[group[a as usize] as usize] = true;
            s[group[b as usize] as usize] = true;
        }
        s
    };
    let split_of: HashMap<u32, [u32; 2]> =
        w.steiner.iter().enumerate().map(|(i, &e)| ((w.input_vertices + i) as u32, e)).collect();
    for (i, &[a, b]) in w.steiner.iter().enumerate() {
        let m = w.pos[w.input_vertices + i];
        let (pa, pb) = (w.pos[a as usize], w.pos[b as usize]);
        let mid = [(pa[0] + pb[0]) / 2.0, (pa[1] + pb[1]) / 2.0, (pa[2] + pb[2]) / 2.0];
        let d = sub(m, mid);
        let scale = dot(sub(pa, pb), sub(pa, pb)).sqrt().max(f64::MIN_POSITIVE);
        if dot(d, d).sqrt() > 1e-9 * scale {
            return Err(format!("Steiner vertex {} is not the midpoint of {a}-{b}", w.input_vertices + i));
        }
    }
    // Pieces per group, in input order of their groups.
    let mut pieces: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut changed = vec![false; n];
    for (t, &o) in w.origin.iter().enumerate() {
        let g = group[o as usize] as usize;
        pieces[g].push(t as u32);
        if t >= n || w.tris[t] != input[t] {
            changed[g] = true;
        }
    }
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); n];
    for t in 0..n {
        members[group[t] as usize].push(t as u32);
    }
    let mut out = Cover::default();
    for g in 0..n {
        if members[g].is_empty() || !changed[g] {
            continue;
        }
        if swapped[g] {
            out.swap_groups += 1;
        } else {
            out.split_triangles += 1;
        }
        let want = boundary(members[g].iter().map(|&t| input[t as usize]), &HashMap::new());
        let got = boundary(pieces[g].iter().map(|&t| w.tris[t as usize]), &split_of);
        if want != got {
            return Err(format!("the pieces of input triangle {g} do not have its boundary"));
        }
        if !swapped[g] {
            let [a, b, c] = input[g].map(|i| w.pos[i as usize]);
            let normal = tri_normal(a, b, c);
            let nn = dot(normal, normal);
            if nn == 0.0 {
                continue; // degenerate input: the boundary check is all there is
            }
            let scale = dot(sub(b, a), sub(b, a)).max(dot(sub(c, a), sub(c, a))).sqrt();
            for &t in &pieces[g] {
                let q = w.tris[t as usize].map(|i| w.pos[i as usize]);
                for p in q {
                    if dot(sub(p, a), normal).abs() / nn.sqrt() > 1e-9 * scale {
                        return Err(format!("a piece of input triangle {g} leaves its plane"));
                    }
                }
                if dot(tri_normal(q[0], q[1], q[2]), normal) <= 0.0 {
                    return Err(format!("a piece of input triangle {g} is flipped or flat"));
                }
            }
        }
    }
    Ok(out)
}

/// The oriented boundary of a set of triangles, as a sorted list of directed edges,
/// after removing every Steiner vertex of `split_of` from it (`x -> m -> y` with
/// `{x, y}` the edge `m` split becomes `x -> y`), latest Steiner vertex first.
fn boundary(tris: impl Iterator<Item = [u32; 3]>, split_of: &HashMap<u32, [u32; 2]>) -> Vec<(u32, u32)> {
    let mut count: HashMap<(u32, u32), i32> = HashMap::new();
    for t in tris {
        for j in 0..3 {
            let (a, b) = (t[j], t[(j + 1) % 3]);
            if a == b {
                continue;
            }
            let r = count.entry((b, a)).or_insert(0);
            if *r > 0 {
                *r -= 1;
            } else {
                *count.entry((a, b)).or_insert(0) += 1;
            }
        }
    }
    let mut edges: Vec<(u32, u32)> = Vec::new();
    for (&e, &c) in &count {
        for _ in 0..c {
            edges.push(e);
        }
    }
    let mut steiner: Vec<u32> = edges.iter().map(|e| e.0).filter(|m| split_of.contains_key(m)).collect();
    steiner.sort_unstable_by(|a, b| b.cmp(a));
    steiner.dedup();
    for m in steiner {
        let [x, y] = split_of[&m];
        for (p, q) in [(x, y), (y, x)] {
            if let (Some(i), Some(k)) =
                (edges.iter().position(|&e| e == (p, m)), edges.iter().position(|&e| e == (m, q)))
            {
                edges[i] = (p, q);
                edges.swap_remove(k);
            }
        }
    }
    edges.sort_unstable();
    edges
}

/// The largest distance between the old and the new diagonal of a swapped quad (the
/// two segments meet in a planar convex quad).
pub(crate) fn max_swap_deviation(w: &WorkMesh) -> f64 {
    let p = |i: u32| w.pos[i as usize];
    w.swap_quads.iter().map(|&[a, b, c, d]| segment_distance(p(a), p(b), p(c), p(d))).fold(0.0, f64::max)
}

/// Distance between the segments `p0 p1` and `q0 q1`.
pub(crate) fn segment_distance(p0: [f64; 3], p1: [f64; 3], q0: [f64; 3], q1: [f64; 3]) -> f64 {
    let d1 = sub(p1, p0);
    let d2 = sub(q1, q0);
    let r = sub(p0, q0);
    let (a, e, f) = (dot(d1, d1), dot(d2, d2), dot(d2, r));
    let (mut s, mut t);
    if a <= f64::EPSILON && e <= f64::EPSILON {
        return dot(r, r).sqrt();
    }
    if a <= f64::EPSILON {
        s = 0.0;
        t = (f / e).clamp(0.0, 1.0);
    } else {
        let c = dot(d1, r);
        if e <= f64::EPSILON {
            t = 0.0;
            s = (-c / a).clamp(0.0, 1.0);
        } else {
            let b = dot(d1, d2);
            let denom = a * e - b * b;
            s = if denom > 0.0 { ((b * f - c * e) / denom).clamp(0.0, 1.0) } else { 0.0 };
            t = (b * s + f) / e;
            if t < 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else if t > 1.0 {
                t = 1.0;
                s = ((b - c) / a).clamp(0.0, 1.0);
            }
        }
    }
    let cp = [p0[0] + d1[0] * s, p0[1] + d1[1] * s, p0[2] + d1[2] * s];
    let cq = [q0[0] + d2[0] * t, q0[1] + d2[1] * t, q0[2] + d2[2] * t];
    let d = sub(cp, cq);
    dot(d, d).sqrt()
}

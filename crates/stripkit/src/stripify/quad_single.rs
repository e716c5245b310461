//! One generalized triangle strip per connected component of a closed quad mesh, after
//! the idea of Taubin ("Constructing Hamiltonian triangle strips on quadrilateral
//! meshes", 2002): the dual graph of a closed quad mesh is 4-regular, so it has a
//! 2-factor (disjoint cycles through every quad); adjacent cycles are then spliced
//! until one cycle per component remains, and that cycle becomes one strip.
//!
//! * **Eulerian orientation.** Closed trails over unused dual edges orient every edge
//!   so that each quad has two edges out and two in.
//! * **2-factor.** Out-ends and in-ends form a 2-regular bipartite graph; taking every
//!   other edge of each of its cycles leaves each quad one successor and one
//!   predecessor: a set of disjoint quad cycles.
//! * **Splicing.** Where quads `a -> b` of one cycle lie beside quads `c`, `d` of
//!   another (`a` next to `c`, `b` next to `d`, `d -> c` there), the two cycles become
//!   one: `a -> c -> ... -> d -> b`. When the other cycle runs `c -> d`, the smaller
//!   of the two is reversed first. This is the quad-level form of Taubin's diagonal
//!   flip; it needs the 2 x 2 blocks every regular vertex gives, and stops where none
//!   joins two cycles (the component then keeps more than one strip).
//! * **Strip.** The cycle, cut once, is a quad sequence that the QSTRIP programme turns
//!   into one strip with the fewest swaps for it (turns are frequent, so indices per
//!   quad are higher than QSTRIP's; the point is one strip).
//!
//! O(quads log quads) (reversals always take the smaller cycle).

use super::quad_adjacency::{QuadAdjacency, NONE};
use super::quad_sequence::{emit_quad_sequence, step, INF, NO_EDGE};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::strip::StripSet;
use crate::topology::EdgeMap;

/// The result of [`quad_single`].
#[derive(Clone, Debug, Default)]
pub struct SingleStrips {
    /// The strips: one per connected component when splicing joined every cycle (and
    /// no forced diagonal cut one).
    pub strips: StripSet,
    /// Quads covered.
    pub quads: usize,
    /// Cycles left after splicing (the ideal is the number of components).
    #[cfg_attr(not(test), allow(dead_code))] // read by the tests
    pub cycles: usize,
    /// Swaps inside the strips.
    #[cfg_attr(not(test), allow(dead_code))] // read by the tests
    pub swaps: usize,
}

/// Single generalized strips on a closed pure-quad mesh. Fails with
/// [`Error::Invalid`] when a face is not a quad or a quad lacks a quad neighbour
/// across one of its edges (boundary, non-manifold or flipped edge).
pub fn quad_single(mesh: &Mesh) -> Result<SingleStrips> {
    let edges = EdgeMap::build(mesh);
    let adj = QuadAdjacency::build(mesh, &edges);
    if adj.quad_face.len() != mesh.face_count() {
        let f =
            (0..mesh.face_count()).find(|&f| adj.quad_face.get(f).is_none_or(|&q| q as usize != f));
        return Err(Error::Invalid(format!(
            "quad-single needs a pure quad mesh: face {} is not a quad of four distinct vertices",
            f.unwrap_or(0)
        )));
    }
    let n = adj.quad_face.len();
    let link = &adj.link;
    if let Some(s) = link.iter().position(|&l| l == NONE) {
        return Err(Error::Invalid(format!(
            "quad-single needs a closed, manifold, consistently oriented quad mesh: edge {} of face {} \
             has no quad on its other side",
            s % 4,
            adj.quad_face[s / 4]
        )));
    }    let (outs, ins) = orient(link, n);
    let mut succ_slot = two_factor(link, &outs, &ins);
    if succ_slot.contains(&NONE) {
        return Err(Error::Invalid(
            "quad-single: could not build a cycle cover of the quads".into(),
        ));
    }
    splice_cycles(link, &mut succ_slot);
    let (strips, cycles, swaps) = emit_cycles(&adj, &succ_slot);
    Ok(SingleStrips {
        strips,
        quads: n,
        cycles,
        swaps,
    })
}

/// The quad across slot `s` (edge `s % 4` of quad `s / 4`).
fn slot_head(link: &[u32], s: u32) -> u32 {
    link[s as usize] >> 2
}

/// The partner slot of `s`: the same edge seen from the other quad.
fn slot_partner(link: &[u32], s: u32) -> u32 {
    let l = link[s as usize];
    4 * (l >> 2) + (l & 3)
}

/// Eulerian orientation of the dual edges by closed trails: for each of the `n`
/// quads, the slots of its two edges out and of the two edges in (as the other
/// quad's slot).
fn orient(link: &[u32], n: usize) -> (Vec<[u32; 2]>, Vec<[u32; 2]>) {
    let head = |s: u32| slot_head(link, s);
    let partner = |s: u32| slot_partner(link, s);
    let mut used = vec![false; 4 * n];
    let mut outs = vec![[NONE; 2]; n];
    let mut ins = vec![[NONE; 2]; n];
    let push = |pair: &mut [u32; 2], s: u32| {
        if pair[0] == NONE {
            pair[0] = s;
        } else {
            pair[1] = s;
        }
    };
    for q0 in 0..n as u32 {
        let mut cur = q0;
        let mut came_in = NO_EDGE as u32;
        loop {
            // Prefer leaving straight across from the entry edge: chords make long
            // straight runs in the cycles, and straight steps need no swap.
            let straight = (came_in + 2) % 4;
            let k = if came_in != NO_EDGE as u32 && !used[(4 * cur + straight) as usize] {
                straight
            } else {
                match (0..4).find(|&k| !used[(4 * cur + k) as usize]) {
                    Some(k) => k,
                    None => break,
                }
            };
            let s = 4 * cur + k;
            used[s as usize] = true;
            used[partner(s) as usize] = true;
            push(&mut outs[cur as usize], s);
            let h = head(s);
            push(&mut ins[h as usize], s);
            came_in = link[s as usize] & 3;
            cur = h;
        }
    }
    (outs, ins)
}

/// A 2-factor of the oriented dual graph: each quad's successor slot (NONE where
/// none was found).
fn two_factor(link: &[u32], outs: &[[u32; 2]], ins: &[[u32; 2]]) -> Vec<u32> {
    let n = outs.len();
    let head = |s: u32| slot_head(link, s);
    // 2-factor: every other edge of each cycle of the out/in bipartite graph. Each
    // such cycle offers two choices (even or odd edges); take the one that lets more
    // quads go straight through (entry and exit on opposite edges), judged against
    // the choices already made.
    let mut succ_slot = vec![NONE; n];
    let mut in_pick = vec![NONE; n];
    let mut seen = vec![false; 4 * n];
    let mut cycle: Vec<u32> = Vec::new();
    let straight = |v: usize, succ_slot: &[u32], in_pick: &[u32]| {
        let (o, i) = (succ_slot[v], in_pick[v]);
        o != NONE && i != NONE && ((link[i as usize] & 3) + 2) % 4 == o % 4
    };
    for u in 0..n {
        for &e0 in &outs[u] {
            if e0 == NONE || seen[e0 as usize] {
                continue;
            }
            cycle.clear();
            let mut e = e0;
            loop {
                seen[e as usize] = true;
                cycle.push(e);
                let v = head(e) as usize;
                let other_in = if ins[v][0] == e { ins[v][1] } else { ins[v][0] };
                seen[other_in as usize] = true;
                cycle.push(other_in);
                let w = (other_in / 4) as usize;
                let next = if outs[w][0] == other_in {
                    outs[w][1]
                } else {
                    outs[w][0]
                };
                if next == NONE || seen[next as usize] {
                    break;
                }
                e = next;
            }
            let mut score = [0usize; 2];
            for (parity, sc) in score.iter_mut().enumerate() {
                for &e in cycle.iter().skip(parity).step_by(2) {
                    succ_slot[(e / 4) as usize] = e;
                    in_pick[head(e) as usize] = e;
                }
                for &e in cycle.iter().skip(parity).step_by(2) {
                    *sc += straight((e / 4) as usize, &succ_slot, &in_pick) as usize
                        + straight(head(e) as usize, &succ_slot, &in_pick) as usize;
                }
                for &e in cycle.iter().skip(parity).step_by(2) {
                    succ_slot[(e / 4) as usize] = NONE;
                    in_pick[head(e) as usize] = NONE;
                }
            }
            let parity = if score[1] > score[0] { 1 } else { 0 };
            for &e in cycle.iter().skip(parity).step_by(2) {
                succ_slot[(e / 4) as usize] = e;
                in_pick[head(e) as usize] = e;
            }
        }
    }
    succ_slot
}

/// Splices the cycles of the 2-factor `succ_slot` (each quad's successor slot)
/// together wherever two of them run side by side (see the module docs).
fn splice_cycles(link: &[u32], succ_slot: &mut [u32]) {
    let n = succ_slot.len();
    let head = |s: u32| slot_head(link, s);
    let partner = |s: u32| slot_partner(link, s);
    let mut succ: Vec<u32> = succ_slot.iter().map(|&s| head(s)).collect();
    let mut pred = vec![NONE; n];
    for u in 0..n {
        pred[succ[u] as usize] = u as u32;
    }

    // Cycles as union-find sets with sizes.
    let mut parent: Vec<u32> = (0..n as u32).collect();
    let mut size = vec![1u32; n];
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            parent[x as usize] = parent[parent[x as usize] as usize];
            x = parent[x as usize];
        }
        x
    }
    let mut label = vec![false; n];
    for r in 0..n {
        if label[r] {
            continue;
        }
        let mut x = r as u32;
        let mut count = 0;
        loop {
            label[x as usize] = true;
            parent[x as usize] = r as u32;
            count += 1;
            x = succ[x as usize];
            if x as usize == r {
                break;
            }
        }
        size[r] = count;
    }

    let mut merged = true;
    let mut rounds = 0;
    while merged && rounds < 64 {
        merged = false;
        rounds += 1;
        for a in 0..n as u32 {
            let b = succ[a as usize];
            for k in 0..4 {
                let sa = 4 * a + k;
                if sa == succ_slot[a as usize] {
                    continue;
                }
                let c = head(sa);
                if c == b || c == a {
                    continue;
                }
                let (ra, rc) = (find(&mut parent, a), find(&mut parent, c));
                if ra == rc {
                    continue;
                }
                // d beside b, next to c in its cycle.
                let mut done = false;
                for d in [pred[c as usize], succ[c as usize]] {
                    let Some(kb) = (0..4).find(|&kb| {
                        head(4 * b + kb) == d && 4 * b + kb != partner(succ_slot[a as usize])
                    }) else {
                        continue;
                    };
                    let sb = 4 * b + kb;
                    if succ[c as usize] == d && pred[c as usize] != d {
                        // Other cycle runs c -> d: reverse the smaller cycle.
                        if size[rc as usize] <= size[ra as usize] {
                            reverse_cycle(c, &mut succ, &mut pred, succ_slot, link);
                        } else {
                            reverse_cycle(a, &mut succ, &mut pred, succ_slot, link);
                            // Now b -> a and (still) c -> d: splice b -> d ... c -> a.
                            let sbd = sb;
                            let sca = partner(sa);
                            splice(b, d, c, a, sbd, sca, &mut succ, &mut pred, succ_slot);
                            union(&mut parent, &mut size, ra, rc);
                            done = true;
                            break;
                        }
                    }
                    if pred[c as usize] == d {
                        // a -> c ... (forward in the other cycle) ... d -> b.
                        let sdb = partner(sb);
                        splice(a, c, d, b, sa, sdb, &mut succ, &mut pred, succ_slot);
                        union(&mut parent, &mut size, ra, rc);
                        done = true;
                        break;
                    }
                }
                if done {
                    merged = true;
                    break;
                }
            }
        }
    }
}

/// Cuts every cycle of `succ_slot` once and emits it as a strip (more where a forced
/// diagonal forbids a turn): the strips, the cycles and the swaps.
fn emit_cycles(adj: &QuadAdjacency, succ_slot: &[u32]) -> (StripSet, usize, usize) {
    let (link, n) = (&adj.link, succ_slot.len());
    let head = |s: u32| slot_head(link, s);
    // Cut every cycle once and emit it.
    let mut strips = StripSet::new();
    let mut swaps = 0;
    let mut cycles = 0;
    let mut visited = vec![false; n];
    let mut seq: Vec<(u32, u8, u8)> = Vec::new();
    let mut togo = Vec::new();
    let mut strip = Vec::new();
    let mut flush = |seq: &mut Vec<(u32, u8, u8)>, strips: &mut StripSet, swaps: &mut usize| {
        if let Some(last) = seq.last_mut() {
            last.2 = NO_EDGE;
            strip.clear();
            *swaps += emit_quad_sequence(adj, seq, &mut togo, &mut strip);
            strips.push(&strip);
        }
        seq.clear();
    };
    for r in 0..n {
        if visited[r] {
            continue;
        }
        cycles += 1;
        let mut q = r as u32;
        let mut entry = NO_EDGE;
        let mut costs = [0u32, 0];
        loop {
            visited[q as usize] = true;
            let s = succ_slot[q as usize];
            let next = head(s);
            let exit = if next as usize == r {
                NO_EDGE
            } else {
                (s % 4) as u8
            };
            if exit != NO_EDGE {
                let after = step(costs, entry, exit, adj.forced[q as usize]);
                if after[0].min(after[1]) >= INF {
                    // A forced diagonal forbids this turn: end the strip here.
                    seq.push((q, entry, NO_EDGE));
                    flush(&mut seq, &mut strips, &mut swaps);
                    entry = NO_EDGE;
                    costs = [0, 0];
                    q = next;
                    continue;
                }
                costs = after;
            }
            seq.push((q, entry, exit));
            if exit == NO_EDGE {
                break;
            }
            entry = (link[s as usize] & 3) as u8;
            q = next;
        }
        flush(&mut seq, &mut strips, &mut swaps);
    }
    (strips, cycles, swaps)
}

fn union(parent: &mut [u32], size: &mut [u32], ra: u32, rc: u32) {
    let (big, small) = if size[ra as usize] >= size[rc as usize] {
        (ra, rc)
    } else {
        (rc, ra)
    };
    parent[small as usize] = big;
    size[big as usize] += size[small as usize];
}

/// `x -> y` over slot `sxy` and `z -> w` over slot `szw` replace `x -> w0` and `z0 -> y`
/// style links: with `pred(y) = z` in the other cycle, the cycles become
/// `x -> y -> ... -> z -> w -> ...`.
#[allow(clippy::too_many_arguments)]
fn splice(
    x: u32,
    y: u32,
    z: u32,
    w: u32,
    sxy: u32,
    szw: u32,
    succ: &mut [u32],
    pred: &mut [u32],
    succ_slot: &mut [u32],
) {
    succ[x as usize] = y;
    succ_slot[x as usize] = sxy;
    pred[y as usize] = x;
    succ[z as usize] = w;
    succ_slot[z as usize] = szw;
    pred[w as usize] = z;
}

/// Reverses the cycle through `x`: every successor becomes the predecessor, each
/// over the same dual edge seen from the other side.
fn reverse_cycle(x: u32, succ: &mut [u32], pred: &mut [u32], succ_slot: &mut [u32], link: &[u32]) {
    // The slot from y back to its old predecessor p is the partner of p's old slot.
    let mut y = x;
    let mut prev_slot = {
        let p = pred[x as usize];
        succ_slot[p as usize]
    };
    loop {
        let old_succ = succ[y as usize];
        let old_slot = succ_slot[y as usize];
        let l = link[prev_slot as usize];
        succ_slot[y as usize] = 4 * (l >> 2) + (l & 3);
        let old_pred = pred[y as usize];
        succ[y as usize] = old_pred;
        pred[y as usize] = old_succ;
        prev_slot = old_slot;
        y = old_succ;
        if y == x {
            break;
        }
    }
}

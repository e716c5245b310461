//! From a matching to strips: the strip links the matching leaves, the pieces they
//! form (loops and, on meshes with boundaries, paths), and the greedy merging of the
//! pieces by the operations of the paper (nodal vertex, edge swap, edge split) plus
//! two that only paths allow (joining two path ends, and opening a loop onto a path
//! end).
//!
//! Merging runs in passes. A pass finds every operation valid on the pieces as they
//! are, sorts them by (class, cost) — operations that leave the mesh alone first, then
//! swaps, then splits; inside a class the weight the strip loses — and applies them in
//! that order while union-find says they still join different pieces. Each triangle
//! takes part in at most one operation per pass, so the operations of a pass are
//! independent local rewirings and union-find tracks exactly what they join. The next
//! pass starts over on the changed mesh (the pieces of a split may merge again), until
//! one piece is left per component or no operation applies.

use super::work::{edge, WorkMesh};
use crate::vec3::{dot, tri_normal};
use crate::strip::is_degenerate;
use crate::topology::NO_NEIGHBOR;
use crate::topology::{edge_key, EdgeHasher, UnionFind};
use std::collections::HashSet;
use std::hash::BuildHasherDefault;

/// Undirected edges of the mesh, for the swaps' check that the new diagonal is new.
pub(super) type EdgeSet = HashSet<u64, BuildHasherDefault<EdgeHasher>>;

const NONE: u32 = u32::MAX;

/// The pieces of the strip graph: `comp[t]` for every triangle, and whether each piece
/// is a path (else a loop).
pub(crate) struct Pieces {
    pub comp: Vec<u32>,
    pub is_path: Vec<bool>,
    /// Place of each triangle along its piece (from one end, or around the loop).
    pub pos: Vec<u32>,
}

/// The next triangle of the piece after `t`, entered from slot `from` (or from nowhere
/// with `from == 3`): `(next, its slot of the shared edge)`.
fn step(w: &WorkMesh, t: usize, from: usize) -> Option<(usize, usize)> {
    let j = (0..3).find(|&j| j != from && w.linked(t, j))?;
    Some((w.nbr[t][j] as usize, w.twin(t, j)))
}

/// Visits every piece: paths from one end, then loops from their lowest triangle;
/// `f(piece, is_path, triangles in order)`. Degenerate triangles with no links are
/// single-triangle paths.
pub(crate) fn for_each_piece(w: &WorkMesh, mut f: impl FnMut(u32, bool, &[u32])) -> usize {
    let n = w.len();
    let mut seen = vec![false; n];
    let mut buf = Vec::new();
    let mut pieces = 0u32;
    for pass in 0..2 {
        for s in 0..n {
            if seen[s] || (pass == 0 && w.degree(s) == 2) {
                continue;
            }
            buf.clear();
            let (mut t, mut from) = (s, 3);
            loop {
                seen[t] = true;
                buf.push(t as u32);
                match step(w, t, from) {
                    Some((u, k)) if !seen[u] => (t, from) = (u, k),
                    _ => break,
                }
            }
            f(pieces, pass == 0, &buf);
            pieces += 1;
        }
    }
    pieces as usize
}

pub(crate) fn pieces(w: &WorkMesh) -> Pieces {
    let mut comp = vec![NONE; w.len()];
    let mut pos = vec![0; w.len()];
    let mut is_path = Vec::new();
    for_each_piece(w, |p, path, tris| {
        is_path.push(path);
        for (i, &t) in tris.iter().enumerate() {
            comp[t as usize] = p;
            pos[t as usize] = i as u32;
        }
    });
    Pieces { comp, is_path, pos }
}

/// Union-find over pieces, with the path flag of each root.
struct Union {
    sets: UnionFind,
    path: Vec<bool>,
}

impl Union {
    fn find(&mut self, x: u32) -> u32 {
        self.sets.find(x)
    }
    fn union(&mut self, a: u32, b: u32) {
        let (a, b) = (self.find(a), self.find(b));
        if self.sets.union(a, b) {
            let r = self.find(a);
            self.path[r as usize] = self.path[a as usize] | self.path[b as usize];
        }
    }
}

#[derive(Clone, Copy, Debug)]
enum Kind {
    /// Link two path ends across slot `j` of `t`.
    Join { t: u32, j: u8 },
    /// Link path end `e` across slot `j` to loop triangle `t = nbr[e][j]`, and cut the
    /// loop at `t`'s slot `cut`.
    Attach { e: u32, j: u8, cut: u8 },
    /// Swap the edge in slot `j` of `t`.
    Swap { t: u32, j: u8 },
    /// Split the edge in slot `j` of `t`.
    Split { t: u32, j: u8 },
    /// Toggle the links around vertex `v`; `fan` indexes into the pass's fan store.
    Nodal { fan: u32 },
}

#[derive(Clone, Copy, Debug)]
struct Op {
    class: u8,
    cost: f64,
    /// Pieces the operation joins (more first among equal costs).
    joins: u8,
    kind: Kind,
}

/// What merging did.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct MergeStats {
    /// Pieces (and of them paths) before merging.
    pub initial_pieces: usize,
    pub initial_paths: usize,
    pub passes: usize,
    pub nodal: usize,
    pub joins: usize,
    pub attaches: usize,
    pub swaps: usize,
    pub splits: usize,
}

/// Settings of the merge.
pub(crate) struct MergeSettings {
    /// Swaps allowed up to this dihedral angle (radians); `None`: no swaps.
    pub swap_angle: Option<f64>,
}

/// Merges the pieces of `w` greedily (see the module docs).
/// Costs are read from `w.weight`.
pub(crate) fn merge(w: &mut WorkMesh, settings: &MergeSettings) -> MergeStats {
    let mut stats = MergeStats::default();
    let mut stamp: Vec<u32> = Vec::new();
    loop {
        stats.passes += 1;
        let pass = stats.passes as u32;
        let p = pieces(w);
        let piece_count = p.is_path.len();
        if stats.passes == 1 {
            stats.initial_pieces = piece_count;
            stats.initial_paths = p.is_path.iter().filter(|&&x| x).count();
        }
        // Candidate operations on the pieces as they are.
        let edges = settings.swap_angle.map(|_| edge_set(w));
        let mut ops = pair_candidates(w, &p, settings.swap_angle, edges.as_ref());
        let mut fans = Fans { store: Vec::new(), offsets: vec![0] };
        nodal_candidates(w, &p, &mut ops, &mut fans);
        if ops.is_empty() {
            break;
        }
        ops.sort_by(|a, b| a.class.cmp(&b.class).then(a.cost.total_cmp(&b.cost)).then(b.joins.cmp(&a.joins)));
        stamp.resize(w.len(), 0);
        let mut run = Pass {
            w: &mut *w,
            p: &p,
            uf: Union { sets: UnionFind::new(piece_count), path: p.is_path.clone() },
            stamp: &mut stamp,
            pass,
            edges,
            fans: &fans,
            stats: &mut stats,
        };
        if run.apply(ops) == 0 {
            break;
        }
    }
    stats
}

/// The undirected edges of `w`'s triangles.
fn edge_set(w: &WorkMesh) -> EdgeSet {
    let mut s = EdgeSet::with_capacity_and_hasher(w.len() * 3 / 2, Default::default());
    for t in &w.tris {
        for j in 0..3 {
            let (a, b) = edge(t, j);
            s.insert(edge_key(a, b));
        }
    }
    s
}

/// The operations across one unlinked edge between two pieces, for every such edge
/// in triangle order: joining two path ends, attaching a path end to a loop (cut
/// where the strip loses least), and unless both pieces are paths, a swap
/// (`swap_angle` given and [`swap_ok`]) and a split.
fn pair_candidates(w: &WorkMesh, p: &Pieces, swap_angle: Option<f64>, edges: Option<&EdgeSet>) -> Vec<Op> {
    let mut ops: Vec<Op> = Vec::new();
    for t in 0..w.len() {
        for j in 0..3 {
            let u = w.nbr[t][j];
            if u == NO_NEIGHBOR || (u as usize) < t || w.linked(t, j) {
                continue;
            }
            let u = u as usize;
            let (ct, cu) = (p.comp[t], p.comp[u]);
            if ct == cu {
                continue;
            }
            let wt = w.weight[t][j];
            let (et, eu) = (w.degree(t) < 2, w.degree(u) < 2);
            if et && eu {
                ops.push(Op { class: 0, cost: wt, joins: 2, kind: Kind::Join { t: t as u32, j: j as u8 } });
                continue;
            }
            if et != eu {
                let (e, je, l) = if et { (t, j, u) } else { (u, w.twin(t, j), t) };
                if !p.is_path[p.comp[l] as usize] {
                    // Cut the loop at l where the strip loses least.
                    let (cut, cw) = (0..3)
                        .filter(|&k| w.linked(l, k))
                        .map(|k| (k, w.weight[l][k]))
                        .fold((3, f64::NEG_INFINITY), |b, x| if x.1 > b.1 { x } else { b });
                    if cut < 3 {
                        ops.push(Op {
                            class: 0,
                            cost: wt - cw,
                            joins: 2,
                            kind: Kind::Attach { e: e as u32, j: je as u8, cut: cut as u8 },
                        });
                    }
                }
            }
            if p.is_path[ct as usize] && p.is_path[cu as usize] {
                continue;
            }
            if let (Some(max), Some(edges)) = (swap_angle, edges) {
                if swap_ok(w, t, j, max, edges) {
                    ops.push(Op { class: 1, cost: 2.0 * wt, joins: 2, kind: Kind::Swap { t: t as u32, j: j as u8 } });
                }
            }
            let (c, d) = swap_diagonal(w, t, j);
            if c != d && !is_degenerate(&w.tris[t]) && !is_degenerate(&w.tris[u]) {
                // (c == d: the two share every edge, a pillow no split can open.)
                ops.push(Op { class: 2, cost: 2.0 * wt, joins: 2, kind: Kind::Split { t: t as u32, j: j as u8 } });
            }
        }
    }
    ops
}

/// The fans of a pass's nodal operations: (triangle, slot towards the next) pairs,
/// flattened, fan `i` at `store[offsets[i]..offsets[i + 1]]`.
struct Fans {
    store: Vec<u32>,
    offsets: Vec<u32>,
}

/// One pass applying its sorted operations: what the steps share.
struct Pass<'a> {
    w: &'a mut WorkMesh,
    p: &'a Pieces,
    uf: Union,
    /// `stamp[t] == pass`: triangle `t` took part in an operation of this pass.
    stamp: &'a mut Vec<u32>,
    pass: u32,
    /// The mesh's edges, kept up to date by swaps and splits (with swaps only).
    edges: Option<EdgeSet>,
    fans: &'a Fans,
    stats: &'a mut MergeStats,
}

impl Pass<'_> {
    /// Applies `ops` in order while they still join different pieces through
    /// triangles no earlier operation of the pass touched; returns how many ran.
    fn apply(&mut self, ops: Vec<Op>) -> usize {
        let mut applied = 0;
        // Only the cheapest class that applies runs in a pass: after free merges, the
        // next pass may find new free ones where a swap or split was queued.
        let mut pass_class = None;
        for op in ops {
            if pass_class.is_some_and(|c| op.class > c) {
                break;
            }
            let done = match op.kind {
                Kind::Join { t, j } => self.join(t, j),
                Kind::Attach { e, j, cut } => self.attach(e, j, cut),
                Kind::Swap { t, j } => self.swap_or_split(t, j, true),
                Kind::Split { t, j } => self.swap_or_split(t, j, false),
                Kind::Nodal { fan } => self.nodal(fan, op.joins),
            };
            if done {
                applied += 1;
                pass_class = Some(op.class);
            }
        }
        applied
    }

    fn free(&self, t: u32) -> bool {
        self.stamp[t as usize] != self.pass
    }

    fn mark(&mut self, t: u32) {
        self.stamp[t as usize] = self.pass;
    }

    /// The roots of the pieces of triangles `t` and `u`.
    fn roots(&mut self, t: u32, u: u32) -> (u32, u32) {
        (self.uf.find(self.p.comp[t as usize]), self.uf.find(self.p.comp[u as usize]))
    }

    fn join(&mut self, t: u32, j: u8) -> bool {
        let u = self.w.nbr[t as usize][j as usize];
        if !self.free(t) || !self.free(u) {
            return false;
        }
        let (a, b) = self.roots(t, u);
        if a == b {
            return false;
        }
        self.w.set_link(t as usize, j as usize, true);
        self.uf.union(a, b);
        self.stats.joins += 1;
        self.mark(t);
        self.mark(u);
        true
    }

    fn attach(&mut self, e: u32, j: u8, cut: u8) -> bool {
        let l = self.w.nbr[e as usize][j as usize];
        let x = self.w.nbr[l as usize][cut as usize];
        if !self.free(e) || !self.free(l) || !self.free(x) {
            return false;
        }
        let (a, b) = self.roots(e, l);
        if a == b || self.uf.path[b as usize] {
            return false;
        }
        self.w.set_link(l as usize, cut as usize, false);
        self.w.set_link(e as usize, j as usize, true);
        self.uf.union(a, b);
        self.stats.attaches += 1;
        for s in [e, l, x] {
            self.mark(s);
        }
        true
    }

    /// A swap (`swap`) or a split of the edge in slot `j` of `t`.
    fn swap_or_split(&mut self, t: u32, j: u8, swap: bool) -> bool {
        let u = self.w.nbr[t as usize][j as usize];
        if !self.free(t) || !self.free(u) {
            return false;
        }
        let (a, b) = self.roots(t, u);
        if a == b || (self.uf.path[a as usize] && self.uf.path[b as usize]) {
            return false;
        }
        let w = &mut *self.w;
        if swap {
            let edges = self.edges.as_mut().expect("swaps only with the edge set");
            let (c, d) = swap_diagonal(w, t as usize, j as usize);
            if edges.contains(&edge_key(c, d)) {
                return false;
            }
            let (x, y) = edge(&w.tris[t as usize], j as usize);
            edges.remove(&edge_key(x, y));
            edges.insert(edge_key(c, d));
            w.swap(t as usize, j as usize);
            self.stats.swaps += 1;
        } else {
            let [tb, ub] = w.split(t as usize, j as usize, true);
            self.stamp.resize(w.len(), 0);
            if let Some(edges) = self.edges.as_mut() {
                let m = w.tris[tb as usize][0];
                let [x, y] = *w.steiner.last().expect("just split");
                edges.remove(&edge_key(x, y));
                let c = w.tris[tb as usize][2];
                let d = w.tris[ub as usize][2];
                for q in [x, y, c, d] {
                    edges.insert(edge_key(q, m));
                }
            }
            self.mark(tb);
            self.mark(ub);
            self.stats.splits += 1;
        }
        self.uf.union(a, b);
        self.mark(t);
        self.mark(u);
        true
    }

    /// Toggles the links of fan `fan` when its on links still lie in `joins`
    /// different pieces, at most one of them a path.
    fn nodal(&mut self, fan: u32, joins: u8) -> bool {
        let fans = self.fans;
        let f = &fans.store[fans.offsets[fan as usize] as usize..fans.offsets[fan as usize + 1] as usize];
        if f.chunks(2).any(|c| !self.free(c[0])) {
            return false;
        }
        let mut roots: Vec<u32> = f.chunks(2).map(|c| self.uf.find(self.p.comp[c[0] as usize])).collect();
        roots.sort_unstable();
        roots.dedup();
        if roots.len() != joins as usize || roots.iter().filter(|&&r| self.uf.path[r as usize]).count() > 1 {
            return false;
        }
        // Toggle the link out of every fan triangle towards the next.
        let links: Vec<bool> = f.chunks(2).map(|c| self.w.linked(c[0] as usize, c[1] as usize)).collect();
        for (c, on) in f.chunks(2).zip(links) {
            self.w.set_link(c[0] as usize, c[1] as usize, !on);
        }
        for &r in &roots[1..] {
            self.uf.union(roots[0], r);
        }
        for c in f.chunks(2) {
            self.mark(c[0]);
        }
        self.stats.nodal += 1;
        true
    }
}

/// The new diagonal `(c, d)` a swap of slot `j` of `t` would make.
fn swap_diagonal(w: &WorkMesh, t: usize, j: usize) -> (u32, u32) {
    let u = w.nbr[t][j] as usize;
    let k = w.twin(t, j);
    (w.tris[t][(j + 2) % 3], w.tris[u][(k + 2) % 3])
}

/// A swap is allowed on a convex, nearly flat quad whose other diagonal is no edge yet.
pub(super) fn swap_ok(w: &WorkMesh, t: usize, j: usize, max_angle: f64, edges: &EdgeSet) -> bool {
    let max_angle = max_angle.max(1e-6); // rounding in the normals of coplanar triangles
    let u = w.nbr[t][j] as usize;
    let (a, b) = edge(&w.tris[t], j);
    let (c, d) = swap_diagonal(w, t, j);
    if c == d || a == b || edges.contains(&edge_key(c, d)) || is_degenerate(&w.tris[t]) || is_degenerate(&w.tris[u]) {
        return false;
    }
    let (nt, nu) = (w.normal(t), w.normal(u));
    if nt == [0.0; 3] || nu == [0.0; 3] || dot(nt, nu).clamp(-1.0, 1.0).acos() > max_angle {
        return false;
    }
    // Convex: both new triangles (a, d, c) and (d, b, c) face the way of the old ones.
    let p = |i: u32| w.pos[i as usize];
    let n = [nt[0] + nu[0], nt[1] + nu[1], nt[2] + nu[2]];
    let ln = dot(n, n).sqrt();
    let n1 = tri_normal(p(a), p(d), p(c));
    let n2 = tri_normal(p(d), p(b), p(c));
    let (l1, l2) = (dot(n1, n1).sqrt(), dot(n2, n2).sqrt());
    let min_cos = max_angle.cos();
    ln > 0.0 && l1 > 0.0 && l2 > 0.0 && dot(n1, n) / (l1 * ln) >= min_cos && dot(n2, n) / (l2 * ln) >= min_cos
}

/// Whether toggling the alternating links of `fan` (loops only) leaves one loop
/// through it. Cut at the fan, the loops are arcs joining the fan triangles' outer
/// sides in pairs (`sigma`, read off the triangles' places along their loops); the
/// links around the vertex pair them the other way (`alpha` now, `beta` after the
/// toggle); the loops through the fan are the cycles of `sigma` and the pairing.
fn joins_all(p: &Pieces, fan: &[u32], on0: bool) -> bool {
    let n = fan.len() / 2;
    if n > 32 {
        return false;
    }
    let on = |q: usize| (q % 2 == 0) == on0; // link T_q - T_{q+1}
    let alpha = |q: usize| if on(q) { (q + 1) % n } else { (q + n - 1) % n };
    let beta = |q: usize| if on(q) { (q + n - 1) % n } else { (q + 1) % n };
    let mut order: [(u32, u32, u8); 32] = [(0, 0, 0); 32];
    for q in 0..n {
        let t = fan[2 * q] as usize;
        order[q] = (p.comp[t], p.pos[t], q as u8);
    }
    let order = &mut order[..n];
    order.sort_unstable();
    let mut sigma = [0u8; 32];
    let mut i = 0;
    while i < n {
        let mut j = i;
        while j < n && order[j].0 == order[i].0 {
            j += 1;
        }
        // order[i..j]: one loop's fan triangles by place; alpha pairs are neighbours
        // in this order, either (i, i+1), .. or wrapped (j-1, i), (i+1, i+2), ..
        let run = &order[i..j];
        let m = run.len();
        if m % 2 == 1 {
            return false;
        }
        let shift = if alpha(run[0].2 as usize) == run[1 % m].2 as usize { 1 } else { 0 };
        for k in (0..m).step_by(2) {
            let (a, b) = (run[(k + shift) % m].2, run[(k + shift + 1) % m].2);
            if alpha(a as usize) == b as usize && m > 2 {
                return false; // not the alternation assumed
            }
            sigma[a as usize] = b;
            sigma[b as usize] = a;
        }
        i = j;
    }
    // Cycles of beta then sigma: one cycle is one loop.
    let mut seen = 0u32;
    let mut q = 0;
    let mut len = 0;
    loop {
        seen |= 1 << q;
        let r = beta(q);
        seen |= 1 << r;
        len += 2;
        q = sigma[r] as usize;
        if seen >> q & 1 == 1 {
            break;
        }
    }
    len == n
}

/// Nodal vertices: a closed fan of an even number of triangles whose links to the next
/// triangle alternate on and off, the on links in as many different pieces as there
/// are on links, at most one of them a path. Toggling every link of the fan joins them.
/// The fan is stored as (triangle, slot towards the next) pairs.
fn nodal_candidates(w: &WorkMesh, p: &Pieces, ops: &mut Vec<Op>, fans: &mut Fans) {
    let nv = w.pos.len();
    // One triangle and corner per vertex, the first met.
    let mut first = vec![NONE; nv];
    for (t, tri) in w.tris.iter().enumerate() {
        for (i, &v) in tri.iter().enumerate() {
            if first[v as usize] == NONE {
                first[v as usize] = (t * 3 + i) as u32;
            }
        }
    }
    let mut fan: Vec<u32> = Vec::new();
    let mut comps: Vec<u32> = Vec::new();
    'vertex: for (v, &f0) in first.iter().enumerate() {
        if f0 == NONE {
            continue;
        }
        fan.clear();
        let (t0, i0) = ((f0 / 3) as usize, (f0 % 3) as usize);
        let (mut t, mut i) = (t0, i0);
        loop {
            // Slot i is the edge (v, x) out of t; the next fan triangle is across it.
            fan.push(t as u32);
            fan.push(i as u32);
            if fan.len() > 64 {
                continue 'vertex; // valence over 32: not worth it
            }
            let u = w.nbr[t][i];
            if u == NO_NEIGHBOR {
                continue 'vertex;
            }
            let k = w.twin(t, i);
            (t, i) = (u as usize, (k + 1) % 3);
            if w.tris[t][i] != v as u32 {
                continue 'vertex;
            }
            if t == t0 {
                break;
            }
        }
        let n = fan.len() / 2;
        if n < 4 || n % 2 == 1 || t != t0 || i != i0 {
            continue;
        }
        // Alternation, and the on links' pieces.
        let on0 = w.linked(fan[0] as usize, fan[1] as usize);
        comps.clear();
        let mut cost = 0.0;
        let mut paths = 0;
        for q in 0..n {
            let (ft, fs) = (fan[2 * q] as usize, fan[2 * q + 1] as usize);
            let on = w.linked(ft, fs);
            if on != ((q % 2 == 0) == on0) {
                continue 'vertex;
            }
            let wq = w.weight[ft][fs];
            if on {
                cost -= wq;
                let c = p.comp[ft];
                paths += p.is_path[c as usize] as usize;
                comps.push(c);
            } else {
                cost += wq;
            }
        }
        comps.sort_unstable();
        comps.dedup();
        let strict = comps.len() * 2 == n;
        if paths > 1 || (paths == 1 && !strict) || comps.len() < 2 || !(strict || joins_all(p, &fan, on0)) {
            continue;
        }
        let fan_id = (fans.offsets.len() - 1) as u32;
        ops.push(Op { class: 0, cost, joins: comps.len().min(255) as u8, kind: Kind::Nodal { fan: fan_id } });
        fans.store.extend_from_slice(&fan);
        fans.offsets.push(fans.store.len() as u32);
    }
}

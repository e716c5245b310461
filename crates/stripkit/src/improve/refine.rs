//! The local search over walks: [`refine`] and the FIFO replay that scores its moves
//! exactly ([`Refiner`]).

use super::flips::{Flips, FLIP_LINKS};
use super::moves::{attach, ends, Move, Piece, MOVE_SLOTS, NONE};
use super::tunnels::Tunnels;
use crate::metrics::Fifo;
use crate::strip::{join_shared_ends, joins_at_vertex, StripSet};
use crate::topology::walks::{inner_swap, walk};
use crate::topology::{vertex_bound, DualGraph, Walks, NO_NEIGHBOR};

/// Triangles simulated past a change: a move whose FIFO has not come back to the old
/// contents by then is not taken (so that every taken move is measured exactly).
pub(super) const REFINE_WINDOW: usize = 1024;

/// How hard [`refine`] searches.
#[derive(Clone, Copy)]
pub(crate) struct Effort {
    /// Passes over the strips; the later ones look only at strips next to those the
    /// pass before changed.
    pub(crate) passes: u32,
    /// Most links one flip drops (at most [`FLIP_LINKS`]).
    pub(crate) flip_links: usize,
}

/// The strips of [`refine`] with the FIFO before each of them, and a private FIFO to
/// replay a stretch of the output from one of those snapshots.
pub(super) struct Refiner<'a> {
    pub(super) tris: &'a [[u32; 3]],
    pub(super) graph: &'a DualGraph,
    /// Cache entries.
    pub(super) c: usize,
    /// Walk and encoded strip per slot (empty: the slot lost its strip).
    pub(super) walks: Vec<Vec<u32>>,
    pub(super) enc: Vec<Vec<u32>>,
    /// Triangle -> slot, position in the slot's walk, and the swaps its walk needs
    /// at inner triangles up to it (see [`Refiner::index_walk`]).
    pub(super) slot_of: Vec<u32>,
    pub(super) pos: Vec<u32>,
    pub(super) pre: Vec<u32>,
    /// FIFO contents (oldest first, NONE for empty entries) before each slot, and
    /// after the last one: `snap[k * c..(k + 1) * c]`.
    pub(super) snap: Vec<u32>,
    /// Misses of each slot's strip.
    pub(super) miss: Vec<u32>,
    /// The pass in which a taken move last replayed the slot.
    pub(super) touched: Vec<u32>,
    pub(super) pass: u32,
    /// The replay FIFO.
    pub(super) fifo: Fifo,
    /// The encoded new strips of the move being evaluated.
    pub(super) nbuf: [Vec<u32>; MOVE_SLOTS],
}

impl Refiner<'_> {
    /// Fills `pos` and `pre` for the walk of slot `k`: `pre[w[j]]` counts the swaps at
    /// `w[2..=j]`. A swap at an inner triangle depends only on it, the triangle after
    /// it and the two before (see the module docs of `stripify`): the swaps of a
    /// 4-window less those of its first three triangles.
    fn index_walk(&mut self, k: usize) {
        let w = &self.walks[k];
        let mut acc = 0;
        for (j, &t) in w.iter().enumerate() {
            self.pos[t as usize] = j as u32;
            if j >= 2 && j + 1 < w.len() {
                acc += inner_swap(self.tris, self.graph, &w[j - 2..j + 2]);
            }
            self.pre[t as usize] = acc;
        }
    }

    /// The strip in slot `k` after the move being evaluated: its new strip (in
    /// `nbuf`) when `mv` changes the slot, else the slot's own.
    fn strip_after<'s>(&'s self, mv: &Move, k: u32) -> &'s [u32] {
        match mv.ch[..mv.n as usize].iter().position(|c| c.0 == k) {
            Some(i) => &self.nbuf[i],
            None => &self.enc[k as usize],
        }
    }

    /// Joins at a vertex ([`joins_at_vertex`]) that `mv` makes less those it breaks,
    /// the new strips being in `nbuf`. Only the boundaries next to a changed slot
    /// change: those between a changed slot and the nearest non-empty slot before and
    /// after it (empty slots are skipped), before and after the move; where a move
    /// empties slots, the non-empty slots around them become neighbours.
    fn join_change(&self, mv: &Move) -> i64 {
        let n = mv.n as usize;
        // The changed slots and their non-empty neighbours before the move, sorted.
        let mut u = [0u32; 3 * MOVE_SLOTS];
        let mut m = 0;
        for &(k, _, _) in &mv.ch[..n] {
            u[m] = k;
            m += 1;
            let k = k as usize;
            if let Some(p) = (0..k).rev().find(|&p| !self.enc[p].is_empty()) {
                u[m] = p as u32;
                m += 1;
            }
            if let Some(q) = (k + 1..self.enc.len()).find(|&q| !self.enc[q].is_empty()) {
                u[m] = q as u32;
                m += 1;
            }
        }
        let u = &mut u[..m];
        u.sort_unstable();
        self.boundary_joins(mv, u, true) - self.boundary_joins(mv, u, false)
    }

    /// Joins at a vertex on the boundaries between the slots `u` (sorted, possibly
    /// repeated) that touch a slot `mv` changes, or that have changed slots, empty,
    /// between their two strips: after the move (`after`) or before it.
    fn boundary_joins(&self, mv: &Move, u: &[u32], after: bool) -> i64 {
        let changed = |k: u32| mv.ch[..mv.n as usize].iter().any(|c| c.0 == k);
        let strip = |k: u32| {
            if after {
                self.strip_after(mv, k)
            } else {
                &self.enc[k as usize][..]
            }
        };
        let mut joins = 0i64;
        let mut prev: Option<u32> = None;
        let mut gap = false;
        for (i, &k) in u.iter().enumerate() {
            if i > 0 && u[i - 1] == k {
                continue;
            }
            let s = strip(k);
            if s.is_empty() {
                gap |= changed(k);
                continue;
            }
            if let Some(p) = prev {
                if (gap || changed(p) || changed(k)) && joins_at_vertex(strip(p), s) {
                    joins += 1;
                }
            }
            prev = Some(k);
            gap = false;
        }
        joins
    }

    /// Joins at a vertex between consecutive non-empty slots: the strips of
    /// [`refine`] save that many restart indices once [`join_shared_ends`] has run.
    fn vertex_joins(&self) -> u64 {
        let mut joins = 0;
        let mut prev: Option<&[u32]> = None;
        for s in self.enc.iter().filter(|s| !s.is_empty()) {
            if prev.is_some_and(|p| joins_at_vertex(p, s)) {
                joins += 1;
            }
            prev = Some(s);
        }
        joins
    }

    /// Starts a replay from the FIFO before slot `k`.
    fn load(&mut self, k: usize) {
        let c = self.c;
        self.fifo.load(&self.snap[k * c..(k + 1) * c]);
    }

    /// Feeds the triangles of one strip; returns its misses.
    #[inline]
    fn replay(&mut self, strip: &[u32]) -> u32 {
        let mut m = 0;
        crate::strip::for_each_triangle(strip, |t| {
            for v in t {
                m += u32::from(self.fifo.touch(v));
            }
        });
        m
    }

    /// Whether the replay FIFO holds what snapshot `k` holds, in the same order.
    fn matches(&self, k: usize) -> bool {
        let c = self.c;
        self.fifo.matches(&self.snap[k * c..(k + 1) * c])
    }

    fn store(&mut self, k: usize) {
        let c = self.c;
        self.fifo.snapshot(&mut self.snap[k * c..(k + 1) * c]);
    }

    /// Replays every strip from an empty FIFO, taking the snapshots; the misses.
    fn replay_all(&mut self) -> u64 {
        let c = self.c;
        self.snap[..c].fill(NONE);
        self.load(0);
        let mut total = 0;
        for k in 0..self.walks.len() {
            let strip = std::mem::take(&mut self.enc[k]);
            self.miss[k] = self.replay(&strip);
            self.enc[k] = strip;
            total += u64::from(self.miss[k]);
            self.store(k + 1);
        }
        total
    }

    /// The change in indices and misses that `mv` makes, or None when its effect on
    /// the FIFO outlasts [`REFINE_WINDOW`] triangles. With `apply`, makes the move
    /// (taken only for moves that returned Some without it: the replay is the same).
    ///
    /// From the first slot changed, the strips are replayed (new walks in the changed
    /// slots) until the FIFO matches the old one before some slot after the last
    /// change: from there on nothing differs. Between changes far apart, the replay
    /// jumps to the next change once the FIFO matches.
    fn eval(&mut self, mv: &Move, pool: &[u32], apply: bool) -> Option<(i64, i64)> {
        let slots = self.walks.len();
        let n = mv.n as usize;
        let mut di = 0i64;
        for i in 0..n {
            let (k, start, len) = mv.ch[i];
            let w = &pool[start as usize..(start + len) as usize];
            let mut buf = std::mem::take(&mut self.nbuf[i]);
            buf.clear();
            if !w.is_empty() {
                walk(self.tris, self.graph, w.len(), |j| w[j], |v| buf.push(v));
                di += buf.len() as i64 + 1;
            }
            self.nbuf[i] = buf;
            let old = &self.enc[k as usize];
            if !old.is_empty() {
                di -= old.len() as i64 + 1;
            }
        }
        di -= self.join_change(mv);
        let mut ci = 0;
        let mut k = mv.ch[0].0 as usize;
        self.load(k);
        let mut steps = 0;
        let mut dm = 0i64;
        loop {
            let misses = if ci < n && mv.ch[ci].0 as usize == k {
                let strip = std::mem::take(&mut self.nbuf[ci]);
                let m = self.replay(&strip);
                self.nbuf[ci] = strip;
                steps += mv.ch[ci].2 as usize;
                ci += 1;
                m
            } else {
                let strip = std::mem::take(&mut self.enc[k]);
                let m = self.replay(&strip);
                self.enc[k] = strip;
                steps += self.walks[k].len();
                m
            };
            dm += i64::from(misses) - i64::from(self.miss[k]);
            if apply {
                self.miss[k] = misses;
                self.touched[k] = self.pass;
            }
            k += 1;
            let same = self.matches(k);
            if apply {
                self.store(k);
            }
            if k == slots {
                break;
            }
            if same || steps > REFINE_WINDOW {
                if !same && !apply {
                    return None;
                }
                if ci == n {
                    break;
                }
                if mv.ch[ci].0 as usize > k {
                    k = mv.ch[ci].0 as usize;
                    self.load(k);
                }
                steps = 0;
            }
        }
        if apply {
            for i in 0..n {
                let (k, start, len) = mv.ch[i];
                let w = &pool[start as usize..(start + len) as usize];
                for &t in w {
                    self.slot_of[t as usize] = k;
                }
                let k = k as usize;
                self.walks[k].clear();
                self.walks[k].extend_from_slice(w);
                self.enc[k].clear();
                self.enc[k].extend_from_slice(&self.nbuf[i]);
            }
            for i in 0..n {
                self.index_walk(mv.ch[i].0 as usize);
            }
        }
        Some((di, dm))
    }
}

/// Local search over `walks` (the strips in output order, as the stripifier records
/// them), scored by
/// `indices_restart + lambda * misses` on the exact FIFO of `cache_size` entries,
/// with the total misses kept at most `budget`. `indices_restart` is that of the
/// strips after [`join_shared_ends`]: a boundary where a strip of even length ends on
/// the vertex the next non-empty slot's strip starts with costs no restart index.
/// Returns the strips, so joined, and their misses.
///
/// For each strip X in turn, the moves tried are: X read backwards; X joined to a
/// strip S whose end triangle is a dual neighbour of an end of X (X appended or
/// prepended, reversed as needed), the joined walk taking the place of S or of X; and,
/// where the neighbour `n` lies inside S = A n B, X joined to `A n` (or `n B`) while
/// the part cut off joins a third strip Z at one of its ends, the two new walks taking
/// the places of two of X, S and Z; and the tunnels of [`Tunnels`] from X's ends
/// (paths through two or three strips that end at a strip end, or through one to
/// three that end after a cut), the new walks taking the places of the strips on the
/// path in their order, shifted by one or not; and the flips of [`Flips`]
/// (alternating cycles through a swap of X, and alternating paths from an end of X
/// that touch some strip twice), the new walks in the places of the strips they
/// touch. The best move that lowers the cost is taken. Every walk is encoded with [`walk`], so every triangle keeps its
/// winding.
///
/// A move is evaluated by replaying the FIFO from the snapshot before the first strip
/// it changes until the FIFO matches the old one again (see [`Refiner::eval`]): on
/// bunny about 200 triangles per move, 113,000 moves in three passes (23,000 of them
/// tunnels, out of about 300,000 paths whose index change is counted in O(1)).
pub(crate) fn refine(
    tris: &[[u32; 3]],
    graph: &DualGraph,
    walks: &Walks,
    cache_size: usize,
    lambda: f64,
    budget: u64,
    effort: Effort,
) -> (StripSet, u64) {
    let walks: Vec<Vec<u32>> = walks.iter().map(|w| w.to_vec()).collect();
    let c = cache_size;
    let slots = walks.len();
    let mut slot_of = vec![NONE; tris.len()];
    for (k, w) in walks.iter().enumerate() {
        for &t in w {
            slot_of[t as usize] = k as u32;
        }
    }
    let enc = walks
        .iter()
        .map(|w| {
            let mut strip = Vec::with_capacity(w.len() + 4);
            walk(tris, graph, w.len(), |i| w[i], |v| strip.push(v));
            strip
        })
        .collect();
    let vcount = vertex_bound(tris);
    let mut r = Refiner {
        tris,
        graph,
        c,
        walks,
        enc,
        slot_of,
        pos: vec![0; tris.len()],
        pre: vec![0; tris.len()],
        snap: vec![NONE; (slots + 1) * c],
        miss: vec![0; slots],
        touched: vec![0; slots],
        pass: 0,
        fifo: Fifo::new(c as u32, vcount),
        nbuf: Default::default(),
    };
    for k in 0..slots {
        r.index_walk(k);
    }
    let mut total = r.replay_all();
    // The index count of the strips once joined at their shared ends, kept up to date
    // by the moves taken (checked against the output in debug builds).
    let mut indices = r.enc.iter().map(|s| s.len() as i64 + 1).sum::<i64>()
        - 1
        - r.vertex_joins() as i64;
    let mut pool: Vec<u32> = Vec::new();
    let mut moves: Vec<Move> = Vec::new();
    let mut used: Vec<u32> = Vec::new();
    let mut joins: Vec<(Piece, Piece)> = Vec::new();
    let mut seen: Vec<[u32; 2 * FLIP_LINKS + 2]> = Vec::new();
    for pass in 1..=effort.passes {
        r.pass = pass;
        let mut changed = false;
        for x in 0..slots {
            let lx = r.walks[x].len();
            if lx == 0 {
                continue;
            }
            let (xe, nx) = ends(&r.walks[x]);
            if pass > 1 {
                // Only strips next to the last pass's changes.
                let recent = |k: u32| k != NONE && r.touched[k as usize] + 1 >= pass;
                let near = recent(x as u32)
                    || xe[..nx].iter().any(|&e| {
                        graph.neighbors[e as usize]
                            .iter()
                            .any(|&n| n != NO_NEIGHBOR && recent(r.slot_of[n as usize]))
                    });
                if !near {
                    continue;
                }
            }
            pool.clear();
            moves.clear();
            let xw = &r.walks[x];
            let xs = x as u32;
            if lx >= 2 {
                let start = pool.len() as u32;
                pool.extend(xw.iter().rev());
                moves.push(Move::new(&[(xs, start, lx as u32)]));
            }
            for &e in &xe[..nx] {
                for &n in &graph.neighbors[e as usize] {
                    if n == NO_NEIGHBOR {
                        continue;
                    }
                    let s = r.slot_of[n as usize];
                    if s == xs || s == NONE {
                        continue;
                    }
                    let sw = &r.walks[s as usize];
                    if sw[0] == n || sw[sw.len() - 1] == n {
                        attach(&mut pool, sw, n, xw, e, |start, len| {
                            moves.push(Move::new(&[(s, start, len), (xs, 0, 0)]));
                            moves.push(Move::new(&[(xs, start, len), (s, 0, 0)]));
                        });
                        continue;
                    }
                    // n inside S = A n B: X joins `A n` (B cut off) or `n B` (A cut
                    // off); the part cut off joins a strip Z at one of its ends.
                    let i = sw.iter().position(|&t| t == n).unwrap_or(0);
                    for (kept, cut) in [(&sw[..=i], &sw[i + 1..]), (&sw[i..], &sw[..i])] {
                        let mut joined = [(0u32, 0u32); 2];
                        let mut nj = 0;
                        attach(&mut pool, kept, n, xw, e, |start, len| {
                            joined[nj] = (start, len);
                            nj += 1;
                        });
                        let (ce, nc) = ends(cut);
                        for &p in &ce[..nc] {
                            for &q in &graph.neighbors[p as usize] {
                                if q == NO_NEIGHBOR {
                                    continue;
                                }
                                let z = r.slot_of[q as usize];
                                if z == xs || z == s || z == NONE {
                                    continue;
                                }
                                let zw = &r.walks[z as usize];
                                if zw[0] != q && zw[zw.len() - 1] != q {
                                    continue;
                                }
                                attach(&mut pool, zw, q, cut, p, |zs, zl| {
                                    for &(js, jl) in &joined[..nj] {
                                        for (a, b, e) in [(s, z, xs), (xs, z, s), (xs, s, z)] {
                                            moves.push(Move::new(&[
                                                (a, js, jl),
                                                (b, zs, zl),
                                                (e, 0, 0),
                                            ]));
                                        }
                                    }
                                });
                            }
                        }
                    }
                }
            }
            let mut tun = Tunnels {
                tris,
                graph,
                walks: &r.walks,
                enc: &r.enc,
                slot_of: &r.slot_of,
                pos: &r.pos,
                pre: &r.pre,
                pool: &mut pool,
                moves: &mut moves,
                used: &mut used,
                joins: &mut joins,
            };
            tun.search(xs);
            let mut flips = Flips {
                tris,
                graph,
                walks: &r.walks,
                slot_of: &r.slot_of,
                pos: &r.pos,
                pre: &r.pre,
                pool: &mut pool,
                moves: &mut moves,
                cyc: [NONE; 2 * FLIP_LINKS + 2],
                links: effort.flip_links.min(FLIP_LINKS),
                seen: &mut seen,
            };
            flips.search(xs);
            flips.search_paths(xs);
            let mut best: Option<(f64, usize, i64)> = None;
            for (i, mv) in moves.iter().enumerate() {
                let Some((di, dm)) = r.eval(mv, &pool, false) else {
                    continue;
                };
                if total as i64 + dm > budget as i64 {
                    continue;
                }
                let d = di as f64 + lambda * dm as f64;
                if d < -1e-9 && best.is_none_or(|b| d < b.0) {
                    best = Some((d, i, dm));
                }
            }
            if let Some((_, i, dm)) = best {
                let mv = moves[i];
                if let Some((di, _)) = r.eval(&mv, &pool, true) {
                    indices += di;
                }
                total = (total as i64 + dm) as u64;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let mut out = StripSet::new();
    for strip in r.enc.iter().filter(|s| !s.is_empty()) {
        out.push(strip);
    }
    join_shared_ends(&mut out);
    debug_assert_eq!(out.restart_len() as i64, indices.max(0));
    (out, total)
}

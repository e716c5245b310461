//! The local search over walks: [`refine`] and the FIFO replay that scores its moves
//! exactly ([`Refiner`]).

use super::flips::Flips;
use super::moves::{simple_moves, Move, MoveList};
use super::piece::{ends, Piece, FLIP_LINKS, MOVE_SLOTS, NONE};
use super::slots::Slots;
use super::tunnels::Tunnels;
use crate::metrics::Fifo;
use crate::strip::{join_shared_ends, joins_at_vertex, StripSet};
use crate::topology::walks::walk;
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
struct Refiner<'a> {
    /// The walks and strips in their slots.
    s: Slots<'a>,
    /// Cache entries.
    c: usize,
    /// FIFO contents (oldest first, NONE for empty entries) before each slot, and
    /// after the last one: `snap[k * c..(k + 1) * c]`.
    snap: Vec<u32>,
    /// Misses of each slot's strip.
    miss: Vec<u32>,
    /// The pass in which a taken move last replayed the slot.
    touched: Vec<u32>,
    pass: u32,
    /// The replay FIFO.
    fifo: Fifo,
    /// The encoded new strips of the move being evaluated.
    nbuf: [Vec<u32>; MOVE_SLOTS],
}

impl<'a> Refiner<'a> {
    /// The slots of `walks` and the FIFO before each of them.
    fn new(tris: &'a [[u32; 3]], graph: &'a DualGraph, walks: &Walks, cache_size: usize) -> Self {
        let s = Slots::new(tris, graph, walks);
        let (slots, c) = (s.len(), cache_size);
        Refiner {
            s,
            c,
            snap: vec![NONE; (slots + 1) * c],
            miss: vec![0; slots],
            touched: vec![0; slots],
            pass: 0,
            fifo: Fifo::new(c as u32, vertex_bound(tris)),
            nbuf: Default::default(),
        }
    }

    /// The strip in slot `k` after the move being evaluated: its new strip (in
    /// `nbuf`) when `mv` changes the slot, else the slot's own.
    fn strip_after<'s>(&'s self, mv: &Move, k: u32) -> &'s [u32] {
        match mv.ch[..mv.n as usize].iter().position(|c| c.0 == k) {
            Some(i) => &self.nbuf[i],
            None => &self.s.enc[k as usize],
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
            if let Some(p) = (0..k).rev().find(|&p| !self.s.enc[p].is_empty()) {
                u[m] = p as u32;
                m += 1;
            }
            if let Some(q) = (k + 1..self.s.enc.len()).find(|&q| !self.s.enc[q].is_empty()) {
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
                &self.s.enc[k as usize][..]
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

    /// Whether slot `x`, or a slot next to one of its ends, was replayed by a move of
    /// the pass before `pass` (the later passes look only there).
    fn near_change(&self, x: usize, pass: u32) -> bool {
        let recent = |k: u32| k != NONE && self.touched[k as usize] + 1 >= pass;
        let (xe, nx) = ends(&self.s.walks[x]);
        recent(x as u32)
            || xe[..nx].iter().any(|&e| {
                self.s.graph.neighbors[e as usize]
                    .iter()
                    .any(|&n| n != NO_NEIGHBOR && recent(self.s.slot_of[n as usize]))
            })
    }

    /// The move of `list` that lowers `indices + lambda * misses` most with the misses
    /// (now `total`) kept within `budget`, and its change in misses.
    fn best(&mut self, list: &MoveList, total: u64, budget: u64, lambda: f64) -> Option<(usize, i64)> {
        let mut best: Option<(f64, usize, i64)> = None;
        for (i, mv) in list.moves.iter().enumerate() {
            let Some((di, dm)) = self.eval(mv, &list.pool, false) else {
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
        best.map(|(_, i, dm)| (i, dm))
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
        for k in 0..self.s.walks.len() {
            let strip = std::mem::take(&mut self.s.enc[k]);
            self.miss[k] = self.replay(&strip);
            self.s.enc[k] = strip;
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
        let slots = self.s.walks.len();
        let n = mv.n as usize;
        let mut di = 0i64;
        for i in 0..n {
            let (k, start, len) = mv.ch[i];
            let w = &pool[start as usize..(start + len) as usize];
            let mut buf = std::mem::take(&mut self.nbuf[i]);
            buf.clear();
            if !w.is_empty() {
                walk(self.s.tris, self.s.graph, w.len(), |j| w[j], |v| buf.push(v));
                di += buf.len() as i64 + 1;
            }
            self.nbuf[i] = buf;
            let old = &self.s.enc[k as usize];
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
                let strip = std::mem::take(&mut self.s.enc[k]);
                let m = self.replay(&strip);
                self.s.enc[k] = strip;
                steps += self.s.walks[k].len();
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
                self.s.set(k, w, &self.nbuf[i]);
            }
            for i in 0..n {
                self.s.index_walk(mv.ch[i].0 as usize);
            }
        }
        Some((di, dm))
    }
}

/// Local search over `walks` (the strips in output order, as the stripifier records
/// them), scored by `indices_restart + lambda * misses` on the exact FIFO of
/// `cache_size` entries,
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
/// touch. The best move that lowers the cost is taken. Every walk is encoded with
/// [`walk`], so every triangle keeps its winding.
///
/// A move is evaluated by replaying the FIFO from the snapshot before the first strip
/// it changes until the FIFO matches the old one again (see [`Refiner::eval`]): a few
/// hundred triangles per move; most generated paths are dropped by their O(1) index
/// count before any replay.
pub(crate) fn refine(
    tris: &[[u32; 3]],
    graph: &DualGraph,
    walks: &Walks,
    cache_size: usize,
    lambda: f64,
    budget: u64,
    effort: Effort,
) -> (StripSet, u64) {
    let mut r = Refiner::new(tris, graph, walks, cache_size);
    let mut total = r.replay_all();
    // The index count of the strips once joined at their shared ends, kept up to date
    // by the moves taken (checked against the output in debug builds).
    let mut indices = r.s.enc.iter().map(|s| s.len() as i64 + 1).sum::<i64>()
        - 1
        - r.s.vertex_joins() as i64;
    let mut list = MoveList::default();
    let mut used: Vec<u32> = Vec::new();
    let mut joins: Vec<(Piece, Piece)> = Vec::new();
    let mut seen: Vec<[u32; 2 * FLIP_LINKS + 2]> = Vec::new();
    for pass in 1..=effort.passes {
        r.pass = pass;
        let mut changed = false;
        for x in 0..r.s.len() {
            if r.s.walks[x].is_empty() || (pass > 1 && !r.near_change(x, pass)) {
                continue;
            }
            let xs = x as u32;
            list.clear();
            simple_moves(&r.s, xs, &mut list);
            Tunnels {
                s: &r.s,
                out: &mut list,
                used: &mut used,
                joins: &mut joins,
            }
            .search(xs);
            let mut flips = Flips {
                s: &r.s,
                out: &mut list,
                cyc: [NONE; 2 * FLIP_LINKS + 2],
                links: effort.flip_links.min(FLIP_LINKS),
                seen: &mut seen,
            };
            flips.search(xs);
            flips.search_paths(xs);
            if let Some((i, dm)) = r.best(&list, total, budget, lambda) {
                if let Some((di, _)) = r.eval(&list.moves[i], &list.pool, true) {
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
    let mut out = r.s.strips();
    join_shared_ends(&mut out);
    debug_assert_eq!(out.restart_len() as i64, indices.max(0));
    (out, total)
}

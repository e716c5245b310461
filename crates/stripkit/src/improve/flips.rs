//! The flips of [`refine`]: alternating cycles through swaps and alternating
//! paths that touch some strip twice.
//!
//! [`refine`]: super::refine::refine

use super::moves::{Move, MoveList};
use super::piece::{ends, Piece, FLIP_LINKS, MOVE_SLOTS, NONE};
use super::slots::Slots;
use crate::topology::walks::{inner_swap, walk_swaps};
use crate::topology::NO_NEIGHBOR;

/// Generates the flips of [`refine`]: alternating cycles and paths in the dual graph,
/// whose edges alternate between links of the walks (used) and dual edges no walk
/// crosses (unused). Flipping one drops its used links and takes its unused ones; the
/// strips it touches are cut where links are dropped and the pieces reassembled along
/// the new links (no move when a closed loop of links appears), the new walks in the
/// slots of the strips they came from.
///
/// * **Cycles** through a link that takes part in a swap of the current strip (three
///   consecutive links around one vertex): every triangle keeps its link count, so as
///   many walks as before, rerouted (e.g. around a vertex whose fan the strip and its
///   neighbours cross in turn). They are rare in strips laid side by side (an unused
///   edge leads to the next strip, whose next unused edge leads further on), so they
///   give little but cost little.
/// * **Paths** from an end of the current strip (a link into a triangle, one of its
///   links dropped, a link from the triangle left with a free side, ..) ending after a
///   drop (as many walks) or with a link into a walk end (one walk fewer) that touch
///   some strip twice: Pósa's rotations (an end linked into its own strip's inside)
///   and tunnels that come back through a strip they cut. Those through distinct
///   strips are [`Tunnels`]. They give most of the gain of the flips.
///
/// The index change of a flip is its swap change plus three per walk gained or lost,
/// counted in O(1) per piece like [`Tunnels::cost`]: the swaps inside each piece from
/// `pre`, the windows of four triangles across each new link (three links around one
/// vertex) and each new walk's first three triangles walked; flips of no more indices
/// become moves and `Refiner::eval` scores them exactly.
///
/// [`refine`]: super::refine::refine
/// [`Tunnels`]: super::tunnels::Tunnels
/// [`Tunnels::cost`]: super::tunnels::Tunnels::cost
pub(super) struct Flips<'a> {
    pub(super) s: &'a Slots<'a>,
    pub(super) out: &'a mut MoveList,
    /// The cycle being grown: `cyc[2i]`, `cyc[2i + 1]` is a used link, `cyc[2i + 1]`,
    /// `cyc[2i + 2]` (cyclically) an unused dual edge.
    pub(super) cyc: [u32; 2 * FLIP_LINKS + 2],
    /// Most links a flip drops ([`Effort::flip_links`], at most [`FLIP_LINKS`]).
    ///
    /// [`Effort::flip_links`]: super::refine::Effort::flip_links
    pub(super) links: usize,
    /// The cycles found from the current strip, as sorted triangle lists (each cycle
    /// is found once per link of it that takes part in a swap; each path only once).
    pub(super) seen: &'a mut Vec<[u32; 2 * FLIP_LINKS + 2]>,
}

/// Most pieces a flip cuts its strips into: one per cut and one per strip.
pub(super) const FLIP_PIECES: usize = 2 * FLIP_LINKS + 2;

/// A flip being assembled, in fixed arrays: the slots it touches (sorted), their
/// strips cut into pieces, and the new walks as runs of pieces
/// (`order[bounds[i]..bounds[i + 1]]`).
struct Assembly {
    slots: [u32; MOVE_SLOTS],
    nslots: usize,
    segs: [Piece; FLIP_PIECES],
    ns: usize,
    order: [Piece; FLIP_PIECES],
    bounds: [usize; MOVE_SLOTS + 1],
    nw: usize,
}

impl Flips<'_> {
    /// Whether `a` and `b` are consecutive in a walk.
    #[inline]
    fn linked(&self, a: u32, b: u32) -> bool {
        let s = self.s.slot_of[a as usize];
        s != NONE
            && s == self.s.slot_of[b as usize]
            && self.s.pos[a as usize].abs_diff(self.s.pos[b as usize]) == 1
    }

    /// The triangles before and after `u` in its walk that are not in `cyc[..len]`
    /// (the links a flip may drop at `u`), NONE where there is none.
    fn walk_neighbours(&self, u: u32, len: usize) -> [u32; 2] {
        let w = &self.s.walks[self.s.slot_of[u as usize] as usize];
        let p = self.s.pos[u as usize] as usize;
        [p.wrapping_sub(1), p + 1].map(|q| match w.get(q) {
            Some(&v) if !self.cyc[..len].contains(&v) => v,
            _ => NONE,
        })
    }

    /// Swaps of the walk made of `pieces` in order, each in its direction: the swaps
    /// inside each piece (stored windows: a swap inside a walk does not depend on the
    /// direction of reading), the windows of four triangles across the joins and the
    /// first three triangles walked.
    fn new_swaps(&self, pieces: &[Piece]) -> i64 {
        let n: usize = pieces.iter().map(|p| p.len()).sum();
        if n < 3 {
            return 0;
        }
        let at = |mut i: usize| {
            for p in pieces {
                if i < p.len() {
                    return p.at(&self.s.walks, i);
                }
                i -= p.len();
            }
            unreachable!("index within the walk")
        };
        let tri3 = [at(0), at(1), at(2)];
        let mut s = i64::from(walk_swaps(self.s.tris, self.s.graph, &tri3));
        let mut prev_j = 0usize;
        let mut j = 0usize;
        for (k, p) in pieces.iter().enumerate() {
            s += i64::from(self.s.inner(*p,
                p.lo + 2,
                p.hi.saturating_sub(2),
            ));
            if k > 0 && n >= 4 {
                // Windows starting in max(prev_j, j - 3)..j that hold the join at j.
                let lo = prev_j.max(j.saturating_sub(3));
                let hi = (j - 1).min(n - 4);
                for st in lo..=hi {
                    if st > hi {
                        break;
                    }
                    let win = [at(st), at(st + 1), at(st + 2), at(st + 3)];
                    s += i64::from(inner_swap(self.s.tris, self.s.graph, &win));
                }
                prev_j = j;
            }
            j += p.len();
        }
        s
    }

    /// Flips from the links of strip `x` that take part in a swap.
    pub(super) fn search(&mut self, x: u32) {
        self.seen.clear();
        let walks = &self.s.walks;
        let w = &walks[x as usize];
        let n = w.len();
        if n < 4 {
            return;
        }
        // Swap at position q (2 <= q <= n - 2): the links q - 1, q, q + 1 around one
        // vertex (link j joins w[j - 1] and w[j]).
        let swap_at = |q: usize| {
            q >= 2 && q + 2 <= n && self.s.pre[w[q] as usize] != self.s.pre[w[q - 1] as usize]
        };
        for j in 0..n - 1 {
            // The link w[j], w[j + 1] takes part in the swaps at j, j + 1, j + 2.
            if !(swap_at(j) || swap_at(j + 1) || swap_at(j + 2)) {
                continue;
            }
            self.cyc[0] = w[j];
            self.cyc[1] = w[j + 1];
            self.grow(2);
        }
    }

    /// Extends the alternating path `cyc[..len]` (ending with a used link) by an unused
    /// dual edge and a used link, or closes it into a cycle.
    fn grow(&mut self, len: usize) {
        let t = self.cyc[len - 1];
        for u in self.s.graph.neighbors[t as usize] {
            if u == NO_NEIGHBOR || self.s.slot_of[u as usize] == NONE || self.linked(t, u) {
                continue;
            }
            if u == self.cyc[0] {
                if len >= 4 {
                    self.found(len);
                }
                continue;
            }
            if len / 2 >= self.links || self.cyc[..len].contains(&u) {
                continue;
            }
            for v in self.walk_neighbours(u, len).into_iter().filter(|&v| v != NONE) {
                self.cyc[len] = u;
                self.cyc[len + 1] = v;
                self.grow(len + 2);
            }
        }
    }

    /// The flip of the cycle `cyc[..len]`.
    fn found(&mut self, len: usize) {
        let mut key = [NONE; 2 * FLIP_LINKS + 2];
        key[..len].copy_from_slice(&self.cyc[..len]);
        key[..len].sort_unstable();
        if self.seen.contains(&key) {
            return;
        }
        self.seen.push(key);
        let k = len / 2;
        let mut drops = [(0u32, 0u32); FLIP_LINKS];
        let mut adds = [(0u32, 0u32); FLIP_LINKS + 1];
        for i in 0..k {
            drops[i] = (self.cyc[2 * i], self.cyc[2 * i + 1]);
            adds[i] = (self.cyc[2 * i + 1], self.cyc[(2 * i + 2) % len]);
        }
        self.assemble(&drops[..k], &adds[..k]);
    }

    /// Alternating paths from the ends of strip `x` that visit some strip twice (those
    /// through distinct strips are [`Tunnels`]): a link added from the end into a
    /// triangle, one of its links dropped, a link added from the triangle left with a
    /// free side, ..., ending after a drop or with a link into a walk end.
    ///
    /// [`Tunnels`]: super::tunnels::Tunnels
    pub(super) fn search_paths(&mut self, x: u32) {
        let walks = &self.s.walks;
        let w = &walks[x as usize];
        let (xe, nx) = ends(w);
        for &e in &xe[..nx] {
            self.cyc[0] = e;
            self.grow_path(1);
        }
    }

    /// Whether the events of the path `cyc[..len]` (its start, each drop, and its
    /// last triangle when `joined`) touch some strip twice.
    fn repeats(&self, len: usize, joined: bool) -> bool {
        let mut ev = [NONE; FLIP_LINKS + 2];
        let mut m = 0;
        ev[m] = self.s.slot_of[self.cyc[0] as usize];
        m += 1;
        let mut i = 2;
        while i < len {
            ev[m] = self.s.slot_of[self.cyc[i] as usize];
            m += 1;
            i += 2;
        }
        if joined {
            ev[m] = self.s.slot_of[self.cyc[len - 1] as usize];
            m += 1;
        }
        let ev = &mut ev[..m];
        ev.sort_unstable();
        ev.windows(2).any(|p| p[0] == p[1])
    }

    /// Extends the path `cyc[..len]` (odd length: its last triangle has a free side).
    fn grow_path(&mut self, len: usize) {
        let t = self.cyc[len - 1];
        for u in self.s.graph.neighbors[t as usize] {
            if u == NO_NEIGHBOR
                || self.s.slot_of[u as usize] == NONE
                || self.linked(t, u)
                || self.cyc[..len].contains(&u)
            {
                continue;
            }
            let w = &self.s.walks[self.s.slot_of[u as usize] as usize];
            let p = self.s.pos[u as usize] as usize;
            self.cyc[len] = u;
            if (p == 0 || p + 1 == w.len()) && len >= 3 && self.repeats(len + 1, true) {
                self.path(len + 1);
            }
            if len / 2 >= self.links {
                continue;
            }
            for v in self.walk_neighbours(u, len).into_iter().filter(|&v| v != NONE) {
                self.cyc[len + 1] = v;
                if self.repeats(len + 2, false) {
                    self.path(len + 2);
                }
                self.grow_path(len + 2);
            }
        }
    }

    /// The flip of the path `cyc[..len]`: links added at even steps, dropped at odd
    /// ones (it ends with a link into a walk end or after a drop).
    fn path(&mut self, len: usize) {
        let mut drops = [(0u32, 0u32); FLIP_LINKS];
        let mut adds = [(0u32, 0u32); FLIP_LINKS + 1];
        let (mut nd, mut na) = (0, 0);
        for i in 0..len - 1 {
            let pair = (self.cyc[i], self.cyc[i + 1]);
            if i % 2 == 0 {
                adds[na] = pair;
                na += 1;
            } else {
                drops[nd] = pair;
                nd += 1;
            }
        }
        self.assemble(&drops[..nd], &adds[..na]);
    }

    /// Drops the links `drops`, adds the dual edges `adds`, reassembles the strips
    /// touched into walks (none when a closed loop appears), counts the index change
    /// and, when it is at most 0, makes the move: each new walk in the slot of its
    /// longest piece where free, the others in the free slots, slots left over
    /// emptied.
    fn assemble(&mut self, drops: &[(u32, u32)], adds: &[(u32, u32)]) {
        let Some(mut asm) = self.cut(drops, adds) else {
            return;
        };
        if !self.relink(&mut asm, drops, adds) {
            return;
        }
        let mut di = 3 * (asm.nw as i64 - asm.nslots as i64);
        for &s in &asm.slots[..asm.nslots] {
            di -= self.s.swaps(s);
        }
        for i in 0..asm.nw {
            di += self.new_swaps(&asm.order[asm.bounds[i]..asm.bounds[i + 1]]);
        }
        if di > 0 {
            return;
        }
        self.place(&asm);
    }

    /// The strips that dropping `drops` and adding `adds` touch, cut at the dropped
    /// links into pieces (in stored order); None when they are too many for a move.
    fn cut(&self, drops: &[(u32, u32)], adds: &[(u32, u32)]) -> Option<Assembly> {
        let walks = &self.s.walks;
        // Touched slots.
        let mut slots = [0u32; MOVE_SLOTS];
        let mut nslots = 0;
        for &(a, b) in drops.iter().chain(adds.iter()) {
            for t in [a, b] {
                let s = self.s.slot_of[t as usize];
                if !slots[..nslots].contains(&s) {
                    if nslots == MOVE_SLOTS {
                        return None;
                    }
                    slots[nslots] = s;
                    nslots += 1;
                }
            }
        }
        slots[..nslots].sort_unstable();
        // Cuts (slot, position of the link's first triangle), sorted.
        let k = drops.len();
        let mut cuts = [(0u32, 0u32); FLIP_LINKS];
        for (i, &(a, b)) in drops.iter().enumerate() {
            cuts[i] = (
                self.s.slot_of[a as usize],
                self.s.pos[a as usize].min(self.s.pos[b as usize]),
            );
        }
        let cuts = &mut cuts[..k];
        cuts.sort_unstable();
        // Pieces: each touched strip cut at its cuts, in stored order.
        let mut segs = [Piece {
            slot: 0,
            lo: 0,
            hi: 0,
            rev: false,
        }; FLIP_PIECES];
        let mut ns = 0;
        for &s in &slots[..nslots] {
            let mut lo = 0;
            for &(cs, c) in cuts.iter() {
                if cs == s {
                    segs[ns] = Piece {
                        slot: s,
                        lo,
                        hi: c + 1,
                        rev: false,
                    };
                    ns += 1;
                    lo = c + 1;
                }
            }
            segs[ns] = Piece {
                slot: s,
                lo,
                hi: walks[s as usize].len() as u32,
                rev: false,
            };
            ns += 1;
        }
        Some(Assembly {
            slots,
            nslots,
            segs,
            ns,
            order: [segs[0]; FLIP_PIECES],
            bounds: [0; MOVE_SLOTS + 1],
            nw: 0,
        })
    }

    /// Joins the pieces of `a` along the links `adds` (each at the free end its
    /// triangle offers: at its dropped link, else at its walk end) into the new walks,
    /// each read in the direction of its longest piece's old strip; false when that
    /// is no flip (an added link at no free end, a closed loop, more walks than
    /// slots).
    fn relink(&self, asm: &mut Assembly, drops: &[(u32, u32)], adds: &[(u32, u32)]) -> bool {
        let walks = &self.s.walks;
        let (segs, ns, nslots) = (&asm.segs, asm.ns, asm.nslots);
        let (order, bounds) = (&mut asm.order, &mut asm.bounds);
        let mut nw = 0;
        let mut mate = [usize::MAX; 2 * FLIP_PIECES];
        // The free end (2 * piece + side, side 1 at hi) that triangle t offers to an
        // added link: at its dropped link, else at its walk end.
        let end_of = |t: u32, mate: &[usize]| -> usize {
            let (s, p) = (self.s.slot_of[t as usize], self.s.pos[t as usize]);
            let dropped = drops.iter().find_map(|&(a, b)| {
                if a == t {
                    Some(b)
                } else if b == t {
                    Some(a)
                } else {
                    None
                }
            });
            let seg =
                |f: &dyn Fn(&Piece) -> bool| (0..ns).find(|&g| segs[g].slot == s && f(&segs[g]));
            match dropped {
                Some(o) if self.s.pos[o as usize] == p + 1 => {
                    2 * seg(&|q| q.hi == p + 1).expect("a cut end") + 1
                }
                Some(_) => 2 * seg(&|q| q.lo == p).expect("a cut end"),
                None => {
                    let g = seg(&|q| q.lo <= p && p < q.hi).expect("a piece");
                    let len = walks[s as usize].len() as u32;
                    if p == 0 && segs[g].lo == 0 && mate[2 * g] == usize::MAX {
                        2 * g
                    } else if p + 1 == len && segs[g].hi == len {
                        2 * g + 1
                    } else {
                        // Not a free side: no flip.
                        usize::MAX
                    }
                }
            }
        };
        for &(a, b) in adds {
            let ea = end_of(a, &mate);
            let eb = end_of(b, &mate);
            if ea == usize::MAX
                || eb == usize::MAX
                || mate[ea] != usize::MAX
                || mate[eb] != usize::MAX
                || ea == eb
            {
                return false;
            }
            mate[ea] = eb;
            mate[eb] = ea;
        }
        // Reassembly from the free ends: walks as runs of pieces.
        let mut no = 0;
        let mut visited = [false; FLIP_PIECES];
        for g0 in 0..ns {
            for side0 in 0..2 {
                if visited[g0] || mate[2 * g0 + side0] != usize::MAX {
                    continue;
                }
                let (mut g, mut enter) = (g0, side0);
                loop {
                    if visited[g] {
                        return false;
                    }
                    visited[g] = true;
                    order[no] = Piece {
                        rev: enter == 1,
                        ..segs[g]
                    };
                    no += 1;
                    let exit = 1 - enter;
                    let m = mate[2 * g + exit];
                    if m == usize::MAX {
                        break;
                    }
                    g = m / 2;
                    enter = m % 2;
                }
                if nw == MOVE_SLOTS {
                    return false;
                }
                nw += 1;
                bounds[nw] = no;
            }
        }
        if no < ns {
            // A closed loop of links.
            return false;
        }
        if nw > nslots {
            return false;
        }
        // Each new walk read in the direction of its longest piece's old strip.
        for i in 0..nw {
            let run = &mut order[bounds[i]..bounds[i + 1]];
            let longest = run
                .iter()
                .max_by_key(|p| p.len())
                .copied()
                .expect("a piece");
            if longest.rev {
                run.reverse();
                for p in run.iter_mut() {
                    p.rev = !p.rev;
                }
            }
        }
        asm.nw = nw;
        true
    }

    /// Makes the move of the assembled flip: each new walk in the slot of its longest
    /// piece where free, the others in the free slots, slots left over emptied.
    fn place(&mut self, asm: &Assembly) {
        let walks = &self.s.walks;
        let (slots, nslots, order, bounds, nw) =
            (&asm.slots, asm.nslots, &asm.order, &asm.bounds, asm.nw);
        // Each new walk in the slot of its longest piece, where still free; the others
        // in the free slots in order; slots left over emptied.
        let mut home = [NONE; MOVE_SLOTS];
        let mut taken = [false; MOVE_SLOTS];
        let mut by_len = [0usize; MOVE_SLOTS];
        for (i, b) in by_len[..nw].iter_mut().enumerate() {
            *b = i;
        }
        let wlen = |i: usize| {
            order[bounds[i]..bounds[i + 1]]
                .iter()
                .map(|p| p.len())
                .sum::<usize>()
        };
        by_len[..nw].sort_unstable_by_key(|&i| std::cmp::Reverse(wlen(i)));
        for &i in &by_len[..nw] {
            let longest = order[bounds[i]..bounds[i + 1]]
                .iter()
                .max_by_key(|p| p.len())
                .copied()
                .expect("a piece");
            let h = slots[..nslots]
                .iter()
                .position(|&s| s == longest.slot)
                .expect("a slot");
            if !taken[h] {
                taken[h] = true;
                home[i] = h as u32;
            }
        }
        for hm in home[..nw].iter_mut().filter(|h| **h == NONE) {
            let h = taken[..nslots]
                .iter()
                .position(|&t| !t)
                .expect("a free slot");
            taken[h] = true;
            *hm = h as u32;
        }
        let mut list = [(0u32, 0u32, 0u32); MOVE_SLOTS];
        for i in 0..nw {
            let start = self.out.pool.len();
            for p in &order[bounds[i]..bounds[i + 1]] {
                p.extend(walks, &mut self.out.pool);
            }
            list[i] = (
                slots[home[i] as usize],
                start as u32,
                (self.out.pool.len() - start) as u32,
            );
        }
        let mut m = nw;
        for h in 0..nslots {
            if !taken[h] {
                list[m] = (slots[h], 0, 0);
                m += 1;
            }
        }
        self.out.moves.push(Move::new(&list[..m]));
    }
}

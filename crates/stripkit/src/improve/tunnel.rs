//! Fewer strips after the fact: *tunnelling* (after A. J. Stewart, "Tunneling for
//! triangle strips in continuous level-of-detail meshes", Graphics Interface 2001),
//! scored by the index count of docs/metrics.md.
//!
//! A set of strips is a set of disjoint paths in the dual graph: each triangle has at
//! most two *links* (the dual edges its strip runs through). A strip ends at a triangle
//! with fewer than two links. A *tunnel* is an alternating path that starts at an end,
//! crosses a dual edge that is not a link, then runs along a link, then across a
//! non-link, and so on, and stops at another end. Turning each of its non-links into a
//! link and each of its links into a non-link keeps every triangle at two links or
//! fewer and adds one link: one strip fewer, three indices fewer with a restart index,
//! provided no cycle appears.
//!
//! The relinking also moves *pivots* (the vertex shared by a triangle's two link
//! edges), and two linked inner triangles with the same pivot cost a swap (one repeated
//! index). Every candidate tunnel is therefore scored exactly on the triangles it
//! touches (swaps added minus three) and applied only when that is negative; the same
//! search also accepts a relinking that keeps the strip count but removes swaps (it
//! stops at an inner triangle and cuts one of its links). Searches are depth-first from
//! every strip end, bounded in length and in the relinkings each may score
//! ([`SEARCH_BUDGET`]: never reached at three cuts or fewer), so the pass is
//! O(triangles) with a small constant whatever the depth; the strip ends'
//! start-of-strip swap is settled by the encoder.
//!
//! **Why this is not the search of `tunnels.rs`.** The refinement's tunnels
//! (`super::tunnels`) look for the same alternating paths, but the two searches
//! differ in ways that decide which path is found, so one search with the scoring
//! passed in would change the strips of one or the other:
//!
//! * *Acceptance.* This pass applies the first improving path it meets and goes on
//!   from the changed links (first improvement, ends requeued after a change); the
//!   refinement collects every path of no more indices from one strip as moves on a
//!   fixed snapshot and takes the best after replaying each on the FIFO (best
//!   improvement, ties to the first generated). Here the visiting order decides the
//!   output; there it decides the tie-breaks.
//! * *Order at a cut.* Here a linked triangle's links are cut in the order of its link
//!   array, which earlier relinkings leave in either order; the refinement cuts after
//!   the crossing triangle first, then before it.
//! * *Pruning.* Here only triangles already on the path are excluded (a path may come
//!   back through a strip it cut, guarded by a cycle check); the refinement excludes
//!   whole strips already on the path (paths that come back are its flips, scored
//!   differently), and joins at a strip end only after two cuts (shorter joins are its
//!   simple moves).
//! * *Scoring.* Here swaps are counted from the pivots of the touched triangles on the
//!   live links; the refinement counts them from stored prefix sums over windows of
//!   the old walks, then exactly on the FIFO.
//!
//! What the two share is the walk encoding and its swap rule
//! ([`crate::topology::Walks`], [`crate::topology::walks::encode_path`]).

#[cfg(test)]
use crate::strip::StripSet;
use crate::topology::{DualGraph, Walks, NO_NEIGHBOR};

const NONE: u32 = u32::MAX;

/// Pivot not computed yet.
const UNKNOWN: u32 = u32::MAX - 1;

/// Options of [`tunnel`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TunnelOptions {
    /// Most links a tunnel may cut (its length is about twice that).
    pub max_cuts: usize,
    /// Most searches from one strip end: every end is searched once, and again (up to
    /// this many times) when a change next to it may have opened a new path.
    pub passes: usize,
    /// Index cost of one strip (3 with a restart index: two start indices and the
    /// restart); a swap costs 1.
    pub strip_cost: i32,
    /// Most work one search from a strip end may do before it gives up, counted in
    /// undo-log entries scored (see [`SEARCH_BUDGET`]).
    pub max_work: usize,
}

/// The default [`TunnelOptions::max_work`]: the most work a search of up to three cuts
/// can do, so that searches of three cuts or fewer (the greedy default is one) are
/// never cut short and give exactly the strips of an unbounded search.
///
/// Scoring a candidate reads the undo-log entries of its path: `4k + 2` for a close
/// after `k` cuts, `4k + 4` for a cut. A search at `k` of `m` cuts scores, for each of
/// the three neighbours of its triangle, either one close or, below `m` cuts, each of
/// the two links of the neighbour (a cut and a search at `k + 1`):
/// `W(m) <= 3 (4m + 2)`, `W(k) <= 6 (4k + 4 + W(k + 1))`, so `W(0)` is 132, 1,392
/// and 11,976 for one to three cuts. Unbounded, deeper searches branch up to six ways
/// per cut (cow: 0.3 s at 8 cuts, 2.2 s at 12; `--tunnel 32` did not finish); with the
/// budget every search is O(1), the pass O(strip ends), whatever the depth.
pub const SEARCH_BUDGET: usize = 11_976;

impl Default for TunnelOptions {
    fn default() -> Self {
        TunnelOptions {
            max_cuts: 4,
            passes: 3,
            strip_cost: 3,
            max_work: SEARCH_BUDGET,
        }
    }
}

struct State<'a> {
    tris: &'a [[u32; 3]],
    nbr: &'a [[u32; 3]],
    links: Vec<[u32; 2]>,
    /// Pivot of every triangle under `links` (NONE with fewer than two links), computed
    /// on first use (UNKNOWN until then).
    pivots: Vec<u32>,
    /// Triangles the walks cover.
    member: &'a [bool],
    /// Undo log of the tentative changes: (triangle, old links, old pivot).
    log: Vec<(u32, [u32; 2], u32)>,
    /// Triangles on the current search path.
    path: Vec<u32>,
    /// Triangles touched by the candidate (for scoring).
    touched: Vec<u32>,
    options: TunnelOptions,
    /// `stamp[t] == now` marks the triangles touched by the candidate being scored.
    stamp: Vec<u32>,
    now: u32,
    /// Scratch, beside `touched`: the index in `log` of each touched triangle's first
    /// entry (its links and pivot before the change).
    first: Vec<usize>,
    /// Work of the current search: undo-log entries scored (it stops past
    /// `options.max_work`).
    work: usize,
}

impl State<'_> {
    #[inline]
    fn deg(&self, t: u32) -> usize {
        let l = self.links[t as usize];
        usize::from(l[0] != NONE) + usize::from(l[1] != NONE)
    }

    #[inline]
    fn linked(&self, a: u32, b: u32) -> bool {
        self.links[a as usize].contains(&b)
    }

    fn set(&mut self, t: u32, l: [u32; 2]) {
        self.log
            .push((t, self.links[t as usize], self.pivots[t as usize]));
        self.links[t as usize] = l;
        self.pivots[t as usize] = UNKNOWN;
    }

    /// The pivot of `t` under the current links, cached.
    #[inline]
    fn piv(&mut self, t: u32) -> u32 {
        let p = self.pivots[t as usize];
        if p != UNKNOWN {
            return p;
        }
        let p = self.pivot_of(t, self.links[t as usize]);
        self.pivots[t as usize] = p;
        p
    }

    fn add_link(&mut self, a: u32, b: u32) {
        for (x, y) in [(a, b), (b, a)] {
            let mut l = self.links[x as usize];
            if l[0] == NONE {
                l[0] = y;
            } else {
                l[1] = y;
            }
            self.set(x, l);
        }
    }

    fn cut_link(&mut self, a: u32, b: u32) {
        for (x, y) in [(a, b), (b, a)] {
            let mut l = self.links[x as usize];
            if l[0] == y {
                l[0] = l[1];
            }
            l[1] = NONE;
            self.set(x, l);
        }
    }

    fn undo_to(&mut self, mark: usize) {
        while self.log.len() > mark {
            let (t, l, p) = self.log.pop().expect("log entry");
            self.links[t as usize] = l;
            self.pivots[t as usize] = p;
        }
    }

    /// The pivot of `t` with links `l`: the vertex its two link edges share (NONE with
    /// fewer links).
    #[inline]
    fn pivot_of(&self, t: u32, l: [u32; 2]) -> u32 {
        if l[1] == NONE {
            return NONE;
        }
        let n = &self.nbr[t as usize];
        let (Some(j0), Some(j1)) = (n.iter().position(|&x| x == l[0]), n.iter().position(|&x| x == l[1])) else {
            return NONE;
        };
        // Edge j runs tri[j] -> tri[j + 1]; two edges of a triangle share one corner.
        let tri = &self.tris[t as usize];
        if j1 == (j0 + 1) % 3 {
            tri[j1]
        } else if j0 == (j1 + 1) % 3 {
            tri[j0]
        } else {
            NONE
        }
    }

    /// Twice the swaps on the links at the touched triangles (linked pairs with equal
    /// pivots) under the current links: a pair with both ends touched is seen from
    /// both, one with one touched end is counted twice from it. Stops once the count
    /// reaches `bound` (it only grows).
    fn local_swaps2(&mut self, bound: i32) -> i32 {
        let mut s = 0;
        for i in 0..self.touched.len() {
            let t = self.touched[i];
            let pt = self.piv(t);
            if pt == NONE {
                continue;
            }
            for u in self.links[t as usize] {
                if u != NONE && self.piv(u) == pt {
                    s += if self.stamp[u as usize] == self.now { 1 } else { 2 };
                }
            }
            if s >= bound {
                break;
            }
        }
        s
    }

    /// The pivot of touched triangle `touched[i]` before the change, from its first
    /// log entry (computed there once when not known).
    #[inline]
    fn old_piv(&mut self, i: usize) -> u32 {
        let k = self.first[i];
        let (t, l, p) = self.log[k];
        if p != UNKNOWN {
            return p;
        }
        let p = self.pivot_of(t, l);
        self.log[k].2 = p;
        p
    }

    /// [`State::local_swaps2`] before the change: the touched triangles' links and
    /// pivots are read from their first log entries, the others are unchanged.
    fn old_swaps2(&mut self) -> i32 {
        let mut s = 0;
        for i in 0..self.touched.len() {
            let pt = self.old_piv(i);
            if pt == NONE {
                continue;
            }
            for u in self.log[self.first[i]].1 {
                if u == NONE {
                    continue;
                }
                if self.stamp[u as usize] == self.now {
                    let j = self.touched.iter().position(|&x| x == u).expect("touched");
                    if self.old_piv(j) == pt {
                        s += 1;
                    }
                } else if self.piv(u) == pt {
                    s += 2;
                }
            }
        }
        s
    }

    /// True when the strip through `a` (which has a link to `b`) closes into a cycle.
    ///
    /// It walks from `a` both ways at once, a step each in turn: a path shows an end
    /// after twice the steps to its nearer end (often a short strip just joined),
    /// a cycle shows itself where the two walks meet.
    fn on_cycle(&self, a: u32, b: u32) -> bool {
        let step = |prev: u32, cur: u32| {
            let l = self.links[cur as usize];
            if l[0] == prev {
                l[1]
            } else {
                l[0]
            }
        };
        // Forward from `a` through `b`, backward from `a` through its other link.
        let (mut p1, mut c1) = (a, b);
        let (mut p2, mut c2) = (b, a);
        for _ in 0..self.links.len() {
            let n1 = step(p1, c1);
            if n1 == NONE {
                return false;
            }
            (p1, c1) = (c1, n1);
            let n2 = step(p2, c2);
            if n2 == NONE {
                return false;
            }
            (p2, c2) = (c2, n2);
            // On a path the two walks stay on either side of `a` and never meet; on a
            // cycle they meet at a triangle or cross on a link.
            if c1 == c2 || c1 == p2 {
                return true;
            }
        }
        true
    }

    /// Whether the tentative change made since `mark` (links now in place) lowers the
    /// index count (swaps added minus `strips_saved` strips) without closing a cycle.
    ///
    /// The swaps before the change are read from the undo log (the first entry of each
    /// touched triangle holds its old links and pivot), so the links are not rolled
    /// back and forth; the swaps after it are counted only up to the point where the
    /// change can no longer pay.
    fn improves(&mut self, mark: usize, strips_saved: i32, new_links: &[(u32, u32)]) -> bool {
        self.work += self.log.len() - mark;
        self.touched.clear();
        self.first.clear();
        self.now = self.now.wrapping_add(1);
        if self.now == 0 {
            self.stamp.fill(0);
            self.now = 1;
        }
        for k in mark..self.log.len() {
            let t = self.log[k].0;
            if self.stamp[t as usize] != self.now {
                self.stamp[t as usize] = self.now;
                self.touched.push(t);
                self.first.push(k);
            }
        }
        // It pays when after - before - 2 * saved * strip_cost < 0 (all doubled).
        let bound = self.old_swaps2() + 2 * strips_saved * self.options.strip_cost;
        if bound <= 0 || self.local_swaps2(bound) >= bound {
            return false;
        }
        !new_links.iter().any(|&(a, b)| self.on_cycle(a, b))
    }

    /// Whether `t` has a swap with one of its links under the current links (equal
    /// pivots).
    fn has_swap(&mut self, t: u32) -> bool {
        let p = self.piv(t);
        p != NONE && self.links[t as usize].into_iter().any(|u| u != NONE && self.piv(u) == p)
    }

    /// Whether the search from `y` after the cut of link (x, y) and the new link
    /// (c, x), on a path that is `[c, x, y]`, would find a strip end to close with:
    /// read on the links before that change, which differ only at `c`, `x` and `y`.
    fn closes_from(&self, y: u32, c: u32, x: u32) -> bool {
        self.nbr[y as usize].iter().any(|&z| {
            z != NO_NEIGHBOR
                && z != y
                && z != c
                && z != x
                && self.member[z as usize]
                && !self.linked(y, z)
                && self.deg(z) < 2
        })
    }

    /// Depth-first search for an improving alternating path from `c`, which has a free
    /// link slot. Returns true when one was applied (links left changed). Gives up
    /// (false) once its work reaches `options.max_work`: each iteration below scores
    /// at most one candidate before it recurses.
    fn search(&mut self, c: u32, cuts: usize, new_links: &mut Vec<(u32, u32)>, mark: usize) -> bool {
        for j in 0..3 {
            if self.work >= self.options.max_work {
                return false;
            }
            let x = self.nbr[c as usize][j];
            if x == NO_NEIGHBOR
                || x == c
                || !self.member[x as usize]
                || self.linked(c, x)
                || self.path.contains(&x)
            {
                continue;
            }
            if self.deg(x) < 2 {
                // Close at an end: one strip fewer.
                let m = self.log.len();
                self.add_link(c, x);
                new_links.push((c, x));
                if self.improves(mark, 1, new_links) {
                    return true;
                }
                new_links.pop();
                self.undo_to(m);
                continue;
            }
            if cuts >= self.options.max_cuts {
                continue;
            }
            let lx = self.links[x as usize];
            // At one cut (the default) with the default budget: relinking (x, y) cannot
            // pay where neither `x` nor `y` has a swap to remove (no other links
            // change) and the search from `y` finds no strip end to close with. Such
            // a relinking is skipped, neither made nor scored, its work counted as
            // its scoring would (4 log entries): the walks are the full search's.
            let first_of_one = cuts == 0 && self.options.max_cuts == 1 && self.options.max_work >= SEARCH_BUDGET;
            let x_swaps = first_of_one && self.has_swap(x);
            for y in lx {
                if self.path.contains(&y) || self.work >= self.options.max_work {
                    continue;
                }
                if first_of_one && !x_swaps && !self.has_swap(y) && !self.closes_from(y, c, x) {
                    self.work += 4;
                    continue;
                }
                let m = self.log.len();
                self.cut_link(x, y);
                self.add_link(c, x);
                new_links.push((c, x));
                self.path.push(x);
                self.path.push(y);
                // Stopping here keeps the strip count: accept when swaps fall.
                if self.improves(mark, 0, new_links) {
                    return true;
                }
                if self.search(y, cuts + 1, new_links, mark) {
                    return true;
                }
                self.path.pop();
                self.path.pop();
                new_links.pop();
                self.undo_to(m);
            }
        }
        false
    }
}

/// [`tunnel_walks`] for walks held in a [`StripSet`] (each entry a sequence of triangle
/// ids of `tris`, each a `graph` neighbour of the one before, as this function took
/// them before [`Walks`] existed); returns the new walks the same way.
#[cfg(test)]
pub fn tunnel(tris: &[[u32; 3]], graph: &DualGraph, walks: &StripSet, options: &TunnelOptions) -> StripSet {
    tunnel_walks(tris, graph, &Walks::from_strip_set(walks), options).into_strip_set()
}

/// Reduces the index count of `walks` by tunnelling and returns the new walks (encode
/// them with [`Walks::encode`]). Every triangle of `walks` appears exactly once in the
/// result, and every walk is a path through `graph`, so encoding keeps every
/// triangle's winding.
pub fn tunnel_walks(tris: &[[u32; 3]], graph: &DualGraph, walks: &Walks, options: &TunnelOptions) -> Walks {
    tunnel_walks_peak(tris, graph, walks, options).0
}

/// [`tunnel_walks`], and the most work one search did (see [`SEARCH_BUDGET`]).
fn tunnel_walks_peak(tris: &[[u32; 3]], graph: &DualGraph, walks: &Walks, options: &TunnelOptions) -> (Walks, usize) {
    let n = tris.len();
    let mut links = vec![[NONE; 2]; n];
    let mut member = vec![false; n];
    for w in walks.iter() {
        for (k, &t) in w.iter().enumerate() {
            member[t as usize] = true;
            let mut l = [NONE; 2];
            let mut m = 0;
            if k > 0 {
                l[m] = w[k - 1];
                m += 1;
            }
            if k + 1 < w.len() {
                l[m] = w[k + 1];
            }
            links[t as usize] = l;
        }
    }
    let nbr = &graph.neighbors;
    let mut st = State {
        tris,
        nbr,
        pivots: vec![UNKNOWN; n],
        member: &member,
        links,
        log: Vec::new(),
        path: Vec::new(),
        touched: Vec::new(),
        options: *options,
        stamp: vec![0; n],
        now: 0,
        first: Vec::new(),
        work: 0,
    };
    // Every strip end is searched once; a change puts the ends it touched (and the
    // ends next to them) back on the work list, up to `passes` times each.
    let mut new_links = Vec::new();
    let mut queue: std::collections::VecDeque<u32> =
        (0..n as u32).filter(|&t| member[t as usize] && st.deg(t) < 2).collect();
    let mut visits = vec![0u8; n];
    let mut queued = vec![false; n];
    let mut peak = 0;
    for &t in &queue {
        queued[t as usize] = true;
    }
    while let Some(t) = queue.pop_front() {
        queued[t as usize] = false;
        if st.deg(t) >= 2 || visits[t as usize] as usize >= options.passes {
            continue;
        }
        visits[t as usize] += 1;
        st.log.clear();
        st.path.clear();
        st.work = 0;
        st.path.push(t);
        new_links.clear();
        let found = st.search(t, 0, &mut new_links, 0);
        peak = peak.max(st.work);
        if !found {
            st.undo_to(0);
            continue;
        }
        // Applied: requeue the touched triangles that are ends now, and their
        // neighbours that are ends.
        for k in 0..st.log.len() {
            let x = st.log[k].0;
            for y in std::iter::once(x).chain(nbr[x as usize].iter().copied()) {
                if y != NO_NEIGHBOR && member[y as usize] && !queued[y as usize] && st.deg(y) < 2 {
                    queued[y as usize] = true;
                    queue.push_back(y);
                }
            }
        }
    }
    // Read the paths from their ends, in the order the input walks reach the ends
    // (keeps most of the producer's locality, e.g. for the vertex cache).
    let links = st.links;
    let mut out = Walks::with_capacity(walks.triangles().len());
    let mut done = vec![false; n];
    for &s0 in walks.triangles() {
        if done[s0 as usize] || links[s0 as usize][1] != NONE {
            continue;
        }
        let (mut prev, mut cur) = (NONE, s0);
        loop {
            done[cur as usize] = true;
            out.push_triangle(cur);
            let l = links[cur as usize];
            let next = if l[0] == prev { l[1] } else { l[0] };
            if next == NONE {
                break;
            }
            prev = cur;
            cur = next;
        }
        out.end_walk();
    }
    if out.triangles().len() != walks.triangles().len() {
        // A cycle would lose its triangles here; the searches never close one, but
        // should that ever fail, the input walks are still a correct answer.
        debug_assert!(false, "tunnelling lost or added triangles");
        return (walks.clone(), peak);
    }
    (out, peak)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Checks that `out` covers exactly `expect` (as a set) with valid dual walks.
    fn check_walks(graph: &DualGraph, out: &Walks, expect: &[u32]) {
        let mut got: Vec<u32> = out.triangles().to_vec();
        got.sort_unstable();
        let mut want = expect.to_vec();
        want.sort_unstable();
        assert_eq!(got, want, "triangles lost or repeated");
        for i in 0..out.len() {
            for p in out.walk(i).windows(2) {
                assert!(graph.neighbors[p[0] as usize].contains(&p[1]), "not a walk: {p:?}");
            }
        }
    }

    fn grid_tris(w: u32, h: u32) -> Vec<[u32; 3]> {
        crate::gen::grid(w, h).triangulate().tris
    }

    #[test]
    fn single_triangles_are_tunnelled_into_long_walks() {
        let tris = grid_tris(8, 6);
        let graph = DualGraph::from_triangles(&tris, 9 * 7);
        let mut walks = Walks::new();
        for t in 0..tris.len() as u32 {
            walks.push(&[t]);
        }
        let out = tunnel_walks(&tris, &graph, &walks, &TunnelOptions::default());
        check_walks(&graph, &out, &(0..tris.len() as u32).collect::<Vec<_>>());
        // 96 single triangles: adjacent ends join directly, so very few walks remain.
        assert!(out.len() <= 12, "{} walks", out.len());
    }

    /// A grid of quads each split along a diagonal picked by a small LCG (valences 3
    /// to 9, many swaps), with the walks of the plain greedy stripifier (no tunnels).
    fn random_diagonals(w: u32, h: u32, seed: u64) -> (Vec<[u32; 3]>, DualGraph, Walks) {
        let (tris, vc) = crate::test_support::random_diagonals(w, h, seed);
        let graph = DualGraph::from_triangles(&tris, vc);
        let plain = crate::stripify::greedy::GreedyOptions { tunnel_cuts: None, ..Default::default() };
        let walks = crate::stripify::greedy::walks_with_graph(&tris, &graph, &plain);
        (tris, graph, walks)
    }

    #[test]
    fn skipping_relinkings_that_cannot_pay_keeps_the_walks_and_the_work() {
        // At one cut with the default budget a relinking that removes no swap and opens
        // no strip end to close with is skipped unscored; a budget below the default
        // (yet above the 132 a one-cut search can do) turns the skip off. Both must
        // give the same walks and count the same work.
        for seed in [1, 7, 12345] {
            let (tris, graph, walks) = random_diagonals(24, 16, seed);
            let all: Vec<u32> = (0..tris.len() as u32).collect();
            for strip_cost in [3, 1 << 16] {
                let skip = TunnelOptions { max_cuts: 1, strip_cost, ..TunnelOptions::default() };
                let full = TunnelOptions { max_work: 1_000, ..skip };
                let (a, peak_a) = tunnel_walks_peak(&tris, &graph, &walks, &skip);
                let (b, peak_b) = tunnel_walks_peak(&tris, &graph, &walks, &full);
                assert_eq!(a, b, "seed {seed}, strip cost {strip_cost}");
                assert_eq!(peak_a, peak_b, "seed {seed}, strip cost {strip_cost}");
                let indices = |w: &Walks| w.encode(&tris, &graph).restart_len();
                assert!(indices(&a) < indices(&walks), "seed {seed}: {} from {}", indices(&a), indices(&walks));
                check_walks(&graph, &a, &all);
            }
        }
    }

    #[test]
    fn the_work_budget_never_cuts_searches_of_three_cuts_or_fewer() {
        // SEARCH_BUDGET is the worst-case work of a search of three cuts: up to three
        // cuts the bounded search gives exactly the walks of the unbounded one; deeper,
        // the budget applies and the walks stay valid.
        for seed in [1, 7, 12345] {
            let (tris, graph, walks) = random_diagonals(24, 16, seed);
            let all: Vec<u32> = (0..tris.len() as u32).collect();
            // The worst-case work of one search of m cuts, by the recurrence of
            // SEARCH_BUDGET.
            let worst = |m: usize| {
                let mut w = 3 * (4 * m + 2);
                for k in (0..m).rev() {
                    w = (3 * (4 * k + 2)).max(6 * (4 * k + 4 + w));
                }
                w
            };
            assert_eq!([worst(1), worst(2), worst(3)], [132, 1392, SEARCH_BUDGET]);
            for max_cuts in 1..=3 {
                let bounded = TunnelOptions { max_cuts, ..TunnelOptions::default() };
                let unbounded = TunnelOptions { max_work: usize::MAX, ..bounded };
                let (a, _) = tunnel_walks_peak(&tris, &graph, &walks, &bounded);
                let (b, peak) = tunnel_walks_peak(&tris, &graph, &walks, &unbounded);
                assert!(peak <= worst(max_cuts), "seed {seed}, {max_cuts} cuts: {peak}");
                assert_eq!(a, b, "seed {seed}, {max_cuts} cuts");
                check_walks(&graph, &a, &all);
            }
            for max_cuts in [8, 32] {
                let o = TunnelOptions { max_cuts, ..TunnelOptions::default() };
                let (out, peak) = tunnel_walks_peak(&tris, &graph, &walks, &o);
                // A search stops at the first check past the budget: at most one more
                // candidate's log (4 * max_cuts + 4 entries) past it.
                assert!(peak < SEARCH_BUDGET + 4 * max_cuts + 4, "seed {seed}, {max_cuts} cuts: {peak}");
                check_walks(&graph, &out, &all);
            }
            // Deep searches do reach the budget (else it would bound nothing here).
            let deep = TunnelOptions { max_cuts: 32, ..TunnelOptions::default() };
            let (_, peak) = tunnel_walks_peak(&tris, &graph, &walks, &deep);
            assert!(peak >= SEARCH_BUDGET, "seed {seed}: {peak}");
        }
    }

    #[test]
    fn a_closed_ring_is_never_closed_into_a_cycle() {
        // A band of 2n triangles around a cylinder: one walk covers it, and its two
        // ends are neighbours. Joining them would make a cycle.
        let n = 6u32;
        let mut tris = Vec::new();
        for i in 0..n {
            let (a, b) = (i, (i + 1) % n);
            let (c, d) = (n + i, n + (i + 1) % n);
            tris.push([a, c, b]);
            tris.push([b, c, d]);
        }
        let graph = DualGraph::from_triangles(&tris, 2 * n as usize);
        let mut walks = Walks::new();
        walks.push(&(0..2 * n).collect::<Vec<u32>>());
        let out = tunnel_walks(&tris, &graph, &walks, &TunnelOptions::default());
        check_walks(&graph, &out, &(0..2 * n).collect::<Vec<_>>());
        assert_eq!(out.len(), 1);
        // Cut into pieces, it comes back to one walk, still not a cycle.
        let mut walks = Walks::new();
        walks.push(&(0..5).collect::<Vec<u32>>());
        walks.push(&(5..9).collect::<Vec<u32>>());
        walks.push(&(9..2 * n).collect::<Vec<u32>>());
        let out = tunnel_walks(&tris, &graph, &walks, &TunnelOptions::default());
        check_walks(&graph, &out, &(0..2 * n).collect::<Vec<_>>());
        assert_eq!(out.len(), 1);
    }

    #[test]
    fn triangles_outside_the_walks_are_left_alone() {
        let tris = grid_tris(6, 4);
        let graph = DualGraph::from_triangles(&tris, 7 * 5);
        let mut walks = Walks::new();
        let mut covered = Vec::new();
        for t in (0..tris.len() as u32).filter(|t| t % 5 != 0) {
            walks.push(&[t]);
            covered.push(t);
        }
        let out = tunnel_walks(&tris, &graph, &walks, &TunnelOptions::default());
        check_walks(&graph, &out, &covered);
        assert!(out.len() < walks.len());
    }

    #[test]
    fn empty_input_and_a_second_pass() {
        let tris = grid_tris(5, 5);
        let graph = DualGraph::from_triangles(&tris, 36);
        let out = tunnel_walks(&tris, &graph, &Walks::new(), &TunnelOptions::default());
        assert!(out.is_empty());
        let mut walks = Walks::new();
        for t in 0..tris.len() as u32 {
            walks.push(&[t]);
        }
        let once = tunnel_walks(&tris, &graph, &walks, &TunnelOptions::default());
        let twice = tunnel_walks(&tris, &graph, &once, &TunnelOptions::default());
        let all: Vec<u32> = (0..tris.len() as u32).collect();
        check_walks(&graph, &once, &all);
        check_walks(&graph, &twice, &all);
        assert!(twice.len() <= once.len());
    }
}

#[cfg(test)]
mod strip_set_tests {
    use super::*;

    #[test]
    fn walks_in_a_strip_set_give_the_same_walks() {
        let tris = crate::gen::grid(6, 5).triangulate().tris;
        let graph = DualGraph::from_triangles(&tris, 7 * 6);
        let mut set = StripSet::new();
        let mut walks = Walks::new();
        for t in 0..tris.len() as u32 {
            set.push(&[t]);
            walks.push(&[t]);
        }
        let o = TunnelOptions::default();
        let out = tunnel(&tris, &graph, &set, &o);
        assert_eq!(out, tunnel_walks(&tris, &graph, &walks, &o).into_strip_set());
        assert_eq!(tunnel(&tris, &graph, &StripSet::default(), &o), StripSet::new());
    }
}

//! Cache-aware strips: a vertex-cache-optimised triangle order whose consecutive
//! triangles are, as often as the cache allows, strip neighbours.
//!
//! One pass builds the order and the strips together, in the manner of Forsyth's
//! linear-speed vertex cache optimisation, while it simulates the FIFO cache of
//! METRICS.md (`cache_size` entries, a hit does not reorder, a miss evicts the
//! oldest), so every decision sees the cache the figures will measure:
//!
//! * **Scores.** A vertex scores by its place in the FIFO (a cached vertex scores
//!   more the newer it is; the newest three score a flat value, as in Forsyth) plus a
//!   bonus that falls with the number of its triangles still free (finishing a vertex
//!   frees its slot for good). A free triangle scores the sum of its vertices.
//! * **Coupling.** The triangle that continues the current strip across its last
//!   edge (no extra index) gets `continue_bonus` on top, the one across the other edge
//!   (one repeated index, a "swap") `swap_bonus`; any other triangle starts a new
//!   strip (three more indices with a restart index) and pays `start_penalty` per
//!   free neighbour it has, so new strips start in corners of the free region
//!   rather than cutting it into islands. Large bonuses give long strips (few
//!   indices), small ones give the order a pure cache optimiser would pick.
//! * **Choosing.** The next triangle is the best-scored free triangle around the
//!   cached vertices; when none is left, a stack of recently used vertices (as in
//!   Tipsify) gives one near the last strips, and only then a scan of the input.
//!   The input order matters only there and in ties, so shuffled inputs give about
//!   the same figures.
//! * **Strips.** A strip's first triangle may still be rotated, so its second
//!   triangle may lie across any of its edges; after that, steps follow the
//!   [`DualGraph`] only (which keeps the winding).
//!
//! Cost: O(T + V) time and memory (each step looks at the free triangles around the
//! `cache_size` cached vertices), flat arrays, nothing allocated per step.

use crate::strip::{is_degenerate, StripSet};
use crate::topology::{DualGraph, NO_NEIGHBOR};

/// Settings of the cache-aware stripifier.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CacheOptions {
    /// Entries of the FIFO vertex cache the order is tuned for (at least 3).
    pub cache_size: u32,
    /// Score added to the triangle that continues the current strip without a swap.
    /// Larger: longer strips (fewer indices), more cache misses.
    pub continue_bonus: f32,
    /// Score added to the triangle that continues the current strip with a swap (one
    /// repeated index).
    pub swap_bonus: f32,
    /// Allow swaps at all.
    pub swaps: bool,
    /// Score taken off a triangle that would start a new strip, per free neighbour.
    pub start_penalty: f32,
    /// The continuation bonuses fall linearly to zero once the current strip has
    /// missed the cache this many times (0: they never fall): a strip that has left
    /// the cached side of the previous strip ends.
    pub strip_misses: u32,
    /// Weight of the "few free triangles left" vertex bonus (`weight / sqrt(free)`).
    pub valence_weight: f32,
    /// A cached vertex scores `1 + age_tilt * age / cache_size` (age 1 = newest push):
    /// negative prefers the newest vertices, positive the ones about to be evicted.
    /// Small values mostly break ties, so the input order does not.
    pub age_tilt: f32,
    /// Candidates are the free triangles around the newest `scan_entries` cache
    /// entries (at most `cache_size`): fewer is faster and keeps the order closer to
    /// the newest vertices.
    pub scan_entries: u32,
}

impl CacheOptions {
    /// The `cache` mode: about the cache misses of a pure vertex-cache order, with
    /// strips as long as that order allows.
    pub fn cache(cache_size: u32) -> Self {
        let cache_size = cache_size.max(3);
        CacheOptions {
            cache_size,
            continue_bonus: 1.5,
            swap_bonus: 0.3,
            swaps: true,
            start_penalty: 0.0,
            strip_misses: (cache_size * 3 / 8).max(1),
            valence_weight: 1.0,
            age_tilt: -0.03,
            scan_entries: cache_size / 2,
        }
    }

    /// The `balanced` mode: longer strips (fewer indices) for a few more misses.
    pub fn balanced(cache_size: u32) -> Self {
        let cache_size = cache_size.max(3);
        CacheOptions {
            continue_bonus: 2.0,
            swap_bonus: 0.5,
            start_penalty: 0.2,
            strip_misses: cache_size * 5 / 4,
            age_tilt: 0.2,
            scan_entries: cache_size * 3 / 4,
            ..CacheOptions::cache(cache_size)
        }
    }
}

impl Default for CacheOptions {
    fn default() -> Self {
        CacheOptions::cache(16)
    }
}

/// Strips for `tris` (indices below `vertex_count`), ordered for a FIFO vertex cache.
/// Degenerate triangles are dropped; every other triangle appears exactly once with
/// its winding. Finds the [`DualGraph`] neighbours itself, from the lists of triangles
/// around each vertex it keeps anyway; see [`stripify_with_graph`].
pub fn stripify(tris: &[[u32; 3]], vertex_count: usize, options: &CacheOptions) -> StripSet {
    let mut s = State::new(tris, vertex_count, None, options);
    s.run();
    s.out
}

/// As [`stripify`], with the dual graph of `tris` already built.
pub fn stripify_with_graph(
    tris: &[[u32; 3]],
    vertex_count: usize,
    graph: &DualGraph,
    options: &CacheOptions,
) -> StripSet {
    let mut s = State::new(tris, vertex_count, Some(graph), options);
    s.run();
    s.out
}

const NEVER: u32 = u32::MAX;
/// Valence bonus table length; vertices with more free triangles share the last entry.
const VALENCE_TABLE: usize = 32;


/// A triangle's score is `base + tilt * (cached * time - stamps)`: the flat and
/// valence parts of its vertices, plus the age part of its cached vertices (the sum
/// of their ages is `cached * time - stamps`), so it changes only when one of its
/// vertices enters or leaves the cache or loses a triangle.
#[derive(Clone, Copy, Default)]
struct TriScore {
    base: f32,
    cached: u32,
    /// Sum of the push stamps of the cached vertices, wrapping: `cached * time -
    /// stamps` (wrapping too) is the sum of their ages, small and exact.
    stamps: u32,
}

/// The [`DualGraph`] neighbours from the lists of triangles around each vertex: the
/// triangle across edge `(a, b)` of `t` is the other triangle around `a` that holds
/// `b`, when there is exactly one and it runs `b -> a` (a manifold, consistently
/// oriented edge), as [`DualGraph::from_triangles`] defines it.
fn dual_neighbors(tris: &[[u32; 3]], degenerate: &[bool], vt_start: &[u32], vt_tris: &[u32]) -> Vec<[u32; 3]> {
    let mut nb = vec![[NO_NEIGHBOR; 3]; tris.len()];
    for (t, tri) in tris.iter().enumerate() {
        if degenerate[t] {
            continue;
        }
        for j in 0..3 {
            let (a, b) = (tri[j], tri[(j + 1) % 3]);
            let around = &vt_tris[vt_start[a as usize] as usize..vt_start[a as usize + 1] as usize];
            let mut count = 0;
            let mut partner = NO_NEIGHBOR;
            for &u in around {
                let ut = tris[u as usize];
                for k in 0..3 {
                    if ut[k] == b {
                        count += 1;
                        if ut[(k + 1) % 3] == a {
                            partner = u;
                        }
                    }
                }
            }
            if count == 2 {
                nb[t][j] = partner;
            }
        }
    }
    nb
}

struct State<'a> {
    tris: &'a [[u32; 3]],
    /// [`DualGraph`] neighbours of each triangle.
    neighbors: Vec<[u32; 3]>,
    o: CacheOptions,
    cache_size: u32,
    /// Score of a cached vertex per push of age (`age_tilt / cache_size`).
    tilt: f32,
    /// Score of a vertex by its number of free triangles.
    valence_score: [f32; VALENCE_TABLE],
    /// Triangle already in a strip (degenerate ones count as done from the start).
    done: Vec<bool>,
    /// Score parts of each free triangle, kept up to date as its vertices change.
    score: Vec<TriScore>,
    /// Free neighbours of each triangle.
    free_nb: Vec<u8>,
    /// Free triangles around each vertex: `vt_tris[vt_start[v]..vt_start[v] + vt_live[v]]`.
    vt_start: Vec<u32>,
    vt_live: Vec<u32>,
    vt_tris: Vec<u32>,
    /// Position of corner `3 * t + c` in `vt_tris`, for O(1) removal.
    corner_pos: Vec<u32>,
    /// FIFO cache: push time of each vertex (NEVER if never pushed), the ring of the
    /// last `cache_size` pushes and the push count.
    stamp: Vec<u32>,
    ring: Vec<u32>,
    time: u32,
    /// Vertices of emitted triangles, most recent last (Tipsify's dead-end stack).
    dead_end: Vec<u32>,
    scan: usize,
    /// The strip being built and the triangle at its end.
    strip: Vec<u32>,
    cur: u32,
    strip_misses: u32,
    out: StripSet,
}

impl<'a> State<'a> {
    fn new(tris: &'a [[u32; 3]], vertex_count: usize, graph: Option<&DualGraph>, o: &CacheOptions) -> Self {
        let n = tris.len();
        let mut done = vec![false; n];
        let mut vt_start = vec![0u32; vertex_count + 1];
        for (t, tri) in tris.iter().enumerate() {
            if is_degenerate(tri) {
                done[t] = true;
                continue;
            }
            for &v in tri {
                vt_start[v as usize + 1] += 1;
            }
        }
        for v in 0..vertex_count {
            vt_start[v + 1] += vt_start[v];
        }
        let mut vt_live = vec![0u32; vertex_count];
        let mut vt_tris = vec![0u32; vt_start[vertex_count] as usize];
        let mut corner_pos = vec![0u32; 3 * n];
        for (t, tri) in tris.iter().enumerate() {
            if done[t] {
                continue;
            }
            for (c, &v) in tri.iter().enumerate() {
                let p = vt_start[v as usize] + vt_live[v as usize];
                vt_tris[p as usize] = t as u32;
                corner_pos[3 * t + c] = p;
                vt_live[v as usize] += 1;
            }
        }
        let cache_size = o.cache_size.max(3);
        let mut valence_score = [0.0f32; VALENCE_TABLE];
        for (k, s) in valence_score.iter_mut().enumerate().skip(1) {
            *s = o.valence_weight / (k as f32).sqrt();
        }
        let mut state = State {
            tris,
            neighbors: match graph {
                Some(g) => g.neighbors.clone(),
                None => dual_neighbors(tris, &done, &vt_start, &vt_tris),
            },
            o: *o,
            cache_size,
            tilt: o.age_tilt / cache_size as f32,
            valence_score,
            score: vec![TriScore::default(); n],
            free_nb: vec![0; n],
            done,
            vt_start,
            vt_live,
            vt_tris,
            corner_pos,
            stamp: vec![NEVER; vertex_count],
            ring: vec![NEVER; cache_size as usize],
            time: 0,
            dead_end: Vec::with_capacity(3 * n),
            scan: 0,
            strip: Vec::with_capacity(64),
            cur: NO_NEIGHBOR,
            strip_misses: 0,
            out: StripSet {
                indices: Vec::with_capacity(n + n / 2),
                offsets: {
                    let mut o = Vec::with_capacity(n / 4 + 2);
                    o.push(0);
                    o
                },
            },
        };
        for t in 0..n {
            if !state.done[t] {
                state.free_nb[t] = state.neighbors[t].iter().filter(|&&m| state.free(m)).count() as u8;
                state.rescore(t as u32);
            }
        }
        state
    }

    /// Recomputes the score parts of free triangle `t` from its vertices.
    #[inline]
    fn rescore(&mut self, t: u32) {
        let mut sc = TriScore::default();
        for v in self.tris[t as usize] {
            let live = self.vt_live[v as usize] as usize;
            sc.base += self.valence_score[live.min(VALENCE_TABLE - 1)];
            if self.age(v) != 0 {
                sc.base += 1.0;
                sc.cached += 1;
                sc.stamps = sc.stamps.wrapping_add(self.stamp[v as usize]);
            }
        }
        self.score[t as usize] = sc;
    }

    /// Changes the score parts of the free triangles around `v` when `v` changes.
    #[inline]
    fn shift(&mut self, v: u32, base: f32, cached: u32, stamps: u32) {
        let start = self.vt_start[v as usize] as usize;
        for idx in start..start + self.vt_live[v as usize] as usize {
            let sc = &mut self.score[self.vt_tris[idx] as usize];
            sc.base += base;
            sc.cached = sc.cached.wrapping_add(cached);
            sc.stamps = sc.stamps.wrapping_add(stamps);
        }
    }

    /// Current score of free triangle `t` (without strip bonuses).
    #[inline]
    fn score_of(&self, t: u32) -> f32 {
        let sc = self.score[t as usize];
        sc.base + self.tilt * sc.cached.wrapping_mul(self.time).wrapping_sub(sc.stamps) as f32
    }

    /// Age of `v` in the FIFO (1 = newest), or 0 when not cached.
    #[inline]
    fn age(&self, v: u32) -> u32 {
        let s = self.stamp[v as usize];
        if s == NEVER {
            return 0;
        }
        let a = self.time - s;
        if a <= self.cache_size {
            a
        } else {
            0
        }
    }

    /// Feeds one vertex to the FIFO.
    #[inline]
    fn touch(&mut self, v: u32) {
        if self.age(v) != 0 {
            return;
        }
        self.strip_misses += 1;
        let slot = (self.time % self.cache_size) as usize;
        let old = self.ring[slot];
        if old != NEVER && self.time >= self.cache_size {
            // `old` leaves the cache.
            self.shift(old, -1.0, u32::MAX, self.stamp[old as usize].wrapping_neg());
        }
        self.stamp[v as usize] = self.time;
        self.ring[slot] = v;
        self.shift(v, 1.0, 1, self.time);
        self.time = self.time.wrapping_add(1);
    }

    fn free(&self, t: u32) -> bool {
        t != NO_NEIGHBOR && !self.done[t as usize]
    }

    fn free_degree(&self, t: u32) -> u32 {
        self.free_nb[t as usize] as u32
    }

    /// Neighbour of `t` across the undirected edge `{a, b}` (or NO_NEIGHBOR).
    fn across(&self, t: u32, a: u32, b: u32) -> u32 {
        let tri = self.tris[t as usize];
        for j in 0..3 {
            let (x, y) = (tri[j], tri[(j + 1) % 3]);
            if (x == a && y == b) || (x == b && y == a) {
                return self.neighbors[t as usize][j];
            }
        }
        NO_NEIGHBOR
    }

    fn third(&self, t: u32, a: u32, b: u32) -> u32 {
        let tri = self.tris[t as usize];
        tri.into_iter().find(|&v| v != a && v != b).unwrap_or(tri[0])
    }

    /// Marks `t` emitted: off its vertices' free lists, onto the dead-end stack.
    fn take(&mut self, t: u32) {
        self.done[t as usize] = true;
        for m in self.neighbors[t as usize] {
            if self.free(m) {
                self.free_nb[m as usize] -= 1;
            }
        }
        let tri = self.tris[t as usize];
        for (c, &v) in tri.iter().enumerate() {
            let v = v as usize;
            let p = self.corner_pos[3 * t as usize + c];
            let last = self.vt_start[v] + self.vt_live[v] - 1;
            let moved = self.vt_tris[last as usize];
            self.vt_tris[p as usize] = moved;
            let mt = self.tris[moved as usize];
            let mc = (0..3).find(|&k| mt[k] as usize == v).unwrap_or(0);
            self.corner_pos[3 * moved as usize + mc] = p;
            let live = self.vt_live[v] as usize;
            self.vt_live[v] -= 1;
            self.dead_end.push(v as u32);
            let delta = self.valence_score[(live - 1).min(VALENCE_TABLE - 1)]
                - self.valence_score[live.min(VALENCE_TABLE - 1)];
            if delta != 0.0 {
                self.shift(v as u32, delta, 0, 0);
            }
        }
    }

    fn finish_strip(&mut self) {
        if !self.strip.is_empty() {
            self.out.indices.extend_from_slice(&self.strip);
            self.out.offsets.push(self.out.indices.len() as u32);
            self.strip.clear();
        }
        self.cur = NO_NEIGHBOR;
    }

    fn run(&mut self) {
        loop {
            // Continuations of the current strip: across any edge while it has one
            // triangle (it can still be rotated), else across its last edge (natural)
            // or, with a swap, across the edge before.
            let (mut nat, mut swp, mut first) = (NO_NEIGHBOR, NO_NEIGHBOR, [NO_NEIGHBOR; 3]);
            if self.cur != NO_NEIGHBOR {
                let len = self.strip.len();
                if len == 3 {
                    first = self.neighbors[self.cur as usize];
                } else {
                    let (p, u, w) = (self.strip[len - 3], self.strip[len - 2], self.strip[len - 1]);
                    nat = self.across(self.cur, u, w);
                    if self.o.swaps {
                        swp = self.across(self.cur, p, w);
                    }
                }
            }
            let f = if self.o.strip_misses > 0 {
                (1.0 - self.strip_misses as f32 / self.o.strip_misses as f32).max(0.0)
            } else {
                1.0
            };
            let (cb, sb) = (self.o.continue_bonus * f, self.o.swap_bonus * f);
            let mut best = NO_NEIGHBOR;
            let mut best_score = f32::NEG_INFINITY;
            for i in 0..self.cache_size.min(self.time).min(self.o.scan_entries.max(1)) {
                let v = self.ring[((self.time - 1 - i) % self.cache_size) as usize];
                let start = self.vt_start[v as usize] as usize;
                let live = self.vt_live[v as usize] as usize;
                for idx in start..start + live {
                    let t = self.vt_tris[idx];
                    let mut s = self.score_of(t);
                    if t == nat || first.contains(&t) {
                        s += cb;
                    } else if t == swp {
                        s += sb;
                    } else if self.o.start_penalty != 0.0 {
                        s -= self.o.start_penalty * self.free_degree(t) as f32;
                    }
                    if s > best_score {
                        best_score = s;
                        best = t;
                    }
                }
            }
            if best == NO_NEIGHBOR {
                best = match self.fallback() {
                    Some(t) => t,
                    None => break,
                };
            }
            self.step(best, nat, swp, first);
        }
        self.finish_strip();
    }

    /// A free triangle when no cached vertex has one: around the most recently used
    /// vertex that still has free triangles, else the next free one in input order.
    fn fallback(&mut self) -> Option<u32> {
        while let Some(v) = self.dead_end.pop() {
            let live = self.vt_live[v as usize] as usize;
            if live > 0 {
                let start = self.vt_start[v as usize] as usize;
                let list = &self.vt_tris[start..start + live];
                return list.iter().copied().min_by_key(|&t| self.free_degree(t));
            }
        }
        while self.scan < self.tris.len() {
            if !self.done[self.scan] {
                return Some(self.scan as u32);
            }
            self.scan += 1;
        }
        None
    }

    /// Emits `t`: continues the current strip when it is a continuation, else starts
    /// a new strip with it.
    fn step(&mut self, t: u32, nat: u32, swp: u32, first: [u32; 3]) {
        self.take(t);
        self.place(t, nat, swp, first);
    }

    /// Puts the emitted `t` into the strips and feeds its decoded vertices to the FIFO.
    fn place(&mut self, t: u32, nat: u32, swp: u32, first: [u32; 3]) {
        if let Some(j) = first.iter().position(|&n| n == t) {
            // Rotate the one-triangle strip so it leaves across edge j.
            let tri = self.tris[self.cur as usize];
            self.strip.clear();
            self.strip.extend_from_slice(&[tri[(j + 2) % 3], tri[j], tri[(j + 1) % 3]]);
        } else if t == swp {
            // [.., p, u, w] -> [.., p, u, p, w]: the current triangle decodes the same
            // and the strip now ends on edge (p, w).
            let len = self.strip.len();
            let (p, w) = (self.strip[len - 3], self.strip[len - 1]);
            self.strip[len - 1] = p;
            self.strip.push(w);
        } else if t != nat {
            self.finish_strip();
            let tri = self.tris[t as usize];
            self.strip.extend_from_slice(&tri);
            self.cur = t;
            self.strip_misses = 0;
            for v in tri {
                self.touch(v);
            }
            return;
        }
        let len = self.strip.len();
        let (u, w) = (self.strip[len - 2], self.strip[len - 1]);
        let x = self.third(t, u, w);
        self.strip.push(x);
        // Decoded order: (u, w, x) or (w, u, x); u and w are usually cached already.
        self.touch(u);
        self.touch(w);
        self.touch(x);
        self.cur = t;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strip::decode;

    fn canon(t: [u32; 3]) -> [u32; 3] {
        let r = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
        [t[r], t[(r + 1) % 3], t[(r + 2) % 3]]
    }

    fn grid(w: u32, h: u32) -> (Vec<[u32; 3]>, usize) {
        let mut tris = Vec::new();
        for y in 0..h {
            for x in 0..w {
                let a = y * (w + 1) + x;
                let b = a + 1;
                let c = a + w + 1;
                let d = c + 1;
                tris.push([a, b, d]);
                tris.push([a, d, c]);
            }
        }
        (tris, ((w + 1) * (h + 1)) as usize)
    }

    #[test]
    fn own_neighbours_match_the_dual_graph() {
        let (mut tris, vc) = grid(9, 7);
        // Awkward bits: a duplicated triangle, a flipped one, a degenerate one, three
        // triangles on one edge, a triangle whose neighbour runs the same way.
        tris.push(tris[5]);
        let t = tris[20];
        tris[20] = [t[0], t[2], t[1]];
        tris.push([3, 3, 4]);
        tris.push([40, 41, 70]);
        tris.push([41, 40, 71]);
        tris.push([40, 41, 72]);
        tris.push([60, 61, 73]);
        tris.push([61, 60, 74]);
        let vc = vc.max(75);
        let graph = DualGraph::from_triangles(&tris, vc);
        let s = State::new(&tris, vc, None, &CacheOptions::default());
        assert_eq!(s.neighbors, graph.neighbors);
        assert!(graph.neighbors.iter().flatten().any(|&n| n == NO_NEIGHBOR));
    }

    #[test]
    fn grid_strips_decode_to_the_input() {
        let (tris, vc) = grid(20, 13);
        for o in [CacheOptions::cache(16), CacheOptions::balanced(16), CacheOptions::cache(3)] {
            let set = stripify(&tris, vc, &o);
            let mut got: Vec<_> = decode(&set).into_iter().map(canon).collect();
            let mut want: Vec<_> = tris.iter().map(|&t| canon(t)).collect();
            got.sort_unstable();
            want.sort_unstable();
            assert_eq!(got, want);
        }
    }
}

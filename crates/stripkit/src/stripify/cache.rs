//! Cache-aware strips: short strips laid side by side, ordered for a FIFO vertex
//! cache.
//!
//! The stripifier grows one strip at a time while it simulates the FIFO cache of
//! METRICS.md (`cache_size` entries, a hit does not reorder, a miss evicts the
//! oldest entry), so every decision sees exactly the cache the figures will measure.
//!
//! * **Growing.** A strip steps only between [`DualGraph`] neighbours, so winding is
//!   kept. It takes the neighbour across the "natural" edge (no extra index) when that
//!   triangle is still free, otherwise the one across the other edge at the cost of a
//!   swap (one repeated index, cheaper than a restart's three). A strip ends when no
//!   neighbour is free or when it has pushed `strip_misses` new vertices into the
//!   cache: bounded that way, the vertices it shares with the *next* strip are still
//!   cached when the next strip comes back along it.
//! * **Starting.** The next strip starts at the *oldest* vertex still in the cache
//!   that has free triangles: the vertex that would be evicted first, at the head of
//!   the strip just finished, so the new strip runs along the previous one in the same
//!   direction and every vertex it shares is used about `strip_misses` pushes after it
//!   entered the cache. Among that vertex's free triangles the start is the one with
//!   the most cached vertices and the fewest free neighbours (a corner of the free
//!   region, so strips do not cut it into islands); the strip leaves it across the
//!   edge whose next triangles hit the cache most.
//! * **Falling back.** When no cached vertex has free triangles, a stack of recently
//!   used vertices (as in Tipsify) gives a start near the last strips, and only when
//!   that is empty too does a scan over the triangles pick the next free one. The
//!   input order matters only there, so shuffled inputs give the same figures.
//!
//! Cost: O(T + V) time and memory, a few flat arrays, nothing allocated per strip.

use crate::strip::StripSet;
use crate::topology::{DualGraph, NO_NEIGHBOR};

/// Settings of the cache-aware stripifier.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CacheOptions {
    /// Entries of the FIFO vertex cache the order is tuned for (at least 3).
    pub cache_size: u32,
    /// A strip ends after pushing this many new vertices into the cache; smaller
    /// gives fewer cache misses, larger gives fewer strips (fewer indices).
    pub strip_misses: u32,
    /// Let a strip turn the "wrong" way at the cost of one repeated index rather
    /// than end (a restart costs three).
    pub swaps: bool,
    /// Also turn the "wrong" way (one repeated index) when that reaches a cached
    /// vertex and the natural turn would miss.
    pub hit_swaps: bool,
    /// Triangles looked ahead when choosing the direction a strip leaves its start.
    pub lookahead: u32,
    /// End a strip after this many consecutive missing vertices (0: never): the
    /// strip has left the cached side of the previous strip.
    pub max_run: u32,
    /// Start the next strip at the newest cached vertex with free triangles (the
    /// strip runs back along the previous one) rather than the oldest.
    pub newest_first: bool,
    /// Cached vertices with free triangles whose triangles are tried as starts.
    pub candidates: u32,
}

impl CacheOptions {
    /// The `cache` mode: fewest cache misses for a FIFO of `cache_size` entries.
    /// Strips end after `cache_size / 4` misses or as soon as they leave the cached
    /// side of the previous strip.
    pub fn cache(cache_size: u32) -> Self {
        let cache_size = cache_size.max(3);
        CacheOptions {
            cache_size,
            strip_misses: (cache_size / 4).max(2),
            swaps: true,
            hit_swaps: true,
            lookahead: 4,
            max_run: 2,
            newest_first: true,
            candidates: 1,
        }
    }

    /// The `balanced` mode: longer strips (fewer indices) for a few more misses.
    /// Strips end only after `5 * cache_size / 8` misses.
    pub fn balanced(cache_size: u32) -> Self {
        CacheOptions { strip_misses: (cache_size.max(3) * 5 / 8).max(2), max_run: 0, ..CacheOptions::cache(cache_size) }
    }
}

impl Default for CacheOptions {
    fn default() -> Self {
        CacheOptions::cache(16)
    }
}

/// Strips for `tris` (indices below `vertex_count`), ordered for a FIFO vertex cache.
/// Degenerate triangles are dropped; every other triangle appears exactly once with
/// its winding. Builds the dual graph itself; see [`stripify_with_graph`].
pub fn stripify(tris: &[[u32; 3]], vertex_count: usize, options: &CacheOptions) -> StripSet {
    let graph = DualGraph::from_triangles(tris, vertex_count);
    stripify_with_graph(tris, vertex_count, &graph, options)
}

/// As [`stripify`], with the dual graph of `tris` already built.
pub fn stripify_with_graph(
    tris: &[[u32; 3]],
    vertex_count: usize,
    graph: &DualGraph,
    options: &CacheOptions,
) -> StripSet {
    let mut s = State::new(tris, vertex_count, graph, options);
    s.run();
    s.out
}

const NEVER: u32 = u32::MAX;

fn is_degenerate(t: &[u32; 3]) -> bool {
    t[0] == t[1] || t[1] == t[2] || t[2] == t[0]
}

struct State<'a> {
    tris: &'a [[u32; 3]],
    graph: &'a DualGraph,
    cache_size: u32,
    strip_misses: u32,
    swaps: bool,
    hit_swaps: bool,
    depth: u32,
    max_run: u32,
    newest_first: bool,
    candidates: u32,
    /// Triangle already in a strip (degenerate ones count as done from the start).
    done: Vec<bool>,
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
    strip: Vec<u32>,
    out: StripSet,
}

impl<'a> State<'a> {
    fn new(tris: &'a [[u32; 3]], vertex_count: usize, graph: &'a DualGraph, o: &CacheOptions) -> Self {
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
        State {
            tris,
            graph,
            cache_size,
            strip_misses: o.strip_misses.max(1),
            swaps: o.swaps,
            hit_swaps: o.hit_swaps,
            depth: o.lookahead,
            max_run: o.max_run,
            newest_first: o.newest_first,
            candidates: o.candidates.max(1),
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
            out: StripSet {
                indices: Vec::with_capacity(n + n / 4),
                offsets: {
                    let mut o = Vec::with_capacity(n / 4 + 2);
                    o.push(0);
                    o
                },
            },
        }
    }

    #[inline]
    fn cached(&self, v: u32) -> bool {
        let s = self.stamp[v as usize];
        s != NEVER && self.time - s <= self.cache_size
    }

    /// Feeds one vertex to the FIFO; returns true on a miss.
    #[inline]
    fn touch(&mut self, v: u32) -> bool {
        if self.cached(v) {
            return false;
        }
        self.stamp[v as usize] = self.time;
        self.ring[(self.time % self.cache_size) as usize] = v;
        self.time = self.time.wrapping_add(1);
        true
    }

    /// Marks triangle `t` emitted (decoded as `decoded`); returns the misses.
    fn emit(&mut self, t: u32, decoded: [u32; 3]) -> u32 {
        self.done[t as usize] = true;
        let tri = self.tris[t as usize];
        for (c, &v) in tri.iter().enumerate() {
            // Swap-remove t from v's free list.
            let v = v as usize;
            let p = self.corner_pos[3 * t as usize + c];
            let last = self.vt_start[v] + self.vt_live[v] - 1;
            let moved = self.vt_tris[last as usize];
            self.vt_tris[p as usize] = moved;
            let mt = self.tris[moved as usize];
            let mc = (0..3).find(|&k| mt[k] as usize == v).unwrap_or(0);
            self.corner_pos[3 * moved as usize + mc] = p;
            self.vt_live[v] -= 1;
            self.dead_end.push(v as u32);
        }
        let mut misses = 0;
        for v in decoded {
            misses += self.touch(v) as u32;
        }
        misses
    }

    fn free(&self, t: u32) -> bool {
        t != NO_NEIGHBOR && !self.done[t as usize]
    }

    /// Free neighbours of `t`.
    fn free_degree(&self, t: u32) -> u32 {
        self.graph.neighbors[t as usize].iter().filter(|&&n| self.free(n)).count() as u32
    }

    /// Neighbour of `t` across the undirected edge `{a, b}` (or NO_NEIGHBOR).
    fn across(&self, t: u32, a: u32, b: u32) -> u32 {
        let tri = self.tris[t as usize];
        for j in 0..3 {
            let (x, y) = (tri[j], tri[(j + 1) % 3]);
            if (x == a && y == b) || (x == b && y == a) {
                return self.graph.neighbors[t as usize][j];
            }
        }
        NO_NEIGHBOR
    }

    fn third(&self, t: u32, a: u32, b: u32) -> u32 {
        let tri = self.tris[t as usize];
        tri.into_iter().find(|&v| v != a && v != b).unwrap_or(tri[0])
    }

    fn run(&mut self) {
        while let Some(t) = self.next_start() {
            self.grow(t);
        }
    }

    /// Scores a free triangle as a strip start: cached vertices first, then few free
    /// neighbours.
    fn start_score(&self, t: u32) -> i32 {
        let tri = self.tris[t as usize];
        let cached = tri.iter().filter(|&&v| self.cached(v)).count() as i32;
        cached * 8 - self.free_degree(t) as i32
    }

    fn best_around(&self, v: u32) -> u32 {
        let start = self.vt_start[v as usize] as usize;
        let live = self.vt_live[v as usize] as usize;
        let mut best = NO_NEIGHBOR;
        let mut best_score = i32::MIN;
        for &t in &self.vt_tris[start..start + live] {
            let s = self.start_score(t);
            if s > best_score {
                best_score = s;
                best = t;
            }
        }
        best
    }

    fn next_start(&mut self) -> Option<u32> {
        // Oldest cached vertex with free triangles.
        let n = self.cache_size.min(self.time);
        let mut found = 0;
        let mut best = NO_NEIGHBOR;
        let mut best_score = i32::MIN;
        for i in 0..n {
            let k = if self.newest_first { i } else { n - 1 - i };
            let v = self.ring[((self.time - 1 - k) % self.cache_size) as usize];
            let live = self.vt_live[v as usize] as usize;
            if live > 0 {
                let start = self.vt_start[v as usize] as usize;
                for idx in start..start + live {
                    let t = self.vt_tris[idx];
                    let (_, score) = self.best_rotation(t);
                    let score = score - found as i32;
                    if score > best_score {
                        best_score = score;
                        best = t;
                    }
                }
                found += 1;
                if found >= self.candidates {
                    break;
                }
            }
        }
        if best != NO_NEIGHBOR {
            return Some(best);
        }
        while let Some(v) = self.dead_end.pop() {
            if self.vt_live[v as usize] > 0 {
                return Some(self.best_around(v));
            }
        }
        while self.scan < self.tris.len() {
            let t = self.scan as u32;
            if !self.done[self.scan] {
                return Some(t);
            }
            self.scan += 1;
        }
        None
    }

    /// Cache hits of the first `depth` triangles along the natural path leaving the
    /// strip `[a, b]` through `next`.
    fn lookahead(&self, mut a: u32, mut b: u32, mut next: u32, depth: u32) -> i32 {
        let mut score = 0;
        for _ in 0..depth {
            if !self.free(next) {
                break;
            }
            let x = self.third(next, a, b);
            score += if self.cached(x) { 1 } else { 0 };
            let nn = self.across(next, b, x);
            a = b;
            b = x;
            next = nn;
        }
        score
    }

    /// The best rotation `k` to start a strip at `t0` (strip `[tri[k], tri[k+1],
    /// tri[k+2]]` leaves across edge `(tri[k+1], tri[k+2])` = dual edge `(k + 1) % 3`),
    /// and its score.
    fn best_rotation(&self, t0: u32) -> (usize, i32) {
        let tri = self.tris[t0 as usize];
        let mut best_k = 0;
        let mut best_score = i32::MIN;
        for k in 0..3 {
            let j = (k + 1) % 3;
            let next = self.graph.neighbors[t0 as usize][j];
            let score = self.lookahead(tri[j], tri[(j + 1) % 3], next, self.depth) * 4
                - if self.free(next) { self.free_degree(next) as i32 } else { 1000 }
                + if self.cached(tri[k]) { 1 } else { 0 };
            if score > best_score {
                best_score = score;
                best_k = k;
            }
        }
        let own = tri.iter().filter(|&&v| self.cached(v)).count() as i32;
        (best_k, best_score + own)
    }

    fn grow(&mut self, t0: u32) {
        let tri = self.tris[t0 as usize];
        let (best_k, _) = self.best_rotation(t0);
        let (a, b, c) = (tri[best_k], tri[(best_k + 1) % 3], tri[(best_k + 2) % 3]);
        self.strip.clear();
        self.strip.extend_from_slice(&[a, b, c]);
        let mut misses = self.emit(t0, [a, b, c]);
        // Decoded position of the newest triangle in the strip (parity).
        let mut pos = 0usize;
        let mut run = 0u32;
        let mut hugging = false;
        let mut cur = t0;
        loop {
            if misses >= self.strip_misses && !hugging {
                break;
            }
            if misses >= 2 * self.strip_misses {
                break;
            }
            let len = self.strip.len();
            let (p, u, w) = (self.strip[len - 3], self.strip[len - 2], self.strip[len - 1]);
            let natural = self.across(cur, u, w);
            let other = if self.swaps { self.across(cur, p, w) } else { NO_NEIGHBOR };
            let (next, swap) = if self.free(natural)
                && !(self.hit_swaps
                    && pos > 0
                    && self.free(other)
                    && !self.cached(self.third(natural, u, w))
                    && self.cached(self.third(other, p, w)))
            {
                (natural, false)
            } else if self.free(other) {
                (other, true)
            } else {
                break;
            };
            let x = if swap { self.third(next, p, w) } else { self.third(next, u, w) };
            let x_cached = self.cached(x);
            if self.max_run > 0 && hugging && run + 1 >= self.max_run && !x_cached {
                break;
            }
            if swap {
                // [.., p, u, w] -> [.., p, u, p, w]: the current triangle decodes the
                // same and the strip now ends on edge (p, w).
                self.strip[len - 1] = p;
                self.strip.push(w);
                pos += 1;
            }
            let len = self.strip.len();
            let (u, w) = (self.strip[len - 2], self.strip[len - 1]);
            let x = self.third(next, u, w);
            self.strip.push(x);
            pos += 1;
            let decoded = if pos % 2 == 0 { [u, w, x] } else { [w, u, x] };
            let m = self.emit(next, decoded);
            misses += m;
            run = if m > 0 { run + 1 } else { 0 };
            hugging |= x_cached;
            cur = next;
        }
        self.out.indices.extend_from_slice(&self.strip);
        self.out.offsets.push(self.out.indices.len() as u32);
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

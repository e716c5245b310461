//! Cache-aware short strips laid side by side, running back and forth (serpentine).
//!
//! An experimental alternative to the `balanced` mode of [`super::cache`]: on the
//! research models it lands on about the same index-count / ACMR16 curve (see
//! ARCHITECTURE.md for figures), so the CLI does not use it yet.
//!
//! Strips are grown one at a time while the exact FIFO of METRICS.md is simulated
//! (push stamps: a vertex is cached while fewer than `cache_size` misses happened
//! since it was pushed), and the indices are emitted as the strip grows (a swap
//! repeats one index), so every choice sees exactly the cache the figures measure.
//!
//! * **Start.** A new strip starts at a free triangle around the cached vertices:
//!   lowest free degree first (corners of the free region, so it is not cut into
//!   islands), then most cached vertices, then the *oldest* cached vertex, so the next
//!   strip starts beside the beginning of the previous one and runs the same way
//!   along its side (Hoppe's bounded-width bands, SIGGRAPH 1999) while that side is
//!   still in the FIFO. (Newest-first, a true back-and-forth serpentine, is 0.7% fewer
//!   indices on bunny at 0.004 less ACMR16 but degenerates on regular meshes: on an
//!   ordered torus each next strip continues the last one around the ring and ACMR16
//!   goes to 1.0.) When no cached vertex has a free triangle, a free triangle of
//!   lowest degree is taken (most recently lowered first, as in the greedy
//!   stripifier).
//! * **Growth.** Only across [`DualGraph`] edges (winding kept). The next triangle is
//!   a dead end first (degree 0, it would be a strip of its own), then one whose new
//!   vertex is cached, then one without a swap, then the lowest degree.
//! * **End.** After `max_len` triangles a strip only goes on into a neighbour left with
//!   at most one free neighbour (which would otherwise become a strip of one or two).
//!
//! O(T + V) time and memory, flat arrays, nothing allocated per step.

use super::greedy::Buckets;
use crate::strip::{is_degenerate, StripSet};
use crate::topology::{DualGraph, NO_NEIGHBOR};

/// Settings of the serpentine stripifier.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SerpentineOptions {
    /// Entries of the FIFO vertex cache the order is tuned for (at least 3).
    pub cache_size: u32,
    /// Strip length (triangles) after which a strip only goes on into a neighbour of
    /// at most one free neighbour (a dead end it would otherwise leave behind).
    pub max_len: u32,
}

impl SerpentineOptions {
    /// The `balanced` mode for a FIFO of `cache_size` entries.
    pub fn balanced(cache_size: u32) -> Self {
        let cache_size = cache_size.max(3);
        SerpentineOptions {
            cache_size,
            max_len: cache_size,
        }
    }
}

/// Turns triangles into short cache-aware strips (see the module docs). Indices must
/// be below `vertex_count` (larger ones are tolerated); degenerate triangles are
/// dropped. The result decodes to every other triangle once with its winding.
pub fn stripify(tris: &[[u32; 3]], vertex_count: usize, options: &SerpentineOptions) -> StripSet {
    let graph = DualGraph::from_triangles(tris, vertex_count);
    stripify_with_graph(tris, vertex_count, &graph, options)
}

/// [`stripify`] with a dual graph already built for `tris`.
pub fn stripify_with_graph(
    tris: &[[u32; 3]],
    vertex_count: usize,
    graph: &DualGraph,
    options: &SerpentineOptions,
) -> StripSet {
    let vcount = tris
        .iter()
        .flatten()
        .map(|&v| v as usize + 1)
        .max()
        .unwrap_or(0)
        .max(vertex_count);
    let mut s = State::new(tris, &graph.neighbors, vcount, options);
    s.run();
    s.out
}

const NONE: u32 = u32::MAX;

struct State<'a> {
    tris: &'a [[u32; 3]],
    nbr: &'a [[u32; 3]],
    opt: SerpentineOptions,
    /// Free triangles by degree (the greedy stripifier's buckets).
    b: Buckets,
    /// Vertex -> incident triangles (CSR).
    vstart: Vec<u32>,
    vtris: Vec<u32>,
    /// Free triangles left around each vertex.
    vfree: Vec<u32>,
    /// Miss counter value when the vertex was pushed (0: never).
    stamp: Vec<u64>,
    clock: u64,
    /// The last `cache_size` pushed vertices, by `clock % cache_size`.
    fifo: Vec<u32>,
    out: StripSet,
}

impl<'a> State<'a> {
    fn new(
        tris: &'a [[u32; 3]],
        nbr: &'a [[u32; 3]],
        vcount: usize,
        opt: &SerpentineOptions,
    ) -> Self {
        let n = tris.len();
        let mut opt = *opt;
        opt.cache_size = opt.cache_size.max(3);
        opt.max_len = opt.max_len.max(1);
        let mut vstart = vec![0u32; vcount + 1];
        for t in tris.iter().filter(|t| !is_degenerate(t)) {
            for &v in t {
                vstart[v as usize + 1] += 1;
            }
        }
        for v in 0..vcount {
            vstart[v + 1] += vstart[v];
        }
        let mut fill = vstart.clone();
        let mut vtris = vec![0u32; vstart[vcount] as usize];
        let mut vfree = vec![0u32; vcount];
        let mut b = Buckets::new(n);
        for (i, t) in tris.iter().enumerate().rev() {
            if is_degenerate(t) {
                continue;
            }
            for &v in t {
                vtris[fill[v as usize] as usize] = i as u32;
                fill[v as usize] += 1;
                vfree[v as usize] += 1;
            }
            b.free[i] = true;
            let d = nbr[i].iter().filter(|&&x| x != NO_NEIGHBOR).count() as u8;
            b.push_front(i as u32, d);
        }
        let mut out = StripSet::new();
        out.indices.reserve(n + n / 3);
        State {
            tris,
            nbr,
            opt,
            b,
            vstart,
            vtris,
            vfree,
            stamp: vec![0; vcount],
            clock: 0,
            fifo: vec![NONE; opt.cache_size as usize],
            out,
        }
    }

    #[inline]
    fn is_free(&self, t: u32) -> bool {
        t != NO_NEIGHBOR && self.b.free[t as usize]
    }

    #[inline]
    fn cached(&self, v: u32) -> bool {
        let s = self.stamp[v as usize];
        s != 0 && self.clock - s < u64::from(self.opt.cache_size)
    }

    /// Emits one index, simulating the FIFO.
    #[inline]
    fn emit(&mut self, v: u32) {
        if !self.cached(v) {
            self.clock += 1;
            self.stamp[v as usize] = self.clock;
            let c = self.opt.cache_size as u64;
            self.fifo[(self.clock % c) as usize] = v;
        }
        self.out.indices.push(v);
    }

    fn take(&mut self, t: u32) {
        self.b.free[t as usize] = false;
        for &v in &self.tris[t as usize] {
            self.vfree[v as usize] -= 1;
        }
        for k in 0..3 {
            let m = self.nbr[t as usize][k];
            if self.is_free(m) {
                let d = self.b.degree[m as usize] - 1;
                self.b.push_front(m, d);
            }
        }
    }

    /// A free triangle around the cached vertices (see the module docs).
    fn start_near_cache(&self) -> Option<u32> {
        let c = u64::from(self.opt.cache_size);
        let mut best: Option<(u32, (u8, u8, u64))> = None;
        let first = self.clock.saturating_sub(c - 1).max(1);
        for tick in first..=self.clock {
            let v = self.fifo[(tick % c) as usize];
            if v == NONE || self.vfree[v as usize] == 0 {
                continue;
            }
            let (a, b) = (
                self.vstart[v as usize] as usize,
                self.vstart[v as usize + 1] as usize,
            );
            for &t in &self.vtris[a..b] {
                if !self.b.free[t as usize] {
                    continue;
                }
                let cached = self.tris[t as usize]
                    .iter()
                    .filter(|&&u| self.cached(u))
                    .count() as u8;
                // Oldest cached vertex first (see the module docs).
                let key = (self.b.degree[t as usize], 3 - cached, tick);
                if best.is_none_or(|(_, k)| key < k) {
                    best = Some((t, key));
                }
            }
        }
        best.map(|(t, _)| t)
    }

    /// Ranks leaving `cur` (entry edge `{p, q}`, or none) through slot `k`.
    fn step_key(&self, cur: u32, k: usize, q: u32, has_entry: bool) -> Option<(u8, u8, u8, u8)> {
        let n = self.nbr[cur as usize][k];
        if !self.is_free(n) {
            return None;
        }
        let tri = &self.tris[cur as usize];
        let (u, v) = (tri[k], tri[(k + 1) % 3]);
        let ntri = &self.tris[n as usize];
        let s = *ntri.iter().find(|&&w| w != u && w != v)?;
        let d = self.b.degree[n as usize];
        let swap = u8::from(has_entry && u != q && v != q);
        let miss = u8::from(!self.cached(s));
        Some((u8::from(d != 0), miss, swap, d))
    }

    fn run(&mut self) {
        while let Some(t0) = self.start_near_cache().or_else(|| self.b.lowest()) {
            self.strip_from(t0);
            let len = self.out.indices.len() as u32;
            self.out.offsets.push(len);
        }
    }

    fn strip_from(&mut self, t0: u32) {
        self.take(t0);
        let tri = self.tris[t0 as usize];
        // First step: any edge; the start rotation is free.
        let mut best: Option<(usize, (u8, u8, u8, u8))> = None;
        for k in 0..3 {
            if let Some(key) = self.step_key(t0, k, NONE, false) {
                if best.is_none_or(|(_, b)| key < b) {
                    best = Some((k, key));
                }
            }
        }
        let Some((k, _)) = best else {
            tri.iter().for_each(|&v| self.emit(v));
            return;
        };
        let (x, y, a) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
        self.emit(a);
        self.emit(x);
        self.emit(y);
        let (mut p, mut q) = (x, y);
        let mut cur = self.nbr[t0 as usize][k];
        let mut len = 1u32;
        loop {
            // Enter `cur` over the edge {p, q}.
            self.take(cur);
            len += 1;
            let ctri = self.tris[cur as usize];
            let r = *ctri
                .iter()
                .find(|&&w| w != p && w != q)
                .expect("dual neighbours share an edge");
            let stop = len >= self.opt.max_len;
            let mut best: Option<(usize, (u8, u8, u8, u8))> = None;
            for k in 0..3 {
                let (u, v) = (ctri[k], ctri[(k + 1) % 3]);
                if (u == p || u == q) && (v == p || v == q) {
                    continue;
                }
                if let Some(key) = self.step_key(cur, k, q, true) {
                    // Past `max_len`: only into a neighbour that would be left
                    // with at most one free neighbour.
                    if stop && key.3 > 1 {
                        continue;
                    }
                    if best.is_none_or(|(_, b)| key < b) {
                        best = Some((k, key));
                    }
                }
            }
            let Some((k, _)) = best else {
                self.emit(r);
                return;
            };
            let (u, v) = (ctri[k], ctri[(k + 1) % 3]);
            if u == q || v == q {
                self.emit(r);
                p = q;
            } else {
                self.emit(p);
                self.emit(r);
            }
            q = r;
            cur = self.nbr[cur as usize][k];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strip::verify;

    #[test]
    fn small_meshes_verify() {
        let tris = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5], [7, 8, 9]];
        let out = stripify(&tris, 10, &SerpentineOptions::balanced(16));
        assert!(verify(&tris, &out).ok());
        let out = stripify(&[], 0, &SerpentineOptions::balanced(16));
        assert!(verify(&[], &out).ok());
    }
}

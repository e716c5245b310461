//! Figures of docs/metrics.md: strip counts, index counts per join, swaps, vertex-cache
//! miss ratios (FIFO as docs/metrics.md defines it, LRU as an option), and the verdict of
//! [`crate::strip::verify`].
//!
//! ```
//! use stripkit::{figures, CacheModel, StripSet};
//! let tris = [[0, 1, 2], [2, 1, 3]];
//! let strips = StripSet::from_strips(&[vec![0, 1, 2, 3]]);
//! let f = figures(&tris, &strips, CacheModel::fifo(16));
//! assert!(f.verified);
//! assert_eq!((f.strips, f.indices_restart, f.indices_degenerate), (1, 4, 4));
//! ```

use crate::strip::{self, StripSet};

/// How a simulated vertex cache replaces entries.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum CacheKind {
    /// First in, first out: a hit does not reorder, a miss evicts the oldest entry
    /// (the model of docs/metrics.md and of most post-transform caches).
    #[default]
    Fifo,
    /// Least recently used: a hit moves the vertex to the front.
    Lru,
}

/// A simulated vertex cache: replacement policy and number of entries.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct CacheModel {
    /// Replacement policy.
    pub kind: CacheKind,
    /// Number of entries (at least 1 to mean anything; 0 misses every vertex).
    pub size: usize,
}

impl CacheModel {
    /// A FIFO cache of `size` entries.
    pub fn fifo(size: usize) -> Self {
        CacheModel {
            kind: CacheKind::Fifo,
            size,
        }
    }
    /// An LRU cache of `size` entries.
    pub fn lru(size: usize) -> Self {
        CacheModel {
            kind: CacheKind::Lru,
            size,
        }
    }
}

impl Default for CacheModel {
    fn default() -> Self {
        CacheModel::fifo(16)
    }
}

/// Number of cache misses when the vertices of `triangles` are fed, in order, through
/// an initially empty cache. `vertex_count` sizes the per-vertex records; an index at
/// or past it is counted like any other (never a panic), and a cache larger than the
/// vertices behaves as one of their number. O(n) for FIFO, O(n * size) for LRU.
pub fn cache_misses(
    triangles: &[[u32; 3]],
    vertex_count: usize,
    cache_size: usize,
    kind: CacheKind,
) -> usize {
    if cache_size == 0 {
        return triangles.len() * 3;
    }
    // An index at or past `vertex_count` is a vertex too: size the records to cover
    // it rather than fail on it.
    let vertex_count = triangles.iter().flatten().map(|&v| v as usize + 1).max().unwrap_or(0).max(vertex_count);
    // Neither cache ever holds more vertices than there are.
    let cache_size = cache_size.min(vertex_count.max(1));
    let mut misses = 0usize;
    match kind {
        CacheKind::Fifo => {
            // A FIFO at least as large as the vertex count never evicts, whatever its
            // size.
            let size = cache_size.min(vertex_count.max(1)).min(1 << 30) as u32;
            let mut fifo = Fifo::new(size, vertex_count);
            for t in triangles {
                for &v in t {
                    misses += usize::from(fifo.touch(v));
                }
            }
        }
        CacheKind::Lru => {
            let mut cache: Vec<u32> = Vec::with_capacity(cache_size + 1);
            for t in triangles {
                for &v in t {
                    match cache.iter().position(|&c| c == v) {
                        Some(p) => {
                            cache[..=p].rotate_right(1);
                        }
                        None => {
                            misses += 1;
                            cache.insert(0, v);
                            cache.truncate(cache_size);
                        }
                    }
                }
            }
        }
    }
    misses
}

/// The FIFO vertex cache of docs/metrics.md, simulated: a hit does not reorder, a miss
/// pushes the vertex and evicts the oldest entry. The one simulation behind
/// [`cache_misses`], the cache-aware stripifier (which also asks what a few more
/// pushes would leave cached) and its refinement (which replays stretches of the
/// output from snapshots of the contents). O(1) per vertex, nothing allocated after
/// [`Fifo::new`].
#[derive(Clone, Debug)]
pub(crate) struct Fifo {
    size: u32,
    /// Advances by one per push; starts at `size + 1` so that a stamp of 0 (never
    /// pushed) reads as long evicted.
    clock: u32,
    /// Pushes so far (wrapping).
    pushes: u32,
    /// Per vertex: the clock at its last push (0: never).
    stamp: Vec<u32>,
    /// The last `size` pushes by `clock % size` ([`NONE`] where there was none).
    ring: Vec<u32>,
}

/// An empty entry of [`Fifo`]'s ring and snapshots.
pub(crate) const NONE: u32 = u32::MAX;

/// The clock at which [`Fifo`] moves its clock back (keeping it far from overflow).
const REBASE_AT: u32 = u32::MAX / 2;

impl Fifo {
    /// An empty FIFO of `size` entries (1 to 2^30) for vertices `0..vertex_count`.
    pub(crate) fn new(size: u32, vertex_count: usize) -> Fifo {
        assert!((1..=1 << 30).contains(&size), "FIFO size {size} out of range");
        Fifo {
            size,
            clock: size + 1,
            pushes: 0,
            stamp: vec![0; vertex_count],
            ring: vec![NONE; size as usize],
        }
    }

    /// Whether `v` is cached.
    #[inline(always)]
    pub(crate) fn contains(&self, v: u32) -> bool {
        self.clock - self.stamp[v as usize] <= self.size
    }

    /// Whether `v` is still cached after `pushes` more pushes (of other vertices).
    #[inline(always)]
    pub(crate) fn contains_after(&self, v: u32, pushes: u32) -> bool {
        self.clock - self.stamp[v as usize] + pushes <= self.size
    }

    /// Feeds `v` to the cache; true on a miss.
    #[inline(always)]
    pub(crate) fn touch(&mut self, v: u32) -> bool {
        if self.contains(v) {
            return false;
        }
        self.push(v);
        true
    }

    /// Pushes `v` (not cached), evicting the oldest entry; `NONE` pushes an empty
    /// entry.
    #[inline(always)]
    fn push(&mut self, v: u32) {
        if self.clock >= REBASE_AT {
            self.rebase();
        }
        if v != NONE {
            self.stamp[v as usize] = self.clock;
        }
        self.ring[(self.clock % self.size) as usize] = v;
        self.clock += 1;
        self.pushes = self.pushes.wrapping_add(1);
    }

    /// Pushes so far (the misses, for a FIFO fed only through [`Fifo::touch`]).
    pub(crate) fn pushes(&self) -> u32 {
        self.pushes
    }

    /// Entries in the cache: `size` once that many pushes were made.
    pub(crate) fn len(&self) -> u32 {
        self.size.min(self.pushes)
    }

    /// The entry pushed `i` pushes before the newest (`i < len()`).
    #[inline]
    pub(crate) fn newest(&self, i: u32) -> u32 {
        self.ring[((self.clock - 1 - i) % self.size) as usize]
    }

    /// The entries, oldest first, into `out[..size]` ([`NONE`] for empty ones).
    pub(crate) fn snapshot(&self, out: &mut [u32]) {
        let (h, c) = (self.clock as usize, self.size as usize);
        for (i, e) in out[..c].iter_mut().enumerate() {
            *e = self.ring[(h + i) % c];
        }
    }

    /// Whether the entries, oldest first, are `snap` (as [`Fifo::snapshot`] gives them).
    pub(crate) fn matches(&self, snap: &[u32]) -> bool {
        let (h, c) = (self.clock as usize, self.size as usize);
        (0..c).all(|i| snap[i] == self.ring[(h + i) % c])
    }

    /// Empties the cache, then pushes the entries of `snap[..size]` (oldest first,
    /// [`NONE`] for an empty entry): the cache then holds what it held when the
    /// snapshot was taken.
    pub(crate) fn load(&mut self, snap: &[u32]) {
        if self.clock >= REBASE_AT {
            self.stamp.fill(0);
            self.clock = self.size + 1;
        }
        // Every stamp falls more than `size` pushes behind: nothing is cached.
        self.clock += self.size + 1;
        for &v in &snap[..self.size as usize] {
            self.push(v);
        }
    }

    /// Moves the clock back to its start, keeping the contents: each entry, oldest
    /// first, restamped as if pushed again.
    #[cold]
    fn rebase(&mut self) {
        let c = self.size;
        self.stamp.fill(0);
        // Oldest first, then placed so that the entry pushed at clock k sits at k % c.
        self.ring.rotate_left((self.clock % c) as usize);
        self.clock = c + 1;
        for (i, &v) in self.ring.iter().enumerate() {
            if v != NONE {
                self.stamp[v as usize] = self.clock + i as u32;
            }
        }
        self.ring.rotate_right((self.clock % c) as usize);
        self.clock += c;
    }
}

/// Average cache miss ratio: [`cache_misses`] per triangle (0 for no triangles).
pub fn acmr(
    triangles_in_order: &[[u32; 3]],
    vertex_count: usize,
    cache_size: usize,
    kind: CacheKind,
) -> f64 {
    if triangles_in_order.is_empty() {
        return 0.0;
    }
    cache_misses(triangles_in_order, vertex_count, cache_size, kind) as f64
        / triangles_in_order.len() as f64
}

/// Degenerate triangle windows inside the strips: each is one swap (a repeated index)
/// and costs one index.
pub fn swaps(strips: &StripSet) -> usize {
    let mut n = 0;
    for s in strips.iter() {
        n += s.windows(3).filter(|w| strip::is_degenerate(&[w[0], w[1], w[2]])).count();
    }
    n
}

/// Every figure of docs/metrics.md for one strip set.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Figures {
    /// T: non-degenerate input triangles.
    pub triangles: usize,
    /// Degenerate input triangles (repeated index), left out of the strips.
    pub dropped_degenerate: usize,
    /// Number of strips.
    pub strips: usize,
    /// Degenerate windows inside the strips.
    pub swaps: usize,
    /// Sum of the strip lengths.
    pub indices_separate: usize,
    /// One buffer with restart indices: `indices_separate + strips - 1` (0 without strips).
    pub indices_restart: usize,
    /// One stitched strip ([`strip::encode_stitched`]): its length.
    pub indices_degenerate: usize,
    /// `indices_restart / triangles` (0 without triangles).
    pub indices_per_triangle: f64,
    /// ACMR with a FIFO cache of 16 entries, triangles in strip order.
    pub acmr16: f64,
    /// ACMR with a FIFO cache of 32 entries.
    pub acmr32: f64,
    /// The cache model of [`Figures::acmr`].
    pub cache: CacheModel,
    /// ACMR with the chosen cache model.
    pub acmr: f64,
    /// Decoded triangles equal the input's (multiset of oriented triangles).
    pub verified: bool,
    /// No triangle came out flipped.
    pub winding_preserved: bool,
    /// Input triangles missing from the output.
    pub lost: usize,
    /// Output triangles not in the input.
    pub added: usize,
    /// Input triangles drawn with the opposite winding.
    pub flipped: usize,
}

/// Measures `strips` against the `input` triangles they should draw: counts, the three
/// joins, swaps, ACMR (FIFO 16 and 32, and `cache`), and verification. O(n log n).
pub fn figures(input: &[[u32; 3]], strips: &StripSet, cache: CacheModel) -> Figures {
    figures_with(input, strips, cache, crate::parallel::Threads::SERIAL)
}

/// [`figures`] with the three cache simulations, the stitched length and the check
/// run side by side (and the check's sorting in parallel) when `threads` allows: the
/// same figures at any thread count.
pub fn figures_with(
    input: &[[u32; 3]],
    strips: &StripSet,
    cache: CacheModel,
    threads: crate::parallel::Threads,
) -> Figures {
    use crate::parallel::{join, map_ordered};
    let decoded = strip::decode_with(strips, threads);
    let vertex_count = strips.vertex_bound();
    // The asked-for cache is mostly one of the two fixed ones (FIFO 16 by default):
    // simulated once, its figure copied.
    let same = [(16, CacheKind::Fifo), (32, CacheKind::Fifo)].iter().position(|&m| m == (cache.size, cache.kind));
    let models: &[(usize, CacheKind)] =
        &[(16, CacheKind::Fifo), (32, CacheKind::Fifo), (cache.size, cache.kind)][..if same.is_some() { 2 } else { 3 }];
    // The check's expected list is sorted while the simulations read the decoded
    // list in order; the decoded list is then the check's to sort (no copy of it).
    let ((acmrs, (swaps, stitched)), want) = join(
        threads,
        || {
            let mut acmrs = map_ordered(threads, models, |&(size, kind)| acmr(&decoded, vertex_count, size, kind));
            if let Some(i) = same {
                acmrs.push(acmrs[i]);
            }
            (acmrs, join(threads, || swaps(strips), || strip::stitched_len(strips)))
        },
        || strip::sorted_expected(input, threads),
    );
    let v = strip::compare_sorted(&want, decoded, threads);
    drop(want);
    let n_strips = strips.len();
    let indices_separate = strips.index_count();
    let indices_restart = strips.restart_len();
    Figures {
        triangles: v.expected,
        dropped_degenerate: v.dropped_degenerate,
        strips: n_strips,
        swaps,
        indices_separate,
        indices_restart,
        indices_degenerate: stitched,
        indices_per_triangle: if v.expected == 0 {
            0.0
        } else {
            indices_restart as f64 / v.expected as f64
        },
        acmr16: acmrs[0],
        acmr32: acmrs[1],
        cache,
        acmr: acmrs[2],
        verified: v.ok(),
        winding_preserved: v.flipped == 0,
        lost: v.lost,
        added: v.added,
        flipped: v.flipped,
    }
}

/// A model of how a GPU batches the vertices of one draw for vertex shading, fitted
/// to measured vertex-shader invocation counts (`stripkit-bench gpu-model`):
///
/// - the index stream is cut into batches of at most `max_triangles` primitives
///   (degenerate triangles of a strip included, restarts not) and at most
///   `max_vertices` shaded vertices;
/// - in a triangle list, a vertex is shaded once per batch (any earlier use in the
///   batch is reused);
/// - in a strip, a vertex is reused only while it is among the last `strip_window`
///   vertices shaded in the batch (`strip_fifo`; otherwise among its last
///   `strip_window` indices), `restart_window` for the first two indices of a strip;
///   a batch that begins inside a strip starts with the strip's last two vertices,
///   shaded again.
///
/// ```
/// use stripkit::BatchModel;
/// let m = BatchModel::NVIDIA_H100;
/// // Two triangles sharing an edge: 4 vertices shaded, as a list or as a strip.
/// assert_eq!(m.list_invocations(&[0, 1, 2, 2, 1, 3]), 4);
/// assert_eq!(m.strip_invocations(&[0, 1, 2, 3], u32::MAX), 4);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BatchModel {
    /// Primitives per batch.
    pub max_triangles: usize,
    /// Shaded vertices per batch.
    pub max_vertices: usize,
    /// How far back a strip vertex can be reused: in shaded vertices when
    /// `strip_fifo`, else in indices.
    pub strip_window: usize,
    /// The strip window holds the last `strip_window` shaded vertices (a FIFO), not
    /// the last indices.
    pub strip_fifo: bool,
    /// The window (counted as `strip_window`) for the first two indices of a strip
    /// after a restart; at most `strip_window` (`strip_window` itself: no difference).
    pub restart_window: usize,
}

impl BatchModel {
    /// The model fitted to an NVIDIA H100: batches of 30 triangles and 32 shaded
    /// vertices, strips reusing the last 15 shaded vertices (the fit and its error:
    /// docs/experiments/gpu/h100-model-fit.md).
    pub const NVIDIA_H100: BatchModel = BatchModel {
        max_triangles: 30,
        max_vertices: 32,
        strip_window: 15,
        strip_fifo: true,
        restart_window: 15,
    };

    /// What the `batch` stripifier plans for by default ([`crate::Algorithm::batch`]):
    /// [`BatchModel::NVIDIA_H100`] with a reuse window of 14, 10 for the first two
    /// indices of a strip, which shaded the fewest vertices on a real GPU of the
    /// windows tried (docs/experiments/gpu-batch-strips.md).
    pub const NVIDIA_H100_PLANNING: BatchModel = BatchModel {
        strip_window: 14,
        restart_window: 10,
        ..BatchModel::NVIDIA_H100
    };

    /// Vertex-shader invocations the model predicts for a triangle list (`indices` in
    /// threes; a trailing partial triangle is ignored).
    pub fn list_invocations(&self, indices: &[u32]) -> u64 {
        let mut total = 0u64;
        let mut batch: Vec<u32> = Vec::with_capacity(self.max_vertices);
        let mut tris = 0;
        for t in indices.chunks_exact(3) {
            let fresh = |k: usize, v: &u32, batch: &[u32]| !batch.contains(v) && !t[..k].contains(v);
            let new = t.iter().enumerate().filter(|&(k, v)| fresh(k, v, &batch)).count();
            if tris == self.max_triangles || batch.len() + new > self.max_vertices {
                batch.clear();
                tris = 0;
            }
            for (k, &v) in t.iter().enumerate() {
                if fresh(k, &v, &batch) {
                    batch.push(v);
                    total += 1;
                }
            }
            tris += 1;
        }
        total
    }

    /// Vertex-shader invocations the model predicts for a strip buffer whose strips
    /// are separated by `restart` (primitive restart).
    pub fn strip_invocations(&self, indices: &[u32], restart: u32) -> u64 {
        let mut sim = StripBatches::new(*self);
        for &i in indices {
            if i == restart {
                sim.restart();
            } else {
                sim.push(i);
            }
        }
        sim.total
    }
}

/// [`BatchModel`]'s strip rule as a running simulation, one index at a time (the
/// batch stripifier plans with the very rule that measures it).
#[derive(Clone, Debug)]
pub(crate) struct StripBatches {
    model: BatchModel,
    /// The batch's history: its shaded vertices (FIFO window) or its indices.
    hist: Vec<u32>,
    shaded: usize,
    /// Triangles of the batch (degenerate ones included).
    pub(crate) tris: usize,
    /// Indices of the running strip.
    run: usize,
    last2: [u32; 2],
    /// Vertices shaded so far, all batches.
    pub(crate) total: u64,
}

impl StripBatches {
    pub(crate) fn new(model: BatchModel) -> Self {
        StripBatches {
            model,
            hist: Vec::with_capacity(2 * model.max_vertices.max(model.max_triangles + 2)),
            shaded: 0,
            tris: 0,
            run: 0,
            last2: [u32::MAX; 2],
            total: 0,
        }
    }

    /// A primitive restart: the next index starts a strip (same batch).
    pub(crate) fn restart(&mut self) {
        self.run = 0;
    }

    /// Whether `i` is in the batch's reuse window: the next index would reuse it (as
    /// long as no new batch begins first).
    pub(crate) fn reused(&self, i: u32) -> bool {
        let m = self.model;
        let w = if self.run < 2 { m.restart_window.min(m.strip_window) } else { m.strip_window };
        self.hist.iter().rev().take(w).any(|&h| h == i)
    }

    /// Feeds one index of the running strip.
    pub(crate) fn push(&mut self, i: u32) {
        let m = self.model;
        // Whether the window (of the batch before any break) holds `i`: this decides
        // whether `i` enters the history, as in the fitted model.
        let before = self.reused(i);
        let mut reused = before;
        let makes_tri = self.run >= 2;
        if (makes_tri && self.tris == m.max_triangles) || (!reused && self.shaded == m.max_vertices) {
            // New batch: the running strip's last two vertices come again, shaded.
            self.hist.clear();
            self.shaded = 0;
            self.tris = 0;
            if self.run >= 2 {
                for v in self.last2 {
                    self.hist.push(v);
                    self.shaded += 1;
                    self.total += 1;
                }
            }
            reused = self.reused(i);
        }
        if !reused {
            self.shaded += 1;
            self.total += 1;
        }
        if !m.strip_fifo || !before {
            self.hist.push(i);
        }
        if makes_tri {
            self.tris += 1;
        }
        self.last2 = [self.last2[1], i];
        self.run += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_past_the_vertex_count_and_huge_caches_are_counted() {
        let tris = [[0, 1, 2], [1, 2, 3], [0, 3, 4], [0, 1, 4]];
        for kind in [CacheKind::Fifo, CacheKind::Lru] {
            let right = cache_misses(&tris, 5, 3, kind);
            assert_eq!(cache_misses(&tris, 2, 3, kind), right);
            assert_eq!(cache_misses(&tris, 0, 3, kind), right);
            // Every vertex misses once and never again.
            assert_eq!(cache_misses(&tris, 5, usize::MAX, kind), 5);
        }
    }

    #[test]
    fn fifo_against_a_hand_computed_sequence() {
        // Cache of 3. Vertices: 0 1 2 | 1 2 3 | 0 3 4 | 0 1 4
        // 0m 1m 2m [0 1 2] | 1h 2h 3m [1 2 3] | 0m [2 3 0] 3h 4m [3 0 4] | 0h 1m [0 4 1] 4h
        let tris = [[0, 1, 2], [1, 2, 3], [0, 3, 4], [0, 1, 4]];
        assert_eq!(cache_misses(&tris, 5, 3, CacheKind::Fifo), 7);
        // LRU of 3: 0 1 2 -> [2 1 0]; 1h [1 2 0]; 2h [2 1 0]; 3m [3 2 1]; 0m [0 3 2];
        // 3h [3 0 2]; 4m [4 3 0]; 0h [0 4 3]; 1m [1 0 4]; 4h.
        assert_eq!(cache_misses(&tris, 5, 3, CacheKind::Lru), 7);
        // FIFO keeps 0 at the back after its hit, LRU refreshes it: they differ here.
        let tris = [[0, 1, 2], [0, 3, 4], [0, 5, 6]];
        // FIFO 4: 0m1m2m [0 1 2]; 0h 3m [0 1 2 3] 4m [1 2 3 4]; 0m [2 3 4 0] 5m [3 4 0 5] 6m
        assert_eq!(cache_misses(&tris, 7, 4, CacheKind::Fifo), 8);
        // LRU 4: 0m 1m 2m [2 1 0]; 0h [0 2 1]; 3m [3 0 2 1]; 4m [4 3 0 2]; 0h [0 4 3 2];
        // 5m [5 0 4 3]; 6m.
        assert_eq!(cache_misses(&tris, 7, 4, CacheKind::Lru), 7);
        assert_eq!(acmr(&[], 0, 16, CacheKind::Fifo), 0.0);
    }

    /// A plain FIFO, for comparison: the entries, oldest first.
    fn naive_touch(q: &mut std::collections::VecDeque<u32>, size: usize, v: u32) -> bool {
        if q.contains(&v) {
            return false;
        }
        if q.len() == size {
            q.pop_front();
        }
        q.push_back(v);
        true
    }

    #[test]
    fn fifo_matches_a_plain_queue_through_snapshots_loads_and_rebases() {
        let mut next = crate::test_support::xorshift(0x5DEE_CE66_D1CE_4E5Bu64);
        for round in 0..60 {
            let size = 1 + round % 7;
            let vc = 2 + (round * 3) % 20;
            let mut f = Fifo::new(size as u32, vc);
            if round % 3 == 1 {
                // Close to the rebase: it happens during the round.
                f.clock = REBASE_AT - 50;
                f.stamp.fill(0);
            }
            let mut q = std::collections::VecDeque::new();
            let mut saved: Option<(Vec<u32>, std::collections::VecDeque<u32>)> = None;
            let mut loaded = false;
            for step in 0..400 {
                let v = next(vc as u32);
                assert_eq!(f.touch(v), naive_touch(&mut q, size, v), "round {round} step {step}");
                for w in 0..vc as u32 {
                    assert_eq!(f.contains(w), q.contains(&w));
                }
                // A load pushes the empty entries of its snapshot too.
                if !loaded {
                    let live = f.len() as usize;
                    assert_eq!(live, q.len());
                    for i in 0..live {
                        assert_eq!(f.newest(i as u32), q[q.len() - 1 - i]);
                    }
                }
                match step % 97 {
                    13 => {
                        let mut snap = vec![0; size];
                        f.snapshot(&mut snap);
                        assert!(f.matches(&snap));
                        saved = Some((snap, q.clone()));
                    }
                    71 => {
                        if let Some((snap, sq)) = &saved {
                            f.load(snap);
                            q = sq.clone();
                            loaded = true;
                            assert!(f.matches(snap));
                        }
                    }
                    _ => {}
                }
            }
        }
    }

    #[test]
    fn cache_larger_than_the_vertices_never_evicts() {
        let tris = [[0, 1, 2], [2, 1, 0], [1, 2, 0]];
        assert_eq!(cache_misses(&tris, 3, usize::MAX, CacheKind::Fifo), 3);
        assert_eq!(cache_misses(&tris, 3, 2, CacheKind::Fifo), 7);
    }
}

//! Figures of METRICS.md: strip counts, index counts per join, swaps, vertex-cache
//! miss ratios (FIFO as METRICS.md defines it, LRU as an option), and the verdict of
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
    /// (the model of METRICS.md and of most post-transform caches).
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
/// an initially empty cache. `vertex_count` must exceed every index. O(n) for FIFO,
/// O(n * size) for LRU.
pub fn cache_misses(
    triangles: &[[u32; 3]],
    vertex_count: usize,
    cache_size: usize,
    kind: CacheKind,
) -> usize {
    if cache_size == 0 {
        return triangles.len() * 3;
    }
    let mut misses = 0usize;
    match kind {
        CacheKind::Fifo => {
            // A vertex is cached while fewer than `cache_size` misses followed its own:
            // `clock - pushed_at[v] - 1` pushes came after it.
            let mut pushed_at = vec![0u64; vertex_count];
            let mut clock = cache_size as u64 + 1; // stamps of 0 read as "long evicted"
            for t in triangles {
                for &v in t {
                    let v = v as usize;
                    if clock - pushed_at[v] > cache_size as u64 {
                        pushed_at[v] = clock;
                        clock += 1;
                        misses += 1;
                    }
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
        for w in s.windows(3) {
            if w[0] == w[1] || w[1] == w[2] || w[2] == w[0] {
                n += 1;
            }
        }
    }
    n
}

/// Every figure of METRICS.md for one strip set.
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
    let decoded = strip::decode(strips);
    let v = strip::verify_triangles(input, &decoded);
    let vertex_count = strips.vertex_bound();
    let n_strips = strips.len();
    let indices_separate = strips.index_count();
    let indices_restart = strips.restart_len();
    Figures {
        triangles: v.expected,
        dropped_degenerate: v.dropped_degenerate,
        strips: n_strips,
        swaps: swaps(strips),
        indices_separate,
        indices_restart,
        indices_degenerate: strip::stitched_len(strips),
        indices_per_triangle: if v.expected == 0 {
            0.0
        } else {
            indices_restart as f64 / v.expected as f64
        },
        acmr16: acmr(&decoded, vertex_count, 16, CacheKind::Fifo),
        acmr32: acmr(&decoded, vertex_count, 32, CacheKind::Fifo),
        cache,
        acmr: acmr(&decoded, vertex_count, cache.size, cache.kind),
        verified: v.ok(),
        winding_preserved: v.flipped == 0,
        lost: v.lost,
        added: v.added,
        flipped: v.flipped,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}

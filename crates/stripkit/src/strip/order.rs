//! The check's ordering of canonical triangle lists in linear time.
//!
//! [`sort_triangles`] gives exactly the slice `sort_unstable` gives (ascending
//! `[u32; 3]`), so the comparison after it sees the same lists and reaches the same
//! verdicts; it only gets there without an O(n log n) sort. A canonical triangle's
//! first index is its lowest, so the list is bucketed by that vertex (counting sorts,
//! coarse then fine, the elements moved in place by cycles: no second list), and each
//! bucket, a vertex's own triangles (a handful on a mesh), is then sorted on its own.

use crate::parallel::{fill_parts, Threads};

/// Lists shorter than this are sorted by comparison (faster than counting there).
const SMALL: usize = 1024;

/// Coarse buckets at most: the first pass moves triangles among this many write
/// positions only, so its moves stay within a few hundred cache lines and pages
/// instead of one per vertex.
const COARSE: usize = 256;

/// Sorts `v` ascending (the same slice as `v.sort_unstable()`), in O(n + V) where V
/// is the largest first index plus one, plus the buckets' own small sorts. Meant for
/// canonical triangles (lowest index first), where a bucket is one vertex's
/// triangles; any list comes out sorted. Two counting passes, both moving triangles
/// in place: by the first index's high bits into at most 256 coarse buckets, then,
/// within each coarse bucket (a few hundred kilobytes on a mesh of millions), by the
/// first index itself, each vertex's bucket then sorted on its own. Lists whose first
/// indices are sparse (V above 2n + 1024) or short fall back to a comparison sort.
/// The coarse buckets are finished in parallel when `threads` allows: the same slice
/// at any thread count.
pub(crate) fn sort_triangles(threads: Threads, v: &mut [[u32; 3]]) {
    let n = v.len();
    let keys = v.iter().map(|t| t[0] as usize + 1).max().unwrap_or(0);
    if n < SMALL || n >= u32::MAX as usize || keys > 2 * n + 1024 {
        crate::parallel::sort_unstable(threads, v);
        return;
    }
    let mut shift = 0;
    while (keys - 1) >> shift >= COARSE {
        shift += 1;
    }
    let starts = bucket_starts(v, (keys - 1) >> shift, |t| t[0] as usize >> shift);
    place(v, &starts, |t| t[0] as usize >> shift);
    let part_starts: Vec<usize> = starts[..starts.len() - 1].iter().map(|&s| s as usize).collect();
    fill_parts(threads, v, &part_starts, |c, part| {
        let base = c << shift;
        let local = |t: &[u32; 3]| t[0] as usize - base;
        let fine = bucket_starts(part, (1 << shift) - 1, local);
        place(part, &fine, local);
        for k in 0..fine.len() - 1 {
            let (lo, hi) = (fine[k] as usize, fine[k + 1] as usize);
            if hi - lo > 1 {
                part[lo..hi].sort_unstable();
            }
        }
    });
}

/// `starts[k]..starts[k + 1]`: where bucket `k` (keys `0..=last`) lies once placed.
fn bucket_starts(v: &[[u32; 3]], last: usize, key: impl Fn(&[u32; 3]) -> usize) -> Vec<u32> {
    let mut starts = vec![0u32; last + 2];
    for t in v {
        starts[key(t) + 1] += 1;
    }
    for k in 0..=last {
        starts[k + 1] += starts[k];
    }
    starts
}

/// Moves every triangle into its bucket in place: each one moves at most once to a
/// slot of its own bucket, following cycles (an American flag sort).
fn place(v: &mut [[u32; 3]], starts: &[u32], key: impl Fn(&[u32; 3]) -> usize) {
    let buckets = starts.len() - 1;
    // next[k]: the first slot of bucket k not yet holding one of its own.
    let mut next: Vec<u32> = starts[..buckets].to_vec();
    for b in 0..buckets {
        let end = starts[b + 1] as usize;
        for i in next[b] as usize..end {
            let mut t = v[i];
            loop {
                let k = key(&t);
                if k == b {
                    break;
                }
                let j = next[k] as usize;
                next[k] += 1;
                std::mem::swap(&mut t, &mut v[j]);
            }
            v[i] = t;
        }
        next[b] = end as u32;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(list: Vec<[u32; 3]>) {
        let mut want = list.clone();
        want.sort_unstable();
        for threads in [Threads::SERIAL, Threads::new(2), Threads::new(3)] {
            let mut got = list.clone();
            sort_triangles(threads, &mut got);
            assert_eq!(got, want, "{threads} threads, {} triangles", list.len());
        }
    }

    #[test]
    fn the_same_slice_as_a_comparison_sort() {
        let mut next = crate::test_support::xorshift(0x9e37_79b9_7f4a_7c15);
        // Dense canonical triangles (a mesh's shape: n/2 vertices), with repeats,
        // shuffled; short lists; sparse first indices (the comparison fallback); one
        // vertex in every triangle (a fan: one big bucket); a list over several parts.
        for (n, vertices) in [(5_000, 2_500), (300, 150), (3_000, 1 << 30), (200_000, 100_000)] {
            let list: Vec<[u32; 3]> = (0..n)
                .map(|_| {
                    let mut t = [next(vertices), next(vertices), next(vertices)];
                    t.sort_unstable();
                    if next(2) == 0 {
                        t.swap(1, 2);
                    }
                    t
                })
                .collect();
            check(list);
        }
        let fan: Vec<[u32; 3]> = (0..4_000).map(|i| [0, (i * 7919) % 4_001 + 1, (i * 104_729) % 4_001 + 1]).collect();
        check(fan);
        let mut repeats: Vec<[u32; 3]> = (0..3_000).map(|i| [i % 10, i % 10 + 1, i % 10 + 2]).collect();
        repeats.reverse();
        check(repeats);
        check(Vec::new());
    }
}

//! The check's ordering of canonical triangle lists in linear time.
//!
//! [`sort_triangles`] gives exactly the slice `sort_unstable` gives (ascending
//! `[u32; 3]`), so the comparison after it sees the same lists and reaches the same
//! verdicts; it only gets there without an O(n log n) sort. A canonical triangle's
//! first index is its lowest, so the list is bucketed by that vertex (counting sorts
//! on its bits, most significant first, the elements moved in place by cycles: no
//! second list), and each vertex's own triangles (a handful on a mesh) are then
//! sorted on their own.
//!
//! What keeps the time per triangle flat from thousands to millions of triangles is
//! where the moves land. An in-place pass moves each triangle to its bucket's next
//! free slot and takes the next one to move from that same slot: a chain of
//! dependent loads, each a cache miss once the list outgrows the caches. So the
//! check's two lists are not copied and then sorted: [`sorted_from`] writes each
//! triangle straight into its coarse bucket as it is decoded or read (a scatter,
//! whose stores do not wait on each other), and the in-place first pass that remains
//! (for lists handed over whole) asks for each bucket's next cache lines ahead. The
//! later passes run inside one coarse bucket (a few hundred kilobytes) on at most 10
//! bits at a time, so their write positions stay in the first-level caches at any
//! mesh size; the coarse buckets (256, up to 4,096 from a million vertices on) are
//! chosen so that a mesh of up to 4 million vertices takes two passes in all.

use crate::hint::prefetch;
use crate::parallel::{fill_parts, Threads};

/// Lists shorter than this are sorted by comparison (faster than counting there).
const SMALL: usize = 1024;

/// Bits of the first index the first pass buckets on, at most, while the bits under
/// them fit one later pass: 256 coarse buckets, the parts the later passes finish (in
/// parallel when allowed).
const COARSE_BITS: u32 = 8;

/// Bits of the first index the first pass buckets on at most when the rest would
/// not fit one later pass.
const MAX_COARSE_BITS: u32 = 12;

/// Bits one later pass buckets on at most when one pass finishes the key; above
/// that the key is cut into passes of at most [`DIGIT_BITS`].
const LAST_BITS: u32 = 10;

/// Bits of a later pass that is not the last one, at most.
const DIGIT_BITS: u32 = 9;

/// Buckets of this many triangles or fewer are sorted by comparison.
const TINY: usize = 16;

/// How far ahead of a bucket's write position the first pass asks for the list's
/// cache lines (16 triangles: 3 lines).
const AHEAD: usize = 16;

/// Sorts `v` ascending (the same slice as `v.sort_unstable()`), in O(n + V) where V
/// is the largest first index plus one, plus the vertices' own small sorts. Meant for
/// canonical triangles (lowest index first), where a bucket is one vertex's
/// triangles; any list comes out sorted. Counting passes on the first index, most
/// significant bits first, each moving triangles in place: into coarse buckets, then,
/// within each, passes of at most 10 bits down to single vertices, each vertex's
/// triangles then sorted on their own. Lists whose first indices are sparse (V above
/// 2n + 1024) or short fall back to a comparison sort. The coarse buckets are
/// finished in parallel when `threads` allows: the same slice at any thread count.
pub(crate) fn sort_triangles(threads: Threads, v: &mut [[u32; 3]]) {
    let n = v.len();
    let keys = v.iter().map(|t| t[0] as usize + 1).max().unwrap_or(0);
    if !counting_pays(n, keys) {
        crate::parallel::sort_unstable(threads, v);
        return;
    }
    let shift = coarse_shift(keys);
    let key = |t: &[u32; 3]| (t[0] >> shift) as usize;
    let starts = bucket_starts(v, ((keys - 1) >> shift) + 1, key);
    place(v, &starts, key, AHEAD);
    finish_coarse(threads, v, &starts, shift);
}

/// Triangles that can be walked more than once, the same ones each time: what
/// [`sorted_from`] gathers.
pub(crate) trait Source {
    /// Calls `emit` with every triangle, canonical (lowest index first).
    fn for_each(&self, emit: impl FnMut([u32; 3]));
}

/// The triangles of `source` in a list of their own, sorted as [`sort_triangles`]
/// sorts (the same list as collecting them and calling `sort_unstable`). `keys` is
/// above every triangle's first index (the largest index plus one will do). The
/// source is walked twice, counting then writing each triangle straight into its
/// coarse bucket, so the list is written once, by a scatter whose stores do not wait
/// on each other (the in-place first pass is a chain of dependent loads), and no
/// unsorted copy is ever made; the buckets are then finished as in
/// [`sort_triangles`]. Short or sparse sources are collected and sorted by comparison.
pub(crate) fn sorted_from(threads: Threads, source: &impl Source, keys: usize) -> Vec<[u32; 3]> {
    let shift = coarse_shift(keys.max(1));
    let key = |t: &[u32; 3]| (t[0] >> shift) as usize;
    let mut starts = vec![0u32; ((keys.max(1) - 1) >> shift) + 2];
    let mut n = 0usize;
    source.for_each(|t| {
        starts[key(&t) + 1] += 1;
        n += 1;
    });
    if !counting_pays(n, keys) {
        let mut v = Vec::with_capacity(n);
        source.for_each(|t| v.push(t));
        crate::parallel::sort_unstable(threads, &mut v);
        return v;
    }
    prefix_sums(&mut starts);
    let mut v = vec![[0u32; 3]; n];
    let mut next: Vec<u32> = starts[..starts.len() - 1].to_vec();
    source.for_each(|t| {
        let k = key(&t);
        let j = next[k] as usize;
        next[k] += 1;
        if let Some(later) = v.get(j + AHEAD) {
            prefetch(later);
        }
        v[j] = t;
    });
    finish_coarse(threads, &mut v, &starts, shift);
    v
}

/// How far the first pass shifts first indices below `keys` (at least 1): 256 coarse
/// buckets, or, when the bits under those would not fit one later pass, up to 4,096,
/// so that a mesh of up to 4 million vertices takes two passes in all.
fn coarse_shift(keys: usize) -> u32 {
    let bits = usize::BITS - (keys - 1).leading_zeros();
    let top = if bits <= COARSE_BITS + LAST_BITS { bits.min(COARSE_BITS) } else { (bits - LAST_BITS).min(MAX_COARSE_BITS) };
    bits - top
}

/// Finishes each coarse bucket (`starts`, first indices shifted by `shift`), in
/// parallel when `threads` allows.
fn finish_coarse(threads: Threads, v: &mut [[u32; 3]], starts: &[u32], shift: u32) {
    let part_starts: Vec<usize> = starts[..starts.len() - 1].iter().map(|&s| s as usize).collect();
    fill_parts(threads, v, &part_starts, |c, part| finish(part, (c as u32) << shift, shift));
}

/// Sorts `v`, whose first indices all lie in `base..base + 2^bits`: by passes on
/// those bits (most significant first, at most [`LAST_BITS`] in one), then each
/// vertex's triangles on their own.
fn finish(v: &mut [[u32; 3]], base: u32, bits: u32) {
    if v.len() <= 1 {
        return;
    }
    if bits == 0 || v.len() <= TINY {
        v.sort_unstable();
        return;
    }
    let width = if bits <= LAST_BITS { bits } else { bits.div_ceil(bits.div_ceil(DIGIT_BITS)) };
    let shift = bits - width;
    let key = |t: &[u32; 3]| ((t[0] - base) >> shift) as usize;
    let starts = bucket_starts(v, 1 << width, key);
    place(v, &starts, key, 0);
    for k in 0..starts.len() - 1 {
        let (lo, hi) = (starts[k] as usize, starts[k + 1] as usize);
        finish(&mut v[lo..hi], base + ((k as u32) << shift), shift);
    }
}

/// `starts[k]..starts[k + 1]`: where bucket `k` (of `buckets`) lies once placed.
fn bucket_starts(v: &[[u32; 3]], buckets: usize, key: impl Fn(&[u32; 3]) -> usize) -> Vec<u32> {
    let mut starts = vec![0u32; buckets + 1];
    for t in v {
        starts[key(t) + 1] += 1;
    }
    prefix_sums(&mut starts);
    starts
}

/// Turns per-bucket counts (bucket `k`'s in `starts[k + 1]`, `starts[0]` = 0) into
/// where each bucket starts.
fn prefix_sums(starts: &mut [u32]) {
    for k in 1..starts.len() {
        starts[k] += starts[k - 1];
    }
}

/// Whether `n` triangles with first indices below `keys` are worth counting sorts:
/// not a short list (a comparison sort is faster there), not sparse first indices
/// (`keys` above 2n + 1024), and counts that fit `u32`.
fn counting_pays(n: usize, keys: usize) -> bool {
    n >= SMALL && n < u32::MAX as usize && keys <= 2 * n + 1024
}

/// Moves every triangle into its bucket in place: each one moves at most once to a
/// slot of its own bucket, following cycles (an American flag sort). With `ahead`
/// above 0, each move asks for the list `ahead` triangles past the slot it takes, the
/// bucket's next cache lines (a pass over a list larger than the caches).
fn place(v: &mut [[u32; 3]], starts: &[u32], key: impl Fn(&[u32; 3]) -> usize, ahead: usize) {
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
                if ahead > 0 {
                    if let Some(later) = v.get(j + ahead) {
                        prefetch(later);
                    }
                }
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

    /// A list as a [`Source`], walked in its own order.
    struct Listed<'a>(&'a [[u32; 3]]);

    impl Source for Listed<'_> {
        fn for_each(&self, emit: impl FnMut([u32; 3])) {
            self.0.iter().copied().for_each(emit);
        }
    }

    fn check(list: Vec<[u32; 3]>) {
        let mut want = list.clone();
        want.sort_unstable();
        // The bound gathering takes: exact (largest first index + 1) or loose (largest
        // index of all + 1, what the check passes).
        let exact = list.iter().map(|t| t[0] as usize + 1).max().unwrap_or(0);
        let loose = list.as_flattened().iter().map(|&i| i as usize + 1).max().unwrap_or(0);
        for threads in [Threads::SERIAL, Threads::new(2), Threads::new(3)] {
            let mut got = list.clone();
            sort_triangles(threads, &mut got);
            assert_eq!(got, want, "{threads} threads, {} triangles", list.len());
            for keys in [exact, loose] {
                let gathered = sorted_from(threads, &Listed(&list), keys);
                assert_eq!(gathered, want, "gathered, {threads} threads, {} triangles, keys {keys}", list.len());
            }
        }
    }

    #[test]
    fn the_same_slice_as_a_comparison_sort() {
        let mut next = crate::test_support::xorshift(0x9e37_79b9_7f4a_7c15);
        // Dense canonical triangles (a mesh's shape: n/2 vertices), with repeats,
        // shuffled; short lists; sparse first indices (the comparison fallback); one
        // vertex in every triangle (a fan: one big bucket); a list over several parts.
        // The last list has 300,000 vertices (19 bits): a first pass of 512 buckets.
        for (n, vertices) in [(5_000, 2_500), (300, 150), (3_000, 1 << 30), (200_000, 100_000), (600_000, 300_000)] {
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

    #[test]
    fn later_passes_cut_wide_keys_into_digits() {
        // 21 bits under one coarse bucket: three passes of 7 bits, then the vertices'
        // own sorts; the same slice as a comparison sort.
        let mut next = crate::test_support::xorshift(0x2545_f491_4f6c_dd1d);
        let base = 5 << 21;
        let list: Vec<[u32; 3]> =
            (0..60_000).map(|_| [base + next(1 << 21), next(1 << 30), next(1 << 30)]).collect();
        let mut want = list.clone();
        want.sort_unstable();
        let mut got = list;
        finish(&mut got, base, 21);
        assert_eq!(got, want);
    }
}

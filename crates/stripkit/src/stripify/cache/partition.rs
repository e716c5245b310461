//! The partitioned mode of the cache stripifier, for big meshes: the canonical
//! triangle list (sorted by its lowest vertex, vertices in Z-order, so that a range of
//! it is a spatially coherent patch) is cut into ranges of about [`PART_TRIANGLES`]
//! triangles, each range is stripified on its own (in parallel when threads allow),
//! and the parts' strips are put back in order and joined across the part borders
//! where one part's last strip ends on the vertex the next part's first strip starts
//! with ([`join_shared_ends`]).
//!
//! The cut depends on the triangle count only, never on the thread count, so the
//! strips are the same at any thread count.

use super::{run_once, CacheOptions};
use crate::strip::{join_shared_ends, StripSet};

/// Triangles per part, about: the `n` triangles are cut into `ceil(n / PART_TRIANGLES)`
/// ranges of equal size (within one).
pub const PART_TRIANGLES: usize = 1 << 18;

/// The ranges of `n` triangles the partitioned mode stripifies on their own: one range
/// when `n <= above` or `above == 0`, else `ceil(n / PART_TRIANGLES)` ranges of equal
/// size (within one), in order.
pub fn parts(n: usize, above: u32) -> Vec<std::ops::Range<usize>> {
    parts_of(n, above, PART_TRIANGLES)
}

/// [`parts`] with parts of about `size` triangles.
fn parts_of(n: usize, above: u32, size: usize) -> Vec<std::ops::Range<usize>> {
    if above == 0 || n <= above as usize {
        return vec![0..n];
    }
    let k = n.div_ceil(size.max(1)).max(1);
    (0..k).map(|i| i * n / k..(i + 1) * n / k).collect()
}

/// One part stripified: its triangles renumbered onto the vertices they use (in the
/// same order, so the stripifier sees the same relative order as in the whole mesh),
/// run, and the strips mapped back to the mesh's vertex ids. Returns the strips and
/// their misses in the part's own FIFO (started empty).
fn run_part(tris: &[[u32; 3]], options: &CacheOptions) -> (StripSet, u64) {
    // The part's vertices, numbered in their order: a dense map over the span of its
    // ids (a range of the Z-order, mostly), O(span + triangles).
    let lo = tris.iter().flatten().copied().min().unwrap_or(0);
    let hi = tris.iter().flatten().copied().max().unwrap_or(0);
    let mut local = vec![u32::MAX; (hi - lo) as usize + 1];
    for &v in tris.iter().flatten() {
        local[(v - lo) as usize] = 0;
    }
    let mut verts: Vec<u32> = Vec::new();
    for (i, l) in local.iter_mut().enumerate() {
        if *l == 0 {
            *l = verts.len() as u32;
            verts.push(lo + i as u32);
        }
    }
    let part: Vec<[u32; 3]> = tris
        .iter()
        .map(|t| t.map(|v| local[(v - lo) as usize]))
        .collect();
    drop(local);
    let (mut strips, misses) = run_once(&part, None, verts.len(), options);
    for v in &mut strips.indices {
        *v = verts[*v as usize];
    }
    (strips, misses)
}

/// The partitioned run over the canonical triangles `tris` (see the module docs):
/// the strips, and the sum of the parts' misses (each part's FIFO started empty; the
/// figures measure the joined output's real FIFO).
pub fn run_parted(
    tris: &[[u32; 3]],
    ranges: &[std::ops::Range<usize>],
    options: &CacheOptions,
    threads: crate::parallel::Threads,
) -> (StripSet, u64) {
    let done = crate::parallel::map_ordered(threads, ranges, |r| run_part(&tris[r.clone()], options));
    let mut out = StripSet::new();
    let mut misses = 0;
    out.indices.reserve(done.iter().map(|(s, _)| s.indices.len()).sum());
    for (s, m) in done {
        misses += m;
        let base = out.indices.len() as u32;
        out.indices.extend_from_slice(&s.indices);
        out.offsets.extend(s.offsets[1..].iter().map(|&o| o + base));
    }
    // Within a part the strips are joined already; this joins across the borders.
    join_shared_ends(&mut out);
    (out, misses)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parallel::Threads;
    use crate::strip::verify;

    #[test]
    fn parts_cover_the_triangles_in_order_and_depend_on_the_count_only() {
        assert_eq!(parts_of(10, 0, 3), vec![0..10]);
        assert_eq!(parts_of(10, 10, 3), vec![0..10]);
        assert_eq!(parts_of(10, 9, 3), vec![0..2, 2..5, 5..7, 7..10]);
        assert_eq!(parts(1_000_000, 1).len(), 4);
        assert_eq!(parts(PART_TRIANGLES, 1), vec![0..PART_TRIANGLES]);
    }

    #[test]
    fn the_default_threshold_cuts_only_meshes_above_a_million_triangles() {
        // The door's default: every shared model (at most 100,000 triangles) and every
        // test mesh stays whole; a mesh just above the threshold gets four parts.
        let above = crate::DEFAULT_PARTITION_ABOVE;
        assert_eq!(crate::StripOptions::default().partition_above, above);
        assert_eq!(parts(1_000_000, above), vec![0..1_000_000]);
        assert_eq!(parts(1_000_001, above).len(), 4);
        assert_eq!(parts(4_444_864, above).len(), 17);
    }

    #[test]
    fn small_parts_verify_and_are_the_same_at_any_thread_count() {
        // A shuffled grid with random diagonals in ranges of 300 triangles: every
        // output verified, the same strips at 1, 2 and 4 threads, and the borders
        // costing a few indices against the whole-list run.
        let (tris, vc) = crate::test_support::random_diagonals(60, 40, 3);
        let o = CacheOptions::cache(16);
        let ranges = parts_of(tris.len(), 1, 300);
        assert_eq!(ranges.len(), 16);
        let (one, misses) = run_parted(&tris, &ranges, &o, Threads::SERIAL);
        assert!(verify(&tris, &one).ok(), "{}", verify(&tris, &one));
        for n in [2, 4] {
            assert_eq!(run_parted(&tris, &ranges, &o, Threads::new(n)), (one.clone(), misses), "{n}");
        }
        let (whole, _) = run_once(&tris, None, vc, &o);
        let (a, b) = (one.restart_len() as f64, whole.restart_len() as f64);
        eprintln!("parts of 300: {a} indices, whole: {b}");
        assert!(a < b * 1.05, "{a} against {b}");
        // The parts' own FIFOs are counted: no fewer misses than the joined output has.
        let measured = crate::metrics::cache_misses(&crate::strip::decode(&one), vc, 16, crate::metrics::CacheKind::Fifo);
        assert!(measured as u64 <= misses, "{measured} > {misses}");
    }
}

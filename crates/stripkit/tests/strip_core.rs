//! The strip core: encoders round-trip, verify catches every kind of error, the figures
//! of a small mesh match values worked out by hand.

use proptest::prelude::*;
use stripkit::{
    cache_misses, decode, decode_restart, encode_restart, encode_separate, encode_stitched, figures, stitched_len,
    verify, CacheKind, CacheModel, StripSet, DEFAULT_RESTART,
};

/// The rotation of `t` that starts at its smallest index: equal for triangles that are
/// equal up to rotation.
fn canonical(t: [u32; 3]) -> [u32; 3] {
    let r = (0..3).min_by_key(|&i| t[i]).expect("three corners");
    [t[r], t[(r + 1) % 3], t[(r + 2) % 3]]
}

fn strip_sets() -> impl Strategy<Value = StripSet> {
    // Strips over vertices 0..40 (some with repeated indices, some shorter than 3).
    prop::collection::vec(prop::collection::vec(0u32..40, 0..12), 0..8)
        .prop_map(|strips| StripSet::from_strips(&strips))
}

proptest! {
    #[test]
    fn restart_round_trip(set in strip_sets()) {
        let buf = encode_restart(&set, DEFAULT_RESTART);
        prop_assert_eq!(buf.len(), (set.index_count() + set.len()).saturating_sub(1));
        let back = decode_restart(&buf, DEFAULT_RESTART);
        // A set of one empty strip encodes like no strip at all.
        if !(set.len() == 1 && set.index_count() == 0) {
            prop_assert_eq!(&back, &set);
        }
        prop_assert_eq!(decode(&back), decode(&set));
    }

    #[test]
    fn restart_round_trip_with_other_index(set in strip_sets()) {
        let buf = encode_restart(&set, 1000);
        prop_assert_eq!(decode(&decode_restart(&buf, 1000)), decode(&set));
    }

    #[test]
    fn stitched_draws_the_same_triangles(set in strip_sets()) {
        let one = encode_stitched(&set);
        prop_assert_eq!(one.len(), stitched_len(&set));
        let stitched = StripSet::from_strips(&[one]);
        // Same triangles up to rotation (a re-encoded strip may read from its other end).
        let canon = |s: &StripSet| {
            let mut v: Vec<[u32; 3]> = decode(s).into_iter().map(canonical).collect();
            v.sort_unstable();
            v
        };
        prop_assert_eq!(canon(&stitched), canon(&set));
        let v = verify(&decode(&set), &stitched);
        prop_assert!(v.ok(), "{}", v);
        // At most 3 extra indices per join (a strip re-encoded for an odd start may
        // also save a swap).
        let drawn: Vec<&[u32]> = set.iter().filter(|s| s.len() >= 3).collect();
        let base: usize = drawn.iter().map(|s| s.len()).sum();
        let joins = drawn.len().saturating_sub(1);
        prop_assert!(stitched_len(&set) <= base + 3 * joins);
    }

    #[test]
    fn separate_round_trip(set in strip_sets()) {
        let lists = encode_separate(&set);
        prop_assert_eq!(StripSet::from_strips(&lists), set);
    }

    #[test]
    fn verify_accepts_own_decoding_in_any_rotation(set in strip_sets(), rot in 0usize..3) {
        let mut tris = decode(&set);
        for t in &mut tris { t.rotate_left(rot); }
        tris.reverse();
        prop_assert!(verify(&tris, &set).ok());
    }
}

#[test]
fn verify_catches_lost_added_and_flipped() {
    // A 2x1 quad band: 0 1 2 over 3 4 5.
    let tris = [[0, 3, 1], [1, 3, 4], [1, 4, 2], [2, 4, 5]];
    let good = StripSet::from_strips(&[vec![0, 3, 1, 4, 2, 5]]);
    assert!(verify(&tris, &good).ok());

    let lost = StripSet::from_strips(&[vec![0, 3, 1, 4, 2]]);
    let v = verify(&tris, &lost);
    assert_eq!((v.lost, v.added, v.flipped, v.ok()), (1, 0, 0, false));

    let added = StripSet::from_strips(&[vec![0, 3, 1, 4, 2, 5], vec![7, 8, 9]]);
    let v = verify(&tris, &added);
    assert_eq!((v.lost, v.added, v.flipped, v.ok()), (0, 1, 0, false));

    // The same band started on the wrong foot: every triangle reversed.
    let flipped = StripSet::from_strips(&[vec![0, 0, 3, 1, 4, 2, 5]]);
    let v = verify(&tris, &flipped);
    assert_eq!((v.lost, v.added, v.flipped, v.ok()), (0, 0, 4, false));

    // A triangle drawn twice is an addition even though it is expected once.
    let twice = StripSet::from_strips(&[vec![0, 3, 1, 4, 2, 5], vec![0, 3, 1]]);
    let v = verify(&tris, &twice);
    assert_eq!((v.lost, v.added), (0, 1));

    // Degenerate expected triangles are not required, and are counted.
    let mut with_degenerate = tris.to_vec();
    with_degenerate.push([6, 6, 7]);
    let v = verify(&with_degenerate, &good);
    assert!(v.ok());
    assert_eq!(v.dropped_degenerate, 1);
}

#[test]
fn figures_of_a_hand_checked_mesh() {
    // Band of 4 triangles (0 1 2 over 3 4 5) drawn as one strip, a lone triangle
    // (6 7 8), a fan of 3 around vertex 9 drawn with one swap, and a degenerate input
    // triangle. The fan strip s = [10, 11, 9, 12, 9, 13]:
    //   0: (10,11,9) = (9,10,11) rotated
    //   1: (12, 9... odd: (s2,s1,s3) = (9,11,12)
    //   2: (9,12,9) degenerate (the swap)
    //   3: odd: (s4,s3,s5) = (9,12,13)
    let tris = [
        [0, 3, 1],
        [1, 3, 4],
        [1, 4, 2],
        [2, 4, 5],
        [6, 7, 8],
        [9, 10, 11],
        [9, 11, 12],
        [9, 12, 13],
        [5, 5, 6],
    ];
    let strips = StripSet::from_strips(&[
        vec![0, 3, 1, 4, 2, 5],
        vec![6, 7, 8],
        vec![10, 11, 9, 12, 9, 13],
    ]);
    let f = figures(&tris, &strips, CacheModel::lru(4));
    assert!(f.verified, "{f:?}");
    assert!(f.winding_preserved);
    assert_eq!(f.triangles, 8);
    assert_eq!(f.dropped_degenerate, 1);
    assert_eq!(f.strips, 3);
    assert_eq!(f.swaps, 1);
    assert_eq!(f.indices_separate, 6 + 3 + 6);
    assert_eq!(f.indices_restart, 15 + 2);
    // Stitch: 6 indices, then (even) +2 +3 = 11 (odd). At that odd position the fan is
    // re-encoded from its other end without a swap: [13, 12, 9, 11, 10] reads
    // (12,13,9) (12,9,11) (11,9,10) there. +2 +5 = 18.
    assert_eq!(f.indices_degenerate, 18);
    let one = encode_stitched(&strips);
    assert_eq!(one.len(), 18);
    assert!(verify(&tris, &StripSet::from_strips(&[one])).ok());
    assert!((f.indices_per_triangle - 17.0 / 8.0).abs() < 1e-12);
    // FIFO 16 never evicts here: every vertex 0..13 misses once: 14 / 8.
    assert!((f.acmr16 - 14.0 / 8.0).abs() < 1e-12);
    assert!((f.acmr32 - 14.0 / 8.0).abs() < 1e-12);
    // LRU 4 over the decoded order:
    // (0,3,1) 3m; (3,4,1)/(1,3,4) 4m; (1,4,2) 2m [2 4 1 3]; (2,4,5) 5m [5 4 2 1];
    // (6,7,8) 3m [8 7 6 5]; (10,11,9) 3m [9 11 10 8]; (9,11,12) 12m [12 11 9 10];
    // (9,12,13) 13m -> 3+1+1+1+3+3+1+1 = 14 misses.
    assert_eq!(f.cache.size, 4);
    assert!((f.acmr - 14.0 / 8.0).abs() < 1e-12);
    // FIFO of 3 by hand: 0 3 1 m [0 3 1]; 1h 3h 4m [3 1 4]; 1h 4h 2m [1 4 2];
    // 2h 4h 5m [4 2 5]; 6 7 8 m; 10 11 9 m [10 11 9]; 9h 11h 12m [11 9 12]; 9h 12h 13m.
    let order = decode(&strips);
    assert_eq!(cache_misses(&order, 14, 3, CacheKind::Fifo), 14);
    // FIFO of 1: only a vertex repeated right after itself hits: (0,3,1)(1,3,4): 1 hits.
    // 0 3 1 | 1h 3 4 | 1 4 2 | 2h 4 5 | 6 7 8 | 10 11 9 | 9h 11 12 | 9 12 13 -> 24 - 3.
    assert_eq!(cache_misses(&order, 14, 1, CacheKind::Fifo), 21);
}

#[test]
fn empty_input_gives_zero_figures() {
    let f = figures(&[], &StripSet::new(), CacheModel::default());
    assert!(f.verified);
    assert_eq!(
        (
            f.triangles,
            f.strips,
            f.indices_restart,
            f.indices_degenerate
        ),
        (0, 0, 0, 0)
    );
    assert_eq!(f.acmr16, 0.0);
    assert!(encode_restart(&StripSet::new(), 7).is_empty());
    assert!(encode_stitched(&StripSet::new()).is_empty());
}

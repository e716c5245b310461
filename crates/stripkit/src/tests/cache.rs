//! The cache-aware stripifier on raw triangle lists with its tuning knobs (moved from
//! `tests/cache_strips.rs`; what `stripify` gives on a mesh is tested there): every
//! output verified with its winding on procedural meshes, awkward topology, shuffled
//! inputs and (when present) the research meshes; shuffled input gives the figures of
//! ordered input; the bounded search, its refinement and tunnels.

use super::support::{grid, icosphere, shuffled, torus, Rng};
use crate::metrics::{self, CacheKind, CacheModel, Figures};
use crate::strip::{self, StripSet};
use crate::stripify::cache::{self, CacheOptions};
use crate::test_support::{model, models_dir};

/// Stripifies, verifies and checks the bookkeeping identities; returns the figures.
fn check(tris: &[[u32; 3]], vertex_count: usize, o: &CacheOptions) -> (StripSet, Figures) {
    let strips = cache::stripify(tris, vertex_count, o);
    let f = metrics::figures(tris, &strips, CacheModel::fifo(16));
    assert!(f.verified, "{o:?}: {}", strip::verify(tris, &strips));
    assert!(f.winding_preserved);
    if f.strips > 0 {
        assert_eq!(f.indices_separate, f.triangles + 2 * f.strips + f.swaps);
        assert_eq!(f.indices_restart, f.indices_separate + f.strips - 1);
    }
    (strips, f)
}

fn modes() -> Vec<CacheOptions> {
    let mut v = Vec::new();
    for n in [3, 8, 16, 32] {
        v.push(CacheOptions::cache(n));
        v.push(CacheOptions::balanced(n));
    }
    v.push(CacheOptions {
        max_swaps: 0,
        join: false,
        ..CacheOptions::cache(16)
    });
    v.push(CacheOptions {
        min_cached: 0,
        start_penalty: 0.0,
        ..CacheOptions::balanced(16)
    });
    v.push(CacheOptions {
        scan_entries: 1,
        max_len: 1,
        ..CacheOptions::cache(16)
    });
    v.push(CacheOptions {
        miss_weight: 0.0,
        max_len: 200,
        ..CacheOptions::cache(8)
    });
    v
}

#[test]
fn every_output_is_verified_on_procedural_meshes() {
    let mut rng = Rng(7);
    let meshes = vec![
        grid(1, 1),
        grid(17, 9),
        grid(40, 40),
        torus(24, 16, None),
        torus(30, 20, Some(&mut rng)),
        icosphere(3),
    ];
    for (tris, vc) in &meshes {
        for o in modes() {
            check(tris, *vc, &o);
            check(&shuffled(tris, *vc, &mut rng), *vc, &o);
        }
    }
}

#[test]
fn awkward_topology_is_kept_whole() {
    let cases: Vec<(Vec<[u32; 3]>, usize)> = vec![
        (vec![], 0),
        (vec![[0, 1, 2]], 3),
        // Degenerate triangles are dropped; the rest is kept.
        (vec![[0, 1, 1], [0, 1, 2], [2, 2, 2]], 3),
        // Three triangles on one edge, a flipped neighbour, a duplicate.
        (
            vec![[0, 1, 2], [1, 0, 3], [1, 0, 4], [1, 2, 5], [0, 1, 2]],
            6,
        ),
        // Two fans meeting at a pinch vertex.
        (
            vec![
                [0, 1, 2],
                [0, 2, 3],
                [0, 3, 1],
                [0, 4, 5],
                [0, 5, 6],
                [0, 6, 4],
            ],
            7,
        ),
        // Unreferenced vertices around.
        (vec![[5, 9, 7], [7, 9, 8]], 20),
    ];
    for (tris, vc) in &cases {
        for o in modes() {
            check(tris, *vc, &o);
        }
    }
}

#[test]
fn strips_run_side_by_side_on_a_torus() {
    // A regular torus of 64 x 48 quads: strips laid side by side keep both modes close
    // to the 0.5 floor of a closed mesh with few indices (a strip of 14 triangles with
    // its restart costs 1.21 per triangle).
    let (tris, vc) = torus(64, 48, None);
    let (_, c) = check(&tris, vc, &CacheOptions::cache(16));
    let (_, b) = check(&tris, vc, &CacheOptions::balanced(16));
    let t = c.triangles as f64;
    eprintln!(
        "cache {} {}, balanced {} {}",
        c.indices_restart, c.acmr, b.indices_restart, b.acmr
    );
    assert!(c.acmr < 0.62, "cache acmr16 {}", c.acmr);
    assert!(b.acmr < 0.67, "balanced acmr16 {}", b.acmr);
    assert!(b.indices_restart < c.indices_restart);
    assert!(
        (c.indices_restart as f64) < 1.40 * t,
        "cache {} indices",
        c.indices_restart
    );
    assert!(
        (b.indices_restart as f64) < 1.23 * t,
        "balanced {} indices",
        b.indices_restart
    );
}

#[test]
fn shuffled_input_gives_the_figures_of_ordered_input() {
    // A procedural mesh of bunny's size with irregular diagonals: faces shuffled,
    // rotated and vertices renumbered must give index counts and ACMR within 1%. (The
    // input order only breaks ties, but one different tie changes every later choice:
    // over eight shuffles the spread was 0.2-0.3% here, up to 2% on 19k triangles.)
    let mut rng = Rng(99);
    let (tris, vc) = torus(240, 160, Some(&mut rng));
    for o in [CacheOptions::cache(16), CacheOptions::balanced(16)] {
        let (_, a) = check(&tris, vc, &o);
        for seed in [1, 2] {
            let mut r = Rng(seed * 7919);
            let (_, b) = check(&shuffled(&tris, vc, &mut r), vc, &o);
            let rel = |x: f64, y: f64| (x - y).abs() / x;
            eprintln!(
                "{o:?}: ordered {} {} {}, shuffled {} {} {}",
                a.strips, a.indices_restart, a.acmr, b.strips, b.indices_restart, b.acmr
            );
            assert!(rel(a.indices_restart as f64, b.indices_restart as f64) < 0.01);
            assert!(rel(a.acmr, b.acmr) < 0.01);
        }
    }
}

#[test]
fn the_miss_weight_trades_misses_for_indices() {
    // On an irregular torus: the heavier a miss, the fewer misses and the more
    // indices; swaps and going on from the last strip both save indices, and the
    // swaps that keep a strip on the cached side save misses too.
    let mut rng = Rng(5);
    let (tris, vc) = torus(90, 70, Some(&mut rng));
    let t = tris.len() as f64;
    let (_, c) = check(&tris, vc, &CacheOptions::cache(16));
    let (_, b) = check(&tris, vc, &CacheOptions::balanced(16));
    let (_, no_swaps) = check(
        &tris,
        vc,
        &CacheOptions {
            max_swaps: 0,
            ..CacheOptions::cache(16)
        },
    );
    let (_, no_join) = check(
        &tris,
        vc,
        &CacheOptions {
            join: false,
            ..CacheOptions::cache(16)
        },
    );
    eprintln!(
        "cache {} {}, balanced {} {}, no swaps {} {}, no join {} {}",
        c.indices_restart,
        c.acmr,
        b.indices_restart,
        b.acmr,
        no_swaps.indices_restart,
        no_swaps.acmr,
        no_join.indices_restart,
        no_join.acmr
    );
    assert!(c.acmr < 0.71, "cache acmr16 {}", c.acmr);
    assert!(
        (c.indices_restart as f64) < 1.47 * t,
        "cache {} indices",
        c.indices_restart
    );
    assert!(b.indices_restart < c.indices_restart && b.acmr > c.acmr);
    assert!(no_swaps.indices_restart > c.indices_restart && no_swaps.acmr > c.acmr);
    assert!(no_join.indices_restart > c.indices_restart);
}

#[test]
fn bunny_figures_beat_meshoptimizer_and_the_old_designs() {
    // meshoptimizer optimize_vertex_cache + stripify on bunny: 120,924 indices at acmr16
    // 0.711 (docs/metrics.md); issue #4's cache target: at most 0.711 with at most 100,000
    // indices. The previous design (Forsyth scores with strip bonuses): 112,354 at
    // 0.703 (cache) and 95,591 at 0.798 (balanced). Now about 94,400 at 0.646 and
    // (balanced: the weight search 88,807 at 0.790, refined) 85,540 at 0.800, 1.232
    // per triangle (86,528 before the refinement's tunnels).
    // `model` prints why it skips.
    let Some(mesh) = model("bunny.obj") else {
        return;
    };
    let tris = mesh.triangulate().tris;
    let (_, c) = check(&tris, mesh.vertex_count(), &CacheOptions::cache(16));
    assert!(
        c.acmr <= 0.66 && c.indices_restart <= 95_000,
        "cache {} at {}",
        c.indices_restart,
        c.acmr
    );
    let (strips, _, _) =
        cache::stripify_within(&tris, mesh.vertex_count(), &CacheOptions::balanced(16), 0.8);
    let b = metrics::figures(&tris, &strips, CacheModel::fifo(16));
    assert!(b.verified);
    assert!(
        b.acmr <= 0.80 && b.indices_restart <= 86_000,
        "balanced {} at {}",
        b.indices_restart,
        b.acmr
    );
}

#[test]
fn research_meshes_are_verified_in_both_modes() {
    // models_dir prints why it skips.
    let Some(dir) = models_dir() else {
        return;
    };
    for name in [
        "bunny_res4.ply",
        "bunny_res3.ply",
        "cow.obj",
        "spot_triangulated.obj",
        "fandisk.obj",
        "bunny.obj",
    ] {
        let mesh = crate::test_support::read_surface(&dir.join(name)).expect(name);
        let tris = mesh.triangulate().tris;
        let vc = mesh.vertex_count();
        let graph = crate::topology::DualGraph::from_triangles(&tris, vc);
        for o in [
            CacheOptions::cache(16),
            CacheOptions::balanced(16),
            CacheOptions::cache(32),
        ] {
            let (strips, f) = check(&tris, vc, &o);
            let acmr = if o.cache_size == 32 {
                f.acmr32
            } else {
                f.acmr16
            };
            assert!(acmr < 0.9, "{name} {o:?}: acmr {acmr}");
            if o == CacheOptions::cache(16) {
                assert!(acmr < 0.75, "{name}: cache acmr16 {acmr}");
            }
            // Built with or without a ready dual graph: the same strips.
            let with_graph = cache::stripify_with_graph(&tris, vc, &graph, &o);
            assert_eq!(strips.indices, with_graph.indices, "{name}");
            assert_eq!(strips.offsets, with_graph.offsets, "{name}");
        }
        // The bounded search keeps its bound, and reports the ACMR it measured.
        let (strips, weight, acmr) =
            cache::stripify_within(&tris, vc, &CacheOptions::balanced(16), 0.8);
        let f = metrics::figures(&tris, &strips, CacheModel::fifo(16));
        assert!(f.verified, "{name}");
        assert!(
            (f.acmr16 - acmr).abs() < 1e-9,
            "{name}: {} vs {acmr}",
            f.acmr16
        );
        assert!(
            f.acmr16 <= 0.8,
            "{name}: balanced acmr16 {} (weight {weight})",
            f.acmr16
        );
        let (_, plain) = check(&tris, vc, &CacheOptions::cache(16));
        assert!(
            f.indices_restart <= plain.indices_restart + plain.indices_restart / 50,
            "{name}"
        );
    }
}

#[test]
fn the_bounded_search_refines_its_strips() {
    // After its weight search, `stripify_within` joins strips where the exact FIFO says
    // it pays (0.3 indices per miss) while the misses stay within the bound: fewer
    // indices than the stripifier at the weight it reports, still verified, and the
    // ACMR it reports is the measured one.
    let mut rng = Rng(11);
    let (t, tv) = torus(60, 36, Some(&mut rng));
    let (s, sv) = icosphere(5);
    let sphere = shuffled(&s, sv, &mut rng);
    for (name, tris, vc) in [("torus", t, tv), ("icosphere", sphere, sv)] {
        let o = CacheOptions::balanced(16);
        let (strips, weight, acmr) = cache::stripify_within(&tris, vc, &o, 0.8);
        let f = metrics::figures(&tris, &strips, CacheModel::fifo(16));
        assert!(f.verified && f.winding_preserved, "{name}");
        assert!(
            f.acmr16 <= 0.8 && (f.acmr16 - acmr).abs() < 1e-9,
            "{name}: {}",
            f.acmr16
        );
        assert_eq!(
            f.indices_separate,
            f.triangles + 2 * f.strips + f.swaps,
            "{name}"
        );
        let (_, plain) = check(
            &tris,
            vc,
            &CacheOptions {
                miss_weight: weight,
                ..o
            },
        );
        eprintln!(
            "{name}: stripifier {} @ {:.3}, refined {} @ {:.3}",
            plain.indices_restart, plain.acmr16, f.indices_restart, f.acmr16
        );
        assert!(
            (f.indices_restart as f64) < 0.99 * plain.indices_restart as f64,
            "{name}: {} vs {}",
            f.indices_restart,
            plain.indices_restart
        );
    }
}

#[test]
fn tunnels_in_the_refinement_relink_strips_within_the_bound() {
    // The refinement's tunnels (alternating paths through up to three strips, each
    // cut next to the triangle the path enters, ending at a strip end or after a cut)
    // are scored by the exact FIFO like its other moves. Measured without them:
    // fandisk 15,856 @ 0.800, cow 7,610 @ 0.782, bunny_small 9,308 @ 0.799; with them
    // 15,707 @ 0.795, 7,492 @ 0.791, 9,197 @ 0.799. `model` prints why it skips.
    for (name, most) in [
        ("fandisk.obj", 15_750),
        ("cow.obj", 7_530),
        ("bunny_small.off", 9_240),
    ] {
        let Some(mesh) = model(name) else {
            continue;
        };
        let tris = mesh.triangulate().tris;
        let vc = mesh.vertex_count();
        let (strips, _, acmr) = cache::stripify_within(&tris, vc, &CacheOptions::balanced(16), 0.8);
        let f = metrics::figures(&tris, &strips, CacheModel::fifo(16));
        eprintln!("{name}: {} @ {:.4}", f.indices_restart, f.acmr16);
        assert!(f.verified && f.winding_preserved, "{name}");
        assert!(f.acmr16 <= 0.8 && (f.acmr16 - acmr).abs() < 1e-9, "{name}");
        assert!(f.indices_restart <= most, "{name}: {}", f.indices_restart);
    }
}

#[test]
fn the_bounded_search_keeps_any_reachable_bound() {
    let mut rng = Rng(3);
    let (tris, vc) = torus(50, 40, Some(&mut rng));
    let mut last = 0;
    for bound in [0.9, 0.8, 0.7] {
        let (strips, _, acmr) =
            cache::stripify_within(&tris, vc, &CacheOptions::balanced(16), bound);
        let f = metrics::figures(&tris, &strips, CacheModel::fifo(16));
        assert!(
            f.verified && f.acmr16 <= bound && (f.acmr16 - acmr).abs() < 1e-9,
            "{bound}: {}",
            f.acmr16
        );
        // A tighter bound never buys fewer indices.
        assert!(f.indices_restart >= last, "{bound}");
        last = f.indices_restart;
    }
    // An unreachable bound gives the last try's strips, still verified.
    let (strips, weight, _) = cache::stripify_within(&tris, vc, &CacheOptions::balanced(16), 0.1);
    assert!(metrics::figures(&tris, &strips, CacheModel::fifo(16)).verified);
    // Seven growths of a quarter from the first weight.
    assert!((weight - 0.5 * 1.25f32.powi(7)).abs() < 1e-3, "{weight}");
}

mod soups {
    use super::*;
    use proptest::prelude::*;

    /// Triangle soups over few vertices: shared edges, non-manifold edges, flipped
    /// neighbours, duplicates and degenerate triangles all come up often.
    fn soups() -> impl Strategy<Value = (Vec<[u32; 3]>, usize)> {
        (4usize..40).prop_flat_map(|vc| {
            let v = 0..vc as u32;
            (
                prop::collection::vec([v.clone(), v.clone(), v], 0..120),
                Just(vc),
            )
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        #[test]
        fn every_soup_is_kept_whole((tris, vc) in soups(), n in 3u32..20) {
            let refined = CacheOptions { refine: true, ..CacheOptions::cache(n) };
            for o in [CacheOptions::cache(n), CacheOptions::balanced(n), refined] {
                let strips = cache::stripify(&tris, vc, &o);
                let v = strip::verify(&tris, &strips);
                prop_assert!(v.ok(), "{:?}: {}", o, v);
            }
            let (strips, _, acmr) = cache::stripify_within(&tris, vc, &CacheOptions::balanced(n), 0.9);
            let v = strip::verify(&tris, &strips);
            prop_assert!(v.ok(), "within: {}", v);
            let decoded = strip::decode(&strips);
            let measured = metrics::acmr(&decoded, vc, n as usize, CacheKind::Fifo);
            prop_assert!((measured - acmr).abs() < 1e-9, "simulated {} measured {}", acmr, measured);
        }
    }
}

#[test]
fn quads_split_along_qstrip_diagonals_beat_a_random_fan() {
    // A quad torus, shuffled with every face rotated: its fan splits the quads along
    // random diagonals, so lines break everywhere. `Split::Auto` must take QSTRIP's
    // split, pass the quad-level check, and beat the fan clearly (cache: 8% fewer
    // indices and 0.09 fewer misses per triangle; balanced: 14% fewer indices).
    use crate::stripify::{cache::stripify_mesh, Split};
    use crate::stripify::quad_verify::verify_quads;
    let mesh = crate::gen::shuffle_faces(&crate::gen::torus_quads(96, 48, 3.0, 1.0), 5);
    for (o, bound) in [
        (CacheOptions::cache(16), None),
        (CacheOptions::balanced(16), Some(0.8)),
    ] {
        let fan = stripify_mesh(&mesh, &o, bound, Split::Fan, Default::default());
        let auto = stripify_mesh(&mesh, &o, bound, Split::Auto, Default::default());
        assert!(!fan.qstrip_diagonals);
        assert!(auto.qstrip_diagonals, "{o:?}");
        verify_quads(&mesh, &auto.strips).expect("quad-level check");
        let measure = |m: &cache::MeshStrips| {
            let f = metrics::figures(&m.triangles, &m.strips, CacheModel::fifo(16));
            assert!(f.verified && f.winding_preserved, "{o:?}");
            f
        };
        let (f, a) = (measure(&fan), measure(&auto));
        if bound.is_none() {
            // Same stripifier and weight on the same triangles: the same strips (the
            // bounded search refines its strips further).
            let at = CacheOptions {
                miss_weight: auto.miss_weight,
                ..o
            };
            let (strips, _) = check(&auto.triangles, mesh.vertex_count(), &at);
            assert_eq!(strips, auto.strips);
        }
        eprintln!(
            "{o:?}: fan {} @ {:.3}, qstrip diagonals {} @ {:.3}",
            f.indices_restart, f.acmr, a.indices_restart, a.acmr
        );
        assert!((a.indices_restart as f64) < 0.95 * f.indices_restart as f64);
        match bound {
            // cache: fewer misses too.
            None => assert!(a.acmr < f.acmr - 0.02),
            // balanced spends its slack on indices: both within the bound.
            Some(b) => assert!(a.acmr <= b && f.acmr <= b),
        }
        assert!((auto.acmr - a.acmr).abs() < 1e-9);
    }
    // A mesh without quads: Auto is the fan.
    let tris = crate::gen::icosphere(3);
    let m = stripify_mesh(&tris, &CacheOptions::cache(16), None, Split::Auto, Default::default());
    assert!(!m.qstrip_diagonals);
    // The same triangles (in a canonical order, each possibly rotated).
    let sorted = |t: &[[u32; 3]]| {
        let mut v: Vec<[u32; 3]> = t.iter().map(|&x| strip::canonical(x)).collect();
        v.sort_unstable();
        v
    };
    assert_eq!(sorted(&m.triangles), sorted(&tris.triangulate().tris));
    assert!(strip::verify(&tris.triangulate().tris, &m.strips).ok());
}

#[test]
fn refining_the_cache_strips_lowers_indices_without_adding_misses() {
    // An irregular torus: the refined cache strips have fewer indices and no more
    // misses than the plain ones (measured: about 3% fewer indices, fewer misses).
    let mut rng = Rng(23);
    let (tris, vc) = torus(120, 80, Some(&mut rng));
    let plain = check(&tris, vc, &CacheOptions::cache(16)).1;
    let refined = check(&tris, vc, &CacheOptions { refine: true, ..CacheOptions::cache(16) }).1;
    eprintln!(
        "plain {} @ {:.4}, refined {} @ {:.4}",
        plain.indices_restart, plain.acmr, refined.indices_restart, refined.acmr
    );
    assert!((refined.indices_restart as f64) < 0.99 * plain.indices_restart as f64);
    assert!(refined.acmr <= plain.acmr);
}

#[test]
fn a_big_mesh_in_parts_verifies_and_is_the_same_at_any_thread_count_and_face_order() {
    // icosphere(7): 327,680 triangles, two parts. The partitioned strips verify against
    // the mesh, are the same at 1 and 4 threads and for shuffled faces, and cost a
    // little against the whole-mesh run (measured: 425,847 indices against 423,228,
    // +0.62%; ACMR 0.5910 against 0.5851).
    use crate::parallel::Threads;
    use crate::stripify::cache::stripify_mesh;
    use crate::stripify::Split;
    let mesh = crate::gen::icosphere(7);
    let tris = mesh.triangulate().tris;
    let parted = CacheOptions { partition_above: 1, ..CacheOptions::cache(16) };
    let one = stripify_mesh(&mesh, &parted, None, Split::Auto, Threads::SERIAL);
    assert!(strip::verify(&tris, &one.strips).ok());
    let four = stripify_mesh(&mesh, &parted, None, Split::Auto, Threads::new(4));
    assert_eq!(one.strips, four.strips);
    let shuffled = crate::gen::shuffle_faces(&mesh, 5);
    let again = stripify_mesh(&shuffled, &parted, None, Split::Auto, Threads::new(2));
    assert!(strip::verify(&shuffled.triangulate().tris, &again.strips).ok());
    assert_eq!(one.strips.restart_len(), again.strips.restart_len());
    let whole = stripify_mesh(&mesh, &CacheOptions::cache(16), None, Split::Auto, Threads::SERIAL);
    let (a, b) = (one.strips.restart_len() as f64, whole.strips.restart_len() as f64);
    eprintln!("icosphere(7) in parts: {a} indices (acmr {}), whole: {b} (acmr {})", one.acmr, whole.acmr);
    assert!(a > b && a <= b * 1.01, "{a} against {b}");
    assert!(one.acmr <= whole.acmr + 0.01, "{} against {}", one.acmr, whole.acmr);
}

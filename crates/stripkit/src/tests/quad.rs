//! QSTRIP's internals (moved from `tests/quad_strips.rs` and `tests/quad_models.rs`;
//! what `stripify` gives on a quad mesh is tested there): forced diagonals, the
//! quad-level checker, the mixed entry with a custom triangle stripifier, the checker's
//! counts against the stripifier's, and the timing on spot's level 4.

use super::support::{cube, quad_grid, quad_torus, shuffled_mesh, subdivide};
use crate::stripify::quad::{qstrip, qstrip_mesh, Policy, QuadOptions, QuadStrips};
use crate::stripify::quad_verify::{verify_quads, QuadCheck};
use crate::test_support::models_dir;
use crate::Mesh;

/// Runs QSTRIP, verifies the output at quad level, checks that the stripifier and the
/// checker count the same quads and swaps.
fn strip_and_verify(mesh: &Mesh) -> (QuadStrips, QuadCheck) {
    let (q, all) = qstrip_mesh(mesh, &QuadOptions::default());
    let check = match verify_quads(mesh, &all) {
        Ok(c) => c,
        Err(e) => panic!("verification failed: {e}"),
    };
    assert_eq!(check.quads, q.quad_count());
    assert_eq!(
        verify_quads(mesh, &q.strips)
            .map(|c| c.degenerate)
            .unwrap_or(q.swaps),
        q.swaps,
        "swaps counted by the stripifier and the checker differ"
    );
    (q, check)
}

/// The research quad meshes of `tests/quad_models.rs`.
const MODELS: [&str; 6] = [
    "fandisk_quads.off",
    "halftunnel.off",
    "inspired_mesh_quads_Conjugate.off",
    "horse_quad.obj",
    "spot_quadrangulated.obj",
    "spot_control_mesh.obj",
];

/// The checks of `strip_and_verify` (the checker's quads and swaps equal the
/// stripifier's) on the meshes whose figures `tests/quad_strips.rs` and
/// `tests/quad_models.rs` assert through the door.
#[test]
fn the_checker_and_the_stripifier_agree() {
    let mut meshes = Vec::new();
    for (nx, ny) in [(1, 1), (2, 1), (1, 7), (3, 3), (10, 10), (40, 7), (64, 64)] {
        meshes.push(quad_grid(nx, ny));
    }
    for (nu, nv) in [(3, 3), (4, 3), (8, 5), (32, 16), (100, 60)] {
        meshes.push(quad_torus(nu, nv));
    }
    for n in [1, 2, 5, 20, 40] {
        meshes.push(cube(n));
    }
    for (i, mesh) in [cube(3), quad_torus(9, 7), quad_grid(5, 4)].iter().enumerate() {
        let s1 = subdivide(mesh);
        let s2 = subdivide(&s1);
        for m in [mesh, &s1, &s2] {
            for seed in [1u64, 7, 12345] {
                meshes.push(shuffled_mesh(m, seed + i as u64));
            }
        }
    }
    if let Some(dir) = models_dir() {
        for name in MODELS {
            if let Ok(mesh) = crate::test_support::read_surface(&dir.join("quads").join(name)) {
                if name.starts_with("spot_quad") {
                    let l1 = subdivide(&mesh);
                    meshes.push(subdivide(&l1));
                    meshes.push(l1);
                }
                meshes.push(mesh);
            }
        }
    }
    for mesh in &meshes {
        strip_and_verify(mesh);
    }
}

#[test]
fn two_quads_sharing_two_edges_never_give_coincident_triangles() {
    // Fold at the valence-2 vertex 0: (0,1,2,3) and (1,0,3,4) share 0-1 and 3-0.
    let fold = Mesh::from_polygons(vec![[0.0; 3]; 5], &[vec![0, 1, 2, 3], vec![1, 0, 3, 4]]);
    // Closed: the fold capped by (4,3,2,1), which folds against both.
    let capped = Mesh::from_polygons(
        vec![[0.0; 3]; 5],
        &[vec![0, 1, 2, 3], vec![1, 0, 3, 4], vec![4, 3, 2, 1]],
    );
    // A pillow: two quads on the same four vertices, all four edges shared.
    let pillow = Mesh::from_polygons(vec![[0.0; 3]; 4], &[vec![0, 1, 2, 3], vec![3, 2, 1, 0]]);
    for mesh in [&fold, &capped, &pillow] {
        for seed in 1..40u64 {
            let sh = shuffled_mesh(mesh, seed);
            let (q, _) = strip_and_verify(&sh);
            assert!(q.forced_diagonals >= 1);
        }
    }
    // A fold inside a larger surface: a grid whose corner quad is replaced by a fold.
    let mut g = quad_grid(6, 6);
    let n = g.vertex_count() as u32;
    g.positions.push([0.5, -1.0, 0.0]);
    g.positions.push([-1.0, -1.0, 0.0]);
    // Grid vertex 0 is the corner; quad 0 is (0, 1, 8, 7). Add (1, 0, n, n+1)? That shares
    // only 0-1; add a second quad sharing 0-1 and 7-0 with quad 0 instead.
    let fold_quad = [1, 0, 7, n];
    g.push_face(&fold_quad);
    for seed in 1..20u64 {
        let sh = shuffled_mesh(&g, seed);
        let (q, _) = strip_and_verify(&sh);
        assert_eq!(q.quad_count(), 37);
        assert!(q.forced_diagonals >= 1);
    }
}

#[test]
fn the_checker_catches_a_wrong_split_and_a_flip() {
    let mesh = quad_grid(2, 1); // (0,1,4,3), (1,2,5,4)
    let good = qstrip(&mesh, &QuadOptions::default());
    assert!(verify_quads(&mesh, &good.strips).is_ok());
    // (1,5,2) is the flip of a half of quad 1.
    let good_by_hand = crate::StripSet::from_strips(&[vec![0, 1, 3, 4], vec![1, 2, 4, 5]]);
    assert!(
        verify_quads(&mesh, &good_by_hand).is_ok(),
        "a correct hand-made strip set passes"
    );
    let wrong = crate::StripSet::from_strips(&[vec![0, 1, 3, 4], vec![1, 5, 2, 4]]);
    assert!(verify_quads(&mesh, &wrong).is_err());
    let flipped = crate::StripSet::from_strips(&[vec![1, 0, 4, 3], vec![1, 2, 4, 5]]);
    assert!(verify_quads(&mesh, &flipped).is_err());
    let missing = crate::StripSet::from_strips(&[vec![0, 1, 3, 4]]);
    assert!(verify_quads(&mesh, &missing).is_err());
    let extra =
        crate::StripSet::from_strips(&[vec![0, 1, 3, 4], vec![1, 2, 4, 5], vec![0, 1, 3]]);
    assert!(verify_quads(&mesh, &extra).is_err());
    // Coincident triangles from a fold split the wrong way: (0,1,3)+(1,2,3) and (1,0,3)+(1,3,4).
    let fold = Mesh::from_polygons(vec![[0.0; 3]; 5], &[vec![0, 1, 2, 3], vec![1, 0, 3, 4]]);
    let clash = crate::StripSet::from_strips(&[vec![0, 1, 3, 2], vec![1, 0, 3], vec![1, 3, 4]]);
    let err = verify_quads(&fold, &clash).unwrap_err().to_string();
    assert!(err.contains("coincident"), "{err}");
}

#[test]
fn mixed_meshes_strip_quads_and_leave_the_rest_to_a_triangle_stripifier() {
    // A grid with a triangle fan and a pentagon attached: every face covered.
    let mut m = quad_grid(4, 4);
    let base = m.vertex_count() as u32;
    m.positions.push([-1.0, 0.5, 0.0]);
    m.positions.push([-1.0, 2.5, 0.0]);
    m.push_face(&[0, 5, base]); // left of column 0 (orientation: 0 -> 5 runs up; grid left edge is 5 -> 0)
    m.push_face(&[base, 5, 10, 15, base + 1]);
    let (quads, all) =
        crate::stripify::quad::qstrip_mixed(&m, &QuadOptions::default(), |tris, _| {
            crate::StripSet::from_strips(&tris.iter().map(|t| t.to_vec()).collect::<Vec<_>>())
        });
    assert_eq!(quads.quad_count(), 16);
    let check = verify_quads(&m, &all).expect("mixed output verifies");
    assert_eq!(check.quads, 16);
    assert_eq!(check.other_triangles, 1 + 3);
}

#[test]
fn awkward_topology_is_covered_and_verified() {
    // Three quads on edge 0-1 (non-manifold), a flipped neighbour, a quad with a
    // repeated vertex (not a quad: fanned, its degenerate triangle dropped), an
    // isolated quad, and an unreferenced vertex.
    let mesh = Mesh::from_polygons(
        vec![[0.0; 3]; 16],
        &[
            vec![0, 1, 2, 3],
            vec![1, 0, 4, 5],
            vec![1, 0, 6, 7],
            vec![2, 1, 5, 8],  // consistent with quad 0 across 1-2
            vec![3, 2, 9, 10], // flipped against quad 0 across 2-3? quad 0 runs 2->3; this runs 3->2: consistent
            vec![10, 9, 11, 12],
            vec![9, 2, 11, 9], // repeated vertex 9
            vec![12, 11, 13, 14],
            vec![11, 12, 13, 14], // flipped against the previous across 11-12... shares 12-11 in the same direction
        ],
    );
    for seed in 0..10u64 {
        let m = if seed == 0 {
            mesh.clone()
        } else {
            shuffled_mesh(&mesh, seed)
        };
        let (q, check) = strip_and_verify(&m);
        assert_eq!(q.quad_count(), 8);
        assert_eq!(check.quads, 8);
        assert_eq!(
            check.other_triangles, 1,
            "the repeated-vertex quad keeps one real triangle"
        );
    }
    // No quads at all, and no faces at all.
    let tris = Mesh::from_polygons(vec![[0.0; 3]; 4], &[vec![0, 1, 2], vec![2, 1, 3]]);
    let (q, check) = strip_and_verify(&tris);
    assert_eq!((q.quad_count(), check.other_triangles), (0, 2));
    let empty = Mesh::new();
    let (q, check) = strip_and_verify(&empty);
    assert_eq!((q.quad_count(), check.quads, q.strips.len()), (0, 0, 0));
}

/// CPU seconds this thread has run (user + system), from /proc; 0 where unavailable.
/// The machine is shared, so wall time says little; CPU time says what the code costs.
fn thread_cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/thread-self/stat") else {
        return 0.0;
    };
    let Some(after) = stat.rfind(')').map(|i| &stat[i + 2..]) else {
        return 0.0;
    };
    let fields: Vec<&str> = after.split_whitespace().collect();
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|f| f.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    // Fields 14 and 15 of the line (utime, stime) are 11 and 12 after the name.
    (ticks(11) + ticks(12)) / 100.0
}

/// Timing on Catmull-Clark level 4 of spot (749,568 quads); run in release:
/// `cargo test --release -p stripkit --lib -- --ignored timing_on_spot_level_4 --nocapture`.
#[test]
#[ignore]
fn timing_on_spot_level_4() {
    let Some(dir) = models_dir() else {
        return;
    };
    let mut mesh =
        crate::test_support::read_surface(&dir.join("quads/spot_quadrangulated.obj")).expect("spot loads");
    for _ in 0..4 {
        mesh = subdivide(&mesh);
    }
    let mut times = Vec::new();
    let mut last = None;
    let cpu0 = thread_cpu_seconds();
    for _ in 0..7 {
        let t = std::time::Instant::now();
        let q = qstrip(&mesh, &QuadOptions::default());
        times.push(t.elapsed().as_secs_f64());
        last = Some(q);
    }
    let cpu = (thread_cpu_seconds() - cpu0) / 7.0;
    times.sort_by(f64::total_cmp);
    let q = last.expect("ran");
    let restart = q.strips.indices.len() + q.strips.len() - 1;
    let edges_t = std::time::Instant::now();
    let _ = crate::topology::EdgeMap::build(&mesh);
    eprintln!(
        "spot CC level 4: {} quads, {} strips, {} swaps, indices_per_quad {:.4}; qstrip median {:.1} ms \
         ({:.2} M quads/s); CPU time per run {:.1} ms ({:.2} M quads/s); EdgeMap alone {:.1} ms",
        q.quad_count(),
        q.strips.len(),
        q.swaps,
        restart as f64 / q.quad_count() as f64,
        times[3] * 1e3,
        q.quad_count() as f64 / times[3] / 1e6,
        cpu * 1e3,
        q.quad_count() as f64 / cpu / 1e6,
        edges_t.elapsed().as_secs_f64() * 1e3
    );
    for (name, options) in [
        (
            "FewestSwaps only",
            QuadOptions {
                policies: vec![Policy::FewestSwaps],
                ..QuadOptions::default()
            },
        ),
        ("paper (forward only)", QuadOptions::paper()),
    ] {
        let mut times = Vec::new();
        let mut last = None;
        let cpu0 = thread_cpu_seconds();
        for _ in 0..5 {
            let t = std::time::Instant::now();
            last = Some(qstrip(&mesh, &options));
            times.push(t.elapsed().as_secs_f64());
        }
        let cpu = (thread_cpu_seconds() - cpu0) / 5.0;
        times.sort_by(f64::total_cmp);
        let q = last.expect("ran");
        let restart = q.strips.indices.len() + q.strips.len() - 1;
        eprintln!(
            "  {name}: {} strips, indices_per_quad {:.4}, median {:.1} ms ({:.2} M quads/s), CPU {:.1} ms",
            q.strips.len(),
            restart as f64 / q.quad_count() as f64,
            times[2] * 1e3,
            q.quad_count() as f64 / times[2] / 1e6,
            cpu * 1e3
        );
    }
    let check = verify_quads(&mesh, &q.strips).expect("verifies");
    assert_eq!(check.quads, q.quad_count());
    let cpu0 = thread_cpu_seconds();
    let t = std::time::Instant::now();
    let single = crate::stripify::quad_single::quad_single(&mesh).expect("closed quad mesh");
    let wall = t.elapsed().as_secs_f64();
    let cpu = thread_cpu_seconds() - cpu0;
    let restart = single.strips.indices.len() + single.strips.len() - 1;
    eprintln!(
        "  quad-single: {} strips ({} cycles), indices_per_quad {:.4}, {:.1} ms wall, {:.1} ms CPU",
        single.strips.len(),
        single.cycles,
        restart as f64 / single.quads as f64,
        wall * 1e3,
        cpu * 1e3
    );
    verify_quads(&mesh, &single.strips)
        .expect("single strips verify");
}

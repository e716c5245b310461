//! QSTRIP on the research quad meshes (../shared/models/quads) and their Catmull-Clark
//! refinements, when present: every output verified, the figures of the target held.

mod quad_support;

use quad_support::*;
use stripkit::stripify::quad::{qstrip, Policy, QuadOptions};

const MODELS: [(&str, bool); 6] = [
    ("fandisk_quads.off", true),
    ("halftunnel.off", false),
    ("inspired_mesh_quads_Conjugate.off", false),
    ("horse_quad.obj", true),
    ("spot_quadrangulated.obj", true),
    ("spot_control_mesh.obj", true),
];

#[test]
fn research_quad_meshes_verify_and_meet_the_target() {
    let Some(dir) = stripkit::test_support::models_dir() else {
        return;
    };
    let mut failures = Vec::new();
    for (name, closed) in MODELS {
        let path = dir.join("quads").join(name);
        if !path.exists() {
            eprintln!("skipped: {} not found", path.display());
            continue;
        }
        let mesh = stripkit::mesh::io::read(&path).expect("model loads");
        let pure = mesh.is_quad_mesh();
        let (_, check, fig) = strip_and_verify(&mesh);
        eprintln!("{name}: {fig:?} other triangles {}", check.other_triangles);
        if closed && pure && (fig.indices_per_quad > 2.20 || fig.strips * 50 >= fig.quads) {
            failures.push(format!("{name}: {fig:?}"));
        }
        if name.starts_with("spot_quad") {
            let l1 = subdivide(&mesh);
            let l2 = subdivide(&l1);
            for (level, m) in [(1, &l1), (2, &l2)] {
                let (_, _, fig) = strip_and_verify(m);
                eprintln!("{name} CC level {level}: {fig:?}");
                if fig.indices_per_quad > 2.20 || fig.strips * 50 >= fig.quads {
                    failures.push(format!("{name} level {level}: {fig:?}"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "over the target: {failures:#?}");
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
/// `cargo test --release -p stripkit --test quad_models -- --ignored --nocapture`.
#[test]
#[ignore]
fn timing_on_spot_level_4() {
    let Some(dir) = stripkit::test_support::models_dir() else {
        return;
    };
    let mut mesh =
        stripkit::mesh::io::read(&dir.join("quads/spot_quadrangulated.obj")).expect("spot loads");
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
    let _ = stripkit::topology::EdgeMap::build(&mesh);
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
    let check = stripkit::stripify::quad_verify::verify_quads(&mesh, &q.strips).expect("verifies");
    assert_eq!(check.quads, q.quad_count());
    let cpu0 = thread_cpu_seconds();
    let t = std::time::Instant::now();
    let single = stripkit::stripify::quad_single::quad_single(&mesh).expect("closed quad mesh");
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
    stripkit::stripify::quad_verify::verify_quads(&mesh, &single.strips)
        .expect("single strips verify");
}

/// `indices_restart` of the greedy stripifier on the fan-triangulated mesh, the better
/// of its two heuristics, verified.
fn greedy_after_triangulation(mesh: &stripkit::Mesh) -> usize {
    use stripkit::stripify::greedy::{stripify, GreedyOptions, Heuristic};
    let tris = mesh.triangulate().tris;
    [Heuristic::Strips, Heuristic::Indices]
        .into_iter()
        .map(|heuristic| {
            let s = stripify(&tris, mesh.vertex_count(), &GreedyOptions::with_heuristic(heuristic));
            assert!(stripkit::strip::verify(&tris, &s).ok());
            s.indices.len() + s.len().saturating_sub(1)
        })
        .min()
        .unwrap_or(0)
}

/// Strictly fewer indices on every real pure-quad mesh and on subdivided ones. On
/// perfectly regular procedural grids, tori and cubes the fan triangulation puts every
/// diagonal the same way, which suits a triangle stripifier; there QSTRIP stays within
/// 1% (measured: grid 1278 vs 1278, torus 2014 vs 2000, cube 1837 vs 1824).
#[test]
fn qstrip_beats_triangulate_then_greedy_on_every_quad_mesh() {
    let mut meshes: Vec<(String, stripkit::Mesh)> = vec![
        ("cube 3, CC level 2".into(), subdivide(&subdivide(&cube(3)))),
        (
            "torus 7x5, CC level 2".into(),
            subdivide(&subdivide(&torus(7, 5))),
        ),
    ];
    for (name, mesh) in [
        ("grid 30x20", grid(30, 20)),
        ("torus 40x24", torus(40, 24)),
        ("cube 12", cube(12)),
    ] {
        let (_, all) = stripkit::stripify::quad::qstrip_mesh(&mesh, &QuadOptions::default());
        let ours = all.indices.len() + all.len() - 1;
        let greedy = greedy_after_triangulation(&mesh);
        eprintln!("{name}: QSTRIP {ours}, greedy {greedy}");
        assert!(
            ours * 100 <= greedy * 101,
            "{name}: QSTRIP {ours} vs greedy {greedy}"
        );
    }
    if let Some(dir) = stripkit::test_support::models_dir() {
        for (name, _) in MODELS {
            let path = dir.join("quads").join(name);
            if let Ok(mesh) = stripkit::mesh::io::read(&path) {
                meshes.push((name.to_string(), mesh));
            }
        }
    }
    let mut failures = Vec::new();
    for (name, mesh) in meshes.iter().filter(|(_, m)| m.is_quad_mesh()) {
        let (q, all) = stripkit::stripify::quad::qstrip_mesh(mesh, &QuadOptions::default());
        stripkit::stripify::quad_verify::verify_quads(mesh, &all).expect("verifies");
        let ours = all.indices.len() + all.len() - 1;
        let greedy = greedy_after_triangulation(mesh);
        eprintln!(
            "{name}: QSTRIP {ours} indices ({} strips, {} quads), greedy {greedy}",
            all.len(),
            q.quad_count()
        );
        if ours >= greedy {
            failures.push(format!("{name}: QSTRIP {ours} vs greedy {greedy}"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

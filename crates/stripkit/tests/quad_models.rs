//! QSTRIP through the front door on the research quad meshes (../shared/models/quads)
//! and their Catmull-Clark refinements, when present: every output verified (by the
//! door), the figures of the target held, fewer indices than greedy on the fan. (The
//! timing on spot's level 4 runs inside the crate: `src/tests/quad.rs`.)

mod quad_support;
mod support;

use quad_support::*;
use stripkit::{stripify, Algorithm, GreedyOptions, Heuristic, StripOptions};

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
    let Some(dir) = support::models_dir() else {
        return;
    };
    let mut failures = Vec::new();
    for (name, closed) in MODELS {
        let path = dir.join("quads").join(name);
        if !path.exists() {
            eprintln!("skipped: {} not found", path.display());
            continue;
        }
        let mesh = support::read_surface(&path).expect("model loads");
        let pure = mesh.is_quad_mesh();
        let (s, fig) = strip_and_verify(&mesh);
        eprintln!("{name}: {fig:?} triangles {}", s.figures.triangles);
        if closed && pure && (fig.indices_per_quad > 2.20 || fig.strips * 50 >= fig.quads) {
            failures.push(format!("{name}: {fig:?}"));
        }
        if name.starts_with("spot_quad") {
            let l1 = subdivide(&mesh);
            let l2 = subdivide(&l1);
            for (level, m) in [(1, &l1), (2, &l2)] {
                let (_, fig) = strip_and_verify(m);
                eprintln!("{name} CC level {level}: {fig:?}");
                if fig.indices_per_quad > 2.20 || fig.strips * 50 >= fig.quads {
                    failures.push(format!("{name} level {level}: {fig:?}"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "over the target: {failures:#?}");
}

/// `indices_restart` of the greedy stripifier on the fan-triangulated mesh, the better
/// of its two heuristics, verified.
fn greedy_after_triangulation(mesh: &stripkit::Mesh) -> usize {
    [Heuristic::Strips, Heuristic::Indices]
        .into_iter()
        .map(|heuristic| {
            let options = StripOptions::default().algorithm(Algorithm::Greedy(GreedyOptions::default().heuristic(heuristic)));
            let s = stripify(mesh, &options).expect("verified greedy strips");
            assert!(s.figures.verified);
            s.figures.indices_restart
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
        let (_, fig) = strip_and_verify(&mesh);
        let ours = fig.indices_restart;
        let greedy = greedy_after_triangulation(&mesh);
        eprintln!("{name}: QSTRIP {ours}, greedy {greedy}");
        assert!(
            ours * 100 <= greedy * 101,
            "{name}: QSTRIP {ours} vs greedy {greedy}"
        );
    }
    if let Some(dir) = support::models_dir() {
        for (name, _) in MODELS {
            let path = dir.join("quads").join(name);
            if let Ok(mesh) = support::read_surface(&path) {
                meshes.push((name.to_string(), mesh));
            }
        }
    }
    let mut failures = Vec::new();
    for (name, mesh) in meshes.iter().filter(|(_, m)| m.is_quad_mesh()) {
        let (s, fig) = strip_and_verify(mesh);
        let ours = fig.indices_restart;
        let greedy = greedy_after_triangulation(mesh);
        eprintln!(
            "{name}: QSTRIP {ours} indices ({} strips, {} quads), greedy {greedy}",
            s.figures.strips,
            fig.quads
        );
        if ours >= greedy {
            failures.push(format!("{name}: QSTRIP {ours} vs greedy {greedy}"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

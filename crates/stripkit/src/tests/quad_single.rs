//! Single strips: the cycles left after splicing (moved from `tests/quad_single.rs`,
//! which checks the strips `stripify` gives through the door). Every output verified
//! at quad level; a strip per cycle; at most three cycles on the procedural meshes,
//! one on the research closed quad meshes and their first Catmull-Clark level.

use super::support::{cube, quad_torus, shuffled_mesh, subdivide};
use crate::stripify::quad_single::quad_single;
use crate::stripify::quad_verify::verify_quads;
use crate::test_support::models_dir;
use crate::Mesh;

/// Cycles and strips of one run, verified.
fn run(name: &str, mesh: &Mesh) -> (usize, usize) {
    let s = match quad_single(mesh) {
        Ok(s) => s,
        Err(e) => panic!("{name}: {e}"),
    };
    let check = verify_quads(mesh, &s.strips).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(check.quads, mesh.face_count(), "{name}");
    eprintln!("{name}: {} quads, {} cycles, {} strips, {} swaps", s.quads, s.cycles, s.strips.len(), s.swaps);
    (s.cycles, s.strips.len())
}

#[test]
fn one_strip_per_cycle_on_closed_procedural_meshes() {
    for (name, mesh) in [
        ("torus 8x6", quad_torus(8, 6)),
        ("torus 31x17", quad_torus(31, 17)),
        ("cube 1", cube(1)),
        ("cube 4", cube(4)),
        ("cube 15", cube(15)),
        ("cube 3 CC2", subdivide(&subdivide(&cube(3)))),
    ] {
        for seed in [0u64, 3, 99] {
            let m = if seed == 0 { mesh.clone() } else { shuffled_mesh(&mesh, seed) };
            let (cycles, strips) = run(name, &m);
            assert!(cycles <= 3, "{name} seed {seed}: {cycles} cycles");
            assert_eq!(strips, cycles, "{name} seed {seed}");
        }
    }
}

#[test]
fn one_cycle_on_research_closed_quad_meshes() {
    let Some(dir) = models_dir() else {
        return;
    };
    for name in ["fandisk_quads.off", "horse_quad.obj", "spot_quadrangulated.obj"] {
        let Ok(mesh) = crate::test_support::read_surface(&dir.join("quads").join(name)) else {
            continue;
        };
        assert_eq!(run(name, &mesh), (1, 1), "{name}");
        assert_eq!(run(&format!("{name} CC1"), &subdivide(&mesh)), (1, 1), "{name} CC1");
    }
}

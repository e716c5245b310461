//! QSTRIP through the front door on procedural quad meshes: every output verified at
//! quad level (by the door), figures asserted. (Forced diagonals, the quad checker and
//! the mixed entry are tested inside the crate: `src/tests/quad.rs`.)

mod quad_support;

use quad_support::*;

#[test]
fn grids_are_covered_with_few_strips_and_swaps() {
    for (nx, ny) in [(1, 1), (2, 1), (1, 7), (3, 3), (10, 10), (40, 7), (64, 64)] {
        let (_, fig) = strip_and_verify(&grid(nx, ny));
        eprintln!("grid {nx}x{ny}: {fig:?}");
        assert_eq!(fig.quads, nx * ny);
    }
    let (_, fig) = strip_and_verify(&grid(64, 64));
    assert!(fig.indices_per_quad < 2.2, "{fig:?}");
}

#[test]
fn tori_and_cubes_stay_under_the_target() {
    for (nu, nv) in [(3, 3), (4, 3), (8, 5), (32, 16), (100, 60)] {
        let (_, fig) = strip_and_verify(&torus(nu, nv));
        eprintln!("torus {nu}x{nv}: {fig:?}");
        if nu * nv >= 512 {
            assert!(fig.indices_per_quad <= 2.2, "{fig:?}");
        }
    }
    for n in [1, 2, 5, 20, 40] {
        let (_, fig) = strip_and_verify(&cube(n));
        eprintln!("cube {n}: {fig:?}");
        if n >= 20 {
            assert!(fig.indices_per_quad <= 2.2, "{fig:?}");
        }
    }
}

#[test]
fn subdivided_and_shuffled_meshes_verify() {
    let base = [cube(3), torus(9, 7), grid(5, 4)];
    for (i, mesh) in base.iter().enumerate() {
        let s1 = subdivide(mesh);
        let s2 = subdivide(&s1);
        for (m, name) in [(mesh, "base"), (&s1, "level 1"), (&s2, "level 2")] {
            for seed in [1u64, 7, 12345] {
                let sh = shuffled(m, seed + i as u64);
                let (_, fig) = strip_and_verify(&sh);
                assert_eq!(fig.quads, m.face_count(), "{name}");
            }
        }
    }
}

//! Inputs for the crate's internal tests: a seeded generator, triangle lists of
//! procedural meshes, shuffles, and the procedural quad meshes of the QSTRIP tests.
#![allow(dead_code)] // each test module uses a different subset

use crate::{gen, Mesh};

/// The tests' seeded generator (xorshift64), from the shared test kit.
pub(crate) use stripkit_testkit::XorShift64 as Rng;

/// Triangles and vertex count of a generated mesh.
pub(crate) fn tris_of(mesh: Mesh) -> (Vec<[u32; 3]>, usize) {
    (mesh.triangulate().tris, mesh.vertex_count())
}

/// A `w` x `h` triangle grid.
pub(crate) fn grid(w: u32, h: u32) -> (Vec<[u32; 3]>, usize) {
    tris_of(gen::grid(w, h))
}

/// An icosphere of `levels` subdivisions.
pub(crate) fn icosphere(levels: u32) -> (Vec<[u32; 3]>, usize) {
    tris_of(gen::icosphere(levels))
}

/// A torus of `n x m` quads, each split along a random diagonal when `rng` is given.
pub(crate) fn torus(n: u32, m: u32, mut rng: Option<&mut Rng>) -> (Vec<[u32; 3]>, usize) {
    let id = |x: u32, y: u32| (y % m) * n + (x % n);
    let mut tris = Vec::new();
    for y in 0..m {
        for x in 0..n {
            let (a, b, c, d) = (id(x, y), id(x + 1, y), id(x + 1, y + 1), id(x, y + 1));
            if rng.as_mut().is_some_and(|r| r.below(2) == 0) {
                tris.push([a, b, d]);
                tris.push([b, c, d]);
            } else {
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            }
        }
    }
    (tris, (n * m) as usize)
}

/// Faces shuffled, each rotated, vertices renumbered.
pub(crate) fn shuffled(tris: &[[u32; 3]], vertex_count: usize, rng: &mut Rng) -> Vec<[u32; 3]> {
    let mut perm: Vec<u32> = (0..vertex_count as u32).collect();
    for i in (1..perm.len()).rev() {
        perm.swap(i, rng.below(i + 1));
    }
    let mut out: Vec<[u32; 3]> = tris
        .iter()
        .map(|t| {
            let r = rng.below(3);
            let u = t.map(|v| perm[v as usize]);
            [u[r], u[(r + 1) % 3], u[(r + 2) % 3]]
        })
        .collect();
    for i in (1..out.len()).rev() {
        out.swap(i, rng.below(i + 1));
    }
    out
}

// ---- quad meshes (the same as tests/quad_support) ----

/// `nx` x `ny` quads in the plane, counter-clockwise seen from +z.
pub(crate) fn quad_grid(nx: usize, ny: usize) -> Mesh {
    gen::grid_quads(nx as u32, ny as u32)
}

/// A closed torus of `nu` x `nv` quads, outward orientation.
pub(crate) fn quad_torus(nu: usize, nv: usize) -> Mesh {
    gen::torus_quads(nu as u32, nv as u32, 2.0, 1.0)
}

/// A closed cube with `n` x `n` quads on each side, outward orientation.
pub(crate) fn cube(n: usize) -> Mesh {
    gen::cube_grid(n as u32)
}

/// One Catmull-Clark step: a face of k vertices becomes k quads.
pub(crate) fn subdivide(mesh: &Mesh) -> Mesh {
    gen::subdivide_catmull_clark(mesh, 1).expect("a valid polygon mesh")
}

/// Same surface, faces in random order, each face's corners rotated at random, vertex
/// ids permuted.
pub(crate) fn shuffled_mesh(mesh: &Mesh, seed: u64) -> Mesh {
    gen::shuffle_faces(&gen::renumber_vertices(mesh, seed), seed)
}

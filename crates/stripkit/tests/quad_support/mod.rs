//! Procedural quad meshes for the QSTRIP tests: grids (open), tori and cubes (closed),
//! a connectivity-exact Catmull-Clark split, shuffles; and QSTRIP through the door.
#![allow(dead_code)]

use stripkit::{stripify, Algorithm, Mesh, Split, StripOptions, Strips};

/// `nx` x `ny` quads in the plane, counter-clockwise seen from +z.
pub fn grid(nx: usize, ny: usize) -> Mesh {
    stripkit::gen::grid_quads(nx as u32, ny as u32)
}

/// A closed torus of `nu` x `nv` quads, outward orientation.
pub fn torus(nu: usize, nv: usize) -> Mesh {
    stripkit::gen::torus_quads(nu as u32, nv as u32, 2.0, 1.0)
}

/// A closed cube with `n` x `n` quads on each side, outward orientation.
pub fn cube(n: usize) -> Mesh {
    stripkit::gen::cube_grid(n as u32)
}

/// One Catmull-Clark step: a face of k vertices becomes k quads.
pub fn subdivide(mesh: &Mesh) -> Mesh {
    stripkit::gen::subdivide_catmull_clark(mesh, 1).expect("a valid polygon mesh")
}

/// The tests' seeded generator (xorshift64), from the shared test kit.
#[allow(unused_imports)] // not every test binary draws random numbers
pub use stripkit_testkit::XorShift64 as Rng;

/// Same surface, faces in random order, each face's corners rotated at random, vertex
/// ids permuted.
pub fn shuffled(mesh: &Mesh, seed: u64) -> Mesh {
    stripkit::gen::shuffle_faces(&stripkit::gen::renumber_vertices(mesh, seed), seed)
}

/// QSTRIP figures of one run.
#[derive(Debug, Clone, Copy)]
pub struct Figures {
    pub quads: usize,
    pub strips: usize,
    pub swaps: usize,
    pub indices_restart: usize,
    pub indices_per_quad: f64,
}

/// Runs QSTRIP through the door, which verifies the output at quad level; returns the
/// door's result and its figures (of all strips: on a pure-quad mesh, QSTRIP's own).
pub fn strip_and_verify(mesh: &Mesh) -> (Strips, Figures) {
    let options = StripOptions::default().algorithm(Algorithm::qstrip());
    let s = match stripify(mesh, &options) {
        Ok(s) => s,
        Err(e) => panic!("verification failed: {e}"),
    };
    assert_eq!(s.split, Split::Qstrip);
    let quads = s.quads.expect("QSTRIP counts the quads it strips");
    let f = &s.figures;
    let fig = Figures {
        quads,
        strips: f.strips,
        swaps: f.swaps,
        indices_restart: f.indices_restart,
        indices_per_quad: f.indices_restart as f64 / quads.max(1) as f64,
    };
    (s, fig)
}

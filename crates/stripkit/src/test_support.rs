//! Helpers for the crate's own tests, over the shared test kit (`stripkit-testkit`,
//! which the integration, CLI and renderer tests use too): the research meshes read
//! as the library reads them, and a seeded generator.

pub(crate) use stripkit_testkit::models_dir;

/// The research mesh `name` from [`models_dir`]; `None` (after printing why) when the
/// folder or the file is absent or unreadable, so that a test can skip it.
/// Read as a surface ([`read_surface`]).
pub(crate) fn model(name: &str) -> Option<crate::Mesh> {
    stripkit_testkit::model_with(name, read_surface)
}

/// A mesh file's positions and faces only (`ReadOptions::positions_only`): the
/// research meshes' documented facts are about their surfaces, which UV seams would
/// cut into pieces.
pub(crate) fn read_surface(path: &std::path::Path) -> crate::Result<crate::Mesh> {
    crate::io::read_with(path, &crate::io::ReadOptions::default().positions_only(true))
}

/// A xorshift64 generator for tests: each call returns the next state modulo `m`
/// (`m` > 0), so that random inputs are the same on every run.
pub(crate) fn xorshift(seed: u64) -> impl FnMut(u32) -> u32 {
    let mut rng = stripkit_testkit::XorShift64(seed);
    move |m: u32| (rng.next() % u64::from(m)) as u32
}

/// A `w` x `h` grid of quads, each split along a diagonal picked by a small LCG from
/// `seed`: irregular valences (3 to 9), so strips need swaps. Returns the triangles
/// and the vertex count.
pub(crate) fn random_diagonals(w: u32, h: u32, seed: u64) -> (Vec<[u32; 3]>, usize) {
    let id = |x: u32, y: u32| y * (w + 1) + x;
    let mut rng = stripkit_testkit::Lcg(seed);
    let mut tris = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let (a, b, c, d) = (id(x, y), id(x + 1, y), id(x + 1, y + 1), id(x, y + 1));
            // the state's top bit (`next` gives the state's top 31 bits)
            if rng.next() >> 30 == 0 {
                tris.extend([[a, b, c], [a, c, d]]);
            } else {
                tris.extend([[a, b, d], [b, c, d]]);
            }
        }
    }
    (tris, ((w + 1) * (h + 1)) as usize)
}

//! Helpers for the crate's own tests: the research meshes and a seeded generator.
//! (`models_dir` is the one of `tests/support/dirs.rs`, shared with the integration
//! and CLI tests.)

#[path = "../tests/support/dirs.rs"]
mod dirs;
pub(crate) use dirs::models_dir;

/// The research mesh `name` from [`models_dir`]; `None` (after printing why) when the
/// folder or the file is absent or unreadable, so that a test can skip it.
/// Read as a surface ([`read_surface`]).
pub(crate) fn model(name: &str) -> Option<crate::Mesh> {
    dirs::model_with(name, read_surface)
}

/// A mesh file's positions and faces only (`ReadOptions::positions_only`): the
/// research meshes' documented facts are about their surfaces, which UV seams would
/// cut into pieces.
pub(crate) fn read_surface(path: &std::path::Path) -> crate::Result<crate::Mesh> {
    crate::io::read_with(path, &crate::io::ReadOptions::default().positions_only(true))
}

/// A xorshift64 generator for tests: each call returns the next state modulo `m`
/// (`m` > 0), so that random inputs are the same on every run.
pub(crate) fn xorshift(mut x: u64) -> impl FnMut(u32) -> u32 {
    move |m: u32| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x % u64::from(m)) as u32
    }
}

/// A `w` x `h` grid of quads, each split along a diagonal picked by a small LCG from
/// `seed`: irregular valences (3 to 9), so strips need swaps. Returns the triangles
/// and the vertex count.
pub(crate) fn random_diagonals(w: u32, h: u32, mut seed: u64) -> (Vec<[u32; 3]>, usize) {
    let id = |x: u32, y: u32| y * (w + 1) + x;
    let mut tris = Vec::new();
    for y in 0..h {
        for x in 0..w {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            let (a, b, c, d) = (id(x, y), id(x + 1, y), id(x + 1, y + 1), id(x, y + 1));
            if seed >> 63 == 0 {
                tris.extend([[a, b, c], [a, c, d]]);
            } else {
                tris.extend([[a, b, d], [b, c, d]]);
            }
        }
    }
    (tris, ((w + 1) * (h + 1)) as usize)
}

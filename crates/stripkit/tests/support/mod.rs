//! Helpers shared by the integration tests that need the library's types (the
//! algorithm list, decoded triangle sets, reading a research mesh); the generators and
//! folders come from `stripkit-testkit`. Include with `mod support;`.
#![allow(dead_code)] // each test binary uses a different subset

#[allow(unused_imports)] // each test binary uses a different subset
pub use stripkit_testkit::{assets_dir, encode_base64, gltf_validator, models_dir};

/// Every algorithm setting the door offers for triangle input (quad-single needs quads).
pub fn algorithms() -> Vec<stripkit::Algorithm> {
    use stripkit::{Algorithm, GreedyOptions, Heuristic};
    vec![
        Algorithm::auto(),
        Algorithm::greedy(),
        Algorithm::Greedy(GreedyOptions::default().heuristic(Heuristic::Strips).tunnel_cuts(Some(2))),
        Algorithm::Greedy(GreedyOptions::default().heuristic(Heuristic::Indices).tunnel_cuts(None)),
        Algorithm::qstrip(),
        Algorithm::cache(),
        Algorithm::Cache { refine: true },
        Algorithm::balanced(0.8),
        Algorithm::batch(),
    ]
}

/// The non-degenerate triangles `strips` draw (its restart buffer decoded), as
/// vertex sets (sorted), sorted; so that equal neighbours are coincident triangles.
pub fn drawn_sets(strips: &stripkit::Strips) -> Vec<[u32; 3]> {
    let mut sets: Vec<[u32; 3]> = stripkit::unstripify(&strips.restart_buffer(), strips.restart_index)
        .chunks_exact(3)
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .map(|t| {
            let mut t = [t[0], t[1], t[2]];
            t.sort_unstable();
            t
        })
        .collect();
    sets.sort_unstable();
    sets
}

/// The research mesh `name` from [`models_dir`]; `None` (after printing why) when the
/// folder or the file is absent or unreadable, so that a test can skip it.
/// Read as a surface ([`read_surface`]).
pub fn model(name: &str) -> Option<stripkit::Mesh> {
    stripkit_testkit::model_with(name, read_surface)
}

/// A mesh file's positions and faces only (`ReadOptions::positions_only`): the
/// research meshes' documented facts are about their surfaces, which UV seams would
/// cut into pieces.
pub fn read_surface(path: &std::path::Path) -> stripkit::Result<stripkit::Mesh> {
    stripkit::io::read_with(path, &stripkit::io::ReadOptions::default().positions_only(true))
}

/// `bytes` (a `.sets` or `.lodseq` file) with one byte behind the 8-byte header
/// replaced, both chosen by the random word `x`, and the trailing CRC-32 written
/// again, so that the damage reaches the reader's parsing behind a valid checksum.
pub fn damaged_with_valid_checksum(bytes: &[u8], x: u64) -> Vec<u8> {
    let mut bad = bytes.to_vec();
    let at = 8 + (x as usize >> 8) % (bad.len() - 12);
    bad[at] = (x & 0xff) as u8;
    let n = bad.len() - 4;
    let mut crc = flate2::Crc::new();
    crc.update(&bad[..n]);
    bad[n..].copy_from_slice(&crc.sum().to_le_bytes());
    bad
}

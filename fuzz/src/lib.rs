//! Shared body of the mesh-reader targets: read the bytes as one format and, for a
//! small mesh, stripify it; a verification failure is a finding.

use std::path::Path;
use stripkit::io::Format;
use stripkit::{stripify, StripOptions};

/// Meshes with at most this many faces are also stripified.
pub const MAX_FACES: usize = 4000;

/// Reads `data` as `format` (file name `fuzz.EXT`) and, on success with a small mesh,
/// runs the default stripifier; panics on an [`stripkit::Error::Verification`] or any error
/// other than an invalid input ([`stripkit::Error::is_invalid`]).
pub fn read_and_stripify(ext: &str, format: Format, data: &[u8]) {
    let name = format!("fuzz.{ext}");
    let Ok(mesh) = stripkit::io::read_bytes(Path::new(&name), format, data) else {
        return;
    };
    if mesh.face_count() == 0 || mesh.face_count() > MAX_FACES || mesh.vertex_count() > 4 * MAX_FACES + 64 {
        return;
    }
    match stripify(&mesh, &StripOptions::default()) {
        Ok(_) => {}
        Err(e) if e.is_invalid() => {}
        Err(e) => panic!("stripify of a {}-face mesh read from {ext}: {e}", mesh.face_count()),
    }
}

/// `t` rotated so that its smallest vertex comes first (the same oriented triangle).
pub fn rotate_min(t: [u32; 3]) -> [u32; 3] {
    let r = (0..3).min_by_key(|&i| t[i]).unwrap_or(0);
    [t[r], t[(r + 1) % 3], t[(r + 2) % 3]]
}

/// The non-degenerate triangles of a flat index list, each rotated by
/// [`rotate_min`], sorted: oriented triangles as a comparable multiset.
pub fn oriented(flat: &[u32]) -> Vec<[u32; 3]> {
    let mut out: Vec<[u32; 3]> = flat
        .chunks_exact(3)
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .map(|t| rotate_min([t[0], t[1], t[2]]))
        .collect();
    out.sort_unstable();
    out
}

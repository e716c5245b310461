#![no_main]
//! The front door on a small mesh of quads and triangles, with every algorithm,
//! QSTRIP and quad-single included. Byte 0 picks the algorithm; every further pair of
//! bytes is one face of 16 vertices: four nibbles, a quad, or a triangle when the last
//! nibble is 15. `stripify` must give Ok (its own verification passed) or
//! `Error::Invalid`; every non-degenerate triangle of the restart buffer must then be
//! one a face may give (a quad of four distinct vertices: a triangle of either
//! diagonal; any other face: a fan triangle), with its orientation, and there are no
//! more of them than the faces hold.

use libfuzzer_sys::fuzz_target;
use stripkit_fuzz::{oriented, rotate_min};
use stripkit::{stripify, unstripify, Algorithm, Mesh, StripOptions};

fuzz_target!(|data: &[u8]| {
    let Some((&first, rest)) = data.split_first() else { return };
    let algorithm = match first % 8 {
        0 => Algorithm::auto(),
        1 => Algorithm::greedy(),
        2 => Algorithm::qstrip(),
        3 => Algorithm::QuadSingle,
        4 => Algorithm::cache(),
        5 => Algorithm::Cache { refine: true },
        6 => Algorithm::balanced(0.8),
        _ => Algorithm::balanced(1.5),
    };
    let faces: Vec<Vec<u32>> = rest
        .chunks_exact(2)
        .take(150)
        .map(|p| {
            let n = [p[0] & 15, p[0] >> 4, p[1] & 15, p[1] >> 4].map(u32::from);
            if n[3] == 15 { n[..3].to_vec() } else { n.to_vec() }
        })
        .collect();
    if faces.is_empty() {
        return;
    }
    // A 4x4 grid, slightly bent so that no four points are coplanar by accident.
    let positions = (0..16).map(|i| [(i % 4) as f32, (i / 4) as f32, ((i * 7) % 5) as f32 * 0.1]).collect();
    let mesh = Mesh::from_polygons(positions, &faces);
    let options = StripOptions::default().algorithm(algorithm.clone());
    let strips = match stripify(&mesh, &options) {
        Ok(s) => s,
        Err(e) if e.is_invalid() => return,
        Err(e) => panic!("{}: {e}", algorithm.name()),
    };
    // The triangles a face may give, up to rotation: a quad of four distinct
    // vertices either diagonal's pair, any other face its fan (v0, vi, vi+1).
    let mut allowed: Vec<[u32; 3]> = Vec::new();
    for f in &faces {
        let distinct = f.len() == 4 && (0..4).all(|i| (i + 1..4).all(|j| f[i] != f[j]));
        if distinct {
            for d in 0..2 {
                allowed.push(rotate_min([f[d], f[d + 1], f[(d + 2) % 4]]));
                allowed.push(rotate_min([f[d], f[(d + 2) % 4], f[(d + 3) % 4]]));
            }
        } else {
            allowed.extend((1..f.len() - 1).map(|i| rotate_min([f[0], f[i], f[i + 1]])));
        }
    }
    allowed.sort_unstable();
    let on_a_face = |t: &[u32; 3]| allowed.binary_search(t).is_ok();
    let drawn = oriented(&unstripify(&strips.restart_buffer(), strips.restart_index));
    let budget: usize = faces.iter().map(|f| f.len() - 2).sum();
    assert!(drawn.len() <= budget, "{}: more triangles than the faces hold", algorithm.name());
    for t in &drawn {
        assert!(on_a_face(t), "{}: triangle {t:?} lies on no input face", algorithm.name());
    }
});

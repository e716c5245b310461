#![no_main]
//! The front door on a small mesh of quads and triangles, with every algorithm,
//! QSTRIP and quad-single included. Byte 0 picks the algorithm; every further pair of
//! bytes is one face of 16 vertices: four nibbles, a quad, or a triangle when the last
//! nibble is 15. `stripify` must give Ok (its own verification passed) or
//! `Error::Invalid`; every non-degenerate triangle of the restart buffer must then lie
//! on one input face, in that face's cyclic order (a quad's triangles come from one
//! of its two diagonals), and there are no more of them than the faces hold.

use libfuzzer_sys::fuzz_target;
use stripkit::{stripify, unstripify, Algorithm, Error, Mesh, StripOptions};

fuzz_target!(|data: &[u8]| {
    let Some((&first, rest)) = data.split_first() else { return };
    let algorithm = match first % 8 {
        0 => Algorithm::Auto,
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
        Err(Error::Invalid(_)) => return,
        Err(e) => panic!("{}: {e}", algorithm.name()),
    };
    let on_a_face = |t: &[u32; 3]| {
        faces.iter().any(|f| {
            let n = f.len();
            (0..n).any(|i| {
                f[i] == t[0] && {
                    let j = (1..n).find(|&d| f[(i + d) % n] == t[1]);
                    let k = (1..n).find(|&d| f[(i + d) % n] == t[2]);
                    matches!((j, k), (Some(j), Some(k)) if j < k)
                }
            })
        })
    };
    let drawn: Vec<[u32; 3]> = unstripify(&strips.restart_buffer(), strips.restart_index)
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]])
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .collect();
    let budget: usize = faces.iter().map(|f| f.len() - 2).sum();
    assert!(drawn.len() <= budget, "{}: more triangles than the faces hold", algorithm.name());
    for t in &drawn {
        assert!(on_a_face(t), "{}: triangle {t:?} lies on no input face", algorithm.name());
    }
});

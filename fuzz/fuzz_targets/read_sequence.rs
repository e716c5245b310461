#![no_main]
//! `CollapseSequence::read_bytes`: byte 0 picks the format (even: binary, odd:
//! JSON), the rest is the file. It must never panic; a sequence it accepts must
//! round-trip through its own encoding, and replaying it on a small mesh of its
//! announced size gives Ok or an error, never a panic, with every vertex in range.

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use stripkit::simplify::CollapseSequence;
use stripkit::Mesh;

fuzz_target!(|data: &[u8]| {
    let Some((&first, rest)) = data.split_first() else { return };
    let name = if first % 2 == 0 { "fuzz.bin" } else { "fuzz.json" };
    let Ok(seq) = CollapseSequence::read_bytes(Path::new(name), rest) else { return };
    let again = CollapseSequence::read_bytes(Path::new("again.bin"), &seq.to_bytes()).expect("own encoding");
    assert!(again == seq, "binary round trip differs");
    let (n, t) = (seq.vertex_count as usize, seq.triangle_count as usize);
    if !(3..=4096).contains(&n) || t > 4096 {
        return;
    }
    let positions = (0..n).map(|i| [i as f32, (i * i % 7) as f32, 0.0]).collect();
    let tris: Vec<[u32; 3]> = (0..t).map(|i| [i % n, (i + 1) % n, (i + 2) % n].map(|v| v as u32)).collect();
    let mesh = Mesh::from_triangles(positions, &tris);
    if let Ok(r) = seq.replay(&mesh, seq.len()) {
        assert!(r.triangles.iter().flatten().all(|&v| (v as usize) < n));
        assert_eq!(r.triangles.len(), r.triangle_ids.len());
    }
});

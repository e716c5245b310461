#![no_main]
//! `LodSeq::from_bytes`: the input is a `.lodseq` body; the target appends its CRC-32
//! so that the fuzzer explores the structure behind the checksum. It must never
//! panic; a sequence it accepts round-trips through its encoding, and a cursor moved
//! over its frames and levels names only its vertices.

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use stripkit::lod::{LevelSpec, LodSeq};

fuzz_target!(|data: &[u8]| {
    let mut bytes = data.to_vec();
    let mut crc = flate2::Crc::new();
    crc.update(&bytes);
    bytes.extend_from_slice(&crc.sum().to_le_bytes());
    let Ok(seq) = LodSeq::from_bytes(Path::new("fuzz.lodseq"), &bytes) else { return };
    let again = LodSeq::from_bytes(Path::new("again.lodseq"), &seq.to_bytes()).expect("own encoding");
    assert!(again == seq, "round trip differs");
    let n = seq.positions(0).len();
    let mut cursor = seq.cursor(0, LevelSpec::Level(0));
    for (f, spec) in [(seq.frame_count() - 1, LevelSpec::Ratio(0.5)), (0, LevelSpec::Level(u32::MAX)), (usize::MAX, LevelSpec::Triangles(3))] {
        cursor.set(f, spec);
        assert!(cursor.strips().indices.iter().all(|&v| (v as usize) < n));
    }
    let _ = seq.morph(0.5 * seq.frame_count() as f64);
});

#![no_main]
//! `Sets::from_bytes`: the input is a `.sets` body; the target appends its CRC-32 so
//! that the fuzzer explores the structure behind the checksum. It must never panic;
//! a model it accepts must round-trip through its own encoding, and recovering any
//! level (from scratch and through a cursor moving both ways) names only vertices it
//! has, in strips no longer than their level-0 slots.

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use stripkit::lod::Sets;

fuzz_target!(|data: &[u8]| {
    let mut bytes = data.to_vec();
    let mut crc = flate2::Crc::new();
    crc.update(&bytes);
    bytes.extend_from_slice(&crc.sum().to_le_bytes());
    let Ok(sets) = Sets::from_bytes(Path::new("fuzz.sets"), &bytes) else { return };
    let again = Sets::from_bytes(Path::new("again.sets"), &sets.to_bytes()).expect("own encoding");
    assert!(again == sets, "round trip differs");
    let n = sets.positions().len();
    let mut cursor = sets.cursor(sets.levels());
    for level in [0, sets.levels() / 3, sets.levels(), 1, u32::MAX] {
        let strips = sets.strips_at(level);
        assert!(strips.indices.iter().all(|&v| (v as usize) < n));
        assert!(strips.index_count() <= sets.slot_count());
        cursor.set_level(level);
        assert!(cursor.strips() == strips, "cursor and walk differ");
    }
});

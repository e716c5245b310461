#![no_main]
//! `stripkit::io::read_bytes` as Obj, then `stripify` on small meshes.

use libfuzzer_sys::fuzz_target;
use stripkit::io::Format;

fuzz_target!(|data: &[u8]| {
    stripkit_fuzz::read_and_stripify("obj", Format::Obj, data);
});

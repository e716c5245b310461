#![no_main]
//! A glTF or GLB document read as a scene, stripped, written and read back
//! (`stripkit_fuzzcheck::scene::check`, which the stable replay test also runs).

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    stripkit_fuzzcheck::scene::check(data);
});

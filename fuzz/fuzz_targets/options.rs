#![no_main]
//! The CLI's memory-sizing option values through the library's bounds checks
//! (`stripkit_fuzzcheck::options::check`, which the stable replay test also runs).

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    stripkit_fuzzcheck::options::check(data);
});

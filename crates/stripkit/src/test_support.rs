//! Helpers for the crate's own tests: the research meshes and a seeded generator.
//! (Integration tests, the CLI's tests and the bench have their own copies of
//! `models_dir`: this module exists only under `cfg(test)`.)

use std::path::PathBuf;

/// The research meshes folder `../shared/models` beside the checkout, or the folder
/// named by `STRIPKIT_MODELS`; `None` (after printing why) when it is absent, so that
/// tests needing it can skip with a reason.
pub(crate) fn models_dir() -> Option<PathBuf> {
    let dir = match std::env::var_os("STRIPKIT_MODELS") {
        Some(d) => PathBuf::from(d),
        None => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/models"),
    };
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipped: research meshes not found at {} (set STRIPKIT_MODELS)", dir.display());
        None
    }
}

/// The research mesh `name` from [`models_dir`]; `None` (after printing why) when the
/// folder or the file is absent or unreadable, so that a test can skip it.
pub(crate) fn model(name: &str) -> Option<crate::Mesh> {
    let dir = models_dir()?;
    match crate::io::read(&dir.join(name)) {
        Ok(mesh) => Some(mesh),
        Err(e) => {
            eprintln!("skipped: {name} in {}: {e}", dir.display());
            None
        }
    }
}

/// A xorshift64 generator for tests: each call returns the next state modulo `m`
/// (`m` > 0), so that random inputs are the same on every run.
pub(crate) fn xorshift(mut x: u64) -> impl FnMut(u32) -> u32 {
    move |m: u32| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x % u64::from(m)) as u32
    }
}

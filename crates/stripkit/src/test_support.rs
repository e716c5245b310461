//! Helpers for the crate's own tests: the research meshes and a seeded generator.
//! (`models_dir` is the one of `tests/support/dirs.rs`, shared with the integration
//! and CLI tests.)

#[path = "../tests/support/dirs.rs"]
mod dirs;
pub(crate) use dirs::models_dir;

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

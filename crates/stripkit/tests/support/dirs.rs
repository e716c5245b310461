//! Where tests find their meshes: one copy, included by path into the library's own
//! tests (`src/test_support.rs`), its integration tests (`tests/support/mod.rs`) and
//! the CLI's tests, so that all of them skip, or not, for the same reason.

use std::path::{Path, PathBuf};

/// The research meshes folder `../shared/models` beside the checkout, or the folder
/// named by `STRIPKIT_MODELS`; `None` (after printing why) when it is absent, so that
/// tests needing it can skip with a reason.
#[allow(dead_code)] // each test binary uses a different subset
pub fn models_dir() -> Option<PathBuf> {
    let dir = match std::env::var_os("STRIPKIT_MODELS") {
        Some(d) => PathBuf::from(d),
        // Every crate of the workspace sits two folders below its root.
        None => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/models"),
    };
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipped: research meshes not found at {} (set STRIPKIT_MODELS)", dir.display());
        None
    }
}

/// The bundled public-domain meshes (`assets/` at the workspace root).
#[allow(dead_code)]
pub fn assets_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets")
}

/// The research mesh `name` from [`models_dir`], read by `read` (the library's
/// `io::read`, named by the includer); `None` (after printing why) when the folder or
/// the file is absent or unreadable, so that a test can skip it.
#[allow(dead_code)]
pub fn model_with<M, E: std::fmt::Display>(name: &str, read: impl Fn(&Path) -> Result<M, E>) -> Option<M> {
    let dir = models_dir()?;
    match read(&dir.join(name)) {
        Ok(mesh) => Some(mesh),
        Err(e) => {
            eprintln!("skipped: {name} in {}: {e}", dir.display());
            None
        }
    }
}

//! Where tests find their meshes, so that every test skips, or not, for the same reason.

use std::path::{Path, PathBuf};

/// The workspace root (two folders above this crate, like every crate of the workspace).
pub fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Where the research meshes should be: the folder named by `STRIPKIT_MODELS`, else
/// `../shared/models` beside the checkout. It may not exist; see [`models_dir`].
pub fn models_path() -> PathBuf {
    match std::env::var_os("STRIPKIT_MODELS") {
        Some(d) => PathBuf::from(d),
        None => repo_root().join("../shared/models"),
    }
}

/// The research meshes folder ([`models_path`]); `None` (after printing why) when it is
/// absent, so that tests needing it can skip with a reason.
pub fn models_dir() -> Option<PathBuf> {
    let dir = models_path();
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipped: research meshes not found at {} (set STRIPKIT_MODELS)", dir.display());
        None
    }
}

/// The bundled public-domain meshes (`assets/` at the workspace root).
pub fn assets_dir() -> PathBuf {
    repo_root().join("assets")
}

/// The research mesh `name` from [`models_dir`], read by `read` (the library's
/// `io::read`, or a reader of the caller's); `None` (after printing why) when the
/// folder or the file is absent or unreadable, so that a test can skip it.
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

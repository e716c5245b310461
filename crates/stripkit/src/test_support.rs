//! Helpers for tests and benchmarks (not part of the stable API).

use std::path::PathBuf;

/// The research meshes folder `../shared/models` beside the checkout, or the folder
/// named by `STRIPKIT_MODELS`; `None` (after printing why) when it is absent, so that
/// tests needing it can skip with a reason.
pub fn models_dir() -> Option<PathBuf> {
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

/// The bundled public-domain meshes (`assets/` at the workspace root).
pub fn assets_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets")
}

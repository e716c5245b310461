//! Helpers shared by the integration tests: where the research meshes and the bundled
//! assets are. Include with `mod support;`.
#![allow(dead_code)] // each test binary uses a different subset

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

/// The research mesh `name` from [`models_dir`]; `None` (after printing why) when the
/// folder or the file is absent or unreadable, so that a test can skip it.
pub fn model(name: &str) -> Option<stripkit::Mesh> {
    let dir = models_dir()?;
    match stripkit::io::read(&dir.join(name)) {
        Ok(mesh) => Some(mesh),
        Err(e) => {
            eprintln!("skipped: {name} in {}: {e}", dir.display());
            None
        }
    }
}

/// The bundled public-domain meshes (`assets/` at the workspace root).
pub fn assets_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets")
}

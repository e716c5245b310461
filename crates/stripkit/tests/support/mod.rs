//! Helpers shared by the integration tests: where the research meshes and the bundled
//! assets are. Include with `mod support;`.
#![allow(dead_code)] // each test binary uses a different subset

mod dirs;
#[allow(unused_imports)] // each test binary uses a different subset
pub use dirs::{assets_dir, models_dir};

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

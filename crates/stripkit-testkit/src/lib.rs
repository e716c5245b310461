//! The shared kit of the workspace's tests (a dev-dependency of every crate; never
//! published): seeded random generators, where the research meshes and the bundled
//! assets are (with the reason printed when a test skips), f64 vector helpers for
//! geometric checks, a GLB container written and split independently of the library,
//! and small fixtures.
//!
//! It does not depend on `stripkit`, so that the library's own `#[cfg(test)]` code can
//! use it without a second copy of the library's types; readers are passed in
//! (`model_with(name, stripkit::io::read)`).
#![warn(missing_docs)]

mod base64;
mod dirs;
pub mod geom;
mod glb;
pub mod gltf_validator;
mod rng;

pub use base64::encode_base64;
pub use glb::{glb, unglb};
pub use dirs::{assets_dir, fresh_scratch_dir, model_with, models_dir, models_path, repo_root, scratch_dir, scratch_root};
pub use rng::{Lcg, XorShift64, XorShift64Star};

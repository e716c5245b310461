//! # stripkit
//!
//! Triangle strips for meshes: read a mesh, build strips with one of several
//! algorithms, check them independently, measure them, write them out.
//!
//! Data flows one way: **file -> [`Mesh`] -> [`topology`] -> [`strip::StripSet`] ->
//! encoded buffers / files**, with [`simplify`] and [`lod`] branching off the mesh.
//!
//! Every stripifier returns a [`strip::StripSet`] that [`strip::verify`] checks
//! against the input: nothing lost, nothing added, winding kept.

#![warn(missing_docs)]

pub mod error;
pub mod mesh;
pub mod topology;
pub mod strip;
pub mod metrics;
pub mod stripify;
mod improve;
pub mod matching;
pub mod simplify;
pub mod distance;
pub mod lod;
pub mod gen;
#[doc(hidden)]
pub mod test_support;

pub use error::{Error, Result};
pub use mesh::{Mesh, Triangles};
pub use strip::StripSet;

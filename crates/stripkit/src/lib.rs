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
mod pipeline;
pub mod mesh;
pub mod topology;
pub mod strip;
pub mod metrics;
pub mod stripify;
pub mod matching;
pub mod simplify;
pub mod distance;
pub mod lod;
pub mod gen;
#[doc(hidden)]
pub mod test_support;
#[cfg(test)]
mod tests;

pub use error::{Error, Result};
pub use mesh::{io, Mesh, Triangles};
pub use metrics::{acmr, cache_misses, figures, swaps, CacheKind, CacheModel, Figures};
pub use pipeline::{
    is_quad_dominant, stripify, stripify_bound, stripify_indices, unstripify, Algorithm, Join, Split,
    StripOptions, Stripifier, Strips, QUAD_DOMINANT,
};
pub use strip::{
    decode, decode_restart, encode_restart, encode_separate, encode_stitched, for_each_triangle,
    is_degenerate, stitched_len, verify, verify_triangles, StripSet, Verification, DEFAULT_RESTART,
};
pub use stripify::greedy::{GreedyOptions, Heuristic};
pub use stripify::quad::{Policy, QuadOptions};
pub use topology::{validate, MeshFacts};

//! The C API of stripkit (`include/stripkit.h`): thin `extern "C"` wrappers over the
//! library's public entry points, meshoptimizer-shaped (plain arrays in and out, the
//! caller owning memory where the size is known in advance).
//!
//! Every function catches panics, checks its pointers and sizes, and returns a status
//! (negative [`Status`] codes) whose message [`stripkit_last_error`] gives on the same
//! thread. The header is written by hand; `tests/header.rs` checks that its prototypes
//! and structs match the ones here.

#![allow(non_camel_case_types)]
#![warn(missing_docs)]

mod boundary;
mod indices;
mod lod;
mod mesh;
mod options;

pub use boundary::{stripkit_last_error, Status};
pub use indices::{
    stripkit_stripify, stripkit_stripify16, stripkit_stripify_bound, stripkit_unstripify, stripkit_unstripify16,
    stripkit_unstripify_bound,
};
pub use lod::{
    stripkit_lod, stripkit_lod_extract, stripkit_lod_extract_bound, stripkit_lod_free, stripkit_lod_level_for_triangles,
    stripkit_lod_levels, stripkit_lod_open, stripkit_lod_positions, stripkit_lod_triangles, stripkit_lod_vertex_count,
};
pub use mesh::{stripkit_mesh_result, stripkit_mesh_result_free, stripkit_stripify_mesh};
pub use options::{stripkit_options, stripkit_options_default};

//! Stripifiers: one file (or folder) per algorithm. Each takes triangles (or a mesh)
//! and returns a [`crate::strip::StripSet`] that [`crate::strip::verify`] accepts.
//!
//! The triangle stripifiers ([`greedy`], [`cache`]) build walks through the dual graph
//! ([`crate::topology::Walks`]), improve them with the local searches of
//! `crate::improve` (greedy's tunnelling and the refinement of `cache`), and encode them
//! with [`crate::topology::walks::encode_path`]. The quad stripifiers ([`quad`], [`quad_single`]) work on quad
//! sequences instead, and [`quad_verify`] checks their output against the quads.

pub mod batch;
mod buckets;
pub mod cache;
pub mod greedy;
pub mod quad;
mod quad_adjacency;
mod quad_sequence;
pub mod quad_single;
pub mod single;
pub mod quad_verify;

use crate::error::named_enum;

/// How faces of more than three corners become triangles before stripping (for
/// quads: which diagonal each is split along).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Split {
    /// The algorithm's own choice (the default): the fan for greedy; QSTRIP's
    /// diagonals for QSTRIP and quad-single; for cache and balanced, on quad-dominant
    /// meshes both the fan and QSTRIP's diagonals, keeping the cheaper strips, else
    /// the fan.
    #[default]
    Auto,
    /// Every face fanned from its first corner (the triangles other tools get).
    Fan,
    /// Quads along QSTRIP's diagonals (rows of quads run without swaps), other faces
    /// fanned. Quad-level verification.
    Qstrip,
}

named_enum!(Split, "split", Auto => "auto", Fan => "fan", Qstrip => "qstrip");


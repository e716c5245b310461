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

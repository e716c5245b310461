//! Stripifiers: one file per algorithm. Each takes triangles (or a mesh) and returns a
//! [`crate::strip::StripSet`] that [`crate::strip::verify`] accepts.

pub mod cache;

//! Weighted perfect matching, re-exported from the [`stripkit_matching`] crate, plus
//! the glue that turns a mesh into a matching graph ([`mesh_dual_graph`]).
//!
//! Everything but [`mesh_dual_graph`] and [`DualWeights`] lives in `stripkit-matching`, which has no mesh
//! dependency; see its docs for the solver, the certificate and the DIMACS reader.
//! Its error type converts into [`crate::Error`], so `?` works in stripkit code.

mod dual;

pub use dual::{mesh_dual_graph, DualWeights};
pub(crate) use dual::splitmix;
pub use stripkit_matching::*;

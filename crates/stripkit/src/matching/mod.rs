//! Weighted perfect matching, re-exported from the [`stripkit_matching`] crate, plus
//! the glue that turns a mesh into a matching graph ([`mesh_dual_graph`]).
//!
//! Everything but [`dual`] lives in `stripkit-matching`, which has no mesh
//! dependency; see its docs for the solver, the certificate and the DIMACS reader.
//! Its error type converts into [`crate::Error`], so `?` works in stripkit code.

pub mod dual;

pub use dual::{graph_from_dual, mesh_dual_graph, DualWeights};
pub use stripkit_matching::*;

/// The unweighted matcher under its former path `stripkit::matching::unweighted`.
pub mod unweighted {
    pub use stripkit_matching::{
        maximum_cardinality_matching, maximum_cardinality_matching_bounded,
        unweighted_perfect_matching as perfect_matching,
    };
}

//! # stripkit-matching
//!
//! Weighted perfect matching on large sparse graphs: Edmonds' primal-dual blossom
//! algorithm with the speed-ups of the sparse implementations, and an optimality
//! certificate that is checked from scratch on every solve.
//!
//! * [`Graph`]: edge list + CSR adjacency, `i64` weights, DIMACS-style reader
//!   ([`Graph::read_dimacs`], [`Graph::parse_dimacs`]) and writers ([`Graph::to_dimacs`],
//!   [`Graph::to_edge_lines`] for a matching's edges).
//! * [`max_weight_perfect_matching`] / [`min_cost_perfect_matching`] (both [`solve`]):
//!   the exact optimum as a [`Matching`]. When the graph has no perfect matching the
//!   result says so (`perfect == false`) and holds a maximum-cardinality matching of
//!   maximum weight (minimum cost).
//! * [`Certificate`], [`check_certificate`] and [`verify`]: the dual solution and its
//!   independent checker.
//! * [`maximum_cardinality_matching`] and [`unweighted_perfect_matching`]: the
//!   unweighted matcher, used for the uniform-weight case and as a pre-check.
//!
//! The crate knows nothing of meshes; `stripkit::matching` builds matching graphs from
//! a mesh's dual graph and re-exports this crate.
//!
//! ## Example
//!
//! ```
//! use stripkit_matching::{solve, verify, Graph, Objective};
//!
//! // A square 0-1-2-3 with the diagonal 0-2; edge ids are the list positions.
//! let g = Graph::new(4, vec![[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]], vec![5, 1, 5, 1, 3])?;
//!
//! // Maximum weight: the two heavy sides 0-1 and 2-3.
//! let m = solve(&g, Objective::MaxWeight)?;
//! assert!(m.perfect && m.certified);
//! assert_eq!(m.edges, vec![0, 2]);
//! assert_eq!(m.mate, vec![1, 0, 3, 2]);
//! assert_eq!(m.total_weight, 10);
//! // The matched edges as text, one `U V W` line each (1-based, as in DIMACS).
//! assert_eq!(g.to_edge_lines(&m.edges), "1 2 5\n3 4 5\n");
//!
//! // The certificate proves it: its dual bound equals the matching's weight, in the
//! // internal (doubled) weights.
//! let report = verify(&g, Objective::MaxWeight, &m.edges, m.certificate.as_ref().unwrap())?;
//! assert_eq!(report.primal, 2 * 10);
//! assert_eq!(report.dual, report.primal);
//!
//! // Minimum cost: the two light sides.
//! let m = solve(&g, Objective::MinCost)?;
//! assert_eq!((m.edges.clone(), m.total_weight), (vec![1, 3], 2));
//!
//! // The same square from DIMACS-style text (1-based vertices).
//! let text = "c a square\np edge 4 5\ne 1 2 5\ne 2 3 1\ne 3 4 5\ne 4 1 1\ne 1 3 3\n";
//! assert_eq!(Graph::parse_dimacs(text, "square.dimacs".as_ref())?, g);
//! # Ok::<(), stripkit_matching::Error>(())
//! ```
//!
//! ## Weights
//!
//! Integers with `|w| <= 2^40` ([`MAX_WEIGHT`]). Inside, weights are doubled (and
//! negated when minimising, see [`Objective::internal`]) so that all duals stay
//! integers and optimality is exact. Floating-point weights are scaled to integers by
//! [`scale_f64_weights`]. Self-loops are ignored; of parallel edges the best is used
//! (ties: lower id).
//!
//! ## The certificate
//!
//! A perfect matching `M` is maximum-weight when there are vertex duals `y` and
//! blossom duals `z_B >= 0` on a laminar family of odd vertex sets such that
//!
//! * every edge `uv` has slack `y_u + y_v + sum(z_B : u, v in B) - w_uv >= 0`;
//! * every edge of `M` has slack 0;
//! * every blossom with `z_B > 0` is full: `M` has `(|B| - 1) / 2` edges inside it.
//!
//! Then `w(M) = sum y + sum z_B (|B| - 1) / 2`, the dual bound, so no perfect matching
//! is heavier. [`check_certificate`] verifies all of it, trusting nothing the solver
//! computed; [`solve`] runs it before returning and fails with
//! [`Error::Verification`] rather than return an unproven result. The certificate is
//! stated for the internal weights `2w` (maximising) or `-2w` (minimising cost `w`).
//!
//! ## Cost
//!
//! O(n + m) set-up and greedy start, then all alternating trees grow at once from the
//! vertices left exposed; each event costs O(log m) plus the size of the blossoms it
//! touches. Worst case O(n m log m); on sparse graphs such as mesh dual graphs the
//! trees stay small and the run is close to linear.

#![warn(missing_docs)]

mod blossom;
mod certificate;
mod error;
mod graph;
mod solve;
mod unweighted;

pub use blossom::Stats;
pub use certificate::{check_certificate, Certificate, CheckReport, DualBlossom};
pub use error::{Error, Result};
pub use graph::{scale_f64_weights, Graph, DIMACS_SPARE_NODES, MAX_WEIGHT};
pub use solve::{
    max_weight_perfect_matching, min_cost_perfect_matching, solve, verify, Matching, Objective, UNMATCHED,
};
pub use unweighted::{
    maximum_cardinality_matching, maximum_cardinality_matching_bounded, maximum_cardinality_matching_from,
    unweighted_perfect_matching,
};

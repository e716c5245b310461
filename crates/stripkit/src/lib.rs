//! # stripkit
//!
//! Triangle strips for meshes: read a mesh, build strips with one of several
//! algorithms (greedy, cache-aware, QSTRIP on quads, one strip per closed quad mesh),
//! check them independently, measure them, write them out.
//!
//! ## Data flow
//!
//! **file -> [`Mesh`] -> [`stripify`] -> [`Strips`] -> buffers / files**:
//!
//! * [`io::read`] turns a file (OBJ, PLY, OFF, STL, glTF) into a [`Mesh`] of polygons;
//!   [`gen`] makes procedural ones. [`io::Scene`] keeps a whole glTF document;
//!   [`scene`] strips each of its triangle primitives on its own.
//! * [`stripify`] (the front door) chooses a stripifier ([`Algorithm::Auto`]: QSTRIP on
//!   quad-dominant meshes, greedy otherwise) or runs the one [`StripOptions`] names,
//!   verifies what it made with [`verify`] (or at quad level where the algorithm chose
//!   the quads' diagonals), and returns [`Strips`]: the [`StripSet`], the triangles it
//!   was verified against, and its [`Figures`]. A failed check is
//!   [`Error::Verification`], never a silent result.
//! * [`Strips`] encodes itself ([`Strips::restart_buffer`], [`Strips::stitched`],
//!   [`Strips::to_file_bytes`]); [`encode_restart`], [`encode_stitched`] and
//!   [`encode_separate`] do the same for any [`StripSet`].
//! * For plain index buffers, [`stripify_indices`], [`stripify_bound`] and
//!   [`unstripify`] do the same without a [`Mesh`] (meshoptimizer's shape).
//!
//! A strip `s` draws triangle `i` as `(s[i], s[i+1], s[i+2])` for even `i` and
//! `(s[i+1], s[i], s[i+2])` for odd `i`, so every triangle keeps its winding; a
//! triangle with a repeated index (a *swap*) draws nothing. [`decode`] applies this
//! rule, [`figures`] measures strips by it (indices per join, swaps, vertex-cache
//! misses per triangle under a [`CacheModel`]).
//!
//! [`lod`] keeps strips across a whole collapse sequence (SETS): every level of
//! detail recovered by binary search, winding kept, checked against a replay.
//!
//! [`cull`] cuts single strips into a few segments per view for back-face culling (a
//! segment tree with a render front).
//!
//! Beside the strips: [`MeshFacts`] (what `stripkit stats` prints), [`simplify`]
//! (edge collapse), [`distance`] (Hausdorff and RMS distances between surfaces) and
//! [`matching`] (weighted perfect matching).
//!
//! [`parallel`]: the thread count ([`parallel::Threads`], one by default) the library's
//! independent work may use, with outputs the same bytes at any count.
//!
//! ## Example
//!
//! ```
//! use stripkit::{gen, stripify, stripify_indices, unstripify, Algorithm, StripOptions};
//!
//! // A mesh: strips chosen, run, verified and measured by the front door.
//! let mesh = gen::icosphere(3);
//! let strips = stripify(&mesh, &StripOptions::default())?;
//! assert!(strips.figures.verified);
//! assert_eq!(strips.figures.triangles, mesh.triangle_count());
//! let buffer = strips.restart_buffer(); // strips separated by u32::MAX
//! assert_eq!(buffer.len(), strips.figures.indices_restart);
//!
//! // Another algorithm: the cache-aware stripifier, tuned for a FIFO of 32.
//! let options = StripOptions::default().algorithm(Algorithm::cache()).cache_size(32);
//! assert!(stripify(&mesh, &options)?.figures.acmr < 1.0);
//!
//! // A plain index list: two triangles sharing the edge 1-2.
//! let triangles = [0, 1, 2, 2, 1, 3];
//! let strip = stripify_indices(&triangles, 4, &StripOptions::default())?;
//! assert_eq!(strip.len(), 4);
//! assert_eq!(unstripify(&strip, u32::MAX).len(), triangles.len());
//! # Ok::<(), stripkit::Error>(())
//! ```

#![warn(missing_docs)]

/// The README's Rust examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;

mod error;
mod hint;
mod improve;
mod mesh;
mod metrics;
mod pipeline;
mod strip;
mod stripify;
mod topology;
mod vec3;
mod vertex_order;

pub mod cull;
pub mod distance;
pub mod gen;
pub mod matching;
pub mod parallel;
pub mod lod;
pub mod scene;
pub mod simplify;

#[cfg(test)]
pub(crate) mod test_support;
#[cfg(test)]
mod tests;

pub use error::{Error, OptionName, Result};
pub use mesh::{io, weld_map, weld_map_with, Attribute, Group, Mesh, Scalar, Triangles};
pub use metrics::{acmr, cache_misses, figures, figures_with, swaps, BatchModel, CacheKind, CacheModel, Figures};
pub use pipeline::{
    is_quad_dominant, stripify, stripify_bound, stripify_indices, unstripify, Algorithm, AutoOptions, Join, Split,
    StripOptions, Stripifier, Strips, DEFAULT_PARTITION_ABOVE, MAX_CACHE_SIZE, MAX_TUNNEL_CUTS, QUAD_DOMINANT,
};
pub use strip::{
    decode, decode_restart, degenerate_windows, encode_restart, encode_separate, encode_stitched, for_each_triangle,
    decode_with, is_degenerate, stitched_len, verify, verify_decoded, verify_decoded_with, verify_triangles, verify_with, StripSet, Verification, DEFAULT_RESTART,
};
pub use stripify::greedy::{GreedyOptions, Heuristic};
pub use stripify::quad::{Policy, QuadOptions};
pub use stripify::single::{MatchingMode, SingleOptions, SingleReport, Weights, EXACT_MATCHING_NODES};
pub use topology::{validate, MeshFacts};
pub use vec3::unit_scale;
pub use vertex_order::first_use_order;

//! Back-face culling of single strips with a segment tree (the constrained single-strip
//! paper, sections 4.2 to 4.4): cut a strip into a few long segments per view, drawing
//! the front-facing ones and skipping the back-facing ones.
//!
//! * [`SegmentTree::build`] builds the tree bottom-up over the strips of a [`StripSet`](crate::StripSet):
//!   neighbouring segments whose normals deviate least are merged first (a priority
//!   queue over adjacent pairs keyed by the merged normal cone, neighbours in a linked
//!   list, `O(n log n)`), so flat regions join early and sharp features stay near the
//!   root. The tree is not balanced. Each [`Node`] holds its index range in the strip
//!   buffer, its average normal and conservative [`Bounds`]: a normal cone that holds
//!   its children's cones and a bounding sphere around the centroid of its vertices.
//! * [`SegmentTree::cull`] classifies nodes for an eye point from the roots down
//!   ([`Bounds::classify`]: wholly front-facing, wholly back-facing, or split) and
//!   returns the index ranges to draw ([`Culled`]), for one multi-draw call.
//! * [`RenderFront`] does the same, starting at the lowest nodes tested in the last
//!   frame and merging or splitting them; it gives exactly the ranges of
//!   [`SegmentTree::cull`].
//! * [`helix_eyes`]: the eye points of the helix camera path the figures use;
//!   [`FacingCounter`] counts, by brute force, the triangles a view's ranges draw
//!   facing the eye and facing away; [`survey`] culls along a path view by view and
//!   times it (a bench API).
//!
//! **Parity.** A leaf of the tree is a *pair* of strip triangles, `2k` and `2k + 1`
//! counted from the start of their strip (pairs made only of swaps are dropped), so
//! every node, and every range drawn, starts at an even triangle of its strip: decoded
//! from its first index with the rule of [`decode`](crate::decode), each triangle keeps
//! the winding it has in the strip, without an extra index. The price is that a pair
//! across the silhouette is drawn whole (its back-facing triangle is a *leak*, counted
//! by the callers).
//!
//! ```
//! use stripkit::cull::{helix_eyes, RenderFront, SegmentTree, Culled, CullOptions, HELIX_VIEWS};
//! use stripkit::{gen, stripify, Algorithm, SingleOptions, StripOptions, Weights};
//!
//! let mesh = gen::icosphere(3);
//! let single = Algorithm::Single(SingleOptions::new(Weights::Cull));
//! let strips = stripify(&mesh, &StripOptions::default().algorithm(single))?;
//! let positions = strips.with_added_vertices(&mesh.positions);
//! let tree = SegmentTree::build(&strips.strips, &positions);
//! let mut front = RenderFront::new(&tree);
//! let (mut a, mut b) = (Culled::default(), Culled::default());
//! for eye in helix_eyes([0.0; 3], 1.0, HELIX_VIEWS) {
//!     tree.cull(eye, &CullOptions::default(), &mut a);
//!     front.cull(&tree, eye, &CullOptions::default(), &mut b);
//!     assert_eq!(a.ranges, b.ranges);
//!     // About half the sphere faces away from the eye.
//!     assert!(a.culled_triangles > mesh.triangle_count() / 4);
//! }
//! # Ok::<(), stripkit::Error>(())
//! ```

mod bounds;
mod count;
mod frustum;
mod path;
pub mod survey;
mod traverse;
mod tree;

pub use bounds::Bounds;
pub use count::{FacingCounter, FacingCounts};
pub use frustum::{Frustum, Side};
pub use path::{bounding_sphere, helix_eyes, HELIX_VIEWS, MAX_VIEWS};
pub use traverse::{CullOptions, Culled, RenderFront};
pub use tree::{Node, SegmentTree};

/// "No node": the children of a leaf, the parent of a root ([`Node`] stores it as
/// `u32::MAX`).
const NONE: u32 = u32::MAX;

/// How a segment faces an eye point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Facing {
    /// Every triangle faces the eye: draw it.
    Front,
    /// Every triangle faces away (or is seen edge-on): skip it.
    Back,
    /// The test cannot tell: test the children (a leaf is drawn).
    Split,
}

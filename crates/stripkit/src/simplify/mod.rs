//! Quadric-error-metric edge collapse (Garland and Heckbert 1997) that records its
//! collapse sequence, the input of the multiresolution strip models of [`crate::lod`].
//!
//! * Per-vertex quadrics from area-weighted face planes; boundary edges add penalty
//!   planes perpendicular to their face, so borders keep their shape, and so do
//!   crease edges (faces folded by more than about 107 degrees: fin rims, ear edges)
//!   through each of their faces.
//! * A collapse costs its quadric error divided by the face area in its quadric (an
//!   area-averaged squared distance, so small features are not cheap to remove) plus
//!   a weighted *fan distance*: the largest squared distance of the edge's two current
//!   positions to the triangles around the new position, and of the new position to
//!   the triangles around the two old ones. Quadrics measure distances to planes, not
//!   triangles, and miss a tip that retreats within the nearly parallel planes of a
//!   thin part; the fan distance is what the collapse does to the surface, both ways.
//! * Candidates sit in a 4-ary min-heap with lazy invalidation (a vertex version stamp
//!   per endpoint), keyed by the quadric part (a lower bound) until they reach the top,
//!   where the fan distance is added and they are queued again if no longer the
//!   cheapest; O(n log n) overall.
//! * A collapse is refused when it would flip a triangle (against its current normal or
//!   its ancestor's in the input), make it degenerate, break the link condition
//!   (non-manifold result), pinch a boundary or duplicate a triangle.
//! * Around a vertex in more than 256 live triangles (a *hub*: a star's centre, a
//!   fanned polygon's first corner) the work of a collapse is bounded by the other
//!   end's valence: the hub is only ever kept, in place, and its other edges are not
//!   re-planned (see `collapse::HUB_TRIANGLES`); meshes without a hub are untouched.
//! * [`Placement::Endpoint`] is a half-edge collapse: the removed vertex moves onto the
//!   kept one, no new positions (what LoD strips need). [`Placement::Optimal`] puts the
//!   survivor at the cheapest (by the cost above) of the quadric's minimiser, both
//!   ends and the midpoint.
//!
//! * Vertex attributes (normals, UVs, colours, ...) follow the survivor: its own at
//!   its own position, interpolated along the edge by the new position's projection
//!   otherwise. Where the mesh has attributes, vertices sharing a position with
//!   another (the two sides of a seam) are kept in place, so seams stay closed. Face
//!   groups follow their triangles.
//!
//! Every collapse is recorded in a [`CollapseSequence`]; [`CollapseSequence::replay`]
//! of its first `k` records rebuilds exactly the simplifier's mesh after `k` collapses.
//! Vertex ids never change: the output keeps all vertex records (removed ones become
//! unreferenced), triangles keep their input order.

pub(crate) mod attributes;
mod collapse;
mod heap;
pub mod quadric;
mod sequence;

pub use sequence::{Collapse, CollapseSequence, Replayed};

use crate::error::{Error, Result};
use crate::mesh::Mesh;

/// Where the surviving vertex of a collapse goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Placement {
    /// Half-edge collapse: the removed vertex moves onto the kept one, which keeps its
    /// id and position.
    #[default]
    Endpoint,
    /// The cheapest of the point minimising the summed quadric, the two ends and
    /// their midpoint.
    Optimal,
}

crate::error::named_enum!(Placement, "placement", Endpoint => "endpoint", Optimal => "optimal");

/// When to stop collapsing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    /// Keep at most this fraction of the input triangles (0..=1).
    Ratio(f64),
    /// Keep at most this many triangles.
    Triangles(usize),
    /// Collapse while the cheapest collapse costs at most this much (a squared
    /// distance: the area-averaged quadric error plus the weighted fan distance, see
    /// the module documentation).
    Error(f64),
}

/// The triangle count [`Target::Ratio`] stops at: `ceil(ratio x triangles)`, the one
/// definition that `simplify`, [`CollapseSequence::level_for_ratio`] and the
/// level-of-detail models share.
pub fn ratio_target(triangles: usize, ratio: f64) -> usize {
    (triangles as f64 * ratio).ceil() as usize
}

/// Options of [`simplify`]: the defaults below unless changed with the builder
/// methods.
///
/// ```
/// use stripkit::simplify::{Options, Placement, Target};
/// let options = Options::default().target(Target::Ratio(0.1)).placement(Placement::Optimal);
/// assert_eq!((options.target, options.boundary_weight), (Target::Ratio(0.1), 100.0));
/// ```
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Options {
    /// When to stop. Default [`Target::Ratio`]`(0.5)`: half the triangles.
    pub target: Target,
    /// Survivor placement. Default [`Placement::Endpoint`].
    pub placement: Placement,
    /// Weight of the boundary penalty planes, relative to face planes of the same area
    /// (each boundary edge adds a plane weighted `boundary_weight * length^2`).
    /// Default 100.
    pub boundary_weight: f64,
    /// QSlim's pair contraction: also consider vertex pairs closer than this distance
    /// that share no edge (joins separate pieces; may create non-manifold vertices).
    /// `None` (the default) contracts edges only. Must be finite and not negative
    /// (0 finds no pair); anything else is [`Error::Invalid`]. A distance that finds
    /// more than 32 pairs per used vertex plus 2^20 is refused ([`Error::Invalid`])
    /// before the pairs are queued, since a distance near the mesh's size pairs every
    /// vertex with every other (gigabytes on a 35,000-vertex mesh).
    pub pair_distance: Option<f64>,
    /// Stop after this many collapses in any case. Default `None`: no limit.
    pub max_collapses: Option<usize>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            target: Target::Ratio(0.5),
            placement: Placement::Endpoint,
            boundary_weight: 100.0,
            pair_distance: None,
            max_collapses: None,
        }
    }
}

impl Options {
    /// Sets [`Options::target`].
    pub fn target(mut self, target: Target) -> Self {
        self.target = target;
        self
    }

    /// Sets [`Options::placement`].
    pub fn placement(mut self, placement: Placement) -> Self {
        self.placement = placement;
        self
    }

    /// Sets [`Options::boundary_weight`].
    pub fn boundary_weight(mut self, weight: f64) -> Self {
        self.boundary_weight = weight;
        self
    }

    /// Sets [`Options::pair_distance`].
    pub fn pair_distance(mut self, distance: Option<f64>) -> Self {
        self.pair_distance = distance;
        self
    }

    /// Sets [`Options::max_collapses`].
    pub fn max_collapses(mut self, collapses: Option<usize>) -> Self {
        self.max_collapses = collapses;
        self
    }
}

/// What [`simplify`] returns.
#[derive(Clone, Debug)]
pub struct Simplified {
    /// The simplified triangle mesh: all input vertex records (removed vertices
    /// unreferenced, survivors at their final positions, with their attributes),
    /// surviving triangles in input order with their face groups.
    pub mesh: Mesh,
    /// The input triangle id (`Mesh::triangulate` order) of each output triangle.
    pub triangle_ids: Vec<u32>,
    /// Every collapse, in order.
    pub sequence: CollapseSequence,
    /// Non-degenerate input triangles.
    pub triangles_in: usize,
    /// Largest error of any performed collapse.
    pub max_error: f64,
}

impl Simplified {
    /// Output triangles.
    pub fn triangles_out(&self) -> usize {
        self.triangle_ids.len()
    }
}

/// Simplifies `mesh` (faces are fanned into triangles first) by quadric edge collapse.
/// O(n log n). `progress` is called now and then with the fraction done (0..=1).
pub fn simplify(mesh: &Mesh, options: &Options, progress: &mut dyn FnMut(f64)) -> Result<Simplified> {
    if let Target::Ratio(r) = options.target {
        if !(0.0..=1.0).contains(&r) {
            return Err(Error::Invalid(format!("ratio {r} is not between 0 and 1")));
        }
    }
    if let Target::Error(e) = options.target {
        if e.is_nan() || e < 0.0 {
            return Err(Error::Invalid(format!("error bound {e} is not a non-negative number")));
        }
    }
    if !(options.boundary_weight >= 0.0 && options.boundary_weight.is_finite()) {
        return Err(Error::Invalid(format!("boundary weight {} is not a finite non-negative number", options.boundary_weight)));
    }
    if let Some(d) = options.pair_distance {
        if !(d >= 0.0 && d.is_finite()) {
            return Err(Error::Invalid(format!("pair distance {d} is not a finite non-negative number")));
        }
    }
    let n = mesh.positions.len();
    if mesh.face_indices.iter().any(|&v| v as usize >= n) {
        return Err(Error::Invalid(format!("a face refers to a vertex beyond the mesh's {n} vertices")));
    }
    if mesh.positions.iter().flatten().any(|x| !x.is_finite()) {
        return Err(Error::Invalid("a vertex position is not a finite number".into()));
    }
    mesh.check_attributes()?;
    let scale = crate::vec3::unit_scale(&mesh.positions);
    if scale == 1.0 {
        return collapse::run(mesh, options, progress);
    }
    scaled(mesh, options, scale, progress)
}

/// [`simplify`] of a mesh far from unit size (see `vec3::unit_scale`): run on the
/// positions times `scale`, a power of two, with the distances of the options scaled
/// alike, then everything measured scaled back to the input's units. The collapse
/// costs are squared distances, queued as f32: a mesh 1e20 across overflowed them
/// (`max error inf`, collapses in the wrong order) and one 1e-20 across lost them
/// in f32's subnormals; scaled, the collapses are those of the same mesh at unit size.
fn scaled(mesh: &Mesh, options: &Options, scale: f64, progress: &mut dyn FnMut(f64)) -> Result<Simplified> {
    let mut unit = mesh.clone();
    for p in &mut unit.positions {
        *p = p.map(|x| (x as f64 * scale) as f32);
    }
    let mut unit_options = options.clone();
    unit_options.pair_distance = options.pair_distance.map(|d| d * scale);
    if let Target::Error(e) = options.target {
        unit_options.target = Target::Error(e * scale * scale);
    }
    let mut out = collapse::run(&unit, &unit_options, progress).map_err(|e| match (e, unit_options.pair_distance) {
        // The refusal names the distance asked for, not the scaled one.
        (Error::Invalid(text), Some(d)) => Error::Invalid(text.replace(&format!("pair distance {d} "), &format!(
            "pair distance {} ",
            options.pair_distance.unwrap_or(d)
        ))),
        (e, _) => e,
    })?;
    let back = 1.0 / scale;
    let squared = back * back;
    // A vertex where the scaled input had it keeps its input position bit for bit
    // (f32 subnormals would not come back from scaling down and up).
    for ((p, q), original) in out.mesh.positions.iter_mut().zip(&unit.positions).zip(&mesh.positions) {
        *p = if p == q { *original } else { p.map(|x| (x as f64 * back) as f32) };
    }
    for c in &mut out.sequence.collapses {
        let kept = c.kept as usize;
        c.position = if c.position == unit.positions[kept] {
            mesh.positions[kept]
        } else {
            c.position.map(|x| (x as f64 * back) as f32)
        };
        c.error *= squared;
    }
    out.max_error *= squared;
    Ok(out)
}

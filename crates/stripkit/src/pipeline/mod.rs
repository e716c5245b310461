//! The front door: [`stripify`] chooses a stripifier, runs it, verifies what it made
//! and returns the strips with their figures; [`stripify_indices`] and
//! [`unstripify`] do the same for plain index buffers.
//!
//! Every result has passed an independent check before it is returned:
//! * triangle level: the strips decode (the reading rule of docs/metrics.md) to exactly the mesh's fan
//!   triangles, as multisets of oriented triangles (nothing lost, added or flipped);
//! * quad level, where the algorithm split quads along diagonals of its choosing
//!   (QSTRIP, quad-single, cache or balanced on QSTRIP's split): every quad is covered
//!   by two triangles forming it along one diagonal, with its winding, other faces by
//!   their fan; the triangles the strips chose are then the reference;
//! * the joined form ([`Join`]) is encoded, decoded again and checked once more.
//!
//! A failed check is [`Error::Verification`], never a silent result.
//!
//! (Over 1,000 lines because the door, its options, its result type [`Strips`] with
//! its encoders, and the per-group door share private helpers — `joined`,
//! `strip_range`, the checks — and a split would export them; a fifth is docs and
//! examples.)

use crate::error::{Error, Result};
use crate::mesh::io::{self, Format, WriteOptions};
use crate::mesh::Mesh;
use crate::metrics::{self, BatchModel, CacheModel, Figures};
use crate::strip::{self, StripSet};
use crate::stripify::cache::{self, CacheOptions, Diagonals};
use crate::stripify::greedy::{self, GreedyOptions};
use crate::stripify::single::{self, SingleOptions, SingleReport};
use crate::stripify::{quad, quad_single, quad_verify};
use std::ops::Range;
use std::time::{Duration, Instant};

mod groups;
use groups::run_groups;

/// Faces that must be quads for [`Algorithm::Auto`] to take QSTRIP (and for
/// [`Split::Auto`] to try QSTRIP's diagonals): half, where QSTRIP's strips beat
/// greedy's on the fan on every quad-dominant shared model.
pub const QUAD_DOMINANT: f64 = 0.5;

/// True when at least [`QUAD_DOMINANT`] of the mesh's faces are quads.
pub fn is_quad_dominant(mesh: &Mesh) -> bool {
    quad::quad_fraction(mesh) >= QUAD_DOMINANT
}

/// Which stripifier runs, with the settings that belong to it alone.
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub enum Algorithm {
    /// QSTRIP on quad-dominant meshes (see [`QUAD_DOMINANT`]), greedy otherwise; the
    /// result names the one that ran.
    #[default]
    Auto,
    /// Greedy lowest-degree strips with one-level look-ahead (van Kaick et al.), then
    /// tunnelling; on the mesh's fan triangulation.
    Greedy(GreedyOptions),
    /// QSTRIP: quad sequences made into strips, each quad split along the diagonal
    /// that needs the fewest swaps; other faces by greedy.
    Qstrip(quad::QuadOptions),
    /// One generalized strip per connected component of a closed pure-quad mesh.
    QuadSingle,
    /// Cache-aware short strips side by side under a simulated FIFO of
    /// [`StripOptions::cache`] entries. `refine`: then the local search of
    /// `balanced` with no move adding a miss (fewer indices and misses, about 30x
    /// the time).
    Cache {
        /// Refine the strips with the local search.
        refine: bool,
    },
    /// The fewest indices the cache-aware stripifier and its local search find while
    /// the cache misses per triangle stay at most `max_acmr`.
    Balanced {
        /// The most FIFO misses per triangle to accept (positive, finite).
        max_acmr: f64,
    },
    /// Strips planned for a GPU that shades vertices in batches ([`BatchModel`]):
    /// the mesh's fan cut into compact patches of one batch of triangles each, each
    /// patch covered by short swap-free strips side by side, every choice simulated
    /// on the model. The model predicts fewer shaded vertices than meshoptimizer's
    /// vertex-cache-optimized list on most shared models, but an H200 shades 9-15%
    /// more than modelled for these strips: 0-3% fewer than `cache` with a FIFO of 8
    /// (0.91 to 0.92 per triangle against the list's 0.82 to 0.85), at about 2
    /// indices per triangle, in about 100 times the time of `cache`. Experimental
    /// (docs/experiments/gpu-batch-strips.md).
    Batch(BatchModel),
    /// One strip per connected component (the fewest strips on meshes with boundaries)
    /// from a maximum-weight perfect matching of the dual graph, its loops merged at
    /// nodal vertices, by edge swaps on flat convex quads and by edge splits (Steiner
    /// vertices at edge midpoints): the mesh may change, and [`Strips::single`] says
    /// how. The weights steer the strip ([`SingleOptions`]).
    Single(SingleOptions),
}

impl Algorithm {
    /// Greedy with its default settings (fewest indices, tunnelling of one cut).
    pub fn greedy() -> Self {
        Algorithm::Greedy(GreedyOptions::default())
    }
    /// QSTRIP with its default settings.
    pub fn qstrip() -> Self {
        Algorithm::Qstrip(quad::QuadOptions::default())
    }
    /// The cache-aware stripifier without refinement.
    pub fn cache() -> Self {
        Algorithm::Cache { refine: false }
    }
    /// Balanced at the given bound on misses per triangle (0.8 in the CLI).
    pub fn balanced(max_acmr: f64) -> Self {
        Algorithm::Balanced { max_acmr }
    }
    /// Batch strips for the batch model fitted to an NVIDIA H100, planned with shorter
    /// reuse windows than fitted ([`BatchModel::NVIDIA_H100_PLANNING`]: the fewest
    /// vertices measured on an H200).
    pub fn batch() -> Self {
        Algorithm::Batch(BatchModel::NVIDIA_H100_PLANNING)
    }
    /// The lowercase name the CLI uses for this algorithm.
    pub fn name(&self) -> &'static str {
        match self {
            Algorithm::Auto => "auto",
            Algorithm::Greedy(_) => "greedy",
            Algorithm::Qstrip(_) => "qstrip",
            Algorithm::QuadSingle => "quad-single",
            Algorithm::Cache { .. } => "cache",
            Algorithm::Balanced { .. } => "balanced",
            Algorithm::Batch(_) => "batch",
            Algorithm::Single(_) => "single",
        }
    }
}

/// How faces of more than three corners become triangles before stripping.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Split {
    /// The algorithm's own choice: the fan for greedy; QSTRIP's diagonals for QSTRIP
    /// and quad-single; for cache and balanced, on quad-dominant meshes both the fan
    /// and QSTRIP's diagonals, keeping the cheaper strips, else the fan.
    #[default]
    Auto,
    /// Every face fanned from its first corner (the triangles other tools get).
    Fan,
    /// Quads along QSTRIP's diagonals (rows of quads run without swaps), other faces
    /// fanned. Quad-level verification.
    Qstrip,
}

impl Split {
    /// The lowercase name the CLI uses.
    pub fn name(self) -> &'static str {
        match self {
            Split::Auto => "auto",
            Split::Fan => "fan",
            Split::Qstrip => "qstrip",
        }
    }
}

/// How strips are joined into what is written or drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Join {
    /// One index buffer, strips separated by the primitive-restart index.
    #[default]
    Restart,
    /// One strip, strips stitched by degenerate triangles (winding kept).
    Degenerate,
    /// Each strip on its own.
    Separate,
}

impl Join {
    /// The lowercase name the CLI uses.
    pub fn name(self) -> &'static str {
        match self {
            Join::Restart => "restart",
            Join::Degenerate => "degenerate",
            Join::Separate => "separate",
        }
    }
}

/// Largest vertex cache [`StripOptions`] accepts: 65,536 entries (hardware caches hold
/// 16 to 128). The cache-aware stripifiers keep a ring of this many entries and tune
/// their walks to it, so a size read from the command line (`--cache 4294967295`)
/// must not size an allocation unchecked.
pub const MAX_CACHE_SIZE: usize = 1 << 16;

/// Most strip links one tunnel may cut ([`GreedyOptions::tunnel_cuts`]) that
/// [`StripOptions`] accepts. Each search from a strip end scores at most a fixed number
/// of relinkings (searches of four cuts or fewer never reach it), so a deeper search
/// costs no more time, but a depth read from the command line (`--tunnel 4294967295`)
/// must still be a sensible one.
pub const MAX_TUNNEL_CUTS: usize = 32;

/// Everything [`stripify`] needs to know. Build it from [`StripOptions::default`]
/// with the builder methods; fields that do not apply to the chosen algorithm are
/// rejected by [`stripify`] with [`Error::Invalid`].
///
/// ```
/// use stripkit::{Algorithm, Join, StripOptions};
/// let options = StripOptions::default()
///     .algorithm(Algorithm::balanced(0.8))
///     .cache_size(32)
///     .join(Join::Degenerate);
/// assert_eq!(options.cache.size, 32);
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct StripOptions {
    /// Which stripifier runs. Default [`Algorithm::Auto`].
    pub algorithm: Algorithm,
    /// The vertex cache: `cache` and `balanced` tune for a FIFO of `cache.size`
    /// entries, and [`Figures::acmr`] is measured with it (acmr16 and acmr32 are
    /// always measured too). Default FIFO of 16.
    pub cache: CacheModel,
    /// How quads are split. Default [`Split::Auto`].
    pub split: Split,
    /// How the strips are joined in [`Strips::joined`]. Default [`Join::Restart`].
    pub join: Join,
    /// The primitive-restart index of [`Join::Restart`]: never a vertex id of the
    /// mesh. Default `u32::MAX` (what `GL_PRIMITIVE_RESTART_FIXED_INDEX` uses).
    pub restart_index: u32,
}

impl Default for StripOptions {
    fn default() -> Self {
        StripOptions {
            algorithm: Algorithm::Auto,
            cache: CacheModel::fifo(16),
            split: Split::Auto,
            join: Join::Restart,
            restart_index: strip::DEFAULT_RESTART,
        }
    }
}

impl StripOptions {
    /// Sets the algorithm.
    pub fn algorithm(mut self, algorithm: Algorithm) -> Self {
        self.algorithm = algorithm;
        self
    }
    /// Sets the size of the FIFO the strips are tuned for and measured with: 1 to
    /// [`MAX_CACHE_SIZE`] entries (checked when stripifying).
    pub fn cache_size(mut self, entries: usize) -> Self {
        self.cache.size = entries;
        self
    }
    /// Sets the cache model of [`Figures::acmr`] (kind and size).
    pub fn cache_model(mut self, cache: CacheModel) -> Self {
        self.cache = cache;
        self
    }
    /// Sets how quads are split.
    pub fn split(mut self, split: Split) -> Self {
        self.split = split;
        self
    }
    /// Sets how strips are joined.
    pub fn join(mut self, join: Join) -> Self {
        self.join = join;
        self
    }
    /// Sets the primitive-restart index.
    pub fn restart_index(mut self, index: u32) -> Self {
        self.restart_index = index;
        self
    }

    /// Checks the options on their own (not against a mesh).
    fn check(&self) -> Result<()> {
        let bad = |m: String| Err(Error::Invalid(m));
        if self.cache.size == 0 {
            return bad("the cache size must be at least 1 (a cache of 0 entries misses every vertex)".into());
        }
        if self.cache.size > MAX_CACHE_SIZE {
            return bad(format!("the cache size {} is too large (at most {MAX_CACHE_SIZE} entries)", self.cache.size));
        }
        match &self.algorithm {
            Algorithm::Balanced { max_acmr } if !(max_acmr.is_finite() && *max_acmr > 0.0) => {
                bad(format!("balanced needs a positive number of misses per triangle as its bound (got {max_acmr})"))
            }
            Algorithm::Greedy(g) if g.tunnel_cuts.is_some_and(|n| n > MAX_TUNNEL_CUTS) => bad(format!(
                "greedy's tunnels may cut at most {MAX_TUNNEL_CUTS} strip links (got {})",
                g.tunnel_cuts.unwrap_or(0)
            )),
            Algorithm::Greedy(_) if self.split == Split::Qstrip => bad(
                "greedy strips the fan of every face; split qstrip applies to qstrip, quad-single, cache and balanced"
                    .into(),
            ),
            Algorithm::Single(_) if self.split == Split::Qstrip => bad(
                "single strips the fan of every face; split qstrip applies to qstrip, quad-single, cache and balanced"
                    .into(),
            ),
            Algorithm::Single(o) => o.check(),
            Algorithm::Batch(_) if self.split == Split::Qstrip => bad(
                "batch strips the fan of every face; split qstrip applies to qstrip, quad-single, cache and balanced"
                    .into(),
            ),
            Algorithm::Batch(m) if m.max_triangles == 0 || m.max_vertices < 3 || m.strip_window == 0 => bad(format!(
                "a batch model needs at least one triangle, three vertices and a window of one per batch (got {m:?})"
            )),
            Algorithm::Qstrip(_) | Algorithm::QuadSingle if self.split == Split::Fan => bad(format!(
                "{} chooses each quad's diagonal itself; split fan applies to greedy, cache and balanced",
                self.algorithm.name()
            )),
            Algorithm::Qstrip(q) if q.policies.is_empty() => bad("qstrip needs at least one walk policy".into()),
            _ => Ok(()),
        }
    }
}

/// Verified strips and what they were verified against.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Strips {
    /// The strips as the stripifier made them.
    pub strips: StripSet,
    /// The triangles the strips draw, each with its face's winding: the mesh's fan, or
    /// (quad-level verification) the split the strips chose. Degenerate triangles of the
    /// input are left in and counted in [`Figures::dropped_degenerate`].
    pub triangles: Vec<[u32; 3]>,
    /// The algorithm that ran, with its settings ([`Algorithm::Auto`] resolved).
    pub algorithm: Algorithm,
    /// How quads were split: [`Split::Fan`] or [`Split::Qstrip`] (quad-level check).
    pub split: Split,
    /// QSTRIP and quad-single: quads stripped as quads.
    pub quads: Option<usize>,
    /// Every figure of docs/metrics.md, measured against [`Strips::triangles`].
    pub figures: Figures,
    /// The join used.
    pub join: Join,
    /// The restart index of [`Join::Restart`].
    pub restart_index: u32,
    /// Time of the stripifier alone (no verification, no figures).
    pub stripify_time: Duration,
    /// [`Algorithm::Single`]: what the builder did (Steiner vertices, swaps, pieces
    /// merged, times).
    pub single: Option<SingleReport>,
    /// Vertices the algorithm added after the mesh's own (Steiner vertices of
    /// [`Algorithm::Single`], each at the midpoint of the edge it split): the strips
    /// and [`Strips::triangles`] index the mesh's positions followed by these.
    pub added_positions: Vec<[f32; 3]>,
    /// For each added vertex, the two vertices whose midpoint it is (an edge split);
    /// either may itself be an added vertex of a lower number.
    pub added_from: Vec<[u32; 2]>,
    /// For each face group of the mesh ([`Mesh::group_count`]: one for a mesh without
    /// groups), the range of [`Strips::strips`] drawing its faces. A strip never draws
    /// faces of two groups, and the joined forms never join strips of two groups.
    pub group_ranges: Vec<Range<usize>>,
}

impl Strips {
    /// The strips as [`Strips::join`] joins them, read back from the encoded form
    /// (the door checked this form too): the strips themselves for
    /// [`Join::Restart`] and [`Join::Separate`], one stitched strip for
    /// [`Join::Degenerate`].
    ///
    /// With several face groups, [`Join::Degenerate`] gives one stitched strip per
    /// group (in group order, empty groups left out), never one across groups.
    pub fn joined(&self) -> StripSet {
        joined(&self.strips, &self.group_ranges, self.join, self.restart_index)
    }

    /// One buffer with [`Strips::restart_index`] between strips (every group; a restart
    /// separates the strips of two groups, but one draw call gives them one material:
    /// see [`Strips::restart_buffer_of`]).
    pub fn restart_buffer(&self) -> Vec<u32> {
        strip::encode_restart(&self.strips, self.restart_index)
    }
    /// One strip, strips stitched by degenerate triangles. With several face groups
    /// this stitches across them; draw [`Strips::stitched_of`] each group instead.
    pub fn stitched(&self) -> Vec<u32> {
        strip::encode_stitched(&self.strips)
    }
    /// Number of face groups the strips are kept apart by (at least 1).
    pub fn group_count(&self) -> usize {
        self.group_ranges.len().max(1)
    }
    /// The strips of face group `g` (empty for a group without faces or past the last).
    pub fn strips_of(&self, g: usize) -> StripSet {
        let range = self.group_ranges.get(g).cloned().unwrap_or(0..0);
        strip_range(&self.strips, range)
    }
    /// The restart buffer of group `g`'s strips alone: one draw call with its material.
    pub fn restart_buffer_of(&self, g: usize) -> Vec<u32> {
        strip::encode_restart(&self.strips_of(g), self.restart_index)
    }
    /// Group `g`'s strips stitched into one by degenerate triangles.
    pub fn stitched_of(&self, g: usize) -> Vec<u32> {
        strip::encode_stitched(&self.strips_of(g))
    }
    /// The group of strip `s` (0 past the last).
    pub fn group_of_strip(&self, s: usize) -> usize {
        self.group_ranges.iter().position(|r| r.contains(&s)).unwrap_or(0)
    }
    /// `indices_restart / quads` of docs/metrics.md, for QSTRIP and quad-single.
    pub fn indices_per_quad(&self) -> Option<f64> {
        self.quads.filter(|&q| q > 0).map(|q| self.figures.indices_restart as f64 / q as f64)
    }

    /// The strips a file of `format` holds: PLY's `tristrips` ends each strip with -1
    /// (its own restart), or holds the one stitched strip of [`Join::Degenerate`]; core
    /// glTF has no restart index, so it gets the one stitched strip as a
    /// `TRIANGLE_STRIP` primitive, or one primitive per strip with [`Join::Separate`].
    /// `None` for formats that cannot hold strips (OBJ, OFF, STL; for OBJ,
    /// [`Strips::to_file_bytes`] writes the triangles in strip order instead).
    pub fn for_format(&self, format: Format) -> Option<StripSet> {
        match (format, self.join) {
            (Format::Ply, Join::Degenerate) | (Format::Gltf | Format::Glb, Join::Separate) => Some(self.joined()),
            (Format::Ply, _) => Some(self.strips.clone()),
            (Format::Gltf | Format::Glb, _) => {
                Some(joined(&self.strips, &self.group_ranges, Join::Degenerate, self.restart_index))
            }
            _ => None,
        }
    }

    /// The bytes of a `format` file holding `mesh`'s vertices and these strips (see
    /// [`Strips::for_format`]; OBJ gets the strips' triangles in strip order, group by
    /// group), read back with the library's own reader and checked against
    /// [`Strips::triangles`] before they are returned.
    pub fn to_file_bytes(&self, mesh: &Mesh, format: Format) -> Result<Vec<u8>> {
        self.to_file_bytes_with(mesh, format, &WriteOptions::default())
    }

    /// [`Strips::to_file_bytes`] with write options (ASCII PLY).
    pub fn to_file_bytes_with(&self, mesh: &Mesh, format: Format, options: &WriteOptions) -> Result<Vec<u8>> {
        let changed;
        let mesh = if !self.changes_mesh() {
            mesh
        } else {
            changed = self.changed_mesh(mesh);
            &changed
        };
        if format == Format::Obj {
            return self.obj_bytes(mesh, options);
        }
        let Some(to_write) = self.for_format(format) else {
            return Err(Error::Invalid(format!(
                "{format:?} files cannot hold strips; write PLY, glTF, GLB or OBJ (or JSON)"
            )));
        };
        let bytes = io::write_bytes(format, mesh, Some(&to_write), options)?;
        let name = format!("the {format:?} bytes to be written");
        let back = io::read_bytes(std::path::Path::new(&name), format, &bytes)?;
        let v = strip::verify_triangles(&self.triangles, &back.triangulate().tris);
        if !v.ok() {
            return Err(fail(&format!("{name}, read back"), &v));
        }
        Ok(bytes)
    }

    /// OBJ has no strips: the triangles the strips draw, in strip order (what a vertex
    /// cache sees), group by group with their `g`/`usemtl`, over the mesh's vertices and
    /// attributes; read back and checked (triangles and each one's group) before they
    /// are returned.
    fn obj_bytes(&self, mesh: &Mesh, options: &WriteOptions) -> Result<Vec<u8>> {
        let mut out = Mesh { face_offsets: vec![0], face_indices: Vec::new(), face_groups: Vec::new(), ..mesh.clone() };
        for g in 0..self.group_count() {
            for s in self.strips_of(g).iter() {
                strip::for_each_triangle(s, |t| {
                    out.push_face(&t);
                    out.face_groups.push(g as u32);
                });
            }
        }
        if out.groups.is_empty() {
            out.face_groups.clear();
        }
        let bytes = io::write_bytes(Format::Obj, &out, None, options)?;
        let name = "the Obj bytes to be written";
        let back = io::read_bytes(std::path::Path::new(name), Format::Obj, &bytes)?;
        // Welded on reading (vt or vn written): vertices renumbered by first use.
        let ids: Vec<u32> = if back.attributes.is_empty() {
            (0..out.vertex_count() as u32).collect()
        } else {
            let mut seen = vec![false; out.vertex_count()];
            out.face_indices.iter().copied().filter(|&v| !std::mem::replace(&mut seen[v as usize], true)).collect()
        };
        let tris: Vec<[u32; 3]> = back.triangulate().tris.iter().map(|t| t.map(|i| ids[i as usize])).collect();
        let v = strip::verify_triangles(&self.triangles, &tris);
        let group = |m: &Mesh, f: usize| m.groups.get(m.group_of(f) as usize).cloned().unwrap_or_default();
        let same_groups =
            back.face_count() == out.face_count() && (0..out.face_count()).all(|f| group(&back, f) == group(&out, f));
        if !v.ok() || !same_groups {
            return Err(fail(&format!("{name}, read back (groups kept: {same_groups})"), &v));
        }
        Ok(bytes)
    }

    /// Whether the strips draw a changed mesh (Steiner vertices or swapped edges).
    pub fn changes_mesh(&self) -> bool {
        !self.added_positions.is_empty() || self.single.as_ref().is_some_and(|r| r.swapped_edges > 0)
    }

    /// Per-vertex values (`values[v]` for each of the mesh's vertices: positions of
    /// another frame, normals, texture coordinates) extended over the added vertices,
    /// each the mean of the two it splits: what the changed mesh needs of them.
    pub fn with_added_vertices<const N: usize>(&self, values: &[[f32; N]]) -> Vec<[f32; N]> {
        let mut out = values.to_vec();
        out.reserve(self.added_from.len());
        for &[a, b] in &self.added_from {
            let (x, y) = (out[a as usize], out[b as usize]);
            out.push(std::array::from_fn(|d| ((x[d] as f64 + y[d] as f64) / 2.0) as f32));
        }
        out
    }

    /// The mesh the strips draw: `mesh` itself, or, where the algorithm changed it
    /// ([`Algorithm::Single`]), its positions plus [`Strips::added_positions`] and
    /// [`Strips::triangles`] as faces. Attributes follow: an added vertex gets the
    /// blend of the two it splits ([`Attribute::push_lerp`] at one half); so do the
    /// mesh's group (single takes one) and material libraries.
    ///
    /// [`Attribute::push_lerp`]: crate::Attribute::push_lerp
    pub fn changed_mesh(&self, mesh: &Mesh) -> Mesh {
        if !self.changes_mesh() {
            return mesh.clone();
        }
        let mut positions = mesh.positions.clone();
        positions.extend_from_slice(&self.added_positions);
        let mut out = Mesh::from_triangles(positions, &self.triangles);
        out.attributes = mesh.attributes.clone();
        for a in &mut out.attributes {
            for &[x, y] in &self.added_from {
                a.push_lerp(x as usize, y as usize, 0.5);
            }
        }
        out.groups = mesh.groups.clone();
        if !out.groups.is_empty() && mesh.face_count() > 0 {
            out.face_groups = vec![mesh.group_of(0); out.face_count()];
        }
        out.material_libraries = mesh.material_libraries.clone();
        out
    }

    /// The strips as JSON: `{"join", "strips": [[..], ..]}` (the joined strips), plus
    /// `"restart_index"` and `"indices"` (the restart buffer) with [`Join::Restart`], and
    /// with several face groups `"groups": [[start, end], ..]`, the entries of
    /// `"strips"` each group draws.
    pub fn to_json(&self) -> serde_json::Map<String, serde_json::Value> {
        let mut obj = serde_json::Map::new();
        obj.insert("join".into(), self.join.name().into());
        let strips: Vec<serde_json::Value> =
            self.joined().iter().map(|s| s.iter().map(|&i| serde_json::Value::from(i)).collect()).collect();
        obj.insert("strips".into(), strips.into());
        if self.group_ranges.len() > 1 {
            let mut next = 0;
            let groups: Vec<serde_json::Value> = self
                .group_ranges
                .iter()
                .map(|r| {
                    // Join::Degenerate stitches each non-empty group into one strip.
                    let n = if self.join == Join::Degenerate { usize::from(!r.is_empty()) } else { r.len() };
                    next += n;
                    serde_json::json!([next - n, next])
                })
                .collect();
            obj.insert("groups".into(), groups.into());
        }
        if self.join == Join::Restart {
            obj.insert("restart_index".into(), self.restart_index.into());
            obj.insert("indices".into(), self.restart_buffer().into());
        }
        obj
    }
}

/// A stripifier with its options checked once, for many meshes.
///
/// ```
/// use stripkit::{gen, Algorithm, StripOptions, Stripifier};
/// let mut s = Stripifier::new(StripOptions::default().algorithm(Algorithm::cache()))?;
/// for n in [4u32, 8] {
///     let strips = s.stripify(&gen::grid(n, n))?;
///     assert_eq!(strips.figures.triangles, (2 * n * n) as usize);
/// }
/// # Ok::<(), stripkit::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Stripifier {
    options: StripOptions,
}

impl Stripifier {
    /// Checks `options` (see [`StripOptions`]) and keeps them.
    pub fn new(options: StripOptions) -> Result<Self> {
        options.check()?;
        Ok(Stripifier { options })
    }

    /// The options in use.
    pub fn options(&self) -> &StripOptions {
        &self.options
    }

    /// [`stripify`] with these options.
    pub fn stripify(&mut self, mesh: &Mesh) -> Result<Strips> {
        run(mesh, &self.options)
    }
}

/// Strips for `mesh`, verified: chooses the algorithm ([`Algorithm::Auto`]), runs it,
/// checks the strips (triangle level, or quad level where the algorithm chose the
/// quads' diagonals) and their joined form, and measures them.
///
/// A mesh without faces gives no strips (verified, all figures 0).
///
/// Errors: [`Error::Invalid`] for options that do not apply (see [`StripOptions`]), a
/// face of fewer than three corners, an index past the
/// vertices, a restart index that is a vertex id, or a mesh quad-single cannot take;
/// [`Error::Verification`] if a check fails (a bug, reported rather than returned).
///
/// Cost: the algorithm's (greedy, QSTRIP and cache O(n) to O(n log n); `balanced` and
/// `cache` with refinement about 30x `cache`), plus an O(n log n) check.
///
/// ```
/// use stripkit::{gen, stripify, StripOptions};
/// let mesh = gen::icosphere(2);
/// let strips = stripify(&mesh, &StripOptions::default())?;
/// assert!(strips.figures.verified);
/// assert_eq!(strips.figures.triangles, mesh.triangle_count());
/// assert_eq!(strips.algorithm.name(), "greedy");
/// # Ok::<(), stripkit::Error>(())
/// ```
pub fn stripify(mesh: &Mesh, options: &StripOptions) -> Result<Strips> {
    options.check()?;
    run(mesh, options)
}

fn fail(what: &str, v: &strip::Verification) -> Error {
    Error::Verification(format!("{what}: {v}"))
}

/// The door's body, with the options already checked: per group where the mesh's
/// faces fall in several.
fn run(mesh: &Mesh, options: &StripOptions) -> Result<Strips> {
    mesh.check_faces()?;
    if mesh.has_groups() {
        return run_groups(mesh, options);
    }
    let mut strips = run_one(mesh, options)?;
    if mesh.group_count() > 1 {
        // Every face in one group (the first face's), the others empty.
        let g = mesh.group_of(0) as usize;
        let n = strips.strips.len();
        strips.group_ranges = (0..mesh.group_count()).map(|k| if k == g { 0..n } else { n..n }).collect();
    }
    Ok(strips)
}

/// Checks the restart index against the mesh's vertex ids and resolves
/// `Algorithm::Auto` (QSTRIP on quad-dominant meshes, else greedy).
fn resolve(mesh: &Mesh, options: &StripOptions) -> Result<Algorithm> {
    let vertex_count = mesh.vertex_count();
    if options.join == Join::Restart && (options.restart_index as usize) < vertex_count {
        return Err(Error::Invalid(format!(
            "restart index {} is a vertex id of the mesh ({vertex_count} vertices); choose one of at least {vertex_count}",
            options.restart_index
        )));
    }
    Ok(match &options.algorithm {
        Algorithm::Auto if is_quad_dominant(mesh) => Algorithm::qstrip(),
        Algorithm::Auto => Algorithm::greedy(),
        other => other.clone(),
    })
}

/// The door for one group of faces (the whole mesh), its faces already checked.
fn run_one(mesh: &Mesh, options: &StripOptions) -> Result<Strips> {
    let vertex_count = mesh.vertex_count();
    let algorithm = resolve(mesh, options)?;
    if options.algorithm == Algorithm::Auto && options.split != Split::Auto {
        // The split must suit the algorithm auto chose (QSTRIP takes no fan).
        StripOptions { algorithm: algorithm.clone(), ..options.clone() }.check()?;
    }
    // The fan is the greedy stripifier's input, made outside its timing.
    let fan = matches!(algorithm, Algorithm::Greedy(_) | Algorithm::Batch(_)).then(|| mesh.triangulate().tris);
    let mut added_positions = Vec::new();
    let mut added_from = Vec::new();
    let mut single_report = None;
    let mut stripify_time_single = None;
    let start = Instant::now();
    let (strips, split, quads, fan) = match &algorithm {
        Algorithm::Greedy(g) => {
            let tris = fan.unwrap_or_default();
            let strips = greedy::stripify(&tris, vertex_count, g);
            (strips, Split::Fan, None, Some(tris))
        }
        Algorithm::Batch(model) => {
            let tris = fan.unwrap_or_default();
            let strips = crate::stripify::batch::stripify(&tris, &mesh.positions, vertex_count, model);
            (strips, Split::Fan, None, Some(tris))
        }
        Algorithm::Qstrip(q) => {
            let (qs, strips) = quad::qstrip_mesh(mesh, q);
            (strips, Split::Qstrip, Some(qs.quad_count()), None)
        }
        Algorithm::QuadSingle => {
            let single = quad_single::quad_single(mesh)?;
            (single.strips, Split::Qstrip, Some(single.quads), None)
        }
        Algorithm::Cache { .. } | Algorithm::Balanced { .. } => {
            let size = options.cache.size as u32;
            let (cache_options, bound) = match algorithm {
                Algorithm::Balanced { max_acmr } => (CacheOptions::balanced(size), Some(max_acmr)),
                Algorithm::Cache { refine } => (CacheOptions { refine, ..CacheOptions::cache(size) }, None),
                _ => unreachable!("matched above"),
            };
            let diagonals = match options.split {
                Split::Auto => Diagonals::Auto,
                Split::Fan => Diagonals::Fan,
                Split::Qstrip => Diagonals::Qstrip,
            };
            let m = cache::stripify_mesh(mesh, &cache_options, bound, diagonals);
            if m.qstrip_diagonals {
                (m.strips, Split::Qstrip, None, None)
            } else {
                // Checked against the input's own fan, not the triangles the
                // stripifier reports: the check stays independent of it.
                (m.strips, Split::Fan, None, Some(mesh.triangulate().tris))
            }
        }
        Algorithm::Single(o) => {
            let input = mesh.triangulate().tris;
            let single = single::single_strips(&mesh.positions, input.clone(), o)?;
            stripify_time_single = Some(start.elapsed());
            if let Err(why) = single::check::cover(&input, &single.work) {
                return Err(Error::Verification(format!("the changed mesh of single: {why}")));
            }
            added_positions = single.work.pos[vertex_count..].iter().map(|p| p.map(|x| x as f32)).collect();
            added_from = single.work.steiner.clone();
            single_report = Some(single.report);
            (single.strips, Split::Fan, None, Some(single.work.tris))
        }
        Algorithm::Auto => unreachable!("resolved above"),
    };
    let stripify_time = stripify_time_single.unwrap_or_else(|| start.elapsed());
    let triangles = match fan {
        Some(tris) => tris,
        None => {
            // Either diagonal of a quad is right: check at quad level, then the
            // triangles the strips chose are the reference (the check proved them a
            // triangulation of the mesh with its winding).
            quad_verify::verify_quads(mesh, &strips)?;
            strip::decode(&strips)
        }
    };
    let figures = metrics::figures(&triangles, &strips, options.cache);
    if !figures.verified {
        return Err(fail("the strips", &strip::verify(&triangles, &strips)));
    }
    // The joined form is checked here and rebuilt on demand (`Strips::joined`): for
    // two of the three joins it is the strips themselves.
    let v = strip::verify(
        &triangles,
        &joined(&strips, std::slice::from_ref(&(0..strips.len())), options.join, options.restart_index),
    );
    if !v.ok() {
        return Err(fail(&format!("the strips joined by {}", options.join.name()), &v));
    }
    let strips_len = strips.len();
    Ok(Strips {
        strips,
        triangles,
        algorithm,
        split,
        quads,
        figures,
        join: options.join,
        restart_index: options.restart_index,
        stripify_time,
        single: single_report,
        added_positions,
        added_from,
        group_ranges: std::iter::once(0..strips_len).collect(),
    })
}

/// The strips as `join` joins them, read back from the encoded form; `groups` are the
/// ranges of strips that may be stitched together (one per face group).
fn joined(strips: &StripSet, groups: &[Range<usize>], join: Join, restart: u32) -> StripSet {
    match join {
        Join::Restart => strip::decode_restart(&strip::encode_restart(strips, restart), restart),
        Join::Degenerate => {
            let mut out = StripSet::new();
            for r in groups {
                let one = strip::encode_stitched(&strip_range(strips, r.clone()));
                if !one.is_empty() {
                    out.push(&one);
                }
            }
            out
        }
        Join::Separate => StripSet::from_strips(&strip::encode_separate(strips)),
    }
}

/// The strips `range` of a set (clamped to it).
fn strip_range(strips: &StripSet, range: Range<usize>) -> StripSet {
    let end = range.end.min(strips.len());
    let mut out = StripSet::new();
    for s in range.start.min(end)..end {
        out.push(strips.strip(s));
    }
    out
}

/// The most indices [`stripify_indices`] returns for `index_count` input indices, for
/// any options: 7 per input triangle (a lone triangle stitched at an odd position
/// takes 3 indices and 3 to join; a strip's swaps never outnumber its triangles).
/// Checked on every output.
pub fn stripify_bound(index_count: usize) -> usize {
    (index_count / 3).saturating_mul(7)
}

/// Strips for a plain triangle list, meshoptimizer-style: `indices` holds three
/// vertex ids per triangle, all below `vertex_count`. Returns one buffer: strips
/// separated by `restart_index` ([`Join::Restart`], which then must not be below
/// `vertex_count`) or one stitched strip ([`Join::Degenerate`]; `restart_index`
/// unused). At most [`stripify_bound`]`(indices.len())` indices, verified like
/// [`stripify`]'s, which it calls (positions are not needed: vertices are given
/// coincident positions, and orders that would use them fall back to vertex ids).
///
/// Errors: an empty list, a length that is not a multiple of 3, an index at or past
/// `vertex_count`, a restart index below `vertex_count`, [`Join::Separate`] (a flat
/// buffer cannot hold it), and everything [`stripify`] refuses.
///
/// ```
/// use stripkit::{stripify_indices, unstripify, StripOptions};
/// // A 2 x 1 quad grid: 4 triangles.
/// let tris = [0, 3, 1, 1, 3, 4, 1, 4, 2, 2, 4, 5];
/// let buf = stripify_indices(&tris, 6, u32::MAX, &StripOptions::default())?;
/// assert_eq!(buf.len(), 6); // one strip, no restart
/// let mut back = unstripify(&buf, u32::MAX);
/// assert_eq!(back.len(), tris.len());
/// # Ok::<(), stripkit::Error>(())
/// ```
pub fn stripify_indices(
    indices: &[u32],
    vertex_count: usize,
    restart_index: u32,
    options: &StripOptions,
) -> Result<Vec<u32>> {
    if indices.is_empty() {
        return Err(Error::Invalid("the index list is empty: nothing to strip".into()));
    }
    if indices.len() % 3 != 0 {
        return Err(Error::Invalid(format!(
            "{} indices is not a whole number of triangles (a multiple of 3)",
            indices.len()
        )));
    }
    if vertex_count > u32::MAX as usize {
        return Err(Error::Invalid(format!("{vertex_count} vertices do not fit 32-bit indices")));
    }
    if let Some(i) = indices.iter().position(|&v| v as usize >= vertex_count) {
        return Err(Error::Invalid(format!(
            "index {i} (triangle {}) is vertex {} but there are {vertex_count} vertices",
            i / 3,
            indices[i]
        )));
    }
    if options.join == Join::Separate {
        return Err(Error::Invalid(
            "a flat buffer holds restart-separated or stitched strips, not separate ones (join restart or degenerate)"
                .into(),
        ));
    }
    if let Algorithm::Single(_) = options.algorithm {
        return Err(Error::Invalid(
            "single may add vertices (edge splits) and swap edges, which a plain index buffer cannot return; \
             use stripify on a Mesh and read Strips::changed_mesh"
                .into(),
        ));
    }
    // Against the caller's vertex count, not only the vertices used.
    if options.join == Join::Restart && (restart_index as usize) < vertex_count {
        return Err(Error::Invalid(format!(
            "restart index {restart_index} is a vertex id ({vertex_count} vertices); choose one of at least {vertex_count}"
        )));
    }
    let options = StripOptions { restart_index, ..options.clone() };
    options.check()?;
    // Vertices past the largest index are unreferenced: leaving them out changes no
    // strip and keeps the allocation to the input's size.
    let used = indices.iter().map(|&v| v as usize + 1).max().unwrap_or(0);
    let tris: Vec<[u32; 3]> = indices.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let mesh = Mesh::from_triangles(vec![[0.0; 3]; used], &tris);
    let strips = run(&mesh, &options)?;
    let out = match options.join {
        Join::Degenerate => strips.stitched(),
        _ => strips.restart_buffer(),
    };
    if out.len() > stripify_bound(indices.len()) {
        return Err(Error::Verification(format!(
            "{} indices exceed the bound of {} for {} input indices",
            out.len(),
            stripify_bound(indices.len()),
            indices.len()
        )));
    }
    Ok(out)
}

/// The triangle list a strip buffer draws (the reading rule of docs/metrics.md), three indices per
/// triangle, in order; `restart_index` separates strips, degenerate triangles are
/// dropped. For a stitched strip pass any index it does not use (e.g. `u32::MAX`).
/// O(n).
pub fn unstripify(strip_indices: &[u32], restart_index: u32) -> Vec<u32> {
    let mut out = Vec::with_capacity(strip_indices.len().saturating_sub(2) * 3);
    for s in strip_indices.split(|&i| i == restart_index) {
        strip::for_each_triangle(s, |t| out.extend_from_slice(&t));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bound_covers_lone_triangles_stitched() {
        // Three triangles sharing no edge: each its own strip.
        let tris = [0, 1, 2, 3, 4, 5, 6, 7, 8];
        let options = StripOptions::default().join(Join::Degenerate);
        let out = stripify_indices(&tris, 9, 0, &options).unwrap();
        assert!(out.len() <= stripify_bound(tris.len()));
        let restart = stripify_indices(&tris, 9, 9, &StripOptions::default()).unwrap();
        assert_eq!(restart.len(), 11);
    }
}

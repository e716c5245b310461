//! The door's options: which stripifier runs ([`Algorithm`]), how quads are split
//! ([`Split`]) and strips joined ([`Join`]), the limits on what is accepted, and
//! [`StripOptions`], which holds them all and checks them on their own.

use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::metrics::{BatchModel, CacheModel};
use crate::strip;
use crate::stripify::greedy::GreedyOptions;
use crate::stripify::quad;
use crate::stripify::single::SingleOptions;

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
    /// vertices at edge midpoints): the mesh may change, and [`Strips::single`](super::Strips::single) says
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

/// Everything [`stripify`](super::stripify) needs to know. Build it from [`StripOptions::default`]
/// with the builder methods; fields that do not apply to the chosen algorithm are
/// rejected by [`stripify`](super::stripify) with [`Error::Invalid`].
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
    /// entries, and [`Figures::acmr`](crate::Figures::acmr) is measured with it (acmr16 and acmr32 are
    /// always measured too). Default FIFO of 16.
    pub cache: CacheModel,
    /// How quads are split. Default [`Split::Auto`].
    pub split: Split,
    /// How the strips are joined in [`Strips::joined`](super::Strips::joined). Default [`Join::Restart`].
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
    /// Sets the cache model of [`Figures::acmr`](crate::Figures::acmr) (kind and size).
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
    pub(super) fn check(&self) -> Result<()> {
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

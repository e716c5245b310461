//! The door's options: which stripifier runs ([`Algorithm`]), how quads are split
//! ([`Split`]) and strips joined ([`Join`]), the limits on what is accepted, and
//! [`StripOptions`], which holds them all and checks them on their own.

use crate::error::{Error, OptionName, Result};
use crate::mesh::Mesh;
use crate::metrics::{BatchModel, CacheModel};
use crate::strip;
use crate::error::named_enum;
use crate::stripify::greedy::GreedyOptions;
pub use crate::stripify::Split;
use crate::stripify::quad::{self, QuadOptions};
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
///
/// Each algorithm has a lowercase name ([`Algorithm::name`], listed in
/// [`Algorithm::NAMES`]); parsing a name ([`str::parse`]) gives that algorithm with
/// its default settings.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Algorithm {
    /// QSTRIP on quad-dominant meshes (see [`QUAD_DOMINANT`]), greedy otherwise, each
    /// with the settings [`AutoOptions`] holds for it; the result names the one that
    /// ran. The default algorithm.
    Auto(AutoOptions),
    /// Greedy lowest-degree strips with one-level look-ahead (van Kaick et al.), then
    /// tunnelling; on the mesh's fan triangulation.
    Greedy(GreedyOptions),
    /// QSTRIP: quad sequences made into strips, each quad split along the diagonal
    /// that needs the fewest swaps; other faces by greedy.
    Qstrip(QuadOptions),
    /// One generalized strip per connected component of a closed pure-quad mesh.
    QuadSingle,
    /// Cache-aware short strips side by side under a simulated FIFO of
    /// [`StripOptions::cache`] entries. `refine`: then the local search of
    /// `balanced` with no move adding a miss (fewer indices and misses, many times
    /// the time). Default without refinement.
    Cache {
        /// Refine the strips with the local search.
        refine: bool,
    },
    /// The fewest indices the cache-aware stripifier and its local search find while
    /// the cache misses per triangle stay at most `max_acmr` (FIFO of
    /// [`StripOptions::cache`] entries). A bound out of reach is no error: the
    /// strips then miss more, and [`Strips::max_acmr_unreached`](super::Strips::max_acmr_unreached)
    /// says how much. Default bound [`Algorithm::DEFAULT_MAX_ACMR`].
    Balanced {
        /// The most FIFO misses per triangle to accept (positive, finite).
        max_acmr: f64,
    },
    /// Strips planned for a GPU that shades vertices in batches ([`BatchModel`]):
    /// the mesh's fan cut into compact patches of one batch of triangles each, each
    /// patch covered by short swap-free strips side by side, every choice simulated
    /// on the model. Experimental: what a real GPU shades for them is measured in
    /// docs/experiments/gpu-batch-strips.md. Default model
    /// [`BatchModel::NVIDIA_H100_PLANNING`].
    Batch(BatchModel),
    /// One strip per connected component (the fewest strips on meshes with boundaries)
    /// from a maximum-weight perfect matching of the dual graph, its loops merged at
    /// nodal vertices, by edge swaps on flat convex quads and by edge splits (Steiner
    /// vertices at edge midpoints): the mesh may change, and [`Strips::single`](super::Strips::single) says
    /// how. The weights steer the strip ([`SingleOptions`]).
    Single(SingleOptions),
}

impl Default for Algorithm {
    /// [`Algorithm::Auto`] with its default settings.
    fn default() -> Self {
        Algorithm::Auto(AutoOptions::default())
    }
}

/// The settings [`Algorithm::Auto`] runs each algorithm it may choose with. Build it
/// from [`AutoOptions::default`] (both algorithms' defaults) with the builder methods.
///
/// ```
/// use stripkit::{Algorithm, AutoOptions, GreedyOptions, Heuristic};
/// let auto = Algorithm::Auto(AutoOptions::default().greedy(GreedyOptions::default().heuristic(Heuristic::Strips)));
/// assert_eq!(auto.name(), "auto");
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct AutoOptions {
    /// Greedy's settings, where auto takes greedy. Default [`GreedyOptions::default`].
    pub greedy: GreedyOptions,
    /// QSTRIP's settings, where auto takes QSTRIP. Default [`QuadOptions::default`].
    pub qstrip: QuadOptions,
}

impl AutoOptions {
    /// Sets greedy's settings.
    pub fn greedy(mut self, greedy: GreedyOptions) -> Self {
        self.greedy = greedy;
        self
    }
    /// Sets QSTRIP's settings.
    pub fn qstrip(mut self, qstrip: QuadOptions) -> Self {
        self.qstrip = qstrip;
        self
    }
    /// The algorithm auto takes on `mesh`: QSTRIP on quad-dominant meshes, else greedy.
    pub fn resolve(&self, mesh: &Mesh) -> Algorithm {
        if is_quad_dominant(mesh) {
            Algorithm::Qstrip(self.qstrip.clone())
        } else {
            Algorithm::Greedy(self.greedy)
        }
    }
}

impl Algorithm {
    /// Every algorithm's name, in the order of the variants.
    pub const NAMES: &'static [&'static str] =
        &["auto", "greedy", "qstrip", "quad-single", "cache", "balanced", "batch", "single"];

    /// The default bound of [`Algorithm::Balanced`]: 0.8 misses per triangle.
    pub const DEFAULT_MAX_ACMR: f64 = 0.8;

    /// Auto with its default settings (the default algorithm).
    pub fn auto() -> Self {
        Algorithm::default()
    }
    /// Greedy with its default settings (fewest indices, tunnelling of one cut).
    pub fn greedy() -> Self {
        Algorithm::Greedy(GreedyOptions::default())
    }
    /// QSTRIP with its default settings.
    pub fn qstrip() -> Self {
        Algorithm::Qstrip(QuadOptions::default())
    }
    /// The cache-aware stripifier without refinement.
    pub fn cache() -> Self {
        Algorithm::Cache { refine: false }
    }
    /// Balanced at the given bound on misses per triangle (default
    /// [`Algorithm::DEFAULT_MAX_ACMR`]).
    pub fn balanced(max_acmr: f64) -> Self {
        Algorithm::Balanced { max_acmr }
    }
    /// Batch strips for the batch model fitted to an NVIDIA H100, planned with shorter
    /// reuse windows than fitted ([`BatchModel::NVIDIA_H100_PLANNING`]).
    pub fn batch() -> Self {
        Algorithm::Batch(BatchModel::NVIDIA_H100_PLANNING)
    }
    /// The lowercase name of this algorithm (one of [`Algorithm::NAMES`]).
    pub fn name(&self) -> &'static str {
        match self {
            Algorithm::Auto(_) => "auto",
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

impl std::str::FromStr for Algorithm {
    type Err = Error;
    /// The algorithm of this name ([`Algorithm::NAMES`]) with its default settings.
    fn from_str(s: &str) -> Result<Self> {
        Ok(match s {
            "auto" => Algorithm::auto(),
            "greedy" => Algorithm::greedy(),
            "qstrip" => Algorithm::qstrip(),
            "quad-single" => Algorithm::QuadSingle,
            "cache" => Algorithm::cache(),
            "balanced" => Algorithm::balanced(Algorithm::DEFAULT_MAX_ACMR),
            "batch" => Algorithm::batch(),
            "single" => Algorithm::Single(SingleOptions::default()),
            _ => return Err(crate::error::unknown("algorithm", s, Algorithm::NAMES)),
        })
    }
}

/// How strips are joined into what is written or drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Join {
    /// One index buffer, strips separated by the primitive-restart index (the
    /// default).
    #[default]
    Restart,
    /// One strip, strips stitched by degenerate triangles (winding kept).
    Degenerate,
    /// Each strip on its own.
    Separate,
}

named_enum!(Join, "join", Restart => "restart", Degenerate => "degenerate", Separate => "separate");

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
    /// Weld bit-identical vertices before stripping ([`Mesh::welded`]): faces move onto
    /// the lowest id of each set of vertices equal in position bits and every attribute,
    /// so that an unindexed mesh (every triangle its own three vertices) strips as a
    /// connected surface. Vertex data and ids are kept; the strips and
    /// [`Strips::triangles`](super::Strips::triangles) use the welded ids and
    /// [`Strips::welded`](super::Strips::welded) counts the vertices left unused. Default `true`.
    pub weld: bool,
    /// Threads the door may use for independent work: a mesh's groups, a glTF scene's
    /// primitives, the two candidates of [`Split::Auto`]. The strips are the same at
    /// any count. Default one (the library starts no thread unless asked); more need
    /// the `parallel` feature.
    pub threads: crate::parallel::Threads,
    /// `cache` (without a bound) on meshes of more triangles than this: the partitioned
    /// mode, where ranges of about 262,144 triangles of the canonical (Z-order) list
    /// are stripified on their own, in parallel when [`StripOptions::threads`]
    /// allows, and joined across their borders. The parts depend on the mesh only:
    /// the strips are the same at any thread count; `0` never cuts. Default
    /// [`DEFAULT_PARTITION_ABOVE`] (1,000,000): the parts cost a few indices and misses
    /// (measured: +0.17% indices and +0.004 ACMR on a 4.4M-triangle subdivided bunny,
    /// but +1.2% and +0.008 on a 1.3M-triangle icosphere), for about half the peak
    /// memory and, on two threads, about half the stripifier's time.
    pub partition_above: u32,
}

/// The default of [`StripOptions::partition_above`]: meshes of more than 1,000,000
/// triangles are cut into parts. Every shared model (at most 100,000 triangles) and
/// every test mesh stays whole; above it the whole-mesh stripifier takes about half a
/// second or more, which two threads halve.
pub const DEFAULT_PARTITION_ABOVE: u32 = 1_000_000;

impl Default for StripOptions {
    fn default() -> Self {
        StripOptions {
            algorithm: Algorithm::default(),
            cache: CacheModel::fifo(16),
            split: Split::Auto,
            join: Join::Restart,
            restart_index: strip::DEFAULT_RESTART,
            weld: true,
            threads: crate::parallel::Threads::SERIAL,
            partition_above: DEFAULT_PARTITION_ABOVE,
        }
    }
}

impl StripOptions {
    /// Sets the size above which `cache` cuts a mesh into parts
    /// ([`StripOptions::partition_above`]; `0` never).
    pub fn partition_above(mut self, triangles: u32) -> Self {
        self.partition_above = triangles;
        self
    }

    /// Sets the threads for independent work ([`StripOptions::threads`]).
    pub fn threads(mut self, threads: crate::parallel::Threads) -> Self {
        self.threads = threads;
        self
    }

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
    /// Sets [`StripOptions::weld`].
    pub fn weld(mut self, on: bool) -> Self {
        self.weld = on;
        self
    }

    /// Checks the options on their own (not against a mesh).
    pub(super) fn check(&self) -> Result<()> {
        use OptionName as O;
        let bad = |option, m: String| Err(Error::option(option, m));
        if self.cache.size == 0 {
            return bad(O::CacheSize, "must be at least 1 (a cache of 0 entries misses every vertex)".into());
        }
        if self.cache.size > MAX_CACHE_SIZE {
            return bad(O::CacheSize, format!("{} is too large (at most {MAX_CACHE_SIZE} entries)", self.cache.size));
        }
        let fan_only = |name: &str| {
            bad(O::Split, format!("qstrip applies to qstrip, quad-single, cache and balanced; {name} strips the fan of every face"))
        };
        match &self.algorithm {
            Algorithm::Auto(auto) => check_greedy(&auto.greedy).and_then(|()| check_quad(&auto.qstrip)),
            Algorithm::Balanced { max_acmr } if !(max_acmr.is_finite() && *max_acmr > 0.0) => {
                bad(O::MaxAcmr, format!("must be a positive number of misses per triangle (got {max_acmr})"))
            }
            Algorithm::Greedy(_) | Algorithm::Single(_) | Algorithm::Batch(_) if self.split == Split::Qstrip => {
                fan_only(self.algorithm.name())
            }
            Algorithm::Greedy(g) => check_greedy(g),
            Algorithm::Single(o) => o.check(),
            Algorithm::Batch(m) if m.max_triangles == 0 || m.max_vertices < 3 || m.strip_window == 0 => bad(
                O::BatchModel,
                format!("needs at least one triangle, three vertices and a window of one per batch (got {m:?})"),
            ),
            Algorithm::Qstrip(_) | Algorithm::QuadSingle if self.split == Split::Fan => bad(
                O::Split,
                format!(
                    "fan applies to greedy, cache and balanced; {} chooses each quad's diagonal itself",
                    self.algorithm.name()
                ),
            ),
            Algorithm::Qstrip(q) => check_quad(q),
            _ => Ok(()),
        }
    }
}

/// Greedy's settings on their own.
fn check_greedy(g: &GreedyOptions) -> Result<()> {
    match g.tunnel_cuts {
        Some(n) if n > MAX_TUNNEL_CUTS => Err(Error::option(
            OptionName::TunnelCuts,
            format!("{n} is too many: greedy's tunnels may cut at most {MAX_TUNNEL_CUTS} strip links"),
        )),
        _ => Ok(()),
    }
}

/// QSTRIP's settings on their own.
fn check_quad(q: &QuadOptions) -> Result<()> {
    if q.policies.is_empty() {
        return Err(Error::option(OptionName::QuadPolicies, "must hold at least one walk policy"));
    }
    Ok(())
}

//! The flags of `stripkit strip` and the strip flags that `render` and `lod` share
//! ([`StripArgs`]), and how they become the library's [`StripOptions`]. An unset flag
//! leaves the library's default; the values of enum flags are the library's types.

use super::super::{flag_error, named};
use std::path::{Path, PathBuf};
use stripkit::io::Format;
use stripkit::{Algorithm, CacheModel, Error, GreedyOptions, Heuristic, Join, MatchingMode, Split, StripOptions, Stripifier};

/// The strip options: which stripifier and its settings. `stripkit strip` and
/// `stripkit render` both take them (flattened), so that a picture shows the strips
/// `strip` writes. Defaults are the library's.
#[derive(clap::Args, Clone, Debug)]
pub struct StripArgs {
    /// Stripifier: auto (qstrip on meshes at least half quads, else greedy), greedy, qstrip, quad-single (closed quad meshes), cache, balanced, batch (experimental), single (one strip per component). Default auto.
    #[arg(long, value_name = "ALGO", value_parser = named::<Algorithm>(Algorithm::NAMES), hide_possible_values = true)]
    pub algo: Option<Algorithm>,
    /// Greedy (and auto): minimise strips or indices (a swap costing one index). Default indices.
    #[arg(long, value_parser = named::<Heuristic>(Heuristic::NAMES), hide_possible_values = true)]
    pub heuristic: Option<Heuristic>,
    /// Greedy (and auto): strip links one tunnel may cut after the greedy pass, 0 to 32; 0 is the plain greedy. Default 1.
    #[arg(long, value_name = "N", value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(0..=stripkit::MAX_TUNNEL_CUTS as u64))]
    pub tunnel: Option<usize>,
    /// Vertex-cache entries (1 to 65,536): the FIFO cache and balanced tune for, and the cache of the acmr figure; their candidate scan grows with it (O(triangles x cache) at worst). Default 16.
    #[arg(long, value_name = "N")]
    pub cache: Option<usize>,
    /// Balanced: the most cache misses per triangle to accept for fewer indices. Default 0.8.
    #[arg(long, value_name = "ACMR")]
    pub max_acmr: Option<f64>,
    /// How quads are split: auto (the algorithm's choice; cache and balanced try both on quad meshes), fan, or qstrip (QSTRIP's diagonals). Default auto.
    #[arg(long, alias = "diagonals", value_parser = named::<Split>(Split::NAMES), hide_possible_values = true)]
    pub split: Option<Split>,
    /// Cache: then refine the strips with balanced's local search (fewer indices and misses, much slower).
    #[arg(long)]
    pub refine: bool,
    /// Cache: cut meshes of more triangles than N into parts of about 262,144 (Z-order ranges), stripified in parallel and joined across their borders (the same strips at any --threads): about half the memory and, on 2 threads, half the stripifier's time, for +0.2% to +1.2% indices; 0 never (the whole-mesh run). Default 1000000.
    #[arg(long, value_name = "N")]
    pub partition_above: Option<u32>,
    /// Simulate an LRU cache for the acmr figure instead of FIFO.
    #[arg(long)]
    pub lru: bool,
    /// Single: what steers the strip: uniform, cull, cache, direction:X,Y,Z or mix:cull=0.5,cache=0.5. Default uniform.
    #[arg(long, value_name = "W")]
    pub weights: Option<String>,
    /// Single: swap an edge only where its triangles' normals differ by at most this (0 to 90), or off. Default 5.
    #[arg(long, value_name = "DEGREES")]
    pub swap_angle: Option<String>,
    /// Single with cull weights: the most normal deviation inside a cluster. Default 30.
    #[arg(long, value_name = "DEGREES")]
    pub cull_angle: Option<f64>,
    /// Single with cull weights: seeded noise on the weights, which speeds up the matching (on or off). Default on.
    #[arg(long, value_name = "ON|OFF")]
    pub cull_noise: Option<String>,
    /// Single: seed of the randomized parts. Default 1.
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// Single: how the dual graph is matched (exact, greedy, or auto: exact where affordable). Default auto.
    #[arg(long, value_parser = named::<MatchingMode>(MatchingMode::NAMES), hide_possible_values = true)]
    pub matching: Option<MatchingMode>,
    /// Keep vertices that are bit-identical in position and every attribute apart (by default faces are moved onto one of them before stripping, as gltfpack welds).
    #[arg(long)]
    pub no_weld: bool,
}

/// The order of the vertices in the output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum VertexOrder {
    // (Plain comments: value docs would make `--help` list each value on its own lines.)
    // Renumbered in the order the strips first use them; vertices no face uses are
    // dropped (meshoptimizer's `optimizeVertexFetch`).
    #[allow(missing_docs)]
    FirstUse,
    // As in the input, every vertex kept (ids stay the input's).
    #[allow(missing_docs)]
    Input,
}

/// Arguments of `stripkit strip`.
#[derive(clap::Args, Clone, Debug)]
#[command(after_help = "Output by extension of OUT: .ply (a `tristrips` element), .json (strips and figures), \
    .gltf/.glb (a stitched TRIANGLE_STRIP plus EXT_mesh_primitive_restart; a glTF input keeps its whole scene), \
    .obj (the strips' triangles in strip order). Exit status: 0 success, 1 verification failed (nothing written), \
    2 bad input or argument. Formats, figures and measurements: docs/cli.md, docs/experiments/front-door.md.")]
pub struct Args {
    /// Input mesh (.obj, .ply, .off, .stl, .gltf, .glb, optionally .gz), `-` for standard input, or a folder of them.
    pub input: PathBuf,
    /// Output: .ply, .json, .gltf, .glb or .obj; `-` for standard output; a folder for a folder input.
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Format written to standard output or into an output folder: ply, gltf or glb.
    #[arg(long, value_name = "FORMAT", value_parser = super::super::parse_format)]
    pub output_format: Option<Format>,
    /// Write PLY as ASCII text instead of binary.
    #[arg(long)]
    pub ascii: bool,
    #[command(flatten)]
    pub strip: StripArgs,
    /// How strips are joined: restart (restart index between strips), degenerate (one stitched strip) or separate. Default restart.
    #[arg(long, value_parser = named::<Join>(Join::NAMES), hide_possible_values = true)]
    pub join: Option<Join>,
    /// Order of the written vertices: first-use (renumbered as the strips first use them, unused ones dropped) or input. Default first-use for glTF, input otherwise.
    #[arg(long, value_enum)]
    pub vertex_order: Option<VertexOrder>,
    /// Primitive-restart index for join restart; must not be a vertex id. Default 4294967295.
    #[arg(long, value_name = "N")]
    pub restart_index: Option<u32>,
    /// glTF output: write index and vertex data compressed with EXT_meshopt_compression (index-sequence codec for the strips), required by the file.
    #[arg(long)]
    pub compress: bool,
    /// Print one JSON object with every figure instead of the text summary.
    #[arg(long)]
    pub json: bool,
    /// Print the seconds of each phase (read, strip with its check, encode, write) to standard error.
    #[arg(long)]
    pub timings: bool,
    #[command(flatten)]
    pub read: super::super::ReadArgs,
}

impl Args {
    /// `strip`'s own options on top of the strip flags: the join and its restart index.
    pub fn with_join(&self, mut options: StripOptions) -> StripOptions {
        if let Some(join) = self.join {
            options = options.join(join);
        }
        if let Some(index) = self.restart_index {
            options = options.restart_index(index);
        }
        options
    }
}

impl StripArgs {
    /// The algorithm `--algo` names, with its default settings.
    fn algorithm(&self) -> Algorithm {
        self.algo.clone().unwrap_or_default()
    }

    /// Flags that belong to one algorithm, given with another: an error, not silence.
    pub fn check(&self) -> Result<(), Error> {
        let bad = |m: &str| Err(Error::Invalid(m.to_string()));
        let algo = self.algorithm();
        if self.refine && !matches!(algo, Algorithm::Cache { .. }) {
            return bad("--refine applies to --algo cache (balanced always refines)");
        }
        if self.partition_above.is_some() && !matches!(algo, Algorithm::Cache { .. }) {
            return bad("--partition-above applies to --algo cache");
        }
        if self.max_acmr.is_some() && !matches!(algo, Algorithm::Balanced { .. }) {
            return bad("--max-acmr applies to --algo balanced");
        }
        let splits_quads = matches!(algo, Algorithm::Cache { .. } | Algorithm::Balanced { .. } | Algorithm::Auto(_));
        if self.split == Some(Split::Auto) && !splits_quads {
            return bad("--split auto applies to --algo cache and balanced (the others split quads their own way)");
        }
        if (self.heuristic.is_some() || self.tunnel.is_some()) && !matches!(algo, Algorithm::Greedy(_) | Algorithm::Auto(_)) {
            return bad("--heuristic and --tunnel apply to --algo greedy (and auto on meshes that are not quad-dominant)");
        }
        let single_flags = self.weights.is_some()
            || self.swap_angle.is_some()
            || self.cull_angle.is_some()
            || self.cull_noise.is_some()
            || self.seed.is_some()
            || self.matching.is_some();
        if single_flags && !matches!(algo, Algorithm::Single(_)) {
            return bad("--weights, --swap-angle, --cull-angle, --cull-noise, --seed and --matching apply to --algo single");
        }
        self.options().map(|_| ())
    }

    /// Greedy's settings with `--heuristic` and `--tunnel` applied.
    fn greedy(&self, mut g: GreedyOptions) -> GreedyOptions {
        if let Some(h) = self.heuristic {
            g = g.heuristic(h);
        }
        if let Some(n) = self.tunnel {
            g = g.tunnel_cuts(Some(n).filter(|&n| n > 0));
        }
        g
    }

    /// `--algo single`'s settings with its flags applied.
    fn single(&self, mut o: stripkit::SingleOptions) -> Result<stripkit::SingleOptions, Error> {
        if let Some(w) = &self.weights {
            o = o.weights(w.parse::<stripkit::Weights>().map_err(flag_error)?);
        }
        if let Some(a) = &self.swap_angle {
            o = o.swap_angle(if a == "off" {
                None
            } else {
                Some(a.parse::<f64>().map_err(|_| {
                    Error::Invalid(format!("--swap-angle '{a}': expected degrees (0 to 90) or 'off'"))
                })?)
            });
        }
        if let Some(a) = self.cull_angle {
            o = o.cull_angle(a);
        }
        if let Some(n) = &self.cull_noise {
            o = o.cull_noise(match n.as_str() {
                "on" => true,
                "off" => false,
                _ => return Err(Error::Invalid(format!("--cull-noise '{n}': expected on or off"))),
            });
        }
        if let Some(s) = self.seed {
            o = o.seed(s);
        }
        if let Some(m) = self.matching {
            o = o.matching(m);
        }
        Ok(o)
    }

    /// The library's options for these flags (the library's join and restart index):
    /// the algorithm `--algo` names with the flags given for it applied, every other
    /// setting the library's default.
    pub fn options(&self) -> Result<StripOptions, Error> {
        let mut algorithm = self.algorithm();
        match &mut algorithm {
            Algorithm::Auto(auto) => auto.greedy = self.greedy(auto.greedy),
            Algorithm::Greedy(g) => *g = self.greedy(*g),
            Algorithm::Cache { refine } => *refine |= self.refine,
            Algorithm::Balanced { max_acmr } => *max_acmr = self.max_acmr.unwrap_or(*max_acmr),
            Algorithm::Single(o) => *o = self.single(o.clone())?,
            _ => {}
        }
        let mut options = StripOptions::default().algorithm(algorithm).threads(crate::cmd::threads());
        if let Some(n) = self.partition_above {
            options = options.partition_above(n);
        }
        if self.no_weld {
            options = options.weld(false);
        }
        if let Some(split) = self.split {
            options = options.split(split);
        }
        let size = self.cache.unwrap_or(options.cache.size);
        options = options.cache_model(if self.lru { CacheModel::lru(size) } else { CacheModel::fifo(size) });
        Ok(options)
    }

    /// Checks the flags before any file is read: each flag with its own algorithm, and
    /// the options (`more` adds the command's own) as the library will take them.
    pub fn validate(&self, more: impl FnOnce(StripOptions) -> StripOptions) -> anyhow::Result<()> {
        self.check()?;
        Stripifier::new(more(self.options()?)).map_err(flag_error)?;
        Ok(())
    }

    /// Strips `mesh`, read from `input`, through the door with these flags (`more`
    /// adds the command's own options); errors name the flags and the file.
    pub fn stripify(
        &self,
        mesh: &stripkit::Mesh,
        input: &Path,
        more: impl FnOnce(StripOptions) -> StripOptions,
    ) -> anyhow::Result<stripkit::Strips> {
        self.check_mesh(mesh, input)?;
        let mut stripifier = Stripifier::new(more(self.options()?)).map_err(flag_error)?;
        stripifier.stripify(mesh).map_err(|e| anyhow::anyhow!(flag_error(e)).context(format!("{}", input.display())))
    }

    /// Flags that cannot apply to this mesh: `--algo qstrip` on a mesh without a quad
    /// would silently run greedy.
    pub fn check_mesh(&self, mesh: &stripkit::Mesh, input: &Path) -> Result<(), Error> {
        if matches!(self.algo, Some(Algorithm::Qstrip(_))) && !mesh.faces().any(|f| f.len() == 4) {
            return Err(Error::Invalid(format!(
                "{}: --algo qstrip strips quads and this mesh has none (it would run greedy); use --algo greedy or cache",
                input.display()
            )));
        }
        Ok(())
    }
}

/// The heuristic greedy ran with, for reports: `None` for other algorithms.
pub fn heuristic_of(algorithm: &Algorithm) -> Option<&'static str> {
    match algorithm {
        Algorithm::Greedy(g) => Some(g.heuristic.name()),
        _ => None,
    }
}

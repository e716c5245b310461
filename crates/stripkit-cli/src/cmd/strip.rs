//! `stripkit strip`: read a mesh, turn it into triangle strips, check them, print their
//! figures and write them out.
//!
//! Every run verifies what it writes: the encoded buffer (after the chosen join) is
//! decoded again and, for PLY and glTF, the written bytes are read back, and the
//! triangles must equal the input's (nothing lost, nothing added, no winding flipped).
//! A failed check writes nothing and exits with status 1.
//!
//! The work is the library's front door ([`stripkit::stripify`]): this module maps
//! flags to [`StripOptions`], writes what the door returns and prints its figures.
//! Adding a stripifier: a variant of [`Algo`] and its line in [`options`].

use clap::ValueEnum;
use serde::Serialize;
use std::io::Write;
use std::path::{Path, PathBuf};
use stripkit::io::Format;
use stripkit::{
    Algorithm, CacheKind, CacheModel, Error, Figures, GreedyOptions, Heuristic, Split, StripOptions, Stripifier,
    DEFAULT_RESTART,
};

/// The stripifying algorithm.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Algo {
    /// QSTRIP for pure-quad and quad-dominant meshes (at least half the faces are
    /// quads), greedy otherwise.
    Auto,
    /// Greedy lowest-degree strips with one-level look-ahead (van Kaick et al. 2004).
    Greedy,
    /// QSTRIP (Vaněček et al.): quad sequences turned into strips, each quad split
    /// along the diagonal that needs the fewest swaps; other faces by greedy.
    Qstrip,
    /// One generalized strip per connected component of a closed pure-quad mesh
    /// (after Taubin 2002: cycle cover of the quads, cycles spliced into one).
    #[serde(rename = "quad-single")]
    QuadSingle,
    /// Cache-aware short strips laid side by side, tuned for a FIFO of `--cache` entries:
    /// fewer cache misses than meshoptimizer's cache order on most meshes, with about a
    /// fifth fewer indices than its strips.
    Cache,
    /// Cache-aware strips with the fewest indices that keep the cache misses per
    /// triangle at most `--max-acmr`: the `cache` stripifier at the lightest miss
    /// weight that keeps the bound, then strips joined by a local search scored on the
    /// exact FIFO (bunny: 1.22 indices per triangle at 0.80 misses).
    Balanced,
    /// Strips planned for a GPU that shades vertices in batches (the batch model fitted
    /// to an NVIDIA H100: 30 triangles, strips reusing recently shaded vertices):
    /// compact one-batch patches of short strips, about 2 indices per triangle. Fans
    /// every face. Experimental: an H200 shades as many vertices for them as for
    /// `cache --cache 8`, more than for meshoptimizer's cache-optimized list.
    Batch,
    /// One strip per connected component from a maximum-weight perfect matching of the
    /// dual graph (Gopi and Eppstein; weights as in "Constrained single strips"): the
    /// loops the matching leaves are merged at nodal vertices, by edge swaps on flat
    /// convex quads (`--swap-angle`) and by edge splits, which add a vertex at an edge's
    /// midpoint. The written mesh holds those vertices and swaps; the report counts
    /// them. `--weights` steers the strip. Meshes with boundaries get the fewest strips
    /// the merges reach.
    Single,
}

/// How `cache` and `balanced` split quads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum DiagonalsArg {
    /// On quad-dominant meshes try both and keep the cheaper strips; fan otherwise.
    Auto,
    /// Fan every face from its first corner (the triangles other tools get).
    Fan,
    /// Split quads along QSTRIP's diagonals (swap-free rows of quads).
    Qstrip,
}

/// What the greedy choice optimises.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum HeuristicArg {
    /// Fewest strips; swaps allowed (for hardware where a swap is free).
    Strips,
    /// Fewest indices when a swap costs a repeated index (prefers no swap on a tie).
    Indices,
}

/// How the strips are joined in the output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Join {
    /// One index buffer, strips separated by the primitive-restart index.
    Restart,
    /// One strip, strips stitched by degenerate triangles (winding kept).
    Degenerate,
    /// Each strip on its own.
    Separate,
}

impl From<Join> for stripkit::Join {
    fn from(j: Join) -> Self {
        match j {
            Join::Restart => stripkit::Join::Restart,
            Join::Degenerate => stripkit::Join::Degenerate,
            Join::Separate => stripkit::Join::Separate,
        }
    }
}

/// The strip options: which stripifier and its settings. `stripkit strip` and
/// `stripkit render` both take them (flattened), so that a picture shows the strips
/// `strip` writes.
#[derive(clap::Args, Clone, Debug)]
pub struct StripArgs {
    /// Stripifying algorithm.
    #[arg(long, value_enum, default_value = "auto")]
    pub algo: Algo,
    /// Greedy (and auto on meshes that are not quad-dominant): what it minimises,
    /// `strips` (count of strips) or `indices` (index count when each swap costs a
    /// repeated index). Default `indices`.
    #[arg(long, value_enum)]
    pub heuristic: Option<HeuristicArg>,
    /// Greedy only: after the greedy pass, relink strips along alternating paths
    /// ("tunnelling") that cut at most N strip links each, keeping a change only when it
    /// saves indices (or strips, with `--heuristic strips`). 0 gives the plain greedy of
    /// van Kaick et al.; larger N finds more and takes longer (bunny, indices:
    /// 0: 83,179 indices, 1: 81,755, 2: 81,215). The search from each strip end is
    /// exponential in N, so its work is bounded (a budget never reached for N <= 3):
    /// the time stays linear in the strips whatever N (dragon, 100k triangles: N = 3:
    /// 0.3 s, N = 8: 1.7 s, N = 32: 0.7 s), and past about N = 8 the strips get more
    /// indices, not fewer (bunny: N = 8: 81,155; N = 32: 82,613). At most 32. Default 1.
    #[arg(long, value_name = "N", value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(0..=stripkit::MAX_TUNNEL_CUTS as u64))]
    pub tunnel: Option<usize>,
    /// Vertex-cache size: the FIFO `--algo cache|balanced` tune for, and the cache of the
    /// `acmr` figure (acmr16 and acmr32 are always printed). 1 to 65,536.
    #[arg(long, value_name = "N", default_value_t = 16)]
    pub cache: usize,
    /// `--algo balanced`: the most cache misses per triangle (FIFO of `--cache`
    /// entries) to accept for fewer indices. Default 0.8.
    #[arg(long, value_name = "ACMR")]
    pub max_acmr: Option<f64>,
    /// `--algo cache|balanced`: how quads are split into triangles. A quad may be split
    /// along either diagonal; QSTRIP's diagonals let rows of quads run without swaps
    /// (fandisk_quads, cache: 2,137 indices at 0.715 misses per triangle with the fan,
    /// 2,081 at 0.639 with them). `auto` tries both on meshes that are at least half
    /// quads and keeps the cheaper; such strips are checked at quad level (each quad
    /// covered by two triangles along one of its diagonals, winding kept). Default
    /// `auto`. Greedy takes only `fan`; qstrip and quad-single only `qstrip`.
    #[arg(long, value_enum)]
    pub diagonals: Option<DiagonalsArg>,
    /// `--algo cache`: then refine the strips with balanced's local search (joins and
    /// relinks scored by the exact FIFO, a miss costing 1.1 indices, no move adding a
    /// miss): bunny 94,283 indices at 0.645 misses per triangle -> 91,564 at 0.630, in
    /// about 0.46 s instead of 17 ms. `balanced` always refines.
    #[arg(long)]
    pub refine: bool,
    /// Simulate an LRU cache for the `acmr` figure instead of FIFO.
    #[arg(long)]
    pub lru: bool,
    /// `--algo single`: what steers the strip. `uniform` (any matching, fewest
    /// changes), `cull` (stays inside clusters of similar normals, for back-face
    /// culling), `cache` (winds around a breadth-first tree of edges, for the vertex
    /// cache), `direction:X,Y,Z` (advances along the axis), or a mix such as
    /// `mix:cull=0.5,cache=0.5` (in a mix, `direction:X:Y:Z=C`). Default `uniform`.
    #[arg(long, value_name = "W")]
    pub weights: Option<String>,
    /// `--algo single`: swap an edge to merge two loops only where its two triangles'
    /// normals differ by at most this many degrees and they form a convex quad (the
    /// surface then moves by the distance between the diagonals, reported); `off`:
    /// never swap, split instead. Default 5 (dragon, cache weights: 1,212 Steiner
    /// vertices without swaps, 908 at 1 degree, 378 at 5).
    #[arg(long, value_name = "DEGREES")]
    pub swap_angle: Option<String>,
    /// `--algo single` with cull weights: the most normal deviation inside a cluster,
    /// in degrees. Default 30.
    #[arg(long, value_name = "DEGREES")]
    pub cull_angle: Option<f64>,
    /// `--algo single` with cull weights: small seeded noise on the weights inside
    /// clusters, which speeds up the matching (`on` or `off`). Default on.
    #[arg(long, value_name = "ON|OFF")]
    pub cull_noise: Option<String>,
    /// `--algo single`: seed of the randomized parts (cache weights' tree, clustering
    /// seeds). Default 1.
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// `--algo single`: how the dual graph is matched. `exact`: the maximum-weight
    /// matching, proved by its certificate; `greedy`: heaviest edges first, then
    /// shortest augmenting paths (every triangle still matched, a few percent of the
    /// weight lost, 5 to 50 times faster); `auto`: exact on closed meshes and on
    /// others of up to 65,536 triangles, greedy for uniform weights.
    /// Default `auto`.
    #[arg(long, value_enum)]
    pub matching: Option<MatchingArg>,
}

/// The order of the vertices in the output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum VertexOrder {
    /// Renumbered in the order the strips first use them; vertices no face uses are
    /// dropped (meshoptimizer's `optimizeVertexFetch`).
    FirstUse,
    /// As in the input, every vertex kept (ids stay the input's).
    Input,
}

/// How `--algo single` matches the dual graph.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MatchingArg {
    /// Exact on closed meshes and up to 65,536 triangles, else (and for uniform
    /// weights) greedy.
    Auto,
    /// The maximum-weight matching.
    Exact,
    /// Heaviest edges first, then shortest augmenting paths.
    Greedy,
}

/// Arguments of `stripkit strip`.
#[derive(clap::Args, Clone, Debug)]
#[command(after_help = "Output by extension of OUT:\n  \
    .ply   vertices plus a `tristrips` element (-1 ends a strip); --join degenerate writes one stitched strip\n  \
    .json  {\"strips\": [[...], ...], \"figures\": {...}} (with --join restart also \"indices\" and \"restart_index\")\n  \
    .gltf, .glb  per primitive (per group for a mesh with materials), a TRIANGLE_STRIP primitive holding the\n               \
    stitched strip every viewer draws, plus the strips with restart indices through EXT_mesh_primitive_restart\n               \
    (--join degenerate: the stitched strips alone). A glTF input keeps its whole scene: nodes, materials,\n               \
    skins, animations, morph targets (stitched only) and extensions. A plain mesh with --join separate:\n               \
    one primitive per strip\n  \
    .obj   no strips in OBJ: the strips' triangles in strip order, per group (g/usemtl), with vt/vn\n\
Exit status: 0 success, 1 verification failed (nothing written), 2 bad input or argument.")]
pub struct Args {
    /// Input mesh (.obj, .ply, .off, .stl, .gltf, .glb, optionally .gz); polygons are
    /// fanned into triangles. `-` reads standard input (with --format). A folder strips
    /// every mesh file in it (not its subfolders) into the folder -o names.
    pub input: PathBuf,
    /// Output file: .ply, .json, .gltf, .glb or .obj (see below); `-` writes standard output
    /// in --output-format (the report then goes to standard error). For a folder input,
    /// a folder (created if missing) that gets one NAME.EXT per input, EXT from
    /// --output-format (default glb).
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// The format written to standard output (`-o -`) or into an output folder: ply,
    /// gltf or glb. Default for `-o -`: the --format of a standard input.
    #[arg(long, value_name = "FORMAT", value_parser = super::parse_format)]
    pub output_format: Option<Format>,
    /// Write PLY as ASCII text instead of binary (PLY outputs only).
    #[arg(long)]
    pub ascii: bool,
    #[command(flatten)]
    pub strip: StripArgs,
    /// How strips are joined in the output: `restart` (one buffer with a restart index),
    /// `degenerate` (one stitched strip), `separate` (one list per strip).
    #[arg(long, value_enum, default_value = "restart")]
    pub join: Join,
    /// Order of the written vertices: `first-use` renumbers them in the order the
    /// strips first use them and drops unreferenced ones (the GPU then reads the
    /// vertex buffer front to back); `input` keeps the input's ids. Default
    /// `first-use` for .gltf and .glb outputs, `input` for PLY (.json holds no
    /// vertices: `input` only).
    #[arg(long, value_enum)]
    pub vertex_order: Option<VertexOrder>,
    /// Primitive-restart index for `--join restart`; must not be a vertex id of the mesh.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_RESTART)]
    pub restart_index: u32,
    /// Print one JSON object with every figure on stdout instead of the text summary.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: super::ReadArgs,
}

/// The JSON object printed by `--json` (and embedded in `.json` outputs).
#[derive(Serialize)]
struct Report<'a> {
    input: &'a Path,
    output: &'a Path,
    algo: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    heuristic: Option<HeuristicArg>,
    join: Join,
    vertex_order: VertexOrder,
    vertices: usize,
    #[serde(flatten)]
    figures: &'a Figures,
    /// Milliseconds of the stripify call alone.
    ms: f64,
    /// `cache` and `balanced`: how the quads were split (`fan` or `qstrip`).
    #[serde(skip_serializing_if = "Option::is_none")]
    diagonals: Option<&'static str>,
    /// QSTRIP only: quads stripped as quads.
    #[serde(skip_serializing_if = "Option::is_none")]
    quads: Option<usize>,
    /// QSTRIP only: `indices_restart / quads` (docs/metrics.md).
    #[serde(skip_serializing_if = "Option::is_none")]
    indices_per_quad: Option<f64>,
    /// `single` only: Steiner vertices, swaps, pieces merged, times.
    #[serde(skip_serializing_if = "Option::is_none")]
    single: Option<&'a stripkit::SingleReport>,
    /// `balanced` only, when its `--max-acmr` was out of reach: the misses per
    /// triangle reached instead (FIFO of `--cache` entries).
    #[serde(skip_serializing_if = "Option::is_none")]
    max_acmr_unreached: Option<f64>,
}

enum OutKind {
    Json,
    Mesh(Format),
}

fn output_kind(path: &Path, stdout_format: Option<Format>) -> anyhow::Result<OutKind> {
    if let Some(format) = stdout_format.filter(|_| super::is_dash(path)) {
        return match format {
            Format::Ply | Format::Gltf | Format::Glb => Ok(OutKind::Mesh(format)),
            _ => {
                let name = format!("{format:?}").to_lowercase();
                Err(Error::Invalid(format!("--output-format {name} cannot hold strips; use ply, gltf or glb")).into())
            }
        };
    }
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if name.ends_with(".json") {
        return Ok(OutKind::Json);
    }
    match Format::from_path(path) {
        Some((f @ (Format::Ply | Format::Gltf | Format::Glb | Format::Obj), _)) => Ok(OutKind::Mesh(f)),
        _ => Err(Error::Invalid(format!(
            "{}: cannot hold strips; the output must end in .ply, .json, .gltf, .glb or .obj (triangles in strip order)",
            path.display()
        ))
        .into()),
    }
}

impl StripArgs {
    /// Flags that belong to one algorithm, given with another: an error, not silence.
    pub fn check(&self) -> Result<(), Error> {
        let bad = |m: &str| Err(Error::Invalid(m.to_string()));
        if self.refine && self.algo != Algo::Cache {
            return bad("--refine applies to --algo cache (balanced always refines)");
        }
        if self.max_acmr.is_some() && self.algo != Algo::Balanced {
            return bad("--max-acmr applies to --algo balanced");
        }
        let splits_quads = matches!(self.algo, Algo::Cache | Algo::Balanced | Algo::Auto);
        if self.diagonals == Some(DiagonalsArg::Auto) && !splits_quads {
            return bad("--diagonals auto applies to --algo cache and balanced (the others split quads their own way)");
        }
        if (self.heuristic.is_some() || self.tunnel.is_some()) && !matches!(self.algo, Algo::Greedy | Algo::Auto) {
            return bad("--heuristic and --tunnel apply to --algo greedy (and auto on meshes that are not quad-dominant)");
        }
        if (self.weights.is_some()
            || self.swap_angle.is_some()
            || self.cull_angle.is_some()
            || self.cull_noise.is_some()
            || self.seed.is_some()
            || self.matching.is_some())
            && self.algo != Algo::Single
        {
            return bad("--weights, --swap-angle, --cull-angle, --cull-noise, --seed and --matching apply to --algo single");
        }
        if self.algo == Algo::Single {
            self.single_options()?;
        }
        Ok(())
    }

    /// `--algo single`'s settings from the flags.
    fn single_options(&self) -> Result<stripkit::SingleOptions, Error> {
        let mut o = stripkit::SingleOptions::new(match &self.weights {
            Some(w) => w.parse::<stripkit::Weights>().map_err(|e| match e {
                Error::Invalid(m) => Error::Invalid(format!("--{m}")),
                other => other,
            })?,
            None => stripkit::Weights::Uniform,
        });
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
            o = o.matching(match m {
                MatchingArg::Auto => stripkit::MatchingMode::Auto,
                MatchingArg::Exact => stripkit::MatchingMode::Exact,
                MatchingArg::Greedy => stripkit::MatchingMode::Greedy,
            });
        }
        Ok(o)
    }

    /// The library's options for these arguments (default join and restart index).
    /// `mesh`: resolve `--algo auto` the library's way (`is_quad_dominant`) so that
    /// greedy gets the flags given for it.
    pub fn options(&self, mesh: Option<&stripkit::Mesh>) -> StripOptions {
        let greedy = || {
            Algorithm::Greedy(GreedyOptions {
                heuristic: match self.heuristic.unwrap_or(HeuristicArg::Indices) {
                    HeuristicArg::Strips => Heuristic::Strips,
                    HeuristicArg::Indices => Heuristic::Indices,
                },
                tunnel_cuts: Some(self.tunnel.unwrap_or(1)).filter(|&n| n > 0),
            })
        };
        let algorithm = match self.algo {
            Algo::Auto => match mesh {
                Some(m) if stripkit::is_quad_dominant(m) => Algorithm::qstrip(),
                Some(_) => greedy(),
                None => Algorithm::Auto,
            },
            Algo::Greedy => greedy(),
            Algo::Qstrip => Algorithm::qstrip(),
            Algo::QuadSingle => Algorithm::QuadSingle,
            Algo::Cache => Algorithm::Cache { refine: self.refine },
            Algo::Balanced => Algorithm::balanced(self.max_acmr.unwrap_or(0.8)),
            Algo::Batch => Algorithm::batch(),
            // Checked by `check` first; an unparsable value falls back to the default
            // only where `check` was skipped.
            Algo::Single => Algorithm::Single(self.single_options().unwrap_or_default()),
        };
        let split = match self.diagonals {
            None | Some(DiagonalsArg::Auto) => Split::Auto,
            Some(DiagonalsArg::Fan) => Split::Fan,
            Some(DiagonalsArg::Qstrip) => Split::Qstrip,
        };
        let cache = if self.lru { CacheModel::lru(self.cache) } else { CacheModel::fifo(self.cache) };
        StripOptions::default().algorithm(algorithm).cache_model(cache).split(split)
    }

    /// Checks the flags before any file is read: each flag with its own algorithm, and
    /// the options (`more` adds the command's own) as the library will take them.
    pub fn validate(&self, more: impl FnOnce(StripOptions) -> StripOptions) -> anyhow::Result<()> {
        self.check()?;
        Stripifier::new(more(self.options(None))).map_err(|e| anyhow::anyhow!(flag_names(e)))?;
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
        let mut stripifier =
            Stripifier::new(more(self.options(Some(mesh)))).map_err(|e| anyhow::anyhow!(flag_names(e)))?;
        stripifier.stripify(mesh).map_err(|e| anyhow::anyhow!(flag_names(e)).context(format!("{}", input.display())))
    }

    /// Flags that cannot apply to this mesh: `--algo qstrip` on a mesh without a quad
    /// would silently run greedy.
    pub fn check_mesh(&self, mesh: &stripkit::Mesh, input: &Path) -> Result<(), Error> {
        if self.algo == Algo::Qstrip && !mesh.faces().any(|f| f.len() == 4) {
            return Err(Error::Invalid(format!(
                "{}: --algo qstrip strips quads and this mesh has none (it would run greedy); use --algo greedy or cache",
                input.display()
            )));
        }
        Ok(())
    }

    /// The heuristic greedy ran with, for reports: `None` for other algorithms.
    pub fn heuristic_used(&self, algorithm: &Algorithm) -> Option<HeuristicArg> {
        matches!(algorithm, Algorithm::Greedy(_)).then(|| self.heuristic.unwrap_or(HeuristicArg::Indices))
    }
}

/// `strip`'s own options on top of the strip flags: the join and its restart index.
fn with_join(args: &Args, options: StripOptions) -> StripOptions {
    options.join(args.join.into()).restart_index(args.restart_index)
}

/// Runs the command on one input file: read -> door -> encode -> write. `batch`: the
/// progress bar of a folder run (`main` runs each file of a folder input through
/// here), above which the report is one line.
pub fn run(args: Args, batch: Option<&indicatif::ProgressBar>) -> anyhow::Result<()> {
    let stdout_format = if super::is_dash(&args.output) {
        Some(super::output_format(&args.output, args.output_format, Some((&args.input, &args.read)))?)
    } else {
        anyhow::ensure!(
            args.output_format.is_none() || batch.is_some(),
            "--output-format applies to standard output (-o -) and folder outputs; \
             {} names its format by its extension",
            args.output.display()
        );
        None
    };
    let kind = output_kind(&args.output, stdout_format)?;
    // Fail before the work when the output cannot be written at all.
    super::check_output_folder(&args.output)?;
    let write_options = super::write_options(
        args.ascii,
        &args.output,
        match kind {
            OutKind::Mesh(format) => Some(format),
            OutKind::Json => None,
        },
    )?;
    // Arguments are checked before the file is read.
    args.strip.validate(|o| with_join(&args, o))?;
    let vertex_order = match (args.vertex_order, &kind) {
        (Some(VertexOrder::FirstUse), OutKind::Json) => {
            return Err(Error::Invalid(format!(
                "--vertex-order first-use applies to mesh outputs; {} holds no vertices",
                args.output.display()
            ))
            .into())
        }
        (Some(order), _) => order,
        (None, OutKind::Mesh(Format::Gltf | Format::Glb)) => VertexOrder::FirstUse,
        (None, _) => VertexOrder::Input,
    };
    if is_scene(&args.input, &kind) {
        return run_scene(&args, format_of(&kind), vertex_order, batch);
    }
    // A spinner on a terminal (indicatif draws nothing when stderr is not one):
    // balanced and --refine take seconds on meshes of a million triangles.
    let progress = match batch {
        Some(_) => indicatif::ProgressBar::hidden(),
        None => indicatif::ProgressBar::new_spinner(),
    };
    progress.enable_steady_tick(std::time::Duration::from_millis(120));
    progress.set_message(format!("reading {}", args.input.display()));
    let mesh = args.read.read(&args.input)?;
    // A mesh written as glTF: the library chooses its writer (a scene of one
    // primitive per group, or the plain writer; stripkit::scene::for_gltf_output).
    let start = std::time::Instant::now();
    let scene = match kind {
        OutKind::Mesh(Format::Gltf | Format::Glb) => stripkit::scene::for_gltf_output(&mesh, &with_join(&args, args.strip.options(None)))
            .map_err(|e| anyhow::anyhow!(e).context(format!("{}", args.input.display())))?,
        _ => None,
    };
    if let Some(scene) = scene {
        progress.finish_and_clear();
        for note in scene.notes() {
            eprintln!("note: {}: {note}", args.input.display());
        }
        return strip_scene(&args, scene, start.elapsed(), format_of(&kind), vertex_order, batch);
    }

    progress.set_message(format!("stripifying and verifying {} triangles", mesh.triangle_count()));
    let strips = args.strip.stripify(&mesh, &args.input, |o| with_join(&args, o))?;
    let (mesh, strips) = match (vertex_order, &kind) {
        (VertexOrder::FirstUse, OutKind::Mesh(format)) => strips.in_first_use_order(&mesh, *format),
        _ => (mesh, strips),
    };

    progress.set_message(format!("writing {}", args.output.display()));
    let figures = &strips.figures;
    let report = Report {
        input: &args.input,
        output: &args.output,
        algo: strips.algorithm.name(),
        heuristic: args.strip.heuristic_used(&strips.algorithm),
        join: args.join,
        vertex_order,
        vertices: mesh.vertex_count() + strips.added_positions.len(),
        figures,
        ms: strips.stripify_time.as_secs_f64() * 1e3,
        diagonals: matches!(strips.algorithm, Algorithm::Cache { .. } | Algorithm::Balanced { .. })
            .then(|| strips.split.name()),
        quads: strips.quads,
        indices_per_quad: strips.indices_per_quad(),
        single: strips.single.as_ref(),
        max_acmr_unreached: unreached_acmr(&strips, mesh.vertex_count()),
    };
    if let (Some(reached), Algorithm::Balanced { max_acmr }) = (report.max_acmr_unreached, &strips.algorithm) {
        eprintln!(
            "stripkit: warning: {}: --max-acmr {max_acmr} is below what balanced reaches on this mesh; \
             its strips have {reached:.3} misses per triangle (FIFO of {} entries)",
            args.input.display(),
            args.strip.cache
        );
    }
    let bytes = match kind {
        OutKind::Json => {
            let mut obj = strips.to_json();
            obj.insert("figures".into(), serde_json::to_value(&report)?);
            let mut bytes = serde_json::to_vec(&serde_json::Value::Object(obj))?;
            bytes.push(b'\n');
            bytes
        }
        OutKind::Mesh(format) => strips.to_file_bytes_with(&mesh, format, &write_options)?,
    };
    super::write_output(&args.output, &bytes)?;
    progress.finish_and_clear();

    let sink = match batch {
        Some(bar) => super::Sink::Batch(bar.clone()),
        None => super::Sink::for_output(&args.output),
    };
    super::print_report_to(&sink, args.json, &report, |out, r| match batch {
        Some(_) => print_line(out, r),
        None => print_summary(out, r),
    })
}

/// `balanced`'s misses per triangle (FIFO of the cache size it ran with) where they
/// exceed its `max_acmr` bound, which the strips then did not reach; `None` otherwise.
fn unreached_acmr(strips: &stripkit::Strips, vertex_count: usize) -> Option<f64> {
    let Algorithm::Balanced { max_acmr } = strips.algorithm else { return None };
    let cache = strips.figures.cache;
    let reached = if cache.kind == CacheKind::Fifo {
        strips.figures.acmr
    } else {
        let order = stripkit::decode(&strips.strips);
        let vertices = vertex_count + strips.added_positions.len();
        stripkit::acmr(&order, vertices, cache.size, CacheKind::Fifo)
    };
    // A relative slack for the float sums behind the two figures.
    (reached > max_acmr * (1.0 + 1e-9)).then_some(reached)
}

/// The library names its settings; the user typed flags: say which.
/// glTF in and glTF out: the whole scene goes through [`stripkit::io::Scene`].
fn is_scene(input: &Path, kind: &OutKind) -> bool {
    let gltf = |f: Option<(Format, bool)>| matches!(f, Some((Format::Gltf | Format::Glb, _)));
    input.as_os_str() != "-" && gltf(Format::from_path(input)) && matches!(kind, OutKind::Mesh(Format::Gltf | Format::Glb))
}

/// What `strip` reports for a glTF scene.
#[derive(Serialize)]
struct SceneCliReport<'a> {
    input: &'a Path,
    output: &'a Path,
    join: Join,
    /// Always true: every primitive was verified, and the written file read back and
    /// checked (a failure is an error and writes nothing), as in the mesh report.
    verified: bool,
    vertex_order: VertexOrder,
    /// Reading and decoding the input, in milliseconds.
    read_ms: f64,
    /// Encoding, checking (read back) and writing the output, in milliseconds.
    write_ms: f64,
    #[serde(flatten)]
    scene: &'a stripkit::scene::SceneReport,
}

/// `strip` on a glTF scene: every triangle primitive stripped on its own, everything
/// else written as read; `--join restart` (default) adds EXT_mesh_primitive_restart
/// groups beside the stitched strips, `--join degenerate` writes the stitched strips
/// alone.
fn run_scene(
    args: &Args,
    format: Format,
    vertex_order: VertexOrder,
    batch: Option<&indicatif::ProgressBar>,
) -> anyhow::Result<()> {
    use stripkit::io::Scene;
    let invalid = |m: String| -> anyhow::Result<()> { Err(Error::Invalid(m).into()) };
    match args.join {
        Join::Restart | Join::Degenerate => {}
        Join::Separate => {
            return invalid(
                "--join separate does not apply to a glTF scene, where each primitive becomes one strip primitive: \
                 use --join restart (EXT_mesh_primitive_restart with a stitched fallback, the default) or \
                 --join degenerate (plain stitched strips)"
                    .into(),
            )
        }
    }
    if args.restart_index != DEFAULT_RESTART {
        return invalid(
            "--restart-index does not apply to a glTF scene: the restart value is the largest of the index type \
             (65535 or 4294967295), as EXT_mesh_primitive_restart asks"
                .into(),
        );
    }
    if args.strip.algo == Algo::Single {
        return invalid(
            "--algo single adds vertices, and a glTF scene's vertex data is written as read; choose another algorithm"
                .into(),
        );
    }
    let start = std::time::Instant::now();
    let scene = Scene::read_with(&args.input, &args.read.options())?;
    if scene.primitives().iter().all(|p| p.mesh.face_count() == 0) {
        return invalid(format!("no faces in {}", args.input.display()));
    }
    strip_scene(args, scene, start.elapsed(), format, vertex_order, batch)
}

/// The mesh format of an output kind (glTF for the scene paths, which only take mesh outputs).
fn format_of(kind: &OutKind) -> Format {
    match kind {
        OutKind::Mesh(f) => *f,
        OutKind::Json => Format::Glb,
    }
}

/// Strips a scene's primitives, writes it and reports, for [`run_scene`] and for a
/// mesh with attributes or groups written as glTF.
fn strip_scene(
    args: &Args,
    mut scene: stripkit::io::Scene,
    read_time: std::time::Duration,
    format: Format,
    vertex_order: VertexOrder,
    batch: Option<&indicatif::ProgressBar>,
) -> anyhow::Result<()> {
    let scene_options = match args.join {
        Join::Degenerate => stripkit::scene::SceneOptions::stitched(),
        _ => stripkit::scene::SceneOptions::default(),
    }
    .reorder(vertex_order == VertexOrder::FirstUse);
    let progress = match batch {
        Some(_) => indicatif::ProgressBar::hidden(),
        None => indicatif::ProgressBar::new_spinner(),
    };
    progress.enable_steady_tick(std::time::Duration::from_millis(120));
    for p in scene.primitives() {
        args.strip.check_mesh(&p.mesh, &args.input)?;
    }
    progress.set_message(format!("stripifying and verifying {} primitives", scene.primitives().len()));
    let options = args.strip.options(None);
    let report = scene.strip(&options, &scene_options).map_err(|e| anyhow::anyhow!(flag_names(e)))?;
    progress.set_message(format!("writing {}", args.output.display()));
    let start = std::time::Instant::now();
    let bytes = scene.to_bytes(format)?;
    super::write_output(&args.output, &bytes)?;
    let write_ms = start.elapsed().as_secs_f64() * 1e3;
    progress.finish_and_clear();
    let r = SceneCliReport {
        input: &args.input,
        output: &args.output,
        join: args.join,
        verified: true,
        vertex_order,
        read_ms: read_time.as_secs_f64() * 1e3,
        write_ms,
        scene: &report,
    };
    let sink = match batch {
        Some(bar) => super::Sink::Batch(bar.clone()),
        None => super::Sink::for_output(&args.output),
    };
    super::print_report_to(&sink, args.json, &r, |out, r| {
        let s = r.scene;
        if batch.is_some() {
            return writeln!(
                out,
                "{} -> {}: {} triangles, {} primitives, {} indices stitched, {} with restart, {:.1} ms",
                r.input.display(),
                r.output.display(),
                s.triangles,
                s.primitives.len(),
                s.indices_stitched,
                s.indices_drawn_restart,
                s.total_ms
            );
        }
        writeln!(
            out,
            "{} -> {} (scene: {} triangle primitives stripped, {} left as read; {})",
            r.input.display(),
            r.output.display(),
            s.primitives.len(),
            s.skipped,
            if r.join == Join::Restart {
                "EXT_mesh_primitive_restart with stitched fallback"
            } else {
                "stitched strips"
            }
        )?;
        writeln!(out, "verified: {} triangles, 0 lost, 0 added, 0 flipped; written file read back and checked", s.triangles)?;
        writeln!(out, "  indices read         {:>10}", s.indices_read)?;
        writeln!(out, "  indices stitched     {:>10}", s.indices_stitched)?;
        if r.join == Join::Restart {
            writeln!(out, "  indices restart      {:>10}", s.indices_drawn_restart)?;
        }
        const SHOWN: usize = 20;
        if s.primitives.len() > SHOWN {
            writeln!(out, "  (the first {SHOWN} of {} primitives; --json lists all)", s.primitives.len())?;
        }
        for p in s.primitives.iter().take(SHOWN) {
            writeln!(
                out,
                "  meshes[{}].primitives[{}]: {} triangles, {} strips, {} -> {} indices{} ({})",
                p.mesh,
                p.primitive,
                p.figures.triangles,
                p.figures.strips,
                p.indices_read,
                p.indices_stitched,
                p.indices_restart.map(|n| format!(" (restart {n})")).unwrap_or_default(),
                p.algorithm
            )?;
        }
        Ok(())
    })
}

pub fn flag_names(e: Error) -> Error {
    match e {
        Error::Invalid(m) => Error::Invalid(
            m.replace("the cache size", "--cache")
                .replace("restart index", "--restart-index")
                .replace("balanced needs a positive number of misses per triangle as its bound", "--max-acmr must be a positive number of misses per triangle")
                .replace("split qstrip", "--diagonals qstrip")
                .replace("split fan", "--diagonals fan")
                .replace("swap angle", "--swap-angle")
                .replace("cull angle", "--cull-angle"),
        ),
        other => other,
    }
}

/// A folder run's line for one file.
fn print_line(out: &mut impl Write, r: &Report) -> std::io::Result<()> {
    let f = r.figures;
    writeln!(
        out,
        "{} -> {}: {} triangles, {} strips, {} indices ({:.3} per triangle), acmr16 {:.3}, {:.1} ms",
        r.input.display(),
        r.output.display(),
        f.triangles,
        f.strips,
        f.indices_restart,
        f.indices_per_triangle,
        f.acmr16,
        r.ms
    )
}

fn print_summary(out: &mut impl Write, r: &Report) -> std::io::Result<()> {
    let f = r.figures;
    let name = |v: &dyn std::fmt::Debug| format!("{v:?}").to_lowercase();
    writeln!(
        out,
        "{} -> {} ({}{}, join {})",
        r.input.display(),
        r.output.display(),
        r.algo,
        r.heuristic.map(|h| format!(", heuristic {}", name(&h))).unwrap_or_default(),
        name(&r.join)
    )?;
    writeln!(
        out,
        "verified: {} triangles, 0 lost, 0 added, 0 flipped{}",
        f.triangles,
        if f.dropped_degenerate > 0 {
            format!(
                " ({} degenerate input triangles dropped)",
                f.dropped_degenerate
            )
        } else {
            String::new()
        }
    )?;
    writeln!(out, "  strips               {:>10}", f.strips)?;
    writeln!(out, "  swaps                {:>10}", f.swaps)?;
    writeln!(out, "  indices_separate     {:>10}", f.indices_separate)?;
    writeln!(out, "  indices_restart      {:>10}", f.indices_restart)?;
    writeln!(out, "  indices_degenerate   {:>10}", f.indices_degenerate)?;
    writeln!(
        out,
        "  indices_per_triangle {:>10.4}",
        f.indices_per_triangle
    )?;
    if let Some(d) = r.diagonals {
        writeln!(out, "  quads split along    {:>10}", d)?;
    }
    if let (Some(q), Some(ipq)) = (r.quads, r.indices_per_quad) {
        writeln!(out, "  quads                {:>10}", q)?;
        writeln!(out, "  indices_per_quad     {:>10.4}", ipq)?;
    }
    writeln!(out, "  acmr16 (FIFO)        {:>10.4}", f.acmr16)?;
    writeln!(out, "  acmr32 (FIFO)        {:>10.4}", f.acmr32)?;
    let kind = match f.cache.kind {
        CacheKind::Fifo => "FIFO",
        CacheKind::Lru => "LRU",
    };
    if !(f.cache.kind == CacheKind::Fifo && (f.cache.size == 16 || f.cache.size == 32)) {
        writeln!(
            out,
            "  acmr{} ({kind}){:>w$.4}",
            f.cache.size,
            f.acmr,
            w = 20usize.saturating_sub(format!("acmr{} ({kind})", f.cache.size).len()) + 11
        )?;
    }
    if let Some(s) = r.single {
        writeln!(out, "  components           {:>10}", s.components)?;
        writeln!(out, "  steiner_vertices     {:>10}", s.steiner_vertices)?;
        if s.clusters > 0 {
            writeln!(out, "  cull clusters        {:>10} ({} peaks split)", s.clusters, s.cull_peaks)?;
            if s.boundary_edges > 0 {
                writeln!(out, "  boundary crossings   {:>10} (of {} boundary edges)", s.boundary_crossings, s.boundary_edges)?;
            }
        }
        writeln!(out, "  swapped_edges        {:>10}", s.swapped_edges)?;
        if s.swapped_edges > 0 {
            writeln!(out, "  max swap deviation   {:>10.3e}", s.max_swap_deviation)?;
        }
        writeln!(out, "  pieces merged        {:>10} ({} paths; {} nodal, {} joins, {} attaches)", s.initial_pieces, s.initial_paths, s.nodal, s.joins, s.attaches)?;
        writeln!(
            out,
            "  ms: weights {:.1}, matching {:.1}, merge {:.1}",
            s.weights_ms, s.matching_ms, s.merge_ms
        )?;
    }
    writeln!(out, "  stripify ms          {:>10.2}", r.ms)?;
    Ok(())
}

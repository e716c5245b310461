//! `stripkit strip`: read a mesh, turn it into triangle strips, check them, print their
//! figures and write them out.
//!
//! Every run verifies what it writes: the encoded buffer (after the chosen join) is
//! decoded again and, for PLY and glTF, the written bytes are read back, and the
//! triangles must equal the input's (nothing lost, nothing added, no winding flipped).
//! A failed check writes nothing and exits with status 1.
//!
//! Adding a stripifier: a variant of [`Algo`] and its branch where [`run`] picks the strips.

use anyhow::Context;
use clap::ValueEnum;
use serde::Serialize;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;
use stripkit::mesh::io::{self, Format, WriteOptions};
use stripkit::metrics::{self, CacheKind, CacheModel, Figures};
use stripkit::strip::{self, StripSet};
use stripkit::stripify::cache::{self, CacheOptions};
use stripkit::stripify::greedy::{self, GreedyOptions};
use stripkit::stripify::{quad, quad_single, quad_verify};
use stripkit::{Error, Mesh};

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

/// Arguments of `stripkit strip`.
#[derive(clap::Args, Debug)]
#[command(after_help = "Output by extension of OUT:\n  \
    .ply   vertices plus a `tristrips` element (-1 ends a strip); --join degenerate writes one stitched strip\n  \
    .json  {\"strips\": [[...], ...], \"figures\": {...}} (with --join restart also \"indices\" and \"restart_index\")\n  \
    .gltf, .glb  core glTF has no restart index: one TRIANGLE_STRIP primitive holding the stitched strip\n               \
    (--join separate: one primitive per strip)\n\
Exit status: 0 success, 1 verification failed (nothing written), 2 bad input or argument.")]
pub struct Args {
    /// Input mesh (.obj, .ply, .off, .stl, .gltf, .glb, optionally .gz); polygons are fanned into triangles.
    pub input: PathBuf,
    /// Output file: .ply, .json, .gltf or .glb (see below).
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Stripifying algorithm.
    #[arg(long, value_enum, default_value = "auto")]
    pub algo: Algo,
    /// What the greedy algorithm minimises: `strips` (count of strips) or `indices`
    /// (index count when each swap costs a repeated index).
    #[arg(long, value_enum, default_value = "indices")]
    pub heuristic: HeuristicArg,
    /// Greedy only: after the greedy pass, relink strips along alternating paths
    /// ("tunnelling") that cut at most N strip links each, keeping a change only when it
    /// saves indices (or strips, with `--heuristic strips`). 0 gives the plain greedy of
    /// van Kaick et al.; larger N finds more and takes longer (bunny, indices:
    /// 0: 83,179 indices, 1: 81,755, 2: 81,215).
    #[arg(long, value_name = "N", default_value_t = 1)]
    pub tunnel: usize,
    /// How strips are joined in the output: `restart` (one buffer with a restart index),
    /// `degenerate` (one stitched strip), `separate` (one list per strip).
    #[arg(long, value_enum, default_value = "restart")]
    pub join: Join,
    /// Primitive-restart index for `--join restart`; must not be a vertex id of the mesh.
    #[arg(long, value_name = "N", default_value_t = strip::DEFAULT_RESTART)]
    pub restart_index: u32,
    /// Vertex-cache size: the FIFO `--algo cache|balanced` tune for, and the cache of the
    /// `acmr` figure (acmr16 and acmr32 are always printed).
    #[arg(long, value_name = "N", default_value_t = 16)]
    pub cache: usize,
    /// `--algo balanced`: the most cache misses per triangle (FIFO of `--cache`
    /// entries) to accept for fewer indices.
    #[arg(long, value_name = "ACMR", default_value_t = 0.8)]
    pub max_acmr: f64,
    /// `--algo cache|balanced`: how quads are split into triangles. A quad may be split
    /// along either diagonal; QSTRIP's diagonals let rows of quads run without swaps
    /// (fandisk_quads, cache: 2,137 indices at 0.715 misses per triangle with the fan,
    /// 2,081 at 0.639 with them). `auto` tries both on meshes that are at least half
    /// quads and keeps the cheaper; such strips are checked at quad level (each quad
    /// covered by two triangles along one of its diagonals, winding kept).
    #[arg(long, value_enum, default_value = "auto")]
    pub diagonals: DiagonalsArg,
    /// `--algo cache`: then refine the strips with balanced's local search (joins and
    /// relinks scored by the exact FIFO, a miss costing 1.1 indices, no move adding a
    /// miss): bunny 94,283 indices at 0.645 misses per triangle -> 91,564 at 0.630, in
    /// about 0.46 s instead of 17 ms. `balanced` always refines.
    #[arg(long)]
    pub refine: bool,
    /// Simulate an LRU cache for the `acmr` figure instead of FIFO.
    #[arg(long)]
    pub lru: bool,
    /// Print one JSON object with every figure on stdout instead of the text summary.
    #[arg(long)]
    pub json: bool,
}

/// The JSON object printed by `--json` (and embedded in `.json` outputs).
#[derive(Serialize)]
struct Report<'a> {
    input: &'a Path,
    output: &'a Path,
    algo: Algo,
    heuristic: HeuristicArg,
    join: Join,
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
    /// QSTRIP only: `indices_restart / quads` (METRICS.md).
    #[serde(skip_serializing_if = "Option::is_none")]
    indices_per_quad: Option<f64>,
}

/// The greedy stripifier on triangles (`--algo greedy`, and `auto` on meshes that are
/// not quad-dominant): `heuristic` and the `--tunnel` cuts (0: none).
fn greedy_strips(
    heuristic: HeuristicArg,
    tunnel: usize,
    tris: &[[u32; 3]],
    vertex_count: usize,
) -> StripSet {
    let heuristic = match heuristic {
        HeuristicArg::Strips => greedy::Heuristic::Strips,
        HeuristicArg::Indices => greedy::Heuristic::Indices,
    };
    let options = GreedyOptions {
        heuristic,
        tunnel_cuts: (tunnel > 0).then_some(tunnel),
    };
    greedy::stripify(tris, vertex_count, &options)
}

enum OutKind {
    Json,
    Mesh(Format),
}

fn output_kind(path: &Path) -> anyhow::Result<OutKind> {
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if name.ends_with(".json") {
        return Ok(OutKind::Json);
    }
    match Format::from_path(path) {
        Some((f @ (Format::Ply | Format::Gltf | Format::Glb), _)) => Ok(OutKind::Mesh(f)),
        _ => Err(Error::Invalid(format!(
            "{}: cannot hold strips; the output must end in .ply, .json, .gltf or .glb",
            path.display()
        ))
        .into()),
    }
}

fn fail_verification(what: &str, v: &strip::Verification) -> anyhow::Error {
    Error::Verification(format!("{what}: {v}; nothing was written")).into()
}

/// Runs the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    if !(args.max_acmr > 0.0 && args.max_acmr.is_finite()) {
        return Err(Error::Invalid(format!(
            "--max-acmr must be a positive number of misses per triangle (got {})",
            args.max_acmr
        ))
        .into());
    }
    if args.cache == 0 {
        return Err(Error::Invalid(
            "--cache must be at least 1 (a vertex cache of 0 entries misses everything)".into(),
        )
        .into());
    }
    let kind = output_kind(&args.output)?;
    // Fail before the work when the output cannot be written at all.
    if let Some(dir) = args.output.parent().filter(|d| !d.as_os_str().is_empty()) {
        if !dir.is_dir() {
            return Err(Error::Invalid(format!(
                "cannot write {}: the folder {} does not exist",
                args.output.display(),
                dir.display()
            ))
            .into());
        }
    }
    let progress = indicatif::ProgressBar::new_spinner();
    progress.set_message(format!("reading {}", args.input.display()));

    let mesh = io::read(&args.input)?;
    let mut tris = mesh.triangulate().tris;
    let algo = match args.algo {
        Algo::Auto if quad::quad_fraction(&mesh) >= 0.5 => Algo::Qstrip,
        Algo::Auto => Algo::Greedy,
        other => other,
    };
    let vertex_count = mesh.vertex_count();
    if args.join == Join::Restart && (args.restart_index as usize) < vertex_count {
        return Err(Error::Invalid(format!(
            "--restart-index {} is a vertex id of {} ({} vertices); choose one of at least {}",
            args.restart_index,
            args.input.display(),
            vertex_count,
            vertex_count
        ))
        .into());
    }

    progress.set_message(format!("stripifying {} triangles", tris.len()));
    let start = Instant::now();
    let mut quads = None;
    // True when quads were split along diagonals of the algorithm's choosing.
    let mut quad_split = matches!(algo, Algo::Qstrip | Algo::QuadSingle);
    let mut split = None;
    let strips = if algo == Algo::Qstrip {
        let (q, all) = quad::qstrip_mesh(&mesh, &quad::QuadOptions::default());
        quads = Some(q.quad_count());
        all
    } else if algo == Algo::QuadSingle {
        let single = quad_single::quad_single(&mesh)
            .map_err(|e| anyhow::anyhow!(e).context(format!("{}", args.input.display())))?;
        quads = Some(single.quads);
        single.strips
    } else if matches!(algo, Algo::Cache | Algo::Balanced) {
        let size = args.cache.min(u32::MAX as usize) as u32;
        let (options, bound) = if algo == Algo::Cache {
            let options = CacheOptions {
                refine: args.refine,
                ..CacheOptions::cache(size)
            };
            (options, None)
        } else {
            (CacheOptions::balanced(size), Some(args.max_acmr))
        };
        let diagonals = match args.diagonals {
            DiagonalsArg::Auto => cache::Diagonals::Auto,
            DiagonalsArg::Fan => cache::Diagonals::Fan,
            DiagonalsArg::Qstrip => cache::Diagonals::Qstrip,
        };
        let m = cache::stripify_mesh(&mesh, &options, bound, diagonals);
        // On the fan the strips are checked against the input's own fan (`tris`), not
        // against the triangles the stripifier reports; on QSTRIP's split at quad level.
        quad_split = m.qstrip_diagonals;
        split = Some(if m.qstrip_diagonals { "qstrip" } else { "fan" });
        m.strips
    } else {
        greedy_strips(args.heuristic, args.tunnel, &tris, vertex_count)
    };
    let ms = start.elapsed().as_secs_f64() * 1e3;
    if quad_split {
        // A quad may be split along either diagonal: check at quad level, then take
        // the triangles the strips chose as the reference for the figures and for
        // every later check (the quad check proved them a triangulation of the mesh).
        progress.set_message("verifying quads");
        quad_verify::verify_quads(&mesh, &strips)
            .map_err(|e| anyhow::anyhow!(e).context("the strips"))?;
        tris = strip::decode(&strips);
    }

    progress.set_message("verifying");
    let cache = CacheModel {
        kind: if args.lru {
            CacheKind::Lru
        } else {
            CacheKind::Fifo
        },
        size: args.cache,
    };
    let figures = metrics::figures(&tris, &strips, cache);
    let v = strip::verify(&tris, &strips);
    if !v.ok() {
        return Err(fail_verification("the strips", &v));
    }
    // The strips as the output will hold them, checked again after the join.
    let joined = match args.join {
        Join::Restart => strip::decode_restart(
            &strip::encode_restart(&strips, args.restart_index),
            args.restart_index,
        ),
        Join::Degenerate => single_stitched(&strips),
        Join::Separate => StripSet::from_strips(&strip::encode_separate(&strips)),
    };
    let v = strip::verify(&tris, &joined);
    if !v.ok() {
        return Err(fail_verification("the joined buffer", &v));
    }

    progress.set_message(format!("writing {}", args.output.display()));
    let report = Report {
        input: &args.input,
        output: &args.output,
        algo,
        heuristic: args.heuristic,
        join: args.join,
        vertices: vertex_count,
        figures: &figures,
        ms,
        diagonals: split,
        quads,
        indices_per_quad: quads
            .filter(|&q| q > 0)
            .map(|q| figures.indices_restart as f64 / q as f64),
    };
    match kind {
        OutKind::Json => {
            let bytes = json_output(&args, &joined, &strips, &report)?;
            std::fs::write(&args.output, bytes).map_err(|source| Error::Io {
                path: args.output.clone(),
                source,
            })?;
        }
        OutKind::Mesh(format) => {
            let to_write = mesh_output(&args, format, &mesh, &strips, &joined, &tris)?;
            io::write(&args.output, &mesh, Some(&to_write))?;
        }
    }
    progress.finish_and_clear();

    let mut stdout = std::io::stdout().lock();
    let printed = if args.json {
        writeln!(stdout, "{}", serde_json::to_string(&report)?)
    } else {
        print_summary(&mut stdout, &report)
    };
    match printed {
        // A closed pipe (`| head`) is not an error of ours.
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(e.into()),
        _ => Ok(()),
    }
}

fn single_stitched(strips: &StripSet) -> StripSet {
    let one = strip::encode_stitched(strips);
    if one.is_empty() {
        StripSet::new()
    } else {
        StripSet::from_strips(&[one])
    }
}

fn json_output(
    args: &Args,
    joined: &StripSet,
    strips: &StripSet,
    report: &Report,
) -> anyhow::Result<Vec<u8>> {
    let mut obj = serde_json::Map::new();
    obj.insert("join".into(), serde_json::to_value(args.join)?);
    obj.insert(
        "strips".into(),
        serde_json::to_value(strip::encode_separate(joined))?,
    );
    if args.join == Join::Restart {
        obj.insert("restart_index".into(), args.restart_index.into());
        obj.insert(
            "indices".into(),
            serde_json::to_value(strip::encode_restart(strips, args.restart_index))?,
        );
    }
    obj.insert("figures".into(), serde_json::to_value(report)?);
    let mut bytes = serde_json::to_vec(&serde_json::Value::Object(obj))?;
    bytes.push(b'\n');
    Ok(bytes)
}

fn mesh_output(
    args: &Args,
    format: Format,
    mesh: &Mesh,
    strips: &StripSet,
    joined: &StripSet,
    tris: &[[u32; 3]],
) -> anyhow::Result<StripSet> {
    // PLY `tristrips` ends strips with -1 (its own restart); glTF has no restart, so
    // it gets the stitched strip unless strips are asked for separately.
    let to_write = match (format, args.join) {
        (Format::Ply, Join::Degenerate) | (Format::Gltf | Format::Glb, Join::Separate) => {
            joined.clone()
        }
        (Format::Ply, _) => strips.clone(),
        _ => single_stitched(strips),
    };
    let bytes = io::write_bytes(format, mesh, Some(&to_write), &WriteOptions::default())?;
    // Read the bytes back with the library's reader and check them once more.
    let back = io::read_bytes(&args.output, format, &bytes).with_context(|| {
        format!(
            "reading back the {} bytes about to be written",
            args.output.display()
        )
    })?;
    let v = strip::verify_triangles(tris, &back.triangulate().tris);
    if !v.ok() {
        return Err(fail_verification(
            &format!("{} read back", args.output.display()),
            &v,
        ));
    }
    Ok(to_write)
}

fn print_summary(out: &mut impl Write, r: &Report) -> std::io::Result<()> {
    let f = r.figures;
    let name = |v: &dyn std::fmt::Debug| format!("{v:?}").to_lowercase();
    writeln!(
        out,
        "{} -> {} ({}, heuristic {}, join {})",
        r.input.display(),
        r.output.display(),
        name(&r.algo),
        name(&r.heuristic),
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
    writeln!(out, "  stripify ms          {:>10.2}", r.ms)?;
    Ok(())
}

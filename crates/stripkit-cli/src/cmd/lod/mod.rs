//! `stripkit lod`: multiresolution strips (SETS). `build` makes a `.sets` model from a
//! mesh and proves every level against a replay of the collapses, `extract` writes
//! one level, `bench` runs the paper's recovery tests.

mod bench;
mod extract;

use anyhow::Context;
use clap::{Subcommand, ValueEnum};
use serde::Serialize;
use std::io::Write;
use std::path::PathBuf;
use stripkit::lod::{self, BuildOptions, SeqOptions};
use stripkit::simplify::Placement;

/// Arguments of `stripkit lod`.
#[derive(clap::Args)]
#[command(after_help = "Levels: level L is the mesh after the first L collapses of the simplifier; \
level 0 is the input, the last level the coarsest the simplifier reaches.

  stripkit lod build ../shared/models/bunny.obj -o bunny.sets
  stripkit lod extract bunny.sets --ratio 0.1 -o bunny_10.glb
  stripkit lod bench bunny.sets")]
pub struct Args {
    #[command(subcommand)]
    what: What,
}

#[derive(Subcommand)]
enum What {
    /// Strip a mesh, simplify it as far as the simplifier goes (its defaults), and
    /// write the SETS model of both: the strips of every level, recovered by binary
    /// search. Every level is checked against a replay of the collapses before the
    /// file is written.
    Build(BuildArgs),
    /// Build the level-of-detail strips of an animation: a folder of frames that
    /// share one face list (`.obj.gz` and every mesh format; a file whose name
    /// contains `reference` is the reference pose). One set of strips for every
    /// frame; each frame's own simplification, and the reference pose's, measured on
    /// every frame; a few kept (each a SETS model), each frame taking the best kept
    /// one that is no worse than the reference pose's. Writes a `.lodseq`.
    BuildSeq(BuildSeqArgs),
    /// Write the strips of one level of a `.sets` model or of one frame of a
    /// `.lodseq` (`--frame`) (PLY `tristrips`, glTF
    /// `TRIANGLE_STRIP` stitched, OBJ/OFF/STL as triangles, `.json` as strips).
    Extract(extract::ExtractArgs),
    /// The paper's recovery tests on a `.sets` model: 1, 3, 6, 10, 15 and 20% of the
    /// levels, spaced linearly and exponentially, from the finest level to the
    /// coarsest and back; mean time per level recovered.
    Bench(bench::BenchArgs),
}

/// How much of the model `lod build` checks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum CheckArg {
    /// Every level.
    All,
    /// 2,000 levels spread over the range, plus the coarsest.
    Sample,
    /// Only the library's own check: 17 levels spread over the range.
    Off,
}

#[derive(clap::Args)]
struct BuildArgs {
    /// Input mesh (OBJ, PLY, OFF, STL, glTF; `.gz` is decompressed).
    file: PathBuf,
    /// Output model (`.sets`).
    #[arg(short, long)]
    output: PathBuf,
    /// Survivor placement of the collapses: endpoint (half-edge collapses, no new vertices) or optimal (a new vertex per collapse at the simplifier's optimal position). Default endpoint.
    #[arg(long, value_parser = crate::cmd::named::<Placement>(Placement::NAMES))]
    placement: Option<Placement>,
    /// Re-strip as the strips decay: a level whose strips take more than this many indices per triangle (restart buffer) gets new greedy strips, every level still exact (a version-3 `.sets`). At least 1; default 1.6 (the library's `lod::DEFAULT_RESTRIP`), which keeps every level at most 1.6 indices per triangle and makes switches faster. `off` keeps the level-0 strips at every level (a smaller model in memory, but coarse levels cost up to about 4 indices per triangle).
    #[arg(long, value_name = "INDICES_PER_TRIANGLE|off", value_parser = restrip_threshold)]
    restrip: Option<Restrip>,
    #[command(flatten)]
    common: CommonArgs,
}

/// `--restrip`'s value: a threshold, or `None` for `off` (keep the level-0 strips).
#[derive(Clone, Copy, Debug)]
struct Restrip(Option<f64>);

/// `--restrip`'s value: a number of at least 1, or `off`.
fn restrip_threshold(s: &str) -> Result<Restrip, String> {
    if s == "off" {
        return Ok(Restrip(None));
    }
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 1.0 => Ok(Restrip(Some(x))),
        _ => Err(format!("{s} is neither `off` nor a number of indices per triangle of at least 1")),
    }
}

#[derive(clap::Args)]
struct BuildSeqArgs {
    /// The folder of frames.
    folder: PathBuf,
    /// Output (`.lodseq`).
    #[arg(short, long)]
    output: PathBuf,
    /// Most simplification sequences to choose (each is one SETS model, about
    /// 9 bytes per triangle), besides the reference pose's, which is kept too when
    /// a frame falls back to it.
    #[arg(long, default_value_t = SeqOptions::default().max_sequences)]
    max_sequences: usize,
    /// Stop keeping sequences once every frame's Hausdorff distance, at 10% and 2%
    /// of the triangles, is within this factor of its own simplification's.
    #[arg(long, default_value_t = SeqOptions::default().tolerance)]
    tolerance: f64,
    /// Samples per surface for the distances that choose the sequences (and the
    /// quality table the report prints). 1 to 10,000,000 (24 bytes each).
    #[arg(long, default_value_t = SeqOptions::default().samples)]
    samples: usize,
    /// Candidate sequences: every frame's when there are at most this many frames,
    /// else this many evenly spaced (the reference pose's is always one).
    #[arg(long, default_value_t = SeqOptions::default().candidates)]
    candidates: usize,
    /// Store positions quantized to this many bits per coordinate (8 to 20) over the
    /// animation's bounding box, as differences from the previous frame, deflated
    /// (sizes and errors: docs/experiments/lod-seq.md). The frames are quantized first, so the sequences and
    /// the quality table see the stored positions. Default: exact f32 positions.
    #[arg(long, value_name = "BITS", value_parser = clap::value_parser!(u32).range(8..=20))]
    position_bits: Option<u32>,
    #[command(flatten)]
    common: CommonArgs,
}

impl CheckArg {
    /// The levels to check: `None` for none, `Some(None)` for all, `Some(Some(n))`
    /// for about `n`.
    fn max_levels(self) -> Option<Option<usize>> {
        match self {
            CheckArg::All => Some(None),
            CheckArg::Sample => Some(Some(2000)),
            CheckArg::Off => None,
        }
    }
}

/// What `lod build` and `lod build-seq` share.
#[derive(clap::Args)]
struct CommonArgs {
    /// How many levels of each model to check against a replay of its collapses
    /// before the file is written.
    #[arg(long, value_enum, default_value = "all")]
    check: CheckArg,
    /// Print one JSON object on stdout (`build-seq`: with the per-frame quality table).
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    strip: crate::cmd::strip::StripArgs,
    #[command(flatten)]
    read: crate::cmd::ReadArgs,
}

/// Runs the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    match args.what {
        What::Build(a) => build(a),
        What::BuildSeq(a) => build_seq(a),
        What::Extract(a) => extract::extract(a),
        What::Bench(a) => bench::bench(a),
    }
}

#[derive(Serialize)]
struct BuildOut {
    input: String,
    output: String,
    #[serde(flatten)]
    report: lod::BuildReport,
    placement: &'static str,
    bytes: usize,
    check: Option<lod::LevelCheck>,
}

fn build(args: BuildArgs) -> anyhow::Result<()> {
    args.common.strip.check()?;
    crate::cmd::check_extension("-o", &args.output, "a SETS model", &["sets"])?;
    crate::cmd::check_not_inputs(&[("input", &args.file)], &[("-o", &args.output)])?;
    crate::cmd::check_output_folder(&args.output)?;
    let mesh = args.common.read.read(&args.file)?;
    args.common.strip.check_mesh(&mesh, &args.file)?;
    let placement = args.placement.unwrap_or(BuildOptions::default().placement);
    let mut options = BuildOptions::default().strip(args.common.strip.options()?).placement(placement);
    if let Some(Restrip(threshold)) = args.restrip {
        options = options.restrip(threshold);
    }
    let bar = crate::cmd::progress_bar(mesh.triangle_count() > 200_000, "simplify");
    let built = lod::build(&mesh, &options, &mut |f| bar.set_position((f * 1000.0) as u64))
        .with_context(|| format!("building the model of {}", args.file.display()))?;
    bar.finish_and_clear();
    let check = args.common.check.max_levels().map(|max| built.check_with(max, crate::cmd::threads())).transpose()?;
    // Written once the bytes read back to the model that was checked.
    let bytes = built.sets.write(&args.output)?;
    let out = BuildOut {
        input: args.file.display().to_string(),
        output: args.output.display().to_string(),
        report: built.report,
        placement: placement.name(),
        bytes,
        check,
    };
    crate::cmd::print_report(args.common.json, &out, |w, o| {
        let r = &o.report;
        writeln!(
            w,
            "{}: {} triangles in {} {} strips, {} levels down to {} triangles ({} placement)",
            o.input, r.triangles, r.strips, r.algorithm, r.levels, r.coarsest_triangles, o.placement
        )?;
        writeln!(
            w,
            "model: {} slots, {} versions, {} strip beginnings; {} bytes on disk, {} in memory",
            r.slots, r.versions, r.beginnings, o.bytes, r.memory_bytes
        )?;
        if r.restripped_strips > 0 {
            writeln!(w, "re-stripped: {} strips made where the strips decayed", r.restripped_strips)?;
        }
        match &o.check {
            Some(c) => writeln!(
                w,
                "checked: {} levels against the replay ({} replays from scratch), exact with winding, {:.0} ms",
                c.levels_checked, c.replays, c.ms
            )?,
            None => writeln!(w, "checked: no (--check off)")?,
        }
        writeln!(
            w,
            "times: strips {:.1} ms, simplify {:.1} ms, model {:.1} ms -> {}",
            r.strip_ms, r.simplify_ms, r.build_ms, o.output
        )
    })
}

#[derive(Serialize)]
struct BuildSeqOut {
    input: String,
    output: String,
    #[serde(flatten)]
    report: lod::SeqReport,
    bytes: usize,
    /// Bytes of the file outside the models: the frames' positions, names, header.
    position_bytes: usize,
    /// Bytes of the models: the level-of-detail data.
    lod_bytes: usize,
    levels_checked: usize,
    check_ms: f64,
}

fn build_seq(args: BuildSeqArgs) -> anyhow::Result<()> {
    args.common.strip.check()?;
    // Not a mesh name, so never one of the folder's frames.
    crate::cmd::check_extension("-o", &args.output, "a level-of-detail animation", &["lodseq"])?;
    crate::cmd::check_not_inputs(&[("input folder", &args.folder)], &[("-o", &args.output)])?;
    crate::cmd::check_output_folder(&args.output)?;
    anyhow::ensure!(args.max_sequences >= 1, "--max-sequences must be at least 1");
    anyhow::ensure!(args.tolerance >= 1.0, "--tolerance {} must be 1 or more", args.tolerance);
    let max = stripkit::distance::MAX_SAMPLES;
    anyhow::ensure!(
        (1..=max).contains(&args.samples),
        "--samples {} is out of range: 1 to {max} (each sample takes 24 bytes)",
        args.samples
    );
    anyhow::ensure!(args.candidates >= 1, "--candidates must be at least 1");
    let frames = lod::read_frames(&args.folder, &args.common.read.options())?;
    if frames.mesh.face_count() == 0 {
        return Err(stripkit::Error::Invalid(format!("no faces in {}", args.folder.display())).into());
    }
    args.common.strip.check_mesh(&frames.mesh, &args.folder)?;
    let options = SeqOptions::default()
        .strip(args.common.strip.options()?)
        .max_sequences(args.max_sequences)
        .tolerance(args.tolerance)
        .samples(args.samples)
        .candidates(args.candidates)
        .position_bits(args.position_bits);
    let bar = crate::cmd::progress_bar(true, "simplify and measure");
    let built = lod::build_seq(&frames, &options, &mut |f| bar.set_position((f * 1000.0) as u64))
        .with_context(|| format!("building the level-of-detail strips of {}", args.folder.display()))?;
    bar.finish_and_clear();
    let threads = crate::cmd::threads();
    let check = args.common.check.max_levels().map(|max| built.check_with(max, threads)).transpose()?.unwrap_or_default();
    let bytes = built.seq.write(&args.output)?;
    let lod_bytes = built.seq.model_bytes();
    let position_bytes = bytes - lod_bytes;
    let out = BuildSeqOut {
        input: args.folder.display().to_string(),
        output: args.output.display().to_string(),
        report: built.report,
        bytes,
        position_bytes,
        lod_bytes,
        levels_checked: check.levels_checked,
        check_ms: check.ms,
    };
    crate::cmd::print_report(args.common.json, &out, |w, o| {
        let r = &o.report;
        let f = r.frames as f64 * 1024.0;
        writeln!(
            w,
            "{}: {} frames of {} vertices, {} triangles in {} strips; {} sequences kept of {} candidates: {}",
            o.input,
            r.frames,
            r.vertices,
            r.triangles,
            r.strips,
            r.sequences.len(),
            r.candidates,
            r.sequences.join(", ")
        )?;
        writeln!(
            w,
            "size: {} bytes, {:.1} KB per frame: positions {:.1} KB, level-of-detail data {:.1} KB",
            o.bytes,
            o.bytes as f64 / f,
            o.position_bytes as f64 / f,
            o.lod_bytes as f64 / f
        )?;
        let worst = |g: &dyn Fn(&lod::FrameQuality) -> f64| r.quality.iter().map(g).fold(0.0, f64::max);
        for (i, pct) in ["10%", "2%"].iter().enumerate() {
            writeln!(
                w,
                "worst frame at {pct} (Hausdorff / diagonal): this scheme {:.3e}, reference pose's sequence {:.3e}, each frame's own {:.3e}",
                worst(&|q| q.chosen.hausdorff[i]),
                worst(&|q| q.reference.hausdorff[i]),
                worst(&|q| q.own.hausdorff[i])
            )?;
        }
        writeln!(
            w,
            "checked: {} levels against the replay, {:.0} ms; times: simplify {:.0} ms, distances {:.0} ms, models {:.0} ms -> {}",
            o.levels_checked, o.check_ms, r.simplify_ms, r.distance_ms, r.model_ms, o.output
        )
    })
}

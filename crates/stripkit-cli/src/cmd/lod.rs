//! `stripkit lod`: multiresolution strips (SETS). `build` makes a `.sets` model from a
//! mesh and proves every level against a replay of the collapses, `extract` writes
//! one level, `bench` runs the paper's recovery tests.

use anyhow::Context;
use clap::{Subcommand, ValueEnum};
use serde::Serialize;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;
use stripkit::io::{self, Format};
use stripkit::lod::{self, BuildOptions, Extracted, LevelSpec, LodSeq, Model, SeqOptions, Sets, Spacing};
use stripkit::simplify::Placement;
use stripkit::{Error, Mesh, StripSet};

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
    Extract(ExtractArgs),
    /// The paper's recovery tests on a `.sets` model: 1, 3, 6, 10, 15 and 20% of the
    /// levels, spaced linearly and exponentially, from the finest level to the
    /// coarsest and back; mean time per level recovered.
    Bench(BenchArgs),
}


/// How much of the model `lod build` checks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum CheckArg {
    /// Every level (bunny: 34,819 levels in about 1.6 s).
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
    #[arg(long, value_parser = super::named::<Placement>(Placement::NAMES))]
    placement: Option<Placement>,
    #[command(flatten)]
    common: CommonArgs,
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
    #[arg(long, default_value_t = 16)]
    max_sequences: usize,
    /// Stop keeping sequences once every frame's Hausdorff distance, at 10% and 2%
    /// of the triangles, is within this factor of its own simplification's.
    #[arg(long, default_value_t = 1.25)]
    tolerance: f64,
    /// Samples per surface for the distances that choose the sequences (and the
    /// quality table the report prints).
    #[arg(long, default_value_t = 4000)]
    samples: usize,
    /// Candidate sequences: every frame's when there are at most this many frames,
    /// else this many evenly spaced (the reference pose's is always one).
    #[arg(long, default_value_t = 24)]
    candidates: usize,
    /// Store positions quantized to this many bits per coordinate (8 to 20) over the
    /// animation's bounding box, as differences from the previous frame, deflated
    /// (horse-gallop, 12 bits: about 22 KB per frame instead of 99 KB, within
    /// 7e-5 of the diagonal). The frames are quantized first, so the sequences and
    /// the quality table see the stored positions. Default: exact f32 positions.
    #[arg(long, value_name = "BITS", value_parser = clap::value_parser!(u32).range(8..=20))]
    position_bits: Option<u32>,
    #[command(flatten)]
    common: CommonArgs,
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
    strip: super::strip::StripArgs,
    #[command(flatten)]
    read: super::ReadArgs,
}

#[derive(clap::Args)]
#[command(group(clap::ArgGroup::new("which").required(true).args(["level", "triangles", "ratio"])))]
struct ExtractArgs {
    /// The model (`.sets`).
    file: PathBuf,
    /// Level (collapses applied; 0 is the input); past the coarsest is the coarsest.
    #[arg(long)]
    level: Option<u32>,
    /// The first level with at most this many triangles.
    #[arg(long)]
    triangles: Option<u64>,
    /// The first level with at most ceil(RATIO x input triangles): where `stripkit
    /// simplify --ratio RATIO` stops. 0 to 1.
    #[arg(long)]
    ratio: Option<f64>,
    /// Animations (.lodseq): the frame, 0 to frames - 1. A fraction morphs the
    /// positions linearly between the two key frames around it; the level follows
    /// the nearest key frame.
    #[arg(long)]
    frame: Option<f64>,
    /// Output file; the extension picks the format.
    #[arg(short, long)]
    output: PathBuf,
    /// Print one JSON object on stdout.
    #[arg(long)]
    json: bool,
    /// Write PLY as ASCII text instead of binary (PLY outputs only).
    #[arg(long)]
    ascii: bool,
}

#[derive(clap::Args)]
struct BenchArgs {
    /// The model (`.sets`).
    file: PathBuf,
    /// Passes over each test's levels (the mean is over all of them).
    #[arg(long, default_value_t = 5)]
    rounds: usize,
    /// Also build the tight restart buffer after each level change.
    #[arg(long)]
    compact: bool,
    /// Print one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// Runs the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    match args.what {
        What::Build(a) => build(a),
        What::BuildSeq(a) => build_seq(a),
        What::Extract(a) => extract(a),
        What::Bench(a) => bench(a),
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
    super::check_output_folder(&args.output)?;
    let mesh = args.common.read.read(&args.file)?;
    args.common.strip.check_mesh(&mesh, &args.file)?;
    let placement = args.placement.unwrap_or_default();
    let options = BuildOptions { strip: args.common.strip.options()?, placement };
    let bar = super::progress_bar(mesh.triangle_count() > 200_000, "simplify");
    let built = lod::build(&mesh, &options, &mut |f| bar.set_position((f * 1000.0) as u64))
        .with_context(|| format!("building the model of {}", args.file.display()))?;
    bar.finish_and_clear();
    let check = match args.common.check {
        CheckArg::Off => None,
        CheckArg::All | CheckArg::Sample => {
            let stride =
                if args.common.check == CheckArg::All { 1 } else { (built.sets.levels() as usize / 2000).max(1) };
            Some(lod::check_levels(&built.sets, &built.mesh, &built.sequence, stride, 100)?)
        }
    };
    let bytes = built.sets.to_bytes();
    // The file read back must be the model that was checked.
    let back = Sets::from_bytes(&args.output, &bytes)?;
    if back != built.sets {
        return Err(Error::Verification("the .sets bytes do not read back to the model".into()).into());
    }
    io::write_atomic(&args.output, &bytes)?;
    let out = BuildOut {
        input: args.file.display().to_string(),
        output: args.output.display().to_string(),
        report: built.report,
        placement: placement.name(),
        bytes: bytes.len(),
        check,
    };
    super::print_report(args.common.json, &out, |w, o| {
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
    super::check_output_folder(&args.output)?;
    anyhow::ensure!(args.max_sequences >= 1, "--max-sequences must be at least 1");
    anyhow::ensure!(args.tolerance >= 1.0, "--tolerance {} must be 1 or more", args.tolerance);
    anyhow::ensure!(args.samples >= 1, "--samples must be at least 1");
    anyhow::ensure!(args.candidates >= 1, "--candidates must be at least 1");
    let frames = lod::read_frames(&args.folder, &args.common.read.options())?;
    if frames.mesh.face_count() == 0 {
        return Err(stripkit::Error::Invalid(format!("no faces in {}", args.folder.display())).into());
    }
    args.common.strip.check_mesh(&frames.mesh, &args.folder)?;
    let options = SeqOptions {
        strip: args.common.strip.options()?,
        max_sequences: args.max_sequences,
        tolerance: args.tolerance,
        samples: args.samples,
        candidates: args.candidates,
        position_bits: args.position_bits,
    };
    let bar = super::progress_bar(true, "simplify and measure");
    let built = lod::build_seq(&frames, &options, &mut |f| bar.set_position((f * 1000.0) as u64))
        .with_context(|| format!("building the level-of-detail strips of {}", args.folder.display()))?;
    bar.finish_and_clear();
    let t = Instant::now();
    let mut levels_checked = 0;
    if args.common.check != CheckArg::Off {
        let mesh = Mesh::from_triangles(frames.positions[0].clone(), &built.triangles);
        for (sets, sequence) in built.seq.models().iter().zip(&built.sequences) {
            let stride = if args.common.check == CheckArg::All { 1 } else { (sets.levels() as usize / 2000).max(1) };
            levels_checked += lod::check_levels(sets, &mesh, sequence, stride, 20)?.levels_checked;
        }
    }
    let check_ms = t.elapsed().as_secs_f64() * 1e3;
    let bytes = built.seq.to_bytes();
    if LodSeq::from_bytes(&args.output, &bytes)? != built.seq {
        return Err(Error::Verification("the .lodseq bytes do not read back to the model".into()).into());
    }
    io::write_atomic(&args.output, &bytes)?;
    // Each model is stored as its length (a varint) and its bytes.
    let varint_len = |n: usize| (usize::BITS - n.max(1).leading_zeros()).div_ceil(7) as usize;
    let lod_bytes: usize = built.seq.models().iter().map(|m| m.to_bytes().len()).map(|n| n + varint_len(n)).sum();
    let position_bytes = bytes.len() - lod_bytes;
    let out = BuildSeqOut {
        input: args.folder.display().to_string(),
        output: args.output.display().to_string(),
        report: built.report,
        bytes: bytes.len(),
        position_bytes,
        lod_bytes,
        levels_checked,
        check_ms,
    };
    super::print_report(args.common.json, &out, |w, o| {
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

#[derive(Serialize)]
struct ExtractOut {
    input: String,
    output: String,
    frame: Option<f64>,
    level: u32,
    levels: u32,
    triangles: u32,
    strips: usize,
    indices: usize,
    indices_per_triangle: f64,
    verified: bool,
    us: f64,
}

fn extract(args: ExtractArgs) -> anyhow::Result<()> {
    let format = match Format::from_path(&args.output) {
        Some((f, _)) => Some(f),
        None if is_json(&args.output) => None,
        None => {
            return Err(Error::Invalid(format!(
                "cannot tell the format of {} from its extension (use {} or .json)",
                args.output.display(),
                io::supported_write_extensions()
            ))
            .into())
        }
    };
    if let Some(r) = args.ratio {
        anyhow::ensure!((0.0..=1.0).contains(&r), "--ratio {r} is out of range: 0 to 1");
    }
    let write_options = super::write_options(args.ascii, &args.output, super::path_format(&args.output))?;
    super::check_output_folder(&args.output)?;
    let model = read_model(&args.file)?;
    let spec = match (args.level, args.triangles, args.ratio) {
        (Some(l), _, _) => LevelSpec::Level(l),
        (_, Some(t), _) => LevelSpec::Triangles(t),
        (_, _, Some(r)) => LevelSpec::Ratio(r),
        _ => anyhow::bail!("give one of --level, --triangles, --ratio"),
    };
    // A .lodseq (by its header) needs --frame; a .sets refuses it.
    let start = Instant::now();
    let Extracted { positions, strips, level, levels, triangles: expected, frame } =
        model.extract(spec, args.frame).with_context(|| format!("{} (--frame)", args.file.display()))?;
    let us = start.elapsed().as_secs_f64() * 1e6;
    let frame = frame.map(|(t, _)| t);
    let triangles = stripkit::decode(&strips);
    if triangles.len() != expected as usize {
        return Err(Error::Verification(format!(
            "level {level}: the strips draw {} triangles, the model says {expected}",
            triangles.len()
        ))
        .into());
    }
    let bytes = match format {
        None => {
            let obj = serde_json::json!({
                "level": level,
                "frame": frame,
                "restart_index": u32::MAX,
                "strips": strips.iter().collect::<Vec<_>>(),
            });
            serde_json::to_vec(&obj)?
        }
        Some(format) => encode_level(positions, &strips, &triangles, format, &args.output, &write_options)?,
    };
    io::write_encoded(&args.output, &bytes)?;
    let indices = strips.index_count();
    let out = ExtractOut {
        input: args.file.display().to_string(),
        output: args.output.display().to_string(),
        frame,
        level,
        levels,
        triangles: triangles.len() as u32,
        strips: strips.len(),
        indices,
        indices_per_triangle: (strips.restart_len()) as f64 / triangles.len().max(1) as f64,
        verified: true,
        us,
    };
    super::print_report(args.json, &out, |w, o| {
        writeln!(
            w,
            "{}: level {} of {}: {} triangles in {} strips, {} indices ({:.3} per triangle with restarts), verified -> {}",
            o.input, o.level, o.levels, o.triangles, o.strips, o.indices, o.indices_per_triangle, o.output
        )
    })
}

/// The file bytes of one level, read back and compared with the strips' triangles.
fn encode_level(
    positions: Vec<[f32; 3]>,
    strips: &StripSet,
    triangles: &[[u32; 3]],
    format: Format,
    path: &Path,
    options: &io::WriteOptions,
) -> anyhow::Result<Vec<u8>> {
    let mesh = Mesh::from_triangles(positions, triangles);
    let to_write = match format {
        Format::Ply => Some(strips.clone()),
        Format::Gltf | Format::Glb => Some(StripSet::from_strips(&[stripkit::encode_stitched(strips)])),
        _ => None,
    };
    let bytes = io::write_bytes(format, &mesh, to_write.as_ref(), options)?;
    let name = format!("the {format:?} bytes of {}", path.display());
    let back = io::read_bytes(Path::new(&name), format, &bytes)?;
    let v = stripkit::verify_triangles(triangles, &back.triangulate().tris);
    if !v.ok() {
        return Err(Error::Verification(format!("{name}, read back: {v}")).into());
    }
    Ok(bytes)
}

/// A `.sets` or `.lodseq` file; anything else is a format error naming it.
fn read_model(path: &Path) -> anyhow::Result<Model> {
    Model::read(path)?.ok_or_else(|| {
        Error::Format {
            path: path.to_path_buf(),
            at: "byte 0".into(),
            what: "not a stripkit .sets or .lodseq file (bad magic)".into(),
        }
        .into()
    })
}

fn is_json(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

#[derive(Serialize)]
struct BenchRow {
    percent: f64,
    spacing: Spacing,
    levels: usize,
    us_per_level: f64,
}

#[derive(Serialize)]
struct BenchOut {
    input: String,
    levels: u32,
    triangles: u32,
    strips: usize,
    rows: Vec<BenchRow>,
    /// One change from the coarsest level to the finest (every strip re-walked).
    coarsest_to_finest_us: f64,
    /// A cursor made at the finest level (every strip walked from scratch).
    from_scratch_us: f64,
    compact: bool,
}

fn bench(args: BenchArgs) -> anyhow::Result<()> {
    let sets = match read_model(&args.file)? {
        Model::Seq(seq) => return bench_seq(&args, &seq),
        Model::Sets(sets) => sets,
    };
    let mut rows = Vec::new();
    for percent in [1.0, 3.0, 6.0, 10.0, 15.0, 20.0] {
        for spacing in [Spacing::Linear, Spacing::Exponential] {
            let (levels, us) = lod::bench_levels(&sets, percent, spacing, args.rounds, args.compact);
            rows.push(BenchRow { percent, spacing, levels, us_per_level: us });
        }
    }
    // The worst single change: coarsest to finest, the median of the rounds.
    let mut cursor = sets.cursor(sets.levels());
    let mut worst = Vec::new();
    let mut scratch = Vec::new();
    for _ in 0..args.rounds.max(1) {
        cursor.set_level(sets.levels());
        let t = Instant::now();
        cursor.set_level(0);
        worst.push(t.elapsed().as_secs_f64() * 1e6);
        let t = Instant::now();
        let c = sets.cursor(0);
        scratch.push(t.elapsed().as_secs_f64() * 1e6);
        drop(c);
    }
    let out = BenchOut {
        input: args.file.display().to_string(),
        levels: sets.levels(),
        triangles: sets.triangles_at(0),
        strips: sets.strip_count(),
        rows,
        coarsest_to_finest_us: median(&mut worst),
        from_scratch_us: median(&mut scratch),
        compact: args.compact,
    };
    super::print_report(args.json, &out, |w, o| {
        writeln!(
            w,
            "{}: {} levels, {} triangles, {} strips; mean microseconds per level recovered{}",
            o.input,
            o.levels,
            o.triangles,
            o.strips,
            if o.compact { " (with the tight buffer)" } else { "" }
        )?;
        writeln!(w, "{:>6} {:>10} {:>8} {:>10} {:>8}", "levels", "linear", "count", "exponential", "count")?;
        for pair in o.rows.chunks(2) {
            writeln!(
                w,
                "{:>5}% {:>10.1} {:>8} {:>10.1} {:>8}",
                pair[0].percent, pair[0].us_per_level, pair[0].levels, pair[1].us_per_level, pair[1].levels
            )?;
        }
        writeln!(
            w,
            "coarsest -> finest in one change: {:.1} us; a cursor from scratch at the finest: {:.1} us",
            o.coarsest_to_finest_us, o.from_scratch_us
        )
    })
}

#[derive(Serialize)]
struct SeqTiming {
    /// What changes: "frame" (every frame of the animation in turn at a fixed
    /// level), "level" (1% of the levels per step, or one level up and back, at a
    /// fixed frame), "play" (the animation plays and the level changes every 24
    /// frames).
    test: &'static str,
    /// The fixed ratio of triangles ("frame"), or the frame ("level").
    at: String,
    changes: usize,
    mean_us: f64,
    max_us: f64,
    /// Mean strips re-uploaded per change.
    strips_changed: f64,
}

#[derive(Serialize)]
struct BenchSeqOut {
    input: String,
    frames: usize,
    models: usize,
    triangles: u32,
    strips: usize,
    rows: Vec<SeqTiming>,
    /// A cursor made from scratch (every strip walked) at frame 0, full level.
    from_scratch_us: f64,
}

/// Times `cursor.set` over `steps`, `rounds` times: mean and max microseconds and
/// mean strips changed per timed step. A step whose flag is false only positions
/// the cursor (untimed).
fn time_changes(cursor: &mut lod::SeqCursor<'_>, steps: &[(usize, LevelSpec, bool)], rounds: usize) -> (f64, f64, f64) {
    let (mut total, mut max, mut changed, mut n) = (0.0f64, 0.0f64, 0usize, 0usize);
    for _ in 0..rounds.max(1) {
        for &(f, spec, timed) in steps {
            let t = Instant::now();
            let c = cursor.set(f, spec).len();
            let us = t.elapsed().as_secs_f64() * 1e6;
            if timed {
                total += us;
                max = max.max(us);
                changed += c;
                n += 1;
            }
        }
    }
    let n = n.max(1) as f64;
    (total / n, max, changed as f64 / n)
}

fn bench_seq(args: &BenchArgs, seq: &LodSeq) -> anyhow::Result<()> {
    let frames = seq.frame_count();
    let mut rows = Vec::new();
    // Frame changes at a fixed level: the animation played at each ratio.
    for ratio in [1.0, 0.5, 0.1, 0.02] {
        let spec = LevelSpec::Ratio(ratio);
        let mut cursor = seq.cursor(0, spec);
        let steps: Vec<(usize, LevelSpec, bool)> = (0..frames).map(|f| ((f + 1) % frames, spec, true)).collect();
        time_changes(&mut cursor, &steps, 1); // every model's cursor made once
        let (mean, max, changed) = time_changes(&mut cursor, &steps, args.rounds);
        rows.push(SeqTiming {
            test: "frame",
            at: format!("{}%", ratio * 100.0),
            changes: steps.len(),
            mean_us: mean,
            max_us: max,
            strips_changed: changed,
        });
    }
    // Level changes at a fixed frame: 1% of the levels per step, down and back.
    for f in [0, frames / 2] {
        let levels = seq.models()[seq.model_of(f)].levels();
        let step = (levels / 100).max(1);
        let mut steps: Vec<(usize, LevelSpec, bool)> =
            (0..=levels).step_by(step as usize).map(|l| (f, LevelSpec::Level(l), true)).collect();
        let back: Vec<_> = steps.iter().rev().skip(1).copied().collect();
        steps.extend(back);
        let mut cursor = seq.cursor(f, LevelSpec::Level(0));
        let (mean, max, changed) = time_changes(&mut cursor, &steps, args.rounds);
        rows.push(SeqTiming {
            test: "level",
            at: format!("frame {f}, 1% steps"),
            changes: steps.len(),
            mean_us: mean,
            max_us: max,
            strips_changed: changed,
        });
    }
    // One level up and back at 100 points of the range, at frame 0.
    let levels = seq.models()[seq.model_of(0)].levels();
    // Placed at each point untimed, then one level down and back up, timed.
    let steps: Vec<(usize, LevelSpec, bool)> = (0..levels)
        .step_by((levels as usize / 100).max(1))
        .flat_map(|l| {
            [(0, LevelSpec::Level(l), false), (0, LevelSpec::Level(l + 1), true), (0, LevelSpec::Level(l), true)]
        })
        .collect();
    let mut cursor = seq.cursor(0, LevelSpec::Level(0));
    let (mean, max, changed) = time_changes(&mut cursor, &steps, args.rounds);
    rows.push(SeqTiming {
        test: "level",
        at: "frame 0, one level".into(),
        changes: 2 * steps.len() / 3,
        mean_us: mean,
        max_us: max,
        strips_changed: changed,
    });
    // The paper's Fig. 5b: the animation plays, the level moves every 24 frames
    // (100% -> 2% -> 100% in ten steps each way).
    let ratios: Vec<f64> =
        (0..=10).map(|i| 1.0 - 0.098 * i as f64).chain((0..10).rev().map(|i| 1.0 - 0.098 * i as f64)).collect();
    let steps: Vec<(usize, LevelSpec, bool)> =
        (0..ratios.len() * 24).map(|i| (i % frames, LevelSpec::Ratio(ratios[i / 24]), true)).collect();
    let mut cursor = seq.cursor(0, LevelSpec::Ratio(1.0));
    time_changes(&mut cursor, &steps, 1);
    let (mean, max, changed) = time_changes(&mut cursor, &steps, args.rounds);
    rows.push(SeqTiming {
        test: "play",
        at: "level every 24 frames".into(),
        changes: steps.len(),
        mean_us: mean,
        max_us: max,
        strips_changed: changed,
    });
    let mut scratch = Vec::new();
    for _ in 0..args.rounds.max(1) {
        let t = Instant::now();
        let c = seq.cursor(0, LevelSpec::Level(0));
        scratch.push(t.elapsed().as_secs_f64() * 1e6);
        drop(c);
    }
    let out = BenchSeqOut {
        input: args.file.display().to_string(),
        frames,
        models: seq.models().len(),
        triangles: seq.models()[0].triangles_at(0),
        strips: seq.models()[0].strip_count(),
        rows,
        from_scratch_us: median(&mut scratch),
    };
    super::print_report(args.json, &out, |w, o| {
        writeln!(
            w,
            "{}: {} frames, {} models, {} triangles, {} strips; microseconds per change (extraction only, CPU)",
            o.input, o.frames, o.models, o.triangles, o.strips
        )?;
        writeln!(
            w,
            "{:>6} {:>22} {:>8} {:>10} {:>10} {:>14}",
            "test", "at", "changes", "mean", "max", "strips changed"
        )?;
        for r in &o.rows {
            writeln!(
                w,
                "{:>6} {:>22} {:>8} {:>10.1} {:>10.1} {:>14.1}",
                r.test, r.at, r.changes, r.mean_us, r.max_us, r.strips_changed
            )?;
        }
        writeln!(w, "a cursor from scratch (every strip walked): {:.1} us", o.from_scratch_us)
    })
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(0.0)
}

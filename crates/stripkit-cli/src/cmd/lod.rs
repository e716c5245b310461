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
use stripkit::lod::{self, BuildOptions, Sets, Spacing};
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
    /// Write the strips of one level of a `.sets` model (PLY `tristrips`, glTF
    /// `TRIANGLE_STRIP` stitched, OBJ/OFF/STL as triangles, `.json` as strips).
    Extract(ExtractArgs),
    /// The paper's recovery tests on a `.sets` model: 1, 3, 6, 10, 15 and 20% of the
    /// levels, spaced linearly and exponentially, from the finest level to the
    /// coarsest and back; mean time per level recovered.
    Bench(BenchArgs),
}

/// Where a collapse puts the surviving vertex.
#[derive(Clone, Copy, Debug, ValueEnum)]
enum PlacementArg {
    /// Half-edge collapses: the kept vertex keeps its position; no new vertices.
    Endpoint,
    /// A new vertex per collapse at the simplifier's optimal position
    /// (progressive-mesh style): closer surfaces, one more position per level.
    Optimal,
}

/// How much of the model `lod build` checks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum CheckArg {
    /// Every level (bunny: 34,819 levels in about 1.6 s).
    All,
    /// 2,000 levels spread over the range, plus the coarsest.
    Sample,
    /// No check (the builder's output is still what the tests check).
    Off,
}

#[derive(clap::Args)]
struct BuildArgs {
    /// Input mesh (OBJ, PLY, OFF, STL, glTF; `.gz` is decompressed).
    file: PathBuf,
    /// Output model (`.sets`).
    #[arg(short, long)]
    output: PathBuf,
    /// Survivor placement of the collapses.
    #[arg(long, value_enum, default_value = "endpoint")]
    placement: PlacementArg,
    /// How many levels to check against the replay before writing.
    #[arg(long, value_enum, default_value = "all")]
    check: CheckArg,
    /// Print one JSON object on stdout.
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
    /// Output file; the extension picks the format.
    #[arg(short, long)]
    output: PathBuf,
    /// Print one JSON object on stdout.
    #[arg(long)]
    json: bool,
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
    args.strip.check()?;
    super::check_output_folder(&args.output)?;
    let mesh = args.read.read(&args.file)?;
    let placement = match args.placement {
        PlacementArg::Endpoint => Placement::Endpoint,
        PlacementArg::Optimal => Placement::Optimal,
    };
    let options = BuildOptions { strip: args.strip.options(Some(&mesh)), placement };
    let bar = progress_bar(mesh.triangle_count() > 200_000, "simplify");
    let built = lod::build(&mesh, &options, &mut |f| bar.set_position((f * 1000.0) as u64))
        .with_context(|| format!("building the model of {}", args.file.display()))?;
    bar.finish_and_clear();
    let check = match args.check {
        CheckArg::Off => None,
        CheckArg::All | CheckArg::Sample => {
            let stride = if args.check == CheckArg::All { 1 } else { (built.sets.levels() as usize / 2000).max(1) };
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
        placement: match placement {
            Placement::Endpoint => "endpoint",
            Placement::Optimal => "optimal",
        },
        bytes: bytes.len(),
        check,
    };
    super::print_report(args.json, &out, |w, o| {
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
struct ExtractOut {
    input: String,
    output: String,
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
            return Err(
            Error::Invalid(format!(
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
    super::check_output_folder(&args.output)?;
    let sets = Sets::read(&args.file)?;
    let level = match (args.level, args.triangles, args.ratio) {
        (Some(l), _, _) => l.min(sets.levels()),
        (_, Some(t), _) => sets.level_for_triangles(t),
        (_, _, Some(r)) => sets.level_for_ratio(r),
        _ => anyhow::bail!("give one of --level, --triangles, --ratio"),
    };
    let start = Instant::now();
    let cursor = sets.cursor(level);
    let us = start.elapsed().as_secs_f64() * 1e6;
    let strips = cursor.strips();
    let triangles = stripkit::decode(&strips);
    if triangles.len() != sets.triangles_at(level) as usize {
        return Err(Error::Verification(format!(
            "level {level}: the strips draw {} triangles, the model says {}",
            triangles.len(),
            sets.triangles_at(level)
        ))
        .into());
    }
    let bytes = match format {
        None => {
            let obj = serde_json::json!({
                "level": level,
                "restart_index": u32::MAX,
                "strips": strips.iter().collect::<Vec<_>>(),
            });
            serde_json::to_vec(&obj)?
        }
        Some(format) => encode_level(&sets, &strips, &triangles, format, &args.output)?,
    };
    io::write_encoded(&args.output, &bytes)?;
    let indices = strips.index_count();
    let out = ExtractOut {
        input: args.file.display().to_string(),
        output: args.output.display().to_string(),
        level,
        levels: sets.levels(),
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
    sets: &Sets,
    strips: &StripSet,
    triangles: &[[u32; 3]],
    format: Format,
    path: &Path,
) -> anyhow::Result<Vec<u8>> {
    let mesh = Mesh::from_triangles(sets.positions().to_vec(), triangles);
    let to_write = match format {
        Format::Ply => Some(strips.clone()),
        Format::Gltf | Format::Glb => Some(StripSet::from_strips(&[stripkit::encode_stitched(strips)])),
        _ => None,
    };
    let bytes = io::write_bytes(format, &mesh, to_write.as_ref(), &io::WriteOptions::default())?;
    let name = format!("the {format:?} bytes of {}", path.display());
    let back = io::read_bytes(Path::new(&name), format, &bytes)?;
    let v = stripkit::verify_triangles(triangles, &back.triangulate().tris);
    if !v.ok() {
        return Err(Error::Verification(format!("{name}, read back: {v}")).into());
    }
    Ok(bytes)
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
    let sets = Sets::read(&args.file)?;
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

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(0.0)
}

fn progress_bar(show: bool, what: &str) -> indicatif::ProgressBar {
    if !show {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::with_draw_target(Some(1000), indicatif::ProgressDrawTarget::stderr());
    bar.set_style(
        indicatif::ProgressStyle::with_template(&format!("{what} {{bar:40}} {{percent:>3}}% {{elapsed}}"))
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    bar
}

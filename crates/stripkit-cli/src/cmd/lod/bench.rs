//! `stripkit lod bench`: the recovery timings of `stripkit::lod::timing`, as a table.

use serde::Serialize;
use std::io::Write;
use std::path::PathBuf;
use stripkit::lod::{timing, LodSeq, Model};

#[derive(clap::Args)]
pub(super) struct BenchArgs {
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

#[derive(Serialize)]
struct BenchOut {
    input: String,
    levels: u32,
    triangles: u32,
    strips: usize,
    rows: Vec<timing::RecoveryRow>,
    /// One change from the coarsest level to the finest (every strip re-walked).
    coarsest_to_finest_us: f64,
    /// A cursor made at the finest level (every strip walked from scratch).
    from_scratch_us: f64,
    compact: bool,
}

pub(super) fn bench(args: BenchArgs) -> anyhow::Result<()> {
    let sets = match Model::read(&args.file)? {
        Model::Seq(seq) => return bench_seq(&args, &seq),
        Model::Sets(sets) => sets,
    };
    let t = timing::sets(&sets, args.rounds, args.compact);
    let out = BenchOut {
        input: args.file.display().to_string(),
        levels: sets.levels(),
        triangles: sets.triangles_at(0),
        strips: sets.strip_count(),
        rows: t.rows,
        coarsest_to_finest_us: t.coarsest_to_finest_us,
        from_scratch_us: t.from_scratch_us,
        compact: args.compact,
    };
    crate::cmd::print_report(args.json, &out, |w, o| {
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
struct BenchSeqOut {
    input: String,
    frames: usize,
    models: usize,
    triangles: u32,
    strips: usize,
    rows: Vec<timing::SeqRow>,
    /// A cursor made from scratch (every strip walked) at frame 0, full level.
    from_scratch_us: f64,
}

fn bench_seq(args: &BenchArgs, seq: &LodSeq) -> anyhow::Result<()> {
    let t = timing::seq(seq, args.rounds);
    let out = BenchSeqOut {
        input: args.file.display().to_string(),
        frames: seq.frame_count(),
        models: seq.models().len(),
        triangles: seq.models()[0].triangles_at(0),
        strips: seq.models()[0].strip_count(),
        rows: t.rows,
        from_scratch_us: t.from_scratch_us,
    };
    crate::cmd::print_report(args.json, &out, |w, o| {
        writeln!(
            w,
            "{}: {} frames, {} models, {} triangles, {} strips; microseconds per change (extraction only, CPU)",
            o.input, o.frames, o.models, o.triangles, o.strips
        )?;
        writeln!(
            w,
            "{:>6} {:>22} {:>8} {:>10} {:>10} {:>10} {:>10} {:>14}",
            "test", "at", "changes", "mean", "median", "p99", "max", "strips changed"
        )?;
        for r in &o.rows {
            writeln!(
                w,
                "{:>6} {:>22} {:>8} {:>10.1} {:>10.1} {:>10.1} {:>10.1} {:>14.1}",
                r.test, r.at, r.changes, r.mean_us, r.median_us, r.p99_us, r.max_us, r.strips_changed
            )?;
        }
        writeln!(w, "a cursor from scratch (every strip walked): {:.1} us", o.from_scratch_us)
    })
}

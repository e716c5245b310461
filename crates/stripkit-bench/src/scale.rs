//! The `scale` bench: time and peak memory per triangle of every phase (read, the
//! stripifiers, verify, the writes, meshoptimizer's vcache + stripify) on a series of
//! Loop subdivisions (1x, 4x, 16x, 64x) of bunny and of a held-back model, at one thread
//! and at N. Each phase runs in a child process of its own ([`crate::scale_phase`]),
//! which reports its time and its own peak resident size. Writes a markdown table, a
//! JSON file of the rows and a log-log PNG of ns per triangle.

use crate::chart::{self, Colours, Series};
use crate::scale_phase::{Report, PHASES, SLOW};
use anyhow::Context;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Arguments of the `scale` bench.
#[derive(clap::Args)]
pub struct Args {
    /// The model of the series (a triangle mesh; default: bunny.obj of the research meshes).
    #[arg(long, value_name = "MODEL")]
    pub base: Option<PathBuf>,
    /// A held-back model, subdivided the same way (up to 1.5x the base's largest mesh).
    #[arg(long, value_name = "MODEL")]
    pub held_back: Option<PathBuf>,
    /// The parallel thread count measured beside one thread (default: every core).
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// The log-log PNG.
    #[arg(long, value_name = "FILE", default_value = "docs/pictures/scale.png")]
    pub out: PathBuf,
    /// Also write the markdown table to this file.
    #[arg(long, value_name = "FILE")]
    pub table: Option<PathBuf>,
    /// Also write the rows as JSON to this file.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// 1x and 4x only (seconds; the test's mode).
    #[arg(long)]
    pub quick: bool,
    /// balanced, batch and single run only on meshes up to this many triangles.
    #[arg(long, value_name = "TRIANGLES", default_value_t = 300_000)]
    pub slow_limit: usize,
    /// Runs each row this many times (each in a fresh process; round 1 of every row,
    /// then round 2, ...) and keeps the run of median time: single runs on a busy
    /// machine differ by tens of percent, and a machine's speed drifts over a run.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    pub rounds: u32,
    /// Only these phases (comma-separated names of the table; default: all).
    #[arg(long, value_name = "PHASES", value_delimiter = ',')]
    pub phases: Vec<String>,
}

/// One row of the table: a phase on a mesh at a thread count.
#[derive(serde::Serialize, serde::Deserialize, Clone, Debug)]
pub struct Row {
    /// The mesh: model name and subdivision (`bunny 4x`).
    pub mesh: String,
    /// The model's name, for the chart's lines.
    pub model: String,
    /// The phase (one of [`PHASES`]).
    pub phase: String,
    /// Threads the phase was given.
    pub threads: usize,
    /// What the phase's process reported.
    pub report: Report,
}

impl Row {
    /// Nanoseconds per triangle.
    pub fn ns_per_triangle(&self) -> f64 {
        self.report.ns as f64 / self.report.triangles.max(1) as f64
    }

    /// Peak bytes per triangle.
    pub fn bytes_per_triangle(&self) -> f64 {
        self.report.peak_bytes as f64 / self.report.triangles.max(1) as f64
    }
}

/// A model read as its bare surface, as a plain triangle mesh.
fn read_model(path: &Path) -> anyhow::Result<stripkit::Mesh> {
    let mesh = crate::common::read_surface(path).with_context(|| format!("reading {}", path.display()))?;
    Ok(stripkit::Mesh::from_triangles(mesh.positions.clone(), &mesh.triangulate().tris))
}

/// Runs one phase in a child process and reads its report.
fn run_phase(phase: &str, mesh: &Path, threads: usize, work: &Path) -> anyhow::Result<Report> {
    let exe = std::env::current_exe().context("finding the bench's own executable")?;
    let out = Command::new(exe)
        .arg("scale-phase")
        .args(["--phase", phase, "--threads", &threads.to_string()])
        .arg("--mesh")
        .arg(mesh)
        .arg("--work")
        .arg(work)
        .output()
        .with_context(|| format!("starting the {phase} phase"))?;
    anyhow::ensure!(
        out.status.success(),
        "phase {phase} at {threads} threads on {}: {}",
        mesh.display(),
        String::from_utf8_lossy(&out.stderr).trim()
    );
    let line = String::from_utf8_lossy(&out.stdout);
    serde_json::from_str(line.trim()).with_context(|| format!("phase {phase}: report {line:?}"))
}

/// The report of median time among a row's runs (the lower middle one for an even count).
fn median_report(mut reports: Vec<Report>) -> Report {
    reports.sort_by_key(|r| r.ns);
    reports.swap_remove((reports.len() - 1) / 2)
}

/// Runs the bench.
pub fn run(args: Args) -> anyhow::Result<()> {
    let base = match &args.base {
        Some(p) => p.clone(),
        None => crate::common::models_dir()
            .map(|d| d.join("bunny.obj"))
            .context("no research meshes (set STRIPKIT_MODELS) and no --base model")?,
    };
    if let Some(p) = args.phases.iter().find(|p| !PHASES.contains(&p.as_str())) {
        anyhow::bail!("unknown phase {p}; one of {}", PHASES.join(", "));
    }
    let threads = args.threads.unwrap_or_else(|| stripkit::parallel::Threads::ALL.count()).max(1);
    let thread_counts: Vec<usize> = if threads == 1 { vec![1] } else { vec![1, threads] };
    let levels = if args.quick { 1 } else { 3 };
    let work = std::env::temp_dir().join(format!("stripkit-scale-{}", std::process::id()));
    std::fs::create_dir_all(&work).with_context(|| format!("creating {}", work.display()))?;
    let result = measure(&args, &base, levels, &thread_counts, &work);
    std::fs::remove_dir_all(&work).ok();
    let rows = result?;
    let table = render(&rows, &thread_counts);
    print!("{table}");
    if let Some(path) = &args.table {
        stripkit::io::write_encoded(path, table.as_bytes())?;
    }
    if let Some(path) = &args.json {
        stripkit::io::write_encoded(path, serde_json::to_string_pretty(&rows)?.as_bytes())?;
    }
    let png = plot(&rows, &thread_counts).to_png()?;
    stripkit::io::write_encoded(&args.out, &png).with_context(|| format!("writing {}", args.out.display()))?;
    eprintln!("wrote {}", args.out.display());
    Ok(())
}

/// One row of the table: a mesh file, a phase and a thread count.
struct Job {
    mesh: usize,
    phase: &'static str,
    threads: usize,
    reports: Vec<Report>,
}

/// Writes every mesh of the series first, then runs the rows' rounds interleaved (round
/// 1 of every row, then round 2, ...), so that a machine whose speed drifts during the
/// run shifts every row alike instead of the rows measured at a slow moment.
fn measure(args: &Args, base: &Path, levels: u32, thread_counts: &[usize], work: &Path) -> anyhow::Result<Vec<Row>> {
    let mut meshes: Vec<(String, String, std::path::PathBuf)> = Vec::new();
    let mut jobs: Vec<Job> = Vec::new();
    let mut most_triangles = 0;
    let models = std::iter::once(base).chain(args.held_back.as_deref());
    for (m, path) in models.enumerate() {
        let model = path.file_stem().map_or("model".into(), |s| s.to_string_lossy().into_owned());
        let mut mesh = read_model(path)?;
        for level in 0..=levels {
            if level > 0 {
                mesh = stripkit::gen::subdivide_loop(&mesh, 1).with_context(|| format!("subdividing {model}"))?;
            }
            // The held-back model stops at 1.5x the base's largest mesh.
            if m > 0 && 2 * mesh.triangle_count() > 3 * most_triangles.max(1) {
                break;
            }
            most_triangles = most_triangles.max(mesh.triangle_count());
            let name = format!("{model} {}x", 4usize.pow(level));
            let file = work.join(format!("mesh-{m}-{level}.ply"));
            stripkit::io::write(&file, &mesh, None).with_context(|| format!("writing {}", file.display()))?;
            eprintln!("{name}: {} triangles", mesh.triangle_count());
            let big = mesh.triangle_count() > args.slow_limit;
            for phase in PHASES {
                let asked = args.phases.is_empty() || args.phases.iter().any(|p| p == phase);
                if !asked || (SLOW.contains(phase) && big) {
                    continue;
                }
                // meshoptimizer's calls use one thread whatever the count.
                let counts = if *phase == "meshopt" { &thread_counts[..1] } else { thread_counts };
                for &threads in counts {
                    jobs.push(Job { mesh: meshes.len(), phase, threads, reports: Vec::new() });
                }
            }
            meshes.push((name, model.clone(), file));
        }
    }
    for round in 0..args.rounds.max(1) {
        eprintln!("round {} of {}", round + 1, args.rounds.max(1));
        for job in &mut jobs {
            job.reports.push(run_phase(job.phase, &meshes[job.mesh].2, job.threads, work)?);
        }
    }
    Ok(jobs
        .into_iter()
        .map(|job| {
            let (name, model, _) = &meshes[job.mesh];
            let report = median_report(job.reports);
            eprintln!("  {name} {} x{}: {:.1} ms, {:.0} MB", job.phase, job.threads, report.ns as f64 / 1e6, report.peak_bytes as f64 / 1e6);
            Row { mesh: name.clone(), model: model.clone(), phase: job.phase.to_string(), threads: job.threads, report }
        })
        .collect())
}

fn render(rows: &[Row], thread_counts: &[usize]) -> String {
    let mut s = String::from("# Scale: time and peak memory per triangle\n\n");
    s.push_str(&format!(
        "Each phase in a process of its own, its peak resident size reset before the phase: `before MB` is the \
         resident size then (the program and the phase's inputs), `peak MB` the peak during the phase, inputs \
         included; `bytes/tri` = peak / triangles. \
         Threads: {}. Stripifier times are the stripify call alone (as meshoptimizer's are); their peaks include the \
         front door's verification. `verify` and the writes work on greedy's strips; the writes are the library's \
         checked writes (read back and compared). acmr16 as METRICS.md defines it, by stripkit's figures.\n\n",
        thread_counts.iter().map(|t| t.to_string()).collect::<Vec<_>>().join(" and ")
    ));
    s.push_str("| mesh | triangles | phase | threads | ms | ns/tri | before MB | peak MB | bytes/tri | indices | acmr16 |\n");
    s.push_str("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for r in rows {
        let rep = &r.report;
        s.push_str(&format!(
            "| {} | {} | {} | {} | {:.1} | {:.0} | {:.0} | {:.0} | {:.0} | {} | {} |\n",
            r.mesh,
            rep.triangles,
            if r.phase == "meshopt" { "meshopt vcache + stripify" } else { &r.phase },
            r.threads,
            rep.ns as f64 / 1e6,
            r.ns_per_triangle(),
            rep.rss_before as f64 / 1e6,
            rep.peak_bytes as f64 / 1e6,
            r.bytes_per_triangle(),
            rep.indices.map_or("-".into(), |n| n.to_string()),
            rep.acmr.map_or("-".into(), |a| format!("{a:.4}")),
        ));
    }
    s
}

/// ns per triangle against triangles: one line per model, phase and thread count
/// (dashed at N threads, thinner for the held-back model), meshoptimizer in black.
fn plot(rows: &[Row], thread_counts: &[usize]) -> chart::Canvas {
    let mut colours = Colours::default();
    let mut series: Vec<Series> = Vec::new();
    let mut keys: Vec<(String, String, usize)> = Vec::new();
    for r in rows {
        let key = (r.model.clone(), r.phase.clone(), r.threads);
        let k = match keys.iter().position(|k| *k == key) {
            Some(k) => k,
            None => {
                let parallel = thread_counts.len() > 1 && r.threads != 1;
                let label = match (r.phase.as_str(), parallel) {
                    ("meshopt", _) => format!("{} meshopt vcache+strip", r.model),
                    (p, false) => format!("{} {p} 1t", r.model),
                    (p, true) => format!("{} {p} {}t", r.model, r.threads),
                };
                let colour = if r.phase == "meshopt" { [0, 0, 0] } else { colours.of(&r.phase) };
                keys.push(key);
                // The held-back model's lines are thinner.
                let width = if Some(&r.model) == rows.first().map(|f| &f.model) { 2 } else { 1 };
                series.push(Series { label, colour, dashed: parallel, width, points: Vec::new() });
                series.len() - 1
            }
        };
        series[k].points.push((r.report.triangles as f64, r.ns_per_triangle()));
    }
    chart::log_log(1100, 700, "ns per triangle against triangles (log-log)", "triangles", "ns / triangle", &series).0
}

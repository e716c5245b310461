//! One phase of `stripkit-bench scale`, in a process of its own (the hidden
//! `scale-phase` subcommand): the inputs are prepared, the process's peak resident size
//! is reset (`/proc/self/clear_refs`), the phase runs, and one JSON line reports its
//! time and the peak during it, so that no phase's memory hides another's.

use anyhow::Context;
use std::path::PathBuf;
use std::time::Instant;
use stripkit::parallel::Threads;
use stripkit::{Algorithm, CacheModel, StripOptions};

/// The phases, in table order: read, the stripifiers, verify, the writes, meshoptimizer.
pub const PHASES: &[&str] =
    &["read", "greedy", "cache", "cache-parts", "balanced", "batch", "single", "verify", "write-ply", "write-glb", "meshopt"];

/// Stripifiers that are not O(n log n) (or not near it): measured only on meshes up to
/// `--slow-limit` triangles.
pub const SLOW: &[&str] = &["balanced", "batch", "single"];

/// The partition threshold of the `cache-parts` row: parts of about 262,144 triangles
/// from the 4x mesh on.
pub const PARTS_ABOVE: u32 = 262_144;

/// Arguments of the hidden `scale-phase` subcommand.
#[derive(clap::Args)]
pub struct Args {
    /// The phase (one of [`PHASES`]).
    #[arg(long)]
    pub phase: String,
    /// The mesh, a binary PLY.
    #[arg(long)]
    pub mesh: PathBuf,
    /// Threads the phase may use.
    #[arg(long, default_value_t = 1)]
    pub threads: usize,
    /// A folder for the written files.
    #[arg(long)]
    pub work: PathBuf,
}

/// What a phase reports (one JSON line on standard output).
#[derive(serde::Serialize, serde::Deserialize, Clone, Debug)]
pub struct Report {
    /// Triangles of the mesh.
    pub triangles: usize,
    /// Wall time of the phase, nanoseconds.
    pub ns: u64,
    /// The process's peak resident size during the phase (bytes; its inputs included).
    pub peak_bytes: u64,
    /// Whether the peak was reset before the phase (else it includes the preparation).
    pub peak_reset: bool,
    /// The resident size when the phase started (bytes: the program and the phase's
    /// inputs), so that `peak_bytes - rss_before` is what the phase itself added.
    pub rss_before: u64,
    /// Indices with restarts of the strips (stripifier rows).
    pub indices: Option<usize>,
    /// acmr16 of the strips (stripifier rows).
    pub acmr: Option<f64>,
    /// Bytes of the mesh in memory: 12 per vertex, 12 per triangle.
    pub mesh_bytes: u64,
}

/// The options of a stripifier row, as `stripkit strip --algo NAME` makes them.
pub fn options(phase: &str, threads: Threads) -> Option<StripOptions> {
    let base = StripOptions::default().threads(threads);
    Some(match phase {
        "cache-parts" => base.algorithm(Algorithm::cache()).partition_above(PARTS_ABOVE),
        // The whole-mesh run, whatever the library's default threshold.
        "cache" => base.algorithm(Algorithm::cache()).partition_above(0),
        "greedy" | "balanced" | "batch" | "single" => base.algorithm(phase.parse().ok()?),
        _ => return None,
    })
}

fn status_kb(field: &str) -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with(field))?;
    line[field.len()..].trim().trim_end_matches("kB").trim().parse().ok()
}

/// Resets the peak resident size to the current one (Linux: "5" to clear_refs).
fn reset_peak() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// Runs one phase and prints its [`Report`].
pub fn run(args: Args) -> anyhow::Result<()> {
    let threads = Threads::new(args.threads.max(1));
    let report = threads.install(|| phase(&args, threads))?;
    println!("{}", serde_json::to_string(&report)?);
    Ok(())
}

fn phase(args: &Args, threads: Threads) -> anyhow::Result<Report> {
    let name = args.phase.as_str();
    anyhow::ensure!(PHASES.contains(&name), "unknown phase {name}; one of {}", PHASES.join(", "));
    let read = || stripkit::io::read(&args.mesh).with_context(|| format!("reading {}", args.mesh.display()));
    let (mut indices, mut acmr) = (None, None);
    let rss_before;
    let (ns, peak_reset, mesh) = if name == "read" {
        let reset = reset_peak();
        rss_before = status_kb("VmRSS:").unwrap_or(0) * 1024;
        let t = Instant::now();
        let mesh = read()?;
        (t.elapsed().as_nanos() as u64, reset, mesh)
    } else {
        let mesh = read()?;
        let greedy = options("greedy", threads).expect("greedy is a stripifier");
        let strips = match name {
            "verify" | "write-ply" | "write-glb" => Some(stripkit::stripify(&mesh, &greedy)?),
            _ => None,
        };
        let tris = (name == "meshopt").then(|| mesh.triangulate().tris);
        let reset = reset_peak();
        rss_before = status_kb("VmRSS:").unwrap_or(0) * 1024;
        let t = Instant::now();
        let ns = match name {
            "verify" => {
                let s = strips.as_ref().expect("made above");
                let check = stripkit::verify_with(&s.triangles, &s.strips, threads);
                let ns = t.elapsed().as_nanos() as u64;
                anyhow::ensure!(check.ok(), "verify failed on the greedy strips");
                ns
            }
            "write-ply" | "write-glb" => {
                let path = args.work.join(if name == "write-ply" { "out.ply" } else { "out.glb" });
                let s = strips.as_ref().expect("made above");
                s.write_file(&mesh, &path, &stripkit::io::WriteOptions::default())?;
                let ns = t.elapsed().as_nanos() as u64;
                std::fs::remove_file(&path).ok();
                ns
            }
            "meshopt" => {
                let tris = tris.as_deref().expect("made above");
                let n = mesh.vertex_count();
                let ordered = crate::strips::reorder_cache(tris, n);
                let out = crate::strips::meshopt_stripify(&ordered, n);
                let ns = t.elapsed().as_nanos() as u64;
                let f = stripkit::figures(tris, &out, CacheModel::default());
                anyhow::ensure!(f.verified, "meshoptimizer's strips lost triangles");
                (indices, acmr) = (Some(f.indices_restart), Some(f.acmr16));
                ns
            }
            stripifier => {
                let options = options(stripifier, threads).expect("a stripifier row");
                let s = stripkit::stripify(&mesh, &options)?;
                (indices, acmr) = (Some(s.figures.indices_restart), Some(s.figures.acmr16));
                s.stripify_time.as_nanos() as u64
            }
        };
        (ns, reset, mesh)
    };
    Ok(Report {
        triangles: mesh.triangle_count(),
        ns,
        peak_bytes: status_kb("VmHWM:").unwrap_or(0) * 1024,
        peak_reset,
        rss_before,
        indices,
        acmr,
        mesh_bytes: 12 * (mesh.vertex_count() + mesh.triangle_count()) as u64,
    })
}

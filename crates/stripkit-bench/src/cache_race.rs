//! `cache-race`: stripkit's `cache` stripifier against meshoptimizer's
//! `optimizeVertexCache` + `stripify` on one mesh, the two run in turns on the same
//! input (ours, theirs, ours, theirs, ...) so that both see the same machine load.
//!
//! Our time is the door's stripify time (canonical order, the stripifier and the
//! joins; not the read, nor the door's verification); theirs is the reorder plus the
//! stripify call. `--threads` gives our door threads (the partitioned mode's parts run
//! side by side; meshoptimizer stays on one); `--partition-above` its threshold
//! (default the library's; `0` the whole-mesh run). Figures by stripkit's decoder and metrics (FIFO of 16), both
//! outputs verified against the mesh's triangles. Each time is given as wall and as
//! the process's CPU time (user + system, from `/proc/self/stat` in ticks of 10 ms;
//! both sides run on one thread unless `--threads` says otherwise): on a shared
//! machine the CPU time is the steadier.

use anyhow::Context;
use std::path::PathBuf;
use std::time::Instant;
use stripkit::{Algorithm, CacheModel, StripOptions, Strips};

/// Arguments of the `cache-race` comparison.
#[derive(clap::Args)]
pub struct Args {
    /// The mesh (any format stripkit reads).
    pub mesh: PathBuf,
    /// Turns (each runs ours, then theirs).
    #[arg(long, default_value_t = 3)]
    pub runs: usize,
    /// Threads of our door (meshoptimizer runs on one).
    #[arg(long, default_value_t = 1)]
    pub threads: usize,
    /// Our partition threshold in triangles (`0`: the whole-mesh run).
    #[arg(long, default_value_t = stripkit::DEFAULT_PARTITION_ABOVE)]
    pub partition_above: u32,
}

/// The process's user + system time in seconds (`/proc/self/stat`, USER_HZ = 100),
/// or 0 where that file is not there.
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // Fields after the command name (which may hold spaces, in parentheses).
    let rest = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let f: Vec<f64> = rest.split_whitespace().map(|x| x.parse().unwrap_or(0.0)).collect();
    // utime and stime are fields 14 and 15 of the line, 12 and 13 after the name.
    (f.get(11).unwrap_or(&0.0) + f.get(12).unwrap_or(&0.0)) / 100.0
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Runs the race and prints one line per turn and a summary.
pub fn run(args: Args) -> anyhow::Result<()> {
    let mesh = crate::common::read_surface(&args.mesh).with_context(|| format!("reading {}", args.mesh.display()))?;
    let tris = mesh.triangulate().tris;
    let n = mesh.vertex_count();
    let options = StripOptions::default()
        .algorithm(Algorithm::cache())
        .partition_above(args.partition_above)
        .threads(stripkit::parallel::Threads::new(args.threads.max(1)));
    let (mut ours, mut theirs, mut reorder) = (Vec::new(), Vec::new(), Vec::new());
    let (mut ours_cpu, mut theirs_cpu) = (Vec::new(), Vec::new());
    let (mut ours_fig, mut theirs_fig) = (None, None);
    println!("{}: {} triangles, {} vertices", args.mesh.display(), tris.len(), n);
    for turn in 0..args.runs.max(1) {
        let (c, w) = (cpu_seconds(), Instant::now());
        let s = stripkit::stripify(&mesh, &options)?;
        let door_wall = w.elapsed().as_secs_f64();
        ours.push(s.stripify_time.as_secs_f64());
        // Our CPU time includes the door's checks after the stripifier: the share of
        // the stripifier is taken as its share of the wall time.
        let door_cpu = cpu_seconds() - c;
        let Strips { figures, .. } = s;
        ours_fig = Some(figures);
        ours_cpu.push(door_cpu * ours[turn] / door_wall.max(1e-9));
        let c = cpu_seconds();
        let t = Instant::now();
        let input = crate::strips::reorder_cache(&tris, n);
        let r = t.elapsed().as_secs_f64();
        let strips = crate::strips::meshopt_stripify(&input, n);
        let total = t.elapsed().as_secs_f64();
        theirs_cpu.push(cpu_seconds() - c);
        drop(input);
        reorder.push(r);
        theirs.push(total);
        if theirs_fig.is_none() {
            theirs_fig = Some(stripkit::figures(&tris, &strips, CacheModel::default()));
        }
        println!(
            "turn {}: stripkit cache {:.3} s (cpu ~{:.2}), meshopt vcache + stripify {:.3} s ({:.3} + {:.3}; cpu {:.2})",
            turn + 1,
            ours[turn],
            ours_cpu[turn],
            total,
            r,
            total - r,
            theirs_cpu[turn]
        );
    }
    let (o, t) = (ours_fig.expect("one turn"), theirs_fig.expect("one turn"));
    anyhow::ensure!(o.verified && t.verified, "verification failed: ours {}, theirs {}", o.verified, t.verified);
    let (mo, mt) = (median(ours), median(theirs));
    println!("median: stripkit cache {mo:.3} s, meshopt {mt:.3} s (reorder {:.3} s): ratio {:.2}", median(reorder), mo / mt);
    let (co, ct) = (median(ours_cpu), median(theirs_cpu));
    println!("median cpu: stripkit cache ~{co:.2} s (the door's cpu x the stripifier's share of its wall), meshopt {ct:.2} s: ratio {:.2}", co / ct.max(1e-9));
    println!("stripkit cache: {} indices (restart), acmr16 {:.4}", o.indices_restart, o.acmr16);
    println!("meshopt:        {} indices (restart), acmr16 {:.4}", t.indices_restart, t.acmr16);
    Ok(())
}

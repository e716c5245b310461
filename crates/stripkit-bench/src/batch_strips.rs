//! The `batch-strips` comparison: modelled vertex-shader invocations
//! ([`stripkit::BatchModel::NVIDIA_H100`]) and indices per triangle of stripkit's
//! strip modes next to meshoptimizer's vertex-cache list, on the shared meshes. No
//! GPU needed: the model stands in for one (its fit: docs/experiments/gpu-draw-times.md).

use anyhow::Context;
use std::path::PathBuf;
use stripkit::{Algorithm, BatchModel, StripOptions};

/// Arguments of `batch-strips`.
#[derive(clap::Args)]
pub struct Args {
    /// Folder of meshes.
    #[arg(long, default_value = "../shared/models")]
    pub models: PathBuf,
    /// Mesh files (in `--models`).
    #[arg(default_values_t = ["bunny.obj", "horse.ply", "dragon.obj", "fandisk.obj", "cow.obj", "spot_triangulated.obj", "bunny_small.off"].map(String::from))]
    pub meshes: Vec<String>,
    /// Also sweep the cache mode's FIFO size (3 to 16) and its refinement.
    #[arg(long)]
    pub sweep: bool,
    /// The strip reuse window of the model that measures (and of an extra `batch`
    /// row planned for it); default the H100 model's.
    #[arg(long)]
    pub window: Option<usize>,
    /// The window of the extra `batch` row (default `--window`).
    #[arg(long)]
    pub plan_window: Option<usize>,
    /// The model's window for a strip's first two indices (default `--window`).
    #[arg(long)]
    pub restart_window: Option<usize>,
    /// The extra row's window for a strip's first two indices.
    #[arg(long)]
    pub plan_restart_window: Option<usize>,
}

/// Prints one markdown table: per mesh and row, shaded vertices per triangle under the
/// H100 model and indices per triangle.
pub fn run(args: Args) -> anyhow::Result<()> {
    let window = args.window.unwrap_or(BatchModel::NVIDIA_H100.strip_window);
    let model = BatchModel { strip_window: window, restart_window: args.restart_window.unwrap_or(window), ..BatchModel::NVIDIA_H100 };
    let mut modes: Vec<(String, StripOptions)> = vec![
        ("stripkit cache --cache 8".into(), StripOptions::default().algorithm(Algorithm::cache()).cache_size(8)),
        ("stripkit batch".into(), StripOptions::default().algorithm(Algorithm::batch())),
    ];
    let pw = args.plan_window.unwrap_or(model.strip_window);
    let plan = BatchModel { strip_window: pw, restart_window: args.plan_restart_window.unwrap_or(model.restart_window.min(pw)), ..model };
    if plan != BatchModel::NVIDIA_H100 {
        modes.push((format!("stripkit batch planned for window {} ({} after a restart)", plan.strip_window, plan.restart_window), StripOptions::default().algorithm(Algorithm::Batch(plan))));
    }
    if args.sweep {
        for size in [3, 4, 5, 6, 7, 10, 12, 16] {
            modes.push((format!("stripkit cache --cache {size}"), StripOptions::default().algorithm(Algorithm::cache()).cache_size(size)));
        }
        for size in [6, 8] {
            modes.push((
                format!("stripkit cache --cache {size} --refine"),
                StripOptions::default().algorithm(Algorithm::Cache { refine: true }).cache_size(size),
            ));
        }
    }
    println!("| mesh | triangles | row | shaded / tri | vs list | indices / tri |\n|---|---:|---|---:|---:|---:|");
    for name in &args.meshes {
        let path = args.models.join(name);
        let mesh = crate::common::read_surface(&path).with_context(|| path.display().to_string())?;
        let tris = mesh.triangulate().tris;
        let t = tris.len() as f64;
        let list: Vec<u32> = tris.iter().flatten().copied().collect();
        let vc = meshopt::optimize_vertex_cache(&list, mesh.vertex_count());
        let base = model.list_invocations(&vc) as f64;
        println!("| {name} | {} | meshopt optimizeVertexCache list | {:.4} | | 3.000 |", tris.len(), base / t);
        for (label, opts) in &modes {
            let start = std::time::Instant::now();
            let strips = stripkit::stripify(&mesh, opts).with_context(|| format!("{name}: {label}"))?;
            let secs = start.elapsed().as_secs_f64();
            let buf = strips.restart_buffer();
            let inv = model.strip_invocations(&buf, u32::MAX) as f64;
            println!(
                "| {name} | {} | {label} | {:.4} | {:+.1}% | {:.3} |",
                tris.len(),
                inv / t,
                (inv / base - 1.0) * 100.0,
                buf.len() as f64 / t
            );
            eprintln!("{name}: {label}: {secs:.2} s");
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use stripkit::{gen, Algorithm, BatchModel, StripOptions};

    #[test]
    fn batch_strips_shade_fewer_vertices_than_meshopts_list_on_procedural_meshes() {
        let model = BatchModel::NVIDIA_H100;
        for (name, mesh) in [("icosphere 4", gen::icosphere(4)), ("torus 96x32", gen::torus(96, 32, 2.0, 0.5))] {
            let tris = mesh.triangulate().tris;
            let t = tris.len() as f64;
            let list: Vec<u32> = tris.iter().flatten().copied().collect();
            let vc = meshopt::optimize_vertex_cache(&list, mesh.vertex_count());
            let l = model.list_invocations(&vc) as f64 / t;
            let strips = stripkit::stripify(&mesh, &StripOptions::default().algorithm(Algorithm::batch())).expect("batch");
            assert!(strips.figures.verified);
            let buf = strips.restart_buffer();
            let b = model.strip_invocations(&buf, u32::MAX) as f64 / t;
            eprintln!("{name}: list {l:.4}, batch {b:.4} shaded per triangle, {:.3} indices per triangle", buf.len() as f64 / t);
            assert!(b < l, "{name}: batch {b} against the list's {l}");
            assert!((buf.len() as f64) < 3.0 * t);
        }
    }
}

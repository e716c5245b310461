//! A model of how a GPU batches vertices, fitted to the invocation counts that
//! `stripkit-bench gpu` measures, and the `gpu-model` command that fits it.
//!
//! The model is the library's [`BatchModel`] (its docs give the rule).

use anyhow::Context;
use std::path::PathBuf;
use crate::buffers::{buffers, invocations};
use stripkit_render::Topology;

/// The model itself lives in the library ([`stripkit::BatchModel`], one copy: the
/// `batch` stripifier plans with it).
pub use stripkit::BatchModel;

/// Arguments of `gpu-model`.
#[derive(clap::Args)]
pub struct Args {
    /// JSON written by `stripkit-bench gpu --json` on the GPU to model.
    pub measured: PathBuf,
    /// The folder of meshes that run used.
    #[arg(long, default_value = "../shared/models")]
    pub models: PathBuf,
}

/// Fits the model: for each parameter choice, the mean relative error of the predicted
/// invocations over every probe and every row of every mesh.
pub fn run(args: Args) -> anyhow::Result<()> {
    let text = std::fs::read_to_string(&args.measured).with_context(|| args.measured.display().to_string())?;
    let j: serde_json::Value = serde_json::from_str(&text)?;
    let mut cases: Vec<(String, Topology, Vec<u32>, f64)> = Vec::new();
    for m in j["meshes"].as_array().context("meshes")? {
        let name = m["name"].as_str().context("name")?;
        let path = args.models.join(name);
        let Ok(mesh) = crate::common::read_surface(&path) else {
            eprintln!("skipping {name}: not in {}", args.models.display());
            continue;
        };
        let bufs = buffers(&mesh, true)?;
        for row in m["rows"].as_array().context("rows")? {
            let label = row["label"].as_str().unwrap_or_default();
            let Some(inv) = row["invocations"].as_f64() else { continue };
            if let Some(b) = bufs.iter().find(|b| b.label == label) {
                cases.push((format!("{name}: {label}"), b.topology, b.indices.clone(), inv));
            }
        }
    }
    eprintln!("{} measured buffers", cases.len());
    let mut best = Vec::new();
    for max_triangles in [30, 32, 33] {
        for max_vertices in [32, 48, 64, 96] {
            for (strip_window, strip_fifo) in [8, 12, 14, 15, 16].into_iter().flat_map(|w| [(w, false), (w, true)]) {
                let model = BatchModel { max_triangles, max_vertices, strip_window, strip_fifo, restart_window: strip_window };
                let mut err = 0.0;
                for (_, topo, idx, inv) in &cases {
                    err += ((invocations(&model, idx, *topo) as f64 - inv) / inv).abs();
                }
                best.push((err / cases.len().max(1) as f64, model));
            }
        }
    }
    best.sort_by(|a, b| a.0.total_cmp(&b.0));
    println!("| model | mean relative error |\n|---|---:|");
    for (e, m) in best.iter().take(8) {
        println!("| {m:?} | {:.2}% |", e * 100.0);
    }
    let model = best[0].1;
    println!("\nper buffer, model {model:?}:\n\n| buffer | measured | model |\n|---|---:|---:|");
    for (name, topo, idx, inv) in &cases {
        println!("| {name} | {inv} | {} |", invocations(&model, idx, *topo));
    }
    Ok(())
}

//! A model of how a GPU batches vertices, fitted to the invocation counts that
//! `stripkit-bench gpu` measures, and the `gpu-model` command that fits it.
//!
//! The model (parameters in [`BatchModel`]):
//! - the index stream is cut into batches of at most `max_triangles` primitives and at
//!   most `max_vertices` shaded vertices;
//! - in a triangle list, a vertex is shaded once per batch (any earlier use in the batch
//!   is reused);
//! - in a strip, a vertex is reused only when it occurred within the last `strip_window`
//!   indices of the same batch; a new batch starts with the last two vertices of the
//!   running strip, shaded again.

use anyhow::Context;
use std::path::PathBuf;
use stripkit_render::Topology;

/// Batch limits and the strip reuse window.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BatchModel {
    /// Primitives per batch.
    pub max_triangles: usize,
    /// Shaded vertices per batch.
    pub max_vertices: usize,
    /// How far back a strip vertex can be reused: in indices, or in shaded vertices
    /// when `strip_fifo`.
    pub strip_window: usize,
    /// The strip window holds the last `strip_window` shaded vertices (a FIFO), not the
    /// last indices.
    pub strip_fifo: bool,
}

impl BatchModel {
    /// The model fitted to an NVIDIA H100 (driver 580.159.04) by `gpu-model`: batches of
    /// 30 triangles and 32 shaded vertices, strips reusing the last 15 shaded vertices
    /// (0.82% mean error over the 176 index buffers of the shared models).
    pub const NVIDIA_H100: BatchModel = BatchModel { max_triangles: 30, max_vertices: 32, strip_window: 15, strip_fifo: true };

    /// Vertex-shader invocations the model predicts for one draw.
    pub fn invocations(&self, indices: &[u32], topology: Topology) -> u64 {
        match topology {
            Topology::Triangles => self.list(indices),
            Topology::Strip => self.strip(indices),
        }
    }

    fn list(&self, indices: &[u32]) -> u64 {
        let mut total = 0u64;
        let mut batch: Vec<u32> = Vec::with_capacity(self.max_vertices);
        let mut tris = 0;
        for t in indices.chunks_exact(3) {
            let new = t.iter().enumerate().filter(|&(k, v)| !batch.contains(v) && !t[..k].contains(v)).count();
            if tris == self.max_triangles || batch.len() + new > self.max_vertices {
                batch.clear();
                tris = 0;
            }
            for (k, &v) in t.iter().enumerate() {
                if !batch.contains(&v) && !t[..k].contains(&v) {
                    batch.push(v);
                    total += 1;
                }
            }
            tris += 1;
        }
        total
    }

    fn strip(&self, indices: &[u32]) -> u64 {
        let mut total = 0u64;
        // The batch's index history (for the window) and its counts.
        let mut hist: Vec<u32> = Vec::new();
        let mut shaded = 0;
        let mut tris = 0;
        let mut run = 0; // indices of the running strip
        let mut last2 = [u32::MAX; 2];
        for &i in indices {
            if i == u32::MAX {
                run = 0;
                continue;
            }
            let reused = hist.iter().rev().take(self.strip_window).any(|&h| h == i);
            let makes_tri = run >= 2;
            if (makes_tri && tris == self.max_triangles) || (!reused && shaded == self.max_vertices) {
                // New batch: the running strip's last two vertices come again, shaded.
                hist.clear();
                shaded = 0;
                tris = 0;
                if run >= 2 {
                    for v in last2 {
                        hist.push(v);
                        shaded += 1;
                        total += 1;
                    }
                }
                let reused = hist.iter().rev().take(self.strip_window).any(|&h| h == i);
                if !reused {
                    shaded += 1;
                    total += 1;
                }
            } else if !reused {
                shaded += 1;
                total += 1;
            }
            if !self.strip_fifo || !reused {
                hist.push(i);
            }
            if makes_tri {
                tris += 1;
            }
            last2 = [last2[1], i];
            run += 1;
        }
        total
    }
}

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
        let Ok(mesh) = stripkit::io::read(&path) else {
            eprintln!("skipping {name}: not in {}", args.models.display());
            continue;
        };
        let bufs = crate::gpu::buffers(&mesh)?;
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
                let model = BatchModel { max_triangles, max_vertices, strip_window, strip_fifo };
                let mut err = 0.0;
                for (_, topo, idx, inv) in &cases {
                    err += ((model.invocations(idx, *topo) as f64 - inv) / inv).abs();
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
        println!("| {name} | {inv} | {} |", model.invocations(idx, *topo));
    }
    Ok(())
}

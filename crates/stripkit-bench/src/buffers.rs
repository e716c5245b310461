//! The index buffers the GPU comparisons draw (`gpu`, `gpu-model`), and what the batch
//! model predicts for them: shared by `gpu.rs` and `batch.rs`, which import it
//! downward instead of each other.

use anyhow::Context;
use stripkit::{Algorithm, BatchModel, StripOptions};
use stripkit_render::Topology;

/// One index buffer to draw: strips use `u32::MAX` as restart.
pub struct Buffer {
    /// Row label.
    pub label: String,
    /// Triangles or strips.
    pub topology: Topology,
    /// The indices.
    pub indices: Vec<u32>,
}

/// Vertex-shader invocations `model` predicts for one draw.
pub fn invocations(model: &BatchModel, indices: &[u32], topology: Topology) -> u64 {
    match topology {
        Topology::Triangles => model.list_invocations(indices),
        Topology::Strip => model.strip_invocations(indices, u32::MAX),
    }
}

/// Every index buffer of the comparison for one mesh, each checked against its triangles.
/// `variants` adds the rows that explore settings (batch windows, cache sizes 32 and
/// 64) next to the modes a user would pick. stripkit's modes run on parallel threads.
pub fn buffers(mesh: &stripkit::Mesh, variants: bool) -> anyhow::Result<Vec<Buffer>> {
    let tris = mesh.triangulate().tris;
    let n = mesh.vertex_count();
    let list = tris.as_flattened().to_vec();
    let vc = meshopt::optimize_vertex_cache(&list, n);
    let vcs = meshopt::optimize_vertex_cache_strip(&list, n);
    let mo_strip = |l: &[u32]| meshopt::stripify(l, n, u32::MAX).map_err(|e| anyhow::anyhow!("meshopt stripify: {e:?}"));
    let mut out = vec![
        Buffer { label: "input triangle list".into(), topology: Topology::Triangles, indices: list.clone() },
        Buffer { label: "meshopt optimizeVertexCache list".into(), topology: Topology::Triangles, indices: vc.clone() },
        Buffer { label: "meshopt vc + stripify".into(), topology: Topology::Strip, indices: mo_strip(&vc)? },
        Buffer { label: "meshopt optimizeVertexCacheStrip + stripify".into(), topology: Topology::Strip, indices: mo_strip(&vcs)? },
    ];
    let mut modes: Vec<(String, StripOptions)> = vec![
        ("stripkit greedy".into(), StripOptions::default().algorithm(Algorithm::greedy())),
        ("stripkit cache".into(), StripOptions::default().algorithm(Algorithm::cache())),
        ("stripkit balanced".into(), StripOptions::default().algorithm(Algorithm::balanced(0.8))),
        ("stripkit batch".into(), StripOptions::default().algorithm(Algorithm::batch())),
    ];
    modes.push(("stripkit cache --cache 8".into(), StripOptions::default().algorithm(Algorithm::cache()).cache_size(8)));
    // The batch stripifier planned for neighbouring reuse windows: where the model's
    // window is right, one of these shades fewer vertices than the other.
    for window in [13, 14, 15].into_iter().filter(|_| variants) {
        let model = stripkit::BatchModel { strip_window: window, restart_window: window, ..stripkit::BatchModel::NVIDIA_H100 };
        modes.push((format!("stripkit batch, window {window}"), StripOptions::default().algorithm(Algorithm::Batch(model))));
    }
    // Planned for a shorter window at the start of a strip (the variant of the model
    // that fits the H200's counts best: 16 and 11; the default plans for 14 and 10).
    if variants {
        let model = stripkit::BatchModel { strip_window: 16, restart_window: 11, ..stripkit::BatchModel::NVIDIA_H100 };
        modes.push(("stripkit batch, window 16, 11 after a restart".into(), StripOptions::default().algorithm(Algorithm::Batch(model))));
    }
    for size in [32, 64].into_iter().filter(|_| variants) {
        modes.push((format!("stripkit cache --cache {size}"), StripOptions::default().algorithm(Algorithm::cache()).cache_size(size)));
    }
    if stripkit::is_quad_dominant(mesh) {
        modes.push(("stripkit qstrip".into(), StripOptions::default().algorithm(Algorithm::qstrip())));
    }
    let strips: Vec<anyhow::Result<Vec<u32>>> = std::thread::scope(|scope| {
        let handles: Vec<_> = modes
            .iter()
            .map(|(label, opts)| {
                scope.spawn(move || {
                    stripkit::stripify(mesh, opts).map(|s| s.restart_buffer()).with_context(|| label.clone())
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap_or_else(|_| Err(anyhow::anyhow!("stripifier thread panicked")))).collect()
    });
    for ((label, _), indices) in modes.into_iter().zip(strips) {
        out.push(Buffer { label, topology: Topology::Strip, indices: indices? });
    }
    // stripkit's rows are verified by the door (QSTRIP against its own diagonals); the
    // peers' rows are checked here.
    for b in out.iter().take(4) {
        let decoded = match b.topology {
            Topology::Triangles => b.indices.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
            Topology::Strip => stripkit::decode(&stripkit::decode_restart(&b.indices, u32::MAX)),
        };
        let v = stripkit::verify_triangles(&tris, &decoded);
        if !v.ok() {
            eprintln!("warning: {}: {} lost, {} added, {} flipped", b.label, v.lost, v.added, v.flipped);
        }
    }
    Ok(out)
}

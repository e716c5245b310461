//! Variants of the batch model's strip rule scored against measured invocation counts
//! (`cargo test --release -p stripkit-bench restart_variants -- --ignored --nocapture`):
//! a restart taking window entries, a shorter window for a strip's first two indices,
//! a window in indices. Findings in docs/experiments/gpu-batch-strips.md.
#[cfg(test)]
mod tests {
    use crate::buffers::invocations;
    use stripkit::BatchModel;
    use stripkit_render::Topology;

    /// The strip rule with a restart occupying `r` window entries and a first-two
    /// window of `w0` after a restart.
    fn strip(indices: &[u32], window: usize, r: usize, w0: usize, push_all: bool) -> u64 {
        let (max_t, max_v) = (30, 32);
        let mut total = 0u64;
        let mut hist: Vec<u32> = Vec::new();
        let (mut shaded, mut tris, mut run) = (0, 0, 0);
        let mut last2 = [u32::MAX; 2];
        for &i in indices {
            if i == u32::MAX {
                run = 0;
                for _ in 0..r {
                    hist.push(u32::MAX - 1);
                }
                continue;
            }
            let w = if run < 2 { w0 } else { window };
            let reused_in = |hist: &Vec<u32>| hist.iter().rev().take(w).any(|&h| h == i);
            let before = reused_in(&hist);
            let mut reused = before;
            let makes_tri = run >= 2;
            if (makes_tri && tris == max_t) || (!reused && shaded == max_v) {
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
                reused = reused_in(&hist);
            }
            if !reused {
                shaded += 1;
                total += 1;
            }
            if push_all || !before {
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

    #[test]
    #[ignore = "scratch: needs docs/experiments/gpu/h200-batch-strips.json and the shared models"]
    fn restart_variants() {
        let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/experiments/gpu/h200-batch-strips.json")).unwrap();
        let j: serde_json::Value = serde_json::from_str(&text).unwrap();
        let mut cases = Vec::new();
        for m in j["meshes"].as_array().unwrap() {
            let name = m["name"].as_str().unwrap();
            let Some(dir) = crate::common::models_dir() else { return };
            let mesh = crate::common::read_surface(&dir.join(name)).unwrap();
            let bufs = crate::buffers::buffers(&mesh, true).unwrap();
            for row in m["rows"].as_array().unwrap() {
                let label = row["label"].as_str().unwrap_or_default();
                let Some(inv) = row["invocations"].as_f64() else { continue };
                if let Some(b) = bufs.iter().find(|b| b.label == label) {
                    cases.push((format!("{name}: {label}"), b.topology, b.indices.clone(), inv));
                }
            }
        }
        let base = BatchModel::NVIDIA_H100;
        let mut rows = Vec::new();
        let mut grid = Vec::new();
        for window in [13, 14, 15, 16, 17, 18] {
            for r in [0, 1, 2] {
                for w0 in [8, 9, 10, 11, 12, 13, 14, 15, 16] {
                    if w0 <= window { grid.push((window, r, w0, false)); }
                }
            }
        }
        for window in [16, 18, 20, 22, 24, 26, 28, 32] {
            for r in [0, 1, 2] {
                for w0 in [8, 10, 12, 14, 16, 20, 24, 28, 32] {
                    if w0 <= window { grid.push((window, r, w0, true)); }
                }
            }
        }
        for (window, r, w0, push_all) in grid {
                {
                    let (mut e_all, mut e_batch, mut nb) = (0.0, 0.0, 0);
                    for (name, topo, idx, inv) in &cases {
                        let p = match topo {
                            Topology::Triangles => invocations(&base, idx, *topo) as f64,
                            Topology::Strip => strip(idx, window, r, w0, push_all) as f64,
                        };
                        let e = ((p - inv) / inv).abs();
                        e_all += e;
                        if name.contains("batch") {
                            e_batch += e;
                            nb += 1;
                        }
                    }
                    rows.push((e_all / cases.len() as f64, e_batch / nb as f64, window, r, w0, push_all));
                }
        }
        rows.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (a, b, w, r, w0, pa) in rows.iter().take(15) {
            println!("window {w} restart-slots {r} first-two-window {w0} index-window {pa}: all {:.2}% batch rows {:.2}%", a * 100.0, b * 100.0);
        }
    }
}

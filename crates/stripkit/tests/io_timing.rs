//! Reader timings (not a test of speed: it only prints). Run with
//! `cargo test --release -p stripkit --test io_timing -- --ignored --nocapture`.

mod support;

use std::path::{Path, PathBuf};
use std::time::Instant;
use stripkit::io;
use stripkit::Mesh;

/// Median wall time of five reads, in milliseconds, and the mesh read.
fn median_read_ms(path: &Path) -> (f64, Mesh) {
    let mut times = Vec::new();
    let mut mesh = Mesh::new();
    for _ in 0..5 {
        let t = Instant::now();
        mesh = io::read(path).unwrap();
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    (times[2], mesh)
}

/// A `n x n` grid of vertices with perturbed, non-round coordinates: 2 (n-1)^2 triangles.
fn grid(n: u32) -> Mesh {
    let mut positions = Vec::with_capacity((n * n) as usize);
    for y in 0..n {
        for x in 0..n {
            let h = ((x as f32 * 0.37).sin() * (y as f32 * 0.21).cos()) * 3.3;
            positions.push([x as f32 * 0.0137 - 5.0, y as f32 * 0.0119 + 0.3, h]);
        }
    }
    let mut tris = Vec::with_capacity(2 * ((n - 1) * (n - 1)) as usize);
    for y in 0..n - 1 {
        for x in 0..n - 1 {
            let v = y * n + x;
            tris.push([v, v + 1, v + n + 1]);
            tris.push([v, v + n + 1, v + n]);
        }
    }
    Mesh::from_triangles(positions, &tris)
}

#[test]
#[ignore]
fn print_read_times() {
    let mut files: Vec<PathBuf> = Vec::new();
    if let Some(dir) = support::models_dir() {
        for name in ["bunny.obj", "horse.ply", "dragon.obj", "bunny_res2.ply", "cow_tristrips.ply"] {
            files.push(dir.join(name));
        }
        files.push(dir.join("sequences/horse-gallop/horse-gallop-01.obj.gz"));
    }
    let tmp = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let big = grid(708); // 707^2 * 2 = 999,698 triangles, 501,264 vertices
    for name in ["grid1m.obj", "grid1m.ply", "grid1m.off", "grid1m.stl", "grid1m.glb"] {
        let path = tmp.join(name);
        let t = Instant::now();
        io::write(&path, &big, None).unwrap();
        println!("write {name}: {:.1} ms", t.elapsed().as_secs_f64() * 1e3);
        files.push(path);
    }
    // STRIPKIT_TIMING_FILTER=obj times only files whose name contains "obj".
    let filter = std::env::var("STRIPKIT_TIMING_FILTER").unwrap_or_default();
    for path in files.into_iter().filter(|p| p.to_string_lossy().contains(filter.as_str())) {
        let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        let (ms, mesh) = median_read_ms(&path);
        println!(
            "read {}: {} V, {} F, {:.1} MB: median of 5 {:.1} ms",
            path.file_name().unwrap().to_string_lossy(),
            mesh.vertex_count(),
            mesh.face_count(),
            size as f64 / 1e6,
            ms
        );
    }
}

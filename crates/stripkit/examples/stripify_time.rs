//! Times the library's two doors on one mesh, for the Python binding's overhead
//! figure (crates/stripkit-py/bench/overhead.py runs this and the same calls from
//! Python in one run): `stripify` on the mesh as read and `stripify_indices` on its
//! triangles, each the median of `runs` calls, in milliseconds, one JSON line.
//!
//! `cargo run --release -p stripkit --example stripify_time -- MESH [RUNS]`

use std::time::Instant;
use stripkit::{io, stripify, stripify_indices, StripOptions};

fn median_ms(runs: usize, mut f: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..runs)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

fn main() -> stripkit::Result<()> {
    let mut args = std::env::args().skip(1);
    let path = args.next().ok_or_else(|| stripkit::Error::Invalid("usage: stripify_time MESH [RUNS]".into()))?;
    let runs = args.next().and_then(|r| r.parse().ok()).unwrap_or(15).max(1);
    let mesh = io::read(&path)?;
    let options = StripOptions::default();
    let flat: Vec<u32> = mesh.triangulate().tris.into_iter().flatten().collect();
    let vertex_count = mesh.vertex_count();
    let mesh_ms = median_ms(runs, || {
        stripify(&mesh, &options).expect("the mesh strips");
    });
    let indices_ms = median_ms(runs, || {
        stripify_indices(&flat, vertex_count, &options).expect("the triangles strip");
    });
    println!("{{\"stripify_mesh_ms\": {mesh_ms:.4}, \"stripify_indices_ms\": {indices_ms:.4}, \"runs\": {runs}}}");
    Ok(())
}

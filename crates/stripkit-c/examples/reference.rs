//! The Rust library's side of the C examples' checks (scripts/test) and timing
//! (docs/experiments/c-api.md): the same OBJ, the same calls, the same printout.
//!
//! ```text
//! cargo run -p stripkit-c --example reference -- [--mesh] [--algorithm N] [--join N] [--time RUNS] mesh.obj
//! ```
//!
//! Prints one strip index per line, then `added X Y Z A B` for each vertex `single`
//! added (position bits in hex, the edge it splits), as examples/c/strip_obj.c does;
//! `--time RUNS` prints the median time of `stripify_indices` instead.

use libstripkit::{io, stripify, stripify_indices, Algorithm, Join, Mesh, StripOptions};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (mut mesh_level, mut runs, mut path) = (false, 0usize, None);
    let mut options = StripOptions::default();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--mesh" => mesh_level = true,
            "--algorithm" => {
                let n: usize = args.next().ok_or("--algorithm needs a number")?.parse()?;
                options = options.algorithm(Algorithm::NAMES.get(n).ok_or("unknown algorithm")?.parse::<Algorithm>()?);
            }
            "--join" => {
                let join = match args.next().as_deref() {
                    Some("0") => Join::Restart,
                    Some("1") => Join::Degenerate,
                    _ => return Err("--join takes 0 or 1".into()),
                };
                options = options.join(join);
            }
            "--time" => runs = args.next().ok_or("--time needs a number")?.parse()?,
            _ => path = Some(arg),
        }
    }
    let path = path.ok_or("usage: reference [--mesh] [--algorithm N] [--join N] [--time RUNS] mesh.obj")?;
    // Vertex ids are then the file's `v` records, as the C example reads them.
    let mesh = io::read_with(path, &io::ReadOptions::default().positions_only(true))?;
    let tris = mesh.triangulate().tris;
    let flat: Vec<u32> = tris.iter().flatten().copied().collect();
    if runs > 0 {
        let mut times = Vec::with_capacity(runs);
        let mut written = 0;
        for _ in 0..runs {
            let start = Instant::now();
            written = stripify_indices(&flat, mesh.vertex_count(), &options)?.len();
            times.push(start.elapsed().as_secs_f64() * 1e3);
        }
        times.sort_by(f64::total_cmp);
        println!(
            "rust {} triangles: median {:.3} ms over {runs} runs ({written} indices)",
            tris.len(),
            times[runs / 2]
        );
        return Ok(());
    }
    let mut out = String::new();
    if mesh_level {
        // What a C caller gives stripkit_stripify_mesh: positions and triangles only.
        let strips = stripify(&Mesh::from_triangles(mesh.positions.clone(), &tris), &options)?;
        let buffer = if strips.join == Join::Degenerate { strips.stitched() } else { strips.restart_buffer() };
        for i in buffer {
            out.push_str(&format!("{i}\n"));
        }
        for (p, [a, b]) in strips.added_positions.iter().zip(&strips.added_from) {
            let [x, y, z] = p.map(f32::to_bits);
            out.push_str(&format!("added {x:08x} {y:08x} {z:08x} {a} {b}\n"));
        }
    } else {
        for i in stripify_indices(&flat, mesh.vertex_count(), &options)? {
            out.push_str(&format!("{i}\n"));
        }
    }
    print!("{out}");
    Ok(())
}

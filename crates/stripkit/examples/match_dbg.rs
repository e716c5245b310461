//! Timing helper: `match_dbg ico LEVEL` or `match_dbg MESH SUBDIV [two]`.
use std::time::Instant;
use stripkit::matching::{self, DualWeights, Graph};
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let mesh = if a[1] == "ico" {
        stripkit::gen::icosphere(a[2].parse().unwrap())
    } else {
        let m = stripkit::mesh::io::read(std::path::Path::new(&a[1])).unwrap();
        stripkit::gen::subdivide_loop(&m, a[2].parse().unwrap()).unwrap()
    };
    let mut g = matching::mesh_dual_graph(&mesh, DualWeights::Random { seed: 1 }).unwrap();
    if a.len() > 3 {
        let pert = a.len() > 4;
        let k = (g.node_count() as i64 / 2 + 1) * 1024;
        let w: Vec<i64> = g.weights().iter().enumerate().map(|(i, &w)| {
            let base = 1 + (w & 1);
            if pert { base * k + ((i as u64).wrapping_mul(0x9E3779B97F4A7C15) >> 54) as i64 } else { base }
        }).collect();
        g = Graph::new(g.node_count(), g.edges().to_vec(), w).unwrap();
    }
    let t = Instant::now();
    let m = matching::max_weight_perfect_matching(&g).unwrap();
    println!("n {} perfect {} w {} {:?} {:?}", g.node_count(), m.perfect, m.total_weight, m.stats, t.elapsed());
}

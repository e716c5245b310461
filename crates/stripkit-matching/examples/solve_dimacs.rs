//! Solves DIMACS-style graph files and prints the time, weight and work counters:
//! `cargo run --release -p stripkit-matching --example solve_dimacs -- FILE...`.
use std::time::Instant;
use stripkit_matching::{solve, Graph, Objective};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    for arg in std::env::args().skip(1) {
        let g = Graph::read_dimacs(arg.as_ref())?;
        let t = Instant::now();
        let m = solve(&g, Objective::MaxWeight)?;
        let s = t.elapsed().as_secs_f64();
        println!("{arg}: {s:.2} s, weight {}, perfect {}, certified {}, {:?}", m.total_weight, m.perfect, m.certified, m.stats);
    }
    Ok(())
}

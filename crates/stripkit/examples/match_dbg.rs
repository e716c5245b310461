use std::time::Instant;
use stripkit::matching::{self, DualWeights, Graph, UNMATCHED};
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let mesh = stripkit::mesh::io::read(std::path::Path::new(&path)).unwrap();
    let g = matching::mesh_dual_graph(&mesh, DualWeights::Random { seed: 1 }).unwrap();
    let t = Instant::now();
    let mate = matching::unweighted::maximum_cardinality_matching(&g);
    let card = mate.iter().filter(|&&x| x != UNMATCHED).count();
    println!("n {} card {} k {} unweighted {:?}", g.node_count(), card, g.node_count() - card, t.elapsed());
    let _ = Graph::default();
    let t = Instant::now();
    let m = matching::max_weight_perfect_matching(&g).unwrap();
    println!("{:?} {:?}", m.stats, t.elapsed());
}

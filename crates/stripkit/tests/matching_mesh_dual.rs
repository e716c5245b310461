//! The matching solver on mesh dual graphs built by `stripkit::matching::mesh_dual_graph`
//! (shuffled icospheres, all three weightings): perfect, certified, and agreeing with
//! the unweighted matcher. Moved from stripkit-matching's matching_medium.rs, which
//! has no meshes.

use stripkit::matching::{self, DualWeights, Graph, Objective, UNMATCHED};

/// Solves; the matching must be perfect (every triangle matched once) and its
/// certificate must check again from scratch. The full checks of a matching's weight and
/// cardinality live with the solver's own tests in stripkit-matching.
fn check(g: &Graph, obj: Objective) -> matching::Matching {
    let m = matching::solve(g, obj).unwrap();
    assert!(m.certified && m.perfect);
    let mut seen = vec![0u8; g.node_count()];
    for &e in &m.edges {
        g.edges()[e as usize].iter().for_each(|&v| seen[v as usize] += 1);
    }
    assert!(seen.iter().all(|&s| s == 1));
    let report = matching::verify(g, obj, &m.edges, m.certificate.as_ref().unwrap()).unwrap();
    assert_eq!(report.primal, report.dual);
    m
}

#[test]
fn mesh_dual_graphs_have_certified_perfect_matchings() {
    for level in 0..4 {
        let mesh = stripkit::gen::shuffle_faces(&stripkit::gen::icosphere(level), 9 + level as u64);
        for w in [DualWeights::Uniform, DualWeights::Random { seed: 3 }, DualWeights::NormalAngle] {
            let g = matching::mesh_dual_graph(&mesh, w).unwrap();
            assert_eq!(g.node_count(), 20 << (2 * level));
            assert_eq!(g.edge_count(), 30 << (2 * level));
            let m = check(&g, Objective::MaxWeight);
            assert!(m.perfect);
            if w == DualWeights::Uniform {
                assert_eq!(m.total_weight, (10 << (2 * level)) as i64);
            }
            let u = matching::unweighted_perfect_matching(&g).unwrap();
            assert!(u.iter().all(|&x| x != UNMATCHED));
        }
    }
}

#[test]
fn dual_weights_default_to_random_with_seed_one() {
    assert_eq!(DualWeights::default(), DualWeights::Random { seed: 1 });
    assert_eq!("random".parse::<DualWeights>().unwrap(), DualWeights::default());
}

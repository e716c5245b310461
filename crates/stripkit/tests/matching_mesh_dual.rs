//! The matching solver on mesh dual graphs built by `stripkit::matching::mesh_dual_graph`
//! (shuffled icospheres, all three weightings): perfect, certified, and agreeing with
//! the unweighted matcher. Moved from stripkit-matching's matching_medium.rs, which
//! has no meshes.

use stripkit::matching::{self, DualWeights, Graph, Objective, UNMATCHED};

/// Solves, then checks the matching, its weight, its certificate and its cardinality.
fn check(g: &Graph, obj: Objective) -> matching::Matching {
    let m = matching::solve(g, obj).unwrap();
    assert!(m.certified);
    let mut seen = vec![false; g.node_count()];
    let mut sum = 0;
    for &e in &m.edges {
        let [a, b] = g.edges()[e as usize];
        assert!(a != b && !seen[a as usize] && !seen[b as usize]);
        seen[a as usize] = true;
        seen[b as usize] = true;
        sum += g.weights()[e as usize];
    }
    assert_eq!(sum, m.total_weight);
    if m.perfect {
        assert!(seen.iter().all(|&s| s));
        let report = matching::verify(g, obj, &m.edges, m.certificate.as_ref().unwrap()).unwrap();
        assert_eq!(report.primal, report.dual);
        assert_eq!(report.primal, 2 * m.total_weight as i128 * if obj == Objective::MaxWeight { 1 } else { -1 });
    }
    let mate = matching::maximum_cardinality_matching(g);
    let card = mate.iter().filter(|&&x| x != UNMATCHED).count();
    assert_eq!(card, 2 * m.edges.len());
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

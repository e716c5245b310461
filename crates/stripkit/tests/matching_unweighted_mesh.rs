//! The unweighted matcher on mesh dual graphs (3-regular, large blossoms): it must
//! finish and agree with the weighted solver's cardinality.

mod support;

use stripkit::matching::{self, DualWeights};

#[test]
fn unweighted_matches_weighted_cardinality_on_icosphere_duals() {
    for level in 0..5 {
        let mesh = stripkit::gen::icosphere(level);
        let g = matching::mesh_dual_graph(&mesh, DualWeights::Random { seed: 3 }).unwrap();
        let mate = matching::maximum_cardinality_matching(&g);
        let card = mate.iter().filter(|&&x| x != matching::UNMATCHED).count();
        let m = matching::solve(&g, matching::Objective::MaxWeight).unwrap();
        assert!(m.certified);
        assert_eq!(card, 2 * m.edges.len(), "level {level}");
    }
}

#[test]
fn unweighted_bunny_dual_reaches_the_odd_component_bound() {
    let Some(dir) = support::models_dir() else {
        eprintln!("skipped: ../shared/models not found");
        return;
    };
    let mesh = stripkit::io::read(dir.join("bunny.obj")).unwrap();
    let g = matching::mesh_dual_graph(&mesh, DualWeights::Uniform).unwrap();
    let mate = matching::maximum_cardinality_matching(&g);
    let exposed = mate.iter().filter(|&&x| x == matching::UNMATCHED).count();
    assert_eq!(exposed, 1);
    let m = matching::solve(&g, matching::Objective::MaxWeight).unwrap();
    assert!(m.certified && !m.perfect);
    assert_eq!(2 * m.edges.len(), g.node_count() - 1);
}

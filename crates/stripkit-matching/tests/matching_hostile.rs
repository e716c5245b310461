//! Hostile graphs for the matching (issue #30, classes 2 and 3): a star, whose
//! uniform-weight fallback once built a gadget of leaves x nodes edges (2 GiB at
//! 20,000 leaves), and a path with weights `i mod 7`, all ties. Correctness only: each
//! result solved, certified and of the known weight (growth figures:
//! docs/experiments/reliability.md, "The matching on stars and tie-heavy paths").

use stripkit_matching::{solve, Graph, Objective, UNMATCHED};

/// Node 0 joined to `leaves` leaves, every weight `w`.
fn star(leaves: u32, w: i64) -> Graph {
    let edges: Vec<[u32; 2]> = (1..=leaves).map(|v| [0, v]).collect();
    Graph::new(leaves as usize + 1, edges, vec![w; leaves as usize]).unwrap()
}

#[test]
fn uniform_star_is_certified_without_the_quadratic_gadget() {
    for obj in [Objective::MaxWeight, Objective::MinCost] {
        let m = solve(&star(5000, 1), obj).unwrap();
        assert!(!m.perfect && m.certified);
        assert_eq!((m.edges.len(), m.total_weight), (1, 1));
        assert_eq!(m.mate.iter().filter(|&&x| x != UNMATCHED).count(), 2);
        // The unweighted matcher decided and its certificate was checked on the
        // k-dummy gadget without building it: the weighted engine, whose hub rescans
        // cost leaves^2 in time and heap, never ran.
        assert_eq!(m.stats.events, 0, "{obj:?}: the weighted engine ran");
    }
}

#[test]
fn tied_star_is_solved_with_linear_work() {
    // One heavier leaf: not uniform, so the weighted engine runs (on the doubled
    // graph). Its hub was freed after every augmentation and rescanned its 3,000 edges.
    let mut ws = vec![1i64; 3000];
    ws[2999] = 2;
    let edges: Vec<[u32; 2]> = (1..=3000).map(|v| [0, v]).collect();
    let g = Graph::new(3001, edges, ws).unwrap();
    let m = solve(&g, Objective::MaxWeight).unwrap();
    assert!(!m.perfect && m.certified);
    assert_eq!((m.edges.clone(), m.total_weight), (vec![2999], 2));
    assert!(m.stats.events < 10 * 3001, "{} events", m.stats.events);
}

#[test]
fn uniform_star_with_a_tail_keeps_maximum_cardinality() {
    // Leaves 1..=300 on the hub 0, and a path 0 - 301 - 302 - 303: two edges at
    // most through the hub's side (hub-leaf or hub-301, then 302-303).
    let mut edges: Vec<[u32; 2]> = (1..=300).map(|v| [0, v]).collect();
    edges.extend([[0, 301], [301, 302], [302, 303]]);
    let g = Graph::new(304, edges.clone(), vec![4; edges.len()]).unwrap();
    let m = solve(&g, Objective::MaxWeight).unwrap();
    assert!(!m.perfect && m.certified);
    assert_eq!((m.edges.len(), m.total_weight), (2, 8));
}

#[test]
fn path_with_weights_mod_7_is_solved_and_certified() {
    // A path of n nodes has one perfect matching, the edges 0, 2, 4, ...
    for n in [2000u32, 2001] {
        let edges: Vec<[u32; 2]> = (0..n - 1).map(|i| [i, i + 1]).collect();
        let ws: Vec<i64> = (0..n as i64 - 1).map(|i| i % 7).collect();
        let g = Graph::new(n as usize, edges, ws.clone()).unwrap();
        let m = solve(&g, Objective::MaxWeight).unwrap();
        assert!(m.certified);
        if n % 2 == 0 {
            assert!(m.perfect);
            let want: i64 = ws.iter().step_by(2).sum();
            assert_eq!(m.total_weight, want);
            assert_eq!(m.edges, (0..n - 1).step_by(2).collect::<Vec<u32>>());
        } else {
            assert!(!m.perfect);
            assert_eq!(m.edges.len() as u32, (n - 1) / 2);
        }
        // Work linear in the path: the engine once let one tree sweep the region freed
        // by earlier augmentations again and again (n^2 / 56 events; 1,428
        // augmentations labelled 14 million nodes at n = 20,000).
        assert!(m.stats.events < 10 * n as usize, "n {n}: {} events", m.stats.events);
        let c = solve(&g, Objective::MinCost).unwrap();
        assert!(c.certified);
        if n % 2 == 0 {
            assert_eq!(c.edges, m.edges);
        }
    }
}

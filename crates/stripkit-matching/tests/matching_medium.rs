//! The weighted engine on graphs of a few hundred to a few thousand nodes: against a
//! dense O(n^3) Hungarian reference on bipartite graphs, for consistency between the
//! objectives and with the unweighted matcher elsewhere, and on disconnected graphs
//! (mesh dual graphs: stripkit's tests/matching_mesh_dual.rs). Every solve checks its
//! certificate; tests check it again.

use stripkit_matching::{self as matching, Graph, Objective, UNMATCHED};

use stripkit_testkit::XorShift64Star as Rng;

/// Dense Hungarian algorithm (shortest augmenting paths with potentials), O(n^3):
/// maximum-weight perfect assignment of `w[i][j]`; `None` entries are missing edges.
/// Returns the best total, or None when no perfect assignment exists.
fn hungarian(w: &[Vec<Option<i64>>]) -> Option<i64> {
    let n = w.len();
    const BIG: i64 = 1 << 40;
    // Minimise cost = -w; missing edges cost BIG.
    let cost = |i: usize, j: usize| w[i][j].map_or(BIG, |x| -x);
    let inf = i64::MAX / 4;
    let (mut u, mut v) = (vec![0i64; n + 1], vec![0i64; n + 1]);
    let mut p = vec![0usize; n + 1];
    let mut way = vec![0usize; n + 1];
    for i in 1..=n {
        p[0] = i;
        let mut j0 = 0;
        let mut minv = vec![inf; n + 1];
        let mut used = vec![false; n + 1];
        loop {
            used[j0] = true;
            let i0 = p[j0];
            let mut delta = inf;
            let mut j1 = 0;
            for j in 1..=n {
                if !used[j] {
                    let cur = cost(i0 - 1, j - 1) - u[i0] - v[j];
                    if cur < minv[j] {
                        minv[j] = cur;
                        way[j] = j0;
                    }
                    if minv[j] < delta {
                        delta = minv[j];
                        j1 = j;
                    }
                }
            }
            for j in 0..=n {
                if used[j] {
                    u[p[j]] += delta;
                    v[j] -= delta;
                } else {
                    minv[j] -= delta;
                }
            }
            j0 = j1;
            if p[j0] == 0 {
                break;
            }
        }
        loop {
            let j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
            if j0 == 0 {
                break;
            }
        }
    }
    let mut total = 0;
    for j in 1..=n {
        total += w[p[j] - 1][j - 1]?;
    }
    Some(total)
}

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
    // Cardinality is maximum in every case.
    let mate = matching::maximum_cardinality_matching(g);
    let card = mate.iter().filter(|&&x| x != UNMATCHED).count();
    assert_eq!(card, 2 * m.edges.len());
    m
}

#[test]
fn bipartite_graphs_match_the_hungarian_reference() {
    let mut rng = Rng(77);
    let mut expanded = 0;
    for round in 0..24 {
        let half = 60 + 10 * (round % 10);
        let density = [4, 8, 20, 60][round % 4];
        let range = [1000, 3, 1, 200][round % 4] as u64;
        let mut dense = vec![vec![None; half]; half];
        let mut edges = Vec::new();
        let mut ws = Vec::new();
        for (i, row) in dense.iter_mut().enumerate() {
            for (j, cell) in row.iter_mut().enumerate() {
                if rng.below(100) < density || i == j && round % 3 == 0 {
                    let w = rng.below(range + 1) as i64 - if round % 5 == 0 { range as i64 / 2 } else { 0 };
                    *cell = Some(w);
                    // Shuffle the side order in the edge list.
                    let (a, b) = (i as u32, (half + j) as u32);
                    edges.push(if rng.below(2) == 0 { [a, b] } else { [b, a] });
                    ws.push(w);
                }
            }
        }
        let g = Graph::new(2 * half, edges, ws).unwrap();
        let m = check(&g, Objective::MaxWeight);
        if m.perfect {
            expanded += m.stats.blossoms_expanded + m.stats.blossoms_formed;
        }
        match hungarian(&dense) {
            Some(best) => {
                assert!(m.perfect, "round {round}");
                assert_eq!(m.total_weight, best, "round {round}");
            }
            None => assert!(!m.perfect, "round {round}"),
        }
        // Minimum cost equals minus the maximum weight of the negated weights.
        let neg = Graph::new(g.node_count(), g.edges().to_vec(), g.weights().iter().map(|w| -w).collect()).unwrap();
        let mc = check(&neg, Objective::MinCost);
        assert_eq!(mc.perfect, m.perfect);
        assert_eq!(mc.total_weight, -m.total_weight);
    }
    // A bipartite graph has no odd cycle, so no blossom may form (the no-perfect
    // fallback adds dummy vertices that break bipartiteness, so it is not counted).
    assert_eq!(expanded, 0);
}

fn random_sparse(rng: &mut Rng, n: usize, avg_deg: u64, range: u64) -> Graph {
    let mut edges = Vec::new();
    let mut ws = Vec::new();
    let m = n as u64 * avg_deg / 2;
    for _ in 0..m {
        let a = rng.below(n as u64) as u32;
        let b = rng.below(n as u64) as u32;
        edges.push([a, b]);
        ws.push(rng.below(range) as i64 - (range as i64) / 3);
    }
    Graph::new(n, edges, ws).unwrap()
}

#[test]
fn general_sparse_graphs_are_optimal_and_consistent() {
    let mut rng = Rng(4242);
    let (mut formed, mut expanded, mut perfect) = (0, 0, 0);
    for round in 0..60 {
        let n = 100 + 20 * (round % 15);
        let g = random_sparse(&mut rng, n, [3, 4, 6, 10][round % 4], [2, 5, 100, 100000][round % 4]);
        let a = check(&g, Objective::MaxWeight);
        let neg = Graph::new(n, g.edges().to_vec(), g.weights().iter().map(|w| -w).collect()).unwrap();
        let b = check(&neg, Objective::MinCost);
        assert_eq!(a.perfect, b.perfect);
        assert_eq!(a.total_weight, -b.total_weight);
        // Reordering the edge list does not change the optimum.
        let mut order: Vec<usize> = (0..g.edge_count()).collect();
        for i in (1..order.len()).rev() {
            order.swap(i, rng.below(i as u64 + 1) as usize);
        }
        let shuffled = Graph::new(
            n,
            order.iter().map(|&i| { let e = g.edges()[i]; [e[1], e[0]] }).collect(),
            order.iter().map(|&i| g.weights()[i]).collect(),
        )
        .unwrap();
        let c = check(&shuffled, Objective::MaxWeight);
        assert_eq!(c.total_weight, a.total_weight);
        formed += a.stats.blossoms_formed;
        expanded += a.stats.blossoms_expanded + b.stats.blossoms_expanded;
        perfect += a.perfect as usize;
    }
    eprintln!("perfect {perfect}/60, blossoms formed {formed}, inner expanded {expanded}");
    assert!(formed > 100 && expanded > 0 && perfect > 5 && perfect < 55);
}

#[test]
fn disconnected_graphs_and_isolated_vertices() {
    // Two triangles joined by nothing: each odd, so no perfect matching.
    let tri = |o: u32| vec![[o, o + 1], [o + 1, o + 2], [o + 2, o]];
    let mut edges = tri(0);
    edges.extend(tri(3));
    let g = Graph::new(6, edges.clone(), vec![5, 1, 1, 2, 7, 2]).unwrap();
    let m = check(&g, Objective::MaxWeight);
    assert!(!m.perfect);
    assert_eq!(m.edges.len(), 2);
    assert_eq!(m.total_weight, 12);
    let m = check(&g, Objective::MinCost);
    assert_eq!(m.total_weight, 3);
    // Two even components: perfect.
    let g = Graph::new(8, vec![[0, 1], [1, 2], [2, 3], [4, 5], [5, 6], [6, 7], [7, 4]], vec![1, 10, 1, 3, 3, 3, 4]).unwrap();
    let m = check(&g, Objective::MaxWeight);
    assert!(m.perfect);
    assert_eq!(m.total_weight, 2 + 7);
    // Isolated vertices and the empty graph.
    let g = Graph::new(3, vec![[0, 1]], vec![-4]).unwrap();
    let m = check(&g, Objective::MaxWeight);
    assert!(!m.perfect);
    assert_eq!((m.edges.len(), m.total_weight), (1, -4));
    assert_eq!(m.mate[2], UNMATCHED);
    let g = Graph::new(0, vec![], vec![]).unwrap();
    assert!(check(&g, Objective::MaxWeight).perfect);
    // Large deficiency takes the doubled-graph fallback: a star.
    let n = 400;
    let g = Graph::new(n, (1..n as u32).map(|v| [0, v]).collect(), (1..n as i64).collect()).unwrap();
    let m = check(&g, Objective::MaxWeight);
    assert_eq!((m.perfect, m.edges.len(), m.total_weight), (false, 1, n as i64 - 1));
    let m = check(&g, Objective::MinCost);
    assert_eq!(m.total_weight, 1);
}

#[test]
fn float_weights_scale_to_integers() {
    let w = matching::scale_f64_weights(&[0.5, -1.0, 0.25, 0.0]).unwrap();
    assert_eq!(w, vec![1 << 29, -(1 << 30), 1 << 28, 0]);
    assert!(matching::scale_f64_weights(&[1.0, f64::NAN]).is_err());
    assert_eq!(matching::scale_f64_weights(&[0.0, 0.0]).unwrap(), vec![0, 0]);
}

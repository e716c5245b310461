//! The weighted matching engine against exhaustive search on all kinds of small
//! random graphs; every solve's certificate is checked independently.

use stripkit_matching::{self as matching, Graph, Objective, UNMATCHED};

use stripkit_testkit::XorShift64Star as Rng;

mod matching_brute;

/// Best (cardinality, weight) over all matchings, cardinality first.
fn exhaustive(n: usize, edges: &[[u32; 2]], w: &[i64], obj: Objective) -> (usize, i64) {
    let sign = if obj == Objective::MaxWeight { 1 } else { -1 };
    matching_brute::brute(n, edges, w, sign, true)
}

fn random_graph(rng: &mut Rng, n: usize, density: u64, wmin: i64, wmax: i64, loops: bool) -> Graph {
    let mut edges = Vec::new();
    let mut ws = Vec::new();
    for a in 0..n as u32 {
        for b in a..n as u32 {
            if a == b && !loops {
                continue;
            }
            if rng.below(100) < density {
                let (x, y) = if rng.below(2) == 0 { (a, b) } else { (b, a) };
                edges.push([x, y]);
                ws.push(wmin + rng.below((wmax - wmin + 1) as u64) as i64);
                if rng.below(8) == 0 {
                    // A parallel edge.
                    edges.push([y, x]);
                    ws.push(wmin + rng.below((wmax - wmin + 1) as u64) as i64);
                }
            }
        }
    }
    Graph::new(n, edges, ws).unwrap()
}

fn check_against_exhaustive(g: &Graph, obj: Objective) -> matching::Matching {
    let m = matching::solve(g, obj).unwrap();
    assert!(m.certified);
    let (card, best) = exhaustive(g.node_count(), g.edges(), g.weights(), obj);
    let got_card = m.edges.len();
    // The matching is a matching of input edges.
    let mut seen = vec![false; g.node_count()];
    let mut sum = 0;
    for &e in &m.edges {
        let [a, b] = g.edges()[e as usize];
        assert_ne!(a, b);
        assert!(!seen[a as usize] && !seen[b as usize]);
        seen[a as usize] = true;
        seen[b as usize] = true;
        assert_eq!(m.mate[a as usize], b);
        sum += g.weights()[e as usize];
    }
    assert_eq!(sum, m.total_weight);
    assert_eq!(m.perfect, 2 * card == g.node_count(), "{}", g.to_dimacs());
    assert_eq!(got_card, card, "cardinality\n{}", g.to_dimacs());
    assert_eq!(m.total_weight, best, "{obj:?} weight\n{}", g.to_dimacs());
    if m.perfect {
        let cert = m.certificate.as_ref().unwrap();
        matching::verify(g, obj, &m.edges, cert).unwrap();
    } else {
        assert!(m.mate.contains(&UNMATCHED));
    }
    m
}

#[test]
fn all_small_random_graphs_match_exhaustive_search() {
    let mut rng = Rng(0x9E3779B97F4A7C15);
    let mut perfect = 0;
    let mut total = 0;
    let (mut formed, mut expanded, mut dissolved) = (0, 0, 0);
    for round in 0..2000 {
        let n = 1 + (round % 12);
        let density = [20, 35, 50, 70, 100][round % 5];
        let (lo, hi) = [(1, 10), (-5, 5), (0, 0), (1, 2), (-1000, 1000), (0, 1)][round % 6];
        let g = random_graph(&mut rng, n, density, lo, hi, round % 7 == 0);
        for obj in [Objective::MaxWeight, Objective::MinCost] {
            let m = check_against_exhaustive(&g, obj);
            total += 1;
            perfect += m.perfect as usize;
            formed += m.stats.blossoms_formed;
            expanded += m.stats.blossoms_expanded;
            dissolved += m.stats.blossoms_dissolved;
        }
    }
    // Both kinds of result are exercised.
    assert!(perfect > total / 5 && perfect < total * 4 / 5, "{perfect} of {total}");
    // And the blossom machinery is exercised, not just greedy plus simple paths.
    eprintln!("{perfect} perfect of {total}; blossoms formed {formed}, expanded {expanded}, dissolved {dissolved}");
    assert!(formed > 1000 && dissolved > 500 && expanded >= 1, "formed {formed}, expanded {expanded}, dissolved {dissolved}");
}

#[test]
fn uniform_weights_match_unweighted_cardinality() {
    let mut rng = Rng(12345);
    for round in 0..1500 {
        let n = 1 + (round % 12);
        let g = random_graph(&mut rng, n, [15, 30, 60][round % 3], 0, 0, round % 5 == 0);
        let mate = matching::maximum_cardinality_matching(&g);
        let card = mate.iter().filter(|&&m| m != UNMATCHED).count() / 2;
        for (v, &m) in mate.iter().enumerate() {
            if m != UNMATCHED {
                assert_eq!(mate[m as usize], v as u32);
                assert!(g.adjacency(v).iter().any(|&e| {
                    let [a, b] = g.edges()[e as usize];
                    (a as usize == v && b == m) || (b as usize == v && a == m)
                }));
            }
        }
        let (best, _) = exhaustive(n, g.edges(), g.weights(), Objective::MaxWeight);
        assert_eq!(card, best, "{}", g.to_dimacs());
    }
}

/// Equal nonzero weights (positive and negative) on graphs that mostly have no
/// perfect matching: the uniform shortcut of the fallback must agree with exhaustive
/// search and certify its result.
#[test]
fn uniform_nonzero_weights_fallback_matches_exhaustive_search() {
    let mut rng = Rng(0xA5A5_1234);
    let mut fallback = 0;
    for round in 0..1200 {
        let n = 1 + (round % 12);
        let w = [7, -3, 1][round % 3];
        let g = random_graph(&mut rng, n, [15, 30, 60][round % 3], w, w, round % 5 == 0);
        for obj in [Objective::MaxWeight, Objective::MinCost] {
            let m = check_against_exhaustive(&g, obj);
            fallback += !m.perfect as usize;
        }
    }
    assert!(fallback > 600, "{fallback}");
}

//! Massive ties and input order: the optimum's weight must not depend on the order the
//! edges are listed in nor on the vertex numbering, and every result must carry a
//! checked certificate. Graphs: honeycomb and triangular lattices on a torus, and
//! random 3-regular graphs, with weights in {1, 2}, {0, 1} and all equal (the case
//! that built deep blossom nests: docs/experiments/matching-ties.md).

use stripkit_matching::{self as matching, verify, Graph, Objective};

mod matching_brute;
use stripkit_testkit::XorShift64Star as Rng;

/// Honeycomb lattice on a `w x h` torus (`w` even): 3-regular, bipartite.
fn honeycomb(w: u32, h: u32) -> (usize, Vec<[u32; 2]>) {
    let id = |x: u32, y: u32| (y % h) * w + (x % w);
    let mut e = Vec::new();
    for y in 0..h {
        for x in 0..w {
            e.push([id(x, y), id(x + 1, y)]); // along the row
            if (x + y) % 2 == 0 {
                e.push([id(x, y), id(x, y + 1)]); // every other rung
            }
        }
    }
    // Each vertex: two row neighbours and one rung (h even keeps the rungs consistent).
    e.retain(|&[a, b]| a != b);
    ((w * h) as usize, e)
}

/// Triangular lattice on a `w x h` torus: 6-regular, full of odd cycles (blossoms).
fn triangular(w: u32, h: u32) -> (usize, Vec<[u32; 2]>) {
    let id = |x: u32, y: u32| (y % h) * w + (x % w);
    let mut e = Vec::new();
    for y in 0..h {
        for x in 0..w {
            e.push([id(x, y), id(x + 1, y)]);
            e.push([id(x, y), id(x, y + 1)]);
            e.push([id(x, y), id(x + 1, y + 1)]);
        }
    }
    ((w * h) as usize, e)
}

/// A random 3-regular simple graph on `n` (even) vertices: a Hamiltonian cycle plus a
/// random perfect matching of chords (chords that would repeat an edge are redrawn).
fn cubic(n: u32, rng: &mut Rng) -> (usize, Vec<[u32; 2]>) {
    loop {
        let mut e: Vec<[u32; 2]> = (0..n).map(|v| [v, (v + 1) % n]).collect();
        let mut perm: Vec<u32> = (0..n).collect();
        for i in (1..perm.len()).rev() {
            perm.swap(i, rng.below(i as u64 + 1) as usize);
        }
        let mut seen: std::collections::HashSet<[u32; 2]> = e.iter().map(|&[a, b]| [a.min(b), a.max(b)]).collect();
        let mut ok = true;
        for c in perm.chunks(2) {
            let k = [c[0].min(c[1]), c[0].max(c[1])];
            if !seen.insert(k) {
                ok = false;
                break;
            }
            e.push(k);
        }
        if ok {
            return (n as usize, e);
        }
    }
}

/// Solves, checks perfection and the certificate against the graph, returns the weight.
fn solved_weight(g: &Graph, obj: Objective) -> i64 {
    let m = matching::solve(g, obj).expect("solve");
    assert!(m.perfect, "these graphs have perfect matchings");
    assert!(m.certified);
    let report = verify(g, obj, &m.edges, m.certificate.as_ref().expect("certificate")).expect("certificate holds");
    assert_eq!(report.primal, report.dual);
    assert_eq!(report.primal, obj.internal(m.total_weight) as i128);
    m.total_weight
}

/// The same graph listed in other orders and numberings: the edges reversed, shuffled
/// (ends swapped too), and with the vertices renumbered.
fn variants(n: usize, e: &[[u32; 2]], w: &[i64], rng: &mut Rng) -> Vec<Graph> {
    let mut out = vec![Graph::new(n, e.to_vec(), w.to_vec()).unwrap()];
    let rev: Vec<usize> = (0..e.len()).rev().collect();
    out.push(Graph::new(n, rev.iter().map(|&i| e[i]).collect(), rev.iter().map(|&i| w[i]).collect()).unwrap());
    let mut sorted: Vec<usize> = (0..e.len()).collect();
    sorted.sort_by_key(|&i| (e[i][0].min(e[i][1]), e[i][0].max(e[i][1])));
    out.push(Graph::new(n, sorted.iter().map(|&i| e[i]).collect(), sorted.iter().map(|&i| w[i]).collect()).unwrap());
    for _ in 0..2 {
        let mut order: Vec<usize> = (0..e.len()).collect();
        for i in (1..order.len()).rev() {
            order.swap(i, rng.below(i as u64 + 1) as usize);
        }
        let mut relabel: Vec<u32> = (0..n as u32).collect();
        for i in (1..relabel.len()).rev() {
            relabel.swap(i, rng.below(i as u64 + 1) as usize);
        }
        let shuffled: Vec<[u32; 2]> =
            order.iter().map(|&i| if rng.below(2) == 0 { e[i] } else { [e[i][1], e[i][0]] }).collect();
        let ws: Vec<i64> = order.iter().map(|&i| w[i]).collect();
        out.push(Graph::new(n, shuffled.clone(), ws.clone()).unwrap());
        let renumbered = shuffled.iter().map(|&[a, b]| [relabel[a as usize], relabel[b as usize]]).collect();
        out.push(Graph::new(n, renumbered, ws).unwrap());
    }
    out
}

fn graphs(rng: &mut Rng) -> Vec<(String, usize, Vec<[u32; 2]>)> {
    let mut gs = Vec::new();
    let (n, e) = honeycomb(40, 30);
    gs.push(("honeycomb 40x30".to_string(), n, e));
    let (n, e) = triangular(36, 30);
    gs.push(("triangular 36x30".to_string(), n, e));
    let (n, e) = triangular(3, 5);
    gs.push(("triangular 3x5 + 1".to_string(), n, e)); // odd: made even below
    for i in 0..3 {
        let (n, e) = cubic(800 + 2 * i, rng);
        gs.push((format!("cubic {n}"), n, e));
    }
    // The odd 3x5 lattice gets a pendant vertex joined to one corner (and is small
    // enough for the exhaustive check).
    let t = &mut gs[2];
    t.2.push([0, 15]);
    t.1 = 16;
    gs
}

#[test]
fn tied_weights_give_the_same_optimum_in_every_order() {
    let mut rng = Rng(0x7135_2024_0bad_cafe);
    for (name, n, e) in graphs(&mut rng) {
        // Weights drawn uniformly from lo..=hi.
        let schemes = [("weights 1|2", 1, 2), ("weights 0|1", 0, 1), ("all weights 7", 7, 7)];
        for &(wname, lo, hi) in &schemes {
            let w: Vec<i64> = e.iter().map(|_| rng.range(lo, hi)).collect();
            for obj in [Objective::MaxWeight, Objective::MinCost] {
                let gs = variants(n, &e, &w, &mut rng);
                let first = solved_weight(&gs[0], obj);
                for (i, g) in gs.iter().enumerate().skip(1) {
                    assert_eq!(solved_weight(g, obj), first, "{name}, {wname}, {obj:?}: variant {i} differs");
                }
                if n <= 16 {
                    let sign = if obj == Objective::MaxWeight { 1 } else { -1 };
                    let (card, best) = matching_brute::brute(n, &e, &w, sign, true);
                    assert_eq!(card, n / 2);
                    assert_eq!(best, first, "{name}, {wname}, {obj:?}: brute force");
                }
            }
        }
    }
}

/// Weights 1|2 where one heavy edge per vertex pair of a long path makes chains of
/// nested blossoms: the solver's answer must match a shuffled copy's.
#[test]
fn nested_blossom_chains_from_ties() {
    let mut rng = Rng(42);
    // A "ladder of triangles": vertices 0..n on a path, each i joined to i+1 and i+2.
    let n = 2000usize;
    let mut e = Vec::new();
    for i in 0..n as u32 {
        if (i as usize) + 1 < n {
            e.push([i, i + 1]);
        }
        if (i as usize) + 2 < n {
            e.push([i, i + 2]);
        }
    }
    let w: Vec<i64> = e.iter().map(|&[a, b]| if b == a + 2 { 2 } else { 1 + (rng.below(4) == 0) as i64 }).collect();
    let gs = variants(n, &e, &w, &mut rng);
    let first = solved_weight(&gs[0], Objective::MaxWeight);
    for g in &gs[1..] {
        assert_eq!(solved_weight(g, Objective::MaxWeight), first);
    }
}

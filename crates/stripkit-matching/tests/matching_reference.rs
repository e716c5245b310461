//! The weighted matching engine against an independent, deliberately simple dense
//! O(n^3) Edmonds blossom algorithm (primal-dual, adjacency matrix, written for this
//! test only) on random general graphs of 100-300 nodes. The reference itself is first
//! checked against exhaustive search on many tiny graphs.

use std::collections::VecDeque;
use stripkit_matching::{self as matching, Graph, Objective, UNMATCHED};

mod matching_brute;
use stripkit_testkit::XorShift64Star as Rng;

// ---------------------------------------------------------------------------------
// Reference: dense O(n^3) maximum-weight matching for general graphs.
//
// Vertices are 1..=n, blossoms n+1..=2n, 0 means "none". Weights must be positive
// (0 marks a missing edge). `lab` holds the vertex duals u_v and, for a blossom, 2 z_B;
// the slack of an edge between two different top-level blossoms is
// lab[u] + lab[v] - 2 w. Each stage grows alternating trees from all free vertices
// until an augmenting path is found (O(n^2) per stage with the slack arrays); a stage
// ends without augmenting when the dual of the free vertices reaches zero, which makes
// the result a maximum-weight (not necessarily maximum-cardinality) matching.
// ---------------------------------------------------------------------------------

#[derive(Clone, Copy, Default)]
struct E {
    u: usize,
    v: usize,
    w: i64,
}

struct Dense {
    n: usize,
    nx: usize,
    g: Vec<E>, // (2n+1)^2, row major: g[x * dim + y]
    dim: usize,
    lab: Vec<i64>,
    mate: Vec<usize>,
    slack: Vec<usize>,
    st: Vec<usize>,
    pa: Vec<usize>,
    s: Vec<i8>, // -1 free of labels, 0 = S (even), 1 = T (odd)
    vis: Vec<usize>,
    vis_t: usize,
    flower: Vec<Vec<usize>>,
    flower_from: Vec<usize>, // (2n+1) x (n+1): sub-blossom of b holding vertex x
    q: VecDeque<usize>,
    formed: usize,
    expanded: usize,
}

impl Dense {
    fn new(n: usize, w: &[Vec<i64>]) -> Dense {
        let dim = 2 * n + 1;
        let mut g = vec![E::default(); dim * dim];
        for u in 1..=n {
            for v in 1..=n {
                g[u * dim + v] = E { u, v, w: w[u - 1][v - 1] };
            }
        }
        let mut d = Dense {
            n,
            nx: n,
            g,
            dim,
            lab: vec![0; dim],
            mate: vec![0; dim],
            slack: vec![0; dim],
            st: vec![0; dim],
            pa: vec![0; dim],
            s: vec![-1; dim],
            vis: vec![0; dim],
            vis_t: 0,
            flower: vec![Vec::new(); dim],
            flower_from: vec![0; dim * (n + 1)],
            q: VecDeque::new(),
            formed: 0,
            expanded: 0,
        };
        let wmax = w.iter().flatten().copied().max().unwrap_or(0);
        for u in 1..=n {
            d.st[u] = u;
            d.flower_from[u * (n + 1) + u] = u;
            d.lab[u] = wmax;
        }
        d
    }
    fn e(&self, x: usize, y: usize) -> E {
        self.g[x * self.dim + y]
    }
    fn ff(&self, b: usize, x: usize) -> usize {
        self.flower_from[b * (self.n + 1) + x]
    }
    fn delta(&self, e: E) -> i64 {
        self.lab[e.u] + self.lab[e.v] - 2 * e.w
    }
    fn update_slack(&mut self, u: usize, x: usize) {
        if self.slack[x] == 0 || self.delta(self.e(u, x)) < self.delta(self.e(self.slack[x], x)) {
            self.slack[x] = u;
        }
    }
    fn set_slack(&mut self, x: usize) {
        self.slack[x] = 0;
        for u in 1..=self.n {
            if self.e(u, x).w > 0 && self.st[u] != x && self.s[self.st[u]] == 0 {
                self.update_slack(u, x);
            }
        }
    }
    fn q_push(&mut self, x: usize) {
        if x <= self.n {
            self.q.push_back(x);
        } else {
            for i in 0..self.flower[x].len() {
                let y = self.flower[x][i];
                self.q_push(y);
            }
        }
    }
    fn set_st(&mut self, x: usize, b: usize) {
        self.st[x] = b;
        if x > self.n {
            for i in 0..self.flower[x].len() {
                let y = self.flower[x][i];
                self.set_st(y, b);
            }
        }
    }
    /// Position of sub-blossom `xr` in the cycle of `b`, after reorienting the cycle so
    /// that the path base -> xr along increasing positions has even length.
    fn get_pr(&mut self, b: usize, xr: usize) -> usize {
        let pr = self.flower[b].iter().position(|&x| x == xr).unwrap();
        if pr % 2 == 1 {
            self.flower[b][1..].reverse();
            self.flower[b].len() - pr
        } else {
            pr
        }
    }
    /// Matches top-level (or sub-) blossom `u` along its best edge towards `v`,
    /// re-matching the inside of `u` so that the entering vertex becomes its base.
    fn set_match(&mut self, u: usize, v: usize) {
        let e = self.e(u, v);
        self.mate[u] = e.v;
        if u > self.n {
            let xr = self.ff(u, e.u);
            let pr = self.get_pr(u, xr);
            for i in 0..pr {
                let (a, b) = (self.flower[u][i], self.flower[u][i ^ 1]);
                self.set_match(a, b);
            }
            self.set_match(xr, v);
            self.flower[u].rotate_left(pr);
        }
    }
    fn augment(&mut self, mut u: usize, mut v: usize) {
        loop {
            let xnv = self.st[self.mate[u]];
            self.set_match(u, v);
            if xnv == 0 {
                return;
            }
            let p = self.st[self.pa[xnv]];
            self.set_match(xnv, p);
            u = p;
            v = xnv;
        }
    }
    fn lca(&mut self, mut u: usize, mut v: usize) -> usize {
        self.vis_t += 1;
        let t = self.vis_t;
        while u != 0 || v != 0 {
            if u != 0 {
                if self.vis[u] == t {
                    return u;
                }
                self.vis[u] = t;
                u = self.st[self.mate[u]];
                if u != 0 {
                    u = self.st[self.pa[u]];
                }
            }
            std::mem::swap(&mut u, &mut v);
        }
        0
    }
    /// Appends the tree path from `x` up to (not including) `lca` to `fl`, pairs of
    /// (outer, its mate's blossom), queueing the mates' blossoms.
    fn trace_to(&mut self, mut x: usize, lca: usize, fl: &mut Vec<usize>) {
        while x != lca {
            fl.push(x);
            let y = self.st[self.mate[x]];
            fl.push(y);
            self.q_push(y);
            x = self.st[self.pa[y]];
        }
    }

    fn add_blossom(&mut self, u: usize, lca: usize, v: usize) {
        let n = self.n;
        let mut b = n + 1;
        while b <= self.nx && self.st[b] != 0 {
            b += 1;
        }
        if b > self.nx {
            self.nx += 1;
        }
        assert!(b <= 2 * n, "reference ran out of blossom ids");
        self.formed += 1;
        self.lab[b] = 0;
        self.s[b] = 0;
        self.mate[b] = self.mate[lca];
        let mut fl = vec![lca];
        self.trace_to(u, lca, &mut fl);
        fl[1..].reverse();
        self.trace_to(v, lca, &mut fl);
        self.flower[b] = fl.clone();
        self.set_st(b, b);
        let dim = self.dim;
        for x in 1..=self.nx {
            self.g[b * dim + x].w = 0;
            self.g[x * dim + b].w = 0;
        }
        for x in 1..=n {
            self.flower_from[b * (n + 1) + x] = 0;
        }
        for &xs in &fl {
            for x in 1..=self.nx {
                let cand = self.e(xs, x);
                if cand.w > 0 && (self.e(b, x).w == 0 || self.delta(cand) < self.delta(self.e(b, x))) {
                    self.g[b * dim + x] = cand;
                    self.g[x * dim + b] = self.e(x, xs);
                }
            }
            for x in 1..=n {
                if self.ff(xs, x) != 0 {
                    self.flower_from[b * (n + 1) + x] = xs;
                }
            }
        }
        self.set_slack(b);
    }
    /// Expands a T-blossom whose dual reached zero: the even path from its entry
    /// sub-blossom to its base stays in the tree, the rest becomes unlabelled.
    fn expand_blossom(&mut self, b: usize) {
        self.expanded += 1;
        let fl = self.flower[b].clone();
        for &x in &fl {
            self.set_st(x, x);
        }
        let entry = self.e(b, self.pa[b]).u;
        let xr = self.ff(b, entry);
        let pr = self.get_pr(b, xr);
        let fl = self.flower[b].clone();
        let mut i = 0;
        while i < pr {
            let (xs, xns) = (fl[i], fl[i + 1]);
            self.pa[xs] = self.e(xns, xs).u;
            self.s[xs] = 1;
            self.s[xns] = 0;
            self.slack[xs] = 0;
            self.set_slack(xns);
            self.q_push(xns);
            i += 2;
        }
        self.s[xr] = 1;
        self.pa[xr] = self.pa[b];
        for &xs in &fl[pr + 1..] {
            self.s[xs] = -1;
            self.set_slack(xs);
        }
        self.st[b] = 0;
    }
    /// A tight edge from an S vertex: grow, form a blossom, or augment (true).
    fn on_found_edge(&mut self, e: E) -> bool {
        let u = self.st[e.u];
        let v = self.st[e.v];
        if self.s[v] == -1 {
            self.pa[v] = e.u;
            self.s[v] = 1;
            let nu = self.st[self.mate[v]];
            self.slack[v] = 0;
            self.slack[nu] = 0;
            self.s[nu] = 0;
            self.q_push(nu);
        } else if self.s[v] == 0 {
            let l = self.lca(u, v);
            if l == 0 {
                self.augment(u, v);
                self.augment(v, u);
                return true;
            }
            self.add_blossom(u, l, v);
        }
        false
    }
    /// One stage; true when it augmented.
    fn stage(&mut self) -> bool {
        let n = self.n;
        for x in 1..=self.nx {
            self.s[x] = -1;
            self.slack[x] = 0;
        }
        self.q.clear();
        for x in 1..=self.nx {
            if self.st[x] == x && self.mate[x] == 0 {
                self.pa[x] = 0;
                self.s[x] = 0;
                self.q_push(x);
            }
        }
        if self.q.is_empty() {
            return false;
        }
        loop {
            while let Some(u) = self.q.pop_front() {
                if self.s[self.st[u]] == 1 {
                    continue;
                }
                for v in 1..=n {
                    let e = self.e(u, v);
                    if e.w > 0 && self.st[u] != self.st[v] {
                        if self.delta(e) == 0 {
                            if self.on_found_edge(e) {
                                return true;
                            }
                        } else {
                            self.update_slack(u, self.st[v]);
                        }
                    }
                }
            }
            let mut d = i64::MAX;
            for b in n + 1..=self.nx {
                if self.st[b] == b && self.s[b] == 1 {
                    d = d.min(self.lab[b] / 2);
                }
            }
            for x in 1..=self.nx {
                if self.st[x] == x && self.slack[x] != 0 {
                    let sl = self.delta(self.e(self.slack[x], x));
                    if self.s[x] == -1 {
                        d = d.min(sl);
                    } else if self.s[x] == 0 {
                        assert_eq!(sl % 2, 0, "odd slack between S blossoms");
                        d = d.min(sl / 2);
                    }
                }
            }
            // The free vertices' dual reaching zero first: no augmentation can gain
            // weight any more.
            if (1..=n).any(|u| self.s[self.st[u]] == 0 && self.lab[u] <= d) {
                return false;
            }
            for u in 1..=n {
                match self.s[self.st[u]] {
                    0 => self.lab[u] -= d,
                    1 => self.lab[u] += d,
                    _ => {}
                }
            }
            for b in n + 1..=self.nx {
                if self.st[b] == b {
                    match self.s[b] {
                        0 => self.lab[b] += 2 * d,
                        1 => self.lab[b] -= 2 * d,
                        _ => {}
                    }
                }
            }
            self.q.clear();
            for x in 1..=self.nx {
                if self.st[x] == x && self.slack[x] != 0 && self.st[self.slack[x]] != x {
                    let e = self.e(self.slack[x], x);
                    if self.delta(e) == 0 && self.on_found_edge(e) {
                        return true;
                    }
                }
            }
            for b in n + 1..=self.nx {
                if self.st[b] == b && self.s[b] == 1 && self.lab[b] == 0 {
                    self.expand_blossom(b);
                }
            }
        }
    }
}

/// Reference maximum-weight matching of a general graph: returns the mate of every
/// vertex (`usize::MAX` when unmatched). With `max_card`, a maximum-cardinality matching
/// of maximum weight among those; otherwise a maximum-weight matching of any size.
/// Parallel edges: the heaviest counts; self-loops are ignored. Also returns how many
/// blossoms the reference formed and expanded.
fn reference(n: usize, edges: &[[u32; 2]], w: &[i64], max_card: bool) -> (Vec<usize>, usize, usize) {
    if n == 0 {
        return (Vec::new(), 0, 0);
    }
    let (wmin, wmax) = w.iter().fold((0i64, 0i64), |(lo, hi), &x| (lo.min(x), hi.max(x)));
    // Bonus making one more matched edge outweigh any weight difference.
    let bonus = if max_card { (n as i64 / 2 + 1) * (wmax - wmin) + wmin.abs() + 1 } else { 0 };
    let mut mat = vec![vec![0i64; n]; n];
    for (e, &x) in edges.iter().zip(w) {
        let (a, b) = (e[0] as usize, e[1] as usize);
        let x = x + bonus;
        if a != b && x > 0 && x > mat[a][b] {
            mat[a][b] = x;
            mat[b][a] = x;
        }
    }
    let mut d = Dense::new(n, &mat);
    while d.stage() {}
    let mate = (1..=n).map(|u| if d.mate[u] == 0 { usize::MAX } else { d.mate[u] - 1 }).collect();
    (mate, d.formed, d.expanded)
}

/// (cardinality, weight) of the reference's matching, after checking it is a matching
/// of existing edges; `obj` picks maximum weight or minimum cost (by negation).
fn reference_value(n: usize, edges: &[[u32; 2]], w: &[i64], obj: Objective, max_card: bool) -> (usize, i64) {
    let (c, s, _) = reference_stats(n, edges, w, obj, max_card);
    (c, s)
}

/// [`reference_value`] plus (blossoms formed, blossoms expanded) by the reference.
fn reference_stats(
    n: usize,
    edges: &[[u32; 2]],
    w: &[i64],
    obj: Objective,
    max_card: bool,
) -> (usize, i64, (usize, usize)) {
    let sign = if obj == Objective::MaxWeight { 1 } else { -1 };
    let ws: Vec<i64> = w.iter().map(|&x| sign * x).collect();
    let (mate, formed, expanded) = reference(n, edges, &ws, max_card);
    let mut best = vec![vec![None::<i64>; n]; n];
    for (e, &x) in edges.iter().zip(&ws) {
        let (a, b) = (e[0] as usize, e[1] as usize);
        if a != b {
            let m = best[a][b].map_or(x, |y: i64| y.max(x));
            best[a][b] = Some(m);
            best[b][a] = Some(m);
        }
    }
    let (mut card, mut sum) = (0, 0);
    for u in 0..n {
        let v = mate[u];
        if v != usize::MAX {
            assert_eq!(mate[v], u, "reference mate not symmetric");
            let x = best[u][v].expect("reference matched a non-edge");
            if u < v {
                card += 1;
                sum += x;
            }
        }
    }
    (card, sign * sum, (formed, expanded))
}

fn tiny_graph(rng: &mut Rng, n: usize, density: u64, lo: i64, hi: i64) -> (Vec<[u32; 2]>, Vec<i64>) {
    let mut edges = Vec::new();
    let mut ws = Vec::new();
    for a in 0..n as u32 {
        for b in a + 1..n as u32 {
            if rng.below(100) < density {
                edges.push([a, b]);
                ws.push(rng.range(lo, hi));
                if rng.below(10) == 0 {
                    edges.push([b, a]);
                    ws.push(rng.range(lo, hi));
                }
            }
        }
    }
    (edges, ws)
}

#[test]
fn reference_matches_brute_force_on_tiny_graphs() {
    let mut rng = Rng(0xD1B54A32D192ED03);
    let mut nontrivial = 0;
    let (mut formed, mut expanded) = (0, 0);
    for round in 0..1500 {
        let n = 1 + round % 11;
        let density = [25, 40, 60, 85, 100][round % 5];
        let (lo, hi) = [(1, 20), (-10, 10), (1, 2), (-1000, 1000), (-5, -1), (0, 0)][round % 6];
        let (edges, ws) = tiny_graph(&mut rng, n, density, lo, hi);
        for max_card in [false, true] {
            let (bc, bw) = matching_brute::brute(n, &edges, &ws, 1, max_card);
            let (rc, rw, (f, x)) = reference_stats(n, &edges, &ws, Objective::MaxWeight, max_card);
            formed += f;
            expanded += x;
            assert_eq!(rw, bw, "weight, n {n} max_card {max_card} edges {edges:?} w {ws:?}");
            if max_card {
                assert_eq!(rc, bc, "cardinality, n {n} edges {edges:?} w {ws:?}");
            }
            nontrivial += (bc >= 3) as usize;
        }
    }
    eprintln!("reference: {nontrivial} cases with >= 3 matched edges; blossoms formed {formed}, expanded {expanded}");
    assert!(nontrivial > 500, "{nontrivial}");
    // The reference's blossom code is exercised by this cross-check, not just paths.
    assert!(formed > 300 && expanded > 20, "formed {formed}, expanded {expanded}");
}

/// A random general graph on `n` vertices: a hidden random perfect matching on the
/// first `2 * (n / 2)` shuffled vertices (when `with_perfect`), plus random edges for
/// a mean degree of about `deg`, some parallel edges and a few triangles to force
/// odd cycles.
fn random_graph(rng: &mut Rng, n: usize, deg: u64, with_perfect: bool, lo: i64, hi: i64) -> Graph {
    let mut edges = Vec::new();
    let mut perm: Vec<u32> = (0..n as u32).collect();
    for i in (1..n).rev() {
        perm.swap(i, rng.below(i as u64 + 1) as usize);
    }
    if with_perfect {
        for p in perm.chunks_exact(2) {
            edges.push([p[0], p[1]]);
        }
    }
    let extra = n as u64 * deg / 2 - edges.len() as u64;
    for _ in 0..extra {
        let a = rng.below(n as u64) as u32;
        let b = rng.below(n as u64) as u32;
        if a != b {
            edges.push([a, b]);
            if rng.below(20) == 0 {
                edges.push([b, a]);
            }
        }
    }
    // Shuffle the edge order so the hidden matching does not come first.
    for i in (1..edges.len()).rev() {
        edges.swap(i, rng.below(i as u64 + 1) as usize);
    }
    let ws = (0..edges.len()).map(|_| rng.range(lo, hi)).collect();
    Graph::new(n, edges, ws).unwrap()
}

/// Checks that `m` is a matching of `g`'s edges with the stated mate array and total.
fn check_consistent(g: &Graph, m: &matching::Matching) {
    let mut seen = vec![false; g.node_count()];
    let mut sum = 0;
    for &e in &m.edges {
        let [a, b] = g.edges()[e as usize];
        assert_ne!(a, b);
        assert!(!seen[a as usize] && !seen[b as usize], "vertex matched twice");
        seen[a as usize] = true;
        seen[b as usize] = true;
        assert_eq!(m.mate[a as usize], b);
        assert_eq!(m.mate[b as usize], a);
        sum += g.weights()[e as usize];
    }
    for (v, &s) in seen.iter().enumerate() {
        assert_eq!(s, m.mate[v] != UNMATCHED);
    }
    assert_eq!(sum, m.total_weight);
}

const WEIGHT_RANGES: [(i64, i64); 5] = [
    (0, 1_000_000),                 // wide, non-negative
    (-1_000_000_000, 1_000_000_000), // very wide, mixed signs
    (1, 3),                          // small: many ties
    (-100, -1),                      // all negative
    (0, 0),                          // all equal
];

#[test]
fn perfect_matchings_agree_with_reference() {
    let mut rng = Rng(0x2545F4914F6CDD1D);
    let mut blossoms = 0;
    for round in 0..20 {
        let n = 100 + 2 * rng.below(101) as usize; // even, 100..=300
        let deg = 4 + rng.below(3);
        let (lo, hi) = WEIGHT_RANGES[round % WEIGHT_RANGES.len()];
        let g = random_graph(&mut rng, n, deg, true, lo, hi);
        for obj in [Objective::MaxWeight, Objective::MinCost] {
            let m = match obj {
                Objective::MaxWeight => matching::max_weight_perfect_matching(&g).unwrap(),
                Objective::MinCost => matching::min_cost_perfect_matching(&g).unwrap(),
            };
            check_consistent(&g, &m);
            assert!(m.perfect, "round {round} n {n} {obj:?}: not perfect");
            assert!(m.certified, "round {round} n {n} {obj:?}: not certified");
            assert_eq!(m.edges.len() * 2, n);
            let (rc, rw) = reference_value(n, g.edges(), g.weights(), obj, true);
            assert_eq!(rc * 2, n, "round {round}: reference found no perfect matching");
            assert_eq!(
                m.total_weight, rw,
                "round {round} n {n} deg {deg} weights {lo}..={hi} {obj:?}: engine {} reference {rw}",
                m.total_weight
            );
            blossoms += m.stats.blossoms_formed;
        }
    }
    // The blossom machinery is exercised, not just augmenting paths.
    assert!(blossoms > 100, "{blossoms}");
}

#[test]
fn imperfect_graphs_agree_with_reference_max_cardinality() {
    let mut rng = Rng(0x9E3779B97F4A7C15);
    let mut deficiencies = Vec::new();
    for round in 0..20 {
        let (lo, hi) = WEIGHT_RANGES[round % WEIGHT_RANGES.len()];
        let size = rng.below(201) as usize;
        let g = match round % 4 {
            // Odd n, near-perfect.
            0 => random_graph(&mut rng, 101 + 2 * (size / 2).min(99), 5, true, lo, hi),
            // Sparse: many vertices stay exposed (the engine's doubled-graph path).
            1 => random_graph(&mut rng, 100 + size, 2, false, lo, hi),
            // Even n with two odd components (an odd block joined to nothing else).
            _ => {
                let n = 100 + 2 * (size / 2);
                let k = 11 + 2 * rng.below(20) as usize; // odd component size
                let a = random_graph(&mut rng, k, 5, true, lo, hi);
                let b = random_graph(&mut rng, n - k, 5, true, lo, hi);
                let mut edges = a.edges().to_vec();
                let mut ws = a.weights().to_vec();
                edges.extend(b.edges().iter().map(|e| [e[0] + k as u32, e[1] + k as u32]));
                ws.extend_from_slice(b.weights());
                Graph::new(n, edges, ws).unwrap()
            }
        };
        let n = g.node_count();
        for obj in [Objective::MaxWeight, Objective::MinCost] {
            let m = matching::solve(&g, obj).unwrap();
            check_consistent(&g, &m);
            assert!(m.certified);
            let (rc, rw) = reference_value(n, g.edges(), g.weights(), obj, true);
            assert!(rc * 2 < n);
            assert!(!m.perfect, "round {round} n {n}: claims perfect");
            assert_eq!(m.edges.len(), rc, "round {round} n {n} {obj:?}: cardinality");
            assert_eq!(
                m.total_weight, rw,
                "round {round} n {n} weights {lo}..={hi} {obj:?}: engine {} reference {rw}",
                m.total_weight
            );
            deficiencies.push(n - 2 * rc);
        }
    }
    // Both small and large deficiencies occur.
    assert!(deficiencies.iter().any(|&k| k <= 2) && deficiencies.iter().any(|&k| k > 20), "{deficiencies:?}");
}

//! The solver's entry points: the input reduced to a simple graph, the odd-component
//! and k-dummy gadgets for graphs without a perfect matching, the uniform-weight
//! shortcut, and the certificate check of every result.

use crate::blossom::{Engine, SimpleGraph, Stats, NONE};
use crate::certificate::{check_certificate, CheckReport, Certificate, DualBlossom};
use crate::error::{Error, Result};
use crate::graph::Graph;
use crate::unweighted;

/// Graphs up to this many vertices without odd components get an unweighted
/// cardinality check before the weighted perfect attempt (tens of milliseconds there;
/// it saves a failing attempt that can take seconds).
const PRECHECK_NODES: usize = 1 << 19;

/// Marks an unmatched vertex in [`Matching::mate`].
pub const UNMATCHED: u32 = u32::MAX;

/// What to optimise.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Objective {
    /// Maximise the total weight.
    MaxWeight,
    /// Minimise the total weight (cost).
    MinCost,
}

impl Objective {
    /// The internal (maximised, doubled) weight of a user weight.
    pub fn internal(self, w: i64) -> i64 {
        match self {
            Objective::MaxWeight => 2 * w,
            Objective::MinCost => -2 * w,
        }
    }
}

/// A solved matching problem.
#[derive(Clone, Debug)]
pub struct Matching {
    /// True when the matching is perfect (and then optimal among perfect matchings).
    /// False when the graph has no perfect matching: the matching is then of maximum
    /// cardinality and, among those, of maximum weight (or minimum cost).
    pub perfect: bool,
    /// Partner of each vertex, or [`UNMATCHED`].
    pub mate: Vec<u32>,
    /// Ids of the matched input edges, ascending.
    pub edges: Vec<u32>,
    /// Sum of the input weights of the matched edges.
    pub total_weight: i64,
    /// The dual solution for a perfect matching, in internal weights (see
    /// [`Certificate`]); `None` when not perfect.
    pub certificate: Option<Certificate>,
    /// True when the solver's own certificate passed [`check_certificate`] (for a
    /// non-perfect result: the certificate of the auxiliary perfect-matching problem,
    /// the graph plus `k` dummy vertices joined to every vertex, or for large
    /// deficiency `k` the doubled graph).
    pub certified: bool,
    /// Work counters.
    pub stats: Stats,
}

/// Maximum-weight perfect matching (see [`solve`]).
pub fn max_weight_perfect_matching(g: &Graph) -> Result<Matching> {
    solve(g, Objective::MaxWeight)
}

/// Minimum-cost perfect matching (see [`solve`]).
pub fn min_cost_perfect_matching(g: &Graph) -> Result<Matching> {
    solve(g, Objective::MinCost)
}

/// The simple graph the engine sees: no self-loops, one edge per vertex pair (the
/// best of parallel edges), internal weights; plus the input id of each edge.
fn simplify(g: &Graph, obj: Objective) -> (Vec<[u32; 2]>, Vec<i64>, Vec<u32>) {
    let n = g.node_count();
    // Bucket edges by their lower end (counting sort), then sort each small bucket.
    let mut start = vec![0u32; n + 1];
    for e in g.edges() {
        if e[0] != e[1] {
            start[e[0].min(e[1]) as usize + 1] += 1;
        }
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut order = vec![0u32; start[n] as usize];
    for (i, e) in g.edges().iter().enumerate() {
        if e[0] != e[1] {
            let lo = e[0].min(e[1]) as usize;
            order[fill[lo] as usize] = i as u32;
            fill[lo] += 1;
        }
    }
    let w = g.weights();
    let hi = |i: u32| {
        let e = g.edges()[i as usize];
        e[0].max(e[1])
    };
    let mut ends = Vec::with_capacity(order.len());
    let mut ws = Vec::with_capacity(order.len());
    let mut ids = Vec::with_capacity(order.len());
    for v in 0..n {
        let bucket = &mut order[start[v] as usize..start[v + 1] as usize];
        if bucket.len() > 1 {
            bucket.sort_unstable_by_key(|&i| (hi(i), std::cmp::Reverse(obj.internal(w[i as usize])), i));
        }
        let mut last = NONE;
        for &i in bucket.iter() {
            let h = hi(i);
            if h == last {
                continue;
            }
            last = h;
            ends.push([v as u32, h]);
            ws.push(obj.internal(w[i as usize]));
            ids.push(i);
        }
    }
    (ends, ws, ids)
}

/// Connected components: the root of each vertex's component, and the roots of the
/// components with an odd number of vertices (each leaves at least one vertex exposed
/// in every matching).
fn components(n: usize, ends: &[[u32; 2]]) -> (Vec<u32>, Vec<u32>) {
    let mut parent: Vec<u32> = (0..n as u32).collect();
    fn find(p: &mut [u32], mut x: u32) -> u32 {
        while p[x as usize] != x {
            p[x as usize] = p[p[x as usize] as usize];
            x = p[x as usize];
        }
        x
    }
    for e in ends {
        let (a, b) = (find(&mut parent, e[0]), find(&mut parent, e[1]));
        if a != b {
            parent[a as usize] = b;
        }
    }
    let mut size = vec![0u32; n];
    for v in 0..n as u32 {
        let r = find(&mut parent, v);
        parent[v as usize] = r;
        size[r as usize] += 1;
    }
    let odd = (0..n as u32).filter(|&r| parent[r as usize] == r && size[r as usize] % 2 == 1).collect();
    (parent, odd)
}

/// Perfect-matching certificate data of an engine run, with the matched edge ids of
/// the engine's graph.
fn engine_certificate(sg: &SimpleGraph, engine: &mut Engine) -> (Vec<u32>, Certificate) {
    let sol = engine.solution();
    let n = sol.mate_edge.len();
    let matched: Vec<u32> = (0..n)
        .filter(|&v| {
            let [a, b] = sg.ends[sol.mate_edge[v] as usize];
            v as u32 == a.min(b)
        })
        .map(|v| sol.mate_edge[v])
        .collect();
    let cert = Certificate {
        y: sol.y,
        blossoms: sol.blossoms.iter().map(|&(z, parent)| DualBlossom { z, parent }).collect(),
        vertex_blossom: sol.vertex_blossom,
    };
    (matched, cert)
}

/// The internal weight of every dummy edge in the max-cardinality gadgets. Any
/// constant gives the same optimum (every perfect matching of a gadget uses the same
/// number of dummy edges); the largest real weight makes dummy edges tight early, so
/// the trees meet a dummy while they are still small. (A strongly negative weight,
/// tried first, made one tree cover a whole odd component before any dummy edge became
/// tight: bunny with normal-angle weights 0.81 s instead of 0.37 s.)
fn dummy_weight(ws: &[i64]) -> i64 {
    ws.iter().copied().max().unwrap_or(0)
}

/// The graph plus one dummy vertex per odd component, joined to every vertex of that
/// component by an edge of internal weight `dummy`. Its perfect matchings are the
/// matchings of the graph that leave exactly one vertex of each odd component
/// exposed: when one exists, those are the maximum-cardinality matchings (no matching
/// exposes fewer), and with all dummy edges equal the optimum is the best of them.
fn odd_component_gadget(
    n: usize,
    ends: &[[u32; 2]],
    ws: &[i64],
    root: &[u32],
    odd: &[u32],
    dummy: i64,
) -> (usize, Vec<[u32; 2]>, Vec<i64>) {
    let mut dummy_of = vec![NONE; n];
    for (i, &r) in odd.iter().enumerate() {
        dummy_of[r as usize] = (n + i) as u32;
    }
    let mut dends = ends.to_vec();
    let mut dws = ws.to_vec();
    for v in 0..n {
        let d = dummy_of[root[v] as usize];
        if d != NONE {
            dends.push([v as u32, d]);
            dws.push(dummy);
        }
    }
    (n + odd.len(), dends, dws)
}

/// Uniform weights: every maximum-cardinality matching is optimal, so the unweighted
/// matcher decides, stopped at the odd-component bound; the certificate is `y = w / 2`
/// on every vertex (every edge tight), extended to the odd-component gadget by
/// `y_d = dummy - w / 2`; past the bound, on the k-dummy gadget the same way, whose
/// k x n dummy edges are checked without being built (see [`check_k_dummy`]).
fn solve_uniform(g: &Graph, obj: Objective, ends: &[[u32; 2]], ws: &[i64], ids: &[u32], root: &[u32], odd: &[u32]) -> Result<Matching> {
    let n = g.node_count();
    let w = ws[0];
    let plain = Graph::new(n, ends.to_vec(), vec![0; ends.len()])?;
    let mate = unweighted::maximum_cardinality_matching_bounded(&plain, odd.len());
    let exposed = mate.iter().filter(|&&x| x == UNMATCHED).count();
    // Matched simple-edge ids (plain has the simplified edges in order).
    let mut matched_simple: Vec<u32> = Vec::with_capacity(n / 2);
    for v in 0..n as u32 {
        let u = mate[v as usize];
        if u != UNMATCHED && v < u {
            let e = plain
                .adjacency(v as usize)
                .iter()
                .copied()
                .find(|&e| {
                    let [a, b] = ends[e as usize];
                    (a == v && b == u) || (a == u && b == v)
                })
                .expect("matched along an edge");
            matched_simple.push(e);
        }
    }
    let mut matched: Vec<u32> = matched_simple.iter().map(|&e| ids[e as usize]).collect();
    matched.sort_unstable();
    let stats = Stats::default();
    if exposed == 0 {
        let cert = Certificate { y: vec![w / 2; n], blossoms: Vec::new(), vertex_blossom: vec![NONE; n] };
        verify(g, obj, &matched, &cert)?;
        return Ok(finish(g, true, matched, Some(cert), true, stats));
    }
    let dummy = dummy_weight(ws);
    if exposed != odd.len() {
        // k = exposed dummies, each joined to every vertex; the i-th exposed vertex
        // takes dummy i. Every edge is tight under y = w/2, y_d = dummy - w/2.
        let k = exposed;
        let exposed_vertices: Vec<u32> = (0..n as u32).filter(|&v| mate[v as usize] == UNMATCHED).collect();
        let mut y = vec![w / 2; n + k];
        for yd in &mut y[n..] {
            *yd = dummy - w / 2;
        }
        let cert = Certificate { y, blossoms: Vec::new(), vertex_blossom: vec![NONE; n + k] };
        check_k_dummy(n, ends, ws, dummy, &matched_simple, &exposed_vertices, &cert)?;
        return Ok(finish(g, false, matched, None, true, stats));
    }
    let (n2, dends, dws) = odd_component_gadget(n, ends, ws, root, odd, dummy);
    let mut y = vec![w / 2; n2];
    for yd in &mut y[n..] {
        *yd = dummy - w / 2;
    }
    // Each exposed vertex takes its component's dummy: the gadget edge after the real
    // ones, in vertex order.
    let mut all = matched_simple;
    let mut gadget_edge = ends.len() as u32;
    for v in 0..n {
        if odd.binary_search(&root[v]).is_ok() {
            if mate[v] == UNMATCHED {
                all.push(gadget_edge);
            }
            gadget_edge += 1;
        }
    }
    let cert = Certificate { y, blossoms: Vec::new(), vertex_blossom: vec![NONE; n2] };
    check_certificate(n2, &dends, &dws, &all, &cert)?;
    Ok(finish(g, false, matched, None, true, stats))
}

/// Checks a certificate of the k-dummy gadget (the graph plus `k` dummy vertices
/// `n..n+k`, each joined to every vertex by an edge of internal weight `dummy`, no
/// blossoms) without building its k x n dummy edges: the graph's edges and the `k`
/// matched dummy edges (the i-th exposed vertex to dummy i) go to
/// [`check_certificate`], and every other dummy edge's constraint
/// `y_v + y_d >= dummy` holds for all pairs exactly when it holds for the smallest
/// `y_v` and the smallest `y_d`. The gadget was built in full before: 20,000 exposed
/// vertices of a star asked for 2 GiB.
fn check_k_dummy(
    n: usize,
    ends: &[[u32; 2]],
    ws: &[i64],
    dummy: i64,
    matched: &[u32],
    exposed: &[u32],
    cert: &Certificate,
) -> Result<()> {
    let k = exposed.len();
    if !cert.blossoms.is_empty() || cert.y.len() != n + k {
        return Err(Error::Verification("k-dummy certificate: blossoms or wrong dual count (bug)".into()));
    }
    let mut dends = ends.to_vec();
    let mut dws = ws.to_vec();
    let mut all = matched.to_vec();
    for (i, &v) in exposed.iter().enumerate() {
        all.push(dends.len() as u32);
        dends.push([v, (n + i) as u32]);
        dws.push(dummy);
    }
    check_certificate(n + k, &dends, &dws, &all, cert)?;
    let (ymin, ydmin) = (cert.y[..n].iter().min(), cert.y[n..].iter().min());
    if let (Some(&a), Some(&b)) = (ymin, ydmin) {
        if (a as i128) + (b as i128) < (dummy as i128) {
            return Err(Error::Verification(format!(
                "k-dummy certificate: a dummy edge has negative slack ({a} + {b} < {dummy})"
            )));
        }
    }
    Ok(())
}

/// Solves the matching problem for `obj`: an optimal perfect matching with its
/// certificate (checked before returning), or, when there is no perfect matching, a
/// maximum-cardinality matching optimal among those (`perfect == false`).
/// Fails only when the certificate check fails (a bug) or weights are too large for
/// the max-cardinality fallback.
pub fn solve(g: &Graph, obj: Objective) -> Result<Matching> {
    let n = g.node_count();
    let (ends, ws, ids) = simplify(g, obj);
    let (root, odd) = components(n, &ends);
    // Uniform weights (over every input edge, parallel ones included): cardinality is
    // all that matters.
    let uniform = {
        let mut it = g.edges().iter().zip(g.weights()).filter(|(e, _)| e[0] != e[1]).map(|(_, &w)| w);
        match it.next() {
            Some(first) => it.all(|w| w == first),
            None => false,
        }
    };
    if uniform {
        return solve_uniform(g, obj, &ends, &ws, &ids, &root, &odd);
    }
    // A failing perfect attempt costs far more than a success (the last trees grow
    // over everything before the engine gives up), so on graphs of moderate size the
    // fast unweighted matcher decides first whether a perfect matching exists.
    let mut known_card = None;
    if odd.is_empty() && n <= PRECHECK_NODES {
        let plain = Graph::new(n, ends.clone(), vec![0; ends.len()])?;
        let mate = unweighted::maximum_cardinality_matching(&plain);
        known_card = Some(mate.iter().filter(|&&x| x != UNMATCHED).count());
    }
    if odd.is_empty() && known_card.is_none_or(|c| c == n) {
        let sg = SimpleGraph::new(n, ends.clone(), ws.clone());
        let mut engine = Engine::new(&sg);
        engine.init_greedy();
        let ok = engine.run();
        let stats = engine.stats;
        if ok {
            let (edges, cert) = engine_certificate(&sg, &mut engine);
            let mut matched: Vec<u32> = edges.iter().map(|&e| ids[e as usize]).collect();
            matched.sort_unstable();
            verify(g, obj, &matched, &cert)?;
            return Ok(finish(g, true, matched, Some(cert), true, stats));
        }
    } else {
        // Try the odd-component bound first: one dummy per odd component. Mesh dual
        // graphs almost always reach it, and then no unweighted pre-pass is needed.
        let dummy = dummy_weight(&ws);
        let (n2, dends, dws) = odd_component_gadget(n, &ends, &ws, &root, &odd, dummy);
        let sg = SimpleGraph::new(n2, dends, dws);
        let mut engine = Engine::new(&sg);
        engine.init_greedy();
        if engine.run() {
            let stats = engine.stats;
            let (all, cert) = engine_certificate(&sg, &mut engine);
            check_certificate(n2, &sg.ends, &sg.w, &all, &cert)?;
            let mut matched: Vec<u32> =
                all.iter().filter(|&&e| (e as usize) < ends.len()).map(|&e| ids[e as usize]).collect();
            matched.sort_unstable();
            return Ok(finish(g, false, matched, None, true, stats));
        }
    }
    // No perfect matching, and more exposed vertices than odd components: maximum
    // cardinality from the unweighted matcher, then best weight.
    let m = ends.len();
    // The deficiency k = n - 2 * (maximum cardinality), from the unweighted matcher.
    let card = match known_card {
        Some(c) => c,
        None => {
            let plain = Graph::new(n, ends.clone(), vec![0; m])?;
            unweighted::maximum_cardinality_matching(&plain).iter().filter(|&&x| x != UNMATCHED).count()
        }
    };
    let k = n - card;
    let (n2, dends, dws) = if (k as u64) * (n as u64) <= 4 * (n as u64 + m as u64) {
        // Few vertices stay exposed: add k dummy vertices joined to every vertex. A
        // perfect matching there is a maximum-cardinality matching of G plus exactly k
        // dummy edges, so with equal dummy weights its optimum is the best such
        // matching, whatever that weight. A strongly negative one keeps the trees from
        // running through the dummies (each would rescan its n edges) until nothing
        // else is left.
        let maxabs = ws.iter().map(|w| w.abs()).max().unwrap_or(0);
        let dummy = -2 * (64 * (maxabs / 2 + 1)).min(1 << 50);
        let mut dends = ends.clone();
        let mut dws = ws.clone();
        dends.reserve(k * n);
        dws.reserve(k * n);
        for d in 0..k {
            for v in 0..n as u32 {
                dends.push([v, (n + d) as u32]);
                dws.push(dummy);
            }
        }
        (n + k, dends, dws)
    } else {
        // Many exposed vertices: the doubled graph (two copies, each vertex joined to
        // its copy by a zero edge; real edges get a bonus C larger than any weight
        // difference a smaller matching could win).
        let (wmin, wmax) = ws.iter().fold((0i64, 0i64), |(lo, hi), &w| (lo.min(w), hi.max(w)));
        let c: i128 = (n as i128 / 2 + 1) * (wmax as i128 - wmin as i128) + (wmin as i128).abs() + 2;
        let big = (c + wmax.abs().max(wmin.abs()) as i128) * 2;
        if big > (1i128 << 56) {
            return Err(Error::Invalid(format!(
                "no perfect matching, and the weights are too large (bonus {c}) for the exact \
                 maximum-cardinality fallback; scale them down"
            )));
        }
        let c = c as i64;
        let mut dends = Vec::with_capacity(2 * m + n);
        let mut dws = Vec::with_capacity(2 * m + n);
        for (e, &w) in ends.iter().zip(&ws) {
            dends.push(*e);
            dws.push(2 * (w + c));
        }
        for (e, &w) in ends.iter().zip(&ws) {
            dends.push([e[0] + n as u32, e[1] + n as u32]);
            dws.push(2 * (w + c));
        }
        for v in 0..n as u32 {
            dends.push([v, v + n as u32]);
            dws.push(0);
        }
        (2 * n, dends, dws)
    };
    let sg = SimpleGraph::new(n2, dends, dws);
    let mut engine = Engine::new(&sg);
    engine.init_greedy();
    if !engine.run() {
        return Err(Error::Verification("the auxiliary graph has no perfect matching (bug)".into()));
    }
    let stats = engine.stats;
    let (all, cert) = engine_certificate(&sg, &mut engine);
    check_certificate(n2, &sg.ends, &sg.w, &all, &cert)?;
    let mut matched: Vec<u32> = all.iter().filter(|&&e| (e as usize) < m).map(|&e| ids[e as usize]).collect();
    matched.sort_unstable();
    if matched.len() * 2 != card {
        return Err(Error::Verification(format!(
            "weighted fallback matched {} vertices, the maximum is {card} (bug)",
            matched.len() * 2
        )));
    }
    Ok(finish(g, false, matched, None, true, stats))
}

fn finish(
    g: &Graph,
    perfect: bool,
    edges: Vec<u32>,
    certificate: Option<Certificate>,
    certified: bool,
    stats: Stats,
) -> Matching {
    let mut mate = vec![UNMATCHED; g.node_count()];
    let mut total_weight = 0i64;
    for &e in &edges {
        let [a, b] = g.edges()[e as usize];
        mate[a as usize] = b;
        mate[b as usize] = a;
        total_weight += g.weights()[e as usize];
    }
    Matching { perfect, mate, edges, total_weight, certificate, certified, stats }
}

/// Checks a perfect matching (input edge ids) and its certificate against the input
/// graph for `obj`; every input edge (parallel ones included, self-loops excluded)
/// must satisfy its dual constraint. Returns the primal and dual values.
pub fn verify(g: &Graph, obj: Objective, matched: &[u32], cert: &Certificate) -> Result<CheckReport> {
    let w: Vec<i64> = g.weights().iter().map(|&w| obj.internal(w)).collect();
    check_certificate(g.node_count(), g.edges(), &w, matched, cert)
}

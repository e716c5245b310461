//! Single strips from a weighted perfect matching (Gopi and Eppstein's single-strip
//! triangulation, steered by weights as in "Constrained single strips", sections 3 to
//! 6).
//!
//! 1. **Weights** on the dual edges ([`Weights`]): a heavy edge is one the strip should
//!    not cross.
//! 2. **Matching.** A maximum-weight matching of the dual graph's degree-3 triangles
//!    (on a closed manifold mesh: a perfect matching of every triangle). Every
//!    triangle is linked to its other neighbours, so the links form disjoint loops;
//!    triangles with fewer neighbours (boundaries, non-manifold or degenerate
//!    neighbours) are never matched and keep every link they have, and a degree-3
//!    triangle the matching leaves out drops its heaviest link. The pieces are then
//!    loops and paths.
//! 3. **Merging** ([`merge`]): nodal vertices (mesh unchanged), path-end joins and
//!    attaches (mesh unchanged), edge swaps on convex, nearly flat quads, and edge
//!    splits (a Steiner vertex at an edge's midpoint, surface unchanged), greedily by
//!    class then by the weight lost, until one piece is left per component.
//! 4. **Strips.** Each piece, a loop cut once or a path, is one strip with the fewest
//!    swaps for it ([`crate::topology::walks::encode_path`]).
//!
//! The result names the changed mesh: Steiner vertices appended after the input's
//! vertices, swapped pairs recorded; [`check`] proves the changed triangles cover the
//! input triangles.

pub(crate) mod check;
mod cull;
pub(crate) mod merge;
mod weights;
pub(crate) mod work;

use crate::error::{named_enum, Error, OptionName, Result};
use crate::strip::{is_degenerate, StripSet};
use crate::topology::walks::encode_path;
use crate::topology::DualGraph;
use std::fmt;
use std::str::FromStr;
use std::time::Instant;
use stripkit_matching::{solve, Graph, Objective, UNMATCHED};
use work::WorkMesh;

/// How the single-strip builder weights the dual edges: a heavy edge is one the strip
/// should not cross. Each kind gives weights in `[0, 1]`.
#[derive(Clone, Debug, PartialEq)]
pub enum Weights {
    /// Every edge the same: any perfect matching; loops merged at the fewest changes.
    Uniform,
    /// Back-face culling: 0 inside clusters of nearly parallel normals, more across
    /// clusters whose normals differ more, so the strip stays inside flat regions.
    Cull,
    /// Vertex caching: edges of a randomized breadth-first spanning tree of the mesh
    /// edges (at most one per triangle) weigh 1, the rest 0; the strip winds around the
    /// tree like a space-filling curve.
    Cache,
    /// Direction: edges along the axis weigh most (`|cos|` of their angle to it), so
    /// the strip advances along the axis.
    Direction([f64; 3]),
    /// A linear combination `sum c_k * w_k`.
    Mix(Vec<(f64, Weights)>),
}

impl Weights {
    fn fmt_term(&self, f: &mut fmt::Formatter<'_>, in_mix: bool) -> fmt::Result {
        match self {
            Weights::Uniform => write!(f, "uniform"),
            Weights::Cull => write!(f, "cull"),
            Weights::Cache => write!(f, "cache"),
            Weights::Direction([x, y, z]) if in_mix => write!(f, "direction:{x}:{y}:{z}"),
            Weights::Direction([x, y, z]) => write!(f, "direction:{x},{y},{z}"),
            Weights::Mix(terms) => {
                write!(f, "mix:")?;
                for (i, (c, k)) in terms.iter().enumerate() {
                    if i > 0 {
                        write!(f, ",")?;
                    }
                    k.fmt_term(f, true)?;
                    write!(f, "={c}")?;
                }
                Ok(())
            }
        }
    }
}

impl fmt::Display for Weights {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.fmt_term(f, false)
    }
}

fn parse_axis(s: &str, sep: char) -> Option<[f64; 3]> {
    let v: Vec<f64> = s.split(sep).map(|x| x.trim().parse::<f64>().ok()).collect::<Option<_>>()?;
    let a: [f64; 3] = v.try_into().ok()?;
    (a.iter().all(|x| x.is_finite()) && a.iter().any(|&x| x != 0.0)).then_some(a)
}

impl FromStr for Weights {
    type Err = Error;
    /// `uniform`, `cull`, `cache`, `direction:X,Y,Z`, or `mix:TERM=C,TERM=C,..` where a
    /// term is `uniform`, `cull`, `cache` or `direction:X:Y:Z` and `C` a non-negative
    /// coefficient.
    fn from_str(s: &str) -> Result<Weights> {
        let bad = |why: &str| {
            Error::option(
                OptionName::Weights,
                format!(
                    "'{s}': {why}; expected uniform, cull, cache, direction:X,Y,Z or mix:TERM=C,.. \
                     (e.g. mix:cull=0.5,cache=0.5, direction in a mix as direction:X:Y:Z)"
                ),
            )
        };
        let simple = |t: &str, sep: char| -> Option<Weights> {
            match t {
                "uniform" => Some(Weights::Uniform),
                "cull" => Some(Weights::Cull),
                "cache" => Some(Weights::Cache),
                _ => t.strip_prefix("direction:").and_then(|a| parse_axis(a, sep)).map(Weights::Direction),
            }
        };
        if let Some(rest) = s.strip_prefix("mix:") {
            let mut terms = Vec::new();
            for part in rest.split(',') {
                let (name, c) = part.rsplit_once('=').ok_or_else(|| bad(&format!("term '{part}' has no '=C'")))?;
                let k = simple(name.trim(), ':').ok_or_else(|| bad(&format!("unknown term '{name}'")))?;
                let c: f64 = c.trim().parse().map_err(|_| bad(&format!("coefficient '{c}' is not a number")))?;
                if !(c.is_finite() && c >= 0.0) {
                    return Err(bad(&format!("coefficient {c} is not a finite non-negative number")));
                }
                terms.push((c, k));
            }
            if terms.iter().all(|(c, _)| *c == 0.0) {
                return Err(bad("every coefficient is 0"));
            }
            return Ok(Weights::Mix(terms));
        }
        simple(s.trim(), ',').ok_or_else(|| bad("unknown kind or bad axis (three numbers, not all 0)"))
    }
}

/// Settings of the single-strip builder ([`crate::Algorithm::Single`]).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SingleOptions {
    /// The dual-edge weights. Default [`Weights::Uniform`].
    pub weights: Weights,
    /// Edge swaps are allowed on convex quads whose two triangles' normals differ by
    /// at most this many degrees (0 to 90); `None`: never swap (splits instead).
    /// Default 5 (why: docs/experiments/single-strips.md).
    pub swap_angle: Option<f64>,
    /// Normal deviation bound of the culling clusters, in degrees. Default 30.
    pub cull_angle: f64,
    /// Seed of the randomized parts (the cache weights' tree, the clustering's seeds,
    /// the cull noise). Default 1.
    pub seed: u64,
    /// How the matching is found. Default [`MatchingMode::Auto`].
    pub matching: MatchingMode,
    /// Small seeded noise on the cull weights inside clusters (at most 3 of the
    /// integer weights' 1000), which speeds up the matching (section 6 of the paper).
    /// Default on.
    pub cull_noise: bool,
}

/// How the single-strip builder matches the dual graph.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum MatchingMode {
    /// [`MatchingMode::Exact`] on closed manifold meshes (every triangle has three
    /// neighbours: a perfect matching exists) and on meshes of up to
    /// [`EXACT_MATCHING_NODES`] triangles; [`MatchingMode::Greedy`] otherwise, and for
    /// uniform weights (where every maximum-cardinality matching is a heaviest one).
    #[default]
    Auto,
    /// The maximum-weight matching, proved by its certificate.
    Exact,
    /// Heaviest edges first (greedy), then shortest augmenting paths until the
    /// matching is maximum: every triangle matched as in the exact case, most heavy
    /// edges kept, in about the time of an unweighted matching.
    Greedy,
}

named_enum!(MatchingMode, "matching mode", Auto => "auto", Exact => "exact", Greedy => "greedy");

/// Greedy matchings tried (different tie-breaking orders) on small meshes.
const GREEDY_TRIES: usize = 8;
/// Triangles times tries the greedy matching may spend: 8 tries up to 2^17 triangles.
const GREEDY_TRY_BUDGET: usize = 1 << 20;

/// The most triangles [`MatchingMode::Auto`] matches exactly on a mesh that is not
/// closed.
pub const EXACT_MATCHING_NODES: usize = 1 << 16;

impl Default for SingleOptions {
    fn default() -> Self {
        SingleOptions {
            weights: Weights::Uniform,
            swap_angle: Some(5.0),
            cull_angle: 30.0,
            seed: 1,
            matching: MatchingMode::Auto,
            cull_noise: true,
        }
    }
}

impl SingleOptions {
    /// The default settings with these weights.
    pub fn new(weights: Weights) -> Self {
        SingleOptions { weights, ..Default::default() }
    }
    /// Sets [`SingleOptions::weights`].
    pub fn weights(mut self, weights: Weights) -> Self {
        self.weights = weights;
        self
    }
    /// Sets [`SingleOptions::swap_angle`].
    pub fn swap_angle(mut self, degrees: Option<f64>) -> Self {
        self.swap_angle = degrees;
        self
    }
    /// Sets [`SingleOptions::cull_angle`].
    pub fn cull_angle(mut self, degrees: f64) -> Self {
        self.cull_angle = degrees;
        self
    }
    /// Sets [`SingleOptions::matching`].
    pub fn matching(mut self, mode: MatchingMode) -> Self {
        self.matching = mode;
        self
    }
    /// Sets [`SingleOptions::cull_noise`].
    pub fn cull_noise(mut self, on: bool) -> Self {
        self.cull_noise = on;
        self
    }
    /// Sets [`SingleOptions::seed`].
    pub fn seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }
    pub(crate) fn check(&self) -> Result<()> {
        if let Some(a) = self.swap_angle {
            if !(a.is_finite() && (0.0..90.0).contains(&a)) {
                return Err(Error::option(OptionName::SwapAngle, format!("{a} is not in 0..90 degrees")));
            }
        }
        if !(self.cull_angle.is_finite() && self.cull_angle > 0.0 && self.cull_angle < 180.0) {
            return Err(Error::option(
                OptionName::CullAngle,
                format!("{} is not in (0, 180) degrees", self.cull_angle),
            ));
        }
        Ok(())
    }
}

/// What the single-strip builder reports beside the strips.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub struct SingleReport {
    /// Steiner vertices added (one per edge split, cull peaks included).
    pub steiner_vertices: usize,
    /// Cull weights: clusters of nearly parallel normals (0 for other weights).
    pub clusters: usize,
    /// Cull weights: cluster peaks split (one Steiner vertex each).
    pub cull_peaks: usize,
    /// Cull weights (alone, not in a mix): dual edges between clusters, after the
    /// peak splits and merging (halves of a split boundary edge count twice).
    pub boundary_edges: usize,
    /// Of those, the ones the strip crosses (strip links).
    pub boundary_crossings: usize,
    /// Edges swapped.
    pub swapped_edges: usize,
    /// Pieces (loops and paths) the matching left, before merging.
    pub initial_pieces: usize,
    /// Of those, paths.
    pub initial_paths: usize,
    /// Merge operations applied: nodal vertices, path joins, attaches.
    pub nodal: usize,
    /// Path ends joined.
    pub joins: usize,
    /// Loops opened onto a path end.
    pub attaches: usize,
    /// Merge passes run.
    pub passes: usize,
    /// Whether the matching was perfect on the degree-3 triangles.
    pub perfect_matching: bool,
    /// Path ends every strip set of the input mesh has at least, from the matching: a
    /// triangle with three dual neighbours needs one of them off its strip, so
    /// `sum(2 - degree) + 2 (full - matched edges)` over the triangles, where `full` counts
    /// those with three neighbours. Strips without mesh changes are at least half of
    /// it (and at least one per component); splits do not lower it.
    pub forced_ends: usize,
    /// Total matched weight (integer weights, scaled by 1000).
    pub matched_weight: i64,
    /// Connected components of the changed mesh's dual graph (the fewest strips
    /// possible).
    pub components: usize,
    /// Components that are closed (every triangle has three dual neighbours).
    pub closed_components: usize,
    /// Connected surfaces when vertices at the same position count as one (seams
    /// closed); [`SingleReport::components`] exceeds it where seams split vertices,
    /// and no strip crosses a seam.
    pub surfaces: usize,
    /// UV islands: surfaces cut along every edge whose `TEXCOORD_0` differs on its two
    /// sides (`None` without texture coordinates).
    pub uv_islands: Option<usize>,
    /// Triangles the changed mesh has beyond the input's (two per interior edge
    /// split, one per boundary edge split; swaps add none).
    pub triangles_added: usize,
    /// Vertices added (the Steiner vertices).
    pub vertices_added: usize,
    /// Strips made.
    pub strips: usize,
    /// Largest distance between the two diagonals of a swapped quad (0 for a planar
    /// quad), in model units.
    pub max_swap_deviation: f64,
    /// Milliseconds of the weights (cull: clustering included).
    pub weights_ms: f64,
    /// Milliseconds of the matching.
    pub matching_ms: f64,
    /// Milliseconds of merging and encoding.
    pub merge_ms: f64,
}

/// The output of [`single_strips`]: the strips over the changed mesh.
#[derive(Clone, Debug)]
pub(crate) struct Single {
    pub strips: StripSet,
    pub work: WorkMesh,
    pub report: SingleReport,
}

/// Integer weights for the matching: `round(1000 w)`.
pub(crate) const WEIGHT_SCALE: f64 = 1000.0;

/// Single strips for the triangles `tris` over `positions` (see the module docs).
pub(crate) fn single_strips(positions: &[[f32; 3]], tris: Vec<[u32; 3]>, options: &SingleOptions) -> Result<Single> {
    options.check()?;
    let mut report = SingleReport::default();
    let clock = Instant::now();
    let mut w = WorkMesh::new(positions, tris);
    let cull = weights::assign(
        &mut w,
        &options.weights,
        options.seed,
        options.cull_angle.to_radians(),
        options.cull_noise,
    );
    report.clusters = cull.clusters;
    report.cull_peaks = cull.peaks;
    report.weights_ms = ms(clock);

    let clock = Instant::now();
    let (perfect, matched_weight, forced_ends) = match_links(&mut w, options.matching)?;
    report.forced_ends = forced_ends;
    report.perfect_matching = perfect;
    report.matched_weight = matched_weight;
    report.matching_ms = ms(clock);

    let clock = Instant::now();
    let settings = merge::MergeSettings { swap_angle: options.swap_angle.map(f64::to_radians) };
    let stats = merge::merge(&mut w, &settings);
    report.initial_pieces = stats.initial_pieces;
    report.initial_paths = stats.initial_paths;
    report.nodal = stats.nodal;
    report.joins = stats.joins;
    report.attaches = stats.attaches;
    report.passes = stats.passes;
    report.steiner_vertices = w.steiner.len();
    report.swapped_edges = w.swaps.len();
    if options.weights == Weights::Cull {
        (report.boundary_edges, report.boundary_crossings) = boundary_crossings(&w);
    }

    let dual = DualGraph { neighbors: w.nbr.clone() };
    let mut strips = StripSet::new();
    merge::for_each_piece(&w, |_, _, walk| {
        let drawn: Vec<u32> = walk.iter().copied().filter(|&t| !is_degenerate(&w.tris[t as usize])).collect();
        if !drawn.is_empty() {
            encode_path(&w.tris, &dual, &drawn, &mut strips);
        }
    });
    report.strips = strips.len();
    let (components, closed) = components(&w);
    report.components = components;
    report.closed_components = closed;
    report.max_swap_deviation = check::max_swap_deviation(&w);
    report.merge_ms = ms(clock);
    Ok(Single { strips, work: w, report })
}

/// Dual edges whose weight marks a cluster boundary, and how many are strip links.
fn boundary_crossings(w: &WorkMesh) -> (usize, usize) {
    let (mut edges, mut crossed) = (0, 0);
    for t in 0..w.len() {
        for j in 0..3 {
            let u = w.nbr[t][j];
            if u != crate::topology::NO_NEIGHBOR && (t as u32) < u && w.weight[t][j] >= cull::FLOOR {
                edges += 1;
                crossed += w.linked(t, j) as usize;
            }
        }
    }
    (edges, crossed)
}

fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}

/// Components of the dual graph of non-degenerate triangles, and how many are closed.
fn components(w: &WorkMesh) -> (usize, usize) {
    let n = w.len();
    let mut seen = vec![false; n];
    let mut stack = Vec::new();
    let (mut count, mut closed) = (0, 0);
    for s in 0..n {
        if seen[s] || is_degenerate(&w.tris[s]) {
            continue;
        }
        count += 1;
        let mut all3 = true;
        seen[s] = true;
        stack.push(s);
        while let Some(t) = stack.pop() {
            all3 &= w.dual_degree(t) == 3;
            for &u in &w.nbr[t] {
                if u != crate::topology::NO_NEIGHBOR && !seen[u as usize] {
                    seen[u as usize] = true;
                    stack.push(u as usize);
                }
            }
        }
        closed += all3 as usize;
    }
    (count, closed)
}

/// Links from a maximum-weight matching of the degree-3 triangles: every dual edge is
/// a link unless matched; a degree-3 triangle left unmatched drops its heaviest link.
/// Returns whether the matching was perfect, its weight, and the ends it forces (see
/// [`SingleReport::forced_ends`]).
fn match_links(w: &mut WorkMesh, mode: MatchingMode) -> Result<(bool, i64, usize)> {
    let n = w.len();
    let full: Vec<bool> = (0..n).map(|t| w.dual_degree(t) == 3 && !is_degenerate(&w.tris[t])).collect();
    let mut id = vec![u32::MAX; n];
    let mut nodes = 0u32;
    for t in 0..n {
        if full[t] {
            id[t] = nodes;
            nodes += 1;
        }
    }
    let mut ends = Vec::with_capacity(nodes as usize * 3 / 2);
    let mut ws = Vec::with_capacity(nodes as usize * 3 / 2);
    let mut slot_of_edge = Vec::with_capacity(nodes as usize * 3 / 2);
    let mut mesh_edge: Vec<(u32, u32)> = Vec::with_capacity(nodes as usize * 3 / 2);
    for t in 0..n {
        for j in 0..3 {
            let u = w.nbr[t][j];
            if u != crate::topology::NO_NEIGHBOR && (t as u32) < u && full[t] && full[u as usize] {
                ends.push([id[t], id[u as usize]]);
                ws.push((w.weight[t][j] * WEIGHT_SCALE).round().max(0.0) as i64);
                slot_of_edge.push((t as u32, j as u8));
                mesh_edge.push(work::edge(&w.tris[t], j));
            }
        }
    }
    // Every dual edge starts as a link; matched ones are cut.
    for t in 0..n {
        for j in 0..3 {
            if w.nbr[t][j] != crate::topology::NO_NEIGHBOR {
                w.link[t] |= 1 << j;
            }
        }
    }
    // A cover by paths and loops has sum(2 - d) + 2 |off| ends, and the links off the
    // strips cover every full triangle: at least full - (matched edges) of them.
    let base: i64 = (0..n).filter(|&t| !is_degenerate(&w.tris[t])).map(|t| 2 - w.dual_degree(t) as i64).sum();
    if nodes == 0 {
        return Ok((true, 0, base.max(0) as usize));
    }
    // Equal weights: every maximum-cardinality matching is a heaviest one, and the
    // greedy one leaves fewer loops.
    let uniform = ws.iter().all(|&x| x == ws[0]);
    let g = Graph::new(nodes as usize, ends, ws)?;
    let exact = match mode {
        MatchingMode::Exact => true,
        MatchingMode::Greedy => false,
        // Without a perfect matching the engine solves a larger auxiliary problem,
        // seconds where a closed mesh takes a fraction (bunny Loop x1, cache
        // weights: 17.8 s against 3.3 s for the closed 1.55M Loop x2 horse).
        MatchingMode::Auto => !uniform && (nodes as usize == n || (nodes as usize) <= EXACT_MATCHING_NODES),
    };
    let apply = |w: &mut WorkMesh, m: &Found| {
        for &e in &m.edges {
            let (t, j) = slot_of_edge[e as usize];
            w.set_link(t as usize, j as usize, false);
        }
        if !m.perfect {
            for t in 0..n {
                if full[t] && m.mate[id[t] as usize] == UNMATCHED && w.degree(t) == 3 {
                    let j = (0..3).max_by(|&a, &b| w.weight[t][a].total_cmp(&w.weight[t][b])).expect("three slots");
                    w.set_link(t, j, false);
                }
            }
        }
    };
    let m = if exact {
        let m = solve(&g, Objective::MaxWeight)?;
        Found { perfect: m.perfect, mate: m.mate, edges: m.edges, total_weight: m.total_weight }
    } else {
        // Several tie-breaking orders on smaller meshes; the one leaving the fewest
        // pieces is kept (fewer merges, fewer Steiner vertices).
        let tries = (GREEDY_TRY_BUDGET / nodes as usize).clamp(1, GREEDY_TRIES);
        let all_on = w.link.clone();
        let mut best: Option<(usize, Found)> = None;
        for k in 0..tries {
            let m = greedy_matching(&g, k as u64, &mesh_edge, w.pos.len());
            w.link.copy_from_slice(&all_on);
            apply(w, &m);
            let pieces = merge::pieces(w).is_path.len();
            if best.as_ref().is_none_or(|(p, b)| (m.total_weight, std::cmp::Reverse(pieces)) > (b.total_weight, std::cmp::Reverse(*p))) {
                best = Some((pieces, m));
            }
        }
        w.link.copy_from_slice(&all_on);
        best.expect("at least one try").1
    };
    apply(w, &m);
    let forced = base + 2 * (nodes as i64 - m.edges.len() as i64);
    Ok((m.perfect, m.total_weight, forced.max(0) as usize))
}

/// [`MatchingMode::Greedy`]: edges by weight, heaviest first, taken where both ends
/// are free and the mesh edge closes no cycle among the mesh edges taken; then
/// shortest augmenting paths to a maximum-cardinality matching.
///
/// The matched mesh edges are what the strip does not cross, its "medial axis"; on a
/// closed genus-0 mesh a perfect matching whose edges form no cycle leaves exactly one
/// loop (its edges are a spanning forest of two trees, and the strip runs around
/// them), and every cycle they form adds loops. So the greedy pass keeps them a forest.
fn greedy_matching(g: &Graph, order_seed: u64, mesh_edge: &[(u32, u32)], vertices: usize) -> Found {
    let n = g.node_count();
    let mut order: Vec<u32> = (0..g.edge_count() as u32).collect();
    let ws = g.weights();
    // Ties in a seeded order (seed 0: edge order).
    let tie = |e: u32| if order_seed == 0 { e as u64 } else { crate::matching::splitmix(&mut (e as u64 ^ order_seed.wrapping_mul(0x9E37_79B9_7F4A_7C15))) };
    order.sort_by_key(|&e| (std::cmp::Reverse(ws[e as usize]), tie(e)));
    let mut mate = vec![UNMATCHED; n];
    let mut forest = crate::topology::UnionFind::new(vertices);
    for e in order {
        let [a, b] = g.edges()[e as usize];
        if a != b && mate[a as usize] == UNMATCHED && mate[b as usize] == UNMATCHED {
            let (p, q) = mesh_edge[e as usize];
            if !forest.union(p, q) {
                continue;
            }
            mate[a as usize] = b;
            mate[b as usize] = a;
        }
    }
    let mate = stripkit_matching::maximum_cardinality_matching_from(g, &mate);
    // Edge ids of the pairs: the heaviest edge between each pair.
    let mut edges = Vec::with_capacity(n / 2);
    let mut total = 0;
    for (v, &u) in mate.iter().enumerate() {
        if u != UNMATCHED && (v as u32) < u {
            let e = g
                .adjacency(v)
                .iter()
                .copied()
                .filter(|&e| {
                    let [a, b] = g.edges()[e as usize];
                    (a == u) || (b == u)
                })
                .max_by_key(|&e| ws[e as usize])
                .expect("partners are neighbours");
            total += ws[e as usize];
            edges.push(e);
        }
    }
    edges.sort_unstable();
    Found { perfect: edges.len() * 2 == n, mate, edges, total_weight: total }
}

/// A matching: whether perfect, partners, edge ids, weight.
struct Found {
    perfect: bool,
    mate: Vec<u32>,
    edges: Vec<u32>,
    total_weight: i64,
}

#[cfg(test)]
mod tests;

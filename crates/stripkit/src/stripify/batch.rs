//! Batch strips: strips planned for a GPU that shades the vertices of a draw in
//! batches ([`BatchModel`]): a batch holds a fixed number of triangles, a strip vertex
//! is reused only while it is among the last few vertices the batch shaded, and
//! nothing is reused from one batch to the next.
//!
//! Under such a model the cost of a batch is the number of distinct vertices of the
//! triangles it draws (when every reuse falls inside the window), so the stripifier
//! cuts the mesh into compact *patches* of one batch of triangles each and covers
//! each patch with short swap-free strips laid side by side, every choice scored by
//! simulating the model exactly ([`StripBatches`], the rule that measures it):
//!
//! 1. **Seeds.** The triangle across the exit edge of the running strip when it is
//!    free (the strip may go on into the new batch: no restart, and the two vertices
//!    the batch shades again are its first triangle's anyway), and up to [`SEEDS`]
//!    free triangles around the vertices of the last patch: first those with two
//!    vertices still in the reuse window (a strip started on that edge costs the
//!    old batch nothing), then those with the fewest free neighbours (the patches
//!    hug the covered region). The first free triangle in input order when there are
//!    none.
//! 2. **Growth.** From each seed a patch grows, one triangle at a time up to the
//!    batch's free triangle slots, by the free triangle across one of its edges that
//!    adds the fewest vertices, then has the fewest free neighbours outside the
//!    patch, then lies nearest the patch's centroid (a round patch: about 24
//!    vertices for 30 triangles, against 32 for one strip of 30); when no triangle
//!    is across its edges, by one around its vertices.
//! 3. **Strips.** Each patch is covered by lines (strips without swaps: a swap takes
//!    a triangle slot of the batch) under four strategies ([`Strategy::ALL`]): the
//!    next line is, among the lines from every free patch triangle through each of
//!    its three exits and the running strip's going on, the prefix with the fewest
//!    shaded vertices per triangle (or only lines at the oldest shaded vertex with
//!    free triangles left, or another index weight, or the fewest shaded vertices
//!    less 0.9 per triangle). The plan that shades the fewest vertices is kept.
//! 4. **Choice.** The patch (and plan) with the fewest shaded vertices per triangle,
//!    each pocket it leaves (see [`POCKET_WEIGHT`]) counted, is emitted.
//!
//! Strips are separated by restarts (a restart takes no triangle slot). Time: about
//! `T * SEEDS * 4 * P * L` simulated indices for patches of P triangles and lines of
//! L triangles: seconds on the 100k-triangle models (about 100 times `cache`).

use crate::metrics::{BatchModel, StripBatches};
use crate::strip::{is_degenerate, StripSet};
use crate::stripify::cache::FAN_CANDIDATES;
use crate::topology::{vertex_triangles, Csr, DualGraph, FreeCursor, NO_NEIGHBOR};

/// What one index costs, in shaded vertices, when choosing among lines: a small
/// preference for fewer strips at equal shading.
pub const INDEX_WEIGHT: f64 = 0.05;

/// Seeds tried per patch besides going on from the running strip (each patch grown
/// and planned: the time grows with it). On the shared models 1 seed left bunny 1.1%
/// above meshoptimizer's list, 3 seeds 0.7% below, 6 seeds 1.5% below.
pub const SEEDS: usize = 6;

/// What each free triangle a patch leaves with at most one free neighbour costs, in
/// shaded vertices, when patches are compared: such pockets end up in small patches
/// that shade about one vertex per triangle.
pub const POCKET_WEIGHT: f64 = 1.0;

/// Strips of `tris` (indices below `vertex_count`) planned for `model`: every
/// non-degenerate triangle once, with its winding; degenerate ones dropped.
pub fn stripify(tris: &[[u32; 3]], positions: &[[f32; 3]], vertex_count: usize, model: &BatchModel) -> StripSet {
    let graph = DualGraph::from_triangles(tris, vertex_count);
    let vt = vertex_triangles(tris, vertex_count);
    let n = tris.len();
    let mut s = Planner {
        tris,
        positions,
        graph: &graph,
        taken: tris.iter().map(is_degenerate).collect(),
        left: tris.iter().filter(|t| !is_degenerate(t)).count(),
        patch_mark: vec![u32::MAX; n],
        epoch: 0,
        sim: StripBatches::new(*model),
        model: *model,
        out: StripSet::new(),
        cur: Vec::new(),
        end: None,
        recent: Vec::new(),
        scan: 0,
        free: FreeCursor::new(vt.values().len()),
        around: Vec::new(),
    };
    while s.left > 0 {
        let slots = if s.sim.tris >= model.max_triangles {
            model.max_triangles
        } else {
            model.max_triangles - s.sim.tris
        };
        // A patch from every seed, each planned; the cheapest per triangle is emitted.
        let mut best: Option<(f64, Vec<u32>, Vec<Choice>)> = None;
        for seed in s.seeds(&vt) {
            let patch = s.grow(seed, slots, &vt);
            let (cost, plan) = s.best_plan(&patch);
            let score = (cost as f64 + POCKET_WEIGHT * s.isolated(&patch) as f64) / patch.len() as f64;
            if best.as_ref().is_none_or(|(b, ..)| score < *b) {
                best = Some((score, patch, plan));
            }
        }
        let (_, patch, plan) = best.expect("a free triangle gives a seed");
        for choice in &plan {
            s.apply(choice);
        }
        s.recent.clear();
        for &t in &patch {
            s.recent.extend_from_slice(&tris[t as usize]);
        }
    }
    if s.cur.len() >= 3 {
        s.out.push(&s.cur);
    }
    s.out
}

struct Planner<'a> {
    tris: &'a [[u32; 3]],
    positions: &'a [[f32; 3]],
    graph: &'a DualGraph,
    taken: Vec<bool>,
    left: usize,
    /// `epoch` for triangles of the current patch.
    patch_mark: Vec<u32>,
    epoch: u32,
    sim: StripBatches,
    model: BatchModel,
    out: StripSet,
    /// The running strip, and its last triangle with the exit edge `(a, b)`.
    cur: Vec<u32>,
    end: Option<(u32, u32, u32)>,
    /// Vertices of the last patch.
    recent: Vec<u32>,
    /// Every triangle before it is taken.
    scan: usize,
    /// The free triangles around a vertex without rescanning its taken ones, so that
    /// a vertex in thousands of triangles costs no more per batch than any other.
    free: FreeCursor,
    /// Scratch: free triangles around one vertex.
    around: Vec<u32>,
}

impl Planner<'_> {
    /// The slot of `t`'s edge `{a, b}`.
    fn slot(&self, t: u32, a: u32, b: u32) -> Option<usize> {
        let v = self.tris[t as usize];
        (0..3).find(|&k| {
            let (x, y) = (v[k], v[(k + 1) % 3]);
            (x == a && y == b) || (x == b && y == a)
        })
    }

    /// The triangle across `t`'s edge `{a, b}`.
    fn across(&self, t: u32, a: u32, b: u32) -> u32 {
        match self.slot(t, a, b) {
            Some(k) => self.graph.neighbors[t as usize][k],
            None => NO_NEIGHBOR,
        }
    }

    fn free(&self, t: u32) -> bool {
        t != NO_NEIGHBOR && !self.taken[t as usize]
    }

    /// Free triangles outside the current patch, next to it, that it leaves with at
    /// most one free neighbour (the start of a pocket).
    fn isolated(&self, patch: &[u32]) -> usize {
        let e = self.epoch;
        let mut n = 0;
        for &t in patch {
            for &m in &self.graph.neighbors[t as usize] {
                if self.free(m) && self.patch_mark[m as usize] != e {
                    let deg = self.graph.neighbors[m as usize]
                        .iter()
                        .filter(|&&x| self.free(x) && self.patch_mark[x as usize] != e)
                        .count();
                    n += usize::from(deg <= 1);
                }
            }
        }
        n
    }

    fn free_degree(&self, t: u32) -> usize {
        self.graph.neighbors[t as usize].iter().filter(|&&m| self.free(m)).count()
    }

    /// The seeds of the next patch (see the module docs): at most [`SEEDS`] and the
    /// triangle across the running strip's exit.
    fn seeds(&mut self, vt: &Csr<u32>) -> Vec<u32> {
        let mut out = Vec::new();
        if let Some((t, a, b)) = self.end {
            let m = self.across(t, a, b);
            if self.free(m) {
                out.push(m);
            }
        }
        let mut keys: Vec<((usize, usize), u32)> = Vec::new();
        for i in 0..self.recent.len() {
            self.free_around(vt, self.recent[i], FAN_CANDIDATES as usize);
            for &t in &self.around {
                {
                    let tri = self.tris[t as usize];
                    let cached = tri.iter().filter(|&&x| self.sim.reused(x)).count();
                    let edge_cached = usize::from(cached >= 2);
                    keys.push(((1 - edge_cached, self.free_degree(t)), t));
                }
            }
        }
        keys.sort_unstable();
        keys.dedup();
        for (_, t) in keys {
            if out.len() >= SEEDS {
                break;
            }
            if !out.contains(&t) {
                out.push(t);
            }
        }
        if out.is_empty() {
            while self.taken[self.scan] {
                self.scan += 1;
            }
            out.push(self.scan as u32);
        }
        out
    }

    /// A patch of up to `slots` free triangles grown from `seed` (see the module docs),
    /// marked as the current patch.
    fn grow(&mut self, seed: u32, slots: usize, vt: &Csr<u32>) -> Vec<u32> {
        self.epoch += 1;
        let e = self.epoch;
        let mut patch = vec![seed];
        self.patch_mark[seed as usize] = e;
        let mut verts: Vec<u32> = self.tris[seed as usize].to_vec();
        let centroid = |t: u32| {
            let mut c = [0f32; 3];
            for &v in &self.tris[t as usize] {
                let p = self.positions.get(v as usize).copied().unwrap_or_default();
                for k in 0..3 {
                    c[k] += p[k] / 3.0;
                }
            }
            c
        };
        let mut sum = centroid(seed);
        while patch.len() < slots {
            // (new vertices, free neighbours outside the patch, distance to its centre)
            let mut best: Option<((usize, usize, f32), u32)> = None;
            let n = patch.len() as f32;
            let mid = sum.map(|x| x / n);
            for &p in &patch {
                for &m in &self.graph.neighbors[p as usize] {
                    if !self.free(m) || self.patch_mark[m as usize] == e {
                        continue;
                    }
                    let new = self.tris[m as usize].iter().filter(|v| !verts.contains(v)).count();
                    let outside = self.graph.neighbors[m as usize]
                        .iter()
                        .filter(|&&x| self.free(x) && self.patch_mark[x as usize] != e)
                        .count();
                    let c = centroid(m);
                    let d2: f32 = (0..3).map(|k| (c[k] - mid[k]) * (c[k] - mid[k])).sum();
                    let key = (new, outside, d2);
                    if best.is_none_or(|(b, _)| key < b) {
                        best = Some((key, m));
                    }
                }
            }
            if best.is_none() {
                // No free triangle across the patch's edges: one around its vertices.
                for &v in &verts {
                    // The patch's own triangles are free too: look past them.
                    self.free_around(vt, v, FAN_CANDIDATES as usize + patch.len());
                    for &m in &self.around {
                        if self.patch_mark[m as usize] == e {
                            continue;
                        }
                        let new = self.tris[m as usize].iter().filter(|v| !verts.contains(v)).count();
                        let c = centroid(m);
                        let d2: f32 = (0..3).map(|k| (c[k] - mid[k]) * (c[k] - mid[k])).sum();
                        let key = (new, self.free_degree(m), d2);
                        if best.is_none_or(|(b, _)| key < b) {
                            best = Some((key, m));
                        }
                    }
                }
            }
            let Some(((new, ..), m)) = best else { break };
            if verts.len() + new > self.model.max_vertices {
                break;
            }
            self.patch_mark[m as usize] = e;
            patch.push(m);
            let c = centroid(m);
            for k in 0..3 {
                sum[k] += c[k];
            }
            for &v in &self.tris[m as usize] {
                if !verts.contains(&v) {
                    verts.push(v);
                }
            }
        }
        patch
    }

    /// At most `limit` free triangles around `v`, in `around`.
    fn free_around(&mut self, vt: &Csr<u32>, v: u32, limit: usize) {
        self.around.clear();
        let taken = &self.taken;
        self.free.free_in(vt, v as usize, limit, |t| taken[t as usize], &mut self.around);
    }

    /// A free triangle of the current patch not yet used by the plan.
    fn open(&self, t: u32, used: &[u32]) -> bool {
        t != NO_NEIGHBOR && self.patch_mark[t as usize] == self.epoch && !self.taken[t as usize] && !used.contains(&t)
    }

    /// Covers the patch with lines: every strategy of [`Strategy::ALL`] plans it on a
    /// copy of the simulation, the plan that shades the fewest vertices is emitted.
    fn best_plan(&self, patch: &[u32]) -> (u64, Vec<Choice>) {
        let mut best: Option<(u64, Vec<Choice>)> = None;
        for strategy in Strategy::ALL {
            let (cost, plan) = self.plan(patch, strategy);
            if best.as_ref().is_none_or(|(b, _)| cost < *b) {
                best = Some((cost, plan));
            }
        }
        best.unwrap_or_default()
    }

    /// Emits one line: into the simulation, the running strip and the taken marks.
    fn apply(&mut self, choice: &Choice) {
        let (mut t, mut a, mut b) = match choice.start {
            None => self.end.expect("going on needs a running strip"),
            Some((t0, rot)) => {
                if self.cur.len() >= 3 {
                    self.out.push(&self.cur);
                }
                self.cur.clear();
                let [x, u, w] = rotation(self.tris[t0 as usize], rot);
                self.sim.restart();
                for i in [x, u, w] {
                    self.sim.push(i);
                    self.cur.push(i);
                }
                self.take(t0);
                (t0, u, w)
            }
        };
        let skip = usize::from(choice.start.is_some());
        for &m in &choice.path[skip..] {
            debug_assert_eq!(m, self.across(t, a, b));
            let c = opposite(self.tris[m as usize], a, b);
            self.sim.push(c);
            self.cur.push(c);
            self.take(m);
            (t, a, b) = (m, b, c);
        }
        self.end = Some((t, a, b));
    }

    /// Walks a line on from triangle `t` across its exit edge `(a, b)`, through triangles
    /// of the patch that are open and not on `path` yet: each step's new vertex goes to
    /// `sim`, its triangle to `path`, and `step` sees the line so far.
    fn walk_line(
        &self,
        (mut t, mut a, mut b): (u32, u32, u32),
        used: &[u32],
        sim: &mut StripBatches,
        path: &mut Vec<u32>,
        mut step: impl FnMut(&StripBatches, &[u32]),
    ) {
        loop {
            let m = self.across(t, a, b);
            if !self.open(m, used) || path.contains(&m) {
                break;
            }
            let c = opposite(self.tris[m as usize], a, b);
            sim.push(c);
            path.push(m);
            step(sim, path);
            (t, a, b) = (m, b, c);
        }
    }

    /// One plan for the patch under `strategy`: the vertices it shades and its lines.
    fn plan(&self, patch: &[u32], strategy: Strategy) -> (u64, Vec<Choice>) {
        let mut sim = self.sim.clone();
        let start_total = sim.total;
        let mut end = self.end;
        let mut used: Vec<u32> = Vec::with_capacity(patch.len());
        let mut plan = Vec::new();
        let mut scratch = sim.clone();
        let mut path: Vec<u32> = Vec::new();
        // Shading order of the patch's vertices in this plan (for `Oldest`).
        let mut order: Vec<u32> = Vec::new();
        let patch_free = patch.iter().filter(|&&t| self.open(t, &[])).count();
        while used.len() < patch_free {
            let mut best: Option<((f64, i64), Choice)> = None;
            let consider = |best: &mut Option<((f64, i64), Choice)>, start, cost: f64, path: &[u32]| {
                let k = path.len();
                let key = match strategy {
                    Strategy::Ratio(_) | Strategy::Oldest => (cost / k as f64, -(k as i64)),
                    Strategy::Marginal(w) => (cost - w * k as f64, -(k as i64)),
                };
                if best.as_ref().is_none_or(|(b, _)| key < *b) {
                    *best = Some((key, Choice { start, path: path.to_vec() }));
                }
            };
            let iw = match strategy {
                Strategy::Ratio(w) => w,
                _ => INDEX_WEIGHT,
            };
            // Going on from the running strip.
            if let Some((t, a, b)) = end {
                scratch.clone_from(&sim);
                let base = scratch.total;
                path.clear();
                self.walk_line((t, a, b), &used, &mut scratch, &mut path, |sim, path| {
                    consider(&mut best, None, (sim.total - base) as f64 + iw * path.len() as f64, path);
                });
            }
            // Under `Oldest`, new lines start only at triangles of the oldest shaded
            // vertex that still has open triangles in the patch.
            let oldest = match strategy {
                Strategy::Oldest => order.iter().copied().find(|&v| {
                    patch.iter().any(|&t| self.open(t, &used) && self.tris[t as usize].contains(&v))
                }),
                _ => None,
            };
            for &t0 in patch {
                if !self.open(t0, &used) {
                    continue;
                }
                if let Some(v) = oldest {
                    if !self.tris[t0 as usize].contains(&v) {
                        continue;
                    }
                }
                for rot in 0..3 {
                    let [x, u, w] = rotation(self.tris[t0 as usize], rot);
                    scratch.clone_from(&sim);
                    let base = scratch.total;
                    scratch.restart();
                    for i in [x, u, w] {
                        scratch.push(i);
                    }
                    path.clear();
                    path.push(t0);
                    // A new line costs its three indices, the restart and one per triangle after the first.
                    let cost = |sim: &StripBatches, path: &[u32]| (sim.total - base) as f64 + iw * (path.len() + 3) as f64;
                    consider(&mut best, Some((t0, rot)), cost(&scratch, &path), &path);
                    self.walk_line((t0, u, w), &used, &mut scratch, &mut path, |sim, path| {
                        consider(&mut best, Some((t0, rot)), cost(sim, path), path);
                    });
                }
            }
            let Some((_, choice)) = best else { break };
            // Replay the choice on the plan's simulation.
            let mut feed = |sim: &mut StripBatches, v: u32| {
                let before = sim.total;
                sim.push(v);
                if sim.total > before && !order.contains(&v) {
                    order.push(v);
                }
            };
            let (mut t, mut a, mut b) = match choice.start {
                None => end.expect("going on needs a running strip"),
                Some((t0, rot)) => {
                    let [x, u, w] = rotation(self.tris[t0 as usize], rot);
                    sim.restart();
                    for i in [x, u, w] {
                        feed(&mut sim, i);
                    }
                    used.push(t0);
                    (t0, u, w)
                }
            };
            let skip = usize::from(choice.start.is_some());
            for &m in &choice.path[skip..] {
                let c = opposite(self.tris[m as usize], a, b);
                feed(&mut sim, c);
                used.push(m);
                (t, a, b) = (m, b, c);
            }
            end = Some((t, a, b));
            plan.push(choice);
        }
        (sim.total - start_total, plan)
    }

    fn take(&mut self, t: u32) {
        self.taken[t as usize] = true;
        self.left -= 1;
    }
}

/// How [`Planner::plan`] picks the next line of a patch.
#[derive(Clone, Copy, Debug)]
enum Strategy {
    /// Fewest shaded vertices per triangle, an index weighing this many vertices.
    Ratio(f64),
    /// As `Ratio(INDEX_WEIGHT)`, new lines only at the oldest shaded vertex with open
    /// triangles (a sweep that reads its vertices before they leave the window).
    Oldest,
    /// Fewest shaded vertices less this many per triangle (longer lines).
    Marginal(f64),
}

impl Strategy {
    const ALL: [Strategy; 4] = [Strategy::Ratio(INDEX_WEIGHT), Strategy::Oldest, Strategy::Ratio(0.3), Strategy::Marginal(0.9)];
}

/// One line of a plan: a new strip at `(triangle, rotation)` or going on from the
/// running strip (`None`), through the triangles of `path` (the first one included).
struct Choice {
    start: Option<(u32, usize)>,
    path: Vec<u32>,
}

/// `tri` read from corner `rot`: a strip's first three indices.
fn rotation(tri: [u32; 3], rot: usize) -> [u32; 3] {
    [tri[rot], tri[(rot + 1) % 3], tri[(rot + 2) % 3]]
}

/// The vertex of `tri` other than `a` and `b`.
fn opposite(tri: [u32; 3], a: u32, b: u32) -> u32 {
    tri.into_iter().find(|&v| v != a && v != b).unwrap_or(tri[0])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strip::{encode_restart, verify};
    use crate::{gen, stripify as door, Algorithm, Split, StripOptions};

    const H100: BatchModel = BatchModel::NVIDIA_H100;

    fn check(mesh: &crate::Mesh) -> StripSet {
        let tris = mesh.triangulate().tris;
        let strips = stripify(&tris, &mesh.positions, mesh.vertex_count(), &H100);
        assert!(verify(&tris, &strips).ok());
        // Lines only: no strip repeats an index within a window.
        for s in strips.iter() {
            for w in s.windows(3) {
                assert!(!is_degenerate(&[w[0], w[1], w[2]]), "a swap in {s:?}");
            }
        }
        strips
    }

    #[test]
    fn procedural_meshes_verify() {
        check(&gen::icosphere(3));
        check(&gen::torus(24, 12, 2.0, 0.5));
        check(&gen::grid(17, 9));
        check(&gen::cube());
        check(&gen::disjoint_union(&[&gen::icosphere(1), &gen::grid(3, 2), &gen::cube()]));
        check(&gen::shuffle_faces(&gen::icosphere(2), 7));
        // Degenerate triangles are dropped, an empty input gives no strips.
        let tris = [[0, 1, 2], [2, 1, 3], [1, 1, 2], [4, 4, 4]];
        let strips = stripify(&tris, &[], 5, &H100);
        assert!(verify(&tris, &strips).ok());
        assert!(stripify(&[], &[], 0, &H100).is_empty());
    }

    #[test]
    fn other_models_verify() {
        // A narrow window and small batches: still every triangle once.
        let mesh = gen::torus(20, 10, 2.0, 0.5);
        let tris = mesh.triangulate().tris;
        for model in [
            BatchModel { max_triangles: 7, max_vertices: 9, strip_window: 4, strip_fifo: true, restart_window: 2 },
            BatchModel { max_triangles: 1, max_vertices: 3, strip_window: 1, strip_fifo: false, restart_window: 1 },
            BatchModel { max_triangles: 96, max_vertices: 96, strip_window: 32, strip_fifo: true, restart_window: 40 },
        ] {
            let strips = stripify(&tris, &mesh.positions, mesh.vertex_count(), &model);
            assert!(verify(&tris, &strips).ok(), "{model:?}");
        }
    }

    /// Shaded vertices per triangle of strips, under the model the door plans for.
    fn per_triangle(strips: &StripSet, triangles: usize) -> f64 {
        BatchModel::NVIDIA_H100_PLANNING.strip_invocations(&encode_restart(strips, u32::MAX), u32::MAX) as f64 / triangles as f64
    }

    #[test]
    fn fewer_shaded_vertices_than_cache_strips_on_a_sphere_and_a_torus() {
        // Batch patches against the best cache mode under the model (a FIFO of 8) and
        // against one vertex per triangle; through the door, verified.
        for mesh in [gen::icosphere(4), gen::torus(64, 24, 2.0, 0.5)] {
            let t = mesh.triangle_count();
            let batch = door(&mesh, &StripOptions::default().algorithm(Algorithm::batch())).expect("batch");
            assert!(batch.figures.verified);
            assert_eq!(batch.algorithm.name(), "batch");
            let cache = door(&mesh, &StripOptions::default().algorithm(Algorithm::cache()).cache_size(8)).expect("cache");
            let (b, c) = (per_triangle(&batch.strips, t), per_triangle(&cache.strips, t));
            eprintln!("{t} triangles: batch {b:.4}, cache-8 {c:.4} shaded per triangle");
            assert!(b < c && b < 0.87, "batch {b} against cache-8 {c}");
            // Fewer indices than a list.
            assert!((batch.figures.indices_restart as f64) < 2.2 * t as f64);
        }
    }

    #[test]
    fn the_door_rejects_qstrip_diagonals_and_empty_batches() {
        let mesh = gen::grid_quads(4, 4);
        let o = StripOptions::default().algorithm(Algorithm::batch());
        assert!(door(&mesh, &o.clone().split(Split::Qstrip)).is_err());
        assert!(door(&mesh, &o.clone().split(Split::Fan)).expect("fan").figures.verified);
        let empty = BatchModel { max_triangles: 0, ..H100 };
        assert!(door(&mesh, &StripOptions::default().algorithm(Algorithm::Batch(empty))).is_err());
    }

    #[test]
    fn the_model_counts_batches() {
        // One strip of 40 triangles on a grid row: 32 vertices for the first batch of
        // 30 triangles, then the last two again and 10 new ones.
        let strip: Vec<u32> = (0..42).collect();
        assert_eq!(H100.strip_invocations(&strip, u32::MAX), 32 + 2 + 10);
        // A vertex read again after 15 other shaded vertices is shaded again.
        let mut s: Vec<u32> = vec![0, 1, 2, u32::MAX];
        s.extend(3..19); // 16 new vertices in one strip
        s.extend([u32::MAX, 0, 1, 2]); // the first triangle again (0, 1 evicted, 2 evicted)
        assert_eq!(H100.strip_invocations(&s, u32::MAX), 3 + 16 + 3);
        // A list reuses anything in the batch of 30 triangles.
        let list: Vec<u32> = (0..31).flat_map(|_| [0, 1, 2]).collect();
        assert_eq!(H100.list_invocations(&list), 6);
    }
}

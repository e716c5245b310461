//! The collapse engine: quadrics, the candidates (in `super::heap`), the validity
//! checks, the collapse itself, hub mode and pair contraction.
//!
//! Why one file of about 1,300 lines: the engine's state (per-vertex quadrics and
//! triangle lists, the heap, the pair union-find, the hub triangle lists) is private
//! to this file. `run` reads as its steps: the face quadrics, the state, hub mode, the
//! boundary and crease planes, the initial candidates (edges, then close pairs), the
//! main loop (`collapse_all`, about 110 lines) and the output. Hub mode (issue #16)
//! reads and writes the same lists at every step, so it stayed here too; the heap,
//! which holds no mesh state, moved out.

use super::heap::{tag, Entry, QuadHeap, CHOICE_END, CHOICE_MASK, CHOICE_MID, CHOICE_MIN, KIND_EDGE, KIND_EDGE_REVERSED, KIND_PAIR};
use super::quadric::{dot, norm, sub, tri_normal, Quadric, V3};
use super::{CollapseSequence, Collapse, Options, Placement, Simplified, Target};
use crate::distance::bvh::point_triangle_distance2;
use crate::mesh::Mesh;
use std::collections::HashMap;
use std::hash::BuildHasherDefault;
use crate::topology::{edge_key, EdgeHasher};

/// Cosine of the largest normal change one collapse may cause in a triangle; 0.5
/// (60 degrees) measured best against 0.0 and 0.25 on bunny, horse and dragon.
const MIN_TURN_COS: f64 = 0.5;
/// The optimal position may lie at most this many edge lengths from the edge's
/// midpoint (a nearly singular quadric can put it far away).
const MAX_OPTIMAL_OFFSET: f64 = 2.0;
/// Weight of the fan distance in a collapse's cost (see `State::plan`), for optimal
/// and for endpoint placement. 0.2 and 0.1 measured best against 0.1 to 1 on bunny,
/// horse and dragon at 20% down to 0.5% of the triangles.
const FAN_WEIGHT_OPTIMAL: f64 = 0.2;
const FAN_WEIGHT_ENDPOINT: f64 = 0.1;
/// An interior edge whose two faces' normals have a cosine below this is a crease
/// (a fold sharper than about 107 degrees: the rim of a fin, an ear's edge)...
const CREASE_COS: f64 = -0.3;
/// ... and gets penalty planes like a boundary edge, weighted
/// `CREASE_WEIGHT * sharpness * length^2` (sharpness 0 at `CREASE_COS`, 1 for a
/// complete fold).
const CREASE_WEIGHT: f64 = 10.0;

/// A vertex in more live triangles than this is a *hub* (the centre of a star of
/// 10^5 triangles, the ends of an edge shared by 10^4 triangles, the first corner of
/// a fanned polygon of 10^6 corners). A hub is never removed nor moved; a collapse
/// into it does work in the other end's triangles only (no re-planning of all the
/// hub's edges, which made such meshes quadratic or worse); see `State::hubs`.
/// Meshes without a hub at the start never take these paths: their output is
/// unchanged. 256 is far above the valence of any vertex of the real models.
const HUB_TRIANGLES: u32 = 256;

enum Verdict {
    Ok,
    /// The pair is no longer an edge: drop the entry silently.
    Stale,
    Refused,
}

struct State {
    pos: Vec<V3>,
    quadric: Vec<Quadric>,
    /// Face area summed into each vertex's quadric; a collapse's quadric error is
    /// divided by that of its two vertices (an area-averaged squared distance).
    area: Vec<f64>,
    /// Weight of the fan distance in the cost.
    fan_weight: f64,
    /// Scratch buffer of `gather_ring`.
    ring: Vec<RingTri>,
    tris: Vec<[u32; 3]>,
    tri_alive: Vec<bool>,
    ancestor_normal: Vec<V3>,
    /// Vertex -> triangle lists, `refs[start[v]..start[v] + len[v]]`; may hold dead
    /// triangles (skipped). A survivor's new list is appended at the end.
    refs: Vec<u32>,
    start: Vec<u32>,
    len: Vec<u32>,
    version: Vec<u32>,
    alive: Vec<bool>,
    mark: Vec<u32>,
    stamp: u32,
    placement: Placement,
    neighbors_removed: NeighborSet,
    neighbors_kept: NeighborSet,
    removed_now: Vec<u32>,
    heap: QuadHeap,
    /// Pair contraction only (empty otherwise): close non-edge partners of each
    /// input vertex (`pair_partner[pair_start[v]..pair_start[v + 1]]`), the survivor
    /// each vertex was merged into (union-find), and the members merged into each
    /// survivor as a linked list, so that pairs outlive their vertices' collapses.
    pair_start: Vec<u32>,
    pair_partner: Vec<u32>,
    root: Vec<u32>,
    member_next: Vec<u32>,
    member_tail: Vec<u32>,
    /// Hub mode, on when some input vertex is in more than `HUB_TRIANGLES` live
    /// triangles (the rest is empty otherwise). In hub mode a hub (see
    /// `HUB_TRIANGLES`) is only ever the kept vertex, at its own position; a collapse
    /// into a hub keeps the hub's version (its other edges' entries stay valid, their
    /// keys possibly stale: they are re-costed when popped) and pushes only the edges
    /// of the removed vertex's triangles; the fan distance of such a collapse uses
    /// only the hub's triangles that share a vertex (not itself a hub) with the
    /// removed vertex's triangles (fewer triangles: a larger or equal distance,
    /// except where none is found); the link and pinch checks read the live
    /// triangle count of each edge and the boundary-edge count of each vertex, kept
    /// up to date in a hash map, instead of gathering the hub's neighbours. A hub's
    /// triangle list has spare room (`cap`), doubled when full, so appending to it
    /// is amortised O(1).
    hubs: bool,
    live_tris: Vec<u32>,
    edge_count: EdgeMap,
    boundary_edges: Vec<u32>,
    cap: Vec<u32>,
    tri_mark: Vec<u32>,
    tri_stamp: u32,
    /// Scratch buffer of the hub paths.
    hub_tris: Vec<u32>,
    /// Attribute seams (empty when the mesh has no attributes): vertices that share
    /// their position with another used vertex, the two sides of a UV or normal seam.
    /// A seam vertex is never removed nor moved, so both sides stay where they were
    /// and the seam cannot open.
    locked: Vec<bool>,
}

const NONE: u32 = u32::MAX;

type EdgeMap = HashMap<u64, u32, BuildHasherDefault<EdgeHasher>>;

/// The neighbours of a vertex with the number of live triangles each shares with it,
/// in first-seen order: a sparse set (`at[u]` is u's index in `list` when that entry
/// names u; stale values need no clearing), so adding and testing are O(1) however
/// high the valence (a list search made a check around a vertex of valence 10^5
/// cost 10^10 steps).
#[derive(Default)]
struct NeighborSet {
    list: Vec<(u32, u32)>,
    at: Vec<u32>,
}

impl NeighborSet {
    fn new(n: usize) -> Self {
        NeighborSet { list: Vec::new(), at: vec![0; n] }
    }

    fn clear(&mut self) {
        self.list.clear();
    }

    fn index(&self, u: u32) -> Option<usize> {
        let i = self.at[u as usize] as usize;
        (i < self.list.len() && self.list[i].0 == u).then_some(i)
    }

    fn add(&mut self, u: u32) {
        match self.index(u) {
            Some(i) => self.list[i].1 += 1,
            None => {
                self.at[u as usize] = self.list.len() as u32;
                self.list.push((u, 1));
            }
        }
    }

    fn has(&self, u: u32) -> bool {
        self.index(u).is_some()
    }
}

impl State {
    /// In hub mode, is `v` a hub (see `HUB_TRIANGLES`)?
    fn is_hub(&self, v: u32) -> bool {
        self.hubs && self.live_tris[v as usize] > HUB_TRIANGLES
    }

    /// Hub mode: the live triangles of edge (a, b) go up or down by one.
    fn edge_step(&mut self, a: u32, b: u32, up: bool) {
        let key = edge_key(a, b);
        let c = self.edge_count.get(&key).copied().unwrap_or(0);
        let nc = if up { c + 1 } else { c.saturating_sub(1) };
        if c == 1 {
            self.boundary_edges[a as usize] -= 1;
            self.boundary_edges[b as usize] -= 1;
        }
        if nc == 1 {
            self.boundary_edges[a as usize] += 1;
            self.boundary_edges[b as usize] += 1;
        }
        if nc == 0 {
            self.edge_count.remove(&key);
        } else {
            self.edge_count.insert(key, nc);
        }
    }

    /// Hub mode: edge counts, boundary-edge counts and live triangle counts after the
    /// collapse r -> k (called before it rewrites the triangles).
    fn count_collapse(&mut self, r: u32, k: u32) {
        for i in self.tris_of(r) {
            let Some(t) = self.live(i) else { continue };
            let tri = self.tris[t];
            if tri.contains(&k) {
                for e in 0..3 {
                    self.edge_step(tri[e], tri[(e + 1) % 3], false);
                }
                for v in tri {
                    self.live_tris[v as usize] -= 1;
                }
            } else {
                let (a, b) = others_of(tri, r);
                self.edge_step(r, a, false);
                self.edge_step(r, b, false);
                self.edge_step(k, a, true);
                self.edge_step(k, b, true);
                self.live_tris[k as usize] += 1;
            }
        }
        self.live_tris[r as usize] = 0;
    }

    /// The triangle at position `i` of a vertex's list, when it is still alive.
    #[inline]
    fn live(&self, i: usize) -> Option<usize> {
        let t = self.refs[i] as usize;
        self.tri_alive[t].then_some(t)
    }

    fn tris_of(&self, v: u32) -> std::ops::Range<usize> {
        let s = self.start[v as usize] as usize;
        s..s + self.len[v as usize] as usize
    }

    /// Cost, removed vertex, kept vertex, position and placement choice of collapsing
    /// the pair (u, v). Symmetric in (u, v), so that re-planning names the same pair.
    ///
    /// The cost of a placement p is the area-averaged quadric error at p plus
    /// `fan_weight` times the fan distance: the largest squared distance of u's and
    /// v's current positions to the triangles around p after the collapse, and of p
    /// to the triangles around u and v before it. Quadrics measure distances to
    /// planes, not to triangles: on a thin fin or an ear the faces of both sides are
    /// nearly parallel, so moving the tip inwards within them costs almost nothing,
    /// and the surface there is eaten away; and p can sit on a plane's extension far
    /// from its face. The fan distance is what the collapse actually does, both ways.
    /// Every placement (both ends, the midpoint, the minimiser) is costed this way and
    /// the cheapest taken.
    ///
    /// Without `exact` only the quadric part is computed (no fan distance), a lower
    /// bound of the exact cost; the heap is keyed by such bounds until an entry
    /// reaches the top (see `run`).
    fn plan(&mut self, u: u32, v: u32, exact: bool) -> (f64, u32, u32, V3, u32) {
        let (u, v) = (u.min(v), u.max(v));
        let q = self.quadric[u as usize].sum(&self.quadric[v as usize]);
        let (pu, pv) = (self.pos[u as usize], self.pos[v as usize]);
        let scale = self.scale(u, v);
        let (cu, cv) = (q.eval(pu) * scale, q.eval(pv) * scale);
        if self.is_locked(u) || self.is_locked(v) {
            // A seam vertex is only kept, in place; an edge between two never collapses.
            if self.is_locked(u) && self.is_locked(v) {
                return (f64::INFINITY, u, v, pv, CHOICE_END);
            }
            let (mut c, r, k, p) = if self.is_locked(u) { (cu, v, u, pu) } else { (cv, u, v, pv) };
            if exact {
                let ring = self.gather_ring(u, v);
                c += self.fan_weight * fan_distance2(&ring, [pu, pv], p, f64::INFINITY);
                self.ring = ring;
            }
            return (c, r, k, p, CHOICE_END);
        }
        if self.hubs && (self.is_hub(u) || self.is_hub(v)) {
            // A hub stays where it is and is never removed: one placement, or none
            // between two hubs.
            if self.is_hub(u) && self.is_hub(v) {
                return (f64::INFINITY, u, v, pv, CHOICE_END);
            }
            let (mut c, r, k, p) = if self.is_hub(u) { (cu, v, u, pu) } else { (cv, u, v, pv) };
            if exact {
                let ring = self.gather_ring(u, v);
                c += self.fan_weight * fan_distance2(&ring, [pu, pv], p, f64::INFINITY);
                self.ring = ring;
            }
            return (c, r, k, p, CHOICE_END);
        }
        let mut cands: [(f64, u32, u32, V3); 4] = [(f64::INFINITY, u, v, pv); 4];
        let mut nc = 0;
        let mut add = |c: (f64, u32, u32, V3)| {
            cands[nc] = c;
            nc += 1;
        };
        if cv <= cu {
            add((cv, u, v, pv));
            add((cu, v, u, pu));
        } else {
            add((cu, v, u, pu));
            add((cv, u, v, pv));
        }
        if self.placement == Placement::Optimal {
            let mid = midpoint(pu, pv);
            add((q.eval(mid) * scale, u, v, mid));
            if let Some(p) = minimizer_near(&q, pu, pv) {
                add((q.eval(p) * scale, u, v, p));
            }
        }
        let cands = &mut cands[..nc];
        if exact {
            // Branch and bound: each quadric part is a lower bound of its total.
            let ring = self.gather_ring(u, v);
            let mut order = [0usize, 1, 2, 3];
            let order = &mut order[..cands.len()];
            order.sort_by(|&a, &b| cands[a].0.total_cmp(&cands[b].0));
            let mut best_total = f64::INFINITY;
            for &i in order.iter() {
                if cands[i].0 > best_total {
                    cands[i].0 = f64::INFINITY;
                    continue;
                }
                let bound = (best_total - cands[i].0) / self.fan_weight;
                cands[i].0 += self.fan_weight * fan_distance2(&ring, [pu, pv], cands[i].3, bound);
                best_total = best_total.min(cands[i].0);
            }
            self.ring = ring;
        }
        // Ties: the better end first, then the midpoint only when strictly better,
        // the minimiser when at least as good.
        let mut best = 0;
        for i in 1..cands.len() {
            if cands[i].0 < cands[best].0 || (i == 3 && cands[i].0 <= cands[best].0) {
                best = i;
            }
        }
        let (c, r, k, p) = cands[best];
        (c, r, k, p, [CHOICE_END, CHOICE_END, CHOICE_MID, CHOICE_MIN][best])
    }

    /// The position of an exact entry's placement `choice` for r -> k, as `plan`
    /// computes it; `None` when it no longer exists (a wrapped stale entry).
    fn position_of(&self, r: u32, k: u32, choice: u32) -> Option<V3> {
        let (u, v) = (r.min(k), r.max(k));
        let (pu, pv) = (self.pos[u as usize], self.pos[v as usize]);
        match choice {
            CHOICE_END => Some(self.pos[k as usize]),
            CHOICE_MID => Some(midpoint(pu, pv)),
            _ => minimizer_near(&self.quadric[u as usize].sum(&self.quadric[v as usize]), pu, pv),
        }
    }

    /// The exact cost of collapsing u and v at p (for forced directions).
    fn cost_at(&mut self, u: u32, v: u32, p: V3) -> f64 {
        let q = self.quadric[u as usize].sum(&self.quadric[v as usize]);
        let ring = self.gather_ring(u, v);
        let fan = fan_distance2(&ring, [self.pos[u as usize], self.pos[v as usize]], p, f64::INFINITY);
        self.ring = ring;
        q.eval(p) * self.scale(u, v) + self.fan_weight * fan
    }

    /// The triangles around u and v (the new fan is those the collapse keeps, with u
    /// and v moved to the new position), in `self.ring`'s buffer, taken out of it.
    fn gather_ring(&mut self, u: u32, v: u32) -> Vec<RingTri> {
        if self.hubs && (self.is_hub(u) || self.is_hub(v)) {
            return self.gather_ring_hub(u, v);
        }
        let mut ring = std::mem::take(&mut self.ring);
        ring.clear();
        for (w, other, centre) in [(u, v, 0u8), (v, u, 1)] {
            for i in self.tris_of(w) {
                let Some(t) = self.live(i) else { continue };
                let removed = self.tris[t].contains(&other);
                if removed && centre == 1 {
                    continue; // seen from u
                }
                let (a, b) = others_of(self.tris[t], w);
                ring.push(RingTri { a: self.pos[a as usize], b: self.pos[b as usize], centre, removed });
            }
        }
        ring
    }

    /// `gather_ring` when one of u and v is a hub: the hub's side holds only the
    /// triangles the collapse removes and the hub's triangles that share a vertex
    /// (not a hub) with the other end's triangles, found through that vertex's list:
    /// O(the other end's valence times its neighbours'), not O(the hub's valence).
    fn gather_ring_hub(&mut self, u: u32, v: u32) -> Vec<RingTri> {
        let (h, o) = if self.is_hub(u) { (u, v) } else { (v, u) };
        let mut hub_tris = std::mem::take(&mut self.hub_tris);
        hub_tris.clear();
        self.tri_stamp = self.tri_stamp.wrapping_add(1);
        let ts = self.tri_stamp;
        for i in self.tris_of(o) {
            let t = self.refs[i] as usize;
            if self.tri_alive[t] && self.tris[t].contains(&h) {
                self.tri_mark[t] = ts;
                hub_tris.push(t as u32);
            }
        }
        for i in self.tris_of(o) {
            let Some(t) = self.live(i) else { continue };
            for w in self.tris[t] {
                if w == o || w == h || self.is_hub(w) {
                    continue;
                }
                for j in self.tris_of(w) {
                    let t2 = self.refs[j] as usize;
                    let tri2 = self.tris[t2];
                    if self.tri_alive[t2] && self.tri_mark[t2] != ts && tri2.contains(&h) && !tri2.contains(&o) {
                        self.tri_mark[t2] = ts;
                        hub_tris.push(t2 as u32);
                    }
                }
            }
        }
        let mut ring = std::mem::take(&mut self.ring);
        ring.clear();
        for (w, other, centre) in [(u, v, 0u8), (v, u, 1)] {
            let own = self.start[w as usize] as usize;
            let list: &[u32] = if w == h { &hub_tris } else { &self.refs[own..own + self.len[w as usize] as usize] };
            for &t in list {
                let t = t as usize;
                if !self.tri_alive[t] {
                    continue;
                }
                let removed = self.tris[t].contains(&other);
                if removed && centre == 1 {
                    continue;
                }
                let (a, b) = others_of(self.tris[t], w);
                ring.push(RingTri { a: self.pos[a as usize], b: self.pos[b as usize], centre, removed });
            }
        }
        self.hub_tris = hub_tris;
        ring
    }

    /// 1 / the face area in the quadrics of u and v.
    fn scale(&self, u: u32, v: u32) -> f64 {
        1.0 / (self.area[u as usize] + self.area[v as usize]).max(f64::MIN_POSITIVE)
    }

    fn push(&mut self, u: u32, v: u32, kind: u8) {
        let (cost, removed, kept, _, _) = self.plan(u, v, false);
        if cost == f64::INFINITY && self.hubs {
            return; // between two hubs
        }
        self.push_planned(cost, removed, kept, kind, 0);
    }

    fn push_planned(&mut self, cost: f64, removed: u32, kept: u32, kind: u8, choice: u32) {
        let e = self.entry(cost, removed, kept, kind, choice);
        self.heap.push(e);
    }

    fn entry(&self, cost: f64, removed: u32, kept: u32, kind: u8, choice: u32) -> Entry {
        Entry {
            cost: (cost as f32).to_bits(),
            removed,
            kept,
            tag: tag(self.version[removed as usize], self.version[kept as usize], kind) | choice << 2,
        }
    }

    /// Would triangle `t` with vertex `x` moved to `p` be valid?
    fn triangle_ok(&self, t: usize, x: u32, p: V3) -> bool {
        let tri = self.tris[t];
        let old = tri.map(|v| self.pos[v as usize]);
        let new = [0, 1, 2].map(|j| if tri[j] == x { p } else { old[j] });
        let n0 = tri_normal(old[0], old[1], old[2]);
        let n1 = tri_normal(new[0], new[1], new[2]);
        let l2 = |a: V3, b: V3| dot(sub(a, b), sub(a, b));
        let longest = l2(new[0], new[1]).max(l2(new[1], new[2])).max(l2(new[2], new[0]));
        let area2 = dot(n1, n1);
        // Degenerate: height below a millionth of the longest edge.
        #[allow(clippy::neg_cmp_op_on_partial_ord)] // also true for NaN, on purpose
        if !(area2 > 1e-12 * longest * longest) {
            return false;
        }
        // One collapse may turn a triangle by at most 60 degrees (meshoptimizer-like
        // folds otherwise show up as Hausdorff spikes), and never past 90 degrees from
        // its input ancestor.
        dot(n1, n0) > MIN_TURN_COS * (dot(n1, n1) * dot(n0, n0)).sqrt() && dot(n1, self.ancestor_normal[t]) > 0.0
    }

    /// Whether `v` is a seam vertex (see `State::locked`).
    fn is_locked(&self, v: u32) -> bool {
        self.locked.get(v as usize).copied().unwrap_or(false)
    }

    fn check(&mut self, r: u32, k: u32, p: V3, pair: bool) -> Verdict {
        if self.is_locked(r) || (self.is_locked(k) && p != self.pos[k as usize]) {
            return Verdict::Refused;
        }
        let hub = self.hubs && self.is_hub(k);
        if self.hubs && (self.is_hub(r) || (hub && p != self.pos[k as usize])) {
            return Verdict::Refused;
        }
        let mut na = std::mem::take(&mut self.neighbors_removed);
        let mut nb = std::mem::take(&mut self.neighbors_kept);
        na.clear();
        nb.clear();
        let mut shared = 0;
        for i in self.tris_of(r) {
            let Some(t) = self.live(i) else { continue };
            let tri = self.tris[t];
            if tri.contains(&k) {
                shared += 1;
            }
            for v in tri {
                if v != r {
                    na.add(v);
                }
            }
        }
        let verdict = if hub {
            // The hub's neighbours come from the edge counts, not from its list.
            let count = |u: u32| self.edge_count.get(&edge_key(k, u)).copied().unwrap_or(0);
            self.check_with(r, k, p, pair, shared, &na, |u| count(u) > 0, || self.boundary_edges[k as usize] > 0, true)
        } else {
            for i in self.tris_of(k) {
                let t = self.refs[i] as usize;
                if self.tri_alive[t] {
                    for v in self.tris[t] {
                        if v != k {
                            nb.add(v);
                        }
                    }
                }
            }
            let boundary = || nb.list.iter().any(|&(_, c)| c == 1);
            self.check_with(r, k, p, pair, shared, &na, |u| nb.has(u), boundary, false)
        };
        self.neighbors_removed = na;
        self.neighbors_kept = nb;
        verdict
    }

    #[allow(clippy::too_many_arguments)]
    fn check_with(
        &self,
        r: u32,
        k: u32,
        p: V3,
        pair: bool,
        shared: usize,
        na: &NeighborSet,
        nb_has: impl Fn(u32) -> bool,
        k_boundary: impl Fn() -> bool,
        hub: bool,
    ) -> Verdict {
        if shared == 0 && !pair {
            return Verdict::Stale;
        }
        if shared > 2 {
            return Verdict::Refused;
        }
        if shared > 0 {
            // Link condition on vertices: the only common neighbours are the vertices
            // opposite the edge.
            let common = na.list.iter().filter(|&&(u, _)| u != k && nb_has(u)).count();
            if common != shared {
                return Verdict::Refused;
            }
            // An interior edge between two boundary vertices would pinch the surface.
            if shared == 2 && na.list.iter().any(|&(_, c)| c == 1) && k_boundary() {
                return Verdict::Refused;
            }
        }
        let alive = |i: usize| {
            let t = self.refs[i] as usize;
            if self.tri_alive[t] {
                Some(t)
            } else {
                None
            }
        };
        for t in self.tris_of(r).filter_map(alive) {
            let tri = self.tris[t];
            if tri.contains(&k) {
                continue;
            }
            // Would this triangle duplicate one of k's (link condition on edges)?
            let others: Vec2 = others_of(tri, r);
            if nb_has(others.0) && nb_has(others.1) {
                // Through the shorter list of the three (a hub's is long).
                let mut w = k;
                if hub {
                    w = if self.len[others.0 as usize] <= self.len[others.1 as usize] { others.0 } else { others.1 };
                }
                let dup = self.tris_of(w).filter_map(alive).any(|t2| {
                    let t2 = self.tris[t2];
                    t2.contains(&k) && t2.contains(&others.0) && t2.contains(&others.1)
                });
                if dup {
                    return Verdict::Refused;
                }
            }
            if !self.triangle_ok(t, r, p) {
                return Verdict::Refused;
            }
        }
        if p != self.pos[k as usize] {
            for t in self.tris_of(k).filter_map(alive) {
                if !self.tris[t].contains(&r) && !self.triangle_ok(t, k, p) {
                    return Verdict::Refused;
                }
            }
        }
        Verdict::Ok
    }

    /// Performs the collapse r -> k at p; returns the number of triangles removed
    /// (their ids are in `removed_now`).
    fn collapse(&mut self, r: u32, k: u32, p: V3) -> usize {
        self.removed_now.clear();
        if self.hubs {
            self.count_collapse(r, k);
        }
        for i in self.tris_of(r) {
            let Some(t) = self.live(i) else { continue };
            if self.tris[t].contains(&k) {
                self.tri_alive[t] = false;
                self.removed_now.push(t as u32);
            } else {
                for v in self.tris[t].iter_mut() {
                    if *v == r {
                        *v = k;
                    }
                }
            }
        }
        let hub = self.is_hub(k);
        // The triangles new to k's list: all of them, or r's only (hub).
        let new_tris;
        if hub {
            new_tris = self.append_to_hub(r, k);
        } else {
            let new_start = self.refs.len();
            for list in [self.tris_of(k), self.tris_of(r)] {
                for i in list {
                    let t = self.refs[i];
                    if self.tri_alive[t as usize] {
                        self.refs.push(t);
                    }
                }
            }
            self.start[k as usize] = new_start as u32;
            self.len[k as usize] = (self.refs.len() - new_start) as u32;
            if self.hubs {
                self.cap[k as usize] = self.len[k as usize];
            }
            new_tris = self.tris_of(k);
        }
        self.len[r as usize] = 0;
        self.alive[r as usize] = false;
        self.version[r as usize] += 1;
        if !hub {
            self.version[k as usize] += 1;
        }
        let qr = self.quadric[r as usize];
        self.quadric[k as usize].add(&qr);
        self.area[k as usize] += self.area[r as usize];
        self.pos[k as usize] = p;
        // New candidates: every edge around the survivor (a hub: those of the
        // triangles it took from r).
        self.stamp += 1;
        let stamp = self.stamp;
        self.mark[k as usize] = stamp;
        for i in new_tris {
            let t = self.refs[i] as usize;
            for v in self.tris[t] {
                if self.mark[v as usize] != stamp {
                    self.mark[v as usize] = stamp;
                    self.push(k, v, KIND_EDGE);
                }
            }
        }
        if !self.pair_start.is_empty() {
            self.repush_pairs(r, k, stamp, hub);
        }
        self.removed_now.len()
    }

    /// Appends r's live triangles to hub k's list, in place when its spare room
    /// allows, otherwise moving k's live triangles to the end of `refs` with room for
    /// twice as many; returns the range of the appended ones.
    fn append_to_hub(&mut self, r: u32, k: u32) -> std::ops::Range<usize> {
        let mut moved = std::mem::take(&mut self.hub_tris);
        moved.clear();
        for i in self.tris_of(r) {
            let t = self.refs[i];
            if self.tri_alive[t as usize] {
                moved.push(t);
            }
        }
        let (l, c) = (self.len[k as usize] as usize, self.cap[k as usize] as usize);
        if l + moved.len() > c {
            let new_start = self.refs.len();
            for i in self.tris_of(k) {
                let t = self.refs[i];
                if self.tri_alive[t as usize] {
                    self.refs.push(t);
                }
            }
            let live = self.refs.len() - new_start;
            let room = 2 * (live + moved.len());
            self.refs.resize(new_start + room, 0);
            self.start[k as usize] = new_start as u32;
            self.len[k as usize] = live as u32;
            self.cap[k as usize] = room as u32;
        }
        let at = self.start[k as usize] as usize + self.len[k as usize] as usize;
        self.refs[at..at + moved.len()].copy_from_slice(&moved);
        self.len[k as usize] += moved.len() as u32;
        let range = at..at + moved.len();
        self.hub_tris = moved;
        range
    }

    fn find(&mut self, mut v: u32) -> u32 {
        while self.root[v as usize] != v {
            let up = self.root[self.root[v as usize] as usize];
            self.root[v as usize] = up;
            v = up;
        }
        v
    }

    /// After r merged into k: k inherits r's pair partners; push k's pairs again
    /// (their entries died with the version bump). `stamp` marks k's neighbours.
    /// A hub's old pairs' entries are still valid (its version stays): only r's
    /// members' pairs are pushed.
    fn repush_pairs(&mut self, r: u32, k: u32, stamp: u32, hub: bool) {
        self.root[r as usize] = k;
        let tail = self.member_tail[k as usize];
        self.member_next[tail as usize] = r;
        self.member_tail[k as usize] = self.member_tail[r as usize];
        let mut m = if hub { r } else { k };
        while m != NONE {
            for i in self.pair_start[m as usize]..self.pair_start[m as usize + 1] {
                let q = self.find(self.pair_partner[i as usize]);
                if q != k && self.alive[q as usize] && self.mark[q as usize] != stamp {
                    self.mark[q as usize] = stamp;
                    self.push(k, q, KIND_PAIR);
                }
            }
            m = self.member_next[m as usize];
        }
    }

    /// Rewrites `refs` without dead lists once it has grown a lot.
    fn compact(&mut self) {
        let mut refs = Vec::with_capacity(self.refs.len() / 2);
        for v in 0..self.start.len() {
            let s = refs.len();
            for i in self.tris_of(v as u32) {
                let t = self.refs[i];
                if self.tri_alive[t as usize] {
                    refs.push(t);
                }
            }
            self.start[v] = s as u32;
            self.len[v] = (refs.len() - s) as u32;
            if self.hubs {
                self.cap[v] = self.len[v];
            }
        }
        self.refs = refs;
    }
}

type Vec2 = (u32, u32);

fn others_of(tri: [u32; 3], v: u32) -> Vec2 {
    let j = tri.iter().position(|&x| x == v).unwrap_or(0);
    (tri[(j + 1) % 3], tri[(j + 2) % 3])
}

/// A triangle around a collapsing edge: its corners other than the edge's end
/// `centre` (0 for u, 1 for v), and whether the collapse removes it.
#[derive(Clone, Copy)]
struct RingTri {
    a: V3,
    b: V3,
    centre: u8,
    removed: bool,
}

/// The fan distance of moving both ends of an edge (at `ends`) to p: the largest
/// squared distance of either end to the new triangles around p, and of p to the old
/// triangles around the ends (a local one-sided Hausdorff distance each way). Stops
/// early, returning more than `bound`, once the result is certain to exceed it.
fn fan_distance2(ring: &[RingTri], ends: [V3; 2], p: V3, bound: f64) -> f64 {
    // Each end is likely nearest to the triangles that were its own (u's come first
    // in `ring`, v's last), and p to the triangles the collapse removes: those are
    // scanned first, for the early exits.
    let mut worst = 0.0f64;
    for (end, x) in ends.into_iter().enumerate() {
        if x == p {
            continue;
        }
        let mut d = f64::INFINITY;
        for i in 0..ring.len() {
            let t = &ring[if end == 0 { i } else { ring.len() - 1 - i }];
            if !t.removed {
                d = d.min(point_triangle_distance2(x, &[p, t.a, t.b]));
                if d <= worst {
                    break;
                }
            }
        }
        if d.is_finite() {
            worst = worst.max(d);
        }
        if worst > bound {
            return worst;
        }
    }
    if p != ends[0] && p != ends[1] {
        let mut d = f64::INFINITY;
        let removed_first = ring.iter().filter(|t| t.removed).chain(ring.iter().filter(|t| !t.removed));
        for t in removed_first {
            d = d.min(point_triangle_distance2(p, &[ends[t.centre as usize], t.a, t.b]));
            if d <= worst {
                break;
            }
        }
        if d.is_finite() {
            worst = worst.max(d);
        }
    }
    worst
}

/// The midpoint of an edge, rounded to f32 like every stored position.
fn midpoint(pu: V3, pv: V3) -> V3 {
    round([(pu[0] + pv[0]) * 0.5, (pu[1] + pv[1]) * 0.5, (pu[2] + pv[2]) * 0.5])
}

/// The minimiser of `q` for the edge (pu, pv), rounded to f32; none when the system
/// is singular, or nearly so and the point lies more than `MAX_OPTIMAL_OFFSET` edge
/// lengths from the edge's midpoint.
fn minimizer_near(q: &Quadric, pu: V3, pv: V3) -> Option<V3> {
    let p = q.minimizer()?;
    let edge = norm(sub(pu, pv));
    (norm(sub(p, midpoint(pu, pv))) <= MAX_OPTIMAL_OFFSET * edge.max(f64::MIN_POSITIVE)).then(|| round(p))
}

fn round(p: V3) -> V3 {
    p.map(|x| x as f32 as f64)
}

pub(super) fn run(mesh: &Mesh, options: &Options, progress: &mut dyn FnMut(f64)) -> crate::error::Result<Simplified> {
    let n = mesh.positions.len();
    let crate::mesh::Triangles { tris: all, face_of } = mesh.triangulate();
    // The survivors' attributes, updated collapse by collapse.
    let mut attributes = mesh.attributes.clone();
    let triangle_count = all.len();
    let tri_alive: Vec<bool> = all.iter().map(|t| t[0] != t[1] && t[1] != t[2] && t[2] != t[0]).collect();
    let triangles_in = tri_alive.iter().filter(|&&a| a).count();
    let pos: Vec<V3> = mesh.positions.iter().map(|p| p.map(|x| x as f64)).collect();

    // Vertex -> triangle lists.
    let (mut start, refs) = crate::topology::vertex_triangles(&all, n).into_parts();
    let len: Vec<u32> = (0..n).map(|v| start[v + 1] - start[v]).collect();
    start.pop();
    let (quadric, area, ancestor_normal) = face_quadrics(&all, &tri_alive, &pos);

    let mut st = State {
        pos,
        quadric,
        area,
        fan_weight: match options.placement {
            Placement::Endpoint => FAN_WEIGHT_ENDPOINT,
            Placement::Optimal => FAN_WEIGHT_OPTIMAL,
        },
        ring: Vec::new(),
        tris: all,
        tri_alive,
        ancestor_normal,
        refs,
        start,
        len,
        version: vec![0; n],
        alive: vec![true; n],
        mark: vec![0; n],
        stamp: 0,
        placement: options.placement,
        neighbors_removed: NeighborSet::new(n),
        neighbors_kept: NeighborSet::new(n),
        removed_now: Vec::new(),
        heap: QuadHeap::default(),
        pair_start: Vec::new(),
        pair_partner: Vec::new(),
        root: Vec::new(),
        member_next: Vec::new(),
        member_tail: Vec::new(),
        hubs: false,
        live_tris: Vec::new(),
        edge_count: EdgeMap::default(),
        boundary_edges: Vec::new(),
        cap: Vec::new(),
        tri_mark: Vec::new(),
        tri_stamp: 0,
        hub_tris: Vec::new(),
        locked: super::attributes::seam_vertices(mesh),
    };
    st.init_hubs(triangle_count);
    st.add_edge_planes(options.boundary_weight);
    st.push_edges();
    if let Some(d) = options.pair_distance {
        push_close_pairs(&mut st, d)?;
    }
    let (sequence, live, max_error) = collapse_all(&mut st, options, triangles_in, &mut attributes, progress);
    Ok(simplified(&st, mesh, attributes, &face_of, sequence, live, triangles_in, max_error))
}

/// The area-weighted plane quadric of every vertex (the sum over its live
/// triangles), the area around each vertex, and each triangle's normal.
fn face_quadrics(all: &[[u32; 3]], tri_alive: &[bool], pos: &[V3]) -> (Vec<Quadric>, Vec<f64>, Vec<V3>) {
    let n = pos.len();
    let mut quadric = vec![Quadric::default(); n];
    let mut area = vec![0.0f64; n];
    let mut ancestor_normal = vec![[0.0; 3]; all.len()];
    for (t, tri) in all.iter().enumerate() {
        if !tri_alive[t] {
            continue;
        }
        let [a, b, c] = tri.map(|v| pos[v as usize]);
        let nrm = tri_normal(a, b, c);
        ancestor_normal[t] = nrm;
        let len2 = norm(nrm);
        if len2 > 0.0 {
            let unit = nrm.map(|x| x / len2);
            let q = Quadric::plane(unit, -dot(unit, a), 0.5 * len2);
            for &v in tri {
                quadric[v as usize].add(&q);
                area[v as usize] += 0.5 * len2;
            }
        }
    }

    (quadric, area, ancestor_normal)
}

impl State {
    /// Hub mode, when some vertex has more than [`HUB_TRIANGLES`] live triangles:
    /// live triangle counts, edge counts and boundary edges per vertex.
    fn init_hubs(&mut self, triangle_count: usize) {
        let st = self;
        let n = st.pos.len();
        let mut live_tris = vec![0u32; n];
        for (t, tri) in st.tris.iter().enumerate() {
            if st.tri_alive[t] {
                tri.iter().for_each(|&v| live_tris[v as usize] += 1);
            }
        }
        if live_tris.iter().any(|&c| c > HUB_TRIANGLES) {
            st.hubs = true;
            st.boundary_edges = vec![0; n];
            for (t, tri) in st.tris.iter().enumerate() {
                if st.tri_alive[t] {
                    for e in 0..3 {
                        *st.edge_count.entry(edge_key(tri[e], tri[(e + 1) % 3])).or_insert(0) += 1;
                    }
                }
            }
            for (&key, &c) in &st.edge_count {
                if c == 1 {
                    st.boundary_edges[(key >> 32) as usize] += 1;
                    st.boundary_edges[(key & 0xFFFF_FFFF) as usize] += 1;
                }
            }
            st.live_tris = live_tris;
            st.cap = st.len.clone();
            st.tri_mark = vec![0; triangle_count];
        }

    }

    /// Adds the penalty planes of the boundary edges (weighted by `boundary_weight`;
    /// none for 0) and of the crease edges to the quadrics.
    fn add_edge_planes(&mut self, boundary_weight: f64) {
        let st = self;
        let n = st.pos.len();
        // Penalty planes through each boundary edge, perpendicular to its face, and
        // through each crease edge, perpendicular to each of its two faces: these keep
        // borders and the rims of folds (fins, ears) in place, which the face planes
        // alone do not (a fin's faces are nearly parallel).
        // (Neighbour, triangles, first and last triangle) of each edge (v, u > v), in
        // first-seen order; `count_at[u]` is u's index in `counts` (a sparse set, O(1) a
        // lookup however high v's valence).
        let mut counts: Vec<(u32, u32, u32, u32)> = Vec::new();
        let mut count_at = vec![0u32; n];
        for v in 0..n as u32 {
            counts.clear();
            for i in st.tris_of(v) {
                let t = st.refs[i];
                for u in st.tris[t as usize] {
                    if u > v {
                        let j = count_at[u as usize] as usize;
                        if j < counts.len() && counts[j].0 == u {
                            counts[j].1 += 1;
                            counts[j].3 = t;
                        } else {
                            count_at[u as usize] = counts.len() as u32;
                            counts.push((u, 1, t, t));
                        }
                    }
                }
            }
            for &(u, c, t, t2) in &counts {
                if c == 2 {
                    let normal = |t: u32| {
                        let [a, b, cc] = st.tris[t as usize].map(|x| st.pos[x as usize]);
                        tri_normal(a, b, cc)
                    };
                    let (n1, n2) = (normal(t), normal(t2));
                    let (l1, l2) = (norm(n1), norm(n2));
                    if !(l1 > 0.0 && l2 > 0.0) {
                        continue;
                    }
                    let cos = dot(n1, n2) / (l1 * l2);
                    if cos >= CREASE_COS {
                        continue;
                    }
                    let sharp = (CREASE_COS - cos) / (1.0 + CREASE_COS);
                    let (pv, pu) = (st.pos[v as usize], st.pos[u as usize]);
                    let e = sub(pu, pv);
                    for face in [n1, n2] {
                        let pn = super::quadric::cross(e, face);
                        let l = norm(pn);
                        if l > 0.0 {
                            let unit = pn.map(|x| x / l);
                            let q = Quadric::plane(unit, -dot(unit, pv), CREASE_WEIGHT * sharp * dot(e, e));
                            st.quadric[v as usize].add(&q);
                            st.quadric[u as usize].add(&q);
                        }
                    }
                    continue;
                }
                if c != 1 || boundary_weight == 0.0 {
                    continue;
                }
                let tri = st.tris[t as usize];
                let [a, b, cc] = tri.map(|x| st.pos[x as usize]);
                let face = tri_normal(a, b, cc);
                let (pv, pu) = (st.pos[v as usize], st.pos[u as usize]);
                let e = sub(pu, pv);
                let pn = super::quadric::cross(e, face);
                let l = norm(pn);
                if l > 0.0 {
                    let unit = pn.map(|x| x / l);
                    let q = Quadric::plane(unit, -dot(unit, pv), boundary_weight * dot(e, e));
                    st.quadric[v as usize].add(&q);
                    st.quadric[u as usize].add(&q);
                }
            }
        }

    }

    /// Queues every edge once as a candidate.
    fn push_edges(&mut self) {
        let st = self;
        let n = st.pos.len();
            for v in 0..n as u32 {
            st.stamp += 1;
            let stamp = st.stamp;
            for i in st.tris_of(v) {
                let t = st.refs[i] as usize;
                for u in st.tris[t] {
                    if u > v && st.mark[u as usize] != stamp {
                        st.mark[u as usize] = stamp;
                        st.push(v, u, KIND_EDGE);
                    }
                }
            }
        }
    }
}

/// The main loop: the cheapest valid collapse, one after another, until the target,
/// the error bound or `max_collapses`; returns the sequence, the live triangles left
/// and the largest error.
fn collapse_all(
    st: &mut State,
    options: &Options,
    triangles_in: usize,
    attributes: &mut [crate::mesh::Attribute],
    progress: &mut dyn FnMut(f64),
) -> (CollapseSequence, usize, f64) {
    let (n, triangle_count) = (st.pos.len(), st.tris.len());
    let (target, max_cost) = match options.target {
        Target::Ratio(r) => (super::ratio_target(triangles_in, r), f64::INFINITY),
        Target::Triangles(t) => (t, f64::INFINITY),
        Target::Error(e) => (0, e),
    };
    let max_collapses = options.max_collapses.unwrap_or(usize::MAX);
    let mut live = triangles_in;
    let mut sequence = CollapseSequence::new(n as u32, triangle_count as u32);
    let mut max_error = 0.0f64;
    let to_remove = triangles_in.saturating_sub(target).max(1) as f64;
    let initial_refs = st.refs.len();
    // The next entry, when it was found with a push-pop.
    let mut next: Option<Entry> = None;
    while live > target && sequence.len() < max_collapses {
        let Some(e) = next.take().or_else(|| st.heap.pop()) else { break };
        let (r, k) = (e.removed, e.kept);
        let kind = (e.tag & 3) as u8;
        let choice = (e.tag & CHOICE_MASK) >> 2;
        if !st.alive[r as usize]
            || !st.alive[k as usize]
            || tag(st.version[r as usize], st.version[k as usize], kind) != e.tag & !CHOICE_MASK
        {
            continue;
        }
        // Keys are exact costs or lower bounds, so an exact entry at the top is the
        // cheapest collapse (its fan distance may have grown since, when a neighbour
        // moved; that is not re-checked). A lower-bound entry gets its exact cost
        // now: still no more than the next key, it goes ahead, otherwise it is
        // queued again at that cost, as exact.
        let exact = match choice {
            0 => None,
            _ => st.position_of(r, k, choice).map(|p| (r, k, p, f32::from_bits(e.cost) as f64)),
        };
        let (r, k, p, cost) = match exact {
            Some(x) => x,
            None => {
                let (planned_cost, pr, pk, p, choice) = st.plan(r, k, true);
                // A reversed entry forces the other direction.
                let (r, k, p, cost, choice) = if (pr, pk) == (r, k) || kind != KIND_EDGE_REVERSED {
                    (pr, pk, p, planned_cost, choice)
                } else {
                    (r, k, st.pos[k as usize], st.cost_at(r, k, st.pos[k as usize]), CHOICE_END)
                };
                if (r, k) != (e.removed, e.kept)
                    || ((cost as f32) > f32::from_bits(e.cost)
                        && st.heap.items.first().is_some_and(|top| (cost as f32) > f32::from_bits(top.cost)))
                {
                    next = Some(st.heap.push_pop(st.entry(cost, r, k, kind, choice)));
                    continue;
                }
                (r, k, p, cost)
            }
        };
        if cost > max_cost {
            break;
        }
        match st.check(r, k, p, kind == KIND_PAIR) {
            Verdict::Stale => continue,
            Verdict::Refused => {
                if kind == KIND_EDGE && options.placement == Placement::Endpoint && !st.is_hub(k) {
                    // Try the other direction: k moves onto r.
                    let c = st.cost_at(r, k, st.pos[r as usize]);
                    st.push_planned(c, k, r, KIND_EDGE_REVERSED, CHOICE_END);
                }
                continue;
            }
            Verdict::Ok => {}
        }
        if !attributes.is_empty() {
            // Over the stored (f32) positions, as the replay sees them.
            use super::attributes::stored;
            let ends = [stored(st.pos[k as usize]), stored(st.pos[r as usize])];
            super::attributes::carry(attributes, r, k, ends, stored(p));
        }
        let removed = st.collapse(r, k, p);
        live -= removed;
        max_error = max_error.max(cost);
        let position = p.map(|x| x as f32);
        sequence.push(Collapse { removed: r, kept: k, position, error: cost }, &st.removed_now);
        if sequence.len() % 4096 == 0 {
            progress(((triangles_in - live) as f64 / to_remove).min(1.0));
        }
        // Most popped entries would be stale (every collapse outdates the entries of
        // both vertices' edges); dropping them in bulk with a linear pass is much
        // cheaper than popping each one through the cache-missing sift-down. Only
        // entries that a pop would skip anyway go, so the result is unchanged. (Only
        // once a quarter of the heap was pushed since the last pass: linear time
        // overall even where most entries stay valid, as with many pairs.)
        if st.heap.items.len() > 2 * live + 4096 && 4 * st.heap.pushes >= st.heap.items.len() {
            let State { heap, alive, version, .. } = st;
            heap.retain(|e| {
                alive[e.removed as usize]
                    && alive[e.kept as usize]
                    && tag(version[e.removed as usize], version[e.kept as usize], (e.tag & 3) as u8) == e.tag & !CHOICE_MASK
            });
            st.heap.pushes = 0;
        }
        if st.refs.len() > 4 * initial_refs.max(1024) {
            st.compact();
        }
    }
    progress(1.0);

    (sequence, live, max_error)
}

/// The output of [`run`]: the live triangles in input order, with their groups and
/// the survivors' attributes.
#[allow(clippy::too_many_arguments)]
fn simplified(
    st: &State,
    mesh: &Mesh,
    attributes: Vec<crate::mesh::Attribute>,
    face_of: &[u32],
    sequence: CollapseSequence,
    live: usize,
    triangles_in: usize,
    max_error: f64,
) -> Simplified {
    let mut triangle_ids = Vec::with_capacity(live);
    let mut out_tris = Vec::with_capacity(live);
    for (t, tri) in st.tris.iter().enumerate() {
        if st.tri_alive[t] {
            triangle_ids.push(t as u32);
            out_tris.push(*tri);
        }
    }
    let positions = st.pos.iter().map(|p| p.map(|x| x as f32)).collect();
    let mut out = Mesh::from_triangles(positions, &out_tris);
    out.attributes = attributes;
    if !mesh.face_groups.is_empty() {
        out.face_groups = triangle_ids.iter().map(|&t| mesh.group_of(face_of[t as usize] as usize)).collect();
    }
    out.groups = mesh.groups.clone();
    Simplified {
        mesh: out,
        triangle_ids,
        sequence,
        triangles_in,
        max_error,
    }
}

/// How many close pairs per used vertex [`push_close_pairs`] may queue (beyond
/// [`PAIR_ALLOWANCE`]): a distance that finds more is refused.
const PAIRS_PER_VERTEX: usize = 32;
/// Close pairs any mesh may queue besides [`PAIRS_PER_VERTEX`] per used vertex.
const PAIR_ALLOWANCE: usize = 1 << 20;

/// QSlim's pair contraction: vertex pairs closer than `d` that share no edge become
/// candidates too (found through a uniform grid of cell size `d`).; more than
/// [`PAIRS_PER_VERTEX`] per used vertex plus [`PAIR_ALLOWANCE`] is an error.
fn push_close_pairs(st: &mut State, d: f64) -> crate::error::Result<()> {
    if !(d > 0.0 && d.is_finite()) {
        return Ok(());
    }
    let n = st.pos.len();
    let used: Vec<u32> = (0..n as u32).filter(|&v| st.len[v as usize] > 0).collect();
    let limit = used.len().saturating_mul(PAIRS_PER_VERTEX).saturating_add(PAIR_ALLOWANCE);
    let cell = |p: V3| p.map(|x| (x / d).floor() as i64);
    let mut keyed: Vec<([i64; 3], u32)> = used.iter().map(|&v| (cell(st.pos[v as usize]), v)).collect();
    keyed.sort_unstable();
    let find = |key: [i64; 3]| keyed.partition_point(|e| e.0 < key);
    let mut pairs = Vec::new();
    for &(c, v) in &keyed {
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let key = [c[0] + dx, c[1] + dy, c[2] + dz];
                    let mut i = find(key);
                    while i < keyed.len() && keyed[i].0 == key {
                        let u = keyed[i].1;
                        i += 1;
                        if u > v && norm(sub(st.pos[u as usize], st.pos[v as usize])) < d {
                            if pairs.len() == limit {
                                return Err(crate::error::Error::Invalid(format!(
                                    "pair distance {d} finds more than {limit} vertex pairs \
                                     ({PAIRS_PER_VERTEX} per each of the {} used vertices + {PAIR_ALLOWANCE}); \
                                     choose a smaller distance",
                                    used.len()
                                )));
                            }
                            if pairs.len() == pairs.capacity() {
                                // Grow by doubling, but never past the limit: the
                                // refusal above then costs at most `limit` pairs.
                                pairs.reserve_exact(pairs.len().max(1024).min(limit - pairs.len()));
                            }
                            pairs.push((v, u));
                        }
                    }
                }
            }
        }
    }
    // Through the shorter of the two lists (a hub's is long).
    pairs.retain(|&(v, u)| {
        let (a, b) = if st.len[v as usize] <= st.len[u as usize] { (v, u) } else { (u, v) };
        !st.tris_of(a).any(|i| st.tris[st.refs[i] as usize].contains(&b))
    });
    let mut both: Vec<(u32, u32)> = pairs.iter().flat_map(|&(v, u)| [(v, u), (u, v)]).collect();
    both.sort_unstable();
    (st.pair_start, st.pair_partner) =
        crate::topology::Csr::from_entries(n, both.iter().map(|&(v, u)| (v as usize, u))).into_parts();
    st.root = (0..n as u32).collect();
    st.member_next = vec![NONE; n];
    st.member_tail = (0..n as u32).collect();
    for (v, u) in pairs {
        st.push(v, u, KIND_PAIR);
    }
    Ok(())
}

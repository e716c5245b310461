//! QSTRIP: triangle strips for quadrilateral meshes (Vaněček, Sviták, Kolingerová,
//! Skala, "Quadrilateral meshes stripification").
//!
//! The quads are never triangulated up front. The algorithm first grows *sequences of
//! quads* over the quad adjacency (built from the mesh's own quad faces through
//! [`EdgeMap`]; a half-edge is a face corner), then turns each sequence into one
//! generalized triangle strip, choosing every quad's diagonal at that point.
//!
//! * **Sequences.** Free quads sit in a bucket queue keyed by their number of free
//!   neighbours (0..=4, O(1) updates through intrusive lists). A sequence starts at a
//!   quad with the fewest free neighbours and is extended with the free neighbour whose
//!   step adds the fewest swaps (going straight adds none), ties going to the neighbour
//!   with the fewest free neighbours; when the forward end is stuck, the sequence is
//!   extended backwards from its first quad the same way.
//! * **Strips.** A quad entered through its half-edge `a -> b` (quad `a b c d`) is left
//!   straight through `c d` with no swap and either diagonal (the one that starts at the
//!   newer strip vertex of `a b`), or through a side edge with one swap (diagonal
//!   fixed by the side). The first quad starts with a counter-clockwise triangle.
//!   An exact two-state dynamic programme over each sequence (state: which end of the
//!   shared edge is the newer strip vertex) picks the diagonals and swap positions with
//!   the fewest swaps; these are the paper's straight, one-swap and two-swap cases.
//! * **Two quads that share two edges** (a fold at a valence-2 vertex, or a two-quad
//!   "pillow") could give two coincident triangles. Such pairs are found up front and
//!   one quad's diagonal is forced so that no coincident triangle can appear; the
//!   programme above respects forced diagonals.
//!
//! Every output triangle keeps its quad's orientation, so the strips decode (by the reading
//! rule of docs/metrics.md) to exactly two triangles per quad that together form it; see
//! [`verify_quads`](super::quad_verify::verify_quads).
//!
//! Cost: O(faces + vertices) time and memory, dominated by [`EdgeMap::build`].

use super::quad_adjacency::{QuadAdjacency, NONE};
use super::quad_sequence::{emit_quad_sequence, step, INF, NO_EDGE};
use crate::mesh::{Mesh, Triangles};
use crate::strip::StripSet;
use crate::topology::EdgeMap;

pub use super::quad_adjacency::is_quad;

/// How the greedy walk picks the next quad among the free neighbours.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Policy {
    /// The paper's rule: the step that adds the fewest swaps (straight ahead adds
    /// none), ties to the neighbour with the fewest free neighbours.
    FewestSwaps,
    /// Trades one swap for four more quads of straight run ahead: a turn that leads
    /// into a long free row beats going straight into a short one. Breaks the costly
    /// same-side spirals (4 quads per swap, runs counted up to 32).
    LongRuns,
}

/// Quads of straight run ahead that [`Policy::LongRuns`] counts as worth one swap.
pub const SWAP_WORTH: i64 = 4;
const RUN_CAP: u32 = 32;

/// Options of QSTRIP ([`Algorithm::Qstrip`](crate::Algorithm::Qstrip)). Build it from
/// [`QuadOptions::default`] (or [`QuadOptions::paper`]) with the builder methods.
///
/// ```
/// use stripkit::{Policy, QuadOptions};
/// let one_pass = QuadOptions::default().policies(vec![Policy::LongRuns]);
/// assert!(one_pass.extend_backward);
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct QuadOptions {
    /// After a sequence's forward end is stuck, extend it backwards from its first
    /// quad too (default `true`; the paper extends forwards only).
    pub extend_backward: bool,
    /// The walk policies to run; the result with the fewest `indices_restart` is kept
    /// (ties: the earlier policy). Default: both, [`Policy::FewestSwaps`] first. Each
    /// policy is one full O(quads) pass; the adjacency is built once.
    pub policies: Vec<Policy>,
    /// A later policy runs only while the best result so far has more than this many
    /// swaps per quad (default 0.05): on meshes with long regular rows (fine
    /// subdivisions) the first pass leaves little to gain and the second would only
    /// cost time.
    pub retry_above_swaps_per_quad: f64,
}

impl Default for QuadOptions {
    fn default() -> Self {
        QuadOptions {
            extend_backward: true,
            policies: vec![Policy::FewestSwaps, Policy::LongRuns],
            retry_above_swaps_per_quad: 0.05,
        }
    }
}

impl QuadOptions {
    /// Sets [`QuadOptions::extend_backward`].
    pub fn extend_backward(mut self, on: bool) -> Self {
        self.extend_backward = on;
        self
    }
    /// Sets [`QuadOptions::policies`] (at least one: the door refuses none).
    pub fn policies(mut self, policies: Vec<Policy>) -> Self {
        self.policies = policies;
        self
    }
    /// Sets [`QuadOptions::retry_above_swaps_per_quad`].
    pub fn retry_above_swaps_per_quad(mut self, swaps_per_quad: f64) -> Self {
        self.retry_above_swaps_per_quad = swaps_per_quad;
        self
    }
    /// The paper's algorithm alone: one pass, [`Policy::FewestSwaps`], forward only.
    pub fn paper() -> Self {
        QuadOptions {
            extend_backward: false,
            policies: vec![Policy::FewestSwaps],
            retry_above_swaps_per_quad: 0.0,
        }
    }
}

/// The result of [`qstrip`]: strips covering exactly the mesh's quads.
#[derive(Clone, Debug, Default)]
pub struct QuadStrips {
    /// One strip per quad sequence; each quad decodes to two triangles.
    pub strips: StripSet,
    /// The faces that went through QSTRIP (quads: four distinct vertices), ascending.
    pub quad_faces: Vec<u32>,
    /// Swaps (degenerate triangles) inside the strips.
    #[cfg_attr(not(test), allow(dead_code))] // read by the tests
    pub swaps: usize,
    /// Pairs of quads that share two or more edges (or three vertices) and had a
    /// diagonal forced to avoid coincident triangles.
    #[cfg_attr(not(test), allow(dead_code))] // read by the tests
    pub forced_diagonals: usize,
}

impl QuadStrips {
    /// Number of quads covered.
    pub fn quad_count(&self) -> usize {
        self.quad_faces.len()
    }

    /// The faces that are not quads, fanned into triangles (each remembering its
    /// face), ready for a triangle stripifier.
    pub fn other_triangles(&self, mesh: &Mesh) -> Triangles {
        let mut out = Triangles::default();
        let mut next_quad = self.quad_faces.iter().peekable();
        for (f, face) in mesh.faces().enumerate() {
            if next_quad.peek().is_some_and(|&&q| q as usize == f) {
                next_quad.next();
                continue;
            }
            for i in 1..face.len().saturating_sub(1) {
                out.tris.push([face[0], face[i], face[i + 1]]);
                out.face_of.push(f as u32);
            }
        }
        out
    }
}

/// Fraction of a mesh's faces that are quads (by [`is_quad`]); 0 for no faces.
pub fn quad_fraction(mesh: &Mesh) -> f64 {
    let n = mesh.face_count();
    if n == 0 {
        return 0.0;
    }
    mesh.faces().filter(|f| is_quad(f)).count() as f64 / n as f64
}

/// Strips the quads of `mesh` with QSTRIP. Faces that are not quads are left out
/// (see [`QuadStrips::other_triangles`] and [`qstrip_mixed`]). O(faces + vertices).
pub fn qstrip(mesh: &Mesh, options: &QuadOptions) -> QuadStrips {
    let edges = EdgeMap::build(mesh);
    qstrip_with_edges(mesh, &edges, options)
}

/// [`qstrip`] with an edge map the caller already has.
pub fn qstrip_with_edges(mesh: &Mesh, edges: &EdgeMap, options: &QuadOptions) -> QuadStrips {
    let adjacency = QuadAdjacency::build(mesh, edges);
    let mut best: Option<(StripSet, usize)> = None;
    let policies: &[Policy] = if options.policies.is_empty() {
        &[Policy::FewestSwaps]
    } else {
        &options.policies
    };
    for &policy in policies {
        if let Some((_, swaps)) = &best {
            if (*swaps as f64)
                <= options.retry_above_swaps_per_quad * adjacency.quad_face.len() as f64
            {
                break;
            }
        }
        let mut builder = Builder::new(&adjacency, options, policy);
        builder.run();
        let cost = |s: &StripSet| s.indices.len() + s.len();
        if best
            .as_ref()
            .is_none_or(|(b, _)| cost(&builder.strips) < cost(b))
        {
            best = Some((builder.strips, builder.swaps));
        }
    }
    let (strips, swaps) = best.unwrap_or_default();
    QuadStrips {
        strips,
        swaps,
        forced_diagonals: adjacency.forced_pairs,
        quad_faces: adjacency.quad_face,
    }
}

/// Strips a mixed mesh: quads through QSTRIP, the other faces fanned into triangles
/// and handed to `strip_triangles(triangles, vertex_count)` (a triangle stripifier,
/// e.g. the greedy one). The result holds the quad strips first, then the others.
pub fn qstrip_mixed(
    mesh: &Mesh,
    options: &QuadOptions,
    strip_triangles: impl FnOnce(&[[u32; 3]], usize) -> StripSet,
) -> (QuadStrips, StripSet) {
    let quads = qstrip(mesh, options);
    let rest = quads.other_triangles(mesh);
    let mut all = quads.strips.clone();
    if !rest.tris.is_empty() {
        let others = strip_triangles(&rest.tris, mesh.vertex_count());
        for s in others.iter() {
            all.push(s);
        }
    }
    (quads, all)
}

/// [`qstrip_mixed`] with the greedy stripifier ([`super::greedy`], aiming at the
/// fewest indices) for the faces that are not quads: the full cover of any polygon
/// mesh. Returns the quad part and the combined strips.
pub fn qstrip_mesh(mesh: &Mesh, options: &QuadOptions) -> (QuadStrips, StripSet) {
    qstrip_mixed(mesh, options, |tris, vcount| {
        let greedy = super::greedy::GreedyOptions::default().heuristic(super::greedy::Heuristic::Indices);
        super::greedy::stripify(tris, vcount, &greedy)
    })
}


struct Builder<'a, 'm> {
    adj: &'a QuadAdjacency<'m>,
    options: &'a QuadOptions,
    used: Vec<bool>,
    /// Free neighbour edges of each free quad.
    degree: Vec<u8>,
    /// Bucket queue: intrusive doubly linked lists, one per degree.
    head: [u32; 5],
    next: Vec<u32>,
    prev: Vec<u32>,
    /// Current sequence: quad, entry edge, exit edge.
    seq: Vec<(u32, u8, u8)>,
    back: Vec<(u32, u8, u8)>,
    /// Cost-to-go per sequence position and state.
    togo: Vec<[u32; 2]>,
    strip: Vec<u32>,
    strips: StripSet,
    swaps: usize,
    policy: Policy,
}

impl<'a, 'm> Builder<'a, 'm> {
    fn new(adj: &'a QuadAdjacency<'m>, options: &'a QuadOptions, policy: Policy) -> Self {
        let n = adj.len();
        let mut b = Builder {
            adj,
            options,
            used: vec![false; n],
            degree: vec![0; n],
            head: [NONE; 5],
            next: vec![NONE; n],
            prev: vec![NONE; n],
            seq: Vec::new(),
            back: Vec::new(),
            togo: Vec::new(),
            strip: Vec::new(),
            strips: StripSet::new(),
            swaps: 0,
            policy,
        };
        // Insert in reverse so that equal-degree quads come out in index order.
        for q in (0..n).rev() {
            let d = adj.link[4 * q..4 * q + 4]
                .iter()
                .filter(|&&l| l != NONE)
                .count();
            b.degree[q] = d as u8;
            b.push_bucket(q as u32);
        }
        b
    }

    fn push_bucket(&mut self, q: u32) {
        let d = self.degree[q as usize] as usize;
        let h = self.head[d];
        self.next[q as usize] = h;
        self.prev[q as usize] = NONE;
        if h != NONE {
            self.prev[h as usize] = q;
        }
        self.head[d] = q;
    }

    fn unlink_bucket(&mut self, q: u32) {
        let (p, n) = (self.prev[q as usize], self.next[q as usize]);
        if p != NONE {
            self.next[p as usize] = n;
        } else {
            self.head[self.degree[q as usize] as usize] = n;
        }
        if n != NONE {
            self.prev[n as usize] = p;
        }
    }

    /// Removes a quad from the free set and updates its free neighbours' degrees.
    fn take(&mut self, q: u32) {
        self.unlink_bucket(q);
        self.used[q as usize] = true;
        for k in 0..4 {
            let l = self.adj.link[4 * q as usize + k];
            if l == NONE {
                continue;
            }
            let nb = l >> 2;
            if !self.used[nb as usize] {
                self.unlink_bucket(nb);
                self.degree[nb as usize] -= 1;
                self.push_bucket(nb);
            }
        }
    }

    fn run(&mut self) {
        while let Some(start) = self.head.iter().copied().find(|&h| h != NONE) {
            self.take(start);
            self.seq.clear();
            let first_exit = self.extend(start, NO_EDGE, NO_EDGE, Direction::Forward);
            if self.options.extend_backward {
                self.back.clear();
                let back_exit = self.extend(start, NO_EDGE, first_exit, Direction::Backward);
                if back_exit != NO_EDGE {
                    // Sequence = reversed backward walk, then the forward walk.
                    let mut combined = Vec::with_capacity(self.back.len() + self.seq.len());
                    for &(q, entry, exit) in self.back.iter().rev() {
                        combined.push((q, exit, entry));
                    }
                    let start_entry = back_exit;
                    let (_, _, start_exit) = self.seq[0];
                    combined.push((start, start_entry, start_exit));
                    combined.extend_from_slice(&self.seq[1..]);
                    self.seq = combined;
                }
            }
            self.emit_sequence();
        }
    }

    /// Greedy walk from `start` (already taken). Forward: fills `seq` with `start`
    /// first. Backward: fills `back` with the quads after `start` (not `start`) and
    /// never leaves `start` through `avoid`. Returns the edge `start` was left through.
    fn extend(&mut self, start: u32, entry: u8, avoid: u8, dir: Direction) -> u8 {
        let adj = self.adj;
        let mut cur = start;
        let mut entry = entry;
        let mut costs = [0u32, 0];
        let mut first_exit = NO_EDGE;
        // LongRuns: free quads straight ahead of the straight neighbour, carried from
        // step to step (a lower bound once it came from a capped count).
        let mut ahead: Option<(u32, bool)> = None;
        loop {
            let forced = adj.forced[cur as usize];
            let straight_k = if entry == NO_EDGE {
                NO_EDGE
            } else {
                (entry + 2) % 4
            };
            let mut run_straight = 0;
            let mut skip_turns = false;
            if self.policy == Policy::LongRuns && straight_k != NO_EDGE {
                let l = adj.link[4 * cur as usize + straight_k as usize];
                if l != NONE && !self.used[(l >> 2) as usize] {
                    let (run, exact) = match ahead {
                        Some((run, exact)) if exact || run + 3 >= RUN_CAP => (run, exact),
                        _ => {
                            let run = self.straight_run(l >> 2, (l & 3) as u8, RUN_CAP);
                            (run, run < RUN_CAP)
                        }
                    };
                    ahead = Some((run, exact));
                    run_straight = run;
                    // A turn costs at least one swap, worth SWAP_WORTH quads of run.
                    skip_turns = run + 3 >= RUN_CAP;
                }
            }
            // (exit edge, neighbour's entry edge, neighbour, costs after the step)
            let mut best: Option<(u8, u8, u32, [u32; 2])> = None;
            let mut best_key = (i64::MAX, u8::MAX);
            for k in 0..4u8 {
                if k == entry || (cur == start && k == avoid) {
                    continue;
                }
                let l = adj.link[4 * cur as usize + k as usize];
                if l == NONE || self.used[(l >> 2) as usize] {
                    continue;
                }
                let next_costs = step(costs, entry, k, forced);
                let cost = next_costs[0].min(next_costs[1]);
                if cost >= INF {
                    continue;
                }
                // Going backward, `start` will be crossed from `k` to the forward
                // walk's first exit `avoid`: a turn that its forced diagonal forbids
                // would leave the joined sequence with no way through `start`.
                if cur == start && avoid != NO_EDGE && step([0, 0], k, avoid, forced)[0] >= INF {
                    continue;
                }
                let degree = self.degree[(l >> 2) as usize];
                let key = match self.policy {
                    Policy::FewestSwaps => (cost as i64, degree),
                    Policy::LongRuns => {
                        let run = if k == straight_k {
                            run_straight
                        } else if skip_turns {
                            continue;
                        } else {
                            self.straight_run(l >> 2, (l & 3) as u8, RUN_CAP)
                        };
                        (cost as i64 * SWAP_WORTH - run as i64, degree)
                    }
                };
                if key < best_key {
                    best_key = key;
                    best = Some((k, (l & 3) as u8, l >> 2, next_costs));
                }
            }
            let Some((k, nb_edge, nb, next_costs)) = best else {
                if cur == start && dir == Direction::Forward {
                    self.seq.push((cur, entry, NO_EDGE));
                } else if cur != start {
                    self.back_or_seq(dir).push((cur, entry, NO_EDGE));
                }
                return first_exit;
            };
            if cur == start {
                first_exit = k;
            }
            ahead = match ahead {
                Some((run, exact)) if k == straight_k && run > 1 => Some((run - 1, exact)),
                _ => None,
            };
            if cur != start || dir == Direction::Forward {
                self.back_or_seq(dir).push((cur, entry, k));
            }
            self.take(nb);
            cur = nb;
            entry = nb_edge;
            costs = next_costs;
        }
    }

    /// Free quads met going straight from `q` entered through `entry` (`q` counted).
    fn straight_run(&self, mut q: u32, mut entry: u8, cap: u32) -> u32 {
        let mut n = 1;
        while n < cap {
            let l = self.adj.link[4 * q as usize + ((entry + 2) % 4) as usize];
            if l == NONE || self.used[(l >> 2) as usize] {
                break;
            }
            q = l >> 2;
            entry = (l & 3) as u8;
            n += 1;
        }
        n
    }

    fn back_or_seq(&mut self, dir: Direction) -> &mut Vec<(u32, u8, u8)> {
        match dir {
            Direction::Forward => &mut self.seq,
            Direction::Backward => &mut self.back,
        }
    }

    /// Turns the current sequence into one strip with the fewest swaps.
    fn emit_sequence(&mut self) {
        self.strip.clear();
        self.swaps += emit_quad_sequence(self.adj, &self.seq, &mut self.togo, &mut self.strip);
        self.strips.push(&self.strip);
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Direction {
    Forward,
    Backward,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_quad_gives_its_two_triangles() {
        let mesh = Mesh::from_polygons(vec![[0.0; 3]; 4], &[vec![0, 1, 2, 3]]);
        let q = qstrip(&mesh, &QuadOptions::default());
        assert_eq!(q.strips.len(), 1);
        assert_eq!(q.strips.strip(0).len(), 4);
        let tris = crate::strip::decode(&q.strips);
        assert_eq!(tris, vec![[0, 1, 3], [3, 1, 2]]);
    }
}

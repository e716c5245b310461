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
//! Every output triangle keeps its quad's orientation, so the strips decode (by the
//! METRICS.md rule) to exactly two triangles per quad that together form it; see
//! [`verify_quads`](super::quad_verify::verify_quads).
//!
//! Cost: O(faces + vertices) time and memory, dominated by [`EdgeMap::build`].

use crate::mesh::{Mesh, Triangles};
use crate::strip::StripSet;
use crate::topology::EdgeMap;

/// No neighbour / no edge.
pub(super) const NONE: u32 = u32::MAX;
/// Local edge marker for "no entry" / "no exit".
pub(super) const NO_EDGE: u8 = 4;
/// Diagonal not forced.
const FREE: u8 = 2;
/// An unreachable programme state.
pub(super) const INF: u32 = u32::MAX / 4;

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

/// Options of QSTRIP ([`Algorithm::Qstrip`](crate::Algorithm::Qstrip)).
#[derive(Clone, Debug, PartialEq)]
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

/// True for a face that QSTRIP takes: four vertices, all distinct.
pub fn is_quad(face: &[u32]) -> bool {
    face.len() == 4
        && face[0] != face[1]
        && face[0] != face[2]
        && face[0] != face[3]
        && face[1] != face[2]
        && face[1] != face[3]
        && face[2] != face[3]
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
        let greedy = super::greedy::GreedyOptions::with_heuristic(super::greedy::Heuristic::Indices);
        super::greedy::stripify(tris, vcount, &greedy)
    })
}

/// Quads and their neighbours across manifold, consistently oriented quad-quad edges.
pub(super) struct QuadAdjacency<'m> {
    /// The four vertices of each quad, flat.
    pub(super) verts: Vec<u32>,
    /// Face id of each quad.
    pub(super) quad_face: Vec<u32>,
    /// `link[4 q + k]`: `(neighbour << 2) | neighbour's local edge` across local edge
    /// `k` (from `verts[4q+k]` to `verts[4q+(k+1)%4]`), or [`NONE`].
    pub(super) link: Vec<u32>,
    /// Forced diagonal per quad: 0 (v0-v2), 1 (v1-v3) or [`FREE`].
    pub(super) forced: Vec<u8>,
    pub(super) forced_pairs: usize,
    _mesh: std::marker::PhantomData<&'m Mesh>,
}

impl QuadAdjacency<'_> {
    pub(super) fn build<'m>(mesh: &'m Mesh, edges: &EdgeMap) -> QuadAdjacency<'m> {
        let fcount = mesh.face_count();
        let mut quad_of_face = vec![NONE; fcount];
        let mut quad_face = Vec::new();
        let mut verts = Vec::new();
        for (f, face) in mesh.faces().enumerate() {
            if is_quad(face) {
                quad_of_face[f] = quad_face.len() as u32;
                quad_face.push(f as u32);
                verts.extend_from_slice(face);
            }
        }
        let qcount = quad_face.len();
        let mut link = vec![NONE; 4 * qcount];
        let local = |h: u32| -> (u32, u32) {
            let f = edges.halfedge_face[h as usize];
            (quad_of_face[f as usize], h - mesh.face_offsets[f as usize])
        };
        // Edges that are not plain two-quad edges (more faces, a flipped neighbour):
        // the only places besides `link` where two quads can share an edge.
        let mut odd_edges = Vec::new();
        for e in 0..edges.edge_count() {
            let hs = edges.halfedges(e);
            if hs.len() != 2 {
                if hs.len() > 2 {
                    odd_edges.push(e);
                }
                continue;
            }
            let (h1, h2) = (hs[0], hs[1]);
            let (q1, k1) = local(h1);
            let (q2, k2) = local(h2);
            if q1 == NONE || q2 == NONE || q1 == q2 {
                continue;
            }
            // Opposite directions: h1 starts where h2 ends.
            let next2 = edges.halfedge_next[h2 as usize];
            if mesh.face_indices[h1 as usize] != mesh.face_indices[next2 as usize] {
                odd_edges.push(e);
                continue;
            }
            link[(4 * q1 + k1) as usize] = (q2 << 2) | k2;
            link[(4 * q2 + k2) as usize] = (q1 << 2) | k1;
        }
        // Quads that share three or more vertices share an edge (any three corners of
        // a quad include two of its edges, and a vertex has one diagonal partner): a
        // `link` neighbour or a quad on an odd edge. Across a link the two shared
        // vertices are known, so it takes a third: one of the other quad's far corners.
        let mut forced = vec![FREE; qcount];
        let mut forced_pairs = 0;
        for q1 in 0..qcount {
            for k in 0..4 {
                let l = link[4 * q1 + k];
                if l == NONE || (l >> 2) as usize <= q1 {
                    continue;
                }
                let q2 = (l >> 2) as usize;
                let k2 = (l & 3) as usize;
                let far = [verts[4 * q2 + (k2 + 2) % 4], verts[4 * q2 + (k2 + 3) % 4]];
                let mine = &verts[4 * q1..4 * q1 + 4];
                if (mine.contains(&far[0]) || mine.contains(&far[1]))
                    && force_pair(&verts, &mut forced, q1, q2)
                {
                    forced_pairs += 1;
                }
            }
        }
        for e in odd_edges {
            let hs = edges.halfedges(e);
            for (i, &ha) in hs.iter().enumerate() {
                for &hb in &hs[i + 1..] {
                    let (qa, _) = local(ha);
                    let (qb, _) = local(hb);
                    if qa == NONE || qb == NONE || qa == qb {
                        continue;
                    }
                    let (q1, q2) = (qa.min(qb) as usize, qa.max(qb) as usize);
                    let a = &verts[4 * q1..4 * q1 + 4];
                    let b = &verts[4 * q2..4 * q2 + 4];
                    let common = a.iter().filter(|v| b.contains(v)).count();
                    if common >= 3 && force_pair(&verts, &mut forced, q1, q2) {
                        forced_pairs += 1;
                    }
                }
            }
        }
        QuadAdjacency {
            verts,
            quad_face,
            link,
            forced,
            forced_pairs,
            _mesh: std::marker::PhantomData,
        }
    }

    fn len(&self) -> usize {
        self.quad_face.len()
    }
}

/// The two triangles of quad `v` split along diagonal `diag`, as sorted vertex sets.
fn split_sets(v: &[u32], diag: u8) -> [[u32; 3]; 2] {
    let d = diag as usize;
    let mut t1 = [v[d], v[d + 1], v[(d + 2) % 4]];
    let mut t2 = [v[d], v[(d + 2) % 4], v[(d + 3) % 4]];
    t1.sort_unstable();
    t2.sort_unstable();
    [t1, t2]
}

fn coincide(a: &[u32], da: u8, b: &[u32], db: u8) -> bool {
    let ta = split_sets(a, da);
    let tb = split_sets(b, db);
    ta.iter().any(|t| tb.contains(t))
}

/// Forces diagonals of `q1`, `q2` so that no triangle of one lies on the same three
/// vertices as a triangle of the other. Returns whether anything was forced.
fn force_pair(verts: &[u32], forced: &mut [u8], q1: usize, q2: usize) -> bool {
    let a = &verts[4 * q1..4 * q1 + 4];
    let b = &verts[4 * q2..4 * q2 + 4];
    let options = |f: u8| if f == FREE { vec![0u8, 1] } else { vec![f] };
    let bad = |d1: u8, d2: u8| coincide(a, d1, b, d2);
    if options(forced[q1])
        .iter()
        .all(|&d1| options(forced[q2]).iter().all(|&d2| !bad(d1, d2)))
    {
        return false;
    }
    // Prefer forcing one quad only: a diagonal of q1 that suits every choice of q2.
    for d1 in options(forced[q1]) {
        if options(forced[q2]).iter().all(|&d2| !bad(d1, d2)) {
            forced[q1] = d1;
            return true;
        }
    }
    for d2 in options(forced[q2]) {
        if options(forced[q1]).iter().all(|&d1| !bad(d1, d2)) {
            forced[q2] = d2;
            return true;
        }
    }
    for d1 in options(forced[q1]) {
        for d2 in options(forced[q2]) {
            if !bad(d1, d2) {
                forced[q1] = d1;
                forced[q2] = d2;
                return true;
            }
        }
    }
    // Both already forced into a clash (a pathological cluster); verification reports it.
    false
}

/// How a quad is crossed, given its entry and exit edges.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// Entered through `a b`, left through `c d` (no swap).
    Straight,
    /// Left through `b c` (one swap inside the quad).
    TurnBc,
    /// Left through `d a` (one swap inside the quad).
    TurnDa,
    /// Last quad of a sequence.
    Last,
    /// First quad, strip `a b d c` (diagonal `b d`).
    FirstBd,
    /// First quad, strip `b c a c d` (diagonal `a c`, one swap).
    FirstAc,
}

/// One way to cross a quad. States: 0 = the newer strip vertex on the shared edge is
/// the start `a` of the quad's own half-edge on it, 1 = its end `b`.
#[derive(Clone, Copy, Debug)]
struct Mode {
    kind: Kind,
    /// Required entry state (ignored for first quads).
    need: u8,
    /// State on the next quad's entry half-edge (ignored for last quads).
    out: u8,
    /// Swaps inside the quad.
    cost: u32,
    /// Diagonal used: 0 = v0-v2, 1 = v1-v3.
    diag: u8,
}

/// The ways to cross a quad with entry edge `j` and exit edge `k` (local, or
/// [`NO_EDGE`]), honouring a forced diagonal. At most two.
fn modes(j: u8, k: u8, forced: u8) -> [Option<Mode>; 2] {
    let m = |kind, need, out, cost, diag: u8| Mode {
        kind,
        need,
        out,
        cost,
        diag: diag % 2,
    };
    let list = if j == NO_EDGE {
        [
            Some(m(Kind::FirstBd, 0, 1, 0, k + 1)),
            Some(m(Kind::FirstAc, 0, 0, 1, k)),
        ]
    } else if k == NO_EDGE {
        [
            Some(m(Kind::Last, 0, 0, 0, j)),
            Some(m(Kind::Last, 1, 0, 0, j + 1)),
        ]
    } else {
        match (k + 4 - j) % 4 {
            2 => [
                Some(m(Kind::Straight, 0, 0, 0, j)),
                Some(m(Kind::Straight, 1, 1, 0, j + 1)),
            ],
            1 => [Some(m(Kind::TurnBc, 1, 0, 1, j + 1)), None],
            _ => [Some(m(Kind::TurnDa, 0, 1, 1, j)), None],
        }
    };
    list.map(|o| o.filter(|mode| forced == FREE || mode.diag == forced))
}

/// Programme step: costs at the next quad's entry from costs `f` at this quad's entry.
pub(super) fn step(f: [u32; 2], j: u8, k: u8, forced: u8) -> [u32; 2] {
    let mut out = [INF; 2];
    for mode in modes(j, k, forced).into_iter().flatten() {
        let base = if j == NO_EDGE {
            0
        } else {
            let n = mode.need as usize;
            f[n].min(f[1 - n] + 1)
        };
        let c = base + mode.cost;
        let o = mode.out as usize;
        out[o] = out[o].min(c);
    }
    // A swap at the start of the next quad turns one state into the other.
    [out[0].min(out[1] + 1), out[1].min(out[0] + 1)]
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

/// Turns a sequence of adjacent quads `(quad, entry edge, exit edge)` into one strip
/// (appended to `strip`) with the fewest swaps, by the two-state programme; returns the
/// swaps. Every step must be feasible under the forced diagonals (see [`step`]).
pub(super) fn emit_quad_sequence(
    adj: &QuadAdjacency,
    seq: &[(u32, u8, u8)],
    togo: &mut Vec<[u32; 2]>,
    strip: &mut Vec<u32>,
) -> usize {
    let n = seq.len();
    let mut swaps = 0;
    if n == 0 {
        return 0;
    }
    if n == 1 {
        let q = seq[0].0 as usize;
        let v = &adj.verts[4 * q..4 * q + 4];
        if adj.forced[q] == 0 {
            strip.extend_from_slice(&[v[1], v[2], v[0], v[3]]);
        } else {
            strip.extend_from_slice(&[v[0], v[1], v[3], v[2]]);
        }
        return 0;
    }
    // Cost to go, from the back.
    togo.clear();
    togo.resize(n + 1, [0, 0]);
    for i in (0..n).rev() {
        let (q, j, k) = seq[i];
        let after = togo[i + 1];
        let mut g = [INF; 2];
        for mode in modes(j, k, adj.forced[q as usize]).into_iter().flatten() {
            let rest = mode.cost
                + if k == NO_EDGE {
                    0
                } else {
                    after[mode.out as usize]
                };
            if j == NO_EDGE {
                g[0] = g[0].min(rest);
            } else {
                let need = mode.need as usize;
                g[need] = g[need].min(rest);
                g[1 - need] = g[1 - need].min(rest + 1);
            }
        }
        togo[i] = g;
    }
    // Forward emission.
    let mut state = 0u8;
    for i in 0..n {
        let (q, j, k) = seq[i];
        let after = togo[i + 1];
        let mut best: Option<Mode> = None;
        let mut best_cost = INF;
        for mode in modes(j, k, adj.forced[q as usize]).into_iter().flatten() {
            let swap = if j == NO_EDGE || mode.need == state {
                0
            } else {
                1
            };
            let c = swap
                + mode.cost
                + if k == NO_EDGE {
                    0
                } else {
                    after[mode.out as usize]
                };
            if c < best_cost {
                best_cost = c;
                best = Some(mode);
            }
        }
        let Some(mode) = best else {
            // Callers only pass feasible sequences.
            debug_assert!(false, "no way through quad {q}");
            return swaps;
        };
        let qv = &adj.verts[4 * q as usize..4 * q as usize + 4];
        let at = |o: u8| qv[((if j == NO_EDGE { k + 2 } else { j }) + o) as usize % 4];
        let (a, b, c, d) = (at(0), at(1), at(2), at(3));
        if j != NO_EDGE && mode.need != state {
            // Repeat the second-to-last vertex: the next triangle pivots on the other end.
            let older = strip[strip.len() - 2];
            strip.push(older);
            swaps += 1;
        }
        match mode.kind {
            Kind::FirstBd => strip.extend_from_slice(&[a, b, d, c]),
            Kind::FirstAc => {
                strip.extend_from_slice(&[b, c, a, c, d]);
                swaps += 1;
            }
            Kind::Straight | Kind::Last => {
                if mode.need == 0 {
                    strip.extend_from_slice(&[c, d]);
                } else {
                    strip.extend_from_slice(&[d, c]);
                }
            }
            Kind::TurnBc => {
                strip.extend_from_slice(&[d, b, c]);
                swaps += 1;
            }
            Kind::TurnDa => {
                strip.extend_from_slice(&[c, a, d]);
                swaps += 1;
            }
        }
        state = mode.out;
    }
    swaps
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

    #[test]
    fn step_costs_match_the_paper_cases() {
        // Straight keeps the state at no cost.
        assert_eq!(step([0, 1], 0, 2, FREE), [0, 1]);
        // Turns cost one swap from the right state, two from the other.
        assert_eq!(step([0, 1], 0, 3, FREE), [2, 1]);
        assert_eq!(step([0, 1], 0, 1, FREE), [2, 3]);
        // First quad: state 1 free, state 0 one swap.
        assert_eq!(step([0, 0], NO_EDGE, 1, FREE), [1, 0]);
    }
}

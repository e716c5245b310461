//! The greedy stripifier of van Kaick, da Silva and Pedrini, "Efficient Generation of
//! Triangle Strips from Triangulated Meshes" (WSCG 2004).
//!
//! A triangle is *free* until a strip takes it; its *degree* is its number of free dual
//! neighbours (0 to 3). Free triangles live in four buckets, one per degree, ordered
//! most recent first: a triangle whose degree drops goes to the front of its new
//! bucket (the paper's "insert before the first node of degree k-1") in O(1), so the
//! next strip starts near the last one. (The paper's intrusive linked lists are
//! replaced by stacks with lazy deletion that give the same order; see
//! `super::buckets`.)
//!
//! * A strip starts at a free triangle of lowest degree.
//! * It grows forwards, then backwards from its start. The next triangle is the free
//!   neighbour of lowest degree. Two cases are taken at once: a neighbour of degree 0
//!   (it would otherwise be a strip of its own) and a neighbour of degree 1 whose only
//!   free neighbour has degree 1 (the pair would otherwise be a strip of two). Other
//!   ties go to a one-level look-ahead over the candidate's own free neighbours. With
//!   [`Heuristic::Strips`] the paper's "lowest degree ahead" wins, but coarsened: only
//!   "some neighbour has degree below 3" counts first, then no swap, then the exact
//!   look-ahead (on the research meshes 5 to 10% fewer strips than the plain rule).
//! * [`Heuristic::Strips`] aims at the fewest strips: swaps do not matter.
//!   [`Heuristic::Indices`] aims at the fewest indices when a swap costs a repeated
//!   index: on a tie of degree it takes the neighbour that needs no swap, and on a
//!   further tie the one with more open surface ahead.
//!
//! * Then, unless [`GreedyOptions::tunnel_cuts`] is `None`, [`super::tunnel`] relinks
//!   the strips along short alternating paths where that saves indices (`indices`) or
//!   strips (`strips`).
//!
//! Strips step only between [`DualGraph`] neighbours (two triangles running an edge in
//! opposite directions; on a non-manifold edge, the pairs the graph makes), so every
//! triangle keeps its winding; boundaries and inconsistently oriented regions simply
//! end strips. Degenerate triangles (a repeated index) are dropped. Runs in
//! O(triangles + vertices).

use super::buckets::Buckets;
use crate::strip::StripSet;
use crate::topology::{DualGraph, Walks, NO_NEIGHBOR};

/// What the greedy choice optimises (names `strips` and `indices`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Heuristic {
    /// Fewest strips (for hardware where a swap is free).
    Strips,
    /// Fewest indices when a swap costs one repeated index (the default).
    #[default]
    Indices,
}

crate::error::named_enum!(Heuristic, "heuristic", Strips => "strips", Indices => "indices");

/// Options of the greedy stripifier ([`Algorithm::Greedy`](crate::Algorithm::Greedy)).
/// Build it from [`GreedyOptions::default`] with the builder methods.
///
/// ```
/// use stripkit::{GreedyOptions, Heuristic};
/// let plain = GreedyOptions::default().heuristic(Heuristic::Strips).tunnel_cuts(None);
/// assert_eq!(plain.tunnel_cuts, None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct GreedyOptions {
    /// What to optimise. Default [`Heuristic::Indices`].
    pub heuristic: Heuristic,
    /// Tunnelling after the greedy pass (strips relinked along alternating paths
    /// through the dual graph, where that saves indices): the most strip links one
    /// relinking may cut, or `None` for the plain greedy of the paper. Default 1. At
    /// most [`crate::MAX_TUNNEL_CUTS`] (the door refuses more); each search does
    /// bounded work (`SEARCH_BUDGET` of `improve/tunnel.rs`, never reached at three
    /// cuts or fewer), so depth costs little time, but deep searches find worse
    /// strips, not better (docs/experiments/greedy-tunnelling.md).
    pub tunnel_cuts: Option<usize>,
}

impl Default for GreedyOptions {
    fn default() -> Self {
        GreedyOptions {
            heuristic: Heuristic::default(),
            tunnel_cuts: Some(1),
        }
    }
}

impl GreedyOptions {
    /// Sets [`GreedyOptions::heuristic`].
    pub fn heuristic(mut self, heuristic: Heuristic) -> Self {
        self.heuristic = heuristic;
        self
    }
    /// Sets [`GreedyOptions::tunnel_cuts`].
    pub fn tunnel_cuts(mut self, cuts: Option<usize>) -> Self {
        self.tunnel_cuts = cuts;
        self
    }
}

const NONE: u32 = u32::MAX;

/// Ranking of a candidate: smaller is better, compared field by field.
type Key = (u8, u8, u8, u8, u8);
/// Slot value meaning "no entry edge".
const NO_SLOT: usize = 3;

struct Greedy<'a> {
    tris: &'a [[u32; 3]],
    nbr: &'a [[u32; 3]],
    b: Buckets,
    heuristic: Heuristic,
}

/// The vertex shared by edges `a` and `b` (distinct slots) of `tri`.
#[inline]
fn pivot(tri: &[u32; 3], a: usize, b: usize) -> u32 {
    if b == (a + 1) % 3 {
        tri[b]
    } else {
        tri[a]
    }
}

impl Greedy<'_> {
    #[inline]
    fn is_free(&self, t: u32) -> bool {
        t != NO_NEIGHBOR && self.b.free[t as usize]
    }

    /// Takes `t` into the current strip: off the lists, neighbours' degrees down.
    fn take(&mut self, t: u32) {
        self.b.free[t as usize] = false;
        for &n in &self.nbr[t as usize] {
            if self.is_free(n) {
                let d = self.b.degree[n as usize];
                self.b.push_front(n, d - 1);
            }
        }
    }

    /// Lowest degree among the free neighbours of `c` (4 when it has none).
    #[inline]
    fn look_ahead(&self, c: u32) -> u8 {
        let mut best = 4;
        for &m in &self.nbr[c as usize] {
            if self.is_free(m) {
                best = best.min(self.b.degree[m as usize]);
            }
        }
        best
    }

    /// Picks the slot of `cur` to leave through, or `None` when no neighbour is free.
    /// `entry` is the slot we came in by, `last_pivot` the pivot before `cur`.
    fn choose(&self, cur: u32, entry: usize, last_pivot: u32) -> Option<usize> {
        let tri = &self.tris[cur as usize];
        let nbr = &self.nbr[cur as usize];
        let mut best: Option<(usize, Key)> = None;
        for (j, &n) in nbr.iter().enumerate() {
            if j == entry || !self.is_free(n) {
                continue;
            }
            let d = self.b.degree[n as usize];
            let la = self.look_ahead(n);
            // Early insertions of the paper: a dead end, or an isolated pair.
            let early = u8::from(!(d == 0 || (d == 1 && la == 1)));
            let swap = u8::from(entry != NO_SLOT && pivot(tri, entry, j) == last_pivot);
            // Strips: among equal degrees, hug the already stripped region (a
            // neighbour's neighbour of degree 3 means open surface ahead); this keeps
            // the free region compact and saves strips. Indices: avoid the swap first,
            // then head into open surface (measured: slightly fewer indices than the
            // lowest look-ahead on every research mesh).
            let key = match self.heuristic {
                Heuristic::Strips => (d, early, u8::from(la >= 3), swap, la),
                Heuristic::Indices => (d, early, swap, 3 - la.min(3), 0),
            };
            match best {
                Some((_, k)) if k <= key => {}
                _ => best = Some((j, key)),
            }
        }
        best.map(|(j, _)| j)
    }

    /// Grows `path` from its last triangle `cur` until no free neighbour is left.
    fn grow(&mut self, path: &mut Vec<u32>, mut cur: u32, mut entry: usize, mut last_pivot: u32) {
        while let Some(j) = self.choose(cur, entry, last_pivot) {
            let tri = self.tris[cur as usize];
            let n = self.nbr[cur as usize][j];
            last_pivot = if entry == NO_SLOT {
                tri[j]
            } else {
                pivot(&tri, entry, j)
            };
            let (u, v) = (tri[j], tri[(j + 1) % 3]);
            let ntri = &self.tris[n as usize];
            entry = (0..3)
                .find(|&k| self.nbr[n as usize][k] == cur && ntri[k] == v && ntri[(k + 1) % 3] == u)
                .expect("dual graph neighbours share an opposite edge");
            self.take(n);
            path.push(n);
            cur = n;
        }
    }

    /// The slot of `a` across which `b` lies.
    fn slot_to(&self, a: u32, b: u32) -> usize {
        (0..3)
            .find(|&k| self.nbr[a as usize][k] == b)
            .expect("neighbours")
    }
}

/// Turns triangles into strips with the greedy algorithm of van Kaick et al.
///
/// `tris` are oriented triangles over vertices `0..vertex_count` (every index must be
/// below `vertex_count`); degenerate ones are dropped. The result, decoded by the
/// strip reading rule (docs/metrics.md), gives every other triangle exactly once with its winding.
/// O(triangles + vertices) time and memory.
pub fn stripify(tris: &[[u32; 3]], vertex_count: usize, options: &GreedyOptions) -> StripSet {
    let graph = DualGraph::from_triangles(tris, vertex_count);
    stripify_with_graph(tris, &graph, options)
}

/// [`stripify`] with a dual graph already built for `tris` (by
/// [`DualGraph::from_triangles`]); a graph of other triangles is a caller bug and may
/// panic.
pub fn stripify_with_graph(
    tris: &[[u32; 3]],
    graph: &DualGraph,
    options: &GreedyOptions,
) -> StripSet {
    walks_with_graph(tris, graph, options).encode(tris, graph)
}

/// The strips of [`stripify_with_graph`] as walks, before they are encoded.
pub(crate) fn walks_with_graph(tris: &[[u32; 3]], graph: &DualGraph, options: &GreedyOptions) -> Walks {
    let n = tris.len();
    let mut g = Greedy {
        tris,
        nbr: &graph.neighbors,
        b: Buckets::of(tris, graph),
        heuristic: options.heuristic,
    };
    let mut walks = Walks::with_capacity(n);
    let mut path: Vec<u32> = Vec::new();
    let mut back: Vec<u32> = Vec::new();
    while let Some(t0) = g.b.lowest() {
        path.clear();
        back.clear();
        g.take(t0);
        path.push(t0);
        g.grow(&mut path, t0, NO_SLOT, NONE);
        // Grow backwards from the start: the walk reversed, continued from t0.
        if path.len() >= 2 {
            let t1 = path[1];
            let entry = g.slot_to(t0, t1);
            let tri1 = &tris[t1 as usize];
            let k1 = g.slot_to(t1, t0);
            let last_pivot = if path.len() >= 3 {
                pivot(tri1, k1, g.slot_to(t1, path[2]))
            } else {
                tri1[k1]
            };
            g.grow(&mut back, t0, entry, last_pivot);
        }
        walks.push_iter(back.iter().rev().chain(&path).copied());
    }
    // The buckets (18 bytes per triangle) are spent: freed before the tunnel pass
    // builds its own state.
    drop(g);
    match options.tunnel_cuts {
        Some(max_cuts) => {
            // `strips` counts strips only: a swap is free, so any strip saved is worth
            // it; `indices` weighs a strip as its three indices against one per swap.
            let strip_cost = match options.heuristic {
                Heuristic::Strips => 1 << 16,
                Heuristic::Indices => 3,
            };
            let topts = crate::improve::tunnel::TunnelOptions {
                max_cuts,
                strip_cost,
                ..Default::default()
            };
            crate::improve::tunnel::tunnel_walks(tris, graph, &walks, &topts)
        }
        None => walks,
    }
}

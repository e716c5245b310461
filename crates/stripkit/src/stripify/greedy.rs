//! The greedy stripifier of van Kaick, da Silva and Pedrini, "Efficient Generation of
//! Triangle Strips from Triangulated Meshes" (WSCG 2004).
//!
//! A triangle is *free* until a strip takes it; its *degree* is its number of free dual
//! neighbours (0 to 3). Free triangles live in four intrusive doubly linked lists, one
//! per degree, kept in flat arrays, so a degree change moves a triangle in O(1), and a
//! triangle whose degree drops goes to the front of its new list (the paper's "insert
//! before the first node of degree k-1"): the next strip starts near the last one.
//!
//! * A strip starts at a free triangle of lowest degree.
//! * It grows forwards, then backwards from its start. The next triangle is the free
//!   neighbour of lowest degree. Two cases are taken at once: a neighbour of degree 0
//!   (it would otherwise be a strip of its own) and a neighbour of degree 1 whose only
//!   free neighbour has degree 1 (the pair would otherwise be a strip of two). Other
//!   ties go to the paper's one-level look-ahead: the neighbour whose own free
//!   neighbours have the lowest degree.
//! * [`Heuristic::Strips`] aims at the fewest strips: swaps do not matter.
//!   [`Heuristic::Indices`] aims at the fewest indices when a swap costs a repeated
//!   index: on a tie of degree it takes the neighbour that needs no swap.
//!
//! Strips step only between [`DualGraph`] neighbours (manifold, consistently oriented
//! edges), so every triangle keeps its winding; non-manifold edges, boundaries and
//! inconsistently oriented regions simply end strips. Degenerate triangles (a repeated
//! index) are dropped. Runs in O(triangles + vertices).

use super::encode_path;
use crate::strip::{is_degenerate, StripSet};
use crate::topology::{DualGraph, NO_NEIGHBOR};

/// What the greedy choice optimises.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Heuristic {
    /// Fewest strips (for hardware where a swap is free).
    #[default]
    Strips,
    /// Fewest indices when a swap costs one repeated index.
    Indices,
}

impl std::str::FromStr for Heuristic {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "strips" => Ok(Heuristic::Strips),
            "indices" => Ok(Heuristic::Indices),
            _ => Err(format!("unknown heuristic `{s}` (expected `strips` or `indices`)")),
        }
    }
}

/// Options of [`stripify`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GreedyOptions {
    /// What to optimise.
    pub heuristic: Heuristic,
}

const NONE: u32 = u32::MAX;
/// Slot value meaning "no entry edge".
const NO_SLOT: usize = 3;

/// Free triangles bucketed by degree: intrusive doubly linked lists in flat arrays.
struct Buckets {
    head: [u32; 4],
    next: Vec<u32>,
    prev: Vec<u32>,
    degree: Vec<u8>,
    free: Vec<bool>,
}

impl Buckets {
    #[inline]
    fn push_front(&mut self, t: u32, d: u8) {
        let h = self.head[d as usize];
        self.next[t as usize] = h;
        self.prev[t as usize] = NONE;
        if h != NONE {
            self.prev[h as usize] = t;
        }
        self.head[d as usize] = t;
        self.degree[t as usize] = d;
    }

    #[inline]
    fn unlink(&mut self, t: u32) {
        let (p, n) = (self.prev[t as usize], self.next[t as usize]);
        if p != NONE {
            self.next[p as usize] = n;
        } else {
            self.head[self.degree[t as usize] as usize] = n;
        }
        if n != NONE {
            self.prev[n as usize] = p;
        }
    }

    fn lowest(&self) -> Option<u32> {
        self.head.iter().copied().find(|&h| h != NONE)
    }
}

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
        self.b.unlink(t);
        self.b.free[t as usize] = false;
        for &n in &self.nbr[t as usize] {
            if self.is_free(n) {
                let d = self.b.degree[n as usize];
                self.b.unlink(n);
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
        let mut best: Option<(usize, (u8, u8, u8, u8))> = None;
        for j in 0..3 {
            let n = nbr[j];
            if j == entry || !self.is_free(n) {
                continue;
            }
            let d = self.b.degree[n as usize];
            let la = self.look_ahead(n);
            // Early insertions of the paper: a dead end, or an isolated pair.
            let early = u8::from(!(d == 0 || (d == 1 && la == 1)));
            let swap = u8::from(entry != NO_SLOT && pivot(tri, entry, j) == last_pivot);
            let key = match self.heuristic {
                Heuristic::Strips => (d, early, la, swap),
                Heuristic::Indices => (d, early, swap, la),
            };
            if best.map_or(true, |(_, k)| key < k) {
                best = Some((j, key));
            }
        }
        best.map(|(j, _)| j)
    }

    /// Grows `path` from its last triangle `cur` until no free neighbour is left.
    fn grow(&mut self, path: &mut Vec<u32>, mut cur: u32, mut entry: usize, mut last_pivot: u32) {
        while let Some(j) = self.choose(cur, entry, last_pivot) {
            let tri = self.tris[cur as usize];
            let n = self.nbr[cur as usize][j];
            last_pivot = if entry == NO_SLOT { tri[j] } else { pivot(&tri, entry, j) };
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
        (0..3).find(|&k| self.nbr[a as usize][k] == b).expect("neighbours")
    }
}

/// Turns triangles into strips with the greedy algorithm of van Kaick et al.
///
/// `tris` are oriented triangles over vertices `0..vertex_count` (every index must be
/// below `vertex_count`); degenerate ones are dropped. The result, decoded by the
/// METRICS.md rule, gives every other triangle exactly once with its winding.
/// O(triangles + vertices) time and memory.
pub fn stripify(tris: &[[u32; 3]], vertex_count: usize, options: &GreedyOptions) -> StripSet {
    let graph = DualGraph::from_triangles(tris, vertex_count);
    stripify_with_graph(tris, &graph, options)
}

/// [`stripify`] with a dual graph already built for `tris`.
pub fn stripify_with_graph(tris: &[[u32; 3]], graph: &DualGraph, options: &GreedyOptions) -> StripSet {
    let n = tris.len();
    let mut g = Greedy {
        tris,
        nbr: &graph.neighbors,
        b: Buckets {
            head: [NONE; 4],
            next: vec![NONE; n],
            prev: vec![NONE; n],
            degree: vec![0; n],
            free: vec![false; n],
        },
        heuristic: options.heuristic,
    };
    // Insert in reverse so that each list starts in input order.
    for t in (0..n).rev() {
        if is_degenerate(&tris[t]) {
            continue;
        }
        g.b.free[t] = true;
        let d = graph.neighbors[t].iter().filter(|&&x| x != NO_NEIGHBOR).count() as u8;
        g.b.push_front(t as u32, d);
    }
    let mut out = StripSet::new();
    out.indices.reserve(n + n / 4);
    let mut path: Vec<u32> = Vec::new();
    let mut back: Vec<u32> = Vec::new();
    let mut seq: Vec<u32> = Vec::new();
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
        seq.clear();
        seq.extend(back.iter().rev());
        seq.extend_from_slice(&path);
        encode_path(tris, graph, &seq, &mut out);
    }
    out
}

//! The mesh the single-strip builder changes: triangles with their dual neighbours per
//! edge slot, the strip links (which dual edges the strip crosses), and the two changes
//! loop merging may make, an edge split (a Steiner vertex at the midpoint) and an edge
//! swap. Flat arrays; a change touches a constant number of entries.

use crate::topology::{DualGraph, NO_NEIGHBOR};
use crate::vec3::{tri_normal, unit};

/// Slot `j` of a triangle is its edge `(t[j], t[(j + 1) % 3])`.
#[inline]
pub(crate) fn edge(t: &[u32; 3], j: usize) -> (u32, u32) {
    (t[j], t[(j + 1) % 3])
}

/// The working mesh of the single-strip builder.
#[derive(Clone, Debug)]
pub(crate) struct WorkMesh {
    /// Vertex positions: the input's, then one per Steiner vertex.
    pub pos: Vec<[f64; 3]>,
    /// The input's vertex count (Steiner vertices are numbered from here).
    pub input_vertices: usize,
    /// Triangles; an input triangle keeps its index while it is changed, pieces are
    /// appended.
    pub tris: Vec<[u32; 3]>,
    /// `nbr[t][j]`: the triangle across slot `j`, or [`NO_NEIGHBOR`]; symmetric.
    pub nbr: Vec<[u32; 3]>,
    /// Bit `j` of `link[t]`: the strip crosses slot `j` (the dual edge is unmatched).
    pub link: Vec<u8>,
    /// The input triangle each triangle comes from (itself, a split piece of it, or one
    /// of a swapped pair).
    pub origin: Vec<u32>,
    /// The edge each Steiner vertex splits, in the order they were added.
    pub steiner: Vec<[u32; 2]>,
    /// The triangle pairs that were swapped, as the input triangles they replaced.
    pub swaps: Vec<[u32; 2]>,
    /// Each swap's old diagonal `a - b` and new diagonal `c - d`.
    pub swap_quads: Vec<[u32; 4]>,
    /// The weight of every slot's dual edge (0 where none was set); splits and swaps
    /// carry it to the pieces: the halves of a split edge keep its weight, the new
    /// edges to the midpoint weigh 0, a swapped diagonal keeps the old one's.
    pub weight: Vec<[f64; 3]>,
}

impl WorkMesh {
    /// The input triangles with their dual graph, no links yet.
    pub fn new(positions: &[[f32; 3]], tris: Vec<[u32; 3]>) -> WorkMesh {
        let dual = DualGraph::from_triangles(&tris, positions.len());
        let n = tris.len();
        WorkMesh {
            pos: positions.iter().map(|p| p.map(f64::from)).collect(),
            input_vertices: positions.len(),
            tris,
            nbr: dual.neighbors,
            link: vec![0; n],
            origin: (0..n as u32).collect(),
            steiner: Vec::new(),
            swaps: Vec::new(),
            swap_quads: Vec::new(),
            weight: vec![[0.0; 3]; n],
        }
    }

    /// Triangles now.
    pub fn len(&self) -> usize {
        self.tris.len()
    }

    /// Whether slot `j` of `t` is a strip link.
    #[inline]
    pub fn linked(&self, t: usize, j: usize) -> bool {
        self.link[t] >> j & 1 == 1
    }

    /// Strip links of `t`.
    #[inline]
    pub fn degree(&self, t: usize) -> u32 {
        self.link[t].count_ones()
    }

    /// Dual neighbours of `t`.
    #[inline]
    pub fn dual_degree(&self, t: usize) -> usize {
        self.nbr[t].iter().filter(|&&u| u != NO_NEIGHBOR).count()
    }

    /// Sets or clears the link across slot `j` of `t` on both sides.
    pub fn set_link(&mut self, t: usize, j: usize, on: bool) {
        let u = self.nbr[t][j] as usize;
        let k = self.twin(t, j);
        if on {
            self.link[t] |= 1 << j;
            self.link[u] |= 1 << k;
        } else {
            self.link[t] &= !(1 << j);
            self.link[u] &= !(1 << k);
        }
    }

    /// The slot of `nbr[t][j]` that holds the same edge (run the other way).
    #[inline]
    pub fn twin(&self, t: usize, j: usize) -> usize {
        let (a, b) = edge(&self.tris[t], j);
        let u = &self.tris[self.nbr[t][j] as usize];
        (0..3)
            .find(|&k| edge(u, k) == (b, a))
            .expect("dual neighbours share their edge, run in opposite directions")
    }

    /// Points the neighbour `across` the edge `(p, q)` (as its new owner `to` runs it)
    /// at `to`: the slot is found by the edge, since a neighbour may touch the owner
    /// across more than one edge.
    fn repoint(&mut self, across: u32, (p, q): (u32, u32), to: u32) {
        if across == NO_NEIGHBOR {
            return;
        }
        let a = across as usize;
        let k = (0..3).find(|&k| edge(&self.tris[a], k) == (q, p)).expect("a dual neighbour shares the edge");
        self.nbr[a][k] = to;
    }

    fn link_bit(&self, t: usize, j: usize) -> u8 {
        self.link[t] >> j & 1
    }

    /// The two triangles across slot `j` of `t` as a quad: `t = (a, b, c)` and
    /// `u = (b, a, d)`, their outer neighbours, links and weights.
    fn pair(&self, t: usize, j: usize) -> Pair {
        let u = self.nbr[t][j] as usize;
        let k = self.twin(t, j);
        let (j1, j2, k1, k2) = ((j + 1) % 3, (j + 2) % 3, (k + 1) % 3, (k + 2) % 3);
        let (wt, wu) = (self.weight[t], self.weight[u]);
        Pair {
            u,
            a: self.tris[t][j],
            b: self.tris[t][j1],
            c: self.tris[t][j2],
            d: self.tris[u][k2],
            x_ca: self.nbr[t][j2],
            x_bc: self.nbr[t][j1],
            y_ad: self.nbr[u][k1],
            y_db: self.nbr[u][k2],
            l_ca: self.link_bit(t, j2),
            l_bc: self.link_bit(t, j1),
            l_ad: self.link_bit(u, k1),
            l_db: self.link_bit(u, k2),
            w_ab: wt[j],
            w_bc: wt[j1],
            w_ca: wt[j2],
            w_ad: wu[k1],
            w_db: wu[k2],
        }
    }

    /// Splits the edge in slot `j` of `t` (shared with `u = nbr[t][j]`) at its midpoint
    /// `m`: `t = (a, b, c)` becomes `(a, m, c)` in place and `(m, b, c)` appended;
    /// `u = (b, a, d)` becomes `(b, m, d)` in place and `(m, a, d)` appended. The outer
    /// edges keep their links; when `merge`, the pieces are linked `t - (m, a, d)` and
    /// `(m, b, c) - u`, which joins the strips through `t` and `u` into one. Returns
    /// the ids of the two appended pieces.
    pub fn split(&mut self, t: usize, j: usize, merge: bool) -> [u32; 2] {
        let Pair { u, a, b, c, d, x_ca, x_bc, y_ad, y_db, l_ca, l_bc, l_ad, l_db, w_ab, w_bc, w_ca, w_ad, w_db } =
            self.pair(t, j);
        self.weight[t] = [w_ab, 0.0, w_ca];
        self.weight[u] = [w_ab, 0.0, w_db];
        self.weight.push([w_ab, w_bc, 0.0]);
        self.weight.push([w_ab, w_ad, 0.0]);
        let m = self.pos.len() as u32;
        let (pa, pb) = (self.pos[a as usize], self.pos[b as usize]);
        self.pos.push([(pa[0] + pb[0]) / 2.0, (pa[1] + pb[1]) / 2.0, (pa[2] + pb[2]) / 2.0]);
        self.steiner.push([a, b]);
        let tb = self.tris.len() as u32;
        let ub = tb + 1;
        let (t32, u32_) = (t as u32, u as u32);
        let mm = merge as u8;
        // t = (a, m, c): (a,m) -> ub, (m,c) -> tb, (c,a) -> x_ca
        self.tris[t] = [a, m, c];
        self.nbr[t] = [ub, tb, x_ca];
        self.link[t] = mm | l_ca << 2;
        // u = (b, m, d): (b,m) -> tb, (m,d) -> ub, (d,b) -> y_db
        self.tris[u] = [b, m, d];
        self.nbr[u] = [tb, ub, y_db];
        self.link[u] = mm | l_db << 2;
        // tb = (m, b, c): (m,b) -> u, (b,c) -> x_bc, (c,m) -> t
        self.tris.push([m, b, c]);
        self.nbr.push([u32_, x_bc, t32]);
        self.link.push(mm | l_bc << 1);
        self.origin.push(self.origin[t]);
        // ub = (m, a, d): (m,a) -> t, (a,d) -> y_ad, (d,m) -> u
        self.tris.push([m, a, d]);
        self.nbr.push([t32, y_ad, u32_]);
        self.link.push(mm | l_ad << 1);
        self.origin.push(self.origin[u]);
        self.repoint(x_bc, (b, c), tb);
        self.repoint(y_ad, (a, d), ub);
        [tb, ub]
    }

    /// Swaps the edge in slot `j` of `t` (shared with `u`): `t = (a, b, c)` and
    /// `u = (b, a, d)` become `(a, d, c)` and `(d, b, c)`, in place, every outer edge
    /// keeping its link (so the strips through `t` and `u` are rejoined into one). The
    /// caller checks the quad is convex and nearly flat and `c - d` is not an edge.
    pub fn swap(&mut self, t: usize, j: usize) {
        let Pair { u, a, b, c, d, x_ca, x_bc, y_ad, y_db, l_ca, l_bc, l_ad, l_db, w_ab, w_bc, w_ca, w_ad, w_db } =
            self.pair(t, j);
        self.swaps.push([self.origin[t], self.origin[u]]);
        self.swap_quads.push([a, b, c, d]);
        self.weight[t] = [w_ad, w_ab, w_ca];
        self.weight[u] = [w_db, w_bc, w_ab];
        let (t32, u32_) = (t as u32, u as u32);
        // t = (a, d, c): (a,d) -> y_ad, (d,c) -> u, (c,a) -> x_ca
        self.tris[t] = [a, d, c];
        self.nbr[t] = [y_ad, u32_, x_ca];
        self.link[t] = l_ad | l_ca << 2;
        // u = (d, b, c): (d,b) -> y_db, (b,c) -> x_bc, (c,d) -> t
        self.tris[u] = [d, b, c];
        self.nbr[u] = [y_db, x_bc, t32];
        self.link[u] = l_db | l_bc << 1;
        self.repoint(y_ad, (a, d), t32);
        self.repoint(x_bc, (b, c), u32_);
    }

    /// The unit normal of `t` (zero for a degenerate triangle).
    pub fn normal(&self, t: usize) -> [f64; 3] {
        let [a, b, c] = self.tris[t].map(|i| self.pos[i as usize]);
        unit(tri_normal(a, b, c)).unwrap_or([0.0; 3])
    }
}

/// Two triangles across an edge, `t = (a, b, c)` and `u = (b, a, d)`: the outer
/// neighbours (`x_ca` across `c - a` of `t`, ..), their link bits and the weights of
/// the five edges.
struct Pair {
    u: usize,
    a: u32,
    b: u32,
    c: u32,
    d: u32,
    x_ca: u32,
    x_bc: u32,
    y_ad: u32,
    y_db: u32,
    l_ca: u8,
    l_bc: u8,
    l_ad: u8,
    l_db: u8,
    w_ab: f64,
    w_bc: f64,
    w_ca: f64,
    w_ad: f64,
    w_db: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles of a unit square sharing the diagonal 0-2... as (a,b,c) = (0,1,2)
    /// and (b,a,d) = (1,0,3).
    fn pair() -> WorkMesh {
        let pos = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]];
        WorkMesh::new(&pos, vec![[0, 1, 2], [1, 0, 3]])
    }

    fn check_symmetric(w: &WorkMesh) {
        for t in 0..w.len() {
            for j in 0..3 {
                let u = w.nbr[t][j];
                if u != NO_NEIGHBOR {
                    let k = w.twin(t, j);
                    assert_eq!(w.nbr[u as usize][k] as usize, t);
                    assert_eq!(w.linked(t, j), w.linked(u as usize, k));
                }
            }
        }
    }

    #[test]
    fn split_makes_four_pieces_around_the_midpoint() {
        let mut w = pair();
        assert_eq!(w.nbr[0][0], 1);
        let [tb, ub] = w.split(0, 0, true);
        assert_eq!(w.tris, vec![[0, 4, 2], [1, 4, 3], [4, 1, 2], [4, 0, 3]]);
        assert_eq!((tb, ub), (2, 3));
        assert_eq!(w.pos[4], [0.5, 0.5, 0.0]);
        assert_eq!(w.origin, vec![0, 1, 0, 1]);
        check_symmetric(&w);
        // valence 4 at m: every piece has two neighbours
        assert!((0..4).all(|t| w.dual_degree(t) == 2));
        assert!(w.linked(0, 0) && w.linked(1, 0) && !w.linked(0, 1));
    }

    #[test]
    fn swap_turns_the_diagonal() {
        let mut w = pair();
        w.swap(0, 0);
        assert_eq!(w.tris, vec![[0, 3, 2], [3, 1, 2]]);
        check_symmetric(&w);
        assert_eq!(w.swaps, vec![[0, 1]]);
    }
}

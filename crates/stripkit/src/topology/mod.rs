//! Topology of a mesh, computed once into flat arrays.
//!
//! * [`EdgeMap`]: every undirected edge with the half-edges (face corners) on it,
//!   built in O(n) by bucketing half-edges on their lower vertex.
//! * [`DualGraph`]: for a triangle list, each triangle's neighbour across each of its
//!   three edges, but only across *manifold* edges (exactly two faces) whose two
//!   triangles are *consistently oriented* (they traverse the edge in opposite
//!   directions). Only such neighbours may follow each other in a strip without
//!   flipping a triangle, so every stripifier walks this graph.
//! * [`Csr`]: lists bucketed by vertex (or any small key) by one counting sort;
//!   [`vertex_triangles`] is the vertex -> triangles list. Every such list of the
//!   crate is built by it.
//! * [`Walks`]: paths through the dual graph, what the stripifiers build and the
//!   local searches of `crate::improve` rewrite, and their encoding as strips
//!   ([`walks::encode_path`]).
//! * [`facts`]: the figures `stripkit stats` prints.

mod csr;
pub mod facts;
pub(crate) mod walks;

pub use csr::{vertex_triangles, Csr, FreeCursor};
pub use facts::{validate, MeshFacts};
pub(crate) use facts::UnionFind;
pub use walks::Walks;

use crate::mesh::Mesh;
use crate::strip::is_degenerate;

/// Marks "no neighbour" in [`DualGraph::neighbors`].
pub const NO_NEIGHBOR: u32 = u32::MAX;

/// A multiplicative hasher for edge keys ([`edge_key`]: two vertex ids in one u64),
/// for hash maps and sets of undirected edges.
#[derive(Default, Clone, Copy)]
pub(crate) struct EdgeHasher(u64);

impl std::hash::Hasher for EdgeHasher {
    fn finish(&self) -> u64 {
        self.0 ^ (self.0 >> 29)
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0 ^ x).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

/// The key of the undirected edge `a - b`: the lower id in the high half.
pub(crate) fn edge_key(a: u32, b: u32) -> u64 {
    (u64::from(a.min(b)) << 32) | u64::from(a.max(b))
}

/// Undirected edges and the half-edges on them.
///
/// A half-edge is a face corner: half-edge `h` (an index into `mesh.face_indices`)
/// runs from `face_indices[h]` to the next vertex of the same face.
#[derive(Clone, Debug, Default)]
pub struct EdgeMap {
    /// Vertex pair `[lo, hi]` (lo < hi) of each undirected edge. Edges whose two ends
    /// are the same vertex (from degenerate faces) are not listed.
    pub edges: Vec<[u32; 2]>,
    /// `edge_halfedges[edge_offsets[e]..edge_offsets[e + 1]]` are the half-edges on `e`.
    pub edge_offsets: Vec<u32>,
    /// Half-edges grouped by edge.
    pub edge_halfedges: Vec<u32>,
    /// Edge of each half-edge (`u32::MAX` for a half-edge from a vertex to itself).
    pub halfedge_edge: Vec<u32>,
    /// Face of each half-edge.
    pub halfedge_face: Vec<u32>,
    /// Next half-edge in the same face.
    pub halfedge_next: Vec<u32>,
}

impl EdgeMap {
    /// Builds the edge map of a mesh in O(faces + vertices).
    pub fn build(mesh: &Mesh) -> EdgeMap {
        let h_count = mesh.face_indices.len();
        let mut halfedge_face = vec![0u32; h_count];
        let mut halfedge_next = vec![0u32; h_count];
        for f in 0..mesh.face_count() {
            let start = mesh.face_offsets[f];
            let end = mesh.face_offsets[f + 1];
            for h in start..end {
                halfedge_face[h as usize] = f as u32;
                halfedge_next[h as usize] = if h + 1 == end { start } else { h + 1 };
            }
        }
        // Bucket half-edges by their lower vertex, each as the key `hi << 32 | h`;
        // sorting a bucket's keys orders it by higher vertex, then by half-edge id, so
        // the result depends on nothing but the mesh. Buckets hold about six entries.
        let vcount = mesh.vertex_count();
        let ends = |h: usize| {
            let a = mesh.face_indices[h];
            let b = mesh.face_indices[halfedge_next[h] as usize];
            (a.min(b), a.max(b))
        };
        let mut bucketed = Csr::from_entries(
            vcount,
            (0..h_count).filter_map(|h| {
                let (lo, hi) = ends(h);
                (lo != hi).then_some((lo as usize, (hi as u64) << 32 | h as u64))
            }),
        );
        let mut edges = Vec::with_capacity(h_count / 2 + 1);
        let mut edge_offsets = Vec::with_capacity(h_count / 2 + 2);
        let mut edge_halfedges = Vec::with_capacity(bucketed.values().len());
        let mut halfedge_edge = vec![u32::MAX; h_count];
        edge_offsets.push(0);
        for v in 0..vcount {
            let bucket = bucketed.bucket_mut(v);
            bucket.sort_unstable();
            let mut i = 0;
            while i < bucket.len() {
                let hi = (bucket[i] >> 32) as u32;
                let e = edges.len() as u32;
                edges.push([v as u32, hi]);
                while i < bucket.len() && (bucket[i] >> 32) as u32 == hi {
                    let h = bucket[i] as u32;
                    halfedge_edge[h as usize] = e;
                    edge_halfedges.push(h);
                    i += 1;
                }
                edge_offsets.push(edge_halfedges.len() as u32);
            }
        }
        EdgeMap { edges, edge_offsets, edge_halfedges, halfedge_edge, halfedge_face, halfedge_next }
    }

    /// Number of undirected edges.
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// The half-edges on edge `e`.
    pub fn halfedges(&self, e: usize) -> &[u32] {
        &self.edge_halfedges[self.edge_offsets[e] as usize..self.edge_offsets[e + 1] as usize]
    }
}

/// One more than the largest index of `tris` (0 for none).
pub(crate) fn vertex_bound(tris: &[[u32; 3]]) -> usize {
    tris.iter()
        .flatten()
        .map(|&v| v as usize + 1)
        .max()
        .unwrap_or(0)
}

/// Sorts one bucket of a counting sort: insertion sort for the usual handful of
/// entries, pdqsort for a large one (a high-valence vertex), so never quadratic.
pub(crate) fn sort_bucket<T: Ord>(bucket: &mut [T]) {
    if bucket.len() > 16 {
        bucket.sort_unstable();
        return;
    }
    for i in 1..bucket.len() {
        let mut k = i;
        while k > 0 && bucket[k - 1] > bucket[k] {
            bucket.swap(k - 1, k);
            k -= 1;
        }
    }
}

/// `f(corner, a, b)` for every corner `3 t + j` of the non-degenerate triangles, its
/// edge running `a = t[j]` to `b = t[j + 1]`, bucketed by the edge's lower vertex.
fn corners_by_lower_vertex<T: Copy + Default>(
    tris: &[[u32; 3]],
    vertex_count: usize,
    f: impl Fn(usize, u32, u32) -> T + Copy,
) -> Csr<T> {
    Csr::from_entries(
        vertex_count,
        tris.iter()
            .enumerate()
            .filter(|(_, t)| !is_degenerate(t))
            .flat_map(move |(ti, t)| {
                (0..3).map(move |j| {
                    let (a, b) = (t[j], t[(j + 1) % 3]);
                    (a.min(b) as usize, f(ti * 3 + j, a, b))
                })
            }),
    )
}

/// The dual graph of a triangle list: neighbours across edges that two triangles run
/// in opposite directions (see [`DualGraph::from_triangles`] for non-manifold edges).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DualGraph {
    /// `neighbors[t][j]` is the triangle across edge `(t[j], t[(j + 1) % 3])`, or
    /// [`NO_NEIGHBOR`]. The relation is symmetric.
    pub neighbors: Vec<[u32; 3]>,
}

impl DualGraph {
    /// Builds the dual graph: neighbours across edges that two triangles run in
    /// opposite directions. On a non-manifold edge (three or more triangles) the
    /// triangles running it one way are paired, in input order, with those running it
    /// the other way, as far as they go: a strip may cross such an edge between the
    /// two triangles of a pair, and every pair still meets the strip rule's winding.
    /// Degenerate triangles (a repeated index) get no neighbours and take no part in
    /// other triangles' edges. Indices at or above
    /// `vertex_count` are tolerated (the count is raised to cover them).
    ///
    /// Each corner is bucketed once by its edge's lower vertex, packed with the other
    /// vertex and its direction, so pairing never goes back to the triangle array; a
    /// bucket is sorted by the other vertex (insertion sort for the usual handful of
    /// entries, an O(k log k) sort for high-valence vertices). O(triangles + vertices)
    /// for bounded valence, O(t log t) at worst.
    pub fn from_triangles(tris: &[[u32; 3]], vertex_count: usize) -> DualGraph {
        Self::build(tris, vertex_count, None)
    }

    /// [`DualGraph::from_triangles`], and for every link the slot of the shared edge in
    /// the neighbour: `twins[t][j]` is the slot `k` with `neighbors[neighbors[t][j]][k]
    /// == t` across the same edge (0 where there is no neighbour). Free on top of the
    /// graph (the pairing knows both corners).
    #[cfg(test)]
    pub(crate) fn from_triangles_with_twins(
        tris: &[[u32; 3]],
        vertex_count: usize,
    ) -> (DualGraph, Vec<[u8; 3]>) {
        let mut twins = vec![[0u8; 3]; tris.len()];
        let g = Self::build(tris, vertex_count, Some(&mut twins));
        (g, twins)
    }

    /// For every link, the slot of the shared edge in the neighbour (as
    /// [`DualGraph::from_triangles_with_twins`] gives them), looked up for a graph
    /// already built for `tris`: the neighbour's slot that runs the edge the other way.
    pub(crate) fn twins(&self, tris: &[[u32; 3]]) -> Vec<[u8; 3]> {
        self.neighbors
            .iter()
            .enumerate()
            .map(|(t, nbr)| {
                let mut tw = [0u8; 3];
                for k in 0..3 {
                    let m = nbr[k];
                    if m != NO_NEIGHBOR {
                        let (u, v) = (tris[t][k], tris[t][(k + 1) % 3]);
                        let mt = &tris[m as usize];
                        tw[k] = (0..3).find(|&j| mt[j] == v && mt[(j + 1) % 3] == u).unwrap_or(0) as u8;
                    }
                }
                tw
            })
            .collect()
    }

    fn build(
        tris: &[[u32; 3]],
        vertex_count: usize,
        mut twins: Option<&mut Vec<[u8; 3]>>,
    ) -> DualGraph {
        let n = tris.len();
        let vcount = vertex_count.max(vertex_bound(tris));
        // Entry: higher vertex in the top 32 bits, below it corner * 2 + 1 when the
        // corner runs low -> high; corner * 2 + 1 must fit in 32 bits.
        if n >= (u32::MAX / 6) as usize {
            let g = Self::from_triangles_simple(tris, vcount);
            if let Some(twins) = twins {
                *twins = g.twins(tris);
            }
            return g;
        }
        let mut entries = corners_by_lower_vertex(tris, vcount, |corner, a, b| {
            (u64::from(a.max(b)) << 32) | (corner as u64 * 2 + u64::from(a < b))
        });
        let mut neighbors = vec![[NO_NEIGHBOR; 3]; n];
        let hi = |e: u64| (e >> 32) as u32;
        for v in 0..vcount {
            let bucket = entries.bucket_mut(v);
            sort_bucket(bucket);
            let mut i = 0;
            while i < bucket.len() {
                let mut k = i + 1;
                while k < bucket.len() && hi(bucket[k]) == hi(bucket[i]) {
                    k += 1;
                }
                let mut link = |eu: u64, ed: u64| {
                    let c = ((eu & 0xFFFF_FFFF) >> 1) as usize;
                    let d = ((ed & 0xFFFF_FFFF) >> 1) as usize;
                    neighbors[c / 3][c % 3] = (d / 3) as u32;
                    neighbors[d / 3][d % 3] = (c / 3) as u32;
                    if let Some(tw) = twins.as_deref_mut() {
                        tw[c / 3][c % 3] = (d % 3) as u8;
                        tw[d / 3][d % 3] = (c % 3) as u8;
                    }
                };
                if k == i + 2 {
                    // The usual manifold edge: two corners, linked when they run it
                    // in opposite directions.
                    if (bucket[i] & 1) != (bucket[i + 1] & 1) {
                        link(bucket[i], bucket[i + 1]);
                    }
                } else if k > i + 2 {
                    // The j-th corner running the edge one way (by corner id) pairs
                    // with the j-th running it the other way.
                    let group = &bucket[i..k];
                    let mut up = group.iter().filter(|&&e| e & 1 == 1);
                    let mut down = group.iter().filter(|&&e| e & 1 == 0);
                    while let (Some(&eu), Some(&ed)) = (up.next(), down.next()) {
                        link(eu, ed);
                    }
                }
                i = k;
            }
        }
        DualGraph { neighbors }
    }

    /// The plain version of [`DualGraph::from_triangles`] (corner ids only, the edge
    /// looked up again for every comparison), for inputs too large for its packed
    /// entries.
    fn from_triangles_simple(tris: &[[u32; 3]], vertex_count: usize) -> DualGraph {
        let n = tris.len();
        // Bucket the corners (t, j) of non-degenerate triangles by the lower vertex of
        // their edge; in a bucket, a corner pairs with the one running the other way.
        let corners = corners_by_lower_vertex(tris, vertex_count, |corner, _, _| corner as u32);
        let mut neighbors = vec![[NO_NEIGHBOR; 3]; n];
        let edge = |c: u32| {
            let t = &tris[(c / 3) as usize];
            let j = (c % 3) as usize;
            (t[j], t[(j + 1) % 3])
        };
        for v in 0..vertex_count {
            let bucket = corners.bucket(v);
            for &c in bucket {
                let (a, b) = edge(c);
                // The rank of `c` among the corners running its edge its way (by
                // corner id); its partner is the corner of that rank running the other
                // way, as in the packed version.
                let rank = bucket
                    .iter()
                    .filter(|&&d| d < c && edge(d) == (a, b))
                    .count();
                let partner = bucket.iter().copied().find(|&d| {
                    edge(d) == (b, a)
                        && bucket
                            .iter()
                            .filter(|&&e| e < d && edge(e) == (b, a))
                            .count()
                            == rank
                });
                if let Some(d) = partner {
                    neighbors[(c / 3) as usize][(c % 3) as usize] = d / 3;
                }
            }
        }
        DualGraph { neighbors }
    }

    /// Number of triangles (nodes).
    pub fn len(&self) -> usize {
        self.neighbors.len()
    }

    /// Number of neighbours of triangle `t` (0 to 3).
    pub fn degree(&self, t: usize) -> usize {
        self.neighbors[t].iter().filter(|&&n| n != NO_NEIGHBOR).count()
    }

    /// Number of dual edges (each counted once).
    #[cfg(test)]
    pub fn edge_count(&self) -> usize {
        self.neighbors.iter().flatten().filter(|&&n| n != NO_NEIGHBOR).count() / 2
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_triangles_sharing_an_edge_are_neighbours() {
        // 0-1-2 and 2-1-3 share edge 1-2 in opposite directions.
        let g = DualGraph::from_triangles(&[[0, 1, 2], [2, 1, 3]], 4);
        assert_eq!(g.neighbors[0], [NO_NEIGHBOR, 1, NO_NEIGHBOR]);
        assert_eq!(g.neighbors[1], [0, NO_NEIGHBOR, NO_NEIGHBOR]);
        assert_eq!(g.edge_count(), 1);
    }

    #[test]
    fn flipped_neighbours_are_not_linked_and_nonmanifold_edges_pair_up() {
        // Same direction on 1-2: inconsistent orientation.
        let g = DualGraph::from_triangles(&[[0, 1, 2], [1, 2, 3]], 4);
        assert_eq!(g.edge_count(), 0);
        // Three triangles on edge 0-1: the one running 0 -> 1 pairs with the first
        // running 1 -> 0; the third stays unlinked there.
        let g = DualGraph::from_triangles(&[[0, 1, 2], [1, 0, 3], [1, 0, 4]], 5);
        assert_eq!(g.edge_count(), 1);
        assert_eq!(g.neighbors[0][0], 1);
        assert_eq!(g.neighbors[1][0], 0);
        assert_eq!(g.neighbors[2], [NO_NEIGHBOR; 3]);
        // Four on one edge, two each way: two pairs.
        let g = DualGraph::from_triangles(&[[0, 1, 2], [1, 0, 3], [0, 1, 4], [1, 0, 5]], 6);
        assert_eq!(g.edge_count(), 2);
        assert_eq!((g.neighbors[0][0], g.neighbors[2][0]), (1, 3));
        // A duplicated face shares its edges with the first copy in the same
        // direction: the copies never link to each other.
        let g = DualGraph::from_triangles(&[[0, 1, 2], [0, 1, 2]], 3);
        assert_eq!(g.edge_count(), 0);
        // Degenerate triangle takes no part.
        let g = DualGraph::from_triangles(&[[0, 1, 2], [2, 1, 1]], 3);
        assert_eq!(g.edge_count(), 0);
    }

    #[test]
    fn edge_map_groups_halfedges() {
        let mesh = Mesh::from_polygons(vec![[0.0; 3]; 5], &[vec![0, 1, 2, 3], vec![3, 2, 4]]);
        let map = EdgeMap::build(&mesh);
        assert_eq!(map.edge_count(), 6);
        let shared = map.edges.iter().position(|&e| e == [2, 3]).unwrap();
        assert_eq!(map.halfedges(shared).len(), 2);
        assert_eq!(map.halfedge_face[map.halfedges(shared)[1] as usize], 1);
    }
}

#[cfg(test)]
mod dual_graph_tests {
    use super::*;

    #[test]
    fn packed_and_simple_builders_agree() {
        // Pseudo-random soups over few vertices (shared, flipped, non-manifold and
        // degenerate edges) and a high-valence fan.
        let mut next = crate::test_support::xorshift(0x9E37_79B9_7F4A_7C15u64);
        for round in 0..300 {
            let len = next(40) as usize;
            let v = 3 + round % 9;
            let tris: Vec<[u32; 3]> = (0..len).map(|_| [next(v), next(v), next(v)]).collect();
            assert_eq!(
                DualGraph::from_triangles(&tris, v as usize),
                DualGraph::from_triangles_simple(&tris, v as usize)
            );
        }
        let fan: Vec<[u32; 3]> = (0..100u32).map(|i| [0, 1 + i, 1 + (i + 1) % 100]).collect();
        assert_eq!(DualGraph::from_triangles(&fan, 101), DualGraph::from_triangles_simple(&fan, 101));
    }

    #[test]
    fn twins_name_the_shared_edge_in_the_neighbour() {
        // Soups with shared, flipped, non-manifold and pillow edges.
        let mut next = crate::test_support::xorshift(0x2545_F491_4F6C_DD1Du64);
        let mut links = 0;
        for round in 0..300 {
            let v = 3 + round % 7;
            let tris: Vec<[u32; 3]> = (0..next(40)).map(|_| [next(v), next(v), next(v)]).collect();
            let (g, twins) = DualGraph::from_triangles_with_twins(&tris, v as usize);
            assert_eq!(g, DualGraph::from_triangles(&tris, v as usize));
            assert_eq!(twins, g.twins(&tris));
            for (t, nbr) in g.neighbors.iter().enumerate() {
                for k in 0..3 {
                    let m = nbr[k];
                    if m == NO_NEIGHBOR {
                        continue;
                    }
                    links += 1;
                    let j = twins[t][k] as usize;
                    assert_eq!(g.neighbors[m as usize][j], t as u32);
                    let (a, b) = (tris[t][k], tris[t][(k + 1) % 3]);
                    let mt = tris[m as usize];
                    assert_eq!((mt[j], mt[(j + 1) % 3]), (b, a));
                }
            }
        }
        assert!(links > 100, "{links}");
    }
}

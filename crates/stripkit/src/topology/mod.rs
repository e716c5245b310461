//! Topology of a mesh, computed once into flat arrays.
//!
//! * [`EdgeMap`]: every undirected edge with the half-edges (face corners) on it,
//!   built in O(n) by bucketing half-edges on their lower vertex.
//! * [`DualGraph`]: for a triangle list, each triangle's neighbour across each of its
//!   three edges, but only across *manifold* edges (exactly two faces) whose two
//!   triangles are *consistently oriented* (they traverse the edge in opposite
//!   directions). Only such neighbours may follow each other in a strip without
//!   flipping a triangle, so every stripifier walks this graph.
//! * [`facts`]: the figures `stripkit stats` prints.

pub mod facts;

pub use facts::{validate, MeshFacts};

use crate::mesh::Mesh;

/// Marks "no neighbour" in [`DualGraph::neighbors`].
pub const NO_NEIGHBOR: u32 = u32::MAX;

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
        // Bucket half-edges by their lower vertex (counting sort), then pair them up
        // inside each bucket by their higher vertex; buckets hold about six entries.
        let vcount = mesh.vertex_count();
        let mut bucket_start = vec![0u32; vcount + 1];
        let ends = |h: usize| {
            let a = mesh.face_indices[h];
            let b = mesh.face_indices[halfedge_next[h] as usize];
            (a.min(b), a.max(b))
        };
        for h in 0..h_count {
            let (lo, hi) = ends(h);
            if lo != hi {
                bucket_start[lo as usize + 1] += 1;
            }
        }
        for v in 0..vcount {
            bucket_start[v + 1] += bucket_start[v];
        }
        let mut fill = bucket_start.clone();
        let mut bucketed = vec![0u32; bucket_start[vcount] as usize];
        for h in 0..h_count {
            let (lo, hi) = ends(h);
            if lo != hi {
                bucketed[fill[lo as usize] as usize] = h as u32;
                fill[lo as usize] += 1;
            }
        }
        let mut edges = Vec::with_capacity(h_count / 2 + 1);
        let mut edge_offsets = Vec::with_capacity(h_count / 2 + 2);
        let mut edge_halfedges = Vec::with_capacity(bucketed.len());
        let mut halfedge_edge = vec![u32::MAX; h_count];
        edge_offsets.push(0);
        for v in 0..vcount {
            let bucket = &mut bucketed[bucket_start[v] as usize..bucket_start[v + 1] as usize];
            // Small buckets: sort by the higher vertex, then by half-edge id, so the
            // result depends on nothing but the mesh.
            bucket.sort_unstable_by_key(|&h| (ends(h as usize).1, h));
            let mut i = 0;
            while i < bucket.len() {
                let hi = ends(bucket[i] as usize).1;
                let e = edges.len() as u32;
                edges.push([v as u32, hi]);
                while i < bucket.len() && ends(bucket[i] as usize).1 == hi {
                    halfedge_edge[bucket[i] as usize] = e;
                    edge_halfedges.push(bucket[i]);
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

/// The dual graph of a triangle list: neighbours across manifold, consistently
/// oriented edges.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DualGraph {
    /// `neighbors[t][j]` is the triangle across edge `(t[j], t[(j + 1) % 3])`, or
    /// [`NO_NEIGHBOR`]. The relation is symmetric.
    pub neighbors: Vec<[u32; 3]>,
}

impl DualGraph {
    /// Builds the dual graph in O(triangles + vertices). Degenerate triangles (a
    /// repeated index) get no neighbours and take no part in other triangles' edges.
    /// Every index must be below `vertex_count`.
    pub fn from_triangles(tris: &[[u32; 3]], vertex_count: usize) -> DualGraph {
        let n = tris.len();
        let degenerate = |t: &[u32; 3]| t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
        // Bucket the corners (t, j) of non-degenerate triangles by the lower vertex of
        // their edge; in a bucket, a corner pairs with the one running the other way.
        let mut start = vec![0u32; vertex_count + 1];
        for t in tris.iter().filter(|t| !degenerate(t)) {
            for j in 0..3 {
                start[t[j].min(t[(j + 1) % 3]) as usize + 1] += 1;
            }
        }
        for v in 0..vertex_count {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut corners = vec![0u32; start[vertex_count] as usize];
        for (ti, t) in tris.iter().enumerate() {
            if degenerate(t) {
                continue;
            }
            for j in 0..3 {
                let lo = t[j].min(t[(j + 1) % 3]) as usize;
                corners[fill[lo] as usize] = (ti * 3 + j) as u32;
                fill[lo] += 1;
            }
        }
        let mut neighbors = vec![[NO_NEIGHBOR; 3]; n];
        let edge = |c: u32| {
            let t = &tris[(c / 3) as usize];
            let j = (c % 3) as usize;
            (t[j], t[(j + 1) % 3])
        };
        for v in 0..vertex_count {
            let bucket = &corners[start[v] as usize..start[v + 1] as usize];
            for &c in bucket {
                let (a, b) = edge(c);
                let other = a.max(b);
                // Count the corners on the same undirected edge; link only a pair of
                // opposite directions with nothing else on the edge.
                let mut count = 0;
                let mut partner = None;
                for &d in bucket {
                    let (x, y) = edge(d);
                    if x.max(y) == other {
                        count += 1;
                        if x == b && y == a {
                            partner = Some(d);
                        }
                    }
                }
                if count == 2 {
                    if let Some(d) = partner {
                        neighbors[(c / 3) as usize][(c % 3) as usize] = d / 3;
                    }
                }
            }
        }
        DualGraph { neighbors }
    }

    /// Number of triangles (nodes).
    pub fn len(&self) -> usize {
        self.neighbors.len()
    }

    /// True for an empty graph.
    pub fn is_empty(&self) -> bool {
        self.neighbors.is_empty()
    }

    /// Number of neighbours of triangle `t` (0 to 3).
    pub fn degree(&self, t: usize) -> usize {
        self.neighbors[t].iter().filter(|&&n| n != NO_NEIGHBOR).count()
    }

    /// Number of dual edges (each counted once).
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
    fn flipped_neighbour_and_nonmanifold_edge_are_not_linked() {
        // Same direction on 1-2: inconsistent orientation.
        let g = DualGraph::from_triangles(&[[0, 1, 2], [1, 2, 3]], 4);
        assert_eq!(g.edge_count(), 0);
        // Three triangles on edge 0-1.
        let g = DualGraph::from_triangles(&[[0, 1, 2], [1, 0, 3], [1, 0, 4]], 5);
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

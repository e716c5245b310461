//! Quad meshes as the quad stripifiers ([`super::quad`], [`super::quad_single`]) and
//! [`super::quad_verify`] see them: which faces are quads, how a quad splits along a
//! diagonal, and [`QuadAdjacency`], the quads with their neighbours across manifold,
//! consistently oriented quad-quad edges and the diagonals forced where two quads share
//! two edges.

use crate::mesh::Mesh;
use crate::topology::EdgeMap;

/// No neighbour / no edge.
pub(super) const NONE: u32 = u32::MAX;
/// Diagonal not forced.
pub(super) const FREE: u8 = 2;

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
        // The quads on each odd edge, in half-edge order (the faces that are not quads
        // left out first: an edge of k triangles and a quad or two is O(k), not O(k^2)).
        let mut on_edge: Vec<u32> = Vec::new();
        for e in odd_edges {
            on_edge.clear();
            on_edge.extend(edges.halfedges(e).iter().map(|&h| local(h).0).filter(|&q| q != NONE));
            for (i, &qa) in on_edge.iter().enumerate() {
                for &qb in &on_edge[i + 1..] {
                    if qa == qb {
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

    pub(super) fn len(&self) -> usize {
        self.quad_face.len()
    }
}

/// The two triangles of quad `v` split along diagonal `diag` (0: v0-v2, 1: v1-v3),
/// with the quad's orientation.
pub(super) fn split(v: &[u32], diag: u8) -> [[u32; 3]; 2] {
    let d = diag as usize;
    [[v[d], v[d + 1], v[(d + 2) % 4]], [v[d], v[(d + 2) % 4], v[(d + 3) % 4]]]
}

/// The two triangles of quad `v` split along diagonal `diag`, as sorted vertex sets.
fn split_sets(v: &[u32], diag: u8) -> [[u32; 3]; 2] {
    split(v, diag).map(|mut t| {
        t.sort_unstable();
        t
    })
}


/// True when quads `a` and `b` are the same face: the same four vertices in the same
/// cyclic order (a face listed twice, perhaps from another corner). Their triangles
/// may coincide: that is the input's doing, not a wrong split, so no diagonal is
/// forced between them and the quad-level check accepts it.
pub(super) fn same_quad(a: &[u32], b: &[u32]) -> bool {
    a.len() == 4 && b.len() == 4 && (0..4).any(|r| (0..4).all(|i| a[i] == b[(i + r) % 4]))
}

pub(super) fn coincide(a: &[u32], da: u8, b: &[u32], db: u8) -> bool {
    let ta = split_sets(a, da);
    let tb = split_sets(b, db);
    ta.iter().any(|t| tb.contains(t))
}

/// Forces diagonals of `q1`, `q2` so that no triangle of one lies on the same three
/// vertices as a triangle of the other. Returns whether anything was forced.
fn force_pair(verts: &[u32], forced: &mut [u8], q1: usize, q2: usize) -> bool {
    let a = &verts[4 * q1..4 * q1 + 4];
    let b = &verts[4 * q2..4 * q2 + 4];
    if same_quad(a, b) {
        // A quad listed twice: forcing its copies apart would gain nothing (their
        // triangles may coincide) and could force a clash with a real neighbour.
        return false;
    }
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

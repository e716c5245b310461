//! Facts about a mesh's topology: what `stripkit stats` prints.
//!
//! [`MeshFacts::of`] computes every figure over flat arrays (an [`EdgeMap`],
//! union-finds over faces and vertices, per-vertex corner lists for the fans,
//! duplicate candidates taken from the edge map), in O(n).
//!
//! The definitions are on [`MeshFacts`], where the public documentation shows them.

use super::{Csr, EdgeMap};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use std::fmt;

/// Topological and combinatorial facts about a mesh, computed by [`MeshFacts::of`] in
/// O(n). Serialises to one flat JSON object.
///
/// Definitions (the ones `../shared/models/README.md` uses for its table):
///
/// * an edge's *incident faces* are its half-edges (face corners running along it);
/// * **boundary edge**: exactly one incident face; **non-manifold edge**: three or more;
/// * **boundary loop**: a closed walk along boundary half-edges; at a vertex where
///   several boundary walks meet, the walk turns to the next boundary half-edge found
///   by rotating through the fan of faces it arrived through (the loops of the surface
///   once every pinch vertex is split into one copy per fan: two triangles sharing a
///   vertex have two loops, two holes of a grid touching at one corner form one
///   figure-eight loop); every boundary half-edge is used once, so the walk ends;
/// * **non-manifold (pinch) vertex**: the faces around the vertex form more than one
///   group when two faces are joined if they share an edge incident to the vertex
///   (any edge with two or more faces, non-manifold edges included);
/// * **component**: faces joined through shared vertices, as the models README counts
///   them (a pinch vertex does not split a component); unreferenced vertices form none;
/// * **edge component**: faces joined across shared edges only (two triangles sharing
///   just a vertex are two: no strip can cross between them; `bunny_res4.ply` has one
///   triangle that touches the rest at two vertices only: 1 component, 2 edge
///   components);
/// * **Euler characteristic** χ = V_used − E + F;
/// * **degenerate face**: a repeated vertex index, or zero area (exactly zero Newell
///   normal in `f64`);
/// * **duplicate face**: the same cycle of vertices as an earlier face, up to rotation
///   and orientation (for triangles: the same three vertices); each such later face
///   counts once;
/// * **consistently oriented**: no edge with exactly two faces is traversed in the same
///   direction by both.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct MeshFacts {
    /// Vertex records, referenced or not.
    pub vertices: usize,
    /// Faces of any size.
    pub faces: usize,
    /// Faces with three vertices.
    pub triangles: usize,
    /// Faces with four vertices.
    pub quads: usize,
    /// Faces with five or more vertices.
    pub polygons: usize,
    /// Triangles a fan triangulation gives (a quad counts as two).
    pub fan_triangles: usize,
    /// Vertex records that no face refers to.
    pub unreferenced_vertices: usize,
    /// Undirected edges (an edge from a vertex to itself is not an edge).
    pub edges: usize,
    /// Edges with exactly one incident face.
    pub boundary_edges: usize,
    /// Closed walks along the boundary edges.
    pub boundary_loops: usize,
    /// Edges with three or more incident faces.
    pub nonmanifold_edges: usize,
    /// Pinch vertices: their faces form more than one edge-connected fan.
    pub nonmanifold_vertices: usize,
    /// Connected components of faces, joined through shared vertices (the `comp`
    /// column of the models README).
    pub components: usize,
    /// Components of faces joined across shared edges only.
    pub edge_components: usize,
    /// χ = V_used − E + F.
    pub euler_characteristic: i64,
    /// Faces with a repeated vertex index or zero area.
    pub degenerate_faces: usize,
    /// Faces equal to an earlier face up to rotation and orientation.
    pub duplicate_faces: usize,
    /// Two-face edges whose two faces traverse them in the same direction.
    pub inconsistent_edges: usize,
    /// True when `inconsistent_edges` is zero.
    pub consistently_oriented: bool,
    /// No boundary, non-manifold edge or non-manifold vertex (and at least one face).
    pub closed_manifold: bool,
}

/// Checks that a mesh is well formed: offsets start at 0, grow, end at the index
/// count, every face has at least three vertices and every index names a vertex.
/// Every algorithm that indexes by vertex id relies on this.
pub fn validate(mesh: &Mesh) -> Result<()> {
    let offsets = &mesh.face_offsets;
    if offsets.first().copied().unwrap_or(0) != 0 {
        return Err(Error::Invalid("mesh face offsets do not start at 0".into()));
    }
    if offsets.len() > 1 && *offsets.last().unwrap_or(&0) as usize != mesh.face_indices.len() {
        return Err(Error::Invalid(format!(
            "mesh face offsets end at {} but there are {} face indices",
            offsets.last().unwrap_or(&0),
            mesh.face_indices.len()
        )));
    }
    if offsets.len() <= 1 && !mesh.face_indices.is_empty() {
        return Err(Error::Invalid("mesh has face indices but no face offsets".into()));
    }
    for (f, w) in offsets.windows(2).enumerate() {
        if w[1] < w[0] + 3 {
            return Err(Error::Invalid(format!(
                "face {f} has {} vertices; a face needs at least 3",
                w[1] as i64 - w[0] as i64
            )));
        }
    }
    if mesh.positions.len() > u32::MAX as usize {
        return Err(Error::Invalid("mesh has more than 2^32 - 1 vertices".into()));
    }
    let vcount = mesh.positions.len() as u32;
    if let Some(pos) = mesh.face_indices.iter().position(|&i| i >= vcount) {
        let face = offsets.partition_point(|&o| o as usize <= pos) - 1;
        return Err(Error::Invalid(format!(
            "face {face} refers to vertex {} but the mesh has {vcount} vertices",
            mesh.face_indices[pos]
        )));
    }
    Ok(())
}

/// Union-find over `0..n` with path halving and union by rank.
pub(crate) struct UnionFind {
    parent: Vec<u32>,
    rank: Vec<u8>,
}

impl UnionFind {
    pub(crate) fn new(n: usize) -> Self {
        UnionFind { parent: (0..n as u32).collect(), rank: vec![0; n] }
    }

    pub(crate) fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let grand = self.parent[self.parent[x as usize] as usize];
            self.parent[x as usize] = grand;
            x = grand;
        }
        x
    }

    /// Joins the sets of `a` and `b`; true when they were apart.
    pub(crate) fn union(&mut self, a: u32, b: u32) -> bool {
        let ra = self.find(a);
        let rb = self.find(b);
        if ra == rb {
            return false;
        }
        let (ka, kb) = (self.rank[ra as usize], self.rank[rb as usize]);
        if ka < kb {
            self.parent[ra as usize] = rb;
        } else {
            self.parent[rb as usize] = ra;
            if ka == kb {
                self.rank[ra as usize] += 1;
            }
        }
        true
    }
}

impl MeshFacts {
    /// Computes all facts of `mesh`. Fails only on a malformed mesh (see [`validate`]).
    pub fn of(mesh: &Mesh) -> Result<MeshFacts> {
        validate(mesh)?;
        let map = EdgeMap::build(mesh);
        Ok(Self::with_edge_map(mesh, &map))
    }

    /// Computes all facts from an already built edge map of a valid mesh.
    pub(crate) fn with_edge_map(mesh: &Mesh, map: &EdgeMap) -> MeshFacts {
        let vcount = mesh.vertex_count();
        let fcount = mesh.face_count();
        let fi = &mesh.face_indices;
        let mut facts = MeshFacts { vertices: vcount, faces: fcount, ..Default::default() };

        for face in mesh.faces() {
            match face.len() {
                3 => facts.triangles += 1,
                4 => facts.quads += 1,
                _ => facts.polygons += 1,
            }
        }
        facts.fan_triangles = mesh.triangle_count();

        let mut referenced = vec![false; vcount];
        for &v in fi {
            referenced[v as usize] = true;
        }
        let used = referenced.iter().filter(|&&r| r).count();
        facts.unreferenced_vertices = vcount - used;

        // Edges by incidence. Orientation: count, per edge, the half-edges running
        // from its lower to its higher vertex, in one pass in face order (a small
        // per-edge counter instead of random reads of the index array); a two-face
        // edge is consistent when exactly one of its half-edges runs that way.
        facts.edges = map.edge_count();
        let mut forward = vec![0u8; map.edge_count()];
        for w in mesh.face_offsets.windows(2) {
            let (s, t) = (w[0] as usize, w[1] as usize);
            for h in s..t {
                let next = if h + 1 == t { s } else { h + 1 };
                let e = map.halfedge_edge[h];
                if e != u32::MAX && fi[h] < fi[next] {
                    forward[e as usize] = forward[e as usize].saturating_add(1);
                }
            }
        }
        for (e, w) in map.edge_offsets.windows(2).enumerate() {
            match w[1] - w[0] {
                1 => facts.boundary_edges += 1,
                2 if forward[e] != 1 => facts.inconsistent_edges += 1,
                n if n >= 3 => facts.nonmanifold_edges += 1,
                _ => {}
            }
        }
        facts.consistently_oriented = facts.inconsistent_edges == 0;
        facts.euler_characteristic = used as i64 - facts.edges as i64 + fcount as i64;

        facts.boundary_loops = count_boundary_loops(mesh, map);
        facts.nonmanifold_vertices = count_pinch_vertices(mesh, map);
        facts.components = count_vertex_components(mesh, &referenced);
        // Faces meeting at a vertex that is not a pinch lie in one fan, so they are
        // edge-connected: without pinch vertices both counts agree.
        facts.edge_components =
            if facts.nonmanifold_vertices == 0 { facts.components } else { count_edge_components(mesh, map) };
        facts.degenerate_faces = count_degenerate_faces(mesh);
        facts.duplicate_faces = count_duplicate_faces(mesh, map);
        facts.closed_manifold = fcount > 0
            && facts.boundary_edges == 0
            && facts.nonmanifold_edges == 0
            && facts.nonmanifold_vertices == 0;
        facts
    }
}

/// Counts closed walks over boundary half-edges (see the module docs).
fn count_boundary_loops(mesh: &Mesh, map: &EdgeMap) -> usize {
    let fi = &mesh.face_indices;
    let is_boundary = |h: u32| {
        let e = map.halfedge_edge[h as usize];
        e != u32::MAX && map.halfedges(e as usize).len() == 1
    };
    // Boundary half-edges bucketed by their start vertex, for the fallback step.
    let leaving = Csr::from_entries(
        mesh.vertex_count(),
        (0..fi.len() as u32).filter(|&h| is_boundary(h)).map(|h| (fi[h as usize] as usize, h)),
    );
    if leaving.values().is_empty() {
        return 0;
    }
    let (start, leaving) = leaving.into_parts();
    // `cursor[v]` skips used entries of bucket `v` in the fallback.
    let mut cursor = start.clone();
    let mut used = vec![false; fi.len()];
    let step_limit = fi.len();

    // The boundary half-edge that follows `h` around the hole: rotate around the end
    // vertex of `h` through consistently oriented two-face edges.
    let rotate = |h: u32| -> Option<u32> {
        let mut cur = map.halfedge_next[h as usize];
        for _ in 0..step_limit {
            let e = map.halfedge_edge[cur as usize];
            if e == u32::MAX {
                return None;
            }
            let hs = map.halfedges(e as usize);
            match hs.len() {
                1 => return Some(cur),
                2 => {
                    let other = if hs[0] == cur { hs[1] } else { hs[0] };
                    if fi[other as usize] == fi[cur as usize] {
                        return None; // same direction: orientation flips here
                    }
                    cur = map.halfedge_next[other as usize];
                    if cur == map.halfedge_next[h as usize] {
                        return None;
                    }
                }
                _ => return None,
            }
        }
        None
    };

    let mut loops = 0;
    for h0 in 0..fi.len() as u32 {
        if used[h0 as usize] || !is_boundary(h0) {
            continue;
        }
        loops += 1;
        let mut h = h0;
        used[h as usize] = true;
        loop {
            let mut next = rotate(h).filter(|&n| !used[n as usize] || n == h0);
            if next.is_none() {
                // Fallback: any unused boundary half-edge leaving the end vertex.
                let v = fi[map.halfedge_next[h as usize] as usize] as usize;
                while cursor[v] < start[v + 1] && used[leaving[cursor[v] as usize] as usize] {
                    cursor[v] += 1;
                }
                if cursor[v] < start[v + 1] {
                    next = Some(leaving[cursor[v] as usize]);
                }
            }
            match next {
                Some(n) if n != h0 => {
                    used[n as usize] = true;
                    h = n;
                }
                _ => break,
            }
        }
    }
    loops
}

/// Counts vertices whose incident faces form more than one fan. Corners (half-edges
/// by their start vertex) are listed per vertex with their outgoing edge, incoming
/// edge and face; at each vertex a tiny local union-find joins corners that share an
/// edge (or a face), so the work per vertex stays within its few corners; a vertex
/// with many corners sorts them by edge and face instead.
fn count_pinch_vertices(mesh: &Mesh, map: &EdgeMap) -> usize {
    let fi = &mesh.face_indices;
    let vcount = mesh.vertex_count();
    // [outgoing edge, incoming edge, face] of each corner, grouped by vertex.
    let corners = Csr::from_items(
        vcount,
        0..fi.len(),
        |&h| fi[h] as usize,
        |h| {
            let f = map.halfedge_face[h];
            let start = mesh.face_offsets[f as usize] as usize;
            let prev = if h == start { mesh.face_offsets[f as usize + 1] as usize - 1 } else { h - 1 };
            [map.halfedge_edge[h], map.halfedge_edge[prev], f]
        },
    );
    let mut local: Vec<u32> = Vec::new();
    let mut pinches = 0;
    for v in 0..vcount {
        let cs = corners.bucket(v);
        if cs.len() < 2 {
            continue;
        }
        let fans = if cs.len() > SMALL_BUCKET { fans_by_sorting(cs) } else { fans_pairwise(cs, &mut local) };
        if fans > 1 {
            pinches += 1;
        }
    }
    pinches
}

/// The fans of one vertex's few corners (`[outgoing edge, incoming edge, face]`):
/// corners sharing an edge or a face are joined, pair by pair.
#[allow(clippy::needless_range_loop)] // indices are corner ids
fn fans_pairwise(cs: &[[u32; 3]], local: &mut Vec<u32>) -> usize {
    local.clear();
    local.extend(0..cs.len() as u32);
    let mut groups = cs.len();
    // Quadratic in the corners of one vertex (about six): cheaper than sorting.
    for i in 1..cs.len() {
        let [out_i, in_i, face_i] = cs[i];
        for j in 0..i {
            let [out_j, in_j, face_j] = cs[j];
            let shared_edge = |e: u32| e != u32::MAX && (e == out_j || e == in_j);
            if face_i == face_j || shared_edge(out_i) || shared_edge(in_i) {
                let mut a = i as u32;
                while local[a as usize] != a {
                    a = local[a as usize];
                }
                let mut b = j as u32;
                while local[b as usize] != b {
                    b = local[b as usize];
                }
                if a != b {
                    local[a.max(b) as usize] = a.min(b);
                    groups -= 1;
                }
            }
        }
    }
    groups
}

/// Corners of one vertex (or faces on one edge) beyond which the pairwise tests give
/// way to sorting: a vertex or edge shared by N faces (a book of N pages, N identical
/// triangles) made them quadratic (32k pages: 5.5 s).
const SMALL_BUCKET: usize = 32;

/// The fans of one vertex's corners (`[outgoing edge, incoming edge, face]`, edges
/// `u32::MAX` where none) when they are many: corners sharing an edge or a face are
/// joined, as the pairwise test does, through their sorted keys; O(k log k).
fn fans_by_sorting(cs: &[[u32; 3]]) -> usize {
    // (kind, id, corner): kind 0 for an edge, 1 for a face.
    let mut keys: Vec<(u8, u32, u32)> = Vec::with_capacity(cs.len() * 3);
    for (i, &[out, inc, face]) in cs.iter().enumerate() {
        for e in [out, inc].into_iter().filter(|&e| e != u32::MAX) {
            keys.push((0, e, i as u32));
        }
        keys.push((1, face, i as u32));
    }
    keys.sort_unstable();
    let mut fans = UnionFind::new(cs.len());
    let mut groups = cs.len();
    for w in keys.windows(2) {
        if (w[0].0, w[0].1) == (w[1].0, w[1].1) && fans.union(w[0].2, w[1].2) {
            groups -= 1;
        }
    }
    groups
}

/// Counts edge-connected components of faces.
fn count_edge_components(mesh: &Mesh, map: &EdgeMap) -> usize {
    let mut uf = UnionFind::new(mesh.face_count());
    for e in 0..map.edge_count() {
        let hs = map.halfedges(e);
        let f0 = map.halfedge_face[hs[0] as usize];
        for &h in &hs[1..] {
            uf.union(f0, map.halfedge_face[h as usize]);
        }
    }
    (0..mesh.face_count() as u32).filter(|&f| uf.find(f) == f).count()
}


/// Counts groups of referenced vertices joined by faces.
fn count_vertex_components(mesh: &Mesh, referenced: &[bool]) -> usize {
    let mut uf = UnionFind::new(mesh.vertex_count());
    for face in mesh.faces() {
        for &v in &face[1..] {
            uf.union(face[0], v);
        }
    }
    (0..mesh.vertex_count() as u32).filter(|&v| referenced[v as usize] && uf.find(v) == v).count()
}

/// Counts faces with a repeated index or zero area.
fn count_degenerate_faces(mesh: &Mesh) -> usize {
    let mut scratch: Vec<u32> = Vec::new();
    let mut count = 0;
    for face in mesh.faces() {
        let repeated = if face.len() <= 8 {
            (0..face.len()).any(|a| (a + 1..face.len()).any(|b| face[a] == face[b]))
        } else {
            scratch.clear();
            scratch.extend_from_slice(face);
            scratch.sort_unstable();
            scratch.windows(2).any(|w| w[0] == w[1])
        };
        if repeated || newell_normal(mesh, face) == [0.0; 3] {
            count += 1;
        }
    }
    count
}

/// The Newell normal of a polygon (twice its area vector), in f64.
fn newell_normal(mesh: &Mesh, face: &[u32]) -> [f64; 3] {
    let p = |i: u32| {
        let q = mesh.positions[i as usize];
        [q[0] as f64, q[1] as f64, q[2] as f64]
    };
    if face.len() == 3 {
        return crate::vec3::tri_normal(p(face[0]), p(face[1]), p(face[2]));
    }
    let mut n = [0.0f64; 3];
    for i in 0..face.len() {
        let a = p(face[i]);
        let b = p(face[(i + 1) % face.len()]);
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    n
}

/// Counts faces that repeat an earlier face up to rotation and orientation. Such a
/// face shares every edge with its twin, so only faces on its first edge are
/// candidates; faces without any edge (all corners on one vertex) are compared apart.
fn count_duplicate_faces(mesh: &Mesh, map: &EdgeMap) -> usize {
    let mut count = 0;
    let mut edgeless: Vec<(u32, u32)> = Vec::new();
    // For faces whose first edge carries many faces: whether an earlier face on it has
    // the same cycle, found by sorting that edge's faces once (see `mark_repeats_on_edge`).
    let mut sorted_edge = vec![false; map.edge_count()];
    let mut repeat = vec![false; mesh.face_count()];
    for f in 0..mesh.face_count() {
        let (s, t) = (mesh.face_offsets[f], mesh.face_offsets[f + 1]);
        let Some(h) = (s..t).find(|&h| map.halfedge_edge[h as usize] != u32::MAX) else {
            edgeless.push((mesh.face_indices[s as usize], t - s));
            continue;
        };
        let face = mesh.face(f);
        let e = map.halfedge_edge[h as usize] as usize;
        let hs = map.halfedges(e);
        let is_dup = if hs.len() > SMALL_BUCKET {
            if !sorted_edge[e] {
                mark_repeats_on_edge(mesh, map, e, &mut repeat);
                sorted_edge[e] = true;
            }
            repeat[f]
        } else {
            hs.iter().any(|&g| {
                let gf = map.halfedge_face[g as usize] as usize;
                gf < f && same_cycle(face, mesh.face(gf))
            })
        };
        if is_dup {
            count += 1;
        }
    }
    edgeless.sort_unstable();
    count + edgeless.windows(2).filter(|w| w[0] == w[1]).count()
}

/// Sets `repeat[f]` for every face `f` on edge `e` that repeats an earlier face on
/// `e` (the same cycle up to rotation and orientation): the faces are sorted by their
/// canonical cycle, then by id, and all but the first of each run repeat. A face's
/// earlier twin shares all its edges, so the answer does not depend on the edge.
fn mark_repeats_on_edge(mesh: &Mesh, map: &EdgeMap, e: usize, repeat: &mut [bool]) {
    let mut faces: Vec<u32> = map.halfedges(e).iter().map(|&h| map.halfedge_face[h as usize]).collect();
    faces.sort_unstable();
    faces.dedup();
    let mut keyed: Vec<(Vec<u32>, u32)> = faces.iter().map(|&f| (canonical_cycle(mesh.face(f as usize)), f)).collect();
    keyed.sort_unstable();
    for w in keyed.windows(2) {
        if w[0].0 == w[1].0 {
            repeat[w[1].1 as usize] = true;
        }
    }
}

/// The least of a cycle's rotations and reversed rotations: equal for two faces
/// exactly when [`same_cycle`] holds.
fn canonical_cycle(a: &[u32]) -> Vec<u32> {
    let k = a.len();
    let Some(&low) = a.iter().min() else { return Vec::new() };
    let mut best: Option<Vec<u32>> = None;
    for j in (0..k).filter(|&j| a[j] == low) {
        for c in [(0..k).map(|i| a[(j + i) % k]).collect::<Vec<u32>>(), (0..k).map(|i| a[(j + k - i) % k]).collect()] {
            if best.as_ref().is_none_or(|b| c < *b) {
                best = Some(c);
            }
        }
    }
    best.unwrap_or_default()
}

/// True when `b` is `a` rotated, possibly reversed.
fn same_cycle(a: &[u32], b: &[u32]) -> bool {
    let k = a.len();
    if b.len() != k {
        return false;
    }
    (0..k).filter(|&j| b[j] == a[0]).any(|j| {
        (0..k).all(|i| a[i] == b[(j + i) % k]) || (0..k).all(|i| a[i] == b[(j + k - i) % k])
    })
}

impl fmt::Display for MeshFacts {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "vertices              {} ({} unreferenced)", self.vertices, self.unreferenced_vertices)?;
        writeln!(
            f,
            "faces                 {} ({} triangles, {} quads, {} polygons; {} triangles after fanning)",
            self.faces, self.triangles, self.quads, self.polygons, self.fan_triangles
        )?;
        writeln!(f, "edges                 {}", self.edges)?;
        writeln!(f, "boundary edges        {} in {} loops", self.boundary_edges, self.boundary_loops)?;
        writeln!(f, "non-manifold edges    {}", self.nonmanifold_edges)?;
        writeln!(f, "non-manifold vertices {}", self.nonmanifold_vertices)?;
        writeln!(
            f,
            "components            {} ({} when only shared edges connect)",
            self.components, self.edge_components
        )?;
        writeln!(f, "euler characteristic  {}", self.euler_characteristic)?;
        writeln!(f, "degenerate faces      {}", self.degenerate_faces)?;
        writeln!(f, "duplicate faces       {}", self.duplicate_faces)?;
        writeln!(
            f,
            "consistently oriented {}{}",
            if self.consistently_oriented { "yes" } else { "no" },
            if self.consistently_oriented { String::new() } else { format!(" ({} edges disagree)", self.inconsistent_edges) }
        )?;
        write!(f, "closed manifold       {}", if self.closed_manifold { "yes" } else { "no" })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (xorshift), enough for test corners.
    fn next(state: &mut u64) -> u64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        *state
    }

    #[test]
    fn sorted_fans_agree_with_the_pairwise_test() {
        let mut state = 0x9e37_79b9_7f4a_7c15;
        let mut b = Vec::new();
        for round in 0..2000 {
            let k = 2 + (next(&mut state) % 40) as usize;
            let ids = 1 + (next(&mut state) % (round as u64 % 60 + 1)) as u32;
            let mut pick = |none: bool| {
                let x = (next(&mut state) % (ids as u64 + 1)) as u32;
                if none && x == ids {
                    u32::MAX
                } else {
                    x % ids
                }
            };
            let cs: Vec<[u32; 3]> = (0..k).map(|_| [pick(true), pick(true), pick(false)]).collect();
            assert_eq!(fans_by_sorting(&cs), fans_pairwise(&cs, &mut b), "{cs:?}");
        }
    }

    #[test]
    fn canonical_cycles_are_equal_exactly_for_the_same_cycle() {
        let mut state = 0x2545_f491_4f6c_dd1d;
        for _ in 0..5000 {
            let k = 1 + (next(&mut state) % 6) as usize;
            let range = 1 + next(&mut state) % 4;
            let a: Vec<u32> = (0..k).map(|_| (next(&mut state) % range) as u32).collect();
            let b: Vec<u32> = (0..k).map(|_| (next(&mut state) % range) as u32).collect();
            assert_eq!(canonical_cycle(&a) == canonical_cycle(&b), same_cycle(&a, &b), "{a:?} {b:?}");
            // Every rotation and reversal of a face has its canonical cycle.
            for j in 0..k {
                let rot: Vec<u32> = (0..k).map(|i| a[(j + i) % k]).collect();
                let rev: Vec<u32> = (0..k).map(|i| a[(j + k - i) % k]).collect();
                assert_eq!(canonical_cycle(&rot), canonical_cycle(&a));
                assert_eq!(canonical_cycle(&rev), canonical_cycle(&a));
            }
        }
    }
}

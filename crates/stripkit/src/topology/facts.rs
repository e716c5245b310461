//! Facts about a mesh's topology: what `stripkit stats` prints.
//!
//! [`MeshFacts::of`] computes every figure in one pass over flat arrays (an
//! [`EdgeMap`], two union-finds over half-edges and faces, a bucketed duplicate
//! search), in O(n) apart from sorting the few faces that share a lowest vertex.
//!
//! Definitions (the ones `../shared/models/README.md` uses for its table):
//!
//! * an edge's *incident faces* are its half-edges (face corners running along it);
//! * **boundary edge**: exactly one incident face; **non-manifold edge**: three or more;
//! * **boundary loop**: a closed walk along boundary half-edges; at a vertex where
//!   several boundary walks meet, the walk turns to the next boundary half-edge found
//!   by rotating through the fan of faces it arrived through (the loops of the surface
//!   once every pinch vertex is split into one copy per fan: two triangles sharing a
//!   vertex have two loops, two holes of a grid touching at one corner form one
//!   figure-eight loop); every boundary half-edge is used once, so the walk ends;
//! * **non-manifold (pinch) vertex**: the faces around the vertex form more than one
//!   group when two faces are joined if they share an edge incident to the vertex
//!   (any edge with two or more faces, non-manifold edges included);
//! * **component**: faces joined across shared edges; unreferenced vertices form none;
//! * **Euler characteristic** χ = V_used − E + F;
//! * **degenerate face**: a repeated vertex index, or zero area (exactly zero Newell
//!   normal in `f64`);
//! * **duplicate face**: the same vertices (as a multiset, any rotation or orientation)
//!   as an earlier face; each such later face counts once;
//! * **consistently oriented**: no edge with exactly two faces is traversed in the same
//!   direction by both.

use super::EdgeMap;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use std::fmt;

/// Topological and combinatorial facts about a mesh (see the module docs for the
/// definitions). Serialises to one flat JSON object.
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
    /// Edge-connected components of faces.
    pub components: usize,
    /// χ = V_used − E + F.
    pub euler_characteristic: i64,
    /// Faces with a repeated vertex index or zero area.
    pub degenerate_faces: usize,
    /// Faces with the same vertices as an earlier face.
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

/// Union-find over `0..n` with path halving and union by size.
pub(crate) struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    pub(crate) fn new(n: usize) -> Self {
        UnionFind { parent: (0..n as u32).collect() }
    }

    pub(crate) fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let grand = self.parent[self.parent[x as usize] as usize];
            self.parent[x as usize] = grand;
            x = grand;
        }
        x
    }

    pub(crate) fn union(&mut self, a: u32, b: u32) {
        let ra = self.find(a);
        let rb = self.find(b);
        if ra != rb {
            // Attach the larger id under the smaller: deterministic, and path halving
            // keeps the trees shallow enough for meshes.
            let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
            self.parent[hi as usize] = lo;
        }
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
    pub fn with_edge_map(mesh: &Mesh, map: &EdgeMap) -> MeshFacts {
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

        // Edges by incidence.
        facts.edges = map.edge_count();
        for e in 0..map.edge_count() {
            let hs = map.halfedges(e);
            match hs.len() {
                1 => facts.boundary_edges += 1,
                2 => {
                    if fi[hs[0] as usize] == fi[hs[1] as usize] {
                        facts.inconsistent_edges += 1;
                    }
                }
                n if n >= 3 => facts.nonmanifold_edges += 1,
                _ => {}
            }
        }
        facts.consistently_oriented = facts.inconsistent_edges == 0;
        facts.euler_characteristic = used as i64 - facts.edges as i64 + fcount as i64;

        facts.boundary_loops = count_boundary_loops(mesh, map);
        facts.nonmanifold_vertices = count_pinch_vertices(mesh, map);
        facts.components = count_components(mesh, map);
        facts.degenerate_faces = count_degenerate_faces(mesh);
        facts.duplicate_faces = count_duplicate_faces(mesh);
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
    let vcount = mesh.vertex_count();
    let mut start = vec![0u32; vcount + 1];
    let mut boundary_count = 0usize;
    for h in 0..fi.len() as u32 {
        if is_boundary(h) {
            start[fi[h as usize] as usize + 1] += 1;
            boundary_count += 1;
        }
    }
    if boundary_count == 0 {
        return 0;
    }
    for v in 0..vcount {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut leaving = vec![0u32; boundary_count];
    for h in 0..fi.len() as u32 {
        if is_boundary(h) {
            let v = fi[h as usize] as usize;
            leaving[fill[v] as usize] = h;
            fill[v] += 1;
        }
    }
    // `fill[v]` now marks the end; `cursor[v]` skips used entries in the fallback.
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
                while cursor[v] < fill[v] && used[leaving[cursor[v] as usize] as usize] {
                    cursor[v] += 1;
                }
                if cursor[v] < fill[v] {
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

/// Counts vertices whose incident faces form more than one fan. Works on corners
/// (half-edges by their start vertex): two corners at the same vertex are joined when
/// their faces share an edge incident to it, or when they belong to the same face.
fn count_pinch_vertices(mesh: &Mesh, map: &EdgeMap) -> usize {
    let fi = &mesh.face_indices;
    let mut uf = UnionFind::new(fi.len());
    for e in 0..map.edge_count() {
        let hs = map.halfedges(e);
        if hs.len() < 2 {
            continue;
        }
        let [lo, _] = map.edges[e];
        // The corner of face(h) at vertex x is the half-edge of that face leaving x:
        // h itself if h starts at x, else next(h).
        let corner_at = |h: u32, x: u32| if fi[h as usize] == x { h } else { map.halfedge_next[h as usize] };
        let first = hs[0];
        for &h in &hs[1..] {
            uf.union(corner_at(first, lo), corner_at(h, lo));
            let hi_first = corner_at(first, map.edges[e][1]);
            uf.union(hi_first, corner_at(h, map.edges[e][1]));
        }
    }
    // A face that visits a vertex twice (degenerate) is still one face around it.
    for face_range in mesh.face_offsets.windows(2) {
        let (s, t) = (face_range[0] as usize, face_range[1] as usize);
        if t - s <= 8 {
            for a in s..t {
                for b in a + 1..t {
                    if fi[a] == fi[b] {
                        uf.union(a as u32, b as u32);
                    }
                }
            }
        }
    }
    let mut groups = vec![0u32; mesh.vertex_count()];
    for h in 0..fi.len() as u32 {
        if uf.find(h) == h {
            groups[fi[h as usize] as usize] += 1;
        }
    }
    groups.iter().filter(|&&g| g > 1).count()
}

/// Counts edge-connected components of faces.
fn count_components(mesh: &Mesh, map: &EdgeMap) -> usize {
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
        let (a, b, c) = (p(face[0]), p(face[1]), p(face[2]));
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
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

/// Counts faces whose sorted vertex list equals that of an earlier face.
fn count_duplicate_faces(mesh: &Mesh) -> usize {
    // Sorted copy of every face, then faces bucketed by their lowest vertex: only faces
    // in one bucket can be equal, and buckets are small.
    let mut sorted = mesh.face_indices.clone();
    for w in mesh.face_offsets.windows(2) {
        sorted[w[0] as usize..w[1] as usize].sort_unstable();
    }
    let fcount = mesh.face_count();
    let vcount = mesh.vertex_count();
    let key = |f: u32| {
        let s = mesh.face_offsets[f as usize] as usize;
        let t = mesh.face_offsets[f as usize + 1] as usize;
        &sorted[s..t]
    };
    let mut start = vec![0u32; vcount + 1];
    for f in 0..fcount as u32 {
        start[key(f)[0] as usize + 1] += 1;
    }
    for v in 0..vcount {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut bucketed = vec![0u32; fcount];
    for f in 0..fcount as u32 {
        let v = key(f)[0] as usize;
        bucketed[fill[v] as usize] = f;
        fill[v] += 1;
    }
    let mut count = 0;
    for v in 0..vcount {
        let bucket = &mut bucketed[start[v] as usize..start[v + 1] as usize];
        if bucket.len() < 2 {
            continue;
        }
        bucket.sort_unstable_by(|&a, &b| key(a).cmp(key(b)).then(a.cmp(&b)));
        count += bucket.windows(2).filter(|w| key(w[0]) == key(w[1])).count();
    }
    count
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
        writeln!(f, "components            {}", self.components)?;
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

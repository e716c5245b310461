//! The mesh model: vertex positions plus polygon faces kept as the file gave them.
//!
//! Faces are stored flat: `face_indices` holds every face's vertex indices one after
//! another, `face_offsets[f]..face_offsets[f + 1]` is the range of face `f`. Triangles,
//! quads and n-gons live side by side; algorithms that need triangles use
//! [`Mesh::triangulate`], which fans every face from its first vertex and remembers
//! which face each triangle came from.
//!
//! Vertex indices are stable: unreferenced vertices are kept (and reported by the
//! topology module), so strips written out refer to the same vertices as the input.
//!
//! Besides positions, a vertex may carry named [`Attribute`]s (normals, UV sets,
//! colours, ...), and faces may belong to [`Group`]s (materials); see [`attr`].

pub mod attr;
pub mod io;
pub(crate) mod order;
mod weld;

pub use attr::{Attribute, Group, Scalar};
pub use weld::{weld_map, weld_map_with};

use crate::error::{Error, Result};

/// A polygon mesh: positions and faces of three or more vertices.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// Vertex positions, indexed by `u32` vertex ids.
    pub positions: Vec<[f32; 3]>,
    /// Start of each face in `face_indices`, plus one final entry equal to
    /// `face_indices.len()`. Always holds at least the leading `0`.
    pub face_offsets: Vec<u32>,
    /// Vertex indices of all faces, concatenated.
    pub face_indices: Vec<u32>,
    /// Other per-vertex data (normals, UVs, colours, ...), each with one value per
    /// vertex.
    pub attributes: Vec<Attribute>,
    /// The group of each face, or empty when every face is in group 0.
    pub face_groups: Vec<u32>,
    /// The groups (materials) faces refer to; may be empty when `face_groups` is.
    pub groups: Vec<Group>,
    /// Material libraries the file names (OBJ `mtllib`), written back as they were.
    pub material_libraries: Vec<String>,
}

/// Triangles of a mesh, one `[a, b, c]` per triangle, each remembering its face.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Triangles {
    /// The triangles, in face order; a face of `k` vertices gives `k - 2` triangles.
    pub tris: Vec<[u32; 3]>,
    /// `face_of[t]` is the index of the mesh face triangle `t` came from.
    pub face_of: Vec<u32>,
}

impl Default for Mesh {
    /// The same as [`Mesh::new`]: the face offsets hold their leading `0`.
    fn default() -> Self {
        Mesh::new()
    }
}

impl Mesh {
    /// An empty mesh (no vertices, no faces).
    pub fn new() -> Self {
        Mesh {
            positions: Vec::new(),
            face_offsets: vec![0],
            face_indices: Vec::new(),
            attributes: Vec::new(),
            face_groups: Vec::new(),
            groups: Vec::new(),
            material_libraries: Vec::new(),
        }
    }

    /// A mesh whose faces are the given triangles.
    pub fn from_triangles(positions: Vec<[f32; 3]>, tris: &[[u32; 3]]) -> Self {
        let mut mesh = Mesh { positions, ..Mesh::new() };
        mesh.face_offsets.reserve(tris.len());
        mesh.face_indices.reserve(tris.len() * 3);
        for t in tris {
            mesh.push_face(t);
        }
        mesh
    }

    /// A mesh from positions and a list of polygon faces.
    pub fn from_polygons<F: AsRef<[u32]>>(positions: Vec<[f32; 3]>, faces: &[F]) -> Self {
        let mut mesh = Mesh { positions, ..Mesh::new() };
        for f in faces {
            mesh.push_face(f.as_ref());
        }
        mesh
    }

    /// Appends a face. The caller guarantees at least three indices; readers check
    /// this (and index ranges) before calling.
    pub fn push_face(&mut self, indices: &[u32]) {
        if self.face_offsets.is_empty() {
            self.face_offsets.push(0);
        }
        self.face_indices.extend_from_slice(indices);
        self.face_offsets.push(self.face_indices.len() as u32);
    }

    /// Checks that the faces are well formed: offsets from 0 to the end of
    /// `face_indices`, never decreasing; every face of at least 3 corners; every index
    /// below the vertex count, which fits 32 bits; every attribute one value per
    /// vertex; face groups empty or one per face, each naming a group.
    /// [`Error::Invalid`] names the first fault. (Coordinates are not checked.)
    /// O(faces + indices).
    ///
    /// [`Error::Invalid`]: crate::Error::Invalid
    pub fn check_faces(&self) -> Result<()> {
        let n = self.vertex_count();
        if n > u32::MAX as usize {
            return Err(Error::Invalid(format!("{n} vertices do not fit 32-bit indices")));
        }
        let offsets = &self.face_offsets;
        if offsets.first().is_some_and(|&o| o != 0)
            || offsets.last().is_some_and(|&o| o as usize != self.face_indices.len())
            || offsets.windows(2).any(|w| w[1] < w[0])
        {
            return Err(Error::Invalid("the mesh's face offsets are malformed".into()));
        }
        for (f, face) in self.faces().enumerate() {
            if face.len() < 3 {
                return Err(Error::Invalid(format!("face {f} has {} corners; a face needs at least 3", face.len())));
            }
            if let Some(&v) = face.iter().find(|&&v| v as usize >= n) {
                return Err(Error::Invalid(format!("face {f} refers to vertex {v} but the mesh has {n} vertices")));
            }
        }
        self.check_attributes()
    }

    /// The attribute and group half of [`Mesh::check_faces`]: every attribute one whole
    /// value per vertex, face groups empty or one per face, each naming a group.
    pub(crate) fn check_attributes(&self) -> Result<()> {
        attr::check(&self.attributes, &self.face_groups, &self.groups, self.vertex_count(), self.face_count())
    }

    /// The attribute of this name, if the mesh has one.
    pub fn attribute(&self, name: &str) -> Option<&Attribute> {
        self.attributes.iter().find(|a| a.name == name)
    }

    /// Number of face groups: at least 1 (every face in group 0 when `face_groups` is empty).
    pub fn group_count(&self) -> usize {
        self.groups.len().max(1)
    }

    /// The group of face `f`.
    pub fn group_of(&self, f: usize) -> u32 {
        self.face_groups.get(f).copied().unwrap_or(0)
    }

    /// True when faces fall in more than one group, so strips must be built per group.
    pub fn has_groups(&self) -> bool {
        self.face_groups.iter().any(|&g| g != self.face_groups[0])
    }

    /// The vertices `map[0], map[1], ...` of this mesh (positions and attributes), with
    /// no faces: the start of a renumbered or partial copy.
    pub fn gather_vertices(&self, map: &[u32]) -> Mesh {
        Mesh {
            positions: map.iter().map(|&v| self.positions[v as usize]).collect(),
            attributes: self.attributes.iter().map(|a| a.gather(map)).collect(),
            groups: self.groups.clone(),
            material_libraries: self.material_libraries.clone(),
            ..Mesh::new()
        }
    }

    /// Appends the vertex `(1 - t) * a + t * b`, attributes blended by
    /// [`Attribute::push_lerp`]; returns its id.
    pub fn push_vertex_lerp(&mut self, a: u32, b: u32, t: f64) -> u32 {
        let (pa, pb) = (self.positions[a as usize], self.positions[b as usize]);
        self.positions.push([0, 1, 2].map(|k| ((1.0 - t) * pa[k] as f64 + t * pb[k] as f64) as f32));
        for at in &mut self.attributes {
            at.push_lerp(a as usize, b as usize, t);
        }
        (self.positions.len() - 1) as u32
    }

    /// The mesh without unreferenced vertices, kept in their order, and for every old
    /// vertex its new id (`u32::MAX` where dropped). Faces, groups and attributes follow.
    pub fn compact(&self) -> (Mesh, Vec<u32>) {
        let mut new_id = vec![u32::MAX; self.vertex_count()];
        for &v in &self.face_indices {
            new_id[v as usize] = 0;
        }
        for (next, id) in new_id.iter_mut().filter(|id| **id == 0).enumerate() {
            *id = next as u32;
        }
        (self.renumbered(&new_id), new_id)
    }

    /// The mesh with vertex `v` renamed `new_id[v]`: the ids other than `u32::MAX` are
    /// `0..k` in some order, and the vertices marked `u32::MAX` are dropped (no face may
    /// use one). Faces, groups and attributes follow.
    pub fn renumbered(&self, new_id: &[u32]) -> Mesh {
        let mut order = vec![0u32; new_id.iter().filter(|&&id| id != u32::MAX).count()];
        for (v, &id) in new_id.iter().enumerate() {
            if id != u32::MAX {
                order[id as usize] = v as u32;
            }
        }
        let mut out = self.gather_vertices(&order);
        out.face_offsets = self.face_offsets.clone();
        out.face_indices = self.face_indices.iter().map(|&v| new_id[v as usize]).collect();
        out.face_groups = self.face_groups.clone();
        out
    }

    /// The faces `faces` over the vertices they use, kept in increasing id order
    /// (positions and attributes; no groups), and for each vertex of the result its id
    /// in this mesh.
    pub fn submesh(&self, faces: &[u32]) -> (Mesh, Vec<u32>) {
        // Work in the size of `faces` only, never of the whole mesh (no per-vertex flags,
        // no copy of the group list): the group door calls this once per group, and a
        // mesh with one group per face made that quadratic (16k faces: 11 s).
        let mut map: Vec<u32> = faces.iter().flat_map(|&f| self.face(f as usize).iter().copied()).collect();
        map.sort_unstable();
        map.dedup();
        let mut out = Mesh {
            positions: map.iter().map(|&v| self.positions[v as usize]).collect(),
            attributes: self.attributes.iter().map(|a| a.gather(&map)).collect(),
            material_libraries: self.material_libraries.clone(),
            ..Mesh::new()
        };
        out.face_indices.reserve(faces.len() * 3);
        out.face_offsets.reserve(faces.len());
        for &f in faces {
            out.face_indices.extend(self.face(f as usize).iter().map(|&v| map.partition_point(|&m| m < v) as u32));
            out.face_offsets.push(out.face_indices.len() as u32);
        }
        (out, map)
    }

    /// Number of vertex records (referenced or not).
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.face_offsets.len().saturating_sub(1)
    }

    /// The vertex indices of face `f`.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.face_indices[self.face_offsets[f] as usize..self.face_offsets[f + 1] as usize]
    }

    /// Iterates over the faces' index slices.
    pub fn faces(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        self.face_offsets.windows(2).map(move |w| &self.face_indices[w[0] as usize..w[1] as usize])
    }

    /// Number of triangles a fan triangulation gives (a quad counts as two).
    /// Faces of fewer than three corners give none.
    pub fn triangle_count(&self) -> usize {
        self.faces().map(|f| f.len().saturating_sub(2)).sum()
    }

    /// True when every face is a triangle.
    pub fn is_triangle_mesh(&self) -> bool {
        self.faces().all(|f| f.len() == 3)
    }

    /// True when every face is a quad (and there is at least one face).
    pub fn is_quad_mesh(&self) -> bool {
        self.face_count() > 0 && self.faces().all(|f| f.len() == 4)
    }

    /// Fans every face from its first vertex: face `[v0, v1, ..., vk]` gives
    /// `[v0, v1, v2], [v0, v2, v3], ...`, each keeping the face's orientation.
    pub fn triangulate(&self) -> Triangles {
        let n = self.triangle_count();
        let mut out = Triangles { tris: Vec::with_capacity(n), face_of: Vec::with_capacity(n) };
        for (f, face) in self.faces().enumerate() {
            for i in 1..face.len().saturating_sub(1) {
                out.tris.push([face[0], face[i], face[i + 1]]);
                out.face_of.push(f as u32);
            }
        }
        out
    }

    /// The fan triangles of [`Mesh::triangulate`] alone, the mesh consumed: its
    /// vertices and attributes are freed before the list is built, its faces after,
    /// so a check of a big mesh's triangles holds one copy of them at a time.
    pub fn into_triangles(self) -> Vec<[u32; 3]> {
        let Mesh { face_offsets, face_indices, positions, attributes, .. } = self;
        drop((positions, attributes));
        let mut tris = Vec::with_capacity(face_indices.len().saturating_sub(2 * face_offsets.len().saturating_sub(1)));
        for w in face_offsets.windows(2) {
            let face = &face_indices[w[0] as usize..w[1] as usize];
            for i in 1..face.len().saturating_sub(1) {
                tris.push([face[0], face[i], face[i + 1]]);
            }
        }
        tris
    }

    /// The faces alone (`face_offsets`, `face_indices`), the mesh consumed and the rest
    /// of it freed: what a check of a big mesh's triangles reads them from.
    pub(crate) fn into_faces(self) -> (Vec<u32>, Vec<u32>) {
        (self.face_offsets, self.face_indices)
    }

    /// Axis-aligned bounding box `(min, max)`; `None` for a mesh without vertices.
    pub fn bounds(&self) -> Option<([f32; 3], [f32; 3])> {
        let first = *self.positions.first()?;
        let mut lo = first;
        let mut hi = first;
        for p in &self.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        Some((lo, hi))
    }

    /// Positions of the vertices some face uses, in vertex order (unreferenced
    /// vertices left out: what a camera should frame, for instance). O(vertices +
    /// face indices). The faces must be in range ([`Mesh::check_faces`]); panics
    /// otherwise.
    pub fn used_positions(&self) -> Vec<[f32; 3]> {
        let mut used = vec![false; self.vertex_count()];
        for &v in &self.face_indices {
            used[v as usize] = true;
        }
        self.positions.iter().zip(&used).filter(|(_, &u)| u).map(|(p, _)| *p).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygon_faces_fan_into_triangles_with_their_face() {
        let positions = vec![[0.0; 3]; 6];
        let mesh = Mesh::from_polygons(positions, &[vec![0, 1, 2], vec![1, 3, 4, 2], vec![0, 2, 4, 5, 1]]);
        assert_eq!(mesh.face_count(), 3);
        assert_eq!(mesh.triangle_count(), 1 + 2 + 3);
        assert_eq!(mesh.face(1), &[1, 3, 4, 2]);
        let t = mesh.triangulate();
        assert_eq!(t.tris[1], [1, 3, 4]);
        assert_eq!(t.tris[2], [1, 4, 2]);
        assert_eq!(t.face_of, vec![0, 1, 1, 2, 2, 2]);
        assert!(!mesh.is_triangle_mesh());
        let tris = mesh.into_triangles();
        assert_eq!(tris, t.tris);
        assert_eq!(tris.capacity(), 6);
    }

    #[test]
    fn a_submesh_keeps_its_faces_over_the_vertices_they_use() {
        let positions: Vec<[f32; 3]> = (0..6).map(|i| [i as f32, 0.0, 0.0]).collect();
        let mut mesh = Mesh::from_polygons(positions, &[vec![0, 1, 2], vec![5, 3, 4, 1]]);
        mesh.attributes.push(Attribute::from_f32("w", 1, &[10.0, 11.0, 12.0, 13.0, 14.0, 15.0]));
        let (sub, map) = mesh.submesh(&[1]);
        assert_eq!(map, vec![1, 3, 4, 5]);
        assert_eq!(sub.face(0), &[3, 1, 2, 0]);
        assert_eq!(sub.attribute("w").unwrap().value(3), vec![15.0]);
        sub.check_faces().unwrap();
        // renumbered with a permutation: vertex v becomes 3 - v.
        let flipped = sub.renumbered(&[3, 2, 1, 0]);
        assert_eq!(flipped.face(0), &[0, 2, 1, 3]);
        assert_eq!(flipped.positions[0], [5.0, 0.0, 0.0]);
        assert_eq!(flipped.attribute("w").unwrap().value(0), vec![15.0]);
    }

    #[test]
    fn empty_mesh_has_no_faces() {
        let mesh = Mesh::new();
        assert_eq!(mesh.face_count(), 0);
        assert_eq!(mesh.triangle_count(), 0);
        assert!(mesh.triangulate().tris.is_empty());
        assert!(mesh.bounds().is_none());
        assert!(mesh.used_positions().is_empty());
    }

    #[test]
    fn used_positions_leave_out_unreferenced_vertices_in_vertex_order() {
        let positions = (0..5).map(|i| [i as f32, 0.0, 0.0]).collect();
        let mesh = Mesh::from_triangles(positions, &[[3, 1, 4]]);
        assert_eq!(mesh.used_positions(), [[1.0, 0.0, 0.0], [3.0, 0.0, 0.0], [4.0, 0.0, 0.0]]);
    }
}

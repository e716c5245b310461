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

pub mod io;

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
        Mesh { positions: Vec::new(), face_offsets: vec![0], face_indices: Vec::new() }
    }

    /// A mesh whose faces are the given triangles.
    pub fn from_triangles(positions: Vec<[f32; 3]>, tris: &[[u32; 3]]) -> Self {
        let mut mesh = Mesh {
            positions,
            face_offsets: Vec::with_capacity(tris.len() + 1),
            face_indices: Vec::with_capacity(tris.len() * 3),
        };
        mesh.face_offsets.push(0);
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
    /// below the vertex count, which fits 32 bits. [`Error::Invalid`] names the first
    /// face at fault. (Coordinates are not checked.) O(faces + indices).
    ///
    /// [`Error::Invalid`]: crate::Error::Invalid
    pub fn check_faces(&self) -> crate::Result<()> {
        use crate::Error;
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
        Ok(())
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
    }

    #[test]
    fn empty_mesh_has_no_faces() {
        let mesh = Mesh::new();
        assert_eq!(mesh.face_count(), 0);
        assert_eq!(mesh.triangle_count(), 0);
        assert!(mesh.triangulate().tris.is_empty());
        assert!(mesh.bounds().is_none());
    }
}

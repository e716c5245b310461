//! Welding bit-identical vertices: two vertices are one where their positions are
//! equal bit for bit and so is every attribute's stored value (the check meshoptimizer's
//! vertex remap makes). Exporters write flat-shaded meshes unindexed, every triangle
//! with three vertices of its own; welded, their triangles become neighbours that
//! strips can follow (docs/experiments/weld-and-materials.md).

use super::Mesh;
use std::collections::HashMap;

/// For every vertex, the lowest vertex id bit-identical to it (itself where none is
/// lower), and how many vertices map to another. Cost: one pass over the vertex data
/// and a hash map of the distinct vertices.
pub fn weld_map(mesh: &Mesh) -> (Vec<u32>, usize) {
    let n = mesh.vertex_count();
    // Each vertex's key: position bits, then every attribute's bytes.
    let sizes: Vec<usize> = mesh.attributes.iter().map(|a| a.components as usize * a.scalar.size()).collect();
    let stride = 12 + sizes.iter().sum::<usize>();
    let mut keys = Vec::with_capacity(n * stride);
    for v in 0..n {
        for x in mesh.positions[v] {
            keys.extend_from_slice(&x.to_bits().to_le_bytes());
        }
        for (a, &size) in mesh.attributes.iter().zip(&sizes) {
            // An attribute shorter than the vertices (a malformed mesh) keys as absent.
            keys.extend(a.data.get(v * size..(v + 1) * size).map_or_else(|| vec![0xff; size], <[u8]>::to_vec));
        }
    }
    let mut first: HashMap<&[u8], u32> = HashMap::with_capacity(n);
    let mut merged = 0;
    let map = (0..n)
        .map(|v| {
            let key = &keys[v * stride..(v + 1) * stride];
            let rep = *first.entry(key).or_insert(v as u32);
            merged += usize::from(rep != v as u32);
            rep
        })
        .collect();
    (map, merged)
}

impl Mesh {
    /// This mesh with its faces moved onto the lowest of each set of bit-identical
    /// vertices ([`weld_map`]), and how many vertices faces no longer use for that; `None` where no
    /// face uses a vertex that has a bit-identical twin of lower id. Vertex data and
    /// ids stay as they are (the twins are left unused), so strips of the welded mesh
    /// index this mesh's vertices; they draw the same triangles in every attribute.
    pub fn welded(&self) -> Option<(Mesh, usize)> {
        let (map, merged) = weld_map(self);
        if merged == 0 || self.face_indices.iter().all(|&v| map.get(v as usize) == Some(&v)) {
            return None;
        }
        let mut used = vec![false; self.vertex_count()];
        let face_indices: Vec<u32> = self
            .face_indices
            .iter()
            .map(|&v| {
                used[v as usize] = true;
                map[v as usize]
            })
            .collect();
        let moved = (0..self.vertex_count()).filter(|&v| used[v] && map[v] != v as u32).count();
        Some((Mesh { face_indices, ..self.clone() }, moved))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Attribute;

    #[test]
    fn welds_only_where_every_attribute_agrees() {
        // Two triangles sharing an edge, written unindexed; vertex 5 differs from 1 in UV.
        let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]];
        let positions = vec![p[0], p[1], p[2], p[2], p[1], p[1], p[3]];
        let mut mesh = Mesh::from_triangles(positions, &[[0, 1, 2], [3, 4, 6]]);
        let uv = [0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5, 0.0, 1.0, 1.0];
        mesh.attributes.push(Attribute::from_f32("TEXCOORD_0", 2, &uv));
        let (map, merged) = weld_map(&mesh);
        assert_eq!(map, vec![0, 1, 2, 2, 1, 5, 6]);
        assert_eq!(merged, 2);
        let (welded, moved) = mesh.welded().unwrap();
        assert_eq!(moved, 2);
        assert_eq!(welded.face_indices, vec![0, 1, 2, 2, 1, 6]);
        assert_eq!(welded.positions, mesh.positions);
        // -0.0 and 0.0 differ by bits: not welded.
        let signed = Mesh::from_triangles(vec![[0.0; 3], [-0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], &[[0, 2, 1]]);
        assert!(signed.welded().is_none());
    }
}

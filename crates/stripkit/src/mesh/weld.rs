//! Welding bit-identical vertices: two vertices are one where their positions are
//! equal bit for bit and so is every attribute's stored value (the check meshoptimizer's
//! vertex remap makes). Exporters write flat-shaded meshes unindexed, every triangle
//! with three vertices of its own; welded, their triangles become neighbours that
//! strips can follow (docs/experiments/weld-and-materials.md).

use super::Mesh;
use crate::parallel::{map_range, sort_unstable, sort_unstable_by, Threads};

/// For every vertex, the lowest vertex id bit-identical to it (itself where none is
/// lower), and how many vertices map to another. Cost: one pass over the vertex data
/// and a sort of the vertices by a hash of it.
pub fn weld_map(mesh: &Mesh) -> (Vec<u32>, usize) {
    weld_map_with(mesh, Threads::SERIAL)
}

/// [`weld_map`] with its hashing and sorting in parallel when `threads` allows; the
/// same map at any thread count. The vertices are sorted by (hash of their key, key,
/// id), so bit-identical vertices end up side by side, lowest id first, whatever
/// order the sort visits them in.
pub fn weld_map_with(mesh: &Mesh, threads: Threads) -> (Vec<u32>, usize) {
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
            match a.data.get(v * size..(v + 1) * size) {
                Some(bytes) => keys.extend_from_slice(bytes),
                None => keys.extend(std::iter::repeat_n(0xff, size)),
            }
        }
    }
    let key = |v: u32| &keys[v as usize * stride..(v as usize + 1) * stride];
    let hashes: Vec<u64> = map_range(threads, n, |v| hash_key(key(v as u32)));
    // Big meshes mostly have no twins at all: all hashes distinct proves it with a
    // sort of the bare hashes, cheaper than the sort by (hash, key, id) below, and the
    // map is then every vertex itself.
    let mut sorted = hashes.clone();
    sort_unstable(threads, &mut sorted);
    if sorted.windows(2).all(|w| w[0] != w[1]) {
        return ((0..n as u32).collect(), 0);
    }
    drop(sorted);
    let mut order: Vec<(u64, u32)> = hashes.into_iter().zip(0..n as u32).collect();
    sort_unstable_by(threads, &mut order, |a, b| {
        a.0.cmp(&b.0).then_with(|| key(a.1).cmp(key(b.1))).then(a.1.cmp(&b.1))
    });
    let mut map = vec![0u32; n];
    let mut merged = 0;
    let mut i = 0;
    while i < n {
        let (hash, rep) = order[i];
        map[rep as usize] = rep;
        i += 1;
        while i < n && order[i].0 == hash && key(order[i].1) == key(rep) {
            map[order[i].1 as usize] = rep;
            merged += 1;
            i += 1;
        }
    }
    (map, merged)
}

/// A 64-bit hash of a vertex key (FxHash's step over 8-byte words, then a final mix).
fn hash_key(key: &[u8]) -> u64 {
    const K: u64 = 0x517c_c1b7_2722_0a95;
    let mut h: u64 = key.len() as u64;
    let mut words = key.chunks_exact(8);
    for w in &mut words {
        let x = u64::from_le_bytes(w.try_into().unwrap_or([0; 8]));
        h = (h.rotate_left(5) ^ x).wrapping_mul(K);
    }
    let mut tail = [0u8; 8];
    tail[..words.remainder().len()].copy_from_slice(words.remainder());
    h = (h.rotate_left(5) ^ u64::from_le_bytes(tail)).wrapping_mul(K);
    h ^ (h >> 29)
}

impl Mesh {
    /// This mesh with its faces moved onto the lowest of each set of bit-identical
    /// vertices ([`weld_map`]), and how many vertices faces no longer use for that; `None` where no
    /// face uses a vertex that has a bit-identical twin of lower id. Vertex data and
    /// ids stay as they are (the twins are left unused), so strips of the welded mesh
    /// index this mesh's vertices; they draw the same triangles in every attribute.
    pub fn welded(&self) -> Option<(Mesh, usize)> {
        self.welded_with(Threads::SERIAL)
    }

    /// [`Mesh::welded`] with [`weld_map_with`]: the same mesh at any thread count.
    pub fn welded_with(&self, threads: Threads) -> Option<(Mesh, usize)> {
        let (map, merged) = weld_map_with(self, threads);
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
        // Every field but the faces' indices cloned (those are remapped above).
        let mesh = Mesh {
            positions: self.positions.clone(),
            face_offsets: self.face_offsets.clone(),
            face_indices,
            attributes: self.attributes.clone(),
            face_groups: self.face_groups.clone(),
            groups: self.groups.clone(),
            material_libraries: self.material_libraries.clone(),
        };
        Some((mesh, moved))
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

//! The canonical copy of a mesh that [`super::stripify_mesh`] runs on: vertices
//! renumbered by position (Z-order), faces sorted, so that the strips do not depend on
//! the order of the faces or the vertex ids.

use crate::strip::StripSet;
use crate::stripify::quad_adjacency::is_quad;
use crate::topology::{sort_bucket, Csr};

/// A mesh's vertices renumbered in an order that depends only on the geometry, so that
/// the stripifier sees the same input whatever the order of the faces and the ids of
/// the vertices: by the Morton code (Z-order) of their positions quantized to 21 bits
/// per axis in the bounding box, then by a mix of the exact coordinates, then by id
/// (only for coincident vertices). Z-order keeps neighbours close in memory (measured:
/// the cache run about 1.6x faster than in x-then-y-then-z order on a 1.1M-triangle
/// mesh, about the same strips).
pub(super) struct Canonical {
    /// The new id of every input vertex, and the input id of every new one.
    new: Vec<u32>,
    old: Vec<u32>,
}

impl Canonical {
    /// The order of `mesh`'s vertices; the keys are made and sorted in parallel when
    /// `threads` allows (every key is distinct: the same order at any thread count).
    pub(super) fn of(mesh: &crate::mesh::Mesh, threads: crate::parallel::Threads) -> Canonical {
        // f32 bits in an order that sorts like the numbers (a total order).
        let k = |x: f32| {
            let b = x.to_bits();
            if b >> 31 == 1 {
                !b
            } else {
                b | 1 << 31
            }
        };
        let (lo, hi) = mesh.bounds().unwrap_or(([0.0; 3], [1.0; 3]));
        let q = |x: f32, i: usize| -> u64 {
            let span = (hi[i] - lo[i]).max(f32::MIN_POSITIVE);
            (((x - lo[i]) / span).clamp(0.0, 1.0) * 2097151.0) as u64
        };
        let spread = |mut x: u64| {
            x &= 0x1f_ffff;
            x = (x | x << 32) & 0x1f00000000ffff;
            x = (x | x << 16) & 0x1f0000ff0000ff;
            x = (x | x << 8) & 0x100f00f00f00f00f;
            x = (x | x << 4) & 0x10c30c30c30c30c3;
            (x | x << 2) & 0x1249249249249249
        };
        let mut keys: Vec<u128> = crate::parallel::map_range(threads, mesh.positions.len(), |v| {
            let p = mesh.positions[v];
            let m = spread(q(p[0], 0)) | spread(q(p[1], 1)) << 1 | spread(q(p[2], 2)) << 2;
            let exact = k(p[0]) ^ k(p[1]).rotate_left(11) ^ k(p[2]).rotate_left(22);
            u128::from(m) << 64 | u128::from(exact) << 32 | v as u128
        });
        crate::parallel::sort_unstable(threads, &mut keys);
        let old: Vec<u32> = keys.iter().map(|&key| key as u32).collect();
        let mut new = vec![0u32; old.len()];
        for (i, &v) in old.iter().enumerate() {
            new[v as usize] = i as u32;
        }
        Canonical { new, old }
    }

    /// The fan of every face (from the face's own first corner), in new ids, each
    /// triangle starting at its lowest id, sorted: the same list for any face order,
    /// any vertex ids and any rotation of a triangle.
    /// The renumbering runs in parallel when `threads` allows.
    pub(super) fn fan(&self, mesh: &crate::mesh::Mesh, threads: crate::parallel::Threads) -> Vec<[u32; 3]> {
        let mut tris = mesh.triangulate().tris;
        crate::parallel::for_each_mut(threads, &mut tris, |t| {
            *t = [self.new[t[0] as usize], self.new[t[1] as usize], self.new[t[2] as usize]];
            let r = (0..3).min_by_key(|&i| t[i]).unwrap_or(0);
            t.rotate_left(r);
        });
        // Sorted: bucketed by the first (lowest) id, each bucket (about two triangles)
        // sorted on its own. O(triangles + vertices) for bounded valence, O(t log t)
        // at worst.
        let n = self.old.len();
        let mut out = Csr::from_entries(n, tris.iter().map(|t| (t[0] as usize, *t)));
        for v in 0..n {
            sort_bucket(out.bucket_mut(v));
        }
        out.into_parts().1
    }

    /// The mesh in new ids, faces sorted, triangles and quads starting at their lowest
    /// id (for QSTRIP, which splits the quads itself); any other face keeps its own
    /// first corner, since its fan is part of the input: a larger polygon, and a face
    /// of four corners that repeats a vertex (no quad to QSTRIP or to the quad-level
    /// check, which fan it: `(5, 1, 5, 2)` fans to two degenerate triangles, while
    /// from its lowest corner, `(1, 5, 2, 5)`, it would fan to two real ones).
    pub(super) fn rotated(&self, mesh: &crate::mesh::Mesh) -> crate::mesh::Mesh {
        let mut ids: Vec<u32> = mesh.face_indices.iter().map(|&v| self.new[v as usize]).collect();
        let range = |f: usize| mesh.face_offsets[f] as usize..mesh.face_offsets[f + 1] as usize;
        let mut shift = vec![0usize; mesh.face_count()];
        for f in 0..mesh.face_count() {
            let face = &mut ids[range(f)];
            let r = (0..face.len()).min_by_key(|&i| face[i]).unwrap_or(0);
            face.rotate_left(r);
            shift[f] = r;
        }
        let mut order: Vec<u32> = (0..mesh.face_count() as u32).collect();
        order.sort_unstable_by(|&x, &y| ids[range(x as usize)].cmp(&ids[range(y as usize)]));
        let mut out = crate::mesh::Mesh {
            positions: self.old.iter().map(|&v| mesh.positions[v as usize]).collect(),
            ..crate::mesh::Mesh::new()
        };
        out.face_indices.reserve(ids.len());
        for &f in &order {
            let face = &ids[range(f as usize)];
            if face.len() <= 3 || is_quad(face) {
                out.face_indices.extend_from_slice(face);
            } else {
                // Back to the input's first corner.
                let k = face.len() - shift[f as usize];
                out.face_indices.extend_from_slice(&face[k % face.len()..]);
                out.face_indices.extend_from_slice(&face[..k % face.len()]);
            }
            out.face_offsets.push(out.face_indices.len() as u32);
        }
        out
    }

    /// Frees the new ids ([`Canonical::fan`] and [`Canonical::rotated`] need them; the
    /// way back does not).
    pub(super) fn forget_new(&mut self) {
        self.new = Vec::new();
    }

    /// The strips in input ids (in parallel when `threads` allows; each index on its own).
    pub(super) fn strips_back(&self, mut s: StripSet, threads: crate::parallel::Threads) -> StripSet {
        crate::parallel::for_each_mut(threads, &mut s.indices, |v| *v = self.old[*v as usize]);
        s
    }

    /// The triangles in input ids (in parallel when `threads` allows).
    pub(super) fn triangles_back(&self, mut t: Vec<[u32; 3]>, threads: crate::parallel::Threads) -> Vec<[u32; 3]> {
        crate::parallel::for_each_mut(threads, &mut t, |tri| *tri = tri.map(|v| self.old[v as usize]));
        t
    }
}

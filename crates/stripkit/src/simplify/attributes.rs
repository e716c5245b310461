//! Attributes through simplification: the survivor of a collapse keeps its own values
//! at its own position (endpoint placement) and is interpolated along the collapsed
//! edge elsewhere; seam vertices (two used vertices at one position: the sides of a
//! UV or normal seam) are never removed nor moved, so a seam cannot open and no
//! triangle takes values from the other side.

use super::quadric::{dot, sub, V3};
use crate::mesh::Mesh;
use crate::mesh::Attribute;
use std::collections::HashMap;

/// The seam vertices of `mesh` (kept in place by the collapses): used vertices at the same
/// position as another used vertex. Empty when the mesh has no attributes (nothing
/// tells a seam from a mesh that is merely unwelded there).
pub(crate) fn seam_vertices(mesh: &Mesh) -> Vec<bool> {
    if mesh.attributes.is_empty() {
        return Vec::new();
    }
    let mut used = vec![false; mesh.vertex_count()];
    mesh.face_indices.iter().for_each(|&v| used[v as usize] = true);
    let mut first: HashMap<[u32; 3], u32> = HashMap::new();
    let mut locked = vec![false; mesh.vertex_count()];
    for (v, p) in mesh.positions.iter().enumerate().filter(|&(v, _)| used[v]) {
        // +0.0 and -0.0 are one position.
        let key = p.map(|x| if x == 0.0 { 0 } else { x.to_bits() });
        match first.entry(key) {
            std::collections::hash_map::Entry::Occupied(o) => {
                locked[*o.get() as usize] = true;
                locked[v] = true;
            }
            std::collections::hash_map::Entry::Vacant(e) => {
                e.insert(v as u32);
            }
        }
    }
    locked
}

/// The attributes of survivor `k` after the collapse r -> k at `p`, where `ends` are
/// k's and r's positions before it: k's own values when p is k's position (endpoint
/// placement), else interpolated towards r's by p's projection onto the edge.
pub(crate) fn carry(attributes: &mut [Attribute], r: u32, k: u32, ends: [V3; 2], p: V3) {
    if p == ends[0] {
        return;
    }
    for a in attributes.iter_mut() {
        // Appended, read back into k, then dropped.
        let last = a.len();
        push_carried(a, r, k, ends, p);
        let stride = a.stride();
        let value = a.data[last * stride..].to_vec();
        a.data[k as usize * stride..(k as usize + 1) * stride].copy_from_slice(&value);
        a.data.truncate(last * stride);
    }
}

/// Appends to `a` the value [`carry`] gives survivor `k` of the collapse r -> k at
/// `p` (`ends`: k's and r's positions before it): k's own at k's position, else
/// push_lerp's rule by kind (normalized and float values blend by p's projection
/// onto the edge, integer ones take the nearer end), `NORMAL` and `TANGENT` made
/// unit again. The rule every path shares: the simplifier, the replay of its
/// sequence and the optimal-placement vertices of the level-of-detail models.
pub(crate) fn push_carried(a: &mut Attribute, r: u32, k: u32, ends: [V3; 2], p: V3) {
    if p == ends[0] {
        a.push_from_self(k as usize);
        return;
    }
    let e = sub(ends[1], ends[0]);
    let len2 = dot(e, e);
    let t = if len2 > 0.0 { (dot(sub(p, ends[0]), e) / len2).clamp(0.0, 1.0) } else { 0.5 };
    let last = a.len();
    a.push_lerp(k as usize, r as usize, t);
    unit_directions(a, last..last + 1);
}

/// A position as the files and the sequence store it (f32), widened again: the
/// simplifier carries attributes over these, so that a replay of the recorded
/// positions gives the same values bit for bit.
pub(crate) fn stored(p: V3) -> V3 {
    p.map(|x| x as f32 as f64)
}

/// Blends of unit vectors are shorter than 1: makes `NORMAL` (x, y, z) and `TANGENT`
/// (x, y, z; w back to +1 or -1) unit again at `vertices`, as glTF requires; other
/// attributes are left alone. A zero-length blend stays as it is.
pub(crate) fn unit_directions(a: &mut Attribute, vertices: std::ops::Range<usize>) {
    let tangent = match a.name.as_str() {
        "NORMAL" if a.components >= 3 => false,
        "TANGENT" if a.components == 4 => true,
        _ => return,
    };
    if !(a.scalar.is_float() || a.normalized) {
        return;
    }
    let unit = a.unit();
    for v in vertices {
        let xyz = [0, 1, 2].map(|c| a.get(v, c) * unit);
        let len = dot(xyz, xyz).sqrt();
        if len > 0.0 {
            for (c, x) in xyz.iter().enumerate() {
                a.set(v, c, x / len / unit);
            }
        }
        if tangent {
            let w = if a.get(v, 3) < 0.0 { -1.0 } else { 1.0 };
            a.set(v, 3, w / unit);
        }
    }
}

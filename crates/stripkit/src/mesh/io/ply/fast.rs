//! Binary PLY elements read whole records at a time into arrays sized once: the
//! vertex element when all its properties are scalars, the face element when its one
//! property is the index list. Sizes come from the bytes the file holds (a count the
//! file cannot hold is declined before anything is allocated). Anything unusual (a
//! short file, a bad index, a NaN) declines too, with the mesh and the reading
//! position as they were: the value-by-value readers then read the element again and
//! report the fault in their words, so errors are the same either way.

use super::body::{number, Body};
use super::{flip_texcoord, vertex_attributes, Element, Kind};
use crate::mesh::{Mesh, Scalar};

/// A coordinate as the value-by-value reader makes it (`f32` kept, others through `f64`).
#[inline]
fn coordinate(b: &[u8], s: Scalar, big: bool) -> f32 {
    if s == Scalar::F32 {
        let bytes: [u8; 4] = b[..4].try_into().unwrap_or([0; 4]);
        return if big { f32::from_be_bytes(bytes) } else { f32::from_le_bytes(bytes) };
    }
    number(b, s, big) as f32
}

/// An integer of integer type `s` at the start of `b`.
#[inline]
fn integer(b: &[u8], s: Scalar, big: bool) -> i64 {
    if s == Scalar::I32 && !big {
        return i32::from_le_bytes(b[..4].try_into().unwrap_or([0; 4])) as i64;
    }
    number(b, s, big) as i64
}

/// Reads a vertex element of scalar properties into `mesh`'s positions and attributes
/// (none with `positions_only`); false, with nothing changed, where it declines.
pub(super) fn vertices<B: Body>(element: &Element, r: &mut B, positions_only: bool, mesh: &mut Mesh) -> bool {
    let Some((data, pos, big)) = r.binary() else { return false };
    let mut offsets = Vec::with_capacity(element.props.len());
    let mut record = 0;
    for p in &element.props {
        let Kind::Scalar(s) = p.kind else { return false };
        offsets.push(record);
        record += s.size();
    }
    let slot = |n: &str| element.props.iter().position(|p| p.name == n);
    let (Some(x), Some(y), Some(z)) = (slot("x"), slot("y"), slot("z")) else { return false };
    let Ok(count) = usize::try_from(element.count) else { return false };
    let Some(end) = count.checked_mul(record).and_then(|n| n.checked_add(pos)).filter(|&e| e <= data.len()) else {
        return false;
    };
    let body = &data[pos..end];
    let kind = |k: usize| match element.props[k].kind {
        Kind::Scalar(s) => s,
        Kind::List { count, .. } => count,
    };
    let xyz = [(offsets[x], kind(x)), (offsets[y], kind(y)), (offsets[z], kind(z))];
    let mut positions: Vec<[f32; 3]> = Vec::with_capacity(count);
    for rec in body.chunks_exact(record.max(1)).take(count) {
        let p = xyz.map(|(off, s)| coordinate(&rec[off..], s, big));
        if !p.iter().all(|c| c.is_finite()) {
            return false;
        }
        positions.push(p);
    }
    let mut attributes = Vec::new();
    if !positions_only {
        let (mut made, slots) = vertex_attributes(&element.props, [x, y, z], count);
        for a in &mut made {
            a.data.resize(count * a.stride(), 0);
        }
        for (k, slot) in slots.iter().enumerate() {
            let Some((a, c)) = *slot else { continue };
            let (off, size) = (offsets[k], kind(k).size());
            let at = &mut made[a];
            let stride = at.stride();
            for (v, rec) in body.chunks_exact(record).enumerate() {
                let dst = &mut at.data[v * stride + c * size..v * stride + (c + 1) * size];
                dst.copy_from_slice(&rec[off..off + size]);
                if big {
                    dst.reverse();
                }
            }
        }
        flip_texcoord(&mut made);
        attributes = made;
    }
    mesh.positions = positions;
    mesh.attributes = attributes;
    r.seek(end);
    true
}

/// Reads a face element whose one property is its index list (integer count and
/// items) into `mesh`'s faces; false, with nothing changed, where it declines.
pub(super) fn faces<B: Body>(element: &Element, r: &mut B, vertex_count: u64, mesh: &mut Mesh) -> bool {
    let Some((data, pos, big)) = r.binary() else { return false };
    let [prop] = &element.props[..] else { return false };
    let Kind::List { count: count_type, item } = prop.kind else { return false };
    if !matches!(prop.name.as_str(), "vertex_indices" | "vertex_index") || item.is_float() {
        return false;
    }
    let (count_size, item_size) = (count_type.size(), item.size());
    let (old_offsets, old_indices) = (mesh.face_offsets.len(), mesh.face_indices.len());
    // Every face takes at least its count and three items: the arrays are sized by
    // what the bytes left can hold, never by the announced count alone.
    let most = (data.len() - pos) / (count_size + 3 * item_size);
    let faces = (element.count).min(most as u64) as usize;
    mesh.face_offsets.reserve(faces);
    mesh.face_indices.reserve(faces.saturating_mul(3));
    let mut at = pos;
    let ok = (|| {
        for _ in 0..element.count {
            let n = integer(data.get(at..at + count_size)?, count_type, big);
            at += count_size;
            if n < 3 {
                return None;
            }
            let end = (n as usize).checked_mul(item_size)?.checked_add(at).filter(|&e| e <= data.len())?;
            for b in data[at..end].chunks_exact(item_size) {
                let i = integer(b, item, big);
                if i < 0 || i as u64 >= vertex_count {
                    return None;
                }
                mesh.face_indices.push(i as u32);
            }
            at = end;
            if mesh.face_indices.len() > u32::MAX as usize {
                return None;
            }
            mesh.face_offsets.push(mesh.face_indices.len() as u32);
        }
        Some(())
    })();
    if ok.is_none() {
        mesh.face_offsets.truncate(old_offsets);
        mesh.face_indices.truncate(old_indices);
        return false;
    }
    r.seek(at);
    true
}

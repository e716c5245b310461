//! The position and index bytes of a scene made from a mesh
//! ([`Scene::from_mesh`](super::Scene::from_mesh)), held out of its buffer while it is
//! stripped: each primitive's [`Mesh`] holds the same values, so the bytes are made
//! again from it when the scene is encoded, and only those the written file reads (the
//! positions, which reordering gathers, and the indices of a view still written).
//! On bunny Loop x3 (4,444,864 triangles) that is 80 MB not held beside the
//! stripifier.

use super::primitive::ScenePrimitive;
use super::{Buffer, Shared, View};
use crate::mesh::Mesh;

/// What a held-out view holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Held {
    /// The primitive's positions, 12 bytes each (`VEC3` floats, little-endian).
    Positions,
    /// The primitive's faces fanned into triangles, 2 or 4 bytes per index.
    Indices {
        /// 4-byte indices.
        wide: bool,
    },
}

/// One view of the buffer held out.
#[derive(Clone, Debug)]
pub(super) struct HeldView {
    /// The primitive (index in the scene's primitives) whose mesh holds the values.
    pub primitive: usize,
    /// The buffer view.
    pub view: usize,
    /// What it holds.
    pub held: Held,
}

/// The bytes of a held-out view, made from the primitive's mesh exactly as the mesh's
/// document wrote them.
pub(super) fn bytes(mesh: &Mesh, held: Held) -> Vec<u8> {
    match held {
        Held::Positions => mesh.positions.iter().flatten().flat_map(|c| c.to_le_bytes()).collect(),
        Held::Indices { wide } => {
            let mut out = Vec::with_capacity(3 * mesh.triangle_count() * if wide { 4 } else { 2 });
            fan(mesh, wide, &mut out);
            out
        }
    }
}

/// Appends a mesh's faces fanned into triangles (`[f0, fi, fi+1]`) as 2- or 4-byte
/// little-endian indices.
pub(super) fn fan(mesh: &Mesh, wide: bool, out: &mut Vec<u8>) {
    for face in mesh.faces() {
        for i in 1..face.len().saturating_sub(1) {
            for v in [face[0], face[i], face[i + 1]] {
                if wide {
                    out.extend_from_slice(&v.to_le_bytes());
                } else {
                    out.extend_from_slice(&(v as u16).to_le_bytes());
                }
            }
        }
    }
}

/// Buffer 0 without the bytes of the `held` views, and the views moved to match (a
/// held view keeps its length, at offset 0 of an empty buffer appended last: reading
/// it fails, never returns other bytes). The views must not overlap, as a mesh's
/// document writes them.
pub(super) fn compact(buffers: &[Buffer], views: &[View], held: &[HeldView]) -> (Vec<Buffer>, Vec<View>) {
    let is_held = |k: usize| held.iter().any(|h| h.view == k);
    let mut ranges: Vec<(usize, usize)> = held.iter().map(|h| (views[h.view].offset, views[h.view].length)).collect();
    ranges.sort_unstable();
    let whole = &buffers[0];
    let mut kept = Vec::with_capacity(whole.len() - ranges.iter().map(|r| r.1).sum::<usize>());
    let mut at = 0;
    for &(offset, length) in &ranges {
        kept.extend_from_slice(&whole[at..offset]);
        at = offset + length;
    }
    kept.extend_from_slice(&whole[at..]);
    let empty = buffers.len();
    let moved = views
        .iter()
        .enumerate()
        .map(|(k, v)| {
            if is_held(k) {
                View { buffer: empty, offset: 0, length: v.length, stride: v.stride }
            } else if v.buffer == 0 {
                let before: usize = ranges.iter().filter(|r| r.0 < v.offset).map(|r| r.1).sum();
                View { offset: v.offset - before, ..v.clone() }
            } else {
                v.clone()
            }
        })
        .collect();
    let mut out = buffers.to_vec();
    out[0] = Buffer { len: kept.len(), bytes: Shared::from(kept) };
    out.push(Buffer { len: 0, bytes: Shared::from(Vec::new()) });
    (out, moved)
}

/// The buffers and views to encode from: each held view that is read (every
/// positions view, and the index views not in `dead`) gets its bytes again, made from
/// `primitives`' meshes, in a buffer of its own. With `whole` (the buffers copied whole into the
/// file) buffer 0 is put back as it was made, `original` giving its views.
pub(super) fn restore(
    buffers: &[Buffer],
    views: &[View],
    held: &[HeldView],
    primitives: &[ScenePrimitive],
    dead: &[usize],
    whole: Option<&[View]>,
) -> (Vec<Buffer>, Vec<View>) {
    let mut buffers = buffers.to_vec();
    let mut views = views.to_vec();
    let made = |h: &HeldView| primitives.get(h.primitive).map(|sp| bytes(&sp.mesh, h.held));
    if let Some(original) = whole {
        let mut sorted: Vec<&HeldView> = held.iter().collect();
        sorted.sort_by_key(|h| original[h.view].offset);
        let compacted = &buffers[0];
        let length: usize = compacted.len() + sorted.iter().map(|h| original[h.view].length).sum::<usize>();
        let mut out = Vec::with_capacity(length);
        let mut at = 0;
        for h in sorted {
            let gap = original[h.view].offset - (out.len());
            out.extend_from_slice(&compacted[at..at + gap]);
            at += gap;
            let bytes = made(h).unwrap_or_else(|| vec![0; original[h.view].length]);
            out.extend_from_slice(&bytes);
        }
        out.extend_from_slice(&compacted[at..]);
        buffers[0] = Buffer { len: out.len(), bytes: Shared::from(out) };
        buffers.pop(); // the empty one `compact` appended
        return (buffers, original.to_vec());
    }
    for h in held {
        if matches!(h.held, Held::Indices { .. }) && dead.binary_search(&h.view).is_ok() {
            continue;
        }
        if let Some(bytes) = made(h) {
            views[h.view] =
                View { buffer: buffers.len(), offset: 0, length: bytes.len(), stride: views[h.view].stride };
            buffers.push(Buffer { len: bytes.len(), bytes: Shared::from(bytes) });
        }
    }
    (buffers, views)
}

//! Writing glTF: a mesh (and its strips) as a plain one-mesh document (`write_gltf`,
//! `write_glb`), the GLB container, and base64 for `data:` URIs.

use super::{CHUNK_BIN, CHUNK_JSON, GLB_MAGIC};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::strip::StripSet;
use serde_json::{json, Value};

const B64: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

pub(crate) fn base64_encode(data: &[u8]) -> String {
    let mut out = String::with_capacity(data.len().div_ceil(3) * 4);
    for chunk in data.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(B64[(n >> (18 - 6 * k)) as usize & 63] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Decodes base64 (padding optional); `Err(position)` at the first invalid character.
pub(crate) fn base64_decode(text: &[u8]) -> Result<Vec<u8>, usize> {
    let mut out = Vec::with_capacity(text.len() / 4 * 3 + 3);
    let mut acc = 0u32;
    let mut bits = 0;
    let mut padding = false;
    for (k, &c) in text.iter().enumerate() {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            b'=' => {
                padding = true;
                continue;
            }
            _ => return Err(k),
        };
        if padding {
            return Err(k);
        }
        acc = (acc << 6) | v as u32;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    Ok(out)
}

/// The glTF JSON and the binary buffer for a mesh (or its strips).
fn build(mesh: &Mesh, strips: Option<&StripSet>) -> Result<(Value, Vec<u8>)> {
    let nv = mesh.positions.len();
    let mut json = json!({
        "asset": {"version": "2.0", "generator": "stripkit"},
        "scene": 0,
        "scenes": [{"nodes": []}],
    });
    if nv == 0 {
        return Ok((json, Vec::new()));
    }
    super::from_mesh::check_attribute_count(mesh)?;
    let wide = nv >= u16::MAX as usize;
    let index_size = if wide { 4 } else { 2 };
    // Index runs: (first index, count) in the concatenated index list.
    let mut index_list: Vec<u32> = Vec::new();
    let mut runs: Vec<(usize, usize)> = Vec::new();
    match strips {
        Some(set) => {
            for s in set.iter().filter(|s| s.len() >= 3) {
                runs.push((index_list.len(), s.len()));
                index_list.extend_from_slice(s);
            }
        }
        None => {
            for t in mesh.triangulate().tris {
                index_list.extend_from_slice(&t);
            }
            if !index_list.is_empty() {
                runs.push((0, index_list.len()));
            }
        }
    }
    // POSITION and every attribute the mesh carries (the shapes and names of
    // `from_mesh`); the index list follows, 4-byte aligned.
    let mut bin = Vec::with_capacity(nv * 12 + index_list.len() * index_size + 4);
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut notes = Vec::new();
    let attributes = super::from_mesh::write_vertices(mesh, &mut bin, &mut views, &mut accessors, &mut notes);
    bin.resize(bin.len().next_multiple_of(4), 0);
    let index_start = bin.len();
    for &i in &index_list {
        if wide {
            bin.extend_from_slice(&i.to_le_bytes());
        } else {
            bin.extend_from_slice(&(i as u16).to_le_bytes());
        }
    }
    let mut primitives = Vec::new();
    if runs.is_empty() {
        primitives.push(json!({"attributes": attributes, "mode": 0}));
    } else {
        views.push(json!({
            "buffer": 0, "byteOffset": index_start, "byteLength": index_list.len() * index_size, "target": 34963,
        }));
        let index_view = views.len() - 1;
        let mode = if strips.is_some() { 5 } else { 4 };
        for (first, count) in runs {
            primitives.push(json!({"attributes": attributes, "indices": accessors.len(), "mode": mode}));
            accessors.push(json!({
                "bufferView": index_view, "byteOffset": first * index_size, "componentType": if wide { 5125 } else { 5123 },
                "count": count, "type": "SCALAR",
            }));
        }
    }
    json["scenes"] = json!([{"nodes": [0]}]);
    json["nodes"] = json!([{"mesh": 0}]);
    json["meshes"] = json!([{"primitives": primitives}]);
    json["bufferViews"] = Value::Array(views);
    json["accessors"] = Value::Array(accessors);
    json["buffers"] = json!([{"byteLength": bin.len()}]);
    Ok((json, bin))
}

/// Encodes a mesh as a self-contained `.gltf` (buffer as a base64 data URI).
pub(crate) fn write_gltf(mesh: &Mesh, strips: Option<&StripSet>) -> Result<Vec<u8>> {
    let (mut json, bin) = build(mesh, strips)?;
    if !bin.is_empty() {
        json["buffers"][0]["uri"] =
            Value::String(format!("data:application/octet-stream;base64,{}", base64_encode(&bin)));
    }
    serde_json::to_vec(&json).map_err(|e| Error::Invalid(format!("cannot encode glTF JSON: {e}")))
}

/// Encodes a mesh as `.glb`.
pub(crate) fn write_glb(mesh: &Mesh, strips: Option<&StripSet>) -> Result<Vec<u8>> {
    let (json, bin) = build(mesh, strips)?;
    glb_container(&json, bin)
}

/// The GLB container of a JSON document and its binary chunk, both padded to 4 bytes
/// as the specification asks. The binary chunk is left out when `bin` is empty and no
/// buffer 0 without a `uri` names it; where one does (a scene whose primitives were
/// left with no triangle), it is written empty, so that the file reads back.
pub(super) fn glb_container(json: &Value, mut bin: Vec<u8>) -> Result<Vec<u8>> {
    let with_bin = !bin.is_empty() || json.pointer("/buffers/0").is_some_and(|b| b.get("uri").is_none());
    let mut text = serde_json::to_vec(json).map_err(|e| Error::Invalid(format!("cannot encode glTF JSON: {e}")))?;
    while text.len() % 4 != 0 {
        text.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = 12 + 8 + text.len() + if with_bin { 8 + bin.len() } else { 0 };
    let total32 = u32::try_from(total).map_err(|_| Error::Invalid(format!("{total} bytes do not fit a GLB file")))?;
    let mut head = Vec::with_capacity(12 + 8 + text.len() + 8);
    head.extend_from_slice(GLB_MAGIC);
    head.extend_from_slice(&2u32.to_le_bytes());
    head.extend_from_slice(&total32.to_le_bytes());
    head.extend_from_slice(&(text.len() as u32).to_le_bytes());
    head.extend_from_slice(&CHUNK_JSON.to_le_bytes());
    head.extend_from_slice(&text);
    if !with_bin {
        return Ok(head);
    }
    head.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    head.extend_from_slice(&CHUNK_BIN.to_le_bytes());
    // The head goes in front of the binary chunk in its own allocation (grown, not
    // copied beside it): the file is never held twice.
    drop(bin.splice(0..0, head));
    Ok(bin)
}

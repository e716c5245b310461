//! Writing a scene's buffer views compressed with `EXT_meshopt_compression`
//! ([`compress_views`]), the pass after the document is built: index views with the
//! index-sequence codec (`INDICES`, the mode meant for strips, restart values
//! included), vertex views with the vertex codec version 0 (`ATTRIBUTES`), no filter.
//! Other views (images, animation data, skins) stay as they are.

use super::meshopt::{decode, encode_sequence, encode_vertices, MeshoptFilter, MeshoptMode};
use serde_json::{json, Map, Value};

const EXTENSION: &str = "EXT_meshopt_compression";

/// How one view is compressed: the mode's name and its element size.
fn plan(json: &Value, v: usize, view: &Value) -> Option<(&'static str, usize)> {
    let length = view.get("byteLength")?.as_u64()? as usize;
    let accessors = json.get("accessors").and_then(Value::as_array)?;
    let users: Vec<&Value> =
        accessors.iter().filter(|a| a.get("bufferView").and_then(Value::as_u64) == Some(v as u64)).collect();
    let first = users.first()?;
    let size = match first.get("componentType")?.as_u64()? {
        5120 | 5121 => 1,
        5122 | 5123 => 2,
        _ => 4,
    };
    let target = view.get("target").and_then(Value::as_u64);
    if target == Some(34963) {
        let scalar = users.iter().all(|a| a.get("type").and_then(Value::as_str) == Some("SCALAR"));
        let same = users.iter().all(|a| a.get("componentType") == first.get("componentType"));
        return (scalar && same && (size == 2 || size == 4) && length % size == 0).then_some(("INDICES", size));
    }
    let stride = match view.get("byteStride").and_then(Value::as_u64) {
        Some(s) => s as usize,
        None if users.len() == 1 => {
            let n = match first.get("type")?.as_str()? {
                "SCALAR" => 1,
                "VEC2" => 2,
                "VEC3" => 3,
                "VEC4" => 4,
                _ => return None,
            };
            size * n
        }
        None => return None,
    };
    (target == Some(34962) && stride % 4 == 0 && stride <= 256 && length % stride == 0)
        .then_some(("ATTRIBUTES", stride))
}

/// Rewrites `json` and `bin` (one buffer, buffer 0) so that every index and vertex view
/// whose compressed form is smaller is read from a compressed block in buffer 0, with
/// the view itself in a fallback buffer without data (buffer 1), and lists the
/// extension as used and required (a reader without it has no data to fall back on).
/// Returns the new buffer 0; nothing changes where no view gets smaller.
pub(super) fn compress_views(json: &mut Value, bin: Vec<u8>) -> Vec<u8> {
    let Some(views) = json.get("bufferViews").and_then(Value::as_array).cloned() else { return bin };
    let mut out = Vec::with_capacity(bin.len() / 2);
    let mut fallback = 0usize;
    let mut new_views = Vec::with_capacity(views.len());
    let mut compressed = 0;
    for (v, view) in views.iter().enumerate() {
        let offset = view.get("byteOffset").and_then(Value::as_u64).unwrap_or(0) as usize;
        let length = view.get("byteLength").and_then(Value::as_u64).unwrap_or(0) as usize;
        let Some(bytes) = bin.get(offset..offset + length) else {
            new_views.push(view.clone());
            continue;
        };
        let stream = plan(json, v, view).and_then(|(mode, stride)| {
            let stream = if mode == "INDICES" {
                let indices: Vec<u32> = bytes
                    .chunks_exact(stride)
                    .map(|b| {
                        if stride == 2 {
                            u16::from_le_bytes([b[0], b[1]]) as u32
                        } else {
                            u32::from_le_bytes([b[0], b[1], b[2], b[3]])
                        }
                    })
                    .collect();
                encode_sequence(&indices)
            } else {
                encode_vertices(bytes, stride)
            };
            // Kept only where smaller and decoding it gives the bytes back (the sequence
            // codec keeps 30 bits of a delta between 32-bit indices).
            let mode_of = if mode == "INDICES" { MeshoptMode::Indices } else { MeshoptMode::Attributes };
            let back = decode(&stream, length / stride, stride, mode_of, MeshoptFilter::None);
            (stream.len() < length && back.as_deref() == Ok(bytes)).then_some((mode, stride, stream))
        });
        let mut new = view.clone();
        match stream {
            Some((mode, stride, stream)) => {
                out.resize(out.len().next_multiple_of(4), 0);
                let at = out.len();
                out.extend_from_slice(&stream);
                fallback = fallback.next_multiple_of(4);
                new["buffer"] = 1.into();
                new["byteOffset"] = fallback.into();
                fallback += length;
                let ext = json!({"buffer": 0, "byteOffset": at, "byteLength": stream.len(),
                    "byteStride": stride, "count": length / stride, "mode": mode});
                new.as_object_mut().map(|o| o.entry("extensions").or_insert_with(|| Value::Object(Map::new())));
                new["extensions"][EXTENSION] = ext;
                compressed += 1;
            }
            None => {
                out.resize(out.len().next_multiple_of(4), 0);
                new["byteOffset"] = out.len().into();
                out.extend_from_slice(bytes);
            }
        }
        new_views.push(new);
    }
    if compressed == 0 {
        return bin;
    }
    out.resize(out.len().next_multiple_of(4), 0);
    json["bufferViews"] = Value::Array(new_views);
    if let Some(buffers) = json.get_mut("buffers").and_then(Value::as_array_mut) {
        if let Some(b) = buffers.get_mut(0) {
            b["byteLength"] = out.len().into();
        }
        buffers.truncate(1);
        buffers.push(json!({"byteLength": fallback, "extensions": {EXTENSION: {"fallback": true}}}));
    }
    for key in ["extensionsUsed", "extensionsRequired"] {
        if !json.get(key).is_some_and(Value::is_array) {
            json[key] = json!([]);
        }
        if let Some(list) = json[key].as_array_mut() {
            if !list.iter().any(|e| e == EXTENSION) {
                list.push(EXTENSION.into());
            }
        }
    }
    out
}

//! Hostile and unlucky inputs from issue #16 (items 4, 5 and the reader messages of 9):
//! each is built here as bytes and read through the public API; each must give the
//! right mesh or an error naming the file and what is wrong, never an empty or
//! silently shortened mesh.

use std::path::Path;
use stripkit::io::{self, Format};
use stripkit::{Error, Mesh};

fn read(name: &str, bytes: &[u8]) -> stripkit::Result<Mesh> {
    let format = Format::from_path(Path::new(name)).unwrap().0;
    io::read_bytes(Path::new(name), format, bytes)
}

fn counts(name: &str, bytes: &[u8]) -> (usize, usize) {
    let m = read(name, bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
    (m.vertex_count(), m.face_count())
}

/// (at, what) of the format error, checking that the message names the file.
fn refused(name: &str, bytes: &[u8]) -> (String, String) {
    match read(name, bytes) {
        Err(e @ Error::Format { .. }) => {
            assert!(e.to_string().contains(name), "the message must name the file: {e}");
            let Error::Format { at, what, .. } = e else { unreachable!() };
            (at, what)
        }
        other => panic!("{name}: expected a format error, got {other:?}"),
    }
}

/// A glTF with one buffer (embedded) holding three positions and `indices`.
fn gltf(indices: &[u8], stride: Option<u64>) -> Vec<u8> {
    let mut bin = Vec::new();
    for p in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for c in p {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    bin.extend_from_slice(indices);
    let mut pos_view = serde_json::json!({"buffer": 0, "byteOffset": 0, "byteLength": 36});
    if let Some(s) = stride {
        pos_view["byteStride"] = s.into();
    }
    let doc = serde_json::json!({
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": bin.len(), "uri": format!("data:application/octet-stream;base64,{}", b64(&bin))}],
        "bufferViews": [pos_view, {"buffer": 0, "byteOffset": 36, "byteLength": indices.len()}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": if stride.is_some() { 2 } else { 3 }, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5121, "count": indices.len(), "type": "SCALAR"}
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}]
    });
    serde_json::to_vec(&doc).unwrap()
}

fn b64(data: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for c in data.chunks(3) {
        let n = (c[0] as u32) << 16 | (*c.get(1).unwrap_or(&0) as u32) << 8 | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            out.push(if k <= c.len() { A[(n >> (18 - 6 * k) & 63) as usize] as char } else { '=' });
        }
    }
    out
}

#[test]
fn gltf_triangle_index_counts_and_strides_are_checked() {
    assert_eq!(counts("ok.gltf", &gltf(&[0, 1, 2], None)), (3, 1));
    let (at, what) = refused("tail.gltf", &gltf(&[0, 1, 2, 0, 1], None));
    assert_eq!(at, "meshes[0].primitives[0]");
    assert!(what.contains("multiple of 3") && what.contains("index accessor 1") && what.contains("has 5"), "{what}");
    let (at, what) = refused("stride.gltf", &gltf(&[0, 1, 2], Some(8)));
    assert_eq!(at, "accessors[0]");
    assert!(what.contains("byteStride 8") && what.contains("12-byte"), "{what}");
}

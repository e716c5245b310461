//! Issue #30, class 1, on the command line: `stripkit strip in.glb -o out.glb` on a
//! glb whose morph target has 2 elements under 4 positions panicked (exit 101) in the
//! vertex reordering; it exits 2 naming the file and the accessor, and writes nothing.

mod support;

use serde_json::json;
use support::{stripkit, tmp};

/// A quad (4 positions, 2 indexed triangles) with one morph target of 2 elements.
fn short_target_glb() -> Vec<u8> {
    let mut bin: Vec<u8> = [0f32, 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.]
        .iter()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    bin.extend([0u16, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes()));
    let json = json!({
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": 60}],
        "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
            {"bufferView": 0, "componentType": 5126, "count": 2, "type": "VEC3"},
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "targets": [{"POSITION": 2}]}]}],
    });
    let mut j = serde_json::to_vec(&json).unwrap();
    j.resize(j.len().next_multiple_of(4), b' ');
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend(((28 + j.len() + bin.len()) as u32).to_le_bytes());
    out.extend((j.len() as u32).to_le_bytes());
    out.extend(0x4E4F_534Au32.to_le_bytes());
    out.extend(&j);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(0x004E_4942u32.to_le_bytes());
    out.extend(&bin);
    out
}

#[test]
fn a_short_morph_target_exits_2_naming_the_file_and_accessor() {
    let input = tmp("gltf-counts", "short-target.glb");
    let output = tmp("gltf-counts", "out.glb");
    std::fs::write(&input, short_target_glb()).unwrap();
    let out = stripkit(&["strip", input.to_str().unwrap(), "-o", output.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("short-target.glb") && err.contains("accessors[2]") && err.contains("POSITION has 4"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!output.exists());
}

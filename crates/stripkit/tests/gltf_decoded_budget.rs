//! The mesh a glTF asset decodes to is bounded (issue #16, "memory bounded by input
//! size"): accessors and primitives may read the same buffer bytes any number of
//! times, so an 8 KB `.glb.gz` reusing one 1.2 MB POSITION view through 2,000
//! accessors asked for 2.4 GB (3.9 GB resident) before each accessor was charged to
//! `ReadOptions::max_decoded_bytes` ahead of its allocation.

use std::path::{Path, PathBuf};
use stripkit::io::{self, Format, ReadOptions, DECODED_BYTES_ALLOWANCE, DECODED_BYTES_PER_BUFFER_BYTE};
use stripkit::{Error, Mesh};

/// A GLB whose binary chunk is `bin` and whose JSON is `json` (without the buffers,
/// which are set to the binary chunk).
fn glb(mut json: serde_json::Value, bin: &[u8]) -> Vec<u8> {
    json["asset"] = serde_json::json!({"version": "2.0"});
    json["buffers"] = serde_json::json!([{"byteLength": bin.len()}]);
    stripkit_testkit::glb(&json, bin)
}

/// `accessors` POSITION accessors, all over one view of `vertices` zero positions,
/// each drawn as points by its own primitive: the reproducer at
/// `(2000, 100_000)`.
fn reused_positions(accessors: usize, vertices: usize) -> Vec<u8> {
    let json = serde_json::json!({
        "bufferViews": [{"buffer": 0, "byteLength": 12 * vertices}],
        "accessors": (0..accessors)
            .map(|_| serde_json::json!({"bufferView": 0, "componentType": 5126, "count": vertices, "type": "VEC3"}))
            .collect::<Vec<_>>(),
        "meshes": [{"primitives": (0..accessors)
            .map(|k| serde_json::json!({"attributes": {"POSITION": k}, "mode": 0}))
            .collect::<Vec<_>>()}],
    });
    glb(json, &vec![0u8; 12 * vertices])
}

fn read(name: &str, bytes: &[u8], options: &ReadOptions) -> stripkit::Result<Mesh> {
    io::read_bytes_with(Path::new(name), Format::Glb, bytes, options)
}

/// (at, what) of the format error, checking that the message names the file.
fn refused(name: &str, bytes: &[u8], options: &ReadOptions) -> (String, String) {
    match read(name, bytes, options) {
        Err(e @ Error::Format { .. }) => {
            let msg = e.to_string();
            assert!(msg.contains(name), "the message must name the file: {msg}");
            assert!(msg.contains("ReadOptions::max_decoded_bytes") && msg.contains("--max-memory"), "{msg}");
            let Error::Format { at, what, .. } = e else { unreachable!() };
            (at, what)
        }
        Err(e) => panic!("{name}: expected a format error, got {e}"),
        Ok(m) => panic!("{name}: expected a refusal, read {} vertices", m.vertex_count()),
    }
}

#[test]
fn one_position_view_reused_by_2000_accessors_is_refused_before_its_allocation() {
    let bytes = reused_positions(2000, 100_000);
    let limit = DECODED_BYTES_PER_BUFFER_BYTE * 1_200_000 + DECODED_BYTES_ALLOWANCE;
    assert_eq!(limit, 39_448_576);
    // 32 accessors of 1.2 MB fit (38.4 MB); the 33rd would cross the limit.
    let (at, what) = refused("reuse.glb", &bytes, &ReadOptions::default());
    assert_eq!(at, "meshes[0].primitives[32]");
    assert!(what.contains("accessors[32]: 100000 vertices would bring the mesh to 39600000 bytes"), "{what}");
    assert!(what.contains(&format!("the limit of {limit} bytes (32 x the file's 1200000 buffer bytes")), "{what}");
    assert!(what.contains("reuse accessors"), "{what}");
}

#[test]
fn the_limit_can_be_lowered_and_raised() {
    // 50 accessors over 100 vertices: 60,000 bytes of positions, within the default
    // allowance; the same file against an explicit limit, at and one byte below it.
    let bytes = reused_positions(50, 100);
    assert_eq!(read("small.glb", &bytes, &ReadOptions::default()).unwrap().vertex_count(), 5000);
    let exact = ReadOptions::default().max_decoded_bytes(Some(60_000));
    assert_eq!(read("small.glb", &bytes, &exact).unwrap().vertex_count(), 5000);
    let short = ReadOptions::default().max_decoded_bytes(Some(59_999));
    let (at, what) = refused("small.glb", &bytes, &short);
    assert_eq!(at, "meshes[0].primitives[49]");
    assert!(what.contains("more than the limit of 59999 bytes;"), "{what}");
    // Raising it lets a file through that the input-relative default refuses.
    let bytes = reused_positions(40, 100_000);
    refused("forty.glb", &bytes, &ReadOptions::default());
    let raised = ReadOptions::default().max_decoded_bytes(Some(48_000_000));
    assert_eq!(read("forty.glb", &bytes, &raised).unwrap().vertex_count(), 4_000_000);
}

#[test]
fn reused_index_accessors_are_charged_before_they_are_read() {
    // Three vertices and 30,000 one-byte strip indices (0 1 2 1 2 0 ...): each strip
    // primitive gives up to 29,998 triangles, 16 bytes each (three indices and an
    // offset), charged before the indices are read. 2,000 primitives would be 960 MB.
    let mut bin: Vec<u8> = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        .iter()
        .flatten()
        .flat_map(|c| c.to_le_bytes())
        .collect();
    bin.extend((0..30_000u32).map(|k| (k % 3) as u8));
    let json = serde_json::json!({
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 30_000}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5121, "count": 30_000, "type": "SCALAR"},
        ],
        "meshes": [{"primitives": (0..2000)
            .map(|_| serde_json::json!({"attributes": {"POSITION": 0}, "indices": 1, "mode": 5}))
            .collect::<Vec<_>>()}],
    });
    let bytes = glb(json, &bin);
    let (at, what) = refused("strips.glb", &bytes, &ReadOptions::default());
    // (32 x 30,036 + 1 MiB - 36) / 479,968 bytes per primitive: 4 fit.
    assert_eq!(at, "meshes[0].primitives[4]");
    assert!(what.contains("accessors[1]: 30000 indices"), "{what}");
}

#[test]
fn a_sibling_file_listed_100_times_decodes_within_the_budget() {
    // The "one sibling listed 100 times used 4.9 GB": the file is now read
    // once (gltf_references.rs), and 100 buffers each decoding the whole file as
    // positions are charged against the file's bytes counted once.
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gltf_decoded_budget");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let len = 12 * 400_000; // 4.8 MB
    std::fs::write(dir.join("big.bin"), vec![0u8; len]).unwrap();
    let json = serde_json::json!({
        "asset": {"version": "2.0"},
        "buffers": (0..100).map(|_| serde_json::json!({"byteLength": len, "uri": "big.bin"})).collect::<Vec<_>>(),
        "bufferViews": (0..100).map(|b| serde_json::json!({"buffer": b, "byteLength": len})).collect::<Vec<_>>(),
        "accessors": (0..100)
            .map(|v| serde_json::json!({"bufferView": v, "componentType": 5126, "count": 400_000, "type": "VEC3"}))
            .collect::<Vec<_>>(),
        "meshes": [{"primitives": (0..100)
            .map(|k| serde_json::json!({"attributes": {"POSITION": k}, "mode": 0}))
            .collect::<Vec<_>>()}],
    });
    let path = dir.join("many.gltf");
    std::fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
    let e = io::read(&path).unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains(&path.display().to_string()) && msg.contains("meshes[0].primitives[32]"), "{msg}");
    assert!(msg.contains("32 x the file's 4800000 buffer bytes"), "{msg}");
    std::fs::remove_dir_all(&dir).unwrap();
}

//! Issue #30, classes 6 and 7, on the command line: glTF extensions are decided in one
//! place of the reader, so `stats`, `strip -o x.glb` (the scene path) and
//! `strip -o x.ply` (the mesh path) accept or refuse the same file alike; geometry
//! stored by Draco is refused (exit 2, named), never written back stale, meshopt views
//! are decoded (a broken stream refused, named) and `--compress` writes them again;
//! and a mesh with no drawable triangle is written as glTF as it is as PLY.

mod support;

use serde_json::{json, Value};
use support::{stripkit, tmp};

/// A `.gltf` of one triangle (positions in a data URI), with `edit` applied.
fn gltf(name: &str, edit: impl FnOnce(&mut Value)) -> std::path::PathBuf {
    let bin: Vec<u8> = [0f32, 0., 0., 1., 0., 0., 0., 1., 0.].iter().flat_map(|x| x.to_le_bytes()).collect();
    let mut doc = json!({
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": 36, "uri": format!("data:application/octet-stream;base64,{}",
            stripkit_testkit::encode_base64(&bin))}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
            "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    });
    edit(&mut doc);
    let path = tmp("gltf-extensions", name);
    std::fs::write(&path, serde_json::to_vec(&doc).unwrap()).unwrap();
    path
}

/// Runs `stats`, `strip -o .glb` and `strip -o .ply` on `input`: (exit code, stderr) each.
fn three_commands(input: &std::path::Path) -> Vec<(Option<i32>, String)> {
    let stem = input.file_stem().unwrap().to_str().unwrap();
    let glb = tmp("gltf-extensions", &format!("{stem}-out.glb"));
    let ply = tmp("gltf-extensions", &format!("{stem}-out.ply"));
    let i = input.to_str().unwrap();
    [
        stripkit(&["stats", i]),
        stripkit(&["strip", i, "-o", glb.to_str().unwrap()]),
        stripkit(&["strip", i, "-o", ply.to_str().unwrap()]),
    ]
    .into_iter()
    .map(|o| (o.status.code(), String::from_utf8_lossy(&o.stderr).into_owned()))
    .collect()
}

#[test]
fn an_unknown_required_extension_is_refused_by_every_command() {
    let input = gltf("unknown-required.gltf", |d| {
        d["extensionsUsed"] = json!(["EXT_not_a_real_extension"]);
        d["extensionsRequired"] = json!(["EXT_not_a_real_extension"]);
    });
    for (code, err) in three_commands(&input) {
        assert_eq!(code, Some(2), "{err}");
        assert!(err.contains("unknown-required.gltf") && err.contains("EXT_not_a_real_extension"), "{err}");
    }
}

#[test]
fn a_required_extension_carried_through_is_read_by_every_command() {
    let input = gltf("known-required.gltf", |d| {
        d["extensionsUsed"] = json!(["KHR_materials_emissive_strength", "KHR_texture_transform"]);
        d["extensionsRequired"] = json!(["KHR_materials_emissive_strength", "KHR_texture_transform"]);
    });
    for (code, err) in three_commands(&input) {
        assert_eq!(code, Some(0), "{err}");
    }
}

#[test]
fn a_draco_primitive_is_refused_naming_the_primitive_even_when_only_used() {
    for (name, required) in [("draco-used.gltf", false), ("draco-required.gltf", true)] {
        let input = gltf(name, |d| {
            d["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
            if required {
                d["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
            }
            d["meshes"][0]["primitives"][0]["extensions"] =
                json!({"KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": 0}}});
        });
        for (code, err) in three_commands(&input) {
            assert_eq!(code, Some(2), "{err}");
            assert!(
                err.contains(name)
                    && err.contains("meshes[0].primitives[0]")
                    && err.contains("KHR_draco_mesh_compression"),
                "{err}"
            );
        }
    }
}

/// EXT_meshopt_compression is decoded (issue #31): a view whose compressed bytes are
/// not a meshopt stream (here plain floats) is refused by every command, naming the view.
#[test]
fn a_broken_meshopt_stream_is_refused_naming_the_view() {
    let input = gltf("meshopt-view.gltf", |d| {
        d["bufferViews"][0]["extensions"] = json!({"EXT_meshopt_compression":
            {"buffer": 0, "byteLength": 36, "byteStride": 12, "count": 3, "mode": "ATTRIBUTES"}});
    });
    for (code, err) in three_commands(&input) {
        assert_eq!(code, Some(2), "{err}");
        assert!(err.contains("bufferViews[0]") && err.contains("EXT_meshopt_compression"), "{err}");
    }
}

/// `--compress`: a glTF output with its views compressed (`EXT_meshopt_compression`
/// required), which every command reads back; refused (exit 2) for other outputs.
#[test]
fn compress_writes_meshopt_views_that_read_back() {
    let input = stripkit_testkit::assets_dir().join("spot.obj");
    let i = input.to_str().unwrap();
    let glb = tmp("gltf-extensions", "spot-compressed.glb");
    let o = stripkit(&["strip", i, "-o", glb.to_str().unwrap(), "--compress", "--join", "degenerate"]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let data = std::fs::read(&glb).unwrap();
    let json_len = u32::from_le_bytes(data[12..16].try_into().unwrap()) as usize;
    let doc: Value = serde_json::from_slice(&data[20..20 + json_len]).unwrap();
    assert_eq!(doc["extensionsRequired"], json!(["EXT_meshopt_compression"]));
    for (code, err) in three_commands(&glb) {
        assert_eq!(code, Some(0), "{err}");
    }
    let s = stripkit(&["stats", glb.to_str().unwrap()]);
    assert!(String::from_utf8_lossy(&s.stdout).contains("5856 triangles"));
    stripkit_testkit::gltf_validator::validate(&[&glb]);
    let ply = tmp("gltf-extensions", "spot-compressed.ply");
    let o = stripkit(&["strip", i, "-o", ply.to_str().unwrap(), "--compress"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--compress applies to .gltf and .glb outputs"));
}

/// An OBJ whose only face repeats a vertex: every output format writes the vertices
/// with no triangle (exit 0), and every one reads back alike (`stats`: no faces).
#[test]
fn a_mesh_without_a_drawable_triangle_is_written_alike_in_every_format() {
    let input = tmp("gltf-extensions", "degenerate.obj");
    std::fs::write(&input, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 1\n").unwrap();
    let mut written = Vec::new();
    for ext in ["glb", "gltf", "ply", "obj"] {
        let out = tmp("gltf-extensions", &format!("degenerate-out.{ext}"));
        let o = stripkit(&["strip", input.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(0), "{ext}: {}", String::from_utf8_lossy(&o.stderr));
        let s = stripkit(&["stats", out.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&s.stderr);
        assert_eq!(s.status.code(), Some(2), "{ext}: {err}");
        assert!(err.contains("no faces"), "{ext}: {err}");
        written.push(out);
    }
    let gltf_files: Vec<&std::path::Path> = written[..2].iter().map(|p| p.as_path()).collect();
    stripkit_testkit::gltf_validator::validate(&gltf_files);
}

/// The scene path (glTF to glTF): a primitive whose one triangle is degenerate has
/// nothing to strip and is written as read (it was written with empty accessors and,
/// in a GLB, an empty buffer without its binary chunk, which did not read back).
#[test]
fn a_scene_left_without_triangles_is_written_as_a_readable_glb() {
    let input = gltf("degenerate-scene.gltf", |d| {
        let bin: Vec<u8> = [0f32, 0., 0., 1., 0., 0., 0., 1., 0.]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .chain([0u8; 8])
            .collect();
        d["buffers"][0] = json!({"byteLength": 44, "uri": format!("data:application/octet-stream;base64,{}",
            stripkit_testkit::encode_base64(&bin))});
        d["bufferViews"] = json!([{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}]);
        d["accessors"].as_array_mut().unwrap().push(json!({"bufferView": 1, "componentType": 5123, "count": 3,
            "type": "SCALAR"}));
        d["meshes"][0]["primitives"][0]["indices"] = json!(1);
    });
    let out = tmp("gltf-extensions", "degenerate-scene-out.glb");
    let o = stripkit(&["strip", input.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let s = stripkit(&["stats", out.to_str().unwrap(), "--json"]);
    assert_eq!(s.status.code(), Some(0), "{}", String::from_utf8_lossy(&s.stderr));
    let facts = support::json(&s);
    assert_eq!((facts["faces"].as_u64(), facts["degenerate_faces"].as_u64()), (Some(1), Some(1)), "{facts}");
    stripkit_testkit::gltf_validator::validate(&[out.as_path()]);
}

//! `stripkit strip in.glb -o out.glb` goes through the scene path: both primitives,
//! their materials and the moved node come back, the primitives as strips (with
//! EXT_mesh_primitive_restart by default, plain stitched with `--join degenerate`),
//! the Khronos validator finds no error; flags that mean nothing for a scene exit 2.

mod support;

use serde_json::{json, Value};
use support::{encode_base64, stripkit, tmp};

/// A 4 x 2 grid of quads (15 vertices, 16 triangles, shuffled), its left half drawn
/// with material 0 and its right half with material 1, in a node moved by [3, 0, 0].
fn asset() -> Value {
    let mut pos = Vec::new();
    for y in 0..3 {
        for x in 0..5 {
            pos.extend([x as f32, y as f32, 0.0]);
        }
    }
    let mut halves = [Vec::new(), Vec::new()];
    for y in 0..2u16 {
        for x in 0..4u16 {
            let v = y * 5 + x;
            let half = &mut halves[(x / 2) as usize];
            half.extend([v, v + 1, v + 6]);
            half.extend([v, v + 6, v + 5]);
        }
    }
    halves[0].swap(0, 3);
    halves[1].reverse(); // a different triangle order (and the same orientation per triangle rotated)
    let mut bin: Vec<u8> = pos.iter().flat_map(|v: &f32| v.to_le_bytes()).collect();
    let pos_len = bin.len();
    for h in &halves {
        bin.extend(h.iter().flat_map(|i| i.to_le_bytes()));
    }
    json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "translation": [3.0, 0.0, 0.0], "name": "moved"}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": 0}, "indices": 1, "material": 0},
            {"attributes": {"POSITION": 0}, "indices": 2, "material": 1}
        ]}],
        "materials": [{"name": "left"}, {"name": "right", "doubleSided": true}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 15, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [4.0, 2.0, 0.0]},
            {"bufferView": 1, "componentType": 5123, "count": 24, "type": "SCALAR"},
            {"bufferView": 1, "byteOffset": 48, "componentType": 5123, "count": 24, "type": "SCALAR"}
        ],
        "bufferViews": [
            {"buffer": 0, "byteLength": pos_len, "target": 34962},
            {"buffer": 0, "byteOffset": pos_len, "byteLength": 96, "target": 34963}
        ],
        "buffers": [{"byteLength": bin.len(), "uri": format!("data:application/octet-stream;base64,{}", encode_base64(&bin))}]
    })
}

fn glb_json(path: &std::path::Path) -> Value {
    let data = std::fs::read(path).unwrap();
    let len = u32::from_le_bytes(data[12..16].try_into().unwrap()) as usize;
    serde_json::from_slice(&data[20..20 + len]).unwrap()
}

#[test]
fn strip_keeps_the_scene_and_writes_strips() {
    let input = tmp("gltf-scene", "two.gltf");
    std::fs::write(&input, serde_json::to_vec(&asset()).unwrap()).unwrap();
    let out = tmp("gltf-scene", "two.glb");
    let run = stripkit(&["strip", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--json"]);
    let report = support::json(&run);
    assert_eq!(report["triangles"], 16);
    assert_eq!(report["primitives"].as_array().unwrap().len(), 2);
    assert_eq!(report["indices_read"], 48);
    let j = glb_json(&out);
    assert_eq!(j["nodes"], asset()["nodes"]);
    assert_eq!(j["materials"], asset()["materials"]);
    let prims = j["meshes"][0]["primitives"].as_array().unwrap();
    assert_eq!(prims.len(), 2);
    for (k, p) in prims.iter().enumerate() {
        assert_eq!(p["mode"], 5);
        assert_eq!(p["material"], k);
        // A 2 x 2 quad patch is one strip of 10 indices at best; never more than a list.
        let n = j["accessors"][p["indices"].as_u64().unwrap() as usize]["count"].as_u64().unwrap();
        assert!((10..24).contains(&n), "{n} stitched indices");
    }
    let groups = &j["meshes"][0]["extensions"]["EXT_mesh_primitive_restart"]["primitiveGroups"];
    assert_eq!(groups.as_array().unwrap().len(), 2);
    assert_eq!(j["extensionsUsed"], json!(["EXT_mesh_primitive_restart"]));

    let plain = tmp("gltf-scene", "plain.gltf");
    let run = stripkit(&["strip", input.to_str().unwrap(), "-o", plain.to_str().unwrap(), "--join", "degenerate"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(text.contains("2 triangle primitives stripped"), "{text}");
    let p: Value = serde_json::from_slice(&std::fs::read(&plain).unwrap()).unwrap();
    assert!(p.get("extensionsUsed").is_none());
    assert!(p["meshes"][0].get("extensions").is_none());
    assert_eq!(p["meshes"][0]["primitives"][1]["mode"], 5);

    // The two halves share one 15-vertex array: it is kept as read, even with the
    // default first-use order (a 9-vertex copy each would leave the shared 15 behind,
    // unused: 33 vertices in the file for 15).
    let n = |j: &Value, k: usize| {
        let a = j["meshes"][0]["primitives"][k]["attributes"]["POSITION"].as_u64().unwrap() as usize;
        j["accessors"][a]["count"].as_u64().unwrap()
    };
    assert_eq!((n(&j, 0), n(&j, 1)), (15, 15));
    assert_eq!(j["accessors"].as_array().unwrap().len(), asset()["accessors"].as_array().unwrap().len() + 2,
        "the shared POSITION accessor and the two index accessors reused, plus two restart lists");
    let kept = tmp("gltf-scene", "kept.glb");
    let run = stripkit(&["strip", input.to_str().unwrap(), "-o", kept.to_str().unwrap(), "--vertex-order", "input"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let k = glb_json(&kept);
    assert_eq!((n(&k, 0), n(&k, 1)), (15, 15));
    assert_eq!(k["accessors"][0], asset()["accessors"][0], "the shared POSITION accessor as read");

    support::gltf_validator::validate(&[&input, &out, &plain, &kept]);
}

#[test]
fn flags_that_mean_nothing_for_a_scene_exit_2() {
    let input = tmp("gltf-scene-flags", "two.gltf");
    std::fs::write(&input, serde_json::to_vec(&asset()).unwrap()).unwrap();
    let out = tmp("gltf-scene-flags", "out.glb");
    for (flags, says) in [
        (&["--join", "separate"][..], "--join separate does not apply to a glTF scene"),
        (&["--restart-index", "7"][..], "--restart-index does not apply to a glTF scene"),
        (&["--algo", "single"][..], "--algo single adds vertices"),
        (&["--algo", "qstrip"][..], "has none"),
    ] {
        let mut args = vec!["strip", input.to_str().unwrap(), "-o", out.to_str().unwrap()];
        args.extend_from_slice(flags);
        let run = stripkit(&args);
        assert_eq!(run.status.code(), Some(2), "{flags:?}");
        let err = String::from_utf8_lossy(&run.stderr);
        assert!(err.contains(says), "{flags:?}: {err}");
        assert!(!out.exists(), "{flags:?} wrote a file");
    }
    let json = tmp("gltf-scene-flags", "out.json");
    let run = stripkit(&["strip", input.to_str().unwrap(), "-o", json.to_str().unwrap(), "--vertex-order", "first-use"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("--vertex-order first-use applies to mesh outputs"));
    assert!(!json.exists());
}

#[test]
fn a_scene_without_triangles_is_refused() {
    let mut a = asset();
    a["meshes"][0]["primitives"] = json!([{"attributes": {"POSITION": 0}, "mode": 0}]);
    let input = tmp("gltf-scene-empty", "points.gltf");
    std::fs::write(&input, serde_json::to_vec(&a).unwrap()).unwrap();
    let out = tmp("gltf-scene-empty", "out.glb");
    let run = stripkit(&["strip", input.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("no faces in"));
    assert!(!out.exists());
}

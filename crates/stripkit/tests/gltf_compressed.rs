//! Quantized (`KHR_mesh_quantization`) and meshopt-compressed (`EXT_meshopt_compression`)
//! glTF in and out (issue #31, item 4): a quantized asset built here strips to a
//! quantized asset (every attribute accessor keeps its component type, `normalized` and
//! type; every corner the same stored bytes, decoded here independently of the
//! library), the mesh reader dequantizes through the node transform, hand-made meshopt
//! streams decode and hostile ones are format errors, and, where gltfpack is installed
//! (`.ci/node_modules`, by `.ci/run`), its `-c` and `-cc` outputs decode to its
//! uncompressed output. Every file written goes through the Khronos validator.

mod support;

use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use stripkit::io::{self, Format, ReadOptions};
use stripkit::scene::{Scene, SceneOptions};
use stripkit::{Error, StripOptions};
use stripkit_testkit::{glb, unglb, Lcg};



fn out_dir(name: &str) -> PathBuf {
    stripkit_testkit::scratch_dir(&format!("gltf-compressed-{name}"))
}

/// Element `k` of accessor `a` as its stored bytes (one buffer, view stride honoured).
fn element(json: &Value, bin: &[u8], a: usize, k: usize) -> Vec<u8> {
    let acc = &json["accessors"][a];
    let size = match acc["componentType"].as_u64().unwrap() {
        5120 | 5121 => 1,
        5122 | 5123 => 2,
        _ => 4,
    };
    let n = match acc["type"].as_str().unwrap() {
        "SCALAR" => 1,
        "VEC2" => 2,
        "VEC3" => 3,
        _ => 4,
    };
    let view = &json["bufferViews"][acc["bufferView"].as_u64().unwrap() as usize];
    let stride = view.get("byteStride").and_then(Value::as_u64).unwrap_or((size * n) as u64) as usize;
    let start = view.get("byteOffset").and_then(Value::as_u64).unwrap_or(0) as usize
        + acc.get("byteOffset").and_then(Value::as_u64).unwrap_or(0) as usize
        + k * stride;
    bin[start..start + size * n].to_vec()
}

fn index(json: &Value, bin: &[u8], a: usize, k: usize) -> u32 {
    let e = element(json, bin, a, k);
    e.iter().rev().fold(0u32, |v, &b| v << 8 | b as u32)
}

/// The triangles primitive 0 of mesh 0 draws, each corner the stored bytes of every
/// attribute (sorted by name), each triangle rotated to start at its smallest corner,
/// the list sorted: the same for the same drawing whatever the vertex ids and order.
fn corners(json: &Value, bin: &[u8]) -> Vec<[Vec<Vec<u8>>; 3]> {
    let prim = &json["meshes"][0]["primitives"][0];
    let mut attrs: Vec<(&String, usize)> =
        prim["attributes"].as_object().unwrap().iter().map(|(k, v)| (k, v.as_u64().unwrap() as usize)).collect();
    attrs.sort();
    let ia = prim["indices"].as_u64().unwrap() as usize;
    let n = json["accessors"][ia]["count"].as_u64().unwrap() as usize;
    let idx: Vec<u32> = (0..n).map(|k| index(json, bin, ia, k)).collect();
    let tris: Vec<[u32; 3]> = match prim.get("mode").and_then(Value::as_u64).unwrap_or(4) {
        4 => idx.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
        5 => (0..n.saturating_sub(2))
            .map(|k| if k % 2 == 0 { [idx[k], idx[k + 1], idx[k + 2]] } else { [idx[k + 1], idx[k], idx[k + 2]] })
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .collect(),
        m => panic!("mode {m}"),
    };
    let corner = |v: u32| -> Vec<Vec<u8>> { attrs.iter().map(|&(_, a)| element(json, bin, a, v as usize)).collect() };
    let mut out: Vec<[Vec<Vec<u8>>; 3]> = tris
        .iter()
        .map(|t| {
            let c = [corner(t[0]), corner(t[1]), corner(t[2])];
            let r = (0..3).min_by_key(|&r| c[r].clone()).unwrap();
            [c[r].clone(), c[(r + 1) % 3].clone(), c[(r + 2) % 3].clone()]
        })
        .collect();
    out.sort();
    out
}

/// A grid of `n` x `n` quads, triangles shuffled: POSITION unsigned 16-bit integers
/// (not normalized), NORMAL signed bytes (normalized), TEXCOORD_0 unsigned 16-bit
/// (normalized); a node whose scale and translation dequantize, as gltfpack writes.
fn quantized_asset(n: u32) -> (Value, Vec<u8>) {
    let side = n + 1;
    let mut bin = Vec::new();
    let (mut lo, mut hi) = ([u16::MAX; 3], [0u16; 3]);
    for y in 0..side {
        for x in 0..side {
            let p = [(x * 1000) as u16, (y * 1000) as u16, ((x * 7 + y * 3) % 11 * 300) as u16];
            for c in 0..3 {
                lo[c] = lo[c].min(p[c]);
                hi[c] = hi[c].max(p[c]);
            }
            p.iter().for_each(|c| bin.extend(c.to_le_bytes()));
            bin.extend([0, 0]); // 8-byte stride: vertex attributes start at multiples of 4
        }
    }
    let normals_at = bin.len();
    for v in 0..side * side {
        // Unit normals along the six axis directions, in turn.
        let mut n = [0i8; 3];
        n[(v % 3) as usize] = if v % 2 == 0 { 127 } else { -127 };
        bin.extend([n[0] as u8, n[1] as u8, n[2] as u8, 0]);
    }
    let uv_at = bin.len();
    for y in 0..side {
        for x in 0..side {
            bin.extend(((x * 65535 / n) as u16).to_le_bytes());
            bin.extend(((y * 65535 / n) as u16).to_le_bytes());
        }
    }
    let idx_at = bin.len();
    let mut tris = Vec::new();
    for y in 0..n {
        for x in 0..n {
            let v = y * side + x;
            tris.push([v, v + 1, v + side + 1]);
            tris.push([v, v + side + 1, v + side]);
        }
    }
    Lcg(31).shuffle(&mut tris);
    for t in &tris {
        t.iter().for_each(|&i| bin.extend((i as u16).to_le_bytes()));
    }
    let count = side * side;
    let json = json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_mesh_quantization"],
        "extensionsRequired": ["KHR_mesh_quantization"],
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "translation": [1.0, 2.0, 3.0], "scale": [0.001, 0.001, 0.001]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3}]}],
        "buffers": [{"byteLength": bin.len()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": normals_at, "byteStride": 8, "target": 34962},
            {"buffer": 0, "byteOffset": normals_at, "byteLength": uv_at - normals_at, "byteStride": 4, "target": 34962},
            {"buffer": 0, "byteOffset": uv_at, "byteLength": idx_at - uv_at, "target": 34962},
            {"buffer": 0, "byteOffset": idx_at, "byteLength": bin.len() - idx_at, "target": 34963}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5123, "count": count, "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5120, "normalized": true, "count": count, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5123, "normalized": true, "count": count, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": tris.len() * 3, "type": "SCALAR"}
        ]
    });
    (json, bin)
}

#[test]
fn a_quantized_asset_strips_to_a_quantized_asset_with_the_same_corners() {
    let (json, bin) = quantized_asset(12);
    let dir = out_dir("quantized");
    let input = dir.join("grid_quantized.glb");
    std::fs::write(&input, glb(&json, &bin)).unwrap();

    let mut scene = Scene::read(&input).unwrap();
    let report = scene.strip(&StripOptions::default(), &SceneOptions::default()).unwrap();
    assert_eq!(report.triangles, 288);
    let output = dir.join("grid_quantized_strips.glb");
    scene.write(&output).unwrap();
    let (out_json, out_bin) = unglb(&std::fs::read(&output).unwrap());

    // Still quantized: every attribute accessor as stored, the extension still required.
    let prim = &out_json["meshes"][0]["primitives"][0];
    assert_eq!(prim["mode"], 5);
    for (name, component, normalized) in
        [("POSITION", 5123, None), ("NORMAL", 5120, Some(true)), ("TEXCOORD_0", 5123, Some(true))]
    {
        let a = &out_json["accessors"][prim["attributes"][name].as_u64().unwrap() as usize];
        assert_eq!(a["componentType"], component, "{name}");
        assert_eq!(a.get("normalized").and_then(Value::as_bool), normalized, "{name}");
        assert_eq!(a["count"], 169, "{name}: every vertex is used");
    }
    assert_eq!(out_json["extensionsRequired"], json!(["KHR_mesh_quantization"]));
    assert_eq!(out_json["nodes"], json["nodes"]);
    // Corner by corner: the same triangles with the same stored bytes.
    assert_eq!(corners(&out_json, &out_bin), corners(&json, &bin));
    assert!(corners(&json, &bin).len() == 288);
    support::gltf_validator::validate(&[&input, &output]);

    // The mesh reader dequantizes through the node: (x * 1000, y * 1000, z) * 0.001 + (1, 2, 3).
    let mesh = io::read(&input).unwrap();
    assert_eq!(mesh.triangle_count(), 288);
    let p = mesh.positions[13 * 2 + 3]; // x = 3, y = 2
    let z = ((3 * 7 + 2 * 3) % 11 * 300) as f32 * 0.001 + 3.0;
    assert!((p[0] - 4.0).abs() < 1e-5 && (p[1] - 4.0).abs() < 1e-5 && (p[2] - z).abs() < 1e-5, "{p:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `SceneOptions::compress`: the quantized asset stripped and written with its index and
/// vertex views compressed (index sequences for the strips), smaller than the plain
/// output, validator-clean, and read back to the same primitives, corner by corner.
#[test]
fn a_compressed_output_reads_back_as_the_plain_output() {
    let (json, bin) = quantized_asset(20);
    let dir = out_dir("compress");
    let input = dir.join("grid.glb");
    std::fs::write(&input, glb(&json, &bin)).unwrap();
    let mut written = Vec::new();
    for (name, options) in [
        ("plain", SceneOptions::default()),
        ("compressed", SceneOptions::default().compress(true)),
        ("stitched-compressed", SceneOptions::stitched().compress(true)),
    ] {
        let mut scene = Scene::read(&input).unwrap();
        scene.strip(&StripOptions::default(), &options).unwrap();
        let out = dir.join(format!("grid-{name}.glb"));
        scene.write(&out).unwrap();
        written.push(out);
    }
    let size = |p: &Path| std::fs::metadata(p).unwrap().len();
    // 8,236 against 11,872 bytes when written (a 21 x 21 grid: noise-free vertex deltas).
    assert!(size(&written[1]) * 4 < size(&written[0]) * 3, "{} vs {}", size(&written[1]), size(&written[0]));
    assert!(size(&written[2]) < size(&written[1]), "{} vs {}", size(&written[2]), size(&written[1]));
    let (j, _) = unglb(&std::fs::read(&written[1]).unwrap());
    assert_eq!(j["extensionsRequired"], json!(["KHR_mesh_quantization", "EXT_meshopt_compression"]));
    let modes: Vec<&str> = j["bufferViews"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|v| v.pointer("/extensions/EXT_meshopt_compression/mode").and_then(Value::as_str))
        .collect();
    assert_eq!(modes.iter().filter(|m| **m == "INDICES").count(), 1, "{modes:?}");
    assert_eq!(modes.iter().filter(|m| **m == "ATTRIBUTES").count(), 3, "{modes:?}");
    let plain = Scene::read(&written[0]).unwrap();
    for out in &written[1..] {
        let back = Scene::read(out).unwrap();
        let (a, b) = (&plain.primitives()[0].mesh, &back.primitives()[0].mesh);
        assert_eq!(a.positions, b.positions);
        assert_eq!(a.attributes, b.attributes);
        let tris = |m: &stripkit::Mesh| m.faces().map(<[u32]>::to_vec).collect::<Vec<_>>();
        assert_eq!(tris(a), tris(b));
    }
    let refs: Vec<&Path> = written.iter().map(PathBuf::as_path).collect();
    support::gltf_validator::validate(&refs);
    std::fs::remove_dir_all(&dir).ok();
}

/// Positions of a unit quad (FLOAT) and its two triangles as an index view compressed
/// with EXT_meshopt_compression (the index-sequence codec, written by hand), the view
/// in a fallback buffer without data.
fn meshopt_asset(stream: &[u8], count: usize) -> (Value, Vec<u8>) {
    let mut bin: Vec<u8> = [[0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.], [1., 1., 0.]]
        .iter()
        .flatten()
        .flat_map(|c| c.to_le_bytes())
        .collect();
    let at = bin.len();
    bin.extend_from_slice(stream);
    let json = json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["EXT_meshopt_compression"],
        "extensionsRequired": ["EXT_meshopt_compression"],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": bin.len()}, {"byteLength": 2 * count, "extensions": {"EXT_meshopt_compression": {"fallback": true}}}],
        "bufferViews": [
            {"buffer": 0, "byteLength": 48, "target": 34962},
            {"buffer": 1, "byteLength": 2 * count, "target": 34963, "extensions": {"EXT_meshopt_compression": {
                "buffer": 0, "byteOffset": at, "byteLength": stream.len(), "byteStride": 2, "count": count, "mode": "INDICES"}}}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5123, "count": count, "type": "SCALAR"}
        ]
    });
    (json, bin)
}

#[test]
fn a_meshopt_compressed_view_is_decoded_and_written_back_plain() {
    // 0 1 2 2 1 3 on one baseline: zigzag deltas 0 +1 +1 0 -1 +2, shifted past the
    // baseline bit: 0 4 4 0 2 8; then the 4-byte tail.
    let stream = [0xD1, 0, 4, 4, 0, 2, 8, 0, 0, 0, 0];
    let (json, bin) = meshopt_asset(&stream, 6);
    let dir = out_dir("meshopt");
    let input = dir.join("quad_meshopt.glb");
    std::fs::write(&input, glb(&json, &bin)).unwrap();
    let mesh = io::read(&input).unwrap();
    let faces: Vec<&[u32]> = mesh.faces().collect();
    assert_eq!(faces, vec![&[0, 1, 2][..], &[2, 1, 3]]);

    let mut scene = Scene::read(&input).unwrap();
    scene.strip(&StripOptions::default(), &SceneOptions::default()).unwrap();
    let output = dir.join("quad_strips.glb");
    scene.write(&output).unwrap();
    let (out_json, out_bin) = unglb(&std::fs::read(&output).unwrap());
    let text = out_json.to_string();
    assert!(!text.contains("EXT_meshopt_compression"), "{text}");
    assert_eq!(out_json["buffers"].as_array().unwrap().len(), 1);
    let mut plain = json.clone();
    plain["bufferViews"][1] = json!({"buffer": 0, "byteOffset": 48, "byteLength": 12});
    let plain_bin: Vec<u8> = bin[..48].iter().copied().chain([0u8, 0, 1, 0, 2, 0, 2, 0, 1, 0, 3, 0]).collect();
    assert_eq!(corners(&out_json, &out_bin), corners(&plain, &plain_bin));
    support::gltf_validator::validate(&[&output]);

    // Hostile: cut short, a size that disagrees with the view, a huge count.
    let format = |json: &Value, bin: &[u8]| -> String {
        match Scene::from_bytes(Path::new("h.glb"), Format::Glb, &glb(json, bin), &ReadOptions::default()) {
            Err(e @ Error::Format { .. }) => e.to_string(),
            other => panic!("expected a format error, got {other:?}"),
        }
    };
    let (json, bin) = meshopt_asset(&stream[..10], 6);
    let e = format(&json, &bin);
    assert!(e.contains("bufferViews[1]") && e.contains("too early"), "{e}");
    let (mut json, bin) = meshopt_asset(&stream, 6);
    json["bufferViews"][1]["byteLength"] = 10.into();
    assert!(format(&json, &bin).contains("must equal the view's byteLength 10"));
    let (mut json, bin) = meshopt_asset(&stream, 6);
    json["bufferViews"][1]["byteLength"] = (1u64 << 41).into();
    json["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["count"] = (1u64 << 40).into();
    let e = format(&json, &bin);
    assert!(e.contains("max_decoded_bytes"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// gltfpack's outputs of the shipped spot (UVs kept): `-c` and `-cc` (meshopt
/// compression) decode to the same triangles as its uncompressed output, corner by
/// corner (position and UV), up to the rotation of their corners (the index codec may
/// rotate them) and vertex order (`-cc` reorders); each strips to a validator-clean
/// file. Skipped where gltfpack is absent.
#[test]
fn gltfpack_compressed_outputs_decode_to_its_plain_output() {
    let root = stripkit_testkit::repo_root();
    let cli = root.join(".ci/node_modules/gltfpack/cli.js");
    if !cli.is_file() {
        eprintln!("skip: gltfpack is not installed in .ci/node_modules (.ci/run installs it)");
        return;
    }
    let dir = out_dir("gltfpack");
    let spot = stripkit_testkit::assets_dir().join("spot.obj");
    let mut scenes = Vec::new();
    for flags in [&[][..], &["-c"], &["-cc"]] {
        let out = dir.join(format!("spot{}.glb", flags.join("")));
        let status = std::process::Command::new("node")
            .arg(&cli)
            .arg("-i")
            .arg(&spot)
            .arg("-o")
            .arg(&out)
            .arg("-kv")
            .args(flags)
            .output();
        match status {
            Ok(o) if o.status.success() => {}
            Ok(o) => panic!("gltfpack {flags:?} failed: {}", String::from_utf8_lossy(&o.stderr)),
            Err(e) => {
                eprintln!("skip: cannot run node for gltfpack: {e}");
                return;
            }
        }
        scenes.push((out.clone(), Scene::read(&out).unwrap()));
    }
    // Each triangle as its corners' values (position and every attribute, as bits),
    // rotated to start at the smallest corner; sorted.
    let drawn = |m: &stripkit::Mesh| -> Vec<[Vec<u64>; 3]> {
        let corner = |v: u32| -> Vec<u64> {
            let v = v as usize;
            let mut c: Vec<u64> = m.positions[v].iter().map(|x| x.to_bits() as u64).collect();
            for a in &m.attributes {
                c.extend((0..a.components as usize).map(|k| a.get(v, k).to_bits()));
            }
            c
        };
        let mut t: Vec<[Vec<u64>; 3]> = m
            .faces()
            .map(|f| {
                let c = [corner(f[0]), corner(f[1]), corner(f[2])];
                let r = (0..3).min_by_key(|&r| c[r].clone()).unwrap();
                [c[r].clone(), c[(r + 1) % 3].clone(), c[(r + 2) % 3].clone()]
            })
            .collect();
        t.sort();
        t
    };
    let plain = &scenes[0].1.primitives()[0].mesh;
    assert_eq!(plain.triangle_count(), 5856);
    assert_eq!(plain.attributes.len(), 1, "TEXCOORD_0 kept (-kv)");
    let want = drawn(plain);
    for (path, scene) in &scenes[1..] {
        let m = &scene.primitives()[0].mesh;
        assert_eq!(m.vertex_count(), plain.vertex_count(), "{}", path.display());
        assert_eq!(drawn(m), want, "{}", path.display());
    }
    let mut written = Vec::new();
    for (path, mut scene) in scenes {
        scene.strip(&StripOptions::default(), &SceneOptions::default()).unwrap();
        let out = path.with_extension("strips.glb");
        scene.write(&out).unwrap();
        written.push(out);
    }
    let refs: Vec<&Path> = written.iter().map(PathBuf::as_path).collect();
    support::gltf_validator::validate(&refs);
    std::fs::remove_dir_all(&dir).ok();
}

//! glTF scenes through `stripkit::scene::Scene` (the document of `io`, stripped above the door): a generated asset with two meshes, three
//! triangle primitives and a point primitive, two materials (one textured, one with an
//! unknown extension), interleaved NORMAL + TEXCOORD_0, a skin, an animation, a morph
//! target, two scenes, a node moved by [3, 0, 0] and extras comes back with the same
//! JSON apart from the meshes' indices and modes (and the new accessors, buffer view
//! and extension entries); every primitive draws the same triangles with the same
//! values at every corner, decoded here independently of the library; the Khronos
//! validator reports no error on any file written.

mod support;

use serde_json::{json, Value};
use std::path::Path;
use stripkit::io::{Format, ReadOptions};
use stripkit::scene::{Scene, SceneOptions};
use stripkit_testkit::{glb, unglb};
use stripkit::{gen, StripOptions};

/// Buffer, views and accessors of an asset under construction.
#[derive(Default)]
struct Builder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Builder {
    fn view(&mut self, bytes: &[u8], target: Option<u32>, stride: Option<usize>) -> usize {
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        let mut v = json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()});
        if let Some(t) = target {
            v["target"] = t.into();
        }
        if let Some(s) = stride {
            v["byteStride"] = s.into();
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(v);
        self.views.len() - 1
    }

    fn accessor(&mut self, a: Value) -> usize {
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    fn floats(&mut self, values: &[f32], kind: &str, n: usize, target: Option<u32>, bounds: bool) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes, target, None);
        let mut a = json!({"bufferView": view, "componentType": 5126, "count": values.len() / n, "type": kind});
        if bounds {
            let lo: Vec<f32> =
                (0..n).map(|c| values.iter().skip(c).step_by(n).cloned().fold(f32::MAX, f32::min)).collect();
            let hi: Vec<f32> =
                (0..n).map(|c| values.iter().skip(c).step_by(n).cloned().fold(f32::MIN, f32::max)).collect();
            a["min"] = json!(lo);
            a["max"] = json!(hi);
        }
        self.accessor(a)
    }
}

/// A deterministic shuffle (the triangles' order must not matter).
fn shuffle<T>(v: &mut [T], seed: u64) {
    stripkit_testkit::Lcg(seed).shuffle(v);
}

const PNG_1X1: &str =
    "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNkYPhfDwAChwGA60e6kgAAAABJRU5ErkJggg==";

/// The asset: (JSON, binary chunk).
fn asset() -> (Value, Vec<u8>) {
    let mut b = Builder::default();
    // Mesh 0: an icosphere, NORMAL and TEXCOORD_0 interleaved (stride 20), its shuffled
    // triangles split into two primitives (materials 0 and 1) over the same vertices,
    // plus a POINTS primitive.
    let sphere = gen::icosphere(2);
    let pos: Vec<f32> = sphere.positions.iter().flatten().cloned().collect();
    let p = b.floats(&pos, "VEC3", 3, Some(34962), true);
    let mut inter = Vec::new();
    for q in &sphere.positions {
        let l = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
        let uv = [0.5 + q[0].atan2(q[2]) / std::f32::consts::TAU, 0.5 - q[1].asin() / std::f32::consts::PI];
        for x in [q[0] / l, q[1] / l, q[2] / l, uv[0], uv[1]] {
            inter.extend_from_slice(&x.to_le_bytes());
        }
    }
    let iv = b.view(&inter, Some(34962), Some(20));
    let n =
        b.accessor(json!({"bufferView": iv, "componentType": 5126, "count": sphere.vertex_count(), "type": "VEC3"}));
    let t = b.accessor(
        json!({"bufferView": iv, "byteOffset": 12, "componentType": 5126, "count": sphere.vertex_count(), "type": "VEC2"}),
    );
    let mut tris = sphere.triangulate().tris;
    shuffle(&mut tris, 7);
    let idx: Vec<u8> = tris.iter().flatten().flat_map(|&i| (i as u16).to_le_bytes()).collect();
    let half = tris.len() / 2;
    let sv = b.view(&idx, Some(34963), None);
    let i0 = b.accessor(json!({"bufferView": sv, "componentType": 5123, "count": 3 * half, "type": "SCALAR"}));
    let i1 = b.accessor(json!({"bufferView": sv, "byteOffset": 6 * half, "componentType": 5123,
        "count": 3 * (tris.len() - half), "type": "SCALAR"}));
    // Mesh 1: a torus with u32 indices, a morph target, JOINTS_0 (u8) and WEIGHTS_0.
    let torus = gen::torus(16, 8, 1.0, 0.3);
    let tv = torus.vertex_count();
    let tpos: Vec<f32> = torus.positions.iter().flatten().cloned().collect();
    let tp = b.floats(&tpos, "VEC3", 3, Some(34962), true);
    let disp: Vec<f32> = tpos.iter().map(|x| x * 0.125).collect();
    let td = b.floats(&disp, "VEC3", 3, Some(34962), true);
    let jv = b.view(&vec![0u8; 4 * tv], Some(34962), None);
    let j = b.accessor(json!({"bufferView": jv, "componentType": 5121, "count": tv, "type": "VEC4"}));
    let w: Vec<f32> = (0..tv).flat_map(|_| [1.0, 0.0, 0.0, 0.0]).collect();
    let w = b.floats(&w, "VEC4", 4, Some(34962), false);
    let mut ttris = torus.triangulate().tris;
    shuffle(&mut ttris, 11);
    let tidx: Vec<u8> = ttris.iter().flatten().flat_map(|&i| i.to_le_bytes()).collect();
    let tiv = b.view(&tidx, Some(34963), None);
    let ti = b.accessor(json!({"bufferView": tiv, "componentType": 5125, "count": tidx.len() / 4, "type": "SCALAR"}));
    // Skin, animation.
    let ibm: Vec<f32> = vec![1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1.];
    let ibm = b.floats(&ibm, "MAT4", 16, None, false);
    let times = b.floats(&[0.0, 1.0], "SCALAR", 1, None, true);
    let quats = b.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.70710677, 0.70710677], "VEC4", 4, None, false);
    let json = json!({
        "asset": {"version": "2.0", "generator": "stripkit test", "extras": {"note": "generated"}},
        "extensionsUsed": ["EXT_stripkit_unknown"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2], "name": "all"}, {"nodes": [3], "name": "camera only"}],
        "nodes": [
            {"mesh": 0, "name": "sphere", "translation": [3.0, 0.0, 0.0], "extras": {"tag": 7}},
            {"mesh": 1, "skin": 0, "name": "torus"},
            {"name": "joint", "rotation": [0.0, 0.0, 0.0, 1.0]},
            {"camera": 0, "translation": [0.0, 0.0, 5.0]}
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
        "meshes": [
            {"name": "sphere", "primitives": [
                {"attributes": {"POSITION": p, "NORMAL": n, "TEXCOORD_0": t}, "indices": i0, "material": 0},
                {"attributes": {"POSITION": p, "NORMAL": n, "TEXCOORD_0": t}, "indices": i1, "material": 1, "mode": 4},
                {"attributes": {"POSITION": p}, "mode": 0}
            ]},
            {"name": "torus", "weights": [0.5], "extras": {"kind": "morphing"}, "primitives": [
                {"attributes": {"POSITION": tp, "JOINTS_0": j, "WEIGHTS_0": w}, "indices": ti, "material": 1,
                 "targets": [{"POSITION": td}]}
            ]}
        ],
        "materials": [
            {"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.0, 0.0, 1.0],
              "baseColorTexture": {"index": 0}}, "extensions": {"EXT_stripkit_unknown": {"answer": 42}}},
            {"name": "blue", "doubleSided": true}
        ],
        "textures": [{"source": 0, "sampler": 0}],
        "images": [{"uri": format!("data:image/png;base64,{PNG_1X1}")}],
        "samplers": [{"magFilter": 9729, "minFilter": 9729, "wrapS": 33071}],
        "skins": [{"inverseBindMatrices": ibm, "joints": [2]}],
        "animations": [{"name": "turn", "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}}],
            "samplers": [{"input": times, "output": quats, "interpolation": "LINEAR"}]}],
        "extras": {"root": true},
        "bufferViews": b.views,
        "accessors": b.accessors,
        "buffers": [{"byteLength": b.bin.len()}],
    });
    (json, b.bin)
}

/// The elements of an accessor (no sparse), each as its bytes.
fn elements(json: &Value, bin: &[u8], acc: usize) -> Vec<Vec<u8>> {
    let a = &json["accessors"][acc];
    let v = &json["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
    assert_eq!(v["buffer"], 0);
    let size = match a["componentType"].as_u64().unwrap() {
        5120 | 5121 => 1,
        5122 | 5123 => 2,
        _ => 4,
    };
    let n = match a["type"].as_str().unwrap() {
        "SCALAR" => 1,
        "VEC2" => 2,
        "VEC3" => 3,
        "VEC4" => 4,
        _ => 16,
    };
    let stride = v["byteStride"].as_u64().map_or(size * n, |s| s as usize);
    let start = v["byteOffset"].as_u64().unwrap_or(0) as usize + a["byteOffset"].as_u64().unwrap_or(0) as usize;
    (0..a["count"].as_u64().unwrap() as usize).map(|k| bin[start + k * stride..][..size * n].to_vec()).collect()
}

fn index_values(json: &Value, bin: &[u8], acc: usize) -> Vec<u32> {
    elements(json, bin, acc)
        .into_iter()
        .map(|e| match e.len() {
            1 => e[0] as u32,
            2 => u16::from_le_bytes([e[0], e[1]]) as u32,
            _ => u32::from_le_bytes(e.try_into().unwrap()),
        })
        .collect()
}

/// A corner: its vertex's bytes in every attribute, in attribute-name order.
type Corner = Vec<Vec<u8>>;

/// The triangles a primitive draws, each corner by its values, rotated to start at the
/// smallest corner, sorted. `indices` overrides the primitive's own (a restart group);
/// `restart` splits them into strips.
fn drawn(json: &Value, bin: &[u8], m: usize, p: usize, indices: Option<(usize, u32)>) -> Vec<[Corner; 3]> {
    let prim = &json["meshes"][m]["primitives"][p];
    let attrs = prim["attributes"].as_object().unwrap();
    let values: Vec<Vec<Vec<u8>>> = attrs.values().map(|a| elements(json, bin, a.as_u64().unwrap() as usize)).collect();
    let corner = |v: u32| -> Corner { values.iter().map(|a| a[v as usize].clone()).collect() };
    let mode = prim["mode"].as_u64().unwrap_or(4);
    let (list, restart) = match indices {
        Some((acc, r)) => (index_values(json, bin, acc), Some(r)),
        None => (index_values(json, bin, prim["indices"].as_u64().unwrap() as usize), None),
    };
    let mut tris = Vec::new();
    match mode {
        4 => tris.extend(list.chunks(3).map(|t| [t[0], t[1], t[2]])),
        5 => {
            for s in list.split(|&i| Some(i) == restart) {
                for k in 0..s.len().saturating_sub(2) {
                    let t = if k % 2 == 0 { [s[k], s[k + 1], s[k + 2]] } else { [s[k + 1], s[k], s[k + 2]] };
                    if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                        tris.push(t);
                    }
                }
            }
        }
        _ => panic!("mode {mode}"),
    }
    let mut out: Vec<[Corner; 3]> = tris
        .into_iter()
        .map(|t| {
            let c = [corner(t[0]), corner(t[1]), corner(t[2])];
            let k = (0..3).min_by(|&a, &b| c[a].cmp(&c[b])).unwrap();
            [c[k].clone(), c[(k + 1) % 3].clone(), c[(k + 2) % 3].clone()]
        })
        .collect();
    out.sort();
    out
}

/// `json` without what stripping may change.
fn untouched(json: &Value) -> Value {
    let mut j = json.clone();
    for k in ["meshes", "accessors", "bufferViews", "buffers", "extensionsUsed"] {
        j.as_object_mut().unwrap().remove(k);
    }
    j
}

fn out_dir(name: &str) -> std::path::PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn a_scene_comes_back_whole_with_the_same_triangles_at_every_corner() {
    let (json, bin) = asset();
    let input = glb(&json, &bin);
    let dir = out_dir("gltf_scene_whole");
    let in_path = dir.join("in.glb");
    std::fs::write(&in_path, &input).unwrap();
    let mut scene = Scene::read(&in_path).unwrap();
    let prims = scene.primitives();
    assert_eq!(prims.len(), 3, "two sphere primitives and the torus; points are not listed");
    assert_eq!(prims[0].mesh.face_count() + prims[1].mesh.face_count(), 320);
    assert_eq!(prims[2].mesh.face_count(), 256);
    assert_eq!(prims[2].targets, 1);
    let names: Vec<&str> = prims[0].mesh.attributes.iter().map(|a| a.name.as_str()).collect();
    assert_eq!(names, ["NORMAL", "TEXCOORD_0"]);
    assert_eq!(prims[0].mesh.attributes[1].components, 2);
    let joints = prims[2].mesh.attribute("JOINTS_0").unwrap();
    assert_eq!((joints.scalar, joints.components), (stripkit::Scalar::U8, 4));
    assert_eq!(prims[0].mesh.groups[0].material.as_deref(), Some("red"));
    assert_eq!(prims[1].mesh.groups[0].material.as_deref(), Some("blue"));
    assert_eq!(prims[2].mesh.groups[0].name, "torus");

    let report = scene.strip(&StripOptions::default(), &SceneOptions::default().reorder(false)).unwrap();
    assert_eq!(report.primitives.len(), 3);
    assert_eq!(report.skipped, 1, "the points primitive");
    assert_eq!(report.triangles, 576);
    assert_eq!(report.indices_read, 3 * 576);
    assert!(report.indices_stitched < 3 * 576, "{report:?}");
    assert!(report.primitives[0].indices_restart.is_some() && report.primitives[2].indices_restart.is_none());
    let out_path = dir.join("out.glb");
    scene.write(&out_path).unwrap();
    let out = std::fs::read(&out_path).unwrap();
    let (oj, ob) = unglb(&out);

    assert_eq!(untouched(&oj), untouched(&json), "everything but meshes, accessors, views, buffers is as read");
    let n_acc = json["accessors"].as_array().unwrap().len();
    assert_eq!(oj["accessors"].as_array().unwrap()[..n_acc], json["accessors"].as_array().unwrap()[..]);
    let n_views = json["bufferViews"].as_array().unwrap().len();
    assert_eq!(oj["bufferViews"].as_array().unwrap()[..n_views], json["bufferViews"].as_array().unwrap()[..]);
    assert_eq!(oj["bufferViews"].as_array().unwrap().len(), n_views + 1, "one view for all new indices");
    assert_eq!(oj["extensionsUsed"], json!(["EXT_stripkit_unknown", "EXT_mesh_primitive_restart"]));
    assert!(oj.get("extensionsRequired").is_none());
    // Meshes: only indices and mode of the triangle primitives, and the restart groups.
    for (m, mesh) in json["meshes"].as_array().unwrap().iter().enumerate() {
        let om = &oj["meshes"][m];
        for (p, prim) in mesh["primitives"].as_array().unwrap().iter().enumerate() {
            let op = &om["primitives"][p];
            let mut a = prim.clone();
            let mut o = op.clone();
            for k in ["indices", "mode"] {
                a.as_object_mut().unwrap().remove(k);
                o.as_object_mut().unwrap().remove(k);
            }
            assert_eq!(a, o, "meshes[{m}].primitives[{p}]");
            if prim["mode"] == 0 {
                assert_eq!(prim, op, "the points primitive is untouched");
                continue;
            }
            assert_eq!(op["mode"], 5);
            assert!(op["indices"].as_u64().unwrap() as usize >= n_acc, "a new accessor");
            // The stitched fallback draws the same triangles, corner values included.
            let want = drawn(&json, &bin, m, p, None);
            assert_eq!(want.len(), if m == 0 { 160 } else { 256 });
            assert_eq!(drawn(&oj, &ob, m, p, None), want, "stitched meshes[{m}].primitives[{p}]");
        }
        let mut a = mesh.clone();
        let mut o = om.clone();
        a.as_object_mut().unwrap().remove("primitives");
        o.as_object_mut().unwrap().remove("primitives");
        let groups = o.as_object_mut().unwrap().remove("extensions");
        assert_eq!(a, o, "meshes[{m}] apart from primitives and the extension");
        if m == 0 {
            let groups = groups.unwrap()["EXT_mesh_primitive_restart"]["primitiveGroups"].clone();
            let groups = groups.as_array().unwrap();
            assert_eq!(groups.len(), 2);
            for (k, g) in groups.iter().enumerate() {
                assert_eq!(g["primitives"], json!([k]));
                let acc = g["indices"].as_u64().unwrap() as usize;
                assert_eq!(oj["accessors"][acc]["componentType"], 5123);
                let list = index_values(&oj, &ob, acc);
                assert!(list.contains(&65535), "restart values between strips");
                assert_eq!(drawn(&oj, &ob, 0, k, Some((acc, 65535))), drawn(&json, &bin, 0, k, None));
            }
        } else {
            assert!(groups.is_none(), "a primitive with morph targets gets no restart group");
        }
    }

    // Plain stitched strips: no extension.
    scene.strip(&StripOptions::default(), &SceneOptions::stitched().reorder(false)).unwrap();
    let plain_path = dir.join("plain.gltf");
    scene.write(&plain_path).unwrap();
    let plain: Value = serde_json::from_slice(&std::fs::read(&plain_path).unwrap()).unwrap();
    assert_eq!(plain["extensionsUsed"], json!(["EXT_stripkit_unknown"]));
    assert!(plain["meshes"][0].get("extensions").is_none());
    assert_eq!(untouched(&plain), untouched(&json));
    // The .gltf reads back as a scene with the same triangles.
    let back = Scene::read(&plain_path).unwrap();
    assert_eq!(back.primitives().len(), 3);
    assert_eq!(back.primitives()[0].mesh.attributes, scene.primitives()[0].mesh.attributes);

    support::gltf_validator::validate(&[&in_path, &out_path, &plain_path]);
}

#[test]
fn a_scene_of_a_restart_output_strips_again_without_stale_groups() {
    let (json, bin) = asset();
    let data = glb(&json, &bin);
    let mut scene = Scene::from_bytes(Path::new("a.glb"), Format::Glb, &data, &ReadOptions::default()).unwrap();
    scene.strip(&StripOptions::default(), &SceneOptions::default()).unwrap();
    let once = scene.to_bytes(Format::Glb).unwrap();
    let mut again = Scene::from_bytes(Path::new("b.glb"), Format::Glb, &once, &ReadOptions::default()).unwrap();
    assert!(again.primitives().iter().all(|p| p.mode == 5));
    again.strip(&StripOptions::default(), &SceneOptions::default()).unwrap();
    let twice = again.to_bytes(Format::Glb).unwrap();
    let (j, _) = unglb(&twice);
    let groups = j["meshes"][0]["extensions"]["EXT_mesh_primitive_restart"]["primitiveGroups"].as_array().unwrap();
    assert_eq!(groups.len(), 2, "old groups replaced, not added to");
    assert_eq!(
        j["extensionsUsed"].as_array().unwrap().iter().filter(|e| *e == "EXT_mesh_primitive_restart").count(),
        1
    );
}

#[test]
fn a_restart_output_stripped_without_groups_lists_no_extension() {
    // Found by three.js round trips of stripkit's own outputs: the extension taken out
    // of `extensionsUsed` left `"extensionsUsed": []`, which the validator refuses.
    let mut scene = Scene::from_mesh(&gen::icosphere(2)).unwrap();
    scene.strip(&StripOptions::default(), &SceneOptions::default()).unwrap();
    let once = scene.to_bytes(Format::Glb).unwrap();
    assert_eq!(unglb(&once).0["extensionsUsed"], serde_json::json!(["EXT_mesh_primitive_restart"]));
    let mut again = Scene::from_bytes(Path::new("b.glb"), Format::Glb, &once, &ReadOptions::default()).unwrap();
    again.strip(&StripOptions::default(), &SceneOptions::stitched()).unwrap();
    let twice = again.to_bytes(Format::Glb).unwrap();
    let (j, _) = unglb(&twice);
    assert!(j.get("extensionsUsed").is_none(), "{}", j["extensionsUsed"]);
    assert!(j["meshes"][0].pointer("/extensions/EXT_mesh_primitive_restart").is_none());
    let path = out_dir("stitched-again").join("twice.glb");
    std::fs::write(&path, &twice).unwrap();
    support::gltf_validator::validate(&[&path]);
}

#[test]
fn single_is_refused_for_scenes() {
    let (json, bin) = asset();
    let mut scene =
        Scene::from_bytes(Path::new("a.glb"), Format::Glb, &glb(&json, &bin), &ReadOptions::default()).unwrap();
    let opts = StripOptions::default().algorithm(stripkit::Algorithm::Single(Default::default()));
    let e = scene.strip(&opts, &SceneOptions::default()).unwrap_err().to_string();
    assert!(e.contains("single adds vertices"), "{e}");
}

#[test]
fn hostile_references_are_clear_errors() {
    let (json, bin) = asset();
    type Change = Box<dyn Fn(&mut Value)>;
    let cases: Vec<(&str, Change, &str)> = vec![
        ("accessor past its view", Box::new(|j| j["accessors"][0]["count"] = 1_000_000.into()), "truncated"),
        ("huge count", Box::new(|j| j["accessors"][5]["count"] = u64::MAX.into()), "accessors[5]"),
        ("bufferView index", Box::new(|j| j["accessors"][1]["bufferView"] = 99.into()), "bufferView 99"),
        (
            "accessor index",
            Box::new(|j| j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 77.into()),
            "no such accessor",
        ),
        (
            "view past buffer",
            Box::new(|j| j["bufferViews"][0]["byteLength"] = Value::from(1u64 << 40)),
            "outside buffer",
        ),
        ("attribute count", Box::new(|j| j["accessors"][2]["count"] = 5.into()), "has 5 values but POSITION has 162"),
        ("sparse", Box::new(|j| j["accessors"][1]["sparse"] = json!({"count": 1})), "sparse"),
        (
            "draco",
            Box::new(|j| j["extensionsRequired"] = json!(["KHR_draco_mesh_compression"])),
            "KHR_draco_mesh_compression",
        ),
        (
            "reused accessors",
            Box::new(|j| {
                let p = j["meshes"][0]["primitives"][0].clone();
                j["meshes"][0]["primitives"] = Value::Array(vec![p; 2000]);
            }),
            "ReadOptions::max_decoded_bytes",
        ),
        ("meshopt v1", Box::new(|j| j["extensionsUsed"] = json!(["KHR_meshopt_compression"])), "KHR_meshopt_compression"),
        (
            "index range",
            Box::new(|j| j["meshes"][0]["primitives"][0]["attributes"] = json!({"POSITION": 5})),
            "refers to vertex",
        ),
    ];
    for (what, change, expect) in cases {
        let mut j = json.clone();
        change(&mut j);
        let e = Scene::from_bytes(Path::new("h.glb"), Format::Glb, &glb(&j, &bin), &ReadOptions::default())
            .map(|_| ())
            .unwrap_err()
            .to_string();
        assert!(e.contains(expect), "{what}: {e}");
    }
}

/// A torus in two material groups (by face halves, faces shuffled), with NORMAL,
/// TEXCOORD_0, a PLY-like `quality` (f64) and a five-component attribute glTF cannot
/// take.
fn grouped_torus(quads: bool) -> stripkit::Mesh {
    use stripkit::{Attribute, Group, Scalar};
    let base = if quads { gen::torus_quads(12, 8, 1.0, 0.3) } else { gen::torus(12, 8, 1.0, 0.3) };
    let mut faces: Vec<Vec<u32>> = base.faces().map(|f| f.to_vec()).collect();
    shuffle(&mut faces, 3);
    let mut mesh = stripkit::Mesh::from_polygons(base.positions.clone(), &faces);
    let n = mesh.vertex_count();
    let normals = stripkit_testkit::geom::radial_normals(&base.positions);
    mesh.attributes.push(Attribute::from_f32("NORMAL", 3, &normals));
    let uv: Vec<f32> = (0..n).flat_map(|v| [v as f32 / n as f32, 0.25]).collect();
    mesh.attributes.push(Attribute::from_f32("TEXCOORD_0", 2, &uv));
    let quality: Vec<u8> = (0..n).flat_map(|v| (v as f64 * 0.5).to_le_bytes()).collect();
    mesh.attributes.push(Attribute {
        name: "quality".into(),
        scalar: Scalar::F64,
        components: 1,
        normalized: false,
        data: quality,
    });
    mesh.attributes.push(Attribute::from_f32("big", 5, &vec![0.0; 5 * n]));
    mesh.face_groups = (0..mesh.face_count()).map(|f| (mesh.face(f).iter().min().unwrap() % 2) as u32).collect();
    mesh.groups = vec![
        Group { name: "even".into(), material: Some("gold".into()) },
        Group { name: "odd".into(), material: Some("silver".into()) },
    ];
    mesh
}

/// The triangles of `tris` by their corners' values: position and every listed
/// attribute as f32, rotated to the smallest corner, sorted.
fn corner_values(mesh: &stripkit::Mesh, tris: &[[u32; 3]], attrs: &[&str]) -> Vec<Vec<Vec<u32>>> {
    let corner = |v: u32| -> Vec<u32> {
        let mut c: Vec<u32> = mesh.positions[v as usize].iter().map(|x| x.to_bits()).collect();
        for name in attrs {
            let a = mesh.attribute(name).unwrap_or_else(|| panic!("no {name}"));
            c.extend(a.value(v as usize).iter().map(|&x| (x as f32).to_bits()));
        }
        c
    };
    let mut out: Vec<Vec<Vec<u32>>> = tris
        .iter()
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .map(|t| {
            let c = [corner(t[0]), corner(t[1]), corner(t[2])];
            let k = (0..3).min_by(|&a, &b| c[a].cmp(&c[b])).unwrap();
            vec![c[k].clone(), c[(k + 1) % 3].clone(), c[(k + 2) % 3].clone()]
        })
        .collect();
    out.sort();
    out
}

#[test]
fn a_mesh_with_groups_and_attributes_becomes_one_primitive_per_group() {
    let mesh = grouped_torus(false);
    let mut scene = Scene::from_mesh(&mesh).unwrap();
    assert_eq!(scene.notes().len(), 1, "{:?}", scene.notes());
    assert!(scene.notes()[0].contains("big has 5 components"), "{:?}", scene.notes());
    let report = scene.strip(&StripOptions::default(), &SceneOptions::default()).unwrap();
    assert_eq!(report.triangles, mesh.triangle_count());
    let dir = out_dir("gltf_scene_groups");
    let path = dir.join("torus.glb");
    scene.write(&path).unwrap();
    let back = Scene::read(&path).unwrap();
    let (j, _) = unglb(&std::fs::read(&path).unwrap());
    assert_eq!(j["materials"], json!([{"name": "gold"}, {"name": "silver"}]));
    let prims = back.primitives();
    assert_eq!(prims.len(), 2);
    let attrs = ["NORMAL", "TEXCOORD_0", "_QUALITY"];
    for (g, p) in prims.iter().enumerate() {
        let names: Vec<&str> = p.mesh.attributes.iter().map(|a| a.name.as_str()).collect();
        assert_eq!(names, attrs);
        assert_eq!(p.mesh.groups[0].material.as_deref(), Some(["gold", "silver"][g]));
        assert_eq!(j["meshes"][0]["primitives"][g]["mode"], 5);
        // The group's triangles, with the same values at every corner.
        let want: Vec<[u32; 3]> = mesh
            .triangulate()
            .tris
            .iter()
            .zip(mesh.triangulate().face_of)
            .filter(|(_, f)| mesh.group_of(*f as usize) == g as u32)
            .map(|(t, _)| *t)
            .collect();
        let mut input = mesh.clone();
        input.attributes.retain(|a| a.name != "big");
        input.attributes[2].name = "_QUALITY".into();
        assert_eq!(
            corner_values(&p.mesh, &p.mesh.triangulate().tris, &attrs),
            corner_values(&input, &want, &attrs),
            "group {g}"
        );
    }
    // Quads: the door may split them its own way; the file is checked against that.
    let quads = grouped_torus(true);
    let mut scene = Scene::from_mesh(&quads).unwrap();
    let report = scene.strip(&StripOptions::default(), &SceneOptions::default()).unwrap();
    assert_eq!(report.triangles, 2 * quads.face_count());
    assert!(report.primitives.iter().all(|p| p.algorithm == "qstrip"), "{report:?}");
    let qpath = dir.join("quads.gltf");
    scene.write(&qpath).unwrap();
    support::gltf_validator::validate(&[&path, &qpath]);
}

#[test]
fn the_old_index_data_is_dropped_when_every_extension_is_known() {
    let (mut json, bin) = asset();
    // Without the unknown extension, old index accessors and views may be reused.
    json.as_object_mut().unwrap().remove("extensionsUsed");
    json["materials"][0].as_object_mut().unwrap().remove("extensions");
    let data = glb(&json, &bin);
    let mut scene = Scene::from_bytes(Path::new("a.glb"), Format::Glb, &data, &ReadOptions::default()).unwrap();
    let report = scene.strip(&StripOptions::default(), &SceneOptions::default().reorder(false)).unwrap();
    let dir = out_dir("gltf_scene_collect");
    let path = dir.join("collected.glb");
    scene.write(&path).unwrap();
    let (oj, ob) = unglb(&std::fs::read(&path).unwrap());
    let n_acc = json["accessors"].as_array().unwrap().len();
    // The stitched indices take the old index accessors' numbers (3, 4, 9); the two
    // sphere restart groups are new.
    assert_eq!(oj["accessors"].as_array().unwrap().len(), n_acc + 2);
    for (m, p, old) in [(0, 0, 3), (0, 1, 4), (1, 0, 9)] {
        assert_eq!(oj["meshes"][m]["primitives"][p]["indices"], old);
        assert_eq!(drawn(&oj, &ob, m, p, None), drawn(&json, &bin, m, p, None));
    }
    for (k, a) in json["accessors"].as_array().unwrap().iter().enumerate() {
        if ![3, 4, 9].contains(&k) {
            assert_eq!(oj["accessors"][k], *a, "accessors[{k}] kept");
        }
    }
    assert_eq!(oj["bufferViews"].as_array().unwrap().len(), json["bufferViews"].as_array().unwrap().len());
    // The buffer holds the vertex, skin and animation data and the new indices only.
    let old_index_bytes = 2 * 3 * 320 + 4 * 3 * 256;
    let new_index_bytes = 2
        * (report.indices_stitched
            + report.primitives[0].indices_restart.unwrap()
            + report.primitives[1].indices_restart.unwrap());
    let len = oj["buffers"][0]["byteLength"].as_u64().unwrap() as usize;
    assert!(len <= bin.len() - old_index_bytes + new_index_bytes + 64, "{len} bytes");
    assert!(len >= bin.len() - old_index_bytes + new_index_bytes, "{len} bytes");
    assert_eq!(untouched(&oj), untouched(&json));
    support::gltf_validator::validate(&[&path]);
}

#[test]
fn external_buffers_are_embedded_and_image_uris_kept() {
    let (mut json, bin) = asset();
    let dir = out_dir("gltf_scene_external");
    std::fs::write(dir.join("scene data.bin"), &bin).unwrap();
    json["buffers"][0]["uri"] = "scene%20data.bin".into();
    std::fs::write(dir.join("tex.png"), png_bytes()).unwrap();
    json["images"][0] = json!({"uri": "tex.png"});
    let input = dir.join("external.gltf");
    std::fs::write(&input, serde_json::to_vec(&json).unwrap()).unwrap();
    let mut scene = Scene::read(&input).unwrap();
    scene.strip(&StripOptions::default(), &SceneOptions::default().reorder(false)).unwrap();
    let out = dir.join("external.out.gltf");
    scene.write(&out).unwrap();
    let oj: Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(oj["buffers"].as_array().unwrap().len(), 1);
    assert!(oj["buffers"][0]["uri"].as_str().unwrap().starts_with("data:application/octet-stream;base64,"));
    assert_eq!(oj["images"], json["images"], "image uris as written");
    let back = Scene::read(&out).unwrap();
    assert_eq!(back.primitives().len(), 3);
    for (a, b) in scene.primitives().iter().zip(back.primitives()) {
        assert_eq!(a.mesh.attributes, b.mesh.attributes);
        assert_eq!(a.mesh.positions, b.mesh.positions);
    }
    support::gltf_validator::validate(&[&input, &out]);
}

/// The bytes of the generated asset's 1 x 1 PNG.
fn png_bytes() -> Vec<u8> {
    let table = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = Vec::new();
    let (mut acc, mut bits) = (0u32, 0);
    for c in PNG_1X1.bytes().filter(|&c| c != b'=') {
        acc = (acc << 6) | table.iter().position(|&t| t == c).unwrap() as u32;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    out
}

#[test]
fn vertices_are_renumbered_in_first_use_and_unused_ones_left_out() {
    let (json, bin) = asset();
    let data = glb(&json, &bin);
    let mut scene = Scene::from_bytes(Path::new("a.glb"), Format::Glb, &data, &ReadOptions::default()).unwrap();
    scene.strip(&StripOptions::default(), &SceneOptions::default()).unwrap();
    let dir = out_dir("gltf_scene_reorder");
    let path = dir.join("reordered.glb");
    scene.write(&path).unwrap();
    let (oj, ob) = unglb(&std::fs::read(&path).unwrap());
    for (m, p) in [(0, 0), (0, 1), (1, 0)] {
        let prim = &oj["meshes"][m]["primitives"][p];
        // Same triangles with the same values at every corner, decoded here.
        assert_eq!(drawn(&oj, &ob, m, p, None), drawn(&json, &bin, m, p, None), "meshes[{m}].primitives[{p}]");
        // The sphere halves share one vertex array: it is kept as read (a first-use
        // copy each would leave the shared 162 vertices behind, unused). The torus has
        // its own and is renumbered, all 128 vertices.
        let n = oj["accessors"][prim["attributes"]["POSITION"].as_u64().unwrap() as usize]["count"].as_u64().unwrap();
        for a in prim["attributes"].as_object().unwrap().values() {
            assert_eq!(oj["accessors"][a.as_u64().unwrap() as usize]["count"].as_u64().unwrap(), n);
        }
        if m == 0 {
            assert_eq!(n, 162);
            assert_eq!(prim["attributes"], json["meshes"][m]["primitives"][p]["attributes"], "the shared accessors as read");
            continue;
        }
        assert_eq!(n, 128);
        // First use: vertex k appears before vertex k + 1 in the stitched strip.
        let list = index_values(&oj, &ob, prim["indices"].as_u64().unwrap() as usize);
        let mut next = 0;
        for &v in &list {
            assert!(v <= next, "vertex {v} used before {next}");
            if v == next {
                next += 1;
            }
        }
        assert_eq!(next as u64, n, "every kept vertex is used");
    }
    // The morph target was gathered too: its values follow the positions'.
    let tprim = &oj["meshes"][1]["primitives"][0];
    let pos = elements(&oj, &ob, tprim["attributes"]["POSITION"].as_u64().unwrap() as usize);
    let disp = elements(&oj, &ob, tprim["targets"][0]["POSITION"].as_u64().unwrap() as usize);
    for (p, d) in pos.iter().zip(&disp) {
        for c in 0..3 {
            let x = f32::from_le_bytes(p[4 * c..4 * c + 4].try_into().unwrap());
            let y = f32::from_le_bytes(d[4 * c..4 * c + 4].try_into().unwrap());
            assert_eq!(y, x * 0.125);
        }
    }
    assert_eq!(untouched(&oj), untouched(&json));
    support::gltf_validator::validate(&[&path]);
}

#[test]
fn normals_off_unit_length_are_rescaled_and_zero_ones_renamed() {
    // A PLY's nx ny nz need not be unit vectors; glTF's NORMAL must be.
    let mut mesh = gen::icosphere(1);
    let n = mesh.vertex_count();
    let normals: Vec<f32> = mesh.positions.iter().flat_map(|p| p.map(|x| 7.0 * x)).collect();
    mesh.attributes.push(stripkit::Attribute::from_f32("NORMAL", 3, &normals));
    let scene = Scene::from_mesh(&mesh).unwrap();
    assert!(
        scene.notes().iter().any(|s| s.contains(&format!("{n} of {n} NORMAL vectors rescaled"))),
        "{:?}",
        scene.notes()
    );
    let written = scene.primitives()[0].mesh.attribute("NORMAL").expect("NORMAL written");
    for v in 0..n {
        let len = (0..3).map(|c| written.get(v, c).powi(2)).sum::<f64>().sqrt();
        assert!((len - 1.0).abs() < 1e-6, "vertex {v}: length {len}");
        for c in 0..3 {
            assert!((written.get(v, c) - mesh.positions[v][c] as f64).abs() < 1e-6, "vertex {v}: direction kept");
        }
    }
    let bytes = scene.to_bytes(Format::Glb).unwrap();
    let path = out_dir("unit-normals").join("rescaled.glb");
    std::fs::write(&path, &bytes).unwrap();
    // A zero normal cannot be made unit: the values go out unchanged as _NORMAL.
    let mut zero = normals.clone();
    zero[..3].fill(0.0);
    mesh.attributes[0] = stripkit::Attribute::from_f32("NORMAL", 3, &zero);
    let scene = Scene::from_mesh(&mesh).unwrap();
    assert!(scene.notes().iter().any(|s| s.contains("written as _NORMAL")), "{:?}", scene.notes());
    let p = &scene.primitives()[0].mesh;
    assert!(p.attribute("NORMAL").is_none());
    assert_eq!(p.attribute("_NORMAL").unwrap().value(1), mesh.attributes[0].value(1));
    let renamed = out_dir("unit-normals").join("renamed.glb");
    std::fs::write(&renamed, scene.to_bytes(Format::Glb).unwrap()).unwrap();
    support::gltf_validator::validate(&[&path, &renamed]);
}

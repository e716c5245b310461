//! OBJ `.mtl` materials into glTF (issue #31, item 3): `Kd`, `d` / `Tr`, `Ns` with
//! `Ks`, `map_Kd` and `map_Bump` become a metallic-roughness material with its PNG
//! embedded in the .glb (and in a .gltf's buffer); statements without a glTF
//! counterpart are a note; an `mtllib` outside the OBJ's folder is refused (exit 2).
//! Every glTF written goes through the Khronos validator.

mod support;

use serde_json::Value;
use support::{gltf_validator, stripkit, tmp};

/// A 2x2 RGB PNG (red, green, blue, white), chunks and CRCs written out by hand.
const PNG: [u8; 75] = [
    137, 80, 78, 71, 13, 10, 26, 10, 0, 0, 0, 13, 73, 72, 68, 82, 0, 0, 0, 2, 0, 0, 0, 2, 8, 2, 0, 0, 0, 253, 212,
    154, 115, 0, 0, 0, 18, 73, 68, 65, 84, 120, 156, 99, 248, 207, 192, 192, 0, 194, 12, 255, 129, 0, 0, 31, 238, 5,
    251, 11, 217, 104, 139, 0, 0, 0, 0, 73, 69, 78, 68, 174, 66, 96, 130,
];

const OBJ: &str = "mtllib m.mtl
v 0 0 0
v 1 0 0
v 2 0 0
v 0 1 0
v 1 1 0
v 2 1 0
vt 0 0
vt 0.5 0
vt 1 0
vt 0 1
vt 0.5 1
vt 1 1
usemtl painted
f 1/1 2/2 5/5 4/4
usemtl glass
f 2/2 3/3 6/6 5/5
";

const MTL: &str = "newmtl painted
Kd 0.8 0.2 0.1
Ks 0.5 0.5 0.5
Ns 62
map_Kd tex/paint.png
map_Bump -bm 1.0 tex/paint.png
illum 2
newmtl glass
Kd 0 0 1
Tr 0.75
";

fn glb_json(bytes: &[u8]) -> (Value, Vec<u8>) {
    let u = |o: usize| u32::from_le_bytes(bytes[o..o + 4].try_into().unwrap()) as usize;
    let jl = u(12);
    let json: Value = serde_json::from_slice(&bytes[20..20 + jl]).unwrap();
    let bo = 20 + jl;
    (json, bytes[bo + 8..bo + 8 + u(bo)].to_vec())
}

#[test]
fn an_obj_with_mtl_and_png_becomes_a_textured_pbr_glb() {
    let obj = tmp("mtl", "painted.obj");
    let dir = obj.parent().unwrap();
    std::fs::create_dir_all(dir.join("tex")).unwrap();
    std::fs::write(&obj, OBJ).unwrap();
    std::fs::write(dir.join("m.mtl"), MTL).unwrap();
    std::fs::write(dir.join("tex/paint.png"), PNG).unwrap();
    let glb = dir.join("painted.glb");
    let out = stripkit(&["strip", obj.to_str().unwrap(), "-o", glb.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("m.mtl: not carried into glTF: illum (1), map_Bump options (1)"), "{err}");
    let (json, bin) = glb_json(&std::fs::read(&glb).unwrap());
    let materials = json["materials"].as_array().unwrap();
    let by_name = |n: &str| materials.iter().find(|m| m["name"] == n).unwrap();
    let painted = by_name("painted");
    let pbr = &painted["pbrMetallicRoughness"];
    let color: Vec<f64> = pbr["baseColorFactor"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    assert_eq!(color, [0.8f32, 0.2, 0.1, 1.0].map(f64::from));
    assert_eq!(pbr["metallicFactor"], 0.0);
    let roughness = pbr["roughnessFactor"].as_f64().unwrap();
    assert!((roughness - (2.0f64 / 64.0).powf(0.25)).abs() < 1e-6, "{roughness}");
    assert!(painted.get("alphaMode").is_none());
    // The texture: one image, embedded, the PNG's own bytes; normal map the same image.
    let texture = pbr["baseColorTexture"]["index"].as_u64().unwrap() as usize;
    assert_eq!(painted["normalTexture"]["index"].as_u64().unwrap() as usize, texture);
    let image = &json["images"][json["textures"][texture]["source"].as_u64().unwrap() as usize];
    assert_eq!(image["mimeType"], "image/png");
    let view = &json["bufferViews"][image["bufferView"].as_u64().unwrap() as usize];
    let start = view["byteOffset"].as_u64().unwrap_or(0) as usize;
    assert_eq!(&bin[start..start + view["byteLength"].as_u64().unwrap() as usize], &PNG[..]);
    let glass = by_name("glass");
    let color: Vec<f64> =
        glass["pbrMetallicRoughness"]["baseColorFactor"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    assert_eq!(color, [0.0, 0.0, 1.0, 0.25]);
    assert_eq!(glass["alphaMode"], "BLEND");
    assert!(glass["pbrMetallicRoughness"].get("baseColorTexture").is_none());
    // Each primitive names its material and was stripped.
    for p in json["meshes"][0]["primitives"].as_array().unwrap() {
        assert_eq!(p["mode"], 5);
        assert!(p["attributes"].get("TEXCOORD_0").is_some());
    }
    let gltf = dir.join("painted.gltf");
    let out = stripkit(&["strip", obj.to_str().unwrap(), "-o", gltf.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text: Value = serde_json::from_slice(&std::fs::read(&gltf).unwrap()).unwrap();
    assert_eq!(text["images"].as_array().unwrap().len(), 1);
    gltf_validator::validate(&[&glb, &gltf]);
}

#[test]
fn an_mtllib_outside_the_obj_folder_is_refused() {
    let obj = tmp("mtl-out", "escape.obj");
    std::fs::write(&obj, OBJ.replace("mtllib m.mtl", "mtllib ../escape.mtl")).unwrap();
    let outside = obj.parent().unwrap().parent().unwrap().join("escape.mtl");
    std::fs::write(&outside, MTL).unwrap();
    let glb = obj.with_extension("glb");
    let out = stripkit(&["strip", obj.to_str().unwrap(), "-o", glb.to_str().unwrap()]);
    let _ = std::fs::remove_file(&outside);
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("must be a relative path inside the OBJ's folder"), "{err}");
    assert!(!glb.exists());
}

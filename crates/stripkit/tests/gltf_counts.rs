//! Issue #30, class 1: every accessor a glTF primitive uses (attributes, skin
//! JOINTS / WEIGHTS, morph targets) has as many elements as POSITION, checked when the
//! scene is read, before anything is gathered by vertex id. A morph target of 2
//! elements under 4 positions panicked in the vertex reordering of `Scene::to_bytes`
//! (a slice out of range); it is a format error naming the accessor and both counts.

use serde_json::{json, Value};
use std::path::PathBuf;
use stripkit::io::Format;
use stripkit::scene::{Scene, SceneOptions};
use stripkit::{Error, StripOptions};

/// A GLB of `json` (asset and buffers set here) over the binary chunk `bin`.
fn glb(mut json: Value, bin: &[u8]) -> Vec<u8> {
    json["asset"] = json!({"version": "2.0"});
    json["buffers"] = json!([{"byteLength": bin.len()}]);
    stripkit_testkit::glb(&json, bin)
}

/// A quad of 4 positions (2 triangles, indexed), with `extra` merged into its
/// primitive; accessor 2 is a VEC3 FLOAT of `short` elements (over the positions'
/// bytes), accessor 3 a VEC4 UNSIGNED_BYTE of `short` elements, for `extra` to use.
fn quad(extra: Value, short: usize) -> Vec<u8> {
    let mut bin: Vec<u8> = [[0f32, 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]]
        .iter()
        .flatten()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    bin.extend([0u16, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes()));
    bin.extend([0u8; 16]);
    let mut prim = json!({"attributes": {"POSITION": 0}, "indices": 1});
    for (k, v) in extra.as_object().unwrap() {
        prim[k] = v.clone();
    }
    glb(
        json!({
            "bufferViews": [
                {"buffer": 0, "byteLength": 48},
                {"buffer": 0, "byteOffset": 48, "byteLength": 12},
                {"buffer": 0, "byteOffset": 60, "byteLength": 16},
            ],
            "accessors": [
                {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
                {"bufferView": 0, "componentType": 5126, "count": short, "type": "VEC3"},
                {"bufferView": 2, "componentType": 5121, "count": short, "type": "VEC4"},
            ],
            "meshes": [{"primitives": [prim]}],
            "nodes": [{"mesh": 0}],
            "scenes": [{"nodes": [0]}],
        }),
        &bin,
    )
}

fn write(name: &str, bytes: &[u8]) -> PathBuf {
    let dir = stripkit_testkit::scratch_dir("gltf-counts");
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// Reads, strips (first-use reordering on) and writes `path`: the whole scene path.
fn round_trip(path: &PathBuf) -> stripkit::Result<Vec<u8>> {
    let mut scene = Scene::read(path)?;
    scene.strip(&StripOptions::default(), &SceneOptions::default())?;
    scene.to_bytes(Format::Glb)
}

/// The format error's message, which must name the file.
fn refused(path: &PathBuf) -> String {
    match round_trip(path) {
        Err(e @ Error::Format { .. }) => {
            let msg = e.to_string();
            assert!(msg.contains(&path.display().to_string()), "{msg}");
            msg
        }
        other => panic!("a format error expected, got {:?}", other.map(|b| b.len())),
    }
}

#[test]
fn a_morph_target_shorter_than_position_is_refused_not_a_panic() {
    let path = write("short-target.glb", &quad(json!({"targets": [{"POSITION": 2}]}), 2));
    let msg = refused(&path);
    assert!(msg.contains("accessors[2]") && msg.contains("2 values") && msg.contains("POSITION has 4"), "{msg}");
    assert!(msg.contains("meshes[0].primitives[0]") && msg.contains("morph target 0"), "{msg}");
}

#[test]
fn a_morph_target_longer_than_position_or_missing_is_refused() {
    let path = write("long-target.glb", &quad(json!({"targets": [{}, {"NORMAL": 2}]}), 3));
    assert!(refused(&path).contains("morph target 1 attribute NORMAL (accessors[2]) has 3 values"));
    let path = write("missing-target.glb", &quad(json!({"targets": [{"POSITION": 9}]}), 4));
    assert!(refused(&path).contains("refers to accessors[9] but the file has 4"));
    let path = write("not-an-object.glb", &quad(json!({"targets": [7]}), 4));
    assert!(refused(&path).contains("targets[0] must be an object"));
}

#[test]
fn skin_attributes_shorter_than_position_are_refused() {
    let skin = json!({"attributes": {"POSITION": 0, "JOINTS_0": 3, "WEIGHTS_0": 2}});
    let path = write("short-skin.glb", &quad(skin, 2));
    let msg = refused(&path);
    assert!(msg.contains("has 2 values but POSITION has 4"), "{msg}");
}

#[test]
fn targets_and_skins_of_the_right_count_still_strip() {
    let good = json!({"attributes": {"POSITION": 0, "JOINTS_0": 3}, "targets": [{"POSITION": 2}]});
    let path = write("good.glb", &quad(good, 4));
    let bytes = round_trip(&path).unwrap();
    let back = Scene::from_bytes(&path, Format::Glb, &bytes, &Default::default()).unwrap();
    assert_eq!(back.primitives()[0].mode, 5);
    assert_eq!(back.primitives()[0].mesh.triangle_count(), 2);
}

/// Issue #30, class 2: `n` one-triangle primitives over the same 3 positions and 3
/// indices (44 buffer bytes): each costs the scene memory its data does not show.
fn shared_triangles(n: usize) -> Vec<u8> {
    let mut bin: Vec<u8> = [0f32, 0., 0., 1., 0., 0., 0., 1., 0.].iter().flat_map(|x| x.to_le_bytes()).collect();
    bin.extend([0u16, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    glb(
        json!({
            "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
            "accessors": [
                {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
            ],
            "meshes": [{"primitives": vec![json!({"attributes": {"POSITION": 0}, "indices": 1}); n]}],
        }),
        &bin,
    )
}

#[test]
fn each_triangle_primitive_is_charged_to_the_decoded_bytes_budget() {
    use stripkit::io::ReadOptions;
    let name = std::path::Path::new("many.glb");
    let read = |n: usize, options: &ReadOptions| Scene::from_bytes(name, Format::Glb, &shared_triangles(n), options);
    // The default grants 4,096 primitives beyond the buffer-sized budget.
    assert_eq!(read(4000, &ReadOptions::default()).unwrap().primitives().len(), 4000);
    let msg = read(20_000, &ReadOptions::default()).unwrap_err().to_string();
    assert!(msg.contains("many.glb") && msg.contains("triangle primitive") && msg.contains("--max-memory"), "{msg}");
    assert!(msg.contains("more for the first primitives of a scene"), "{msg}");
    // An explicit limit counts them too: 10 primitives hold more than 100 KB.
    let small = ReadOptions::default().max_decoded_bytes(Some(100_000));
    let msg = read(10, &small).unwrap_err().to_string();
    assert!(msg.contains("primitives[6]") && msg.contains("the limit of 100000 bytes"), "{msg}");
    assert_eq!(read(5, &small).unwrap().primitives().len(), 5);
    // Raised, as the message says, the 20,000 primitives strip and write.
    let mut scene = read(20_000, &ReadOptions::default().max_decoded_bytes(Some(1 << 30))).unwrap();
    scene.strip(&StripOptions::default(), &SceneOptions::default()).unwrap();
    let back = scene.to_bytes(Format::Glb).unwrap();
    assert!(!back.is_empty());
}

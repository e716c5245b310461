//! Seed scenes for the `scene` target: small grids with normals, texture
//! coordinates, a skin (JOINTS_0 / WEIGHTS_0 and a skin of two joints), morph targets,
//! triangle strips and fans, unindexed primitives, as GLB and as glTF with a `data:`
//! buffer; and the defects issue #30 fixed (a morph target or skin attribute shorter
//! than POSITION), which the replay keeps under `fuzz/regressions/scene/`.

use serde_json::{json, Value};

/// A GLB of `json` (asset and the one buffer set here) over the binary chunk `bin`.
pub fn glb(mut json: Value, bin: &[u8]) -> Vec<u8> {
    json["asset"] = json!({"version": "2.0"});
    json["buffers"] = json!([{"byteLength": bin.len()}]);
    let mut j = serde_json::to_vec(&json).expect("JSON");
    j.resize(j.len().next_multiple_of(4), b' ');
    let mut b = bin.to_vec();
    b.resize(b.len().next_multiple_of(4), 0);
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend(((28 + j.len() + b.len()) as u32).to_le_bytes());
    out.extend((j.len() as u32).to_le_bytes());
    out.extend(0x4E4F_534Au32.to_le_bytes());
    out.extend(&j);
    out.extend((b.len() as u32).to_le_bytes());
    out.extend(0x004E_4942u32.to_le_bytes());
    out.extend(&b);
    out
}

/// The same document as a `.gltf`: the buffer a base64 `data:` URI.
pub fn gltf(mut json: Value, bin: &[u8]) -> Vec<u8> {
    json["asset"] = json!({"version": "2.0"});
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        stripkit_testkit::encode_base64(bin)
    );
    json["buffers"] = json!([{"byteLength": bin.len(), "uri": uri}]);
    serde_json::to_vec_pretty(&json).expect("JSON")
}

/// A buffer under construction: each `push` appends a 4-byte aligned view and its
/// accessor and returns the accessor's index.
#[derive(Default)]
struct Doc {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Doc {
    fn push(
        &mut self,
        bytes: Vec<u8>,
        component: u32,
        kind: &str,
        count: usize,
        extra: Value,
    ) -> usize {
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        self.views
            .push(json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()}));
        self.bin.extend(bytes);
        let mut a = json!({"bufferView": self.views.len() - 1, "componentType": component, "count": count, "type": kind});
        for (k, v) in extra.as_object().into_iter().flatten() {
            a[k] = v.clone();
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }
    fn floats(&mut self, v: &[f32], kind: &str, per: usize, minmax: bool) -> usize {
        let count = v.len() / per;
        let extra = if minmax {
            let min: Vec<f32> = (0..per)
                .map(|c| {
                    v.iter()
                        .skip(c)
                        .step_by(per)
                        .copied()
                        .fold(f32::MAX, f32::min)
                })
                .collect();
            let max: Vec<f32> = (0..per)
                .map(|c| {
                    v.iter()
                        .skip(c)
                        .step_by(per)
                        .copied()
                        .fold(f32::MIN, f32::max)
                })
                .collect();
            json!({"min": min, "max": max})
        } else {
            json!({})
        };
        self.push(
            v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            5126,
            kind,
            count,
            extra,
        )
    }
}

/// Options of one seed scene.
#[derive(Clone, Copy)]
struct Shape {
    n: usize,
    mode: u8,
    indexed: bool,
    skin: bool,
    targets: usize,
    primitives: usize,
}

/// One scene of `shape.primitives` primitives, each an n-by-n grid of squares (as
/// triangles, a strip per row, or fans), with its attributes and targets.
fn scene(shape: Shape) -> (Value, Vec<u8>) {
    let n = shape.n;
    let side = n + 1;
    let mut d = Doc::default();
    let mut pos = Vec::new();
    let mut nrm = Vec::new();
    let mut uv = Vec::new();
    for y in 0..side {
        for x in 0..side {
            let (fx, fy) = (x as f32 / n as f32, y as f32 / n as f32);
            pos.extend([fx, fy, 0.25 * (fx * 3.0).sin() * fy]);
            nrm.extend([0.0, 0.0, 1.0]);
            uv.extend([fx, fy]);
        }
    }
    let id = |x: usize, y: usize| (y * side + x) as u16;
    let mut idx: Vec<u16> = Vec::new();
    match shape.mode {
        5 => {
            // One strip over the first row.
            for x in 0..side {
                idx.extend([id(x, 0), id(x, 1)]);
            }
        }
        6 => {
            // A fan around the first vertex of the first row's squares.
            idx.push(id(0, 0));
            for x in (1..side).rev() {
                idx.push(id(x, 0));
            }
            idx.extend([id(n, 1), id(0, 1)]);
        }
        _ => {
            for y in 0..n {
                for x in 0..n {
                    idx.extend([
                        id(x, y),
                        id(x + 1, y),
                        id(x + 1, y + 1),
                        id(x, y),
                        id(x + 1, y + 1),
                        id(x, y + 1),
                    ]);
                }
            }
        }
    }
    let (pos, nrm, uv) = if shape.indexed {
        (pos, nrm, uv)
    } else {
        let gather = |v: &[f32], per: usize| {
            idx.iter()
                .flat_map(|&i| v[i as usize * per..][..per].to_vec())
                .collect::<Vec<f32>>()
        };
        (gather(&pos, 3), gather(&nrm, 3), gather(&uv, 2))
    };
    let count = pos.len() / 3;
    let p = d.floats(&pos, "VEC3", 3, true);
    let nm = d.floats(&nrm, "VEC3", 3, false);
    let t = d.floats(&uv, "VEC2", 2, false);
    let mut attributes = json!({"POSITION": p, "NORMAL": nm, "TEXCOORD_0": t});
    if shape.skin {
        let joints: Vec<u8> = (0..count).flat_map(|i| [0, 1, (i % 2) as u8, 0]).collect();
        let weights: Vec<f32> = (0..count)
            .flat_map(|i| [0.75, 0.25 * (i % 2) as f32, 0.25 * (1 - i % 2) as f32, 0.0])
            .collect();
        attributes["JOINTS_0"] = json!(d.push(joints, 5121, "VEC4", count, json!({})));
        attributes["WEIGHTS_0"] = json!(d.floats(&weights, "VEC4", 4, false));
    }
    let mut targets = Vec::new();
    for k in 0..shape.targets {
        let dz: Vec<f32> = (0..count)
            .flat_map(|i| [0.0, 0.0, 0.1 * (k + 1) as f32 * (i % 3) as f32])
            .collect();
        let mut target = json!({"POSITION": d.floats(&dz, "VEC3", 3, true)});
        if k % 2 == 1 {
            target["NORMAL"] = json!(d.floats(&vec![0.0; count * 3], "VEC3", 3, false));
        }
        targets.push(target);
    }
    let indices = shape.indexed.then(|| {
        d.push(
            idx.iter().flat_map(|i| i.to_le_bytes()).collect(),
            5123,
            "SCALAR",
            idx.len(),
            json!({}),
        )
    });
    let mut prims = Vec::new();
    for m in 0..shape.primitives {
        let mut prim = json!({"attributes": attributes, "mode": shape.mode, "material": m % 2});
        if let Some(i) = indices {
            prim["indices"] = json!(i);
        }
        if !targets.is_empty() {
            prim["targets"] = json!(targets);
        }
        prims.push(prim);
    }
    let mut mesh = json!({"name": "grid", "primitives": prims});
    if !targets.is_empty() {
        mesh["weights"] = json!(vec![0.5; targets.len()]);
    }
    let mut json = json!({
        "scene": 0,
        "materials": [{"name": "a"}, {"name": "b", "doubleSided": true}],
        "meshes": [mesh],
    });
    if shape.skin {
        let ibm: Vec<f32> = (0..2)
            .flat_map(|j| {
                let mut m = [0.0f32; 16];
                m[0] = 1.0;
                m[5] = 1.0;
                m[10] = 1.0;
                m[15] = 1.0;
                m[13] = -(j as f32);
                m
            })
            .collect();
        let inverse = d.floats(&ibm, "MAT4", 16, false);
        json["skins"] = json!([{"joints": [1, 2], "inverseBindMatrices": inverse, "skeleton": 1}]);
        json["nodes"] =
            json!([{"mesh": 0, "skin": 0}, {"children": [2]}, {"translation": [0, 1, 0]}]);
        json["scenes"] = json!([{"nodes": [0, 1]}]);
        json["animations"] = json!([]);
    } else {
        json["nodes"] = json!([{"mesh": 0}]);
        json["scenes"] = json!([{"nodes": [0]}]);
    }
    json["bufferViews"] = json!(d.views);
    json["accessors"] = json!(d.accessors);
    (json, d.bin)
}

/// The first seed shape: a 2-by-2 grid with a skin and two morph targets.
const BASE: Shape = Shape {
    n: 2,
    mode: 4,
    indexed: true,
    skin: true,
    targets: 2,
    primitives: 1,
};

/// The first seed, `skin_morph.glb`: a 2-by-2 grid (9 vertices, 8 triangles) with
/// normals, texture coordinates, a skin of two joints and two morph targets.
pub fn skin_morph_glb() -> Vec<u8> {
    let (json, bin) = scene(BASE);
    glb(json, &bin)
}

/// The seed scenes, named: each shape as GLB and as glTF.
pub fn scenes() -> Vec<(String, Vec<u8>)> {
    let base = BASE;
    let shapes = [
        ("skin_morph", base),
        ("skin", Shape { targets: 0, ..base }),
        (
            "morph3",
            Shape {
                skin: false,
                targets: 3,
                n: 3,
                ..base
            },
        ),
        (
            "plain",
            Shape {
                skin: false,
                targets: 0,
                ..base
            },
        ),
        ("strip", Shape { mode: 5, ..base }),
        (
            "fan",
            Shape {
                mode: 6,
                targets: 1,
                ..base
            },
        ),
        (
            "unindexed",
            Shape {
                indexed: false,
                ..base
            },
        ),
        (
            "two_prims",
            Shape {
                primitives: 2,
                targets: 1,
                ..base
            },
        ),
    ];
    let mut out = Vec::new();
    for (name, shape) in shapes {
        let (json, bin) = scene(shape);
        out.push((format!("{name}.glb"), glb(json.clone(), &bin)));
        out.push((format!("{name}.gltf"), gltf(json, &bin)));
    }
    out.extend(defects());
    out
}

/// The scene defects of issue #30, as tiny GLBs: a morph target of 2 elements under 4
/// positions (a panic in the vertex reordering before the fix), a morph NORMAL of 3,
/// and skin JOINTS_0 / WEIGHTS_0 of 2. Each must be refused as a format error.
pub fn defects() -> Vec<(String, Vec<u8>)> {
    let quad = |extra: Value, short: usize| {
        let mut d = Doc::default();
        let p = d.floats(
            &[0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.],
            "VEC3",
            3,
            true,
        );
        let i = d.push(
            [0u16, 1, 2, 0, 2, 3]
                .iter()
                .flat_map(|i| i.to_le_bytes())
                .collect(),
            5123,
            "SCALAR",
            6,
            json!({}),
        );
        let s = d.floats(&vec![0.5; short * 3], "VEC3", 3, false);
        let j = d.push(vec![0u8; short * 4], 5121, "VEC4", short, json!({}));
        assert_eq!((p, i, s, j), (0, 1, 2, 3));
        let mut prim = json!({"attributes": {"POSITION": 0}, "indices": 1});
        for (k, v) in extra.as_object().into_iter().flatten() {
            prim[k] = v.clone();
        }
        let json = json!({
            "bufferViews": d.views, "accessors": d.accessors,
            "meshes": [{"primitives": [prim]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}],
        });
        glb(json, &d.bin)
    };
    vec![
        (
            "defect_short_morph_target.glb".into(),
            quad(json!({"targets": [{"POSITION": 2}]}), 2),
        ),
        (
            "defect_long_morph_normal.glb".into(),
            quad(json!({"targets": [{}, {"NORMAL": 2}]}), 3),
        ),
        (
            "defect_short_skin.glb".into(),
            quad(
                json!({"attributes": {"POSITION": 0, "JOINTS_0": 3, "WEIGHTS_0": 2}}),
                2,
            ),
        ),
    ]
}

//! Vertex attributes through the collapse sequence, the SETS model, the `.sets` and
//! `.lodseq` files and `lod extract` (issue #31, item 1): a UV'd torus whose texture
//! wraps around both ways (a seam of twin vertices along two loops), faces shuffled,
//! checked corner by corner at several levels; files without attributes keep the
//! version-1 layout, byte for byte.

mod support;

use std::collections::HashMap;
use std::path::PathBuf;
use stripkit::lod::{self, BuildOptions, LevelSpec, LodSeq, Model, Sets};
use stripkit::simplify::{simplify, Options, Placement, Target};
use stripkit::{Attribute, Mesh};
use stripkit_testkit::XorShift64;

const RINGS: u32 = 24;
const SIDES: u32 = 12;

/// A torus with `TEXCOORD_0` (u around the ring, v around the tube; the last column and
/// row are twins of the first at u = 1 / v = 1: the UV seams) and `NORMAL`, its faces
/// shuffled. Vertex `(i, j)` is `j * (RINGS + 1) + i`.
fn seamed_torus() -> Mesh {
    let (big, small) = (1.0f64, 0.35f64);
    let mut positions = Vec::new();
    let (mut uv, mut normal) = (Vec::new(), Vec::new());
    for j in 0..=SIDES {
        for i in 0..=RINGS {
            // The twins take the first column's / row's angle exactly (same position).
            let a = (i % RINGS) as f64 / RINGS as f64 * std::f64::consts::TAU;
            let b = (j % SIDES) as f64 / SIDES as f64 * std::f64::consts::TAU;
            let r = big + small * b.cos() * (1.0 + 0.2 * (3.0 * a).sin());
            positions.push([
                (r * a.cos()) as f32,
                (r * a.sin()) as f32,
                (small * b.sin()) as f32,
            ]);
            uv.extend([i as f32 / RINGS as f32, j as f32 / SIDES as f32]);
            normal.extend([
                (b.cos() * a.cos()) as f32,
                (b.cos() * a.sin()) as f32,
                b.sin() as f32,
            ]);
        }
    }
    let id = |i: u32, j: u32| j * (RINGS + 1) + i;
    let mut tris = Vec::new();
    for j in 0..SIDES {
        for i in 0..RINGS {
            tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    XorShift64(0x9e37_79b9_7f4a_7c15).shuffle(&mut tris);
    let mut mesh = Mesh::from_triangles(positions, &tris);
    mesh.attributes
        .push(Attribute::from_f32("TEXCOORD_0", 2, &uv));
    mesh.attributes
        .push(Attribute::from_f32("NORMAL", 3, &normal));
    mesh
}

fn scratch(name: &str) -> PathBuf {
    stripkit_testkit::fresh_scratch_dir(&format!("lod-attributes-{name}"))
}

/// Every corner of `triangles` (over `attributes`) carries, attribute by attribute,
/// the bytes of the source vertex it names (`source[v]` for model vertex `v`).
fn corners_match(
    triangles: &[[u32; 3]],
    attributes: &[Attribute],
    mesh: &Mesh,
    source: impl Fn(u32) -> u32,
) {
    assert_eq!(attributes.len(), mesh.attributes.len());
    for (a, b) in attributes.iter().zip(&mesh.attributes) {
        assert_eq!(
            (&a.name, a.scalar, a.components),
            (&b.name, b.scalar, b.components)
        );
        for (t, tri) in triangles.iter().enumerate() {
            for &v in tri {
                assert_eq!(
                    a.bytes(v as usize),
                    b.bytes(source(v) as usize),
                    "{} of triangle {t}, vertex {v}",
                    a.name
                );
            }
        }
    }
}

/// Seams stay seams: no triangle spans the texture's wrap (a corner from the other
/// side of a seam would put u or v about 1 apart within one triangle).
fn no_triangle_crosses_a_seam(triangles: &[[u32; 3]], uv: &Attribute) {
    for t in triangles {
        for c in 0..2 {
            let values = t.map(|v| uv.get(v as usize, c));
            let span = values.iter().fold(f64::MIN, |m, &x| m.max(x))
                - values.iter().fold(f64::MAX, |m, &x| m.min(x));
            assert!(
                span < 0.5,
                "triangle {t:?} spans {span} in uv component {c}"
            );
        }
    }
}

/// The triangles as multisets of their corners' values (position bits, then every
/// attribute's bytes, attributes by name), in canonical rotation: what a file holds,
/// whatever its ids and attribute order.
fn corner_values(
    triangles: &[[u32; 3]],
    positions: &[[f32; 3]],
    attributes: &[Attribute],
) -> Vec<Vec<Vec<u8>>> {
    corners(triangles, positions, attributes, None)
}

/// [`corner_values`] with every value rounded to `1 / scale` first: for OBJ and PLY,
/// whose writers store V as `1 - v` (a rounding step each way).
fn corners(
    triangles: &[[u32; 3]],
    positions: &[[f32; 3]],
    attributes: &[Attribute],
    scale: Option<f64>,
) -> Vec<Vec<Vec<u8>>> {
    let mut sorted: Vec<&Attribute> = attributes.iter().collect();
    sorted.sort_by(|a, b| a.name.cmp(&b.name));
    let put = |bytes: &mut Vec<u8>, x: f64, exact: &[u8]| match scale {
        Some(s) => bytes.extend_from_slice(&((x * s).round() as i64).to_le_bytes()),
        None => bytes.extend_from_slice(exact),
    };
    let corner = |v: u32| {
        let mut bytes = Vec::new();
        for x in positions[v as usize] {
            put(&mut bytes, x as f64, &x.to_le_bytes());
        }
        for a in &sorted {
            let size = a.scalar.size();
            for c in 0..a.components as usize {
                put(
                    &mut bytes,
                    a.get(v as usize, c),
                    &a.bytes(v as usize)[c * size..(c + 1) * size],
                );
            }
        }
        bytes
    };
    let mut out: Vec<Vec<Vec<u8>>> = triangles
        .iter()
        .map(|t| {
            let c = t.map(corner);
            let m = (0..3).min_by(|&a, &b| c[a].cmp(&c[b])).unwrap();
            vec![c[m].clone(), c[(m + 1) % 3].clone(), c[(m + 2) % 3].clone()]
        })
        .collect();
    out.sort();
    out
}

/// Two sorted lists of triangle corner values are equal; else names the first
/// difference (not the whole lists).
fn same_corners(got: Vec<Vec<Vec<u8>>>, want: Vec<Vec<Vec<u8>>>, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: triangles");
    if let Some(i) = (0..got.len()).find(|&i| got[i] != want[i]) {
        panic!(
            "{what}: triangle {i} of {} differs: {:?} instead of {:?}",
            got.len(),
            got[i],
            want[i]
        );
    }
}

#[test]
fn replay_carries_every_attribute_and_keeps_seams() {
    let mesh = seamed_torus();
    for placement in [Placement::Endpoint, Placement::Optimal] {
        let options = Options::default()
            .target(Target::Ratio(0.2))
            .placement(placement);
        let s = simplify(&mesh, &options, &mut |_| {}).unwrap();
        assert!(s.sequence.len() > 200, "{} collapses", s.sequence.len());
        // The whole sequence rebuilds the simplifier's mesh, attributes bit for bit.
        let last = s.sequence.replay(&mesh, s.sequence.len()).unwrap();
        assert_eq!(last.attributes, s.mesh.attributes, "{placement:?}");
        assert!(last.to_mesh() == s.mesh, "{placement:?}");
        for k in [
            0,
            1,
            s.sequence.len() / 3,
            s.sequence.len() / 2,
            s.sequence.len(),
        ] {
            let r = s.sequence.replay(&mesh, k).unwrap();
            no_triangle_crosses_a_seam(&r.triangles, &r.attributes[0]);
            if placement == Placement::Endpoint {
                // Half-edge collapses keep every survivor's own values.
                corners_match(&r.triangles, &r.attributes, &mesh, |v| v);
            }
        }
        // The twins of the seams are never removed.
        let mut at: HashMap<[u32; 3], u32> = HashMap::new();
        for p in &mesh.positions {
            *at.entry(p.map(f32::to_bits)).or_default() += 1;
        }
        for c in &s.sequence.collapses {
            assert_eq!(
                at[&mesh.positions[c.removed as usize].map(f32::to_bits)],
                1,
                "{placement:?}: {c:?}"
            );
        }
    }
}

#[test]
fn sets_levels_and_files_carry_every_attribute() {
    let dir = scratch("sets");
    let mesh = seamed_torus();
    for placement in [Placement::Endpoint, Placement::Optimal] {
        let built = lod::build(
            &mesh,
            // The kept strips: a version-2 file (version 3 adds re-strip levels).
            &BuildOptions::default().placement(placement).restrip(None),
            &mut |_| {},
        )
        .unwrap();
        // Every level against the replay, attributes byte for byte.
        built.check(None).unwrap();
        let sets = &built.sets;
        assert_eq!(sets.attributes().len(), 2);
        let path = dir.join(format!("{placement:?}.sets"));
        sets.write(&path).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(
            &bytes[8..12],
            &2u32.to_le_bytes(),
            "a file with attributes is version 2"
        );
        let model = Model::read(&path).unwrap();
        assert!(matches!(&model, Model::Sets(back) if back == sets));
        let levels = sets.levels();
        for level in [0, 1, levels / 4, levels / 2, 3 * levels / 4] {
            let x = model.extract(LevelSpec::Level(level), None).unwrap();
            let triangles = x.checked_triangles().unwrap();
            let replay = built.sequence.replay(&built.mesh, level as usize).unwrap();
            no_triangle_crosses_a_seam(&triangles, &x.attributes[0]);
            if placement == Placement::Endpoint {
                corners_match(&triangles, &x.attributes, &mesh, |v| v);
            }
            // Corner values equal the replay's (optimal: the blended new vertices).
            same_corners(
                corner_values(&triangles, &x.positions, &x.attributes),
                corner_values(&replay.triangles, &replay.positions, &replay.attributes),
                &format!("{placement:?} level {level}"),
            );
            // The extracted file: only the level's vertices, every corner's values.
            for ext in ["glb", "gltf", "ply", "obj"] {
                let out = dir.join(format!("{placement:?}-{level}.{ext}"));
                x.write_file(&out, &Default::default()).unwrap();
                let back = read_back(&out);
                let used = triangles
                    .iter()
                    .flatten()
                    .collect::<std::collections::HashSet<_>>()
                    .len();
                assert_eq!(
                    back.positions.len(),
                    used,
                    "{ext}: only the level's vertices"
                );
                let keep: Vec<Attribute> = x
                    .attributes
                    .iter()
                    .filter(|a| back.attribute(&a.name).is_some())
                    .cloned()
                    .collect();
                let back_attributes: Vec<Attribute> = keep
                    .iter()
                    .map(|a| back.attribute(&a.name).unwrap().clone())
                    .collect();
                if ext != "ply" {
                    assert_eq!(keep.len(), 2, "{ext} keeps both attributes");
                }
                // glTF keeps every bit; OBJ and PLY store V as 1 - v.
                let scale = if ext == "glb" || ext == "gltf" {
                    None
                } else {
                    Some(1e5)
                };
                same_corners(
                    corners(
                        &back.triangulate().tris,
                        &back.positions,
                        &back_attributes,
                        scale,
                    ),
                    corners(&triangles, &x.positions, &keep, scale),
                    &format!(
                        "{ext}, level {level}, attributes {:?}",
                        back.attributes
                            .iter()
                            .map(|a| (&a.name, a.scalar))
                            .collect::<Vec<_>>()
                    ),
                );
                if ext == "glb" || ext == "gltf" {
                    support::gltf_validator::validate(&[&out]);
                }
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The glTF output names its vertices in the order the strip first uses them.
#[test]
fn extracted_gltf_vertices_come_in_first_use_order() {
    let dir = scratch("order");
    let built = lod::build(&seamed_torus(), &BuildOptions::default(), &mut |_| {}).unwrap();
    let x = Model::Sets(built.sets)
        .extract(LevelSpec::Ratio(0.25), None)
        .unwrap();
    let out = dir.join("level.glb");
    x.write_file(&out, &Default::default()).unwrap();
    let (json, bin) = glb_chunks(&std::fs::read(&out).unwrap());
    let primitive = &json["meshes"][0]["primitives"][0];
    assert_eq!(primitive["mode"], 5, "one stitched TRIANGLE_STRIP");
    let indices = accessor_u32(&json, &bin, primitive["indices"].as_u64().unwrap() as usize);
    let mut next = 0;
    for &i in &indices {
        assert!(i <= next, "index {i} before {next}");
        next = next.max(i + 1);
    }
    for semantic in ["POSITION", "TEXCOORD_0", "NORMAL"] {
        let a = primitive["attributes"][semantic].as_u64().unwrap() as usize;
        assert_eq!(
            json["accessors"][a]["count"].as_u64().unwrap() as u32,
            next,
            "{semantic}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A written file as a mesh with its attributes: glTF through its scene (the mesh
/// reader takes glTF positions only), the one primitive's mesh.
fn read_back(path: &std::path::Path) -> Mesh {
    let name = path.to_string_lossy();
    if name.ends_with(".glb") || name.ends_with(".gltf") {
        let scene = stripkit::io::Scene::read(path).unwrap();
        assert_eq!(scene.primitives().len(), 1);
        return scene.primitives()[0].mesh.clone();
    }
    stripkit::io::read(path).unwrap()
}

/// The JSON and binary chunks of a `.glb`.
fn glb_chunks(bytes: &[u8]) -> (serde_json::Value, Vec<u8>) {
    let u32_at = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
    let json_len = u32_at(12);
    let json = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    let bin_at = 20 + json_len;
    let bin_len = u32_at(bin_at);
    (json, bytes[bin_at + 8..bin_at + 8 + bin_len].to_vec())
}

/// The values of a scalar unsigned index accessor.
fn accessor_u32(json: &serde_json::Value, bin: &[u8], accessor: usize) -> Vec<u32> {
    let a = &json["accessors"][accessor];
    let view = &json["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
    let at = view["byteOffset"].as_u64().unwrap_or(0) as usize
        + a["byteOffset"].as_u64().unwrap_or(0) as usize;
    let count = a["count"].as_u64().unwrap() as usize;
    (0..count)
        .map(|i| match a["componentType"].as_u64().unwrap() {
            5121 => bin[at + i] as u32,
            5123 => u16::from_le_bytes([bin[at + 2 * i], bin[at + 2 * i + 1]]) as u32,
            _ => u32::from_le_bytes(bin[at + 4 * i..at + 4 * i + 4].try_into().unwrap()),
        })
        .collect()
}

#[test]
fn lodseq_carries_the_first_frames_attributes() {
    let dir = scratch("seq");
    let mesh = seamed_torus();
    let frame = |t: f32| -> Vec<[f32; 3]> {
        mesh.positions
            .iter()
            .map(|p| [p[0] * (1.0 + 0.3 * t), p[1], p[2]])
            .collect()
    };
    let positions: Vec<Vec<[f32; 3]>> = (0..4).map(|f| frame(f as f32 / 3.0)).collect();
    let frames = lod::Frames {
        names: (0..4).map(|f| format!("f{f}.obj")).collect(),
        mesh: mesh.clone(),
        positions,
        reference: None,
    };
    let built = lod::build_seq(
        &frames,
        &lod::SeqOptions::default().samples(400),
        &mut |_| {},
    )
    .unwrap();
    built.check(Some(16)).unwrap();
    assert_eq!(built.seq.attributes(), &mesh.attributes[..]);
    let path = dir.join("anim.lodseq");
    built.seq.write(&path).unwrap();
    assert_eq!(&std::fs::read(&path).unwrap()[8..12], &2u32.to_le_bytes());
    let back = LodSeq::read(&path).unwrap();
    assert_eq!(back, built.seq);
    let model = Model::Seq(back);
    for f in [0.0, 1.5, 3.0] {
        for ratio in [1.0, 0.4, 0.1] {
            let x = model.extract(LevelSpec::Ratio(ratio), Some(f)).unwrap();
            let triangles = x.checked_triangles().unwrap();
            corners_match(&triangles, &x.attributes, &mesh, |v| v);
            if ratio >= 0.4 {
                // (At 10% a tube's triangles span more than half of it honestly.)
                no_triangle_crosses_a_seam(&triangles, &x.attributes[0]);
            }
            let out = dir.join(format!("f{f}-{ratio}.glb"));
            x.write_file(&out, &Default::default()).unwrap();
            let back = read_back(&out);
            same_corners(
                corner_values(&back.triangulate().tris, &back.positions, &back.attributes),
                corner_values(&triangles, &x.positions, &x.attributes),
                &format!("frame {f}, ratio {ratio}"),
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Models without attributes keep the version-1 layout: a file written before
/// attributes existed (the fixture below, from a two-strip model) still reads, and
/// the writer gives the same bytes back.
#[test]
fn version_one_files_still_read_and_are_still_written() {
    let mesh = stripkit::gen::icosphere(1);
    // The kept strips, without attributes: the version-1 layout.
    let built = lod::build(&mesh, &BuildOptions::default().restrip(None), &mut |_| {}).unwrap();
    assert!(built.sets.attributes().is_empty());
    let bytes = built.sets.to_bytes();
    assert_eq!(&bytes[8..12], &1u32.to_le_bytes());
    let back = Sets::from_bytes(std::path::Path::new("v1.sets"), &bytes).unwrap();
    assert_eq!(back, built.sets);
    let fixture = include_bytes!("lod_attributes/v1.sets");
    let old = Sets::from_bytes(std::path::Path::new("v1.sets"), fixture).unwrap();
    assert!(old.attributes().is_empty());
    assert_eq!(old.to_bytes(), fixture.to_vec());
    let old_seq = include_bytes!("lod_attributes/v1.lodseq");
    let seq = LodSeq::from_bytes(std::path::Path::new("v1.lodseq"), old_seq).unwrap();
    assert!(seq.attributes().is_empty());
    assert_eq!(seq.to_bytes(), old_seq.to_vec());
}

/// A damaged attributes section is refused with the byte it is at, never allocated
/// by its counts.
#[test]
fn attribute_sections_are_checked() {
    // The kept strips: a version-2 file, which a version-3 header does not fit.
    let built = lod::build(&seamed_torus(), &BuildOptions::default().restrip(None), &mut |_| {}).unwrap();
    let good = built.sets.to_bytes();
    let path = std::path::Path::new("bad.sets");
    let reseal = |mut b: Vec<u8>| {
        let n = b.len() - 4;
        let mut crc = flate2::Crc::new();
        crc.update(&b[..n]);
        b[n..].copy_from_slice(&crc.sum().to_le_bytes());
        b
    };
    // The attributes section starts after the 48-byte header and the positions.
    let at = 48 + 12 * built.sets.positions().len();
    let mut huge = good.clone();
    huge[at..at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
    let e = Sets::from_bytes(path, &reseal(huge))
        .unwrap_err()
        .to_string();
    assert!(e.contains("attributes"), "{e}");
    let mut name = good.clone();
    name[at + 4] = 0x7f; // a name longer than the bytes after it
    assert!(Sets::from_bytes(path, &reseal(name)).is_err());
    let mut scalar = good.clone();
    let name_len = good[at + 4] as usize;
    scalar[at + 5 + name_len] = 9;
    let e = Sets::from_bytes(path, &reseal(scalar))
        .unwrap_err()
        .to_string();
    assert!(e.contains("scalar"), "{e}");
    let mut version = good.clone();
    version[8] = 3;
    assert!(Sets::from_bytes(path, &reseal(version)).is_err());
    // Cut inside the values: the file ends before them.
    let short = reseal(good[..at + 40].iter().copied().chain([0; 4]).collect());
    assert!(Sets::from_bytes(path, &short).is_err());
}

/// The shipped spot (UVs with seams, 13 pieces of GPU vertices): every level's files
/// hold its own vertices with their UVs, corner by corner, in every mesh format that
/// keeps UVs.
#[test]
fn spot_levels_keep_their_uvs_in_every_format() {
    let dir = scratch("spot");
    let mesh = stripkit::io::read(support::assets_dir().join("spot.obj")).unwrap();
    assert!(mesh.attribute("TEXCOORD_0").is_some());
    let built = lod::build(&mesh, &BuildOptions::default(), &mut |_| {}).unwrap();
    let model = Model::Sets(built.sets);
    for ratio in [1.0, 0.5, 0.1] {
        let x = model.extract(LevelSpec::Ratio(ratio), None).unwrap();
        let triangles = x.checked_triangles().unwrap();
        corners_match(&triangles, &x.attributes, &built.mesh, |v| v);
        for ext in ["glb", "obj", "ply"] {
            let out = dir.join(format!("spot-{ratio}.{ext}"));
            x.write_file(&out, &Default::default()).unwrap();
            let back = read_back(&out);
            let scale = if ext == "glb" { None } else { Some(1e5) };
            same_corners(
                corners(&back.triangulate().tris, &back.positions, &back.attributes, scale),
                corners(&triangles, &x.positions, &x.attributes, scale),
                &format!("spot {ext} at {ratio}"),
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

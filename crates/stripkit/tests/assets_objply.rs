//! OBJ and PLY assets with attributes and groups (issue #15, items 1 and 3): corners
//! welded into GPU vertices, strips that never cross a seam or a material, and round
//! trips that keep every attribute value at every corner.

mod support;

use std::collections::HashMap;
use std::path::Path;
use stripkit::io::{self, Format, WriteOptions};
use stripkit::{decode, for_each_triangle};
use stripkit::{stripify, Algorithm, Error, Join, Mesh, StripOptions};
use stripkit::{Attribute, Group, Scalar};

use stripkit_testkit::Lcg as Rng;

fn obj(text: &str) -> Mesh {
    io::read_bytes(Path::new("test.obj"), Format::Obj, text.as_bytes()).unwrap()
}

/// A unit cube as OBJ text: 8 positions, every face with its own 4 texture
/// coordinates (24 `vt`) and its own normal, faces (quads) in shuffled order.
fn seamed_cube(rng: &mut Rng) -> String {
    let mut text = String::from("# seamed cube\n");
    for v in 0..8 {
        text += &format!("v {} {} {}\n", v & 1, (v >> 1) & 1, (v >> 2) & 1);
    }
    // Each face counter-clockwise seen from outside, with its outward normal.
    let faces: [([usize; 4], [i32; 3]); 6] = [
        ([0, 2, 3, 1], [0, 0, -1]),
        ([4, 5, 7, 6], [0, 0, 1]),
        ([0, 1, 5, 4], [0, -1, 0]),
        ([2, 6, 7, 3], [0, 1, 0]),
        ([0, 4, 6, 2], [-1, 0, 0]),
        ([1, 3, 7, 5], [1, 0, 0]),
    ];
    for (k, (_, n)) in faces.iter().enumerate() {
        let (cx, cy) = ((k % 3) as f32 / 3.0, (k / 3) as f32 / 2.0);
        for (du, dv) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            text += &format!("vt {} {}\n", cx + du / 3.0, cy + dv / 2.0);
        }
        text += &format!("vn {} {} {}\n", n[0], n[1], n[2]);
    }
    let mut order: Vec<usize> = (0..6).collect();
    rng.shuffle(&mut order);
    for k in order {
        text += "f";
        for (c, &v) in faces[k].0.iter().enumerate() {
            text += &format!(" {}/{}/{}", v + 1, 4 * k + c + 1, k + 1);
        }
        text += "\n";
    }
    text
}

/// The values of every attribute at vertex `v`, with its position: what a corner draws.
fn corner(mesh: &Mesh, v: u32) -> Vec<u64> {
    let mut out: Vec<u64> = mesh.positions[v as usize].iter().map(|c| c.to_bits() as u64).collect();
    let mut attrs: Vec<&Attribute> = mesh.attributes.iter().collect();
    attrs.sort_by(|a, b| a.name.cmp(&b.name));
    for a in attrs {
        out.extend(a.value(v as usize).iter().map(|x| x.to_bits()));
    }
    out
}

/// Every triangle as its corners' values (rotated to start at the least) and its
/// group's (name, material), sorted: what a renderer draws, whatever the vertex ids.
fn drawn(mesh: &Mesh, tris: &[([u32; 3], usize)]) -> Vec<(Vec<Vec<u64>>, Group)> {
    let mut out: Vec<_> = tris
        .iter()
        .map(|&(t, f)| {
            let c: Vec<Vec<u64>> = t.iter().map(|&v| corner(mesh, v)).collect();
            let r = (0..3).min_by(|&a, &b| c[a].cmp(&c[b])).unwrap();
            let rotated = vec![c[r].clone(), c[(r + 1) % 3].clone(), c[(r + 2) % 3].clone()];
            (rotated, mesh.groups.get(mesh.group_of(f) as usize).cloned().unwrap_or_default())
        })
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.name.cmp(&b.1.name)).then(a.1.material.cmp(&b.1.material)));
    out
}

fn fan(mesh: &Mesh) -> Vec<([u32; 3], usize)> {
    let t = mesh.triangulate();
    t.tris.iter().zip(&t.face_of).map(|(&t, &f)| (t, f as usize)).collect()
}

#[test]
fn a_uv_seamed_cube_gives_24_vertices_and_one_strip_per_face() {
    let mut rng = Rng(7);
    for _ in 0..5 {
        let mesh = obj(&seamed_cube(&mut rng));
        assert_eq!((mesh.vertex_count(), mesh.face_count()), (24, 6));
        let normal = mesh.attribute("NORMAL").unwrap();
        for algorithm in [Algorithm::greedy(), Algorithm::cache(), Algorithm::qstrip()] {
            let s = stripify(&mesh, &StripOptions::default().algorithm(algorithm.clone())).unwrap();
            // No two faces share a vertex, so no strip can leave its face: 6 strips,
            // each over vertices of one normal.
            assert_eq!(s.strips.len(), 6, "{algorithm:?}");
            for strip in s.strips.iter() {
                let n0 = normal.value(strip[0] as usize);
                assert!(strip.iter().all(|&v| normal.value(v as usize) == n0), "{algorithm:?}: {strip:?}");
            }
        }
    }
    // The same cube without vt/vn keeps the file's 8 vertices and strips across faces.
    let plain = obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n\
                     f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n");
    assert_eq!(plain.vertex_count(), 8);
    assert!(stripify(&plain, &StripOptions::default()).unwrap().strips.len() < 6);
}

/// A `w` x `h` grid of quads as OBJ text with `vt` per position, the left half in
/// material `red`, the right in `blue`, faces in shuffled order (so the materials
/// alternate in the file).
fn two_materials(w: usize, h: usize, rng: &mut Rng) -> String {
    let mut text = String::from("mtllib grid.mtl\n");
    for y in 0..=h {
        for x in 0..=w {
            text += &format!("v {x} {y} 0\nvt {} {}\n", x as f32 / w as f32, y as f32 / h as f32);
        }
    }
    let mut faces: Vec<(usize, usize)> = (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).collect();
    rng.shuffle(&mut faces);
    let id = |x: usize, y: usize| y * (w + 1) + x + 1;
    for (x, y) in faces {
        let m = if x < w / 2 { "red" } else { "blue" };
        text += &format!("usemtl {m}\n");
        let c = [id(x, y), id(x + 1, y), id(x + 1, y + 1), id(x, y + 1)];
        text += &format!("f {0}/{0} {1}/{1} {2}/{2}\nf {0}/{0} {2}/{2} {3}/{3}\n", c[0], c[1], c[2], c[3]);
    }
    text
}

/// An oriented triangle rotated to start at its least vertex.
fn canonical(t: [u32; 3]) -> [u32; 3] {
    let r = (0..3).min_by_key(|&k| t[k]).unwrap();
    [t[r], t[(r + 1) % 3], t[(r + 2) % 3]]
}

/// For every oriented triangle (rotated to its least vertex) of the mesh, its group.
fn group_by_triangle(mesh: &Mesh) -> HashMap<[u32; 3], u32> {
    fan(mesh).into_iter().map(|(t, f)| (canonical(t), mesh.group_of(f))).collect()
}

#[test]
fn no_strip_crosses_two_materials() {
    let mut rng = Rng(11);
    let mesh = obj(&two_materials(12, 8, &mut rng));
    assert_eq!(mesh.groups.len(), 2);
    assert_eq!(mesh.material_libraries, vec!["grid.mtl"]);
    assert_eq!(mesh.vertex_count(), 13 * 9);
    let group_of = group_by_triangle(&mesh);
    for algorithm in
        support::algorithms().into_iter().filter(|a| !matches!(a, Algorithm::Single(_) | Algorithm::QuadSingle))
    {
        for join in [Join::Restart, Join::Degenerate, Join::Separate] {
            let s = stripify(&mesh, &StripOptions::default().algorithm(algorithm.clone()).join(join)).unwrap();
            assert_eq!(s.group_ranges.len(), 2);
            for (i, strip) in s.strips.iter().enumerate() {
                let mut groups = Vec::new();
                for_each_triangle(strip, |t| groups.push(group_of[&canonical(t)]));
                groups.dedup();
                assert_eq!(groups.len(), 1, "{algorithm:?}: strip {i} crosses materials: {groups:?}");
                assert_eq!(groups[0] as usize, s.group_of_strip(i));
            }
            for g in 0..2 {
                let buffer = s.restart_buffer_of(g);
                let tris = stripkit::unstripify(&buffer, s.restart_index);
                assert_eq!(tris.len(), 3 * 96, "group {g}");
                assert!(tris.chunks(3).all(|t| group_of[&canonical([t[0], t[1], t[2]])] == g as u32));
                let stitched = s.stitched_of(g);
                assert!(decode(&stripkit::StripSet::from_strips(&[stitched]))
                    .iter()
                    .all(|&t| group_of[&canonical(t)] == g as u32));
            }
            if join == Join::Degenerate {
                assert_eq!(s.joined().len(), 2, "one stitched strip per material");
            }
            let json = s.to_json();
            let groups = json["groups"].as_array().unwrap();
            let strips = json["strips"].as_array().unwrap();
            assert_eq!(groups.len(), 2);
            for (g, range) in groups.iter().enumerate() {
                let (a, b) = (range[0].as_u64().unwrap() as usize, range[1].as_u64().unwrap() as usize);
                for strip in &strips[a..b] {
                    let strip: Vec<u32> =
                        strip.as_array().unwrap().iter().map(|i| i.as_u64().unwrap() as u32).collect();
                    for_each_triangle(&strip, |t| assert_eq!(group_of[&canonical(t)], g as u32));
                }
            }
            assert_eq!(groups[1][1].as_u64().unwrap() as usize, strips.len());
        }
    }
    // The test can fail: without the groups some strip of greedy crosses the seam line.
    let mut ungrouped = mesh.clone();
    ungrouped.face_groups.clear();
    ungrouped.groups.clear();
    let s = stripify(&ungrouped, &StripOptions::default()).unwrap();
    let crosses = s.strips.iter().any(|strip| {
        let mut groups = Vec::new();
        for_each_triangle(strip, |t| groups.push(group_of[&canonical(t)]));
        groups.dedup();
        groups.len() > 1
    });
    assert!(crosses);
}

#[test]
fn single_refuses_several_groups() {
    let mesh = obj(&two_materials(4, 4, &mut Rng(3)));
    let e = stripify(&mesh, &StripOptions::default().algorithm(Algorithm::Single(Default::default()))).unwrap_err();
    assert!(matches!(&e, Error::Invalid(m) if m.contains("2 groups")), "{e}");
}

#[test]
fn obj_round_trips_keep_every_corner_and_material() {
    let mut rng = Rng(5);
    let mesh = obj(&two_materials(6, 5, &mut rng));
    let cube = obj(&seamed_cube(&mut rng));
    for m in [&mesh, &cube] {
        let bytes = io::write_bytes(Format::Obj, m, None, &WriteOptions::default()).unwrap();
        let back = io::read_bytes(Path::new("back.obj"), Format::Obj, &bytes).unwrap();
        assert_eq!(back.face_count(), m.face_count());
        // Texture v is flipped on the way out and in: within one rounding of f32.
        let (a, b) = (m.attribute("TEXCOORD_0").unwrap(), back.attribute("TEXCOORD_0").unwrap());
        for f in 0..m.face_count() {
            for (&v, &w) in m.face(f).iter().zip(back.face(f)) {
                assert_eq!(m.positions[v as usize], back.positions[w as usize]);
                assert_eq!(a.get(v as usize, 0), b.get(w as usize, 0));
                assert!((a.get(v as usize, 1) - b.get(w as usize, 1)).abs() <= 6e-8);
            }
            assert_eq!(m.groups.get(m.group_of(f) as usize), back.groups.get(back.group_of(f) as usize));
        }
        assert_eq!(back.material_libraries, m.material_libraries);
        // Stripped to OBJ: the triangles in strip order, same corners, same materials
        // (greedy strips the fan, the reference here).
        let s = stripify(m, &StripOptions::default().algorithm(Algorithm::greedy())).unwrap();
        let bytes = s.to_file_bytes(m, Format::Obj).unwrap();
        let text = String::from_utf8(bytes.clone()).unwrap();
        assert_eq!(text.matches("usemtl ").count(), if m.groups.is_empty() { 0 } else { 2 });
        let back = io::read_bytes(Path::new("strips.obj"), Format::Obj, &bytes).unwrap();
        let exact = |x: &Mesh| {
            let mut x = x.clone();
            x.attributes.retain(|a| a.name != "TEXCOORD_0");
            x
        };
        assert_eq!(drawn(&exact(&back), &fan(&back)), drawn(&exact(m), &fan(m)));
    }
}

/// A PLY file with every kind of vertex property: normals, texture coordinates,
/// colours with alpha, a float `quality`, an int `id`, a ushort `flags`, and a list
/// (skipped).
fn rich_ply(rng: &mut Rng, big_endian: bool, faces: &[[u32; 3]], n: usize) -> Vec<u8> {
    let format = if big_endian { "binary_big_endian" } else { "binary_little_endian" };
    let mut out = format!(
        "ply\nformat {format} 1.0\nelement vertex {n}\nproperty float x\nproperty float y\nproperty float z\n\
         property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\n\
         property uchar blue\nproperty uchar alpha\nproperty float quality\nproperty list uchar int extra\n\
         property int id\nproperty float s\nproperty float t\nproperty ushort flags\n\
         element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        faces.len()
    )
    .into_bytes();
    let put = |out: &mut Vec<u8>, le: Vec<u8>| {
        let mut b = le;
        if big_endian {
            b.reverse();
        }
        out.extend_from_slice(&b);
    };
    for v in 0..n {
        for _ in 0..6 {
            put(&mut out, (rng.next() as f32 / 3e9 - 0.7).to_le_bytes().to_vec());
        }
        for _ in 0..4 {
            out.push(rng.next() as u8);
        }
        put(&mut out, (rng.next() as f32 * 1e-3).to_le_bytes().to_vec());
        out.extend_from_slice(&[2]);
        put(&mut out, 5i32.to_le_bytes().to_vec());
        put(&mut out, 6i32.to_le_bytes().to_vec());
        put(&mut out, (v as i32 - 1_000_000).to_le_bytes().to_vec());
        for _ in 0..2 {
            put(&mut out, ((rng.next() % 1000) as f32 / 999.0).to_le_bytes().to_vec());
        }
        put(&mut out, (rng.next() as u16).to_le_bytes().to_vec());
    }
    for f in faces {
        out.push(3);
        for &i in f {
            put(&mut out, (i as i32).to_le_bytes().to_vec());
        }
    }
    out
}

#[test]
fn ply_round_trips_keep_every_property_bit_for_bit() {
    let mut rng = Rng(21);
    let grid = stripkit::gen::grid(9, 7);
    let mut faces: Vec<[u32; 3]> = grid.faces().map(|f| [f[0], f[1], f[2]]).collect();
    rng.shuffle(&mut faces);
    for big in [false, true] {
        let bytes = rich_ply(&mut rng, big, &faces, grid.vertex_count());
        let mesh = io::read_bytes(Path::new("rich.ply"), Format::Ply, &bytes).unwrap();
        let names: Vec<(&str, Scalar, u8, bool)> =
            mesh.attributes.iter().map(|a| (a.name.as_str(), a.scalar, a.components, a.normalized)).collect();
        assert_eq!(
            names,
            [
                ("NORMAL", Scalar::F32, 3, false),
                ("TEXCOORD_0", Scalar::F32, 2, false),
                ("COLOR_0", Scalar::U8, 4, true),
                ("quality", Scalar::F32, 1, false),
                ("id", Scalar::I32, 1, false),
                ("flags", Scalar::U16, 1, false),
            ]
        );
        assert_eq!(mesh.attribute("id").unwrap().get(3, 0), 3.0 - 1e6);
        for ascii in [false, true] {
            let out = io::write_bytes(Format::Ply, &mesh, None, &WriteOptions::default().ply_ascii(ascii)).unwrap();
            let back = io::read_bytes(Path::new("back.ply"), Format::Ply, &out).unwrap();
            assert_eq!(back.positions, mesh.positions);
            assert_eq!(back.face_indices, mesh.face_indices);
            for (a, b) in mesh.attributes.iter().zip(&back.attributes) {
                assert_eq!(
                    (&a.name, a.scalar, a.components, a.normalized),
                    (&b.name, b.scalar, b.components, b.normalized)
                );
                if a.name == "TEXCOORD_0" {
                    // u exact, v within one rounding of the flip.
                    for v in 0..a.len() {
                        assert_eq!(a.get(v, 0), b.get(v, 0));
                        assert!((a.get(v, 1) - b.get(v, 1)).abs() <= 6e-8);
                    }
                } else {
                    assert_eq!(a.data, b.data, "{} (ascii {ascii}, big-endian input {big})", a.name);
                }
            }
        }
    }
}

#[test]
fn horse_ply_is_written_back_byte_for_byte() {
    let Some(dir) = support::models_dir() else { return };
    let path = dir.join("horse.ply");
    let original = std::fs::read(&path).unwrap();
    let mesh = io::read(&path).unwrap();
    assert_eq!(mesh.attributes.len(), 1);
    assert_eq!(mesh.attribute("NORMAL").unwrap().len(), 48485);
    let out = io::write_bytes(Format::Ply, &mesh, None, &WriteOptions::default()).unwrap();
    // Same layout (x y z nx ny nz floats, uchar-int faces): the bodies are identical.
    let body = |b: &[u8]| {
        let end = b.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
        b[end..].to_vec()
    };
    assert_eq!(body(&out), body(&original));
    // Stripped to PLY, the normals come along unchanged.
    let s = stripify(&mesh, &StripOptions::default()).unwrap();
    let back = io::read_bytes(Path::new("h.ply"), Format::Ply, &s.to_file_bytes(&mesh, Format::Ply).unwrap()).unwrap();
    assert_eq!(back.attributes, mesh.attributes);
}

#[test]
fn spot_keeps_its_uvs_through_strips_to_ply_and_obj() {
    let path = support::assets_dir().join("spot.obj");
    let mesh = io::read(&path).unwrap();
    assert_eq!((mesh.vertex_count(), mesh.face_count()), (3225, 5856));
    let uv = mesh.attribute("TEXCOORD_0").unwrap();
    let s = stripify(&mesh, &StripOptions::default()).unwrap();
    eprintln!(
        "spot: {} vertices, {} strips, {} indices (restart)",
        mesh.vertex_count(),
        s.strips.len(),
        s.figures.indices_restart
    );
    for format in [Format::Ply, Format::Obj] {
        let bytes = s.to_file_bytes(&mesh, format).unwrap();
        let back = io::read_bytes(Path::new("spot-back"), format, &bytes).unwrap();
        assert_eq!(back.vertex_count(), 3225, "{format:?}");
        let b = back.attribute("TEXCOORD_0").unwrap();
        // PLY keeps vertex ids; OBJ renumbers by first use: compare per corner.
        assert_eq!(drawn(&back, &fan(&back)).len(), 5856);
        if format == Format::Ply {
            for v in 0..3225 {
                assert_eq!(b.get(v, 0), uv.get(v, 0));
                assert!((b.get(v, 1) - uv.get(v, 1)).abs() <= 6e-8);
            }
        }
    }
}

#[test]
fn bad_attribute_input_is_refused_clearly() {
    let e = io::read_bytes(Path::new("bad.obj"), Format::Obj, b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/7\n")
        .unwrap_err();
    assert!(e.to_string().contains("line 5") && e.to_string().contains("texture coordinate 7"), "{e}");
    // An ASCII value out of its property's range.
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
                property uchar red\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
                0 0 0 1\n1 0 0 300\n0 1 0 2\n3 0 1 2\n";
    let e = io::read_bytes(Path::new("bad.ply"), Format::Ply, text.as_bytes()).unwrap_err();
    assert!(e.to_string().contains("300 is out of range for a uchar"), "{e}");
    // A header whose vertex count lies: more records than the bytes can hold.
    let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\nproperty float y\n\
        property float z\nproperty double quality\nend_header\n"
        .to_vec();
    bytes.extend_from_slice(&[0u8; 200]);
    let e = io::read_bytes(Path::new("lies.ply"), Format::Ply, &bytes).unwrap_err();
    assert!(e.to_string().contains("1000") && e.to_string().contains("200 bytes"), "{e}");
}

#[test]
fn single_carries_attributes_to_its_steiner_vertices() {
    // Jittered icospheres, until one needs edge splits; normals are the positions,
    // colours normalized bytes.
    let (mesh, s) = (1..40)
        .find_map(|seed| {
            let mut rng = Rng(seed);
            let mut mesh = stripkit::gen::icosphere(3);
            for p in &mut mesh.positions {
                for x in p.iter_mut() {
                    *x += 0.03 * (rng.below(1000) as f32 / 1000.0 - 0.5);
                }
            }
            let flat: Vec<f32> = mesh.positions.iter().flatten().copied().collect();
            mesh.attributes.push(Attribute::from_f32("NORMAL", 3, &flat));
            let data: Vec<u8> = (0..mesh.vertex_count() * 3).map(|_| rng.next() as u8).collect();
            mesh.attributes.push(Attribute {
                name: "COLOR_0".into(),
                scalar: Scalar::U8,
                components: 3,
                normalized: true,
                data,
            });
            let s = stripify(&mesh, &StripOptions::default().algorithm(Algorithm::Single(Default::default()))).unwrap();
            (!s.added_positions.is_empty()).then_some((mesh, s))
        })
        .expect("some jittered icosphere needs splits");
    let changed = s.changed_mesh(&mesh);
    changed.check_faces().unwrap();
    assert_eq!(changed.attributes.len(), 2);
    for a in &changed.attributes {
        assert_eq!(a.len(), mesh.vertex_count() + s.added_positions.len());
        for (k, &[x, y]) in s.added_from.iter().enumerate() {
            let v = mesh.vertex_count() + k;
            for c in 0..3 {
                let mean = (a.get(x as usize, c) + a.get(y as usize, c)) / 2.0;
                // Floats to rounding; bytes to the nearest.
                assert!((a.get(v, c) - mean).abs() <= 0.5 + 1e-6, "{} vertex {v}", a.name);
            }
        }
    }
    let back = io::read_bytes(Path::new("s.ply"), Format::Ply, &s.to_file_bytes(&mesh, Format::Ply).unwrap()).unwrap();
    assert_eq!(back.attributes, changed.attributes);
    eprintln!("single on a jittered icosphere: {} Steiner vertices, attributes blended", s.added_positions.len());
}

/// Random OBJ statements (vertices, UVs, normals, faces of every corner form with
/// indices in and out of range, negative ones, groups and materials): reading never
/// panics, refusals are format errors, and what it accepts is a valid mesh that
/// writes and reads back with the same faces.
#[test]
fn random_obj_statements_read_to_valid_meshes_or_clear_errors() {
    let mut rng = Rng(99);
    let (mut accepted, mut refused) = (0, 0);
    for _ in 0..400 {
        let mut text = String::new();
        let (mut nv, mut nt, mut nn) = (0i64, 0i64, 0i64);
        for _ in 0..rng.below(40) + 1 {
            match rng.below(7) {
                0 | 1 => {
                    text += &format!("v {} {} {}\n", rng.below(9), rng.below(9), rng.below(9));
                    nv += 1;
                }
                2 => {
                    text += &format!("vt {} {}\n", rng.below(9) as f32 / 8.0, rng.below(9) as f32 / 8.0);
                    nt += 1;
                }
                3 => {
                    text += &format!("vn 0 {} 1\n", rng.below(3));
                    nn += 1;
                }
                4 => text += ["g a\n", "usemtl m\n", "o b\n", "usemtl\n", "mtllib x.mtl\n"][rng.below(5)],
                _ => {
                    let form = rng.below(4);
                    text += "f";
                    for _ in 0..rng.below(3) + 2 {
                        let mut pick = |n: i64| {
                            let i = rng.below(n as usize + 3) as i64 - 1;
                            if i < 0 && n > 0 {
                                -(rng.below(n as usize) as i64 + 1)
                            } else {
                                i.max(1)
                            }
                        };
                        let (v, t, n) = (pick(nv), pick(nt), pick(nn));
                        text += &match form {
                            0 => format!(" {v}"),
                            1 => format!(" {v}/{t}"),
                            2 => format!(" {v}//{n}"),
                            _ => format!(" {v}/{t}/{n}"),
                        };
                    }
                    text += "\n";
                }
            }
        }
        match io::read_bytes(Path::new("random.obj"), Format::Obj, text.as_bytes()) {
            Ok(mesh) => {
                accepted += 1;
                mesh.check_faces().unwrap_or_else(|e| panic!("{e}\n{text}"));
                let bytes = io::write_bytes(Format::Obj, &mesh, None, &WriteOptions::default()).unwrap();
                let back = io::read_bytes(Path::new("back.obj"), Format::Obj, &bytes).unwrap();
                assert_eq!(back.face_count(), mesh.face_count(), "{text}");
            }
            Err(e) => {
                refused += 1;
                assert!(matches!(e, Error::Format { .. }), "{e}");
            }
        }
    }
    assert!(accepted > 50 && refused > 50, "{accepted} accepted, {refused} refused");
}

//! Every format and variant written and read back: positions bit for bit, faces
//! (polygons kept where the format can hold them) or decoded strips in order.

mod support;

use std::io::Write;
use support::encode_base64;
use std::path::PathBuf;
use stripkit::io::{self, WriteOptions};
use stripkit::{decode, StripSet};
use stripkit::Mesh;

fn tmp(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("io_roundtrip");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

use stripkit_testkit::Lcg;

/// A number in `[0, 1)` in steps of one millionth.
fn unit(rng: &mut Lcg) -> f32 {
    (rng.next() % 1_000_000) as f32 / 1_000_000.0
}

/// A perturbed `w x h` grid of quads (some rotated, some split into two triangles)
/// plus one pentagon; faces shuffled.
fn mixed_mesh(w: u32, h: u32, seed: u64) -> Mesh {
    let mut rng = Lcg(seed);
    let mut positions = Vec::new();
    for y in 0..=h {
        for x in 0..=w {
            positions.push([x as f32 * 0.731 + unit(&mut rng) * 0.1, y as f32 * 1.37 - unit(&mut rng) * 0.1, unit(&mut rng) * 3.0 - 1.5]);
        }
    }
    let v = |x: u32, y: u32| y * (w + 1) + x;
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let q = [v(x, y), v(x + 1, y), v(x + 1, y + 1), v(x, y + 1)];
            match rng.next() % 3 {
                0 => faces.push(q.to_vec()),
                1 => {
                    faces.push(vec![q[0], q[1], q[2]]);
                    faces.push(vec![q[0], q[2], q[3]]);
                }
                _ => faces.push(vec![q[1], q[2], q[3], q[0]]),
            }
        }
    }
    // One pentagon: a quad with an extra vertex appended at the end of the list.
    positions.push([100.0, 100.0, 100.0]);
    let extra = positions.len() as u32 - 1;
    faces.push(vec![v(0, 0), v(1, 0), v(1, 1), v(0, 1), extra]);
    for i in (1..faces.len()).rev() {
        let j = (rng.next() as usize) % (i + 1);
        faces.swap(i, j);
    }
    Mesh::from_polygons(positions, &faces)
}

fn assert_same_positions(a: &Mesh, b: &Mesh) {
    assert_eq!(a.positions.len(), b.positions.len());
    for (p, q) in a.positions.iter().zip(&b.positions) {
        assert_eq!(p.map(f32::to_bits), q.map(f32::to_bits));
    }
}

fn triangle_faces(m: &Mesh) -> Vec<[u32; 3]> {
    m.faces()
        .map(|f| {
            assert_eq!(f.len(), 3);
            [f[0], f[1], f[2]]
        })
        .collect()
}

#[test]
fn obj_off_and_ply_keep_polygons_exactly() {
    let mesh = mixed_mesh(9, 7, 1);
    assert!(!mesh.is_triangle_mesh() && mesh.faces().any(|f| f.len() == 5));
    for (name, ascii) in [
        ("poly.obj", false),
        ("poly.off", false),
        ("poly_bin.ply", false),
        ("poly_ascii.ply", true),
        ("POLY_UPPER.OBJ", false),
    ] {
        let path = tmp(name);
        io::write_with(&path, &mesh, None, &WriteOptions::default().ply_ascii(ascii)).unwrap();
        let back = io::read(&path).unwrap();
        assert_eq!(back, mesh, "{name}");
        assert_same_positions(&back, &mesh);
    }
    let text = std::fs::read(tmp("poly_ascii.ply")).unwrap();
    assert!(text.starts_with(b"ply\nformat ascii 1.0\n"));
    let bin = std::fs::read(tmp("poly_bin.ply")).unwrap();
    assert!(bin.starts_with(b"ply\nformat binary_little_endian 1.0\n"));
}

#[test]
fn ply_tristrips_round_trip_as_their_decoded_triangles() {
    let mesh = mixed_mesh(4, 3, 2);
    let strips = StripSet::from_strips(&[vec![0, 1, 5, 6, 2, 7], vec![3, 3, 4, 8, 9], vec![10, 11], vec![], vec![12, 13, 17]]);
    for (name, ascii) in [("strips_bin.ply", false), ("strips_ascii.ply", true)] {
        let path = tmp(name);
        io::write_with(&path, &mesh, Some(&strips), &WriteOptions::default().ply_ascii(ascii)).unwrap();
        let back = io::read(&path).unwrap();
        assert_same_positions(&back, &mesh);
        assert_eq!(triangle_faces(&back), decode(&strips), "{name}");
    }
    let bytes = std::fs::read(tmp("strips_bin.ply")).unwrap();
    let text = String::from_utf8_lossy(&bytes);
    assert!(text.contains("element tristrips 1\nproperty list int int vertex_indices\n"));
}

#[test]
fn ply_binary_big_endian_with_mixed_types() {
    let mut bytes = b"ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty double x\nproperty float y\n\
        property short w\nproperty float z\nproperty list ushort uchar skipped\nelement face 2\n\
        property list uint ushort vertex_index\nproperty float quality\nend_header\n"
        .to_vec();
    let positions = [[0.5f32, -1.25, 3.0], [1.0, 2.0, 4.5], [-7.0, 0.125, 0.0], [9.0, 9.5, -0.75]];
    for (k, p) in positions.iter().enumerate() {
        bytes.extend_from_slice(&(p[0] as f64).to_be_bytes());
        bytes.extend_from_slice(&p[1].to_be_bytes());
        bytes.extend_from_slice(&(k as i16 * -3).to_be_bytes());
        bytes.extend_from_slice(&p[2].to_be_bytes());
        bytes.extend_from_slice(&(k as u16).to_be_bytes());
        bytes.extend((0..k as u8).map(|b| b + 40));
    }
    for face in [&[0u16, 1, 2][..], &[0, 2, 3, 1]] {
        bytes.extend_from_slice(&(face.len() as u32).to_be_bytes());
        for &i in face {
            bytes.extend_from_slice(&i.to_be_bytes());
        }
        bytes.extend_from_slice(&0.5f32.to_be_bytes());
    }
    let path = tmp("big_endian.ply");
    std::fs::write(&path, &bytes).unwrap();
    let mesh = io::read(&path).unwrap();
    assert_eq!(mesh.positions, positions.to_vec());
    assert_eq!(mesh.face(0), &[0, 1, 2]);
    assert_eq!(mesh.face(1), &[0, 2, 3, 1]);
}

#[test]
fn stl_binary_round_trips_triangles_and_welds_shared_corners() {
    // A triangle mesh whose vertices appear in first-use order: welding gives the same ids.
    let mesh = Mesh::from_triangles(
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.5], [-0.0, 2.0, 0.0]],
        &[[0, 1, 2], [2, 1, 3], [2, 3, 4]],
    );
    let path = tmp("tri.stl");
    io::write(&path, &mesh, None).unwrap();
    assert_eq!(std::fs::metadata(&path).unwrap().len(), 84 + 50 * 3);
    assert_eq!(io::read(&path).unwrap(), mesh);

    // Polygons are fanned; compare triangles by their positions.
    let poly = mixed_mesh(5, 4, 3);
    let path = tmp("poly.stl");
    io::write(&path, &poly, None).unwrap();
    let back = io::read(&path).unwrap();
    let by_position = |m: &Mesh| -> Vec<[[u32; 3]; 3]> {
        m.triangulate().tris.iter().map(|t| t.map(|v| m.positions[v as usize].map(f32::to_bits))).collect()
    };
    assert_eq!(by_position(&back), by_position(&poly));
    assert_eq!(back.face_count(), poly.triangle_count());
    // The grid's vertices are all distinct and all used (the pentagon's extra one too).
    assert_eq!(back.vertex_count(), poly.vertex_count());
}

#[test]
fn stl_ascii_handcrafted_is_welded() {
    let text = "solid two\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n\
                      vertex 1 1 0\n    endloop\n  endfacet\n  facet normal 0 0 1\n    outer loop\n\
                      vertex 0 0 0\n      vertex 1 1 0\n      vertex 0 1 -0.0\n    endloop\n  endfacet\n\
                endsolid two\n";
    let path = tmp("two.stl");
    std::fs::write(&path, text).unwrap();
    let mesh = io::read(&path).unwrap();
    assert_eq!(mesh.positions, vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]);
    assert_eq!(triangle_faces(&mesh), vec![[0, 1, 2], [0, 2, 3]]);
}

#[test]
fn gltf_and_glb_round_trip_faces_and_strips() {
    let mesh = mixed_mesh(6, 5, 4);
    let strips = StripSet::from_strips(&[vec![0, 1, 7, 8, 2, 9], vec![3, 3, 4, 10, 11], vec![5, 6], vec![12, 13, 19, 20]]);
    for name in ["m.gltf", "m.glb"] {
        let path = tmp(name);
        io::write(&path, &mesh, None).unwrap();
        let back = io::read(&path).unwrap();
        assert_same_positions(&back, &mesh);
        assert_eq!(triangle_faces(&back), mesh.triangulate().tris, "{name}");

        let path = tmp(&format!("strips_{name}"));
        io::write(&path, &mesh, Some(&strips)).unwrap();
        let back = io::read(&path).unwrap();
        assert_same_positions(&back, &mesh);
        assert_eq!(triangle_faces(&back), decode(&strips), "{name}");
    }
    // One TRIANGLE_STRIP primitive per strip of three or more indices.
    let json: serde_json::Value = serde_json::from_slice(&std::fs::read(tmp("strips_m.gltf")).unwrap()).unwrap();
    let prims = json["meshes"][0]["primitives"].as_array().unwrap();
    assert_eq!(prims.len(), 3);
    assert!(prims.iter().all(|p| p["mode"] == 5));
}

#[test]
fn gltf_with_an_external_buffer_and_32_bit_indices() {
    // 70,000 vertices force 32-bit indices.
    let n = 70_000u32;
    let positions: Vec<[f32; 3]> = (0..n).map(|i| [i as f32, (i % 7) as f32, 0.5]).collect();
    let tris: Vec<[u32; 3]> = (0..n - 2).step_by(3).map(|i| [i, i + 1, i + 2]).collect();
    let mesh = Mesh::from_triangles(positions, &tris);
    let path = tmp("external.gltf");
    io::write(&path, &mesh, None).unwrap();
    let mut json: serde_json::Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    assert_eq!(json["accessors"][1]["componentType"], 5125);
    let uri = json["buffers"][0]["uri"].as_str().unwrap().to_string();
    let b64 = uri.split_once(";base64,").unwrap().1;
    let bin = decode_base64(b64);
    std::fs::write(tmp("external data.bin"), &bin).unwrap();
    json["buffers"][0]["uri"] = "external%20data.bin".into();
    std::fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
    let back = io::read(&path).unwrap();
    assert_eq!(back, mesh);
}

fn decode_base64(s: &str) -> Vec<u8> {
    let val = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        _ => 63,
    } as u32;
    let bytes: Vec<u8> = s.bytes().filter(|&c| c != b'=').collect();
    let mut out = Vec::new();
    for chunk in bytes.chunks(4) {
        let mut n = 0u32;
        for (k, &c) in chunk.iter().enumerate() {
            n |= val(c) << (18 - 6 * k);
        }
        for k in 0..chunk.len() - 1 {
            out.push((n >> (16 - 8 * k)) as u8);
        }
    }
    out
}

#[test]
fn gltf_non_indexed_primitives_use_vertices_in_order() {
    let positions: Vec<[f32; 3]> = (0..6).map(|i| [i as f32, 1.0, 2.0]).collect();
    let bin: Vec<u8> = positions.iter().flatten().flat_map(|c| c.to_le_bytes()).collect();
    let json = serde_json::json!({
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": bin.len(), "uri": "data:application/octet-stream;base64,".to_string() + &encode_base64(&bin)}],
        "bufferViews": [{"buffer": 0, "byteLength": bin.len()}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}, {"primitives": [{"attributes": {"POSITION": 0}, "mode": 5}]}]
    });
    let path = tmp("non_indexed.gltf");
    std::fs::write(&path, json.to_string()).unwrap();
    let m = io::read(&path).unwrap();
    assert_eq!(m.positions, positions);
    assert_eq!(triangle_faces(&m), vec![[0, 1, 2], [3, 4, 5], [0, 1, 2], [2, 1, 3], [2, 3, 4], [4, 3, 5]]);
}

#[test]
fn gzip_files_read_like_the_plain_ones() {
    let mesh = mixed_mesh(5, 5, 5);
    let tri = Mesh::from_triangles(mesh.positions.clone(), &mesh.triangulate().tris);
    for name in ["g.obj", "g.off", "g.ply", "g.stl", "g.gltf", "g.glb"] {
        let plain = tmp(name);
        let m = if name.ends_with(".stl") { &tri } else { &mesh };
        io::write(&plain, m, None).unwrap();
        let expected = io::read(&plain).unwrap();
        let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        enc.write_all(&std::fs::read(&plain).unwrap()).unwrap();
        let gz = tmp(&format!("{name}.GZ"));
        std::fs::write(&gz, enc.finish().unwrap()).unwrap();
        assert_eq!(io::read(&gz).unwrap(), expected, "{name}");
        // The writer compresses too.
        let gz2 = tmp(&format!("w_{name}.gz"));
        io::write(&gz2, m, None).unwrap();
        assert_eq!(io::read(&gz2).unwrap(), expected, "{name}");
    }
}

#[test]
fn empty_meshes_are_valid_everywhere() {
    let empty = Mesh::new();
    let points_only = Mesh::from_polygons::<Vec<u32>>(vec![[1.0, 2.0, 3.0]; 1], &[]);
    for name in ["e.obj", "e.off", "e.ply", "e.stl", "e.gltf", "e.glb"] {
        let path = tmp(name);
        io::write(&path, &empty, None).unwrap();
        assert_eq!(io::read(&path).unwrap(), empty, "{name}");
        if !name.ends_with(".stl") {
            io::write(&path, &points_only, None).unwrap();
            assert_eq!(io::read(&path).unwrap(), points_only, "{name}");
        }
    }
}

#[test]
fn degenerate_and_duplicate_faces_are_loaded() {
    let mesh = Mesh::from_polygons(vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[vec![0, 1, 2], vec![0, 1, 2], vec![0, 0, 1]]);
    for name in ["d.obj", "d.off", "d.ply"] {
        let path = tmp(name);
        io::write(&path, &mesh, None).unwrap();
        assert_eq!(io::read(&path).unwrap(), mesh, "{name}");
    }
}

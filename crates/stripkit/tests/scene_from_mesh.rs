//! A scene made from a mesh (`Scene::from_mesh`) leaves its positions and indices out
//! of its buffer (the primitives' meshes hold them) and makes their bytes again when
//! it is written. Every form it writes (not stripped, stripped with and without
//! restart groups, in input vertex order, primitives kept as read, several groups with
//! attributes, 4-byte indices) must be the same bytes as the same scene read back from
//! a file of its document, whose buffer holds them. Every file written goes through the
//! Khronos validator.

mod support;

use std::path::Path;
use stripkit::io::{Format, ReadOptions};
use stripkit::scene::{Scene, SceneOptions};
use stripkit::{gen, Attribute, Group, Mesh, StripOptions};

/// `mesh` with its faces in a shuffled order.
fn shuffled(mesh: &Mesh, seed: u64) -> Mesh {
    let mut faces: Vec<Vec<u32>> = mesh.faces().map(|f| f.to_vec()).collect();
    stripkit_testkit::Lcg(seed).shuffle(&mut faces);
    Mesh::from_polygons(mesh.positions.clone(), &faces)
}

/// A torus in two groups (by the smallest vertex id's parity) with normals.
fn two_groups() -> Mesh {
    let mut mesh = shuffled(&gen::torus(16, 10, 1.0, 0.3), 5);
    let normals = stripkit_testkit::geom::radial_normals(&mesh.positions);
    mesh.attributes.push(Attribute::from_f32("NORMAL", 3, &normals));
    mesh.face_groups = (0..mesh.face_count()).map(|f| mesh.face(f).iter().min().unwrap() % 2).collect();
    mesh.groups = vec![Group { name: "even".into(), material: None }, Group { name: "odd".into(), material: None }];
    mesh
}

/// 60 triangles sharing no vertex: strips take more index bytes than the list, so the
/// primitive is written as read (its indices made again from its faces).
fn apart() -> Mesh {
    let positions: Vec<[f32; 3]> = (0..180).map(|v| [v as f32, (v % 3) as f32, (v / 3) as f32]).collect();
    let faces: Vec<Vec<u32>> = (0..60).map(|t| vec![3 * t, 3 * t + 1, 3 * t + 2]).collect();
    Mesh::from_polygons(positions, &faces)
}

/// Two groups: a shuffled sphere, which strips, and [`apart`]'s triangles, kept as read,
/// interleaved in face order.
fn one_kept() -> Mesh {
    let sphere = shuffled(&gen::icosphere(2), 7);
    let loose = apart();
    let base = sphere.vertex_count() as u32;
    let mut positions = sphere.positions.clone();
    positions.extend(loose.positions.iter().map(|p| [p[0] + 3.0, p[1], p[2]]));
    let mut faces: Vec<(u32, Vec<u32>)> = sphere.faces().map(|f| (0, f.to_vec())).collect();
    faces.extend(loose.faces().map(|f| (1, f.iter().map(|v| v + base).collect())));
    stripkit_testkit::Lcg(11).shuffle(&mut faces);
    let polygons: Vec<Vec<u32>> = faces.iter().map(|f| f.1.clone()).collect();
    let mut mesh = Mesh::from_polygons(positions, &polygons);
    mesh.face_groups = faces.iter().map(|f| f.0).collect();
    mesh.groups = vec![Group { name: "sphere".into(), material: None }, Group { name: "loose".into(), material: None }];
    mesh
}

fn out_dir() -> std::path::PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join("scene_from_mesh");
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn a_scene_made_from_a_mesh_writes_the_bytes_of_its_document_read_back() {
    let dir = out_dir();
    let forms = [
        ("restart", SceneOptions::default()),
        ("stitched", SceneOptions::stitched()),
        ("input-order", SceneOptions::default().reorder(false)),
    ];
    let mut written = Vec::new();
    let mut kept = 0;
    for (name, mesh) in [
        ("sphere", shuffled(&gen::icosphere(3), 1)),
        ("groups", two_groups()),
        ("apart", apart()),
        ("one-kept", one_kept()),
    ] {
        let made = Scene::from_mesh(&mesh).unwrap();
        let plain = made.to_bytes(Format::Glb).unwrap();
        let read = Scene::from_bytes(Path::new("plain.glb"), Format::Glb, &plain, &ReadOptions::default()).unwrap();
        assert_eq!(read.to_bytes(Format::Glb).unwrap(), plain, "{name}: not stripped");
        let path = dir.join(format!("{name}-plain.glb"));
        std::fs::write(&path, &plain).unwrap();
        written.push(path);
        for (form, options) in &forms {
            let (mut a, mut b) = (made.clone(), read.clone());
            let report = a.strip(&StripOptions::default(), options).unwrap();
            b.strip(&StripOptions::default(), options).unwrap();
            assert_eq!(report.triangles, mesh.triangle_count());
            kept += report.kept_as_read;
            let bytes = a.to_bytes(Format::Glb).unwrap();
            assert_eq!(bytes, b.to_bytes(Format::Glb).unwrap(), "{name}, {form}");
            assert_eq!(a.into_bytes(Format::Glb).unwrap(), bytes, "{name}, {form}: into_bytes");
            let path = dir.join(format!("{name}-{form}.glb"));
            std::fs::write(&path, &bytes).unwrap();
            written.push(path);
        }
    }
    // "apart" is kept as read in every form, and one-kept's loose group.
    assert_eq!(kept, 6);
    let refs: Vec<&Path> = written.iter().map(|p| p.as_path()).collect();
    support::gltf_validator::validate(&refs);
}

#[test]
fn four_byte_indices_are_made_again_as_written() {
    // 10,242 vertices per sphere, seven side by side: more than 65,535 vertices.
    let sphere = gen::icosphere(5);
    let mut faces = Vec::new();
    let mut positions = Vec::new();
    for k in 0..7u32 {
        let base = positions.len() as u32;
        positions.extend(sphere.positions.iter().map(|p| [p[0] + 3.0 * k as f32, p[1], p[2]]));
        faces.extend(sphere.faces().map(|f| f.iter().map(|v| v + base).collect::<Vec<u32>>()));
    }
    let mesh = Mesh::from_polygons(positions, &faces);
    assert!(mesh.vertex_count() > 65_535);
    let made = Scene::from_mesh(&mesh).unwrap();
    let plain = made.to_bytes(Format::Glb).unwrap();
    let read = Scene::from_bytes(Path::new("plain.glb"), Format::Glb, &plain, &ReadOptions::default()).unwrap();
    assert_eq!(read.primitives()[0].mesh.triangulate().tris, mesh.triangulate().tris);
    assert_eq!(read.to_bytes(Format::Glb).unwrap(), plain);
    let path = out_dir().join("wide-plain.glb");
    std::fs::write(&path, &plain).unwrap();
    support::gltf_validator::validate(&[&path]);
}

//! Inputs that once took time quadratic in their size (issue #30, class 3): one group
//! per face, many faces on one edge, identical triangles, a PLY vertex with many
//! properties. Each runs a large-ish case as a correctness check only (no timing
//! assertion: the growth tables are in docs/experiments/reliability.md, "Quadratic
//! inputs"); before the fixes these cases took minutes in a debug build.

use std::path::PathBuf;
use stripkit::{io, stripify, Algorithm, Attribute, Group, Mesh, MeshFacts, StripOptions};
use stripkit_testkit::XorShift64;

fn temp_file(name: &str, bytes: &[u8]) -> PathBuf {
    let dir = stripkit_testkit::scratch_dir("quadratic");
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// A strip of `n` triangles along x, two rows of vertices.
fn ribbon(n: u32) -> Mesh {
    let positions: Vec<[f32; 3]> = (0..n / 2 + 2).flat_map(|i| [[i as f32, 0.0, 0.0], [i as f32, 1.0, 0.0]]).collect();
    let tris: Vec<[u32; 3]> = (0..n)
        .map(|i| {
            let a = 2 * (i / 2);
            if i % 2 == 0 {
                [a, a + 2, a + 1]
            } else {
                [a + 1, a + 2, a + 3]
            }
        })
        .collect();
    Mesh::from_triangles(positions, &tris)
}

/// What `Mesh::submesh` gave before it stopped scanning the whole mesh: flags over
/// every vertex, the used ones in increasing order.
fn reference_submesh(mesh: &Mesh, faces: &[u32]) -> (Mesh, Vec<u32>) {
    let mut used = vec![false; mesh.vertex_count()];
    for &f in faces {
        mesh.face(f as usize).iter().for_each(|&v| used[v as usize] = true);
    }
    let mut new_id = vec![u32::MAX; mesh.vertex_count()];
    let mut map = Vec::new();
    for (v, _) in used.iter().enumerate().filter(|(_, &u)| u) {
        new_id[v] = map.len() as u32;
        map.push(v as u32);
    }
    let mut out = mesh.gather_vertices(&map);
    out.groups.clear();
    for &f in faces {
        out.face_indices.extend(mesh.face(f as usize).iter().map(|&v| new_id[v as usize]));
        out.face_offsets.push(out.face_indices.len() as u32);
    }
    (out, map)
}

#[test]
fn submesh_matches_the_whole_mesh_scan() {
    let mut mesh = ribbon(400);
    let values: Vec<f32> = (0..mesh.vertex_count() * 2).map(|i| i as f32 * 0.5).collect();
    mesh.attributes.push(Attribute::from_f32("TEXCOORD_0", 2, &values));
    mesh.material_libraries.push("a.mtl".into());
    mesh.groups = vec![Group::default(), Group { name: "g".into(), material: Some("m".into()) }];
    mesh.face_groups = (0..mesh.face_count() as u32).map(|f| f % 2).collect();
    let mut rng = XorShift64(0x5eed_1234_5678_9abc);
    for round in 0..200 {
        let mut faces: Vec<u32> =
            (0..mesh.face_count() as u32).filter(|_| rng.below(round % 7 + 2) == 0).collect();
        if round % 3 == 0 {
            faces.reverse(); // any face order, vertices still in increasing id order
        }
        assert_eq!(mesh.submesh(&faces), reference_submesh(&mesh, &faces), "round {round}");
    }
}

#[test]
fn one_usemtl_per_face_strips_every_group() {
    let n = 16_000u32;
    let mut obj = String::new();
    for i in 0..n / 2 + 2 {
        obj += &format!("v {i} 0 0\nv {i} 1 0\n");
    }
    let ribbon = ribbon(n);
    for (i, face) in ribbon.faces().enumerate() {
        obj += &format!("usemtl m{i}\nf {} {} {}\n", face[0] + 1, face[1] + 1, face[2] + 1);
    }
    let mesh = io::read(temp_file("usemtl.obj", obj.as_bytes())).unwrap();
    assert_eq!(mesh.group_count(), n as usize);
    let strips = stripify(&mesh, &StripOptions::default().algorithm(Algorithm::greedy())).unwrap();
    // Every face is a group of its own: one strip of one triangle each, in face order.
    assert_eq!(strips.strips.len(), n as usize);
    assert_eq!(strips.group_ranges.len(), n as usize);
    for (i, s) in strips.strips.iter().enumerate() {
        let mut got = s.to_vec();
        let mut want = ribbon.face(i).to_vec();
        got.sort_unstable();
        want.sort_unstable();
        assert_eq!(got, want, "strip {i}");
    }
}

#[test]
fn a_book_of_many_pages_has_one_nonmanifold_edge() {
    // n triangles on the edge 0-1, apexes on a circle around it.
    for n in [5u32, 40, 20_000] {
        let mut positions = vec![[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0]];
        positions.extend((0..n).map(|i| {
            let t = std::f32::consts::TAU * i as f32 / n as f32;
            [0.5, t.cos(), t.sin()]
        }));
        let mut tris: Vec<[u32; 3]> = (0..n).map(|i| [0, 1, i + 2]).collect();
        // One page twice (the second reversed) and one pinch: a triangle at vertex 0 alone.
        tris.push([n + 1, 1, 0]);
        positions.extend([[-1.0, 0.0, 0.0], [-1.0, 1.0, 0.0]]);
        tris.push([0, n + 2, n + 3]);
        let facts = MeshFacts::of(&Mesh::from_triangles(positions, &tris)).unwrap();
        assert_eq!(facts.faces, n as usize + 2);
        assert_eq!(facts.nonmanifold_edges, 1, "n {n}");
        assert_eq!(facts.duplicate_faces, 1, "n {n}");
        assert_eq!(facts.nonmanifold_vertices, 1, "n {n}");
        assert_eq!(facts.edge_components, 2, "n {n}");
        assert_eq!(facts.components, 1, "n {n}");
    }
}

#[test]
fn identical_stl_triangles_are_duplicates() {
    let n = 100_000u32;
    let mut stl = vec![0u8; 80];
    stl.extend_from_slice(&n.to_le_bytes());
    let coords: [f32; 12] = [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    for _ in 0..n {
        coords.iter().for_each(|c| stl.extend_from_slice(&c.to_le_bytes()));
        stl.extend_from_slice(&[0, 0]);
    }
    let mesh = io::read(temp_file("same.stl", &stl)).unwrap();
    let facts = MeshFacts::of(&mesh).unwrap();
    assert_eq!(facts.faces, n as usize);
    assert_eq!(facts.vertices, 3);
    assert_eq!(facts.duplicate_faces, n as usize - 1);
    assert_eq!(facts.nonmanifold_edges, 3);
    assert_eq!(facts.nonmanifold_vertices, 0);
    assert_eq!(facts.degenerate_faces, 0);
}

#[test]
fn a_ply_vertex_with_many_properties_keeps_the_first_of_each_name() {
    let n = 50_000;
    let mut ply = String::from("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n");
    for i in 0..n {
        ply += &format!("property uchar p{}\n", i % (n - 10)); // the last 10 repeat a name
    }
    ply += "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    let values: String = (0..n).map(|i| format!(" {}", i % 200)).collect();
    for p in ["0 0 0", "1 0 0", "0 1 0"] {
        ply += &format!("{p}{values}\n");
    }
    ply += "3 0 1 2\n";
    let mesh = io::read(temp_file("props.ply", ply.as_bytes())).unwrap();
    assert_eq!(mesh.attributes.len(), n - 10);
    assert_eq!(mesh.attributes[7].name, "p7");
    assert_eq!(mesh.attributes[7].value(1), vec![7.0]);
    assert_eq!(mesh.attributes[n - 11].value(2), vec![((n - 11) % 200) as f64]);
}

#[test]
fn many_mtllib_names_keep_the_first_of_each() {
    // 80,000 `mtllib` names (every tenth line repeats an earlier one): 44 s in the
    // release CLI when each name searched the list of earlier ones.
    let n = 80_000;
    let mut obj = String::new();
    for i in 0..n {
        let name = if i % 10 == 9 { i - 5 } else { i };
        obj += &format!("mtllib lib{name}.mtl\n");
    }
    obj += "mtllib lib0.mtl lib80000.mtl lib80000.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let mesh = io::read(temp_file("mtllibs.obj", obj.as_bytes())).unwrap();
    let expected: Vec<String> =
        (0..n).filter(|i| i % 10 != 9).chain([80_000]).map(|i| format!("lib{i}.mtl")).collect();
    assert_eq!(mesh.material_libraries, expected);
}

/// A triangle whose vertices carry `n` one-byte attributes, vertex `v`'s value of
/// attribute `i` being `(i + v) % 251`.
fn many_attributes(n: usize) -> Mesh {
    let mut mesh = Mesh::from_triangles(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
    for i in 0..n {
        let data = (0..3).map(|v| ((i + v) % 251) as u8).collect();
        mesh.attributes.push(Attribute {
            name: format!("p{i}"),
            scalar: stripkit::Scalar::U8,
            components: 1,
            normalized: false,
            data,
        });
    }
    mesh
}

#[test]
fn glb_output_takes_a_bounded_number_of_attributes_and_other_formats_all() {
    // Each attribute is an accessor of its own in glTF (about 4.4 KB of document while
    // the scene is built and checked): 300,000 of them needed 1.4 GB. Past the limit
    // glTF output is refused before anything is built; PLY keeps them all.
    let limit = io::MAX_GLTF_VERTEX_ATTRIBUTES;
    let over = many_attributes(limit + 1);
    let e = io::Scene::from_mesh(&over).unwrap_err();
    assert!(e.is_invalid(), "{e}");
    let text = e.to_string();
    assert!(text.contains(&format!("{} vertex attributes", limit + 1)) && text.contains(&format!("at most {limit}")), "{text}");
    // The plain writer (single's changed mesh, separate strips) writes attributes too,
    // under the same limit.
    let e = io::write_bytes(io::Format::Glb, &over, None, &io::WriteOptions::default()).unwrap_err();
    assert!(e.is_invalid() && e.to_string().contains(&format!("at most {limit}")), "{e}");
    let path = temp_file("many_attributes.ply", b"");
    io::write(&path, &over, None).unwrap();
    let back = io::read(&path).unwrap();
    assert_eq!(back.attributes.len(), limit + 1);
    assert_eq!(back.attributes[limit].value(2), vec![((limit + 2) % 251) as f64]);
    // At the limit the scene is built, every attribute in it.
    let at = many_attributes(limit);
    let scene = io::Scene::from_mesh(&at).unwrap();
    let glb = scene.to_bytes(io::Format::Glb).unwrap();
    let (json, _) = stripkit_testkit::unglb(&glb);
    let attributes = json["meshes"][0]["primitives"][0]["attributes"].as_object().unwrap();
    assert_eq!(attributes.len(), limit + 1, "POSITION and every attribute");
    assert!(attributes.contains_key("_P4095"));
}

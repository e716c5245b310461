//! Procedural meshes and subdivision: counts, topology kept, orientation kept,
//! boundary rules.

mod support;

use stripkit::{gen, Mesh, MeshFacts};
use support::assets_dir;

fn facts(mesh: &Mesh) -> MeshFacts {
    MeshFacts::of(mesh).expect("valid mesh")
}

/// A minimal OBJ reader for the bundled assets (`v` and `f` lines), so these tests
/// do not depend on the io module.
fn read_obj(name: &str) -> Mesh {
    let text = std::fs::read_to_string(assets_dir().join(name)).expect("bundled asset");
    let mut mesh = Mesh::new();
    for line in text.lines() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => {
                let c: Vec<f32> = it.take(3).map(|t| t.parse().unwrap()).collect();
                mesh.positions.push([c[0], c[1], c[2]]);
            }
            Some("f") => {
                let f: Vec<u32> = it.map(|t| t.split('/').next().unwrap().parse::<u32>().unwrap() - 1).collect();
                mesh.push_face(&f);
            }
            _ => {}
        }
    }
    mesh
}

fn normal(mesh: &Mesh, face: &[u32]) -> [f64; 3] {
    let mut n = [0f64; 3];
    for i in 0..face.len() {
        let a = mesh.positions[face[i] as usize].map(|x| x as f64);
        let b = mesh.positions[face[(i + 1) % face.len()] as usize].map(|x| x as f64);
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    n
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[test]
fn loop_subdivision_multiplies_faces_by_four_and_keeps_topology() {
    let inputs = [
        gen::icosphere(1),
        gen::shuffle_faces(&gen::icosphere(1), 5),
        gen::torus(12, 7, 2.0, 0.6),
        gen::grid(5, 3),
        gen::disjoint_union(&[&gen::icosphere(0), &gen::torus(5, 4, 3.0, 1.0)]),
    ];
    for (i, mesh) in inputs.iter().enumerate() {
        let before = facts(mesh);
        let mut prev = mesh.clone();
        for k in 1..=2u32 {
            let out = gen::subdivide_loop(mesh, k).unwrap();
            let after = facts(&out);
            let e_prev = facts(&prev).edges;
            assert_eq!(after.faces, before.faces * 4usize.pow(k), "input {i} level {k}");
            assert_eq!(after.vertices, prev.vertex_count() + e_prev, "input {i} level {k}");
            assert_eq!(after.euler_characteristic, before.euler_characteristic);
            assert_eq!(after.components, before.components);
            assert_eq!(after.boundary_loops, before.boundary_loops);
            assert_eq!(after.boundary_edges, before.boundary_edges * 2usize.pow(k));
            assert_eq!(after.closed_manifold, before.closed_manifold);
            assert!(after.consistently_oriented);
            assert_eq!((after.degenerate_faces, after.duplicate_faces), (0, 0));
            prev = out;
        }
    }
}

#[test]
fn loop_keeps_each_face_orientation() {
    // Every child of an outward triangle of a sphere points outward too.
    let sphere = gen::shuffle_faces(&gen::icosphere(1), 9);
    let out = gen::subdivide_loop(&sphere, 2).unwrap();
    for face in out.faces() {
        let c = out.positions[face[0] as usize].map(|x| x as f64);
        assert!(dot(normal(&out, face), c) > 0.0, "inward face {face:?}");
    }
    // Loop shrinks a convex surface towards its inside, never outside the sphere.
    for p in &out.positions {
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        assert!(r > 0.8 && r <= 1.0 + 1e-6, "radius {r}");
    }
}

#[test]
fn loop_on_a_flat_grid_has_linear_precision_and_boundary_rules() {
    let (w, h) = (6u32, 4u32);
    let grid = gen::grid(w, h);
    let out = gen::subdivide_loop(&grid, 1).unwrap();
    assert!(out.positions.iter().all(|p| p[2] == 0.0), "a plane stays a plane");
    // Interior vertices of the regular pattern have valence 6 and symmetric rings:
    // they stay where they are.
    for j in 1..h {
        for i in 1..w {
            let v = (j * (w + 1) + i) as usize;
            assert_eq!(out.positions[v], grid.positions[v], "vertex ({i},{j})");
        }
    }
    // Boundary vertices that are not corners stay on their side (3/4 v + 1/8 ends).
    for i in 1..w {
        assert_eq!(out.positions[i as usize], [i as f32, 0.0, 0.0]);
    }
    // Boundary edge points are midpoints: every new vertex on y = 0 lies on it.
    let f = facts(&out);
    assert_eq!((f.boundary_loops, f.boundary_edges), (1, 4 * (w + h) as usize));
}

#[test]
fn loop_rejects_non_triangle_and_degenerate_input() {
    let err = gen::subdivide_loop(&gen::cube(), 1).unwrap_err().to_string();
    assert!(err.contains("triangle") && err.contains("face 0"), "{err}");
    let bad = Mesh::from_triangles(vec![[0.0; 3]; 3], &[[0, 1, 1]]);
    assert!(gen::subdivide_loop(&bad, 1).unwrap_err().to_string().contains("face 0"));
    let out_of_range = Mesh::from_triangles(vec![[0.0; 3]; 3], &[[0, 1, 7]]);
    assert!(gen::subdivide_loop(&out_of_range, 1).is_err());
    assert!(gen::subdivide_catmull_clark(&out_of_range, 1).is_err());
    // Level 0 is the identity.
    let ico = gen::icosphere(0);
    assert_eq!(gen::subdivide_loop(&ico, 0).unwrap(), ico);
}

#[test]
fn catmull_clark_of_a_cube_is_a_closed_quad_sphere() {
    let cube = gen::cube();
    let f0 = facts(&cube);
    assert!(f0.closed_manifold && f0.consistently_oriented);
    assert_eq!((f0.vertices, f0.quads, f0.euler_characteristic), (8, 6, 2));
    for k in 1..=3u32 {
        let out = gen::subdivide_catmull_clark(&cube, k).unwrap();
        let f = facts(&out);
        assert_eq!(f.quads, 6 * 4usize.pow(k));
        assert_eq!(f.faces, f.quads);
        assert_eq!(f.vertices, 6 * 4usize.pow(k) + 2);
        assert_eq!(f.euler_characteristic, 2);
        assert!(f.closed_manifold && f.consistently_oriented);
        for face in out.faces() {
            let c = out.positions[face[0] as usize].map(|x| x as f64);
            assert!(dot(normal(&out, face), c) > 0.0, "level {k}: inward quad {face:?}");
        }
        assert!(out.positions.iter().all(|p| p.iter().all(|x| x.abs() <= 1.0)));
    }
    // Level one by hand: an old corner (valence 3) goes to (Q + 2R + 0 S)/3 = 5/9 of
    // the way, i.e. (±5/9, ±5/9, ±5/9).
    let one = gen::subdivide_catmull_clark(&cube, 1).unwrap();
    for p in &one.positions[..8] {
        for x in p {
            assert!((x.abs() - 5.0 / 9.0).abs() < 1e-6, "{p:?}");
        }
    }
}

#[test]
fn catmull_clark_turns_mixed_polygons_into_quads() {
    let control = read_obj("spot_control_mesh.obj");
    let f0 = facts(&control);
    assert_eq!((f0.triangles, f0.quads, f0.polygons), (4, 160, 16));
    let out = gen::subdivide_catmull_clark(&gen::shuffle_faces(&control, 1), 1).unwrap();
    let f = facts(&out);
    assert_eq!(f.quads, 4 * 3 + 160 * 4 + 16 * 5);
    assert_eq!((f.triangles, f.polygons), (0, 0));
    assert_eq!(f.euler_characteristic, 2);
    assert!(f.closed_manifold && f.consistently_oriented);
    let two = gen::subdivide_catmull_clark(&control, 2).unwrap();
    assert_eq!(facts(&two).quads, 4 * 732);
}

#[test]
fn catmull_clark_keeps_open_boundaries() {
    let grid = gen::grid_quads(4, 3);
    let out = gen::subdivide_catmull_clark(&grid, 2).unwrap();
    let f = facts(&out);
    assert_eq!(f.quads, 12 * 16);
    assert_eq!((f.boundary_loops, f.boundary_edges), (1, 2 * 7 * 4));
    assert_eq!(f.euler_characteristic, 1);
    // Flat stays flat; interior vertices of a regular grid stay put (tensor B-spline).
    assert!(out.positions.iter().all(|p| p[2] == 0.0));
    let one = gen::subdivide_catmull_clark(&grid, 1).unwrap();
    assert_eq!(one.positions[5 + 1], grid.positions[5 + 1]);
    // Triangles too: a triangle grid gives 3 quads per triangle.
    let tri = gen::subdivide_catmull_clark(&gen::grid(2, 2), 1).unwrap();
    assert_eq!(facts(&tri).quads, 8 * 3);
}

#[test]
fn generators_have_the_documented_counts() {
    assert_eq!(gen::grid(3, 2).face_count(), 12);
    assert_eq!(gen::grid(3, 2).vertex_count(), 12);
    assert_eq!(gen::grid_quads(3, 2).face_count(), 6);
    let t = gen::torus_quads(10, 6, 1.0, 0.25);
    assert_eq!((t.vertex_count(), t.face_count()), (60, 60));
    for face in t.faces() {
        // Outward: the normal points away from the tube's centre circle.
        let p = t.positions[face[0] as usize].map(|x| x as f64);
        let len = (p[0] * p[0] + p[1] * p[1]).sqrt();
        let centre = [p[0] / len, p[1] / len, 0.0];
        let out = [p[0] - centre[0], p[1] - centre[1], p[2]];
        assert!(dot(normal(&t, face), out) > 0.0);
    }
    let shuffled = gen::shuffle_faces(&gen::grid(4, 4), 3);
    let mut a: Vec<Vec<u32>> = gen::grid(4, 4).faces().map(canonical).collect();
    let mut b: Vec<Vec<u32>> = shuffled.faces().map(canonical).collect();
    assert_ne!(a, b, "shuffled");
    a.sort();
    b.sort();
    assert_eq!(a, b, "same oriented faces");
}

/// A face rotated to start at its smallest vertex (orientation kept).
fn canonical(face: &[u32]) -> Vec<u32> {
    let i = (0..face.len()).min_by_key(|&i| face[i]).unwrap();
    face[i..].iter().chain(&face[..i]).copied().collect()
}

#[test]
#[ignore = "large: icosphere level 8 (1.3M triangles)"]
fn icosphere_level_eight_has_1_310_720_triangles() {
    let m = gen::icosphere(8);
    assert_eq!(m.face_count(), 1_310_720);
    assert!(facts(&m).closed_manifold);
}

#[test]
fn requests_beyond_the_size_limit_are_refused_before_building() {
    let limit = gen::MAX_INDICES;
    // The predictions match what the generators build.
    assert!(gen::check_grid(708, 708, false).is_ok());
    assert_eq!(gen::grid(3, 2).face_indices.len(), 6 * 3 * 2);
    assert!(gen::check_icosphere(gen::MAX_ICOSPHERE_LEVEL).is_ok());
    assert!(gen::check_torus(200, 100).is_ok());
    assert!(gen::check_subdivision(gen::cube().face_indices.len(), 10, "cube").is_ok());
    assert!(gen::check_subdivision(gen::cube().face_indices.len(), 11, "cube").is_err());
    // 13000 x 13000 squares (over 10 GB to build and write) once passed the limit.
    assert!(gen::check_grid(13000, 13000, false).is_err());
    assert!(gen::check_grid(2364, 2364, false).is_ok());
    assert!(gen::check_icosphere(gen::MAX_ICOSPHERE_LEVEL + 1).is_err());
    assert!(gen::check_subdivision(24, 13, "cube").is_err());
    // Over the limit, without wrapping: 2^32 - 1 squares each way passes 2^64 indices.
    let e = gen::check_grid(u32::MAX, u32::MAX, false).unwrap_err().to_string();
    assert!(e.starts_with("the requested mesh is too large (") && e.ends_with(&format!("limit {limit})")), "{e}");
    assert!(gen::check_grid(u32::MAX, u32::MAX, true).is_err());
    assert!(gen::check_torus(u32::MAX, u32::MAX).is_err());
    let e = gen::check_icosphere(11).unwrap_err().to_string();
    assert_eq!(e, "icosphere level 11 is too large (at most 9: 5,242,880 triangles)");
    let e = gen::check_subdivision(24, 14, "cube").unwrap_err().to_string();
    assert!(e.contains("(6442450944 face indices, 0 vertices; limit 33554432)"), "{e}");
    // Nothing grows from nothing: 4^36 overflowed before the multiplication by 0 and
    // refused an empty mesh (found by the `options` fuzz target).
    assert!(gen::check_subdivision(0, 36, "empty").is_ok());
    assert!(gen::check_subdivision(0, u32::MAX, "empty").is_ok());
    // 24 * 4^31 once wrapped to 0 and got past the check.
    for levels in [31, 32, 40, u32::MAX] {
        let e = gen::check_subdivision(24, levels, "cube").unwrap_err().to_string();
        assert!(e.contains(&format!("cube: 24 face indices x 4^{levels} is beyond 2^64")), "{e}");
    }
}

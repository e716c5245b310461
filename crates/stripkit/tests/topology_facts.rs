//! `MeshFacts` on procedural meshes whose figures are known by construction.

use stripkit::gen;
use stripkit::MeshFacts;
use stripkit::Mesh;

fn facts(mesh: &Mesh) -> MeshFacts {
    MeshFacts::of(mesh).expect("valid mesh")
}

/// Removes faces by index (keeps vertex ids).
fn without_faces(mesh: &Mesh, drop: &[usize]) -> Mesh {
    let faces: Vec<Vec<u32>> =
        mesh.faces().enumerate().filter(|(f, _)| !drop.contains(f)).map(|(_, face)| face.to_vec()).collect();
    Mesh::from_polygons(mesh.positions.clone(), &faces)
}

#[test]
fn icospheres_are_closed_oriented_spheres() {
    for level in 0..5u32 {
        let mesh = gen::icosphere(level);
        for (seed, m) in [(0, mesh.clone()), (1, gen::shuffle_faces(&mesh, level as u64 + 7))] {
            let f = facts(&m);
            assert_eq!(f.vertices, 10 * 4usize.pow(level) + 2, "level {level} seed {seed}");
            assert_eq!(f.faces, 20 * 4usize.pow(level));
            assert_eq!(f.triangles, f.faces);
            assert_eq!(f.edges, 30 * 4usize.pow(level));
            assert_eq!((f.quads, f.polygons, f.unreferenced_vertices), (0, 0, 0));
            assert_eq!((f.boundary_edges, f.boundary_loops), (0, 0));
            assert_eq!((f.nonmanifold_edges, f.nonmanifold_vertices), (0, 0));
            assert_eq!(f.components, 1);
            assert_eq!(f.euler_characteristic, 2);
            assert_eq!((f.degenerate_faces, f.duplicate_faces), (0, 0));
            assert!(f.consistently_oriented && f.closed_manifold);
        }
    }
}

#[test]
fn icosphere_faces_point_outwards() {
    let mesh = gen::icosphere(2);
    for face in mesh.faces() {
        let p: Vec<[f64; 3]> =
            face.iter().map(|&v| mesh.positions[v as usize].map(|x| x as f64)).collect();
        let n = stripkit_testkit::geom::tri_normal(p[0], p[1], p[2]);
        assert!(n[0] * p[0][0] + n[1] * p[0][1] + n[2] * p[0][2] > 0.0, "face {face:?} points inwards");
    }
    let level8 = gen::icosphere(3);
    assert_eq!(level8.face_count(), 1280);
}

#[test]
fn tori_have_euler_characteristic_zero() {
    for (major, minor) in [(3, 3), (8, 5), (40, 17)] {
        for m in [gen::torus(major, minor, 2.0, 0.5), gen::torus_quads(major, minor, 2.0, 0.5)] {
            let f = facts(&m);
            assert_eq!(f.vertices, (major * minor) as usize);
            assert_eq!(f.euler_characteristic, 0, "{major}x{minor}");
            assert_eq!(f.edges as u32, 3 * major * minor - if f.quads > 0 { major * minor } else { 0 });
            assert!(f.closed_manifold && f.consistently_oriented);
            assert_eq!(f.components, 1);
        }
    }
}

#[test]
fn grids_have_one_boundary_loop() {
    for (w, h) in [(1, 1), (3, 2), (17, 5)] {
        for m in [gen::grid(w, h), gen::grid_quads(w, h)] {
            let f = facts(&m);
            assert_eq!(f.boundary_edges, 2 * (w + h) as usize);
            assert_eq!(f.boundary_loops, 1);
            assert_eq!(f.euler_characteristic, 1);
            assert_eq!(f.components, 1);
            assert!(f.consistently_oriented && !f.closed_manifold);
            let f2 = facts(&gen::shuffle_faces(&m, 3));
            assert_eq!(f2, f);
        }
    }
    let f = facts(&gen::grid_quads(4, 3));
    assert_eq!((f.quads, f.triangles, f.fan_triangles), (12, 0, 24));
}

#[test]
fn holes_touching_at_a_vertex_are_walked_through_their_fans() {
    // 4x4 quads, remove (1,1) and (2,2): two holes sharing grid vertex (2,2).
    let base = gen::grid_quads(4, 4);
    let mesh = without_faces(&base, &[4 + 1, 2 * 4 + 2]);
    for m in [mesh.clone(), gen::shuffle_faces(&mesh, 11), gen::shuffle_faces(&mesh, 12)] {
        let f = facts(&m);
        assert_eq!(f.boundary_edges, 16 + 8);
        // The walk stays in the fan it arrives through: the two holes' boundaries join
        // into one figure-eight through the pinch (as they do once the pinch vertex is
        // split into one copy per fan), plus the outer loop.
        assert_eq!(f.boundary_loops, 2);
        assert_eq!(f.nonmanifold_vertices, 1, "the shared corner is a pinch");
        assert_eq!(f.euler_characteristic, 1 - 2);
        assert_eq!(f.components, 1);
    }
    // One hole in the middle of a triangle grid.
    let tri = gen::grid(3, 3);
    let holed = without_faces(&tri, &[8, 9]);
    let f = facts(&holed);
    assert_eq!((f.boundary_edges, f.boundary_loops, f.nonmanifold_vertices), (16, 2, 0));
    assert_eq!(f.euler_characteristic, 0);
}

#[test]
fn disjoint_spheres_are_two_components() {
    let a = gen::icosphere(1);
    let b = gen::icosphere(2);
    let f = facts(&gen::disjoint_union(&[&a, &b]));
    assert_eq!(f.components, 2);
    assert_eq!(f.edge_components, 2);
    assert_eq!(f.euler_characteristic, 4);
    assert_eq!(f.faces, 80 + 320);
    assert!(f.closed_manifold);
}

#[test]
fn bow_tie_has_one_pinch_vertex_and_one_component() {
    let mesh = Mesh::from_triangles(
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [-1.0, -1.0, 0.0]],
        &[[0, 1, 2], [0, 3, 4]],
    );
    let f = facts(&mesh);
    assert_eq!(f.nonmanifold_vertices, 1);
    assert_eq!(f.components, 1, "joined through the pinch vertex, as the models README counts");
    assert_eq!(f.edge_components, 2, "no shared edge");
    assert_eq!(f.boundary_edges, 6);
    assert_eq!(f.boundary_loops, 2);
    assert_eq!(f.euler_characteristic, 5 - 6 + 2);
    assert!(!f.closed_manifold);
}

#[test]
fn two_cones_touching_at_the_apex_pinch_a_closed_surface() {
    // Two closed octahedra glued at one vertex: cow.obj's situation.
    let a = gen::icosphere(0);
    let mut b = gen::icosphere(0);
    for p in &mut b.positions {
        p[0] += 3.0;
    }
    let mut both = gen::disjoint_union(&[&a, &b]);
    // Merge vertex 12 (b's vertex 0) into vertex 0.
    for v in &mut both.face_indices {
        if *v == 12 {
            *v = 0;
        }
    }
    let f = facts(&both);
    assert_eq!(f.nonmanifold_vertices, 1);
    assert_eq!((f.components, f.edge_components), (1, 2));
    assert_eq!(f.unreferenced_vertices, 1);
    assert_eq!(f.boundary_edges, 0);
    assert_eq!(f.euler_characteristic, 23 - 60 + 40);
    assert!(!f.closed_manifold);
}

#[test]
fn three_triangles_on_one_edge_make_a_nonmanifold_edge() {
    let mesh = Mesh::from_triangles(
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 1.0, 0.0], [0.5, -1.0, 0.0], [0.5, 0.0, 1.0]],
        &[[0, 1, 2], [1, 0, 3], [0, 1, 4]],
    );
    let f = facts(&mesh);
    assert_eq!(f.nonmanifold_edges, 1);
    assert_eq!(f.nonmanifold_vertices, 0);
    assert_eq!(f.components, 1);
    assert_eq!(f.boundary_edges, 6);
    assert_eq!(f.edges, 7);
    // A three-face edge is not a two-face edge: orientation is only judged on those.
    assert!(f.consistently_oriented);
}

#[test]
fn a_flipped_triangle_breaks_orientation() {
    let mut mesh = gen::grid(3, 3);
    assert!(facts(&mesh).consistently_oriented);
    // Triangle 8 is the lower triangle of the middle square: all three edges interior.
    let s = mesh.face_offsets[8] as usize;
    mesh.face_indices[s..s + 3].reverse();
    let f = facts(&mesh);
    assert!(!f.consistently_oriented);
    assert_eq!(f.inconsistent_edges, 3);
    assert_eq!(f.boundary_edges, 12);
}

#[test]
fn degenerate_and_duplicate_faces_are_counted() {
    let base = gen::grid(2, 2); // 8 triangles, vertices 0..9 on a 3x3 lattice
    let mut faces: Vec<Vec<u32>> = base.faces().map(|f| f.to_vec()).collect();
    let t0 = faces[0].clone();
    faces.push(vec![t0[1], t0[2], t0[0]]); // rotation: duplicate
    faces.push(vec![t0[2], t0[1], t0[0]]); // flipped: duplicate
    faces.push(vec![4, 4, 5]); // repeated index
    faces.push(vec![0, 1, 2]); // collinear: zero area
    faces.push(vec![0, 1, 2, 5, 4, 3]); // a polygon, fine
    faces.push(vec![4, 3, 0, 1, 2, 5]); // the same polygon rotated: duplicate
    faces.push(vec![0, 2, 1, 5, 4, 3]); // same vertices, another cycle: not a duplicate
    let mesh = Mesh::from_polygons(base.positions.clone(), &faces);
    let f = facts(&mesh);
    assert_eq!(f.duplicate_faces, 3);
    assert_eq!(f.degenerate_faces, 2);
    assert_eq!(f.polygons, 3);
    assert_eq!(f.faces, 15);
    // Edgeless faces (one vertex repeated) are compared too.
    let mut more = faces.clone();
    more.push(vec![7, 7, 7]);
    more.push(vec![7, 7, 7]);
    let f = facts(&Mesh::from_polygons(base.positions.clone(), &more));
    assert_eq!((f.duplicate_faces, f.degenerate_faces), (4, 4));
}

#[test]
fn unreferenced_vertices_are_counted_but_not_in_euler() {
    let mut mesh = gen::icosphere(1);
    mesh.positions.push([5.0, 5.0, 5.0]);
    mesh.positions.push([6.0, 5.0, 5.0]);
    let f = facts(&mesh);
    assert_eq!(f.unreferenced_vertices, 2);
    assert_eq!(f.euler_characteristic, 2);
    assert_eq!(f.components, 1);
}

#[test]
fn malformed_meshes_are_errors_not_panics() {
    let bad_index = Mesh::from_triangles(vec![[0.0; 3]; 3], &[[0, 1, 3]]);
    let err = MeshFacts::of(&bad_index).unwrap_err().to_string();
    assert!(err.contains("face 0") && err.contains("vertex 3"), "{err}");
    let bad_offsets = Mesh { positions: vec![[0.0; 3]; 3], face_offsets: vec![0, 2], face_indices: vec![0, 1], ..Mesh::new() };
    assert!(MeshFacts::of(&bad_offsets).is_err());
    let empty = facts(&Mesh::new());
    assert_eq!(empty.faces, 0);
    assert!(!empty.closed_manifold);
}

#[test]
fn display_and_json_name_every_figure() {
    let f = facts(&gen::grid(2, 1));
    let text = f.to_string();
    assert!(text.contains("boundary edges        6 in 1 loops"), "{text}");
    let json = serde_json::to_value(&f).unwrap();
    for key in [
        "vertices", "faces", "triangles", "quads", "polygons", "unreferenced_vertices", "boundary_edges",
        "boundary_loops", "nonmanifold_edges", "nonmanifold_vertices", "components", "euler_characteristic",
        "degenerate_faces", "duplicate_faces", "consistently_oriented",
    ] {
        assert!(json.get(key).is_some(), "missing {key}");
    }
    assert_eq!(json["boundary_edges"], 6);
}

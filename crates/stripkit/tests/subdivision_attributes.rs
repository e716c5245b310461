//! Loop and Catmull-Clark subdivision carry vertex attributes with the positions'
//! own stencil weights, and face groups to the child faces (issue #15 item 1).

use stripkit::{gen, Attribute, Group, Mesh, Scalar};

/// `mesh` with its positions copied into a float attribute `P`, a normalized u8
/// colour and an integer joint index, its faces in two groups (by face parity), shuffled.
fn with_attributes(mesh: Mesh) -> Mesh {
    let mut mesh = gen::shuffle_faces(&mesh, 7);
    let flat: Vec<f32> = mesh.positions.iter().flatten().copied().collect();
    mesh.attributes.push(Attribute::from_f32("P", 3, &flat));
    let n = mesh.vertex_count();
    mesh.attributes.push(Attribute {
        name: "COLOR_0".into(),
        scalar: Scalar::U8,
        components: 1,
        normalized: true,
        data: (0..n).map(|v| if v % 2 == 0 { 255 } else { 0 }).collect(),
    });
    mesh.attributes.push(Attribute {
        name: "JOINTS_0".into(),
        scalar: Scalar::U8,
        components: 1,
        normalized: false,
        data: (0..n).map(|v| (v % 7) as u8).collect(),
    });
    mesh.face_groups = (0..mesh.face_count() as u32).map(|f| f % 2).collect();
    mesh.groups = vec![Group { name: "even".into(), material: None }, Group { name: "odd".into(), material: None }];
    mesh.check_faces().unwrap();
    mesh
}

/// The subdivided `P` equals the subdivided positions, every attribute has a value per
/// vertex, colours stay in range, joints are input joint values, groups follow.
fn check(input: &Mesh, out: &Mesh, children: impl Fn(usize) -> usize, what: &str) {
    out.check_faces().unwrap();
    let p = out.attribute("P").expect("P kept");
    assert_eq!(p.len(), out.vertex_count(), "{what}");
    let mut worst = 0f64;
    for (v, pos) in out.positions.iter().enumerate() {
        for (c, &x) in pos.iter().enumerate() {
            worst = worst.max((p.get(v, c) - x as f64).abs());
        }
    }
    assert!(worst < 1e-5, "{what}: P differs from the position by {worst}");
    let colour = out.attribute("COLOR_0").unwrap();
    let joints = out.attribute("JOINTS_0").unwrap();
    assert_eq!((colour.len(), joints.len()), (out.vertex_count(), out.vertex_count()), "{what}");
    // Colours blend: some new vertices lie strictly between black and white.
    assert!((0..colour.len()).any(|v| (1.0..255.0).contains(&colour.get(v, 0))), "{what}: colours not blended");
    assert!((0..joints.len()).all(|v| joints.get(v, 0) < 7.0), "{what}");
    // Input vertices keep their joint (the heaviest weight of a vertex rule is its own).
    let j_in = input.attribute("JOINTS_0").unwrap();
    for v in 0..input.vertex_count() {
        assert_eq!(joints.get(v, 0), j_in.get(v, 0), "{what}: joint of vertex {v}");
    }
    let mut f = 0;
    for parent in 0..input.face_count() {
        for _ in 0..children(parent) {
            assert_eq!(out.group_of(f), input.group_of(parent), "{what}: face {f}");
            f += 1;
        }
    }
    assert_eq!(f, out.face_count());
    assert_eq!(out.groups, input.groups);
}

#[test]
fn loop_subdivision_carries_attributes_with_its_weights() {
    for (mesh, what) in [(gen::icosphere(1), "icosphere"), (gen::grid(4, 3), "grid, with boundary")] {
        let mesh = with_attributes(mesh);
        let once = gen::subdivide_loop(&mesh, 1).unwrap();
        check(&mesh, &once, |_| 4, what);
        let twice = gen::subdivide_loop(&mesh, 2).unwrap();
        check(&once, &twice, |_| 4, what);
    }
}

#[test]
fn catmull_clark_carries_attributes_with_its_weights() {
    for (mesh, what) in
        [(gen::cube(), "cube"), (gen::grid_quads(3, 2), "quad grid, with boundary"), (gen::icosphere(1), "triangles")]
    {
        let mesh = with_attributes(mesh);
        let once = gen::subdivide_catmull_clark(&mesh, 1).unwrap();
        check(&mesh, &once, |f| mesh.face(f).len(), what);
        let twice = gen::subdivide_catmull_clark(&mesh, 2).unwrap();
        check(&once, &twice, |_| 4, what);
    }
}

#[test]
fn a_uv_seam_stays_closed_and_each_side_keeps_its_own_uvs() {
    // Two quad strips side by side, the middle column duplicated: UV u = x / 4 on the
    // left, 0.6 + x / 10 on the right.
    let mut positions = Vec::new();
    let mut uv = Vec::new();
    for y in 0..3 {
        for x in 0..3 {
            positions.push([x as f32, y as f32, 0.1 * (x * y) as f32]);
            uv.extend([x as f32 / 4.0, 0.0]);
        }
        for x in 2..5 {
            positions.push([x as f32, y as f32, 0.1 * (x * y) as f32]);
            uv.extend([0.6 + x as f32 / 10.0, 1.0]);
        }
    }
    let id = |x: u32, y: u32, right: bool| y * 6 + if right { 3 + x - 2 } else { x };
    let mut faces = Vec::new();
    for y in 0..2 {
        for x in 0..2 {
            faces.push(vec![id(x, y, false), id(x + 1, y, false), id(x + 1, y + 1, false), id(x, y + 1, false)]);
        }
        for x in 2..4 {
            faces.push(vec![id(x, y, true), id(x + 1, y, true), id(x + 1, y + 1, true), id(x, y + 1, true)]);
        }
    }
    let mut mesh = Mesh::from_polygons(positions, &faces);
    mesh.attributes.push(Attribute::from_f32("TEXCOORD_0", 2, &uv));
    let mut triangles = Mesh::from_triangles(mesh.positions.clone(), &mesh.triangulate().tris);
    triangles.attributes = mesh.attributes.clone();
    for levels in 1..=2 {
        for (out, what) in [
            (gen::subdivide_catmull_clark(&mesh, levels).unwrap(), "catmull-clark"),
            (gen::subdivide_loop(&triangles, levels).unwrap(), "loop"),
        ] {
            let uv = out.attribute("TEXCOORD_0").unwrap();
            // The seam: used vertices at x = 2, by side (V is 0 left, 1 right).
            let used: std::collections::BTreeSet<u32> = out.face_indices.iter().copied().collect();
            let (mut left, mut right) = (Vec::new(), Vec::new());
            for &v in used.iter().filter(|&&v| out.positions[v as usize][0] == 2.0) {
                let side = if uv.get(v as usize, 1) > 0.5 { &mut right } else { &mut left };
                side.push(out.positions[v as usize].map(f32::to_bits));
            }
            left.sort();
            right.sort();
            assert_eq!(left, right, "{what} {levels}: the seam opened");
            assert_eq!(left.len(), 2usize.pow(levels) * 2 + 1, "{what} {levels}");
            for f in out.faces() {
                let side = uv.get(f[0] as usize, 1) > 0.5;
                for &v in f {
                    // Each side keeps its own V and its own U range.
                    assert_eq!(uv.get(v as usize, 1) > 0.5, side, "{what}: a face mixes the islands");
                    let u = uv.get(v as usize, 0);
                    let range = if side { 0.8..=1.0 } else { 0.0..=0.5 };
                    assert!(range.contains(&u), "{what}: u {u}");
                }
            }
        }
    }
}

#[test]
fn blended_normals_and_tangents_are_unit_again() {
    // On a unit sphere the normal is the position: blends of unit normals are
    // shorter than 1, and come back unit, pointing about where the new vertex is.
    let mut mesh = gen::icosphere(1);
    let normals: Vec<f32> = mesh.positions.iter().flatten().copied().collect();
    let tangents: Vec<f32> = mesh.positions.iter().flat_map(|p| [-p[1], p[0], 0.0, -1.0]).collect();
    mesh.attributes.push(Attribute::from_f32("NORMAL", 3, &normals));
    mesh.attributes.push(Attribute::from_f32("TANGENT", 4, &tangents));
    for (out, what) in [
        (gen::subdivide_loop(&mesh, 2).unwrap(), "loop"),
        (gen::subdivide_catmull_clark(&mesh, 1).unwrap(), "catmull-clark"),
    ] {
        let n = out.attribute("NORMAL").unwrap();
        let t = out.attribute("TANGENT").unwrap();
        for v in 0..out.vertex_count() {
            let a = n.value(v);
            let len = a.iter().map(|x| x * x).sum::<f64>().sqrt();
            assert!((len - 1.0).abs() < 1e-6, "{what}: normal {v} has length {len}");
            let p = out.positions[v].map(|x| x as f64);
            let plen = p.iter().map(|x| x * x).sum::<f64>().sqrt();
            let cos = (0..3).map(|c| a[c] * p[c]).sum::<f64>() / plen;
            assert!(cos > 0.98, "{what}: normal {v} points away ({cos})");
            let b = t.value(v);
            let tlen = b[..3].iter().map(|x| x * x).sum::<f64>().sqrt();
            if tlen > 0.0 {
                assert!((tlen - 1.0).abs() < 1e-6, "{what}: tangent {v} has length {tlen}");
            }
            assert_eq!(b[3], -1.0, "{what}: tangent {v}'s sign");
        }
    }
}

#[test]
fn attributes_that_do_not_fit_the_mesh_are_refused() {
    let mut short = gen::icosphere(0);
    short.attributes.push(Attribute::from_f32("TEXCOORD_0", 2, &[0.0; 10]));
    let mut groups = gen::icosphere(0);
    groups.face_groups = vec![0; 3];
    let mut ids = gen::icosphere(0);
    ids.face_groups = vec![5; 20];
    let options = stripkit::simplify::Options::default();
    for (mesh, needle) in [(&short, "attribute TEXCOORD_0"), (&groups, "3 face groups"), (&ids, "in group 5")] {
        for err in [
            gen::subdivide_loop(mesh, 1).unwrap_err(),
            gen::subdivide_catmull_clark(mesh, 1).unwrap_err(),
            stripkit::simplify::simplify(mesh, &options, &mut |_| {}).unwrap_err(),
        ] {
            assert!(err.to_string().contains(needle), "{err}");
        }
    }
}

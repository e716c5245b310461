//! Simplification carries vertex attributes and face groups, and keeps attribute
//! seams closed (issue #15 item 1): a height field cut down the middle into two UV
//! islands, whose seam vertices are two vertices at one position.

use stripkit::simplify::{simplify, Options, Placement, Target};
use stripkit::{Attribute, Group, Mesh};
use stripkit_testkit::XorShift64;

const N: u32 = 24;
const SEAM: u32 = N / 2;

fn height(x: f32, y: f32) -> f32 {
    0.3 * (x * 0.45).sin() * (y * 0.35).cos() + 0.02 * x * y
}

/// The U coordinate of a corner at column `x` on the left (`right == false`) or right island.
fn u_of(x: f32, right: bool) -> f32 {
    if right {
        0.55 + 0.45 * (x - SEAM as f32) / (N - SEAM) as f32
    } else {
        0.45 * x / SEAM as f32
    }
}

/// The seamed height field, its faces shuffled by a fixed permutation: vertices
/// `(N+1)^2` of the left island's grid, then the right island's copies of the seam
/// column. Left faces are group 0, right faces group 1. Returns the mesh and, per
/// vertex, whether it belongs to the right island.
fn seamed() -> (Mesh, Vec<bool>) {
    let id = |x: u32, y: u32| y * (N + 1) + x;
    let mut positions = Vec::new();
    let mut uv = Vec::new();
    let mut normal = Vec::new();
    let mut right = Vec::new();
    for y in 0..=N {
        for x in 0..=N {
            let (fx, fy) = (x as f32, y as f32);
            positions.push([fx, fy, height(fx, fy)]);
            uv.extend([u_of(fx, x > SEAM), fy / N as f32]);
            normal.extend([0.0, 0.0, 1.0]);
            right.push(x > SEAM);
        }
    }
    let mut twin = vec![u32::MAX; positions.len()];
    for y in 0..=N {
        let v = id(SEAM, y);
        twin[v as usize] = positions.len() as u32;
        positions.push(positions[v as usize]);
        uv.extend([u_of(SEAM as f32, true), y as f32 / N as f32]);
        normal.extend([0.0, 0.0, 1.0]);
        right.push(true);
    }
    let mut faces = Vec::new();
    for y in 0..N {
        for x in 0..N {
            let mut q = [id(x, y), id(x + 1, y), id(x + 1, y + 1), id(x, y + 1)];
            let is_right = x >= SEAM;
            if is_right {
                q = q.map(|v| if twin[v as usize] != u32::MAX { twin[v as usize] } else { v });
            }
            faces.push(([q[0], q[1], q[2]], is_right as u32));
            faces.push(([q[0], q[2], q[3]], is_right as u32));
        }
    }
    // A fixed shuffle of the faces.
    XorShift64(0x2545_f491_4f6c_dd1d).shuffle(&mut faces);
    let tris: Vec<[u32; 3]> = faces.iter().map(|f| f.0).collect();
    let mut mesh = Mesh::from_triangles(positions, &tris);
    mesh.face_groups = faces.iter().map(|f| f.1).collect();
    mesh.groups = vec![
        Group { name: "left".into(), material: Some("a".into()) },
        Group { name: "right".into(), material: Some("b".into()) },
    ];
    mesh.attributes.push(Attribute::from_f32("TEXCOORD_0", 2, &uv));
    mesh.attributes.push(Attribute::from_f32("NORMAL", 3, &normal));
    mesh.check_faces().unwrap();
    (mesh, right)
}

/// The seam's boundary edges on one island, as position pairs (sorted).
fn seam_edges(mesh: &Mesh, right: &[bool], side: bool) -> Vec<[[u32; 3]; 2]> {
    let mut count = std::collections::HashMap::new();
    for t in mesh.triangulate().tris {
        for e in 0..3 {
            let (a, b) = (t[e].min(t[(e + 1) % 3]), t[e].max(t[(e + 1) % 3]));
            *count.entry((a, b)).or_insert(0) += 1;
        }
    }
    let key = |v: u32| mesh.positions[v as usize].map(f32::to_bits);
    let mut edges: Vec<[[u32; 3]; 2]> = count
        .into_iter()
        .filter(|&((a, b), c)| {
            c == 1
                && right[a as usize] == side
                && mesh.positions[a as usize][0] == SEAM as f32
                && mesh.positions[b as usize][0] == SEAM as f32
        })
        .map(|((a, b), _)| {
            let (ka, kb) = (key(a), key(b));
            if ka <= kb {
                [ka, kb]
            } else {
                [kb, ka]
            }
        })
        .collect();
    edges.sort();
    edges
}

#[test]
fn simplification_keeps_uv_seams_closed_and_never_mixes_the_islands() {
    let (mesh, right) = seamed();
    let input_seam = seam_edges(&mesh, &right, false);
    assert_eq!(input_seam.len(), N as usize);
    assert_eq!(input_seam, seam_edges(&mesh, &right, true));
    for placement in [Placement::Endpoint, Placement::Optimal] {
        let options = Options::default().target(Target::Ratio(0.2)).placement(placement);
        let out = simplify(&mesh, &options, &mut |_| {}).unwrap().mesh;
        let what = format!("{placement:?}");
        let triangles = out.triangle_count();
        assert!(triangles <= (0.2 * mesh.triangle_count() as f64).ceil() as usize + 8, "{what}: {triangles}");
        out.check_faces().unwrap();
        // Both sides of the seam keep the same edges: the seam did not open.
        let (left_seam, right_seam) = (seam_edges(&out, &right, false), seam_edges(&out, &right, true));
        assert_eq!(left_seam, right_seam, "{what}: the seam opened");
        assert_eq!(left_seam, input_seam, "{what}: seam vertices moved or went");
        let uv = out.attribute("TEXCOORD_0").expect("UVs kept");
        let nrm = out.attribute("NORMAL").expect("normals kept");
        assert_eq!(uv.len(), out.vertex_count());
        for (f, t) in out.triangulate().tris.iter().enumerate() {
            // No triangle mixes the islands: its corners' U values are all on one side.
            let side = right[t[0] as usize];
            assert!(t.iter().all(|&v| right[v as usize] == side), "{what}: triangle {t:?} mixes islands");
            for &v in t {
                let (u, p) = (uv.get(v as usize, 0) as f32, out.positions[v as usize]);
                if side {
                    assert!((0.55..=1.0).contains(&u), "{what}: {u}");
                } else {
                    assert!((0.0..=0.45).contains(&u), "{what}: {u}");
                }
                // U follows x inside an island (interpolated along the collapsed edge).
                let tolerance = if placement == Placement::Endpoint { 1e-6 } else { 0.03 };
                assert!((u - u_of(p[0], side)).abs() <= tolerance, "{what}: u {u} at x {}", p[0]);
                assert_eq!(nrm.value(v as usize), vec![0.0, 0.0, 1.0]);
            }
            // Groups follow their triangles.
            assert_eq!(out.group_of(f), side as u32, "{what}: group of triangle {f}");
        }
        assert_eq!(out.groups.len(), 2);
        if placement == Placement::Endpoint {
            // Endpoint: every output corner is an input vertex, attributes and all.
            let input_uv = mesh.attribute("TEXCOORD_0").unwrap();
            for v in out.face_indices.iter().map(|&v| v as usize) {
                assert_eq!(out.positions[v], mesh.positions[v]);
                assert_eq!(uv.bytes(v), input_uv.bytes(v));
            }
        }
    }
}

#[test]
fn without_attributes_nothing_is_locked() {
    // The same mesh without attributes: its seam is just a cut, free to move, so it
    // simplifies further than with the seam kept.
    let (mut mesh, _) = seamed();
    let options = Options::default().target(Target::Ratio(0.02));
    let with = simplify(&mesh, &options, &mut |_| {}).unwrap().triangles_out();
    mesh.attributes.clear();
    let without = simplify(&mesh, &options, &mut |_| {}).unwrap().triangles_out();
    assert!(without < with, "{without} vs {with}");
}

#[test]
fn moved_survivors_get_unit_normals_between_their_ends() {
    // On a unit sphere the normal is the position; optimal placement moves survivors
    // and blends their normals, which come back unit and near the new position's.
    let mut mesh = stripkit::gen::icosphere(3);
    let normals: Vec<f32> = mesh.positions.iter().flatten().copied().collect();
    mesh.attributes.push(Attribute::from_f32("NORMAL", 3, &normals));
    let options = Options::default().target(Target::Ratio(0.1)).placement(Placement::Optimal);
    let out = simplify(&mesh, &options, &mut |_| {}).unwrap().mesh;
    let n = out.attribute("NORMAL").unwrap();
    let mut moved = 0;
    for v in out.face_indices.iter().map(|&v| v as usize) {
        let a = n.value(v);
        let len = a.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!((len - 1.0).abs() < 1e-6, "normal {v} has length {len}");
        let p = out.positions[v].map(|x| x as f64);
        let plen = p.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!((0..3).map(|c| a[c] * p[c]).sum::<f64>() / plen > 0.97, "normal {v} points away");
        moved += (out.positions[v] != mesh.positions[v]) as usize;
    }
    assert!(moved > 0, "optimal placement moved no vertex");
}

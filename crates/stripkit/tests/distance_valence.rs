//! Distances on meshes with one vertex or edge of very high valence (issue #16):
//! their long thin triangles meeting at one vertex or edge once made every
//! closest-point query visit most triangles. These tests check the results, not
//! times (see docs/experiments/valence-simplify.md): a mesh is at distance 0 from
//! itself, a lifted copy at the lift, and the hierarchy's answers (with its oriented
//! boxes) equal a brute-force search.

mod valence_meshes;

use stripkit::distance::bvh::{point_triangle_distance2, Bvh};
use stripkit::distance::{distance, sample_surface};
use stripkit::Mesh;
use valence_meshes::{edge_fan, polygon, star};
use stripkit_testkit::XorShift64;

fn lifted(m: &Mesh, dz: f32) -> Mesh {
    let mut out = m.clone();
    out.positions.iter_mut().for_each(|p| p[2] += dz);
    out
}

#[test]
fn each_mesh_is_at_distance_zero_from_itself() {
    for (name, m) in [("star", star(20_000)), ("edge fan", edge_fan(10_000)), ("polygon", polygon(50_000))] {
        let d = distance(&m, &m, 20_000).unwrap();
        assert!(d.hausdorff < 1e-5, "{name}: {d:?}");
        assert!(d.rms < 1e-6, "{name}: {d:?}");
        assert!(d.diagonal > 2.0, "{name}: {d:?}");
    }
}

#[test]
fn a_lifted_star_is_at_the_lift() {
    let m = star(20_000);
    let d = distance(&m, &lifted(&m, 0.25), 20_000).unwrap();
    assert!((d.hausdorff - 0.25).abs() < 1e-6, "{d:?}");
    assert!((d.rms - 0.25).abs() < 1e-6, "{d:?}");
}

/// The oriented boxes only prune: every answer equals the brute-force minimum, for
/// points on the surface and off it (above, beside, near the shared vertex or edge).
#[test]
fn the_hierarchy_agrees_with_brute_force_on_fans() {
    for m in [star(3_000), edge_fan(3_000), polygon(3_000)] {
        let tris = m.triangulate().tris;
        let bvh = Bvh::build(&m.positions, &tris);
        let corners: Vec<[[f64; 3]; 3]> =
            tris.iter().map(|t| t.map(|v| m.positions[v as usize].map(f64::from))).collect();
        let mut points = sample_surface(&m, 150, 11);
        let mut rng = XorShift64(0x9E37_79B9_7F4A_7C15);
        let mut r = move || rng.unit() * 2.4 - 1.2;
        points.extend((0..150).map(|_| [r(), r(), r()]));
        points.extend((0..50).map(|_| [r() * 1e-3, r() * 1e-3, 0.5 + r() * 1e-3]));
        let mut stack = Vec::new();
        for (i, &p) in points.iter().enumerate() {
            let brute = corners.iter().map(|c| point_triangle_distance2(p, c)).fold(f64::INFINITY, f64::min);
            let (d, _) = bvh.closest(p, i % tris.len(), &mut stack);
            assert_eq!(d, brute, "point {p:?}");
        }
    }
}

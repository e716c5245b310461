//! Hausdorff and RMS distances checked analytically on planes and spheres.

mod simplify_meshes;

use simplify_meshes::*;
use stripkit::distance::{distance, sample_surface};
use stripkit::Mesh;

fn translated(m: &Mesh, d: [f32; 3]) -> Mesh {
    let mut out = m.clone();
    for p in out.positions.iter_mut() {
        for k in 0..3 {
            p[k] += d[k];
        }
    }
    out
}

#[test]
fn a_mesh_is_at_distance_zero_from_itself() {
    let m = shuffled(&bumpy_sphere(3), 2);
    let d = distance(&m, &m, 20_000).unwrap();
    assert!(d.hausdorff < 1e-6, "{d:?}");
    assert!(d.rms < 1e-7);
    assert!(d.diagonal > 2.0 && d.diagonal < 4.5);
}

#[test]
fn plane_lifted_along_its_normal_is_at_the_lift() {
    let m = grid(8, 8, |_, _| 0.0);
    let d = distance(&m, &translated(&m, [0.0, 0.0, 0.375]), 10_000).unwrap();
    assert!((d.hausdorff - 0.375).abs() < 1e-6, "{d:?}");
    assert!((d.rms - 0.375).abs() < 1e-6, "{d:?}");
    assert!((d.diagonal - 2f64.sqrt()).abs() < 1e-6);
}

#[test]
fn plane_slid_in_its_own_plane() {
    // Unit square slid by s along x: a quarter strip of each square is at distance
    // (s - x) from the other; Hausdorff s, mean square s^3 / 3.
    let s = 0.25;
    let m = grid(16, 16, |_, _| 0.0);
    let d = distance(&m, &translated(&m, [s as f32, 0.0, 0.0]), 200_000).unwrap();
    assert!((d.hausdorff - s).abs() < 2e-3, "{d:?}");
    let rms = (s * s * s / 3.0f64).sqrt();
    assert!((d.rms - rms).abs() < 0.01 * rms, "rms {} expected {rms}", d.rms);
    assert!((d.a_to_b.rms - d.b_to_a.rms).abs() < 0.01 * rms);
}

#[test]
fn concentric_spheres_are_the_radius_difference_apart() {
    // Finely tessellated spheres of radius 1 and 1.2: every distance is about 0.2
    // (the chords shave at most 1 - cos(half edge angle) off the radius).
    let a = sphere(5, |_| 1.0);
    let b = sphere(5, |_| 1.2);
    let d = distance(&a, &b, 20_000).unwrap();
    assert!(d.hausdorff > 0.19 && d.hausdorff < 0.21, "{d:?}");
    assert!(d.rms > 0.19 && d.rms < 0.21, "{d:?}");
}

#[test]
fn sampling_is_area_weighted_and_deterministic() {
    // Two squares side by side, one four times the area of the other.
    let m = Mesh::from_triangles(
        vec![[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.], [1., 0., 0.], [3., 0., 0.], [3., 2., 0.], [1., 2., 0.]],
        &[[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]],
    );
    let p = sample_surface(&m, 10_000, 9);
    assert_eq!(p, sample_surface(&m, 10_000, 9));
    let small = p.iter().filter(|q| q[0] < 1.0).count();
    assert!((small as i64 - 2000).abs() <= 2, "{small}");
    assert!(p.iter().all(|q| q[2] == 0.0 && q[0] >= 0.0 && q[0] <= 3.0));
}

#[test]
fn empty_mesh_is_an_error() {
    assert!(distance(&Mesh::new(), &grid(2, 2, |_, _| 0.0), 10).is_err());
}

#[test]
fn sample_counts_out_of_range_are_refused_before_allocating() {
    use stripkit::distance::MAX_SAMPLES;
    let m = grid(2, 2, |_, _| 0.0);
    // 10^11 samples once asked for 2.4 TB; 0 gave NaN figures.
    for n in [0, MAX_SAMPLES + 1, 100_000_000_000, usize::MAX] {
        let e = distance(&m, &m, n).unwrap_err().to_string();
        assert!(e.contains(&format!("{n} samples per surface is out of range: 1 to {MAX_SAMPLES}")), "{e}");
    }
    assert!(distance(&m, &m, 1).is_ok());
}

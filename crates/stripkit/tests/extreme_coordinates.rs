//! Meshes far from unit size (issue #30, class 6): the simplifier and the surface
//! distance give at 1e20 and 1e-20 what they give at 1 (in the input's units).

use stripkit::distance::distance;
use stripkit::simplify::{simplify, Options, Placement, Target};
use stripkit::Mesh;

/// A bumpy, irregular height field (few ties between collapse costs; a boundary, so
/// the boundary planes count too), off the origin.
fn bumpy() -> Mesh {
    let mut m = stripkit::gen::grid(30, 20);
    for (i, p) in m.positions.iter_mut().enumerate() {
        let w = ((i as f32 * 12.9898).sin() * 43758.547).fract();
        *p = [p[0] * 0.1 + 0.7, p[1] * 0.1 - 0.2, (p[0] * 0.3).sin() * 0.4 + w * 0.05];
    }
    m
}

fn scaled(m: &Mesh, s: f64) -> Mesh {
    let mut m = m.clone();
    for p in &mut m.positions {
        *p = p.map(|x| (x as f64 * s) as f32);
    }
    m
}

fn pairs(r: &stripkit::simplify::Simplified) -> Vec<(u32, u32)> {
    r.sequence.collapses.iter().map(|c| (c.removed, c.kept)).collect()
}

#[test]
fn simplify_is_the_same_at_any_scale() {
    let base = bumpy();
    for placement in [Placement::Endpoint, Placement::Optimal] {
        let options = Options::default().target(Target::Ratio(0.1)).placement(placement);
        let one = simplify(&base, &options, &mut |_| {}).unwrap();
        assert!(one.max_error.is_finite() && one.max_error > 0.0);
        // Powers of two: bit for bit the same work, errors scaled by the square.
        for k in [70, -70, 100, -100] {
            let s = 2f64.powi(k);
            let r = simplify(&scaled(&base, s), &options, &mut |_| {}).unwrap();
            assert_eq!(pairs(&r), pairs(&one), "{placement:?} x 2^{k}");
            assert_eq!(r.max_error, one.max_error * s * s, "{placement:?} x 2^{k}");
            assert_eq!(r.mesh.positions, scaled(&one.mesh, s).positions, "{placement:?} x 2^{k}");
        }
        // Powers of ten round the positions differently: the same triangle count and
        // about the same relative error.
        for s in [1e20, 1e-20, 1e30, 1e-30] {
            let r = simplify(&scaled(&base, s), &options, &mut |_| {}).unwrap();
            assert_eq!(r.triangles_out(), one.triangles_out(), "{placement:?} x {s}");
            let rel = r.max_error / (s * s) / one.max_error;
            assert!(r.max_error.is_finite() && (rel - 1.0).abs() < 0.01, "{placement:?} x {s}: {rel}");
        }
    }
}

#[test]
fn an_error_bound_and_a_pair_distance_are_in_the_input_units() {
    let base = bumpy();
    let one = simplify(&base, &Options::default().target(Target::Ratio(0.2)), &mut |_| {}).unwrap();
    let bound = one.max_error;
    let s = 2f64.powi(80);
    let options = Options::default().target(Target::Error(bound)).pair_distance(Some(0.01));
    let a = simplify(&base, &options, &mut |_| {}).unwrap();
    let options = Options::default().target(Target::Error(bound * s * s)).pair_distance(Some(0.01 * s));
    let b = simplify(&scaled(&base, s), &options, &mut |_| {}).unwrap();
    assert_eq!(pairs(&a), pairs(&b));
    assert!(a.sequence.collapses.len() > 100);
}

#[test]
fn distance_is_the_same_at_any_scale() {
    let base = bumpy();
    let coarse = simplify(&base, &Options::default().target(Target::Ratio(0.2)), &mut |_| {}).unwrap().mesh;
    let one = distance(&base, &coarse, 20_000).unwrap();
    assert!(one.hausdorff > 0.0);
    for s in [1e20, 1e-20, 1e36, 1e-36] {
        let d = distance(&scaled(&base, s), &scaled(&coarse, s), 20_000).unwrap();
        for (a, b) in [(d.relative(d.hausdorff), one.relative(one.hausdorff)), (d.relative(d.rms), one.relative(one.rms))] {
            assert!(a.is_finite() && (a / b - 1.0).abs() < 0.01, "x {s}: {a} against {b}");
        }
    }
}

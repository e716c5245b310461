//! The small vector helpers shared by the geometry code (quadrics, distances, the
//! single-strip builder, the culling tree, normals for the matching weights and STL):
//! f64, plus the f32 normal of the sites that compute in the file's precision.

/// A 3-vector of f64.
pub type V3 = [f64; 3];

#[inline]
pub(crate) fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
#[inline]
pub(crate) fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
#[inline]
pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
#[inline]
pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
#[inline]
pub(crate) fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}
/// `a` scaled to unit length; `None` for a zero or non-finite vector.
#[inline]
pub(crate) fn unit(a: V3) -> Option<V3> {
    let n = norm(a);
    (n > 0.0 && n.is_finite()).then(|| [a[0] / n, a[1] / n, a[2] / n])
}
/// Twice the area vector of triangle (a, b, c): its direction is the face normal.
#[inline]
pub(crate) fn tri_normal(a: V3, b: V3, c: V3) -> V3 {
    cross(sub(b, a), sub(c, a))
}
/// [`tri_normal`] computed in f32 throughout (positions as a file stores them).
#[inline]
pub(crate) fn tri_normal_f32(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> [f32; 3] {
    let (u, v) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
    [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
}

/// Extents the f32 parts of the geometry code (stored positions, heap keys of squared
/// distances) hold comfortably: from 2^-16 to 2^16.
const PLAIN_EXTENT: (f64, f64) = (1.0 / 65536.0, 65536.0);

/// The power of two that brings the largest extent of the finite `positions` near 1
/// (into 1..2) when it lies outside 2^-16 ..= 2^16, else 1 (and 1 for no extent).
/// Multiplying by a power of two rounds nothing (short of f32's subnormals), so work
/// done on scaled positions and scaled back is the work done at any scale.
pub fn unit_scale(positions: &[[f32; 3]]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in positions.iter().filter(|p| p.iter().all(|x| x.is_finite())) {
        for d in 0..3 {
            lo[d] = lo[d].min(p[d] as f64);
            hi[d] = hi[d].max(p[d] as f64);
        }
    }
    let extent = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    if !extent.is_finite() || extent == 0.0 || (PLAIN_EXTENT.0..=PLAIN_EXTENT.1).contains(&extent) {
        return 1.0;
    }
    // f32 spans 2^-149 ..= 2^127: the scale and its inverse stay normal f32 numbers.
    2f64.powi(-(extent.log2().floor().clamp(-126.0, 126.0) as i32))
}

#[cfg(test)]
mod unit_scale_tests {
    use super::unit_scale;

    #[test]
    fn unit_scale_is_a_power_of_two_outside_the_plain_extents() {
        let cube = |s: f32| [[0.0, 0.0, 0.0], [s, s, s], [f32::NAN, 0.0, 0.0]];
        for s in [1.0, 0.001, 1000.0, 60000.0] {
            assert_eq!(unit_scale(&cube(s)), 1.0, "{s}");
        }
        for s in [1e18f32, 1e-18, 1e30, 1e-30, f32::MAX, 1e-44] {
            let k = unit_scale(&cube(s));
            assert_eq!(k.log2().fract(), 0.0, "a power of two: {k}");
            // The scale and its inverse are normal single-precision numbers.
            assert!((k as f32).is_normal() && (1.0 / k as f32).is_normal(), "{k}");
            let e = s * k as f32;
            assert!((1.0..2.0).contains(&e) || s < 1e-37 || s == f32::MAX, "{s} -> {e}");
            assert!(e.is_finite() && e > 0.0);
        }
        assert_eq!(unit_scale(&[]), 1.0);
    }
}

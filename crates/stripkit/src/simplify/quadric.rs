//! Quadrics (Garland and Heckbert 1997) and the small f64 vector helpers they need.

pub use crate::vec3::V3;
pub(crate) use crate::vec3::{cross, dot, norm, sub, tri_normal};

/// A symmetric 4x4 quadric `Q` measuring the sum of weighted squared distances to
/// planes: `Q(p) = p^T A p + 2 b.p + c`, stored as its ten distinct entries.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Quadric {
    /// `[a00, a01, a02, a11, a12, a22, b0, b1, b2, c]`.
    pub m: [f64; 10],
}

impl Quadric {
    /// The quadric of the plane `n.p + d = 0` (n of unit length), times `weight`.
    pub fn plane(n: V3, d: f64, weight: f64) -> Quadric {
        let w = weight;
        Quadric {
            m: [
                w * n[0] * n[0],
                w * n[0] * n[1],
                w * n[0] * n[2],
                w * n[1] * n[1],
                w * n[1] * n[2],
                w * n[2] * n[2],
                w * n[0] * d,
                w * n[1] * d,
                w * n[2] * d,
                w * d * d,
            ],
        }
    }

    /// Adds another quadric in place.
    #[inline]
    pub fn add(&mut self, o: &Quadric) {
        for i in 0..10 {
            self.m[i] += o.m[i];
        }
    }

    /// The sum of two quadrics.
    #[inline]
    pub fn sum(&self, o: &Quadric) -> Quadric {
        let mut q = *self;
        q.add(o);
        q
    }

    /// `Q(p)`, clamped at zero (rounding can make it slightly negative).
    #[inline]
    pub fn eval(&self, p: V3) -> f64 {
        let m = &self.m;
        let [x, y, z] = p;
        let v = m[0] * x * x + 2.0 * m[1] * x * y + 2.0 * m[2] * x * z + m[3] * y * y + 2.0 * m[4] * y * z
            + m[5] * z * z
            + 2.0 * (m[6] * x + m[7] * y + m[8] * z)
            + m[9];
        v.max(0.0)
    }

    /// The point minimising `Q`, or `None` when `A` is (nearly) singular.
    pub fn minimizer(&self) -> Option<V3> {
        let m = &self.m;
        let (a, b, c, d, e, f) = (m[0], m[1], m[2], m[3], m[4], m[5]);
        // Cofactors of the symmetric matrix [[a b c][b d e][c e f]].
        let c00 = d * f - e * e;
        let c01 = c * e - b * f;
        let c02 = b * e - c * d;
        let det = a * c00 + b * c01 + c * c02;
        let scale = (a + d + f) / 3.0;
        #[allow(clippy::neg_cmp_op_on_partial_ord)] // also true for NaN, on purpose
        if !(det.abs() > 1e-9 * scale * scale * scale) || scale <= 0.0 {
            return None;
        }
        let c11 = a * f - c * c;
        let c12 = b * c - a * e;
        let c22 = a * d - b * b;
        let r = [-m[6], -m[7], -m[8]];
        let inv = 1.0 / det;
        let p = [
            (c00 * r[0] + c01 * r[1] + c02 * r[2]) * inv,
            (c01 * r[0] + c11 * r[1] + c12 * r[2]) * inv,
            (c02 * r[0] + c12 * r[1] + c22 * r[2]) * inv,
        ];
        if p.iter().all(|x| x.is_finite()) {
            Some(p)
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn three_planes_meet_in_their_corner() {
        let mut q = Quadric::plane([1.0, 0.0, 0.0], -1.0, 1.0); // x = 1
        q.add(&Quadric::plane([0.0, 1.0, 0.0], -2.0, 2.0)); // y = 2
        q.add(&Quadric::plane([0.0, 0.0, 1.0], 3.0, 0.5)); // z = -3
        let p = q.minimizer().unwrap();
        assert!((p[0] - 1.0).abs() < 1e-12 && (p[1] - 2.0).abs() < 1e-12 && (p[2] + 3.0).abs() < 1e-12);
        assert!(q.eval(p) < 1e-20);
        // Distance 2 from x = 1 (weight 1) and 0 from the others.
        assert!((q.eval([3.0, 2.0, -3.0]) - 4.0).abs() < 1e-12);
    }

    #[test]
    fn one_plane_is_singular() {
        assert!(Quadric::plane([0.0, 0.0, 1.0], 0.0, 1.0).minimizer().is_none());
    }
}

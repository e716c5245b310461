//! The bounds of a set of triangles, a normal cone and a bounding sphere, and the
//! facing test of an eye point against them; the running sums and the cone merge the
//! tree is built with.

use super::Facing;
use crate::vec3::{add, cross, dot, norm, sub, tri_normal, unit};

/// Conservative bounds of a set of triangles: a cone around `axis` of half-angle
/// `angle` that holds every triangle's unit normal, and a sphere that holds every
/// vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// Unit axis of the cone ([`Bounds::of_triangles`]: the area-weighted average
    /// normal).
    pub axis: [f32; 3],
    /// Half-angle of the normal cone, radians, in `[0, pi]`; negative for an empty
    /// cone (only zero-area triangles, which draw nothing): such bounds face away.
    pub angle: f32,
    /// `cos(angle)`, for [`Bounds::classify`].
    pub cos_angle: f32,
    /// `sin(angle)`.
    pub sin_angle: f32,
    /// Centroid of the vertices.
    pub center: [f32; 3],
    /// Radius of the sphere around `center` that holds every vertex.
    pub radius: f32,
}

impl Bounds {
    /// Bounds from an axis, a half-angle and a sphere (the angle is clamped to `pi`).
    pub fn new(axis: [f32; 3], angle: f32, center: [f32; 3], radius: f32) -> Self {
        let a = angle.min(std::f32::consts::PI);
        Bounds { axis, angle: a, cos_angle: a.cos(), sin_angle: a.sin().max(0.0), center, radius }
    }

    /// The tightest bounds of `triangles` (indices into `positions`) around their
    /// average normal and centroid, widened by `slack` (radians and length) against
    /// rounding.
    pub fn of_triangles(triangles: &[[u32; 3]], positions: &[[f32; 3]], slack: [f64; 2]) -> Self {
        let mut acc = Acc::default();
        for t in triangles {
            acc.add(t, positions);
        }
        acc.finish(triangles, positions, slack)
    }

    /// How the triangles these bounds hold face the eye point `eye` (perspective).
    ///
    /// With `d = center - eye`, `D = |d|`, `b` the angle between `axis` and `d`, `a`
    /// the cone's half-angle and `r` the radius: a triangle with unit normal `m` in the
    /// cone and a point `p` in the sphere faces away when `m . (p - eye) >= 0`. Over
    /// the sphere, `min m . (p - eye) = m . d - r`; over the cone, `min m . d =
    /// D cos(b + a)` when `b + a <= pi` (else `-D`). So every triangle faces away when
    ///
    /// `B = D cos(b + a) - r = (axis . d) cos a - sqrt(D^2 - (axis . d)^2) sin a - r >= 0`
    ///
    /// (and `cos a * D >= -(axis . d)`, i.e. `b + a <= pi`), and every triangle faces
    /// the eye when `F`, the same with `-d`, is `> 0`; otherwise [`Facing::Split`]. This
    /// is exact for the cone and the sphere (it misclassifies no triangle they could
    /// hold) and looser than meshoptimizer's apex-free test `axis . d >= D sin a + r`,
    /// which implies it. It is monotone: bounds that hold other bounds face the same way
    /// or are split. `B` and `F` are minima of functions of the eye that are
    /// 1-Lipschitz, so the answer holds while the eye moves less than `|B|` (`|F|`, or
    /// `min(-B, -F)` for a split): [`RenderFront`](super::RenderFront) skips the test then.
    #[inline]
    pub fn classify(&self, eye: [f32; 3]) -> Facing {
        if self.angle < 0.0 {
            return Facing::Back;
        }
        classify(self.center, self.radius, self.axis, self.cos_angle, self.sin_angle, eye).0
    }
}

/// [`Bounds::classify`] on the parts of non-empty bounds, with the distance the eye may
/// move (exactly; before rounding) without changing the answer.
#[inline(always)]
pub(super) fn classify(center: [f32; 3], r: f32, axis: [f32; 3], cos_a: f32, sin_a: f32, eye: [f32; 3]) -> (Facing, f32) {
    let d = [center[0] - eye[0], center[1] - eye[1], center[2] - eye[2]];
    let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let dn = axis[0] * d[0] + axis[1] * d[1] + axis[2] * d[2];
    let dd = d2.sqrt();
    // D sin(b) sin(a), and the value of either side where b + a passes pi.
    let s = (d2 - dn * dn).max(0.0).sqrt() * sin_a;
    let far = -dd - r;
    let back = if cos_a * dd >= -dn { dn * cos_a - s - r } else { far };
    let front = if cos_a * dd >= dn { -dn * cos_a - s - r } else { far };
    if back >= 0.0 {
        (Facing::Back, back)
    } else if front > 0.0 {
        (Facing::Front, front)
    } else {
        (Facing::Split, (-back).min(-front))
    }
}

/// A margin of [`classify`] less a bound on its rounding error: how far the eye may move
/// with the f32 test still giving the same answer (negative: no distance).
#[inline(always)]
pub(super) fn safe_reach(margin: f32, center: [f32; 3], r: f32, eye: [f32; 3]) -> f32 {
    let d = [center[0] - eye[0], center[1] - eye[1], center[2] - eye[2]];
    let scale = d[0].abs() + d[1].abs() + d[2].abs() + r;
    margin - 1e-5 * scale - f32::MIN_POSITIVE
}

/// Running sums for the bounds of a set of triangles.
#[derive(Clone, Copy, Default)]
pub(super) struct Acc {
    pub(super) normal: [f64; 3],
    pub(super) vertex_sum: [f64; 3],
    pub(super) vertices: f64,
    pub(super) area: f64,
}

fn angle_between(a: [f64; 3], b: [f64; 3]) -> f64 {
    // atan2 of |a x b| and a . b: accurate at small angles.
    norm(cross(a, b)).atan2(dot(a, b))
}
pub(super) fn p64(p: [f32; 3]) -> [f64; 3] {
    [p[0] as f64, p[1] as f64, p[2] as f64]
}
pub(super) fn f32s(a: [f64; 3]) -> [f32; 3] {
    [a[0] as f32, a[1] as f32, a[2] as f32]
}

/// The (area-scaled) normal of a triangle: `(b - a) x (c - a)`.
pub(crate) fn triangle_normal(t: &[u32; 3], positions: &[[f32; 3]]) -> [f64; 3] {
    let [a, b, c] = t.map(|v| p64(positions[v as usize]));
    tri_normal(a, b, c)
}

impl Acc {
    pub(super) fn add(&mut self, t: &[u32; 3], positions: &[[f32; 3]]) {
        let n = triangle_normal(t, positions);
        self.normal = add(self.normal, n);
        self.area += norm(n);
        for &v in t {
            self.vertex_sum = add(self.vertex_sum, p64(positions[v as usize]));
            self.vertices += 1.0;
        }
    }

    fn center(&self) -> [f64; 3] {
        let n = self.vertices.max(1.0);
        [self.vertex_sum[0] / n, self.vertex_sum[1] / n, self.vertex_sum[2] / n]
    }

    /// Exact bounds of `triangles` around the average normal and the centroid.
    pub(super) fn finish(&self, triangles: &[[u32; 3]], positions: &[[f32; 3]], slack: [f64; 2]) -> Bounds {
        let c = self.center();
        let mut radius = 0.0f64;
        let mut normals = triangles.iter().filter_map(|t| unit(triangle_normal(t, positions))).peekable();
        let axis = unit(self.normal).or_else(|| normals.peek().copied());
        let mut angle = -1.0f64;
        if let Some(axis) = axis {
            for m in normals {
                angle = angle.max(angle_between(axis, m));
            }
        }
        for t in triangles {
            for &v in t {
                radius = radius.max(norm(sub(p64(positions[v as usize]), c)));
            }
        }
        let axis = axis.unwrap_or([0.0, 0.0, 1.0]);
        let angle = if angle < 0.0 { -1.0 } else { angle + slack[0] };
        let b = Bounds::new(f32s(axis), angle as f32, f32s(c), (radius + slack[1]) as f32);
        if angle < 0.0 {
            Bounds { angle: -1.0, ..b }
        } else {
            b
        }
    }
}

/// Build state of a node: its sums and its exact-in-f64 bounds.
#[derive(Clone, Copy)]
pub(super) struct Work {
    pub(super) acc: Acc,
    pub(super) axis: [f64; 3],
    pub(super) angle: f64, // < 0: empty cone
    pub(super) center: [f64; 3],
    pub(super) radius: f64,
}

impl Work {
    pub(super) fn merge(a: &Work, b: &Work, slack: [f64; 2]) -> Work {
        let mut acc = a.acc;
        acc.normal = add(acc.normal, b.acc.normal);
        acc.vertex_sum = add(acc.vertex_sum, b.acc.vertex_sum);
        acc.vertices += b.acc.vertices;
        acc.area += b.acc.area;
        let (axis, angle) = match (a.angle >= 0.0, b.angle >= 0.0) {
            (false, false) => (a.axis, -1.0),
            (true, false) => (a.axis, a.angle),
            (false, true) => (b.axis, b.angle),
            (true, true) => {
                let (axis, angle) = enclosing_cone(a.axis, a.angle, b.axis, b.angle);
                (axis, (angle + slack[0]).min(std::f64::consts::PI))
            }
        };
        let center = acc.center();
        let radius = (norm(sub(center, a.center)) + a.radius).max(norm(sub(center, b.center)) + b.radius) + slack[1];
        Work { acc, axis, angle, center, radius }
    }

    pub(super) fn bounds(&self) -> Bounds {
        let b = Bounds::new(f32s(self.axis), self.angle as f32, f32s(self.center), self.radius as f32);
        if self.angle < 0.0 {
            Bounds { angle: -1.0, ..b }
        } else {
            b
        }
    }
}

/// The smallest cone that holds the cones `(a, x)` and `(b, y)` (unit axes,
/// half-angles): its axis on the arc from `a` to `b`, half-angle `(t + x + y) / 2` for
/// the angle `t` between the axes, unless one cone holds the other.
fn enclosing_cone(a: [f64; 3], x: f64, b: [f64; 3], y: f64) -> ([f64; 3], f64) {
    let t = angle_between(a, b);
    if t + y <= x {
        return (a, x);
    }
    if t + x <= y {
        return (b, y);
    }
    let angle = (t + x + y) / 2.0;
    if angle >= std::f64::consts::PI || t.sin() < 1e-9 {
        // Opposite axes (or nearly): keep the one and cover the other.
        return (a, (t + y).max(x).min(std::f64::consts::PI));
    }
    // Rotate a towards b by angle - x.
    let u = angle - x;
    let (su, sr, st) = (u.sin(), (t - u).sin(), t.sin());
    let axis = unit([(sr * a[0] + su * b[0]) / st, (sr * a[1] + su * b[1]) / st, (sr * a[2] + su * b[2]) / st]).unwrap_or(a);
    // Rounding: make sure both cones are held.
    let angle = angle.max(angle_between(axis, a) + x).max(angle_between(axis, b) + y);
    (axis, angle)
}

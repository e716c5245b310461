//! The view frustum of [`CullOptions::frustum`](super::CullOptions::frustum): six
//! planes, and where a bounding sphere lies against them.

use crate::vec3::{add, cross, dot, sub, unit};

/// A view frustum: six planes `(n, d)` with unit `n` pointing inside, a point `p`
/// inside all of them when `n . p + d >= 0` for each.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Frustum {
    /// Left, right, bottom, top, near, far.
    pub planes: [[f32; 4]; 6],
}

/// Where a sphere lies against a [`Frustum`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// Wholly outside one plane.
    Outside,
    /// Wholly inside every plane.
    Inside,
    /// Neither: it crosses a plane.
    Crossing,
}

impl Frustum {
    /// The frustum of a perspective camera at `eye` looking at `target` with `up`
    /// (any vector not along the view), `fov_y` degrees of vertical field of view,
    /// `aspect` = width / height, and near and far distances. A degenerate camera
    /// (target at the eye, up along the view) gives `None`.
    pub fn perspective(
        eye: [f32; 3],
        target: [f32; 3],
        up: [f32; 3],
        fov_y: f32,
        aspect: f32,
        near: f32,
        far: f32,
    ) -> Option<Frustum> {
        if !(fov_y > 0.0 && fov_y < 179.0 && aspect > 0.0 && near >= 0.0 && far > near && far.is_finite()) {
            return None;
        }
        let p = |a: [f32; 3]| a.map(|x| x as f64);
        let e = p(eye);
        let f = unit(sub(p(target), e))?;
        let r = unit(cross(f, p(up)))?;
        let u = cross(r, f);
        let half = (fov_y as f64).to_radians() / 2.0;
        let (ty, tx) = (half.tan(), half.tan() * aspect as f64);
        // A direction v is inside the right plane when v . r <= tx (v . f), and so on:
        // inward normals of the four side planes through the eye.
        let scaled = |t: f64| [f[0] * t, f[1] * t, f[2] * t];
        let normals = [
            unit(add(scaled(tx), r))?,
            unit(sub(scaled(tx), r))?,
            unit(add(scaled(ty), u))?,
            unit(sub(scaled(ty), u))?,
        ];
        let mut planes = [[0f32; 4]; 6];
        for (k, n) in normals.iter().enumerate() {
            planes[k] = [n[0] as f32, n[1] as f32, n[2] as f32, -dot(*n, e) as f32];
        }
        let nf = f;
        planes[4] = [nf[0] as f32, nf[1] as f32, nf[2] as f32, (-dot(nf, e) - near as f64) as f32];
        planes[5] = [-nf[0] as f32, -nf[1] as f32, -nf[2] as f32, (dot(nf, e) + far as f64) as f32];
        Some(Frustum { planes })
    }

    /// Where the sphere `(center, radius)` lies.
    #[inline]
    pub fn side(&self, center: [f32; 3], radius: f32) -> Side {
        let mut crossing = false;
        let scale = center[0].abs() + center[1].abs() + center[2].abs() + radius;
        for pl in &self.planes {
            let s = pl[0] * center[0] + pl[1] * center[1] + pl[2] * center[2] + pl[3];
            // A little slack against rounding: never call outside what may touch.
            let slack = 1e-5 * (scale + pl[3].abs());
            if s < -radius - slack {
                return Side::Outside;
            }
            if s < radius + slack {
                crossing = true;
            }
        }
        if crossing {
            Side::Crossing
        } else {
            Side::Inside
        }
    }

    /// Whether the point may be inside (within the same slack as [`Frustum::side`]).
    pub fn holds(&self, p: [f32; 3]) -> bool {
        self.side(p, 0.0) != Side::Outside
    }
}


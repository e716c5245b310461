//! Cameras: a look-at view with a perspective projection, fitted to a bounding box or
//! placed at a given eye around a bounding sphere (the eyes of the helix camera path
//! come from the library, `stripkit::cull::helix_eyes`).

use glam::{Mat4, Vec3};

/// A perspective camera looking at a point, +Y up unless told otherwise.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub eye: [f32; 3],
    /// The point looked at.
    pub target: [f32; 3],
    /// Up direction.
    pub up: [f32; 3],
    /// Vertical field of view in degrees.
    pub fov_y_degrees: f32,
    /// Near plane distance.
    pub near: f32,
    /// Far plane distance.
    pub far: f32,
}

impl Camera {
    /// A camera looking at the box `[min, max]` from `direction` (from the centre towards
    /// the eye), far enough for the bounding sphere to fill a 30 degree field of view.
    pub fn fit(min: [f32; 3], max: [f32; 3], direction: [f32; 3]) -> Self {
        let (lo, hi) = (Vec3::from(min), Vec3::from(max));
        let center = (lo + hi) * 0.5;
        let radius = ((hi - lo).length() * 0.5).max(1e-6);
        let fov = 30.0f32;
        let dist = radius / (fov.to_radians() * 0.5).sin() * 1.02;
        let dir = Vec3::from(direction).try_normalize().unwrap_or(Vec3::Z);
        let up = if dir.cross(Vec3::Y).length_squared() < 1e-6 { Vec3::Z } else { Vec3::Y };
        Camera {
            eye: (center + dir * dist).into(),
            target: center.into(),
            up: up.into(),
            fov_y_degrees: fov,
            near: (dist - radius * 1.1).max(radius * 0.01),
            far: dist + radius * 1.1,
        }
    }

    /// A camera at `eye` looking at the centre of the bounding sphere (`center`,
    /// `radius`), +Y up, with a 60 degree vertical field of view and the near and far
    /// planes 1.01 radii either side of the centre (near at least 0.01 radii): the
    /// camera of each eye of the helix camera path (`stripkit::cull::helix_eyes`),
    /// which keeps the whole sphere in view.
    pub fn around(eye: [f32; 3], center: [f32; 3], radius: f32) -> Self {
        let r = radius.max(1e-6);
        let dist = (Vec3::from(eye) - Vec3::from(center)).length();
        Camera {
            eye,
            target: center,
            up: [0.0, 1.0, 0.0],
            fov_y_degrees: 60.0,
            near: (dist - r * 1.01).max(r * 0.01),
            far: dist + r * 1.01,
        }
    }

    /// The column-major model-view-projection matrix for a viewport of `aspect` = width / height.
    pub fn view_proj(&self, aspect: f32) -> [f32; 16] {
        let view = Mat4::look_at_rh(self.eye.into(), self.target.into(), self.up.into());
        let proj = Mat4::perspective_rh_gl(self.fov_y_degrees.to_radians(), aspect, self.near, self.far);
        (proj * view).to_cols_array()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camera_around_a_sphere_holds_it_between_near_and_far() {
        for eye in [[3.0, -1.5, 0.0], [0.0, 1.5, -3.0], [2.0, 0.0, 2.0]] {
            let c = Camera::around(eye, [0.0; 3], 1.0);
            let d = Vec3::from(c.eye).length();
            assert_eq!((c.eye, c.target, c.up, c.fov_y_degrees), (eye, [0.0; 3], [0.0, 1.0, 0.0], 60.0));
            assert!(c.near < d - 1.0 && c.far > d + 1.0);
        }
        // An eye inside the sphere keeps a positive near plane.
        assert!(Camera::around([0.1, 0.0, 0.0], [0.0; 3], 1.0).near > 0.0);
    }

    #[test]
    fn fitted_camera_sees_the_whole_box() {
        let cam = Camera::fit([-1.0, -2.0, -3.0], [1.0, 2.0, 3.0], [1.0, 1.0, 1.0]);
        let m = Mat4::from_cols_array(&cam.view_proj(1.0));
        for corner in 0..8 {
            let p = Vec3::new(
                if corner & 1 == 0 { -1.0 } else { 1.0 },
                if corner & 2 == 0 { -2.0 } else { 2.0 },
                if corner & 4 == 0 { -3.0 } else { 3.0 },
            );
            let clip = m * p.extend(1.0);
            let ndc = clip.truncate() / clip.w;
            assert!(ndc.abs().max_element() <= 1.0, "corner {p} at {ndc}");
        }
    }
}

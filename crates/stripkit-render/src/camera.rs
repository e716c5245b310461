//! Cameras: a look-at view with a perspective projection, fitted to a bounding box, and
//! the helix camera path that the benchmarks and culling figures share.

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

    /// The column-major model-view-projection matrix for a viewport of `aspect` = width / height.
    pub fn view_proj(&self, aspect: f32) -> [f32; 16] {
        let view = Mat4::look_at_rh(self.eye.into(), self.target.into(), self.up.into());
        let proj = Mat4::perspective_rh_gl(self.fov_y_degrees.to_radians(), aspect, self.near, self.far);
        (proj * view).to_cols_array()
    }
}

/// Views on the helix camera path.
pub const HELIX_VIEWS: usize = 591;

/// The helix camera path: `views` eyes on an ascending helix around the bounding-sphere
/// `center`, at 3 `radius` from its axis, three turns, height from -1.5 to +1.5 radii
/// along +Y, each looking at the centre with a 60 degree vertical field of view.
/// [`HELIX_VIEWS`] views is the path the figures use.
pub fn helix_path(center: [f32; 3], radius: f32, views: usize) -> Vec<Camera> {
    let c = Vec3::from(center);
    let r = radius.max(1e-6);
    (0..views)
        .map(|i| {
            let s = if views > 1 { i as f32 / (views - 1) as f32 } else { 0.0 };
            let angle = s * 3.0 * std::f32::consts::TAU;
            let eye = c + Vec3::new(3.0 * r * angle.cos(), (-1.5 + 3.0 * s) * r, 3.0 * r * angle.sin());
            let dist = (eye - c).length();
            Camera {
                eye: eye.into(),
                target: center,
                up: [0.0, 1.0, 0.0],
                fov_y_degrees: 60.0,
                near: (dist - r * 1.01).max(r * 0.01),
                far: dist + r * 1.01,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn helix_starts_low_ends_high_and_turns_three_times() {
        let p = helix_path([0.0; 3], 1.0, HELIX_VIEWS);
        assert_eq!(p.len(), 591);
        assert!((p[0].eye[1] + 1.5).abs() < 1e-5);
        assert!((p[590].eye[1] - 1.5).abs() < 1e-5);
        // Three turns: the eye crosses +X (angle 0 mod 2 pi) at the start and after each turn.
        assert!((p[0].eye[0] - 3.0).abs() < 1e-5 && p[0].eye[2].abs() < 1e-5);
        assert!((p[590].eye[0] - 3.0).abs() < 1e-4 && p[590].eye[2].abs() < 1e-3);
        for c in &p {
            let d = Vec3::from(c.eye).length();
            assert!(c.near < d - 1.0 && c.far > d + 1.0);
        }
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

//! Framing: a camera looking along a direction, placed tightly around the points drawn
//! (not their bounding sphere), so that the model fills the picture.

use crate::Camera;
use glam::DVec3;

/// Share of the picture's half-width (or half-height) the model may fill.
const FILL: f64 = 0.94;

/// Why a camera could not be framed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FrameError {
    /// The view direction is zero.
    #[error("the view direction must not be 0,0,0")]
    ZeroView,
    /// The up direction is zero or parallel to the view direction.
    #[error("the up direction must not be 0,0,0 nor parallel to the view direction")]
    BadUp,
    /// No point, or a point that is not finite.
    #[error("nothing to frame: no finite vertex positions")]
    NothingToFrame,
}

/// A framed camera and the directions of its picture.
#[derive(Clone, Copy, Debug)]
pub struct Framing {
    /// The camera.
    pub camera: Camera,
    /// Distance from the eye to the point looked at.
    pub distance: f32,
    /// Unit vectors of the picture: right and up, in model space.
    pub right: [f32; 3],
    /// See `right`.
    pub up: [f32; 3],
}

/// `v` as a unit vector; `None` for a zero (or not finite) one.
fn unit(v: DVec3) -> Option<DVec3> {
    let l = v.dot(v).sqrt();
    (l > 1e-12 && l.is_finite()).then(|| v / l)
}

fn dvec(p: [f32; 3]) -> DVec3 {
    DVec3::from(p.map(f64::from))
}

fn single(v: DVec3) -> [f32; 3] {
    v.to_array().map(|x| x as f32)
}

impl Framing {
    /// A camera looking from `view` (the direction from the model towards the eye),
    /// `up` pointing up in the picture, `fov_y_degrees` the vertical field of view,
    /// placed so that every point lies inside the middle 94% of a picture of `aspect` =
    /// width / height; then its field of view narrowed `zoom` times (1: none),
    /// magnifying the middle. Cost: two passes over the points.
    pub fn fit(
        points: &[[f32; 3]],
        view: [f32; 3],
        up: [f32; 3],
        fov_y_degrees: f32,
        zoom: f32,
        aspect: f32,
    ) -> Result<Framing, FrameError> {
        let back = unit(dvec(view)).ok_or(FrameError::ZeroView)?;
        let right = unit(dvec(up).cross(back)).ok_or(FrameError::BadUp)?;
        let top = back.cross(right);
        let mut lo = DVec3::INFINITY;
        let mut hi = DVec3::NEG_INFINITY;
        for p in points {
            for d in 0..3 {
                lo[d] = lo[d].min(p[d] as f64);
                hi[d] = hi[d].max(p[d] as f64);
            }
        }
        if points.is_empty() || !(lo.is_finite() && hi.is_finite()) {
            return Err(FrameError::NothingToFrame);
        }
        let centre = (lo + hi) / 2.0;
        let local = |p: &[f32; 3]| {
            let q = dvec(*p) - centre;
            (q.dot(right), q.dot(top), q.dot(back))
        };
        // Centre the picture on the points' extent across it.
        let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        for p in points {
            let (x, y, _) = local(p);
            (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
        }
        let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
        let target = centre + right * cx + top * cy;
        // The nearest distance at which each point is inside the frustum.
        let tan_y = ((fov_y_degrees as f64).to_radians() * 0.5).tan() * FILL;
        let tan_x = tan_y * aspect as f64;
        let (mut dist, mut z_near, mut z_far) = (0.0f64, f64::NEG_INFINITY, f64::INFINITY);
        for p in points {
            let (x, y, z) = local(p);
            dist = dist.max(z + ((x - cx).abs() / tan_x).max((y - cy).abs() / tan_y));
            z_near = z_near.max(z);
            z_far = z_far.min(z);
        }
        let extent = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max).max(1e-6);
        let dist = dist.max(z_near + extent * 0.05);
        let near = ((dist - z_near) * 0.9).max(extent * 1e-3);
        let far = (dist - z_far) * 1.1 + extent * 0.01;
        let eye = target + back * dist;
        let half = ((fov_y_degrees as f64).to_radians() * 0.5).tan() / zoom.max(1.0) as f64;
        Ok(Framing {
            camera: Camera {
                eye: single(eye),
                target: single(target),
                up: single(top),
                fov_y_degrees: (2.0 * half.atan()).to_degrees() as f32,
                near: near as f32,
                far: far as f32,
            },
            distance: dist as f32,
            right: single(right),
            up: single(top),
        })
    }

    /// An eye at the camera's distance from the point looked at, in `direction`
    /// (`None` for a zero direction).
    pub fn eye_towards(&self, direction: [f32; 3]) -> Option<[f32; 3]> {
        let d = unit(dvec(direction))?;
        Some(single(dvec(self.camera.target) + d * self.distance as f64))
    }

    /// The light direction of a picture: from the eye, a little above and to the left.
    pub fn light(&self) -> [f32; 3] {
        let camera = &self.camera;
        let dir: [f32; 3] = std::array::from_fn(|d| camera.eye[d] - camera.target[d]);
        let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt().max(1e-20);
        std::array::from_fn(|d| dir[d] / len + 0.5 * self.up[d] - 0.35 * self.right[d])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Clip-space position of `p` under the camera.
    fn project(c: &Camera, aspect: f32, p: [f32; 3]) -> [f32; 3] {
        let m = c.view_proj(aspect);
        let r = |i: usize| m[i] * p[0] + m[4 + i] * p[1] + m[8 + i] * p[2] + m[12 + i];
        let w = r(3);
        [r(0) / w, r(1) / w, r(2) / w]
    }

    #[test]
    fn the_points_fill_the_picture() {
        // A long thin box along x, seen from +z: wide, not tall.
        let mut pts = Vec::new();
        for i in 0..8 {
            pts.push([
                if i & 1 == 0 { -4.0 } else { 6.0 },
                if i & 2 == 0 { -1.0 } else { 1.0 },
                if i & 4 == 0 { 0.0 } else { 0.5 },
            ]);
        }
        for aspect in [1.0, 2.0, 0.5] {
            let fr = Framing::fit(&pts, [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 30.0, 1.0, aspect).unwrap();
            let ndc: Vec<_> = pts.iter().map(|&p| project(&fr.camera, aspect, p)).collect();
            let max_x = ndc.iter().map(|p| p[0].abs()).fold(0.0, f32::max);
            let max_y = ndc.iter().map(|p| p[1].abs()).fold(0.0, f32::max);
            assert!(ndc.iter().all(|p| p[2].abs() <= 1.0), "inside near and far");
            assert!(max_x <= 0.95 && max_y <= 0.95, "inside: {max_x} {max_y}");
            assert!(max_x.max(max_y) >= 0.85, "fills: {max_x} {max_y} at aspect {aspect}");
            // Centred across: the extreme x on both sides about equal.
            let (l, r) = ndc.iter().fold((0.0f32, 0.0f32), |(l, r), p| (l.min(p[0]), r.max(p[0])));
            assert!((l + r).abs() < 0.1, "centred: {l} {r}");
        }
    }

    #[test]
    fn up_is_up_in_the_picture() {
        let pts = [[0.0, 0.0, 0.0], [0.0, 10.0, 0.0], [1.0, 0.0, 1.0]];
        let fr = Framing::fit(&pts, [0.3, 0.4, 1.0], [0.0, 1.0, 0.0], 30.0, 1.0, 1.0).unwrap();
        let (a, b) = (project(&fr.camera, 1.0, pts[0]), project(&fr.camera, 1.0, pts[1]));
        assert!(b[1] > a[1] + 1.0, "+y up: {a:?} {b:?}");
        let fr = Framing::fit(&pts, [1.0, 0.0, 0.0], [0.0, -1.0, 0.0], 30.0, 1.0, 1.0).unwrap();
        let (a, b) = (project(&fr.camera, 1.0, pts[0]), project(&fr.camera, 1.0, pts[1]));
        assert!(b[1] < a[1] - 1.0, "-y up: {a:?} {b:?}");
        let eye = fr.eye_towards([0.0, 0.0, -2.0]).unwrap();
        assert!((eye[2] - (fr.camera.target[2] - fr.distance)).abs() < 1e-4);
    }

    #[test]
    fn zoom_magnifies_the_middle() {
        let pts = [[-1.0, -1.0, 0.0], [1.0, 1.0, 0.0]];
        let one = Framing::fit(&pts, [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 30.0, 1.0, 1.0).unwrap();
        let three = Framing::fit(&pts, [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 30.0, 3.0, 1.0).unwrap();
        assert_eq!(one.camera.eye, three.camera.eye, "the camera stays");
        let (a, b) = (project(&one.camera, 1.0, [0.2, 0.1, 0.0]), project(&three.camera, 1.0, [0.2, 0.1, 0.0]));
        assert!((b[0] - 3.0 * a[0]).abs() < 1e-4 && (b[1] - 3.0 * a[1]).abs() < 1e-4, "{a:?} {b:?}");
    }

    #[test]
    fn bad_directions_are_refused() {
        let pts = [[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]];
        let fit = |pts: &[[f32; 3]], view| Framing::fit(pts, view, [0.0, 1.0, 0.0], 30.0, 1.0, 1.0).unwrap_err();
        assert_eq!(fit(&pts, [0.0; 3]), FrameError::ZeroView);
        assert_eq!(fit(&pts, [0.0, 2.0, 0.0]), FrameError::BadUp);
        assert_eq!(fit(&[], [0.0, 0.0, 1.0]), FrameError::NothingToFrame);
    }
}

//! The camera of `stripkit render`: looking along a direction, framed tightly around
//! the points drawn (not their bounding sphere), so that the model fills the picture.

use stripkit_render::{cross, Camera};

type V = [f64; 3];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn unit(a: V) -> Option<V> {
    let l = dot(a, a).sqrt();
    (l > 1e-12 && l.is_finite()).then(|| [a[0] / l, a[1] / l, a[2] / l])
}
fn along(p: V, d: V, s: f64) -> V {
    [p[0] + d[0] * s, p[1] + d[1] * s, p[2] + d[2] * s]
}

/// Share of the picture's half-width (or half-height) the model may fill.
const FILL: f64 = 0.94;

/// A framed camera.
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

impl Framing {
    /// An eye at the camera's distance from the point looked at, in `direction`
    /// (`None` for a zero direction).
    pub fn eye_towards(&self, direction: [f32; 3]) -> Option<[f32; 3]> {
        let d = unit(direction.map(f64::from))?;
        Some(along(self.camera.target.map(f64::from), d, self.distance as f64).map(|x| x as f32))
    }
}

/// A camera looking from `view` (the direction from the model towards the eye), `up`
/// pointing up in the picture, `fov_y_degrees` the vertical field of view, placed so that
/// every point lies inside the middle 94% of a picture of `aspect` = width / height;
/// then its field of view narrowed `zoom` times (1: none), magnifying the middle.
pub fn frame(
    points: &[[f32; 3]],
    view: [f32; 3],
    up: [f32; 3],
    fov_y_degrees: f32,
    zoom: f32,
    aspect: f32,
) -> Result<Framing, String> {
    let back = unit(view.map(f64::from)).ok_or("--view must not be 0,0,0")?;
    let right = unit(cross(up.map(f64::from), back)).ok_or("--up must not be 0,0,0 nor parallel to --view")?;
    let top = cross(back, right);
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for d in 0..3 {
            lo[d] = lo[d].min(p[d] as f64);
            hi[d] = hi[d].max(p[d] as f64);
        }
    }
    if points.is_empty() || lo.iter().chain(&hi).any(|x| !x.is_finite()) {
        return Err("nothing to frame: no finite vertex positions".into());
    }
    let centre = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0, (lo[2] + hi[2]) / 2.0];
    let local = |p: &[f32; 3]| {
        let q = sub(p.map(f64::from), centre);
        (dot(q, right), dot(q, top), dot(q, back))
    };
    // Centre the picture on the points' extent across it.
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for p in points {
        let (x, y, _) = local(p);
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    let target = along(along(centre, right, cx), top, cy);
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
    let eye = along(target, back, dist);
    let f = |v: V| v.map(|x| x as f32);
    Ok(Framing {
        camera: Camera {
            eye: f(eye),
            target: f(target),
            up: f(top),
            fov_y_degrees: (2.0 * (((fov_y_degrees as f64).to_radians() * 0.5).tan() / zoom.max(1.0) as f64).atan())
                .to_degrees() as f32,
            near: near as f32,
            far: far as f32,
        },
        distance: dist as f32,
        right: f(right),
        up: f(top),
    })
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
            let fr = frame(&pts, [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 30.0, 1.0, aspect).unwrap();
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
        let fr = frame(&pts, [0.3, 0.4, 1.0], [0.0, 1.0, 0.0], 30.0, 1.0, 1.0).unwrap();
        let (a, b) = (project(&fr.camera, 1.0, pts[0]), project(&fr.camera, 1.0, pts[1]));
        assert!(b[1] > a[1] + 1.0, "+y up: {a:?} {b:?}");
        let fr = frame(&pts, [1.0, 0.0, 0.0], [0.0, -1.0, 0.0], 30.0, 1.0, 1.0).unwrap();
        let (a, b) = (project(&fr.camera, 1.0, pts[0]), project(&fr.camera, 1.0, pts[1]));
        assert!(b[1] < a[1] - 1.0, "-y up: {a:?} {b:?}");
        let eye = fr.eye_towards([0.0, 0.0, -2.0]).unwrap();
        assert!((eye[2] - (fr.camera.target[2] - fr.distance)).abs() < 1e-4);
    }

    #[test]
    fn zoom_magnifies_the_middle() {
        let pts = [[-1.0, -1.0, 0.0], [1.0, 1.0, 0.0]];
        let one = frame(&pts, [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 30.0, 1.0, 1.0).unwrap();
        let three = frame(&pts, [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 30.0, 3.0, 1.0).unwrap();
        assert_eq!(one.camera.eye, three.camera.eye, "the camera stays");
        let (a, b) = (project(&one.camera, 1.0, [0.2, 0.1, 0.0]), project(&three.camera, 1.0, [0.2, 0.1, 0.0]));
        assert!((b[0] - 3.0 * a[0]).abs() < 1e-4 && (b[1] - 3.0 * a[1]).abs() < 1e-4, "{a:?} {b:?}");
    }

    #[test]
    fn bad_directions_are_refused() {
        let pts = [[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]];
        assert!(frame(&pts, [0.0; 3], [0.0, 1.0, 0.0], 30.0, 1.0, 1.0).unwrap_err().contains("--view"));
        assert!(frame(&pts, [0.0, 2.0, 0.0], [0.0, 1.0, 0.0], 30.0, 1.0, 1.0).unwrap_err().contains("parallel"));
        assert!(frame(&[], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 30.0, 1.0, 1.0).is_err());
    }
}

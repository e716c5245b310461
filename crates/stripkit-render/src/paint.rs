//! Colours for pictures of strips: the strips' triangles are "exploded" into an
//! unindexed triangle list, in strip order, three corners per triangle, so that every
//! triangle can carry the colour of its strip, of its place in the strip order, or of
//! its facing. The triangles come decoded, each with the number of its strip.

use glam::Vec3;

/// What a triangle's colour shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Paint {
    /// Each strip its own colour ([`strip_color`]).
    Strips,
    /// A gradient along the strip order ([`gradient`]): first triangle of the first
    /// strip to the last triangle of the last strip.
    Order,
    /// Facing an eye ([`FRONT`]) or turned away from it ([`BACK`]).
    Cull {
        /// The eye the facing is judged from.
        eye: [f32; 3],
    },
    /// One grey ([`GREY`]).
    None,
}

/// [`Paint::Cull`]: a triangle facing the eye.
pub const FRONT: [u8; 4] = [58, 110, 190, 255];
/// [`Paint::Cull`]: a triangle turned away from the eye (back-face culling skips it).
pub const BACK: [u8; 4] = [246, 214, 200, 255];
/// [`Paint::None`].
pub const GREY: [u8; 4] = [205, 205, 205, 255];
/// The edges of a wireframe ([`crate::wire`]).
pub const WIRE: [u8; 4] = [30, 30, 30, 255];

/// The colour of strip `k`: hues a golden-ratio turn apart (consecutive strips differ
/// by at least 0.38 of a turn, and no two of the first hundreds come close), with the
/// saturation and value cycling over three steps so that equal-looking hues differ in
/// lightness too.
pub fn strip_color(k: usize) -> [u8; 4] {
    const GOLDEN: f64 = 0.618_033_988_749_894_9;
    let hue = (0.08 + k as f64 * GOLDEN).fract();
    let (s, v) = [(0.70, 0.95), (0.95, 0.78), (0.45, 0.88)][k % 3];
    hsv(hue, s, v)
}

/// The order gradient at `t` in 0..=1: blue, cyan, green, yellow, orange, red. No dark
/// end, so that lit faces stay readable at both ends.
pub fn gradient(t: f32) -> [u8; 4] {
    const STOPS: [[f32; 3]; 7] = [
        [40.0, 60.0, 200.0],
        [30.0, 150.0, 240.0],
        [40.0, 200.0, 160.0],
        [140.0, 220.0, 60.0],
        [250.0, 200.0, 40.0],
        [240.0, 110.0, 30.0],
        [200.0, 30.0, 30.0],
    ];
    let x = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f32;
    let i = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - i as f32;
    let c = |j: usize| (STOPS[i][j] + (STOPS[i + 1][j] - STOPS[i][j]) * f).round() as u8;
    [c(0), c(1), c(2), 255]
}

fn hsv(h: f64, s: f64, v: f64) -> [u8; 4] {
    let h6 = h * 6.0;
    let i = h6.floor() as i32 % 6;
    let f = h6 - h6.floor();
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - s * f), v * (1.0 - s * (1.0 - f)));
    let (r, g, b) = match i {
        0 => (v, t, p),
        1 => (q, v, p),
        2 => (p, v, t),
        3 => (p, q, v),
        4 => (t, p, v),
        _ => (v, p, q),
    };
    let u = |x: f64| (x * 255.0).round() as u8;
    [u(r), u(g), u(b), 255]
}

/// The strips as an unindexed triangle list: corner `3 j + c` is corner `c` of the
/// `j`-th drawn triangle in strip order, with the winding the strip gives it.
#[derive(Clone, Debug, Default)]
pub struct Exploded {
    /// The mesh vertex of each corner.
    pub corners: Vec<u32>,
    /// The colour of each corner (the same for a triangle's three).
    pub colors: Vec<[u8; 4]>,
    /// Triangles facing the eye (`Paint::Cull` only; 0 otherwise).
    pub front: usize,
}

impl Exploded {
    /// Number of triangles.
    pub fn triangles(&self) -> usize {
        self.corners.len() / 3
    }

    /// `values` (one per mesh vertex) at each corner.
    pub fn gather<T: Copy>(&self, values: &[T]) -> Vec<T> {
        self.corners.iter().map(|&v| values[v as usize]).collect()
    }
}

/// Explodes `triangles` (in strip order, each with the number of its strip, over a
/// mesh whose vertices are at `positions`) and colours each as `paint` says. The
/// caller leaves out the triangles with a repeated index (swaps, stitches), as the GPU
/// leaves them out.
pub fn explode(triangles: &[(usize, [u32; 3])], positions: &[[f32; 3]], paint: Paint) -> Exploded {
    let n = triangles.len();
    let mut out = Exploded { corners: Vec::with_capacity(3 * n), colors: Vec::with_capacity(3 * n), front: 0 };
    for (j, &(k, t)) in triangles.iter().enumerate() {
        let color = match paint {
            Paint::Strips => strip_color(k),
            Paint::Order => gradient(if n > 1 { j as f32 / (n - 1) as f32 } else { 0.0 }),
            Paint::Cull { eye } => {
                if faces(eye, t.map(|v| positions[v as usize])) {
                    out.front += 1;
                    FRONT
                } else {
                    BACK
                }
            }
            Paint::None => GREY,
        };
        out.corners.extend_from_slice(&t);
        out.colors.extend_from_slice(&[color; 3]);
    }
    out
}

/// Whether the triangle `[a, b, c]` (counter-clockwise front, as OpenGL and glTF) faces
/// `eye`: the eye lies on the side its normal points to.
pub fn faces(eye: [f32; 3], [a, b, c]: [[f32; 3]; 3]) -> bool {
    let a = Vec3::from(a);
    let (u, v, w) = (Vec3::from(b) - a, Vec3::from(c) - a, Vec3::from(eye) - a);
    u.cross(v).dot(w) > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn distance(a: [u8; 4], b: [u8; 4]) -> i32 {
        (0..3).map(|i| (a[i] as i32 - b[i] as i32).abs()).sum()
    }

    #[test]
    fn strip_colours_are_distinct_and_neighbours_far_apart() {
        let colors: Vec<_> = (0..2000).map(strip_color).collect();
        // 8-bit channels repeat a colour first at strip 987.
        let distinct: std::collections::HashSet<_> = colors[..987].iter().collect();
        assert_eq!(distinct.len(), 987, "each of the first 987 strips its own colour");
        // Neighbouring strips: far apart in RGB (sum of channel differences).
        let closest = colors.windows(2).map(|w| distance(w[0], w[1])).min().unwrap();
        assert!(closest >= 120, "consecutive strips {closest} apart");
        // Any two of the first 12 strips differ visibly.
        for i in 0..12 {
            for j in 0..i {
                assert!(distance(colors[i], colors[j]) >= 40, "strips {i} and {j}");
            }
        }
        // Never near the background white or the grey of --color none.
        assert!(colors.iter().all(|&c| distance(c, [255; 4]) >= 60));
    }

    #[test]
    fn gradient_runs_from_blue_to_red_without_jumps() {
        assert_eq!(gradient(0.0), [40, 60, 200, 255]);
        assert_eq!(gradient(1.0), [200, 30, 30, 255]);
        assert_eq!(gradient(-1.0), gradient(0.0));
        assert_eq!(gradient(2.0), gradient(1.0));
        let steps: Vec<_> = (0..=1000).map(|i| gradient(i as f32 / 1000.0)).collect();
        assert!(steps.windows(2).all(|w| distance(w[0], w[1]) <= 6), "smooth");
        let distinct: std::collections::HashSet<_> = steps.iter().collect();
        assert!(distinct.len() > 600, "{} distinct of 1,001", distinct.len());
    }

    /// The triangles of strips `[0 1 2 3]` (two) and `[4 4 5 6]` (one swap, then the
    /// odd triangle (5, 4, 6)), as a strip decoder gives them.
    #[test]
    fn explode_keeps_strip_order_winding() {
        let strips = [(0, [0, 1, 2]), (0, [2, 1, 3]), (1, [5, 4, 6])];
        let positions = [[0.0f32; 3]; 7];
        let e = explode(&strips, &positions, Paint::Strips);
        assert_eq!(e.triangles(), 3);
        assert_eq!(e.corners, [0, 1, 2, 2, 1, 3, 5, 4, 6]);
        assert_eq!(&e.colors[..6], &[strip_color(0); 6]);
        assert_eq!(&e.colors[6..], &[strip_color(1); 3]);
        let o = explode(&strips, &positions, Paint::Order);
        assert_eq!(o.colors[0], gradient(0.0));
        assert_eq!(o.colors[3], gradient(0.5));
        assert_eq!(o.colors[8], gradient(1.0));
        assert_eq!(e.gather(&[10, 11, 12, 13, 14, 15, 16]), [10, 11, 12, 12, 11, 13, 15, 14, 16]);
    }

    #[test]
    fn cull_paint_follows_the_eye() {
        // Two triangles of the unit square in z = 0, counter-clockwise seen from +z,
        // and one of them flipped.
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let strips = [(0, [0, 1, 2]), (1, [0, 2, 3]), (2, [0, 3, 2])];
        let from_above = explode(&strips, &positions, Paint::Cull { eye: [0.5, 0.5, 5.0] });
        assert_eq!(from_above.front, 2);
        assert_eq!(from_above.colors.iter().filter(|&&c| c == BACK).count(), 3);
        let from_below = explode(&strips, &positions, Paint::Cull { eye: [0.5, 0.5, -5.0] });
        assert_eq!(from_below.front, 1);
        assert_eq!(explode(&strips, &positions, Paint::None).colors, vec![GREY; 9]);
    }
}

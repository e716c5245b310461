//! f64 vector helpers for tests that check geometry (normals, facing, areas): the same
//! component order as the library's `vec3`, so a test computes what the code does.

/// `a - b`.
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a . b`.
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a x b`.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// Twice the area vector of triangle (a, b, c): `(b - a) x (c - a)`.
pub fn tri_normal(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> [f64; 3] {
    cross(sub(b, a), sub(c, a))
}

/// Unit vectors from the origin to each position, flattened (x, y, z per vertex): a
/// NORMAL attribute that is right for spheres and close for tori, so that tests have a
/// second attribute whose values differ per vertex.
pub fn radial_normals(positions: &[[f32; 3]]) -> Vec<f32> {
    positions
        .iter()
        .flat_map(|p| {
            let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            [p[0] / l, p[1] / l, p[2] / l]
        })
        .collect()
}

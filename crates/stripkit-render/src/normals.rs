//! Vertex normals for smooth shading, from an indexed triangle list, and the cross
//! product the workspace's geometry outside the library uses (the CLI's framing and
//! wireframe, the bench's culling), in f32 or f64.

use std::ops::{Mul, Sub};

/// The cross product `a x b`, computed in `T` (f32 or f64) in the usual component
/// order, so that every caller gets the same bits for the same inputs.
#[inline]
pub fn cross<T: Copy + Mul<Output = T> + Sub<Output = T>>(a: [T; 3], b: [T; 3]) -> [T; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// Area-weighted vertex normals of the triangles (for smooth shading); unit length,
/// +Z for a vertex on no triangle or on triangles of no area.
pub fn vertex_normals(positions: &[[f32; 3]], corners: &[u32]) -> Vec<[f32; 3]> {
    let mut acc = vec![[0.0f64; 3]; positions.len()];
    for t in corners.chunks_exact(3) {
        let p = |i: usize| positions[t[i] as usize].map(f64::from);
        let (a, b, c) = (p(0), p(1), p(2));
        let (u, v) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
        let n = cross(u, v);
        for &i in t {
            for d in 0..3 {
                acc[i as usize][d] += n[d];
            }
        }
    }
    acc.iter()
        .map(|n| {
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            if len > 0.0 && len.is_finite() {
                [(n[0] / len) as f32, (n[1] / len) as f32, (n[2] / len) as f32]
            } else {
                [0.0, 0.0, 1.0]
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normals_point_out_of_the_surface() {
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [5.0, 5.0, 5.0]];
        let n = vertex_normals(&positions, &[0, 1, 2]);
        assert_eq!(n[0], [0.0, 0.0, 1.0]);
        assert_eq!(n[2], [0.0, 0.0, 1.0]);
        assert_eq!(n[3], [0.0, 0.0, 1.0], "unused vertex");
        let n = vertex_normals(&positions, &[0, 2, 1]);
        assert_eq!(n[1], [0.0, 0.0, -1.0]);
    }
}

//! Vertex normals for smooth shading, from an indexed triangle list.

use glam::DVec3;

/// Area-weighted vertex normals of the triangles (for smooth shading); unit length,
/// +Z for a vertex on no triangle or on triangles of no area.
pub fn vertex_normals(positions: &[[f32; 3]], corners: &[u32]) -> Vec<[f32; 3]> {
    let mut acc = vec![[0.0f64; 3]; positions.len()];
    for t in corners.chunks_exact(3) {
        let p = |i: usize| positions[t[i] as usize].map(f64::from);
        let (a, b, c) = (DVec3::from(p(0)), DVec3::from(p(1)), DVec3::from(p(2)));
        let n = (b - a).cross(c - a).to_array();
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

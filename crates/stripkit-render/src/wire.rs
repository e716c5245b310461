//! Wireframes: every edge of the drawn triangles as a thin band of triangles, built on
//! the CPU (the renderer draws triangles only). A band lies across the edge as the eye
//! sees it, `width` pixels wide at each end, and is moved towards the eye along the
//! lines of sight (which keeps its place in the picture) by `lift` pixels' worth, so
//! that the depth test keeps it in front of its own faces and hides it behind others.

use crate::Camera;
use glam::Vec3;
use std::collections::HashSet;

type V = [f32; 3];

/// The wireframe of the triangles `corners` (three per triangle) over `positions` as
/// `camera` sees them in a picture of `(width, height)` pixels: [`bands`] one pixel
/// wide per 640 pixels of the shorter side (at least one), lifted by one and a half
/// pixels. Two band triangles per edge.
pub fn wireframe(positions: &[V], corners: &[u32], camera: &Camera, (w, h): (u32, u32)) -> Vec<V> {
    let fov = (camera.fov_y_degrees as f64).to_radians();
    let pixel = (2.0 * (fov * 0.5).tan() / h as f64) as f32;
    let width = (w.min(h) as f32 / 640.0).max(1.0);
    bands(positions, corners, camera.eye, pixel, width, 1.5)
}

/// Bands for the edges of the triangles `corners` (three per triangle) over `positions`,
/// seen from `eye` where one pixel at distance 1 is `pixel` units wide. Returns the band
/// corners, three per triangle, two triangles per edge.
pub fn bands(positions: &[V], corners: &[u32], eye: V, pixel: f32, width: f32, lift: f32) -> Vec<V> {
    let mut edges = HashSet::with_capacity(corners.len());
    for t in corners.chunks_exact(3) {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            edges.insert((a.min(b), a.max(b)));
        }
    }
    let mut edges: Vec<_> = edges.into_iter().collect();
    edges.sort_unstable();
    let mut out = Vec::with_capacity(edges.len() * 6);
    let eye = Vec3::from(eye);
    for (a, b) in edges {
        let (pa, pb) = (Vec3::from(positions[a as usize]), Vec3::from(positions[b as usize]));
        let mid = pa + (pb - pa) * 0.5;
        let side = (pb - pa).cross(eye - mid);
        let l = side.length();
        if !(l > 0.0 && l.is_finite()) {
            continue; // an edge seen end-on, or of no length
        }
        let side = side / l;
        // Half the width, and the lift, in model units at each end's distance.
        let place = |p: Vec3, s: f32| {
            let d = (eye - p).length().max(1e-20);
            let q = p + side * (s * 0.5 * width * pixel * d);
            // Towards the eye along the line of sight: same pixel, nearer.
            (q + (eye - q) * (lift * pixel).min(0.5)).to_array()
        };
        let (a0, a1, b0, b1) = (place(pa, -1.0), place(pa, 1.0), place(pb, -1.0), place(pb, 1.0));
        out.extend_from_slice(&[a0, a1, b1, a0, b1, b0]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_band_per_edge_shared_edges_once() {
        // Two triangles sharing the edge 0-2: five edges.
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let b = bands(&positions, &[0, 1, 2, 0, 2, 3], [0.5, 0.5, 10.0], 0.01, 2.0, 1.0);
        assert_eq!(b.len(), 5 * 6);
        // The band of edge 0-1 (the first): 2 pixels wide at distance ~10 (0.2 units),
        // across the edge (along y), lifted towards the eye (z > 0).
        let ys: Vec<f32> = b[..6].iter().map(|p| p[1]).collect();
        let spread = ys.iter().cloned().fold(f32::MIN, f32::max) - ys.iter().cloned().fold(f32::MAX, f32::min);
        assert!((spread - 0.2).abs() < 0.02, "{spread}");
        assert!(b.iter().all(|p| p[2] > 0.0));
    }

    #[test]
    fn an_edge_seen_end_on_has_no_band() {
        let positions = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]];
        let b = bands(&positions, &[0, 1, 2], [0.0, 0.0, 5.0], 0.01, 1.0, 1.0);
        assert_eq!(b.len(), 2 * 6, "edge 0-1 points at the eye");
    }
}

//! Wireframes: every edge of the drawn triangles as a thin band of triangles, built on
//! the CPU (the renderer draws triangles only). A band lies across the edge as the eye
//! sees it, `width` pixels wide at each end, and is moved towards the eye along the
//! lines of sight (which keeps its place in the picture) by `lift` pixels' worth, so
//! that the depth test keeps it in front of its own faces and hides it behind others.

use crate::Camera;
use glam::Vec3;

type V = [f32; 3];

/// The wireframe of the triangles `corners` (three per triangle) over `positions` as
/// `camera` sees them in a picture of `(width, height)` pixels: [`bands`] one pixel
/// wide per 640 pixels of the shorter side (at least one), lifted by one and a half
/// pixels. Two band triangles per edge.
pub fn wireframe(positions: &[V], corners: &[u32], camera: &Camera, size: (u32, u32)) -> Vec<V> {
    wireframe_of(positions, &edges(corners), camera, size)
}

/// [`wireframe`] of the given `edges` (from [`edges`]): a slice of them at a time
/// bounds the memory of a large wireframe (48 bytes of band per edge, and as much
/// again in the driver's copy), and the bands of consecutive slices drawn one after
/// another are the picture of the whole.
pub fn wireframe_of(positions: &[V], edges: &[(u32, u32)], camera: &Camera, (w, h): (u32, u32)) -> Vec<V> {
    let fov = (camera.fov_y_degrees as f64).to_radians();
    let pixel = (2.0 * (fov * 0.5).tan() / h as f64) as f32;
    let width = (w.min(h) as f32 / 640.0).max(1.0);
    bands_of(positions, edges, camera.eye, pixel, width, 1.5)
}

/// The edges of the triangles `corners` (three per triangle), each once, smaller
/// vertex first, in order.
pub fn edges(corners: &[u32]) -> Vec<(u32, u32)> {
    let mut edges = Vec::with_capacity(corners.len());
    for t in corners.chunks_exact(3) {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            edges.push((a.min(b), a.max(b)));
        }
    }
    edges.sort_unstable();
    edges.dedup();
    edges
}

/// Bands for the edges of the triangles `corners` (three per triangle) over `positions`,
/// seen from `eye` where one pixel at distance 1 is `pixel` units wide. Returns the band
/// corners, three per triangle, two triangles per edge.
pub fn bands(positions: &[V], corners: &[u32], eye: V, pixel: f32, width: f32, lift: f32) -> Vec<V> {
    bands_of(positions, &edges(corners), eye, pixel, width, lift)
}

/// [`bands`] of the given edges.
pub fn bands_of(positions: &[V], edges: &[(u32, u32)], eye: V, pixel: f32, width: f32, lift: f32) -> Vec<V> {
    let mut out = Vec::with_capacity(edges.len() * 6);
    let eye = Vec3::from(eye);
    for &(a, b) in edges {
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
    fn bands_of_slices_of_edges_are_the_bands_of_all() {
        // A fan of 40 triangles: the wireframe drawn a slice of edges at a time (the
        // render command's bounded memory) is the whole wireframe, in the same order.
        let mut positions = vec![[0.0, 0.0, 0.0]];
        let mut corners = Vec::new();
        for i in 0..41u32 {
            let t = i as f32 * 0.15;
            positions.push([t.cos(), t.sin(), 0.1 * t]);
            if i > 0 {
                corners.extend_from_slice(&[0, i, i + 1]);
            }
        }
        let edges = edges(&corners);
        assert_eq!(edges.len(), 40 + 41);
        let all = bands(&positions, &corners, [0.2, 0.3, 5.0], 0.01, 1.5, 1.5);
        for slice in [1, 7, 64, 100] {
            let parts: Vec<V> =
                edges.chunks(slice).flat_map(|e| bands_of(&positions, e, [0.2, 0.3, 5.0], 0.01, 1.5, 1.5)).collect();
            assert_eq!(parts, all, "slices of {slice}");
        }
    }

    #[test]
    fn an_edge_seen_end_on_has_no_band() {
        let positions = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]];
        let b = bands(&positions, &[0, 1, 2], [0.0, 0.0, 5.0], 0.01, 1.0, 1.0);
        assert_eq!(b.len(), 2 * 6, "edge 0-1 points at the eye");
    }
}

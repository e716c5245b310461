//! `--wireframe`: every edge of the drawn triangles as a thin band of triangles, built on
//! the CPU (the renderer draws triangles only). A band lies across the edge as the eye
//! sees it, `width` pixels wide at each end, and is moved towards the eye along the
//! lines of sight (which keeps its place in the picture) by `lift` pixels' worth, so
//! that the depth test keeps it in front of its own faces and hides it behind others.

use std::collections::HashSet;
use stripkit_render::cross;

type V = [f32; 3];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn len(a: V) -> f32 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}
fn add_scaled(a: V, d: V, s: f32) -> V {
    [a[0] + d[0] * s, a[1] + d[1] * s, a[2] + d[2] * s]
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
    for (a, b) in edges {
        let (pa, pb) = (positions[a as usize], positions[b as usize]);
        let mid = add_scaled(pa, sub(pb, pa), 0.5);
        let side = cross(sub(pb, pa), sub(eye, mid));
        let l = len(side);
        if !(l > 0.0 && l.is_finite()) {
            continue; // an edge seen end-on, or of no length
        }
        let side = side.map(|x| x / l);
        // Half the width, and the lift, in model units at each end's distance.
        let place = |p: V, s: f32| {
            let d = len(sub(eye, p)).max(1e-20);
            let q = add_scaled(p, side, s * 0.5 * width * pixel * d);
            // Towards the eye along the line of sight: same pixel, nearer.
            add_scaled(q, sub(eye, q), (lift * pixel).min(0.5))
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

//! Brute-force facing counts of a view, to measure a culler (figures and tests).

use crate::strip::StripSet;
use std::ops::Range;

/// Every drawable triangle of a [`StripSet`] with its plane, in strip order, to count
/// per view how many triangles face the eye and how many of them a set of ranges
/// draws.
#[derive(Clone, Debug, Default)]
pub struct FacingCounter {
    /// Index position of each drawable triangle in [`StripSet::indices`] (the first of
    /// its three indices), increasing.
    at: Vec<u32>,
    /// Unnormalized normal and its dot product with the first vertex (f64).
    planes: Vec<([f64; 3], f64)>,
}

/// Facing counts of one view. A triangle whose plane holds the eye counts as neither.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FacingCounts {
    /// Triangles facing the eye.
    pub front: usize,
    /// Of those, drawn by the ranges (all of them unless the culler is wrong).
    pub front_drawn: usize,
    /// Triangles facing away.
    pub back: usize,
    /// Of those, drawn by the ranges (the conservative test's leak).
    pub back_drawn: usize,
}

impl FacingCounts {
    /// Back-facing triangles not drawn.
    pub fn back_culled(&self) -> usize {
        self.back - self.back_drawn
    }
}

impl FacingCounter {
    /// The drawable triangles of `strips` (decoded with their winding).
    pub fn new(strips: &StripSet, positions: &[[f32; 3]]) -> Self {
        let mut out = FacingCounter::default();
        for (s, strip) in strips.iter().enumerate() {
            let base = strips.offsets[s];
            for i in 0..strip.len().saturating_sub(2) {
                let t =
                    if i % 2 == 0 { [strip[i], strip[i + 1], strip[i + 2]] } else { [strip[i + 1], strip[i], strip[i + 2]] };
                if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                    continue;
                }
                let n = super::bounds::triangle_normal(&t, positions);
                let a = positions[t[0] as usize].map(|x| x as f64);
                out.at.push(base + i as u32);
                out.planes.push((n, n[0] * a[0] + n[1] * a[1] + n[2] * a[2]));
            }
        }
        out
    }

    /// Number of drawable triangles.
    pub fn len(&self) -> usize {
        self.at.len()
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.at.is_empty()
    }

    /// Counts for the eye point `eye` and the index ranges drawn (non-overlapping,
    /// each starting at an even triangle of its strip).
    pub fn count(&self, eye: [f32; 3], ranges: &[Range<u32>]) -> FacingCounts {
        let e = eye.map(|x| x as f64);
        let side = |&(n, d): &([f64; 3], f64)| n[0] * e[0] + n[1] * e[1] + n[2] * e[2] - d;
        let mut c = FacingCounts::default();
        for p in &self.planes {
            let f = side(p);
            c.front += (f > 0.0) as usize;
            c.back += (f < 0.0) as usize;
        }
        for r in ranges {
            let lo = self.at.partition_point(|&g| g < r.start);
            let hi = self.at.partition_point(|&g| g + 3 <= r.end);
            for p in &self.planes[lo..hi.max(lo)] {
                let f = side(p);
                c.front_drawn += (f > 0.0) as usize;
                c.back_drawn += (f < 0.0) as usize;
            }
        }
        c
    }
}

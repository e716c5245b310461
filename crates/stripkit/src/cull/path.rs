//! The helix camera path of the culling and GPU figures: its eye points, the one copy
//! of the path (stripkit-render's `Camera::around` makes each eye a camera).

/// Views on the helix camera path (the paper's 591 frames).
pub const HELIX_VIEWS: usize = 591;

/// Most views a path may have: 100,000. Each view keeps its eye (12 bytes) and its
/// figures in a survey (about 100 bytes, and a JSON row), and costs a cull per
/// repeat: 10^8 views once asked for over 10 GB. [`crate::cull::survey::survey`]
/// refuses more, and `stripkit cull --views` before reading the mesh.
pub const MAX_VIEWS: usize = 100_000;

/// The eye points of the helix camera path: `views` eyes on an ascending helix around
/// `center` (the centre of the mesh's bounding box), at `3 radius` from the vertical
/// axis through it (`radius`: half the box's diagonal), three turns starting on +X
/// and turning from +X towards +Z, height from `-1.5 radius` to `+1.5 radius` along +Y.
/// Eye `i` is at `s = i / (views - 1)`, angle `6 pi s`, height `(-1.5 + 3 s) radius`.
/// The cameras look at the centre with a 60 degree vertical field of view, so the whole
/// bounding sphere stays in view (it subtends at most 2 asin(1/3) = 39 degrees).
pub fn helix_eyes(center: [f32; 3], radius: f32, views: usize) -> Vec<[f32; 3]> {
    let r = radius.max(1e-6);
    (0..views)
        .map(|i| {
            let s = if views > 1 { i as f32 / (views - 1) as f32 } else { 0.0 };
            let angle = s * 3.0 * std::f32::consts::TAU;
            [center[0] + 3.0 * r * angle.cos(), center[1] + (-1.5 + 3.0 * s) * r, center[2] + 3.0 * r * angle.sin()]
        })
        .collect()
}

/// The centre of the bounding box of `positions` and half its diagonal: the `center`
/// and `radius` of [`helix_eyes`]. The origin and 0 for no positions.
pub fn bounding_sphere(positions: &[[f32; 3]]) -> ([f32; 3], f32) {
    if positions.is_empty() {
        return ([0.0; 3], 0.0);
    }
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for p in positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let c = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
    let r = (0..3).map(|k| ((hi[k] - lo[k]) as f64).powi(2)).sum::<f64>().sqrt() as f32 / 2.0;
    (c, r)
}

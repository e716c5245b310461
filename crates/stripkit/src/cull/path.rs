//! The helix camera path of the culling figures: the eye points of
//! `stripkit_render::camera::helix_path`, which the library does not depend on (a test
//! in stripkit-cli keeps the two equal).

/// Views on the helix camera path (the paper's 591 frames).
pub const HELIX_VIEWS: usize = 591;

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

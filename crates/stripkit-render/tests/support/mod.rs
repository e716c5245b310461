//! Helpers shared by the renderer's tests: a 512x512 renderer, meshes drawn as lists or
//! strips from a fitted camera, and where the research meshes are. Include with
//! `mod support;`.
#![allow(dead_code)] // each test binary uses a different subset

use stripkit_render::{Camera, DrawParams, Image, IndexWidth, Renderer, Shading, Topology, Vertices};

#[allow(unused_imports)]
pub use stripkit_testkit::{assets_dir, models_dir};

/// Picture size of every check.
pub const SIZE: u32 = 512;
/// Background: black; the default vertex colour is light grey, so any drawn pixel differs.
pub const BACKGROUND: [f32; 3] = [0.0; 3];

/// The restart index of every strip buffer handed to the renderer.
pub const RESTART: u32 = u32::MAX;

/// A 512x512 renderer; panics with the renderer's own message (which says what to
/// install) where the machine has no EGL.
pub fn renderer() -> Renderer {
    match Renderer::new(SIZE, SIZE) {
        Ok(r) => r,
        Err(e) => panic!("the render tests need EGL and OpenGL ES 3 (.ci/run installs Mesa's): {e}"),
    }
}

/// The research mesh `name` from [`models_dir`]; `None` (after printing why) when the
/// folder or the file is absent or unreadable, so that a test can skip it.
pub fn model(name: &str) -> Option<stripkit::Mesh> {
    stripkit_testkit::model_with(name, |path| stripkit::io::read(path))
}

/// A camera on `mesh`'s bounding box looking from `direction`.
pub fn camera(positions: &[[f32; 3]], direction: [f32; 3]) -> [f32; 16] {
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for p in positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    Camera::fit(lo, hi, direction).view_proj(1.0) // square pictures
}

/// A colour per vertex id, scattered (a multiplicative hash), so that neighbouring
/// triangles look different and a triangle drawn with other corners or from the other
/// side shows.
pub fn vertex_colors(count: usize) -> Vec<[u8; 4]> {
    (0..count as u32)
        .map(|i| {
            let h = i.wrapping_mul(2_654_435_761);
            [(h >> 24) as u8, (h >> 16) as u8, (h >> 8) as u8, 255]
        })
        .collect()
}

/// One mesh's vertices uploaded twice, light grey (with normals when given) and in
/// [`vertex_colors`], ready for several index buffers and views.
pub struct Scene {
    pub renderer: Renderer,
    grey: stripkit_render::Geometry,
    colored: stripkit_render::Geometry,
}

impl Scene {
    /// Uploads `positions` (and `normals` for the lit pictures).
    pub fn new(mut renderer: Renderer, positions: &[[f32; 3]], normals: Option<&[[f32; 3]]>) -> Scene {
        let v = Vertices { normals, ..Vertices::new(positions) };
        let grey = renderer.upload(&v).expect("uploads the vertices");
        let colors = vertex_colors(positions.len());
        let colored = renderer.upload(&Vertices { colors: Some(&colors), ..v }).expect("uploads the vertices");
        Scene { renderer, grey, colored }
    }

    /// Draws `indices` of the grey vertices with `params` on a cleared framebuffer and
    /// reads the picture back.
    pub fn picture(&mut self, indices: &[u32], topology: Topology, width: IndexWidth, params: &DrawParams) -> Image {
        self.draw(false, indices, topology, width, params)
    }

    /// [`Scene::picture`] with the vertices in [`vertex_colors`].
    pub fn colored_picture(&mut self, indices: &[u32], topology: Topology, width: IndexWidth, params: &DrawParams) -> Image {
        self.draw(true, indices, topology, width, params)
    }

    fn draw(&mut self, colored: bool, indices: &[u32], topology: Topology, width: IndexWidth, params: &DrawParams) -> Image {
        let r = &mut self.renderer;
        let buf = r.upload_indices(indices, topology, width).expect("uploads the indices");
        r.clear(BACKGROUND);
        r.draw(if colored { &self.colored } else { &self.grey }, &buf, params);
        let image = r.read_image();
        assert_eq!(r.gl_error(), None, "GL error after drawing {} indices", indices.len());
        r.delete_indices(buf);
        image
    }
}

/// Depth test on (always), back faces culled, unlit: the settings under which a strip
/// must give exactly the list's picture.
pub fn exact(mvp: [f32; 16]) -> DrawParams {
    DrawParams { shading: Shading::Unlit, cull_back: true, ..DrawParams::new(mvp) }
}

/// Pixels other than the background.
pub fn covered(image: &Image) -> usize {
    image.pixels_other_than([0, 0, 0])
}

/// Pixels whose colour differs from `b`'s by more than `tolerance` in some channel, and
/// the largest channel difference.
pub fn color_difference(a: &Image, b: &Image, tolerance: u8) -> (usize, u8) {
    let mut count = 0;
    let mut max = 0;
    for (p, q) in a.rgba().chunks_exact(4).zip(b.rgba().chunks_exact(4)) {
        let d = p.iter().zip(q).map(|(x, y)| x.abs_diff(*y)).max().unwrap_or(0);
        max = max.max(d);
        count += usize::from(d > tolerance);
    }
    (count, max)
}

/// Triangles as a flat index list.
pub fn flat(tris: &[[u32; 3]]) -> Vec<u32> {
    tris.iter().flatten().copied().collect()
}

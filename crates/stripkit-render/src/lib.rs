//! Offscreen renderer for stripkit: surfaceless EGL, OpenGL ES 3, one framebuffer object.
//!
//! It draws what stripkit produces, the way a GPU reads it:
//! - triangle lists, and triangle strips with primitive restart
//!   (`GL_PRIMITIVE_RESTART_FIXED_INDEX`: 0xFFFF for u16 indices, 0xFFFFFFFF for u32);
//! - ranges of one strip buffer, one draw call each (the segment tree's multi-draw);
//! - morphs between two position buffers in the vertex shader, for deforming LoD.
//!
//! Pictures of strips need a little geometry, all over plain slices of positions and
//! indices: [`Framing`] places a camera tightly around the points drawn, [`paint`]
//! colours triangles by strip, by order or by facing, and [`wire`] turns edges into
//! thin bands of triangles for a wireframe; [`morph_positions`] is the shader's morph
//! on the CPU, for what is built from the drawn positions. [`draw_picture`] composes
//! them into a whole picture in one call (what `stripkit render` and the Python
//! package's `render` draw).
//!
//! It reads pixels back ([`Image`], PNG through the `png` crate), times draws, and counts
//! vertex-shader invocations where the context has storage buffers (GLES 3.1), which
//! measures how a GPU reuses shaded vertices.
//!
//! The same code runs on Mesa llvmpipe (CI, any Linux machine) and on NVIDIA GPUs through
//! NVIDIA's EGL driver. A machine without EGL gets [`RenderError::NoEgl`], which says
//! what to install; nothing is linked at build time.
//!
//! ```no_run
//! use stripkit_render::{Camera, DrawParams, IndexWidth, Renderer, Topology, Vertices};
//! let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]];
//! let mut r = Renderer::new(256, 256)?;
//! let geometry = r.upload(&Vertices::new(&positions))?;
//! let strip = r.upload_indices(&[0, 1, 2, 3], Topology::Strip, IndexWidth::U32)?;
//! let camera = Camera::fit([0.0; 3], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
//! r.clear([1.0; 3]);
//! r.draw(&geometry, &strip, &DrawParams::new(camera.view_proj(1.0)));
//! r.read_image().write_png(std::path::Path::new("quad.png"))?;
//! # Ok::<(), stripkit_render::RenderError>(())
//! ```

mod camera;
pub mod chart;
mod egl;
mod frame;
mod image;
mod morph;
mod normals;
pub mod paint;
mod picture;
mod shaders;
pub mod wire;

pub use camera::Camera;
pub use frame::{FrameError, Framing};
pub use image::Image;
pub use morph::morph_positions;
pub use normals::vertex_normals;
pub use picture::{draw_picture, ColorBy, Picture, PictureError, PictureOptions, Scene};

use glow::HasContext;
use std::time::{Duration, Instant};

/// Why rendering failed.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No EGL library, display or OpenGL ES 3 context; the text says what to install.
    #[error("{0}. {help}", help = egl::NO_EGL_HELP)]
    NoEgl(String),
    /// A GL call or shader failed; the text names it.
    #[error("OpenGL ES: {0}")]
    Gl(String),
    /// Input the renderer cannot draw (an index past the vertices, a u16 index too large).
    #[error("{0}")]
    Input(String),
    /// Writing a picture failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: std::path::PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}

/// Which GPU or software renderer draws, as GL reports it.
#[derive(Clone, Debug)]
pub struct DeviceInfo {
    /// `GL_VENDOR`.
    pub vendor: String,
    /// `GL_RENDERER`, for example "llvmpipe (LLVM 15.0.6, 256 bits)" or "NVIDIA H100 .../PCIe/SSE2".
    pub renderer: String,
    /// `GL_VERSION`.
    pub version: String,
    /// How EGL found the display: "device", "surfaceless" or "default".
    pub platform: &'static str,
    /// Whether vertex-shader invocations can be counted (GLES 3.1 storage buffers in the vertex stage).
    pub can_count_invocations: bool,
}

impl DeviceInfo {
    /// True for Mesa's software rasterisers.
    pub fn is_software(&self) -> bool {
        let r = self.renderer.to_ascii_lowercase();
        r.contains("llvmpipe") || r.contains("softpipe") || r.contains("swrast")
    }
}

/// Vertex data to upload: positions, and optionally normals, colours and morph targets.
#[derive(Clone, Copy, Debug)]
pub struct Vertices<'a> {
    /// Positions; the only required attribute.
    pub positions: &'a [[f32; 3]],
    /// Second positions for morphing (`DrawParams::morph`), same length.
    pub morph_target: Option<&'a [[f32; 3]]>,
    /// Per-vertex normals for smooth shading, same length.
    pub normals: Option<&'a [[f32; 3]]>,
    /// Per-vertex RGBA colours, same length; light grey without.
    pub colors: Option<&'a [[u8; 4]]>,
}

impl<'a> Vertices<'a> {
    /// Positions only.
    pub fn new(positions: &'a [[f32; 3]]) -> Self {
        Vertices { positions, morph_target: None, normals: None, colors: None }
    }
}

/// Uploaded vertices: a vertex array object and its buffers.
#[derive(Debug)]
pub struct Geometry {
    vao: glow::VertexArray,
    buffers: Vec<glow::Buffer>,
    vertex_count: usize,
    has_normals: bool,
}

impl Geometry {
    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }
}

/// How an index buffer is read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Topology {
    /// Three indices per triangle.
    Triangles,
    /// Triangle strips separated by the restart index of the index width.
    Strip,
}

/// Index type on the GPU.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IndexWidth {
    /// 16-bit indices, restart 0xFFFF; only for meshes of at most 65,535 vertices.
    U16,
    /// 32-bit indices, restart 0xFFFFFFFF.
    U32,
}

impl IndexWidth {
    /// u16 where every vertex index fits below the u16 restart value, else u32.
    pub fn smallest(vertex_count: usize) -> Self {
        if vertex_count <= 0xFFFF {
            IndexWidth::U16
        } else {
            IndexWidth::U32
        }
    }
}

/// Uploaded indices.
#[derive(Debug)]
pub struct IndexBuffer {
    buffer: glow::Buffer,
    count: usize,
    width: IndexWidth,
    topology: Topology,
}

impl IndexBuffer {
    /// Number of indices, restart indices included.
    pub fn len(&self) -> usize {
        self.count
    }
    /// True when it holds no index.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }
    /// The index width.
    pub fn width(&self) -> IndexWidth {
        self.width
    }
    /// The topology.
    pub fn topology(&self) -> Topology {
        self.topology
    }
}

/// How fragments are coloured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shading {
    /// Lit by the interpolated vertex normal (flat when the geometry has no normals).
    Smooth,
    /// Lit by each triangle's own normal, from screen-space derivatives.
    Flat,
    /// The vertex colour as it is.
    Unlit,
}

impl Shading {
    /// Every shading's name, as [`Shading::name`] gives it and `FromStr` reads it.
    pub const NAMES: &'static [&'static str] = &["flat", "smooth", "unlit"];

    /// The lowercase name (`flat`, `smooth`, `unlit`).
    pub fn name(self) -> &'static str {
        match self {
            Shading::Flat => "flat",
            Shading::Smooth => "smooth",
            Shading::Unlit => "unlit",
        }
    }
}

impl std::str::FromStr for Shading {
    type Err = String;

    /// Reads one of [`Shading::NAMES`].
    fn from_str(name: &str) -> Result<Self, String> {
        match name {
            "flat" => Ok(Shading::Flat),
            "smooth" => Ok(Shading::Smooth),
            "unlit" => Ok(Shading::Unlit),
            _ => Err(format!("`{name}` is not a shading: {}", Shading::NAMES.join(", "))),
        }
    }
}

/// One draw's settings.
#[derive(Clone, Debug)]
pub struct DrawParams {
    /// Model-view-projection matrix, column-major.
    pub mvp: [f32; 16],
    /// Morph weight between `positions` (0) and `morph_target` (1).
    pub morph: f32,
    /// Shading.
    pub shading: Shading,
    /// Matrix blends per vertex; 0 is a light vertex shader, 32 a heavy (skinning-like) one.
    pub heavy: u32,
    /// Cull back faces (counter-clockwise front faces, as glTF and OpenGL).
    pub cull_back: bool,
    /// Draw only these `(first index, index count)` ranges of the buffer, one draw call each.
    pub ranges: Option<Vec<(usize, usize)>>,
    /// Light direction (normalised in the shader's use).
    pub light: [f32; 3],
}

impl DrawParams {
    /// Light vertex shader, flat-lit faces, no culling, the whole buffer.
    pub fn new(mvp: [f32; 16]) -> Self {
        DrawParams {
            mvp,
            morph: 0.0,
            shading: Shading::Flat,
            heavy: 0,
            cull_back: false,
            ranges: None,
            light: [0.3, 0.5, 0.81],
        }
    }
}

/// Matrix blends per vertex of the "heavy" vertex shader used in timings.
pub const HEAVY_VERTEX_SHADER: u32 = 32;

struct Program {
    program: glow::Program,
    mvp: Option<glow::UniformLocation>,
    t: Option<glow::UniformLocation>,
    heavy: Option<glow::UniformLocation>,
    bone: Option<glow::UniformLocation>,
    shading: Option<glow::UniformLocation>,
    light: Option<glow::UniformLocation>,
}

/// An offscreen OpenGL ES renderer with its own EGL context and framebuffer.
///
/// Not `Send`: the context is current on the thread that made it.
pub struct Renderer {
    gl: glow::Context,
    // Dropped after `gl`'s objects are deleted in Drop.
    _egl: egl::EglContext,
    info: DeviceInfo,
    width: u32,
    height: u32,
    fbo: glow::Framebuffer,
    color: glow::Renderbuffer,
    depth: glow::Renderbuffer,
    program: Program,
    counting: Option<(Program, glow::Buffer)>,
    _not_send: std::marker::PhantomData<*const ()>,
}

impl Renderer {
    /// A renderer drawing into a `width` x `height` RGBA8 framebuffer with a 24-bit depth buffer.
    pub fn new(width: u32, height: u32) -> Result<Self, RenderError> {
        if width == 0 || height == 0 || width > 16384 || height > 16384 {
            return Err(RenderError::Input(format!("picture size {width}x{height} is outside 1..=16384")));
        }
        let egl = egl::EglContext::new()?;
        // SAFETY: the context is current on this thread; glow resolves entry points through EGL.
        let gl = unsafe { glow::Context::from_loader_function(|s| egl.proc_address(s)) };
        // SAFETY: plain GL queries and object creation on the current context.
        unsafe {
            let vendor = gl.get_parameter_string(glow::VENDOR);
            let renderer = gl.get_parameter_string(glow::RENDERER);
            let version = gl.get_parameter_string(glow::VERSION);
            let es31 = egl.version.1 >= 1;
            let vs_ssbo = es31 && gl.get_parameter_i32(glow::MAX_VERTEX_SHADER_STORAGE_BLOCKS) > 0;
            let version_tag = if es31 { "310 es" } else { "300 es" };
            let program = compile(&gl, &shaders::vertex(version_tag, false), &shaders::fragment(version_tag))?;
            let counting = if vs_ssbo {
                let p = compile(&gl, &shaders::vertex("310 es", true), &shaders::fragment("310 es")).ok();
                match p {
                    Some(p) => {
                        let buf = gl.create_buffer().map_err(RenderError::Gl)?;
                        Some((p, buf))
                    }
                    None => None,
                }
            } else {
                None
            };
            let info = DeviceInfo {
                vendor,
                renderer,
                version,
                platform: egl.platform,
                can_count_invocations: counting.is_some(),
            };
            let fbo = gl.create_framebuffer().map_err(RenderError::Gl)?;
            let color = gl.create_renderbuffer().map_err(RenderError::Gl)?;
            let depth = gl.create_renderbuffer().map_err(RenderError::Gl)?;
            let mut r = Renderer {
                gl,
                _egl: egl,
                info,
                width: 0,
                height: 0,
                fbo,
                color,
                depth,
                program,
                counting,
                _not_send: std::marker::PhantomData,
            };
            r.resize(width, height)?;
            r.gl.enable(glow::PRIMITIVE_RESTART_FIXED_INDEX);
            r.gl.enable(glow::DEPTH_TEST);
            r.gl.depth_func(glow::LESS);
            r.gl.front_face(glow::CCW);
            Ok(r)
        }
    }

    /// The GPU or software renderer in use.
    pub fn info(&self) -> &DeviceInfo {
        &self.info
    }

    /// Framebuffer size.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Reallocates the framebuffer at a new size.
    pub fn resize(&mut self, width: u32, height: u32) -> Result<(), RenderError> {
        if width == 0 || height == 0 || width > 16384 || height > 16384 {
            return Err(RenderError::Input(format!("picture size {width}x{height} is outside 1..=16384")));
        }
        let gl = &self.gl;
        // SAFETY: objects of this context; sizes checked above.
        unsafe {
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.fbo));
            gl.bind_renderbuffer(glow::RENDERBUFFER, Some(self.color));
            gl.renderbuffer_storage(glow::RENDERBUFFER, glow::RGBA8, width as i32, height as i32);
            gl.framebuffer_renderbuffer(glow::FRAMEBUFFER, glow::COLOR_ATTACHMENT0, glow::RENDERBUFFER, Some(self.color));
            gl.bind_renderbuffer(glow::RENDERBUFFER, Some(self.depth));
            gl.renderbuffer_storage(glow::RENDERBUFFER, glow::DEPTH_COMPONENT24, width as i32, height as i32);
            gl.framebuffer_renderbuffer(glow::FRAMEBUFFER, glow::DEPTH_ATTACHMENT, glow::RENDERBUFFER, Some(self.depth));
            let status = gl.check_framebuffer_status(glow::FRAMEBUFFER);
            if status != glow::FRAMEBUFFER_COMPLETE {
                return Err(RenderError::Gl(format!("framebuffer {width}x{height} incomplete (status {status:#x})")));
            }
            gl.viewport(0, 0, width as i32, height as i32);
        }
        self.width = width;
        self.height = height;
        Ok(())
    }

    /// Uploads vertices. Every optional attribute must have one entry per position.
    pub fn upload(&mut self, v: &Vertices) -> Result<Geometry, RenderError> {
        let n = v.positions.len();
        for (name, len) in [
            ("morph target", v.morph_target.map(<[_]>::len)),
            ("normal", v.normals.map(<[_]>::len)),
            ("colour", v.colors.map(<[_]>::len)),
        ] {
            if let Some(len) = len {
                if len != n {
                    return Err(RenderError::Input(format!("{len} {name} values for {n} vertices")));
                }
            }
        }
        let gl = &self.gl;
        // SAFETY: buffers sized from the slices they are filled with; attribute layouts match them.
        unsafe {
            let vao = gl.create_vertex_array().map_err(RenderError::Gl)?;
            gl.bind_vertex_array(Some(vao));
            let mut buffers = Vec::new();
            let pos = float_buffer(gl, v.positions)?;
            buffers.push(pos);
            attribute(gl, 0, pos, 3, glow::FLOAT, false);
            let pos2 = match v.morph_target {
                Some(t) => {
                    let b = float_buffer(gl, t)?;
                    buffers.push(b);
                    b
                }
                None => pos,
            };
            attribute(gl, 1, pos2, 3, glow::FLOAT, false);
            if let Some(nrm) = v.normals {
                let b = float_buffer(gl, nrm)?;
                buffers.push(b);
                attribute(gl, 2, b, 3, glow::FLOAT, false);
            } else {
                gl.disable_vertex_attrib_array(2);
                gl.vertex_attrib_3_f32(2, 0.0, 0.0, 1.0);
            }
            if let Some(col) = v.colors {
                let b = gl.create_buffer().map_err(RenderError::Gl)?;
                gl.bind_buffer(glow::ARRAY_BUFFER, Some(b));
                gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, col.as_flattened(), glow::STATIC_DRAW);
                buffers.push(b);
                attribute(gl, 3, b, 4, glow::UNSIGNED_BYTE, true);
            } else {
                gl.disable_vertex_attrib_array(3);
                gl.vertex_attrib_4_f32(3, 0.8, 0.8, 0.8, 1.0);
            }
            gl.bind_vertex_array(None);
            Ok(Geometry { vao, buffers, vertex_count: n, has_normals: v.normals.is_some() })
        }
    }

    /// Uploads indices. `u32::MAX` in a strip buffer is the restart index; with
    /// [`IndexWidth::U16`] it becomes 0xFFFF, and any other index must be below 0xFFFF.
    pub fn upload_indices(&mut self, indices: &[u32], topology: Topology, width: IndexWidth) -> Result<IndexBuffer, RenderError> {
        let gl = &self.gl;
        // SAFETY: the buffer is filled from a slice it is sized by.
        unsafe {
            let buffer = gl.create_buffer().map_err(RenderError::Gl)?;
            gl.bind_vertex_array(None);
            gl.bind_buffer(glow::ELEMENT_ARRAY_BUFFER, Some(buffer));
            match width {
                IndexWidth::U32 => {
                    let bytes: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
                    gl.buffer_data_u8_slice(glow::ELEMENT_ARRAY_BUFFER, &bytes, glow::STATIC_DRAW);
                }
                IndexWidth::U16 => {
                    let mut bytes = Vec::with_capacity(indices.len() * 2);
                    for &i in indices {
                        let v = if i == u32::MAX {
                            0xFFFF
                        } else if i < 0xFFFF {
                            i as u16
                        } else {
                            gl.delete_buffer(buffer);
                            return Err(RenderError::Input(format!(
                                "index {i} does not fit a u16 index buffer (0xFFFF is its restart index, so \
                                 vertices 0 to 65534 only); upload u32 indices"
                            )));
                        };
                        bytes.extend_from_slice(&v.to_le_bytes());
                    }
                    gl.buffer_data_u8_slice(glow::ELEMENT_ARRAY_BUFFER, &bytes, glow::STATIC_DRAW);
                }
            }
            gl.bind_buffer(glow::ELEMENT_ARRAY_BUFFER, None);
            Ok(IndexBuffer { buffer, count: indices.len(), width, topology })
        }
    }

    /// Frees uploaded vertices.
    pub fn delete_geometry(&mut self, g: Geometry) {
        // SAFETY: objects of this context, not used after this.
        unsafe {
            self.gl.delete_vertex_array(g.vao);
            for b in g.buffers {
                self.gl.delete_buffer(b);
            }
        }
    }

    /// Frees uploaded indices.
    pub fn delete_indices(&mut self, i: IndexBuffer) {
        // SAFETY: an object of this context, not used after this.
        unsafe { self.gl.delete_buffer(i.buffer) }
    }

    /// Clears colour to `rgb` and depth to the far plane.
    pub fn clear(&mut self, rgb: [f32; 3]) {
        // SAFETY: state calls on the current context.
        unsafe {
            self.gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.fbo));
            self.gl.clear_color(rgb[0], rgb[1], rgb[2], 1.0);
            self.gl.clear_depth_f32(1.0);
            self.gl.depth_mask(true);
            self.gl.clear(glow::COLOR_BUFFER_BIT | glow::DEPTH_BUFFER_BIT);
        }
    }

    /// Draws `indices` of `geometry` with `params`.
    pub fn draw(&mut self, geometry: &Geometry, indices: &IndexBuffer, params: &DrawParams) {
        self.draw_with(false, geometry, indices, params);
    }

    fn draw_with(&self, counting: bool, geometry: &Geometry, indices: &IndexBuffer, params: &DrawParams) {
        let gl = &self.gl;
        let program = match (&self.counting, counting) {
            (Some((p, _)), true) => p,
            _ => &self.program,
        };
        let shading = match params.shading {
            Shading::Smooth if geometry.has_normals => 0,
            Shading::Smooth | Shading::Flat => 1,
            Shading::Unlit => 2,
        };
        let (ty, size) = match indices.width {
            IndexWidth::U16 => (glow::UNSIGNED_SHORT, 2),
            IndexWidth::U32 => (glow::UNSIGNED_INT, 4),
        };
        let mode = match indices.topology {
            Topology::Triangles => glow::TRIANGLES,
            Topology::Strip => glow::TRIANGLE_STRIP,
        };
        // Four identity matrices: the heavy shader's blends cost work, not change.
        let mut bones = [0f32; 64];
        for m in bones.chunks_exact_mut(16) {
            m.copy_from_slice(&glam::Mat4::IDENTITY.to_cols_array());
        }
        // SAFETY: objects of this context; ranges are clamped to the buffer.
        unsafe {
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.fbo));
            gl.use_program(Some(program.program));
            gl.uniform_matrix_4_f32_slice(program.mvp.as_ref(), false, &params.mvp);
            gl.uniform_1_f32(program.t.as_ref(), params.morph);
            gl.uniform_1_i32(program.heavy.as_ref(), params.heavy as i32);
            gl.uniform_matrix_4_f32_slice(program.bone.as_ref(), false, &bones);
            gl.uniform_1_i32(program.shading.as_ref(), shading);
            let l = glam::Vec3::from(params.light).normalize_or_zero();
            gl.uniform_3_f32(program.light.as_ref(), l.x, l.y, l.z);
            if params.cull_back {
                gl.enable(glow::CULL_FACE);
                gl.cull_face(glow::BACK);
            } else {
                gl.disable(glow::CULL_FACE);
            }
            gl.bind_vertex_array(Some(geometry.vao));
            gl.bind_buffer(glow::ELEMENT_ARRAY_BUFFER, Some(indices.buffer));
            match &params.ranges {
                None => gl.draw_elements(mode, indices.count as i32, ty, 0),
                Some(ranges) => {
                    for &(first, count) in ranges {
                        let first = first.min(indices.count);
                        let count = count.min(indices.count - first);
                        if count > 0 {
                            gl.draw_elements(mode, count as i32, ty, (first * size) as i32);
                        }
                    }
                }
            }
            gl.bind_vertex_array(None);
        }
    }

    /// Waits until every queued command has finished.
    pub fn finish(&mut self) {
        // SAFETY: a plain GL call.
        unsafe { self.gl.finish() }
    }

    /// Mean wall time of one draw over `draws` draws, after one untimed draw, the queue
    /// drained before and after. Draw `i` uses `views[(first_view + i) % views.len()]`
    /// as its matrix (a camera path), or `params.mvp` when `views` is empty.
    pub fn time_draws(
        &mut self,
        geometry: &Geometry,
        indices: &IndexBuffer,
        params: &DrawParams,
        views: &[[f32; 16]],
        first_view: usize,
        draws: u32,
    ) -> Duration {
        let mut p = params.clone();
        self.clear([0.0; 3]);
        self.draw(geometry, indices, &p);
        self.finish();
        let start = Instant::now();
        for i in 0..draws.max(1) as usize {
            if !views.is_empty() {
                p.mvp = views[(first_view + i) % views.len()];
            }
            self.draw(geometry, indices, &p);
        }
        self.finish();
        start.elapsed() / draws.max(1)
    }

    /// How many times the vertex shader ran for one draw, where the context can count
    /// (see [`DeviceInfo::can_count_invocations`]). A GPU that reuses every shaded vertex
    /// gives the vertex count; one that shades every index gives the index count.
    pub fn count_vertex_invocations(&mut self, geometry: &Geometry, indices: &IndexBuffer, params: &DrawParams) -> Option<u64> {
        let (_, buf) = self.counting.as_ref()?;
        let buf = *buf;
        // SAFETY: a 4-byte storage buffer bound at binding 0, read back after the draw.
        unsafe {
            self.gl.bind_buffer(glow::SHADER_STORAGE_BUFFER, Some(buf));
            self.gl.buffer_data_u8_slice(glow::SHADER_STORAGE_BUFFER, &[0u8; 4], glow::DYNAMIC_READ);
            self.gl.bind_buffer_base(glow::SHADER_STORAGE_BUFFER, 0, Some(buf));
        }
        self.draw_with(true, geometry, indices, params);
        // SAFETY: reads the 4-byte buffer written above.
        unsafe {
            self.gl.memory_barrier(glow::BUFFER_UPDATE_BARRIER_BIT);
            self.gl.bind_buffer(glow::SHADER_STORAGE_BUFFER, Some(buf));
            let ptr = self.gl.map_buffer_range(glow::SHADER_STORAGE_BUFFER, 0, 4, glow::MAP_READ_BIT);
            if ptr.is_null() {
                return None;
            }
            let v = std::ptr::read_unaligned(ptr as *const u32);
            self.gl.unmap_buffer(glow::SHADER_STORAGE_BUFFER);
            self.gl.bind_buffer(glow::SHADER_STORAGE_BUFFER, None);
            Some(v as u64)
        }
    }

    /// Reads the framebuffer back, top row first.
    pub fn read_image(&mut self) -> Image {
        let (w, h) = (self.width as usize, self.height as usize);
        let mut rgba = vec![0u8; w * h * 4];
        // SAFETY: the buffer holds exactly width x height RGBA8 pixels.
        unsafe {
            self.gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.fbo));
            self.gl.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
            self.gl.read_pixels(
                0,
                0,
                w as i32,
                h as i32,
                glow::RGBA,
                glow::UNSIGNED_BYTE,
                glow::PixelPackData::Slice(Some(&mut rgba)),
            );
        }
        // GL's first row is the bottom one.
        let row = w * 4;
        let mut flipped = vec![0u8; rgba.len()];
        for y in 0..h {
            flipped[y * row..(y + 1) * row].copy_from_slice(&rgba[(h - 1 - y) * row..(h - y) * row]);
        }
        Image::new(w as u32, h as u32, flipped)
    }

    /// The first pending GL error, if any.
    pub fn gl_error(&self) -> Option<u32> {
        // SAFETY: a plain GL query.
        let e = unsafe { self.gl.get_error() };
        (e != glow::NO_ERROR).then_some(e)
    }
}

impl Drop for Renderer {
    fn drop(&mut self) {
        // SAFETY: objects of this context, deleted before the context goes.
        unsafe {
            self.gl.delete_framebuffer(self.fbo);
            self.gl.delete_renderbuffer(self.color);
            self.gl.delete_renderbuffer(self.depth);
            self.gl.delete_program(self.program.program);
            if let Some((p, b)) = self.counting.take() {
                self.gl.delete_program(p.program);
                self.gl.delete_buffer(b);
            }
        }
    }
}

unsafe fn float_buffer(gl: &glow::Context, data: &[[f32; 3]]) -> Result<glow::Buffer, RenderError> {
    let b = gl.create_buffer().map_err(RenderError::Gl)?;
    gl.bind_buffer(glow::ARRAY_BUFFER, Some(b));
    let bytes: Vec<u8> = data.as_flattened().iter().flat_map(|f| f.to_le_bytes()).collect();
    gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, &bytes, glow::STATIC_DRAW);
    Ok(b)
}

unsafe fn attribute(gl: &glow::Context, loc: u32, buffer: glow::Buffer, n: i32, ty: u32, normalized: bool) {
    gl.bind_buffer(glow::ARRAY_BUFFER, Some(buffer));
    gl.enable_vertex_attrib_array(loc);
    gl.vertex_attrib_pointer_f32(loc, n, ty, normalized, 0, 0);
}

unsafe fn compile(gl: &glow::Context, vs: &str, fs: &str) -> Result<Program, RenderError> {
    let program = gl.create_program().map_err(RenderError::Gl)?;
    let mut shaders = Vec::new();
    for (kind, src, name) in [(glow::VERTEX_SHADER, vs, "vertex"), (glow::FRAGMENT_SHADER, fs, "fragment")] {
        let s = gl.create_shader(kind).map_err(RenderError::Gl)?;
        gl.shader_source(s, src);
        gl.compile_shader(s);
        if !gl.get_shader_compile_status(s) {
            let log = gl.get_shader_info_log(s);
            gl.delete_shader(s);
            gl.delete_program(program);
            return Err(RenderError::Gl(format!("{name} shader: {log}")));
        }
        gl.attach_shader(program, s);
        shaders.push(s);
    }
    gl.link_program(program);
    for s in shaders {
        gl.detach_shader(program, s);
        gl.delete_shader(s);
    }
    if !gl.get_program_link_status(program) {
        let log = gl.get_program_info_log(program);
        gl.delete_program(program);
        return Err(RenderError::Gl(format!("link: {log}")));
    }
    let u = |name: &str| gl.get_uniform_location(program, name);
    Ok(Program {
        program,
        mvp: u("u_mvp"),
        t: u("u_t"),
        heavy: u("u_heavy"),
        bone: u("u_bone"),
        shading: u("u_shading"),
        light: u("u_light"),
    })
}

//! A whole picture of strips in one call: framing, colours by strip, order or facing,
//! shading and an optional wireframe, over plain slices (positions and numbered
//! triangles). `stripkit render` and the Python package's `render` both draw through
//! [`draw_picture`], so that they make the same pixels from the same input.

use crate::paint::{self, Paint};
use crate::{
    vertex_normals, wire, DrawParams, FrameError, Framing, Image, IndexWidth, RenderError, Renderer, Shading,
    Topology, Vertices,
};

/// What the colours of a picture show.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ColorBy {
    /// Each group of triangles (a strip) its own colour ([`paint::strip_color`]).
    Strips,
    /// A gradient along the order of the triangles ([`paint::gradient`]).
    Order,
    /// Facing an eye in `view` (the picture's view direction when `None`), at the
    /// camera's distance: [`paint::FRONT`] or [`paint::BACK`].
    Cull {
        /// The direction of the eye that judges facing.
        view: Option<[f32; 3]>,
    },
    /// One grey ([`paint::GREY`]).
    None,
}

/// How a picture is taken: size, camera, colours, lighting.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PictureOptions {
    /// Width and height in pixels.
    pub size: (u32, u32),
    /// Direction from the model's centre towards the eye.
    pub view: [f32; 3],
    /// The direction that points up in the picture.
    pub up: [f32; 3],
    /// Vertical field of view in degrees.
    pub fov_y_degrees: f32,
    /// Magnification of the middle of the picture (1: none).
    pub zoom: f32,
    /// Background colour.
    pub background: [u8; 3],
    /// Lighting.
    pub shading: Shading,
    /// Also draw every edge of the triangles as a dark line.
    pub wireframe: bool,
    /// What the colours show.
    pub color_by: ColorBy,
}

impl Default for PictureOptions {
    /// `stripkit render`'s defaults: 800x800, view 0.3,0.4,1, up 0,1,0, 30 degrees, no
    /// zoom, white, flat shading, no wireframe, colours by strip.
    fn default() -> Self {
        PictureOptions {
            size: (800, 800),
            view: [0.3, 0.4, 1.0],
            up: [0.0, 1.0, 0.0],
            fov_y_degrees: 30.0,
            zoom: 1.0,
            background: [255; 3],
            shading: Shading::Flat,
            wireframe: false,
            color_by: ColorBy::Strips,
        }
    }
}

impl PictureOptions {
    /// Refuses directions no camera can take (checked without any point or GPU, so
    /// that a caller can refuse them before any work).
    pub fn check(&self) -> Result<(), PictureError> {
        Framing::fit(&[[0.0; 3]], self.view, self.up, self.fov_y_degrees, self.zoom, 1.0)?;
        if let ColorBy::Cull { view: Some(v) } = self.color_by {
            if !v.iter().all(|x| x.is_finite()) || v == [0.0; 3] {
                return Err(PictureError::ZeroCullView);
            }
        }
        Ok(())
    }
}

/// What a picture shows, as plain slices.
#[derive(Clone, Copy, Debug)]
pub struct Scene<'a> {
    /// Vertex positions.
    pub positions: &'a [[f32; 3]],
    /// The triangles in drawing order, each with the number of its group (strip), with
    /// the winding to draw; triangles with a repeated index are left out by the caller.
    pub triangles: &'a [(usize, [u32; 3])],
    /// A morph target (one position per vertex) and the weight towards it, 0 to 1.
    pub morph: Option<(&'a [[f32; 3]], f32)>,
    /// The points the camera frames (the vertices the faces use, of both meshes when
    /// morphing, so that pictures at several weights line up).
    pub frame: &'a [[f32; 3]],
    /// Every position and point is multiplied by this first (a power of two, such as
    /// `stripkit::unit_scale` of `frame`, keeps it exact; 1: none).
    pub scale: f32,
}

/// A picture and what it counted.
#[derive(Clone, Debug)]
pub struct Picture {
    /// The pixels.
    pub image: Image,
    /// Triangles drawn.
    pub triangles: usize,
    /// [`ColorBy::Cull`]: triangles facing the eye (0 otherwise).
    pub front: usize,
    /// With a wireframe: edges drawn.
    pub edges: Option<usize>,
}

/// Why a picture could not be taken.
#[derive(Debug, thiserror::Error)]
pub enum PictureError {
    /// The camera could not be framed.
    #[error(transparent)]
    Frame(#[from] FrameError),
    /// [`ColorBy::Cull`] with a zero view.
    #[error("the view direction of the facing colours must not be 0,0,0")]
    ZeroCullView,
    /// No triangle to draw.
    #[error("no faces to draw (every triangle is degenerate)")]
    NoFaces,
    /// The renderer failed.
    #[error(transparent)]
    Render(#[from] RenderError),
}

/// Edges of a wireframe drawn at a time: about 19 MB of bands, colours and indices
/// (and the driver's copy), where the whole wireframe of 2 million edges took 650 MB
/// more and aborted under a 1.5 GB address-space limit.
const WIRE_EDGES_AT_A_TIME: usize = 1 << 16;

fn scaled(points: &[[f32; 3]], scale: f32) -> Vec<[f32; 3]> {
    if scale == 1.0 {
        return points.to_vec();
    }
    points.iter().map(|p| p.map(|x| x * scale)).collect()
}

/// Takes the picture of `scene`: frames the camera around `scene.frame`, colours the
/// triangles as `options.color_by` says, draws them lit by `options.shading` (and the
/// wireframe), and reads the pixels back. The renderer is resized to `options.size`
/// where it has another size. Every index must be below `scene.positions.len()`.
pub fn draw_picture(renderer: &mut Renderer, scene: &Scene, options: &PictureOptions) -> Result<Picture, PictureError> {
    let (w, h) = options.size;
    let framing = {
        let points = scaled(scene.frame, scene.scale);
        Framing::fit(&points, options.view, options.up, options.fov_y_degrees, options.zoom, w as f32 / h as f32)?
    };
    if let Some(&(_, t)) = scene.triangles.iter().find(|(_, t)| t.iter().any(|&v| v as usize >= scene.positions.len())) {
        return Err(RenderError::Input(format!("triangle {t:?} indexes past {} vertices", scene.positions.len())).into());
    }
    let positions = scaled(scene.positions, scene.scale);
    let target = scene.morph.map(|(o, t)| (scaled(o, scene.scale), t));
    if target.as_ref().is_some_and(|(o, _)| o.len() != positions.len()) {
        return Err(RenderError::Input("the morph target needs one position per vertex".into()).into());
    }
    let blended = target.as_ref().map(|(other, t)| crate::morph_positions(&positions, other, *t));
    let drawn = blended.as_deref().unwrap_or(&positions);
    let paint = match options.color_by {
        ColorBy::Strips => Paint::Strips,
        ColorBy::Order => Paint::Order,
        ColorBy::Cull { view } => {
            Paint::Cull { eye: framing.eye_towards(view.unwrap_or(options.view)).ok_or(PictureError::ZeroCullView)? }
        }
        ColorBy::None => Paint::None,
    };
    let exploded = paint::explode(scene.triangles, drawn, paint);
    if exploded.triangles() == 0 {
        return Err(PictureError::NoFaces);
    }
    if renderer.size() != (w, h) {
        renderer.resize(w, h)?;
    }

    let gathered = exploded.gather(&positions);
    let morph_target = target.as_ref().map(|(o, _)| exploded.gather(o));
    let normals =
        (options.shading == Shading::Smooth).then(|| exploded.gather(&vertex_normals(drawn, &exploded.corners)));
    let geometry = renderer.upload(&Vertices {
        positions: &gathered,
        morph_target: morph_target.as_deref(),
        normals: normals.as_deref(),
        colors: Some(&exploded.colors),
    })?;
    let corners: Vec<u32> = (0..exploded.corners.len() as u32).collect();
    let indices = renderer.upload_indices(&corners, Topology::Triangles, IndexWidth::smallest(corners.len()))?;
    renderer.clear(options.background.map(|c| c as f32 / 255.0));
    let mut params = DrawParams::new(framing.camera.view_proj(w as f32 / h as f32));
    params.morph = target.as_ref().map_or(0.0, |(_, t)| *t);
    params.shading = options.shading;
    params.light = framing.light();
    renderer.draw(&geometry, &indices, &params);
    let mut edges = None;
    if options.wireframe {
        let mut line_params = params.clone();
        line_params.morph = 0.0;
        line_params.shading = Shading::Unlit;
        edges = Some(draw_wireframe(renderer, &exploded.corners, drawn, &framing, options.size, &line_params)?);
    }
    let error = renderer.gl_error();
    let image = renderer.read_image();
    renderer.delete_geometry(geometry);
    renderer.delete_indices(indices);
    if let Some(e) = error {
        return Err(RenderError::Gl(format!("drawing failed (GL error {e:#x})")).into());
    }
    Ok(Picture { image, triangles: exploded.triangles(), front: exploded.front, edges })
}

/// Draws the wireframe of the triangles at `corners` a slice of edges at a time (the
/// same picture as all at once: the slices are drawn in order); returns the number of
/// edges drawn.
fn draw_wireframe(
    renderer: &mut Renderer,
    corners: &[u32],
    drawn: &[[f32; 3]],
    framing: &Framing,
    size: (u32, u32),
    params: &DrawParams,
) -> Result<usize, RenderError> {
    let all = wire::edges(corners);
    let mut count = 0;
    for slice in all.chunks(WIRE_EDGES_AT_A_TIME) {
        let band = wire::wireframe_of(drawn, slice, &framing.camera, size);
        count += band.len() / 6;
        let colors = vec![paint::WIRE; band.len()];
        let lines =
            renderer.upload(&Vertices { positions: &band, morph_target: None, normals: None, colors: Some(&colors) })?;
        let order: Vec<u32> = (0..band.len() as u32).collect();
        let indices = renderer.upload_indices(&order, Topology::Triangles, IndexWidth::smallest(order.len()))?;
        renderer.draw(&lines, &indices, params);
        renderer.delete_geometry(lines);
        renderer.delete_indices(indices);
    }
    Ok(count)
}

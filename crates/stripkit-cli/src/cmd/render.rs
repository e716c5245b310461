//! `stripkit render`: a picture of the strips stripkit makes, drawn offscreen through
//! EGL and OpenGL ES (`stripkit-render`; Mesa's llvmpipe where there is no GPU).
//!
//! The strips come from the same door and the same flags as `stripkit strip`; they are
//! exploded into a triangle list in strip order (`stripkit_render::paint::explode`) so that each
//! triangle can carry its strip's colour, its place in the strip order, or its facing.
//! The picture (framing, colours, shading, wireframe) is `stripkit-render`'s
//! [`draw_picture`], which the Python package's `render` calls too.

mod input;
mod report;
pub mod values;

use clap::ValueEnum;
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;
use stripkit::Error;
use stripkit_render::{draw_picture, ColorBy, FrameError, PictureError, PictureOptions, Renderer, Scene, Shading};

use super::strip::{heuristic_of, StripArgs};

/// What the colours show.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ColorArg {
    /// Each strip its own colour (golden-ratio hues, so that strips made one after the
    /// other differ strongly).
    Strips,
    /// A gradient along the strip order, blue (first triangle of the first strip) to
    /// red (last triangle of the last strip): shows the walk a cache-aware order takes,
    /// or the course of a single strip.
    Order,
    /// Triangles facing the eye of `--cull-view` (default `--view`) in blue, those turned
    /// away from it, which back-face culling skips, in a light pink. Per triangle;
    /// `stripkit cull` measures the ranges of the strip buffer that the segment tree
    /// (issue #18) draws and culls.
    Cull,
    /// Plain grey.
    None,
}

/// Arguments of `stripkit render`.
#[derive(clap::Args, Debug)]
#[command(
    after_help = "The strips are those `stripkit strip` writes with the same --algo and flags, verified as always.\n\
Needs EGL and OpenGL ES 3 at run time (libEGL.so.1, libGLESv2.so.2): a GPU driver, or Mesa's \
software renderer (Debian, Ubuntu: apt-get install libegl1 libegl-mesa0 libgles2 libgl1-mesa-dri).\n\
Exit status: 0 success, 1 the strips failed verification, 2 bad input or argument, or no EGL (nothing written)."
)]
pub struct Args {
    /// Input mesh (.obj, .ply, .off, .stl, .gltf, .glb, optionally .gz); polygons are
    /// fanned into triangles. Or a `.sets` / `.lodseq` model (`stripkit lod`), drawn with
    /// its own strips at `--level` / `--ratio` (and `--frame`).
    pub input: PathBuf,
    /// Output picture (.png), replaced atomically.
    #[arg(short, long, value_name = "OUT.png")]
    pub output: PathBuf,
    #[command(flatten)]
    pub strip: StripArgs,
    /// What the colours show: `strips`, `order`, `cull` or `none`.
    #[arg(long, value_enum, default_value = "strips")]
    pub color: ColorArg,
    /// Direction from the model's centre towards the eye, X,Y,Z (any length).
    #[arg(long, value_name = "X,Y,Z", default_value = "0.3,0.4,1", value_parser = values::parse_vec3, allow_hyphen_values = true)]
    pub view: [f32; 3],
    /// `--color cull`: judge facing from an eye in this direction instead of `--view`
    /// (at the same distance), to see from the side what an eye there would cull.
    #[arg(long, value_name = "X,Y,Z", value_parser = values::parse_vec3, allow_hyphen_values = true)]
    pub cull_view: Option<[f32; 3]>,
    /// The direction that points up in the picture, X,Y,Z (not parallel to `--view`).
    #[arg(long, value_name = "X,Y,Z", default_value = "0,1,0", value_parser = values::parse_vec3, allow_hyphen_values = true)]
    pub up: [f32; 3],
    /// Vertical field of view in degrees, 1 to 120. The camera stands as far back as the
    /// model needs to fill the picture.
    #[arg(long, value_name = "DEGREES", default_value_t = 30.0, value_parser = values::parse_fov)]
    pub fov: f32,
    /// Magnify the middle of the picture this many times, 1 to 100 (the camera stays
    /// where it frames the whole model): a detail, to follow single strips on a large mesh.
    #[arg(long, value_name = "F", default_value_t = 1.0, value_parser = values::parse_zoom)]
    pub zoom: f32,
    /// Picture size in pixels, WIDTHxHEIGHT, each 16 to 4096.
    #[arg(long, value_name = "WxH", default_value = "800x800", value_parser = values::parse_wh)]
    pub size: (u32, u32),
    /// Background colour: `#rrggbb`, `rrggbb` or `R,G,B` (0 to 255 each).
    #[arg(long, value_name = "COLOR", default_value = "#ffffff", value_parser = values::parse_rgb)]
    pub background: [u8; 3],
    /// Lighting: `flat` (each triangle by its own normal), `smooth` (vertex normals) or
    /// `unlit` (exact colours).
    #[arg(long, default_value = "flat", value_parser = super::named::<Shading>(Shading::NAMES))]
    pub shading: Shading,
    /// Also draw every edge of the triangles, a dark line about a pixel wide (wider on
    /// large pictures), hidden where a face is in front of it: shows how strips split
    /// quads and where their triangles run.
    #[arg(long)]
    pub wireframe: bool,
    /// A second mesh with the same vertices (say, another frame of an animation): the
    /// picture shows the mesh morphed towards it by `--t`, on the GPU; the strips are
    /// those of MESH, and the camera frames both meshes, so that the pictures of one
    /// pair at several `--t` line up as frames.
    #[arg(long, value_name = "OTHER")]
    pub morph: Option<PathBuf>,
    /// `--morph`: 0 draws MESH, 1 draws OTHER, in between the linear blend. Default 0.5.
    #[arg(long, value_name = "T", requires = "morph", value_parser = values::parse_unit)]
    pub t: Option<f32>,
    /// A `.sets` or `.lodseq` input (`stripkit lod`): draw its own strips at this level
    /// (collapses applied; default 0, the input).
    #[arg(long, value_name = "L", conflicts_with = "ratio")]
    pub level: Option<u32>,
    /// A `.sets` or `.lodseq` input: draw the first level with at most
    /// ceil(R x triangles) triangles.
    #[arg(long, value_name = "R", value_parser = values::parse_unit)]
    pub ratio: Option<f32>,
    /// A `.lodseq` input: the frame (a fraction morphs between key frames; the level
    /// follows the nearest one). Default 0.
    #[arg(long, value_name = "F")]
    pub frame: Option<f64>,
    /// Print one JSON object (counts, sizes, timings, renderer) on stdout instead of the summary.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: super::ReadArgs,
}

/// Arguments that can be refused before any file is read.
fn check(args: &Args) -> anyhow::Result<()> {
    let is_png = args.output.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png {
        return Err(Error::Invalid(format!("{}: the picture must be a .png file", args.output.display())).into());
    }
    let mut inputs = vec![("input", args.input.as_path())];
    if let Some(morph) = &args.morph {
        inputs.push(("--morph", morph.as_path()));
    }
    super::check_not_inputs(&inputs, &[("-o", &args.output)])?;
    super::check_output_folder(&args.output)?;
    if args.cull_view.is_some() && args.color != ColorArg::Cull {
        return Err(Error::Invalid("--cull-view applies to --color cull".into()).into());
    }
    args.strip.validate(|o| o)
}

/// The picture's options from the flags.
fn options(args: &Args) -> PictureOptions {
    PictureOptions {
        size: args.size,
        view: args.view,
        up: args.up,
        fov_y_degrees: args.fov,
        zoom: args.zoom,
        background: args.background,
        shading: args.shading,
        wireframe: args.wireframe,
        color_by: match args.color {
            ColorArg::Strips => ColorBy::Strips,
            ColorArg::Order => ColorBy::Order,
            ColorArg::Cull => ColorBy::Cull { view: args.cull_view },
            ColorArg::None => ColorBy::None,
        },
    }
}

/// A picture error as the CLI's error, naming the flags and the input.
fn picture_error(e: PictureError, args: &Args) -> anyhow::Error {
    match e {
        PictureError::Frame(FrameError::ZeroView) => Error::Invalid("--view must not be 0,0,0".into()).into(),
        PictureError::Frame(FrameError::BadUp) => {
            Error::Invalid("--up must not be 0,0,0 nor parallel to --view".into()).into()
        }
        PictureError::Frame(e @ FrameError::NothingToFrame) => Error::Invalid(e.to_string()).into(),
        PictureError::ZeroCullView => Error::Invalid("--cull-view must not be 0,0,0".into()).into(),
        PictureError::NoFaces => {
            Error::Invalid(format!("no faces in {} (every triangle is degenerate)", args.input.display())).into()
        }
        PictureError::Render(e) => e.into(),
    }
}

/// Runs the command: read -> frame -> door -> explode and colour -> draw -> PNG.
pub fn run(args: Args) -> anyhow::Result<()> {
    check(&args)?;
    let progress = indicatif::ProgressBar::new_spinner();
    progress.enable_steady_tick(std::time::Duration::from_millis(120));
    progress.set_message(format!("reading {}", args.input.display()));
    let lod = input::read_lod(&args)?;
    let (mesh, target) = match &lod {
        Some((mesh, _, _)) => (mesh.clone(), None),
        None => input::read_meshes(&args)?,
    };
    let t = if target.is_some() { args.t.unwrap_or(0.5) } else { 0.0 };

    // The camera frames every vertex a face uses, of both meshes when morphing, so
    // that the pictures of one pair at several t line up.
    let (w, h) = args.size;
    let options = options(&args);
    options.check().map_err(|e| picture_error(e, &args))?;
    let mut points = mesh.used_positions();
    if let Some(other) = &target {
        points.extend(other.used_positions());
    }
    // Any finite scale is drawn in a frame near unit size (a power of two: exact), so
    // single precision neither overflows in the projection nor falls under the
    // framing's smallest extents.
    let scale = stripkit::unit_scale(&points) as f32;

    // Fail before the stripifier's work where nothing can draw.
    progress.set_message("starting the renderer");
    let start = Instant::now();
    let mut renderer = Renderer::new(w, h)?;
    let start_time = start.elapsed();

    progress.set_message(format!("stripifying and verifying {} triangles", mesh.triangle_count()));
    // A level of detail draws its own strips; a mesh goes through the door.
    let door = match &lod {
        Some(_) => None,
        None => Some(args.strip.stripify(&mesh, &args.input, |o| o)?),
    };
    let (strip_set, positions, target_positions) = match (&door, &lod) {
        // `single` may add vertices (edge midpoints): every per-vertex array gets them.
        (Some(strips), _) => (
            strips.strips.clone(),
            strips.with_added_vertices(&mesh.positions),
            target.as_ref().map(|o| strips.with_added_vertices(&o.positions)),
        ),
        (None, Some((mesh, strips, _))) => (strips.clone(), mesh.positions.clone(), None),
        (None, None) => unreachable!("a mesh goes through the door"),
    };

    progress.set_message("drawing");
    let triangles = input::strip_triangles(&strip_set);
    let scene = Scene {
        positions: &positions,
        triangles: &triangles,
        morph: target_positions.as_deref().map(|o| (o, t)),
        frame: &points,
        scale,
    };
    let draw_start = Instant::now();
    let picture = draw_picture(&mut renderer, &scene, &options).map_err(|e| picture_error(e, &args))?;
    let draw_time = draw_start.elapsed();
    let image = &picture.image;
    let pixels = image.pixels_other_than(args.background);
    progress.set_message(format!("writing {}", args.output.display()));
    let write_start = Instant::now();
    stripkit::io::write_encoded(&args.output, &image.encode_png_rgb())?;
    let write_time = write_start.elapsed();
    progress.finish_and_clear();

    let report = report::Report {
        input: &args.input,
        output: &args.output,
        algo: door.as_ref().map_or("lod", |s| s.algorithm.name()),
        heuristic: door.as_ref().and_then(|s| heuristic_of(&s.algorithm)),
        color: args.color,
        shading: args.shading,
        width: w,
        height: h,
        strips: strip_set.iter().filter(|s| !s.is_empty()).count(),
        triangles: picture.triangles,
        front: (args.color == ColorArg::Cull).then_some(picture.front),
        pixels,
        edges: picture.edges,
        stripify_ms: door.as_ref().map_or(0.0, |s| s.stripify_time.as_secs_f64() * 1e3),
        lod: lod.as_ref().map(|l| l.2.clone()),
        start_ms: start_time.as_secs_f64() * 1e3,
        draw_ms: draw_time.as_secs_f64() * 1e3,
        write_ms: write_time.as_secs_f64() * 1e3,
        renderer: renderer.info().renderer.clone(),
        morph: args.morph.as_deref(),
        t: target.is_some().then_some(t),
    };
    super::print_report(args.json, &report, |out, r| report::print_summary(out, r))
}

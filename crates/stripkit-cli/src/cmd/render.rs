//! `stripkit render`: a picture of the strips stripkit makes, drawn offscreen through
//! EGL and OpenGL ES (`stripkit-render`; Mesa's llvmpipe where there is no GPU).
//!
//! The strips come from the same door and the same flags as `stripkit strip`; they are
//! exploded into a triangle list in strip order ([`paint::explode`]) so that each
//! triangle can carry its strip's colour, its place in the strip order, or its facing.

mod frame;
mod paint;
mod wire;

use clap::ValueEnum;
use serde::Serialize;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;
use stripkit::Error;
use stripkit_render::{DrawParams, IndexWidth, Renderer, Shading, Topology, Vertices};

use super::strip::{heuristic_of, StripArgs};
use paint::Paint;

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
    /// away from it, which back-face culling skips, in a light pink. Per triangle for
    /// now: the segment tree of issue #18 will refine this to the ranges of the strip
    /// buffer that are drawn and culled.
    Cull,
    /// Plain grey.
    None,
}

/// How faces are lit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ShadingArg {
    /// Each triangle lit by its own normal: facets and strip colours read clearly.
    Flat,
    /// Lit by area-weighted vertex normals: a smooth surface.
    Smooth,
    /// No lighting: every pixel is exactly its triangle's colour (for counting colours).
    Unlit,
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
    #[arg(long, value_name = "X,Y,Z", default_value = "0.3,0.4,1", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub view: [f32; 3],
    /// `--color cull`: judge facing from an eye in this direction instead of `--view`
    /// (at the same distance), to see from the side what an eye there would cull.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub cull_view: Option<[f32; 3]>,
    /// The direction that points up in the picture, X,Y,Z (not parallel to `--view`).
    #[arg(long, value_name = "X,Y,Z", default_value = "0,1,0", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub up: [f32; 3],
    /// Vertical field of view in degrees, 1 to 120. The camera stands as far back as the
    /// model needs to fill the picture.
    #[arg(long, value_name = "DEGREES", default_value_t = 30.0, value_parser = parse_fov)]
    pub fov: f32,
    /// Magnify the middle of the picture this many times, 1 to 100 (the camera stays
    /// where it frames the whole model): a detail, to follow single strips on a large mesh.
    #[arg(long, value_name = "F", default_value_t = 1.0, value_parser = parse_zoom)]
    pub zoom: f32,
    /// Picture size in pixels, WIDTHxHEIGHT, each 16 to 4096.
    #[arg(long, value_name = "WxH", default_value = "800x800", value_parser = parse_wh)]
    pub size: (u32, u32),
    /// Background colour: `#rrggbb`, `rrggbb` or `R,G,B` (0 to 255 each).
    #[arg(long, value_name = "COLOR", default_value = "#ffffff", value_parser = parse_rgb)]
    pub background: [u8; 3],
    /// Lighting: `flat` (each triangle by its own normal), `smooth` (vertex normals) or
    /// `unlit` (exact colours).
    #[arg(long, value_enum, default_value = "flat")]
    pub shading: ShadingArg,
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
    #[arg(long, value_name = "T", requires = "morph", value_parser = parse_unit)]
    pub t: Option<f32>,
    /// A `.sets` or `.lodseq` input (`stripkit lod`): draw its own strips at this level
    /// (collapses applied; default 0, the input).
    #[arg(long, value_name = "L", conflicts_with = "ratio")]
    pub level: Option<u32>,
    /// A `.sets` or `.lodseq` input: draw the first level with at most
    /// ceil(R x triangles) triangles.
    #[arg(long, value_name = "R", value_parser = parse_unit)]
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

fn parse_vec3(text: &str) -> Result<[f32; 3], String> {
    let parts: Vec<_> = text.split(',').map(|s| s.trim().parse::<f32>()).collect();
    match parts.as_slice() {
        [Ok(x), Ok(y), Ok(z)] if x.is_finite() && y.is_finite() && z.is_finite() => Ok([*x, *y, *z]),
        _ => Err(format!("`{text}` is not a direction: three finite numbers X,Y,Z, e.g. 0.3,0.4,1")),
    }
}

fn parse_fov(text: &str) -> Result<f32, String> {
    match text.trim().parse::<f32>() {
        Ok(f) if (1.0..=120.0).contains(&f) => Ok(f),
        _ => Err(format!("`{text}` is not a field of view: degrees from 1 to 120")),
    }
}

fn parse_zoom(text: &str) -> Result<f32, String> {
    match text.trim().parse::<f32>() {
        Ok(z) if (1.0..=100.0).contains(&z) => Ok(z),
        _ => Err(format!("`{text}` is not a zoom: a factor from 1 to 100")),
    }
}

fn parse_unit(text: &str) -> Result<f32, String> {
    match text.trim().parse::<f32>() {
        Ok(t) if (0.0..=1.0).contains(&t) => Ok(t),
        _ => Err(format!("`{text}` is not a morph weight: a number from 0 to 1")),
    }
}

/// Largest picture side.
const MAX_SIDE: u32 = 4096;

fn parse_wh(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("`{text}` is not a picture size: WIDTHxHEIGHT, each 16 to {MAX_SIDE}, e.g. 800x800");
    let (w, h) = text
        .trim()
        .to_ascii_lowercase()
        .split_once('x')
        .map(|(w, h)| (w.trim().parse(), h.trim().parse()))
        .ok_or_else(bad)?;
    match (w, h) {
        (Ok(w), Ok(h)) if (16..=MAX_SIDE).contains(&w) && (16..=MAX_SIDE).contains(&h) => Ok((w, h)),
        _ => Err(bad()),
    }
}

fn parse_rgb(text: &str) -> Result<[u8; 3], String> {
    let bad = || format!("`{text}` is not a colour: #rrggbb, rrggbb or R,G,B (0 to 255 each)");
    let t = text.trim();
    if t.contains(',') {
        let parts: Vec<_> = t.split(',').map(|s| s.trim().parse::<u8>()).collect();
        return match parts.as_slice() {
            [Ok(r), Ok(g), Ok(b)] => Ok([*r, *g, *b]),
            _ => Err(bad()),
        };
    }
    let hex = t.strip_prefix('#').unwrap_or(t);
    if hex.len() != 6 || !hex.is_ascii() {
        return Err(bad());
    }
    let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).map_err(|_| bad());
    Ok([byte(0)?, byte(2)?, byte(4)?])
}

/// The JSON object printed by `--json`.
#[derive(Serialize)]
struct Report<'a> {
    input: &'a Path,
    /// A `.sets` / `.lodseq` input: the level (and frame) drawn.
    #[serde(skip_serializing_if = "Option::is_none")]
    lod: Option<String>,
    output: &'a Path,
    algo: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    heuristic: Option<&'static str>,
    color: ColorArg,
    shading: ShadingArg,
    width: u32,
    height: u32,
    strips: usize,
    /// Triangles drawn (the strips' triangles without swaps and degenerate ones).
    triangles: usize,
    /// `--color cull`: triangles facing the eye.
    #[serde(skip_serializing_if = "Option::is_none")]
    front: Option<usize>,
    /// Pixels other than the background.
    pixels: usize,
    /// `--wireframe`: edges drawn.
    #[serde(skip_serializing_if = "Option::is_none")]
    edges: Option<usize>,
    /// Milliseconds of the stripify call alone.
    stripify_ms: f64,
    /// Milliseconds to start the renderer (EGL display, context, shaders).
    start_ms: f64,
    /// Milliseconds to upload the triangles, draw them and read the pixels back.
    draw_ms: f64,
    /// Milliseconds to encode the PNG and write it.
    write_ms: f64,
    /// The renderer, as OpenGL names it (e.g. llvmpipe).
    renderer: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    morph: Option<&'a Path>,
    #[serde(skip_serializing_if = "Option::is_none")]
    t: Option<f32>,
}

/// Positions of the vertices some face uses (unreferenced vertices stay out of the frame).
fn used_positions(mesh: &stripkit::Mesh) -> Vec<[f32; 3]> {
    let mut used = vec![false; mesh.vertex_count()];
    for &v in &mesh.face_indices {
        used[v as usize] = true;
    }
    mesh.positions.iter().zip(&used).filter(|(_, &u)| u).map(|(p, _)| *p).collect()
}

/// Arguments that can be refused before any file is read.
fn check(args: &Args) -> anyhow::Result<()> {
    let is_png = args.output.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png {
        return Err(Error::Invalid(format!("{}: the picture must be a .png file", args.output.display())).into());
    }
    super::check_output_folder(&args.output)?;
    if args.cull_view.is_some() && args.color != ColorArg::Cull {
        return Err(Error::Invalid("--cull-view applies to --color cull".into()).into());
    }
    args.strip.validate(|o| o)
}

/// A level (and frame) of a `.sets` / `.lodseq` input: the positions its strips
/// index, its strips, and a description.
type Level = (Vec<[f32; 3]>, stripkit::StripSet, String);

/// The strips of a `.sets` or `.lodseq` input at `--level` / `--ratio` (and
/// `--frame`, default 0 for an animation); `None` for a mesh (or standard input).
fn read_lod(args: &Args) -> anyhow::Result<Option<Level>> {
    use anyhow::Context;
    use stripkit::lod::{LevelSpec, Model};
    let model = if args.input.as_os_str() == "-" { None } else { Model::read(&args.input)? };
    let Some(model) = model else {
        if args.level.is_some() || args.ratio.is_some() || args.frame.is_some() {
            return Err(Error::Invalid("--level, --ratio and --frame apply to .sets and .lodseq inputs".into()).into());
        }
        return Ok(None);
    };
    if args.morph.is_some() {
        return Err(Error::Invalid("--morph applies to meshes; a .lodseq morphs with --frame".into()).into());
    }
    let spec = match (args.level, args.ratio) {
        (_, Some(r)) => LevelSpec::Ratio(r as f64),
        (l, None) => LevelSpec::Level(l.unwrap_or(0)),
    };
    let frame = match model {
        Model::Seq(_) => Some(args.frame.unwrap_or(0.0)),
        Model::Sets(_) => args.frame,
    };
    let x = model.extract(spec, frame).with_context(|| format!("{} (--frame)", args.input.display()))?;
    let level = format!("level {} of {}, {} triangles", x.level, x.levels, x.triangles);
    let what = match x.frame {
        Some((t, key)) => format!("frame {t} (key frame {key}), {level}"),
        None => level,
    };
    Ok(Some((x.positions, x.strips, what)))
}

/// The mesh, and the `--morph` mesh when given (same vertex count).
fn read_meshes(args: &Args) -> anyhow::Result<(stripkit::Mesh, Option<stripkit::Mesh>)> {
    let mesh = args.read.read(&args.input)?;
    let Some(path) = &args.morph else { return Ok((mesh, None)) };
    let other = args.read.read(path)?;
    if other.vertex_count() != mesh.vertex_count() {
        return Err(Error::Invalid(format!(
            "--morph {}: {} vertices, but {} has {}; a morph needs the same vertices",
            path.display(),
            other.vertex_count(),
            args.input.display(),
            mesh.vertex_count()
        ))
        .into());
    }
    Ok((mesh, Some(other)))
}

/// What is drawn: the exploded triangles over the mesh's positions (and the morph
/// target's), seen by the framed camera.
struct Scene<'a> {
    framing: frame::Framing,
    exploded: paint::Exploded,
    positions: &'a [[f32; 3]],
    target: Option<&'a [[f32; 3]]>,
    /// The positions as drawn: the blend at `t` when morphing.
    drawn: &'a [[f32; 3]],
    t: f32,
}

/// Draws the scene (and its wireframe) and reads the picture back. Returns the picture
/// and, with `--wireframe`, the number of edges drawn.
fn draw(
    renderer: &mut Renderer,
    args: &Args,
    scene: &Scene,
) -> anyhow::Result<(stripkit_render::Image, Option<usize>)> {
    let (w, h) = args.size;
    let exploded = &scene.exploded;
    let camera = &scene.framing.camera;
    let positions = exploded.gather(scene.positions);
    let morph_target = scene.target.map(|o| exploded.gather(o));
    let normals = (args.shading == ShadingArg::Smooth)
        .then(|| exploded.gather(&stripkit_render::vertex_normals(scene.drawn, &exploded.corners)));
    let geometry = renderer.upload(&Vertices {
        positions: &positions,
        morph_target: morph_target.as_deref(),
        normals: normals.as_deref(),
        colors: Some(&exploded.colors),
    })?;
    let corners: Vec<u32> = (0..exploded.corners.len() as u32).collect();
    let indices = renderer.upload_indices(&corners, Topology::Triangles, IndexWidth::smallest(corners.len()))?;
    renderer.clear(args.background.map(|c| c as f32 / 255.0));
    let mut params = DrawParams::new(camera.view_proj(w as f32 / h as f32));
    params.morph = scene.t;
    params.shading = match args.shading {
        ShadingArg::Flat => Shading::Flat,
        ShadingArg::Smooth => Shading::Smooth,
        ShadingArg::Unlit => Shading::Unlit,
    };
    // A light from the eye, a little above and to the left.
    let (up, right) = (scene.framing.up, scene.framing.right);
    let dir: [f32; 3] = std::array::from_fn(|d| camera.eye[d] - camera.target[d]);
    let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt().max(1e-20);
    params.light = std::array::from_fn(|d| dir[d] / len + 0.5 * up[d] - 0.35 * right[d]);
    renderer.draw(&geometry, &indices, &params);
    let mut edges = None;
    if args.wireframe {
        let fov = (camera.fov_y_degrees as f64).to_radians();
        let pixel = (2.0 * (fov * 0.5).tan() / h as f64) as f32;
        let width = (w.min(h) as f32 / 640.0).max(1.0);
        let band = wire::bands(scene.drawn, &exploded.corners, camera.eye, pixel, width, 1.5);
        edges = Some(band.len() / 6);
        let colors = vec![paint::WIRE; band.len()];
        let lines = renderer.upload(&Vertices {
            positions: &band,
            morph_target: None,
            normals: None,
            colors: Some(&colors),
        })?;
        let order: Vec<u32> = (0..band.len() as u32).collect();
        let line_indices = renderer.upload_indices(&order, Topology::Triangles, IndexWidth::smallest(order.len()))?;
        let mut line_params = params.clone();
        line_params.morph = 0.0;
        line_params.shading = Shading::Unlit;
        renderer.draw(&lines, &line_indices, &line_params);
    }
    if let Some(e) = renderer.gl_error() {
        return Err(stripkit_render::RenderError::Gl(format!("drawing failed (GL error {e:#x})")).into());
    }
    Ok((renderer.read_image(), edges))
}

/// Runs the command: read -> frame -> door -> explode and colour -> draw -> PNG.
pub fn run(args: Args) -> anyhow::Result<()> {
    check(&args)?;
    let progress = indicatif::ProgressBar::new_spinner();
    progress.enable_steady_tick(std::time::Duration::from_millis(120));
    progress.set_message(format!("reading {}", args.input.display()));
    let lod = read_lod(&args)?;
    let (mesh, target) = match &lod {
        Some((positions, strips, _)) => {
            (stripkit::Mesh::from_triangles(positions.clone(), &stripkit::decode(strips)), None)
        }
        None => read_meshes(&args)?,
    };
    let t = if target.is_some() { args.t.unwrap_or(0.5) } else { 0.0 };

    // The camera frames every vertex a face uses, of both meshes when morphing, so
    // that the pictures of one pair at several t line up.
    let (w, h) = args.size;
    let mut points = used_positions(&mesh);
    if let Some(other) = &target {
        points.extend(used_positions(other));
    }
    let framing =
        frame::frame(&points, args.view, args.up, args.fov, args.zoom, w as f32 / h as f32).map_err(Error::Invalid)?;
    drop(points);

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
        (None, Some((positions, strips, _))) => (strips.clone(), positions.clone(), None),
        (None, None) => unreachable!("a mesh goes through the door"),
    };
    let blended: Option<Vec<[f32; 3]>> = target_positions.as_ref().map(|other| {
        positions.iter().zip(other).map(|(a, b)| std::array::from_fn(|d| a[d] + (b[d] - a[d]) * t)).collect()
    });
    let drawn = blended.as_deref().unwrap_or(&positions);

    progress.set_message("drawing");
    let paint = match args.color {
        ColorArg::Strips => Paint::Strips,
        ColorArg::Order => Paint::Order,
        ColorArg::Cull => Paint::Cull {
            eye: framing
                .eye_towards(args.cull_view.unwrap_or(args.view))
                .ok_or_else(|| Error::Invalid("--cull-view must not be 0,0,0".into()))?,
        },
        ColorArg::None => Paint::None,
    };
    let exploded = paint::explode(&strip_set, drawn, paint);
    if exploded.triangles() == 0 {
        return Err(
            Error::Invalid(format!("no faces in {} (every triangle is degenerate)", args.input.display())).into()
        );
    }
    let draw_start = Instant::now();
    let scene = Scene { framing, exploded, positions: &positions, target: target_positions.as_deref(), drawn, t };
    let (image, edges) = draw(&mut renderer, &args, &scene)?;
    let draw_time = draw_start.elapsed();
    let pixels = image.pixels_other_than(args.background);
    progress.set_message(format!("writing {}", args.output.display()));
    let write_start = Instant::now();
    stripkit::io::write_atomic(&args.output, &image.encode_png_rgb())?;
    let write_time = write_start.elapsed();
    progress.finish_and_clear();

    let exploded = &scene.exploded;
    let report = Report {
        input: &args.input,
        output: &args.output,
        algo: door.as_ref().map_or("lod", |s| s.algorithm.name()),
        heuristic: door.as_ref().and_then(|s| heuristic_of(&s.algorithm)),
        color: args.color,
        shading: args.shading,
        width: w,
        height: h,
        strips: strip_set.iter().filter(|s| !s.is_empty()).count(),
        triangles: exploded.triangles(),
        front: (args.color == ColorArg::Cull).then_some(exploded.front),
        pixels,
        edges,
        stripify_ms: door.as_ref().map_or(0.0, |s| s.stripify_time.as_secs_f64() * 1e3),
        lod: lod.as_ref().map(|l| l.2.clone()),
        start_ms: start_time.as_secs_f64() * 1e3,
        draw_ms: draw_time.as_secs_f64() * 1e3,
        write_ms: write_time.as_secs_f64() * 1e3,
        renderer: renderer.info().renderer.clone(),
        morph: args.morph.as_deref(),
        t: target.is_some().then_some(t),
    };
    super::print_report(args.json, &report, |out, r| print_summary(out, r))
}

fn print_summary(out: &mut impl Write, r: &Report) -> std::io::Result<()> {
    let name = |v: &dyn std::fmt::Debug| format!("{v:?}").to_lowercase();
    writeln!(
        out,
        "{} -> {} ({}, color {}, {} shading, {}x{}{})",
        r.input.display(),
        r.output.display(),
        r.algo,
        name(&r.color),
        name(&r.shading),
        r.width,
        r.height,
        r.t.map(|t| format!(", morph t = {t}")).unwrap_or_default()
    )?;
    if let Some(l) = &r.lod {
        writeln!(out, "  lod            {l}")?;
    }
    writeln!(out, "  strips         {:>10}", r.strips)?;
    writeln!(out, "  triangles      {:>10}", r.triangles)?;
    if let Some(e) = r.edges {
        writeln!(out, "  edges          {:>10}", e)?;
    }
    if let Some(f) = r.front {
        writeln!(out, "  facing the eye {:>10} ({} culled)", f, r.triangles - f)?;
    }
    let share = 100.0 * r.pixels as f64 / (r.width as f64 * r.height as f64);
    writeln!(out, "  pixels drawn   {:>10} ({share:.1}%)", r.pixels)?;
    writeln!(out, "  stripify ms    {:>10.2}", r.stripify_ms)?;
    writeln!(out, "  start ms       {:>10.2} ({})", r.start_ms, r.renderer)?;
    writeln!(out, "  draw ms        {:>10.2}", r.draw_ms)?;
    writeln!(out, "  write ms       {:>10.2}", r.write_ms)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arguments_parse_and_refuse() {
        assert_eq!(parse_vec3("0.3, 0.4,1"), Ok([0.3, 0.4, 1.0]));
        assert_eq!(parse_vec3("-1,0,-2"), Ok([-1.0, 0.0, -2.0]));
        assert!(parse_vec3("1,2").is_err() && parse_vec3("1,2,x").is_err() && parse_vec3("1,2,inf").is_err());
        assert_eq!(parse_wh("800x600"), Ok((800, 600)));
        assert_eq!(parse_wh("16X4096"), Ok((16, 4096)));
        for bad in ["0x10", "800", "15x800", "4097x10", "axb", "800x-1", ""] {
            assert!(parse_wh(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_rgb("#ff8000"), Ok([255, 128, 0]));
        assert_eq!(parse_rgb("0a0B0c"), Ok([10, 11, 12]));
        assert_eq!(parse_rgb("1, 2,255"), Ok([1, 2, 255]));
        for bad in ["#fff", "256,0,0", "gg0000", "1,2", "é1234"] {
            assert!(parse_rgb(bad).is_err(), "{bad}");
        }
        assert!(parse_zoom("0.5").is_err() && parse_zoom("101").is_err() && parse_zoom("2.5") == Ok(2.5));
        assert!(parse_fov("0.5").is_err() && parse_fov("121").is_err() && parse_fov("45").is_ok());
        assert!(parse_unit("1.5").is_err() && parse_unit("-0.1").is_err() && parse_unit("0.25") == Ok(0.25));
    }
}

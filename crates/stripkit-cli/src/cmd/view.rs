//! `stripkit view`: one self-contained HTML page that draws a mesh's strips with WebGL2
//! (`drawElements(TRIANGLE_STRIP)`, primitive restart at the fixed index), with an
//! orbit/zoom camera, flat or smooth shading, colours by strip, strip order or a
//! checker over the UVs, a wireframe and a panel of the strips' figures.
//!
//! The strips come from the same door and flags as `stripkit strip`. The page's
//! script and style are files beside this module (`view/`), included at compile time;
//! the model travels as base64 inside a JSON block. The first frame uses
//! `stripkit render`'s camera (stripkit-render's framing, same defaults), so that the
//! page and `stripkit render` of the same model draw the same picture.

use serde::Serialize;
use std::path::PathBuf;
use stripkit::Error;
use stripkit_render::{FrameError, Framing};

use super::render::values;
use super::strip::StripArgs;

/// The page: markup, with `/*STYLE*/`, `/*SCRIPT*/` and `/*MODEL*/` filled in.
const PAGE: &str = include_str!("view/page.html");
/// The page's style.
const STYLE: &str = include_str!("view/viewer.css");
/// The page's script: the main function, with the runtime and the pieces at `/*MODULES*/`.
const SCRIPT: &str = include_str!("view/viewer.js");
/// The script's pieces, inlined in this order after the runtime (each a few functions
/// over the page's state; viewer.js says which does what).
const PIECES: [&str; 7] = [
    include_str!("view/decode.js"),
    include_str!("view/colours.js"),
    include_str!("view/gl.js"),
    include_str!("view/camera.js"),
    include_str!("view/cull.js"),
    include_str!("view/panel.js"),
    include_str!("view/hooks.js"),
];
/// The `.sets` runtime (an ES module of its own, js/sets-runtime; `view/sets-runtime.js`
/// is a link to it, which `cargo package` copies), inlined into the page's script at
/// `/*MODULES*/` with its `export` keywords dropped.
const RUNTIME: &str = include_str!("view/sets-runtime.js");

/// Arguments of `stripkit view`.
#[derive(clap::Args, Debug)]
#[command(after_help = "The page needs no network: its script and the model are inside it. \
It draws with WebGL2 in any current browser.\n\
Exit status: 0 success, 1 the strips failed verification, 2 bad input or argument (nothing written).")]
pub struct Args {
    /// Input mesh (.obj, .ply, .off, .stl, .gltf, .glb, optionally .gz), or a `.sets`
    /// model (`stripkit lod build`): the page then has a slider over every level, each
    /// extracted in the page by the JavaScript `.sets` runtime. Or a `.lodseq` animation
    /// (`stripkit lod build-seq`): a frame slider and a play button besides the level's.
    pub input: PathBuf,
    /// Output page (.html), replaced atomically.
    #[arg(short, long, value_name = "OUT.html")]
    pub output: PathBuf,
    #[command(flatten)]
    pub strip: StripArgs,
    /// First view: direction from the model's centre towards the eye, X,Y,Z (as `stripkit render`).
    #[arg(long, value_name = "X,Y,Z", default_value = "0.3,0.4,1", value_parser = values::parse_vec3, allow_hyphen_values = true)]
    pub view: [f32; 3],
    /// The direction that points up at first, X,Y,Z (not parallel to `--view`).
    #[arg(long, value_name = "X,Y,Z", default_value = "0,1,0", value_parser = values::parse_vec3, allow_hyphen_values = true)]
    pub up: [f32; 3],
    /// Vertical field of view in degrees, 1 to 120.
    #[arg(long, value_name = "DEGREES", default_value_t = 30.0, value_parser = values::parse_fov)]
    pub fov: f32,
    /// Canvas size in pixels, WIDTHxHEIGHT, each 16 to 4096.
    #[arg(long, value_name = "WxH", default_value = "800x800", value_parser = values::parse_wh)]
    pub size: (u32, u32),
    /// Culling in the page: the strips' segment tree (as `stripkit cull` builds it) goes
    /// into the page, which traverses it for the current eye and colours the drawn and
    /// culled ranges. For one strip, as `stripkit cull`: `--algo single --weights cull`.
    #[arg(long)]
    pub cull: bool,
    /// A `.lodseq` input: the frame the page opens at (its camera frames that frame, as
    /// `stripkit render --frame F`). Default 0.
    #[arg(long, value_name = "F")]
    pub frame: Option<usize>,
    /// Print one JSON object (counts, page size) on stdout instead of the summary.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: super::ReadArgs,
}

/// The model as the page reads it (arrays as base64 of little-endian values).
#[derive(Serialize)]
struct Model {
    name: String,
    algo: &'static str,
    triangles: usize,
    strips: usize,
    indices: usize,
    acmr: f64,
    vertices: usize,
    size: [u32; 2],
    camera: Camera,
    /// `3 x vertices` f32, scaled into a frame near unit size as `stripkit render` does.
    positions: String,
    /// `2 x vertices` f32 (`TEXCOORD_0`), or empty.
    uv: String,
    /// Each strip's index count (u32), empty strips included.
    lengths: String,
    /// Every strip's indices, one after the other (u32).
    strip_indices: String,
    /// A `.sets` input: the file itself (the page decodes it), else empty.
    sets: String,
    /// A `.lodseq` input: the file itself (the page decodes it, frames and models), else empty.
    lodseq: String,
    /// The factor positions were (a mesh) or are to be (a `.sets`) multiplied by: a
    /// power of two from [`stripkit::unit_scale`].
    scale: f32,
    /// `--cull`: the segment tree, or `None`.
    tree: Option<Tree>,
    /// A `.lodseq` input: the frame the page opens at.
    frame: usize,
}

impl Model {
    /// The figures panel's fields, the size and camera; the buffers empty, no tree.
    fn new(args: &Args, algo: &'static str, figures: &stripkit::Figures, vertices: usize, camera: Camera, scale: f32) -> Self {
        Model {
            name: args.input.file_name().map_or("-".into(), |n| n.to_string_lossy().into_owned()),
            algo,
            triangles: figures.triangles,
            strips: figures.strips,
            indices: figures.indices_restart,
            acmr: figures.acmr,
            vertices,
            size: [args.size.0, args.size.1],
            camera,
            positions: String::new(),
            uv: String::new(),
            lengths: String::new(),
            strip_indices: String::new(),
            sets: String::new(),
            lodseq: String::new(),
            scale,
            tree: None,
            frame: 0,
        }
    }
}

/// A segment tree as the page traverses it (stripkit's `cull` module): per node, 9
/// f32 (centre and radius, scaled as the positions; cone axis; cos, 2 for an empty
/// cone; sin) and 5 u32 (range start and end in the strips' indices, triangles, strip,
/// right child or `u32::MAX` for a leaf; the left child is the next node), and the roots.
#[derive(Serialize)]
struct Tree {
    bounds: String,
    ranges: String,
    roots: String,
}

impl Tree {
    /// The tree of `strips` over `positions` (unscaled: the tree `stripkit cull` builds).
    fn of(strips: &stripkit::StripSet, positions: &[[f32; 3]], scale: f32) -> Tree {
        let tree = stripkit::cull::SegmentTree::build(strips, positions);
        let bounds = tree.nodes.iter().flat_map(|n| {
            let b = &n.bounds;
            let [x, y, z] = b.center.map(|c| c * scale);
            let cos = if b.angle < 0.0 { 2.0 } else { b.cos_angle };
            [x, y, z, b.radius * scale, b.axis[0], b.axis[1], b.axis[2], cos, b.sin_angle]
        });
        let ranges = tree.nodes.iter().flat_map(|n| [n.start, n.end, n.triangles, n.strip, n.children[1]]);
        Tree { bounds: f32_base64(bounds), ranges: u32_base64(ranges), roots: u32_base64(tree.roots.iter().copied()) }
    }
}

/// The first frame's camera: stripkit-render's framing.
#[derive(Serialize)]
struct Camera {
    eye: [f32; 3],
    target: [f32; 3],
    up: [f32; 3],
    fov: f32,
    near: f32,
    far: f32,
    light: [f32; 3],
}

/// What `stripkit view` reports.
#[derive(Serialize)]
struct Report<'a> {
    input: &'a std::path::Path,
    output: &'a std::path::Path,
    algo: &'static str,
    triangles: usize,
    strips: usize,
    indices: usize,
    acmr: f64,
    page_bytes: usize,
}

/// Base64 (standard alphabet, padded) of `bytes`.
fn base64(bytes: &[u8]) -> String {
    const ABC: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(ABC[(n >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Base64 of little-endian f32 values.
fn f32_base64(values: impl Iterator<Item = f32>) -> String {
    base64(&values.flat_map(f32::to_le_bytes).collect::<Vec<u8>>())
}

/// Base64 of little-endian u32 values.
fn u32_base64(values: impl Iterator<Item = u32>) -> String {
    base64(&values.flat_map(u32::to_le_bytes).collect::<Vec<u8>>())
}

/// Arguments that can be refused before any file is read.
fn check(args: &Args) -> anyhow::Result<()> {
    let is_html = args.output.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("html"));
    if !is_html {
        return Err(Error::Invalid(format!("{}: the page must be a .html file", args.output.display())).into());
    }
    super::check_not_inputs(&[("input", args.input.as_path())], &[("-o", &args.output)])?;
    super::check_output_folder(&args.output)?;
    args.strip.validate(|o| o)
}

/// The page with its style, script and model inlined. `</` in the model's JSON cannot
/// occur (base64, numbers and the file name escaped below), so the block ends where it should.
fn page(model: &Model) -> anyhow::Result<String> {
    let json = serde_json::to_string(model)?.replace("</", "<\\/");
    let modules = [RUNTIME.replace("\nexport ", "\n")].into_iter().chain(PIECES.map(String::from)).collect::<Vec<_>>();
    let script = SCRIPT.replacen("/*MODULES*/", &modules.join("\n"), 1);
    Ok(PAGE.replacen("/*STYLE*/", STYLE, 1).replacen("/*SCRIPT*/", &script, 1).replacen("/*MODEL*/", &json, 1))
}

/// The page's camera for `used` (the positions the strips use, already scaled).
fn first_camera(args: &Args, used: &[[f32; 3]]) -> anyhow::Result<Camera> {
    let (w, h) = args.size;
    let framing = Framing::fit(used, args.view, args.up, args.fov, 1.0, w as f32 / h as f32).map_err(|e| {
        Error::Invalid(match e {
            FrameError::ZeroView => "--view must not be 0,0,0".into(),
            FrameError::BadUp => "--up must not be 0,0,0 nor parallel to --view".into(),
            FrameError::NothingToFrame => e.to_string(),
        })
    })?;
    let c = framing.camera;
    let light = framing.light();
    Ok(Camera { eye: c.eye, target: c.target, up: c.up, fov: c.fov_y_degrees, near: c.near, far: c.far, light })
}

/// The level-0 `strips` over `positions`: their figures with the default cache model
/// (as `stripkit strip`), the camera, and the scale of the used positions.
fn level0_view(args: &Args, strips: &stripkit::StripSet, positions: &[[f32; 3]]) -> anyhow::Result<(stripkit::Figures, Camera, f32)> {
    let used: Vec<[f32; 3]> = strips.iter().flatten().map(|&v| positions[v as usize]).collect();
    let scale = stripkit::unit_scale(&used) as f32;
    let used: Vec<[f32; 3]> = used.iter().map(|p| p.map(|x| x * scale)).collect();
    let mut triangles = Vec::new();
    for s in strips.iter() {
        stripkit::for_each_triangle(s, |t| triangles.push(t));
    }
    let figures = stripkit::figures(&triangles, strips, stripkit::CacheModel::default());
    Ok((figures, first_camera(args, &used)?, scale))
}

/// The page's model for a `.sets` file: the file, and its level 0's figures and camera.
fn sets_model(args: &Args, sets: &stripkit::lod::Sets) -> anyhow::Result<Model> {
    let positions = sets.positions();
    let (figures, camera, scale) = level0_view(args, &sets.strips_at(0), positions)?;
    Ok(Model {
        sets: base64(&std::fs::read(&args.input)?),
        ..Model::new(args, "sets", &figures, positions.len(), camera, scale)
    })
}

/// The page's model for a `.lodseq` file: the file, and the figures, camera and scale
/// of the first frame (`--frame`) at level 0 (the scale stays for every frame, so that
/// the animation moves).
fn seq_model(args: &Args, seq: &stripkit::lod::LodSeq) -> anyhow::Result<Model> {
    let frame = args.frame.unwrap_or(0);
    if frame >= seq.frame_count() {
        let why = format!("--frame {frame}: the animation has {} frames (0 to {})", seq.frame_count(), seq.frame_count() - 1);
        return Err(Error::Invalid(why).into());
    }
    let positions = seq.positions(frame);
    let (figures, camera, scale) = level0_view(args, &seq.models()[seq.model_of(frame)].strips_at(0), positions)?;
    Ok(Model {
        lodseq: base64(&std::fs::read(&args.input)?),
        frame,
        ..Model::new(args, "lodseq", &figures, positions.len(), camera, scale)
    })
}

/// The page's model for a mesh: its strips through the door, positions scaled as
/// `stripkit render` scales them.
fn mesh_model(args: &Args) -> anyhow::Result<Model> {
    let mesh = args.read.read(&args.input)?;
    let strips = args.strip.stripify(&mesh, &args.input, |o| o)?;
    let unscaled = strips.with_added_vertices(&mesh.positions);
    let mut positions = unscaled.clone();
    let used = mesh.used_positions();
    let scale = stripkit::unit_scale(&used) as f32;
    for p in &mut positions {
        *p = p.map(|x| x * scale);
    }
    let used: Vec<[f32; 3]> = used.iter().map(|p| p.map(|x| x * scale)).collect();
    let camera = first_camera(args, &used)?;
    // UVs where the mesh has them and `single` added no vertices (their UVs are unknown).
    let uv = mesh
        .attributes
        .iter()
        .find(|a| a.name == "TEXCOORD_0" && a.components == 2 && a.len() == positions.len())
        .map_or(String::new(), |a| f32_base64((0..a.len()).flat_map(|v| [a.get(v, 0) as f32, a.get(v, 1) as f32])));
    let set = &strips.strips;
    let figures = &strips.figures;
    Ok(Model {
        positions: f32_base64(positions.iter().flatten().copied()),
        uv,
        lengths: u32_base64(set.iter().map(|s| s.len() as u32)),
        strip_indices: u32_base64(set.iter().flatten().copied()),
        tree: args.cull.then(|| Tree::of(set, &unscaled, scale)),
        ..Model::new(args, strips.algorithm.name(), figures, positions.len(), camera, scale)
    })
}

/// Runs the command: read -> door (or the `.sets` file) -> frame -> page -> write -> report.
pub fn run(args: Args) -> anyhow::Result<()> {
    check(&args)?;
    let refuse = |why: &str| Err(Error::Invalid(format!("{}: {why}", args.input.display())).into());
    let model = match stripkit::lod::Model::try_read(&args.input)? {
        Some(_) if args.cull => return refuse("--cull applies to meshes, not to .sets or .lodseq models"),
        Some(stripkit::lod::Model::Sets(_)) | None if args.frame.is_some() => return refuse("--frame applies to .lodseq animations"),
        Some(stripkit::lod::Model::Sets(sets)) => sets_model(&args, &sets)?,
        Some(stripkit::lod::Model::Seq(seq)) => seq_model(&args, &seq)?,
        None => mesh_model(&args)?,
    };
    let text = page(&model)?;
    stripkit::io::write_encoded(&args.output, text.as_bytes())?;
    let report = Report {
        input: &args.input,
        output: &args.output,
        algo: model.algo,
        triangles: model.triangles,
        strips: model.strips,
        indices: model.indices,
        acmr: model.acmr,
        page_bytes: text.len(),
    };
    super::print_report(args.json, &report, |out, r| {
        use std::io::Write;
        writeln!(
            out,
            "{}: {} triangles in {} strips ({} indices, ACMR {:.3}, {}) -> {} ({} bytes)",
            r.input.display(),
            r.triangles,
            r.strips,
            r.indices,
            r.acmr,
            r.algo,
            r.output.display(),
            r.page_bytes
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_pads_like_the_standard() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
    }
}

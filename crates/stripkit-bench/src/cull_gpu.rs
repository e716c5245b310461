//! The `cull-gpu` comparison (issue #18, the paper's Tables 2 and 3 on a GPU of today):
//! frame time along the 591-view helix of `stripkit cull`, drawing each single strip
//! whole against drawing only the ranges its segment tree keeps.
//!
//! For every model, the single strips of three weight kinds (cull, cache, uniform), each
//! uploaded once as one strip index buffer with its own vertices. Per strip kind, three
//! ways to draw a frame:
//!
//! * **whole**: every strip, one draw call each, the GPU's back-face culling on (what a
//!   renderer without the tree does);
//! * **tree**: the render front's ranges for the frame's eye (`RenderFront::cull`, on
//!   the CPU, inside the frame), one draw call per range, GPU culling on;
//! * **tree, gaps joined**: the same with ranges separated by at most `--gap` culled
//!   triangles joined into one draw (fewer draw calls, a few more back faces);
//! * **coarse tree**: gaps joined, and split nodes of at most `--min-triangles`
//!   triangles drawn without descending (fewer nodes visited, more back faces drawn).
//!
//! The table's draws, triangles and CPU microseconds are those of the first
//! configuration's best run; the JSON has them per configuration.
//!
//! A frame is: the traversal (where there is one), a clear, the draws. The figure is the
//! mean wall time of a frame over the whole path, the queue drained once at the start
//! and once at the end (so CPU and GPU overlap as in a real renderer), the best of
//! `--repeats` runs. Configurations: 1920x1080 with the light vertex shader, and 64x64
//! with the heavy (skinning-like) one, where vertex work decides.
//!
//! Check: at `--check-views` views of the path, the picture drawn from the tree's ranges
//! must equal the whole strip's picture pixel for pixel (the ranges leave out only
//! triangles the GPU would cull); a difference fails the run.

use anyhow::Context;
use std::ops::Range;
use std::path::PathBuf;
use std::time::Instant;
use stripkit::cull::{bounding_sphere, helix_eyes, CullOptions, Culled, RenderFront, SegmentTree, HELIX_VIEWS};
use stripkit::{Algorithm, SingleOptions, StripOptions, Weights};
use stripkit_render::{
    Camera, DrawParams, Geometry, IndexBuffer, IndexWidth, Renderer, Shading, Topology, Vertices,
    HEAVY_VERTEX_SHADER,
};

/// Arguments of the `cull-gpu` comparison.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub models: crate::common::Models,
    /// Models, comma-separated file names in the folder, or paths.
    #[arg(long, default_value = "fandisk.obj,cow.obj,horse.ply,bunny_small.off,dragon.obj,spot_triangulated.obj")]
    pub only: String,
    /// Also Loop-subdivided copies: `FILE:LEVELS`, e.g. `horse.ply:2` (1.55M triangles).
    #[arg(long = "subdivided", value_name = "FILE:LEVELS")]
    pub subdivided: Vec<String>,
    /// Runs of the whole path per figure; the best is kept.
    #[arg(long, default_value_t = 3)]
    pub repeats: usize,
    /// Ranges separated by at most this many culled triangles are drawn as one in the
    /// "gaps joined" rows.
    #[arg(long, default_value_t = 16)]
    pub gap: u32,
    /// The "coarse" rows: split nodes of at most this many triangles are drawn without
    /// descending (fewer nodes visited and fewer draws, more back faces), gaps joined too.
    #[arg(long, default_value_t = 64)]
    pub min_triangles: u32,
    /// Views at which the tree's picture is compared with the whole strip's (1920x1080).
    #[arg(long, default_value_t = 6)]
    pub check_views: usize,
    /// Only the 1920x1080 light-shader configuration.
    #[arg(long)]
    pub quick: bool,
    #[command(flatten)]
    pub table: crate::common::TableOut,
    /// Write every figure as JSON here.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
}

/// How a frame chooses what to draw.
#[derive(Clone, Copy)]
enum Mode {
    Whole,
    Tree { max_gap: u32, min_triangles: u32 },
}

impl Mode {
    fn label(self) -> String {
        match self {
            Mode::Whole => "whole strip, GPU culling".into(),
            Mode::Tree { max_gap: 0, min_triangles: 0 } => "segment tree (render front)".into(),
            Mode::Tree { max_gap, min_triangles: 0 } => format!("segment tree, gaps <= {max_gap} joined"),
            Mode::Tree { max_gap, min_triangles } => {
                format!("segment tree, nodes <= {min_triangles} triangles drawn whole, gaps <= {max_gap} joined")
            }
        }
    }
}

/// One strip kind of one model on the GPU.
struct Uploaded {
    geometry: Geometry,
    indices: IndexBuffer,
    tree: SegmentTree,
    /// Every strip's index range: what `Mode::Whole` draws.
    whole: Vec<(usize, usize)>,
    triangles: usize,
}

#[derive(serde::Serialize)]
struct Figure {
    model: String,
    triangles: usize,
    weights: String,
    mode: String,
    config: String,
    /// Mean ms per frame over the path (best run).
    ms_per_frame: f64,
    /// Mean draw calls per frame.
    draws: f64,
    /// Mean triangles submitted per frame (swaps counted as the GPU sees them: indices - 2 per range).
    submitted: f64,
    /// Mean CPU microseconds per frame spent choosing ranges.
    cpu_us: f64,
}

fn to_draws(ranges: &[Range<u32>], out: &mut Vec<(usize, usize)>) {
    out.clear();
    out.extend(ranges.iter().map(|r| (r.start as usize, (r.end - r.start) as usize)));
}

/// Mean ms per frame along the path, and mean draws, submitted triangles and CPU us.
fn run_path(
    r: &mut Renderer,
    u: &Uploaded,
    mode: Mode,
    views: &[[f32; 16]],
    eyes: &[[f32; 3]],
    heavy: bool,
) -> (f64, f64, f64, f64) {
    let mut params = DrawParams::new(views[0]);
    params.shading = Shading::Smooth;
    params.heavy = if heavy { HEAVY_VERTEX_SHADER } else { 0 };
    params.cull_back = true;
    let options = match mode {
        Mode::Whole => CullOptions::default(),
        Mode::Tree { max_gap, min_triangles } => CullOptions::default().max_gap(max_gap).min_triangles(min_triangles),
    };
    let mut front = RenderFront::new(&u.tree);
    let mut culled = Culled::default();
    let mut ranges = Vec::new();
    let (mut draws, mut submitted, mut cpu) = (0usize, 0usize, 0f64);
    // One untimed frame warms the driver.
    params.ranges = Some(u.whole.clone());
    r.clear([0.0; 3]);
    r.draw(&u.geometry, &u.indices, &params);
    r.finish();
    let start = Instant::now();
    for (v, &eye) in eyes.iter().enumerate() {
        let t = Instant::now();
        match mode {
            Mode::Whole => {
                ranges.clear();
                ranges.extend_from_slice(&u.whole);
            }
            Mode::Tree { .. } => {
                front.cull(&u.tree, eye, &options, &mut culled);
                to_draws(&culled.ranges, &mut ranges);
            }
        }
        cpu += t.elapsed().as_secs_f64() * 1e6;
        draws += ranges.len();
        submitted += ranges.iter().map(|&(_, n)| n.saturating_sub(2)).sum::<usize>();
        params.mvp = views[v];
        params.ranges = Some(std::mem::take(&mut ranges));
        r.clear([0.0; 3]);
        r.draw(&u.geometry, &u.indices, &params);
        ranges = params.ranges.take().unwrap_or_default();
    }
    r.finish();
    let n = eyes.len() as f64;
    (start.elapsed().as_secs_f64() * 1e3 / n, draws as f64 / n, submitted as f64 / n, cpu / n)
}

/// Compares the tree's picture with the whole strip's at a few views; the number of
/// differing pixels summed over them.
fn check_pictures(r: &mut Renderer, u: &Uploaded, views: &[[f32; 16]], eyes: &[[f32; 3]], count: usize) -> usize {
    let mut differing = 0;
    let mut culled = Culled::default();
    let step = (eyes.len() / count.max(1)).max(1);
    for v in (0..eyes.len()).step_by(step).take(count) {
        let mut params = DrawParams::new(views[v]);
        params.shading = Shading::Smooth;
        params.cull_back = true;
        params.ranges = Some(u.whole.clone());
        r.clear([0.0; 3]);
        r.draw(&u.geometry, &u.indices, &params);
        let whole = r.read_image();
        u.tree.cull(eyes[v], &CullOptions::default(), &mut culled);
        let mut ranges = Vec::new();
        to_draws(&culled.ranges, &mut ranges);
        params.ranges = Some(ranges);
        r.clear([0.0; 3]);
        r.draw(&u.geometry, &u.indices, &params);
        let tree = r.read_image();
        differing += whole.rgba().chunks_exact(4).zip(tree.rgba().chunks_exact(4)).filter(|(a, b)| a != b).count();
    }
    differing
}

fn upload(r: &mut Renderer, mesh: &stripkit::Mesh, w: &Weights) -> anyhow::Result<Uploaded> {
    let opts = StripOptions::default().algorithm(Algorithm::Single(SingleOptions::new(w.clone())));
    let s = stripkit::stripify(mesh, &opts)?;
    let positions = s.with_added_vertices(&mesh.positions);
    let tree = SegmentTree::build(&s.strips, &positions);
    let normals = stripkit_render::vertex_normals(&positions, s.triangles.as_flattened());
    let geometry =
        r.upload(&Vertices { positions: &positions, morph_target: None, normals: Some(&normals), colors: None })?;
    let indices = r.upload_indices(&s.strips.indices, Topology::Strip, IndexWidth::U32)?;
    let whole = (0..s.strips.len())
        .map(|k| (s.strips.offsets[k] as usize, (s.strips.offsets[k + 1] - s.strips.offsets[k]) as usize))
        .collect();
    Ok(Uploaded { geometry, indices, tree, whole, triangles: s.triangles.len() })
}

/// Runs the comparison.
pub fn run(args: Args) -> anyhow::Result<()> {
    let mut r = Renderer::new(1920, 1080)?;
    let info = r.info().clone();
    let gpu = format!("{} ({}, {})", info.renderer, info.vendor, info.version);
    eprintln!("renderer: {gpu}");
    let dir = args.models.dir();
    let find = |name: &str| match &dir {
        Some(d) if d.join(name).exists() => d.join(name),
        _ => PathBuf::from(name),
    };
    let mut meshes: Vec<(String, stripkit::Mesh)> = Vec::new();
    for name in args.only.split(',').map(str::trim).filter(|n| !n.is_empty()) {
        let p = find(name);
        if !p.exists() {
            eprintln!("{name}: not found, skipped");
            continue;
        }
        meshes.push((name.to_string(), crate::common::read_surface(&p).with_context(|| format!("reading {}", p.display()))?));
    }
    for s in &args.subdivided {
        let (file, levels) = s.rsplit_once(':').context("--subdivided takes FILE:LEVELS")?;
        let levels: u32 = levels.parse().context("--subdivided levels")?;
        let p = find(file);
        let m = crate::common::read_surface(&p).with_context(|| format!("reading {}", p.display()))?;
        let m = stripkit::gen::subdivide_loop(
            &stripkit::Mesh::from_triangles(m.positions.clone(), &m.triangulate().tris),
            levels,
        )?;
        meshes.push((format!("{file} Loop x{levels}"), m));
    }
    let mut configs = vec![("1920x1080, light shader", (1920u32, 1080u32), false)];
    if !args.quick {
        configs.push(("64x64, heavy vertex shader", (64, 64), true));
    }
    let mut figures: Vec<Figure> = Vec::new();
    let mut table = format!("GPU: {gpu}\n\n");
    table.push_str("| model | triangles | strip weights | frame | draws per frame | triangles submitted | CPU us | ");
    table.push_str(&configs.iter().map(|c| format!("ms per frame, {}", c.0)).collect::<Vec<_>>().join(" | "));
    table.push_str(" |\n|---|---:|---|---|---:|---:|---:|");
    table.push_str(&"---:|".repeat(configs.len()));
    table.push('\n');
    for (name, mesh) in &meshes {
        let (center, radius) = bounding_sphere(&mesh.positions);
        let eyes = helix_eyes(center, radius, HELIX_VIEWS);
        let cameras: Vec<Camera> = eyes.iter().map(|&e| Camera::around(e, center, radius)).collect();
        for w in [Weights::Cull, Weights::Cache, Weights::Uniform] {
            let t0 = Instant::now();
            r.resize(1920, 1080)?;
            let u = upload(&mut r, mesh, &w)?;
            eprintln!(
                "{name} {w}: {} triangles, {} strips, tree {} nodes ({:.1} s)",
                u.triangles,
                u.whole.len(),
                u.tree.len(),
                t0.elapsed().as_secs_f64()
            );
            let views: Vec<[f32; 16]> = cameras.iter().map(|c| c.view_proj(1920.0 / 1080.0)).collect();
            let differing = check_pictures(&mut r, &u, &views, &eyes, args.check_views);
            anyhow::ensure!(
                differing == 0,
                "{name} {w}: the tree's picture differs from the whole strip's in {differing} pixels"
            );
            let modes = [
                Mode::Whole,
                Mode::Tree { max_gap: 0, min_triangles: 0 },
                Mode::Tree { max_gap: args.gap, min_triangles: 0 },
                Mode::Tree { max_gap: args.gap, min_triangles: args.min_triangles },
            ];
            let mut cells: Vec<Vec<f64>> = vec![Vec::new(); modes.len()];
            let mut per_mode = vec![(0.0, 0.0, 0.0); modes.len()];
            for &(label, (cw, ch), heavy) in &configs {
                r.resize(cw, ch)?;
                let views: Vec<[f32; 16]> = cameras.iter().map(|c| c.view_proj(cw as f32 / ch as f32)).collect();
                for (k, &mode) in modes.iter().enumerate() {
                    let mut best = (f64::INFINITY, 0.0, 0.0, 0.0);
                    for _ in 0..args.repeats.max(1) {
                        let f = run_path(&mut r, &u, mode, &views, &eyes, heavy);
                        if f.0 < best.0 {
                            best = f;
                        }
                    }
                    if cells[k].is_empty() {
                        per_mode[k] = (best.1, best.2, best.3); // the table's draws and CPU us: the first configuration
                    }
                    cells[k].push(best.0);
                    figures.push(Figure {
                        model: name.clone(),
                        triangles: u.triangles,
                        weights: w.to_string(),
                        mode: mode.label(),
                        config: label.into(),
                        ms_per_frame: best.0,
                        draws: best.1,
                        submitted: best.2,
                        cpu_us: best.3,
                    });
                }
            }
            for (k, &mode) in modes.iter().enumerate() {
                let (draws, submitted, cpu) = per_mode[k];
                let ms = cells[k].iter().map(|x| format!("{x:.3}")).collect::<Vec<_>>().join(" | ");
                table.push_str(&format!(
                    "| {name} | {} | {w} | {} | {draws:.1} | {submitted:.0} | {cpu:.1} | {ms} |\n",
                    u.triangles,
                    mode.label()
                ));
            }
            r.delete_indices(u.indices);
            r.delete_geometry(u.geometry);
        }
    }
    print!("{table}");
    if let Some(f) = &args.table.out {
        std::fs::write(f, &table)?;
    }
    if let Some(f) = &args.json {
        std::fs::write(f, serde_json::to_string_pretty(&serde_json::json!({ "gpu": gpu, "figures": figures }))?)?;
    }
    Ok(())
}

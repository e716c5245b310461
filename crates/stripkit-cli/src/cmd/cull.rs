//! `stripkit cull`: back-face culling of a single strip with its segment tree along the
//! helix camera path: segments drawn per view, triangles culled and leaked, traversal
//! times with and without the render front; optionally a picture of the strip bar.

use anyhow::Context;
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;
use stripkit::cull::survey::{self, PathMean, ViewFigures};
use stripkit::cull::{helix_eyes, CullOptions, Culled, FacingCounter, Frustum, SegmentTree, HELIX_VIEWS};
use stripkit::{Algorithm, SingleOptions, StripOptions, Weights};

/// Arguments of `stripkit cull`.
#[derive(clap::Args)]
#[command(after_help = "What it does:
  1. builds the single strip of MESH (`strip --algo single --weights W`, one strip per
     component), verified;
  2. builds its segment tree: leaves are pairs of strip triangles (so every range starts
     at an even triangle and keeps its winding), neighbouring segments with the most
     similar normals merged first; each node holds a normal cone and a bounding sphere;
  3. for each eye of the path, classifies nodes as front-facing (drawn), back-facing
     (skipped) or split (children tested; a split leaf is drawn), from the roots and
     from the render front (the nodes where the last view stopped); both give the same
     ranges.

Path `spiral`: 591 eyes (--views) on an ascending helix around the centre of the
bounding box, 3 half-diagonals from its vertical axis, three turns, height -1.5 to +1.5
half-diagonals, looking at the centre (the paper's Fig. 17; the path of
stripkit-bench gpu).

Figures, per view (--json: every view) and averaged:
  segments        index ranges drawn (one multi-draw; neighbouring nodes merged)
  drawn           triangles drawn
  back_culled     back-facing triangles not drawn
  back_drawn      back-facing triangles drawn (in split leaves: the test's leak)
  front_missed    front-facing triangles not drawn (always 0)
  visited         nodes classified, from the roots / from the front
  reused_front    front nodes kept without a test (the eye moved less than their margin)
  us_root, us_front  microseconds per view (best of --repeat runs of the path)

Example: stripkit cull ../shared/models/fandisk.obj --weights cull --bar bar.svg --view 100")]
pub struct Args {
    /// The mesh file (.obj, .ply, .off, .stl, .gltf, .glb, optionally .gz).
    pub file: PathBuf,
    /// What steers the single strip: `cull` (stays inside clusters of similar
    /// normals), `uniform`, `cache`, `direction:X,Y,Z`, or a mix (as `strip --weights`).
    #[arg(long, value_name = "W", default_value = "cull")]
    pub weights: String,
    /// The camera path; `spiral` (the helix) is the only one.
    #[arg(long, value_enum, default_value = "spiral")]
    pub path: PathKind,
    /// Eyes on the path: 1 to 100,000 (each keeps a row of figures).
    #[arg(long, value_name = "N", default_value_t = HELIX_VIEWS)]
    pub views: usize,
    /// A split node of at most this many triangles is drawn without testing its
    /// children (0: down to the leaves, pairs of triangles).
    #[arg(long, value_name = "N", default_value_t = CullOptions::default().min_triangles)]
    pub min_triangles: u32,
    /// Draw two ranges separated by at most N culled (back-facing) triangles as one:
    /// fewer draws for a few more triangles (0: only neighbouring drawn nodes join).
    #[arg(long, value_name = "N", default_value_t = CullOptions::default().max_gap)]
    pub max_gap: u32,
    /// Also cull by the view frustum, with the tree's bounding spheres: the path's
    /// camera looks at the mesh's centre, +Y up, square viewport, near 0.01 and far
    /// 100 bounding radii. Nodes wholly outside are skipped ("outside"); the render
    /// front then tests every node again (the frustum turns with the camera).
    #[arg(long)]
    pub frustum: bool,
    /// With --frustum: the camera's vertical field of view in degrees (the path's is
    /// 60, which holds the whole mesh; a narrower one leaves parts out).
    #[arg(long, value_name = "DEG", requires = "frustum")]
    pub fov: Option<f32>,
    /// Runs of the path for the times (each view's best is kept).
    #[arg(long, value_name = "N", default_value_t = 5)]
    pub repeat: usize,
    /// Write the strip bar of view --view as SVG: the strip as a horizontal band,
    /// drawn segments dark, culled ones light (the paper's Fig. 18).
    #[arg(long, value_name = "OUT.svg")]
    pub bar: Option<PathBuf>,
    /// The view of --bar (0-based).
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub view: usize,
    /// Print one JSON object on stdout (with every view) instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: super::ReadArgs,
}

/// Camera paths.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathKind {
    /// The ascending helix (591 views).
    Spiral,
}

/// The report.
#[derive(Serialize)]
pub struct Report {
    pub file: String,
    pub weights: String,
    pub triangles: usize,
    pub strips: usize,
    /// Pieces of GPU vertices (the dual graph's components): seams split them, and
    /// no strip crosses a seam, so this is the fewest strips there can be.
    pub pieces: usize,
    /// Connected surfaces with seams closed, and UV islands (`TEXCOORD_0`).
    pub surfaces: usize,
    pub uv_islands: Option<usize>,
    pub steiner_vertices: usize,
    /// Triangles the edge splits added (`triangles` counts them).
    pub triangles_added: usize,
    pub tree_nodes: usize,
    pub tree_depth: usize,
    pub build_ms: f64,
    pub views: usize,
    /// Frustum culling on, and the camera's vertical field of view.
    pub frustum: bool,
    pub fov: f32,
    pub mean: PathMean,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub per_view: Vec<ViewFigures>,
}

/// Runs the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let weights: Weights = args.weights.parse().map_err(|e| anyhow::anyhow!("--weights: {e}"))?;
    let max = stripkit::cull::MAX_VIEWS;
    if !(1..=max).contains(&args.views) {
        anyhow::bail!("--views {} is out of range: 1 to {max}", args.views);
    }
    if args.bar.is_some() && args.view >= args.views {
        anyhow::bail!("--view {} is past the last view ({})", args.view, args.views - 1);
    }
    if let Some(bar) = &args.bar {
        super::check_extension("--bar", bar, "an SVG picture", &["svg"])?;
        super::check_not_inputs(&[("input", &args.file)], &[("--bar", bar)])?;
        super::check_output_folder(bar)?;
    }
    let mesh = args.read.read(&args.file)?;
    let options = StripOptions::default().algorithm(Algorithm::Single(SingleOptions::new(weights.clone())));
    let strips = stripkit::stripify(&mesh, &options).with_context(|| args.file.display().to_string())?;
    let positions = strips.with_added_vertices(&mesh.positions);
    let t0 = Instant::now();
    let tree = SegmentTree::build(&strips.strips, &positions);
    let build_ms = t0.elapsed().as_secs_f64() * 1e3;
    let (center, radius) = stripkit::cull::bounding_sphere(&mesh.positions);
    let eyes = match args.path {
        PathKind::Spiral => helix_eyes(center, radius, args.views),
    };
    let fov = args.fov.unwrap_or(60.0);
    anyhow::ensure!(fov > 0.0 && fov < 179.0, "--fov {fov} is out of range: more than 0 and less than 179 degrees");
    let base = CullOptions::default().min_triangles(args.min_triangles).max_gap(args.max_gap);
    let near_far = (0.01 * radius.max(1e-6), 100.0 * radius.max(1e-6));
    let cull_at = |eye: [f32; 3]| {
        base.frustum(
            args.frustum
                .then(|| Frustum::perspective(eye, center, [0.0, 1.0, 0.0], fov, 1.0, near_far.0, near_far.1))
                .flatten(),
        )
    };
    let counter = FacingCounter::new(&strips.strips, &positions);
    let views = survey::survey(&tree, &counter, &eyes, cull_at, args.repeat)?;
    if let Some(bar) = &args.bar {
        let (v, eye) = (args.view, eyes[args.view]);
        let mut out = Culled::default();
        tree.cull(eye, &cull_at(eye), &mut out);
        let svg = bar_svg(&strips.strips, &out, &format!("{} ({weights} weights), view {v}", file_name(&args.file)));
        stripkit::io::write_encoded(bar, svg.as_bytes())?;
    }
    let single = strips.single.as_ref();
    let report = Report {
        file: args.file.display().to_string(),
        weights: weights.to_string(),
        triangles: counter.len(),
        strips: strips.strips.len(),
        pieces: single.map_or(0, |s| s.components),
        surfaces: single.map_or(0, |s| s.surfaces),
        uv_islands: single.and_then(|s| s.uv_islands),
        steiner_vertices: strips.added_positions.len(),
        triangles_added: single.map_or(0, |s| s.triangles_added),
        tree_nodes: tree.len(),
        tree_depth: tree.depth(),
        build_ms,
        views: views.len(),
        frustum: args.frustum,
        fov,
        mean: survey::mean(&views),
        per_view: if args.json { views } else { Vec::new() },
    };
    // Outside the frustum, front-facing triangles are culled on purpose (the library's
    // tests check that none with a vertex inside is).
    anyhow::ensure!(args.frustum || report.mean.front_missed == 0.0, "front-facing triangles were culled");
    super::print_report(args.json, &report, |w, r| {
        use std::io::Write;
        let m = &r.mean;
        let islands = r.uv_islands.map(|n| format!(", {n} UV island(s)")).unwrap_or_default();
        writeln!(
            w,
            "{} ({} weights): {} triangles ({} added by edge splits), {} Steiner vertices",
            r.file, r.weights, r.triangles, r.triangles_added, r.steiner_vertices
        )?;
        writeln!(
            w,
            "strips        {} over {} piece(s) of GPU vertices ({} surface(s){islands}; no strip crosses a seam)",
            r.strips, r.pieces, r.surfaces
        )?;
        writeln!(w, "tree          {} nodes, depth {}, built in {:.1} ms", r.tree_nodes, r.tree_depth, r.build_ms)?;
        writeln!(w, "path          spiral, {} views; per view on average:", r.views)?;
        writeln!(w, "segments      {:.1}", m.segments)?;
        writeln!(w, "drawn         {:.1} triangles", m.drawn)?;
        writeln!(w, "back-facing   {:.1}: {:.1} culled, {:.1} drawn (leak)", m.back, m.back_culled, m.back_drawn)?;
        if r.frustum {
            writeln!(w, "outside       {:.1} triangles skipped outside the frustum ({:.0} degrees)", m.outside, r.fov)?;
        }
        writeln!(
            w,
            "visited       {:.1} nodes from the roots, {:.1} from the front ({:.1} front nodes kept untested)",
            m.visited_root, m.visited_front, m.reused_front
        )?;
        writeln!(w, "time          {:.2} us from the roots, {:.2} us from the front (max {:.2})", m.us_root, m.us_front, m.us_front_max)
    })
}

fn file_name(p: &std::path::Path) -> String {
    p.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default()
}

/// The strip bar of one view: the index buffer as a horizontal band, drawn ranges dark,
/// culled parts light, strip ends marked.
pub fn bar_svg(strips: &stripkit::StripSet, culled: &Culled, title: &str) -> String {
    let heading = format!(
        "{title} - {} segments drawn, {} triangles drawn, {} culled",
        culled.ranges.len(),
        culled.drawn_triangles,
        culled.culled_triangles
    );
    let strip_starts = &strips.offsets[1..strips.offsets.len().saturating_sub(1)];
    stripkit_render::chart::strip_bar(strips.indices.len(), &culled.ranges, strip_starts, &heading)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bar_marks_drawn_ranges() {
        let set = stripkit::StripSet::from_strips(&[vec![0u32, 1, 2, 3, 4, 5]]);
        let pos = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 2.0, 0.0], [1.0, 2.0, 0.0]];
        let tree = SegmentTree::build(&set, &pos);
        let mut out = Culled::default();
        tree.cull([0.5, 1.0, 4.0], &CullOptions::default(), &mut out);
        assert_eq!(out.ranges.len(), 1);
        let svg = bar_svg(&set, &out, "a <b>");
        assert!(svg.contains("fill=\"#202020\"") && svg.contains("a &lt;b&gt;"));
    }
}

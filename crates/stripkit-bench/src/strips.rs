//! The `strips` comparison: stripkit's stripifiers next to meshoptimizer on every mesh
//! of a folder, every figure computed by stripkit's own decoder and metrics
//! (docs/metrics.md), every row verified, times as medians.
//!
//! Every stripkit row goes through the library's front door, as a user's call would.
//! Adding a row: one more entry in [`modes`] (or [`quad_modes`]).

use anyhow::Context;
use std::path::{Path, PathBuf};
use std::time::Instant;
use stripkit::{Algorithm, CacheModel, Figures, GreedyOptions, Heuristic, Split, StripOptions, StripSet};

/// Arguments of the `strips` comparison.
#[derive(clap::Args)]
pub struct Args {
    /// Folder of meshes; its `quads/` subfolder is read too (quads are fanned).
    #[arg(default_value = "../shared/models")]
    pub dir: PathBuf,
    #[command(flatten)]
    pub table: crate::common::TableOut,
    /// Timed runs per row; the table shows the median.
    #[arg(long, default_value_t = 5)]
    pub runs: usize,
    /// Also write an SVG plot of indices per triangle against acmr16 (one point per
    /// row and model: the Pareto picture) to this file.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
    /// Only meshes whose file name contains this text.
    #[arg(long)]
    pub only: Option<String>,
    /// Loop-subdivide every mesh this many times first (each level: 4x the
    /// triangles; `--only bunny.obj --loop 2` gives 1.1M triangles).
    #[arg(long, value_name = "LEVELS", default_value_t = 0)]
    #[arg(long = "loop")]
    pub loop_levels: u32,
}

/// A triangle list reordered before stripifying (the reorder is timed on its own).
type Reorder = fn(&[[u32; 3]], usize) -> Vec<[u32; 3]>;

/// One row kind of the table for every mesh: a peer, or stripkit through its front
/// door ([`stripkit::stripify`], which verifies what it returns).
pub enum Mode {
    /// stripkit with these options; the time is the door's stripify time (the
    /// algorithm alone, as the peers are timed).
    Ours(&'static str, StripOptions),
    /// A peer: an optional reorder (timed separately), then its stripify call.
    Peer(&'static str, Reorder, fn(&[[u32; 3]], usize) -> StripSet),
}

fn greedy(heuristic: Heuristic, tunnel_cuts: Option<usize>) -> StripOptions {
    StripOptions::default().algorithm(Algorithm::Greedy(GreedyOptions::default().heuristic(heuristic).tunnel_cuts(tunnel_cuts)))
}

/// The rows for every mesh, in table order. Other stripkit modes are one line each.
pub fn modes() -> Vec<Mode> {
    vec![
        Mode::Ours("stripkit greedy --heuristic strips", greedy(Heuristic::Strips, Some(1))),
        Mode::Ours("stripkit greedy --heuristic indices", greedy(Heuristic::Indices, Some(1))),
        Mode::Ours("stripkit greedy --heuristic indices --tunnel 0 (paper)", greedy(Heuristic::Indices, None)),
        Mode::Peer("meshopt optimize_vertex_cache + stripify", reorder_cache, meshopt_stripify),
        Mode::Peer("meshopt optimize_vertex_cache_strip + stripify", reorder_strip, meshopt_stripify),
        Mode::Ours("stripkit cache", StripOptions::default().algorithm(Algorithm::cache())),
        Mode::Ours("stripkit cache --refine", StripOptions::default().algorithm(Algorithm::Cache { refine: true })),
        Mode::Ours("stripkit balanced (acmr16 <= 0.8)", StripOptions::default().algorithm(Algorithm::balanced(0.8))),
    ]
}

/// Extra rows on quad-dominant meshes: the cache-aware modes on the fan alone, so
/// that the gain of QSTRIP's split shows, and QSTRIP itself (followed by the peer on
/// QSTRIP's split, see [`run`]).
fn quad_modes() -> Vec<Mode> {
    let fan = StripOptions::default().split(Split::Fan);
    vec![
        Mode::Ours("stripkit cache --split fan", fan.clone().algorithm(Algorithm::cache())),
        Mode::Ours("stripkit balanced --split fan (acmr16 <= 0.8)", fan.algorithm(Algorithm::balanced(0.8))),
        Mode::Ours("stripkit qstrip (other faces: greedy)", StripOptions::default().algorithm(Algorithm::qstrip())),
    ]
}

fn unflat(indices: &[u32]) -> Vec<[u32; 3]> {
    indices
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect()
}

pub(crate) fn reorder_cache(tris: &[[u32; 3]], n: usize) -> Vec<[u32; 3]> {
    unflat(&meshopt::optimize_vertex_cache(tris.as_flattened(), n))
}

pub(crate) fn reorder_strip(tris: &[[u32; 3]], n: usize) -> Vec<[u32; 3]> {
    unflat(&meshopt::optimize_vertex_cache_strip(tris.as_flattened(), n))
}

/// meshoptimizer's stripify with restart index `u32::MAX`, split by stripkit's decoder.
pub(crate) fn meshopt_stripify(tris: &[[u32; 3]], n: usize) -> StripSet {
    match meshopt::stripify(tris.as_flattened(), n, u32::MAX) {
        Ok(buf) => stripkit::decode_restart(&buf, u32::MAX),
        Err(_) => StripSet::new(), // shows up as "lost" in the verified column
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

/// Runs `f` `runs` times (at least once): its last result and the median time in ms.
fn timed<T>(runs: usize, mut f: impl FnMut() -> T) -> (T, f64) {
    let mut times = Vec::with_capacity(runs.max(1));
    let mut out = None;
    for _ in 0..runs.max(1) {
        let t = Instant::now();
        out = Some(f());
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    (out.expect("at least one run"), median(times))
}

struct Row {
    model: String,
    mode: &'static str,
    figures: Figures,
    ms: f64,
    reorder_ms: Option<f64>,
    /// Quads of the mesh when at least half its faces are quads (for `idx/quad`).
    quads: Option<usize>,
}

/// The meshes of `dir` and of its `quads/` subfolder, sorted by path.
pub(crate) fn mesh_files(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for d in [dir.to_path_buf(), dir.join("quads")] {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries {
            let p = e?.path();
            if p.is_file() && stripkit::io::Format::from_path(&p).is_some() {
                files.push(p);
            }
        }
    }
    files.sort();
    Ok(files)
}

/// Runs the comparison.
pub fn run(args: Args) -> anyhow::Result<()> {
    if !args.dir.is_dir() {
        anyhow::bail!(
            "{}: no such folder of meshes (give one as the first argument)",
            args.dir.display()
        );
    }
    let runs = args.runs.max(1);
    let modes = modes();
    let mut rows = Vec::new();
    let mut failed: Vec<String> = Vec::new();
    for path in mesh_files(&args.dir)? {
        let name = path
            .strip_prefix(&args.dir)
            .unwrap_or(&path)
            .display()
            .to_string();
        if args
            .only
            .as_ref()
            .is_some_and(|o| !name.contains(o.as_str()))
        {
            continue;
        }
        let mut mesh = crate::common::read_surface(&path)
            .with_context(|| format!("reading {}", path.display()))?;
        let name = if args.loop_levels > 0 {
            mesh = stripkit::gen::subdivide_loop(
                &stripkit::Mesh::from_triangles(mesh.positions.clone(), &mesh.triangulate().tris),
                args.loop_levels,
            )?;
            format!("{name} (Loop x{})", args.loop_levels)
        } else {
            name
        };
        let tris = mesh.triangulate().tris;
        let n = mesh.vertex_count();
        eprintln!("{name}: {} triangles", tris.len());
        let quad_dominant = stripkit::is_quad_dominant(&mesh);
        let first = rows.len();
        let mut extra = if quad_dominant { quad_modes() } else { Vec::new() };
        for mode in modes.iter().chain(extra.iter()) {
            let row = match mode {
                Mode::Peer(label, reorder, stripify) => {
                    let (input, reorder_ms) = timed(runs, || reorder(&tris, n));
                    let (strips, ms) = timed(runs, || stripify(&input, n));
                    // Figures against the original triangles: the reorder must not lose any.
                    let figures = stripkit::figures(&tris, &strips, CacheModel::default());
                    Row { model: name.clone(), mode: label, figures, ms, reorder_ms: Some(reorder_ms), quads: None }
                }
                Mode::Ours(label, options) => ours_row(&mesh, &name, label, options, runs, &mut failed),
            };
            rows.push(row);
        }
        extra.clear();
        if quad_dominant {
            // The peer on QSTRIP's split (the triangles the QSTRIP row's strips chose),
            // so that the diagonals' own gain shows.
            let qstrip = stripkit::stripify(&mesh, &StripOptions::default().algorithm(Algorithm::qstrip()))
                .with_context(|| format!("{name}: qstrip"))?;
            let split = qstrip.triangles;
            let (input, reorder_ms) = timed(runs, || reorder_cache(&split, n));
            let (out, ms) = timed(runs, || meshopt_stripify(&input, n));
            rows.push(Row {
                model: name.to_string(),
                mode: "meshopt optimize_vertex_cache + stripify, QSTRIP split",
                figures: stripkit::figures(&split, &out, CacheModel::default()),
                ms,
                reorder_ms: Some(reorder_ms),
                quads: None,
            });
            for r in &mut rows[first..] {
                r.quads = qstrip.quads;
            }
        }
    }
    let table = render(&rows, runs);
    print!("{table}");
    if let Some(out) = &args.table.out {
        stripkit::io::write_encoded(out, table.as_bytes()).with_context(|| format!("writing {}", out.display()))?;
    }
    if let Some(svg) = &args.svg {
        stripkit::io::write_encoded(svg, pareto_svg(&rows).as_bytes()).with_context(|| format!("writing {}", svg.display()))?;
    }
    if !failed.is_empty() {
        anyhow::bail!("verification failed: {}", failed.join(", "));
    }
    Ok(())
}

/// One stripkit row through the front door: the door verifies (at quad level where
/// quads were split along chosen diagonals) and measures; a refusal is recorded as a
/// failure and shown as an unverified row.
fn ours_row(
    mesh: &stripkit::Mesh,
    model: &str,
    label: &'static str,
    options: &StripOptions,
    runs: usize,
    failed: &mut Vec<String>,
) -> Row {
    let mut times = Vec::with_capacity(runs);
    let mut last = None;
    for _ in 0..runs {
        let r = stripkit::stripify(mesh, options);
        if let Ok(s) = &r {
            times.push(s.stripify_time.as_secs_f64() * 1e3);
        }
        last = Some(r);
    }
    match last.expect("at least one run") {
        Ok(s) => Row {
            model: model.to_string(),
            mode: label,
            figures: s.figures,
            ms: median(times),
            reorder_ms: None,
            quads: s.quads,
        },
        Err(e) => {
            eprintln!("{model}: {label}: {e}");
            failed.push(format!("{label} on {model}: {e}"));
            let mut figures = stripkit::figures(&[], &StripSet::new(), CacheModel::default());
            figures.verified = false;
            Row { model: model.to_string(), mode: label, figures, ms: f64::NAN, reorder_ms: None, quads: None }
        }
    }
}

fn render(rows: &[Row], runs: usize) -> String {
    let mut s = String::new();
    s.push_str("# Triangle strips: stripkit next to meshoptimizer\n\n");
    s.push_str(&format!(
        "Every figure by stripkit's decoder and metrics (docs/metrics.md). meshoptimizer's strips use restart \
         index 0xFFFFFFFF and are split with stripkit's decoder. `ms`: median of {runs} runs of the stripify \
         call alone, single thread; `reorder ms`: meshoptimizer's vertex-cache reordering before it. \
         `ok`: decoded triangles equal the input's (nothing lost, nothing added, no winding flipped). \
         Lower is better everywhere; `idx/tri` = indices_restart / triangles; `idx/quad` = \
         indices_restart / quads on quad-dominant meshes, where QSTRIP works on the quads themselves \
         (either diagonal, checked at quad level) and the other rows on the fan triangulation, but \
         for the `--split auto` rows (the fan or QSTRIP's split of the quads, whichever gives the \
         cheaper strips; checked at quad level) and meshoptimizer on QSTRIP's split.\n\n"
    ));
    s.push_str("| model | triangles | stripifier | strips | swaps | indices_restart | idx/tri | idx/quad | indices_degenerate | acmr16 | acmr32 | ms | reorder ms | ok |\n");
    s.push_str("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    let mut last = String::new();
    for r in rows {
        let f = &r.figures;
        let (model, tri) = if r.model != last {
            last = r.model.clone();
            (format!("`{}`", r.model), group(f.triangles))
        } else {
            (String::new(), String::new())
        };
        let ok = if f.verified {
            "yes".to_string()
        } else {
            format!(
                "**no**: {} lost, {} added, {} flipped",
                f.lost, f.added, f.flipped
            )
        };
        s.push_str(&format!(
            "| {model} | {tri} | {} | {} | {} | {} | {:.3} | {} | {} | {:.3} | {:.3} | {:.2} | {} | {ok} |\n",
            r.mode,
            group(f.strips),
            group(f.swaps),
            group(f.indices_restart),
            f.indices_per_triangle,
            r.quads.filter(|&q| q > 0).map_or("-".to_string(), |q| format!("{:.3}", f.indices_restart as f64 / q as f64)),
            group(f.indices_degenerate),
            f.acmr16,
            f.acmr32,
            r.ms,
            r.reorder_ms.map_or("-".to_string(), |m| format!("{m:.2}")),
        ));
    }
    s
}

/// 12345678 -> "12,345,678".
fn group(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).rem_euclid(3) == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// `text` with XML's special characters escaped, for SVG text and titles.
fn xml(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// Indices per triangle (x) against acmr16 (y), one point per row, one colour per
/// stripifier; lower-left is better on both figures.
fn pareto_svg(rows: &[Row]) -> String {
    let (w, h, m) = (760.0, 420.0, 50.0);
    let (x0, x1, y0, y1) = (1.0f64, 2.2f64, 0.5f64, 1.2f64);
    let px = |x: f64| m + (x.clamp(x0, x1) - x0) / (x1 - x0) * (w - 2.0 * m);
    let py = |y: f64| h - m - (y.clamp(y0, y1) - y0) / (y1 - y0) * (h - 2.0 * m);
    let colours = ["#d62728", "#1f77b4", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf", "#000000"];
    let mut names: Vec<&str> = Vec::new();
    for r in rows {
        if !names.contains(&r.mode) {
            names.push(r.mode);
        }
    }
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"11\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n\
         <line x1=\"{m}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"black\"/>\n\
         <line x1=\"{m}\" y1=\"{m}\" x2=\"{m}\" y2=\"{}\" stroke=\"black\"/>\n\
         <text x=\"{}\" y=\"{}\" text-anchor=\"middle\">indices_restart per triangle</text>\n\
         <text x=\"12\" y=\"{}\" transform=\"rotate(-90 12 {})\" text-anchor=\"middle\">acmr16 (FIFO 16)</text>\n",
        h - m, w - m, h - m, h - m, w / 2.0, h - 12.0, h / 2.0, h / 2.0
    );
    for i in 0..=6 {
        let x = x0 + (x1 - x0) * i as f64 / 6.0;
        s.push_str(&format!("<text x=\"{:.1}\" y=\"{}\" text-anchor=\"middle\">{x:.1}</text>\n", px(x), h - m + 14.0));
        let y = y0 + (y1 - y0) * i as f64 / 6.0;
        s.push_str(&format!("<text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">{y:.2}</text>\n", m - 4.0, py(y) + 4.0));
    }
    for r in rows {
        let k = names.iter().position(|&n| n == r.mode).unwrap_or(0) % colours.len();
        s.push_str(&format!(
            "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"3.5\" fill=\"{}\"><title>{} {}: {:.3} idx/tri, acmr16 {:.3}</title></circle>\n",
            px(r.figures.indices_per_triangle),
            py(r.figures.acmr16),
            colours[k],
            xml(&r.model),
            xml(r.mode),
            r.figures.indices_per_triangle,
            r.figures.acmr16
        ));
    }
    for (k, n) in names.iter().enumerate() {
        let y = m + 14.0 * k as f64;
        s.push_str(&format!(
            "<circle cx=\"{}\" cy=\"{y}\" r=\"4\" fill=\"{}\"/><text x=\"{}\" y=\"{}\">{}</text>\n",
            w - 350.0,
            colours[k % colours.len()],
            w - 342.0,
            y + 4.0,
            xml(n)
        ));
    }
    s.push_str("</svg>\n");
    s
}

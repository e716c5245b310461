//! The `strips` comparison: stripkit's stripifiers next to meshoptimizer on every mesh
//! of a folder, every figure computed by stripkit's own decoder and metrics
//! (METRICS.md), every row verified, times as medians.
//!
//! Adding a row: one more entry in [`modes`].

use anyhow::Context;
use std::path::{Path, PathBuf};
use std::time::Instant;
use stripkit::metrics::{self, CacheModel, Figures};
use stripkit::strip::{self, StripSet};
use stripkit::stripify::cache::{self, CacheOptions};
use stripkit::stripify::greedy::{self, GreedyOptions, Heuristic};

/// Arguments of the `strips` comparison.
#[derive(clap::Args)]
pub struct Args {
    /// Folder of meshes; its `quads/` subfolder is read too (quads are fanned).
    #[arg(default_value = "../shared/models")]
    pub dir: PathBuf,
    /// Also write the markdown table to this file.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
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
/// A stripifier: triangles and vertex count in, strips out.
type Stripifier = Box<dyn Fn(&[[u32; 3]], usize) -> StripSet>;

/// One row kind of the table.
pub struct Mode {
    /// Row label.
    pub name: &'static str,
    /// Optional reordering before the stripify call (timed separately).
    pub reorder: Option<Reorder>,
    /// The stripify call (timed).
    pub stripify: Stripifier,
    /// True for stripkit's own modes: a failed verification is then an error.
    pub ours: bool,
}

fn ours(name: &'static str, f: impl Fn(&[[u32; 3]], usize) -> StripSet + 'static) -> Mode {
    Mode {
        name,
        reorder: None,
        stripify: Box::new(f),
        ours: true,
    }
}

fn peer(
    name: &'static str,
    reorder: Reorder,
    f: impl Fn(&[[u32; 3]], usize) -> StripSet + 'static,
) -> Mode {
    Mode {
        name,
        reorder: Some(reorder),
        stripify: Box::new(f),
        ours: false,
    }
}

/// The rows, in table order. Other stripkit modes are one line each.
pub fn modes() -> Vec<Mode> {
    vec![
        ours("stripkit greedy --heuristic strips", |t, n| {
            greedy::stripify(
                t,
                n,
                &GreedyOptions::with_heuristic(Heuristic::Strips),
            )
        }),
        ours("stripkit greedy --heuristic indices", |t, n| {
            greedy::stripify(
                t,
                n,
                &GreedyOptions::with_heuristic(Heuristic::Indices),
            )
        }),
        ours("stripkit greedy --heuristic indices --tunnel 0 (paper)", |t, n| {
            let options = GreedyOptions {
                heuristic: Heuristic::Indices,
                tunnel_cuts: None,
            };
            greedy::stripify(t, n, &options)
        }),
        peer("meshopt optimize_vertex_cache + stripify", reorder_cache, meshopt_stripify),
        peer("meshopt optimize_vertex_cache_strip + stripify", reorder_strip, meshopt_stripify),
    ]
}

fn flat(tris: &[[u32; 3]]) -> Vec<u32> {
    tris.iter().flatten().copied().collect()
}

fn unflat(indices: &[u32]) -> Vec<[u32; 3]> {
    indices
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect()
}

fn reorder_cache(tris: &[[u32; 3]], n: usize) -> Vec<[u32; 3]> {
    unflat(&meshopt::optimize_vertex_cache(&flat(tris), n))
}

fn reorder_strip(tris: &[[u32; 3]], n: usize) -> Vec<[u32; 3]> {
    unflat(&meshopt::optimize_vertex_cache_strip(&flat(tris), n))
}

/// meshoptimizer's stripify with restart index `u32::MAX`, split by stripkit's decoder.
fn meshopt_stripify(tris: &[[u32; 3]], n: usize) -> StripSet {
    match meshopt::stripify(&flat(tris), n, u32::MAX) {
        Ok(buf) => strip::decode_restart(&buf, u32::MAX),
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
    ours: bool,
    /// Quads of the mesh when at least half its faces are quads (for `idx/quad`).
    quads: Option<usize>,
}

fn mesh_files(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for d in [dir.to_path_buf(), dir.join("quads")] {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries {
            let p = e?.path();
            if p.is_file() && stripkit::mesh::io::Format::from_path(&p).is_some() {
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
        let mut mesh = stripkit::mesh::io::read(&path)
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
        for mode in &modes {
            let (input, reorder_ms) = match mode.reorder {
                Some(r) => {
                    let (out, ms) = timed(runs, || r(&tris, n));
                    (out, Some(ms))
                }
                None => (tris.clone(), None),
            };
            let (strips, ms) = timed(runs, || (mode.stripify)(&input, n));
            // Figures against the original triangles: the reorder must not lose any.
            let figures = metrics::figures(&tris, &strips, CacheModel::default());
            rows.push(Row {
                model: name.clone(),
                mode: mode.name,
                figures,
                ms,
                reorder_ms,
                ours: mode.ours,
                quads: None,
            });
        }
        cache_rows(&mesh, &name, &tris, runs, &mut rows);
        quad_row(&mesh, &name, runs, &mut rows);
    }
    let table = render(&rows, runs);
    print!("{table}");
    if let Some(out) = &args.out {
        std::fs::write(out, &table).with_context(|| format!("writing {}", out.display()))?;
    }
    if let Some(svg) = &args.svg {
        std::fs::write(svg, pareto_svg(&rows)).with_context(|| format!("writing {}", svg.display()))?;
    }
    let failed: Vec<String> =
        rows.iter().filter(|r| r.ours && !r.figures.verified).map(|r| format!("{} on {}", r.mode, r.model)).collect();
    if !failed.is_empty() {
        anyhow::bail!("verification failed: {}", failed.join(", "));
    }
    Ok(())
}

/// The cache-aware modes as the CLI runs them (`cache::stripify_mesh`: a canonical
/// vertex order, and on quad-dominant meshes the cheaper of the fan and QSTRIP's split,
/// `--diagonals auto`); on quad-dominant meshes also on the fan alone. Strips on
/// QSTRIP's split are checked at quad level, the others against the input's fan.
fn cache_rows(mesh: &stripkit::Mesh, name: &str, tris: &[[u32; 3]], runs: usize, rows: &mut Vec<Row>) {
    use stripkit::stripify::{quad, quad_verify};
    let quad_dominant = quad::quad_fraction(mesh) >= 0.5;
    let mut modes: Vec<(&'static str, CacheOptions, Option<f64>, cache::Diagonals)> = vec![
        ("stripkit cache", CacheOptions::cache(16), None, cache::Diagonals::Auto),
        (
            "stripkit cache --refine",
            CacheOptions { refine: true, ..CacheOptions::cache(16) },
            None,
            cache::Diagonals::Auto,
        ),
        ("stripkit balanced (acmr16 <= 0.8)", CacheOptions::balanced(16), Some(0.8), cache::Diagonals::Auto),
    ];
    if quad_dominant {
        modes.push(("stripkit cache --diagonals fan", CacheOptions::cache(16), None, cache::Diagonals::Fan));
        modes.push((
            "stripkit balanced --diagonals fan (acmr16 <= 0.8)",
            CacheOptions::balanced(16),
            Some(0.8),
            cache::Diagonals::Fan,
        ));
    }
    for (mode, options, bound, diagonals) in modes {
        let (m, ms) = timed(runs, || cache::stripify_mesh(mesh, &options, bound, diagonals));
        let figures = if m.qstrip_diagonals {
            let mut f = metrics::figures(&m.triangles, &m.strips, CacheModel::default());
            if let Err(e) = quad_verify::verify_quads(mesh, &m.strips) {
                eprintln!("{name}: {mode}: {e}");
                f.verified = false;
            }
            f
        } else {
            metrics::figures(tris, &m.strips, CacheModel::default())
        };
        rows.push(Row { model: name.to_string(), mode, figures, ms, reorder_ms: None, ours: true, quads: None });
    }
}

/// QSTRIP on quad-dominant meshes (at least half the faces quads): quads through
/// QSTRIP, the rest through greedy; verified at quad level (either diagonal), figures
/// against the triangles the strips chose. Marks the mesh's rows with its quad count.
fn quad_row(mesh: &stripkit::Mesh, name: &str, runs: usize, rows: &mut Vec<Row>) {
    use stripkit::stripify::{quad, quad_verify};
    if quad::quad_fraction(mesh) < 0.5 {
        return;
    }
    let ((q, strips), qstrip_ms) =
        timed(runs, || quad::qstrip_mesh(mesh, &quad::QuadOptions::default()));
    let check = quad_verify::verify_quads(mesh, &strips);
    // The triangles the strips chose (the quad check proved them the mesh's).
    let qstrip_tris = strip::decode(&strips);
    let mut figures = metrics::figures(&qstrip_tris, &strips, CacheModel::default());
    if let Err(e) = &check {
        eprintln!("{name}: QSTRIP {e}");
        figures.verified = false;
    }
    let quads = Some(q.quad_count());
    for r in rows.iter_mut().filter(|r| r.model == name) {
        r.quads = quads;
    }
    rows.push(Row {
        model: name.to_string(),
        mode: "stripkit qstrip (other faces: greedy)",
        figures,
        ms: qstrip_ms,
        reorder_ms: None,
        ours: true,
        quads,
    });
    // The peer on the same split, so that the diagonals' own gain shows.
    let n = mesh.vertex_count();
    let (input, reorder_ms) = timed(runs, || reorder_cache(&qstrip_tris, n));
    let (out, ms) = timed(runs, || meshopt_stripify(&input, n));
    rows.push(Row {
        model: name.to_string(),
        mode: "meshopt optimize_vertex_cache + stripify, QSTRIP split",
        figures: metrics::figures(&qstrip_tris, &out, CacheModel::default()),
        ms,
        reorder_ms: Some(reorder_ms),
        ours: false,
        quads,
    });
}

fn render(rows: &[Row], runs: usize) -> String {
    let mut s = String::new();
    s.push_str("# Triangle strips: stripkit next to meshoptimizer\n\n");
    s.push_str(&format!(
        "Every figure by stripkit's decoder and metrics (METRICS.md). meshoptimizer's strips use restart \
         index 0xFFFFFFFF and are split with stripkit's decoder. `ms`: median of {runs} runs of the stripify \
         call alone, single thread; `reorder ms`: meshoptimizer's vertex-cache reordering before it. \
         `ok`: decoded triangles equal the input's (nothing lost, nothing added, no winding flipped). \
         Lower is better everywhere; `idx/tri` = indices_restart / triangles; `idx/quad` = \
         indices_restart / quads on quad-dominant meshes, where QSTRIP works on the quads themselves \
         (either diagonal, checked at quad level) and the other rows on the fan triangulation, but \
         for the `--diagonals auto` rows (the fan or QSTRIP's split of the quads, whichever gives the \
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

//! The `strips` comparison: stripkit's stripifiers next to meshoptimizer on every mesh
//! of a folder, every figure computed by stripkit's own decoder and metrics
//! (METRICS.md), every row verified, times as medians.
//!
//! stripkit's rows run through the library's front door ([`stripkit::stripify`]), which
//! verifies every result; their time is the door's `stripify_time` (the stripifier
//! alone). Adding a row: one more entry in [`modes`] (or in [`cache_rows`]).

use anyhow::Context;
use std::path::{Path, PathBuf};
use std::time::Instant;
use stripkit::{
    figures, stripify, Algorithm, CacheModel, Figures, GreedyOptions, Heuristic, Mesh, Split, StripOptions,
    StripSet, Strips,
};

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
/// A peer's stripifier: triangles and vertex count in, strips out.
type PeerStripify = fn(&[[u32; 3]], usize) -> StripSet;

/// How a row's strips are made.
pub enum Run {
    /// stripkit through the front door with these options (verified there).
    Ours(StripOptions),
    /// Another library on the fan triangles: a reordering (timed separately), then its
    /// stripify call (timed), verified against the fan here.
    Peer(Reorder, PeerStripify),
}

/// One row kind of the table.
pub struct Mode {
    /// Row label.
    pub name: &'static str,
    /// How the strips are made.
    pub run: Run,
}

fn ours(name: &'static str, algorithm: Algorithm) -> Mode {
    Mode { name, run: Run::Ours(StripOptions::default().algorithm(algorithm)) }
}

fn peer(name: &'static str, reorder: Reorder, stripify: PeerStripify) -> Mode {
    Mode { name, run: Run::Peer(reorder, stripify) }
}

/// The rows run on every mesh's fan triangulation, in table order.
pub fn modes() -> Vec<Mode> {
    let greedy = |heuristic, tunnel_cuts| Algorithm::Greedy(GreedyOptions { heuristic, tunnel_cuts });
    vec![
        ours("stripkit greedy --heuristic strips", greedy(Heuristic::Strips, Some(1))),
        ours("stripkit greedy --heuristic indices", greedy(Heuristic::Indices, Some(1))),
        ours("stripkit greedy --heuristic indices --tunnel 0 (paper)", greedy(Heuristic::Indices, None)),
        peer("meshopt optimize_vertex_cache + stripify", reorder_cache, meshopt_stripify),
        peer("meshopt optimize_vertex_cache_strip + stripify", reorder_strip, meshopt_stripify),
    ]
}

/// The door with `options` `runs` times (at least once): its last result and the median
/// of its `stripify_time` in ms. A failed check is an error naming the row.
fn door(mesh: &Mesh, options: &StripOptions, runs: usize, what: &str) -> anyhow::Result<(Strips, f64)> {
    let mut times = Vec::with_capacity(runs.max(1));
    let mut out = None;
    for _ in 0..runs.max(1) {
        let s = stripify(mesh, options).with_context(|| what.to_string())?;
        times.push(s.stripify_time.as_secs_f64() * 1e3);
        out = Some(s);
    }
    Ok((out.expect("at least one run"), median(times)))
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
    ours: bool,
    /// Quads of the mesh when at least half its faces are quads (for `idx/quad`).
    quads: Option<usize>,
}

impl Row {
    /// A row of stripkit's, verified by the door.
    fn ours(model: &str, mode: &'static str, figures: Figures, ms: f64, quads: Option<usize>) -> Row {
        Row { model: model.to_string(), mode, figures, ms, reorder_ms: None, ours: true, quads }
    }
}

fn mesh_files(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
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
        let mut mesh = stripkit::io::read(&path)
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
            rows.push(match &mode.run {
                Run::Ours(options) => {
                    let (s, ms) = door(&mesh, options, runs, &format!("{} on {name}", mode.name))?;
                    Row::ours(&name, mode.name, s.figures, ms, None)
                }
                Run::Peer(reorder, stripify) => {
                    let (input, reorder_ms) = timed(runs, || reorder(&tris, n));
                    let (strips, ms) = timed(runs, || stripify(&input, n));
                    // Figures against the original triangles: the reorder must not lose any.
                    let figures = figures(&tris, &strips, CacheModel::default());
                    Row { model: name.clone(), mode: mode.name, figures, ms, reorder_ms: Some(reorder_ms), ours: false, quads: None }
                }
            });
        }
        cache_rows(&mesh, &name, runs, &mut rows)?;
        quad_row(&mesh, &name, runs, &mut rows)?;
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

/// The cache-aware modes as the CLI runs them (the door's `cache`, `cache` with
/// refinement and `balanced`, FIFO 16, split auto: on quad-dominant meshes the cheaper
/// of the fan and QSTRIP's split); on quad-dominant meshes also on the fan alone. The
/// door checks strips on QSTRIP's split at quad level, the others against the fan.
fn cache_rows(mesh: &Mesh, name: &str, runs: usize, rows: &mut Vec<Row>) -> anyhow::Result<()> {
    let mut modes: Vec<(&'static str, Algorithm, Split)> = vec![
        ("stripkit cache", Algorithm::cache(), Split::Auto),
        ("stripkit cache --refine", Algorithm::Cache { refine: true }, Split::Auto),
        ("stripkit balanced (acmr16 <= 0.8)", Algorithm::balanced(0.8), Split::Auto),
    ];
    if stripkit::is_quad_dominant(mesh) {
        modes.push(("stripkit cache --diagonals fan", Algorithm::cache(), Split::Fan));
        modes.push(("stripkit balanced --diagonals fan (acmr16 <= 0.8)", Algorithm::balanced(0.8), Split::Fan));
    }
    for (mode, algorithm, split) in modes {
        let options = StripOptions::default().algorithm(algorithm).split(split);
        let (s, ms) = door(mesh, &options, runs, &format!("{mode} on {name}"))?;
        rows.push(Row::ours(name, mode, s.figures, ms, None));
    }
    Ok(())
}

/// QSTRIP on quad-dominant meshes (see [`stripkit::is_quad_dominant`]): quads through
/// QSTRIP, the rest through greedy; verified by the door at quad level (either
/// diagonal), figures against the triangles the strips chose. Marks the mesh's rows
/// with its quad count.
fn quad_row(mesh: &Mesh, name: &str, runs: usize, rows: &mut Vec<Row>) -> anyhow::Result<()> {
    if !stripkit::is_quad_dominant(mesh) {
        return Ok(());
    }
    let options = StripOptions::default().algorithm(Algorithm::qstrip());
    let (s, qstrip_ms) = door(mesh, &options, runs, &format!("QSTRIP on {name}"))?;
    // The triangles the strips chose (the quad check proved them the mesh's).
    let qstrip_tris = s.triangles;
    let quads = s.quads;
    for r in rows.iter_mut().filter(|r| r.model == name) {
        r.quads = quads;
    }
    rows.push(Row::ours(name, "stripkit qstrip (other faces: greedy)", s.figures, qstrip_ms, quads));
    // The peer on the same split, so that the diagonals' own gain shows.
    let n = mesh.vertex_count();
    let (input, reorder_ms) = timed(runs, || reorder_cache(&qstrip_tris, n));
    let (out, ms) = timed(runs, || meshopt_stripify(&input, n));
    rows.push(Row {
        model: name.to_string(),
        mode: "meshopt optimize_vertex_cache + stripify, QSTRIP split",
        figures: figures(&qstrip_tris, &out, CacheModel::default()),
        ms,
        reorder_ms: Some(reorder_ms),
        ours: false,
        quads,
    });
    Ok(())
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

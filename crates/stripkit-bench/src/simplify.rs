//! The `simplify` comparison: stripkit's QEM (endpoint and optimal placement) next to
//! meshoptimizer's `simplify` at the same triangle counts, every distance measured by
//! stripkit's own `distance` against the input; writes a markdown table.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;
use stripkit::simplify::{simplify, Options, Placement, Target};
use stripkit::Mesh;

/// Arguments of the `simplify` comparison.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub models: crate::common::Models,
    /// Model files inside that folder.
    #[arg(long, value_delimiter = ',', default_value = "bunny.obj,horse.ply,dragon.obj")]
    pub files: Vec<String>,
    /// Fractions of the triangles to keep.
    #[arg(long, value_delimiter = ',', default_value = "0.1,0.01")]
    pub ratios: Vec<f64>,
    /// Samples per surface for the distances.
    #[arg(long, default_value_t = 200_000)]
    pub samples: usize,
    /// Timing runs per simplification (the median is reported).
    #[arg(long, default_value_t = 3)]
    pub runs: usize,
    /// Also time the whole collapse sequence of a ~1.1M-triangle mesh (the first
    /// model, Loop-subdivided twice) down to 1%.
    #[arg(long)]
    pub big: bool,
    /// Write the markdown table here as well as to stdout.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

pub(crate) fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

pub(crate) fn meshopt_simplify(mesh: &Mesh, tris: &[[u32; 3]], target_tris: usize) -> (Vec<u32>, f64) {
    let indices: Vec<u32> = tris.iter().flatten().copied().collect();
    let bytes: Vec<u8> = mesh.positions.iter().flatten().flat_map(|x| x.to_le_bytes()).collect();
    let adapter = meshopt::VertexDataAdapter::new(&bytes, 12, 0).expect("vertex adapter");
    let start = Instant::now();
    let out = meshopt::simplify(&indices, &adapter, target_tris * 3, 1.0, meshopt::SimplifyOptions::None, None);
    (out, start.elapsed().as_secs_f64() * 1e3)
}

/// Runs the comparison.
pub fn run(args: Args) -> anyhow::Result<()> {
    let dir = match args.models.dir() {
        Some(d) => d,
        None => anyhow::bail!("no models folder (give --models)"),
    };
    let mut table = String::new();
    writeln!(table, "| model | target | method | triangles | Hausdorff | RMS | H / meshopt | RMS / meshopt | ms |")?;
    writeln!(table, "|---|---|---|---:|---:|---:|---:|---:|---:|")?;
    for file in &args.files {
        let path = dir.join(file);
        let mesh = crate::common::read_surface(&path)?;
        let tris = mesh.triangulate().tris;
        for &ratio in &args.ratios {
            let target = ((tris.len() as f64) * ratio).round() as usize;
            let mut mo_ms = Vec::new();
            let mut mo = Vec::new();
            for _ in 0..args.runs.max(1) {
                let (o, ms) = meshopt_simplify(&mesh, &tris, target);
                mo = o;
                mo_ms.push(ms);
            }
            let mo_tris: Vec<[u32; 3]> = mo.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
            let mo_mesh = Mesh::from_triangles(mesh.positions.clone(), &mo_tris);
            let count = mo_tris.len();
            let d_mo = stripkit::distance::distance(&mesh, &mo_mesh, args.samples)?;
            let name = file.rsplit('/').next().unwrap_or(file);
            let label = format!("{}%", ratio * 100.0);
            writeln!(
                table,
                "| {name} | {label} | meshoptimizer simplify | {count} | {:.3e} | {:.3e} | 1 | 1 | {:.1} |",
                d_mo.hausdorff,
                d_mo.rms,
                median(mo_ms)
            )?;
            for placement in [Placement::Endpoint, Placement::Optimal] {
                let opts = Options::default().target(Target::Triangles(count)).placement(placement);
                let mut times = Vec::new();
                let mut result = None;
                for _ in 0..args.runs.max(1) {
                    let start = Instant::now();
                    let r = simplify(&mesh, &opts, &mut |_| {})?;
                    times.push(start.elapsed().as_secs_f64() * 1e3);
                    result = Some(r);
                }
                let Some(r) = result else { continue };
                let d = stripkit::distance::distance(&mesh, &r.mesh, args.samples)?;
                writeln!(
                    table,
                    "| {name} | {label} | stripkit {} | {} | {:.3e} | {:.3e} | {:.2} | {:.2} | {:.1} |",
                    format!("{placement:?}").to_lowercase(),
                    r.triangles_out(),
                    d.hausdorff,
                    d.rms,
                    d.hausdorff / d_mo.hausdorff,
                    d.rms / d_mo.rms,
                    median(times)
                )?;
            }
            eprintln!("done: {file} at {label}");
        }
    }
    if args.big {
        let first = args.files.first().map(|f| dir.join(f)).unwrap_or_default();
        let mesh = stripkit::gen::subdivide_loop(&crate::common::read_surface(&first)?, 2)?;
        let n = mesh.triangle_count();
        for placement in [Placement::Endpoint, Placement::Optimal] {
            let opts = Options::default().target(Target::Ratio(0.01)).placement(placement);
            let mut times = Vec::new();
            let mut out = 0;
            for _ in 0..args.runs.max(1) {
                let start = Instant::now();
                let r = simplify(&mesh, &opts, &mut |_| {})?;
                times.push(start.elapsed().as_secs_f64() * 1e3);
                out = r.triangles_out();
            }
            writeln!(
                table,
                "\n{} Loop-subdivided twice ({n} triangles) to 1% ({out}), {:?}: {:.0} ms (median of {})",
                first.display(),
                placement,
                median(times.clone()),
                times.len()
            )?;
        }
        let tris = mesh.triangulate().tris;
        let (_, ms) = meshopt_simplify(&mesh, &tris, n / 100);
        writeln!(table, "meshoptimizer simplify on the same mesh to 1%: {ms:.0} ms")?;
    }
    print!("{table}");
    if let Some(out) = &args.output {
        stripkit::io::write_encoded(out, table.as_bytes())?;
    }
    Ok(())
}

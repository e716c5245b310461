//! The `single` comparison: single strips (`--algo single`) for every weight kind on
//! the research models and their Loop subdivisions, with the figures the issue asks
//! for (strips against components, Steiner vertices and swaps, acmr16 and acmr32, time
//! end to end and of the matching), next to meshoptimizer's vertex-cache order (its
//! list, and its strips) on the same triangles, in the same run.

use anyhow::Context;
use std::time::Instant;
use stripkit::{Algorithm, CacheModel, MatchingMode, SingleOptions, StripOptions, StripSet, Weights};

/// Arguments of the `single` comparison.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub models: crate::common::Models,
    /// Models, comma-separated file names in the folder.
    #[arg(long, default_value = "bunny_small.off,cow.obj,spot_triangulated.obj,fandisk.obj,horse.ply,dragon.obj,bunny.obj")]
    pub only: String,
    /// Weight kinds, separated by `;` (as `--weights` takes them).
    #[arg(long, default_value = "uniform;cache;cull;direction:0,0,1")]
    pub weights: String,
    /// Loop subdivision levels to run, comma-separated (0: the model itself).
    #[arg(long = "loop", default_value = "0")]
    pub levels: String,
    /// How the dual graph is matched: auto, exact or greedy.
    #[arg(long, default_value = "auto")]
    pub matching: String,
    #[command(flatten)]
    pub table: crate::common::TableOut,
}

/// A triangle list as a strip set of one strip per triangle (figures read it in order).
fn list(tris: &[[u32; 3]]) -> StripSet {
    StripSet::from_strips(&tris.iter().map(|t| t.to_vec()).collect::<Vec<_>>())
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let dir = args.models.dir().context("no models folder (../shared/models or --models)")?;
    let kinds: Vec<Weights> =
        args.weights.split(';').map(|w| w.parse::<Weights>()).collect::<Result<_, _>>()?;
    let levels: Vec<u32> = args.levels.split(',').map(|l| l.trim().parse()).collect::<Result<_, _>>()?;
    let mode = match args.matching.as_str() {
        "auto" => MatchingMode::Auto,
        "exact" => MatchingMode::Exact,
        "greedy" => MatchingMode::Greedy,
        other => anyhow::bail!("--matching {other}: expected auto, exact or greedy"),
    };
    let mut out = String::new();
    out.push_str("| model | triangles | weights | strips / components | Steiner (% of vertices) | swaps | max swap deviation (of the diagonal) | indices/tri | acmr16 | acmr32 | total ms | matching ms |\n");
    out.push_str("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    let mut failed = Vec::new();
    for name in args.only.split(',').map(str::trim) {
        let path = dir.join(name);
        if !path.exists() {
            eprintln!("{name}: not in {}, skipped", dir.display());
            continue;
        }
        let base = crate::common::read_surface(&path).with_context(|| format!("reading {}", path.display()))?;
        for &level in &levels {
            let mesh = if level == 0 {
                base.clone()
            } else {
                stripkit::gen::subdivide_loop(&stripkit::Mesh::from_triangles(base.positions.clone(), &base.triangulate().tris), level)?
            };
            let label = if level == 0 { name.to_string() } else { format!("{name} Loop x{level}") };
            let tris = mesh.triangulate().tris;
            let n = mesh.vertex_count();
            let diag = mesh
                .bounds()
                .map(|(lo, hi)| (0..3).map(|d| ((hi[d] - lo[d]) as f64).powi(2)).sum::<f64>().sqrt())
                .unwrap_or(1.0);
            eprintln!("{label}: {} triangles", tris.len());
            for k in &kinds {
                let o = SingleOptions::new(k.clone()).matching(mode);
                let start = Instant::now();
                let r = stripkit::stripify(&mesh, &StripOptions::default().algorithm(Algorithm::Single(o)));
                let ms = start.elapsed().as_secs_f64() * 1e3;
                let s = match r {
                    Ok(s) => s,
                    Err(e) => {
                        failed.push(format!("{label} {k}: {e}"));
                        continue;
                    }
                };
                let r = s.single.as_ref().expect("single reports");
                let f = &s.figures;
                out.push_str(&format!(
                    "| {label} | {} | {k} | {} / {} | {} ({:.2}%) | {} | {:.1e} | {:.3} | {:.3} | {:.3} | {:.0} | {:.0} |\n",
                    tris.len(),
                    f.strips,
                    r.components,
                    r.steiner_vertices,
                    100.0 * r.steiner_vertices as f64 / n as f64,
                    r.swapped_edges,
                    r.max_swap_deviation / diag,
                    f.indices_per_triangle,
                    f.acmr16,
                    f.acmr32,
                    ms,
                    r.matching_ms
                ));
            }
            for (label_peer, strips) in [
                ("meshopt optimize_vertex_cache (list)", list(&crate::strips::reorder_cache(&tris, n))),
                (
                    "meshopt optimize_vertex_cache_strip + stripify",
                    crate::strips::meshopt_stripify(&crate::strips::reorder_strip(&tris, n), n),
                ),
            ] {
                let f = stripkit::figures(&tris, &strips, CacheModel::default());
                out.push_str(&format!(
                    "| {label} | {} | {label_peer} | {} | - | - | - | {:.3} | {:.3} | {:.3} | - | - |\n",
                    tris.len(),
                    f.strips,
                    f.indices_per_triangle,
                    f.acmr16,
                    f.acmr32
                ));
            }
        }
    }
    print!("{out}");
    if let Some(path) = &args.table.out {
        stripkit::io::write_encoded(path, out.as_bytes())?;
    }
    if !failed.is_empty() {
        anyhow::bail!("failed: {}", failed.join("; "));
    }
    Ok(())
}

//! The `lod` comparison: the SETS multiresolution strips ([`stripkit::lod`]) on the
//! research models, with their size, the strips of a level next to greedy strips made
//! from scratch on that level's mesh, and the model next to a discrete LoD chain of
//! meshoptimizer's `simplify` (memory, levels, time to switch, distance to the input
//! at equal triangle counts), in one run; writes markdown tables.

use crate::simplify::{median, meshopt_simplify};
use anyhow::Context;
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;
use stripkit::{lod, Algorithm, Mesh, StripOptions};

/// The discrete chain's ratios of the input triangles (finest first).
const CHAIN_RATIOS: [f64; 8] = [0.5, 0.35, 0.25, 0.15, 0.1, 0.05, 0.02, 0.01];

/// The levels whose strips are compared with greedy strips from scratch.
const QUALITY_RATIOS: [f64; 3] = [0.5, 0.1, 0.01];

/// Arguments of the `lod` comparison.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub models: crate::common::Models,
    /// Models: file names in the folder, or their stems (`bunny`, `horse`, `dragon`,
    /// `cow`). Default: bunny, horse, dragon.
    #[arg(long, value_name = "NAME", num_args = 1.., value_delimiter = ',')]
    pub only: Vec<String>,
    /// Samples per surface for the distances.
    #[arg(long, default_value_t = 200_000)]
    pub samples: usize,
    /// Rounds of the down-and-back switching path (medians over all switches).
    #[arg(long, default_value_t = 200)]
    pub rounds: usize,
    /// Indices-per-triangle thresholds of the re-stripped models
    /// ([`stripkit::lod::BuildOptions::restrip`]).
    #[arg(long, num_args = 1.., value_delimiter = ',', default_values_t = [1.5, 1.6, 1.8])]
    pub thresholds: Vec<f64>,
    #[command(flatten)]
    pub table: crate::common::TableOut,
}

/// `name` in `dir`: the file itself, else the first `.obj`, `.ply` or `.off` file whose
/// stem is `name`.
fn resolve(dir: &Path, name: &str) -> Option<PathBuf> {
    let direct = dir.join(name);
    if direct.is_file() {
        return Some(direct);
    }
    ["obj", "ply", "off"].iter().map(|ext| dir.join(format!("{name}.{ext}"))).find(|p| p.is_file())
}

/// Medians in microseconds of switching along `path` (indices into whatever `switch`
/// moves between), `rounds` times after one warm-up round: of every switch, and of a
/// whole pass.
fn time_switches(path: &[usize], rounds: usize, mut switch: impl FnMut(usize)) -> (f64, f64) {
    for &i in path {
        switch(i);
    }
    let mut each = Vec::with_capacity(path.len() * rounds);
    let mut passes = Vec::with_capacity(rounds);
    for _ in 0..rounds.max(1) {
        let mut pass = 0.0;
        for &i in path {
            let t = Instant::now();
            switch(i);
            let us = t.elapsed().as_secs_f64() * 1e6;
            each.push(us);
            pass += us;
        }
        passes.push(pass);
    }
    (median(each), median(passes))
}

/// Tables, one string each, filled model by model.
#[derive(Default)]
struct Tables {
    size: String,
    quality: String,
    memory: String,
    switch: String,
    distance: String,
    coarse: String,
    steps: String,
}

/// Runs the comparison.
pub fn run(args: Args) -> anyhow::Result<()> {
    let dir =
        args.models.dir().context("no models folder (../shared/models or --models)")?;
    let names: Vec<String> = if args.only.is_empty() {
        ["bunny", "horse", "dragon"].iter().map(|s| s.to_string()).collect()
    } else {
        args.only.clone()
    };
    let mut t = Tables::default();
    t.size.push_str("| model | vertices | triangles | strips | .sets bytes | in-memory bytes | raw mesh bytes | collapse sequence bytes | levels | build ms (strips + simplify + model) |\n");
    t.size.push_str("|---|---:|---:|---|---:|---:|---:|---:|---:|---:|\n");
    t.quality.push_str("| model | ratio | level | triangles | SETS indices/tri | greedy from scratch indices/tri | SETS / scratch | SETS strips | SETS degenerate windows | scratch strips |\n");
    t.quality.push_str("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    t.memory.push_str("| model | chain index buffers (9 lists, u32) | SETS in-memory minus positions | SETS / chain | SETS strips as 9 restart buffers (u32) | strip buffers / chain | positions (shared, not counted) | distinct levels: chain | distinct levels: SETS |\n");
    t.memory.push_str("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    t.switch.push_str("| model | chain memcpy, median switch us | chain, median pass us | SETS set_level, median switch us | SETS, median pass us | SETS set_level + compact, median switch us | SETS + compact, median pass us | switches per pass | chain bytes uploaded per pass | SETS changed-range bytes per pass |\n");
    t.switch.push_str("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    t.coarse.push_str("| model | strips | re-strip threshold | .sets bytes | in-memory bytes | build ms | 100% | 50% | 25% | 10% | 5% | 2% | 1% | worst level down to 1% |\n");
    t.coarse.push_str("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    t.steps.push_str("| model | strips | path | switches per pass | median switch us | p99 switch us | changed strips' range bytes per switch (mean) | changed-range bytes per switch (mean) |\n");
    t.steps.push_str("|---|---|---|---:|---:|---:|---:|---:|\n");
    t.distance.push_str("| model | ratio | meshopt triangles | SETS level | SETS triangles | Hausdorff meshopt | Hausdorff SETS | lower Hausdorff | RMS meshopt | RMS SETS | lower RMS |\n");
    t.distance.push_str("|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---|\n");
    for name in &names {
        let Some(path) = resolve(&dir, name) else {
            eprintln!("{name}: not in {}, skipped", dir.display());
            continue;
        };
        let label = path.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_else(|| name.clone());
        let mesh = crate::common::read_surface(&path).with_context(|| format!("reading {}", path.display()))?;
        model(&mesh, &label, &args, &mut t)?;
        eprintln!("done: {label}");
    }
    let mut out = String::new();
    for (title, table) in [
        ("Size", &t.size),
        ("Strip quality at a level", &t.quality),
        ("Memory next to a discrete LoD chain (meshoptimizer simplify at 8 ratios + the full mesh)", &t.memory),
        ("Time to switch levels (full -> 8 chain levels -> full)", &t.switch),
        ("Indices per triangle (restart buffer) at every level: kept strips, restart labels (bound), greedy from scratch, re-stripped models", &t.coarse),
        ("Switch times and re-uploads, kept and re-stripped strips (median and 99th percentile of every timed switch)", &t.steps),
        ("Distance to the input at equal triangle counts (relative to the bounding-box diagonal)", &t.distance),
    ] {
        writeln!(out, "### {title}\n\n{table}")?;
    }
    print!("{out}");
    if let Some(file) = &args.table.out {
        stripkit::io::write_encoded(file, out.as_bytes())?;
    }
    Ok(())
}

/// Every table's rows for one model.
fn model(mesh: &Mesh, label: &str, args: &Args, t: &mut Tables) -> anyhow::Result<()> {
    let tris = mesh.triangulate().tris;
    let start = Instant::now();
    let built = lod::build(mesh, &lod::BuildOptions::default().restrip(None), &mut |_| {})?;
    let build_ms = start.elapsed().as_secs_f64() * 1e3;
    let sets = &built.sets;
    let r = &built.report;
    let positions_bytes = 12 * sets.positions().len();
    writeln!(
        t.size,
        "| {label} | {} | {} | {} | {} | {} | {} | {} | {} | {build_ms:.0} ({:.0} + {:.0} + {:.0}) |",
        mesh.vertex_count(),
        tris.len(),
        r.algorithm,
        sets.to_bytes().len(),
        sets.memory_bytes(),
        12 * mesh.vertex_count() + 12 * tris.len(),
        built.sequence.to_bytes().len(),
        sets.levels(),
        r.strip_ms,
        r.simplify_ms,
        r.build_ms
    )?;

    let restripped = coarse(&built, label, args, t)?;

    let greedy = StripOptions::default().algorithm(Algorithm::greedy());
    for ratio in QUALITY_RATIOS {
        let level = sets.level_for_ratio(ratio);
        let n = sets.triangles_at(level);
        let strips = sets.strips_at(level);
        let ours = strips.restart_len() as f64 / n as f64;
        let degenerate = strips.window_count() - n as usize;
        let replay = built.sequence.replay(&built.mesh, level as usize)?;
        let level_mesh = Mesh::from_triangles(replay.positions, &replay.triangles);
        let f = stripkit::stripify(&level_mesh, &greedy)?.figures;
        let scratch = f.indices_restart as f64 / f.triangles as f64;
        if f.triangles != n as usize {
            eprintln!("{label}: level {level} has {n} triangles, its replay {}", f.triangles);
        }
        writeln!(
            t.quality,
            "| {label} | {:.0}% | {level} | {n} | {ours:.3} | {scratch:.3} | {:.3} | {} | {degenerate} | {} |",
            ratio * 100.0,
            ours / scratch,
            strips.len(),
            f.strips
        )?;
    }

    // The discrete chain: the full mesh, then meshoptimizer at every ratio; our
    // matching levels: the first with at most as many triangles.
    let mut chain: Vec<Vec<u32>> = vec![tris.iter().flatten().copied().collect()];
    let mut levels = vec![0u32];
    for ratio in CHAIN_RATIOS {
        let target = ((tris.len() as f64) * ratio).round() as usize;
        let (indices, _) = meshopt_simplify(mesh, &tris, target);
        levels.push(sets.level_for_triangles((indices.len() / 3) as u64));
        chain.push(indices);
    }

    let chain_bytes: usize = chain.iter().map(|c| 4 * c.len()).sum();
    let sets_bytes = sets.memory_bytes() - positions_bytes;
    let strip_bytes: usize = levels.iter().map(|&l| 4 * sets.strips_at(l).restart_len()).sum();
    writeln!(
        t.memory,
        "| {label} | {chain_bytes} | {sets_bytes} | {:.2} | {strip_bytes} | {:.2} | {positions_bytes} | {} | {} |",
        sets_bytes as f64 / chain_bytes as f64,
        strip_bytes as f64 / chain_bytes as f64,
        chain.len(),
        sets.levels() as u64 + 1
    )?;

    // Down and back: 0 -> 1 -> .. -> 8 -> 7 -> .. -> 0, starting at 0.
    let path: Vec<usize> = (1..chain.len()).chain((0..chain.len() - 1).rev()).collect();
    let mut dst = vec![0u32; chain[0].len()];
    let (chain_each, chain_pass) = time_switches(&path, args.rounds, |i| {
        let src = &chain[i];
        dst[..src.len()].copy_from_slice(src);
        black_box(&dst);
    });
    let mut cursor = sets.cursor(0);
    let (set_each, set_pass) = time_switches(&path, args.rounds, |i| {
        black_box(cursor.set_level(levels[i]).len());
    });
    let mut cursor = sets.cursor(0);
    let mut compact = Vec::new();
    let (compact_each, compact_pass) = time_switches(&path, args.rounds, |i| {
        cursor.set_level(levels[i]);
        cursor.compact(u32::MAX, &mut compact);
        black_box(&compact);
    });
    steps(label, sets, restripped.as_ref(), &levels, args.rounds, t)?;
    // What one pass uploads: the chain, every new level's list; SETS, the ranges of
    // the strips that changed (of the padded buffer).
    let chain_upload: usize = path.iter().map(|&i| 4 * chain[i].len()).sum();
    let mut cursor = sets.cursor(0);
    let mut sets_upload = 0;
    for &i in &path {
        let changed = cursor.set_level(levels[i]).to_vec();
        sets_upload += changed.iter().map(|&s| 4 * cursor.strip_range(s as usize).len()).sum::<usize>();
    }
    writeln!(
        t.switch,
        "| {label} | {chain_each:.2} | {chain_pass:.1} | {set_each:.2} | {set_pass:.1} | {compact_each:.2} | {compact_pass:.1} | {} | {chain_upload} | {sets_upload} |",
        path.len()
    )?;

    for (k, ratio) in CHAIN_RATIOS.iter().enumerate() {
        let mo_tris: Vec<[u32; 3]> = chain[k + 1].chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        let mo_mesh = Mesh::from_triangles(mesh.positions.clone(), &mo_tris);
        let d_mo = stripkit::distance::distance(mesh, &mo_mesh, args.samples)?;
        let level = levels[k + 1];
        let replay = built.sequence.replay(&built.mesh, level as usize)?;
        let ours = Mesh::from_triangles(replay.positions, &replay.triangles);
        let d = stripkit::distance::distance(mesh, &ours, args.samples)?;
        let lower = |a: f64, b: f64| {
            if b < a {
                "SETS"
            } else if a < b {
                "meshopt"
            } else {
                "equal"
            }
        };
        writeln!(
            t.distance,
            "| {label} | {:.0}% | {} | {level} | {} | {:.3e} | {:.3e} | {} | {:.3e} | {:.3e} | {} |",
            ratio * 100.0,
            mo_tris.len(),
            sets.triangles_at(level),
            d_mo.hausdorff,
            d.hausdorff,
            lower(d_mo.hausdorff, d.hausdorff),
            d_mo.rms,
            d.rms,
            lower(d_mo.rms, d.rms)
        )?;
    }
    Ok(())
}

/// The ratios of the coarse-strips table.
const COARSE_RATIOS: [f64; 7] = [1.0, 0.5, 0.25, 0.1, 0.05, 0.02, 0.01];

/// The coarse-strips rows of one model: the kept strips, the restart-label bound, the
/// models re-stripped at each threshold ([`lod::BuildOptions::restrip`]), and greedy
/// from scratch, at the 7 ratios
/// and at the worst level from 100% down to 1%.
fn coarse(built: &lod::Built, label: &str, args: &Args, t: &mut Tables) -> anyhow::Result<Option<lod::Sets>> {
    use crate::lod_coarse::{per_level, restart_ratio};
    let sets = &built.sets;
    let floor = sets.level_for_ratio(0.01);
    let row = |t: &mut Tables, what: &str, thr: &str, bytes: usize, mem: usize, ms: f64, at: &dyn Fn(u32) -> f64, worst: f64| -> anyhow::Result<()> {
        let cells: Vec<String> = COARSE_RATIOS.iter().map(|&r| format!("{:.3}", at(sets.level_for_ratio(r)))).collect();
        writeln!(t.coarse, "| {label} | {what} | {thr} | {bytes} | {mem} | {ms:.0} | {} | {worst:.3} |", cells.join(" | "))?;
        Ok(())
    };
    let mut first = None;
    let kept = per_level(sets);
    let worst = kept[..=floor as usize].iter().copied().fold(0.0, f64::max);
    row(t, "SETS (kept)", "-", sets.to_bytes().len(), sets.memory_bytes(), 0.0, &|l: u32| kept[l as usize], worst)?;
    let mut cursor = sets.cursor(0);
    let bound: Vec<(u32, f64)> = COARSE_RATIOS.iter().map(|&r| {
        let l = sets.level_for_ratio(r);
        (l, restart_ratio(sets, &mut cursor, l))
    }).collect();
    let at_bound = |l: u32| bound.iter().find(|b| b.0 == l).map_or(f64::NAN, |b| b.1);
    row(t, "restart labels (bound)", "-", 0, 0, 0.0, &at_bound, f64::NAN)?;
    let greedy = StripOptions::default().algorithm(Algorithm::greedy()).weld(false);
    let mut scratch = Vec::new();
    for &r in &COARSE_RATIOS {
        let l = sets.level_for_ratio(r);
        let replay = built.sequence.replay(&built.mesh, l as usize)?;
        let f = stripkit::stripify(&Mesh::from_triangles(replay.positions, &replay.triangles), &greedy)?.figures;
        scratch.push((l, f.indices_restart as f64 / f.triangles.max(1) as f64));
    }
    let at_scratch = |l: u32| scratch.iter().find(|b| b.0 == l).map_or(f64::NAN, |b| b.1);
    row(t, "greedy from scratch", "-", 0, 0, 0.0, &at_scratch, f64::NAN)?;
    for &threshold in &args.thresholds {
        let start = Instant::now();
        let options = lod::BuildOptions::default().restrip(Some(threshold));
        let re = lod::build(&built.mesh, &options, &mut |_| {})?;
        let ms = start.elapsed().as_secs_f64() * 1e3;
        anyhow::ensure!(re.sets.levels() == sets.levels(), "{label}: the re-stripped model has other levels");
        let all = per_level(&re.sets);
        let worst = all[..=floor as usize].iter().copied().fold(0.0, f64::max);
        let what = format!("re-stripped ({} new strips)", re.sets.restripped_strips());
        let (bytes, mem) = (re.sets.to_bytes().len(), re.sets.memory_bytes());
        row(t, &what, &format!("{threshold}"), bytes, mem, ms, &|l: u32| all[l as usize], worst)?;
        if first.is_none() {
            first = Some(re.sets);
        }
    }
    Ok(first)
}

/// Every switch along `path` (levels), `rounds` times after a warm-up pass: the
/// median and 99th percentile microseconds of one `set_level`, and the mean bytes of
/// the changed strips' ranges.
fn switch_figures(sets: &lod::Sets, path: &[u32], rounds: usize) -> (f64, f64, f64, f64) {
    let mut cursor = sets.cursor(0);
    let (mut whole, mut bytes) = (0usize, 0usize);
    for &l in path {
        let changed = cursor.set_level(l).to_vec();
        whole += changed.iter().map(|&s| 4 * cursor.strip_range(s as usize).len()).sum::<usize>();
        bytes += changed.iter().map(|&s| 4 * cursor.changed_range(s as usize).len()).sum::<usize>();
    }
    let mut each = Vec::with_capacity(path.len() * rounds);
    for _ in 0..rounds.max(1) {
        for &l in path {
            let t = Instant::now();
            black_box(cursor.set_level(l).len());
            each.push(t.elapsed().as_secs_f64() * 1e6);
        }
    }
    each.sort_by(f64::total_cmp);
    let p99 = each[((each.len() as f64 * 0.99) as usize).min(each.len() - 1)];
    let per = |b: usize| b as f64 / path.len().max(1) as f64;
    (median(each), p99, per(whole), per(bytes))
}

/// `down` (starting at level 0) walked down and back, level 0 left out.
fn down_and_back(down: &[u32]) -> Vec<u32> {
    down.iter().copied().skip(1).chain(down.iter().rev().skip(1).copied()).collect()
}

/// The switch rows of one model, down and back, for the kept and the re-stripped
/// strips: the chain's levels; 1% of the levels (the paper's linear test); 1% of
/// the triangles (100%, 99%, ... 1%); and one level at a time over the 200 levels
/// around the one of 1% of the triangles.
fn steps(label: &str, kept: &lod::Sets, restripped: Option<&lod::Sets>, chain_levels: &[u32], rounds: usize, t: &mut Tables) -> anyhow::Result<()> {
    let max = kept.levels();
    let one_percent = down_and_back(&(0..=100).map(|j| (j as f64 / 100.0 * max as f64).round() as u32).collect::<Vec<_>>());
    let triangles = down_and_back(&(0..=99).map(|j| kept.level_for_ratio(1.0 - j as f64 / 100.0)).collect::<Vec<_>>());
    let at = kept.level_for_ratio(0.01);
    let (lo, hi) = (at.saturating_sub(100), (at + 100).min(max));
    let one_level: Vec<u32> = (lo + 1..=hi).chain((lo..hi).rev()).collect();
    let chain = down_and_back(chain_levels);
    for (what, sets) in [("kept", Some(kept)), ("re-stripped", restripped)] {
        let Some(sets) = sets else { continue };
        let paths = [
            ("chain levels", &chain),
            ("1% of the levels", &one_percent),
            ("1% of the triangles", &triangles),
            ("one level, around 1% of the triangles", &one_level),
        ];
        for (name, path) in paths {
            let (med, p99, whole, bytes) = switch_figures(sets, path, rounds);
            writeln!(t.steps, "| {label} | {what} | {name} | {} | {med:.2} | {p99:.2} | {whole:.0} | {bytes:.0} |", path.len())?;
        }
    }
    Ok(())
}

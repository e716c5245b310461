//! The `cull` comparison (issue #18): back-face culling along the 591-view helix of
//! `stripkit cull`, in one run and on the same eyes:
//!
//! * the cull-weight single strip and the uniform-weight single strip, each with its
//!   segment tree (from the roots and from the render front);
//! * greedy strips culled per strip, one cone and sphere per strip (and, for
//!   reference, the same strips with their segment trees);
//! * meshoptimizer's meshlets (`build_meshlets`, 64 vertices, 124 triangles, cone
//!   weight 0.25), `compute_meshlet_bounds`, and its apex-free cone test
//!   `dot(center - eye, axis) >= cutoff * |center - eye| + radius`.
//!
//! Figures per view, averaged: draws (ranges, strips or meshlets), triangles drawn,
//! back-facing triangles culled and drawn, front-facing triangles missed (must be 0),
//! microseconds per view of the culling itself.

use anyhow::Context;
use std::ops::Range;
use std::path::PathBuf;
use std::time::Instant;
use stripkit::cull::{helix_eyes, survey, Bounds, CullOptions, Facing, FacingCounter, SegmentTree, HELIX_VIEWS};
use stripkit::{Algorithm, SingleOptions, StripOptions, StripSet, Weights};

/// Arguments of the `cull` comparison.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub models: crate::common::Models,
    /// Models, comma-separated file names in the folder, or paths.
    #[arg(long, default_value = "fandisk.obj,cow.obj,horse.ply,bunny_small.off,dragon.obj,spot_triangulated.obj")]
    pub only: String,
    /// Runs of the path for the times (each view's best is kept).
    #[arg(long, default_value_t = 3)]
    pub repeat: usize,
    /// Extra rows for the single strips with this `max_gap` (ranges separated by at
    /// most N culled triangles drawn as one); 0: none.
    #[arg(long, default_value_t = 16)]
    pub gap: u32,
    #[command(flatten)]
    pub table: crate::common::TableOut,
}

#[derive(Default)]
struct Row {
    method: String,
    units: usize,
    draws: f64,
    drawn: f64,
    back: f64,
    back_culled: f64,
    back_drawn: f64,
    front_missed: f64,
    us: String,
}

/// A segment tree's row: ranges per view from the roots (checked against the front).
fn tree_row(
    method: &str,
    tree: &SegmentTree,
    counter: &FacingCounter,
    o: CullOptions,
    eyes: &[[f32; 3]],
    repeat: usize,
) -> anyhow::Result<Row> {
    let views = survey::survey(tree, counter, eyes, |_| o, repeat).with_context(|| method.to_string())?;
    let m = survey::mean(&views);
    Ok(Row {
        method: method.into(),
        units: tree.len(),
        draws: m.segments,
        drawn: m.drawn,
        back: m.back,
        back_culled: m.back_culled,
        back_drawn: m.back_drawn,
        front_missed: m.front_missed,
        us: format!("{:.1} / {:.1}", m.us_root, m.us_front),
    })
}

fn add(row: &mut Row, c: &stripkit::cull::FacingCounts, draws: usize, drawn: usize) {
    row.draws += draws as f64;
    row.drawn += drawn as f64;
    row.back += c.back as f64;
    row.back_culled += c.back_culled() as f64;
    row.back_drawn += c.back_drawn as f64;
    row.front_missed += (c.front - c.front_drawn) as f64;
}

fn finish(row: &mut Row, views: usize) {
    let n = views as f64;
    for x in [&mut row.draws, &mut row.drawn, &mut row.back, &mut row.back_culled, &mut row.back_drawn, &mut row.front_missed] {
        *x /= n;
    }
}

/// Greedy strips, one cone and sphere per strip (the strip is drawn unless it faces away).
fn per_strip_row(strips: &StripSet, positions: &[[f32; 3]], eyes: &[[f32; 3]], repeat: usize) -> Row {
    let slack = SegmentTree::slack(strips, positions);
    let bounds: Vec<Bounds> = strips
        .iter()
        .map(|s| {
            let mut tris = Vec::new();
            stripkit::for_each_triangle(s, |t| tris.push(t));
            Bounds::of_triangles(&tris, positions, slack)
        })
        .collect();
    let counter = FacingCounter::new(strips, positions);
    let mut row = Row { method: "greedy strips, one cone per strip".into(), units: strips.len(), ..Row::default() };
    let mut best = vec![f64::MAX; eyes.len()];
    let mut ranges: Vec<Range<u32>> = Vec::new();
    for r in 0..repeat.max(1) {
        for (v, &eye) in eyes.iter().enumerate() {
            let t = Instant::now();
            ranges.clear();
            for (s, b) in bounds.iter().enumerate() {
                if b.classify(eye) != Facing::Back {
                    ranges.push(strips.offsets[s]..strips.offsets[s + 1]);
                }
            }
            best[v] = best[v].min(t.elapsed().as_secs_f64() * 1e6);
            if r == 0 {
                let c = counter.count(eye, &ranges);
                let drawn = c.front_drawn + c.back_drawn; // edge-on triangles aside
                add(&mut row, &c, ranges.len(), drawn);
            }
        }
    }
    finish(&mut row, eyes.len());
    row.us = format!("{:.1}", best.iter().sum::<f64>() / best.len() as f64);
    row
}

/// meshoptimizer's meshlets and its cone test.
fn meshlet_row(tris: &[[u32; 3]], positions: &[[f32; 3]], eyes: &[[f32; 3]], repeat: usize) -> anyhow::Result<Row> {
    let bytes: Vec<u8> = positions.iter().flat_map(|p| p.iter().flat_map(|x| x.to_le_bytes())).collect();
    let adapter = meshopt::VertexDataAdapter::new(&bytes, 12, 0).map_err(|e| anyhow::anyhow!("{e:?}"))?;
    let meshlets = meshopt::build_meshlets(tris.as_flattened(), &adapter, 64, 124, 0.25);
    let mut bounds = Vec::with_capacity(meshlets.len());
    // Per meshlet, its triangles' planes (unnormalized normal, offset) in f64.
    let mut planes: Vec<Vec<([f64; 3], f64)>> = Vec::with_capacity(meshlets.len());
    for m in meshlets.iter() {
        bounds.push(meshopt::compute_meshlet_bounds(m, &adapter));
        let mut p = Vec::new();
        for t in m.triangles.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| positions[m.vertices[t[k] as usize] as usize].map(|x| x as f64));
            let (u, w) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
            let n = glam::DVec3::from(u).cross(glam::DVec3::from(w)).to_array();
            p.push((n, n[0] * a[0] + n[1] * a[1] + n[2] * a[2]));
        }
        planes.push(p);
    }
    let culled = |b: &meshopt::ffi::meshopt_Bounds, eye: [f32; 3]| {
        let d = [b.center[0] - eye[0], b.center[1] - eye[1], b.center[2] - eye[2]];
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        d[0] * b.cone_axis[0] + d[1] * b.cone_axis[1] + d[2] * b.cone_axis[2] >= b.cone_cutoff * len + b.radius
    };
    let mut row = Row { method: "meshoptimizer meshlets 64/124, cone test".into(), units: meshlets.len(), ..Row::default() };
    let mut best = vec![f64::MAX; eyes.len()];
    let mut keep = vec![false; meshlets.len()];
    for r in 0..repeat.max(1) {
        for (v, &eye) in eyes.iter().enumerate() {
            let t = Instant::now();
            for (k, b) in bounds.iter().enumerate() {
                keep[k] = !culled(b, eye);
            }
            best[v] = best[v].min(t.elapsed().as_secs_f64() * 1e6);
            if r == 0 {
                let e = eye.map(|x| x as f64);
                let mut c = stripkit::cull::FacingCounts::default();
                let mut drawn = 0;
                for (k, p) in planes.iter().enumerate() {
                    for (n, d) in p {
                        let f = n[0] * e[0] + n[1] * e[1] + n[2] * e[2] - d;
                        c.front += (f > 0.0) as usize;
                        c.back += (f < 0.0) as usize;
                        if keep[k] {
                            c.front_drawn += (f > 0.0) as usize;
                            c.back_drawn += (f < 0.0) as usize;
                        }
                    }
                    drawn += keep[k] as usize * p.len();
                }
                let draws = keep.iter().filter(|&&k| k).count();
                add(&mut row, &c, draws, drawn);
            }
        }
    }
    finish(&mut row, eyes.len());
    row.us = format!("{:.1}", best.iter().sum::<f64>() / best.len() as f64);
    Ok(row)
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let dir = args.models.dir();
    let mut out = String::new();
    out.push_str("| model | triangles | method | nodes / strips / meshlets | draws per view | triangles drawn | back-facing | back culled | back drawn (leak) | front missed | us per view (roots / front) |\n");
    out.push_str("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for name in args.only.split(',').map(str::trim) {
        let path = match &dir {
            Some(d) if d.join(name).exists() => d.join(name),
            _ => PathBuf::from(name),
        };
        if !path.exists() {
            eprintln!("{name}: not found, skipped");
            continue;
        }
        let mesh = crate::common::read_surface(&path).with_context(|| format!("reading {}", path.display()))?;
        let tris = mesh.triangulate().tris;
        eprintln!("{name}: {} triangles", tris.len());
        let (center, radius) = stripkit::cull::bounding_sphere(&mesh.positions);
        let eyes = helix_eyes(center, radius, HELIX_VIEWS);
        let mut rows = Vec::new();
        let mut cull_tree = None;
        for w in [Weights::Cull, Weights::Uniform] {
            let s = stripkit::stripify(&mesh, &StripOptions::default().algorithm(Algorithm::Single(SingleOptions::new(w.clone()))))?;
            let pos = s.with_added_vertices(&mesh.positions);
            let t0 = Instant::now();
            let tree = SegmentTree::build(&s.strips, &pos);
            eprintln!("  {w}: {} triangles, tree of {} nodes, depth {}, built in {:.1} ms", s.triangles.len(), tree.len(), tree.depth(), t0.elapsed().as_secs_f64() * 1e3);
            let counter = FacingCounter::new(&s.strips, &pos);
            let o = CullOptions::default();
            rows.push(tree_row(&format!("single strip, {w} weights, segment tree"), &tree, &counter, o, &eyes, args.repeat)?);
            if args.gap > 0 {
                let o = o.max_gap(args.gap);
                let m = format!("single strip, {w} weights, segment tree, gaps <= {} joined", args.gap);
                rows.push(tree_row(&m, &tree, &counter, o, &eyes, args.repeat)?);
            }
            if w == Weights::Cull {
                cull_tree = Some((tree, counter));
            }
        }
        let g = stripkit::stripify(&mesh, &StripOptions::default().algorithm(Algorithm::greedy()))?;
        rows.push(per_strip_row(&g.strips, &mesh.positions, &eyes, args.repeat));
        let tree = SegmentTree::build(&g.strips, &mesh.positions);
        let counter = FacingCounter::new(&g.strips, &mesh.positions);
        rows.push(tree_row("greedy strips, segment trees", &tree, &counter, CullOptions::default(), &eyes, args.repeat)?);
        let meshlets = meshlet_row(&tris, &mesh.positions, &eyes, args.repeat)?;
        // The smallest gap at which the cull-weight strip draws at most a tenth of the
        // meshlets' draws (gaps 0, 4, 16, ... 4^8).
        if let Some((tree, counter)) = &cull_tree {
            for k in 0..=8 {
                let gap = if k == 0 { 0 } else { 1u32 << (2 * k) };
                let o = CullOptions::default().max_gap(gap);
                let m = format!("single strip, cull weights, gaps <= {gap} joined (first gap of 4^k with <= 1/10 of the meshlet draws)");
                let row = tree_row(&m, tree, counter, o, &eyes, 1)?;
                if row.draws <= meshlets.draws / 10.0 || k == 8 {
                    rows.push(row);
                    break;
                }
            }
        }
        rows.push(meshlets);
        for r in rows {
            let pct = if r.back > 0.0 { 100.0 * r.back_culled / r.back } else { 0.0 };
            out.push_str(&format!(
                "| {name} | {} | {} | {} | {:.1} | {:.0} | {:.0} | {:.0} ({pct:.1}%) | {:.1} | {:.1} | {} |\n",
                tris.len(),
                r.method,
                r.units,
                r.draws,
                r.drawn,
                r.back,
                r.back_culled,
                r.back_drawn,
                r.front_missed,
                r.us
            ));
        }
    }
    print!("{out}");
    if let Some(f) = &args.table.out {
        std::fs::write(f, &out)?;
    }
    Ok(())
}

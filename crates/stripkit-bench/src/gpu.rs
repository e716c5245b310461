//! The `gpu` comparison: draw time of every index buffer a user could ship, on the GPU
//! (or llvmpipe) this machine has, with the renderer's name on every table.
//!
//! Rows, for every mesh: the input triangle list, meshoptimizer's vertex-cache list, its
//! two strip pipelines, and every stripkit mode (through the door, verified). Each row is
//! drawn with vertices in the input order and reordered for fetch locality (first use
//! by the row's own indices, as meshoptimizer's `optimizeVertexFetch` does), so that
//! fetch order does not decide the result.
//!
//! Each figure is ms per draw: the best of `--repeats` runs of `--draws` draws, each draw
//! from the next view of the helix camera path, the queue drained before and after a
//! run. Configurations: framebuffer 64x64 (vertex-bound) and 1920x1080, a light and a
//! heavy (skinning-like) vertex shader, u32 and u16 indices.
//!
//! Where the context can count vertex-shader invocations, each row also gets the count:
//! how many vertices the GPU shaded for one draw, which tells its reuse model apart from
//! a FIFO cache. `probes` draws synthetic buffers whose counts reveal the batch sizes.

use anyhow::Context;
use std::path::PathBuf;
use std::time::Instant;
use crate::buffers::{buffers, invocations};
use stripkit::CacheKind;
use stripkit::cull::{helix_eyes, HELIX_VIEWS};
use stripkit_render::{
    Camera, DrawParams, Geometry, IndexBuffer, IndexWidth, Renderer, Shading, Topology, Vertices,
    HEAVY_VERTEX_SHADER,
};

/// Arguments of the `gpu` comparison.
#[derive(clap::Args)]
pub struct Args {
    /// Folder of meshes; its `quads/` subfolder is read too.
    #[arg(long, default_value = "../shared/models")]
    pub models: PathBuf,
    /// Only meshes whose file name contains this text.
    #[arg(long)]
    pub only: Option<String>,
    /// Also draw Loop-subdivided copies: `FILE:LEVELS`, e.g. `bunny.obj:2` (1.1M triangles).
    #[arg(long = "subdivided", value_name = "FILE:LEVELS")]
    pub subdivided: Vec<String>,
    /// Draws per timed run (a tenth of it on meshes over 500k triangles).
    #[arg(long, default_value_t = 300)]
    pub draws: u32,
    /// Timed runs per figure; the table shows the best.
    #[arg(long, default_value_t = 5)]
    pub repeats: u32,
    /// Only the main configuration (64x64, light shader, u32, both vertex orders).
    #[arg(long)]
    pub quick: bool,
    #[command(flatten)]
    pub table: crate::common::TableOut,
    /// Write every figure as JSON here.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Also draw the rows that explore settings: batch strips planned for other reuse
    /// windows, cache sizes 32 and 64.
    #[arg(long)]
    pub variants: bool,
    /// Skip the synthetic batch probes.
    #[arg(long)]
    pub no_probes: bool,
}


/// A drawing configuration.
#[derive(Clone, Copy)]
struct Config {
    name: &'static str,
    size: (u32, u32),
    heavy: bool,
    width: IndexWidth,
    fetch: bool,
}

fn configs(quick: bool) -> Vec<Config> {
    let c = |name, size, heavy, width, fetch| Config { name, size, heavy, width, fetch };
    let mut v = vec![
        c("64x64 light u32, input vertex order", (64, 64), false, IndexWidth::U32, false),
        c("64x64 light u32, vertices in first-use order", (64, 64), false, IndexWidth::U32, true),
    ];
    if !quick {
        v.push(c("64x64 heavy u32, vertices in first-use order", (64, 64), true, IndexWidth::U32, true));
        v.push(c("64x64 light u16, vertices in first-use order", (64, 64), false, IndexWidth::U16, true));
        v.push(c("1920x1080 light u32, vertices in first-use order", (1920, 1080), false, IndexWidth::U32, true));
    }
    v
}


/// Vertex order by first use in `indices` (restart skipped): `remap[old] = new`;
/// unreferenced vertices go last.
pub fn first_use_remap(indices: &[u32], n: usize) -> Vec<u32> {
    let mut remap = vec![u32::MAX; n];
    let mut next = 0u32;
    for &i in indices {
        if i != u32::MAX && remap[i as usize] == u32::MAX {
            remap[i as usize] = next;
            next += 1;
        }
    }
    for r in remap.iter_mut() {
        if *r == u32::MAX {
            *r = next;
            next += 1;
        }
    }
    remap
}

/// Uploaded vertices in one order, and the index remap that goes with them.
struct Upload {
    geometry: Geometry,
    remap: Option<Vec<u32>>,
}

fn upload(r: &mut Renderer, positions: &[[f32; 3]], nrm: &[[f32; 3]], remap: Option<Vec<u32>>) -> anyhow::Result<Upload> {
    let geometry = match &remap {
        None => r.upload(&Vertices { positions, morph_target: None, normals: Some(nrm), colors: None })?,
        Some(m) => {
            let mut p = vec![[0f32; 3]; positions.len()];
            let mut q = vec![[0f32; 3]; positions.len()];
            for (old, &new) in m.iter().enumerate() {
                p[new as usize] = positions[old];
                q[new as usize] = nrm[old];
            }
            r.upload(&Vertices { positions: &p, morph_target: None, normals: Some(&q), colors: None })?
        }
    };
    Ok(Upload { geometry, remap })
}

fn remapped(indices: &[u32], remap: Option<&[u32]>) -> Vec<u32> {
    match remap {
        None => indices.to_vec(),
        Some(m) => indices.iter().map(|&i| if i == u32::MAX { i } else { m[i as usize] }).collect(),
    }
}

/// Best mean ms per draw over `repeats` runs of `draws` draws along the camera path.
fn time(r: &mut Renderer, g: &Geometry, ib: &IndexBuffer, views: &[[f32; 16]], heavy: bool, draws: u32, repeats: u32) -> f64 {
    let mut params = DrawParams::new(views[0]);
    params.shading = Shading::Smooth;
    params.heavy = if heavy { HEAVY_VERTEX_SHADER } else { 0 };
    (0..repeats.max(1))
        .map(|k| {
            // Each run goes on along the path where the last one stopped.
            let first = k as usize * draws.max(1) as usize;
            r.time_draws(g, ib, &params, views, first, draws).as_secs_f64() * 1e3
        })
        .fold(f64::INFINITY, f64::min)
}

/// Per-mesh results.
#[derive(serde::Serialize)]
struct MeshResult {
    name: String,
    triangles: usize,
    vertices: usize,
    rows: Vec<RowResult>,
}

#[derive(serde::Serialize)]
struct RowResult {
    label: String,
    strips: bool,
    indices: usize,
    /// Vertex-shader invocations for one draw (None where the context cannot count).
    invocations: Option<u64>,
    /// Invocations predicted by the batch model fitted to the H100 ([`stripkit::BatchModel::NVIDIA_H100`]).
    h100_model: u64,
    fifo16_misses: usize,
    fifo32_misses: usize,
    /// ms per draw for each configuration, by configuration name.
    ms: Vec<(String, f64)>,
}

/// Runs the comparison.
pub fn run(args: Args) -> anyhow::Result<()> {
    let mut r = Renderer::new(64, 64)?;
    let info = r.info().clone();
    let gpu = format!("{} ({}, {})", info.renderer, info.vendor, info.version);
    eprintln!("renderer: {gpu}");
    let mut meshes: Vec<(String, stripkit::Mesh)> = Vec::new();
    if !args.models.is_dir() {
        anyhow::bail!("{}: no such folder of meshes (give one with --models)", args.models.display());
    }
    for p in crate::strips::mesh_files(&args.models)? {
        let name = p.strip_prefix(&args.models).unwrap_or(&p).display().to_string();
        if args.only.as_ref().is_some_and(|o| !name.contains(o.as_str())) {
            continue;
        }
        let m = crate::common::read_surface(&p).with_context(|| format!("reading {}", p.display()))?;
        meshes.push((name, m));
    }
    for s in &args.subdivided {
        let (file, levels) = s.rsplit_once(':').context("--subdivided takes FILE:LEVELS")?;
        let levels: u32 = levels.parse().context("--subdivided levels")?;
        let p = args.models.join(file);
        let m = crate::common::read_surface(&p).with_context(|| format!("reading {}", p.display()))?;
        let m = stripkit::gen::subdivide_loop(&stripkit::Mesh::from_triangles(m.positions.clone(), &m.triangulate().tris), levels)?;
        meshes.push((format!("{file} Loop x{levels}"), m));
    }
    let configs = configs(args.quick);
    let probes = if args.no_probes { Vec::new() } else { probes(&mut r)? };
    let mut results = Vec::new();
    for (name, mesh) in &meshes {
        let t0 = Instant::now();
        let tris = mesh.triangulate().tris;
        let n = mesh.vertex_count();
        let bufs = buffers(mesh, args.variants)?;
        let nrm = stripkit_render::vertex_normals(&mesh.positions, tris.as_flattened());
        let (lo, hi) = mesh.bounds().context("empty mesh")?;
        let center = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0, (lo[2] + hi[2]) / 2.0];
        let radius = glam::Vec3::from(hi).distance(glam::Vec3::from(lo)) / 2.0;
        let path: Vec<Camera> = helix_eyes(center, radius, HELIX_VIEWS).into_iter().map(|e| Camera::around(e, center, radius)).collect();
        let big = tris.len() > 500_000;
        let draws = if big { (args.draws / 10).max(1) } else { args.draws };
        eprintln!("{name}: {} triangles, {} vertices, {} rows", tris.len(), n, bufs.len());
        let mut rows: Vec<RowResult> = bufs
            .iter()
            .map(|b| {
                let decoded: Vec<[u32; 3]> = match b.topology {
                    Topology::Triangles => b.indices.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
                    Topology::Strip => stripkit::decode(&stripkit::decode_restart(&b.indices, u32::MAX)),
                };
                RowResult {
                    label: b.label.clone(),
                    strips: b.topology == Topology::Strip,
                    indices: b.indices.len(),
                    invocations: None,
                    h100_model: invocations(&stripkit::BatchModel::NVIDIA_H100, &b.indices, b.topology),
                    fifo16_misses: stripkit::cache_misses(&decoded, n, 16, CacheKind::Fifo),
                    fifo32_misses: stripkit::cache_misses(&decoded, n, 32, CacheKind::Fifo),
                    ms: Vec::new(),
                }
            })
            .collect();
        let base = upload(&mut r, &mesh.positions, &nrm, None)?;
        // Invocation counts do not depend on the view or the vertex order.
        for (b, row) in bufs.iter().zip(rows.iter_mut()) {
            let ib = r.upload_indices(&b.indices, b.topology, IndexWidth::U32)?;
            let mut p = DrawParams::new(path[0].view_proj(1.0));
            p.shading = Shading::Smooth;
            row.invocations = r.count_vertex_invocations(&base.geometry, &ib, &p);
            r.delete_indices(ib);
        }
        for cfg in &configs {
            if cfg.width == IndexWidth::U16 && n > 0xFFFF {
                continue;
            }
            r.resize(cfg.size.0, cfg.size.1)?;
            let aspect = cfg.size.0 as f32 / cfg.size.1 as f32;
            let views: Vec<[f32; 16]> = path.iter().map(|c| c.view_proj(aspect)).collect();
            for (b, row) in bufs.iter().zip(rows.iter_mut()) {
                let up = if cfg.fetch {
                    Some(upload(&mut r, &mesh.positions, &nrm, Some(first_use_remap(&b.indices, n)))?)
                } else {
                    None
                };
                let (g, remap) = match &up {
                    Some(u) => (&u.geometry, u.remap.as_deref()),
                    None => (&base.geometry, None),
                };
                let ib = r.upload_indices(&remapped(&b.indices, remap), b.topology, cfg.width)?;
                let ms = time(&mut r, g, &ib, &views, cfg.heavy, draws, args.repeats);
                r.delete_indices(ib);
                if let Some(u) = up {
                    r.delete_geometry(u.geometry);
                }
                row.ms.push((cfg.name.to_string(), ms));
            }
        }
        r.delete_geometry(base.geometry);
        eprintln!("  {:.1} s", t0.elapsed().as_secs_f64());
        results.push(MeshResult { name: name.clone(), triangles: tris.len(), vertices: n, rows });
        // Written after every mesh, so a run cut short keeps what it measured.
        report(&args, &info, &gpu, &configs, &results, &probes)?;
    }
    let md = report(&args, &info, &gpu, &configs, &results, &probes)?;
    print!("{md}");
    Ok(())
}

/// Writes the markdown and JSON files that `args` asks for; returns the markdown.
fn report(
    args: &Args,
    info: &stripkit_render::DeviceInfo,
    gpu: &str,
    configs: &[Config],
    results: &[MeshResult],
    probes: &[Probe],
) -> anyhow::Result<String> {
    let md = markdown(gpu, configs, results, probes, args.draws, args.repeats);
    if let Some(out) = &args.table.out {
        std::fs::write(out, &md).with_context(|| out.display().to_string())?;
    }
    if let Some(path) = &args.json {
        let j = serde_json::json!({ "renderer": info.renderer, "vendor": info.vendor, "version": info.version,
            "draws": args.draws, "repeats": args.repeats, "meshes": results, "probes": probes });
        std::fs::write(path, serde_json::to_string_pretty(&j)?).with_context(|| path.display().to_string())?;
    }
    Ok(md)
}

/// A synthetic buffer and the vertex-shader invocations one draw of it took.
#[derive(serde::Serialize)]
struct Probe {
    name: String,
    indices: usize,
    distinct_vertices: usize,
    invocations: Option<u64>,
}

/// Synthetic buffers whose invocation counts give the GPU's batch limits:
/// - one triangle repeated: invocations / 3 = number of batches, so triangles per batch;
/// - random triangles over a pool of V vertices, for growing V: where a batch holds
///   every vertex of the pool, invocations = batches x V;
/// - a strip over fresh vertices: shaded vertices per index, the overlap at batch ends;
/// - a strip that keeps revisiting a small pool.
fn probes(r: &mut Renderer) -> anyhow::Result<Vec<Probe>> {
    let positions: Vec<[f32; 3]> = (0..70_000).map(|i| [(i % 256) as f32 / 256.0, (i / 256) as f32 / 256.0, 0.5]).collect();
    let g = r.upload(&Vertices::new(&positions))?;
    let mut cases: Vec<(String, Topology, Vec<u32>)> = Vec::new();
    cases.push(("list: triangle 0 1 2 repeated 9,600 times".into(), Topology::Triangles, [0, 1, 2].repeat(9600)));
    let mut state = 0x2545F4914F6CDD1Du64;
    let mut rnd = move |m: u32| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state % m as u64) as u32
    };
    for v in [6u32, 8, 12, 16, 24, 32, 48, 64, 96, 128, 256] {
        let mut idx = Vec::new();
        for _ in 0..9600 {
            let a = rnd(v);
            let mut b = rnd(v);
            while b == a {
                b = rnd(v);
            }
            let mut c = rnd(v);
            while c == a || c == b {
                c = rnd(v);
            }
            idx.extend([a, b, c]);
        }
        cases.push((format!("list: 9,600 random triangles over {v} vertices"), Topology::Triangles, idx));
    }
    cases.push(("strip: 0..30,000 fresh vertices".into(), Topology::Strip, (0..30_000).collect()));
    for v in [4u32, 8, 16, 32, 64] {
        cases.push((format!("strip: 30,000 indices cycling over {v} vertices"), Topology::Strip, (0..30_000).map(|i| i % v).collect()));
    }
    for (len, v) in [(3u32, 30_000u32), (4, 30_000), (8, 30_000), (16, 30_000), (32, 30_000)] {
        // Strips of `len` fresh vertices separated by restart.
        let mut idx = Vec::new();
        let mut next = 0;
        while idx.len() < v as usize {
            for _ in 0..len {
                idx.push(next % 70_000);
                next += 1;
            }
            idx.push(u32::MAX);
        }
        cases.push((format!("strips of {len} fresh vertices with restart"), Topology::Strip, idx));
    }
    let mut out = Vec::new();
    let p = DrawParams::new(glam::Mat4::IDENTITY.to_cols_array());
    for (name, topo, idx) in cases {
        let ib = r.upload_indices(&idx, topo, IndexWidth::U32)?;
        let inv = r.count_vertex_invocations(&g, &ib, &p);
        r.delete_indices(ib);
        let mut d: Vec<u32> = idx.iter().copied().filter(|&i| i != u32::MAX).collect();
        d.sort_unstable();
        d.dedup();
        out.push(Probe { name, indices: idx.len(), distinct_vertices: d.len(), invocations: inv });
    }
    r.delete_geometry(g);
    Ok(out)
}

fn markdown(gpu: &str, configs: &[Config], results: &[MeshResult], probes: &[Probe], draws: u32, repeats: u32) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(s, "# GPU draw times on {gpu}\n");
    let _ = writeln!(
        s,
        "ms per draw: the best of {repeats} runs of {draws} draws ({} on meshes over 500k triangles), each draw from the next \
         view of the 591-view helix path. Vertices carry position and normal (24 bytes). Bold: the fastest row of a column.\n",
        (draws / 10).max(1)
    );
    let labels: Vec<&str> = results.first().map(|m| m.rows.iter().map(|r| r.label.as_str()).collect()).unwrap_or_default();
    let all_labels = {
        let mut v: Vec<&str> = Vec::new();
        for m in results {
            for r in &m.rows {
                if !v.contains(&r.label.as_str()) {
                    v.push(&r.label);
                }
            }
        }
        if v.is_empty() {
            labels
        } else {
            v
        }
    };
    let header = |s: &mut String, title: &str| {
        let _ = writeln!(s, "## {title}\n");
        let _ = write!(s, "| index buffer |");
        for m in results {
            let _ = write!(s, " {} {}k |", m.name, (m.triangles + 500) / 1000);
        }
        let _ = write!(s, "\n|---|");
        for _ in results {
            let _ = write!(s, "---:|");
        }
        let _ = writeln!(s);
    };
    for cfg in configs {
        header(&mut s, cfg.name);
        for label in &all_labels {
            let _ = write!(s, "| {label} |");
            for m in results {
                let best = m.rows.iter().filter_map(|r| r.ms.iter().find(|(c, _)| c == cfg.name).map(|x| x.1)).fold(f64::INFINITY, f64::min);
                match m.rows.iter().find(|r| r.label == *label).and_then(|r| r.ms.iter().find(|(c, _)| c == cfg.name)) {
                    Some((_, ms)) if *ms == best => {
                        let _ = write!(s, " **{ms:.4}** |");
                    }
                    Some((_, ms)) => {
                        let _ = write!(s, " {ms:.4} |");
                    }
                    None => {
                        let _ = write!(s, " |");
                    }
                }
            }
            let _ = writeln!(s);
        }
        let _ = writeln!(s);
    }
    header(&mut s, "per triangle: indices / vertex-shader invocations measured / invocations by the H100 batch model / FIFO-32 misses");
    for label in &all_labels {
        let _ = write!(s, "| {label} |");
        for m in results {
            match m.rows.iter().find(|r| r.label == *label) {
                Some(r) => {
                    let t = m.triangles.max(1) as f64;
                    let inv = r.invocations.map_or("-".to_string(), |i| format!("{:.3}", i as f64 / t));
                    let _ = write!(
                        s,
                        " {:.3} / {inv} / {:.3} / {:.3} |",
                        r.indices as f64 / t,
                        r.h100_model as f64 / t,
                        r.fifo32_misses as f64 / t
                    );
                }
                None => {
                    let _ = write!(s, " |");
                }
            }
        }
        let _ = writeln!(s);
    }
    if !probes.is_empty() {
        let _ = writeln!(s, "\n## Batch probes: vertex-shader invocations for one draw\n");
        let _ = writeln!(s, "| buffer | indices | distinct vertices | invocations |\n|---|---:|---:|---:|");
        for p in probes {
            let inv = p.invocations.map_or("-".to_string(), |i| i.to_string());
            let _ = writeln!(s, "| {} | {} | {} | {inv} |", p.name, p.indices, p.distinct_vertices);
        }
    }
    s
}

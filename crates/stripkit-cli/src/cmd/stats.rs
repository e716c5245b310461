//! `stripkit stats`: a mesh's topology facts, as text or one JSON object.

use anyhow::Context;
use std::path::PathBuf;
use std::time::Instant;
use stripkit::MeshFacts;

/// Arguments of `stripkit stats`.
#[derive(clap::Args)]
#[command(after_help = "Definitions:
  boundary edge       an edge with exactly one incident face
  boundary loop       a closed walk along boundary edges (pinch vertices split per fan)
  non-manifold edge   an edge with three or more incident faces
  non-manifold vertex a pinch: its faces form more than one edge-connected fan
  components          groups of faces joined through shared vertices (unreferenced
                      vertices form none); edge_components: joined through edges only
  euler               V_used - E + F
  degenerate face     a repeated vertex index or zero area
  duplicate face      repeats an earlier face up to rotation and orientation
  consistently oriented  no two-face edge is traversed in the same direction twice
  gpu vertices        (OBJ with vt/vn) the vertices strips use: corners welded where every
                      attribute agrees; the facts above are of the surface (the file's v)

Example: stripkit stats bunny.obj --json")]
pub struct Args {
    /// The mesh file (.obj, .ply, .off, .stl, .gltf, .glb, optionally .gz).
    pub file: PathBuf,
    /// Print one JSON object on stdout instead of text (adds the file name and the
    /// load and analysis times in milliseconds).
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: super::ReadArgs,
}

/// Runs the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let start = Instant::now();
    let mesh = args.read.read_surface(&args.file)?;
    let loaded = Instant::now();
    // The GPU vertices strips use: an OBJ's corners welded where every attribute agrees
    // (one more read, only for formats that weld).
    let gpu_vertices = match stripkit::io::Format::from_path(&args.file) {
        Some((stripkit::io::Format::Obj, _)) => Some(args.read.read(&args.file)?.vertex_count()),
        _ => None,
    }
    .filter(|&n| n != mesh.vertex_count());
    let facts = MeshFacts::of(&mesh).with_context(|| format!("{}: malformed mesh", args.file.display()))?;
    let done = Instant::now();
    let load_ms = (loaded - start).as_secs_f64() * 1e3;
    let facts_ms = (done - loaded).as_secs_f64() * 1e3;
    if args.json {
        let mut value = serde_json::to_value(&facts)?;
        if let Some(obj) = value.as_object_mut() {
            obj.insert("file".into(), args.file.display().to_string().into());
            obj.insert("load_ms".into(), serde_json::json!(round3(load_ms)));
            obj.insert("facts_ms".into(), serde_json::json!(round3(facts_ms)));
            if let Some(n) = gpu_vertices {
                obj.insert("gpu_vertices".into(), n.into());
            }
        }
        print_out(&format!("{}\n", serde_json::to_string_pretty(&value)?))
    } else {
        let gpu = match gpu_vertices {
            Some(n) => format!("gpu vertices          {n} (split where attributes differ: what strips use)\n"),
            None => String::new(),
        };
        print_out(&format!(
            "{}\n{facts}\n{gpu}time                  {load_ms:.1} ms to load, {facts_ms:.1} ms to analyse\n",
            args.file.display()
        ))
    }
}

/// Writes to stdout; a closed pipe (`stats ... | head`) is not an error.
fn print_out(text: &str) -> anyhow::Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    super::ignore_closed_pipe(out.write_all(text.as_bytes()).and_then(|()| out.flush()))
}

fn round3(x: f64) -> f64 {
    (x * 1e3).round() / 1e3
}

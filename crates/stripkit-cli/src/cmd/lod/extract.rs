//! `stripkit lod extract`: one level (and frame) of a model, written and read back.

use anyhow::Context;
use serde::Serialize;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;
use stripkit::io::{self, Format};
use stripkit::lod::{Extracted, LevelSpec, Model};
use stripkit::Error;

#[derive(clap::Args)]
#[command(group(clap::ArgGroup::new("which").required(true).args(["level", "triangles", "ratio"])))]
pub(super) struct ExtractArgs {
    /// The model (`.sets`).
    file: PathBuf,
    /// Level (collapses applied; 0 is the input); past the coarsest is the coarsest.
    #[arg(long)]
    level: Option<u32>,
    /// The first level with at most this many triangles.
    #[arg(long)]
    triangles: Option<u64>,
    /// The first level with at most ceil(RATIO x input triangles): where `stripkit
    /// simplify --ratio RATIO` stops. 0 to 1.
    #[arg(long)]
    ratio: Option<f64>,
    /// Animations (.lodseq): the frame, 0 to frames - 1. A fraction morphs the
    /// positions linearly between the two key frames around it; the level follows
    /// the nearest key frame.
    #[arg(long)]
    frame: Option<f64>,
    /// Output file; the extension picks the format.
    #[arg(short, long)]
    output: PathBuf,
    /// Print one JSON object on stdout.
    #[arg(long)]
    json: bool,
    /// Write PLY as ASCII text instead of binary (PLY outputs only).
    #[arg(long)]
    ascii: bool,
}

#[derive(Serialize)]
struct ExtractOut {
    input: String,
    output: String,
    frame: Option<f64>,
    level: u32,
    levels: u32,
    triangles: u32,
    /// Vertices the level uses (what a mesh output holds).
    vertices: usize,
    /// Vertex attributes carried (UVs, normals, ...).
    attributes: Vec<String>,
    strips: usize,
    indices: usize,
    indices_per_triangle: f64,
    verified: bool,
    us: f64,
}

pub(super) fn extract(args: ExtractArgs) -> anyhow::Result<()> {
    let format = match Format::from_path(&args.output) {
        Some((f, _)) => Some(f),
        None if is_json(&args.output) => None,
        None => {
            return Err(Error::Invalid(format!(
                "cannot tell the format of {} from its extension (use {} or .json)",
                args.output.display(),
                io::supported_write_extensions()
            ))
            .into())
        }
    };
    if let Some(r) = args.ratio {
        anyhow::ensure!((0.0..=1.0).contains(&r), "--ratio {r} is out of range: 0 to 1");
    }
    let write_options = crate::cmd::write_options(args.ascii, &args.output, crate::cmd::path_format(&args.output))?;
    crate::cmd::check_not_inputs(&[("input", &args.file)], &[("-o", &args.output)])?;
    crate::cmd::check_output_folder(&args.output)?;
    let model = Model::read(&args.file)?;
    let spec = match (args.level, args.triangles, args.ratio) {
        (Some(l), _, _) => LevelSpec::Level(l),
        (_, Some(t), _) => LevelSpec::Triangles(t),
        (_, _, Some(r)) => LevelSpec::Ratio(r),
        _ => anyhow::bail!("give one of --level, --triangles, --ratio"),
    };
    // A .lodseq (by its header) needs --frame; a .sets refuses it.
    let start = Instant::now();
    let level = model.extract(spec, args.frame).with_context(|| format!("{} (--frame)", args.file.display()))?;
    let us = start.elapsed().as_secs_f64() * 1e6;
    // Either output is checked first: the strips draw the model's triangle count,
    // and a mesh file reads back to those triangles.
    match format {
        None => io::write_encoded(&args.output, &serde_json::to_vec(&level.to_json()?)?)?,
        Some(_) => level.write_file(&args.output, &write_options)?,
    }
    let Extracted { strips, level: number, levels, triangles, frame, attributes, .. } = level;
    let indices = strips.index_count();
    let mut used = strips.indices.clone();
    used.sort_unstable();
    used.dedup();
    let out = ExtractOut {
        input: args.file.display().to_string(),
        output: args.output.display().to_string(),
        frame: frame.map(|(t, _)| t),
        level: number,
        levels,
        triangles,
        vertices: used.len(),
        attributes: attributes.iter().map(|a| a.name.clone()).collect(),
        strips: strips.len(),
        indices,
        indices_per_triangle: (strips.restart_len()) as f64 / triangles.max(1) as f64,
        verified: true,
        us,
    };
    crate::cmd::print_report(args.json, &out, |w, o| {
        let carried =
            if o.attributes.is_empty() { String::new() } else { format!(" ({} and positions)", o.attributes.join(", ")) };
        writeln!(
            w,
            "{}: level {} of {}: {} triangles in {} strips over {} vertices{}, {} indices ({:.3} per triangle with restarts), verified -> {}",
            o.input,
            o.level,
            o.levels,
            o.triangles,
            o.strips,
            o.vertices,
            carried,
            o.indices,
            o.indices_per_triangle,
            o.output
        )
    })
}

fn is_json(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

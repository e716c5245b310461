//! `stripkit simplify`: quadric-error edge collapse down to a target, writing the
//! simplified mesh and (optionally) the collapse sequence.

use anyhow::Context;
use std::path::PathBuf;
use std::time::Instant;
use stripkit::simplify::{simplify, Options, Placement, Target};


/// Arguments of `stripkit simplify`.
#[derive(clap::Args, Clone)]
#[command(group(clap::ArgGroup::new("target").required(true).args(["ratio", "triangles", "error"])))]
pub struct Args {
    /// Input mesh (OBJ, OFF, ...; `.gz` is decompressed). Polygons are fanned into
    /// triangles. A folder simplifies every mesh file in it into the folder -o names
    /// (each in its own format, or --output-format).
    pub file: PathBuf,
    /// Keep at most this fraction of the triangles (0 to 1), e.g. 0.1.
    #[arg(long)]
    pub ratio: Option<f64>,
    /// Keep at most this many triangles.
    #[arg(long)]
    pub triangles: Option<usize>,
    /// Collapse while the cheapest collapse costs at most this much: a squared distance
    /// (the mean squared distance to the original planes under the merged vertices,
    /// plus 0.1 to 0.2 times the largest squared distance the collapse moves the
    /// surface locally).
    #[arg(long)]
    pub error: Option<f64>,
    /// Survivor placement: `endpoint` keeps input positions (and ids), `optimal`
    /// moves the survivor to the cheapest of the quadric's minimiser, the two ends and
    /// their midpoint. Default endpoint.
    #[arg(long, value_parser = super::named::<Placement>(Placement::NAMES))]
    pub placement: Option<Placement>,
    /// Weight of the boundary penalty planes (0 lets borders move freely).
    #[arg(long, default_value_t = Options::default().boundary_weight)]
    pub boundary_weight: f64,
    /// Also contract vertex pairs closer than this distance that share no edge
    /// (QSlim's pair contraction; may join pieces). Off by default. A finite
    /// distance, 0 or more, that finds at most 32 pairs per vertex plus 2^20 (a
    /// larger one pairs almost everything and is refused).
    #[arg(long)]
    pub pair_distance: Option<f64>,
    /// Output mesh; `-` writes standard output in --output-format (the report then
    /// goes to standard error). Vertices no face uses any more are dropped and the
    /// others keep their order (--keep-unreferenced keeps every input vertex id).
    #[arg(short, long)]
    pub output: PathBuf,
    /// The format written to standard output (`-o -`): obj, ply, off, stl, gltf or glb.
    /// Default: the --format of a standard input.
    #[arg(long, value_name = "FORMAT", value_parser = super::parse_format)]
    pub output_format: Option<stripkit::io::Format>,
    /// Keep the vertices the collapses left unreferenced, so that the output's vertex
    /// ids are the input's (what the collapse sequence's ids refer to).
    #[arg(long)]
    pub keep_unreferenced: bool,
    /// Write PLY as ASCII text instead of binary (PLY outputs only).
    #[arg(long)]
    pub ascii: bool,
    /// Write the collapse sequence here: `.json` for JSON, anything else for the
    /// compact binary format. Must not be the same file as `-o`. Both outputs are
    /// encoded and written in full to temporary files before either is renamed into
    /// place (the sequence first, the mesh last): a failure while writing leaves both
    /// files as they were.
    #[arg(long)]
    pub sequence: Option<PathBuf>,
    /// Print one JSON object (input, output, triangles_in, triangles_out, vertices_in,
    /// vertices_out, collapses, max_error, placement, ms) on stdout.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: super::ReadArgs,
}

/// Runs the command on one input file. `batch`: the text of one file of a folder run
/// (`main` runs each file of a folder input through here), where the report goes.
pub fn run(args: Args, batch: Option<&super::BatchText>) -> anyhow::Result<()> {
    let target = match (args.ratio, args.triangles, args.error) {
        (Some(r), _, _) => Target::Ratio(r),
        (_, Some(t), _) => Target::Triangles(t),
        (_, _, Some(e)) => Target::Error(e),
        _ => anyhow::bail!("give one of --ratio, --triangles, --error"),
    };
    let placement = args.placement.unwrap_or(Options::default().placement);
    let mut outputs = vec![("-o", args.output.as_path())];
    if let Some(seq) = &args.sequence {
        outputs.push(("--sequence", seq.as_path()));
        if stripkit::io::same_destination(&args.output, seq) {
            return Err(stripkit::Error::Invalid(format!(
                "-o/--output and --sequence name the same file ({} and {}): the sequence would overwrite the mesh",
                args.output.display(),
                seq.display()
            ))
            .into());
        }
        // A mesh name would read as a mesh and be taken for one (it holds a sequence).
        if stripkit::io::Format::from_path(seq).is_some() {
            return Err(stripkit::Error::Invalid(format!(
                "--sequence {}: a collapse sequence is written there, not a mesh; name it .json (JSON) or .bin (binary)",
                seq.display()
            ))
            .into());
        }
    }
    super::check_not_inputs(&[("input", &args.file)], &outputs)?;
    // Checked before reading the mesh, so a typo fails at once (NaN, negative and
    // infinite distances were silently taken as "no pairs").
    if let Some(d) = args.pair_distance {
        anyhow::ensure!(d >= 0.0 && d.is_finite(), "--pair-distance {d} is out of range: a finite distance, 0 or more");
    }
    let format = super::output_format(&args.output, args.output_format, Some((&args.file, &args.read)))?;
    let write_options = super::write_options(args.ascii, &args.output, Some(format))?;
    super::check_output_folder(&args.output)?;
    let mesh = args.read.read(&args.file)?;
    let options = Options::default()
        .target(target)
        .placement(placement)
        .boundary_weight(args.boundary_weight)
        .pair_distance(args.pair_distance);
    let bar = super::progress_bar(mesh.triangle_count() > 200_000 && batch.is_none(), "simplify");
    let start = Instant::now();
    let result = simplify(&mesh, &options, &mut |f| bar.set_position((f * 1000.0) as u64))
        .with_context(|| format!("simplifying {}", args.file.display()))?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    bar.finish_and_clear();
    // Every output encoded before any is written; then all staged on disk before any
    // is renamed into place, the sequence first and the mesh (-o) last.
    let compacted;
    let out_mesh = if args.keep_unreferenced {
        &result.mesh
    } else {
        compacted = result.mesh.compact().0;
        &compacted
    };
    // Compressed by the writers for a .gz name.
    let mesh_bytes = stripkit::io::write_bytes(format, out_mesh, None, &write_options)?;
    match &args.sequence {
        Some(seq) if super::is_dash(&args.output) => {
            result.sequence.write(seq)?;
            super::write_output(&args.output, &mesh_bytes)?;
        }
        Some(seq) => {
            let seq_bytes = result.sequence.encode(seq)?;
            stripkit::io::write_encoded_all(&[(seq, &seq_bytes), (&args.output, &mesh_bytes)])?;
        }
        None => super::write_output(&args.output, &mesh_bytes)?,
    }
    let sink = match batch {
        Some(text) => super::Sink::Batch(text.clone()),
        None => super::Sink::for_output(&args.output),
    };
    if args.json {
        let out = serde_json::json!({
            "input": args.file.display().to_string(),
            "output": args.output.display().to_string(),
            "triangles_in": result.triangles_in,
            "triangles_out": result.triangles_out(),
            "vertices_in": mesh.vertex_count(),
            "vertices_out": out_mesh.vertex_count(),
            "collapses": result.sequence.len(),
            "max_error": result.max_error,
            "placement": placement.name(),
            "ms": ms,
        });
        super::print_report_to(&sink, true, &out, |_, _| Ok(()))
    } else {
        super::print_report_to(&sink, false, &(), |w, _| {
            use std::io::Write;
            writeln!(
                w,
                "{}: {} -> {} triangles, {} -> {} vertices, {} collapses, max error {:.3e}, {:.1} ms",
                args.file.display(),
                result.triangles_in,
                result.triangles_out(),
                mesh.vertex_count(),
                out_mesh.vertex_count(),
                result.sequence.len(),
                result.max_error,
                ms
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        args: Args,
    }

    #[test]
    fn defaults_are_the_librarys() {
        let args = Cli::parse_from(["simplify", "in.obj", "--ratio", "0.5", "-o", "out.obj"]).args;
        let library = Options::default();
        assert_eq!(args.boundary_weight, library.boundary_weight);
        assert_eq!(args.pair_distance, library.pair_distance);
        // Unset: the library's own placement is used.
        assert_eq!(args.placement, None);
    }
}

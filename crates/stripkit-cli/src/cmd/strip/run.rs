//! `stripkit strip` on one input: flags -> options -> the library's door -> write ->
//! report; a glTF scene (or a mesh written as glTF with its materials) goes through
//! the library's scene path instead.

use super::report::{self, Report, SceneCliReport};
use super::{Args, VertexOrder};
use crate::cmd;
use std::path::Path;
use stripkit::io::Format;
use stripkit::{Algorithm, Error, Join, StripOptions};

enum OutKind {
    Json,
    Mesh(Format),
}

fn output_kind(path: &Path, stdout_format: Option<Format>) -> anyhow::Result<OutKind> {
    if let Some(format) = stdout_format.filter(|_| cmd::is_dash(path)) {
        return match format {
            Format::Ply | Format::Gltf | Format::Glb => Ok(OutKind::Mesh(format)),
            _ => {
                let name = format!("{format:?}").to_lowercase();
                Err(Error::Invalid(format!("--output-format {name} cannot hold strips; use ply, gltf or glb")).into())
            }
        };
    }
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if name.ends_with(".json") {
        return Ok(OutKind::Json);
    }
    match Format::from_path(path) {
        Some((f @ (Format::Ply | Format::Gltf | Format::Glb | Format::Obj), _)) => Ok(OutKind::Mesh(f)),
        _ => Err(Error::Invalid(format!(
            "{}: cannot hold strips; the output must end in .ply, .json, .gltf, .glb or .obj (triangles in strip order)",
            path.display()
        ))
        .into()),
    }
}

/// Runs the command on one input file: read -> door -> encode -> write. `batch`: the
/// text of one file of a folder run (`main` runs each file of a folder input through
/// here): the report is one line of it.
pub fn run(args: Args, batch: Option<&cmd::BatchText>) -> anyhow::Result<()> {
    let stdout_format = if cmd::is_dash(&args.output) {
        Some(cmd::output_format(&args.output, args.output_format, Some((&args.input, &args.read)))?)
    } else {
        anyhow::ensure!(
            args.output_format.is_none() || batch.is_some(),
            "--output-format applies to standard output (-o -) and folder outputs; \
             {} names its format by its extension",
            args.output.display()
        );
        None
    };
    let kind = output_kind(&args.output, stdout_format)?;
    cmd::check_not_inputs(&[("input", &args.input)], &[("-o", &args.output)])?;
    // Fail before the work when the output cannot be written at all.
    cmd::check_output_folder(&args.output)?;
    let write_options = cmd::write_options(
        args.ascii,
        &args.output,
        match kind {
            OutKind::Mesh(format) => Some(format),
            OutKind::Json => None,
        },
    )?;
    // Arguments are checked before the file is read.
    args.strip.validate(|o| args.with_join(o))?;
    let options = args.with_join(args.strip.options()?);
    let vertex_order = vertex_order_for(&args, &kind)?;
    if args.compress && !matches!(kind, OutKind::Mesh(Format::Gltf | Format::Glb)) {
        return Err(Error::Invalid("--compress applies to .gltf and .glb outputs".into()).into());
    }
    if is_scene(&args.input, &kind) {
        return run_scene(&args, &options, format_of(&kind), vertex_order, batch);
    }
    // A spinner on a terminal (indicatif draws nothing when stderr is not one):
    // balanced and --refine take seconds on meshes of a million triangles.
    let progress = match batch {
        Some(_) => indicatif::ProgressBar::hidden(),
        None => indicatif::ProgressBar::new_spinner(),
    };
    progress.enable_steady_tick(std::time::Duration::from_millis(120));
    progress.set_message(format!("reading {}", args.input.display()));
    let read_start = std::time::Instant::now();
    let mesh = args.read.read(&args.input)?;
    let read_time = read_start.elapsed();
    // A mesh written as glTF: the library chooses its writer (a scene of one
    // primitive per group, or the plain writer; stripkit::scene::for_gltf_output).
    let start = std::time::Instant::now();
    let scene = match kind {
        OutKind::Mesh(Format::Gltf | Format::Glb) => {
            // An OBJ's material libraries become glTF materials (textures embedded).
            let materials = match Format::from_path(&args.input) {
                Some((Format::Obj, _)) => {
                    stripkit::io::Materials::read_for_obj(&args.input, &mesh.material_libraries, &args.read.options())?
                }
                _ => stripkit::io::Materials::default(),
            };
            stripkit::scene::for_gltf_output_with(&mesh, &options, &materials)
                .map_err(|e| anyhow::anyhow!(e).context(format!("{}", args.input.display())))?
        }
        _ => None,
    };
    if let Some(scene) = scene {
        drop(mesh); // the scene holds it as a glTF document
        progress.finish_and_clear();
        for note in scene.notes() {
            eprintln!("note: {}: {note}", args.input.display());
        }
        return strip_scene(&args, &options, scene, start.elapsed(), format_of(&kind), vertex_order, batch);
    }
    if args.compress {
        return Err(Error::Invalid(
            "--compress needs the scene writer, which --join separate, --algo single and --restart-index rule out".into(),
        )
        .into());
    }

    progress.set_message(format!("stripifying and verifying {} triangles", mesh.triangle_count()));
    let strip_start = std::time::Instant::now();
    let strips = args.strip.stripify(&mesh, &args.input, |o| args.with_join(o))?;
    let strip_time = strip_start.elapsed();
    let (mut mesh, strips) = match (vertex_order, &kind) {
        (VertexOrder::FirstUse, OutKind::Mesh(format)) => strips.in_first_use_order(&mesh, *format),
        _ => (mesh, strips),
    };
    drop_unwritten_faces(&mut mesh, &kind, &strips);

    progress.set_message(format!("writing {}", args.output.display()));
    let figures = &strips.figures;
    let report = Report {
        input: &args.input,
        output: &args.output,
        algo: strips.algorithm.name(),
        heuristic: super::heuristic_of(&strips.algorithm),
        join: strips.join,
        vertex_order,
        vertices: mesh.vertex_count() + strips.added_positions.len(),
        welded: strips.welded,
        figures,
        ms: strips.stripify_time.as_secs_f64() * 1e3,
        diagonals: matches!(strips.algorithm, Algorithm::Cache { .. } | Algorithm::Balanced { .. })
            .then(|| strips.split.name()),
        quads: strips.quads,
        indices_per_quad: strips.indices_per_quad(),
        single: strips.single.as_ref(),
        max_acmr_unreached: strips.max_acmr_unreached(),
    };
    if let (Some(reached), Algorithm::Balanced { max_acmr }) = (report.max_acmr_unreached, &strips.algorithm) {
        eprintln!(
            "stripkit: warning: {}: --max-acmr {max_acmr} is below what balanced reaches on this mesh; \
             its strips have {reached:.3} misses per triangle (FIFO of {} entries)",
            args.input.display(),
            strips.figures.cache.size
        );
    }
    let encode_start = std::time::Instant::now();
    let bytes = match kind {
        OutKind::Json => {
            let mut obj = strips.to_json();
            obj.insert("figures".into(), serde_json::to_value(&report)?);
            let mut bytes = serde_json::to_vec(&serde_json::Value::Object(obj))?;
            bytes.push(b'\n');
            bytes
        }
        OutKind::Mesh(format) => strips.to_file_bytes_with(&mesh, format, &write_options)?,
    };
    let encode_time = encode_start.elapsed();
    let write_start = std::time::Instant::now();
    cmd::write_output(&args.output, &bytes)?;
    if args.timings {
        print_timings(read_time, (strip_time, &strips.phases), encode_time, write_start.elapsed());
    }
    progress.finish_and_clear();
    // The notes are not data: never where --json data goes to standard error (-o -).
    let notes = batch.is_none() && !(args.json && cmd::is_dash(&args.output));
    if let (OutKind::Mesh(format), true) = (&kind, notes) {
        let degenerate = strips.stitched_degenerate_in(*format).unwrap_or(0);
        report::loader_notes(&args.output, *format == Format::Ply, degenerate, strips.figures.triangles, false);
    }

    let sink = match batch {
        Some(text) => cmd::Sink::Batch(text.clone()),
        None => cmd::Sink::for_output(&args.output),
    };
    cmd::print_report_to(&sink, args.json, &report, |out, r| match batch {
        Some(_) => report::print_line(out, r),
        None => report::print_summary(out, r),
    })
}

/// The vertex order of the output: `--vertex-order` as given (first use only where the
/// output holds vertices), else first use for glTF and the input's order otherwise.
fn vertex_order_for(args: &Args, kind: &OutKind) -> anyhow::Result<VertexOrder> {
    Ok(match (args.vertex_order, kind) {
        (Some(VertexOrder::FirstUse), OutKind::Json) => {
            return Err(Error::Invalid(format!(
                "--vertex-order first-use applies to mesh outputs; {} holds no vertices",
                args.output.display()
            ))
            .into())
        }
        (Some(order), _) => order,
        (None, OutKind::Mesh(Format::Gltf | Format::Glb)) => VertexOrder::FirstUse,
        (None, _) => VertexOrder::Input,
    })
}

/// `--timings`: the seconds of each phase on standard error, the strip phase's own
/// steps (the library's `Strips::phases`) in brackets after it.
fn print_timings(
    read: std::time::Duration,
    (strip, steps): (std::time::Duration, &[(&str, std::time::Duration)]),
    encode: std::time::Duration,
    write: std::time::Duration,
) {
    let secs = |(name, t): &(&str, std::time::Duration)| format!("{name} {:.3}", t.as_secs_f64());
    let mut strip_text = secs(&("strip", strip));
    if !steps.is_empty() {
        let inner: Vec<String> = steps.iter().map(secs).collect();
        strip_text = format!("{strip_text} ({})", inner.join(", "));
    }
    let text = [secs(&("read", read)), strip_text, secs(&("encode", encode)), secs(&("write", write))];
    eprintln!("timings (s): {}", text.join(", "));
}

/// A PLY or JSON output holds the strips and at most the vertices: the faces go
/// before the output is encoded and checked (a fifth of the peak on big meshes).
fn drop_unwritten_faces(mesh: &mut stripkit::Mesh, kind: &OutKind, strips: &stripkit::Strips) {
    if matches!(kind, OutKind::Json | OutKind::Mesh(Format::Ply)) && !strips.changes_mesh() {
        mesh.face_offsets = vec![0];
        mesh.face_indices = Vec::new();
        mesh.face_groups = Vec::new();
    }
}

/// glTF in and glTF out: the whole scene goes through [`stripkit::io::Scene`].
fn is_scene(input: &Path, kind: &OutKind) -> bool {
    let gltf = |f: Option<(Format, bool)>| matches!(f, Some((Format::Gltf | Format::Glb, _)));
    input.as_os_str() != "-" && gltf(Format::from_path(input)) && matches!(kind, OutKind::Mesh(Format::Gltf | Format::Glb))
}

/// `strip` on a glTF scene: every triangle primitive stripped on its own, everything
/// else written as read; `--join restart` (default) adds EXT_mesh_primitive_restart
/// groups beside the stitched strips, `--join degenerate` writes the stitched strips
/// alone.
fn run_scene(
    args: &Args,
    options: &StripOptions,
    format: Format,
    vertex_order: VertexOrder,
    batch: Option<&cmd::BatchText>,
) -> anyhow::Result<()> {
    use stripkit::io::Scene;
    let invalid = |m: String| -> anyhow::Result<()> { Err(Error::Invalid(m).into()) };
    if options.join == Join::Separate {
        return invalid(
            "--join separate does not apply to a glTF scene, where each primitive becomes one strip primitive: \
             use --join restart (EXT_mesh_primitive_restart with a stitched fallback, the default) or \
             --join degenerate (plain stitched strips)"
                .into(),
        );
    }
    if options.restart_index != StripOptions::default().restart_index {
        return invalid(
            "--restart-index does not apply to a glTF scene: the restart value is the largest of the index type \
             (65535 or 4294967295), as EXT_mesh_primitive_restart asks"
                .into(),
        );
    }
    if matches!(options.algorithm, Algorithm::Single(_)) {
        return invalid(
            "--algo single adds vertices, and a glTF scene's vertex data is written as read; choose another algorithm"
                .into(),
        );
    }
    let start = std::time::Instant::now();
    let scene = Scene::read_with(&args.input, &args.read.options())?;
    if scene.primitives().iter().all(|p| p.mesh.face_count() == 0) {
        return invalid(format!("no faces in {}", args.input.display()));
    }
    strip_scene(args, options, scene, start.elapsed(), format, vertex_order, batch)
}

/// The mesh format of an output kind (glTF for the scene paths, which only take mesh outputs).
fn format_of(kind: &OutKind) -> Format {
    match kind {
        OutKind::Mesh(f) => *f,
        OutKind::Json => Format::Glb,
    }
}

/// Strips a scene's primitives, writes it and reports, for [`run_scene`] and for a
/// mesh with attributes or groups written as glTF.
fn strip_scene(
    args: &Args,
    options: &StripOptions,
    mut scene: stripkit::io::Scene,
    read_time: std::time::Duration,
    format: Format,
    vertex_order: VertexOrder,
    batch: Option<&cmd::BatchText>,
) -> anyhow::Result<()> {
    let scene_options = match options.join {
        Join::Degenerate => stripkit::scene::SceneOptions::stitched(),
        _ => stripkit::scene::SceneOptions::default(),
    }
    .reorder(vertex_order == VertexOrder::FirstUse)
    .compress(args.compress);
    let progress = match batch {
        Some(_) => indicatif::ProgressBar::hidden(),
        None => indicatif::ProgressBar::new_spinner(),
    };
    progress.enable_steady_tick(std::time::Duration::from_millis(120));
    for p in scene.primitives() {
        args.strip.check_mesh(&p.mesh, &args.input)?;
    }
    progress.set_message(format!("stripifying and verifying {} primitives", scene.primitives().len()));
    // The scene chooses its written forms and restart values itself (scene_options):
    // the door gets the strip flags alone.
    let strip_start = std::time::Instant::now();
    let report = scene.strip(&args.strip.options()?, &scene_options).map_err(cmd::flag_error)?;
    let strip_time = strip_start.elapsed();
    progress.set_message(format!("writing {}", args.output.display()));
    let start = std::time::Instant::now();
    let bytes = scene.into_bytes(format)?;
    let encode_time = start.elapsed();
    cmd::write_output(&args.output, &bytes)?;
    let write_ms = start.elapsed().as_secs_f64() * 1e3;
    if args.timings {
        print_timings(read_time, (strip_time, &[]), encode_time, start.elapsed() - encode_time);
    }
    progress.finish_and_clear();
    if batch.is_none() && !(args.json && cmd::is_dash(&args.output)) {
        let restart = options.join == Join::Restart;
        report::loader_notes(&args.output, false, report.degenerate_stitched, report.triangles, restart);
    }
    let r = SceneCliReport {
        input: &args.input,
        output: &args.output,
        join: options.join,
        verified: true,
        vertex_order,
        read_ms: read_time.as_secs_f64() * 1e3,
        write_ms,
        scene: &report,
    };
    let sink = match batch {
        Some(text) => cmd::Sink::Batch(text.clone()),
        None => cmd::Sink::for_output(&args.output),
    };
    cmd::print_report_to(&sink, args.json, &r, |out, r| report::print_scene(out, r, batch.is_some()))
}

//! Folder runs: `stripkit strip DIR -o OUTDIR` strips every mesh file in `DIR` into
//! `OUTDIR` (`simplify` likewise simplifies them), one line (or one JSON object with
//! `--json`) per file, under a progress bar. A file that fails is reported on standard error and the others still run; the
//! exit status is then that of the worst failure (1 for a failed verification, else 2).

use std::path::{Path, PathBuf};
use stripkit::io::Format;

/// The mesh files directly in `dir` (not its subfolders), by name: every file whose
/// extension names a format stripkit reads (optionally `.gz`).
pub fn mesh_files(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let read = |e: std::io::Error| stripkit::Error::Io { path: dir.to_path_buf(), source: e };
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(read)? {
        let path = entry.map_err(read)?.path();
        if path.is_file() && Format::from_path(&path).is_some() {
            files.push(path);
        }
    }
    files.sort();
    Ok(files)
}

/// The output file for input `file` in folder `out`: its name without the mesh
/// extension (and `.gz`), then `.ext`.
pub fn output_name(file: &Path, out: &Path, ext: &str) -> PathBuf {
    let name = file.file_name().and_then(|n| n.to_str()).unwrap_or("mesh");
    let name = name.strip_suffix(".gz").unwrap_or(name);
    let stem = Path::new(name).file_stem().and_then(|s| s.to_str()).unwrap_or(name);
    out.join(format!("{stem}.{ext}"))
}

/// The extension of `format`'s files.
fn extension(format: Format) -> &'static str {
    match format {
        Format::Obj => "obj",
        Format::Ply => "ply",
        Format::Off => "off",
        Format::Stl => "stl",
        Format::Gltf => "gltf",
        Format::Glb => "glb",
    }
}

/// `stripkit strip DIR -o OUTDIR`.
pub fn strip_folder(args: super::strip::Args) -> anyhow::Result<()> {
    let format = args.output_format.unwrap_or(Format::Glb);
    anyhow::ensure!(
        matches!(format, Format::Ply | Format::Gltf | Format::Glb),
        "--output-format {} cannot hold strips; use ply, gltf or glb",
        extension(format)
    );
    check_folders(&args.input, &args.output, &args.read)?;
    super::write_options(args.ascii, &args.output, Some(format))?;
    // Every flag is checked once, before any file is read.
    args.strip.validate(|o| o)?;
    run_folder(
        "strip",
        &args.input,
        &args.output,
        |_| format,
        |file, output, bar| {
            let mut one = args.clone();
            one.input = file.to_path_buf();
            one.output = output.to_path_buf();
            one.output_format = Some(format);
            one.batch = Some(bar.clone());
            super::strip::run(one)
        },
    )
}

/// `stripkit simplify DIR -o OUTDIR`: each file in its own format, or `--output-format`.
pub fn simplify_folder(args: super::simplify::Args) -> anyhow::Result<()> {
    check_folders(&args.file, &args.output, &args.read)?;
    anyhow::ensure!(args.sequence.is_none(), "--sequence names one file; a folder run cannot write one per input");
    anyhow::ensure!(
        !args.ascii || args.output_format.is_none_or(|f| f == Format::Ply),
        "--ascii applies to PLY outputs; --output-format is not PLY"
    );
    let chosen = args.output_format;
    let format_of = |file: &Path| chosen.or_else(|| super::path_format(file)).unwrap_or(Format::Ply);
    run_folder("simplify", &args.file, &args.output, format_of, |file, output, bar| {
        let mut one = args.clone();
        one.file = file.to_path_buf();
        one.output = output.to_path_buf();
        one.output_format = None;
        // --ascii on a folder of mixed formats applies to its PLY files.
        one.ascii = args.ascii && format_of(file) == Format::Ply;
        one.batch = Some(bar.clone());
        super::simplify::run(one)
    })
}

/// The checks of a folder run: no `--format`, no standard output, no file as the
/// output folder.
fn check_folders(input: &Path, output: &Path, read: &super::ReadArgs) -> anyhow::Result<()> {
    anyhow::ensure!(read.format.is_none(), "--format applies to standard input (-), not to a folder");
    anyhow::ensure!(!super::is_dash(output), "a folder input writes a folder: -o names it, not standard output");
    anyhow::ensure!(
        !output.is_file(),
        "{} is a file; a folder input ({}) needs an output folder",
        output.display(),
        input.display()
    );
    Ok(())
}

/// Runs `one(file, output, bar)` for every mesh file in `input`, writing
/// `output/NAME.EXT` (EXT of `format_of(file)`), under a progress bar. A failure is
/// reported and the others still run; then the run fails naming every failed file,
/// with exit status 1 if one failed verification, else 2.
fn run_folder(
    what: &str,
    input: &Path,
    output: &Path,
    format_of: impl Fn(&Path) -> Format,
    one: impl Fn(&Path, &Path, &indicatif::ProgressBar) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let files = mesh_files(input)?;
    anyhow::ensure!(!files.is_empty(), "no mesh files in {}", input.display());
    let outputs: Vec<PathBuf> = files.iter().map(|f| output_name(f, output, extension(format_of(f)))).collect();
    if let Some(twice) = outputs.iter().enumerate().find(|(i, o)| outputs[..*i].contains(o)) {
        anyhow::bail!(
            "two inputs would both write {} (same name, different extensions); run them separately",
            twice.1.display()
        );
    }
    std::fs::create_dir_all(output).map_err(|source| stripkit::Error::Io { path: output.to_path_buf(), source })?;
    let bar = super::progress_bar(true, what);
    bar.set_length(files.len() as u64);
    let mut failed: Vec<(PathBuf, anyhow::Error)> = Vec::new();
    for (i, (file, out)) in files.iter().zip(&outputs).enumerate() {
        bar.set_position(i as u64);
        if let Err(err) = one(file, out, &bar) {
            bar.suspend(|| eprintln!("stripkit: error: {}", super::describe(&err)));
            failed.push((file.clone(), err));
        }
    }
    bar.finish_and_clear();
    if failed.is_empty() {
        return Ok(());
    }
    let names: Vec<String> = failed.iter().map(|(f, _)| f.display().to_string()).collect();
    let message = format!(
        "{} of {} files failed ({}); the others were written to {}",
        names.len(),
        files.len(),
        names.join(", "),
        output.display()
    );
    // The worst failure decides the exit status: a failed verification (1) over bad input (2).
    let verification = failed.iter().any(|(_, e)| super::exit_code(e) == std::process::ExitCode::from(1));
    Err(if verification { stripkit::Error::Verification(message) } else { stripkit::Error::Invalid(message) }.into())
}

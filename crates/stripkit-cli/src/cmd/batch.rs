//! Folder runs: `stripkit strip DIR -o OUTDIR` strips every mesh file in `DIR` into
//! `OUTDIR` (`simplify` likewise simplifies them), one line (or one JSON object with
//! `--json`) per file, under a progress bar. A file that fails is reported on standard
//! error and the others still run; the exit status is then that of the worst failure
//! (1 for a failed verification, else 2).
//!
//! The runner knows no command: `main` sees that the input is a folder and hands
//! [`run_folder`] the command's per-file function, which writes its report into the
//! text it is given. Files run in parallel (`--threads`); their reports, errors and
//! the bar follow the input order, so standard output is the same at any count.

use std::path::{Path, PathBuf};
use stripkit::io::Format;

/// The mesh files directly in `dir` (not its subfolders), by name: every file whose
/// extension names a format stripkit reads (optionally `.gz`). A symbolic link is
/// taken only where it leads to a file inside `dir`: a link out of the folder names a
/// file the user did not (`d/x.obj -> /etc/passwd` had its first line quoted in the
/// error), so it is skipped, with a note naming it on standard error.
pub fn mesh_files(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let read = |e: std::io::Error| stripkit::Error::Io { path: dir.to_path_buf(), source: e };
    let root = dir.canonicalize().map_err(read)?;
    let mut files = Vec::new();
    let mut outside = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(read)? {
        let entry = entry.map_err(read)?;
        let path = entry.path();
        if !(path.is_file() && Format::from_path(&path).is_some()) {
            continue;
        }
        if entry.file_type().map_err(read)?.is_symlink()
            && !path.canonicalize().is_ok_and(|target| target.parent().is_some_and(|p| p.starts_with(&root)))
        {
            outside.push(path);
            continue;
        }
        files.push(path);
    }
    files.sort();
    if !outside.is_empty() {
        outside.sort();
        let names: Vec<String> = outside.iter().map(|p| p.display().to_string()).collect();
        eprintln!(
            "stripkit: note: skipped {} symbolic link(s) leading out of {}: {}",
            names.len(),
            dir.display(),
            names.join(", ")
        );
    }
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
pub fn extension(format: Format) -> &'static str {
    match format {
        Format::Obj => "obj",
        Format::Ply => "ply",
        Format::Off => "off",
        Format::Stl => "stl",
        Format::Gltf => "gltf",
        Format::Glb => "glb",
    }
}

/// The checks of a folder run: no `--format`, no standard output, no file as the
/// output folder.
pub fn check_folders(input: &Path, output: &Path, read: &super::ReadArgs) -> anyhow::Result<()> {
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

/// Runs `one(file, output, text)` for every mesh file in `input`, writing
/// `output/NAME.EXT` (EXT of `format_of(file)`), under a progress bar, files in
/// parallel (`--threads`); each file's `text` is printed, and its error reported, in
/// input order as soon as the files before it are done. A failure is reported and
/// the others still run; then the run fails naming every failed file, with exit
/// status 1 if one failed verification, else 2.
pub fn run_folder(
    what: &str,
    input: &Path,
    output: &Path,
    format_of: impl Fn(&Path) -> Format,
    one: impl Fn(&Path, &Path, &super::BatchText) -> anyhow::Result<()> + Sync,
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
    // An output folder that is the input folder (in any spelling) must not write a
    // file over one of the inputs: refused before any file is read.
    check_outputs_not_inputs(&files, &outputs)?;
    std::fs::create_dir_all(output).map_err(|source| stripkit::Error::Io { path: output.to_path_buf(), source })?;
    let bar = super::progress_bar(true, what);
    bar.set_length(files.len() as u64);
    let order = std::sync::Mutex::new(InOrder { next: 0, done: (0..files.len()).map(|_| None).collect(), failed: Vec::new() });
    // The biggest files first (by bytes on disk), so that no thread is left alone
    // with a big one at the end; reports still come out in input order.
    let sizes: Vec<u64> = files.iter().map(|f| std::fs::metadata(f).map_or(0, |m| m.len())).collect();
    let mut by_size: Vec<usize> = (0..files.len()).collect();
    by_size.sort_by_key(|&i| std::cmp::Reverse(sizes[i]));
    let order_of_work = if super::threads().is_serial() { (0..files.len()).collect() } else { by_size };
    stripkit::parallel::for_each_queued(super::threads(), &order_of_work, |i| {
        let text = super::BatchText::default();
        let result = one(&files[i], &outputs[i], &text);
        let text = std::mem::take(&mut *text.lock().unwrap_or_else(|e| e.into_inner()));
        let mut order = order.lock().unwrap_or_else(|e| e.into_inner());
        order.done[i] = Some((text, result));
        order.print_ready(&files, &bar);
    });
    bar.finish_and_clear();
    let failed = order.into_inner().unwrap_or_else(|e| e.into_inner()).failed;
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

/// The files of a folder run done but not yet printed, and those printed that failed.
struct InOrder {
    /// The first file not yet printed.
    next: usize,
    /// Each file's report text and result, from when it is done until it is printed.
    done: Vec<Option<(Vec<u8>, anyhow::Result<()>)>>,
    failed: Vec<(PathBuf, anyhow::Error)>,
}

impl InOrder {
    /// Prints every done file from the first not printed on, in input order, until
    /// one not done: its report on standard output, its error on standard error,
    /// above the bar, which then counts the files printed.
    fn print_ready(&mut self, files: &[PathBuf], bar: &indicatif::ProgressBar) {
        use std::io::Write;
        while let Some((text, mut result)) = self.done.get_mut(self.next).and_then(Option::take) {
            bar.suspend(|| {
                let written = super::ignore_closed_pipe(std::io::stdout().lock().write_all(&text));
                if let (Ok(()), Err(e)) = (&result, written) {
                    result = Err(e);
                }
                if let Err(err) = &result {
                    eprintln!("stripkit: error: {}", super::describe(err));
                }
            });
            if let Err(err) = result {
                self.failed.push((files[self.next].clone(), err));
            }
            self.next += 1;
            bar.set_position(self.next as u64);
        }
    }
}

/// Refuses a folder run one of whose outputs is one of its inputs (the output folder
/// being the input folder, in any spelling, or a link to one of its files): the shared
/// check ([`super::check_not_inputs`]) for the pair found. Only an output that exists
/// can be an input; on Unix the inputs are indexed by device and inode, so a folder of
/// n files costs n look-ups, not n^2.
fn check_outputs_not_inputs(files: &[PathBuf], outputs: &[PathBuf]) -> anyhow::Result<()> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let id = |p: &Path| std::fs::metadata(p).ok().map(|m| (m.dev(), m.ino()));
        let index: std::collections::HashMap<(u64, u64), &PathBuf> =
            files.iter().filter_map(|f| Some((id(f)?, f))).collect();
        for out in outputs {
            if let Some(input) = id(out).and_then(|k| index.get(&k)) {
                super::check_not_inputs(&[("input", input)], &[("output", out)])?;
            }
        }
        Ok(())
    }
    #[cfg(not(unix))]
    {
        let inputs: Vec<(&str, &Path)> = files.iter().map(|f| ("input", f.as_path())).collect();
        for out in outputs.iter().filter(|o| o.exists()) {
            super::check_not_inputs(&inputs, &[("output", out)])?;
        }
        Ok(())
    }
}

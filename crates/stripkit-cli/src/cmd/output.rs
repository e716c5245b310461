//! Where a command's output goes, and what it may not be: the output format (by
//! extension, or `--output-format` for `-o -`), data to standard output (a closed pipe is
//! an error), atomic writes, and the refusals made before any work (an output that is an
//! input, a wrong extension, a missing folder).

use std::path::Path;
use super::ReadArgs;
use stripkit::io::Format;

/// The write options of `--ascii` for `output` of `format` (its extension's, or
/// [`output_format`]'s for `-o -`): ASCII PLY, refused (exit 2) for an output that is
/// not PLY, where it would do nothing.
pub fn write_options(
    ascii: bool,
    output: &Path,
    format: Option<Format>,
) -> Result<stripkit::io::WriteOptions, stripkit::Error> {
    if ascii && format != Some(Format::Ply) {
        return Err(stripkit::Error::Invalid(format!(
            "--ascii applies to PLY outputs; {} is not one",
            output.display()
        )));
    }
    Ok(stripkit::io::WriteOptions::default().ply_ascii(ascii).threads(super::threads()))
}

/// The format a file's extension names (through `.gz`), if any.
pub fn path_format(path: &Path) -> Option<Format> {
    Format::from_path(path).map(|(f, _)| f)
}

/// Whether `path` is `-`, standard input or output.
pub fn is_dash(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// The format of a mesh output: its extension names it, or for `-o -` (standard output)
/// `--output-format`, else the `--format` of a standard input that is also `-`.
/// `--output-format` with a named file is refused, as is `-o -` with neither flag.
pub fn output_format(
    output: &Path,
    output_format: Option<Format>,
    input: Option<(&Path, &ReadArgs)>,
) -> Result<Format, stripkit::Error> {
    if !is_dash(output) {
        if output_format.is_some() {
            return Err(stripkit::Error::Invalid(format!(
                "--output-format applies to standard output (-o -); {} names its format by its extension",
                output.display()
            )));
        }
        return Format::from_path(output).map(|(f, _)| f).ok_or_else(|| {
            stripkit::Error::Invalid(format!(
                "{}: unknown output format; name it .obj, .ply, .off, .stl, .gltf or .glb (optionally .gz)",
                output.display()
            ))
        });
    }
    let stdin_format = input.filter(|(path, _)| is_dash(path)).and_then(|(_, read)| read.format);
    output_format.or(stdin_format).ok_or_else(|| {
        stripkit::Error::Invalid(
            "writing to standard output (-o -) needs --output-format obj, ply, off, stl, gltf or glb".into(),
        )
    })
}

/// Writes a command's data (a mesh for `-o -`, a completion script) to standard
/// output. Unlike a report, data the reader did not take in full is a failure: a
/// closed standard output (EPIPE, `... -o - | head -c 10`) is the error "standard
/// output closed" (exit 2), never success.
pub fn write_stdout_data(bytes: &[u8]) -> anyhow::Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(bytes).and_then(|()| out.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Err(anyhow::anyhow!(
            "standard output closed before the {} bytes of output were written (the reading end went away)",
            bytes.len()
        )),
        Err(e) => Err(anyhow::Error::new(e).context("writing to standard output")),
        Ok(()) => Ok(()),
    }
}

/// Writes encoded bytes to `output`: standard output for `-` ([`write_stdout_data`]:
/// a closed standard output is an error), else atomically to the file
/// (gzip-compressed for a `.gz` name).
pub fn write_output(output: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    if is_dash(output) {
        return write_stdout_data(bytes);
    }
    stripkit::io::write_encoded(output, bytes)?;
    Ok(())
}

/// Refuses, before any work, an output that is one of the command's own inputs in any
/// spelling: the same file through a symbolic or hard link, `..`, a relative path
/// ([`stripkit::io::same_destination`]: device and inode when the output exists, else
/// its resolved folder and name). `inputs` and `outputs` pair each path with what
/// names it (`input`, `-o`, `--sequence`, ...); standard input and output (`-`) are
/// skipped. Every command that writes a file calls it, so none writes over what it reads.
pub fn check_not_inputs(inputs: &[(&str, &Path)], outputs: &[(&str, &Path)]) -> Result<(), stripkit::Error> {
    for (out_name, out) in outputs.iter().filter(|(_, p)| !is_dash(p)) {
        for (in_name, input) in inputs.iter().filter(|(_, p)| !is_dash(p)) {
            if stripkit::io::same_destination(out, input) {
                return Err(stripkit::Error::Invalid(format!(
                    "{out_name} {} is the same file as the {in_name} {}: refusing to write over an input",
                    out.display(),
                    input.display()
                )));
            }
        }
    }
    Ok(())
}

/// Refuses an output whose extension is not one of `expected` (without the dot,
/// case-insensitive): `flag` names the option, `what` what the command writes there.
pub fn check_extension(flag: &str, path: &Path, what: &str, expected: &[&str]) -> Result<(), stripkit::Error> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    if expected.iter().any(|e| ext.eq_ignore_ascii_case(e)) {
        return Ok(());
    }
    let names: Vec<String> = expected.iter().map(|e| format!(".{e}")).collect();
    Err(stripkit::Error::Invalid(format!(
        "{flag} {}: {what} is written there; name it {}",
        path.display(),
        names.join(" or ")
    )))
}

/// Refuses, before any work, an output whose folder does not exist.
pub fn check_output_folder(output: &Path) -> Result<(), stripkit::Error> {
    match output.parent().filter(|d| !d.as_os_str().is_empty()) {
        Some(dir) if !dir.is_dir() => Err(stripkit::Error::Invalid(format!(
            "cannot write {}: the folder {} does not exist",
            output.display(),
            dir.display()
        ))),
        _ => Ok(()),
    }
}

//! One module per subcommand; each has an `Args` (clap) and a `run`.

pub mod batch;
pub mod cull;
pub mod distance;
pub mod gen;
pub mod lod;
pub mod matching;
mod output;
pub mod render;
pub mod simplify;
pub mod stats;
pub mod strip;

use std::path::Path;
use std::process::ExitCode;
pub use output::{
    check_extension, check_not_inputs, check_output_folder, is_dash, output_format, path_format, write_options,
    write_output, write_stdout_data,
};

/// Prints a command's report on stdout: one line of JSON with `--json`, else its text
/// summary. A closed pipe (`... | head`) is not an error of ours.
pub fn print_report<R: serde::Serialize>(
    json: bool,
    report: &R,
    summary: impl FnOnce(&mut std::io::StdoutLock<'static>, &R) -> std::io::Result<()>,
) -> anyhow::Result<()> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    let printed =
        if json { writeln!(stdout, "{}", serde_json::to_string(report)?) } else { summary(&mut stdout, report) };
    ignore_closed_pipe(printed)
}

/// A write to stdout that failed only because the reader went away is not an error.
/// For reports only (the figures of a run whose output is already written, `stats`):
/// data whose reader went away is an error ([`write_stdout_data`]).
pub fn ignore_closed_pipe(result: std::io::Result<()>) -> anyhow::Result<()> {
    match result {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(e.into()),
        _ => Ok(()),
    }
}

/// The memory ceiling for reading meshes, shared by every command that reads one.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct ReadArgs {
    /// Memory ceiling for reading each input (bytes, or 512M, 8G): caps .gz
    /// decompression, a .gltf's external buffers and the mesh a glTF decodes to
    /// (defaults and details: docs/cli.md).
    #[arg(long, value_name = "SIZE", value_parser = parse_size)]
    pub max_memory: Option<u64>,
    /// Format of a mesh read from standard input (`-`): obj, ply, off, stl, gltf or glb.
    #[arg(long, value_name = "FORMAT", value_parser = parse_format)]
    pub format: Option<stripkit::io::Format>,
    /// Read vertex positions alone (no UVs, normals or other attributes; OBJ vertices
    /// stay the file's `v` lines, so seams no longer split them): the bare shape, as
    /// the figures of README.md and docs/ are measured.
    #[arg(long)]
    pub positions_only: bool,
}

/// Parses a mesh format name (the extensions stripkit reads, without `.gz`).
pub fn parse_format(text: &str) -> Result<stripkit::io::Format, String> {
    use stripkit::io::Format;
    match text.trim().trim_start_matches('.').to_ascii_lowercase().as_str() {
        "obj" => Ok(Format::Obj),
        "ply" => Ok(Format::Ply),
        "off" => Ok(Format::Off),
        "stl" => Ok(Format::Stl),
        "gltf" => Ok(Format::Gltf),
        "glb" => Ok(Format::Glb),
        _ => Err(format!("`{text}` is not a mesh format: obj, ply, off, stl, gltf or glb")),
    }
}

impl ReadArgs {
    /// The library's read options for these arguments.
    pub fn options(&self) -> stripkit::io::ReadOptions {
        let mut options = stripkit::io::ReadOptions::default();
        if let Some(n) = self.max_memory {
            options.max_decompressed_bytes = n;
            options.max_external_bytes = n;
            options.max_decoded_bytes = Some(n);
        }
        options.positions_only(self.positions_only)
    }

    /// Reads a mesh under these limits; `-` reads standard input in `--format`. A mesh
    /// with no faces is refused ("no faces in FILE"): no command has anything to do
    /// with one, and an empty output written with exit status 0 reads as success.
    pub fn read(&self, path: &Path) -> stripkit::Result<stripkit::Mesh> {
        self.read_checked(path, self.options())
    }

    /// [`ReadArgs::read`] of the bare surface: positions and faces with the file's
    /// vertex ids, no attributes and no groups (`ReadOptions::positions_only`), for the
    /// commands about the surface's shape (`stats`, `match`), where an OBJ's UV seams,
    /// which split GPU vertices, would cut it into pieces.
    pub fn read_surface(&self, path: &Path) -> stripkit::Result<stripkit::Mesh> {
        self.read_checked(path, self.options().positions_only(true))
    }

    fn read_checked(&self, path: &Path, options: stripkit::io::ReadOptions) -> stripkit::Result<stripkit::Mesh> {
        let mesh = self.read_any(path, options)?;
        if mesh.face_count() == 0 {
            let name = if path.as_os_str() == "-" { "<standard input>".into() } else { path.display().to_string() };
            return Err(stripkit::Error::Invalid(format!("no faces in {name}")));
        }
        Ok(mesh)
    }

    /// [`ReadArgs::read`] without the check for faces.
    fn read_any(&self, path: &Path, options: stripkit::io::ReadOptions) -> stripkit::Result<stripkit::Mesh> {
        use std::io::Read;
        if path.as_os_str() != "-" {
            if self.format.is_some() {
                return Err(stripkit::Error::Invalid(format!(
                    "--format applies to standard input (-); {} names its format by its extension",
                    path.display()
                )));
            }
            return stripkit::io::read_with(path, &options);
        }
        let Some(format) = self.format else {
            return Err(stripkit::Error::Invalid(
                "reading a mesh from standard input (-) needs --format obj, ply, off, stl, gltf or glb".into(),
            ));
        };
        let name = Path::new("<standard input>");
        let cap = options.max_decompressed_bytes;
        let mut data = Vec::new();
        std::io::stdin()
            .lock()
            .take(cap.saturating_add(1))
            .read_to_end(&mut data)
            .map_err(|source| stripkit::Error::Io { path: name.to_path_buf(), source })?;
        if data.len() as u64 > cap {
            return Err(stripkit::Error::Invalid(format!(
                "standard input holds more than {cap} bytes (--max-memory raises the limit)"
            )));
        }
        if data.starts_with(&[0x1f, 0x8b]) {
            return Err(stripkit::Error::Invalid(
                "standard input is gzip-compressed: pipe it through gunzip, or name the .gz file".into(),
            ));
        }
        stripkit::io::read_bytes_with(name, format, &data, &options)
    }
}

/// Where a command's report goes: standard output, or standard error when the
/// output mesh itself goes to standard output (`-o -`), or a folder run's text for
/// one file (printed above its progress bar in input order, see [`batch::run_folder`]).
#[derive(Clone, Debug)]
pub enum Sink {
    /// Standard output.
    Stdout,
    /// Standard error (the mesh is on standard output).
    Stderr,
    /// One file's text of a folder run, printed by the run in input order.
    Batch(BatchText),
}

impl Sink {
    /// Standard error for an output of `-`, else standard output.
    pub fn for_output(output: &Path) -> Sink {
        if is_dash(output) {
            Sink::Stderr
        } else {
            Sink::Stdout
        }
    }
}

/// [`print_report`] to a [`Sink`]: the text is built first, then written at once.
pub fn print_report_to<R: serde::Serialize>(
    sink: &Sink,
    json: bool,
    report: &R,
    summary: impl FnOnce(&mut Vec<u8>, &R) -> std::io::Result<()>,
) -> anyhow::Result<()> {
    use std::io::Write;
    let mut text = Vec::new();
    if json {
        serde_json::to_writer(&mut text, report)?;
        text.push(b'\n');
    } else {
        summary(&mut text, report)?;
    }
    let written = match sink {
        Sink::Stderr => std::io::stderr().lock().write_all(&text),
        Sink::Stdout => std::io::stdout().lock().write_all(&text),
        Sink::Batch(buffer) => {
            buffer.lock().unwrap_or_else(|e| e.into_inner()).extend_from_slice(&text);
            Ok(())
        }
    };
    ignore_closed_pipe(written)
}

/// The standard-output text of one file of a folder run, kept until the run prints
/// it in input order.
pub type BatchText = std::sync::Arc<std::sync::Mutex<Vec<u8>>>;

/// The thread count of this run (`--threads`), set once by `main`.
static THREADS: std::sync::OnceLock<stripkit::parallel::Threads> = std::sync::OnceLock::new();

/// Sets the run's thread count (`--threads`; the first call wins).
pub fn set_threads(threads: stripkit::parallel::Threads) {
    let _ = THREADS.set(threads);
}

/// The run's thread count: `--threads`, every core when not given.
pub fn threads() -> stripkit::parallel::Threads {
    THREADS.get().copied().unwrap_or(stripkit::parallel::Threads::ALL)
}

/// A progress bar of 1,000 steps on stderr, `WHAT [bar] percent elapsed`; hidden
/// unless `show` (short runs draw nothing).
pub fn progress_bar(show: bool, what: &str) -> indicatif::ProgressBar {
    if !show {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::with_draw_target(Some(1000), indicatif::ProgressDrawTarget::stderr());
    bar.set_style(
        indicatif::ProgressStyle::with_template(&format!("{what} {{bar:40}} {{percent:>3}}% {{elapsed}}"))
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    bar
}

/// Parses a size such as `1048576`, `512K`, `64M`, `8G`, `1T` (binary multiples; an
/// optional `iB` or `B` after the letter; case-insensitive).
pub fn parse_size(text: &str) -> Result<u64, String> {
    let t = text.trim().to_ascii_uppercase();
    let t = t.strip_suffix("IB").or_else(|| t.strip_suffix('B')).unwrap_or(&t);
    let (digits, shift) = match t.char_indices().last() {
        Some((i, 'K')) => (&t[..i], 10),
        Some((i, 'M')) => (&t[..i], 20),
        Some((i, 'G')) => (&t[..i], 30),
        Some((i, 'T')) => (&t[..i], 40),
        _ => (t, 0),
    };
    let n: u64 = digits
        .trim()
        .parse()
        .map_err(|_| format!("`{text}` is not a size: a whole number of bytes, optionally followed by K, M, G or T"))?;
    n.checked_mul(1u64 << shift).ok_or_else(|| format!("`{text}` is too large (more than 2^64 bytes)"))
}

/// A clap value parser for a library enum: its names (`T::NAMES`) offered as the
/// possible values, each parsed by the library's `FromStr`. No mirror enum, no
/// conversion: the flag's value is the library's own.
pub fn named<T>(names: &'static [&'static str]) -> impl clap::builder::TypedValueParser<Value = T>
where
    T: std::str::FromStr + Clone + Send + Sync + 'static,
    T::Err: std::fmt::Display,
{
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(names).try_map(|name| name.parse::<T>().map_err(|e| e.to_string()))
}

/// The flag that sets each library option the library's errors can name
/// ([`stripkit::Error::BadOption`]); `None` for options no flag sets.
pub fn flag_of(option: stripkit::OptionName) -> Option<&'static str> {
    use stripkit::OptionName as O;
    Some(match option {
        O::CacheSize => "--cache",
        O::MaxAcmr => "--max-acmr",
        O::TunnelCuts => "--tunnel",
        O::Split => "--split",
        O::Join => "--join",
        O::RestartIndex => "--restart-index",
        O::Weights => "--weights",
        O::SwapAngle => "--swap-angle",
        O::CullAngle => "--cull-angle",
        _ => return None,
    })
}

/// A library error as the user, who typed flags, should read it: an option the
/// library names becomes its flag ([`flag_of`]); other errors pass unchanged.
pub fn flag_error(e: stripkit::Error) -> stripkit::Error {
    match e {
        stripkit::Error::BadOption { option, message } => match flag_of(option) {
            Some(flag) => stripkit::Error::Invalid(format!("{flag} {message}")),
            None => stripkit::Error::BadOption { option, message },
        },
        other => other,
    }
}

/// Exit status for an error: 1 for a failed verification, 2 for bad input.
pub fn exit_code(err: &anyhow::Error) -> ExitCode {
    for cause in err.chain() {
        // The matching solver's errors come either as they are or wrapped in stripkit's.
        let failed_check = cause.downcast_ref::<stripkit::Error>().is_some_and(stripkit::Error::is_verification)
            || matches!(
                cause.downcast_ref::<stripkit::matching::Error>(),
                Some(stripkit::matching::Error::Verification(_))
            );
        if failed_check {
            return ExitCode::from(1);
        }
    }
    ExitCode::from(2)
}

/// The error and its causes on one line, skipping a cause whose text the message
/// already holds (library errors often print their source themselves).
pub fn describe(err: &anyhow::Error) -> String {
    let mut message = String::new();
    for cause in err.chain() {
        let text = cause.to_string();
        if message.contains(&text) {
            continue;
        }
        if !message.is_empty() {
            message.push_str(": ");
        }
        message.push_str(&text);
    }
    message
}

#[cfg(test)]
mod tests {
    use super::parse_size;

    #[test]
    fn sizes_take_binary_suffixes() {
        assert_eq!(parse_size("1048576"), Ok(1 << 20));
        assert_eq!(parse_size("512K"), Ok(512 << 10));
        assert_eq!(parse_size("64m"), Ok(64 << 20));
        assert_eq!(parse_size("8GiB"), Ok(8 << 30));
        assert_eq!(parse_size("2GB"), Ok(2 << 30));
        assert_eq!(parse_size("1T"), Ok(1 << 40));
        assert_eq!(parse_size("0"), Ok(0));
        assert!(parse_size("").is_err() && parse_size("G").is_err() && parse_size("-1").is_err());
        assert!(parse_size("1.5G").is_err() && parse_size("3X").is_err());
        assert!(parse_size("16777216T").unwrap_err().contains("too large"));
    }
}

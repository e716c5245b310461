//! The `stripkit` command-line tool: a thin layer over the `stripkit` library.
//!
//! Exit status: 0 on success, 1 when an output fails verification, 2 on bad input
//! (unreadable or malformed file, bad argument).

mod cmd;

use clap::{CommandFactory, Parser, Subcommand};
use std::process::ExitCode;

/// Triangle strips for meshes: build them, verify them, measure them.
#[derive(Parser)]
#[command(name = "stripkit", version, about, long_about = None)]
struct Cli {
    /// Threads for independent work (files of a folder, glTF primitives, mesh groups,
    /// frames, level checks, distance samples): 0 or absent = every core, 1 = one.
    /// Outputs are the same bytes at any count.
    #[arg(long, global = true, value_name = "N")]
    threads: Option<usize>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print a mesh's facts: counts, boundaries, non-manifold parts, components, Euler characteristic.
    Stats(cmd::stats::Args),
    /// Generate procedural meshes (grid, icosphere, torus) or subdivide a mesh.
    Gen(cmd::gen::Args),
    /// Turn a mesh into triangle strips, verify them and print their figures.
    Strip(cmd::strip::Args),
    /// Weighted perfect matching on a DIMACS graph or a mesh's dual graph.
    Match(cmd::matching::Args),
    /// Simplify a mesh by quadric-error edge collapses, recording the collapse sequence.
    Simplify(cmd::simplify::Args),
    /// Hausdorff and RMS distance between two surfaces.
    Distance(cmd::distance::Args),
    /// Draw a mesh's strips to a PNG: each strip its own colour, the strip order, or back faces.
    Render(cmd::render::Args),
    /// Back-face culling of a single strip with its segment tree along the helix camera path: segments, culled triangles, times.
    Cull(cmd::cull::Args),
    /// Multiresolution strips (SETS): build a model of every level of detail, extract a level, time level changes.
    Lod(cmd::lod::Args),
    /// Print a shell completion script on stdout, e.g.
    /// `stripkit completions bash > ~/.local/share/bash-completion/completions/stripkit`.
    Completions {
        /// The shell: bash, elvish, fish, powershell or zsh.
        shell: clap_complete::Shell,
    },
}

/// glibc raises its mmap threshold to the size of each big block freed (up to 32 MiB),
/// after which blocks of tens of megabytes come from the heap and stay counted in the
/// resident size once freed: on a 4.4M-triangle mesh about 58 MB of the peak (docs/experiments/big-meshes.md).
/// A fixed threshold of 1 MiB gives every big array back to the system when it goes.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn return_big_blocks() {
    // SAFETY: mallopt only sets an allocator parameter; called before any thread starts.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 1 << 20);
    }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn return_big_blocks() {}

fn main() -> ExitCode {
    return_big_blocks();
    let cli = Cli::parse();
    cmd::set_threads(stripkit::parallel::Threads::new(cli.threads.unwrap_or(0)));
    let result = match cli.command {
        Command::Stats(a) => cmd::stats::run(a),
        Command::Gen(a) => cmd::gen::run(a),
        Command::Strip(a) if a.input.is_dir() => strip_folder(a),
        Command::Strip(a) => cmd::strip::run(a, None),
        Command::Match(a) => cmd::matching::run(a),
        Command::Simplify(a) if a.file.is_dir() => simplify_folder(a),
        Command::Simplify(a) => cmd::simplify::run(a, None),
        Command::Distance(a) => cmd::distance::run(a),
        Command::Render(a) => cmd::render::run(a),
        Command::Cull(a) => cmd::cull::run(a),
        Command::Lod(a) => cmd::lod::run(a),
        Command::Completions { shell } => {
            // Built first, then written: the script is the command's data, so a
            // closed standard output (a script cut short) is an error.
            let mut script = Vec::new();
            clap_complete::generate(shell, &mut Cli::command(), "stripkit", &mut script);
            cmd::write_stdout_data(&script)
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("stripkit: error: {}", cmd::describe(&err));
            cmd::exit_code(&err)
        }
    }
}

/// `stripkit strip DIR -o OUTDIR`: every flag checked once, before any file is read,
/// then each file stripped into `OUTDIR/NAME.EXT` (EXT of `--output-format`, default glb).
fn strip_folder(args: cmd::strip::Args) -> anyhow::Result<()> {
    use stripkit::io::Format;
    let format = args.output_format.unwrap_or(Format::Glb);
    anyhow::ensure!(
        matches!(format, Format::Ply | Format::Gltf | Format::Glb),
        "--output-format {} cannot hold strips; use ply, gltf or glb",
        cmd::batch::extension(format)
    );
    cmd::batch::check_folders(&args.input, &args.output, &args.read)?;
    cmd::write_options(args.ascii, &args.output, Some(format))?;
    args.strip.validate(|o| o)?;
    cmd::batch::run_folder("strip", &args.input, &args.output, |_| format, |file, output, text| {
        let one = cmd::strip::Args {
            input: file.to_path_buf(),
            output: output.to_path_buf(),
            output_format: Some(format),
            ..args.clone()
        };
        cmd::strip::run(one, Some(text))
    })
}

/// `stripkit simplify DIR -o OUTDIR`: each file simplified into `OUTDIR/NAME.EXT`, in
/// its own format or `--output-format`.
fn simplify_folder(args: cmd::simplify::Args) -> anyhow::Result<()> {
    use stripkit::io::Format;
    cmd::batch::check_folders(&args.file, &args.output, &args.read)?;
    anyhow::ensure!(args.sequence.is_none(), "--sequence names one file; a folder run cannot write one per input");
    anyhow::ensure!(
        !args.ascii || args.output_format.is_none_or(|f| f == Format::Ply),
        "--ascii applies to PLY outputs; --output-format is not PLY"
    );
    let chosen = args.output_format;
    let format_of = |file: &std::path::Path| chosen.or_else(|| cmd::path_format(file)).unwrap_or(Format::Ply);
    cmd::batch::run_folder("simplify", &args.file, &args.output, format_of, |file, output, text| {
        let one = cmd::simplify::Args {
            file: file.to_path_buf(),
            output: output.to_path_buf(),
            output_format: None,
            // --ascii on a folder of mixed formats applies to its PLY files.
            ascii: args.ascii && format_of(file) == Format::Ply,
            ..args.clone()
        };
        cmd::simplify::run(one, Some(text))
    })
}

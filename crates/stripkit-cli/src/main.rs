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

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Stats(a) => cmd::stats::run(a),
        Command::Gen(a) => cmd::gen::run(a),
        Command::Strip(a) => cmd::strip::run(a),
        Command::Match(a) => cmd::matching::run(a),
        Command::Simplify(a) => cmd::simplify::run(a),
        Command::Distance(a) => cmd::distance::run(a),
        Command::Render(a) => cmd::render::run(a),
        Command::Cull(a) => cmd::cull::run(a),
        Command::Lod(a) => cmd::lod::run(a),
        Command::Completions { shell } => {
            use std::io::Write;
            // Built first, then written: a closed pipe is not an error.
            let mut script = Vec::new();
            clap_complete::generate(shell, &mut Cli::command(), "stripkit", &mut script);
            cmd::ignore_closed_pipe(std::io::stdout().lock().write_all(&script))
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

//! `stripkit-bench`: stripkit next to other libraries, on a folder of meshes, in one
//! run; writes markdown tables. One module per comparison.

mod strips;
mod simplify;
mod matching;

use clap::{Parser, Subcommand};

/// Side-by-side comparisons of stripkit with other libraries.
#[derive(Parser)]
#[command(name = "stripkit-bench", about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Stripifiers: stripkit's modes next to meshoptimizer, every figure by stripkit's decoder.
    Strips(strips::Args),
    /// Simplification: stripkit's QEM next to meshoptimizer's simplify.
    Simplify(simplify::Args),
    /// Weighted perfect matching: stripkit next to LEMON (when installed).
    Matching(matching::Args),
}

fn main() -> anyhow::Result<()> {
    match Cli::parse().command {
        Command::Strips(a) => strips::run(a),
        Command::Simplify(a) => simplify::run(a),
        Command::Matching(a) => matching::run(a),
    }
}

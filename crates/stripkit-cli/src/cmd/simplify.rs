//! `stripkit simplify` (not built yet).

/// Arguments of `stripkit simplify`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`stripkit simplify` is not implemented yet")
}

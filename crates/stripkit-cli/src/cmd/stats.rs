//! `stripkit stats` (not built yet).

/// Arguments of `stripkit stats`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`stripkit stats` is not implemented yet")
}

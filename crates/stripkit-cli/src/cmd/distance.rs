//! `stripkit distance` (not built yet).

/// Arguments of `stripkit distance`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`stripkit distance` is not implemented yet")
}

//! `stripkit gen` (not built yet).

/// Arguments of `stripkit gen`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`stripkit gen` is not implemented yet")
}

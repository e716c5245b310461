//! `stripkit matching` (not built yet).

/// Arguments of `stripkit matching`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`stripkit matching` is not implemented yet")
}

//! `stripkit strip` (not built yet).

/// Arguments of `stripkit strip`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`stripkit strip` is not implemented yet")
}

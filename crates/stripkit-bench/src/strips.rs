//! The `strips` comparison (not built yet).

/// Arguments of the `strips` comparison.
#[derive(clap::Args)]
pub struct Args {}

/// Runs the comparison.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("the strips comparison is not built yet")
}

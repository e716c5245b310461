//! The `matching` comparison (not built yet).

/// Arguments of the `matching` comparison.
#[derive(clap::Args)]
pub struct Args {}

/// Runs the comparison.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("the matching comparison is not built yet")
}

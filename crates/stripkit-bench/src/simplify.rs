//! The `simplify` comparison (not built yet).

/// Arguments of the `simplify` comparison.
#[derive(clap::Args)]
pub struct Args {}

/// Runs the comparison.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("the simplify comparison is not built yet")
}

//! What every comparison shares: where the research meshes are, how they are read, and
//! the argument blocks repeated by the subcommands (flattened into each `Args`).

use std::path::PathBuf;

/// The research meshes: the folder named by `STRIPKIT_MODELS`, else `../shared/models`
/// beside the checkout (the tests' lookup, `stripkit_testkit::models_path`); `None`
/// when it is absent.
pub fn models_dir() -> Option<PathBuf> {
    let dir = stripkit_testkit::models_path();
    dir.is_dir().then_some(dir)
}

/// Reads a research mesh as its bare surface (positions and faces, the file's vertex
/// ids; `ReadOptions::positions_only`): the figures in docs/ are of the shapes, and an
/// OBJ's UV seams (spot) would otherwise split its vertices and its strips.
pub fn read_surface(path: &std::path::Path) -> stripkit::Result<stripkit::Mesh> {
    stripkit::io::read_with(path, &stripkit::io::ReadOptions::default().positions_only(true))
}

/// `--models DIR`: the folder of the research meshes.
#[derive(clap::Args)]
pub struct Models {
    /// Folder of the research meshes (default: `STRIPKIT_MODELS`, else ../shared/models).
    #[arg(long = "models", value_name = "DIR")]
    pub models: Option<PathBuf>,
}

impl Models {
    /// The folder given, else [`models_dir`]; `None` when neither exists.
    pub fn dir(&self) -> Option<PathBuf> {
        self.models.clone().or_else(models_dir)
    }
}

/// `--out FILE`: where the markdown table is written besides stdout.
#[derive(clap::Args)]
pub struct TableOut {
    /// Also write the markdown table(s) to this file.
    #[arg(long = "out", value_name = "FILE")]
    pub out: Option<PathBuf>,
}

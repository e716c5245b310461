//! Where tests find their meshes, so that every test skips, or not, for the same reason.

use std::path::{Path, PathBuf};

/// The workspace root (two folders above this crate, like every crate of the workspace).
pub fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Where the research meshes should be: the folder named by `STRIPKIT_MODELS`, else
/// `../shared/models` beside the checkout. It may not exist; see [`models_dir`].
pub fn models_path() -> PathBuf {
    match std::env::var_os("STRIPKIT_MODELS") {
        Some(d) => PathBuf::from(d),
        None => repo_root().join("../shared/models"),
    }
}

/// The research meshes folder ([`models_path`]); `None` (after printing why) when it is
/// absent, so that tests needing it can skip with a reason.
pub fn models_dir() -> Option<PathBuf> {
    let dir = models_path();
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipped: research meshes not found at {} (set STRIPKIT_MODELS)", dir.display());
        None
    }
}

/// The bundled public-domain meshes (`assets/` at the workspace root).
pub fn assets_dir() -> PathBuf {
    repo_root().join("assets")
}

/// The research mesh `name` from [`models_dir`], read by `read` (the library's
/// `io::read`, or a reader of the caller's); `None` (after printing why) when the
/// folder or the file is absent or unreadable, so that a test can skip it.
pub fn model_with<M, E: std::fmt::Display>(name: &str, read: impl Fn(&Path) -> Result<M, E>) -> Option<M> {
    let dir = models_dir()?;
    match read(&dir.join(name)) {
        Ok(mesh) => Some(mesh),
        Err(e) => {
            eprintln!("skipped: {name} in {}: {e}", dir.display());
            None
        }
    }
}

/// Where tests write their files: `tmp/stripkit-tests` in the build folder that holds the
/// running test binary (`target/tmp`, beside `target/debug`), so that each run replaces
/// the files of the run before instead of leaving a folder per process in the system's
/// temporary folder. A binary outside a cargo build folder (a doctest) gets
/// `stripkit-tests` in the system's temporary folder.
pub fn scratch_root() -> PathBuf {
    let exe = std::env::current_exe().ok();
    // target/<profile>/deps/<test binary>: three folders up is the build folder.
    let built = exe.as_deref().and_then(|e| {
        let deps = e.parent()?;
        (deps.file_name()? == "deps").then_some(())?;
        Some(deps.parent()?.parent()?.join("tmp"))
    });
    built.unwrap_or_else(std::env::temp_dir).join("stripkit-tests")
}

/// The folder `name` under [`scratch_root`], emptied the first time this process asks
/// for it (what an earlier run left is gone, as a folder named by process id gave) and
/// kept as it is after that (tests that share it write files of their own names). Name
/// it after the test file so that two test binaries never share one.
pub fn scratch_dir(name: &str) -> PathBuf {
    static EMPTIED: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());
    let dir = scratch_root().join(name);
    let mut emptied = EMPTIED.lock().unwrap_or_else(|e| e.into_inner());
    if !emptied.contains(&dir) {
        let _ = std::fs::remove_dir_all(&dir);
        emptied.push(dir.clone());
    }
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("making {}: {e}", dir.display()));
    dir
}

/// [`scratch_dir`], emptied first: for one test that lists what it finds there.
pub fn fresh_scratch_dir(name: &str) -> PathBuf {
    let dir = scratch_dir(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("making {}: {e}", dir.display()));
    dir
}

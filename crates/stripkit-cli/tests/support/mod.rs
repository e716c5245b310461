//! Helpers shared by the CLI's end-to-end tests.

use std::path::PathBuf;
use std::process::{Command, Output};

/// Processor seconds a `stripkit_1gib` run may use before it is killed.
#[allow(dead_code)]
pub const CPU_SECONDS: u32 = 20;

/// Runs the built `stripkit` binary with `args`.
#[allow(dead_code)] // not every test binary runs it
pub fn stripkit(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stripkit"))
        .args(args)
        .output()
        .expect("runs")
}

/// A path for file `name` in this test binary's own temporary folder `group`.
#[allow(dead_code)]
pub fn tmp(group: &str, name: &str) -> PathBuf {
    let dir = stripkit_testkit::scratch_dir(&format!("cli-{group}"));
    dir.join(name)
}

/// The one JSON object a successful run printed on stdout.
#[allow(dead_code)] // not every test binary prints JSON
pub fn json(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

/// Writes `mesh` to `path` (format by extension) for a test to read back.
#[allow(dead_code)]
pub fn write_mesh(path: &std::path::Path, mesh: &stripkit::Mesh) {
    stripkit::io::write(path, mesh, None).expect("writes the test mesh");
}

#[allow(unused_imports)] // each test binary uses a different subset
pub use stripkit_testkit::{assets_dir, encode_base64, gltf_validator, models_dir};

/// Runs the built `stripkit` binary with `args` under a 1 GiB address-space limit
/// (`ulimit -v`, through `sh`), so that a run which tries to allocate from an
/// absurd count fails fast instead of exhausting the machine, and under a limit of
/// `CPU_SECONDS` of processor time (`ulimit -t`): a run that starts work of
/// gigabytes is killed by SIGXCPU, so its exit status fails the test. Processor time,
/// not wall time, so a loaded machine cannot fail it. Returns the output and the wall
/// seconds it took (for messages).
#[allow(dead_code)]
pub fn stripkit_1gib(args: &[&str]) -> (Output, f64) {
    let start = std::time::Instant::now();
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v 1048576 && ulimit -t {CPU_SECONDS} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_stripkit"))
        .args(args)
        .output()
        .expect("runs");
    (out, start.elapsed().as_secs_f64())
}


/// This checkout's root (not the testkit's, which may have been built in another tree).
#[allow(dead_code)]
pub fn repo_root() -> PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Why a check in headless Chromium cannot run here, if it cannot: Debian's
/// `chromium` (or `$CHROMIUM`), node, and each of the npm `packages` in
/// `.ci/node_modules` (all of which `.ci/run` installs).
#[allow(dead_code)]
pub fn chromium_missing(packages: &[&str]) -> Option<String> {
    let chromium = std::env::var("CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into());
    if !std::path::Path::new(&chromium).is_file() {
        return Some(format!("{chromium} is absent (.ci/run installs Debian's chromium as root)"));
    }
    for p in packages {
        if !repo_root().join(".ci/node_modules").join(p).join("package.json").is_file() {
            return Some(format!("npm package {p} is not installed in .ci/node_modules (.ci/run installs it)"));
        }
    }
    match Command::new("node").arg("--version").output() {
        Ok(o) if o.status.success() => None,
        _ => Some("node is not on PATH".into()),
    }
}

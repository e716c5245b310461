//! Helpers shared by the CLI's end-to-end tests.

use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs the built `stripkit` binary with `args`.
#[allow(dead_code)] // not every test binary runs it
pub fn stripkit(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stripkit")).args(args).output().expect("runs")
}

/// A path for file `name` in this test binary's own temporary folder `group`.
pub fn tmp(group: &str, name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stripkit-cli-{group}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

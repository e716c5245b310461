//! The Khronos glTF validator on files the tests wrote: `.ci/validate-gltf.js` over the
//! npm package `gltf-validator`, which `.ci/run` installs into `.ci/node_modules`.

use std::path::Path;
use std::process::Command;

/// Runs the validator on `files` and panics naming the errors if any file has one.
/// Returns the per-file reports (JSON), or `None` after printing why it skipped (no
/// `node`, or the package not installed: run `.ci/run` or
/// `npm install --prefix .ci gltf-validator`).
pub fn validate(files: &[&Path]) -> Option<Vec<serde_json::Value>> {
    let root = crate::repo_root();
    let script = root.join(".ci/validate-gltf.js");
    if !root.join(".ci/node_modules/gltf-validator/package.json").is_file() {
        eprintln!("skip: gltf-validator is not installed in .ci/node_modules (.ci/run installs it)");
        return None;
    }
    let out = match Command::new("node").arg(&script).args(files).output() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("skip: cannot run node for the glTF validator: {e}");
            return None;
        }
    };
    let text = String::from_utf8_lossy(&out.stdout);
    let reports: Vec<serde_json::Value> = text.lines().filter_map(|l| serde_json::from_str(l).ok()).collect();
    assert_eq!(
        reports.len(),
        files.len(),
        "the validator did not report on every file: {text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for r in &reports {
        assert_eq!(r["errors"], 0, "glTF validator errors: {r}");
    }
    assert!(out.status.success(), "validator failed: {text}{}", String::from_utf8_lossy(&out.stderr));
    Some(reports)
}

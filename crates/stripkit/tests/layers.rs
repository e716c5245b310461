//! The library's layers hold: no import circle in any crate, no import running up the
//! layers of `crates/stripkit/src`, no module importing through the crate root's
//! re-exports. The listing is `scripts/imports.py` (Python 3, standard library only);
//! this test runs its `--check` so a change that breaks the map in ARCHITECTURE.md fails.

use std::path::Path;
use std::process::Command;

#[test]
fn no_import_circle_no_upward_import_no_use_through_the_root() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let script = root.join("scripts/imports.py");
    let output = match Command::new("python3").arg(&script).arg("--check").current_dir(&root).output() {
        Ok(output) => output,
        Err(e) => {
            println!("skipped: python3 could not be run ({e}); the import check needs it");
            return;
        }
    };
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "scripts/imports.py --check found:\n{text}{}", String::from_utf8_lossy(&output.stderr));
    // The listing covers every crate of the workspace, so a renamed crate cannot pass unseen.
    for name in ["stripkit", "stripkit-matching", "stripkit-render", "stripkit-cli", "stripkit-bench"] {
        assert!(text.contains(&format!("== {name} (")), "no listing of {name} in:\n{text}");
    }
}

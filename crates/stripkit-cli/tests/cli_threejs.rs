//! three.js draws stripkit's glTF outputs like the source: `.ci/threejs-pixels.mjs`
//! (GLTFLoader / OBJLoader in headless Chromium, one launch for every picture) compares
//! every output form (restart groups with their stitched fallback, degenerate-joined,
//! separate, the `.obj` triangle list) of the shipped assets with the source OBJ as
//! OBJLoader reads it: flat normals and UVs from 3 views, and the restart groups drawn
//! on their own. Skips with a printed reason without Chromium (`.ci/run` installs
//! Debian's `chromium` as root), node, or the npm packages three and playwright-core.

mod support;

use std::path::{Path, PathBuf};
use std::process::Command;
use support::{stripkit, tmp};

/// This checkout (not the testkit's, which may have been built in another tree).
fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Why the check cannot run here, if it cannot.
fn missing() -> Option<String> {
    let chromium = std::env::var("CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into());
    if !Path::new(&chromium).is_file() {
        return Some(format!("{chromium} is absent (.ci/run installs Debian's chromium as root)"));
    }
    for p in ["three", "playwright-core"] {
        if !repo_root().join(".ci/node_modules").join(p).join("package.json").is_file() {
            return Some(format!("npm package {p} is not installed in .ci/node_modules (.ci/run installs it)"));
        }
    }
    match Command::new("node").arg("--version").output() {
        Ok(o) if o.status.success() => None,
        _ => Some("node is not on PATH".into()),
    }
}

/// One output to draw: the source's file name in assets/ (or `out:NAME`, an earlier
/// output stripped again and compared with assets/spot.obj), the output's name and
/// the flags that made it.
struct Form {
    source: &'static str,
    output: &'static str,
    flags: &'static [&'static str],
}

/// Every output form of the shipped assets. Quads are split as fans (`--split fan`),
/// the split OBJLoader makes, so that the source as three.js reads it has the same
/// triangles; `.obj` is the list form (the strips' triangles).
const FORMS: &[Form] = &[
    Form { source: "spot.obj", output: "spot_restart.glb", flags: &["--join", "restart"] },
    Form { source: "spot.obj", output: "spot_degenerate.glb", flags: &["--join", "degenerate"] },
    Form { source: "spot.obj", output: "spot_degenerate.gltf", flags: &["--join", "degenerate"] },
    Form { source: "spot.obj", output: "spot_cache.glb", flags: &["--algo", "cache"] },
    Form { source: "spot.obj", output: "spot_balanced.glb", flags: &["--algo", "balanced"] },
    Form { source: "spot.obj", output: "spot_list.obj", flags: &[] },
    Form { source: "spot.obj", output: "spot_separate.glb", flags: &["--join", "separate"] },
    Form { source: "spot_quads.obj", output: "quads_restart.glb", flags: &["--algo", "greedy", "--split", "fan"] },
    Form { source: "spot_quads.obj", output: "quads_degenerate.glb", flags: &["--algo", "greedy", "--split", "fan", "--join", "degenerate"] },
    Form { source: "spot_quads.obj", output: "quads_list.obj", flags: &["--algo", "greedy", "--split", "fan"] },
    Form { source: "spot_control_mesh.obj", output: "control_restart.glb", flags: &["--algo", "cache", "--split", "fan"] },
    Form { source: "spot_control_mesh.obj", output: "control_degenerate.gltf", flags: &["--algo", "greedy", "--split", "fan", "--join", "degenerate"] },
    // glTF in, glTF out (the scene path): the degenerate-joined .glb above stripped
    // again, still compared with the source OBJ.
    Form { source: "out:spot_degenerate.glb", output: "again_restart.glb", flags: &[] },
    Form { source: "out:spot_degenerate.glb", output: "again_degenerate.gltf", flags: &["--join", "degenerate"] },
];

#[test]
fn threejs_draws_every_output_like_the_source() {
    if let Some(why) = missing() {
        eprintln!("skip: {why}");
        return;
    }
    let mut pairs = Vec::new();
    for form in FORMS {
        let (source, reference) = match form.source.strip_prefix("out:") {
            Some(output) => (tmp("threejs", output), repo_root().join("assets/spot.obj")),
            None => (repo_root().join("assets").join(form.source), repo_root().join("assets").join(form.source)),
        };
        let out = tmp("threejs", form.output);
        let mut args = vec!["strip", source.to_str().unwrap(), "-o", out.to_str().unwrap()];
        args.extend(form.flags);
        let run = stripkit(&args);
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        pairs.push(format!("{}={}", reference.display(), out.display()));
    }
    let run = Command::new("node")
        .arg(repo_root().join(".ci/threejs-pixels.mjs"))
        .args(&pairs)
        .output()
        .expect("runs node");
    let text = String::from_utf8_lossy(&run.stdout);
    eprintln!("{text}{}", String::from_utf8_lossy(&run.stderr));
    let reports: Vec<serde_json::Value> = text.lines().filter_map(|l| serde_json::from_str(l).ok()).collect();
    assert_eq!(reports.len(), FORMS.len(), "{text}");
    for (form, r) in FORMS.iter().zip(&reports) {
        let differing = r["differing"].as_object().unwrap();
        // Normals and UVs from 3 views, and from the restart strips where the glb has them.
        let gltf = form.output.ends_with(".glb") || form.output.ends_with(".gltf");
        // A stitched strip stripped again would take 7,114 indices for the source's
        // 7,102, so the primitive is kept as read (never worse than its source) and
        // gets no restart group.
        let again = form.source.starts_with("out:");
        let groups = gltf && !again && !form.flags.contains(&"degenerate") && !form.flags.contains(&"separate");
        let passes = if groups { 4 } else { 2 };
        assert_eq!(differing.len(), passes, "{}: {r}", form.output);
        // The cow drawn: about 16% of the pixels lit.
        assert!(r["drawn"].as_u64().unwrap() > 50_000, "{r}");
        for (pass, n) in differing {
            assert_eq!(n, 0, "{}: {pass} differs: {r}", form.output);
        }
    }
}

//! three.js draws stripkit's glTF outputs like the source: `.ci/threejs-pixels.mjs`
//! (GLTFLoader / OBJLoader in headless Chromium, one launch for every picture) compares
//! every output form (restart groups with their stitched fallback, degenerate-joined,
//! separate, the `.obj` triangle list) of the shipped assets with the source OBJ as
//! OBJLoader reads it: flat normals and UVs from 3 views, and the restart groups drawn
//! on their own. Skips with a printed reason without Chromium (`.ci/run` installs
//! Debian's `chromium` as root), node, or the npm packages three and playwright-core.
//! In the same launch, gltfpack's outputs (its default, KHR_mesh_quantization, and
//! `-c`, EXT_meshopt_compression) of spot and of a small generated torus are stripped
//! four ways and drawn against gltfpack's own file (quantization moves positions
//! slightly from the OBJ's, so the OBJ is not their reference); skipped with a printed
//! reason where gltfpack is not installed.

mod support;

use std::path::{Path, PathBuf};
use std::process::Command;
use support::{chromium_missing, repo_root, stripkit, tmp};

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

/// One gltfpack output to strip: the source (`torus` is written by the test), the
/// packed file's name and gltfpack's flags. `-kv` keeps the UVs (gltfpack's default
/// drops attributes no material reads), so that they are drawn too.
const PACKED: &[(&str, &str, &[&str])] = &[
    ("spot.obj", "gp_spot.glb", &[]),
    ("spot.obj", "gp_spot_c.glb", &["-c"]),
    ("spot.obj", "gp_spot_kv_c.glb", &["-kv", "-c"]),
    ("torus", "gp_torus_kv.glb", &["-kv"]),
    ("torus", "gp_torus_kv_c.glb", &["-kv", "-c"]),
];

/// The ways each gltfpack output is stripped: its name's suffix and stripkit's flags.
const PACKED_STRIPS: &[(&str, &[&str])] = &[
    ("restart", &[]),
    ("degenerate", &["--join", "degenerate"]),
    ("compress", &["--compress"]),
    ("degenerate_compress", &["--join", "degenerate", "--compress"]),
];

/// A torus of 24 x 10 quads (480 triangles) with UVs as OBJ text, its faces shuffled.
fn torus_obj() -> String {
    use std::f64::consts::TAU;
    let (n, m) = (24usize, 10usize);
    let mut text = String::new();
    for i in 0..=n {
        for j in 0..=m {
            let (u, v) = (i as f64 / n as f64, j as f64 / m as f64);
            // The seams' vertices (their own UVs) at the very same positions as the
            // first row's and column's: the surface closed, without cracks or overlaps.
            let (a, b) = ((i % n) as f64 / n as f64 * TAU, (j % m) as f64 / m as f64 * TAU);
            let r = 1.0 + 0.35 * b.cos();
            text += &format!("v {:.6} {:.6} {:.6}\nvt {u:.6} {v:.6}\n", r * a.cos(), r * a.sin(), 0.35 * b.sin());
        }
    }
    let at = |i: usize, j: usize| i * (m + 1) + j + 1;
    let mut faces = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (p, q, r, s) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            faces.push([p, q, r]);
            faces.push([p, r, s]);
        }
    }
    stripkit_testkit::XorShift64(0x7031).shuffle(&mut faces);
    for [a, b, c] in faces {
        text += &format!("f {a}/{a} {b}/{b} {c}/{c}\n");
    }
    text
}

/// Runs gltfpack on `input` with `flags` into `out`; `Err` says why it cannot run here.
fn gltfpack(input: &Path, out: &Path, flags: &[&str]) -> Result<(), String> {
    let cli = repo_root().join(".ci/node_modules/gltfpack/cli.js");
    if !cli.is_file() {
        return Err("gltfpack is not installed in .ci/node_modules (.ci/run installs it)".into());
    }
    let o = Command::new("node").arg(&cli).arg("-i").arg(input).arg("-o").arg(out).args(flags).output();
    let o = o.map_err(|e| format!("cannot run node for gltfpack: {e}"))?;
    assert!(o.status.success(), "gltfpack {flags:?}: {}", String::from_utf8_lossy(&o.stderr));
    Ok(())
}

/// gltfpack's outputs and stripkit's strips of them: (reference, candidate, indices
/// read and stitched) for each strip, every file validator-clean. Empty (after printing why)
/// where gltfpack cannot run.
fn packed_pairs() -> Vec<(PathBuf, PathBuf, [u64; 2])> {
    let torus = tmp("threejs", "torus.obj");
    std::fs::write(&torus, torus_obj()).unwrap();
    let mut pairs = Vec::new();
    for (source, name, flags) in PACKED {
        let input = if *source == "torus" { torus.clone() } else { repo_root().join("assets").join(source) };
        let packed = tmp("threejs", name);
        if let Err(why) = gltfpack(&input, &packed, flags) {
            eprintln!("skip (gltfpack outputs): {why}");
            return Vec::new();
        }
        for (suffix, strip_flags) in PACKED_STRIPS {
            let out = packed.with_extension(format!("{suffix}.glb"));
            let mut args = vec!["strip", packed.to_str().unwrap(), "-o", out.to_str().unwrap(), "--json"];
            args.extend(*strip_flags);
            let report = support::json(&stripkit(&args));
            assert_eq!(report["verified"], true, "{report}");
            let indices = ["indices_read", "indices_stitched"].map(|k| report[k].as_u64().unwrap());
            pairs.push((packed.clone(), out, indices));
        }
    }
    let mut files: Vec<&Path> = pairs.iter().map(|p| p.1.as_path()).collect();
    files.extend(pairs.iter().step_by(PACKED_STRIPS.len()).map(|p| p.0.as_path()));
    support::gltf_validator::validate(&files);
    pairs
}

/// Checks the reports on gltfpack's outputs: every pass 0 pixels differing, the shape
/// drawn, and the UV passes there exactly when gltfpack kept the UVs.
fn check_packed(pairs: &[(PathBuf, PathBuf, [u64; 2])], reports: &[serde_json::Value]) {
    assert_eq!(pairs.len(), reports.len());
    for ((packed, out, indices), r) in pairs.iter().zip(reports) {
        let name = out.file_name().unwrap().to_str().unwrap();
        let kv = name.contains("_kv");
        let groups = !name.contains("degenerate");
        let differing = r["differing"].as_object().unwrap();
        assert_eq!(differing.len(), (1 + kv as usize) * (1 + groups as usize), "{name}: {r}");
        // Lit pixels per material over the 3 views: the cow about 30,800, the torus
        // about 35,000.
        assert!(r["drawn"].as_u64().unwrap() / (1 + kv as u64) > 25_000, "{name}: {r}");
        for (pass, n) in differing {
            // The torus's flat normals: a strip starts some triangles at another corner,
            // and the normal three.js derives from the screen-space derivatives of the
            // interpolated position rounds differently on a few edge pixels (the source
            // OBJ with every face's corners rotated, no strips, differs on 16 pixels of
            // its 69,950). The UVs, and every pass on spot, are exact.
            let allowed = if name.contains("torus") && pass.ends_with("normals") { 40 } else { 0 };
            assert!(n.as_u64().unwrap() <= allowed, "{name}: {pass} differs: {r}");
        }
        let bytes = |p: &Path| std::fs::metadata(p).unwrap().len();
        let passes: Vec<String> = differing.iter().map(|(pass, n)| format!("{pass} {n}")).collect();
        let [read, stitched] = indices;
        eprintln!("| {name} | {} -> {} | {read} -> {stitched} | {} |", bytes(packed), bytes(out), passes.join(", "));
    }
}

#[test]
fn threejs_draws_every_output_like_the_source() {
    if let Some(why) = chromium_missing(&["three", "playwright-core"]) {
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
    let packed = packed_pairs();
    pairs.extend(packed.iter().map(|(r, c, _)| format!("{}={}", r.display(), c.display())));
    let run = Command::new("node")
        .arg(repo_root().join(".ci/threejs-pixels.mjs"))
        .args(&pairs)
        .output()
        .expect("runs node");
    let text = String::from_utf8_lossy(&run.stdout);
    eprintln!("{text}{}", String::from_utf8_lossy(&run.stderr));
    let reports: Vec<serde_json::Value> = text.lines().filter_map(|l| serde_json::from_str(l).ok()).collect();
    assert_eq!(reports.len(), FORMS.len() + packed.len(), "{text}");
    check_packed(&packed, &reports[FORMS.len()..]);
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

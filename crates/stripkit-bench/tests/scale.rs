//! `stripkit-bench scale --quick` on two procedural models (an icosphere and a torus,
//! 1x and 4x): every phase has its rows at 1 and 2 threads, the stripifiers' indices
//! are the library's (and the CLI's where its binary was built beside this test), the
//! same at both thread counts, every peak is above the mesh's own bytes, and the chart
//! is a PNG that decodes.

use std::path::{Path, PathBuf};
use std::process::Command;
use stripkit::{gen, Mesh, StripOptions};

const PHASES: [&str; 11] =
    ["read", "greedy", "cache", "cache-parts", "balanced", "batch", "single", "verify", "write-ply", "write-glb", "meshopt"];
const STRIPIFIERS: [&str; 6] = ["greedy", "cache", "cache-parts", "balanced", "batch", "single"];
const SLOW: [&str; 3] = ["balanced", "batch", "single"];

/// The CLI's binary, when `cargo test --workspace` built it beside this test's.
fn cli_binary() -> Option<PathBuf> {
    let exe = std::env::current_exe().ok()?;
    let bin = exe.parent()?.parent()?.join(format!("stripkit{}", std::env::consts::EXE_SUFFIX));
    bin.is_file().then_some(bin)
}

fn cli_indices(cli: &Path, mesh: &Path, algo: &str, dir: &Path) -> usize {
    let out = Command::new(cli).arg("strip").arg(mesh).args(["--algo", algo, "--json", "-o"]).arg(dir.join("cli.ply")).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    report["indices_restart"].as_u64().unwrap() as usize
}

#[test]
fn quick_scale_run_measures_every_phase_and_matches_the_library() {
    let dir = stripkit_testkit::scratch_dir("bench-scale-test");
    let ico = gen::icosphere(3);
    let torus = gen::torus(24, 12, 1.0, 0.3);
    let (ico_path, torus_path) = (dir.join("ico.ply"), dir.join("torus.ply"));
    stripkit::io::write(&ico_path, &ico, None).unwrap();
    stripkit::io::write(&torus_path, &torus, None).unwrap();
    let (png, json) = (dir.join("scale.png"), dir.join("rows.json"));
    let out = Command::new(env!("CARGO_BIN_EXE_stripkit-bench"))
        .args(["scale", "--quick", "--threads", "2", "--slow-limit", "2000", "--base"])
        .arg(&ico_path)
        .arg("--held-back")
        .arg(&torus_path)
        .arg("--out")
        .arg(&png)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let table = String::from_utf8(out.stdout).unwrap();
    let rows: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let rows = rows.as_array().unwrap();

    let cli = cli_binary();
    if cli.is_none() {
        eprintln!("the CLI's binary is not built beside this test: indices compared with the library only");
    }
    let models: [(&str, &Mesh); 2] = [("ico", &ico), ("torus", &torus)];
    let mut expected_rows = 0;
    for (name, base) in models {
        for level in 0..=1u32 {
            let mesh = gen::subdivide_loop(base, level).unwrap();
            let label = format!("{name} {}x", 4usize.pow(level));
            let triangles = mesh.triangle_count();
            let mesh_path = dir.join("level.ply");
            stripkit::io::write(&mesh_path, &mesh, None).unwrap();
            for phase in PHASES {
                let counts: &[u64] = if phase == "meshopt" { &[1] } else { &[1, 2] };
                if SLOW.contains(&phase) && triangles > 2000 {
                    assert!(!rows.iter().any(|r| r["mesh"] == label.as_str() && r["phase"] == phase), "{label} {phase} skipped");
                    continue;
                }
                let mut indices = Vec::new();
                for &t in counts {
                    let row = rows
                        .iter()
                        .find(|r| r["mesh"] == label.as_str() && r["phase"] == phase && r["threads"] == t)
                        .unwrap_or_else(|| panic!("no row for {label} {phase} at {t} threads"));
                    expected_rows += 1;
                    let rep = &row["report"];
                    assert_eq!(rep["triangles"].as_u64(), Some(triangles as u64), "{label} {phase}");
                    let peak = rep["peak_bytes"].as_u64().unwrap();
                    let mesh_bytes = rep["mesh_bytes"].as_u64().unwrap();
                    assert_eq!(mesh_bytes, 12 * (mesh.vertex_count() + triangles) as u64);
                    assert!(peak > mesh_bytes, "{label} {phase}: peak {peak} <= mesh {mesh_bytes}");
                    let before = rep["rss_before"].as_u64().unwrap();
                    // `before` is read just ahead of the peak's reset, and pages freed in
                    // between (a few KiB) leave the reset peak slightly below it.
                    assert!(before > 0 && peak + (1 << 20) >= before, "{label} {phase}: {before} before, {peak} peak");
                    if phase != "read" {
                        // The phase's inputs (the mesh at least) were resident before it.
                        assert!(before > mesh_bytes, "{label} {phase}: {before} before <= mesh {mesh_bytes}");
                    }
                    assert!(rep["ns"].as_u64().unwrap() > 0);
                    indices.push(rep["indices"].as_u64());
                    assert!(table.contains(&format!("| {label} | {triangles} | ")), "table has {label}");
                }
                if STRIPIFIERS.contains(&phase) {
                    assert!(indices.windows(2).all(|w| w[0] == w[1]), "{label} {phase}: same strips at 1 and 2 threads");
                    let ours = indices[0].unwrap() as usize;
                    let options = if phase == "cache-parts" {
                        StripOptions::default().algorithm(stripkit::Algorithm::cache()).partition_above(262_144)
                    } else {
                        StripOptions::default().algorithm(phase.parse().unwrap())
                    };
                    let strips = stripkit::stripify(&mesh, &options).unwrap();
                    assert!(strips.figures.verified);
                    assert_eq!(ours, strips.figures.indices_restart, "{label} {phase}: the library's indices");
                    if let (Some(cli), "greedy" | "cache") = (&cli, phase) {
                        assert_eq!(ours, cli_indices(cli, &mesh_path, phase, &dir), "{label} {phase}: the CLI's indices");
                    }
                    // Strips cost at least one index per triangle, at most three.
                    assert!(ours > triangles && ours < 3 * triangles, "{label} {phase}: {ours}");
                } else if phase == "meshopt" {
                    let n = indices[0].expect("meshoptimizer's indices") as usize;
                    assert!(n > triangles && n < 3 * triangles);
                } else {
                    assert!(indices.iter().all(Option::is_none));
                }
            }
        }
    }
    assert_eq!(rows.len(), expected_rows, "no other rows");
    let decoder = png::Decoder::new(std::io::Cursor::new(std::fs::read(&png).unwrap()));
    let reader = decoder.read_info().unwrap();
    assert_eq!((reader.info().width, reader.info().height), (1100, 700));
    std::fs::remove_dir_all(&dir).ok();
}

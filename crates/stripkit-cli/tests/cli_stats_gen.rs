//! `stripkit stats` and `stripkit gen` through the built binary.

mod support;

use std::path::PathBuf;
use std::process::Command;

fn stripkit() -> Command {
    Command::new(env!("CARGO_BIN_EXE_stripkit"))
}

fn temp_dir(name: &str) -> PathBuf {
    stripkit_testkit::scratch_dir(&format!("cli-{name}"))
}

fn stats_json(path: &std::path::Path) -> serde_json::Value {
    let out = stripkit().arg("stats").arg(path).arg("--json").output().unwrap();
    assert!(out.status.success(), "stats failed: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("one JSON object on stdout")
}

fn gen_ok(args: &[&str], output: &std::path::Path) -> String {
    let out = stripkit().arg("gen").args(args).arg("-o").arg(output).output().unwrap();
    assert!(out.status.success(), "gen {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn gen_then_stats_reports_the_known_figures() {
    let dir = temp_dir("gen");
    let ico = dir.join("ico.obj");
    let line = gen_ok(&["icosphere", "2"], &ico);
    assert!(line.contains("162 vertices") && line.contains("320 faces"), "{line}");
    let j = stats_json(&ico);
    assert_eq!(j["vertices"], 162);
    assert_eq!(j["faces"], 320);
    assert_eq!(j["triangles"], 320);
    assert_eq!(j["quads"], 0);
    assert_eq!(j["polygons"], 0);
    assert_eq!(j["unreferenced_vertices"], 0);
    assert_eq!(j["boundary_edges"], 0);
    assert_eq!(j["boundary_loops"], 0);
    assert_eq!(j["nonmanifold_edges"], 0);
    assert_eq!(j["nonmanifold_vertices"], 0);
    assert_eq!(j["components"], 1);
    assert_eq!(j["euler_characteristic"], 2);
    assert_eq!(j["degenerate_faces"], 0);
    assert_eq!(j["duplicate_faces"], 0);
    assert_eq!(j["consistently_oriented"], true);

    let grid = dir.join("grid.off");
    gen_ok(&["grid", "7", "3", "--quads"], &grid);
    let j = stats_json(&grid);
    assert_eq!((j["quads"].as_u64(), j["boundary_edges"].as_u64()), (Some(21), Some(20)));
    assert_eq!(j["boundary_loops"], 1);

    let torus = dir.join("torus.obj");
    gen_ok(&["torus", "--major", "9", "--minor", "5"], &torus);
    let j = stats_json(&torus);
    assert_eq!((j["triangles"].as_u64(), j["euler_characteristic"].as_i64()), (Some(90), Some(0)));

    let torus_arg = torus.to_str().unwrap();
    let sub = dir.join("sub.obj");
    gen_ok(&["subdivide", torus_arg, "--scheme", "loop", "--levels", "2"], &sub);
    let j = stats_json(&sub);
    assert_eq!((j["triangles"].as_u64(), j["euler_characteristic"].as_i64()), (Some(90 * 16), Some(0)));
    assert_eq!(j["consistently_oriented"], true);

    let cc = dir.join("cc.obj");
    gen_ok(&["subdivide", torus_arg, "--scheme", "catmull-clark"], &cc);
    assert_eq!(stats_json(&cc)["quads"], 270);

    let cube = dir.join("cube.obj");
    gen_ok(&["cube", "--levels", "2"], &cube);
    let j = stats_json(&cube);
    assert_eq!((j["quads"].as_u64(), j["euler_characteristic"].as_i64()), (Some(96), Some(2)));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_input_exits_with_status_two_and_says_why() {
    let out = stripkit().args(["stats", "/nonexistent/mesh.obj"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("/nonexistent/mesh.obj"));

    let dir = temp_dir("bad");
    let broken = dir.join("broken.obj");
    std::fs::write(&broken, "v 0 0 0\nv 1 0 0\nf 1 2 9\n").unwrap();
    let out = stripkit().arg("stats").arg(&broken).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(!String::from_utf8_lossy(&out.stderr).is_empty());

    // Loop subdivision of a quad mesh is refused, not attempted.
    let quads = dir.join("q.obj");
    gen_ok(&["grid", "2", "2", "--quads"], &quads);
    let out = stripkit()
        .args(["gen", "subdivide"])
        .arg(&quads)
        .args(["--scheme", "loop", "-o"])
        .arg(dir.join("x.obj"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("triangle"));

    let out = stripkit().args(["gen", "icosphere", "40", "-o"]).arg(dir.join("big.obj")).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let out = stripkit().args(["gen", "torus", "--major", "2", "-o"]).arg(dir.join("t.obj")).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let out = stripkit().args(["gen", "grid", "100000", "100000", "-o"]).arg(dir.join("g.obj")).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let out = stripkit().args(["gen", "grid", "0", "3", "-o"]).arg(dir.join("g.obj")).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let out = stripkit().args(["gen", "grid", "2", "2", "-o"]).arg(dir.join("g.unknown")).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("g.unknown"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn stats_on_the_models_matches_the_readme() {
    let Some(dir) = support::models_dir() else { return };
    let j = stats_json(&dir.join("bunny.obj"));
    assert_eq!(j["vertices"], 35947);
    assert_eq!(j["faces"], 69451);
    assert_eq!(j["boundary_edges"], 223);
    assert_eq!(j["boundary_loops"], 5);
    assert_eq!(j["unreferenced_vertices"], 1113);
    assert_eq!(j["euler_characteristic"], -3);
    let out = stripkit().arg("stats").arg(dir.join("cow.obj")).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("non-manifold vertices 1"), "{text}");
}

#[test]
fn help_explains_the_million_triangle_command() {
    let out = stripkit().args(["gen", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&out.stdout);
    assert!(help.contains("--scheme loop --levels 2"), "{help}");
    let out = stripkit().args(["gen", "subdivide", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&out.stdout);
    assert!(help.contains("catmull-clark") && help.contains("--levels"), "{help}");
}

#[test]
fn gen_prints_json_and_qstrip_refuses_a_mesh_without_quads() {
    let out = support::tmp("gen_json", "ico.obj");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_stripkit"))
        .args(["gen", "icosphere", "2", "-o", out.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!((j["triangles"].as_u64(), j["vertices"].as_u64()), (Some(320), Some(162)));
    // --algo qstrip on triangles would silently run greedy: refused, nothing written.
    let strips = support::tmp("gen_json", "never.ply");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_stripkit"))
        .args(["strip", out.to_str().unwrap(), "-o", strips.to_str().unwrap(), "--algo", "qstrip"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("has none"));
    assert!(!strips.exists());
}

#[test]
fn ascii_ply_from_every_writer_and_refused_elsewhere() {
    let run = |args: &[&str]| std::process::Command::new(env!("CARGO_BIN_EXE_stripkit")).args(args).output().unwrap();
    let dir = |name: &str| support::tmp("ascii", name);
    let (ico, strips, simple, model, level) =
        (dir("ico.ply"), dir("strips.ply"), dir("simple.ply"), dir("ico.sets"), dir("level.ply"));
    let p = |x: &std::path::PathBuf| x.to_str().unwrap().to_string();
    for args in [
        vec!["gen".to_string(), "icosphere".into(), "2".into(), "-o".into(), p(&ico), "--ascii".into()],
        vec!["strip".into(), p(&ico), "-o".into(), p(&strips), "--ascii".into()],
        vec!["simplify".into(), p(&ico), "--ratio".into(), "0.5".into(), "-o".into(), p(&simple), "--ascii".into()],
        vec!["lod".into(), "build".into(), p(&ico), "-o".into(), p(&model)],
        vec!["lod".into(), "extract".into(), p(&model), "--ratio".into(), "0.5".into(), "-o".into(), p(&level), "--ascii".into()],
    ] {
        let args: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
        let o = run(&args);
        assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
    }
    for (file, triangles) in [(&ico, 320), (&strips, 320), (&simple, 160), (&level, 160)] {
        let text = std::fs::read(file).unwrap();
        assert!(text.starts_with(b"ply\nformat ascii 1.0\n"), "{}", file.display());
        assert_eq!(stripkit::io::read(file).unwrap().triangle_count(), triangles, "{}", file.display());
    }
    // Where it would do nothing: exit 2, nothing written.
    let glb = dir("never.glb");
    for args in [
        vec!["strip", ico.to_str().unwrap(), "-o", glb.to_str().unwrap(), "--ascii"],
        vec!["gen", "icosphere", "1", "-o", glb.to_str().unwrap(), "--ascii"],
        vec!["simplify", ico.to_str().unwrap(), "--ratio", "0.5", "-o", glb.to_str().unwrap(), "--ascii"],
    ] {
        assert_eq!(run(&args).status.code(), Some(2), "{args:?}");
    }
    assert!(!glb.exists());
}

#[test]
fn meshes_read_from_standard_input_with_format() {
    use std::io::Write;
    use std::process::Stdio;
    let feed = |args: &[&str], data: &[u8]| {
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_stripkit"))
            .args(args)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // A command that fails early may not read its input: a closed pipe is fine.
        let _ = child.stdin.take().unwrap().write_all(data);
        child.wait_with_output().unwrap()
    };
    let obj = support::tmp("stdin", "ico.obj");
    let mesh = stripkit::gen::icosphere(2);
    stripkit::io::write(&obj, &mesh, None).unwrap();
    let bytes = std::fs::read(&obj).unwrap();
    let out = support::tmp("stdin", "ico.ply");
    let o = feed(&["strip", "-", "--format", "obj", "-o", out.to_str().unwrap(), "--json"], &bytes);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["triangles"], 320);
    assert_eq!(stripkit::io::read(&out).unwrap().triangle_count(), 320);
    // The same mesh as binary PLY through stdin, for stats.
    let ply = std::fs::read(&out).unwrap();
    let o = feed(&["stats", "-", "--format", "ply", "--json"], &ply);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // Without --format, with --format on a file, with gzip data: exit 2.
    for (args, data) in [
        (vec!["stats", "-"], bytes.clone()),
        (vec!["stats", obj.to_str().unwrap(), "--format", "obj"], Vec::new()),
        (vec!["stats", "-", "--format", "obj"], vec![0x1f, 0x8b, 8, 0, 0, 0]),
        (vec!["stats", "-", "--format", "xyz"], Vec::new()),
    ] {
        let o = feed(&args, &data);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
    }
}

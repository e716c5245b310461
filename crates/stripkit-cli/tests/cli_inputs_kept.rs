//! No command writes over one of its own inputs, in any spelling (the same path, a
//! relative one, `..`, a symbolic or a hard link): refused before any work, exit 2,
//! naming both; every output's extension checked against what is written there; a
//! closed standard output is an error for data, never success (issue 30, classes 5
//! and 6).

mod support;

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use support::stripkit;

/// A fresh, empty folder for one test.
fn fresh_dir(name: &str) -> PathBuf {
    stripkit_testkit::fresh_scratch_dir(&format!("cli-kept-{name}"))
}

/// A small torus written to `dir/name` (format by extension); returns its path and bytes.
fn mesh_file(dir: &Path, name: &str) -> (PathBuf, Vec<u8>) {
    let path = dir.join(name);
    support::write_mesh(&path, &stripkit::gen::torus(12, 6, 1.0, 0.3));
    let bytes = std::fs::read(&path).unwrap();
    (path, bytes)
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Exit 2, a message naming every one of `names`, no panic.
fn refused(out: &Output, names: &[&str], args: &[&str]) -> String {
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    for name in names {
        assert!(err.contains(name), "{args:?}: the message names {name}: {err}");
    }
    err
}

/// Runs `args` in `dir` (so that relative spellings resolve there).
fn stripkit_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stripkit")).current_dir(dir).args(args).output().expect("runs")
}

#[test]
fn no_command_writes_over_its_input_in_any_spelling() {
    let dir = fresh_dir("spellings");
    std::fs::create_dir(dir.join("sub")).unwrap();
    let (input, before) = mesh_file(&dir, "s.obj");
    std::os::unix::fs::symlink("s.obj", dir.join("link.obj")).unwrap();
    std::fs::hard_link(&input, dir.join("hard.obj")).unwrap();
    let spellings = ["s.obj", "./s.obj", "sub/../s.obj", "link.obj", "hard.obj"];
    let full = s(&input).to_string();
    for out in spellings.iter().copied().chain([full.as_str()]) {
        let cases: Vec<Vec<&str>> = vec![
            vec!["simplify", "s.obj", "--ratio", "0.5", "-o", out],
            vec!["simplify", "s.obj", "--ratio", "0.5", "-o", "o.obj", "--sequence", out],
            vec!["strip", "s.obj", "-o", out],
            vec!["gen", "subdivide", "s.obj", "--scheme", "loop", "-o", out],
        ];
        for args in cases {
            let o = stripkit_in(&dir, &args);
            // --sequence s.obj is refused for its mesh name first; the others name both files.
            let names: &[&str] = if args.contains(&"--sequence") { &["--sequence", out] } else { &[out, "s.obj"] };
            refused(&o, names, &args);
            assert_eq!(std::fs::read(&input).unwrap(), before, "{args:?}: the input is kept");
        }
    }
    // An output named as no input is still written (the check does not refuse good runs).
    let o = stripkit_in(&dir, &["simplify", "s.obj", "--ratio", "0.5", "-o", "o.obj", "--sequence", "o.bin"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(dir.join("o.obj").exists() && dir.join("o.bin").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn outputs_that_are_inputs_are_refused_for_every_command() {
    let dir = fresh_dir("commands");
    let (input, before) = mesh_file(&dir, "s.ply");
    let (other, _) = mesh_file(&dir, "t.ply");
    let model = dir.join("s.sets");
    let o = stripkit(&["lod", "build", s(&input), "-o", s(&model), "--check", "off"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let model_before = std::fs::read(&model).unwrap();
    let link = dir.join("model-link.sets");
    std::os::unix::fs::symlink(&model, &link).unwrap();
    let graph = dir.join("g.txt");
    std::fs::write(&graph, "p edge 2 1\ne 1 2 5\n").unwrap();
    let graph_before = std::fs::read(&graph).unwrap();
    // A model named .json (extract reads it by its header) is an input extract could write.
    let json_model = dir.join("m.json");
    std::fs::copy(&model, &json_model).unwrap();
    let cases: Vec<(Vec<&str>, &Path, &[u8])> = vec![
        (vec!["lod", "build", s(&model), "-o", s(&link)], &model, &model_before),
        (vec!["lod", "extract", s(&json_model), "--ratio", "0.5", "-o", s(&json_model)], &json_model, &model_before),
        (vec!["match", s(&graph), "-o", s(&graph)], &graph, &graph_before),
    ];
    for (args, kept, content) in cases {
        let o = stripkit(&args);
        refused(&o, &["same file"], &args);
        assert_eq!(std::fs::read(kept).unwrap(), content, "{args:?}: the input is kept");
    }
    // render's --morph is an input too.
    let png_named_input = dir.join("m.png");
    std::fs::copy(&other, &png_named_input).unwrap();
    let kept_png = std::fs::read(&png_named_input).unwrap();
    let args = ["render", s(&input), "-o", s(&png_named_input), "--morph", s(&png_named_input)];
    let o = stripkit(&args);
    refused(&o, &["--morph", "m.png"], &args);
    assert_eq!(std::fs::read(&png_named_input).unwrap(), kept_png);
    let args = ["cull", s(&input), "--bar", s(&input)];
    refused(&stripkit(&args), &["--bar", ".svg"], &args);
    assert_eq!(std::fs::read(&input).unwrap(), before);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_folder_run_into_its_own_folder_keeps_its_inputs() {
    let dir = fresh_dir("folder");
    let (a, a_before) = mesh_file(&dir, "a.obj");
    let (b, b_before) = mesh_file(&dir, "b.ply");
    for args in [
        vec!["simplify", s(&dir), "--ratio", "0.5", "-o", s(&dir)],
        vec!["strip", s(&dir), "-o", s(&dir), "--output-format", "ply"],
    ] {
        let o = stripkit(&args);
        refused(&o, &["same file"], &args);
        assert_eq!(std::fs::read(&a).unwrap(), a_before, "{args:?}");
        assert_eq!(std::fs::read(&b).unwrap(), b_before, "{args:?}");
    }
    // Into another folder: written as before.
    let out = dir.join("out");
    let o = stripkit(&["simplify", s(&dir), "--ratio", "0.5", "-o", s(&out)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.join("a.obj").exists() && out.join("b.ply").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn output_extensions_are_checked_against_what_is_written() {
    let dir = fresh_dir("extensions");
    let (input, before) = mesh_file(&dir, "x.obj");
    let frames = dir.join("frames");
    std::fs::create_dir(&frames).unwrap();
    mesh_file(&frames, "f0.obj");
    let y = dir.join("y.obj");
    let cases: Vec<(Vec<&str>, &[&str])> = vec![
        (vec!["lod", "build", s(&input), "-o", s(&y)], &["y.obj", ".sets"]),
        (vec!["lod", "build", s(&input), "-o", s(&input)], &["x.obj", ".sets"]),
        (vec!["lod", "build-seq", s(&frames), "-o", s(&y)], &["y.obj", ".lodseq"]),
        (vec!["simplify", s(&input), "--ratio", "0.5", "-o", "o.ply", "--sequence", s(&y)], &["--sequence", ".bin"]),
        (vec!["cull", s(&input), "--bar", s(&y)], &["--bar", ".svg"]),
        (vec!["match", "--dual", s(&input), "-o", s(&y)], &["y.obj", ".txt"]),
    ];
    for (args, names) in cases {
        let o = stripkit(&args);
        refused(&o, names, &args);
        assert!(!y.exists(), "{args:?}: nothing written");
        assert_eq!(std::fs::read(&input).unwrap(), before);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Runs `args` with standard output a pipe whose reading end is closed before the
/// command starts: a shell waits for one line on its standard input, which the test
/// sends only once it has dropped the reading end, then becomes `stripkit`.
fn into_closed_pipe(args: &[&str]) -> Output {
    use std::io::Write;
    let mut child = Command::new("sh")
        .arg("-c")
        .arg("read _ && exec \"$0\" \"$@\"")
        .arg(env!("CARGO_BIN_EXE_stripkit"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("runs");
    drop(child.stdout.take()); // the reader goes away before anything is written
    let mut stdin = child.stdin.take().unwrap();
    stdin.write_all(b"go\n").unwrap();
    drop(stdin);
    child.wait_with_output().expect("waits")
}

#[test]
fn data_to_a_closed_standard_output_is_an_error() {
    let dir = fresh_dir("pipe");
    let (input, _) = mesh_file(&dir, "x.obj");
    for args in [
        vec!["gen", "grid", "300", "300", "-o", "-", "--output-format", "obj"],
        vec!["strip", s(&input), "-o", "-", "--output-format", "ply"],
        vec!["simplify", s(&input), "--ratio", "0.5", "-o", "-", "--output-format", "obj"],
        vec!["completions", "bash"],
    ] {
        // A small output fits in the pipe's buffer, so it can be taken while another
        // test thread's freshly forked child still holds a copy of the reading end
        // (until it execs): seen once under load for `completions bash`. A real
        // defect fails every try; a ghost reader only the odd one.
        let mut o = into_closed_pipe(&args);
        for _ in 0..4 {
            if !o.status.success() {
                break;
            }
            o = into_closed_pipe(&args);
        }
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(matches!(o.status.code(), Some(1 | 2)), "{args:?}: {:?} {err}", o.status);
        assert!(err.contains("standard output closed"), "{args:?}: {err}");
    }
    // A report after the file was written stays success: the output is complete.
    let out = dir.join("g.obj");
    let o = into_closed_pipe(&["gen", "grid", "4", "4", "-o", s(&out)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

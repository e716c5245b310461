//! Outputs are replaced atomically: never half-written, never one over another
//! (issue 16, part 2).

mod support;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use support::stripkit;

/// A fresh, empty folder for one test.
fn fresh_dir(name: &str) -> PathBuf {
    stripkit_testkit::fresh_scratch_dir(&format!("cli-atomic-{name}"))
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

/// `.NAME.tmp-PID-N`, the temporary name of stripkit's atomic writes (`stripkit::io::write_encoded`).
fn is_temporary_of(file: &str, name: &str) -> bool {
    let Some(rest) = file.strip_prefix(&format!(".{name}.tmp-")) else { return false };
    let Some((pid, n)) = rest.split_once('-') else { return false };
    !pid.is_empty() && !n.is_empty() && pid.bytes().all(|b| b.is_ascii_digit()) && n.bytes().all(|b| b.is_ascii_digit())
}

/// `stripkit simplify INPUT --ratio 0.5 -o OUT --sequence SEQ`.
fn simplify_to(input: &Path, out: &Path, seq: &Path) -> std::process::Output {
    stripkit(&[
        "simplify",
        input.to_str().unwrap(),
        "--ratio",
        "0.5",
        "-o",
        out.to_str().unwrap(),
        "--sequence",
        seq.to_str().unwrap(),
    ])
}

fn gen_icosphere(level: &str, out: &Path) {
    let o = stripkit(&["gen", "icosphere", level, "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn simplify_refuses_a_sequence_over_its_own_output_before_any_work() {
    let dir = fresh_dir("same");
    let input = dir.join("in.obj");
    gen_icosphere("2", &input);
    let out = dir.join("out.obj");
    std::fs::write(&out, b"the user's precious file").unwrap();
    std::fs::create_dir(dir.join("sub")).unwrap();
    let spellings = [out.clone(), dir.join(".").join("out.obj"), dir.join("sub").join("..").join("out.obj")];
    for seq in &spellings {
        let o = simplify_to(&input, &out, seq);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{}: {err}", seq.display());
        assert!(err.contains("-o") && err.contains("--sequence"), "{err}");
        assert_eq!(std::fs::read(&out).unwrap(), b"the user's precious file");
    }
    // A file that does not exist yet, spelled two ways: refused, and still absent.
    let new = dir.join("new.obj");
    let o = simplify_to(&input, &new, &dir.join(".").join("new.obj"));
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!new.exists());
    assert_eq!(names(&dir), ["in.obj", "out.obj", "sub"]);
    // The input as the output is refused too, before any work (issue 30: no command
    // writes over its own input; tests/cli_inputs_kept.rs covers every spelling).
    let before = std::fs::read(&input).unwrap();
    let o = stripkit(&["simplify", input.to_str().unwrap(), "--ratio", "0.5", "-o", input.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read(&input).unwrap(), before);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_failed_sequence_write_leaves_the_previous_mesh_output() {
    let dir = fresh_dir("seqfail");
    let input = dir.join("in.obj");
    gen_icosphere("2", &input);
    let out = dir.join("out.obj");
    std::fs::write(&out, b"old mesh").unwrap();
    // A sequence that cannot be written: its folder is missing, or it is a folder.
    std::fs::create_dir(dir.join("seq.bin")).unwrap();
    for seq in [dir.join("missing").join("seq.bin"), dir.join("seq.bin")] {
        let o = simplify_to(&input, &out, &seq);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(seq.to_str().unwrap()), "{err}");
        assert_eq!(std::fs::read(&out).unwrap(), b"old mesh", "{}", seq.display());
        assert_eq!(names(&dir), ["in.obj", "out.obj", "seq.bin"], "{}", seq.display());
    }
    // And when both can be written, both are.
    let seq = dir.join("seq.json");
    let o = simplify_to(&input, &out, &seq);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_ne!(std::fs::read(&out).unwrap(), b"old mesh");
    assert!(std::fs::read(&seq).unwrap().starts_with(b"{"));
    assert_eq!(names(&dir), ["in.obj", "out.obj", "seq.bin", "seq.json"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn other_writers_leave_no_temporary_file_and_fail_cleanly() {
    let dir = fresh_dir("writers");
    let mesh = dir.join("m.ply.gz");
    gen_icosphere("1", &mesh);
    let strips = dir.join("s.json");
    let o = stripkit(&["strip", mesh.to_str().unwrap(), "-o", strips.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let matched = dir.join("m.txt");
    let o = stripkit(&["match", "--dual", mesh.to_str().unwrap(), "-o", matched.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(names(&dir), ["m.ply.gz", "m.txt", "s.json"]);
    // A folder where the output should go: refused, the folder kept, nothing left over.
    let blocked = dir.join("blocked.obj");
    std::fs::create_dir(&blocked).unwrap();
    let o = stripkit(&["gen", "icosphere", "1", "-o", blocked.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains(blocked.to_str().unwrap()));
    assert!(blocked.is_dir());
    assert_eq!(names(&dir), ["blocked.obj", "m.ply.gz", "m.txt", "s.json"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A `gen` killed with SIGKILL at many moments of its run: the destination is always
/// either the old file byte for byte or the complete new one; anything else left in
/// the folder is a temporary file by its name.
#[test]
fn a_writer_killed_mid_write_never_leaves_a_partial_destination() {
    const LEVEL: &str = "7"; // 327,680 triangles, an OBJ of about 15 MB
    let dir = fresh_dir("kill");
    let reference_dir = fresh_dir("kill-reference");
    let reference = reference_dir.join("dest.obj");
    let started = Instant::now();
    let o = stripkit(&["gen", "icosphere", LEVEL, "-o", reference.to_str().unwrap()]);
    let natural = started.elapsed();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let new_bytes = std::fs::read(&reference).unwrap();
    let stats = support::json(&stripkit(&["stats", reference.to_str().unwrap(), "--json"]));
    assert_eq!(stats["faces"], 20 * 4u64.pow(7));
    // "... in B ms (+W ms to write)": aim half of the kills at the writing itself.
    let line = String::from_utf8_lossy(&o.stdout).into_owned();
    let ms = |after: &str| -> f64 {
        let rest = &line[line.rfind(after).unwrap_or_else(|| panic!("{line}")) + after.len()..];
        rest.split_whitespace().next().unwrap().parse().unwrap_or_else(|_| panic!("{line}"))
    };
    let (build, write) = (ms(" in "), ms("(+"));
    let writing_from = natural.as_secs_f64() * 1e3 - write;

    let dest = dir.join("dest.obj");
    let old_bytes = b"# a complete, older OBJ\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec();
    // Kills at fixed moments: a few over the whole run, more over the encoding and writing.
    let mut rounds: Vec<Kill> = (0..8).map(|i| Kill::After(natural.as_secs_f64() * 1e3 * i as f64 / 8.0)).collect();
    rounds.extend((0..16).map(|i| Kill::After(writing_from + (write + 20.0) * i as f64 / 16.0)));
    // And kills at the first sign of writing (a new name in the folder, or the
    // destination's size changing), then a little later: these hit the writing itself
    // whatever the machine's speed.
    rounds.extend([0.0, 0.0, 0.5, 1.0, 2.0, 3.0, 5.0, 8.0, 12.0, 20.0].map(Kill::OnChangeThen));
    let (mut killed_running, mut changes_seen, mut old_seen, mut new_seen, mut temporaries) = (0, 0, 0, 0, 0);
    for (round, kill) in rounds.iter().enumerate() {
        // Most rounds start from the old file, some from no file at all.
        let fresh = matches!(kill, Kill::After(_)) && round % 2 == 1;
        if fresh {
            let _ = std::fs::remove_file(&dest);
        } else {
            std::fs::write(&dest, &old_bytes).unwrap();
        }
        let mut child = Command::new(env!("CARGO_BIN_EXE_stripkit"))
            .args(["gen", "icosphere", LEVEL, "-o", dest.to_str().unwrap()])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        match *kill {
            Kill::After(ms) => std::thread::sleep(Duration::from_secs_f64(ms.max(0.0) / 1e3)),
            Kill::OnChangeThen(ms) => loop {
                if child.try_wait().unwrap().is_some() {
                    break;
                }
                let changed = names(&dir) != ["dest.obj"]
                    || std::fs::metadata(&dest).map_or(true, |m| m.len() != old_bytes.len() as u64);
                if changed {
                    changes_seen += 1;
                    std::thread::sleep(Duration::from_secs_f64(ms / 1e3));
                    break;
                }
            },
        }
        if child.try_wait().unwrap().is_none() {
            killed_running += 1;
        }
        let _ = child.kill(); // SIGKILL on Unix
        child.wait().unwrap();
        match std::fs::read(&dest) {
            Ok(bytes) if bytes == old_bytes => old_seen += 1,
            Ok(bytes) if bytes == new_bytes => new_seen += 1,
            Ok(bytes) => panic!(
                "{kill:?}: {} holds {} bytes, neither the old {} nor the new {}",
                dest.display(),
                bytes.len(),
                old_bytes.len(),
                new_bytes.len()
            ),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound && fresh => {}
            Err(e) => panic!("{kill:?}: {}: {e}", dest.display()),
        }
        for name in names(&dir) {
            if name != "dest.obj" {
                assert!(is_temporary_of(&name, "dest.obj"), "{kill:?}: left {name}");
                temporaries += 1;
                std::fs::remove_file(dir.join(&name)).unwrap();
            }
        }
    }
    eprintln!(
        "natural run {:.0} ms (build {build:.0}, write {write:.0}); {} kills: {killed_running} while running, \
         {changes_seen} after the first sign of writing, {old_seen} left the old file, {new_seen} the new one, \
         {temporaries} left a temporary file",
        natural.as_secs_f64() * 1e3,
        rounds.len()
    );
    assert!(changes_seen > 0, "no kill came after the writing started: the test tested nothing");
    assert!(killed_running > 0, "every kill came after the end: the test tested nothing");
    std::fs::remove_dir_all(&dir).unwrap();
    std::fs::remove_dir_all(&reference_dir).unwrap();
}

/// When a round of the kill test sends SIGKILL.
#[derive(Clone, Copy, Debug)]
enum Kill {
    /// This many milliseconds after the start.
    After(f64),
    /// This many milliseconds after the first change in the destination's folder.
    OnChangeThen(f64),
}

/// Runs `stripkit args` with a file-size limit of `kib` KiB and SIGXFSZ ignored, so a
/// write past it fails with "File too large" the way a full disk fails with "No space
/// left": the error surfaces mid-write.
#[cfg(unix)]
fn stripkit_with_file_limit(kib: u32, args: &[&str]) -> std::process::Output {
    Command::new("bash")
        .arg("-c")
        .arg(format!("trap '' XFSZ; ulimit -f {kib}; exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_stripkit"))
        .args(args)
        .output()
        .expect("runs bash")
}

/// A disk that fills up mid-write (simulated by a file-size limit): exit 2 naming the
/// destination, the user's old file byte for byte, no temporary file left; and with a
/// mesh and a sequence, neither old file is replaced.
#[cfg(unix)]
#[test]
fn a_disk_full_mid_write_keeps_the_old_files() {
    let dir = fresh_dir("full");
    let good = dir.join("good.ply");
    gen_icosphere("1", &good);
    let before = std::fs::read(&good).unwrap();
    // Level 6 is about 2 MB in PLY; the limit is 64 KiB.
    let o = stripkit_with_file_limit(64, &["gen", "icosphere", "6", "-o", good.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains(good.to_str().unwrap()), "{err}");
    assert_eq!(std::fs::read(&good).unwrap(), before);
    assert_eq!(names(&dir), ["good.ply"]);

    let input = dir.join("in.obj");
    gen_icosphere("5", &input);
    let out = dir.join("out.obj");
    let seq = dir.join("seq.json");
    std::fs::write(&out, b"old mesh").unwrap();
    std::fs::write(&seq, b"old sequence").unwrap();
    let o = stripkit_with_file_limit(
        64,
        &["simplify", input.to_str().unwrap(), "--ratio", "0.5", "-o", out.to_str().unwrap(), "--sequence", seq.to_str().unwrap()],
    );
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read(&out).unwrap(), b"old mesh");
    assert_eq!(std::fs::read(&seq).unwrap(), b"old sequence");
    assert_eq!(names(&dir), ["good.ply", "in.obj", "out.obj", "seq.json"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

//! `stripkit lod`: build a model (checked at every level), extract levels that match
//! `stripkit simplify`, bench it, and refuse damaged `.sets` files with exit 2.

mod support;
use support::{json, stripkit, tmp, write_mesh};

fn torus() -> std::path::PathBuf {
    let path = tmp("lod", "torus.obj");
    write_mesh(&path, &stripkit::gen::torus(32, 12, 1.0, 0.3));
    path
}

/// The mesh's triangles with every corner named by its position's bits (shared
/// `ids`), so that files numbering their vertices differently compare.
fn by_position(mesh: &stripkit::Mesh, ids: &mut std::collections::HashMap<[u32; 3], u32>) -> Vec<[u32; 3]> {
    let tris = mesh.triangulate().tris;
    tris.iter()
        .map(|t| {
            t.map(|v| {
                let next = ids.len() as u32;
                *ids.entry(mesh.positions[v as usize].map(f32::to_bits)).or_insert(next)
            })
        })
        .collect()
}

fn build(input: &std::path::Path, name: &str, extra: &[&str]) -> (std::path::PathBuf, serde_json::Value) {
    let model = tmp("lod", name);
    let mut args = vec!["lod", "build", input.to_str().unwrap(), "-o", model.to_str().unwrap(), "--json"];
    args.extend_from_slice(extra);
    let r = json(&stripkit(&args));
    (model, r)
}

#[test]
fn build_checks_every_level_and_extract_matches_simplify() {
    let input = torus();
    let (model, r) = build(&input, "torus.sets", &[]);
    assert_eq!(r["triangles"], 768);
    let levels = r["levels"].as_u64().unwrap();
    assert!(levels > 300, "{r}");
    assert_eq!(r["check"]["levels_checked"].as_u64().unwrap(), levels + 1, "every level checked");
    assert_eq!(r["bytes"].as_u64().unwrap(), std::fs::metadata(&model).unwrap().len());
    // --ratio stops where `stripkit simplify --ratio` stops: same triangles.
    for ratio in ["0.5", "0.1"] {
        let out = tmp("lod", &format!("level_{ratio}.ply"));
        let e = json(&stripkit(&[
            "lod",
            "extract",
            model.to_str().unwrap(),
            "--ratio",
            ratio,
            "-o",
            out.to_str().unwrap(),
            "--json",
        ]));
        let simplified = tmp("lod", &format!("simplified_{ratio}.obj"));
        let s = json(&stripkit(&[
            "simplify",
            input.to_str().unwrap(),
            "--ratio",
            ratio,
            "-o",
            simplified.to_str().unwrap(),
            "--json",
        ]));
        assert_eq!(e["triangles"], s["triangles_out"], "ratio {ratio}");
        assert_eq!(e["level"], s["collapses"], "ratio {ratio}");
        // Both files hold only the vertices they use (lod extract in the strips'
        // first-use order): triangles compared by their corners' positions.
        let (strips_mesh, want_mesh) = (stripkit::io::read(&out).unwrap(), stripkit::io::read(&simplified).unwrap());
        assert_eq!(strips_mesh.positions.len(), want_mesh.positions.len(), "ratio {ratio}");
        assert_eq!(e["vertices"].as_u64().unwrap() as usize, want_mesh.positions.len(), "ratio {ratio}");
        let mut ids = std::collections::HashMap::new();
        let strips = by_position(&strips_mesh, &mut ids);
        let want = by_position(&want_mesh, &mut ids);
        let v = stripkit::verify_triangles(&want, &strips);
        assert!(v.ok(), "ratio {ratio}: {v}");
    }
    // Every output format, and levels by number and by count.
    for (flag, value, name) in [
        ("--level", "0", "l0.glb"),
        ("--triangles", "100", "t100.gltf"),
        ("--level", "99999", "last.obj"),
        ("--ratio", "0.2", "r.json"),
    ] {
        let out = tmp("lod", name);
        let e = json(&stripkit(&[
            "lod",
            "extract",
            model.to_str().unwrap(),
            flag,
            value,
            "-o",
            out.to_str().unwrap(),
            "--json",
        ]));
        assert!(out.exists(), "{name}");
        match name {
            "l0.glb" => assert_eq!(e["triangles"], 768),
            "t100.gltf" => assert!(e["triangles"].as_u64().unwrap() <= 100),
            "last.obj" => assert_eq!(e["level"].as_u64().unwrap(), levels),
            _ => {
                let j: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
                assert_eq!(j["level"], e["level"]);
            }
        }
    }
}

#[test]
fn optimal_placement_and_other_stripifiers() {
    let input = torus();
    for extra in [&["--placement", "optimal"][..], &["--algo", "cache"], &["--algo", "single", "--check", "sample"]] {
        let (model, r) = build(&input, "other.sets", extra);
        assert!(r["check"]["levels_checked"].as_u64().unwrap() > 0, "{extra:?}: {r}");
        let out = tmp("lod", "other.ply");
        let o = stripkit(&["lod", "extract", model.to_str().unwrap(), "--ratio", "0.3", "-o", out.to_str().unwrap()]);
        assert!(o.status.success(), "{extra:?}: {}", String::from_utf8_lossy(&o.stderr));
    }
}

/// `--restrip`: new strips where the kept ones decay, every level checked, a
/// version-3 file that extracts like any model.
#[test]
fn restripped_models_build_check_and_extract() {
    let input = torus();
    let (model, r) = build(&input, "restrip.sets", &["--restrip", "1.5", "--check", "all"]);
    assert!(r["restripped_strips"].as_u64().unwrap() > 0, "{r}");
    assert_eq!(r["check"]["levels_checked"].as_u64().unwrap(), r["levels"].as_u64().unwrap() + 1, "{r}");
    let bytes = std::fs::read(&model).unwrap();
    assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()), 3);
    let out = tmp("lod", "restrip.ply");
    let o = stripkit(&["lod", "extract", model.to_str().unwrap(), "--ratio", "0.1", "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// The default re-strips at 1.6 indices per triangle; `--restrip off` keeps the
/// level-0 strips at every level (no new strips; a file that is not version 3).
#[test]
fn restrip_defaults_to_1_6_and_off_keeps_the_strips() {
    let input = torus();
    let (default, d) = build(&input, "default.sets", &[]);
    let (explicit, e) = build(&input, "explicit.sets", &["--restrip", "1.6"]);
    let (kept, k) = build(&input, "kept.sets", &["--restrip", "off"]);
    assert!(d["restripped_strips"].as_u64().unwrap() > 0, "{d}");
    assert_eq!(d["restripped_strips"], e["restripped_strips"]);
    assert_eq!(std::fs::read(&default).unwrap(), std::fs::read(&explicit).unwrap(), "the default is --restrip 1.6");
    assert_eq!(k["restripped_strips"].as_u64().unwrap(), 0, "{k}");
    let version = |p: &std::path::Path| u32::from_le_bytes(std::fs::read(p).unwrap()[8..12].try_into().unwrap());
    assert_eq!(version(&default), 3);
    assert_ne!(version(&kept), 3);
}

#[test]
fn bench_prints_the_papers_tests() {
    let (model, _) = build(&torus(), "bench.sets", &[]);
    let r = json(&stripkit(&["lod", "bench", model.to_str().unwrap(), "--rounds", "1", "--json"]));
    let rows = r["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 12, "6 percentages x 2 spacings");
    for row in rows {
        assert!(row["us_per_level"].as_f64().unwrap() > 0.0);
        assert!(row["levels"].as_u64().unwrap() >= 2);
    }
    let o = stripkit(&["lod", "bench", model.to_str().unwrap(), "--rounds", "1"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("exponential") && text.contains("20%"), "{text}");
}

#[test]
fn damaged_models_exit_2_and_write_nothing() {
    let (model, _) = build(&torus(), "good.sets", &[]);
    let bytes = std::fs::read(&model).unwrap();
    let out = tmp("lod", "never.ply");
    let _ = std::fs::remove_file(&out);
    let mut cases: Vec<(&str, Vec<u8>)> = vec![
        ("truncated", bytes[..bytes.len() / 2].to_vec()),
        ("empty", Vec::new()),
        ("not a model", b"solid cube\nendsolid\n".to_vec()),
    ];
    let mut flipped = bytes.clone();
    flipped[100] ^= 1;
    cases.push(("bad checksum", flipped));
    // A wrong count behind a valid checksum.
    let mut counts = bytes.clone();
    counts[8 + 4 * 6..8 + 4 * 7].copy_from_slice(&7u32.to_le_bytes());
    let n = counts.len() - 4;
    let mut crc = flate2::Crc::new();
    crc.update(&counts[..n]);
    counts[n..].copy_from_slice(&crc.sum().to_le_bytes());
    cases.push(("wrong slot count", counts));
    for (what, data) in cases {
        let bad = tmp("lod", "bad.sets");
        std::fs::write(&bad, &data).unwrap();
        for args in [
            vec!["lod", "extract", bad.to_str().unwrap(), "--level", "3", "-o", out.to_str().unwrap()],
            vec!["lod", "bench", bad.to_str().unwrap()],
        ] {
            let o = stripkit(&args);
            assert_eq!(o.status.code(), Some(2), "{what}: {}", String::from_utf8_lossy(&o.stderr));
            assert!(String::from_utf8_lossy(&o.stderr).contains("bad.sets"), "{what}: names the file");
        }
        assert!(!out.exists(), "{what}: nothing written");
    }
}

#[test]
fn misuse_exits_2() {
    let input = torus();
    let (model, _) = build(&input, "misuse.sets", &[]);
    let out = tmp("lod", "misuse.ply");
    for args in [
        vec!["lod", "extract", model.to_str().unwrap(), "-o", out.to_str().unwrap()],
        vec!["lod", "extract", model.to_str().unwrap(), "--ratio", "1.5", "-o", out.to_str().unwrap()],
        vec!["lod", "extract", model.to_str().unwrap(), "--level", "2", "--ratio", "0.5", "-o", out.to_str().unwrap()],
        vec!["lod", "extract", model.to_str().unwrap(), "--level", "2", "-o", "/tmp/x.unknown"],
        vec!["lod", "build", input.to_str().unwrap(), "-o", "/no/such/folder/x.sets"],
        vec!["lod", "build", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--refine"],
        vec!["lod", "build", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--restrip", "0.5"],
        vec!["lod", "build", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--restrip", "nan"],
    ] {
        let o = stripkit(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
    }
}

/// A torus bending over four frames, plus a reference pose, as OBJ files.
fn animation(name: &str) -> std::path::PathBuf {
    let dir = tmp("lod", name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let base = stripkit::gen::torus(24, 8, 1.0, 0.3);
    let pose = |t: f32| {
        let mut m = base.clone();
        for p in m.positions.iter_mut() {
            let (s, c) = (t * p[0]).sin_cos();
            *p = [c * p[0] - s * p[2], p[1], s * p[0] + c * p[2]];
        }
        m
    };
    for f in 0..4 {
        write_mesh(&dir.join(format!("anim-{f:02}.obj")), &pose(f as f32 * 0.4));
    }
    write_mesh(&dir.join("anim-reference.obj"), &pose(0.6));
    dir
}

#[test]
fn animations_build_extract_and_bench() {
    let dir = animation("anim");
    let model = tmp("lod", "anim.lodseq");
    let r = json(&stripkit(&[
        "lod",
        "build-seq",
        dir.to_str().unwrap(),
        "-o",
        model.to_str().unwrap(),
        "--samples",
        "500",
        "--json",
    ]));
    assert_eq!(r["frames"], 4);
    assert_eq!(r["triangles"], 384);
    assert!(r["levels_checked"].as_u64().unwrap() > 100, "{r}");
    let quality = r["quality"].as_array().unwrap();
    assert_eq!(quality.len(), 4);
    for q in quality {
        for i in 0..2 {
            assert!(q["chosen"]["hausdorff"][i].as_f64() <= q["reference"]["hausdorff"][i].as_f64(), "{q}");
        }
    }
    // A frame, a fractional frame (morphed positions), every level spec.
    for (frame, flag, value) in [("2", "--ratio", "0.3"), ("1.5", "--level", "40"), ("3", "--triangles", "50")] {
        let out = tmp("lod", &format!("anim_{frame}.ply"));
        let e = json(&stripkit(&[
            "lod",
            "extract",
            model.to_str().unwrap(),
            "--frame",
            frame,
            flag,
            value,
            "-o",
            out.to_str().unwrap(),
            "--json",
        ]));
        assert_eq!(e["frame"].as_f64().unwrap(), frame.parse::<f64>().unwrap());
        let back = stripkit::io::read(&out).unwrap();
        assert_eq!(back.triangle_count() as u64, e["triangles"].as_u64().unwrap());
    }
    // The morphed frame lies between its key frames.
    let mid = stripkit::io::read(tmp("lod", "anim_1.5.ply")).unwrap();
    let a = stripkit::io::read(dir.join("anim-01.obj")).unwrap();
    let b = stripkit::io::read(dir.join("anim-02.obj")).unwrap();
    // (Its vertices are the level's, in the strips' first-use order: each one is the
    // midpoint of some vertex of the two key frames.)
    let midpoints: Vec<[f32; 3]> =
        a.positions.iter().zip(&b.positions).map(|(p, q)| [0, 1, 2].map(|d| 0.5 * (p[d] + q[d]))).collect();
    for p in &mid.positions {
        assert!(midpoints.iter().any(|m| (0..3).all(|d| (p[d] - m[d]).abs() < 1e-5)), "{p:?}");
    }
    let r = json(&stripkit(&["lod", "bench", model.to_str().unwrap(), "--rounds", "1", "--json"]));
    let rows = r["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 8, "4 frame rows, 3 level rows, 1 play row");
    for row in rows {
        let changed = row["strips_changed"].as_f64().unwrap();
        match (row["test"].as_str().unwrap(), row["at"].as_str().unwrap()) {
            // At level 0 every frame's strips are the level-0 strips: nothing to copy.
            ("frame", "100%") => assert_eq!(changed, 0.0, "{row}"),
            ("level", _) | ("play", _) => assert!(changed > 0.0, "{row}"),
            _ => {}
        }
        assert!(row["changes"].as_u64().unwrap() > 0 && row["max_us"].as_f64() >= row["mean_us"].as_f64(), "{row}");
        assert!(row["max_us"].as_f64() >= row["p99_us"].as_f64() && row["p99_us"].as_f64() >= row["median_us"].as_f64(), "{row}");
    }
    // Quantized positions: a smaller file that still extracts.
    let small = tmp("lod", "anim_q.lodseq");
    let q = json(&stripkit(&[
        "lod",
        "build-seq",
        dir.to_str().unwrap(),
        "-o",
        small.to_str().unwrap(),
        "--samples",
        "500",
        "--position-bits",
        "12",
        "--check",
        "sample",
        "--json",
    ]));
    assert!(q["bytes"].as_u64().unwrap() < std::fs::metadata(&model).unwrap().len());
    let out = tmp("lod", "anim_q.glb");
    let o = stripkit(&[
        "lod",
        "extract",
        small.to_str().unwrap(),
        "--frame",
        "0",
        "--ratio",
        "0.5",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn animation_misuse_exits_2() {
    let dir = animation("anim_misuse");
    let model = tmp("lod", "misuse.lodseq");
    let o = stripkit(&["lod", "build-seq", dir.to_str().unwrap(), "-o", model.to_str().unwrap(), "--samples", "300"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (sets, _) = build(&torus(), "not_anim.sets", &["--check", "off"]);
    let out = tmp("lod", "misuse_anim.ply");
    let _ = std::fs::remove_file(&out);
    let mut bad = std::fs::read(&model).unwrap();
    let mid = bad.len() / 2;
    bad[mid] ^= 8;
    // build-seq's output must be a .lodseq (a .ply would be refused for its name).
    let out_seq = tmp("lod", "misuse_out.lodseq");
    let _ = std::fs::remove_file(&out_seq);
    let damaged = tmp("lod", "damaged.lodseq");
    std::fs::write(&damaged, &bad).unwrap();
    for args in [
        // An animation needs --frame; a single model refuses it; frames in range.
        vec!["lod", "extract", model.to_str().unwrap(), "--level", "3", "-o", out.to_str().unwrap()],
        vec!["lod", "extract", sets.to_str().unwrap(), "--frame", "1", "--level", "3", "-o", out.to_str().unwrap()],
        vec!["lod", "extract", model.to_str().unwrap(), "--frame", "4", "--level", "3", "-o", out.to_str().unwrap()],
        vec!["lod", "extract", model.to_str().unwrap(), "--frame", "-1", "--level", "3", "-o", out.to_str().unwrap()],
        vec!["lod", "extract", damaged.to_str().unwrap(), "--frame", "1", "--level", "3", "-o", out.to_str().unwrap()],
        vec!["lod", "bench", damaged.to_str().unwrap()],
        // Frames that do not share their faces; bad settings.
        vec!["lod", "build-seq", "/no/such/folder", "-o", model.to_str().unwrap()],
        vec!["lod", "build-seq", dir.to_str().unwrap(), "-o", out_seq.to_str().unwrap(), "--position-bits", "4"],
        vec!["lod", "build-seq", dir.to_str().unwrap(), "-o", out_seq.to_str().unwrap(), "--tolerance", "0.5"],
        vec!["lod", "build-seq", dir.to_str().unwrap(), "-o", out_seq.to_str().unwrap(), "--samples", "0"],
    ] {
        let o = stripkit(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
    }
    assert!(!out.exists() && !out_seq.exists(), "nothing written");
    write_mesh(&dir.join("anim-02.obj"), &stripkit::gen::torus(20, 8, 1.0, 0.3));
    let o = stripkit(&["lod", "build-seq", dir.to_str().unwrap(), "-o", out_seq.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("anim-02.obj"), "names the frame");
}

/// Moves collapse 1's removed-triangle count onto collapse 2 in a `.sets` file (the
/// total still adds up) and reseals the checksum: a file whose structure holds but
/// whose level 2 draws fewer triangles than it says.
fn shift_removed_count(bytes: &[u8]) -> Vec<u8> {
    let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
    let (flags, positions) = (word(12), word(20) as usize);
    let endpoint = flags & 1 == 0;
    let positionless = flags & 2 != 0;
    let mut at = 48 + if positionless { 0 } else { 12 * positions };
    let skip = |at: &mut usize| {
        while bytes[*at] & 0x80 != 0 {
            *at += 1;
        }
        *at += 1;
    };
    // The removed counts' offsets of collapses 0, 1 and 2 (one byte each: they are small).
    let mut removed = Vec::new();
    for _ in 0..3 {
        if endpoint {
            skip(&mut at);
        }
        removed.push(at);
        skip(&mut at);
    }
    let mut bad = bytes.to_vec();
    let (one, two) = (removed[1], removed[2]);
    assert!(
        bad[one] > 0 && bad[one] < 64 && bad[two] < 64,
        "small single-byte counts"
    );
    bad[two] += bad[one];
    bad[one] = 0;
    let n = bad.len() - 4;
    let mut crc = flate2::Crc::new();
    crc.update(&bad[..n]);
    bad[n..].copy_from_slice(&crc.sum().to_le_bytes());
    bad
}

#[test]
fn counts_that_add_up_but_miss_the_strips_exit_2_naming_the_file_and_level() {
    // The kept strips' layout (version 1): the offsets above read it.
    let (model, _) = build(&torus(), "shifted_good.sets", &["--restrip", "off"]);
    let bad = tmp("lod", "shifted.sets");
    std::fs::write(&bad, shift_removed_count(&std::fs::read(&model).unwrap())).unwrap();
    let out = tmp("lod", "shifted_never.ply");
    let _ = std::fs::remove_file(&out);
    for args in [
        vec![
            "lod",
            "extract",
            bad.to_str().unwrap(),
            "--level",
            "2",
            "-o",
            out.to_str().unwrap(),
        ],
        vec!["lod", "bench", bad.to_str().unwrap(), "--rounds", "1"],
    ] {
        let o = stripkit(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("shifted.sets") && err.contains("level 2"),
            "{args:?}: {err}"
        );
        assert!(!err.contains("verification failed"), "{args:?}: {err}");
    }
    assert!(!out.exists());
}

#[test]
fn a_level_without_triangles_is_refused_not_written() {
    // One triangle: its last level (1) has none; a degenerate face: level 0 has none.
    for (name, obj, level) in
        [("one", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "1"), ("degenerate", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\n", "0")]
    {
        let input = tmp("lod", &format!("{name}.obj"));
        std::fs::write(&input, obj).unwrap();
        let (model, _) = build(&input, &format!("{name}.sets"), &[]);
        for ext in ["ply", "obj", "stl", "glb"] {
            let out = tmp("lod", &format!("{name}_empty.{ext}"));
            let _ = std::fs::remove_file(&out);
            let o = stripkit(&["lod", "extract", model.to_str().unwrap(), "--level", level, "-o", out.to_str().unwrap()]);
            let err = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{name} {ext}: {err}");
            assert!(err.contains(&format!("level {level} has no triangles")), "{name} {ext}: {err}");
            assert!(!out.exists(), "{name} {ext}: nothing written");
        }
    }
}

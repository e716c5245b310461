//! `stripkit lod`: build a model (checked at every level), extract levels that match
//! `stripkit simplify`, bench it, and refuse damaged `.sets` files with exit 2.

mod support;
use support::{json, stripkit, tmp, write_mesh};

fn torus() -> std::path::PathBuf {
    let path = tmp("lod", "torus.obj");
    write_mesh(&path, &stripkit::gen::torus(32, 12, 1.0, 0.3));
    path
}

fn build(
    input: &std::path::Path,
    name: &str,
    extra: &[&str],
) -> (std::path::PathBuf, serde_json::Value) {
    let model = tmp("lod", name);
    let mut args = vec![
        "lod",
        "build",
        input.to_str().unwrap(),
        "-o",
        model.to_str().unwrap(),
        "--json",
    ];
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
    assert_eq!(
        r["check"]["levels_checked"].as_u64().unwrap(),
        levels + 1,
        "every level checked"
    );
    assert_eq!(
        r["bytes"].as_u64().unwrap(),
        std::fs::metadata(&model).unwrap().len()
    );
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
        let strips = stripkit::io::read(&out).unwrap().triangulate().tris;
        let want = stripkit::io::read(&simplified).unwrap().triangulate().tris;
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
                let j: serde_json::Value =
                    serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
                assert_eq!(j["level"], e["level"]);
            }
        }
    }
}

#[test]
fn optimal_placement_and_other_stripifiers() {
    let input = torus();
    for extra in [
        &["--placement", "optimal"][..],
        &["--algo", "cache"],
        &["--algo", "single", "--check", "sample"],
    ] {
        let (model, r) = build(&input, "other.sets", extra);
        assert!(
            r["check"]["levels_checked"].as_u64().unwrap() > 0,
            "{extra:?}: {r}"
        );
        let out = tmp("lod", "other.ply");
        let o = stripkit(&[
            "lod",
            "extract",
            model.to_str().unwrap(),
            "--ratio",
            "0.3",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(
            o.status.success(),
            "{extra:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

#[test]
fn bench_prints_the_papers_tests() {
    let (model, _) = build(&torus(), "bench.sets", &[]);
    let r = json(&stripkit(&[
        "lod",
        "bench",
        model.to_str().unwrap(),
        "--rounds",
        "1",
        "--json",
    ]));
    let rows = r["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 12, "6 percentages x 2 spacings");
    for row in rows {
        assert!(row["us_per_level"].as_f64().unwrap() > 0.0);
        assert!(row["levels"].as_u64().unwrap() >= 2);
    }
    let o = stripkit(&["lod", "bench", model.to_str().unwrap(), "--rounds", "1"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("exponential") && text.contains("20%"),
        "{text}"
    );
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
            vec![
                "lod",
                "extract",
                bad.to_str().unwrap(),
                "--level",
                "3",
                "-o",
                out.to_str().unwrap(),
            ],
            vec!["lod", "bench", bad.to_str().unwrap()],
        ] {
            let o = stripkit(&args);
            assert_eq!(
                o.status.code(),
                Some(2),
                "{what}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
            assert!(
                String::from_utf8_lossy(&o.stderr).contains("bad.sets"),
                "{what}: names the file"
            );
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
        vec![
            "lod",
            "extract",
            model.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ],
        vec![
            "lod",
            "extract",
            model.to_str().unwrap(),
            "--ratio",
            "1.5",
            "-o",
            out.to_str().unwrap(),
        ],
        vec![
            "lod",
            "extract",
            model.to_str().unwrap(),
            "--level",
            "2",
            "--ratio",
            "0.5",
            "-o",
            out.to_str().unwrap(),
        ],
        vec![
            "lod",
            "extract",
            model.to_str().unwrap(),
            "--level",
            "2",
            "-o",
            "/tmp/x.unknown",
        ],
        vec![
            "lod",
            "build",
            input.to_str().unwrap(),
            "-o",
            "/no/such/folder/x.sets",
        ],
        vec![
            "lod",
            "build",
            input.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--refine",
        ],
    ] {
        let o = stripkit(&args);
        assert_eq!(
            o.status.code(),
            Some(2),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

//! `--threads`: every command's outputs are the same bytes at 1 and 4 threads. A
//! folder of generated meshes (one with material groups, one quad-dominant for the
//! two candidates of the cache stripifier's auto split), a glTF scene of many
//! primitives, `lod build` with its level checks, `lod build-seq` on a small bending
//! torus, `distance`, a big mesh cut into parts (`--partition-above`), and the folder
//! of shared models where present. The reports are compared with their times taken
//! out (and the output folder's name); and one unindexed mesh, read from binary PLY,
//! through every output format.

mod support;

use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use support::{encode_base64, gltf_validator, models_dir, stripkit, tmp, write_mesh};

/// A fresh, empty folder `name` in this test binary's temporary folder.
fn fresh(name: &str) -> PathBuf {
    let dir = tmp("threads", name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `stripkit --threads N args..`, which must succeed; its standard output.
fn run_at(threads: usize, args: &[&str]) -> Vec<u8> {
    let n = threads.to_string();
    let mut all = vec!["--threads", n.as_str()];
    all.extend_from_slice(args);
    let out = stripkit(&all);
    assert!(out.status.success(), "{all:?}: {}", String::from_utf8_lossy(&out.stderr));
    out.stdout
}

/// A report with its times (keys ending in `_ms`, or `ms`) removed and `from` replaced
/// by `to` in its strings: what must not depend on the thread count.
fn timeless(v: &Value, from: &str, to: &str) -> Value {
    match v {
        Value::Object(m) => Value::Object(
            m.iter()
                .filter(|(k, _)| !(k.ends_with("_ms") || k.as_str() == "ms"))
                .map(|(k, x)| (k.clone(), timeless(x, from, to)))
                .collect(),
        ),
        Value::Array(a) => Value::Array(a.iter().map(|x| timeless(x, from, to)).collect()),
        Value::String(s) => Value::String(s.replace(from, to)),
        other => other.clone(),
    }
}

/// The JSON lines of a report, each [`timeless`].
fn lines(stdout: &[u8], from: &Path) -> Vec<Value> {
    let from = from.to_str().unwrap();
    String::from_utf8_lossy(stdout)
        .lines()
        .map(|l| timeless(&serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")), from, "OUT"))
        .collect()
}

/// The files of `dir` by name, with their bytes.
fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut all: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .map(|p| (p.file_name().unwrap().to_string_lossy().into_owned(), std::fs::read(&p).unwrap()))
        .collect();
    all.sort();
    all
}

/// Strips folder `input` at 1 and 4 threads (`extra` flags) and asserts the same
/// files and the same reports; returns the reports.
fn folder_same_at_1_and_4(input: &Path, name: &str, extra: &[&str]) -> Vec<Value> {
    let mut seen = Vec::new();
    for threads in [1, 4] {
        let out = fresh(&format!("{name}-out-{threads}"));
        let mut args = vec!["strip", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--json"];
        args.extend_from_slice(extra);
        let reports = lines(&run_at(threads, &args), &out);
        seen.push((files(&out), reports, out));
    }
    let (one, four) = (&seen[0], &seen[1]);
    assert_eq!(one.0.len(), four.0.len());
    for ((a, x), (b, y)) in one.0.iter().zip(&four.0) {
        assert_eq!(a, b);
        assert!(x == y, "{name}: {a} differs between 1 and 4 threads");
    }
    assert_eq!(one.1, four.1, "{name}: the reports differ between 1 and 4 threads");
    let written: Vec<PathBuf> = one.0.iter().map(|(n, _)| one.2.join(n)).collect();
    let refs: Vec<&Path> = written.iter().filter(|p| p.extension().is_some_and(|e| e == "glb")).map(|p| p.as_path()).collect();
    gltf_validator::validate(&refs);
    seen.swap_remove(0).1
}

/// An OBJ of two icospheres side by side, each its own material group.
fn grouped_obj() -> String {
    let sphere = stripkit::gen::icosphere(3);
    let mut text = String::new();
    for (k, dx) in [0.0f32, 3.0].iter().enumerate() {
        for p in &sphere.positions {
            text += &format!("v {} {} {}\n", p[0] + dx, p[1], p[2]);
        }
        text += &format!("usemtl m{k}\n");
        let base = k * sphere.positions.len() + 1;
        for t in sphere.face_indices.chunks(3) {
            text += &format!("f {} {} {}\n", t[0] as usize + base, t[1] as usize + base, t[2] as usize + base);
        }
    }
    text
}

#[test]
fn a_folder_run_writes_the_same_bytes_and_reports_at_1_and_4_threads() {
    let input = fresh("gen-in");
    write_mesh(&input.join("a-sphere.ply"), &stripkit::gen::icosphere(4));
    write_mesh(&input.join("b-torus.obj"), &stripkit::gen::torus(40, 16, 1.0, 0.3));
    write_mesh(&input.join("c-grid.off"), &stripkit::gen::grid(30, 20));
    write_mesh(&input.join("d-quads.obj"), &stripkit::gen::torus_quads(24, 12, 1.0, 0.3));
    std::fs::write(input.join("e-groups.obj"), grouped_obj()).unwrap();
    for algo in ["auto", "cache"] {
        let reports = folder_same_at_1_and_4(&input, &format!("gen-{algo}"), &["--algo", algo]);
        assert_eq!(reports.len(), 5);
        // In input order, each verified.
        let names: Vec<&str> = reports.iter().map(|r| r["input"].as_str().unwrap()).collect();
        assert!(names.windows(2).all(|w| w[0] < w[1]), "{names:?}");
        assert!(reports.iter().all(|r| r["verified"] == true), "{reports:?}");
        assert_eq!(reports[4]["triangles"], 2 * 1280);
    }
}

#[test]
fn a_big_mesh_in_parts_is_the_same_at_1_and_4_threads() {
    // icosphere(7), 327,680 triangles: `--partition-above 1` cuts it into two parts
    // stripified side by side; the same bytes and reports at 1 and 4 threads, verified.
    let input = fresh("parts-in");
    write_mesh(&input.join("sphere.ply"), &stripkit::gen::icosphere(7));
    let reports = folder_same_at_1_and_4(&input, "parts", &["--algo", "cache", "--partition-above", "1"]);
    assert_eq!(reports.len(), 1);
    assert_eq!(reports[0]["verified"], true);
    assert_eq!(reports[0]["triangles"], 327_680);
}

/// A glTF of `n` primitives, each a shuffled grid of its own size over its own
/// positions, in one mesh.
fn scene(n: usize) -> Value {
    let (mut bin, mut views, mut accessors, mut primitives) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut seed = 7u64;
    for k in 0..n {
        let (w, h) = (4 + k as u16, 3 + (k as u16 % 3));
        let mut pos = Vec::new();
        for y in 0..=h {
            for x in 0..=w {
                pos.extend([x as f32, y as f32, k as f32]);
            }
        }
        let mut tris: Vec<[u16; 3]> = Vec::new();
        for y in 0..h {
            for x in 0..w {
                let v = y * (w + 1) + x;
                tris.push([v, v + 1, v + w + 2]);
                tris.push([v, v + w + 2, v + w + 1]);
            }
        }
        for i in (1..tris.len()).rev() {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            tris.swap(i, (seed >> 33) as usize % (i + 1));
        }
        let offset = bin.len();
        bin.extend(pos.iter().flat_map(|v| v.to_le_bytes()));
        views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": pos.len() * 4, "target": 34962}));
        let count = pos.len() / 3;
        accessors.push(json!({"bufferView": 2 * k, "componentType": 5126, "count": count, "type": "VEC3",
            "min": [0.0, 0.0, k as f32], "max": [w as f32, h as f32, k as f32]}));
        let offset = bin.len();
        bin.extend(tris.iter().flatten().flat_map(|i| i.to_le_bytes()));
        views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": tris.len() * 6, "target": 34963}));
        accessors.push(json!({"bufferView": 2 * k + 1, "componentType": 5123, "count": tris.len() * 3, "type": "SCALAR"}));
        while bin.len() % 4 != 0 {
            bin.push(0);
        }
        primitives.push(json!({"attributes": {"POSITION": 2 * k}, "indices": 2 * k + 1}));
    }
    json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": primitives}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": bin.len(), "uri": format!("data:application/octet-stream;base64,{}", encode_base64(&bin))}]
    })
}

/// `mesh` unindexed: its triangles shuffled, each with three vertices of its own (the
/// weld then has work on every vertex).
fn unindexed_shuffled(mesh: &stripkit::Mesh, seed: u64) -> stripkit::Mesh {
    let mut tris = mesh.triangulate().tris;
    let mut state = seed;
    for i in (1..tris.len()).rev() {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        tris.swap(i, (state >> 33) as usize % (i + 1));
    }
    let positions = tris.iter().flatten().map(|&v| mesh.positions[v as usize]).collect();
    let faces: Vec<[u32; 3]> = (0..tris.len() as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    stripkit::Mesh::from_triangles(positions, &faces)
}

#[test]
fn one_mesh_through_every_output_format_is_the_same_at_1_and_4_threads() {
    // icosphere(6) unindexed (81,920 triangles, 245,760 vertices welded back to
    // 40,962): read from binary PLY, welded, stripped by cache, checked and written
    // in every format; more than one part of every parallel cut of the read, weld and
    // check. The same bytes (JSON without its times) at 1 and 4 threads.
    let dir = fresh("formats");
    let input = dir.join("sphere.ply");
    write_mesh(&input, &unindexed_shuffled(&stripkit::gen::icosphere(6), 3));
    let outputs: [(&str, &[&str]); 6] = [
        ("s.ply", &[]),
        ("s-ascii.ply", &["--ascii"]),
        ("s.obj", &[]),
        ("s.glb", &[]),
        ("s.gltf", &[]),
        ("s.json", &[]),
    ];
    let mut glb = Vec::new();
    for (name, extra) in outputs {
        let mut written = Vec::new();
        for threads in [1, 4] {
            let out = dir.join(format!("{threads}-{name}"));
            let mut args = vec!["strip", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--algo", "cache", "--json"];
            args.extend_from_slice(extra);
            let report = lines(&run_at(threads, &args), &out);
            assert_eq!(report[0]["verified"], true, "{name}");
            assert_eq!(report[0]["triangles"], 81_920, "{name}");
            let bytes = std::fs::read(&out).unwrap();
            let bytes = match name.ends_with(".json") {
                true => serde_json::to_vec(&timeless(&serde_json::from_slice(&bytes).unwrap(), out.to_str().unwrap(), "OUT"))
                    .unwrap(),
                false => bytes,
            };
            written.push((bytes, report));
            if name.ends_with(".glb") || name.ends_with(".gltf") {
                glb.push(out);
            }
        }
        assert!(written[0].0 == written[1].0, "{name}: the file differs between 1 and 4 threads");
        assert_eq!(written[0].1, written[1].1, "{name}: the reports differ between 1 and 4 threads");
    }
    gltf_validator::validate(&glb.iter().map(PathBuf::as_path).collect::<Vec<_>>());
}

#[test]
fn a_scene_of_many_primitives_is_the_same_at_1_and_4_threads() {
    let input = fresh("scene-in");
    std::fs::write(input.join("many.gltf"), serde_json::to_vec(&scene(9)).unwrap()).unwrap();
    let reports = folder_same_at_1_and_4(&input, "scene", &[]);
    let prims = reports[0]["primitives"].as_array().unwrap();
    assert_eq!(prims.len(), 9);
    // Primitive k: a grid of (4 + k) x (3 + k % 3) quads.
    let tris: u64 = (0..9).map(|k| 2 * (4 + k) * (3 + k % 3)).sum();
    assert_eq!(reports[0]["triangles"], tris);
    for (k, p) in prims.iter().enumerate() {
        assert_eq!(p["primitive"], k, "in primitive order");
        assert_eq!(p["figures"]["verified"], true);
    }
}

#[test]
fn lod_build_and_build_seq_are_the_same_at_1_and_4_threads() {
    let frames = fresh("seq-in");
    let base = stripkit::gen::torus(24, 8, 1.0, 0.3);
    for f in 0..6 {
        let mut m = base.clone();
        let t = f as f32 * 0.3;
        for p in m.positions.iter_mut() {
            let (s, c) = (t * p[0]).sin_cos();
            *p = [c * p[0] - s * p[2], p[1], s * p[0] + c * p[2]];
        }
        write_mesh(&frames.join(format!("bend-{f:02}.obj")), &m);
    }
    let torus = frames.join("bend-00.obj");
    let mut outputs = Vec::new();
    for threads in [1, 4] {
        let dir = fresh(&format!("lod-out-{threads}"));
        let (seq, sets) = (dir.join("bend.lodseq"), dir.join("torus.sets"));
        let (seq_s, sets_s, frames_s) = (seq.to_str().unwrap(), sets.to_str().unwrap(), frames.to_str().unwrap());
        let seq_report = run_at(threads, &["lod", "build-seq", frames_s, "-o", seq_s, "--samples", "400", "--json"]);
        let build_report = run_at(threads, &["lod", "build", torus.to_str().unwrap(), "-o", sets_s, "--json"]);
        outputs.push((
            std::fs::read(&seq).unwrap(),
            std::fs::read(&sets).unwrap(),
            lines(&seq_report, &dir),
            lines(&build_report, &dir),
        ));
    }
    let (one, four) = (&outputs[0], &outputs[1]);
    assert!(one.0 == four.0, "the .lodseq differs between 1 and 4 threads");
    assert!(one.1 == four.1, "the .sets differs between 1 and 4 threads");
    assert_eq!(one.2, four.2);
    assert_eq!(one.3, four.3);
    assert_eq!(one.2[0]["frames"], 6);
    assert!(one.2[0]["levels_checked"].as_u64().unwrap() > 100, "{}", one.2[0]);
    assert!(one.3[0]["check"]["levels_checked"].as_u64().unwrap() > 100, "{}", one.3[0]);
}

#[test]
fn distance_is_the_same_bits_at_1_and_4_threads() {
    let dir = fresh("distance");
    let (a, b) = (dir.join("a.ply"), dir.join("b.ply"));
    write_mesh(&a, &stripkit::gen::icosphere(4));
    write_mesh(&b, &stripkit::gen::icosphere(2));
    // More samples than one part of 4,096: several parts, added in order.
    let args = ["distance", a.to_str().unwrap(), b.to_str().unwrap(), "--samples", "20000", "--json"];
    let (one, four) = (lines(&run_at(1, &args), &dir), lines(&run_at(4, &args), &dir));
    assert_eq!(one, four);
    let d = &one[0];
    // The icosphere of level 2 lies inside that of level 4: some, not much, distance.
    let h = d["hausdorff"].as_f64().unwrap();
    assert!(h > 0.0 && h < 0.05, "{d}");
}

#[test]
fn the_shared_models_strip_to_the_same_bytes_at_1_and_4_threads() {
    let Some(models) = models_dir() else { return };
    // Copies: a folder run takes no link leading out of its folder.
    let input = fresh("models-in");
    let mut copied = 0;
    for dir in [models.clone(), models.join("quads")] {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let p = entry.unwrap().path();
            if p.is_file() && stripkit::io::Format::from_path(&p).is_some() {
                std::fs::copy(&p, input.join(p.file_name().unwrap())).unwrap();
                copied += 1;
            }
        }
    }
    if copied == 0 {
        eprintln!("skipped: no mesh files in {}", models.display());
        return;
    }
    for algo in ["auto", "cache"] {
        let reports = folder_same_at_1_and_4(&input, &format!("models-{algo}"), &["--algo", algo]);
        assert_eq!(reports.len(), copied);
        assert!(reports.iter().all(|r| r["verified"] == true));
    }
    // Some 30 MB of copies and outputs: not left behind.
    for name in ["models-in", "models-auto-out-1", "models-auto-out-4", "models-cache-out-1", "models-cache-out-4"] {
        let _ = std::fs::remove_dir_all(tmp("threads", name));
    }
}

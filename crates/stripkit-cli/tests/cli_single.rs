//! `stripkit strip --algo single`: one strip per component, the changed mesh written
//! and read back, the report's figures, and every flag misuse refused with exit 2.

mod support;
use support::{json, stripkit, tmp, write_mesh};

fn sphere() -> std::path::PathBuf {
    let path = tmp("single", "sphere.obj");
    // A jittered icosphere: no flat quads, so merging needs splits or nodal vertices.
    let mut m = stripkit::gen::icosphere(3);
    for (i, p) in m.positions.iter_mut().enumerate() {
        let k = (i as f32 * 12.9898).sin() * 0.01;
        p[0] += k;
        p[1] -= k * 0.5;
    }
    write_mesh(&path, &m);
    path
}

#[test]
fn one_strip_and_the_changed_mesh_in_the_file() {
    let input = sphere();
    let out = tmp("single", "sphere_single.ply");
    for w in ["uniform", "cache", "cull", "direction:0,0,1", "mix:cull=0.5,cache=0.5"] {
        let r = json(&stripkit(&[
            "strip",
            input.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--algo",
            "single",
            "--weights",
            w,
            "--swap-angle",
            "off",
            "--json",
        ]));
        assert_eq!(r["algo"], "single");
        assert_eq!(r["strips"], 1, "{w}: {r}");
        let s = &r["single"];
        assert_eq!(s["components"], 1);
        assert_eq!(s["swapped_edges"], 0, "--swap-angle off");
        let steiner = s["steiner_vertices"].as_u64().unwrap() as usize;
        assert_eq!(r["vertices"].as_u64().unwrap() as usize, 642 + steiner, "{w}");
        assert_eq!(r["triangles"].as_u64().unwrap() as usize, 1280 + 2 * steiner, "{w}");
        // The file holds the Steiner vertices and decodes to the changed mesh.
        let back = stripkit::io::read(&out).unwrap();
        assert_eq!(back.vertex_count(), 642 + steiner);
        assert_eq!(back.triangle_count(), 1280 + 2 * steiner);
    }
}

#[test]
fn text_report_names_the_changes() {
    let input = sphere();
    let out = tmp("single", "text.ply");
    let o = stripkit(&["strip", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--algo", "single", "--weights", "cache"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout);
    for line in ["pieces", "triangles added", "vertices added", "swapped_edges", "pieces merged", "matching"] {
        assert!(text.contains(line), "{line} missing from:\n{text}");
    }
}

/// The shipped spot: its UV seams cut it into 13 pieces of GPU vertices (one surface,
/// 13 UV islands), no strip crosses a seam, and the report says what the edge splits
/// added; `--join degenerate` writes one stitched strip of the whole mesh; the glb
/// keeps the UVs.
#[test]
fn seams_are_reported_and_degenerate_join_stitches_the_whole_mesh() {
    let input = support::assets_dir().join("spot.obj");
    let (input_triangles, input_vertices) = (5856, 3225);
    let out = tmp("single", "spot.json");
    let r = json(&stripkit(&[
        "strip", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--algo", "single", "--join", "degenerate", "--json",
    ]));
    let s = &r["single"];
    assert_eq!((s["components"].as_u64(), s["surfaces"].as_u64(), s["uv_islands"].as_u64()), (Some(13), Some(1), Some(13)), "{s}");
    let (added_t, added_v) = (s["triangles_added"].as_u64().unwrap() as usize, s["vertices_added"].as_u64().unwrap() as usize);
    assert_eq!(added_v, s["steiner_vertices"].as_u64().unwrap() as usize);
    assert_eq!(r["triangles"].as_u64().unwrap() as usize, input_triangles + added_t, "{r}");
    assert_eq!(r["vertices"].as_u64().unwrap() as usize, input_vertices + added_v, "{r}");
    assert!(added_t <= 2 * added_v && added_t >= added_v, "{s}");
    assert!(r["strips"].as_u64().unwrap() >= 13, "at least one strip per piece: {r}");
    let written: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(written["join"], "degenerate");
    assert_eq!(written["strips"].as_array().unwrap().len(), 1, "one stitched strip");

    // The text report says the same; the glb keeps TEXCOORD_0 for every vertex.
    let glb = tmp("single", "spot.glb");
    let o = stripkit(&["strip", input.to_str().unwrap(), "-o", glb.to_str().unwrap(), "--algo", "single"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("13 (of GPU vertices: one strip each at best; 1 surface(s), 13 UV island(s))"), "{text}");
    assert!(text.contains(&format!("{input_triangles} input triangles + {added_t} from edge splits")), "{text}");
    let scene = stripkit::io::Scene::read(&glb).unwrap();
    let mesh = &scene.primitives()[0].mesh;
    let uv = mesh.attribute("TEXCOORD_0").expect("UVs kept");
    assert_eq!(uv.len(), mesh.vertex_count());
    support::gltf_validator::validate(&[&glb]);

    // cull says pieces too.
    let c = json(&stripkit(&["cull", input.to_str().unwrap(), "--views", "3", "--json"]));
    assert_eq!((c["pieces"].as_u64(), c["surfaces"].as_u64(), c["uv_islands"].as_u64()), (Some(13), Some(1), Some(13)), "{c}");
    assert_eq!(c["triangles"].as_u64().unwrap() as usize, input_triangles + c["triangles_added"].as_u64().unwrap() as usize);
}

/// `--positions-only` reads the bare shape: spot's 2,930 positions, no seams, so one
/// piece and one strip (the README's figures are measured so).
#[test]
fn positions_only_has_no_seams() {
    let input = support::assets_dir().join("spot.obj");
    let out = tmp("single", "spot_bare.ply");
    let r = json(&stripkit(&[
        "strip", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--algo", "single", "--weights", "cache",
        "--positions-only", "--json",
    ]));
    let s = &r["single"];
    assert_eq!((s["components"].as_u64(), s["surfaces"].as_u64()), (Some(1), Some(1)), "{s}");
    assert!(s["uv_islands"].is_null(), "{s}");
    assert_eq!(r["strips"], 1, "{r}");
    let added = s["vertices_added"].as_u64().unwrap();
    assert_eq!(r["vertices"].as_u64(), Some(2930 + added), "{r}");
}

#[test]
fn misused_flags_exit_2() {
    let input = sphere();
    let out = tmp("single", "bad.ply");
    let (i, o) = (input.to_str().unwrap(), out.to_str().unwrap());
    for (args, says) in [
        (vec!["--algo", "greedy", "--weights", "cache"], "apply to --algo single"),
        (vec!["--algo", "cache", "--swap-angle", "5"], "apply to --algo single"),
        (vec!["--algo", "single", "--weights", "shiny"], "--weights"),
        (vec!["--algo", "single", "--weights", "direction:0,0,0"], "--weights"),
        (vec!["--algo", "single", "--weights", "mix:cull=-1"], "--weights"),
        (vec!["--algo", "single", "--swap-angle", "sideways"], "--swap-angle"),
        (vec!["--algo", "single", "--swap-angle", "95"], "--swap-angle"),
        (vec!["--algo", "single", "--cull-angle", "0"], "--cull-angle"),
        (vec!["--algo", "single", "--split", "qstrip"], "--split qstrip"),
    ] {
        let mut all = vec!["strip", i, "-o", o];
        all.extend(args.iter());
        let r = stripkit(&all);
        assert_eq!(r.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} wrote a file");
    }
}

//! `stripkit strip --algo qstrip|auto` on quad meshes written to a temporary OBJ.

use std::path::PathBuf;

mod support;
use support::stripkit;

fn tmp(name: &str) -> PathBuf {
    support::tmp("quad", name)
}

/// An `n` x `n` quad grid written to `path`, plus one vertex left of it and, with
/// `extra_triangles`, one triangle joining it to the grid's left side.
fn write_grid(path: &std::path::Path, n: usize, extra_triangles: bool) {
    let mut mesh = stripkit::gen::grid_quads(n as u32, n as u32);
    mesh.positions.push([-1.0, 0.5, 0.0]);
    if extra_triangles {
        let apex = ((n + 1) * (n + 1)) as u32;
        mesh.push_face(&[(n + 1) as u32, apex, 0]);
    }
    support::write_mesh(path, &mesh);
}

fn run_json(input: &std::path::Path, algo: &str) -> serde_json::Value {
    run_json_with(input, algo, &[])
}

/// `stripkit strip INPUT -o OUT --algo ALGO --json` plus `extra`; the printed figures.
fn run_json_with(input: &std::path::Path, algo: &str, extra: &[&str]) -> serde_json::Value {
    let out_path = tmp(&format!("out-{algo}-{}.ply", extra.join("-")));
    let mut args = vec![
        "strip",
        input.to_str().unwrap(),
        "-o",
        out_path.to_str().unwrap(),
        "--algo",
        algo,
        "--json",
    ];
    args.extend_from_slice(extra);
    support::json(&stripkit(&args))
}

#[test]
fn qstrip_reports_quads_and_indices_per_quad() {
    let input = tmp("grid.obj");
    write_grid(&input, 12, false);
    for algo in ["qstrip", "auto"] {
        let v = run_json(&input, algo);
        assert_eq!(v["algo"], "qstrip");
        assert_eq!(v["quads"], 144);
        assert_eq!(v["triangles"], 288);
        assert_eq!(v["verified"], true);
        let ipq = v["indices_per_quad"].as_f64().unwrap();
        let restart = v["indices_restart"].as_f64().unwrap();
        assert!((ipq - restart / 144.0).abs() < 1e-9);
        assert!(ipq < 2.4, "{ipq}");
    }
    let v = run_json(&input, "greedy");
    assert_eq!(v["algo"], "greedy");
    assert!(v.get("quads").is_none());
}

#[test]
fn mixed_mesh_covers_quads_and_triangles() {
    let input = tmp("mixed.obj");
    write_grid(&input, 6, true);
    let v = run_json(&input, "auto");
    assert_eq!(v["algo"], "qstrip");
    assert_eq!(v["quads"], 36);
    assert_eq!(v["triangles"], 73);
    assert_eq!(v["verified"], true);
}

#[test]
fn auto_picks_greedy_for_triangle_meshes() {
    let input = tmp("tri.obj");
    std::fs::write(
        &input,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 3 2 4\n",
    )
    .unwrap();
    let v = run_json(&input, "auto");
    assert_eq!(v["algo"], "greedy");
}

#[test]
fn quad_single_gives_one_strip_on_a_torus_and_refuses_open_meshes() {
    let input = tmp("torus.obj");
    support::write_mesh(&input, &stripkit::gen::torus_quads(20, 12, 2.0, 1.0));
    let v = run_json(&input, "quad-single");
    assert_eq!(v["algo"], "quad-single");
    assert_eq!(v["strips"], 1);
    assert_eq!(v["quads"], 240);
    assert_eq!(v["verified"], true);
    let open = tmp("open.obj");
    write_grid(&open, 3, false);
    let out_path = tmp("open.ply");
    let out = stripkit(&[
        "strip",
        open.to_str().unwrap(),
        "-o",
        out_path.to_str().unwrap(),
        "--algo",
        "quad-single",
    ]);
    assert_eq!(
        out.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn cache_modes_split_shuffled_quads_along_qstrip_diagonals() {
    // Faces shuffled and rotated: the fan splits the quads along random diagonals.
    let input = tmp("shuffled-torus.obj");
    let mesh = stripkit::gen::shuffle_faces(&stripkit::gen::torus_quads(40, 24, 3.0, 1.0), 3);
    support::write_mesh(&input, &mesh);
    for algo in ["cache", "balanced"] {
        let run = |diagonals: &str| run_json_with(&input, algo, &["--split", diagonals]);
        let fan = run("fan");
        let auto = run("auto");
        let forced = run("qstrip");
        assert_eq!(fan["diagonals"], "fan");
        assert_eq!(auto["diagonals"], "qstrip", "{algo}");
        assert_eq!(forced["indices_restart"], auto["indices_restart"]);
        for v in [&fan, &auto] {
            assert_eq!(v["verified"], true);
            assert_eq!(v["triangles"], 1920);
        }
        let idx = |v: &serde_json::Value| v["indices_restart"].as_f64().unwrap();
        let acmr = |v: &serde_json::Value| v["acmr16"].as_f64().unwrap();
        assert!(
            idx(&auto) < 0.97 * idx(&fan),
            "{algo}: {} vs {}",
            idx(&auto),
            idx(&fan)
        );
        if algo == "cache" {
            assert!(acmr(&auto) < acmr(&fan));
        } else {
            assert!(acmr(&auto) <= 0.8 && acmr(&fan) <= 0.8);
        }
    }
}

#[test]
fn cache_refine_keeps_misses_and_saves_indices() {
    let input = tmp("refine-torus.obj");
    let mesh = stripkit::gen::shuffle_faces(&stripkit::gen::torus(48, 32, 3.0, 1.0), 4);
    support::write_mesh(&input, &mesh);
    let plain = run_json_with(&input, "cache", &[]);
    let refined = run_json_with(&input, "cache", &["--refine"]);
    for v in [&plain, &refined] {
        assert_eq!(v["verified"], true);
    }
    let idx = |v: &serde_json::Value| v["indices_restart"].as_u64().unwrap();
    let acmr = |v: &serde_json::Value| v["acmr16"].as_f64().unwrap();
    assert!(idx(&refined) < idx(&plain), "{} vs {}", idx(&refined), idx(&plain));
    assert!(acmr(&refined) <= acmr(&plain) + 1e-12);
}

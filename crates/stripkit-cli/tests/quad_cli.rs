//! `stripkit strip --algo qstrip|auto` on quad meshes written to a temporary OBJ.

use std::path::PathBuf;

mod support;
use support::stripkit;

fn tmp(name: &str) -> PathBuf {
    support::tmp("quad", name)
}

/// An `n` x `n` quad grid as OBJ text, plus `extra` triangles fanned off its left side.
fn grid_obj(n: usize, extra_triangles: bool) -> String {
    let mut s = String::new();
    for j in 0..=n {
        for i in 0..=n {
            s += &format!("v {i} {j} 0\n");
        }
    }
    s += "v -1 0.5 0\n";
    let id = |i: usize, j: usize| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            s += &format!(
                "f {} {} {} {}\n",
                id(i, j),
                id(i + 1, j),
                id(i + 1, j + 1),
                id(i, j + 1)
            );
        }
    }
    if extra_triangles {
        let apex = (n + 1) * (n + 1) + 1;
        s += &format!("f {} {} {}\n", id(0, 1), apex, id(0, 0));
    }
    s
}

fn run_json(input: &std::path::Path, algo: &str) -> serde_json::Value {
    let out_path = tmp(&format!("out-{algo}.ply"));
    let out = stripkit(&[
        "strip",
        input.to_str().unwrap(),
        "-o",
        out_path.to_str().unwrap(),
        "--algo",
        algo,
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

#[test]
fn qstrip_reports_quads_and_indices_per_quad() {
    let input = tmp("grid.obj");
    std::fs::write(&input, grid_obj(12, false)).unwrap();
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
    std::fs::write(&input, grid_obj(6, true)).unwrap();
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

/// A closed torus of quads as OBJ text.
fn torus_obj(nu: usize, nv: usize) -> String {
    let mut s = String::new();
    for j in 0..nv {
        for i in 0..nu {
            let (u, v) = (
                i as f32 / nu as f32 * std::f32::consts::TAU,
                j as f32 / nv as f32 * std::f32::consts::TAU,
            );
            let r = 2.0 + v.cos();
            s += &format!("v {} {} {}\n", r * u.cos(), r * u.sin(), v.sin());
        }
    }
    let id = |i: usize, j: usize| (j % nv) * nu + (i % nu) + 1;
    for j in 0..nv {
        for i in 0..nu {
            s += &format!(
                "f {} {} {} {}\n",
                id(i, j),
                id(i + 1, j),
                id(i + 1, j + 1),
                id(i, j + 1)
            );
        }
    }
    s
}

#[test]
fn quad_single_gives_one_strip_on_a_torus_and_refuses_open_meshes() {
    let input = tmp("torus.obj");
    std::fs::write(&input, torus_obj(20, 12)).unwrap();
    let v = run_json(&input, "quad-single");
    assert_eq!(v["algo"], "quad-single");
    assert_eq!(v["strips"], 1);
    assert_eq!(v["quads"], 240);
    assert_eq!(v["verified"], true);
    let open = tmp("open.obj");
    std::fs::write(&open, grid_obj(3, false)).unwrap();
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

//! `stripkit cull` end to end: a generated torus culled along the helix, JSON per
//! view, the strip bar as SVG, bad flags refused.

use std::path::PathBuf;
use std::process::Command;

mod support;

fn tmp(name: &str) -> PathBuf {
    support::tmp("cull", name)
}

fn stripkit(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_stripkit")).args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn culls_a_torus_along_the_helix() {
    let mesh = tmp("torus.ply");
    let (code, _, err) = stripkit(&["gen", "torus", "-o", mesh.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let bar = tmp("bar.svg");
    let (code, out, err) = stripkit(&[
        "cull",
        mesh.to_str().unwrap(),
        "--views",
        "40",
        "--repeat",
        "1",
        "--json",
        "--bar",
        bar.to_str().unwrap(),
        "--view",
        "7",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["views"], 40);
    assert_eq!(v["weights"], "cull");
    let views = v["per_view"].as_array().unwrap();
    assert_eq!(views.len(), 40);
    let tris = v["triangles"].as_u64().unwrap();
    for view in views {
        assert_eq!(view["front_missed"], 0);
        let (drawn, culled) = (view["drawn"].as_u64().unwrap(), view["back_culled"].as_u64().unwrap());
        assert!(view["segments"].as_u64().unwrap() >= 1 && drawn + culled <= tris && culled > tris / 4, "{view}");
        assert!(view["visited_front"].as_u64().unwrap() <= view["visited_root"].as_u64().unwrap() * 2);
    }
    let svg = std::fs::read_to_string(&bar).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("view 7") && svg.contains("#202020"));
}

#[test]
fn refuses_bad_flags() {
    let mesh = tmp("sphere.ply");
    let (code, _, err) = stripkit(&["gen", "icosphere", "2", "-o", mesh.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let m = mesh.to_str().unwrap();
    let (code, _, err) = stripkit(&["cull", m, "--weights", "bogus"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--weights"), "{err}");
    let (code, _, err) = stripkit(&["cull", m, "--views", "5", "--bar", "/tmp/x.svg", "--view", "5"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--view"), "{err}");
}

#[test]
fn frustum_culling_skips_what_a_narrow_camera_leaves_out() {
    let mesh = tmp("torus_frustum.ply");
    let (code, _, err) = stripkit(&["gen", "torus", "-o", mesh.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let run = |extra: &[&str]| {
        let mut args = vec!["cull", mesh.to_str().unwrap(), "--views", "40", "--repeat", "1", "--json"];
        args.extend_from_slice(extra);
        let (code, out, err) = stripkit(&args);
        assert_eq!(code, 0, "{extra:?}: {err}");
        let j: serde_json::Value = serde_json::from_str(&out).unwrap();
        j
    };
    let plain = run(&[]);
    let wide = run(&["--frustum"]);
    assert_eq!(wide["mean"]["outside"], 0.0, "the path's 60 degrees hold the whole torus");
    assert_eq!(wide["mean"]["segments"], plain["mean"]["segments"]);
    let narrow = run(&["--frustum", "--fov", "15"]);
    assert!(narrow["mean"]["outside"].as_f64().unwrap() > 0.0, "{}", narrow["mean"]);
    assert!(narrow["mean"]["drawn"].as_f64().unwrap() < plain["mean"]["drawn"].as_f64().unwrap());
    assert_eq!(narrow["fov"], 15.0);
    for bad in [&["--fov", "20"][..], &["--frustum", "--fov", "0"], &["--frustum", "--fov", "200"]] {
        let mut args = vec!["cull", mesh.to_str().unwrap(), "--views", "4"];
        args.extend_from_slice(bad);
        let (code, _, err) = stripkit(&args);
        assert_eq!(code, 2, "{bad:?}: {err}");
    }
}

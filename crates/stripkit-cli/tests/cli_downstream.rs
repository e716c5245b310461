//! Real clients downstream of `stripkit strip`: gltf-transform (with the
//! `EXT_mesh_primitive_restart` extension of js/gltf-transform-restart) copies a
//! stripped .glb and keeps its restart groups index for index. Needs `node` and the npm
//! packages `.ci/run` installs into .ci/node_modules; skips with a printed reason
//! without them.

mod support;

use std::path::{Path, PathBuf};
use std::process::Command;
use support::{gltf_validator, stripkit, tmp};

/// This checkout (not the testkit's, which may have been built in another tree).
fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `.ci/node_modules` when `node` runs and every package in `packages` is installed
/// there; otherwise prints why the test skips and returns `None`.
fn node_modules(packages: &[&str]) -> Option<PathBuf> {
    let modules = repo_root().join(".ci/node_modules");
    for p in packages {
        if !modules.join(p).join("package.json").is_file() {
            eprintln!("skip: npm package {p} is not installed in .ci/node_modules (.ci/run installs it)");
            return None;
        }
    }
    match Command::new("node").arg("--version").output() {
        Ok(o) if o.status.success() => Some(modules),
        _ => {
            eprintln!("skip: node is not on PATH");
            None
        }
    }
}

/// A copy of the npm package js/gltf-transform-restart in `dir` with `node_modules`
/// linked to `modules`, so that its ES modules resolve `@gltf-transform/core` there.
fn package_copy(dir: &Path, modules: &Path) -> PathBuf {
    let src = repo_root().join("js/gltf-transform-restart");
    let pkg = dir.join("gltf-transform-restart");
    std::fs::create_dir_all(pkg.join("test")).unwrap();
    for f in ["package.json", "index.js", "test/copy.test.js"] {
        std::fs::copy(src.join(f), pkg.join(f)).unwrap();
    }
    let link = dir.join("node_modules");
    if !link.exists() {
        std::os::unix::fs::symlink(modules, &link).unwrap();
    }
    pkg
}

/// A 4 x 2 grid of quads whose left half uses material `left` and right half `right`:
/// one mesh of two primitives, so two restart groups.
fn two_materials_obj() -> String {
    let mut text = String::new();
    for y in 0..3 {
        for x in 0..5 {
            text += &format!("v {x} {y} {}\n", (x * y) as f32 * 0.1);
        }
    }
    for (name, xs) in [("left", 0..2), ("right", 2..4)] {
        text += &format!("usemtl {name}\n");
        for y in 0..2 {
            for x in xs.clone() {
                let v = y * 5 + x + 1;
                text += &format!("f {} {} {}\nf {} {} {}\n", v, v + 1, v + 6, v, v + 6, v + 5);
            }
        }
    }
    text
}

#[test]
fn gltf_transform_copy_keeps_the_restart_groups() {
    let Some(modules) = node_modules(&["@gltf-transform/core"]) else { return };
    // A sphere (one primitive) and the shipped spot (UVs, seams) stripped with restart groups.
    let sphere_obj = tmp("downstream", "sphere.obj");
    assert!(stripkit(&["gen", "icosphere", "3", "-o", sphere_obj.to_str().unwrap()]).status.success());
    let two = tmp("downstream", "two.obj");
    std::fs::write(&two, two_materials_obj()).unwrap();
    let mut glbs = Vec::new();
    let sources = [
        (sphere_obj.clone(), "sphere.glb"),
        (repo_root().join("assets/spot.obj"), "spot.glb"),
        (two, "two.glb"),
    ];
    for (src, name) in sources {
        let out = tmp("downstream", name);
        let run = stripkit(&["strip", src.to_str().unwrap(), "-o", out.to_str().unwrap(), "--join", "restart"]);
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        glbs.push(out);
    }
    let dir = sphere_obj.parent().unwrap();
    let pkg = package_copy(dir, &modules);
    let list = std::env::join_paths(&glbs).unwrap();
    let run = Command::new("node")
        .args(["--test", "test/"])
        .current_dir(&pkg)
        .env("STRIPKIT_RESTART_GLBS", &list)
        .output()
        .expect("runs node");
    let out = String::from_utf8_lossy(&run.stdout);
    eprintln!("{out}");
    assert!(run.status.success(), "{out}{}", String::from_utf8_lossy(&run.stderr));
    assert!(out.contains("# pass 5") && out.contains("# skipped 0"), "{out}");
    let copies: Vec<PathBuf> = glbs.iter().map(|g| g.with_extension("copy.glb")).collect();
    gltf_validator::validate(&copies.iter().map(|p| p.as_path()).collect::<Vec<_>>());
}

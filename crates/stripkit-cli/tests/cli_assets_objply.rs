//! `stripkit strip` on OBJ assets with UVs and materials (issue #15, items 1 and 3):
//! UVs reach a PLY output, materials an OBJ output, and no strip crosses a material.

use std::path::Path;

mod support;
use support::{json, stripkit, tmp};

fn spot() -> String {
    support::assets_dir().join("spot.obj").to_string_lossy().into_owned()
}

#[test]
fn spot_to_ply_keeps_its_uvs() {
    let out_path = tmp("objply", "spot_uv.ply");
    let v = json(&stripkit(&["strip", &spot(), "-o", out_path.to_str().unwrap(), "--json"]));
    assert_eq!(v["triangles"], 5856);
    let back = stripkit::io::read(&out_path).unwrap();
    // One vertex per (position, UV) pair of the file: its 3,225 UVs.
    assert_eq!(back.vertex_count(), 3225);
    let input = stripkit::io::read(Path::new(&spot())).unwrap();
    let (a, b) = (input.attribute("TEXCOORD_0").unwrap(), back.attribute("TEXCOORD_0").unwrap());
    assert_eq!(b.len(), 3225);
    for v in 0..3225 {
        assert_eq!(a.get(v, 0), b.get(v, 0));
        assert!((a.get(v, 1) - b.get(v, 1)).abs() <= 6e-8, "vertex {v}");
    }
}

#[test]
fn a_two_material_obj_stripped_to_obj_keeps_its_materials() {
    // A row of 4 quads, 0-1 in `red`, 2-3 in `blue`, materials alternating in the file.
    let mut text = String::from("mtllib two.mtl\n");
    for y in 0..2 {
        for x in 0..5 {
            text += &format!("v {x} {y} 0\nvt {} {}\n", x as f32 / 4.0, y as f32);
        }
    }
    let id = |x: usize, y: usize| y * 5 + x + 1;
    for (x, y) in [(0, 0), (3, 0), (1, 0), (2, 0)] {
        let m = if x < 2 { "red" } else { "blue" };
        let c = [id(x, y), id(x + 1, y), id(x + 1, y + 1), id(x, y + 1)];
        text += &format!("usemtl {m}\nf {0}/{0} {1}/{1} {2}/{2} {3}/{3}\n", c[0], c[1], c[2], c[3]);
    }
    let input = tmp("objply", "two.obj");
    std::fs::write(&input, text).unwrap();
    let output = tmp("objply", "two_strips.obj");
    let v = json(&stripkit(&[
        "strip",
        input.to_str().unwrap(),
        "-o",
        output.to_str().unwrap(),
        "--algo",
        "greedy",
        "--json",
    ]));
    assert_eq!(v["triangles"], 8);
    // Without the materials greedy makes one strip of this row; with them, one each.
    assert_eq!(v["strips"], 2);
    let written = std::fs::read_to_string(&output).unwrap();
    assert!(written.contains("mtllib two.mtl\n"), "{written}");
    assert_eq!(written.matches("usemtl red\n").count(), 1, "{written}");
    assert_eq!(written.matches("usemtl blue\n").count(), 1, "{written}");
    let back = stripkit::io::read(&output).unwrap();
    assert_eq!(back.face_count(), 8);
    for f in 0..back.face_count() {
        let material = back.groups[back.group_of(f) as usize].material.as_deref().unwrap();
        let x_max = back.face(f).iter().map(|&v| back.positions[v as usize][0]).fold(0.0f32, f32::max);
        assert_eq!(material, if x_max <= 2.0 { "red" } else { "blue" }, "face {f}");
    }
    // The same grid without its materials: one strip, crossing the line x = 2.
    let plain = tmp("objply", "plain.obj");
    std::fs::write(&plain, std::fs::read_to_string(&input).unwrap().replace("usemtl", "# usemtl")).unwrap();
    let json_out = tmp("objply", "plain.json");
    let v = json(&stripkit(&[
        "strip",
        plain.to_str().unwrap(),
        "-o",
        json_out.to_str().unwrap(),
        "--algo",
        "greedy",
        "--json",
    ]));
    assert_eq!(v["strips"], 1);
}

#[test]
fn stats_and_match_see_the_surface_not_its_uv_seams() {
    // spot's UV seams split 2,930 positions into 3,225 GPU vertices; the surface stays
    // one closed component for stats and for the dual graph of match.
    let v = json(&stripkit(&["stats", &spot(), "--json"]));
    assert_eq!((v["vertices"].as_u64(), v["gpu_vertices"].as_u64()), (Some(2930), Some(3225)), "{v}");
    assert_eq!(v["boundary_edges"], 0, "{v}");
    let m = json(&stripkit(&["match", "--dual", &spot(), "--json"]));
    assert_eq!(m["perfect"], true, "{m}");
}

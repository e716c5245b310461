//! `strip` welds bit-identical vertices by default and says how many (text and
//! `--json`), `--no-weld` keeps them; a glTF primitive whose strips would be larger
//! than its indices is kept as read and the report says so; the notes on PLY
//! `tristrips` and on the stitched strips' zero-area triangles go to standard error,
//! never into the `--json` data (issue #31, items 8 and 5).

mod support;

use stripkit::{gen, Mesh};
use stripkit_testkit::XorShift64;
use support::{gltf_validator, json, stripkit, tmp, write_mesh};

/// `mesh` unindexed, its triangles shuffled, each with three vertices of its own.
fn deindexed(mesh: &Mesh, seed: u64) -> Mesh {
    let mut tris = mesh.triangulate().tris;
    XorShift64(seed).shuffle(&mut tris);
    let corners: Vec<u32> = tris.iter().flatten().copied().collect();
    let mut out = mesh.gather_vertices(&corners);
    for t in 0..tris.len() as u32 {
        out.push_face(&[3 * t, 3 * t + 1, 3 * t + 2]);
    }
    out
}

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn an_unindexed_mesh_is_welded_unless_no_weld_and_the_count_is_reported() {
    let input = tmp("weld", "flat_torus.ply");
    write_mesh(&input, &deindexed(&gen::torus(48, 24, 1.0, 0.3), 3));
    let out = tmp("weld", "out.ply");
    let run = stripkit(&["strip", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--json"]);
    let r = json(&run);
    assert_eq!(r["welded"], 6912 - 1152);
    assert_eq!(r["strips"], 1);
    assert!(r["indices_restart"].as_u64().unwrap() <= 2304 * 11 / 10, "{r}");
    assert!(stderr(&run).contains("PLY `tristrips` element; trimesh and Open3D read it as 0 faces"), "{}", stderr(&run));
    let back = stripkit::io::read(&out).unwrap();
    assert_eq!(back.vertex_count(), 6912, "input vertex order keeps every vertex");

    let run = stripkit(&["strip", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--json", "--no-weld"]);
    let r = json(&run);
    assert_eq!((r["welded"].as_u64(), r["strips"].as_u64()), (Some(0), Some(2304)));

    let text = stripkit(&["strip", input.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(text.status.success());
    assert!(String::from_utf8_lossy(&text.stdout).contains("welded vertices            5760"));
}

#[test]
fn a_gltf_scene_reports_welds_kept_primitives_and_the_stitched_degenerate_triangles() {
    let input = tmp("weld", "flat_torus.glb");
    write_mesh(&input, &deindexed(&gen::torus(48, 24, 1.0, 0.3), 9));
    let out = tmp("weld", "torus_out.glb");
    let run = stripkit(&["strip", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--json"]);
    let r = json(&run);
    assert_eq!((r["welded"].as_u64(), r["kept_as_read"].as_u64()), (Some(5760), Some(0)));
    let p = &r["primitives"][0];
    let stitched = p["indices_stitched"].as_u64().unwrap();
    assert_eq!(p["degenerate_stitched"].as_u64().unwrap(), stitched - 2 - 2304);
    let note = format!("to the 2304; loaders that keep every triangle (trimesh, Open3D) count {} faces", stitched - 2);
    assert!(stderr(&run).contains(&note), "{}", stderr(&run));

    // Without the weld every triangle is its own strip: the primitive is kept as read.
    let kept = tmp("weld", "torus_kept.glb");
    let run = stripkit(&["strip", input.to_str().unwrap(), "-o", kept.to_str().unwrap(), "--no-weld"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(text.contains("kept as read                  1"), "{text}");
    assert!(text.contains("kept as read: strips were larger"), "{text}");
    assert!(!stderr(&run).contains("zero-area"), "{}", stderr(&run));
    let back = stripkit::io::Scene::read(&kept).unwrap();
    assert_eq!((back.primitives()[0].mode, back.primitives()[0].indices_read), (4, 6912));
    gltf_validator::validate(&[&out, &kept]);
}

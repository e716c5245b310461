//! QSTRIP on the research quad meshes (../shared/models/quads) and their Catmull-Clark
//! refinements, when present: every output verified, the figures of the target held.

mod quad_support;

use quad_support::*;

const MODELS: [(&str, bool); 6] = [
    ("fandisk_quads.off", true),
    ("halftunnel.off", false),
    ("inspired_mesh_quads_Conjugate.off", false),
    ("horse_quad.obj", true),
    ("spot_quadrangulated.obj", true),
    ("spot_control_mesh.obj", true),
];

#[test]
fn research_quad_meshes_verify_and_meet_the_target() {
    let Some(dir) = stripkit::test_support::models_dir() else { return };
    let mut failures = Vec::new();
    for (name, closed) in MODELS {
        let path = dir.join("quads").join(name);
        if !path.exists() {
            eprintln!("skipped: {} not found", path.display());
            continue;
        }
        let mesh = stripkit::mesh::io::read(&path).expect("model loads");
        let pure = mesh.is_quad_mesh();
        let (_, check, fig) = strip_and_verify(&mesh);
        eprintln!("{name}: {fig:?} other triangles {}", check.other_triangles);
        if closed && pure {
            if fig.indices_per_quad > 2.20 || fig.strips * 50 >= fig.quads {
                failures.push(format!("{name}: {fig:?}"));
            }
        }
        if name.starts_with("spot_quad") {
            let l1 = subdivide(&mesh);
            let l2 = subdivide(&l1);
            for (level, m) in [(1, &l1), (2, &l2)] {
                let (_, _, fig) = strip_and_verify(m);
                eprintln!("{name} CC level {level}: {fig:?}");
                if fig.indices_per_quad > 2.20 || fig.strips * 50 >= fig.quads {
                    failures.push(format!("{name} level {level}: {fig:?}"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "over the target: {failures:#?}");
}

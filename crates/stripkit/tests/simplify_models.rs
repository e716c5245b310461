//! The simplifier on the research meshes (skipped when they are absent).

mod simplify_meshes;
mod support;

use simplify_meshes::*;
use stripkit::simplify::{simplify, Options, Placement, Target};

#[test]
fn bunny_and_horse_replay_and_stay_valid() {
    let Some(dir) = support::models_dir() else { return };
    for (file, closed) in [("bunny.obj", false), ("horse.ply", true)] {
        let mesh = match stripkit::io::read(dir.join(file)) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("skipped {file}: {e}");
                continue;
            }
        };
        let input = mesh.triangulate().tris;
        for placement in [Placement::Endpoint, Placement::Optimal] {
            let opts = Options::default().target(Target::Ratio(0.01)).placement(placement);
            let s = simplify(&mesh, &opts, &mut |_| {}).unwrap();
            assert!(s.triangles_out() <= input.len().div_ceil(100) + 1, "{file}: {}", s.triangles_out());
            let replay = s.sequence.replay(&mesh, s.sequence.len()).unwrap();
            // The replay rebuilds the surface (positions and faces); the attributes the
            // simplifier carried (horse.ply's normals) are not part of the sequence.
            let r = replay.to_mesh();
            assert!(
                r.positions == s.mesh.positions && r.face_offsets == s.mesh.face_offsets && r.face_indices == s.mesh.face_indices,
                "{file} {placement:?}: replay differs"
            );
            for (t, &id) in s.mesh.triangulate().tris.iter().zip(&s.triangle_ids) {
                let n = normal(&s.mesh, *t);
                let n0 = normal(&mesh, input[id as usize]);
                assert!(n.iter().any(|&x| x != 0.0), "{file}: degenerate triangle");
                assert!(n[0] * n0[0] + n[1] * n0[1] + n[2] * n0[2] > 0.0, "{file}: triangle {id} flipped");
            }
            if closed {
                assert_eq!(assert_closed_manifold(&s.mesh), 2, "{file} {placement:?}");
            }
        }
    }
}

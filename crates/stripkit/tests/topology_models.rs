//! `MeshFacts` on the research meshes must reproduce the figures that
//! `../shared/models/README.md` lists (skipped when that folder is absent).

mod support;

use stripkit::MeshFacts;
use support::models_dir;

/// file, V, F, bnd, nm-e, nm-v, comp, χ, unreferenced (None where the README gives none).
/// The README's `comp` joins faces that share a vertex, as `MeshFacts::components` does.
type Row = (&'static str, usize, usize, usize, usize, usize, usize, i64, Option<usize>);

const ROWS: &[Row] = &[
    ("bunny.obj", 35947, 69451, 223, 0, 0, 1, -3, Some(1113)),
    ("bunny_small.off", 3485, 6966, 0, 0, 0, 1, 2, None),
    ("bunny_res2.ply", 8171, 16301, 123, 150, 0, 1, 84, Some(25)),
    ("bunny_res3.ply", 1889, 3851, 60, 141, 4, 1, 77, Some(2)),
    ("bunny_res4.ply", 453, 948, 26, 70, 4, 1, 38, None),
    ("cow.obj", 2903, 5804, 0, 0, 1, 1, 1, None),
    ("cow_tristrips.ply", 2903, 5804, 0, 0, 1, 1, 1, None),
    ("horse.ply", 48485, 96966, 0, 0, 0, 1, 2, None),
    ("dragon.obj", 50000, 100000, 0, 0, 0, 1, 0, None),
    ("fandisk.obj", 6475, 12946, 0, 0, 0, 1, 2, None),
    ("spot_triangulated.obj", 2930, 5856, 0, 0, 0, 1, 2, None),
    ("quads/fandisk_quads.off", 766, 764, 0, 0, 0, 1, 2, None),
    ("quads/halftunnel.off", 831, 784, 96, 0, 0, 1, -1, None),
    ("quads/inspired_mesh_quads_Conjugate.off", 1749, 1633, 230, 0, 0, 1, 1, None),
    ("quads/horse_quad.obj", 2400, 2398, 0, 0, 0, 1, 2, None),
    ("quads/spot_quadrangulated.obj", 2930, 2928, 0, 0, 0, 1, 2, None),
    ("quads/spot_control_mesh.obj", 188, 180, 0, 0, 0, 1, 2, None),
];

fn check(dir: &std::path::Path, row: &Row) -> MeshFacts {
    let &(file, v, f, bnd, nme, nmv, comp, chi, unref) = row;
    let mesh = support::read_surface(&dir.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
    let facts = MeshFacts::of(&mesh).unwrap();
    let got = (facts.vertices, facts.faces, facts.boundary_edges, facts.nonmanifold_edges);
    assert_eq!(got, (v, f, bnd, nme), "{file}: V, F, bnd, nm-e");
    assert_eq!(
        (facts.nonmanifold_vertices, facts.components, facts.euler_characteristic),
        (nmv, comp, chi),
        "{file}: nm-v, comp, χ"
    );
    // Edge-connected components: one everywhere but in bunny_res4.ply, where one
    // triangle touches the rest at two vertices and shares no edge.
    let edge_components = if file == "bunny_res4.ply" { 2 } else { 1 };
    assert_eq!(facts.edge_components, edge_components, "{file}: edge-connected components");
    if let Some(u) = unref {
        assert_eq!(facts.unreferenced_vertices, u, "{file}: unreferenced");
    }
    // "No file has degenerate faces and every file is consistently oriented."
    assert!(facts.consistently_oriented, "{file}: orientation");
    assert_eq!(facts.degenerate_faces, 0, "{file}: degenerate");
    facts
}

#[test]
fn facts_match_the_models_readme() {
    let Some(dir) = models_dir() else { return };
    for row in ROWS {
        check(&dir, row);
    }
}

#[test]
fn bunny_has_five_boundary_loops_and_halftunnel_three() {
    let Some(dir) = models_dir() else { return };
    let bunny = check(&dir, &ROWS[0]);
    assert_eq!(bunny.boundary_loops, 5);
    let tunnel = check(&dir, &ROWS[12]);
    assert_eq!(tunnel.boundary_loops, 3);
    let control = check(&dir, &ROWS[16]);
    assert_eq!((control.triangles, control.quads, control.polygons), (4, 160, 16));
    let quads = check(&dir, &ROWS[15]);
    assert_eq!(quads.quads, 2928);
}

//! Every research mesh in ../shared/models loads with the vertex and face counts its
//! README lists (skipped when the folder is absent).

mod support;

use stripkit::io;
use support::models_dir;

/// (file, V, F) from the README's tables, read as surfaces (positions only).
const MODELS: &[(&str, usize, usize)] = &[
    ("bunny.obj", 35947, 69451),
    ("bunny_small.off", 3485, 6966),
    ("bunny_res2.ply", 8171, 16301),
    ("bunny_res3.ply", 1889, 3851),
    ("bunny_res4.ply", 453, 948),
    ("cow.obj", 2903, 5804),
    ("cow_tristrips.ply", 2903, 5804),
    ("horse.ply", 48485, 96966),
    ("dragon.obj", 50000, 100000),
    ("fandisk.obj", 6475, 12946),
    ("spot_triangulated.obj", 2930, 5856),
    ("quads/fandisk_quads.off", 766, 764),
    ("quads/halftunnel.off", 831, 784),
    ("quads/inspired_mesh_quads_Conjugate.off", 1749, 1633),
    ("quads/horse_quad.obj", 2400, 2398),
    ("quads/spot_quadrangulated.obj", 2930, 2928),
    ("quads/spot_control_mesh.obj", 188, 180),
    ("sequences/horse-gallop/horse-gallop-01.obj.gz", 8431, 16843),
    ("sequences/cat-poses/cat-01.obj.gz", 7207, 14410),
];

#[test]
fn every_model_loads_with_its_listed_counts() {
    let Some(dir) = models_dir() else { return };
    for &(name, v, f) in MODELS {
        let mesh = support::read_surface(&dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!((mesh.vertex_count(), mesh.face_count()), (v, f), "{name}");
        assert!(mesh.positions.iter().flatten().all(|c| c.is_finite()), "{name}");
    }
}

/// Read with their attributes, the spot models have one vertex per (position, UV)
/// pair: the files' 3,225 UVs (2,930 positions).
#[test]
fn spot_models_weld_one_vertex_per_uv() {
    let Some(dir) = models_dir() else { return };
    for name in ["spot_triangulated.obj", "quads/spot_quadrangulated.obj"] {
        let mesh = io::read(dir.join(name)).unwrap();
        assert_eq!(mesh.vertex_count(), 3225, "{name}");
        assert_eq!(mesh.attribute("TEXCOORD_0").map(|a| a.len()), Some(3225), "{name}");
    }
}

#[test]
fn quad_models_keep_their_polygons() {
    let Some(dir) = models_dir() else { return };
    for name in ["quads/fandisk_quads.off", "quads/horse_quad.obj", "quads/spot_quadrangulated.obj"] {
        assert!(support::read_surface(&dir.join(name)).unwrap().is_quad_mesh(), "{name}");
    }
    let cage = io::read(dir.join("quads/spot_control_mesh.obj")).unwrap();
    let mut sizes = [0usize; 8];
    for f in cage.faces() {
        sizes[f.len().min(7)] += 1;
    }
    assert_eq!((sizes[3], sizes[4], sizes[5]), (4, 160, 16));
}

/// Oriented triangles up to rotation: the smallest index first.
fn canonical(t: &[u32]) -> [u32; 3] {
    let r = (0..3).min_by_key(|&k| t[k]).unwrap();
    [t[r], t[(r + 1) % 3], t[(r + 2) % 3]]
}

#[test]
fn cow_strips_decode_to_the_faces_of_cow_obj() {
    let Some(dir) = models_dir() else { return };
    let strips = io::read(dir.join("cow_tristrips.ply")).unwrap();
    let faces = io::read(dir.join("cow.obj")).unwrap();
    assert_eq!(strips.positions, faces.positions);
    let mut a: Vec<[u32; 3]> = strips.faces().map(canonical).collect();
    let mut b: Vec<[u32; 3]> = faces.faces().map(canonical).collect();
    assert_eq!(a.len(), 5804);
    a.sort_unstable();
    b.sort_unstable();
    assert_eq!(a, b);
}

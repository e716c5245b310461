//! The cache-aware stripifier (`cache` and `balanced`) through the front door: the
//! strips do not depend on the face order or the vertex ids, polygons keep their fans
//! in every split, issue #4's points on the research meshes; the FIFO figures checked
//! by hand. (The stripifier's own knobs, on raw triangle lists, are tested inside the
//! crate: `src/tests/cache.rs`.)

mod support;

use stripkit::{
    cache_misses, decode, stripify, verify, Algorithm, CacheKind, Figures, Mesh, Split, StripOptions, StripSet,
    Strips,
};

use stripkit_testkit::XorShift64 as Rng;

/// A torus of `n x m` quads, each split along a random diagonal.
fn torus(n: u32, m: u32, rng: &mut Rng) -> Vec<[u32; 3]> {
    let id = |x: u32, y: u32| (y % m) * n + (x % n);
    let mut tris = Vec::new();
    for y in 0..m {
        for x in 0..n {
            let (a, b, c, d) = (id(x, y), id(x + 1, y), id(x + 1, y + 1), id(x, y + 1));
            if rng.below(2) == 0 {
                tris.push([a, b, d]);
                tris.push([b, c, d]);
            } else {
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            }
        }
    }
    tris
}

/// The door with `algorithm` and `split` (verified by the door itself).
fn door(mesh: &Mesh, algorithm: &Algorithm, split: Split) -> Strips {
    let options = StripOptions::default().algorithm(algorithm.clone()).split(split);
    let strips = stripify(mesh, &options).unwrap_or_else(|e| panic!("{algorithm:?} {split:?}: {e}"));
    assert!(strips.figures.verified && strips.figures.winding_preserved, "{algorithm:?} {split:?}");
    strips
}

/// `cache` and `balanced` as the CLI runs them (FIFO 16, balanced bound 0.8).
fn both() -> [Algorithm; 2] {
    [Algorithm::cache(), Algorithm::balanced(0.8)]
}

#[test]
fn fifo_figures_match_a_hand_count() {
    // Cache of 3. Triangles (0,1,2) (2,1,3) (3,4,0) (0,2,4):
    // 0 1 2 miss miss miss -> [0 1 2]; 2 1 hit, 3 miss evicts 0 -> [1 2 3];
    // 3 hit, 4 miss evicts 1 -> [2 3 4], 0 miss evicts 2 -> [3 4 0];
    // 0 hit, 2 miss evicts 3 -> [4 0 2], 4 hit (a hit does not reorder). 7 misses.
    let tris = [[0, 1, 2], [2, 1, 3], [3, 4, 0], [0, 2, 4]];
    assert_eq!(cache_misses(&tris, 5, 3, CacheKind::Fifo), 7);
    // FIFO and LRU differ once a hit would refresh an entry:
    let tris = [[0, 1, 2], [0, 3, 4], [0, 5, 6]];
    // FIFO 4: 0 1 2 3 miss, 4 evicts 0; 0 misses again evicting 1, 5 evicts 2, 6 evicts 3.
    assert_eq!(cache_misses(&tris, 7, 4, CacheKind::Fifo), 8);
    // LRU 4: 0 1 2 miss; 0 hits and moves to the front, 3 misses, 4 evicts 1; 0 hits,
    // 5 evicts 2, 6 evicts 3: 7 misses.
    assert_eq!(cache_misses(&tris, 7, 4, CacheKind::Lru), 7);
    // A single strip over a 1 x 3 band: 8 vertices, each missed once in a cache of 16.
    let strips = StripSet::from_strips(&[vec![0, 4, 1, 5, 2, 6, 3, 7]]);
    let decoded = decode(&strips);
    assert_eq!(cache_misses(&decoded, 8, 16, CacheKind::Fifo), 8);
}

/// `mesh` with its vertices renumbered by a pseudo-random permutation (positions moved
/// along), and the permutation (new id of every old vertex).
fn renumbered(mesh: &Mesh, seed: u64) -> (Mesh, Vec<u32>) {
    let n = mesh.vertex_count();
    let mut rng = Rng(seed);
    let mut perm: Vec<u32> = (0..n as u32).collect();
    for i in (1..n).rev() {
        perm.swap(i, rng.below(i + 1));
    }
    let mut positions = vec![[0f32; 3]; n];
    for v in 0..n {
        positions[perm[v] as usize] = mesh.positions[v];
    }
    let faces: Vec<Vec<u32>> = mesh.faces().map(|f| f.iter().map(|&v| perm[v as usize]).collect()).collect();
    (Mesh::from_polygons(positions, &faces), perm)
}

#[test]
fn stripify_gives_the_same_strips_for_any_face_order_and_vertex_ids() {
    // An irregular triangle mesh (a torus with random diagonals), its faces shuffled
    // and rotated and its vertices renumbered: the canonical order makes the strips
    // the same, vertex for vertex through the renumbering, in both modes.
    let mut rng = Rng(17);
    let tris = torus(60, 40, &mut rng);
    let positions: Vec<[f32; 3]> = stripkit::gen::torus(60, 40, 3.0, 1.0).positions;
    let mesh = Mesh::from_triangles(positions, &tris);
    for algorithm in both() {
        let a = door(&mesh, &algorithm, Split::Auto);
        assert!(verify(&tris, &a.strips).ok());
        for seed in [1, 2, 3] {
            let (other, perm) = renumbered(&stripkit::gen::shuffle_faces(&mesh, seed), seed + 100);
            let b = door(&other, &algorithm, Split::Auto);
            assert!(verify(&other.triangulate().tris, &b.strips).ok());
            let mapped: Vec<u32> = a.strips.indices.iter().map(|&v| perm[v as usize]).collect();
            assert_eq!(mapped, b.strips.indices, "{algorithm:?} seed {seed}");
            assert_eq!(a.strips.offsets, b.strips.offsets);
            assert_eq!(a.figures.acmr, b.figures.acmr);
        }
    }
}

#[test]
fn polygons_keep_their_fans_in_every_split() {
    // Quads, a hexagon (two quads merged) and triangles, shuffled: QSTRIP's split may
    // change the quads' diagonals but never a larger polygon's fan, the fan split
    // changes nothing; every result checked at quad level or against the fan (by the
    // door), the fan split against the fan here too.
    let grid = stripkit::gen::grid_quads(12, 10);
    let row = 13u32;
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for (f, face) in grid.faces().enumerate() {
        match f {
            // Quads 0 and 1 (bottom row) become one hexagon.
            0 => faces.push(vec![0, 1, 2, 2 + row, 1 + row, row]),
            1 => {}
            // Quad 30 becomes two triangles, its fan.
            30 => {
                faces.push(vec![face[0], face[1], face[2]]);
                faces.push(vec![face[0], face[2], face[3]]);
            }
            _ => faces.push(face.to_vec()),
        }
    }
    let mesh = Mesh::from_polygons(grid.positions.clone(), &faces);
    let mesh = stripkit::gen::shuffle_faces(&mesh, 9);
    for algorithm in both() {
        for split in [Split::Auto, Split::Fan, Split::Qstrip] {
            let m = door(&mesh, &algorithm, split);
            assert!(verify(&m.triangles, &m.strips).ok(), "{split:?}");
            if split != Split::Auto {
                assert_eq!(m.split, split);
            }
            if m.split == Split::Fan {
                assert!(verify(&mesh.triangulate().tris, &m.strips).ok(), "{split:?}");
            }
        }
    }
}

#[test]
fn issue_4_points_reached_with_the_flips() {
    // Issue #4's balanced point, at most 1.24 indices per triangle at acmr16 <= 0.8,
    // which the flips and balanced's search effort reach on horse (120,167 indices,
    // 71 under the limit; 121,305 before the flips) and spot_control_mesh (461, 465
    // with three passes); and its cache point with `refine` on bunny_res4: at most
    // 0.83x meshoptimizer's 1,613 indices (1,338) at no more than its 0.656 misses
    // per triangle (1,329 @ 0.632). `model` prints why it skips.
    let balanced = |name: &str| -> Option<Figures> {
        let mesh = support::model(name)?;
        Some(door(&mesh, &Algorithm::balanced(0.8), Split::Auto).figures)
    };
    for name in ["horse.ply", "quads/spot_control_mesh.obj"] {
        if let Some(f) = balanced(name) {
            eprintln!("{name}: {} @ {:.4}", f.indices_restart, f.acmr16);
            assert!(f.acmr16 <= 0.8, "{name}: {}", f.acmr16);
            assert!(
                f.indices_restart as f64 <= 1.24 * f.triangles as f64,
                "{name}: {} for {} triangles",
                f.indices_restart,
                f.triangles
            );
        }
    }
    if let Some(mesh) = support::model("bunny_res4.ply") {
        let f = door(&mesh, &Algorithm::Cache { refine: true }, Split::Auto).figures;
        eprintln!("bunny_res4 cache --refine: {} @ {:.4}", f.indices_restart, f.acmr16);
        assert!(f.verified && f.winding_preserved);
        assert!(f.indices_restart <= 1_338 && f.acmr16 <= 0.656);
    }
}

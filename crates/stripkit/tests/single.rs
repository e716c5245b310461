//! Single strips (`Algorithm::Single`) through the door: one strip per closed
//! component on random closed meshes for every weight kind, the changed mesh checked,
//! boundaries and non-manifold input handled, bad settings refused.

use stripkit::{gen, stripify, stripify_indices, Algorithm, Error, Mesh, SingleOptions, StripOptions, Weights};
use stripkit_testkit::XorShift64;

fn jitter(mesh: &Mesh, amount: f32, seed: u64) -> Mesh {
    let mut rng = XorShift64(seed.wrapping_mul(0x9E3779B97F4A7C15) | 1);
    let mut next = move || (rng.next() >> 11) as f32 / (1u64 << 53) as f32 - 0.5;
    let mut m = mesh.clone();
    for p in &mut m.positions {
        for x in p.iter_mut() {
            *x += amount * next();
        }
    }
    m
}

fn kinds() -> Vec<Weights> {
    vec![
        Weights::Uniform,
        Weights::Cache,
        Weights::Cull,
        Weights::Direction([0.0, 1.0, 0.0]),
        Weights::Mix(vec![(0.5, Weights::Cull), (0.5, Weights::Cache)]),
    ]
}

fn single(mesh: &Mesh, o: SingleOptions) -> stripkit::Strips {
    let s = stripify(mesh, &StripOptions::default().algorithm(Algorithm::Single(o.clone())))
        .unwrap_or_else(|e| panic!("{o:?}: {e}"));
    let f = &s.figures;
    assert!(f.verified && f.winding_preserved, "{o:?}: {f:?}");
    assert_eq!((f.lost, f.added, f.flipped), (0, 0, 0));
    s
}

/// Random closed meshes: the strips equal the components, whatever the weights.
#[test]
fn one_strip_per_closed_component() {
    let meshes = [
        ("icosphere 2 jittered", gen::shuffle_faces(&jitter(&gen::icosphere(2), 0.05, 1), 3)),
        ("icosphere 3 jittered", gen::renumber_vertices(&jitter(&gen::icosphere(3), 0.02, 2), 5)),
        ("torus 24x12", gen::shuffle_faces(&gen::torus(24, 12, 2.0, 0.6), 9)),
        ("torus 7x5", gen::torus(7, 5, 2.0, 0.6)),
        ("cube Loop x2", gen::subdivide_loop(&Mesh::from_triangles(gen::cube().positions, &gen::cube().triangulate().tris), 2).unwrap()),
        (
            "two spheres and a torus",
            gen::shuffle_faces(
                &gen::disjoint_union(&[&gen::icosphere(1), &jitter(&gen::icosphere(2), 0.03, 4), &gen::torus(10, 6, 2.0, 0.5)]),
                8,
            ),
        ),
    ];
    for (name, mesh) in &meshes {
        let n = mesh.triangle_count();
        for k in kinds() {
            for seed in [1, 2] {
                let s = single(mesh, SingleOptions::new(k.clone()).seed(seed));
                let r = s.single.as_ref().expect("single reports");
                assert_eq!(r.components, r.closed_components, "{name}");
                assert_eq!(s.figures.strips, r.components, "{name} {k}: {r:?}");
                assert_eq!(r.strips, r.components);
                // Each split adds a vertex and two triangles; swaps keep the count.
                assert_eq!(s.figures.triangles, n + 2 * r.steiner_vertices, "{name} {k}");
                assert_eq!(s.added_positions.len(), r.steiner_vertices);
                // Merging splits stay rare: a few, or at most 5% of the vertices. Cull
                // splits every cluster peak on purpose, and its loops keep to their
                // clusters (23 clusters on the 70 triangles of the 7x5 torus), so they
                // meet at few nodal vertices: at most one split per loop merged there.
                let merge_splits = r.steiner_vertices - r.cull_peaks;
                if r.clusters == 0 {
                    assert!(merge_splits <= 4 + mesh.vertex_count() / 20, "{name} {k}: {r:?}");
                }
                assert!(merge_splits < r.initial_pieces.max(1), "{name} {k}: {r:?}");
            }
        }
        // Without swaps the surface is untouched: the same strips, only splits.
        let s = single(mesh, SingleOptions::new(Weights::Uniform).swap_angle(None));
        let r = s.single.unwrap();
        assert_eq!((r.swapped_edges, s.figures.strips), (0, r.components), "{name}");
    }
}

/// The changed mesh is what the strips index, and what a file holds.
#[test]
fn changed_mesh_is_written_with_its_steiner_vertices() {
    let mesh = jitter(&gen::icosphere(3), 0.03, 7);
    let s = single(&mesh, SingleOptions::new(Weights::Cache).swap_angle(None));
    let r = s.single.clone().unwrap();
    assert!(r.steiner_vertices > 0, "this mesh needs splits: {r:?}");
    let changed = s.changed_mesh(&mesh);
    assert_eq!(changed.vertex_count(), mesh.vertex_count() + r.steiner_vertices);
    assert_eq!(changed.triangle_count(), s.triangles.len());
    for (i, p) in s.added_positions.iter().enumerate() {
        assert!(p.iter().all(|x| x.is_finite()), "Steiner vertex {i}");
    }
    let bytes = s.to_file_bytes(&mesh, stripkit::io::Format::Ply).unwrap();
    let back = stripkit::io::read_bytes("single.ply".as_ref(), stripkit::io::Format::Ply, &bytes).unwrap();
    assert_eq!(back.vertex_count(), changed.vertex_count());
}

/// Boundaries, non-manifold edges, degenerate and duplicate triangles: verified strips,
/// never a panic; a disc is one strip.
#[test]
fn open_and_non_manifold_meshes() {
    let grid = gen::shuffle_faces(&gen::grid(12, 9), 4);
    for k in kinds() {
        let s = single(&grid, SingleOptions::new(k.clone()));
        let r = s.single.unwrap();
        assert_eq!(r.components, 1);
        // No strip set of this grid has fewer than 9 strips (greedy's count): 18 ends
        // are forced, and every one is used.
        assert_eq!((r.forced_ends, s.figures.strips), (18, 9), "{k}: {r:?}");
    }
    // Three triangles on one edge, a degenerate triangle, a duplicate and a lone one.
    let pos = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [5.0, 5.0, 5.0], [6.0, 5.0, 5.0], [5.0, 6.0, 5.0]];
    let tris = [[0, 1, 2], [1, 0, 3], [1, 0, 4], [0, 1, 4], [2, 2, 1], [0, 1, 2], [5, 6, 7]];
    let mesh = Mesh::from_triangles(pos, &tris);
    for k in kinds() {
        let s = single(&mesh, SingleOptions::new(k));
        assert_eq!(s.figures.triangles + s.figures.dropped_degenerate, s.triangles.len());
    }
    // Random soups.
    let mut rng = stripkit_testkit::Lcg(99);
    for _ in 0..30 {
        let mut tris = Vec::new();
        for _ in 0..25 {
            let mut t = [0u32; 3];
            for x in &mut t {
                *x = rng.next() as u32 % 7;
            }
            tris.push(t);
        }
        let pos: Vec<[f32; 3]> = (0..7).map(|i| [(i * 7 % 5) as f32, (i * 3 % 4) as f32, (i % 3) as f32]).collect();
        single(&Mesh::from_triangles(pos, &tris), SingleOptions::new(Weights::Uniform));
    }
    // No faces: no strips.
    let s = single(&Mesh::new(), SingleOptions::default());
    assert_eq!(s.figures.strips, 0);
}

#[test]
fn weights_parse_and_bad_settings_are_refused() {
    assert_eq!("cache".parse::<Weights>().unwrap(), Weights::Cache);
    assert_eq!("direction:0,0,1".parse::<Weights>().unwrap(), Weights::Direction([0.0, 0.0, 1.0]));
    let mix: Weights = "mix:cull=0.5,cache=0.25,direction:1:0:0=1".parse().unwrap();
    assert_eq!(
        mix,
        Weights::Mix(vec![(0.5, Weights::Cull), (0.25, Weights::Cache), (1.0, Weights::Direction([1.0, 0.0, 0.0]))])
    );
    assert_eq!(mix.to_string().parse::<Weights>().unwrap(), mix);
    for bad in ["", "culls", "direction:0,0,0", "direction:1,2", "mix:", "mix:cull", "mix:cull=-1", "mix:cull=0", "mix:cull=nan"] {
        assert!(
            matches!(bad.parse::<Weights>(), Err(Error::BadOption { option: stripkit::OptionName::Weights, .. })),
            "{bad:?}"
        );
    }
    let mesh = gen::icosphere(1);
    for o in [SingleOptions::default().swap_angle(Some(90.0)), SingleOptions::default().cull_angle(0.0)] {
        let r = stripify(&mesh, &StripOptions::default().algorithm(Algorithm::Single(o)));
        assert!(matches!(r, Err(Error::BadOption { .. })));
    }
    // A plain index buffer cannot return Steiner vertices.
    let idx: Vec<u32> = mesh.triangulate().tris.iter().flatten().copied().collect();
    let r = stripify_indices(&idx, mesh.vertex_count(), &StripOptions::default().algorithm(Algorithm::Single(SingleOptions::default())));
    assert!(matches!(r, Err(Error::Invalid(_))));
}

mod soups {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Random soups on a few vertices of a coarse lattice (coplanar quads for swaps,
        /// non-manifold edges, duplicates, degenerate and flat triangles): every weight
        /// kind gives verified strips over a changed mesh that covers the input.
        #[test]
        fn soups_give_verified_single_strips(
            tris in prop::collection::vec((0u32..9, 0u32..9, 0u32..9), 1..48),
            lift in prop::collection::vec(0u8..3, 9),
            kind in 0usize..5,
            swap in prop::option::of(0.0f64..60.0),
        ) {
            let pos: Vec<[f32; 3]> = (0..9).map(|i| [(i % 3) as f32, (i / 3) as f32, lift[i] as f32 * 0.25]).collect();
            let tris: Vec<[u32; 3]> = tris.iter().map(|&(a, b, c)| [a, b, c]).collect();
            let mesh = Mesh::from_triangles(pos, &tris);
            let k = kinds()[kind].clone();
            single(&mesh, SingleOptions::new(k).swap_angle(swap));
        }
    }
}

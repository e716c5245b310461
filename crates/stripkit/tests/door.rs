//! The front door: every algorithm through `stripify` and `stripify_indices`, the
//! output decoded again by `unstripify` and compared with the input as multisets of
//! oriented triangles; the bound; the errors a user can cause.

mod support;

use proptest::prelude::*;
use stripkit::{
    decode, gen, io, stripify, stripify_bound, stripify_indices, unstripify, verify_triangles, Algorithm, Error,
    Join, Mesh, OptionName, Split, StripOptions,
};

use support::algorithms;
use stripkit_testkit::XorShift64;

/// Oriented triangles up to rotation, degenerate ones dropped, sorted.
fn oriented(flat: &[u32]) -> Vec<[u32; 3]> {
    let mut out: Vec<[u32; 3]> = flat
        .chunks_exact(3)
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .map(|t| {
            let r = (0..3).min_by_key(|&i| t[i]).unwrap();
            [t[r], t[(r + 1) % 3], t[(r + 2) % 3]]
        })
        .collect();
    out.sort_unstable();
    out
}

/// A grid of `w x h` quads, each split along a random diagonal, vertices renumbered by
/// a random permutation and triangles shuffled and rotated: a mesh no stripifier saw
/// in this order.
fn scrambled_grid(w: u32, h: u32, seed: u64) -> (Vec<u32>, usize) {
    let mut rng = XorShift64(seed | 1);
    let mut next = move || rng.next();
    let n = ((w + 1) * (h + 1)) as usize;
    let mut perm: Vec<u32> = (0..n as u32).collect();
    for i in (1..n).rev() {
        perm.swap(i, (next() % (i as u64 + 1)) as usize);
    }
    let id = |x: u32, y: u32| perm[(y * (w + 1) + x) as usize];
    let mut tris = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let (a, b, c, d) = (id(x, y), id(x + 1, y), id(x + 1, y + 1), id(x, y + 1));
            if next() % 2 == 0 {
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            } else {
                tris.push([a, b, d]);
                tris.push([b, c, d]);
            }
        }
    }
    for i in (1..tris.len()).rev() {
        tris.swap(i, (next() % (i as u64 + 1)) as usize);
    }
    let flat = tris
        .iter()
        .flat_map(|t| {
            let r = (next() % 3) as usize;
            [t[r], t[(r + 1) % 3], t[(r + 2) % 3]]
        })
        .collect();
    (flat, n)
}

fn round_trip(indices: &[u32], vertex_count: usize) {
    let want = oriented(indices);
    for algorithm in algorithms() {
        for join in [Join::Restart, Join::Degenerate] {
            let restart = vertex_count as u32;
            let options = StripOptions::default().algorithm(algorithm.clone()).join(join).restart_index(restart);
            let buf = stripify_indices(indices, vertex_count, &options)
                .unwrap_or_else(|e| panic!("{} {join:?}: {e}", algorithm.name()));
            assert!(buf.len() <= stripify_bound(indices.len()), "{} {join:?}: over the bound", algorithm.name());
            let back = unstripify(&buf, if join == Join::Restart { restart } else { u32::MAX });
            assert_eq!(oriented(&back), want, "{} {join:?}: triangles differ", algorithm.name());
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn scrambled_grids_round_trip_through_every_algorithm(w in 1u32..9, h in 1u32..9, seed in any::<u64>()) {
        let (indices, n) = scrambled_grid(w, h, seed);
        round_trip(&indices, n);
    }

    /// Triangles drawn at random from a handful of vertices: non-manifold edges,
    /// duplicates, degenerate triangles and isolated pieces.
    #[test]
    fn random_soups_round_trip(tris in prop::collection::vec((0u32..7, 0u32..7, 0u32..7), 1..40)) {
        let indices: Vec<u32> = tris.iter().flat_map(|&(a, b, c)| [a, b, c]).collect();
        round_trip(&indices, 7);
    }
}

#[test]
fn shuffled_meshes_give_verified_strips_for_every_algorithm() {
    let meshes = [
        gen::shuffle_faces(&gen::icosphere(2), 7),
        gen::shuffle_faces(&gen::torus(12, 8, 2.0, 0.5), 11),
        gen::shuffle_faces(&gen::grid_quads(6, 5), 3),
        gen::shuffle_faces(&gen::torus_quads(10, 6, 2.0, 0.5), 5),
    ];
    for mesh in &meshes {
        for algorithm in algorithms() {
            let s = stripify(mesh, &StripOptions::default().algorithm(algorithm.clone())).unwrap();
            assert!(s.figures.verified);
            assert_eq!(s.figures.triangles, mesh.triangle_count(), "{}", algorithm.name());
        }
    }
    // Auto takes QSTRIP on quad meshes, greedy on triangle meshes.
    let s = stripify(&meshes[3], &StripOptions::default()).unwrap();
    assert_eq!((s.algorithm.name(), s.split), ("qstrip", Split::Qstrip));
    assert_eq!(s.quads, Some(60));
    let s = stripify(&meshes[0], &StripOptions::default()).unwrap();
    assert_eq!((s.algorithm.name(), s.split), ("greedy", Split::Fan));
    // Quad-single on a closed quad mesh: one strip per component.
    let s = stripify(&meshes[3], &StripOptions::default().algorithm(Algorithm::QuadSingle)).unwrap();
    assert_eq!(s.figures.strips, 1);
    assert_eq!(s.quads, Some(60));
    // The cache-aware modes on the quads, with each split.
    for split in [Split::Auto, Split::Fan, Split::Qstrip] {
        let options = StripOptions::default().algorithm(Algorithm::balanced(0.8)).split(split);
        let s = stripify(&meshes[3], &options).unwrap();
        assert!(s.figures.acmr <= 0.8, "{split:?}: {}", s.figures.acmr);
        if split != Split::Auto {
            assert_eq!(s.split, split);
        }
    }
}

#[test]
fn the_joined_form_and_files_hold_the_same_triangles() {
    let mesh = gen::shuffle_faces(&gen::torus(10, 6, 2.0, 0.5), 1);
    for join in [Join::Restart, Join::Degenerate, Join::Separate] {
        let s = stripify(&mesh, &StripOptions::default().algorithm(Algorithm::cache()).join(join)).unwrap();
        assert_eq!(decode(&s.joined()).len(), s.figures.triangles);
        for format in [io::Format::Ply, io::Format::Glb, io::Format::Gltf] {
            let bytes = s.to_file_bytes(&mesh, format).unwrap();
            let back = io::read_bytes(std::path::Path::new("x"), format, &bytes).unwrap();
            assert!(verify_triangles(&s.triangles, &back.triangulate().tris).ok());
        }
        // OBJ holds no strips: their triangles, in strip order.
        let bytes = s.to_file_bytes(&mesh, io::Format::Obj).unwrap();
        let back = io::read_bytes(std::path::Path::new("x.obj"), io::Format::Obj, &bytes).unwrap();
        assert!(verify_triangles(&s.triangles, &back.triangulate().tris).ok());
        assert!(s.to_file_bytes(&mesh, io::Format::Off).is_err());
    }
    // A restart buffer separates as many strips as there are.
    let s = stripify(&mesh, &StripOptions::default()).unwrap();
    let buf = s.restart_buffer();
    assert_eq!(buf.len(), s.figures.indices_restart);
    assert_eq!(buf.iter().filter(|&&i| i == u32::MAX).count(), s.figures.strips - 1);
}

fn invalid(r: Result<impl std::fmt::Debug, Error>, needle: &str) {
    match r {
        Err(Error::Invalid(m)) => assert!(m.contains(needle), "{m:?} lacks {needle:?}"),
        other => panic!("expected an Invalid error with {needle:?}, got {other:?}"),
    }
}

/// An [`Error::BadOption`] naming `option`, its text holding `needle`.
fn bad_option(r: Result<impl std::fmt::Debug, Error>, option: OptionName, needle: &str) {
    match r {
        Err(e @ Error::BadOption { option: o, .. }) if o == option => {
            assert!(e.to_string().contains(needle), "{e} lacks {needle:?}")
        }
        other => panic!("expected a bad {option:?} with {needle:?}, got {other:?}"),
    }
}

#[test]
fn bad_input_and_options_that_do_not_apply_are_errors() {
    let d = StripOptions::default();
    let quad = [0, 1, 2, 0, 2, 3];
    invalid(stripify_indices(&[], 3, &d), "empty");
    invalid(stripify_indices(&[0, 1], 3, &d), "multiple of 3");
    invalid(stripify_indices(&[0, 1, 5], 3, &d), "vertex 5");
    bad_option(stripify_indices(&quad, 4, &d.clone().restart_index(2)), OptionName::RestartIndex, "restart index 2");
    bad_option(stripify_indices(&quad, 4, &d.clone().join(Join::Separate)), OptionName::Join, "separate");
    bad_option(stripify_indices(&quad, 4, &d.clone().cache_size(0)), OptionName::CacheSize, "cache");
    // Above MAX_CACHE_SIZE the cache-aware stripifiers' ring would follow the request
    // (u32::MAX once panicked; 2^32 tried 17 GB).
    for size in [stripkit::MAX_CACHE_SIZE + 1, u32::MAX as usize, usize::MAX] {
        for algo in [Algorithm::cache(), Algorithm::balanced(0.8), Algorithm::greedy()] {
            bad_option(
                stripify_indices(&quad, 4, &d.clone().algorithm(algo).cache_size(size)),
                OptionName::CacheSize,
                &format!("the cache size {size} is too large (at most 65536 entries)"),
            );
        }
    }
    assert!(stripify_indices(&quad, 4, &d.clone().algorithm(Algorithm::cache()).cache_size(stripkit::MAX_CACHE_SIZE)).is_ok());
    bad_option(stripify_indices(&quad, 4, &d.clone().algorithm(Algorithm::balanced(f64::NAN))), OptionName::MaxAcmr, "positive");
    bad_option(stripify_indices(&quad, 4, &d.clone().algorithm(Algorithm::balanced(0.0))), OptionName::MaxAcmr, "positive");
    bad_option(
        stripify_indices(&quad, 4, &d.clone().algorithm(Algorithm::greedy()).split(Split::Qstrip)),
        OptionName::Split,
        "greedy",
    );
    bad_option(stripify_indices(&quad, 4, &d.clone().algorithm(Algorithm::qstrip()).split(Split::Fan)), OptionName::Split, "qstrip");
    // Auto's choice is checked against the split too: QSTRIP on quads takes no fan.
    let quads = gen::grid_quads(3, 3);
    bad_option(stripify(&quads, &d.clone().split(Split::Fan)), OptionName::Split, "qstrip");
    assert!(stripify(&quads, &d.clone().split(Split::Qstrip)).is_ok());
    // A restart index at or past the vertices is fine, even one unused by any index.
    assert_eq!(stripify_indices(&quad, 5, &d.clone().restart_index(5)).unwrap().len(), 4);
    // With stitching the restart index is not used at all.
    assert_eq!(stripify_indices(&quad, 4, &d.clone().join(Join::Degenerate).restart_index(0)).unwrap().len(), 4);

    // The mesh door checks faces before any stripifier sees them.
    let mut m = Mesh::from_triangles(vec![[0.0; 3]; 3], &[[0, 1, 2]]);
    m.face_indices[2] = 9;
    invalid(stripify(&m, &d), "vertex 9");
    let m = Mesh::from_polygons(vec![[0.0; 3]; 3], &[vec![0u32, 1]]);
    invalid(stripify(&m, &d), "at least 3");
    bad_option(stripify(&gen::grid(2, 2), &d.clone().restart_index(3)), OptionName::RestartIndex, "restart index 3");
    // Quad-single refuses a mesh that is not closed and made of quads.
    invalid(stripify(&gen::grid_quads(2, 2), &d.clone().algorithm(Algorithm::QuadSingle)), "quad");
    // An empty mesh gives no strips, verified.
    let s = stripify(&Mesh::new(), &d).unwrap();
    assert!(s.figures.verified && s.strips.is_empty());
}

/// The algorithms of the door, each with the splits it accepts.
fn every_setting() -> Vec<StripOptions> {
    let mut out = Vec::new();
    for algorithm in [
        Algorithm::auto(),
        Algorithm::greedy(),
        Algorithm::qstrip(),
        Algorithm::cache(),
        Algorithm::Cache { refine: true },
        Algorithm::balanced(0.8),
    ] {
        let splits: &[Split] = match algorithm {
            Algorithm::Greedy(_) => &[Split::Auto, Split::Fan],
            Algorithm::Qstrip(_) => &[Split::Auto, Split::Qstrip],
            _ => &[Split::Auto, Split::Fan, Split::Qstrip],
        };
        for &split in splits {
            out.push(StripOptions::default().algorithm(algorithm.clone()).split(split));
        }
    }
    out
}

/// Non-degenerate triangles of the fan of every face (from its first corner).
fn fan_triangles(mesh: &Mesh) -> usize {
    mesh.triangulate().tris.iter().filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]).count()
}

fn positions(n: usize) -> Vec<[f32; 3]> {
    (0..n).map(|i| [(i % 5) as f32, (i / 5) as f32, ((i * 7) % 3) as f32]).collect()
}

/// Every algorithm with every split it takes gives verified strips drawing the fan's
/// non-degenerate triangles (auto with the fan on a quad-dominant mesh is refused:
/// auto takes QSTRIP there, which takes no fan).
fn strips_every_face_with_every_setting(name: &str, mesh: &Mesh) {
    let want = fan_triangles(mesh);
    for options in every_setting() {
        let what = format!("{name}: {} split {:?}", options.algorithm.name(), options.split);
        if options.algorithm == Algorithm::auto() && options.split == Split::Fan && stripkit::is_quad_dominant(mesh) {
            assert!(matches!(stripify(mesh, &options), Err(Error::BadOption { option: OptionName::Split, .. })), "{what}");
            continue;
        }
        let s = stripify(mesh, &options).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert!(s.figures.verified, "{what}");
        assert_eq!(s.figures.triangles, want, "{what}");
        assert_eq!(decode(&s.strips).len(), want, "{what}");
    }
}

#[test]
fn a_quad_that_repeats_a_vertex_is_fanned_from_its_first_corner() {
    // From an OBJ: `f 3 4 1 5` then `f 5 1 5 2`. The second face is no quad (vertex 5
    // twice): its fan from the first corner, (5,1,5) and (5,5,2), is degenerate. The
    // cache-aware modes on QSTRIP's diagonals once started it at its lowest vertex and
    // drew (1,5,2) and (1,2,5): two triangles no face has.
    let small = Mesh::from_polygons(positions(5), &[vec![2u32, 3, 0, 4], vec![4, 0, 4, 1]]);
    // The same faces (and every other rotation of a repeated-vertex quad) among the
    // quads of a grid, faces shuffled.
    let mut grid = gen::grid_quads(3, 3);
    for f in [[5u32, 6, 5, 9], [6, 5, 9, 5], [1, 1, 2, 6], [10, 11, 14, 14], [13, 9, 9, 14], [2, 3, 2, 3]] {
        grid.push_face(&f);
    }
    let grid = gen::shuffle_faces(&grid, 9);
    for (name, mesh) in [("two faces", &small), ("grid", &grid)] {
        strips_every_face_with_every_setting(name, mesh);
    }
}

#[test]
fn a_quad_listed_twice_is_stripped_twice() {
    // `qstrip` once refused a quad listed twice ("quad faces 0 and 3 give coincident
    // triangles"): the coincidence is the input's. Every algorithm draws both copies.
    let mut meshes = Vec::new();
    let one = Mesh::from_polygons(positions(4), &[vec![0u32, 1, 2, 3], vec![0, 1, 2, 3]]);
    meshes.push(("one quad twice", one));
    // A pillow (a quad and its reverse: their diagonals must differ) with the first
    // side listed again: forcing the copies apart too left no choice.
    let pillow = Mesh::from_polygons(
        positions(6),
        &[vec![0u32, 1, 2, 3], vec![3, 2, 1, 0], vec![1, 4, 5, 2], vec![0, 1, 2, 3]],
    );
    meshes.push(("a pillow with a side listed twice", pillow));
    let mut row = gen::grid_quads(3, 1);
    let first = row.face(0).to_vec();
    row.push_face(&first);
    meshes.push(("a row with face 0 again as face 3", row));
    let mut grid = gen::grid_quads(4, 3);
    for f in [0usize, 5, 5, 11] {
        let face = grid.face(f).to_vec();
        grid.push_face(&face);
    }
    // Also listed again in another rotation.
    let face = grid.face(7).to_vec();
    grid.push_face(&[face[2], face[3], face[0], face[1]]);
    meshes.push(("a grid with duplicates", gen::shuffle_faces(&grid, 4)));
    let mut torus = gen::torus_quads(8, 6, 2.0, 0.5);
    for f in [0usize, 1, 17] {
        let face = torus.face(f).to_vec();
        torus.push_face(&face);
    }
    meshes.push(("a closed torus with duplicates", torus));
    for (name, mesh) in &meshes {
        strips_every_face_with_every_setting(name, mesh);
    }
}

/// Found by the `read_ply` fuzz target: 13 quads in which the edge 7-8 has three
/// quads, so two quads share three vertices and one of them gets a forced diagonal.
/// QSTRIP's backward walk left its start quad through an edge that, with the forward
/// walk's exit, made a turn the forced diagonal forbids: the joined sequence had no
/// way through that quad (a `debug_assert!` in debug, `Error::Verification` in
/// release). The backward walk now only takes exits the start quad can turn to.
#[test]
fn qstrip_on_an_edge_with_three_quads_gives_verified_strips() {
    let faces: Vec<Vec<u32>> = [
        [1, 4, 5, 2],
        [2, 5, 6, 3],
        [4, 7, 8, 5],
        [5, 8, 9, 6],
        [6, 9, 7, 4],
        [9, 10, 11, 8],
        [8, 11, 12, 9],
        [9, 12, 10, 7],
        [10, 13, 14, 11],
        [12, 15, 13, 10],
        [13, 1, 2, 14],
        [14, 2, 3, 15],
        [15, 3, 1, 13],
    ]
    .iter()
    .map(|f| f.iter().map(|&v| v - 1).collect())
    .collect();
    let mesh = Mesh::from_polygons(positions(15), &faces);
    assert!(stripify(&mesh, &StripOptions::default().algorithm(Algorithm::greedy())).is_ok());
    for algorithm in [Algorithm::auto(), Algorithm::qstrip()] {
        let s = stripify(&mesh, &StripOptions::default().algorithm(algorithm)).unwrap();
        assert_eq!(s.figures.triangles, 26);
    }
}

/// Found by the `read_obj` fuzz target (63 faces, shrunk to these 4): quad 2 and its
/// flipped copy 3 must take opposite diagonals, and quad 0 shares three vertices with
/// both and one with quad 1's diagonal. Forcing pair by pair fixed quad 0's diagonal
/// for the pair (0, 1) first and left quads 2 and 3 no way apart: a coincident
/// triangle and `Error::Verification`. QSTRIP now solves such a cluster as a whole
/// (2-SAT). The strips must hold no two triangles on the same three vertices.
#[test]
fn qstrip_solves_a_cluster_of_quads_that_pairwise_forcing_gets_wrong() {
    let faces = [[2, 1, 7, 3], [0, 2, 3, 1], [2, 6, 7, 3], [2, 3, 7, 6]];
    let mesh = Mesh::from_polygons(positions(8), &faces);
    for algorithm in [Algorithm::auto(), Algorithm::qstrip()] {
        let s = stripify(&mesh, &StripOptions::default().algorithm(algorithm.clone()))
            .unwrap_or_else(|e| panic!("{}: {e}", algorithm.name()));
        let mut sets = support::drawn_sets(&s);
        assert_eq!(sets.len(), 8, "{}", algorithm.name());
        sets.dedup();
        assert_eq!(sets.len(), 8, "{}: coincident triangles", algorithm.name());
    }
}

/// Found by the `read_obj` fuzz target: one quad listed 100 times from different
/// corners and its flip listed 50 times, all on the edge 2-3 with the same third
/// vertex, more than QSTRIP pairs one by one. The flips must take the other diagonal
/// than the copies (the same diagonal gives the same triangles turned over), and the
/// copies must agree whatever corner they start from.
#[test]
fn qstrip_keeps_a_face_listed_many_times_apart_from_its_flip() {
    let quad = [2u32, 3, 7, 6];
    let flip = [2u32, 6, 7, 3];
    let faces: Vec<[u32; 4]> = (0..150)
        .map(|i| {
            let (q, r) = if i % 3 == 2 { (flip, i % 4) } else { (quad, i % 4) };
            [q[r], q[(r + 1) % 4], q[(r + 2) % 4], q[(r + 3) % 4]]
        })
        .collect();
    let mesh = Mesh::from_polygons(positions(8), &faces);
    for algorithm in [Algorithm::auto(), Algorithm::qstrip()] {
        let s = stripify(&mesh, &StripOptions::default().algorithm(algorithm.clone()))
            .unwrap_or_else(|e| panic!("{}: {e}", algorithm.name()));
        let drawn: Vec<[u32; 3]> = unstripify(&s.restart_buffer(), s.restart_index)
            .chunks_exact(3)
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .map(|t| [t[0], t[1], t[2]])
            .collect();
        assert_eq!(drawn.len(), 300, "{}", algorithm.name());
        // No three vertices drawn in both orientations.
        let canon = |t: [u32; 3]| {
            let r = (0..3).min_by_key(|&i| t[i]).unwrap();
            [t[r], t[(r + 1) % 3], t[(r + 2) % 3]]
        };
        let mut oriented: Vec<[u32; 3]> = drawn.iter().map(|&t| canon(t)).collect();
        oriented.sort_unstable();
        oriented.dedup();
        for t in &oriented {
            let back = canon([t[0], t[2], t[1]]);
            assert!(oriented.binary_search(&back).is_err(), "{}: {t:?} drawn both ways", algorithm.name());
        }
    }
}

/// Found by the `read_obj` fuzz target: 63 listings of one quad and 2 of another on
/// the same three vertices (a cluster over the size QSTRIP pairs one by one, so each
/// takes the diagonal away from the shared triangle), and elsewhere on the same edge
/// two quads on the same four vertices that clash whatever their diagonals. That
/// hopeless pair sent QSTRIP to its whole-cluster solver, which did not know the
/// diagonals already set and undid them.
#[test]
fn qstrip_keeps_the_diagonals_of_a_big_cluster_when_it_solves_another() {
    let mut faces: Vec<[u32; 4]> = vec![[4, 5, 9, 8]; 63];
    faces.extend([[4, 5, 9, 7], [4, 5, 9, 7], [0, 1, 4, 5], [0, 1, 5, 4]]);
    let mesh = Mesh::from_polygons(positions(10), &faces);
    for algorithm in [Algorithm::auto(), Algorithm::qstrip()] {
        let s = stripify(&mesh, &StripOptions::default().algorithm(algorithm.clone()))
            .unwrap_or_else(|e| panic!("{}: {e}", algorithm.name()));
        assert_eq!(s.figures.triangles, 2 * faces.len(), "{}", algorithm.name());
    }
}

/// Found by the `door_quads` fuzz target (through `cache`, which strips QSTRIP's
/// triangles of a renumbered copy): five quads on the same four vertices, a face, a
/// copy of it, its flip, and another order with its flip. QSTRIP's diagonals were
/// right; the quad check, handing the drawn triangles to the quads, gave the flip a
/// triangle of the other order and then called that an avoidable coincidence.
#[test]
fn quads_on_the_same_four_vertices_in_every_order_verify() {
    let faces = [[12u32, 4, 2, 10], [4, 2, 10, 12], [2, 12, 10, 4], [12, 10, 2, 4], [12, 2, 4, 10]];
    let mesh = Mesh::from_polygons(positions(13), &faces);
    for algorithm in [Algorithm::auto(), Algorithm::qstrip(), Algorithm::cache(), Algorithm::balanced(0.8)] {
        let s = stripify(&mesh, &StripOptions::default().algorithm(algorithm.clone()).split(Split::Qstrip))
            .unwrap_or_else(|e| panic!("{}: {e}", algorithm.name()));
        assert_eq!(s.figures.triangles, 10, "{}", algorithm.name());
    }
}

/// Random clusters of quads on five vertices (every cyclic order, copies, flips),
/// renumbered and shuffled: every quad algorithm and split verifies. Fixed seed.
#[test]
fn random_quad_clusters_on_few_vertices_verify() {
    let mut rng = XorShift64(0x2545_F491_4F6C_DD1D);
    let mut rnd = |n: u64| (rng.next() % n) as u32;
    for case in 0..400 {
        let k = 2 + rnd(9) as usize;
        let faces: Vec<[u32; 4]> = (0..k)
            .map(|_| loop {
                let q = [rnd(5), rnd(5), rnd(5), rnd(5)];
                if (0..4).all(|i| (i + 1..4).all(|j| q[i] != q[j])) {
                    break q;
                }
            })
            .collect();
        let mesh = Mesh::from_polygons(positions(5), &faces);
        for algorithm in [Algorithm::qstrip(), Algorithm::cache(), Algorithm::balanced(0.8)] {
            let options = StripOptions::default().algorithm(algorithm.clone()).split(Split::Qstrip);
            let s = stripify(&mesh, &options)
                .unwrap_or_else(|e| panic!("case {case} {faces:?} {}: {e}", algorithm.name()));
            assert_eq!(s.figures.triangles, 2 * k, "case {case} {}", algorithm.name());
        }
    }
}

//! The greedy stripifier through the front door, on procedural meshes, awkward
//! topology, shuffled inputs and (when present) the research meshes: every output
//! verified (by the door, and its joins here again), figures consistent. (The dual
//! graph it walks is tested inside the crate: `src/tests/dual_graph.rs`.)

mod support;

use stripkit::{
    decode_restart, encode_restart, encode_stitched, is_degenerate, stripify, verify, Algorithm, Figures,
    GreedyOptions, Heuristic, Mesh, StripOptions, StripSet, DEFAULT_RESTART,
};

const BOTH: [Heuristic; 2] = [Heuristic::Strips, Heuristic::Indices];

/// The door's greedy strips for a triangle list over `vertex_count` vertices (the
/// greedy stripifier needs no positions: they are all 0, placeholders, so welding,
/// which would merge them all, is off).
fn greedy(tris: &[[u32; 3]], vertex_count: usize, options: GreedyOptions) -> (StripSet, Figures) {
    let mesh = Mesh::from_triangles(vec![[0.0; 3]; vertex_count], tris);
    let options = StripOptions::default().algorithm(Algorithm::Greedy(options)).weld(false);
    let strips = stripify(&mesh, &options).unwrap_or_else(|e| panic!("{options:?}: {e}"));
    assert_eq!(strips.triangles, tris, "the door strips the triangles given");
    (strips.strips, strips.figures)
}

/// Stripifies, verifies and checks the bookkeeping identities; returns the figures.
fn check(tris: &[[u32; 3]], vertex_count: usize, heuristic: Heuristic) -> (StripSet, Figures) {
    let (strips, f) = greedy(tris, vertex_count, GreedyOptions::default().heuristic(heuristic));
    assert!(
        f.verified,
        "{heuristic:?}: {}",
        verify(tris, &strips)
    );
    assert!(f.winding_preserved);
    let degenerate = tris.iter().filter(|t| is_degenerate(t)).count();
    assert_eq!(f.dropped_degenerate, degenerate);
    // The other joins draw the same triangles.
    let stitched = StripSet::from_strips(&[encode_stitched(&strips)]);
    assert!(verify(tris, &stitched).ok(), "stitched");
    let restart = encode_restart(&strips, DEFAULT_RESTART);
    assert!(verify(
        tris,
        &decode_restart(&restart, DEFAULT_RESTART)
    )
    .ok());
    // Every strip is t + 2 + swaps long; the joins add one index each.
    if f.strips > 0 {
        assert_eq!(f.indices_separate, f.triangles + 2 * f.strips + f.swaps);
        assert_eq!(f.indices_restart, f.indices_separate + f.strips - 1);
    }
    (strips, f)
}

// ---- small generators (procedural meshes, consistently oriented) ----

fn triangles_of(mesh: Mesh) -> (Vec<[u32; 3]>, usize) {
    (mesh.triangulate().tris, mesh.vertex_count())
}

fn grid(w: u32, h: u32) -> (Vec<[u32; 3]>, usize) {
    triangles_of(stripkit::gen::grid(w, h))
}

fn torus(n: u32, m: u32) -> (Vec<[u32; 3]>, usize) {
    triangles_of(stripkit::gen::torus(n, m, 1.0, 0.3))
}

fn icosphere(levels: u32) -> (Vec<[u32; 3]>, usize) {
    triangles_of(stripkit::gen::icosphere(levels))
}

use stripkit_testkit::Lcg;

/// Shuffles the faces, renumbers the vertices and rotates each triangle.
fn shuffled(tris: &[[u32; 3]], vertex_count: usize, seed: u64) -> Vec<[u32; 3]> {
    let mut rng = Lcg(seed);
    let mut out = tris.to_vec();
    for i in (1..out.len()).rev() {
        out.swap(i, rng.below(i + 1));
    }
    let mut perm: Vec<u32> = (0..vertex_count as u32).collect();
    for i in (1..perm.len()).rev() {
        perm.swap(i, rng.below(i + 1));
    }
    for t in &mut out {
        *t = [
            perm[t[0] as usize],
            perm[t[1] as usize],
            perm[t[2] as usize],
        ];
        t.rotate_left(rng.below(3));
    }
    out
}

#[test]
fn grids_strip_well() {
    for (w, h) in [(1, 1), (1, 5), (7, 3), (20, 20)] {
        let (tris, n) = grid(w, h);
        for heur in BOTH {
            let (_, f) = check(&tris, n, heur);
            assert_eq!(f.triangles, tris.len());
            // A w x h grid is covered by h row strips at worst.
            assert!(
                f.strips <= h.max(1) as usize + 1,
                "{w}x{h} {heur:?}: {} strips",
                f.strips
            );
        }
    }
}

#[test]
fn icospheres_and_tori() {
    for levels in 0..4 {
        let (tris, n) = icosphere(levels);
        for heur in BOTH {
            let (_, f) = check(&tris, n, heur);
            assert_eq!(f.triangles, 20 * 4usize.pow(levels));
        }
    }
    for (a, b) in [(3, 3), (12, 5), (40, 30)] {
        let (tris, n) = torus(a, b);
        for heur in BOTH {
            check(&tris, n, heur);
        }
    }
    // A large regular mesh strips into long strips.
    let (tris, n) = icosphere(5);
    let (_, f) = check(&tris, n, Heuristic::Strips);
    assert!(
        f.strips * 100 < f.triangles,
        "{} strips for {} triangles",
        f.strips,
        f.triangles
    );
    let (_, f) = check(&tris, n, Heuristic::Indices);
    assert!(f.indices_per_triangle < 1.3, "{}", f.indices_per_triangle);
}

#[test]
fn shuffled_inputs_strip_as_well() {
    let (tris, n) = icosphere(4);
    for heur in BOTH {
        let (_, base) = check(&tris, n, heur);
        for seed in 1..4 {
            let s = shuffled(&tris, n, seed);
            let (_, f) = check(&s, n, heur);
            let allowed = base.indices_restart + base.indices_restart / 20;
            assert!(
                f.indices_restart <= allowed,
                "{heur:?} seed {seed}: {} vs {}",
                f.indices_restart,
                base.indices_restart
            );
        }
    }
}

#[test]
fn awkward_topology() {
    // Grid plus a fin on an interior edge (three faces on one edge), a second grid that
    // touches the first in one vertex, an isolated triangle, a back-to-back duplicate
    // pair, a region with flipped orientation, degenerate triangles.
    let (mut tris, mut n) = grid(6, 6);
    let fin = n as u32;
    tris.push([8, 16, fin]); // edge 8-16 is interior to the grid: now non-manifold
    tris.push([16, 8, fin + 1]);
    n += 2;
    let (g2, n2) = grid(3, 3);
    let base = n as u32 - 1; // vertex 0 of the second grid is the last vertex of the first
    tris.extend(g2.iter().map(|t| t.map(|v| v + base)));
    n = base as usize + n2;
    let lone = n as u32;
    tris.push([lone, lone + 1, lone + 2]);
    tris.push([lone + 3, lone + 4, lone + 5]);
    tris.push([lone + 3, lone + 5, lone + 4]);
    n += 6;
    // Flip every third triangle of the first grid's first row.
    for t in tris.iter_mut().take(12).step_by(3) {
        t.swap(1, 2);
    }
    tris.push([1, 1, 2]);
    tris.push([3, 4, 3]);
    for heur in BOTH {
        let (_, f) = check(&tris, n, heur);
        assert_eq!(f.dropped_degenerate, 2);
        assert_eq!(f.triangles, tris.len() - 2);
        for seed in 1..3 {
            check(&shuffled(&tris, n, seed), n, heur);
        }
    }
}

#[test]
fn tiny_inputs() {
    for heur in BOTH {
        let (s, f) = check(&[], 0, heur);
        assert!(s.is_empty());
        assert_eq!(f.strips, 0);
        let (_, f) = check(&[[0, 1, 2]], 3, heur);
        assert_eq!((f.strips, f.indices_restart), (1, 3));
        let (_, f) = check(&[[0, 0, 1]], 3, heur);
        assert_eq!((f.strips, f.triangles, f.dropped_degenerate), (0, 0, 1));
        let (_, f) = check(&[[0, 1, 2], [2, 1, 3]], 4, heur);
        assert_eq!((f.strips, f.indices_restart), (1, 4));
    }
}

#[test]
fn real_meshes_strip_as_well_shuffled() {
    let Some(dir) = support::models_dir() else {
        eprintln!("skipped: ../shared/models not found");
        return;
    };
    // The goal is 1%; horse's strips heuristic measures 0.9% for this seed.
    for (name, tolerance) in [("bunny.obj", 0.01), ("horse.ply", 0.02)] {
        let mesh = stripkit::io::read(dir.join(name)).unwrap();
        let tris = mesh.triangulate().tris;
        let n = mesh.vertex_count();
        for heur in BOTH {
            let (_, base) = check(&tris, n, heur);
            let (_, f) = check(&shuffled(&tris, n, 11), n, heur);
            let ratio = f.indices_restart as f64 / base.indices_restart as f64;
            eprintln!(
                "{name} {heur:?}: {} -> {} shuffled ({ratio:.4})",
                base.indices_restart, f.indices_restart
            );
            assert!((ratio - 1.0).abs() < tolerance, "{name} {heur:?}: {ratio}");
        }
    }
}

#[test]
fn real_meshes_when_present() {
    let Some(dir) = support::models_dir() else {
        eprintln!("skipped: ../shared/models not found");
        return;
    };
    for name in [
        "bunny_small.off",
        "cow.obj",
        "bunny_res3.ply",
        "fandisk.obj",
        "quads/halftunnel.off",
    ] {
        let mesh = match stripkit::io::read(dir.join(name)) {
            Ok(m) => m,
            Err(stripkit::Error::UnknownFormat { .. }) => {
                eprintln!("skipped {name}: no reader for it yet");
                continue;
            }
            Err(e) => panic!("{e}"),
        };
        let tris = mesh.triangulate().tris;
        for heur in BOTH {
            check(&tris, mesh.vertex_count(), heur);
            check(
                &shuffled(&tris, mesh.vertex_count(), 7),
                mesh.vertex_count(),
                heur,
            );
        }
    }
}

/// Figures of one configuration, verified.
fn run_with(tris: &[[u32; 3]], n: usize, options: GreedyOptions) -> Figures {
    let (strips, f) = greedy(tris, n, options);
    assert!(f.verified, "{options:?}: {}", verify(tris, &strips));
    f
}

#[test]
fn tunnelling_saves_indices_and_keeps_every_triangle() {
    let meshes = [
        icosphere(3),
        torus(40, 17),
        grid(31, 9),
        {
            let (t, n) = icosphere(3);
            (shuffled(&t, n, 5), n)
        },
        {
            let (t, n) = torus(33, 20);
            (shuffled(&t, n, 9), n)
        },
    ];
    let mut saved = 0i64;
    for (tris, n) in &meshes {
        for heuristic in BOTH {
            let plain = run_with(
                tris,
                *n,
                GreedyOptions::default().heuristic(heuristic).tunnel_cuts(None),
            );
            let mut last = plain.indices_restart;
            for cuts in [0, 1, 2, 3] {
                let f = run_with(
                    tris,
                    *n,
                    GreedyOptions::default().heuristic(heuristic).tunnel_cuts(Some(cuts)),
                );
                assert_eq!(f.triangles, plain.triangles);
                match heuristic {
                    // Strips: never more strips than the plain greedy.
                    Heuristic::Strips => assert!(f.strips <= plain.strips, "{cuts}: {} > {}", f.strips, plain.strips),
                    // Indices: the relinkings are scored exactly except for the one
                    // start-of-strip swap per strip the encoder settles: allow that.
                    Heuristic::Indices => assert!(
                        f.indices_restart <= plain.indices_restart + f.strips / 20 + 1,
                        "{cuts}: {} > {}",
                        f.indices_restart,
                        plain.indices_restart
                    ),
                }
                if heuristic == Heuristic::Indices {
                    last = last.min(f.indices_restart);
                }
            }
            saved += plain.indices_restart as i64 - last as i64;
        }
    }
    // The pass must actually find something on these meshes.
    assert!(saved > 0, "tunnelling saved nothing");
}

#[test]
fn bunny_meets_the_index_goal() {
    let Some(dir) = support::models_dir() else {
        eprintln!("skipped: ../shared/models not found");
        return;
    };
    let mesh = stripkit::io::read(dir.join("bunny.obj")).unwrap();
    let tris = mesh.triangulate().tris;
    let n = mesh.vertex_count();
    let f = run_with(&tris, n, GreedyOptions::default().heuristic(Heuristic::Indices));
    // Issue #3: at most 82,000 (the paper about 82,470, FTSG about 82,029).
    assert!(f.indices_restart <= 82_000, "{}", f.indices_restart);
    let f = run_with(&tris, n, GreedyOptions::default().heuristic(Heuristic::Strips));
    assert!(f.strips <= 563, "{}", f.strips);
}

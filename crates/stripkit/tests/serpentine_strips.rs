//! The experimental serpentine stripifier: every output verified with its winding on
//! procedural meshes, awkward topology, shuffled inputs and (when present) the research
//! meshes; shuffled input gives about the figures of ordered input.

use stripkit::gen;
use stripkit::metrics::{self, CacheModel, Figures};
use stripkit::strip;
use stripkit::stripify::serpentine::{self, SerpentineOptions};

/// Stripifies, verifies and checks the bookkeeping identities; returns the figures.
fn check(tris: &[[u32; 3]], vertex_count: usize, o: &SerpentineOptions) -> Figures {
    let strips = serpentine::stripify(tris, vertex_count, o);
    let f = metrics::figures(tris, &strips, CacheModel::fifo(16));
    assert!(f.verified, "{o:?}: {}", strip::verify(tris, &strips));
    assert!(f.winding_preserved);
    if f.strips > 0 {
        assert_eq!(f.indices_separate, f.triangles + 2 * f.strips + f.swaps);
    }
    f
}

fn options() -> Vec<SerpentineOptions> {
    let mut v: Vec<_> = [3, 8, 16, 32].map(SerpentineOptions::balanced).to_vec();
    v.push(SerpentineOptions {
        cache_size: 16,
        max_len: 1,
    });
    v.push(SerpentineOptions {
        cache_size: 0,
        max_len: 0,
    });
    v
}

/// Faces shuffled and rotated, vertices renumbered by a seeded permutation.
fn shuffled(mesh: &stripkit::mesh::Mesh, seed: u64) -> Vec<[u32; 3]> {
    let tris = gen::shuffle_faces(mesh, seed).triangulate().tris;
    let n = mesh.vertex_count();
    let mut perm: Vec<u32> = (0..n as u32).collect();
    let mut s = seed | 1;
    for i in (1..n).rev() {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        perm.swap(i, (s % (i as u64 + 1)) as usize);
    }
    tris.iter().map(|t| t.map(|v| perm[v as usize])).collect()
}

#[test]
fn procedural_meshes_verify() {
    let meshes = [
        gen::grid(40, 30),
        gen::icosphere(4),
        gen::torus(48, 24, 2.0, 0.5),
        gen::cube(),
    ];
    for m in &meshes {
        let tris = m.triangulate().tris;
        for o in options() {
            check(&tris, m.vertex_count(), &o);
        }
    }
    // A regular grid: short strips side by side reuse the cache well.
    let g = gen::grid(60, 60);
    let f = check(
        &g.triangulate().tris,
        g.vertex_count(),
        &SerpentineOptions::balanced(16),
    );
    assert!(
        f.acmr16 < 0.85 && f.indices_per_triangle < 1.45,
        "grid {f:?}"
    );
}

#[test]
fn boundaries_and_non_manifold_edges_verify() {
    // A fan, an edge shared by three triangles, one triangle flipped against its
    // neighbour, a degenerate triangle, an isolated triangle and an unused vertex.
    let tris = [
        [0, 1, 2],
        [0, 2, 3],
        [0, 3, 4],
        [0, 4, 5],
        [1, 0, 6],
        [0, 1, 7],
        [2, 1, 8],
        [9, 9, 3],
        [10, 11, 12],
        [3, 2, 13],
        [2, 3, 14],
    ];
    for o in options() {
        check(&tris, 16, &o);
    }
    check(&[], 0, &SerpentineOptions::balanced(16));
    // Indices above vertex_count are tolerated.
    check(
        &[[0, 1, 2], [2, 1, 30]],
        3,
        &SerpentineOptions::balanced(16),
    );
}

/// Issue #4 asks for 1%; this design does not reach it (ties are still broken by the
/// input order in places): measured on icosphere(5) ordered 26,153 indices at ACMR16
/// 0.750; shuffled (seeds 1 and 7) up to 1.5% more indices and 2.9% / 4.9% more
/// ACMR16. The bound guards against worse.
#[test]
fn shuffled_input_is_within_six_percent() {
    let m = gen::icosphere(5);
    let o = SerpentineOptions::balanced(16);
    let a = check(&m.triangulate().tris, m.vertex_count(), &o);
    for seed in [1, 7] {
        let b = check(&shuffled(&m, seed), m.vertex_count(), &o);
        let rel = |x: f64, y: f64| (x - y).abs() / y;
        assert!(
            rel(b.indices_restart as f64, a.indices_restart as f64) <= 0.06,
            "{a:?}\n{b:?}"
        );
        assert!(
            rel(b.acmr16, a.acmr16) <= 0.06,
            "{} vs {}",
            b.acmr16,
            a.acmr16
        );
    }
}

#[test]
fn research_models_verify() {
    let Some(dir) = stripkit::test_support::models_dir() else {
        println!("skipped: ../shared/models not found");
        return;
    };
    for name in ["bunny_res3.ply", "cow.obj", "fandisk.obj", "bunny.obj"] {
        let Ok(mesh) = stripkit::mesh::io::read(&dir.join(name)) else {
            println!("skipped {name}: not readable");
            continue;
        };
        let tris = mesh.triangulate().tris;
        let f = check(&tris, mesh.vertex_count(), &SerpentineOptions::balanced(16));
        // Measured (bunny: 1.372 indices per triangle at ACMR16 0.808); the bounds leave
        // room for tuning, not for a broken cache simulation.
        assert!(
            f.acmr16 < 0.87 && f.indices_per_triangle < 1.56,
            "{name}: {f:?}"
        );
        if name == "bunny.obj" {
            let s = check(
                &shuffled(&mesh, 3),
                mesh.vertex_count(),
                &SerpentineOptions::balanced(16),
            );
            assert!(
                s.acmr16 < 0.87 && s.indices_per_triangle < 1.45,
                "shuffled bunny: {s:?}"
            );
        }
    }
}

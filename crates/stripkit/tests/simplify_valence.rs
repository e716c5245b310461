//! The simplifier on meshes with one vertex (or edge) of very high valence (issue
//! #16): a star of triangles around one vertex, a non-manifold fan of triangles
//! sharing one edge, one polygon of many corners (fanned from its first corner).
//! Each collapse into such a vertex once re-planned all its edges: O(valence^2)
//! per collapse (> 300 s on a star of 10^5 triangles). These tests check the
//! results (target reached, a valid mesh, the sequence replays to it, the centre
//! kept); they assert no times (see docs/experiments/valence-simplify.md). Sizes:
//! large enough that the old quadratic behaviour would not finish in debug; the
//! largest ones run in release builds only.

mod valence_meshes;

use stripkit::simplify::{simplify, Options, Placement, Simplified, Target};
use stripkit::Mesh;
use valence_meshes::{edge_fan, polygon, star};

fn run(mesh: &Mesh, placement: Placement, ratio: f64) -> Simplified {
    let opts = Options::default().target(Target::Ratio(ratio)).placement(placement);
    simplify(mesh, &opts, &mut |_| {}).expect("simplify")
}

fn normal(p: &[[f32; 3]], t: [u32; 3]) -> [f64; 3] {
    let [a, b, c] = t.map(|v| p[v as usize].map(f64::from));
    stripkit_testkit::geom::tri_normal(a, b, c)
}

/// Target reached (not overshot by more than the last collapse), every triangle
/// valid (distinct corners, non-zero area, not turned over against its input
/// ancestor), no triangle twice, every triangle still around `centre` (a hub while
/// it is in more than 256 triangles, never removed), and the sequence replays to
/// the same mesh.
fn check(input: &Mesh, s: &Simplified, ratio: f64, centre: &[u32]) {
    let target = (s.triangles_in as f64 * ratio).ceil() as usize;
    assert_eq!(s.triangles_in, input.triangle_count());
    assert!(s.triangles_out() <= target && s.triangles_out() + 2 >= target, "{} for a target of {target}", s.triangles_out());
    let tris = s.mesh.triangulate().tris;
    let ancestors = input.triangulate().tris;
    assert_eq!(tris.len(), s.triangles_out());
    let mut seen: Vec<[u32; 3]> = Vec::with_capacity(tris.len());
    for (t, &id) in tris.iter().zip(&s.triangle_ids) {
        assert!(t[0] != t[1] && t[1] != t[2] && t[2] != t[0], "{t:?}");
        assert!(t.iter().all(|&v| (v as usize) < s.mesh.positions.len()));
        for c in centre {
            assert!(t.contains(c), "{t:?} lost the centre {c}");
        }
        // (An untouched input triangle may be degenerate in f32 already: the
        // polygon's last slivers next to its first corner.)
        if *t != ancestors[id as usize] {
            let n1 = normal(&s.mesh.positions, *t);
            let n0 = normal(&input.positions, ancestors[id as usize]);
            assert!(n1[0] * n0[0] + n1[1] * n0[1] + n1[2] * n0[2] > 0.0, "{t:?} turned over or degenerate");
        }
        let mut key = *t;
        key.sort_unstable();
        seen.push(key);
    }
    seen.sort_unstable();
    assert!(seen.windows(2).all(|w| w[0] != w[1]), "a triangle twice");
    let replay = s.sequence.replay(input, s.sequence.len()).unwrap();
    assert_eq!(replay.to_mesh(), s.mesh);
    assert_eq!(replay.triangle_ids, s.triangle_ids);
}

/// A disc stays a disc: every edge in at most two triangles, and the area of the
/// star barely shrinks (its border is held by the boundary planes).
fn check_disc(input: &Mesh, s: &Simplified) {
    let area_of = |m: &Mesh| -> f64 { m.triangulate().tris.iter().map(|&t| normal(&m.positions, t)[2] * 0.5).sum() };
    let area_in = area_of(input);
    let tris = s.mesh.triangulate().tris;
    let mut edges: Vec<(u32, u32)> = tris
        .iter()
        .flat_map(|t| (0..3).map(move |e| (t[e].min(t[(e + 1) % 3]), t[e].max(t[(e + 1) % 3]))))
        .collect();
    edges.sort_unstable();
    assert!(edges.windows(3).all(|w| !(w[0] == w[1] && w[1] == w[2])), "an edge in three triangles");
    let area = area_of(&s.mesh);
    assert!(area > 0.9 * area_in && area <= area_in * (1.0 + 1e-6), "area {area} of {area_in}");
}

#[test]
fn star_of_20k_triangles_halves_and_stays_a_disc() {
    let n = 20_000;
    let mesh = star(n);
    for placement in [Placement::Endpoint, Placement::Optimal] {
        let s = run(&mesh, placement, 0.5);
        check(&mesh, &s, 0.5, &[0]);
        check_disc(&mesh, &s);
        assert_eq!(s.mesh.positions[0], [0.0; 3], "the centre moved");
    }
    // Down to 200 triangles: the centre is an ordinary vertex again below 257
    // triangles and may go.
    let s = run(&mesh, Placement::Endpoint, 0.01);
    check(&mesh, &s, 0.01, &[]);
    check_disc(&mesh, &s);
}

#[test]
fn fan_of_10k_triangles_on_one_edge_halves_around_the_edge() {
    let mesh = edge_fan(10_000);
    for (placement, ratio) in [(Placement::Endpoint, 0.5), (Placement::Optimal, 0.5), (Placement::Endpoint, 0.01)] {
        let s = run(&mesh, placement, ratio);
        // Every surviving triangle is still on the shared edge: its two ends are
        // hubs, never removed; two rim vertices never merge (that would put one
        // triangle on the edge twice).
        check(&mesh, &s, ratio, &[0, 1]);
    }
}

#[test]
fn polygon_of_50k_corners_halves_as_a_fan_from_its_first_corner() {
    let n = 50_000;
    let mesh = polygon(n);
    let s = run(&mesh, Placement::Endpoint, 0.5);
    check(&mesh, &s, 0.5, &[0]);
    check_disc(&mesh, &s);
}

#[test]
fn pair_contraction_around_a_hub_reaches_its_target() {
    let mesh = star(10_000);
    let opts = Options::default().target(Target::Ratio(0.1)).pair_distance(Some(1e-3));
    let s = simplify(&mesh, &opts, &mut |_| {}).expect("simplify");
    check(&mesh, &s, 0.1, &[0]);
}

/// The issue's sizes; release builds only (a debug build takes minutes at 10^6).
#[cfg(not(debug_assertions))]
#[test]
fn issue_sizes_release_only() {
    let mesh = star(100_000);
    let s = run(&mesh, Placement::Endpoint, 0.5);
    check(&mesh, &s, 0.5, &[0]);
    let mesh = edge_fan(20_000);
    let s = run(&mesh, Placement::Endpoint, 0.5);
    check(&mesh, &s, 0.5, &[0, 1]);
    let mesh = polygon(1_000_000);
    let s = run(&mesh, Placement::Endpoint, 0.5);
    check(&mesh, &s, 0.5, &[0]);
    check_disc(&mesh, &s);
}

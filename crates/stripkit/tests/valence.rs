//! Valid meshes with one vertex or one edge of very high valence (issue #16): every
//! algorithm through the door on a star of 20,000 triangles around one vertex and on
//! 20,000 triangles sharing one edge. The strips must verify and keep the figures a
//! fan allows. (Times are not asserted here; they are measured with the release CLI
//! in docs/experiments/valence.md. Before the fix, cache and balanced took
//! O(valence^2) walks on these meshes.)

mod support;

use stripkit::{stripify, Algorithm, Error, GreedyOptions, Heuristic, Mesh, StripOptions, MAX_TUNNEL_CUTS};

const N: u32 = 20_000;

/// Vertex 0 at the centre, `n` rim vertices on a circle, triangles (0, 1 + i, 1 + (i + 1) % n):
/// a closed fan, the centre in every triangle.
fn star(n: u32) -> Mesh {
    let mut positions = vec![[0.0f32; 3]];
    positions.extend((0..n).map(|i| {
        let a = std::f32::consts::TAU * i as f32 / n as f32;
        [a.cos(), a.sin(), 0.0]
    }));
    let tris: Vec<[u32; 3]> = (0..n).map(|i| [0, 1 + i, 1 + (i + 1) % n]).collect();
    Mesh::from_triangles(positions, &tris)
}

/// Vertices 0 and 1 on an axis, `n` vertices on a circle between them, triangles
/// (0, 1, 2 + i): every triangle on the one edge {0, 1} (non-manifold).
fn edge_fan(n: u32) -> Mesh {
    let mut positions = vec![[0.0f32, 0.0, 0.0], [0.0, 0.0, 1.0]];
    positions.extend((0..n).map(|i| {
        let a = std::f32::consts::TAU * i as f32 / n as f32;
        [a.cos(), a.sin(), 0.5]
    }));
    let tris: Vec<[u32; 3]> = (0..n).map(|i| [0, 1, 2 + i]).collect();
    Mesh::from_triangles(positions, &tris)
}

/// The door's algorithms plus the deepest tunnel search. `batch` has swap-free strips,
/// so a fan costs it more than the bounds below: it has its own test at the end.
fn algorithms() -> Vec<Algorithm> {
    let mut all: Vec<Algorithm> = support::algorithms().into_iter().filter(|a| a.name() != "batch").collect();
    all.push(Algorithm::Greedy(GreedyOptions::default().heuristic(Heuristic::Indices).tunnel_cuts(Some(MAX_TUNNEL_CUTS))));
    all
}

/// Strips `mesh` with every algorithm; checks the verification and returns, per
/// algorithm, its name, strips and restart-joined index count.
fn every_algorithm(mesh: &Mesh, n: u32) -> Vec<(String, usize, usize)> {
    let mut out = Vec::new();
    for a in algorithms() {
        let s = stripify(mesh, &StripOptions::default().algorithm(a.clone()))
            .unwrap_or_else(|e| panic!("{a:?}: {e}"));
        let f = &s.figures;
        assert!(f.verified && f.winding_preserved, "{a:?}: {f:?}");
        assert_eq!((f.triangles, f.lost, f.added, f.flipped), (n as usize, 0, 0, 0), "{a:?}");
        out.push((format!("{a:?}"), f.strips, f.indices_restart));
    }
    out
}

#[test]
fn star_of_20k_triangles_around_one_vertex() {
    let mesh = star(N);
    for (a, strips, indices) in every_algorithm(&mesh, N) {
        // A fan is one strip with a swap per triangle: two indices per triangle; every
        // algorithm gets there within a few strips.
        assert!(strips <= 4, "{a}: {strips} strips");
        assert!(indices <= 2 * N as usize + 8, "{a}: {indices} indices");
    }
}

#[test]
fn twenty_thousand_triangles_on_one_edge() {
    let mesh = edge_fan(N);
    for (a, strips, indices) in every_algorithm(&mesh, N) {
        // However the triangles on the edge are paired, no strip costs more than three
        // indices and a restart per triangle.
        assert!(strips <= N as usize, "{a}: {strips} strips");
        assert!(indices < 4 * N as usize, "{a}: {indices} indices");
    }
}

#[test]
fn tunnel_depth_beyond_the_maximum_is_refused() {
    let mesh = star(100);
    for cuts in [MAX_TUNNEL_CUTS + 1, usize::MAX] {
        let a = Algorithm::Greedy(GreedyOptions::default().heuristic(Heuristic::Indices).tunnel_cuts(Some(cuts)));
        match stripify(&mesh, &StripOptions::default().algorithm(a)) {
            Err(e @ Error::BadOption { option: stripkit::OptionName::TunnelCuts, .. }) => {
                assert!(e.to_string().contains(&format!("at most {MAX_TUNNEL_CUTS}")), "{e}")
            }
            other => panic!("{cuts} cuts: {other:?}"),
        }
    }
}

/// Quads on one edge {0, 1}: `n` of them with their own two other corners (pairs of
/// them share only the edge), then `m` more that all share a third vertex 2 (every
/// pair of those shares three vertices, so their diagonals must keep apart).
fn quad_book(n: u32, m: u32) -> Mesh {
    let mut positions = vec![[0.0f32, 0.0, 0.0], [0.0, 0.0, 1.0], [2.0, 0.0, 0.5]];
    let mut faces: Vec<[u32; 4]> = Vec::new();
    for i in 0..n + m {
        let a = std::f32::consts::TAU * i as f32 / (n + m) as f32;
        let first = positions.len() as u32;
        positions.push([a.cos(), a.sin(), 0.0]);
        positions.push([a.cos(), a.sin(), 1.0]);
        faces.push(if i < n { [0, first, first + 1, 1] } else { [0, first, 2, 1] });
    }
    Mesh::from_polygons(positions, &faces)
}

#[test]
fn twenty_thousand_quads_on_one_edge() {
    // QSTRIP once tried every pair of quads on an edge: 2 x 10^8 pairs here. The
    // last 300 share three vertices: pair by pair they would be 45,000 pairs.
    let mesh = quad_book(N, 300);
    for a in [Algorithm::auto(), Algorithm::qstrip(), Algorithm::cache(), Algorithm::balanced(0.8)] {
        let s = stripify(&mesh, &StripOptions::default().algorithm(a.clone())).unwrap_or_else(|e| panic!("{a:?}: {e}"));
        let f = &s.figures;
        assert!(f.verified && f.winding_preserved, "{a:?}: {f:?}");
        assert_eq!((f.triangles, f.lost, f.added, f.flipped), (2 * (N as usize + 300), 0, 0, 0), "{a:?}");
        if !matches!(a, Algorithm::Auto(_) | Algorithm::Qstrip(_)) {
            // cache and balanced split quads along the fan here, so the 300 quads all
            // give triangle (0, 2, 1): the input's coincidence, not theirs.
            continue;
        }
        // QSTRIP chose the diagonals: no two drawn triangles on the same three vertices.
        let mut sets = support::drawn_sets(&s);
        let n = sets.len();
        sets.dedup();
        assert_eq!(sets.len(), n, "{a:?}: coincident triangles");
    }
}

/// `batch` (swap-free short strips) on both high-valence meshes: verified, at most
/// three indices and a restart per triangle. Before its scans went through
/// `FreeCursor`, it reread every triangle around the hub for each batch of 30: 89.7 s
/// on the edge and 33.2 s on the star (release CLI), now 2.0 s and 1.4 s.
#[test]
fn batch_strips_around_a_hub_vertex_and_edge() {
    for (name, mesh) in [("star", star(N)), ("edge", edge_fan(N))] {
        let s = stripify(&mesh, &StripOptions::default().algorithm(Algorithm::batch())).unwrap_or_else(|e| panic!("{name}: {e}"));
        let f = &s.figures;
        assert!(f.verified && f.winding_preserved, "{name}: {f:?}");
        assert_eq!((f.triangles, f.lost, f.added, f.flipped), (N as usize, 0, 0, 0), "{name}");
        assert!(f.indices_restart < 4 * N as usize, "{name}: {} indices", f.indices_restart);
    }
}

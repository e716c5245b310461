use super::*;
use crate::gen;
use crate::strip;

fn run(mesh: &crate::Mesh, weights: Weights) -> Single {
    let tris = mesh.triangulate().tris;
    let s = single_strips(&mesh.positions, tris.clone(), &SingleOptions::new(weights)).unwrap();
    let v = strip::verify(&s.work.tris, &s.strips);
    assert!(v.ok(), "{v}");
    check::cover(&tris, &s.work).unwrap();
    s
}

#[test]
fn icosphere_gives_one_strip_for_every_weight_kind() {
    let m = gen::icosphere(3);
    for k in [Weights::Uniform, Weights::Cache, Weights::Cull, Weights::Direction([0.0, 0.0, 1.0])] {
        let s = run(&m, k.clone());
        assert_eq!(s.report.strips, 1, "{k}: {:?}", s.report);
    }
}

/// A hexagonal bipyramid: apex N = 0, S = 1, equator 2..8; upper triangles `U_i = i`
/// around N, lower `L_i = 6 + i` around S.
fn bipyramid() -> WorkMesh {
    let mut pos = vec![[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
    for i in 0..6 {
        let a = i as f32 * std::f32::consts::PI / 3.0;
        pos.push([a.cos(), a.sin(), 0.0]);
    }
    let e = |i: u32| 2 + i % 6;
    let mut tris: Vec<[u32; 3]> = (0..6).map(|i| [e(i), e(i + 1), 0]).collect();
    tris.extend((0..6).map(|i| [e(i + 1), e(i), 1]));
    WorkMesh::new(&pos, tris)
}

fn link(w: &mut WorkMesh, t: usize, u: usize, on: bool) {
    let j = (0..3).find(|&j| w.nbr[t][j] == u as u32).expect("neighbours");
    w.set_link(t, j, on);
}

/// Three loops of four triangles, alternating around both apexes.
fn three_loops() -> WorkMesh {
    let mut w = bipyramid();
    for i in 0..6 {
        link(&mut w, i, 6 + i, true);
    }
    for i in [0, 2, 4] {
        link(&mut w, i, i + 1, true);
        link(&mut w, 6 + i, 6 + i + 1, true);
    }
    w
}

fn pieces_of(w: &WorkMesh) -> usize {
    merge::pieces(w).is_path.len()
}

#[test]
fn nodal_vertex_of_valence_six_joins_three_loops() {
    let mut w = three_loops();
    assert_eq!(pieces_of(&w), 3);
    assert!(merge::pieces(&w).is_path.iter().all(|&p| !p));
    let stats = merge::merge(&mut w, &merge::MergeSettings { swap_angle: None });
    assert_eq!((stats.nodal, stats.splits, stats.swaps), (1, 0, 0));
    assert_eq!(pieces_of(&w), 1);
    assert!((0..w.len()).all(|t| w.degree(t) == 2));
    assert_eq!(w.len(), 12, "the mesh is unchanged");
}

#[test]
fn edge_split_joins_two_loops_with_one_vertex() {
    let mut w = three_loops();
    let input = w.tris.clone();
    // U1 - U2 is matched and joins the loop of U0, U1 to that of U2, U3.
    let j = (0..3).find(|&j| w.nbr[1][j] == 2).unwrap();
    assert!(!w.linked(1, j));
    w.split(1, j, true);
    assert_eq!(pieces_of(&w), 2);
    assert_eq!((w.len(), w.pos.len(), w.steiner.len()), (14, 9, 1));
    assert!((0..w.len()).all(|t| w.degree(t) == 2));
    // The midpoint of N - e2.
    let [a, b] = w.steiner[0];
    assert_eq!((a.min(b), a.max(b)), (0, 4), "U1 = (3, 4, 0) and U2 = (4, 5, 0) share N - e2");
    let m = w.pos[8];
    let (pa, pb) = (w.pos[a as usize], w.pos[b as usize]);
    assert_eq!(m, [(pa[0] + pb[0]) / 2.0, (pa[1] + pb[1]) / 2.0, (pa[2] + pb[2]) / 2.0]);
    check::cover(&input, &w).unwrap();
    // Strips over the changed mesh verify.
    let dual = crate::topology::DualGraph { neighbors: w.nbr.clone() };
    let mut strips = StripSet::new();
    merge::for_each_piece(&w, |_, _, walk| {
        encode_path(&w.tris, &dual, walk, &mut strips);
    });
    assert!(strip::verify(&w.tris, &strips).ok());
}

fn quad(d: [f64; 3]) -> WorkMesh {
    // (a, b, c) = (0, 1, 2) and (b, a, d) = (1, 0, 3), sharing a - b.
    let pos = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [d[0] as f32, d[1] as f32, d[2] as f32]];
    WorkMesh::new(&pos, vec![[0, 1, 2], [1, 0, 3]])
}

#[test]
fn swaps_only_on_flat_convex_quads() {
    let none = merge::EdgeSet::default();
    let deg = |x: f64| x.to_radians();
    // A flat square: allowed even at 0 degrees.
    assert!(merge::swap_ok(&quad([1.0, 0.0, 0.0]), 0, 0, 0.0, &none));
    // A flat dart, reflex at a: the new diagonal c - d leaves the quad.
    assert!(!merge::swap_ok(&quad([-0.5, -1.0, 0.0]), 0, 0, deg(1.0), &none));
    // Flat and convex with d off the square: allowed.
    assert!(merge::swap_ok(&quad([0.3, 0.2, 0.0]), 0, 0, deg(1.0), &none));
    // Folded by about 35 degrees: refused at 1, allowed at 40.
    assert!(!merge::swap_ok(&quad([1.0, 0.0, 0.5]), 0, 0, deg(1.0), &none));
    assert!(merge::swap_ok(&quad([1.0, 0.0, 0.5]), 0, 0, deg(40.0), &none));
    // The other diagonal already an edge: refused.
    let mut edges = merge::EdgeSet::default();
    edges.insert(crate::topology::edge_key(2, 3));
    assert!(!merge::swap_ok(&quad([1.0, 0.0, 0.0]), 0, 0, deg(1.0), &edges));
}

#[test]
fn cull_reports_clusters_and_peaks() {
    // 4 x 4 quads a face, fanned: 6 clusters of 32 triangles, a peak at two corners of
    // each face.
    let g = gen::cube_grid(4);
    let m = crate::Mesh::from_triangles(g.positions.clone(), &g.triangulate().tris);
    let s = run(&m, Weights::Cull);
    assert_eq!(s.report.strips, 1);
    assert_eq!((s.report.clusters, s.report.cull_peaks), (6, 12));
    assert!(s.report.steiner_vertices >= 12, "{:?}", s.report);
    // One strip through six faces crosses at least five face boundaries.
    assert!(s.report.boundary_crossings >= 5 && s.report.boundary_crossings < s.report.boundary_edges, "{:?}", s.report);
    let s = run(&m, Weights::Uniform);
    assert_eq!((s.report.clusters, s.report.cull_peaks), (0, 0));
}

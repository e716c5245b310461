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

#[test]
fn cull_reports_clusters_and_peaks() {
    let m = gen::cube();
    let s = run(&m, Weights::Cull);
    assert_eq!(s.report.strips, 1);
    assert_eq!(s.report.clusters, 6);
    assert_eq!(s.report.cull_peaks, 6);
    assert!(s.report.steiner_vertices >= 6, "{:?}", s.report);
    // One strip through six faces crosses at least five face boundaries.
    assert!(s.report.boundary_crossings >= 5 && s.report.boundary_crossings < s.report.boundary_edges, "{:?}", s.report);
    let s = run(&m, Weights::Uniform);
    assert_eq!((s.report.clusters, s.report.cull_peaks), (0, 0));
}

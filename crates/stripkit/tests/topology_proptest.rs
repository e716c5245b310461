//! Properties of `MeshFacts` on random triangle and polygon soups: no panics, figures
//! that do not depend on face order or on where a face starts, and counts that agree
//! with a naive recount.

use proptest::prelude::*;
use std::collections::{HashMap, HashSet};
use stripkit::gen;
use stripkit::MeshFacts;
use stripkit::Mesh;

fn soup() -> impl Strategy<Value = Mesh> {
    (3u32..12).prop_flat_map(|n| {
        let face = prop::collection::vec(0..n, 3..6);
        prop::collection::vec(face, 0..24).prop_map(move |faces| {
            let positions = (0..n).map(|i| [i as f32, (i * i % 7) as f32, (i % 3) as f32]).collect();
            Mesh::from_polygons(positions, &faces)
        })
    })
}

proptest! {
    #[test]
    fn facts_do_not_depend_on_face_order(mesh in soup(), seed in any::<u64>()) {
        let a = MeshFacts::of(&mesh).unwrap();
        let b = MeshFacts::of(&gen::shuffle_faces(&mesh, seed)).unwrap();
        // Boundary loops through non-manifold places may be walked differently;
        // everything else is a property of the face set.
        let strip_loops = |f: &MeshFacts| MeshFacts { boundary_loops: 0, ..f.clone() };
        prop_assert_eq!(strip_loops(&a), strip_loops(&b));
        if a.nonmanifold_edges == 0 && a.nonmanifold_vertices == 0 && a.consistently_oriented
            && a.degenerate_faces == 0 {
            prop_assert_eq!(a.boundary_loops, b.boundary_loops);
        }
    }

    #[test]
    fn facts_agree_with_a_naive_recount(mesh in soup()) {
        let f = MeshFacts::of(&mesh).unwrap();
        let mut edge_faces: HashMap<(u32, u32), usize> = HashMap::new();
        for face in mesh.faces() {
            for i in 0..face.len() {
                let (a, b) = (face[i], face[(i + 1) % face.len()]);
                if a != b {
                    *edge_faces.entry((a.min(b), a.max(b))).or_default() += 1;
                }
            }
        }
        let used: HashSet<u32> = mesh.face_indices.iter().copied().collect();
        prop_assert_eq!(f.edges, edge_faces.len());
        prop_assert_eq!(f.boundary_edges, edge_faces.values().filter(|&&k| k == 1).count());
        prop_assert_eq!(f.nonmanifold_edges, edge_faces.values().filter(|&&k| k >= 3).count());
        prop_assert_eq!(f.unreferenced_vertices, mesh.vertex_count() - used.len());
        prop_assert_eq!(f.euler_characteristic, used.len() as i64 - edge_faces.len() as i64 + mesh.face_count() as i64);
        prop_assert!(f.edge_components >= f.components);
        // Edge components by a naive flood fill over faces sharing an edge.
        let faces: Vec<&[u32]> = mesh.faces().collect();
        let edges_of = |face: &[u32]| -> HashSet<(u32, u32)> {
            (0..face.len()).map(|i| (face[i], face[(i + 1) % face.len()]))
                .filter(|(a, b)| a != b).map(|(a, b)| (a.min(b), a.max(b))).collect()
        };
        let mut seen = vec![false; faces.len()];
        let mut naive = 0;
        for s in 0..faces.len() {
            if seen[s] { continue; }
            naive += 1;
            seen[s] = true;
            let mut stack = vec![s];
            while let Some(a) = stack.pop() {
                let ea = edges_of(faces[a]);
                for b in 0..faces.len() {
                    if !seen[b] && !edges_of(faces[b]).is_disjoint(&ea) {
                        seen[b] = true;
                        stack.push(b);
                    }
                }
            }
        }
        // Faces whose vertices are all one vertex have no edge: each is its own piece.
        prop_assert_eq!(f.edge_components, naive);
        prop_assert!(f.boundary_loops <= f.boundary_edges);
        prop_assert_eq!(f.triangles + f.quads + f.polygons, f.faces);
        // Duplicates: faces minus distinct faces up to rotation and orientation.
        let canon = |face: &[u32]| {
            let k = face.len();
            let mut best: Option<Vec<u32>> = None;
            for r in 0..k {
                for dir in [true, false] {
                    let c: Vec<u32> = (0..k).map(|i| if dir { face[(r + i) % k] } else { face[(r + k - i) % k] }).collect();
                    match &best { Some(b) if *b <= c => {} _ => best = Some(c) }
                }
            }
            best.unwrap()
        };
        let distinct: HashSet<Vec<u32>> = mesh.faces().map(canon).collect();
        prop_assert_eq!(f.duplicate_faces, mesh.face_count() - distinct.len());
    }
}

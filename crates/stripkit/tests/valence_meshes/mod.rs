//! Meshes with one vertex or edge of very high valence (issue #16), for the
//! simplify and distance tests.

use stripkit::Mesh;

fn circle(n: usize, z: f32) -> impl Iterator<Item = [f32; 3]> {
    (0..n).map(move |i| {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        [a.cos() as f32, a.sin() as f32, z]
    })
}

/// `n` triangles around vertex 0, a closed disc.
pub fn star(n: usize) -> Mesh {
    let positions: Vec<[f32; 3]> = std::iter::once([0.0; 3]).chain(circle(n, 0.0)).collect();
    let tris: Vec<[u32; 3]> = (0..n).map(|i| [0, 1 + i as u32, 1 + ((i + 1) % n) as u32]).collect();
    Mesh::from_triangles(positions, &tris)
}

/// `n` triangles sharing the edge (0, 1), one rim vertex each.
pub fn edge_fan(n: usize) -> Mesh {
    let positions: Vec<[f32; 3]> = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]].into_iter().chain(circle(n, 0.5)).collect();
    let tris: Vec<[u32; 3]> = (0..n).map(|i| [0, 1, 2 + i as u32]).collect();
    Mesh::from_triangles(positions, &tris)
}

/// One polygon of `n` corners on a circle.
pub fn polygon(n: usize) -> Mesh {
    let face: Vec<u32> = (0..n as u32).collect();
    Mesh::from_polygons(circle(n, 0.0).collect(), &[face])
}

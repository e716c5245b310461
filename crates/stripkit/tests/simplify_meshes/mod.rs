//! Procedural meshes and checks shared by the simplify and distance tests.
#![allow(dead_code)]

use stripkit::Mesh;

/// A grid of `nx` x `ny` quads over [0,1]^2, two triangles each, counter-clockwise
/// seen from +z, with height `z(x, y)`.
pub fn grid(nx: u32, ny: u32, z: impl Fn(f64, f64) -> f64) -> Mesh {
    let mut positions = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let (x, y) = (i as f64 / nx as f64, j as f64 / ny as f64);
            positions.push([x as f32, y as f32, z(x, y) as f32]);
        }
    }
    let id = |i: u32, j: u32| j * (nx + 1) + i;
    let mut tris = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            } else {
                tris.push([a, b, d]);
                tris.push([b, c, d]);
            }
        }
    }
    Mesh::from_triangles(positions, &tris)
}

/// A closed sphere: an octahedron subdivided `levels` times (4^levels * 8 triangles),
/// projected to radius `r(direction)`.
pub fn sphere(levels: u32, r: impl Fn([f64; 3]) -> f64) -> Mesh {
    let mut pos: Vec<[f64; 3]> =
        vec![[1., 0., 0.], [-1., 0., 0.], [0., 1., 0.], [0., -1., 0.], [0., 0., 1.], [0., 0., -1.]];
    let mut tris: Vec<[u32; 3]> = vec![
        [0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4],
        [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5],
    ];
    for _ in 0..levels {
        let mut mid = std::collections::HashMap::new();
        let mut next = Vec::with_capacity(tris.len() * 4);
        let mut midpoint = |a: u32, b: u32, pos: &mut Vec<[f64; 3]>| -> u32 {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (pos[a as usize], pos[b as usize]);
                pos.push([(p[0] + q[0]) / 2., (p[1] + q[1]) / 2., (p[2] + q[2]) / 2.]);
                pos.len() as u32 - 1
            })
        };
        for [a, b, c] in tris {
            let ab = midpoint(a, b, &mut pos);
            let bc = midpoint(b, c, &mut pos);
            let ca = midpoint(c, a, &mut pos);
            next.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
        }
        tris = next;
    }
    let positions = pos
        .iter()
        .map(|p| {
            let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            let d = [p[0] / l, p[1] / l, p[2] / l];
            let s = r(d);
            [(d[0] * s) as f32, (d[1] * s) as f32, (d[2] * s) as f32]
        })
        .collect();
    Mesh::from_triangles(positions, &tris)
}

/// A bumpy closed test surface.
pub fn bumpy_sphere(levels: u32) -> Mesh {
    sphere(levels, |d| 1.0 + 0.15 * (5.0 * d[0]).sin() * (3.0 * d[1]).cos() + 0.05 * (9.0 * d[2]).sin())
}

/// Renumbers vertices, reorders triangles and rotates their corners (a fixed seed).
pub fn shuffled(mesh: &Mesh, seed: u64) -> Mesh {
    let mut rng = stripkit_testkit::XorShift64(seed.wrapping_mul(0x9E3779B97F4A7C15) | 1);
    let mut rnd = move || rng.next();
    let n = mesh.positions.len();
    let mut perm: Vec<u32> = (0..n as u32).collect();
    for i in (1..n).rev() {
        perm.swap(i, (rnd() % (i as u64 + 1)) as usize);
    }
    let mut positions = vec![[0.0; 3]; n];
    for v in 0..n {
        positions[perm[v] as usize] = mesh.positions[v];
    }
    let mut tris: Vec<[u32; 3]> = mesh.triangulate().tris.iter().map(|t| t.map(|v| perm[v as usize])).collect();
    for i in (1..tris.len()).rev() {
        tris.swap(i, (rnd() % (i as u64 + 1)) as usize);
    }
    for t in tris.iter_mut() {
        t.rotate_left((rnd() % 3) as usize);
    }
    Mesh::from_triangles(positions, &tris)
}

pub fn normal(m: &Mesh, t: [u32; 3]) -> [f64; 3] {
    let p = t.map(|v| m.positions[v as usize].map(|x| x as f64));
    stripkit_testkit::geom::tri_normal(p[0], p[1], p[2])
}

pub fn area(m: &Mesh) -> f64 {
    m.triangulate().tris.iter().map(|&t| {
        let n = normal(m, t);
        (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt() / 2.0
    }).sum()
}

/// Checks that a triangle mesh is a closed, consistently oriented 2-manifold: every
/// edge has two triangles running opposite ways, every vertex's fan is one cycle.
/// Returns the Euler characteristic.
pub fn assert_closed_manifold(m: &Mesh) -> i64 {
    use std::collections::HashMap;
    let tris = m.triangulate().tris;
    let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &tris {
        assert!(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], "degenerate {t:?}");
        for j in 0..3 {
            *directed.entry((t[j], t[(j + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &c) in &directed {
        assert_eq!(c, 1, "directed edge {a}->{b} used {c} times");
        assert_eq!(directed.get(&(b, a)), Some(&1), "edge {a}-{b} is a boundary");
    }
    // Vertex fans: next-around-vertex map must be one cycle per vertex.
    let mut next: HashMap<u32, HashMap<u32, u32>> = HashMap::new();
    for t in &tris {
        for j in 0..3 {
            next.entry(t[j]).or_default().insert(t[(j + 1) % 3], t[(j + 2) % 3]);
        }
    }
    for (v, fan) in &next {
        let first = *fan.keys().next().unwrap();
        let mut x = first;
        let mut steps = 0;
        loop {
            x = fan[&x];
            steps += 1;
            if x == first {
                break;
            }
            assert!(steps <= fan.len(), "fan of vertex {v} is broken");
        }
        assert_eq!(steps, fan.len(), "vertex {v} is a pinch (fan of {} in {} cycles)", fan.len(), steps);
    }
    let e = directed.len() as i64 / 2;
    next.len() as i64 - e + tris.len() as i64
}

//! Procedural and derived meshes: grids, icospheres, tori, cubes, Loop and
//! Catmull-Clark subdivision, plus helpers that make test inputs (disjoint unions,
//! shuffled face orders).
//!
//! Every generator gives faces oriented counter-clockwise seen from outside (closed
//! meshes) or from +z (grids); subdivision keeps the orientation of its input face by
//! face. Everything runs in O(output) over flat arrays; edge points are numbered in
//! edge order (by lower vertex, then higher vertex), so no hashing is involved.
//!
//! | generator | vertices | faces |
//! |---|---|---|
//! | [`grid`]`(w, h)` | (w+1)(h+1) | 2wh triangles |
//! | [`grid_quads`]`(w, h)` | (w+1)(h+1) | wh quads |
//! | [`icosphere`]`(k)` | 10·4^k + 2 | 20·4^k triangles (k = 8: 1,310,720) |
//! | [`torus`]`(M, m, R, r)` | M·m | 2Mm triangles |
//! | [`torus_quads`]`(M, m, R, r)` | M·m | Mm quads |
//! | [`cube`]`()` | 8 | 6 quads |
//! | [`subdivide_loop`]`(mesh, k)` | V + E per level | F·4^k triangles |
//! | [`subdivide_catmull_clark`]`(mesh, k)` | V + E + F per level | Σ face sizes quads per level |
//!
//! A caller that builds meshes on request (a command line, a service) checks the
//! request first: [`check_grid`], [`check_icosphere`], [`check_torus`] and
//! [`check_subdivision`] predict the size in overflow-free arithmetic and refuse one
//! beyond [`MAX_INDICES`] before anything is allocated.
//!
//! Subdivision carries vertex attributes (normals, UVs, colours, ...) with the
//! positions' own stencil weights ([`crate::mesh::Attribute::push_blend`]) and face groups
//! to the child faces. An attribute seam (two vertices at one position) is a
//! boundary on each side, so both sides follow the same crease rule; where a seam
//! meets another crease, its vertices stay fixed so that the seam stays closed.

use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::topology::{validate, EdgeMap};

/// A grid of `w` by `h` unit squares in the plane z = 0, each split into two triangles
/// along the diagonal from (i, j) to (i+1, j+1); vertex (i, j) has id `j * (w + 1) + i`
/// and position (i, j, 0). Counter-clockwise seen from +z.
pub fn grid(w: u32, h: u32) -> Mesh {
    let mut mesh = grid_vertices(w, h);
    mesh.face_indices.reserve(6 * w as usize * h as usize);
    mesh.face_offsets.reserve(2 * w as usize * h as usize);
    for_each_grid_quad(w, h, |[a, b, c, d]| {
        mesh.push_face(&[a, b, c]);
        mesh.push_face(&[a, c, d]);
    });
    mesh
}

/// Like [`grid`], but each unit square is one quad `[(i,j), (i+1,j), (i+1,j+1), (i,j+1)]`.
pub fn grid_quads(w: u32, h: u32) -> Mesh {
    let mut mesh = grid_vertices(w, h);
    mesh.face_indices.reserve(4 * w as usize * h as usize);
    mesh.face_offsets.reserve(w as usize * h as usize);
    for_each_grid_quad(w, h, |q| mesh.push_face(&q));
    mesh
}

fn grid_vertices(w: u32, h: u32) -> Mesh {
    let mut positions = Vec::with_capacity((w as usize + 1) * (h as usize + 1));
    for j in 0..=h {
        for i in 0..=w {
            positions.push([i as f32, j as f32, 0.0]);
        }
    }
    Mesh { positions, ..Mesh::new() }
}

fn for_each_grid_quad(w: u32, h: u32, mut emit: impl FnMut([u32; 4])) {
    let row = w + 1;
    for j in 0..h {
        for i in 0..w {
            let a = j * row + i;
            emit([a, a + 1, a + 1 + row, a + row]);
        }
    }
}

/// A unit sphere from an icosahedron whose triangles are split into four `level`
/// times, new vertices pushed onto the sphere. Level 0 has 12 vertices and 20
/// triangles, level k has 20·4^k triangles and 10·4^k + 2 vertices.
///
/// # Panics
/// When `level > 12` (the indices would no longer fit in `u32`).
pub fn icosphere(level: u32) -> Mesh {
    assert!(level <= 12, "icosphere level {level} is too large (at most 12)");
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let raw: [[f64; 3]; 12] = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let tris: [[u32; 3]; 20] = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let positions: Vec<[f32; 3]> = raw.iter().map(|&p| to_f32(normalize(p))).collect();
    let mut mesh = Mesh::from_triangles(positions, &tris);
    orient_outward(&mut mesh);
    for _ in 0..level {
        let map = EdgeMap::build(&mesh);
        let mut positions = Vec::with_capacity(mesh.vertex_count() + map.edge_count());
        positions.extend_from_slice(&mesh.positions);
        for &[a, b] in &map.edges {
            let (pa, pb) = (to_f64(mesh.positions[a as usize]), to_f64(mesh.positions[b as usize]));
            positions.push(to_f32(normalize([pa[0] + pb[0], pa[1] + pb[1], pa[2] + pb[2]])));
        }
        mesh = split_triangles_in_four(&mesh, &map, positions);
    }
    mesh
}

/// A torus around the z axis: `major` segments around the central circle of radius
/// `major_radius`, `minor` segments around the tube of radius `minor_radius`; each
/// quad split into two triangles. Vertex (i, j) (i around the axis, j around the tube)
/// has id `i * minor + j`. Genus 1, closed, χ = 0.
///
/// # Panics
/// When `major < 3` or `minor < 3`, or when `major * minor` exceeds `u32`.
pub fn torus(major: u32, minor: u32, major_radius: f32, minor_radius: f32) -> Mesh {
    let mut mesh = torus_vertices(major, minor, major_radius, minor_radius);
    let n = major as usize * minor as usize;
    mesh.face_indices.reserve(6 * n);
    mesh.face_offsets.reserve(2 * n);
    for_each_torus_quad(major, minor, |[a, b, c, d]| {
        mesh.push_face(&[a, b, c]);
        mesh.push_face(&[a, c, d]);
    });
    mesh
}

/// Like [`torus`] with one quad per segment pair.
pub fn torus_quads(major: u32, minor: u32, major_radius: f32, minor_radius: f32) -> Mesh {
    let mut mesh = torus_vertices(major, minor, major_radius, minor_radius);
    let n = major as usize * minor as usize;
    mesh.face_indices.reserve(4 * n);
    mesh.face_offsets.reserve(n);
    for_each_torus_quad(major, minor, |q| mesh.push_face(&q));
    mesh
}

fn torus_vertices(major: u32, minor: u32, major_radius: f32, minor_radius: f32) -> Mesh {
    assert!(major >= 3 && minor >= 3, "a torus needs at least 3 segments each way");
    assert!((major as u64) * (minor as u64) * 6 <= u32::MAX as u64, "torus too large for u32 indices");
    let mut positions = Vec::with_capacity(major as usize * minor as usize);
    let (big, small) = (major_radius as f64, minor_radius as f64);
    for i in 0..major {
        let u = std::f64::consts::TAU * i as f64 / major as f64;
        for j in 0..minor {
            let v = std::f64::consts::TAU * j as f64 / minor as f64;
            let ring = big + small * v.cos();
            positions.push(to_f32([ring * u.cos(), ring * u.sin(), small * v.sin()]));
        }
    }
    Mesh { positions, ..Mesh::new() }
}

fn for_each_torus_quad(major: u32, minor: u32, mut emit: impl FnMut([u32; 4])) {
    for i in 0..major {
        let i1 = (i + 1) % major;
        for j in 0..minor {
            let j1 = (j + 1) % minor;
            // d/du x d/dv points out of the tube, so (u, v) order is counter-clockwise
            // seen from outside.
            emit([i * minor + j, i1 * minor + j, i1 * minor + j1, i * minor + j1]);
        }
    }
}

/// The cube [-1, 1]^3 as 8 vertices and 6 outward-facing quads: the smallest closed
/// quad mesh (χ = 2), and a classic Catmull-Clark input.
pub fn cube() -> Mesh {
    let mut positions = Vec::with_capacity(8);
    for k in 0..8u32 {
        let c = |bit: u32| if k & bit != 0 { 1.0 } else { -1.0 };
        positions.push([c(1), c(2), c(4)]);
    }
    let faces: [[u32; 4]; 6] =
        [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    let mut mesh = Mesh::from_polygons(positions, &faces);
    orient_outward(&mut mesh);
    mesh
}

/// A closed cube of side `n` with `n` x `n` unit quads on each face, outward-facing,
/// corners at integer positions from 0 to `n`: `6 n^2` quads on `6 n^2 + 2` vertices
/// (χ = 2). Where [`cube`] is the smallest closed quad mesh, this one has rows of quads
/// that wrap around the cube (quad stripifiers' test input).
pub fn cube_grid(n: u32) -> Mesh {
    use std::collections::HashMap;
    let mut ids: HashMap<[i32; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    let n = n.min(1 << 20) as i32;
    // For each axis and side: a frame (u, v) with u x v pointing outward.
    for axis in 0..3 {
        for side in [0, n] {
            let (ua, va) = ((axis + 1) % 3, (axis + 2) % 3);
            let outward_positive = side == n;
            let mut vid = |i: i32, j: i32| {
                let mut p = [0i32; 3];
                p[axis] = side;
                p[ua] = i;
                p[va] = j;
                *ids.entry(p).or_insert_with(|| {
                    positions.push([p[0] as f32, p[1] as f32, p[2] as f32]);
                    (positions.len() - 1) as u32
                })
            };
            for j in 0..n {
                for i in 0..n {
                    let q = [vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)];
                    if outward_positive {
                        faces.push(q.to_vec());
                    } else {
                        faces.push(vec![q[0], q[3], q[2], q[1]]);
                    }
                }
            }
        }
    }
    Mesh::from_polygons(positions, &faces)
}

/// Loop subdivision, `levels` times: every triangle becomes four, vertex and edge
/// points follow Loop's weights (β = (5/8 − (3/8 + cos(2π/n)/4)²)/n). Edges with other
/// than two faces (boundary, non-manifold) are creases: their edge point is the
/// midpoint, a vertex on exactly two crease edges follows the boundary curve
/// (3/4·v + 1/8·(two neighbours)), a vertex on one or more than two stays fixed.
///
/// Vertex ids are stable: vertex `v < V` of the output is vertex `v` of the input
/// (unreferenced ones keep their position), then one vertex per input edge in
/// edge order (by lower vertex, then higher vertex). Triangle `4t..4t+4` of the output come from input triangle
/// `t`, with its orientation.
///
/// Fails on a malformed mesh, on faces that are not triangles, on a triangle with a
/// repeated vertex, and when the result would not fit `u32` indices.
pub fn subdivide_loop(mesh: &Mesh, levels: u32) -> Result<Mesh> {
    validate(mesh)?;
    mesh.check_attributes()?;
    if let Some((f, face)) = mesh.faces().enumerate().find(|(_, face)| face.len() != 3) {
        return Err(Error::Invalid(format!(
            "Loop subdivision needs a triangle mesh, but face {f} has {} vertices (use catmull-clark)",
            face.len()
        )));
    }
    check_no_repeated_index(mesh)?;
    let mut current = mesh.clone();
    for _ in 0..levels {
        let map = EdgeMap::build(&current);
        let new_vertices = current.vertex_count() as u64 + map.edge_count() as u64;
        let new_indices = current.face_indices.len() as u64 * 4;
        check_size(new_vertices, new_indices)?;
        current = loop_step(&current, &map);
    }
    Ok(current)
}

fn loop_step(mesh: &Mesh, map: &EdgeMap) -> Mesh {
    let vcount = mesh.vertex_count();
    let fi = &mesh.face_indices;
    let p = |v: u32| to_f64(mesh.positions[v as usize]);
    let mut ring_sum = vec![[0f64; 3]; vcount];
    let mut ring_count = vec![0u32; vcount];
    let mut crease_sum = vec![[0f64; 3]; vcount];
    let mut crease_count = vec![0u32; vcount];
    let mut positions = Vec::with_capacity(vcount + map.edge_count());
    positions.resize(vcount, [0f32; 3]);
    for (e, &[a, b]) in map.edges.iter().enumerate() {
        let hs = map.halfedges(e);
        let (pa, pb) = (p(a), p(b));
        let edge_point = if hs.len() == 2 {
            add(&mut ring_sum[a as usize], pb);
            add(&mut ring_sum[b as usize], pa);
            ring_count[a as usize] += 1;
            ring_count[b as usize] += 1;
            // The vertex opposite the edge in each triangle.
            let opp = |h: u32| p(fi[map.halfedge_next[map.halfedge_next[h as usize] as usize] as usize]);
            let (pc, pd) = (opp(hs[0]), opp(hs[1]));
            std::array::from_fn(|k| 0.375 * (pa[k] + pb[k]) + 0.125 * (pc[k] + pd[k]))
        } else {
            add(&mut crease_sum[a as usize], pb);
            add(&mut crease_sum[b as usize], pa);
            crease_count[a as usize] += 1;
            crease_count[b as usize] += 1;
            std::array::from_fn(|k| 0.5 * (pa[k] + pb[k]))
        };
        positions.push(to_f32(edge_point));
    }
    let corner = seam_corners(mesh, map);
    for v in 0..vcount {
        let pv = to_f64(mesh.positions[v]);
        let new = match crease_count[v] {
            2 if is_set(&corner, v) => pv,
            0 if ring_count[v] > 0 => {
                let n = ring_count[v] as f64;
                let c = 0.375 + 0.25 * (std::f64::consts::TAU / n).cos();
                let beta = (0.625 - c * c) / n;
                std::array::from_fn(|k| (1.0 - n * beta) * pv[k] + beta * ring_sum[v][k])
            }
            2 => std::array::from_fn(|k| 0.75 * pv[k] + 0.125 * crease_sum[v][k]),
            _ => pv,
        };
        positions[v] = to_f32(new);
    }
    let mut out = split_triangles_in_four(mesh, map, positions);
    if !mesh.attributes.is_empty() {
        out.attributes = blend_attributes(mesh, &loop_stencils(mesh, map));
    }
    carry_groups(mesh, &mut out, |_| 4);
    out
}

/// Loop's stencils (input vertices and their weights) of every output vertex: the
/// rules of `loop_step`, for attributes.
fn loop_stencils(mesh: &Mesh, map: &EdgeMap) -> Vec<Vec<(usize, f64)>> {
    let fi = &mesh.face_indices;
    let (ring, crease) = neighbours(mesh, map);
    let corner = seam_corners(mesh, map);
    let mut stencils: Vec<Vec<(usize, f64)>> = (0..mesh.vertex_count())
        .map(|v| match crease[v].len() {
            2 if is_set(&corner, v) => vec![(v, 1.0)],
            0 if !ring[v].is_empty() => {
                let n = ring[v].len() as f64;
                let c = 0.375 + 0.25 * (std::f64::consts::TAU / n).cos();
                let beta = (0.625 - c * c) / n;
                std::iter::once((v, 1.0 - n * beta)).chain(ring[v].iter().map(|&u| (u as usize, beta))).collect()
            }
            2 => vec![(v, 0.75), (crease[v][0] as usize, 0.125), (crease[v][1] as usize, 0.125)],
            _ => vec![(v, 1.0)],
        })
        .collect();
    for (e, &[a, b]) in map.edges.iter().enumerate() {
        let hs = map.halfedges(e);
        let (a, b) = (a as usize, b as usize);
        stencils.push(if hs.len() == 2 {
            let opp = |h: u32| fi[map.halfedge_next[map.halfedge_next[h as usize] as usize] as usize] as usize;
            vec![(a, 0.375), (b, 0.375), (opp(hs[0]), 0.125), (opp(hs[1]), 0.125)]
        } else {
            vec![(a, 0.5), (b, 0.5)]
        });
    }
    stencils
}

/// Where a mesh has attributes, the seam vertices (two used vertices at one position:
/// the sides of a UV or normal seam) where the seam meets another crease, such as an
/// open boundary: each side would follow its own boundary curve there and the seam
/// would open, so they stay fixed, like a corner. Empty (nothing fixed) without
/// attributes.
fn seam_corners(mesh: &Mesh, map: &EdgeMap) -> Vec<bool> {
    let seam = crate::simplify::attributes::seam_vertices(mesh);
    if seam.is_empty() {
        return seam;
    }
    let (_, crease) = neighbours(mesh, map);
    (0..mesh.vertex_count()).map(|v| seam[v] && crease[v].iter().any(|&u| !seam[u as usize])).collect()
}

fn is_set(flags: &[bool], v: usize) -> bool {
    flags.get(v).copied().unwrap_or(false)
}

/// Per vertex, its neighbours across edges with two faces, and across crease edges
/// (any other count), in edge order.
fn neighbours(mesh: &Mesh, map: &EdgeMap) -> (Vec<Vec<u32>>, Vec<Vec<u32>>) {
    let mut ring = vec![Vec::new(); mesh.vertex_count()];
    let mut crease = vec![Vec::new(); mesh.vertex_count()];
    for (e, &[a, b]) in map.edges.iter().enumerate() {
        let list = if map.halfedges(e).len() == 2 { &mut ring } else { &mut crease };
        list[a as usize].push(b);
        list[b as usize].push(a);
    }
    (ring, crease)
}

/// `mesh`'s attributes at new vertices, each a weighted blend of input vertices
/// ([`crate::mesh::Attribute::push_blend`]: floats and normalized integers blended, other
/// integers from the heaviest vertex; normals and tangents made unit again). Empty
/// without attributes (stencils unused).
fn blend_attributes(mesh: &Mesh, stencils: &[Vec<(usize, f64)>]) -> Vec<crate::mesh::Attribute> {
    mesh.attributes
        .iter()
        .map(|a| {
            // Blended after the input's own values, which are then dropped.
            let mut work = a.clone();
            work.data.reserve(stencils.len() * a.stride());
            for parts in stencils {
                work.push_blend(parts);
            }
            work.data.drain(..a.len() * a.stride());
            let n = work.len();
            crate::simplify::attributes::unit_directions(&mut work, 0..n);
            work
        })
        .collect()
}

/// The face groups of `out`, whose faces come `children(f)` at a time from each
/// input face `f` in order.
fn carry_groups(mesh: &Mesh, out: &mut Mesh, children: impl Fn(usize) -> usize) {
    out.groups = mesh.groups.clone();
    if !mesh.face_groups.is_empty() {
        out.face_groups =
            (0..mesh.face_count()).flat_map(|f| std::iter::repeat_n(mesh.group_of(f), children(f))).collect();
    }
}

/// Splits every triangle of a triangle mesh into four using edge vertices numbered
/// `V + edge id`; `positions` already holds all V + E positions.
fn split_triangles_in_four(mesh: &Mesh, map: &EdgeMap, positions: Vec<[f32; 3]>) -> Mesh {
    let vcount = mesh.vertex_count() as u32;
    let fcount = mesh.face_count();
    let fi = &mesh.face_indices;
    let mut face_indices = Vec::with_capacity(12 * fcount);
    for t in 0..fcount {
        let h = 3 * t;
        let (a, b, c) = (fi[h], fi[h + 1], fi[h + 2]);
        let ab = vcount + map.halfedge_edge[h];
        let bc = vcount + map.halfedge_edge[h + 1];
        let ca = vcount + map.halfedge_edge[h + 2];
        face_indices.extend_from_slice(&[a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca]);
    }
    let face_offsets = (0..=4 * fcount as u32).map(|f| 3 * f).collect();
    Mesh { positions, face_offsets, face_indices, ..Mesh::new() }
}

/// Catmull-Clark subdivision, `levels` times, of any polygon mesh: a face of k
/// vertices becomes k quads, so the result is all quads after one level. Face points
/// are centroids; an edge with two faces gets (a + b + two face points)/4; edges with
/// other than two faces are creases (midpoint), and vertices on exactly two crease
/// edges follow the boundary curve (3/4·v + 1/8·(two neighbours)); vertices on one or
/// more than two crease edges stay fixed. Interior vertices: (Q + 2R + (n−3)S)/n.
///
/// Vertex ids are stable: input vertices first, then one per edge (by lower vertex,
/// then higher vertex), then one per face. The quads of input face `f` come in the order of its
/// corners, each `[corner, edge point after it, face point, edge point before it]`,
/// which keeps the face's orientation.
///
/// Fails on a malformed mesh, on a face with a repeated vertex, and when the result
/// would not fit `u32` indices.
pub fn subdivide_catmull_clark(mesh: &Mesh, levels: u32) -> Result<Mesh> {
    validate(mesh)?;
    mesh.check_attributes()?;
    check_no_repeated_index(mesh)?;
    let mut current = mesh.clone();
    for _ in 0..levels {
        let map = EdgeMap::build(&current);
        let new_vertices = current.vertex_count() as u64 + map.edge_count() as u64 + current.face_count() as u64;
        let new_indices = current.face_indices.len() as u64 * 4;
        check_size(new_vertices, new_indices)?;
        current = catmull_clark_step(&current, &map);
    }
    Ok(current)
}

#[allow(clippy::needless_range_loop)] // `h` is a half-edge id, used for more than `fi`
fn catmull_clark_step(mesh: &Mesh, map: &EdgeMap) -> Mesh {
    let vcount = mesh.vertex_count();
    let ecount = map.edge_count();
    let fcount = mesh.face_count();
    let fi = &mesh.face_indices;
    let p = |v: u32| to_f64(mesh.positions[v as usize]);

    let mut face_points = Vec::with_capacity(fcount);
    for face in mesh.faces() {
        let mut c = [0f64; 3];
        for &v in face {
            add(&mut c, p(v));
        }
        let k = face.len() as f64;
        face_points.push([c[0] / k, c[1] / k, c[2] / k]);
    }

    let mut positions = Vec::with_capacity(vcount + ecount + fcount);
    positions.resize(vcount, [0f32; 3]);
    // Per vertex: sum of incident face points, of incident interior edge midpoints,
    // of crease neighbours.
    let mut face_sum = vec![[0f64; 3]; vcount];
    let mut face_count = vec![0u32; vcount];
    let mut mid_sum = vec![[0f64; 3]; vcount];
    let mut mid_count = vec![0u32; vcount];
    let mut crease_sum = vec![[0f64; 3]; vcount];
    let mut crease_count = vec![0u32; vcount];
    for (h, &v) in fi.iter().enumerate() {
        add(&mut face_sum[v as usize], face_points[map.halfedge_face[h] as usize]);
        face_count[v as usize] += 1;
    }
    for (e, &[a, b]) in map.edges.iter().enumerate() {
        let hs = map.halfedges(e);
        let (pa, pb) = (p(a), p(b));
        let mid: [f64; 3] = std::array::from_fn(|k| 0.5 * (pa[k] + pb[k]));
        let edge_point = if hs.len() == 2 {
            add(&mut mid_sum[a as usize], mid);
            add(&mut mid_sum[b as usize], mid);
            mid_count[a as usize] += 1;
            mid_count[b as usize] += 1;
            let f0 = face_points[map.halfedge_face[hs[0] as usize] as usize];
            let f1 = face_points[map.halfedge_face[hs[1] as usize] as usize];
            std::array::from_fn(|k| 0.25 * (pa[k] + pb[k] + f0[k] + f1[k]))
        } else {
            add(&mut crease_sum[a as usize], pb);
            add(&mut crease_sum[b as usize], pa);
            crease_count[a as usize] += 1;
            crease_count[b as usize] += 1;
            mid
        };
        positions.push(to_f32(edge_point));
    }
    let corner = seam_corners(mesh, map);
    for v in 0..vcount {
        let s = to_f64(mesh.positions[v]);
        let new = match crease_count[v] {
            2 if is_set(&corner, v) => s,
            0 if mid_count[v] > 0 && face_count[v] > 0 => {
                let n = mid_count[v] as f64;
                let fc = face_count[v] as f64;
                std::array::from_fn(|k| {
                    let q = face_sum[v][k] / fc;
                    let r = mid_sum[v][k] / n;
                    (q + 2.0 * r + (n - 3.0) * s[k]) / n
                })
            }
            2 => std::array::from_fn(|k| 0.75 * s[k] + 0.125 * crease_sum[v][k]),
            _ => s,
        };
        positions[v] = to_f32(new);
    }
    positions.extend(face_points.iter().map(|&c| to_f32(c)));

    let mut face_indices = Vec::with_capacity(4 * fi.len());
    let edge_base = vcount as u32;
    let face_base = (vcount + ecount) as u32;
    for f in 0..fcount {
        let (s, t) = (mesh.face_offsets[f] as usize, mesh.face_offsets[f + 1] as usize);
        for h in s..t {
            let prev = if h == s { t - 1 } else { h - 1 };
            face_indices.extend_from_slice(&[
                fi[h],
                edge_base + map.halfedge_edge[h],
                face_base + f as u32,
                edge_base + map.halfedge_edge[prev],
            ]);
        }
    }
    let face_offsets = (0..=fi.len() as u32).map(|q| 4 * q).collect();
    let mut out = Mesh { positions, face_offsets, face_indices, ..Mesh::new() };
    if !mesh.attributes.is_empty() {
        out.attributes = blend_attributes(mesh, &catmull_clark_stencils(mesh, map));
    }
    carry_groups(mesh, &mut out, |f| mesh.face(f).len());
    out
}

/// Catmull-Clark's stencils (input vertices and their weights) of every output
/// vertex: the rules of `catmull_clark_step`, for attributes.
fn catmull_clark_stencils(mesh: &Mesh, map: &EdgeMap) -> Vec<Vec<(usize, f64)>> {
    let fi = &mesh.face_indices;
    let face_point = |f: usize, w: f64| {
        let face = mesh.face(f);
        face.iter().map(move |&u| (u as usize, w / face.len() as f64))
    };
    let (ring, crease) = neighbours(mesh, map);
    // The faces around each vertex, one per corner.
    let mut faces_of = vec![Vec::new(); mesh.vertex_count()];
    for (h, &v) in fi.iter().enumerate() {
        faces_of[v as usize].push(map.halfedge_face[h] as usize);
    }
    let corner = seam_corners(mesh, map);
    let mut stencils: Vec<Vec<(usize, f64)>> = (0..mesh.vertex_count())
        .map(|v| match crease[v].len() {
            2 if is_set(&corner, v) => vec![(v, 1.0)],
            0 if !ring[v].is_empty() && !faces_of[v].is_empty() => {
                // (Q + 2R + (n - 3)S) / n: Q the mean face point, R the mean midpoint.
                let n = ring[v].len() as f64;
                let fc = faces_of[v].len() as f64;
                let mut parts = vec![(v, (n - 3.0) / n + 1.0 / n)];
                parts.extend(ring[v].iter().map(|&u| (u as usize, 1.0 / (n * n))));
                for &f in &faces_of[v] {
                    parts.extend(face_point(f, 1.0 / (n * fc)));
                }
                parts
            }
            2 => vec![(v, 0.75), (crease[v][0] as usize, 0.125), (crease[v][1] as usize, 0.125)],
            _ => vec![(v, 1.0)],
        })
        .collect();
    for (e, &[a, b]) in map.edges.iter().enumerate() {
        let hs = map.halfedges(e);
        let (a, b) = (a as usize, b as usize);
        stencils.push(if hs.len() == 2 {
            let mut parts = vec![(a, 0.25), (b, 0.25)];
            for &h in hs {
                parts.extend(face_point(map.halfedge_face[h as usize] as usize, 0.25));
            }
            parts
        } else {
            vec![(a, 0.5), (b, 0.5)]
        });
    }
    stencils.extend((0..mesh.face_count()).map(|f| face_point(f, 1.0).collect()));
    stencils
}

fn check_no_repeated_index(mesh: &Mesh) -> Result<()> {
    for (f, face) in mesh.faces().enumerate() {
        // Faces are small; a quadratic scan beats sorting up to a few dozen vertices.
        let repeated = if face.len() <= 32 {
            (0..face.len()).any(|a| (a + 1..face.len()).any(|b| face[a] == face[b]))
        } else {
            let mut sorted = face.to_vec();
            sorted.sort_unstable();
            sorted.windows(2).any(|w| w[0] == w[1])
        };
        if repeated {
            return Err(Error::Invalid(format!(
                "face {f} repeats a vertex ({face:?}); subdivision needs faces without repeated vertices"
            )));
        }
    }
    Ok(())
}

fn check_size(vertices: u64, indices: u64) -> Result<()> {
    if vertices > u32::MAX as u64 || indices > u32::MAX as u64 {
        return Err(Error::Invalid(format!(
            "subdivision result too large: {vertices} vertices, {indices} face indices (limit 2^32 - 1)"
        )));
    }
    Ok(())
}

/// The largest mesh built on request: 2^25 face indices (11,184,810 triangles; 128 MiB
/// of `u32` indices) and as many vertices. Building and writing a mesh takes about
/// 18 bytes per face index at its peak (positions, faces, the encoded file and its
/// read-back check): `gen grid` at 2^26 indices peaked at 0.9 GB (PLY) and 1.2 GB
/// (OBJ), and the earlier 2^30 let `gen grid 13000 13000` ask for over 10 GB. The `check_*` functions refuse a request beyond it, so that a
/// typo cannot exhaust memory; the generators themselves only need `u32` indices.
pub const MAX_INDICES: u64 = 1 << 25;

/// The highest [`icosphere`] level built on request: 9, 5,242,880 triangles, inside
/// [`MAX_INDICES`] ([`icosphere`] itself goes to 12).
pub const MAX_ICOSPHERE_LEVEL: u32 = 9;

/// Refuses a [`grid`] (`quads == false`) or [`grid_quads`] of `w` by `h` squares
/// whose face indices or vertices would pass [`MAX_INDICES`]. Checks the size only:
/// zero squares is the caller's to refuse.
pub fn check_grid(w: u32, h: u32, quads: bool) -> Result<()> {
    let faces = w as u64 * h as u64;
    // Saturating: at w = h = 2^32 - 1 the products pass 2^64, and a wrapped one would
    // slip under the limit.
    let vertices = (w as u64 + 1).saturating_mul(h as u64 + 1);
    check_limit(faces.saturating_mul(if quads { 4 } else { 6 }), vertices)
}

/// Refuses an [`icosphere`] level above [`MAX_ICOSPHERE_LEVEL`].
pub fn check_icosphere(level: u32) -> Result<()> {
    if level > MAX_ICOSPHERE_LEVEL {
        return Err(Error::Invalid(format!(
            "icosphere level {level} is too large (at most {MAX_ICOSPHERE_LEVEL}: 5,242,880 triangles)"
        )));
    }
    Ok(())
}

/// Refuses a [`torus`] or [`torus_quads`] of `major` by `minor` segments whose face
/// indices or vertices would pass [`MAX_INDICES`] (counted as triangles, six indices
/// per segment pair, for both). Checks the size only.
pub fn check_torus(major: u32, minor: u32) -> Result<()> {
    let segments = major as u64 * minor as u64;
    check_limit(segments.saturating_mul(6), segments)
}

/// Refuses `levels` subdivisions (Loop or Catmull-Clark: each level multiplies the
/// face indices by 4) of a mesh with `face_indices` face indices when the result would
/// pass [`MAX_INDICES`]; a product beyond `u64` is refused with the request in the
/// message, never wrapped. `name` names the input in the message (a file, "cube").
pub fn check_subdivision(face_indices: usize, levels: u32, name: &str) -> Result<()> {
    let indices = face_indices as u64;
    // Nothing grows from nothing: 0 x 4^levels is 0 however large the power.
    if indices == 0 {
        return check_limit(0, 0);
    }
    let grown = 4u64.checked_pow(levels).and_then(|f| f.checked_mul(indices)).ok_or_else(|| {
        Error::Invalid(format!(
            "the requested mesh is too large ({name}: {indices} face indices x 4^{levels} is beyond 2^64; limit {MAX_INDICES})"
        ))
    })?;
    check_limit(grown, 0)
}

fn check_limit(indices: u64, vertices: u64) -> Result<()> {
    if indices > MAX_INDICES || vertices > MAX_INDICES {
        return Err(Error::Invalid(format!(
            "the requested mesh is too large ({indices} face indices, {vertices} vertices; limit {MAX_INDICES})"
        )));
    }
    Ok(())
}

/// All meshes side by side in one: vertex ids of each later mesh shifted past the
/// earlier ones, faces in order. Positions are kept as they are.
pub fn disjoint_union(meshes: &[&Mesh]) -> Mesh {
    let mut out = Mesh::new();
    for m in meshes {
        let base = out.positions.len() as u32;
        out.positions.extend_from_slice(&m.positions);
        for face in m.faces() {
            out.face_indices.extend(face.iter().map(|&v| v + base));
            out.face_offsets.push(out.face_indices.len() as u32);
        }
    }
    out
}

/// The same faces in a pseudo-random order (seeded, reproducible), each face rotated
/// to start at a pseudo-random corner; orientations and vertex ids are unchanged.
/// Meant for tests that must not depend on the input order.
pub fn shuffle_faces(mesh: &Mesh, seed: u64) -> Mesh {
    let mut state = seed ^ 0x9E37_79B9_7F4A_7C15;
    let mut next = move || {
        // splitmix64
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    };
    let mut order: Vec<u32> = (0..mesh.face_count() as u32).collect();
    for i in (1..order.len()).rev() {
        let j = (next() % (i as u64 + 1)) as usize;
        order.swap(i, j);
    }
    let mut out = Mesh { positions: mesh.positions.clone(), ..Mesh::new() };
    out.face_indices.reserve(mesh.face_indices.len());
    for &f in &order {
        let face = mesh.face(f as usize);
        let r = (next() % face.len() as u64) as usize;
        out.face_indices.extend_from_slice(&face[r..]);
        out.face_indices.extend_from_slice(&face[..r]);
        out.face_offsets.push(out.face_indices.len() as u32);
    }
    out
}

/// The same mesh with its vertex ids permuted pseudo-randomly (seeded, reproducible):
/// each vertex keeps its position under its new id, faces keep their corners' order.
/// With [`shuffle_faces`], the input orders a stripifier must not depend on.
pub fn renumber_vertices(mesh: &Mesh, seed: u64) -> Mesh {
    let mut state = seed ^ 0xD1B5_4A32_D192_ED03;
    let mut next = move || {
        // xorshift64*
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        state.wrapping_mul(0x2545_F491_4F6C_DD1D)
    };
    let n = mesh.vertex_count();
    let mut perm: Vec<u32> = (0..n as u32).collect();
    for i in (1..n).rev() {
        perm.swap(i, (next() % (i as u64 + 1)) as usize);
    }
    let mut positions = vec![[0.0; 3]; n];
    for (old, &new) in perm.iter().enumerate() {
        positions[new as usize] = mesh.positions[old];
    }
    Mesh {
        positions,
        face_offsets: mesh.face_offsets.clone(),
        face_indices: mesh.face_indices.iter().map(|&v| perm.get(v as usize).copied().unwrap_or(v)).collect(),
        ..Mesh::new()
    }
}

/// Flips every face whose Newell normal points towards the origin (for the convex,
/// origin-centred base meshes above).
fn orient_outward(mesh: &mut Mesh) {
    for f in 0..mesh.face_count() {
        let (s, t) = (mesh.face_offsets[f] as usize, mesh.face_offsets[f + 1] as usize);
        let face = &mesh.face_indices[s..t];
        let mut n = [0f64; 3];
        let mut c = [0f64; 3];
        for i in 0..face.len() {
            let a = to_f64(mesh.positions[face[i] as usize]);
            let b = to_f64(mesh.positions[face[(i + 1) % face.len()] as usize]);
            n[0] += (a[1] - b[1]) * (a[2] + b[2]);
            n[1] += (a[2] - b[2]) * (a[0] + b[0]);
            n[2] += (a[0] - b[0]) * (a[1] + b[1]);
            add(&mut c, a);
        }
        if n[0] * c[0] + n[1] * c[1] + n[2] * c[2] < 0.0 {
            mesh.face_indices[s..t].reverse();
        }
    }
}

#[inline]
fn add(acc: &mut [f64; 3], p: [f64; 3]) {
    acc[0] += p[0];
    acc[1] += p[1];
    acc[2] += p[2];
}

#[inline]
fn to_f64(p: [f32; 3]) -> [f64; 3] {
    [p[0] as f64, p[1] as f64, p[2] as f64]
}

#[inline]
fn to_f32(p: [f64; 3]) -> [f32; 3] {
    [p[0] as f32, p[1] as f32, p[2] as f32]
}

fn normalize(p: [f64; 3]) -> [f64; 3] {
    let len = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    [p[0] / len, p[1] / len, p[2] / len]
}

//! Single strips keep every vertex attribute: a UV'd torus with a seam, faces shuffled,
//! through `Algorithm::Single` to glb (input and first-use vertex order) and OBJ, read
//! back; every corner of every output triangle carries the attribute values of the
//! vertex it names (a Steiner vertex: the mean of the edge it splits, normals unit
//! length again, integers the first end's), swapped edges included.

mod support;

use std::collections::HashMap;
use stripkit::io::{self, Format};
use stripkit::{Algorithm, Attribute, Mesh, Scalar, SingleOptions, StripOptions, Strips, Weights};
use stripkit_testkit::XorShift64;

/// A torus whose grid is cut open along one meridian (UV seam): `(major + 1) * minor`
/// vertices, the seam's column twice with u = 0 and u = 1; UVs, unit normals and an
/// RGBA colour of normalized bytes and an integer id; quads split on alternating diagonals, positions
/// jittered so the quads are not planar; faces shuffled.
fn seamed_torus(major: u32, minor: u32, seed: u64) -> Mesh {
    let mut rng = XorShift64(seed | 1);
    let (big, small) = (2.0f64, 0.6f64);
    let (mut positions, mut uv, mut normal, mut colour) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for i in 0..=major {
        let a = std::f64::consts::TAU * i as f64 / major as f64;
        for j in 0..minor {
            let b = std::f64::consts::TAU * j as f64 / minor as f64;
            let n = [a.cos() * b.cos(), a.sin() * b.cos(), b.sin()];
            // The seam's two columns share positions exactly (no jitter there).
            let r = if i == 0 || i == major { small } else { small * (1.0 + 0.04 * (rng.unit() - 0.5)) };
            positions.push([(a.cos() * (big + r * b.cos())) as f32, (a.sin() * (big + r * b.cos())) as f32, (r * b.sin()) as f32]);
            uv.extend([i as f32 / major as f32, j as f32 / minor as f32]);
            normal.extend(n.map(|x| x as f32));
            colour.extend([(i * 37 % 256) as u8, (j * 91 % 256) as u8, 200, 255]);
        }
    }
    let id = |i: u32, j: u32| i * minor + j % minor;
    let mut faces = Vec::new();
    for i in 0..major {
        for j in 0..minor {
            let [a, b, c, d] = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            if (i + j) % 2 == 0 {
                faces.extend([vec![a, b, c], vec![a, c, d]]);
            } else {
                faces.extend([vec![a, b, d], vec![b, c, d]]);
            }
        }
    }
    rng.shuffle(&mut faces);
    let mut mesh = Mesh::from_polygons(positions, &faces);
    mesh.attributes.push(Attribute::from_f32("TEXCOORD_0", 2, &uv));
    mesh.attributes.push(Attribute::from_f32("NORMAL", 3, &normal));
    let mut rgba = Attribute::from_f32("COLOR_0", 4, &vec![0.0; colour.len()]);
    rgba.scalar = Scalar::U8;
    rgba.normalized = true;
    rgba.data = colour;
    mesh.attributes.push(rgba);
    // An integer id per vertex (not normalized): a Steiner vertex takes its first end's.
    let mut part = Attribute::from_f32("_PART", 1, &vec![0.0; mesh.vertex_count()]);
    part.scalar = Scalar::U16;
    part.data = (0..mesh.vertex_count() as u16).flat_map(|v| (v * 7 % 1000).to_le_bytes()).collect();
    mesh.attributes.push(part);
    mesh
}

/// The value each vertex of the changed mesh must carry, computed here from the input
/// and the edges split: input vertices their own, a Steiner vertex the mean of its
/// edge's two (normalized integers rounded, other integer kinds the first one's),
/// normals made unit length.
fn expected(mesh: &Mesh, strips: &Strips, name: &str) -> Vec<Vec<f64>> {
    let a = mesh.attribute(name).unwrap();
    let mut out: Vec<Vec<f64>> = (0..mesh.vertex_count()).map(|v| a.value(v)).collect();
    for &[x, y] in &strips.added_from {
        let (p, q) = (&out[x as usize], &out[y as usize]);
        let mut m: Vec<f64> = if a.scalar == Scalar::F32 {
            p.iter().zip(q).map(|(s, t)| (s + t) / 2.0).collect()
        } else if a.normalized {
            // Stored values (0..255 for bytes): the mean rounded to the nearest.
            p.iter().zip(q).map(|(s, t)| ((s + t) / 2.0).round()).collect()
        } else {
            p.clone()
        };
        if name == "NORMAL" {
            let len = m.iter().map(|c| c * c).sum::<f64>().sqrt();
            m.iter_mut().for_each(|c| *c /= len);
        }
        out.push(m);
    }
    out
}

/// The mesh a file holds: OBJ through the mesh reader, glb through the scene reader
/// (which keeps every attribute), one primitive.
fn read_back(format: Format, bytes: &[u8]) -> Mesh {
    let path = std::path::Path::new("back");
    if format == Format::Obj {
        return io::read_bytes(path, format, bytes).unwrap();
    }
    let scene = io::Scene::from_bytes(path, format, bytes, &io::ReadOptions::default()).unwrap();
    assert_eq!(scene.primitives().len(), 1);
    scene.primitives()[0].mesh.clone()
}

/// A triangle's corners as position bits, rotated to start at the smallest: the key
/// that finds it again after the file renumbered its vertices.
fn key(p: [[f32; 3]; 3]) -> [[u32; 3]; 3] {
    let bits = p.map(|c| c.map(f32::to_bits));
    let r = (0..3).min_by_key(|&k| bits[k]).unwrap();
    [bits[r], bits[(r + 1) % 3], bits[(r + 2) % 3]]
}

/// Reads `bytes` back and checks every corner of every triangle against `expected`
/// for each attribute in `names`; returns the corners compared.
fn check_corners(mesh: &Mesh, strips: &Strips, format: Format, bytes: &[u8], names: &[&str], tolerance: f64) -> usize {
    let positions: Vec<[f32; 3]> = mesh.positions.iter().chain(&strips.added_positions).copied().collect();
    let mut want: HashMap<[[u32; 3]; 3], [u32; 3]> = HashMap::new();
    for t in &strips.triangles {
        let p = t.map(|v| positions[v as usize]);
        let r = (0..3).min_by_key(|&k| p[k].map(f32::to_bits)).unwrap();
        assert!(want.insert(key(p), [t[r], t[(r + 1) % 3], t[(r + 2) % 3]]).is_none(), "two triangles at one place");
    }
    let back = read_back(format, bytes);
    let tris = back.triangulate().tris;
    assert_eq!(tris.len(), strips.triangles.len(), "{format:?}: every triangle once");
    let mut compared = 0;
    for name in names {
        let values = expected(mesh, strips, name);
        let got = back.attribute(name).unwrap_or_else(|| panic!("{format:?}: {name} lost"));
        for t in &tris {
            let p = t.map(|v| back.positions[v as usize]);
            let r = (0..3).min_by_key(|&k| p[k].map(f32::to_bits)).unwrap();
            let source = want.get(&key(p)).unwrap_or_else(|| panic!("{format:?}: a triangle not drawn by the strips"));
            for k in 0..3 {
                let corner = t[(r + k) % 3] as usize;
                let (g, w) = (got.value(corner), &values[source[k] as usize]);
                assert_eq!(g.len(), w.len(), "{format:?} {name}");
                for (x, y) in g.iter().zip(w) {
                    assert!((x - y).abs() <= tolerance, "{format:?} {name}: corner of vertex {} is {g:?}, not {w:?}", source[k]);
                }
                compared += 1;
            }
        }
    }
    compared
}

#[test]
fn single_keeps_every_attribute_corner_by_corner() {
    let mesh = seamed_torus(16, 9, 7);
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("single_attributes");
    std::fs::create_dir_all(&dir).unwrap();
    let mut glbs = Vec::new();
    // Cache weights leave loops to merge: by edge swaps (allowed up to 60 degrees, as
    // this coarse torus folds more than the default 5), or by edge splits alone.
    let cache = SingleOptions::new(Weights::Cache);
    for (label, o) in [("swaps", cache.clone().swap_angle(Some(60.0))), ("splits", cache.swap_angle(None))] {
        let strips = stripkit::stripify(&mesh, &StripOptions::default().algorithm(Algorithm::Single(o))).unwrap();
        let f = &strips.figures;
        assert!(f.verified && f.winding_preserved && (f.lost, f.added, f.flipped) == (0, 0, 0), "{f:?}");
        let report = strips.single.clone().unwrap();
        match label {
            "swaps" => assert!(report.swapped_edges > 0, "{report:?}"),
            _ => assert!(report.steiner_vertices > 0 && report.swapped_edges == 0, "{report:?}"),
        }
        let corners = 3 * strips.triangles.len();
        let glb = strips.to_file_bytes(&mesh, Format::Glb).unwrap();
        assert_eq!(check_corners(&mesh, &strips, Format::Glb, &glb, &["TEXCOORD_0", "NORMAL", "COLOR_0", "_PART"], 1e-6), 4 * corners);
        let obj = strips.to_file_bytes(&mesh, Format::Obj).unwrap();
        // OBJ writes decimals: values within its precision.
        assert_eq!(check_corners(&mesh, &strips, Format::Obj, &obj, &["TEXCOORD_0", "NORMAL"], 1e-5), 2 * corners);
        // First-use order (the CLI's default for glTF): the same corners, renumbered.
        let (ordered, renamed) = strips.in_first_use_order(&mesh, Format::Glb);
        let glb_first = renamed.to_file_bytes(&ordered, Format::Glb).unwrap();
        let back = read_back(Format::Glb, &glb_first);
        let tris = back.triangulate().tris;
        let changed = strips.changed_mesh(&mesh);
        let uv_back = back.attribute("TEXCOORD_0").unwrap();
        let uv_changed = changed.attribute("TEXCOORD_0").unwrap();
        let corner_uv = |m: &Mesh, a: &Attribute, t: &[u32; 3]| -> Vec<(Vec<u32>, Vec<f64>)> {
            t.iter().map(|&v| (m.positions[v as usize].map(f32::to_bits).to_vec(), a.value(v as usize))).collect()
        };
        let mut seen: Vec<_> = tris.iter().map(|t| corner_uv(&back, uv_back, t)).collect();
        let mut drawn: Vec<_> = changed.triangulate().tris.iter().map(|t| corner_uv(&changed, uv_changed, t)).collect();
        seen.iter_mut().chain(drawn.iter_mut()).for_each(|t| {
            let r = (0..3).min_by(|&a, &b| t[a].partial_cmp(&t[b]).unwrap()).unwrap();
            t.rotate_left(r);
        });
        seen.sort_by(|a, b| a.partial_cmp(b).unwrap());
        drawn.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(seen, drawn, "{label}: first-use glb corners");
        let path = dir.join(format!("{label}.glb"));
        std::fs::write(&path, &glb).unwrap();
        glbs.push(path);
    }
    let paths: Vec<&std::path::Path> = glbs.iter().map(|p| p.as_path()).collect();
    support::gltf_validator::validate(&paths);
}

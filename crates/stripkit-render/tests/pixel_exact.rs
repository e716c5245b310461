//! Strips draw exactly the triangles of the list they came from: for every algorithm and
//! join (restart buffer, stitched strip, separate strips as draw ranges), u16 and u32
//! indices, rendering the strips gives the same 512x512 picture as rendering the
//! triangle list (depth test on, back faces culled, unlit, two or three camera
//! directions), and the picture is not trivially empty. A mutated strip buffer (one
//! triangle dropped, or a strip's winding flipped by one inserted index) gives a
//! different picture, so the comparison can fail.
//!
//! Lit pictures are compared too but only reported: llvmpipe interpolates from a
//! triangle's first corner, and a strip starts its triangles at another corner than the
//! list does, so a few lit pixels differ in the last bit.
//!
//! Each check prints one line (`cargo test -p stripkit-render --test pixel_exact --
//! --nocapture`): `pixel-exact MESH ALGO JOIN WIDTH VIEW: D of 262144 differ, C covered;
//! lit: S smooth, F flat differ`.

mod support;

use stripkit::{gen, stripify, Algorithm, Error, GreedyOptions, Heuristic, Mesh, Split, StripOptions};
use stripkit_render::{DrawParams, Image, IndexWidth, Shading, Topology};
use support::{camera, covered, exact, flat, model, renderer, vertex_normals, Scene, RESTART, SIZE};

/// Views from the front-upper-right and from behind-below-left (closed meshes).
const VIEWS: [[f32; 3]; 2] = [[0.35, 0.45, 1.0], [-0.8, -0.3, -0.6]];
/// Two views from +z, for open meshes that face +z (grids).
const FRONT_VIEWS: [[f32; 3]; 2] = [[0.35, 0.45, 1.0], [-0.5, 0.2, 0.8]];
/// A picture covering fewer pixels than this is too empty to prove anything.
const MIN_COVERED: usize = 3_000;
const PIXELS: usize = (SIZE * SIZE) as usize;

fn triangle_algorithms() -> Vec<(&'static str, Algorithm)> {
    vec![
        ("auto", Algorithm::Auto),
        ("greedy", Algorithm::greedy()),
        ("greedy-strips", Algorithm::Greedy(GreedyOptions::with_heuristic(Heuristic::Strips))),
        ("greedy-notunnel", Algorithm::Greedy(GreedyOptions { tunnel_cuts: None, ..GreedyOptions::default() })),
        ("cache", Algorithm::cache()),
        ("cache-refine", Algorithm::Cache { refine: true }),
        ("balanced", Algorithm::balanced(0.8)),
    ]
}

fn quad_algorithms() -> Vec<(&'static str, Algorithm)> {
    vec![
        ("auto", Algorithm::Auto),
        ("qstrip", Algorithm::qstrip()),
        ("quad-single", Algorithm::QuadSingle),
        ("greedy", Algorithm::greedy()),
        ("cache", Algorithm::cache()),
        ("balanced", Algorithm::balanced(0.8)),
    ]
}

fn lit(mvp: [f32; 16], shading: Shading) -> DrawParams {
    DrawParams { shading, cull_back: true, ..DrawParams::new(mvp) }
}

/// The pictures of one triangle list from one view: exact (unlit) and lit.
struct Reference {
    exact: Image,
    smooth: Image,
    flat: Image,
}

fn reference(scene: &mut Scene, tris: &[[u32; 3]], mvp: [f32; 16]) -> Reference {
    let list = flat(tris);
    let mut draw = |p: &DrawParams| scene.picture(&list, Topology::Triangles, IndexWidth::U32, p);
    Reference { exact: draw(&exact(mvp)), smooth: draw(&lit(mvp, Shading::Smooth)), flat: draw(&lit(mvp, Shading::Flat)) }
}

/// Strips of `mesh` by every algorithm, drawn every way, against the list; returns the
/// failures (each printed figure line that did not hold), empty when all held.
fn check_mesh(name: &str, mesh: &Mesh, algorithms: &[(&str, Algorithm)], views: &[[f32; 3]]) -> Vec<String> {
    let fan = mesh.triangulate().tris;
    let normals = vertex_normals(&mesh.positions, &fan);
    let mut scene = Scene::new(renderer(), &mesh.positions, Some(&normals));
    let mvps: Vec<[f32; 16]> = views.iter().map(|&d| camera(&mesh.positions, d)).collect();
    let fan_refs: Vec<Reference> = mvps.iter().map(|&m| reference(&mut scene, &fan, m)).collect();
    let mut widths = vec![IndexWidth::U32];
    if mesh.vertex_count() < 0xFFFF {
        widths.push(IndexWidth::U16);
    }
    let mut failures = Vec::new();
    for (algo, algorithm) in algorithms {
        let strips = match stripify(mesh, &StripOptions::default().algorithm(algorithm.clone())) {
            Ok(s) => s,
            Err(Error::Invalid(why)) if matches!(algorithm, Algorithm::QuadSingle) => {
                println!("pixel-exact {name} {algo}: not applicable ({why})");
                continue;
            }
            Err(e) => {
                failures.push(format!("{name} {algo}: stripify failed: {e}"));
                continue;
            }
        };
        // The list to compare with: the mesh's fan, or the split the strips chose
        // (QSTRIP's diagonals), which is then compared with the fan for the record.
        let split_refs: Vec<Reference>;
        let refs = if strips.split == Split::Qstrip {
            split_refs = mvps.iter().map(|&m| reference(&mut scene, &strips.triangles, m)).collect();
            for (v, (s, f)) in split_refs.iter().zip(&fan_refs).enumerate() {
                println!(
                    "pixel-exact {name} {algo} split-vs-fan view{v}: {} of {PIXELS} differ (information: the strips chose other diagonals than the fan)",
                    s.exact.differing_pixels(&f.exact)
                );
            }
            &split_refs
        } else {
            &fan_refs
        };
        let restart = strips.restart_buffer();
        let stitched = strips.stitched();
        let mut ranges = Vec::new();
        let mut start = 0;
        for s in strips.strips.iter() {
            ranges.push((start, s.len()));
            start += s.len() + 1;
        }
        let joins: [(&str, &Vec<u32>, Option<Vec<(usize, usize)>>); 3] =
            [("restart", &restart, None), ("stitched", &stitched, None), ("separate", &restart, Some(ranges))];
        for (join, buffer, ranges) in &joins {
            for (v, (&mvp, r)) in mvps.iter().zip(refs).enumerate() {
                for (w, &width) in widths.iter().enumerate() {
                    let params = DrawParams { ranges: ranges.clone(), ..exact(mvp) };
                    let image = scene.picture(buffer, Topology::Strip, width, &params);
                    let diff = image.differing_pixels(&r.exact);
                    let cov = support::covered(&image);
                    let width_name = if width == IndexWidth::U16 { "u16" } else { "u32" };
                    let mut line = format!(
                        "pixel-exact {name} {algo} {join} {width_name} view{v}: {diff} of {PIXELS} differ, {cov} covered"
                    );
                    if w == 0 {
                        let mut lit_diff = |shading| {
                            let p = DrawParams { ranges: ranges.clone(), ..lit(mvp, shading) };
                            let reference = if shading == Shading::Smooth { &r.smooth } else { &r.flat };
                            scene.picture(buffer, Topology::Strip, width, &p).differing_pixels(reference)
                        };
                        let (s, f) = (lit_diff(Shading::Smooth), lit_diff(Shading::Flat));
                        line += &format!("; lit: {s} smooth, {f} flat differ");
                    }
                    println!("{line}");
                    if diff != 0 || cov < MIN_COVERED || cov != covered(&r.exact) {
                        failures.push(line);
                    }
                }
            }
        }
    }
    failures
}

fn assert_none(failures: Vec<String>) {
    assert!(failures.is_empty(), "{} checks failed:\n{}", failures.len(), failures.join("\n"));
}

#[test]
fn bunny_every_algorithm() {
    let Some(mesh) = model("bunny.obj") else { return };
    assert_none(check_mesh("bunny", &mesh, &triangle_algorithms(), &VIEWS));
}

#[test]
fn shuffled_procedural_triangle_meshes() {
    let sphere = gen::renumber_vertices(&gen::shuffle_faces(&gen::icosphere(3), 21), 7);
    let torus = gen::renumber_vertices(&gen::shuffle_faces(&gen::torus(40, 16, 1.0, 0.35), 22), 8);
    let grid = gen::shuffle_faces(&gen::grid(24, 16), 23);
    let mut failures = check_mesh("icosphere3-shuffled", &sphere, &triangle_algorithms(), &VIEWS);
    failures.extend(check_mesh("torus-shuffled", &torus, &triangle_algorithms(), &VIEWS));
    failures.extend(check_mesh("grid-shuffled", &grid, &triangle_algorithms(), &FRONT_VIEWS));
    assert_none(failures);
}

#[test]
fn quad_meshes() {
    let torus = gen::shuffle_faces(&gen::torus_quads(32, 12, 1.0, 0.4), 31);
    let grid = gen::shuffle_faces(&gen::grid_quads(20, 12), 32);
    let mut failures = check_mesh("torus-quads-shuffled", &torus, &quad_algorithms(), &VIEWS);
    failures.extend(check_mesh("grid-quads-shuffled", &grid, &quad_algorithms(), &FRONT_VIEWS));
    for name in ["quads/spot_quadrangulated.obj", "quads/halftunnel.off"] {
        if let Some(mesh) = model(name) {
            let short = name.trim_start_matches("quads/").split('.').next().unwrap_or(name);
            failures.extend(check_mesh(short, &mesh, &quad_algorithms(), &VIEWS));
        }
    }
    assert_none(failures);
}

/// Four pages sharing one spine edge (an edge of four faces) and two hexagonal fans
/// touching at one vertex (a bowtie), each page and fan of several triangles.
fn non_manifold() -> Mesh {
    let mut positions: Vec<[f32; 3]> = vec![[0.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
    let mut tris: Vec<[u32; 3]> = Vec::new();
    for k in 0..4 {
        let a = 0.4 + k as f32 * std::f32::consts::FRAC_PI_2 * 0.9;
        let (c, s) = (a.cos(), a.sin());
        let base = positions.len() as u32;
        for d in [1.0f32, 2.0] {
            positions.push([c * d, 0.0, s * d]);
            positions.push([c * d, 2.0 - 0.3 * d, s * d]);
        }
        // Spine 0-1, then columns (base, base+1) and (base+2, base+3).
        let (p0, p1, q0, q1) = (base, base + 1, base + 2, base + 3);
        tris.extend([[0, p0, p1], [0, p1, 1], [p0, q0, q1], [p0, q1, p1]]);
    }
    // Bowtie at vertex c: two fans of six triangles in different planes.
    let c = positions.len() as u32;
    positions.push([2.5, 1.0, 0.0]);
    for (k, plane) in [0usize, 1].into_iter().enumerate() {
        let ring = positions.len() as u32;
        let side = if k == 0 { 1.0 } else { -1.0 };
        for i in 0..6 {
            let a = i as f32 * std::f32::consts::TAU / 6.0;
            let (u, v) = (0.9 * a.cos(), 0.9 * a.sin());
            let center = [2.5 + side * 0.9, 1.0, 0.0];
            positions.push(if plane == 0 {
                [center[0] + u, center[1] + v, 0.3 * u]
            } else {
                [center[0] + u, center[1] + 0.3 * u, v]
            });
        }
        // The ring's vertex nearest c is replaced by c itself: the two fans meet there.
        let nearest = if k == 0 { 3 } else { 0 };
        let id = |i: u32| if i == nearest { c } else { ring + i };
        let hub = positions.len() as u32;
        positions.push([2.5 + side * 0.9, 1.0, 0.0]);
        for i in 0..6u32 {
            tris.push([hub, id(i), id((i + 1) % 6)]);
        }
    }
    gen::shuffle_faces(&Mesh::from_triangles(positions, &tris), 41)
}

#[test]
fn non_manifold_meshes() {
    let mesh = non_manifold();
    let facts = stripkit::MeshFacts::of(&mesh).expect("a valid mesh");
    println!(
        "non-manifold procedural: {} triangles, {} non-manifold edges, {} non-manifold vertices",
        mesh.triangle_count(),
        facts.nonmanifold_edges,
        facts.nonmanifold_vertices
    );
    assert!(facts.nonmanifold_edges >= 1 && facts.nonmanifold_vertices >= 1, "{facts:?}");
    let views = [[0.35, 0.45, 1.0], [-0.8, -0.3, -0.6], [0.9, 0.2, -0.4]];
    let mut failures = check_mesh("non-manifold", &mesh, &triangle_algorithms(), &views);
    for name in ["bunny_res3.ply", "cow.obj"] {
        if let Some(mesh) = model(name) {
            let short = name.split('.').next().unwrap_or(name);
            failures.extend(check_mesh(short, &mesh, &triangle_algorithms(), &VIEWS));
        }
    }
    assert_none(failures);
}

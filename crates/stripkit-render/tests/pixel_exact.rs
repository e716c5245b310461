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
use stripkit_render::vertex_normals;
use support::{camera, color_difference, covered, exact, flat, model, renderer, Scene, SIZE};

/// Views from the front-upper-right and from behind-below-left (closed meshes).
const VIEWS: [[f32; 3]; 2] = [[0.35, 0.45, 1.0], [-0.8, -0.3, -0.6]];
/// Two views from +z, for open meshes that face +z (grids).
const FRONT_VIEWS: [[f32; 3]; 2] = [[0.35, 0.45, 1.0], [-0.5, 0.2, 0.8]];
/// Pictures in per-vertex colours may differ by this much per channel: llvmpipe
/// interpolates from a triangle's first corner, which strips choose differently (1 is
/// what bunny shows); a triangle missing, flipped or drawn with other corners differs
/// by far more.
const COLOR_TOLERANCE: u8 = 2;
/// A picture covering fewer pixels than this is too empty to prove anything.
const MIN_COVERED: usize = 3_000;
const PIXELS: usize = (SIZE * SIZE) as usize;

fn triangle_algorithms() -> Vec<(&'static str, Algorithm)> {
    vec![
        ("auto", Algorithm::auto()),
        ("greedy", Algorithm::greedy()),
        ("greedy-strips", Algorithm::Greedy(GreedyOptions::default().heuristic(Heuristic::Strips))),
        ("greedy-notunnel", Algorithm::Greedy(GreedyOptions::default().tunnel_cuts(None))),
        ("cache", Algorithm::cache()),
        ("cache-refine", Algorithm::Cache { refine: true }),
        ("balanced", Algorithm::balanced(0.8)),
    ]
}

fn quad_algorithms() -> Vec<(&'static str, Algorithm)> {
    vec![
        ("auto", Algorithm::auto()),
        ("qstrip", Algorithm::qstrip()),
        ("quad-single", Algorithm::QuadSingle),
        ("greedy", Algorithm::greedy()),
        ("cache", Algorithm::cache()),
        ("balanced", Algorithm::balanced(0.8)),
    ]
}

/// Draw ranges `(first index, count)`, one draw call each; `None` for the whole buffer.
type Ranges = Option<Vec<(usize, usize)>>;

fn lit(mvp: [f32; 16], shading: Shading) -> DrawParams {
    DrawParams { shading, cull_back: true, ..DrawParams::new(mvp) }
}

/// The pictures of one triangle list from one view: exact (unlit) and lit.
struct Reference {
    exact: Image,
    colored: Image,
    smooth: Image,
    flat: Image,
}

fn reference(scene: &mut Scene, tris: &[[u32; 3]], mvp: [f32; 16]) -> Reference {
    let list = flat(tris);
    let mut draw = |p: &DrawParams| scene.picture(&list, Topology::Triangles, IndexWidth::U32, p);
    let (exact, smooth, flat) = (draw(&exact(mvp)), draw(&lit(mvp, Shading::Smooth)), draw(&lit(mvp, Shading::Flat)));
    let colored = scene.colored_picture(&list, Topology::Triangles, IndexWidth::U32, &support::exact(mvp));
    Reference { exact, colored, smooth, flat }
}

/// Strips of `mesh` by every algorithm, drawn every way, against the list; returns the
/// failures (each printed figure line that did not hold), empty when all held.
fn check_mesh(name: &str, mesh: &Mesh, algorithms: &[(&str, Algorithm)], views: &[[f32; 3]]) -> Vec<String> {
    let fan = mesh.triangulate().tris;
    let normals = vertex_normals(&mesh.positions, &flat(&fan));
    let mut scene = Scene::new(renderer(), &mesh.positions, Some(&normals));
    let mvps: Vec<[f32; 16]> = views.iter().map(|&d| camera(&mesh.positions, d)).collect();
    let fan_refs: Vec<Reference> = mvps.iter().map(|&m| reference(&mut scene, &fan, m)).collect();
    let mut widths = vec![IndexWidth::U32];
    if mesh.vertex_count() < 0xFFFF {
        widths.push(IndexWidth::U16);
    }
    let mut failures = Vec::new();
    for (algo, algorithm) in algorithms {
        let started = std::time::Instant::now();
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
        let stripify_time = started.elapsed();
        let started = std::time::Instant::now();
        // The list to compare with: the mesh's fan, or the split the strips chose
        // (QSTRIP's diagonals), which is then compared with the fan for the record.
        let split_refs: Vec<Reference>;
        let refs = if strips.split == Split::Qstrip {
            split_refs = mvps.iter().map(|&m| reference(&mut scene, &strips.triangles, m)).collect();
            for (v, (s, f)) in split_refs.iter().zip(&fan_refs).enumerate() {
                println!(
                    "pixel-exact {name} {algo} split-vs-fan view{v}: {} of {PIXELS} differ (information only: the list of the strips' diagonals against the fan)",
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
        let joins: [(&str, &Vec<u32>, Ranges); 3] =
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
                        let colored = scene.colored_picture(buffer, Topology::Strip, width, &params);
                        let (off, max) = color_difference(&colored, &r.colored, 0);
                        let (far_off, _) = color_difference(&colored, &r.colored, COLOR_TOLERANCE);
                        line += &format!("; lit: {s} smooth, {f} flat differ; coloured: {off} differ, by at most {max}");
                        if far_off > 0 {
                            failures.push(format!("{line} ({far_off} pixels by more than {COLOR_TOLERANCE})"));
                        }
                    }
                    println!("{line}");
                    if diff != 0 || cov < MIN_COVERED || cov != covered(&r.exact) {
                        failures.push(line);
                    }
                }
            }
        }
        println!(
            "pixel-exact {name} {algo}: {} strips, {} indices (restart), stripify and check {:.0} ms, pictures {:.0} ms",
            strips.strips.len(),
            restart.len(),
            stripify_time.as_secs_f64() * 1e3,
            started.elapsed().as_secs_f64() * 1e3
        );
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

/// Signed area in pixels of triangle `t` on screen: positive for counter-clockwise
/// (front-facing, drawn), negative for back-facing (culled).
fn screen_area(mvp: [f32; 16], positions: &[[f32; 3]], t: [u32; 3]) -> f32 {
    let m = glam::Mat4::from_cols_array(&mvp);
    let [a, b, c] = t.map(|i| {
        let clip = m * glam::Vec3::from(positions[i as usize]).extend(1.0);
        (clip.truncate() / clip.w).truncate() * (SIZE as f32 * 0.5)
    });
    0.5 * (b - a).perp_dot(c - a)
}

/// The comparison can fail: in the restart buffer of a shuffled icosphere's strips,
/// dropping a strip's first triangle (its first index replaced by its second, which
/// keeps the winding of the rest) changes the grey picture exactly when that triangle
/// faces the camera and covers pixels; flipping a strip's winding (one index inserted in
/// front of it) changes the coloured picture whenever the strip has a visible triangle;
/// flipping the whole stitched strip changes the coloured one. (A closed mesh turned
/// inside out keeps its grey silhouette: that is what the coloured pictures are for.)
#[test]
fn mutated_strips_give_other_pictures() {
    let mesh = gen::renumber_vertices(&gen::shuffle_faces(&gen::icosphere(2), 51), 9);
    let fan = mesh.triangulate().tris;
    let strips = stripify(&mesh, &StripOptions::default().algorithm(Algorithm::cache())).expect("strips");
    let mvp = camera(&mesh.positions, VIEWS[0]);
    let mut scene = Scene::new(renderer(), &mesh.positions, None);
    let list = flat(&fan);
    let grey = scene.picture(&list, Topology::Triangles, IndexWidth::U32, &exact(mvp));
    let colored = scene.colored_picture(&list, Topology::Triangles, IndexWidth::U32, &exact(mvp));
    let base = strips.restart_buffer();
    // (grey pixels differing, coloured pixels differing by more than the tolerance)
    let mut draw = |buffer: &[u32]| {
        let g = scene.picture(buffer, Topology::Strip, IndexWidth::U32, &exact(mvp)).differing_pixels(&grey);
        let c = scene.colored_picture(buffer, Topology::Strip, IndexWidth::U32, &exact(mvp));
        (g, color_difference(&c, &colored, COLOR_TOLERANCE).0)
    };
    assert_eq!(draw(&base), (0, 0), "the unmutated strips");
    let (mut seen, mut visible, mut culled_changed, mut culled, mut fewest) = (0, 0, 0, 0, usize::MAX);
    let (mut flips_seen, mut flips_grey, mut flips_visible) = (0, 0, 0);
    let mut failures = Vec::new();
    let mut start = 0;
    for (k, s) in strips.strips.iter().enumerate() {
        let first = [s[0], s[1], s[2]];
        let area = screen_area(mvp, &mesh.positions, first);
        if !stripkit::is_degenerate(&first) && !(-1.0..=4.0).contains(&area) {
            let mut dropped = base.clone();
            dropped[start] = s[1];
            let (diff, color_diff) = draw(&dropped);
            if area > 4.0 {
                visible += 1;
                seen += usize::from(diff > 0);
                fewest = fewest.min(diff);
                if diff == 0 {
                    failures.push(format!("strip {k}: dropping its first triangle ({area:.0} px) changed nothing"));
                }
            } else {
                culled += 1;
                culled_changed += usize::from(diff + color_diff > 0);
                if diff + color_diff > 0 {
                    failures.push(format!("strip {k}: dropping its back-facing first triangle changed {diff} pixels"));
                }
            }
        }
        let mut t = Vec::new();
        stripkit::for_each_triangle(s, |tri| t.push(tri));
        if t.iter().any(|&tri| !stripkit::is_degenerate(&tri) && screen_area(mvp, &mesh.positions, tri) > 4.0) {
            let mut flipped = base.clone();
            flipped.insert(start, s[0]);
            let (diff, color_diff) = draw(&flipped);
            flips_visible += 1;
            flips_seen += usize::from(color_diff > 0);
            flips_grey += usize::from(diff > 0);
            if color_diff == 0 {
                failures.push(format!("strip {k}: flipping its winding changed nothing"));
            }
        }
        start += s.len() + 1;
    }
    let stitched = strips.stitched();
    let mut flipped = vec![stitched[0]];
    flipped.extend_from_slice(&stitched);
    let (whole_grey, whole) = draw(&flipped);
    println!(
        "mutation icosphere2 cache restart u32 ({} strips): dropping a visible first triangle changed the grey picture for \
         {seen} of {visible} strips (fewest {fewest} pixels), a culled one for {culled_changed} of {culled}; flipping a strip \
         with a visible triangle changed the coloured picture for {flips_seen} of {flips_visible} (the grey one for {flips_grey}); \
         flipping the whole stitched strip: {whole} coloured, {whole_grey} grey pixels of {PIXELS} differ",
        strips.strips.len()
    );
    assert!(visible >= 5 && culled >= 5 && flips_visible >= 5, "too few strips to try");
    assert!(whole > 0, "flipping the whole stitched strip changed nothing");
    assert_none(failures);
}

/// On the bunny, whose triangles cover a pixel or two each: flipping the longest strip,
/// and dropping the largest visible first triangle of a strip, change the picture.
#[test]
fn mutated_bunny_strips_give_other_pictures() {
    let Some(mesh) = model("bunny.obj") else { return };
    let fan = mesh.triangulate().tris;
    let strips = stripify(&mesh, &StripOptions::default().algorithm(Algorithm::greedy())).expect("strips");
    let mvp = camera(&mesh.positions, VIEWS[0]);
    let mut scene = Scene::new(renderer(), &mesh.positions, None);
    let list = scene.picture(&flat(&fan), Topology::Triangles, IndexWidth::U32, &exact(mvp));
    let base = strips.restart_buffer();
    let mut starts = Vec::new();
    let mut start = 0;
    for s in strips.strips.iter() {
        starts.push(start);
        start += s.len() + 1;
    }
    let longest = (0..strips.strips.len()).max_by_key(|&k| strips.strips.strip(k).len()).expect("strips");
    let mut flipped = base.clone();
    flipped.insert(starts[longest], strips.strips.strip(longest)[0]);
    let largest = (0..strips.strips.len())
        .max_by(|&a, &b| {
            let area = |k: usize| {
                let s = strips.strips.strip(k);
                screen_area(mvp, &mesh.positions, [s[0], s[1], s[2]])
            };
            area(a).total_cmp(&area(b))
        })
        .expect("strips");
    let s = strips.strips.strip(largest);
    let area = screen_area(mvp, &mesh.positions, [s[0], s[1], s[2]]);
    let mut dropped = base.clone();
    dropped[starts[largest]] = s[1];
    let mut draw = |buffer: &[u32]| scene.picture(buffer, Topology::Strip, IndexWidth::U32, &exact(mvp)).differing_pixels(&list);
    let (flip, drop) = (draw(&flipped), draw(&dropped));
    println!(
        "mutation bunny greedy restart u32: flipping the longest strip ({} indices): {flip} of {PIXELS} differ; \
         dropping the largest visible first triangle ({area:.1} px): {drop} differ",
        strips.strips.strip(longest).len()
    );
    assert!(flip > 0 && drop > 0);
}

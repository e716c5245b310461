//! What the renderer promises, each checked against a picture of a triangle list:
//! odd-parity joins of stitched strips keep the winding, the restart index separates
//! strips for u16 and u32, PNGs decode to the framebuffer, ranges draw only their
//! ranges, morphs at t = 0 and 1 are the base and the target, and a u16 buffer refuses
//! an index it cannot hold. Each check prints one line of figures.

mod support;

use stripkit::{gen, stripify, Algorithm, Mesh, StripOptions, StripSet};
use stripkit_render::{DrawParams, IndexWidth, RenderError, Topology, Vertices};
use support::{camera, color_difference, covered, exact, flat, renderer, Scene, BACKGROUND, RESTART, SIZE};

const PIXELS: usize = (SIZE * SIZE) as usize;
const WIDTHS: [(IndexWidth, &str); 2] = [(IndexWidth::U32, "u32"), (IndexWidth::U16, "u16")];

/// How many joins of `encode_stitched(strips)` start the next strip at an odd position
/// (where the stitcher must re-encode it or add a third index to keep its winding).
fn odd_joins(strips: &StripSet) -> (usize, usize) {
    let drawn: Vec<&[u32]> = strips.iter().filter(|s| s.len() >= 3).collect();
    let mut odd = 0;
    for k in 1..drawn.len() {
        let prefix = StripSet::from_strips(&drawn[..k]);
        odd += stripkit::encode_stitched(&prefix).len() % 2;
    }
    (drawn.len().saturating_sub(1), odd)
}

/// Closed meshes stitched into one strip with odd-parity joins, drawn with back faces
/// culled: exactly the list's picture (no hole where a re-encoded or padded strip
/// would have turned its triangles around).
#[test]
fn odd_parity_joins_keep_the_winding() {
    let sphere = gen::renumber_vertices(&gen::shuffle_faces(&gen::icosphere(2), 61), 3);
    let torus = gen::shuffle_faces(&gen::torus(24, 12, 1.0, 0.4), 62);
    // One strip per triangle: every second join is odd.
    let singles = StripSet::from_strips(&sphere.triangulate().tris.iter().map(|t| t.to_vec()).collect::<Vec<_>>());
    let torus_cache = stripify(&torus, &StripOptions::default().algorithm(Algorithm::cache())).expect("strips").strips;
    let sphere_cache = stripify(&sphere, &StripOptions::default().algorithm(Algorithm::cache())).expect("strips").strips;
    let mut cases = vec![
        ("icosphere2 single triangles", sphere.clone(), singles),
        ("torus cache", torus, torus_cache),
        ("icosphere2 cache", sphere, sphere_cache),
    ];
    // A closed scanned mesh, where greedy's strips have odd lengths too.
    if let Some(bunny) = support::model("bunny_small.off") {
        let greedy = stripify(&bunny, &StripOptions::default().algorithm(Algorithm::greedy())).expect("strips").strips;
        cases.push(("bunny_small greedy", bunny, greedy));
    }
    for (name, mesh, strips) in &cases {
        let (joins, odd) = odd_joins(strips);
        assert!(odd > 0, "{name}: no odd-parity join to test");
        let stitched = stripkit::encode_stitched(strips);
        let list = flat(&mesh.triangulate().tris);
        let mut scene = Scene::new(renderer(), &mesh.positions, None);
        for (v, dir) in [[0.35, 0.45, 1.0], [-0.8, -0.3, -0.6]].into_iter().enumerate() {
            let p = exact(camera(&mesh.positions, dir));
            let reference = scene.picture(&list, Topology::Triangles, IndexWidth::U32, &p);
            let colored_ref = scene.colored_picture(&list, Topology::Triangles, IndexWidth::U32, &p);
            for (width, width_name) in WIDTHS {
                let image = scene.picture(&stitched, Topology::Strip, width, &p);
                let colored = scene.colored_picture(&stitched, Topology::Strip, width, &p);
                let diff = image.differing_pixels(&reference);
                let (far, max) = color_difference(&colored, &colored_ref, 2);
                println!(
                    "odd-parity {name} stitched {width_name} view{v}: {joins} joins, {odd} odd; {diff} of {PIXELS} differ, \
                     {} covered; coloured: largest channel difference {max}",
                    covered(&image)
                );
                assert_eq!(diff, 0, "{name} {width_name} view{v}");
                assert_eq!(far, 0, "{name} {width_name} view{v}: coloured");
                assert!(covered(&image) > 10_000);
            }
        }
    }
}

/// Two quads side by side, one strip each, separated by the restart index: exactly
/// the two quads, and no triangle bridging the gap between them.
#[test]
fn restart_separates_strips_for_u16_and_u32() {
    let mut positions = Vec::new();
    for x0 in [-1.0f32, 0.2] {
        // Bottom-left, bottom-right, top-left, top-right: the strip 0 1 2 3 is the quad.
        positions.extend([[x0, -0.4, 0.0], [x0 + 0.8, -0.4, 0.0], [x0, 0.4, 0.0], [x0 + 0.8, 0.4, 0.0]]);
    }
    let strip = [0, 1, 2, 3, RESTART, 4, 5, 6, 7];
    let list = [0, 1, 2, 2, 1, 3, 4, 5, 6, 6, 5, 7];
    let mut scene = Scene::new(renderer(), &positions, None);
    let p = exact(camera(&positions, [0.0, 0.0, 1.0]));
    let reference = scene.picture(&list, Topology::Triangles, IndexWidth::U32, &p);
    for (width, width_name) in WIDTHS {
        let image = scene.picture(&strip, Topology::Strip, width, &p);
        let diff = image.differing_pixels(&reference);
        // The gap: the middle column, from top to bottom.
        let gap = (0..SIZE).filter(|&y| image.pixel(SIZE / 2, y)[..3] != [0, 0, 0]).count();
        let (left, right) = (image.pixel(SIZE / 4, SIZE / 2), image.pixel(3 * SIZE / 4, SIZE / 2));
        println!(
            "restart {width_name}: two strips, {diff} of {PIXELS} differ from the two quads, {} covered, {gap} covered in the gap",
            covered(&image)
        );
        assert_eq!(diff, 0, "{width_name}");
        assert_eq!(gap, 0, "{width_name}: a triangle bridges the restart");
        assert!(left[..3] != [0, 0, 0] && right[..3] != [0, 0, 0], "{width_name}: a quad is missing");
    }
}

/// A PNG written by `Image::write_png` decodes to the framebuffer's size and pixels.
#[test]
fn png_is_written_and_decodes() {
    let mesh = gen::icosphere(3);
    let mut scene = Scene::new(renderer(), &mesh.positions, None);
    let p = DrawParams { cull_back: true, ..DrawParams::new(camera(&mesh.positions, [0.35, 0.45, 1.0])) };
    let image = scene.picture(&flat(&mesh.triangulate().tris), Topology::Triangles, IndexWidth::U32, &p);
    let dir = stripkit_testkit::scratch_dir("render-png");
    let path = dir.join("sphere.png");
    image.write_png(&path).expect("writes the PNG");
    let bytes = std::fs::read(&path).expect("reads the PNG back");
    let mut reader = png::Decoder::new(&bytes[..]).read_info().expect("a PNG header");
    let mut pixels = vec![0; reader.output_buffer_size()];
    let frame = reader.next_frame(&mut pixels).expect("PNG pixels");
    let info = scene.renderer.info().clone();
    println!(
        "png: {} bytes, {}x{} {:?} {:?}, {} covered, drawn by {} ({}, {})",
        bytes.len(),
        frame.width,
        frame.height,
        frame.color_type,
        frame.bit_depth,
        covered(&image),
        info.renderer,
        info.version,
        info.platform
    );
    assert_eq!((frame.width, frame.height), (SIZE, SIZE));
    assert_eq!((frame.color_type, frame.bit_depth), (png::ColorType::Rgba, png::BitDepth::Eight));
    assert_eq!(&pixels[..frame.buffer_size()], image.rgba(), "decoded pixels");
    assert!(covered(&image) > 10_000);
    // Nothing but the picture is left behind (the temporary file was renamed).
    let names: Vec<_> = std::fs::read_dir(&dir).expect("lists").map(|e| e.expect("entry").file_name()).collect();
    assert_eq!(names, ["sphere.png"]);
    std::fs::remove_dir_all(&dir).expect("removes the temporary folder");
}

/// Draw ranges draw exactly their ranges: two whole strips of a restart buffer, part of
/// a strip, and a range past the end (clamped: nothing).
#[test]
fn ranges_draw_only_their_ranges() {
    let mesh = gen::shuffle_faces(&gen::grid(16, 12), 71);
    let strips = stripify(&mesh, &StripOptions::default().algorithm(Algorithm::cache())).expect("strips");
    let buffer = strips.restart_buffer();
    let mut starts = Vec::new();
    let mut at = 0;
    for s in strips.strips.iter() {
        starts.push(at);
        at += s.len() + 1;
    }
    let n = strips.strips.len();
    assert!(n >= 4, "{n} strips");
    let (a, b) = (1, n - 2);
    let (sa, sb) = (strips.strips.strip(a), strips.strips.strip(b));
    let mut scene = Scene::new(renderer(), &mesh.positions, None);
    let base = exact(camera(&mesh.positions, [0.2, 0.3, 1.0]));
    let whole = scene.picture(&buffer, Topology::Strip, IndexWidth::U32, &base);
    for (what, ranges, expected) in [
        (
            "two whole strips",
            vec![(starts[a], sa.len()), (starts[b], sb.len())],
            stripkit::encode_restart(&StripSet::from_strips(&[sa, sb]), RESTART),
        ),
        ("the first 5 indices of a strip", vec![(starts[a], 5)], sa[..5].to_vec()),
        ("past the end", vec![(buffer.len() + 3, 10)], Vec::new()),
    ] {
        for (width, width_name) in WIDTHS {
            let params = DrawParams { ranges: Some(ranges.clone()), ..base.clone() };
            let image = scene.picture(&buffer, Topology::Strip, width, &params);
            let reference = scene.picture(&expected, Topology::Strip, width, &base);
            let diff = image.differing_pixels(&reference);
            println!(
                "ranges {what} {width_name}: {diff} of {PIXELS} differ from drawing those strips alone, {} covered (whole buffer {})",
                covered(&image),
                covered(&whole)
            );
            assert_eq!(diff, 0, "{what} {width_name}");
            assert!(covered(&image) < covered(&whole), "{what}: the ranges drew everything");
            if !expected.is_empty() {
                assert!(covered(&image) > 100, "{what}: nothing drawn");
            }
        }
    }
}

/// Morphing at t = 0 draws the base positions, at t = 1 the target ones, at t = 0.5
/// neither.
#[test]
fn morph_endpoints_are_base_and_target() {
    let mesh: Mesh = gen::icosphere(3);
    let target: Vec<[f32; 3]> = mesh.positions.iter().map(|p| [1.4 * p[0] + 0.3, 0.6 * p[1], p[2] + 0.2 * p[0]]).collect();
    let list = flat(&mesh.triangulate().tris);
    let both: Vec<[f32; 3]> = mesh.positions.iter().chain(&target).copied().collect();
    let mvp = camera(&both, [0.35, 0.45, 1.0]);
    let mut r = renderer();
    let morphing = r.upload(&Vertices { morph_target: Some(&target), ..Vertices::new(&mesh.positions) }).expect("uploads");
    let base = r.upload(&Vertices::new(&mesh.positions)).expect("uploads");
    let moved = r.upload(&Vertices::new(&target)).expect("uploads");
    let indices = r.upload_indices(&list, Topology::Triangles, IndexWidth::U32).expect("uploads");
    let mut draw = |g: &stripkit_render::Geometry, morph: f32| {
        r.clear(BACKGROUND);
        r.draw(g, &indices, &DrawParams { morph, ..exact(mvp) });
        r.read_image()
    };
    let (at0, at1, half) = (draw(&morphing, 0.0), draw(&morphing, 1.0), draw(&morphing, 0.5));
    let (base_image, target_image) = (draw(&base, 0.0), draw(&moved, 0.0));
    let (d0, d1) = (at0.differing_pixels(&base_image), at1.differing_pixels(&target_image));
    let (h0, h1) = (half.differing_pixels(&base_image), half.differing_pixels(&target_image));
    println!(
        "morph: t=0 vs base {d0}, t=1 vs target {d1} of {PIXELS} differ; t=0.5 vs base {h0}, vs target {h1}; \
         base {} covered, target {}",
        covered(&base_image),
        covered(&target_image)
    );
    assert_eq!((d0, d1), (0, 0));
    assert!(h0 > 1000 && h1 > 1000, "t = 0.5 looks like an endpoint");
}

/// A u16 buffer holds indices below 0xFFFF and the restart index; anything else is an
/// Input error, not a silently truncated index.
#[test]
fn u16_refuses_indices_it_cannot_hold() {
    let mut r = renderer();
    for topology in [Topology::Strip, Topology::Triangles] {
        let ok = r.upload_indices(&[0, 0xFFFE, RESTART], topology, IndexWidth::U16).expect("0xFFFE and the restart index fit");
        assert_eq!(ok.len(), 3);
        r.delete_indices(ok);
        for bad in [0xFFFF, 0x1_0000, 70_000, u32::MAX - 1] {
            match r.upload_indices(&[0, 1, bad], topology, IndexWidth::U16) {
                Err(e @ RenderError::Input(_)) => {
                    let text = e.to_string();
                    assert!(text.contains(&bad.to_string()) && text.contains("u16"), "{text}");
                    if bad == 0xFFFF && topology == Topology::Strip {
                        println!("u16 upload of {bad}: {text}");
                    }
                }
                other => panic!("index {bad} in a u16 buffer: {other:?}"),
            }
        }
        let wide = r.upload_indices(&[0, 1, 70_000], topology, IndexWidth::U32).expect("u32 holds it");
        r.delete_indices(wide);
    }
    assert_eq!(r.gl_error(), None);
}

/// Renderers made and dropped on several threads at once all work: EGL hands them one
/// shared display, which must outlive every renderer using it (dropping one renderer
/// used to terminate the display under the others: "EGL is not initialized", or a
/// segfault in Mesa; this test failed in 5 of 6 runs on llvmpipe before the fix).
#[test]
fn renderers_on_several_threads_at_once() {
    let threads: Vec<_> = (0..4)
        .map(|t| {
            std::thread::spawn(move || {
                let positions = [[-0.5f32, -0.5, 0.0], [0.5, -0.5, 0.0], [0.0, 0.5, 0.0]];
                let mut covered_each = Vec::new();
                for _ in 0..12 {
                    let mut r = stripkit_render::Renderer::new(64, 64).unwrap_or_else(|e| panic!("thread {t}: {e}"));
                    let g = r.upload(&Vertices::new(&positions)).expect("uploads");
                    let i = r.upload_indices(&[0, 1, 2], Topology::Triangles, IndexWidth::U16).expect("uploads");
                    r.clear(BACKGROUND);
                    r.draw(&g, &i, &exact(camera(&positions, [0.0, 0.0, 1.0])));
                    covered_each.push(covered(&r.read_image()));
                }
                covered_each
            })
        })
        .collect();
    let covered: Vec<usize> = threads.into_iter().flat_map(|t| t.join().expect("a renderer thread")).collect();
    let (lo, hi) = (covered.iter().min().copied().unwrap_or(0), covered.iter().max().copied().unwrap_or(0));
    println!("threads: 4 x 12 renderers at once, each picture covering {lo} to {hi} pixels");
    assert!(covered.iter().all(|&c| c > 500 && c == covered[0]), "{covered:?}");
}

//! `stripkit render` through the built binary: the pictures are decoded and their
//! pixels counted. Where the machine has no EGL at all, the tests that need a picture
//! say so and pass; the error path itself is tested everywhere.

mod support;

use std::collections::HashSet;
use std::path::Path;
use std::process::{Command, Output};
use support::{json, stripkit, tmp, write_mesh};

/// The colours `--color cull` uses (`stripkit_render::paint`).
const FRONT: [u8; 3] = [58, 110, 190];
const BACK: [u8; 3] = [246, 214, 200];
const WHITE: [u8; 3] = [255, 255, 255];
/// `--wireframe`'s lines.
const WIRE: [u8; 3] = [30, 30, 30];

/// A decoded picture.
struct Picture {
    width: u32,
    height: u32,
    pixels: Vec<[u8; 3]>,
}

impl Picture {
    fn read(path: &Path) -> Picture {
        let decoder = png::Decoder::new(std::fs::File::open(path).expect("the picture exists"));
        let mut reader = decoder.read_info().expect("a PNG");
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).expect("PNG data");
        assert_eq!(info.color_type, png::ColorType::Rgb, "opaque pictures, no alpha channel");
        assert_eq!(info.bit_depth, png::BitDepth::Eight);
        let pixels = buf[..info.buffer_size()].chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
        Picture { width: info.width, height: info.height, pixels }
    }
    /// Pixels other than the background.
    fn drawn(&self) -> impl Iterator<Item = (usize, &[u8; 3])> {
        self.pixels.iter().enumerate().filter(|(_, p)| **p != WHITE)
    }
    fn count(&self, rgb: [u8; 3]) -> usize {
        self.pixels.iter().filter(|p| **p == rgb).count()
    }
    fn colors(&self) -> HashSet<[u8; 3]> {
        self.drawn().map(|(_, p)| *p).collect()
    }
    /// Mean column of the drawn pixels.
    fn mean_x(&self) -> f64 {
        let (sum, n) = self.drawn().fold((0.0, 0usize), |(s, n), (i, _)| (s + (i % self.width as usize) as f64, n + 1));
        sum / n as f64
    }
}

/// Runs `stripkit render ARGS --json`; `None` (after saying why) where this machine
/// has no EGL, so that a test needing a picture passes there without one.
fn render(args: &[&str]) -> Option<serde_json::Value> {
    let mut all = vec!["render"];
    all.extend_from_slice(args);
    all.push("--json");
    let out = stripkit(&all);
    let err = String::from_utf8_lossy(&out.stderr);
    if !out.status.success() && err.contains("stripkit renders through EGL") {
        eprintln!("skipped: no EGL on this machine ({err})");
        return None;
    }
    Some(json(&out))
}

fn strip_count(mesh: &str, algo: &str) -> u64 {
    let out = tmp("render", &format!("count-{algo}.json"));
    let j = json(&stripkit(&["strip", mesh, "-o", out.to_str().unwrap(), "--algo", algo, "--json"]));
    j["strips"].as_u64().unwrap()
}

/// A w x h grid in the plane z = 0, as an OBJ in the test folder.
fn grid(w: u32, h: u32) -> String {
    let path = tmp("render", &format!("grid-{w}x{h}.obj"));
    write_mesh(&path, &stripkit::gen::grid(w, h));
    path.to_str().unwrap().to_string()
}

#[test]
fn every_strip_gets_its_own_colour() {
    // A flat grid seen head-on, unlit: every triangle visible, every pixel exactly
    // its strip's colour, so the picture holds one colour per strip.
    let mesh = grid(12, 8);
    for algo in ["greedy", "cache"] {
        let png = tmp("render", &format!("grid-strips-{algo}.png"));
        let p = png.to_str().unwrap();
        let Some(j) =
            render(&[&mesh, "-o", p, "--algo", algo, "--shading", "unlit", "--view", "0,0,1", "--size", "240x160"])
        else {
            return;
        };
        let strips = strip_count(&mesh, algo);
        assert_eq!(j["strips"].as_u64(), Some(strips), "render shows the strips `strip` writes");
        assert_eq!(j["triangles"], 192);
        assert_eq!(j["algo"], algo);
        let pic = Picture::read(&png);
        assert_eq!((pic.width, pic.height), (240, 160));
        // The 12 x 8 grid fills 94% of both sides of a 3:2 picture: 88% of its pixels.
        let drawn = pic.drawn().count();
        assert_eq!(j["pixels"].as_u64(), Some(drawn as u64));
        let share = drawn as f64 / (240.0 * 160.0);
        assert!((0.84..=0.92).contains(&share), "{algo}: {share:.3} of the picture drawn");
        assert_eq!(pic.colors().len() as u64, strips, "{algo}: one colour per strip");
        assert!(strips >= 2, "{algo}: {strips} strips");
    }
}

#[test]
fn zoom_magnifies_the_middle() {
    // The 12 x 8 grid fills 94% of each side; twice magnified, it covers the picture.
    let mesh = grid(12, 8);
    let png = tmp("render", "grid-zoom.png");
    let p = png.to_str().unwrap();
    let Some(j) = render(&[&mesh, "-o", p, "--zoom", "2", "--view", "0,0,1", "--size", "120x80"]) else {
        return;
    };
    assert_eq!(j["pixels"], 120 * 80);
    assert_eq!(Picture::read(&png).drawn().count(), 120 * 80);
}

#[test]
fn wireframe_draws_every_edge_once() {
    // A 4 x 4 grid: 40 sides and 16 diagonals, 2,900 pixels of length on a 200 x 200
    // picture (47 pixels per unit), a band 1 pixel wide covering one or two pixels
    // across (4,416 on llvmpipe); none without --wireframe.
    let mesh = grid(4, 4);
    let png = tmp("render", "grid-wire.png");
    let p = png.to_str().unwrap();
    let args = [mesh.as_str(), "-o", p, "--shading", "unlit", "--view", "0,0,1", "--size", "200x200"];
    let Some(j) = render(&args) else { return };
    assert!(j.get("edges").is_none());
    assert_eq!(Picture::read(&png).count(WIRE), 0);
    let j = render(&[&args[..], &["--wireframe"]].concat()).unwrap();
    assert_eq!(j["edges"], 56);
    let lines = Picture::read(&png).count(WIRE);
    assert!((2500..6000).contains(&lines), "{lines} line pixels");
}

#[test]
fn order_colours_run_along_the_strips() {
    let mesh = grid(16, 16);
    let png = tmp("render", "grid-order.png");
    let p = png.to_str().unwrap();
    let Some(j) =
        render(&[&mesh, "-o", p, "--color", "order", "--shading", "unlit", "--view", "0,0,1", "--size", "256x256"])
    else {
        return;
    };
    assert_eq!(j["triangles"], 512);
    let pic = Picture::read(&png);
    let colors = pic.colors();
    // The gradient's two ends: the first triangle of the first strip is blue, the
    // last of the last strip red; in between, almost every triangle its own shade.
    assert!(colors.contains(&[40, 60, 200]) && colors.contains(&[200, 30, 30]));
    assert!(colors.len() >= 400, "{} shades for 512 triangles", colors.len());
    // Neighbouring triangles of one strip differ by a small step: most pairs of
    // horizontally adjacent drawn pixels are equal or close.
    let close = pic
        .pixels
        .chunks_exact(256)
        .flat_map(|row| row.windows(2))
        .filter(|w| w[0] != WHITE && w[1] != WHITE)
        .filter(|w| (0..3).map(|c| (w[0][c] as i32 - w[1][c] as i32).abs()).sum::<i32>() <= 40)
        .count();
    let pairs =
        pic.pixels.chunks_exact(256).flat_map(|row| row.windows(2)).filter(|w| w[0] != WHITE && w[1] != WHITE).count();
    assert!(close as f64 >= 0.9 * pairs as f64, "{close} of {pairs} neighbouring pixels close");
}

#[test]
fn cull_colours_follow_the_eye() {
    let path = tmp("render", "sphere.obj");
    write_mesh(&path, &stripkit::gen::icosphere(3));
    let mesh = path.to_str().unwrap();
    let png = tmp("render", "sphere-cull.png");
    let p = png.to_str().unwrap();
    let common = [mesh, "-o", p, "--color", "cull", "--shading", "unlit", "--view", "0,0,1", "--size", "200x200"];
    let Some(j) = render(&common) else { return };
    let pic = Picture::read(&png);
    let drawn = pic.drawn().count();
    // Seen from its own eye, a closed convex surface shows only front faces (a few
    // silhouette pixels may go either way).
    assert!(pic.count(FRONT) as f64 >= 0.99 * drawn as f64, "{} front of {drawn}", pic.count(FRONT));
    assert!(pic.count(BACK) as f64 <= 0.01 * drawn as f64);
    // An eye at a finite distance sees less than half a sphere.
    let front = j["front"].as_u64().unwrap() as f64 / 1280.0;
    assert!((0.3..0.5).contains(&front), "{front:.3} of the triangles face the eye");
    // Judged from behind, everything visible would be culled.
    let mut behind = common.to_vec();
    behind.extend(["--cull-view", "0,0,-1"]);
    let j = render(&behind).unwrap();
    let pic = Picture::read(&png);
    assert!(pic.count(BACK) as f64 >= 0.99 * pic.drawn().count() as f64);
    // The eye behind sees its own cap, as large; the belt between the caps faces neither.
    let behind_front = j["front"].as_u64().unwrap() as f64 / 1280.0;
    assert!((behind_front - front).abs() < 0.05 && front + behind_front < 1.0, "{front} {behind_front}");
}

#[test]
fn morph_frames_line_up() {
    // The same grid moved 8 units to the right: the camera frames both, t = 0 draws
    // the left one, t = 1 the right one, t = 0.5 the middle.
    let a = stripkit::gen::grid(8, 8);
    let mut b = a.clone();
    b.positions.iter_mut().for_each(|p| p[0] += 8.0);
    let (pa, pb) = (tmp("render", "morph-a.obj"), tmp("render", "morph-b.obj"));
    write_mesh(&pa, &a);
    write_mesh(&pb, &b);
    let mut centres = Vec::new();
    for t in ["0", "0.5", "1"] {
        let png = tmp("render", &format!("morph-{t}.png"));
        let args = [pa.to_str().unwrap(), "-o", png.to_str().unwrap(), "--morph", pb.to_str().unwrap(), "--t", t];
        let Some(j) = render(&[&args[..], &["--view", "0,0,1", "--size", "320x160"]].concat()) else {
            return;
        };
        assert_eq!(j["t"].as_f64(), Some(t.parse().unwrap()));
        let pic = Picture::read(&png);
        // Each frame is a square half the picture wide.
        let share = pic.drawn().count() as f64 / (320.0 * 160.0);
        assert!((0.4..0.47).contains(&share), "t = {t}: {share:.3}");
        centres.push(pic.mean_x());
    }
    assert!((centres[0] - 84.0).abs() < 4.0, "{centres:?}");
    assert!((centres[1] - 160.0).abs() < 4.0, "{centres:?}");
    assert!((centres[2] - 236.0).abs() < 4.0, "{centres:?}");
}

/// `render ARGS` fails with exit status 2, says each of `want`, writes no picture.
fn refused(args: &[&str], want: &[&str], env: Option<(&str, &str)>) {
    let png = tmp("render", "refused.png");
    let _ = std::fs::remove_file(&png);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_stripkit"));
    cmd.arg("render").args(args);
    if !args.contains(&"-o") {
        cmd.arg("-o").arg(&png);
    }
    if let Some((k, v)) = env {
        cmd.env(k, v);
    }
    let out: Output = cmd.output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    for w in want {
        assert!(err.contains(w), "{args:?}: want `{w}` in `{err}`");
    }
    assert!(!png.exists(), "{args:?} left a picture");
    let tmps = std::fs::read_dir(png.parent().unwrap())
        .unwrap()
        .filter(|e| e.as_ref().unwrap().file_name().to_string_lossy().starts_with(".refused.png"));
    assert_eq!(tmps.count(), 0, "{args:?} left a temporary file");
}

#[test]
fn without_egl_it_says_what_to_install_and_writes_nothing() {
    let mesh = grid(4, 4);
    refused(
        &[&mesh],
        &["/nonexistent/libEGL.so.1 could not be loaded", "libEGL.so.1", "apt-get install libegl1"],
        Some(("STRIPKIT_EGL_LIBRARY", "/nonexistent/libEGL.so.1")),
    );
}

#[test]
fn bad_arguments_and_meshes_are_refused() {
    let mesh = grid(4, 4);
    let m = mesh.as_str();
    for size in ["0x10", "15x800", "4097x100", "800", "axb", "800x-1"] {
        refused(&[m, "--size", size], &["is not a picture size", "16 to 4096"], None);
    }
    refused(&[m, "--view", "1,2"], &["is not a direction"], None);
    refused(&[m, "--view", "0,0,0"], &["--view must not be 0,0,0"], None);
    refused(&[m, "--view", "0,1,0", "--up", "0,2,0"], &["parallel"], None);
    refused(&[m, "--fov", "170"], &["field of view"], None);
    refused(&[m, "--zoom", "0.5"], &["is not a zoom"], None);
    refused(&[m, "--background", "#12345"], &["is not a colour"], None);
    refused(&[m, "--t", "0.5"], &["--morph"], None);
    refused(&[m, "--cull-view", "1,0,0"], &["--cull-view applies to --color cull"], None);
    refused(&[m, "--refine"], &["--refine applies to --algo cache"], None);
    refused(&[m, "-o", tmp("render", "pic.jpg").to_str().unwrap()], &["must be a .png"], None);
    refused(&[m, "-o", "/nonexistent-folder/pic.png"], &["folder /nonexistent-folder does not exist"], None);
    let other = grid(5, 5);
    refused(&[m, "--morph", &other, "--t", "0.5"], &["--morph", "36 vertices", "has 25", "same vertices"], None);
    let empty = tmp("render", "empty.obj");
    std::fs::write(&empty, "v 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
    refused(&[empty.to_str().unwrap()], &["no faces in", "empty.obj"], None);
    refused(&[tmp("render", "missing.obj").to_str().unwrap()], &["missing.obj"], None);
}

#[test]
fn help_explains_the_options() {
    let out = stripkit(&["render", "--help"]);
    assert!(out.status.success());
    let help = String::from_utf8_lossy(&out.stdout);
    for w in [
        "--color",
        "strips",
        "order",
        "cull",
        "issue #18",
        "--view",
        "--cull-view",
        "--up",
        "--fov",
        "--zoom",
        "--size",
        "--background",
        "--shading",
        "--wireframe",
        "--morph",
        "--t",
        "--algo",
        "--max-memory",
        "--json",
        "libEGL.so.1",
    ] {
        assert!(help.contains(w), "`{w}` missing from render --help");
    }
}

#[test]
fn single_strip_draws_the_same_surface_in_one_colour() {
    // A jittered sphere: merging its loops splits edges (swaps off), so the picture
    // draws the changed mesh; it covers the same pixels as the input's strips, in one
    // colour, and a morph moves the Steiner vertices with their edges.
    let mut m = stripkit::gen::icosphere(3);
    for (i, p) in m.positions.iter_mut().enumerate() {
        p[2] += (i as f32 * 12.9898).sin() * 0.01;
    }
    let mut moved = m.clone();
    moved.positions.iter_mut().for_each(|p| p[0] += 4.0);
    let (pa, pb) = (tmp("render", "single-a.obj"), tmp("render", "single-b.obj"));
    write_mesh(&pa, &m);
    write_mesh(&pb, &moved);
    let a = pa.to_str().unwrap();
    let common = ["--shading", "unlit", "--view", "0,0,1", "--size", "200x200"];
    let (g, s) = (tmp("render", "single-greedy.png"), tmp("render", "single-one.png"));
    let Some(jg) = render(&[&[a, "-o", g.to_str().unwrap(), "--algo", "greedy"][..], &common].concat()) else {
        return;
    };
    let single = ["--algo", "single", "--weights", "cache", "--swap-angle", "off"];
    let js = render(&[&[a, "-o", s.to_str().unwrap()][..], &single, &common].concat()).unwrap();
    assert_eq!(js["strips"], 1);
    assert!(js["triangles"].as_u64().unwrap() > jg["triangles"].as_u64().unwrap(), "splits add triangles: {js}");
    let (pg, ps) = (Picture::read(&g), Picture::read(&s));
    assert_eq!(ps.colors().len(), 1);
    let (ng, ns) = (pg.drawn().count() as f64, ps.drawn().count() as f64);
    assert!((ng - ns).abs() <= 0.005 * ng, "greedy {ng} pixels, single {ns}");
    // Morphed half way: the same disc, moved right by half the offset.
    let png = tmp("render", "single-morph.png");
    let args = [a, "-o", png.to_str().unwrap(), "--morph", pb.to_str().unwrap(), "--t", "0.5"];
    render(&[&args[..], &single, &common].concat()).unwrap();
    let pm = Picture::read(&png);
    let nm = pm.drawn().count() as f64;
    assert!(nm > 0.0 && (pm.mean_x() - 100.0).abs() < 3.0, "{nm} pixels at x {}", pm.mean_x());
}

/// A `.sets` level and a `.lodseq` frame draw with their own strips: as many colours
/// as the level's strips, fewer triangles at a coarser level; the level flags are
/// refused on a mesh, `--frame` on a `.sets`.
#[test]
fn levels_of_detail_draw_their_own_strips() {
    let mesh = tmp("render", "lod-torus.obj");
    write_mesh(&mesh, &stripkit::gen::torus(32, 12, 1.0, 0.3));
    let model = tmp("render", "lod-torus.sets");
    let o = stripkit(&["lod", "build", mesh.to_str().unwrap(), "-o", model.to_str().unwrap(), "--check", "off"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let sets = stripkit::lod::Sets::read(&model).unwrap();
    let png = tmp("render", "lod-torus.png");
    let Some(full) = render(&[model.to_str().unwrap(), "-o", png.to_str().unwrap(), "--level", "0"]) else { return };
    assert_eq!(full["triangles"], 768);
    let level = sets.level_for_ratio(0.25);
    let r = render(&[model.to_str().unwrap(), "-o", png.to_str().unwrap(), "--ratio", "0.25", "--color", "strips"]).unwrap();
    assert_eq!(r["triangles"].as_u64().unwrap(), sets.triangles_at(level) as u64);
    assert_eq!(r["strips"].as_u64().unwrap() as usize, sets.strips_at(level).len());
    assert!(r["lod"].as_str().unwrap().contains(&format!("level {level}")));
    assert!(Picture::read(&png).colors().len() >= 2);
    // An animation frame, morphed between key frames.
    let dir = tmp("render", "lod-anim");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for f in 0..3 {
        let mut m = stripkit::gen::torus(24, 8, 1.0, 0.3);
        for p in m.positions.iter_mut() {
            p[2] += 0.2 * f as f32 * p[0];
        }
        write_mesh(&dir.join(format!("a-{f}.obj")), &m);
    }
    let anim = tmp("render", "lod-anim.lodseq");
    let o = stripkit(&["lod", "build-seq", dir.to_str().unwrap(), "-o", anim.to_str().unwrap(), "--samples", "300"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = render(&[anim.to_str().unwrap(), "-o", png.to_str().unwrap(), "--frame", "1.5", "--ratio", "0.5"]).unwrap();
    assert!(r["lod"].as_str().unwrap().starts_with("frame 1.5"));
    for bad in [
        vec![mesh.to_str().unwrap(), "-o", png.to_str().unwrap(), "--level", "3"],
        vec![model.to_str().unwrap(), "-o", png.to_str().unwrap(), "--frame", "1"],
        vec![anim.to_str().unwrap(), "-o", png.to_str().unwrap(), "--frame", "7"],
    ] {
        let mut args = vec!["render"];
        args.extend(bad.iter().copied());
        assert_eq!(stripkit(&args).status.code(), Some(2), "{bad:?}");
    }
}

#[test]
fn any_finite_scale_is_framed() {
    // A torus drawn at its own size, then scaled by powers of ten far beyond single
    // precision's comfortable range: every picture holds the model (1e18 and 1e-18
    // used to come out blank in some shapes, 1e25 always), and about as many pixels
    // (the scaled positions round differently); scaled by a power of two, exactly as many.
    let mut torus = stripkit::gen::torus(24, 12, 1.0, 0.3);
    for p in &mut torus.positions {
        p[0] += 0.5;
    }
    let pixels = |name: &str, scale: f32| -> Option<u64> {
        let mut mesh = torus.clone();
        for p in &mut mesh.positions {
            *p = p.map(|x| (x as f64 * scale as f64) as f32);
        }
        let obj = tmp("render", &format!("scaled-{name}.obj"));
        write_mesh(&obj, &mesh);
        let png = tmp("render", &format!("scaled-{name}.png"));
        let j = render(&[obj.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "200x150", "--wireframe"])?;
        j["pixels"].as_u64()
    };
    let Some(plain) = pixels("1", 1.0) else {
        return;
    };
    assert!(plain > 5000, "{plain}");
    assert_eq!(pixels("2p64", 2f32.powi(64)), Some(plain), "a power of two is exact");
    assert_eq!(pixels("2p-64", 2f32.powi(-64)), Some(plain), "a power of two is exact");
    for (name, scale) in [("1e18", 1e18f32), ("1e-18", 1e-18), ("1e25", 1e25), ("1e-25", 1e-25), ("1e36", 1e36)] {
        let n = pixels(name, scale).unwrap();
        assert!(n.abs_diff(plain) * 100 <= plain, "{name}: {n} pixels, {plain} at scale 1");
    }
}

#[test]
fn a_wireframe_of_many_edges_is_drawn_in_slices() {
    // 200 x 200 grid: 80,000 triangles, 120,400 edges, more than one slice of 65,536
    // edges (the slices bound the memory: 1.3 M triangles at 4096 x 4096 took 514 MB
    // for the wireframe at once, now 60 MB); every edge is drawn.
    let mesh = grid(200, 200);
    let png = tmp("render", "grid-wire-slices.png");
    let Some(j) = render(&[&mesh, "-o", png.to_str().unwrap(), "--wireframe", "--view", "0,0,1", "--size", "400x400"])
    else {
        return;
    };
    assert_eq!(j["edges"], 200 * 201 * 2 + 200 * 200);
    let pic = Picture::read(&png);
    assert!(pic.count(WIRE) > 400 * 400 / 2, "the wire covers the dense grid: {}", pic.count(WIRE));
}

//! `stripkit view`'s page in a real browser: `.ci/viewer-page.mjs` opens the pages
//! headless (Debian's chromium, WebGL on Mesa's llvmpipe: software rendering) and saves
//! the canvas's first frame, which must match `stripkit render` of the same model and
//! view (llvmpipe too) within a small tolerance, with no console error. Skips with a
//! printed reason without Chromium (`.ci/run` installs Debian's `chromium` as root),
//! node, or the npm package playwright-core.

mod support;

use std::path::{Path, PathBuf};
use std::process::Command;
use support::{chromium_missing, repo_root, stripkit, tmp};

/// An RGB picture from `stripkit render`.
fn read_png(path: &Path) -> Vec<[u8; 3]> {
    let decoder = png::Decoder::new(std::fs::File::open(path).expect("the picture exists"));
    let mut reader = decoder.read_info().expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).expect("PNG data");
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf[..info.buffer_size()].chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect()
}

/// Lit pixels of `stripkit render`'s picture `png`, and pixels where the page's
/// first frame `rgba` differs from it by more than 8 levels in a channel.
fn differing(rgba: &Path, png: &Path) -> (usize, usize) {
    let page: Vec<[u8; 3]> = std::fs::read(rgba).unwrap().chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect();
    let reference = read_png(png);
    assert_eq!(page.len(), reference.len());
    let lit = reference.iter().filter(|p| **p != [255; 3]).count();
    let far = page.iter().zip(&reference).filter(|(a, b)| (0..3).any(|k| (a[k] as i32 - b[k] as i32).abs() > 8)).count();
    (lit, far)
}

/// The most pixels in a thousand lit ones that may differ by more than 8 levels from
/// `stripkit render`'s picture, for the renderer the page `report` names: 1 on Mesa's
/// llvmpipe (render's own rasterizer; 0 differed on every page), else `software`
/// (SwiftShader, another rasterizer: edge pixels differ, 2% to 3%).
fn allowed_per_mille(report: &serde_json::Value, software: usize) -> usize {
    if report["renderer"].as_str().unwrap_or("").contains("llvmpipe") {
        1
    } else {
        software
    }
}

/// One page to compare: the input, the flags both commands take (strips, view), the
/// page's first state (its address's `#`) and `stripkit render`'s flags for it.
struct Case {
    input: PathBuf,
    name: &'static str,
    flags: &'static [&'static str],
    hash: &'static str,
    render: &'static [&'static str],
}

#[test]
fn the_page_draws_what_render_draws() {
    if let Some(why) = chromium_missing(&["playwright-core"]) {
        eprintln!("skip: {why}");
        return;
    }
    // A torus whose faces the generator writes in order; the strips are shuffled by
    // the stripifier's own choices, and `--algo cache` gives a second, different set.
    let torus = tmp("view", "torus.obj");
    let gen = stripkit(&["gen", "torus", "--major", "40", "--minor", "16", "-o", torus.to_str().unwrap()]);
    assert!(gen.status.success(), "{}", String::from_utf8_lossy(&gen.stderr));
    let spot = repo_root().join("assets/spot.obj");
    let cases = [
        Case { input: spot.clone(), name: "spot_flat", flags: &[], hash: "", render: &[] },
        Case {
            input: spot.clone(),
            name: "spot_smooth",
            flags: &["--algo", "cache"],
            hash: "color=none&shading=smooth",
            render: &["--color", "none", "--shading", "smooth"],
        },
        Case { input: torus.clone(), name: "torus_flat", flags: &["--algo", "cache", "--view", "1,2,3"], hash: "", render: &[] },
    ];
    let mut pages = Vec::new();
    for c in &cases {
        let (html, png) = (tmp("view", &format!("{}.html", c.name)), tmp("view", &format!("{}.png", c.name)));
        let mut args = vec!["view", c.input.to_str().unwrap(), "-o", html.to_str().unwrap(), "--size", "256x256", "--json"];
        args.extend(c.flags);
        let report = support::json(&stripkit(&args));
        assert!(report["page_bytes"].as_u64().unwrap() > 1000, "{report}");
        let mut args = vec!["render", c.input.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "256x256"];
        args.extend(c.flags);
        args.extend(c.render);
        let run = stripkit(&args);
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        let hash = if c.hash.is_empty() { String::new() } else { format!("#{}", c.hash) };
        pages.push((format!("{}{hash}", html.display()), tmp("view", &format!("{}.rgba", c.name)), png));
    }
    let run = Command::new("node")
        .arg(repo_root().join(".ci/viewer-page.mjs"))
        .args(pages.iter().map(|(page, rgba, _)| format!("{page}={}", rgba.display())))
        .output()
        .expect("runs node");
    let text = String::from_utf8_lossy(&run.stdout);
    eprintln!("{text}{}", String::from_utf8_lossy(&run.stderr));
    assert!(run.status.success());
    let reports: Vec<serde_json::Value> = text.lines().filter_map(|l| serde_json::from_str(l).ok()).collect();
    assert_eq!(reports.len(), cases.len(), "{text}");
    for ((c, (_, rgba, png)), r) in cases.iter().zip(&pages).zip(&reports) {
        assert_eq!(r["errors"].as_array().unwrap().len(), 0, "{}: console errors {r}", c.name);
        let page: Vec<[u8; 3]> = std::fs::read(rgba).unwrap().chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect();
        let reference = read_png(png);
        assert_eq!(page.len(), reference.len(), "{}", c.name);
        let lit = reference.iter().filter(|p| **p != [255; 3]).count();
        let far = page
            .iter()
            .zip(&reference)
            .filter(|(a, b)| (0..3).any(|k| (a[k] as i32 - b[k] as i32).abs() > 8))
            .count();
        eprintln!("{}: {lit} lit pixels, {far} differ by more than 8 levels", c.name);
        // The model fills the picture; SwiftShader differs from llvmpipe only on edge
        // pixels (spot, flat: 97 of 16,325 lit pixels).
        assert!(lit > 10_000, "{}: {lit} lit pixels", c.name);
        assert!(far * 1000 <= lit * allowed_per_mille(r, 20), "{}: {far} of {lit} lit pixels differ", c.name);
    }
}

/// Runs `.ci/viewer-page.mjs` with `options` on `pages` (page=out pairs); its JSON lines.
fn open_pages(options: &[String], pages: &[String]) -> Vec<serde_json::Value> {
    let run = Command::new("node").arg(repo_root().join(".ci/viewer-page.mjs")).args(options).args(pages).output();
    let run = run.expect("runs node");
    let text = String::from_utf8_lossy(&run.stdout);
    eprintln!("{text}{}", String::from_utf8_lossy(&run.stderr));
    assert!(run.status.success());
    let reports: Vec<serde_json::Value> = text.lines().filter_map(|l| serde_json::from_str(l).ok()).collect();
    assert_eq!(reports.len(), pages.len(), "{text}");
    for r in &reports {
        assert_eq!(r["errors"].as_array().unwrap().len(), 0, "console errors: {r}");
    }
    reports
}

#[test]
fn the_pages_sets_runtime_extracts_every_level_like_lod_extract() {
    if let Some(why) = chromium_missing(&["playwright-core"]) {
        eprintln!("skip: {why}");
        return;
    }
    // Three models: spot with its UVs (a version-2 file, endpoint placement), spot
    // re-stripped (version 3: strips empty at level 0 that begin later) and a generated
    // torus with optimal placement (version 1, a new vertex per collapse).
    let torus = tmp("view-lod", "torus.obj");
    let gen = stripkit(&["gen", "torus", "--major", "36", "--minor", "14", "-o", torus.to_str().unwrap()]);
    assert!(gen.status.success(), "{}", String::from_utf8_lossy(&gen.stderr));
    let models = [
        ("spot", repo_root().join("assets/spot.obj"), &[][..]),
        ("spot_restrip", repo_root().join("assets/spot.obj"), &["--restrip", "1.4"][..]),
        ("torus", torus, &["--placement", "optimal"][..]),
    ];
    for (name, input, flags) in models {
        let sets = tmp("view-lod", &format!("{name}.sets"));
        let mut args = vec!["lod", "build", input.to_str().unwrap(), "-o", sets.to_str().unwrap(), "--json"];
        args.extend(flags);
        let built = support::json(&stripkit(&args));
        let levels = built["levels"].as_u64().unwrap();
        assert!(levels > 100, "{built}");
        // 20 levels: both ends and 18 between, visited in a shuffled order so that the
        // cursor moves both ways by steps of every size.
        let mut chosen: Vec<u64> = (0..20).map(|i| i * levels / 19).collect();
        stripkit_testkit::XorShift64(0x5e75 + levels).shuffle(&mut chosen);
        let html = tmp("view-lod", &format!("{name}.html"));
        let png = tmp("view-lod", &format!("{name}.png"));
        let view = support::json(&stripkit(&["view", sets.to_str().unwrap(), "-o", html.to_str().unwrap(), "--size", "256x256", "--json"]));
        // The page holds the file as base64 (4/3) and the script.
        let page_bytes = view["page_bytes"].as_u64().unwrap();
        let file_bytes = std::fs::metadata(&sets).unwrap().len();
        assert!(page_bytes < 2 * file_bytes + 100_000, "{page_bytes} bytes for a {file_bytes}-byte file");
        let rgba = tmp("view-lod", &format!("{name}.rgba"));
        let list: Vec<String> = chosen.iter().map(u64::to_string).collect();
        let reports = open_pages(&[format!("--levels={}", list.join(","))], &[format!("{}={}", html.display(), rgba.display())]);
        let got: serde_json::Value =
            serde_json::from_slice(&std::fs::read(format!("{}.levels.json", rgba.display())).unwrap()).unwrap();
        for level in &chosen {
            let json = tmp("view-lod", &format!("{name}-{level}.json"));
            let l = level.to_string();
            let run = stripkit(&["lod", "extract", sets.to_str().unwrap(), "--level", &l, "-o", json.to_str().unwrap()]);
            assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
            let want: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
            assert!(!want["strips"].as_array().unwrap().is_empty());
            assert_eq!(got[&l], want["strips"], "{name} level {level}");
        }
        // The first frame (level 0) is `stripkit render`'s picture of the model.
        let run = stripkit(&["render", sets.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "256x256"]);
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        let page: Vec<[u8; 3]> = std::fs::read(&rgba).unwrap().chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect();
        let reference = read_png(&png);
        let lit = reference.iter().filter(|p| **p != [255; 3]).count();
        let far =
            page.iter().zip(&reference).filter(|(a, b)| (0..3).any(|k| (a[k] as i32 - b[k] as i32).abs() > 8)).count();
        eprintln!("{name}: {levels} levels, page {page_bytes} bytes for {file_bytes}; {far} of {lit} lit pixels differ");
        assert!(lit > 10_000 && far * 1000 <= lit * allowed_per_mille(&reports[0], 20), "{name}: {far} of {lit} lit pixels differ");
    }
}

#[test]
fn the_pages_culling_gives_the_ranges_of_stripkit_cull() {
    if let Some(why) = chromium_missing(&["playwright-core"]) {
        eprintln!("skip: {why}");
        return;
    }
    // Spot and a generated torus, each as one strip per component (`stripkit cull`'s
    // strips), the 10 eyes of `stripkit cull --views 10`.
    let torus = tmp("view-cull", "torus.obj");
    let gen = stripkit(&["gen", "torus", "--major", "30", "--minor", "12", "-o", torus.to_str().unwrap()]);
    assert!(gen.status.success(), "{}", String::from_utf8_lossy(&gen.stderr));
    for (name, input) in [("spot", repo_root().join("assets/spot.obj")), ("torus", torus)] {
        let html = tmp("view-cull", &format!("{name}.html"));
        let (i, h) = (input.to_str().unwrap(), html.to_str().unwrap());
        let run = stripkit(&["view", i, "--algo", "single", "--weights", "cull", "--cull", "-o", h, "--size", "64x64"]);
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        let cull = support::json(&stripkit(&["cull", i, "--views", "10", "--repeat", "1", "--json"]));
        let mesh = stripkit::io::read(&input).unwrap();
        let (center, radius) = stripkit::cull::bounding_sphere(&mesh.positions);
        let eyes = stripkit::cull::helix_eyes(center, radius, 10);
        let eyes: Vec<String> = eyes.iter().map(|e| format!("{},{},{}", e[0], e[1], e[2])).collect();
        let rgba = tmp("view-cull", &format!("{name}.rgba"));
        let reports = open_pages(&[format!("--eyes={}", eyes.join(";"))], &[format!("{h}={}", rgba.display())]);
        let page = reports[0]["cull"].as_array().unwrap();
        let views = cull["per_view"].as_array().unwrap();
        assert_eq!(page.len(), 10);
        assert_eq!(views.len(), 10);
        for (k, (p, v)) in page.iter().zip(views).enumerate() {
            assert_eq!(p["segments"], v["segments"], "{name} eye {k}: {p} {v}");
            assert_eq!(p["drawn"], v["drawn"], "{name} eye {k}: {p} {v}");
            assert_eq!(p["visited"], v["visited_root"], "{name} eye {k}: {p} {v}");
            assert!(p["segments"].as_u64().unwrap() > 0 && p["culled"].as_u64().unwrap() > 0, "{name} eye {k}: {p}");
        }
        eprintln!("{name}: 10 eyes, segments {:?}", page.iter().map(|p| p["segments"].as_u64().unwrap()).collect::<Vec<_>>());
    }
}

#[test]
fn the_page_is_self_contained_and_bad_arguments_exit_2() {
    let spot = repo_root().join("assets/spot.obj");
    let html = tmp("view-args", "spot.html");
    let run = stripkit(&["view", spot.to_str().unwrap(), "-o", html.to_str().unwrap()]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let page = std::fs::read_to_string(&html).unwrap();
    // Nothing fetched: no external script, style, image or address.
    for needle in ["<script src", "<link", "<img", "http://", "https://", "import("] {
        assert!(!page.contains(needle), "the page holds `{needle}`");
    }
    assert!(page.contains("TRIANGLE_STRIP") && page.contains("\"strip_indices\":\""));
    let png = tmp("view-args", "spot.png");
    let run = stripkit(&["view", spot.to_str().unwrap(), "-o", png.to_str().unwrap()]);
    assert_eq!(run.status.code(), Some(2), "a page must be .html");
    assert!(!png.exists());
    let sets = tmp("view-args", "spot.sets");
    assert!(stripkit(&["lod", "build", spot.to_str().unwrap(), "-o", sets.to_str().unwrap()]).status.success());
    let run = stripkit(&["view", sets.to_str().unwrap(), "--cull", "-o", html.to_str().unwrap()]);
    assert_eq!(run.status.code(), Some(2), "{}", String::from_utf8_lossy(&run.stderr));
}

/// A procedural animation for `stripkit lod build-seq`: a torus rippled by a wave
/// that travels around it, `frames` OBJ files in a fresh folder.
fn rippling_torus(frames: usize) -> PathBuf {
    let dir = tmp("view-seq", "ripple");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let base = stripkit::gen::torus(30, 10, 1.0, 0.35);
    for f in 0..frames {
        let mut mesh = base.clone();
        let phase = f as f32 * 0.7;
        for p in mesh.positions.iter_mut() {
            let angle = p[2].atan2(p[0]);
            let lift = 0.15 * (3.0 * angle + phase).sin();
            *p = [p[0] * (1.0 + 0.5 * lift), p[1] + lift, p[2] * (1.0 + 0.5 * lift)];
        }
        support::write_mesh(&dir.join(format!("ripple-{f:02}.obj")), &mesh);
    }
    dir
}

/// The first `count` frames of horse-gallop, copied into a fresh folder (the whole
/// animation's 48 frames would take minutes to build in a debug test run).
fn gallop_frames(count: usize) -> Option<PathBuf> {
    let src = stripkit_testkit::models_dir()?.join("sequences/horse-gallop");
    if !src.is_dir() {
        eprintln!("skipped horse-gallop: {} is absent", src.display());
        return None;
    }
    let mut files: Vec<PathBuf> = std::fs::read_dir(&src).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    let dir = tmp("view-seq", "gallop");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for f in files.iter().filter(|f| !f.to_string_lossy().contains("reference")).take(count) {
        std::fs::copy(f, dir.join(f.file_name().unwrap())).unwrap();
    }
    Some(dir)
}

#[test]
fn the_pages_lodseq_runtime_gives_lod_extracts_strips_and_the_frames_positions() {
    if let Some(why) = chromium_missing(&["playwright-core"]) {
        eprintln!("skip: {why}");
        return;
    }
    // The rippling torus with exact and with quantized (deflated) positions, and
    // horse-gallop's first frames when the research models are here.
    let ripple = rippling_torus(6);
    // The first frame is `stripkit render --frame 0`'s picture: under SwiftShader at
    // most 2% of the lit pixels differ on the torus, 3% on the horse (thin legs: more
    // edge pixels; 124 of 6,944 differed); under llvmpipe 0 of each.
    let mut cases = vec![("ripple", ripple.clone(), &[][..], 20), ("ripple_q12", ripple, &["--position-bits", "12"][..], 20)];
    if let Some(gallop) = gallop_frames(5) {
        cases.push(("gallop", gallop, &["--position-bits", "16"][..], 30));
    }
    for (name, dir, flags, software) in cases {
        let file = tmp("view-seq", &format!("{name}.lodseq"));
        let mut args = vec!["lod", "build-seq", dir.to_str().unwrap(), "-o", file.to_str().unwrap(), "--samples", "500", "--json"];
        args.extend(flags);
        support::json(&stripkit(&args));
        let seq = stripkit::lod::LodSeq::read(&file).unwrap();
        let frames = seq.frame_count();
        let levels = seq.models().iter().map(|m| m.levels()).max().unwrap() as usize;
        assert!(frames >= 5 && levels > 100, "{name}: {frames} frames, {levels} levels");
        // 3 frames x 4 levels, shuffled: the cursor moves frames and levels both ways,
        // between models when the frames use different ones.
        let mut chosen: Vec<(usize, usize)> =
            [0, frames / 2, frames - 1].iter().flat_map(|&f| [0, levels / 3, 2 * levels / 3, levels].map(|l| (f, l))).collect();
        stripkit_testkit::XorShift64(0x5e9 + levels as u64).shuffle(&mut chosen);
        let html = tmp("view-seq", &format!("{name}.html"));
        let view = support::json(&stripkit(&["view", file.to_str().unwrap(), "-o", html.to_str().unwrap(), "--size", "256x256", "--json"]));
        let page_bytes = view["page_bytes"].as_u64().unwrap();
        let file_bytes = std::fs::metadata(&file).unwrap().len();
        assert!(page_bytes < 2 * file_bytes + 100_000, "{page_bytes} bytes for a {file_bytes}-byte file");
        let rgba = tmp("view-seq", &format!("{name}.rgba"));
        let list: Vec<String> = chosen.iter().map(|(f, l)| format!("{f}:{l}")).collect();
        let options = [format!("--frames={}", list.join(",")), "--play=1500".to_string()];
        let report = &open_pages(&options, &[format!("{}={}", html.display(), rgba.display())])[0];
        assert_eq!(report["requests"].as_array().unwrap().len(), 0, "{name}: the page fetched {report}");
        // Play moved the frames on (about 30 a second; a loaded machine draws fewer).
        assert!(report["play"]["played"].as_u64().unwrap() >= 2, "{name}: {report}");
        let got: serde_json::Value =
            serde_json::from_slice(&std::fs::read(format!("{}.frames.json", rgba.display())).unwrap()).unwrap();
        for (frame, level) in &chosen {
            let key = format!("{frame}:{level}");
            let json = tmp("view-seq", &format!("{name}-{frame}-{level}.json"));
            let (f, l) = (frame.to_string(), level.to_string());
            let run = stripkit(&["lod", "extract", file.to_str().unwrap(), "--frame", &f, "--level", &l, "-o", json.to_str().unwrap()]);
            assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
            let want: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
            assert!(!want["strips"].as_array().unwrap().is_empty());
            assert_eq!(got[&key]["strips"], want["strips"], "{name} frame {frame} level {level}");
            // The positions as the library decodes them, bit for bit.
            let page: Vec<f32> = got[&key]["positions"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap() as f32).collect();
            let lib: Vec<f32> = seq.positions(*frame).iter().flatten().copied().collect();
            assert_eq!(page.len(), lib.len(), "{name} frame {frame}");
            let differ = page.iter().zip(&lib).filter(|(a, b)| a.to_bits() != b.to_bits()).count();
            assert_eq!(differ, 0, "{name} frame {frame}: {differ} coordinates differ");
        }
        let png = tmp("view-seq", &format!("{name}.png"));
        let run = stripkit(&["render", file.to_str().unwrap(), "--frame", "0", "-o", png.to_str().unwrap(), "--size", "256x256"]);
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        let (lit, far) = differing(&rgba, &png);
        eprintln!(
            "{name}: {frames} frames, {} models, {levels} levels; page {page_bytes} bytes for {file_bytes}; played {}; {far} of {lit} lit pixels differ",
            seq.models().len(),
            report["play"]["played"]
        );
        assert!(lit > 3000 && far * 1000 <= lit * allowed_per_mille(report, software), "{name}: {far} of {lit} lit pixels differ");
    }
}

#[test]
fn a_lodseq_page_opens_at_its_frame() {
    // The rippling torus: the wave has moved between frames 0 and 4, so that the
    // pictures of the two frames differ.
    let ripple = rippling_torus(6);
    let file = tmp("view-frame", "ripple.lodseq");
    let args = ["lod", "build-seq", ripple.to_str().unwrap(), "-o", file.to_str().unwrap(), "--samples", "500", "--json"];
    support::json(&stripkit(&args));
    let (f, html) = (file.to_str().unwrap(), tmp("view-frame", "ripple.html"));
    // Bad frames and --frame on a mesh are refused, nothing written.
    for (input, frame) in [(f, "6"), (f, "-1"), (repo_root().join("assets/spot.obj").to_str().unwrap(), "0")] {
        let run = stripkit(&["view", input, "--frame", frame, "-o", html.to_str().unwrap()]);
        assert_eq!(run.status.code(), Some(2), "--frame {frame}: {}", String::from_utf8_lossy(&run.stderr));
        assert!(!html.exists());
    }
    let view = support::json(&stripkit(&["view", f, "--frame", "4", "-o", html.to_str().unwrap(), "--size", "256x256", "--json"]));
    assert!(view["page_bytes"].as_u64().unwrap() > 1000, "{view}");
    if let Some(why) = chromium_missing(&["playwright-core"]) {
        eprintln!("skip: {why}");
        return;
    }
    let rgba = tmp("view-frame", "ripple.rgba");
    let report = &open_pages(&[], &[format!("{}={}", html.display(), rgba.display())])[0];
    assert_eq!(report["frame"], serde_json::json!([4, 4]), "{report}");
    let mut lit_far = Vec::new();
    for frame in ["4", "0"] {
        let png = tmp("view-frame", &format!("ripple-{frame}.png"));
        let run = stripkit(&["render", f, "--frame", frame, "-o", png.to_str().unwrap(), "--size", "256x256"]);
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        lit_far.push(differing(&rgba, &png));
    }
    let [(lit4, far4), (lit0, far0)] = [lit_far[0], lit_far[1]];
    eprintln!("frame 4: {far4} of {lit4} lit pixels differ from render --frame 4, {far0} of {lit0} from --frame 0");
    assert!(lit4 > 3000 && far4 * 1000 <= lit4 * allowed_per_mille(report, 20), "{far4} of {lit4} lit pixels differ");
    assert!(far0 * 1000 > lit0 * 50, "frame 0's picture is too close: {far0} of {lit0}");
}

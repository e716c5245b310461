//! `stripkit view`'s page in a real browser: `.ci/viewer-page.mjs` opens the pages
//! headless (Debian's chromium, SwiftShader: software rendering) and saves the
//! canvas's first frame, which must match `stripkit render` of the same model and view
//! (Mesa's llvmpipe) within a small tolerance, with no console error. Skips with a
//! printed reason without Chromium (`.ci/run` installs Debian's `chromium` as root),
//! node, or the npm package playwright-core.

mod support;

use std::path::{Path, PathBuf};
use std::process::Command;
use support::{stripkit, tmp};

/// This checkout (not the testkit's, which may have been built in another tree).
fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Why the check cannot run here, if it cannot.
fn missing() -> Option<String> {
    let chromium = std::env::var("CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into());
    if !Path::new(&chromium).is_file() {
        return Some(format!("{chromium} is absent (.ci/run installs Debian's chromium as root)"));
    }
    if !repo_root().join(".ci/node_modules/playwright-core/package.json").is_file() {
        return Some("npm package playwright-core is not installed in .ci/node_modules (.ci/run installs it)".into());
    }
    match Command::new("node").arg("--version").output() {
        Ok(o) if o.status.success() => None,
        _ => Some("node is not on PATH".into()),
    }
}

/// An RGB picture from `stripkit render`.
fn read_png(path: &Path) -> Vec<[u8; 3]> {
    let decoder = png::Decoder::new(std::fs::File::open(path).expect("the picture exists"));
    let mut reader = decoder.read_info().expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).expect("PNG data");
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf[..info.buffer_size()].chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect()
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
    if let Some(why) = missing() {
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
        // The model fills the picture; the two software rasterizers differ only on
        // edge pixels (spot, flat: 97 of 16,325 lit pixels).
        assert!(lit > 10_000, "{}: {lit} lit pixels", c.name);
        assert!(far * 100 <= lit * 2, "{}: {far} of {lit} lit pixels differ", c.name);
    }
}

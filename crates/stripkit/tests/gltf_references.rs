//! External glTF buffers: only `data:` URIs and relative paths that stay inside the
//! asset's folder (or an allowed root) after normalisation and link resolution; only
//! regular files, read up to their `byteLength`; each file read once; refusals that
//! say nothing about files outside.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use stripkit::io::{self, ReadOptions};
use stripkit::{Error, Mesh};

/// A fresh folder for one test.
fn folder(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gltf_references").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// One triangle: 36 bytes of positions, then three u8 indices.
fn triangle_bytes() -> Vec<u8> {
    let mut b: Vec<u8> = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        .iter()
        .flatten()
        .flat_map(|c| c.to_le_bytes())
        .collect();
    b.extend_from_slice(&[0, 1, 2]);
    b
}

/// A `.gltf` whose buffers are `uris` (each with `byte_length`), drawing one triangle
/// from buffer 0 (39 bytes).
fn gltf(uris: &[&str], byte_length: u64) -> String {
    let buffers: Vec<String> =
        uris.iter().map(|u| format!(r#"{{"byteLength":{byte_length},"uri":{}}}"#, serde_json_string(u))).collect();
    format!(
        r#"{{"asset":{{"version":"2.0"}},"buffers":[{}],
        "bufferViews":[{{"buffer":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":3}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}},
                     {{"bufferView":1,"componentType":5121,"count":3,"type":"SCALAR"}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}]}}"#,
        buffers.join(",")
    )
}

fn serde_json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Writes `name` with `text` into `dir` and reads it with `options`, timing it.
fn read_in(dir: &Path, name: &str, text: &str, options: &ReadOptions) -> Result<Mesh, Error> {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let start = Instant::now();
    let result = io::read_with(&path, options);
    assert!(start.elapsed() < Duration::from_secs(2), "{name}: took {:?}", start.elapsed());
    result
}

/// The message of a format error at `buffers[i].uri` naming the `.gltf`.
fn refusal(dir: &Path, name: &str, uri: &str) -> String {
    match read_in(dir, name, &gltf(&[uri], 39), &ReadOptions::default()) {
        Err(e @ Error::Format { .. }) => {
            let msg = e.to_string();
            eprintln!("{uri}: {msg}");
            assert!(msg.contains(name) && msg.contains("buffers[0].uri"), "{msg}");
            msg
        }
        other => panic!("{uri}: expected a refusal, got {other:?}"),
    }
}

fn assert_triangle(mesh: &Mesh) {
    assert_eq!((mesh.vertex_count(), mesh.face_count()), (3, 1));
    assert_eq!(mesh.positions[1], [1.0, 0.0, 0.0]);
}

/// The message with the URI itself taken out, to compare refusals of different URIs.
fn without(msg: &str, uri: &str) -> String {
    msg.replace(&format!("{uri:?}"), "URI")
}

#[test]
fn a_relative_buffer_inside_the_folder_still_reads() {
    let dir = folder("relative");
    std::fs::create_dir_all(dir.join("bin")).unwrap();
    std::fs::write(dir.join("bin/my mesh.bin"), triangle_bytes()).unwrap();
    for uri in ["bin/my%20mesh.bin", "./bin/../bin/my mesh.bin"] {
        let mesh = read_in(&dir, "ok.gltf", &gltf(&[uri], 39), &ReadOptions::default()).unwrap();
        assert_triangle(&mesh);
    }
    // A file longer than byteLength is fine; only byteLength bytes are used.
    let mut long = triangle_bytes();
    long.extend_from_slice(&[7; 1000]);
    std::fs::write(dir.join("long.bin"), long).unwrap();
    assert_triangle(&read_in(&dir, "long.gltf", &gltf(&["long.bin"], 39), &ReadOptions::default()).unwrap());
    // A link that stays inside the folder is followed.
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("bin/my mesh.bin", dir.join("alias.bin")).unwrap();
        assert_triangle(&read_in(&dir, "alias.gltf", &gltf(&["alias.bin"], 39), &ReadOptions::default()).unwrap());
    }
}

#[test]
fn a_data_uri_still_reads() {
    let dir = folder("data");
    // base64 of triangle_bytes(), made by the writer's own encoder through a round trip.
    let mesh = Mesh::from_triangles(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
    let bytes = io::write_bytes(io::Format::Gltf, &mesh, None, &io::WriteOptions::default()).unwrap();
    let back = read_in(&dir, "data.gltf", std::str::from_utf8(&bytes).unwrap(), &ReadOptions::default()).unwrap();
    assert_triangle(&back);
}

#[test]
fn absolute_uris_are_refused_alike_whether_the_file_exists_or_not() {
    let dir = folder("absolute");
    let outside = folder("absolute-outside").join("secret.bin");
    std::fs::write(&outside, triangle_bytes()).unwrap();
    let missing = outside.with_file_name("no-such-file.bin");
    let existing = outside.to_str().unwrap().to_string();
    let absent = missing.to_str().unwrap().to_string();
    let a = refusal(&dir, "abs.gltf", &existing);
    let b = refusal(&dir, "abs.gltf", &absent);
    assert!(a.contains("must be a relative path inside the asset's folder or a data: URI"), "{a}");
    assert_eq!(without(&a, &existing), without(&b, &absent));
    assert!(!without(&a, &existing).contains("bytes") && !a.contains("No such file"), "{a}");
    let c = refusal(&dir, "abs.gltf", "/etc/passwd");
    assert_eq!(without(&c, "/etc/passwd"), without(&b, &absent));
    // Percent-encoded, or with a scheme.
    for uri in ["%2Fetc%2Fpasswd", "file:///etc/passwd", "http://example.com/a.bin", "C:/x.bin"] {
        let m = refusal(&dir, "abs.gltf", uri);
        assert_eq!(without(&m, uri), without(&b, &absent), "{uri}");
    }
}

#[test]
fn dot_dot_escapes_are_refused_alike_whether_the_file_exists_or_not() {
    let base = folder("dotdot");
    let dir = base.join("asset");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(base.join("sibling.bin"), triangle_bytes()).unwrap();
    let a = refusal(&dir, "up.gltf", "../sibling.bin");
    let b = refusal(&dir, "up.gltf", "../nothing-here.bin");
    assert_eq!(without(&a, "../sibling.bin"), without(&b, "../nothing-here.bin"));
    assert!(!a.contains("bytes") && !a.contains("No such file"), "{a}");
    for uri in ["%2E%2E/sibling.bin", "..%2Fsibling.bin", "sub/../../sibling.bin", "../../../../../../../../etc/passwd"] {
        let m = refusal(&dir, "up.gltf", uri);
        assert_eq!(without(&m, uri), without(&b, "../nothing-here.bin"), "{uri}");
    }
}

#[test]
fn a_missing_file_inside_the_folder_names_the_gltf_and_the_buffer() {
    let dir = folder("missing");
    let m = refusal(&dir, "missing.gltf", "no%20such.bin");
    assert!(m.contains("no such.bin"), "{m}");
}

#[cfg(unix)]
#[test]
fn a_link_inside_the_folder_leading_outside_is_refused() {
    let base = folder("link");
    let dir = base.join("asset");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(base.join("outside.bin"), triangle_bytes()).unwrap();
    std::os::unix::fs::symlink(base.join("outside.bin"), dir.join("out.bin")).unwrap();
    std::os::unix::fs::symlink(base.join("absent.bin"), dir.join("dangling.bin")).unwrap();
    std::os::unix::fs::symlink("/etc", dir.join("etc")).unwrap();
    let a = refusal(&dir, "link.gltf", "out.bin");
    let b = refusal(&dir, "link.gltf", "dangling.bin");
    let c = refusal(&dir, "link.gltf", "etc/passwd");
    let d = refusal(&dir, "link.gltf", "etc/no-such-file");
    assert!(a.contains("must be a relative path inside the asset's folder"), "{a}");
    assert_eq!(without(&a, "out.bin"), without(&b, "dangling.bin"));
    assert_eq!(without(&c, "etc/passwd"), without(&d, "etc/no-such-file"));
    assert_eq!(without(&a, "out.bin"), without(&c, "etc/passwd"));
}

#[cfg(unix)]
#[test]
fn a_fifo_is_refused_without_hanging() {
    let dir = folder("fifo");
    let fifo = dir.join("pipe.bin");
    match std::process::Command::new("mkfifo").arg(&fifo).status() {
        Ok(s) if s.success() => {}
        other => {
            eprintln!("skipped: mkfifo unavailable ({other:?})");
            return;
        }
    }
    let m = refusal(&dir, "fifo.gltf", "pipe.bin");
    assert!(m.contains("not a regular file"), "{m}");
}

#[test]
fn a_directory_is_refused() {
    let dir = folder("directory");
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    let m = refusal(&dir, "dir.gltf", "sub");
    assert!(m.contains("not a regular file"), "{m}");
}

#[cfg(unix)]
#[test]
fn dev_zero_is_refused_quickly_even_inside_an_allowed_root() {
    let dir = folder("devzero");
    // Outside the folder: refused before the file system is asked.
    let m = refusal(&dir, "zero.gltf", "/dev/zero");
    assert!(m.contains("must be a relative path"), "{m}");
    // Inside an allowed root: refused as not a regular file, without reading.
    let up = "../".repeat(std::fs::canonicalize(&dir).unwrap().components().count());
    let uri = format!("{up}dev/zero");
    let options = ReadOptions::default().allowed_roots(vec![PathBuf::from("/dev")]);
    match read_in(&dir, "zero.gltf", &gltf(&[&uri], 1 << 20), &options) {
        Err(e) => assert!(e.to_string().contains("not a regular file"), "{e}"),
        Ok(_) => panic!("/dev/zero was read"),
    }
}

#[test]
fn a_file_shorter_than_its_byte_length_is_refused() {
    let dir = folder("short");
    std::fs::write(dir.join("short.bin"), &triangle_bytes()[..20]).unwrap();
    let m = refusal(&dir, "short.gltf", "short.bin");
    assert!(m.contains("byteLength is 39") && m.contains("holds 20 bytes"), "{m}");
}

#[test]
fn a_byte_length_beyond_the_limit_is_refused_before_reading() {
    let dir = folder("limit");
    std::fs::write(dir.join("t.bin"), triangle_bytes()).unwrap();
    let huge = gltf(&["t.bin"], 1 << 40);
    match read_in(&dir, "huge.gltf", &huge, &ReadOptions::default()) {
        Err(e) => assert!(e.to_string().contains("exceeds the limit of 1073741824 bytes"), "{e}"),
        Ok(_) => panic!("accepted"),
    }
    let small = ReadOptions::default().max_external_bytes(38);
    match read_in(&dir, "small.gltf", &gltf(&["t.bin"], 39), &small) {
        Err(e) => assert!(e.to_string().contains("exceeds the limit of 38 bytes"), "{e}"),
        Ok(_) => panic!("accepted"),
    }
    // Two distinct files together over the budget.
    std::fs::write(dir.join("u.bin"), triangle_bytes()).unwrap();
    let pair = ReadOptions::default().max_external_bytes(60);
    match read_in(&dir, "pair.gltf", &gltf(&["t.bin", "u.bin"], 39), &pair) {
        Err(e) => assert!(e.to_string().contains("78 bytes in all, more than the limit of 60"), "{e}"),
        Ok(_) => panic!("accepted"),
    }
}

#[test]
fn one_sibling_listed_many_times_is_read_once() {
    let dir = folder("repeated");
    // 8 MiB listed 1,000 times would be 8 GiB if each buffer read its own copy (and
    // over the default 1 GiB budget, which counts each file once).
    let mut big = triangle_bytes();
    big.resize(8 << 20, 0);
    std::fs::write(dir.join("big.bin"), big).unwrap();
    let uris = vec!["big.bin"; 1000];
    let mesh = read_in(&dir, "many.gltf", &gltf(&uris, 8 << 20), &ReadOptions::default()).unwrap();
    assert_triangle(&mesh);
    // The same file under different spellings is still one file.
    let uris = ["big.bin", "./big.bin", "big%2Ebin", "x/../big.bin"];
    let tight = ReadOptions::default().max_external_bytes(8 << 20);
    assert_triangle(&read_in(&dir, "spellings.gltf", &gltf(&uris, 8 << 20), &tight).unwrap());
}

#[test]
fn an_allowed_root_lets_a_relative_uri_leave_the_folder() {
    let base = folder("roots");
    let dir = base.join("asset");
    let shared = base.join("shared");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::create_dir_all(&shared).unwrap();
    std::fs::write(shared.join("t.bin"), triangle_bytes()).unwrap();
    std::fs::write(base.join("other.bin"), triangle_bytes()).unwrap();
    let text = gltf(&["../shared/t.bin"], 39);
    assert!(read_in(&dir, "shared.gltf", &text, &ReadOptions::default()).is_err());
    let options = ReadOptions::default().allowed_roots(vec![shared.clone()]);
    assert_triangle(&read_in(&dir, "shared.gltf", &text, &options).unwrap());
    // The root does not open its parent, nor absolute paths into itself.
    match read_in(&dir, "other.gltf", &gltf(&["../other.bin"], 39), &options) {
        Err(e) => assert!(e.to_string().contains("(or an allowed root)"), "{e}"),
        Ok(_) => panic!("read outside the allowed root"),
    }
    let abs = shared.join("t.bin");
    assert!(read_in(&dir, "abs.gltf", &gltf(&[abs.to_str().unwrap()], 39), &options).is_err());
}

#[test]
fn read_bytes_with_a_relative_asset_path_uses_the_current_folder() {
    // No external buffer: the folder is never resolved, so any name works.
    let mesh = Mesh::from_triangles(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
    let bytes = io::write_bytes(io::Format::Glb, &mesh, None, &io::WriteOptions::default()).unwrap();
    let back = io::read_bytes_with(Path::new("nowhere/x.glb"), io::Format::Glb, &bytes, &ReadOptions::default());
    assert_triangle(&back.unwrap());
}

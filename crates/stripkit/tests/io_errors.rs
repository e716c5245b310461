//! Bad input: every reader refuses it with an error that names the file, the place
//! (line, element or byte) and what is wrong, and never panics.

use std::path::{Path, PathBuf};
use stripkit::io::{self, Format};
use stripkit::{Error, Mesh};
use stripkit_testkit::XorShift64;

fn tmp(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("io_errors");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Writes `bytes` to a file called `name`, reads it, and returns (at, what) of the
/// format error, checking that the message names the file.
fn format_error(name: &str, bytes: &[u8]) -> (String, String) {
    let path = tmp(name);
    std::fs::write(&path, bytes).unwrap();
    match io::read(&path) {
        Err(e @ Error::Format { .. }) => {
            let msg = e.to_string();
            assert!(msg.contains(name), "the message must name the file: {msg}");
            let Error::Format { at, what, path: p } = e else { unreachable!() };
            assert_eq!(p, path);
            (at, what)
        }
        other => panic!("{name}: expected a format error, got {other:?}"),
    }
}

fn written(name: &str, mesh: &Mesh) -> Vec<u8> {
    let path = tmp(name);
    io::write(&path, mesh, None).unwrap();
    std::fs::read(path).unwrap()
}

fn quad() -> Mesh {
    Mesh::from_polygons(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]], &[vec![0, 1, 2], vec![0, 2, 3]])
}

#[test]
fn missing_file_is_an_io_error_naming_it() {
    let path = tmp("does-not-exist.obj");
    match io::read(&path) {
        Err(e @ Error::Io { .. }) => assert!(e.to_string().contains("does-not-exist.obj"), "{e}"),
        other => panic!("expected an I/O error, got {other:?}"),
    }
}

#[test]
fn unknown_extension_is_refused_with_the_supported_list() {
    let path = tmp("mesh.3ds");
    std::fs::write(&path, b"x").unwrap();
    let e = io::read(&path).unwrap_err();
    assert!(matches!(e, Error::UnknownFormat { .. }));
    let msg = e.to_string();
    assert!(msg.contains("mesh.3ds") && msg.contains(io::supported_read_extensions()), "{msg}");
    assert!(matches!(io::write(&path, &quad(), None), Err(Error::UnknownFormat { .. })));
}

#[test]
fn index_out_of_range_names_face_vertex_and_count() {
    let (at, what) = format_error("range.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 40000\n");
    assert_eq!(at, "line 5");
    assert_eq!(what, "face 1 refers to vertex 40000 but the file has 3 vertices");
    let (at, what) = format_error("range.off", b"OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 3\n");
    assert_eq!(at, "line 7");
    assert_eq!(what, "face 1 refers to vertex 3 but the file has 3 vertices");
    let mut ply = written("ok.ply", &quad());
    let n = ply.len();
    ply[n - 4..].copy_from_slice(&7i32.to_le_bytes());
    let (at, what) = format_error("range.ply", &ply);
    assert!(at.starts_with("face 1 (byte "), "{at}");
    assert_eq!(what, "face 1 refers to vertex 7 but the file has 4 vertices");
    let (at, what) = format_error(
        "range_ascii.ply",
        b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
          element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
    );
    assert_eq!(at, "face 0 (line 13)");
    assert_eq!(what, "face 0 refers to vertex -1 but the file has 3 vertices");
    let json = br#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":42,"uri":"data:;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAUA"}],
        "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}]}"#;
    let (at, what) = format_error("range.gltf", json);
    assert_eq!(at, "meshes[0].primitives[0]");
    assert!(what.contains("refers to vertex 5") && what.contains("3 vertices"), "{what}");
}

#[test]
fn nan_and_infinite_coordinates_are_refused() {
    let (at, what) = format_error("nan.obj", b"v 0 0 0\nv 1 NaN 0\n");
    assert_eq!(at, "line 2");
    assert!(what.contains("NaN or infinite"), "{what}");
    let (at, what) = format_error("inf.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 -inf 0\n3 0 1 2\n");
    assert_eq!(at, "line 5");
    assert!(what.contains("NaN or infinite"), "{what}");
    let (at, what) = format_error("huge.obj", b"v 0 0 1e39\n");
    assert_eq!(at, "line 1");
    assert!(what.contains("NaN or infinite"), "{what}");
    // Binary PLY: the y of vertex 2 becomes NaN.
    let mut ply = written("nan_src.ply", &quad());
    let body = ply.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    ply[body + 2 * 12 + 4..body + 2 * 12 + 8].copy_from_slice(&f32::NAN.to_le_bytes());
    let (at, what) = format_error("nan.ply", &ply);
    assert!(at.starts_with("vertex 2 (byte "), "{at}");
    assert!(what.contains("NaN or infinite"), "{what}");
    let mut stl = written("nan_src.stl", &quad());
    stl[84 + 50 + 12 + 8..84 + 50 + 12 + 12].copy_from_slice(&f32::INFINITY.to_le_bytes());
    let (at, what) = format_error("inf.stl", &stl);
    assert_eq!(at, "triangle 1 (byte 154)");
    assert!(what.contains("NaN or infinite"), "{what}");
    let (at, what) = format_error("nan_ascii.stl", b"solid s\nfacet normal 0 0 0\nouter loop\nvertex 0 0 nan\n");
    assert_eq!(at, "line 4");
    assert!(what.contains("NaN or infinite"), "{what}");
}

#[test]
fn faces_with_fewer_than_three_vertices_are_refused() {
    let (at, what) = format_error("two.obj", b"v 0 0 0\nv 1 0 0\nf 1 2\n");
    assert_eq!((at.as_str(), what.as_str()), ("line 3", "face has 2 vertices, needs at least 3"));
    let (at, what) = format_error("two.off", b"OFF\n2 1 0\n0 0 0\n1 0 0\n2 0 1\n");
    assert_eq!((at.as_str(), what.as_str()), ("line 5", "face 0 has 2 vertices, needs at least 3"));
    let (at, what) = format_error(
        "two.ply",
        b"ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n\
          element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n2 0 1\n",
    );
    assert_eq!(at, "face 0 (line 12)");
    assert_eq!(what, "face 0 has 2 vertices, needs at least 3");
}

#[test]
fn truncated_files_are_refused() {
    let ply = written("t_src.ply", &quad());
    let (at, what) = format_error("truncated.ply", &ply[..ply.len() - 3]);
    assert!(at.starts_with("face 1 (byte "), "{at}");
    assert!(what.contains("truncated"), "{what}");
    let stl = written("t_src.stl", &quad());
    let (at, what) = format_error("truncated.stl", &stl[..stl.len() - 10]);
    assert_eq!(at, "byte 80");
    assert!(what.contains("announces 2 triangles") && what.contains("184 bytes") && what.contains("174 bytes"), "{what}");
    let glb = written("t_src.glb", &quad());
    let (at, what) = format_error("truncated.glb", &glb[..glb.len() - 8]);
    assert_eq!(at, "byte 8");
    assert!(what.contains("truncated"), "{what}");
    let (at, what) = format_error("truncated.off", b"OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n");
    assert_eq!(at, "line 7");
    assert!(what.contains("after 1 of 2 announced faces"), "{what}");
    let (_, what) = format_error("truncated.obj.gz", &[0x1f, 0x8b, 8, 0, 0, 0, 0, 0, 0, 3, 1, 2]);
    assert!(what.contains("cannot decompress"), "{what}");
    let (at, what) = format_error("truncated.gltf", br#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":"#);
    assert!(at.starts_with("line 1 column"), "{at}");
    assert!(what.contains("malformed JSON"), "{what}");
}

#[test]
fn announced_counts_beyond_the_file_size_are_refused_before_allocating() {
    let (at, what) = format_error(
        "count.ply",
        b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
          element face 3000000000\nproperty list uchar int vertex_indices\nend_header\n\
          \0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x03\0\0\0\0\x01\0\0\0\x02\0\0\0",
    );
    assert!(at.starts_with("element 'face' (byte "), "{at}");
    assert!(what.contains("3000000000 'face' records") && what.contains("only 13 bytes are left"), "{what}");
    let mut stl = vec![0u8; 84 + 50];
    stl[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
    let (at, what) = format_error("count.stl", &stl);
    assert_eq!(at, "byte 80");
    assert!(what.contains("4294967295 triangles"), "{what}");
    let (_, what) = format_error("count.off", b"OFF\n999999999999 1 0\n0 0 0\n");
    assert!(what.contains("999999999999 vertices do not fit"), "{what}");
    let (at, what) = format_error("count2.off", b"OFF\n3000000000 1 0\n0 0 0\n");
    assert_eq!(at, "line 3");
    assert!(what.contains("vertex 1 of 3000000000"), "{what}");
    let json = br#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":12,"uri":"data:;base64,AAAAAAAAAAAAAAAA"}],
        "bufferViews":[{"buffer":0,"byteLength":12}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":4000000000,"type":"VEC3"}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}]}"#;
    let (at, what) = format_error("count.gltf", json);
    assert_eq!(at, "accessors[0]");
    assert!(what.contains("4000000000 elements") && what.contains("has 12"), "{what}");
    // A list announcing more entries than bytes remain.
    let (at, what) = format_error(
        "list.ply",
        b"ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\n\
          element tristrips 1\nproperty list int int vertex_indices\nend_header\n\xff\xff\xff\x7f\0\0\0\0",
    );
    assert!(at.starts_with("tristrips 0 (byte "), "{at}");
    assert!(what.contains("2147483647 values"), "{what}");
}

#[test]
fn malformed_numbers_are_refused() {
    let (at, what) = format_error("num.obj", b"v 0 0 0\nv 1.0.0 0 0\n");
    assert_eq!((at.as_str(), what.as_str()), ("line 2", "malformed number '1.0.0'"));
    let (at, what) = format_error("num.off", b"OFF\n1 0 0\n0 0x 0\n");
    assert_eq!((at.as_str(), what.as_str()), ("line 3", "malformed number '0x'"));
    let (at, what) = format_error(
        "num.ply",
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 zero 0\n",
    );
    assert_eq!((at.as_str(), what.as_str()), ("vertex 0 (line 8)", "malformed number 'zero'"));
    let (at, what) = format_error("num.stl", b"solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 -\n");
    assert_eq!((at.as_str(), what.as_str()), ("line 4", "malformed number '-'"));
    let (at, what) = format_error("idx.obj", b"v 0 0 0\nf 1 1.5 1\n");
    assert_eq!((at.as_str(), what.as_str()), ("line 2", "malformed vertex index '1.5'"));
}

/// Cuts and corrupts valid files of every format at many places: the readers must
/// answer Ok or Err, never panic, and never allocate wildly.
#[test]
fn corrupted_files_never_panic() {
    let mesh = Mesh::from_polygons(
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.5], [2.0, 2.0, 2.0]],
        &[vec![0, 1, 2], vec![0, 2, 3], vec![1, 4, 2, 3]],
    );
    let strips = stripkit::StripSet::from_strips(&[vec![0, 1, 2, 3], vec![4, 2, 1]]);
    let mut rng = XorShift64(0x2545_F491_4F6C_DD1D);
    let mut next = move || rng.next();
    let cases: Vec<(Format, Vec<u8>)> = vec![
        (Format::Obj, io::write_bytes(Format::Obj, &mesh, None, &Default::default()).unwrap()),
        (Format::Off, io::write_bytes(Format::Off, &mesh, None, &Default::default()).unwrap()),
        (Format::Ply, io::write_bytes(Format::Ply, &mesh, None, &Default::default()).unwrap()),
        (Format::Ply, io::write_bytes(Format::Ply, &mesh, Some(&strips), &Default::default()).unwrap()),
        (Format::Ply, io::write_bytes(Format::Ply, &mesh, None, &io::WriteOptions::default().ply_ascii(true)).unwrap()),
        (Format::Stl, io::write_bytes(Format::Stl, &mesh, None, &Default::default()).unwrap()),
        (Format::Gltf, io::write_bytes(Format::Gltf, &mesh, Some(&strips), &Default::default()).unwrap()),
        (Format::Glb, io::write_bytes(Format::Glb, &mesh, None, &Default::default()).unwrap()),
    ];
    let path = Path::new("fuzz.bin");
    for (format, good) in &cases {
        assert!(io::read_bytes(path, *format, good).is_ok(), "{format:?}");
        for cut in 0..good.len() {
            let _ = io::read_bytes(path, *format, &good[..cut]);
        }
        for _ in 0..2000 {
            let mut bad = good.clone();
            for _ in 0..1 + next() % 4 {
                let at = (next() as usize) % bad.len();
                bad[at] = match next() % 4 {
                    0 => 0xff,
                    1 => b'9',
                    2 => b'-',
                    _ => next() as u8,
                };
            }
            let _ = io::read_bytes(path, *format, &bad);
        }
    }
}

#[test]
fn gltf_primitives_reusing_accessors_cannot_inflate_the_mesh_without_bound() {
    // 36 bytes of positions, drawn non-indexed by 100,000 primitives.
    let prims: Vec<String> = (0..100_000).map(|_| r#"{"attributes":{"POSITION":0}}"#.to_string()).collect();
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":36,"uri":"data:;base64,{}"}}],
        "bufferViews":[{{"buffer":0,"byteLength":36}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}}],
        "meshes":[{{"primitives":[{}]}}]}}"#,
        "A".repeat(48),
        prims.join(",")
    );
    let (at, what) = format_error("inflate.gltf", json.as_bytes());
    assert!(at.starts_with("meshes[0].primitives["), "{at}");
    assert!(what.contains("reuse accessors"), "{what}");
}

#[test]
fn gltf_required_extensions_and_wrong_versions_are_named() {
    let (at, what) = format_error(
        "draco.gltf",
        br#"{"asset":{"version":"2.0"},"extensionsRequired":["KHR_draco_mesh_compression"],"meshes":[]}"#,
    );
    assert_eq!(at, "extensionsRequired");
    assert!(what.contains("KHR_draco_mesh_compression"), "{what}");
    let (at, what) = format_error("v1.gltf", br#"{"asset":{"version":"1.0"}}"#);
    assert_eq!(at, "asset.version");
    assert!(what.contains("'1.0'"), "{what}");
    let (at, what) = format_error("magic.glb", b"glTf\x02\0\0\0\x0c\0\0\0");
    assert_eq!(at, "byte 0");
    assert!(what.contains("'glTF'"), "{what}");
}

#[test]
fn ascii_ply_counts_beyond_the_file_size_are_refused() {
    let (at, what) = format_error(
        "count_ascii.ply",
        b"ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\nproperty float z\n\
          end_header\n0 0 0\n",
    );
    assert!(at.starts_with("element 'vertex' (line "), "{at}");
    assert!(what.contains("1000000000 'vertex' records"), "{what}");
    // A count that fits the bytes but not the data: the reader runs out and says so.
    let (at, what) = format_error(
        "short_ascii.ply",
        b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
          end_header\n0 0 0\n1 0 0 0 1\n",
    );
    assert_eq!(at, "vertex 2 (line 9)");
    assert!(what.contains("truncated"), "{what}");
}

#[test]
fn a_missing_external_gltf_buffer_is_an_error_naming_the_gltf_and_the_buffer() {
    let path = tmp("external_missing.gltf");
    std::fs::write(
        &path,
        br#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":12,"uri":"no%20such.bin"}]}"#,
    )
    .unwrap();
    match io::read(&path) {
        Err(e @ Error::Format { .. }) => {
            let msg = e.to_string();
            assert!(msg.contains("external_missing.gltf") && msg.contains("buffers[0].uri"), "{msg}");
            assert!(msg.contains("no such.bin"), "{msg}");
        }
        other => panic!("expected a format error naming the glTF and the buffer, got {other:?}"),
    }
}

//! Hostile and unlucky inputs from issue #16 (items 4, 5 and the reader messages of 9):
//! each is built here as bytes and read through the public API; each must give the
//! right mesh or an error naming the file and what is wrong, never an empty or
//! silently shortened mesh.

mod support;

use std::path::Path;
use support::encode_base64;
use stripkit::io::{self, Format};
use stripkit::{Error, Mesh};

fn read(name: &str, bytes: &[u8]) -> stripkit::Result<Mesh> {
    let format = Format::from_path(Path::new(name)).unwrap().0;
    io::read_bytes(Path::new(name), format, bytes)
}

fn counts(name: &str, bytes: &[u8]) -> (usize, usize) {
    let m = read(name, bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
    (m.vertex_count(), m.face_count())
}

/// (at, what) of the format error, checking that the message names the file.
fn refused(name: &str, bytes: &[u8]) -> (String, String) {
    match read(name, bytes) {
        Err(e @ Error::Format { .. }) => {
            assert!(e.to_string().contains(name), "the message must name the file: {e}");
            let Error::Format { at, what, .. } = e else { unreachable!() };
            (at, what)
        }
        other => panic!("{name}: expected a format error, got {other:?}"),
    }
}

const OBJ: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
const OFF: &str = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
const PLY: &str = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
    element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
const STL: &str = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\n\
    facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";

fn utf16(text: &str, big: bool) -> Vec<u8> {
    let mut out = if big { vec![0xFE, 0xFF] } else { vec![0xFF, 0xFE] };
    for u in text.encode_utf16() {
        out.extend_from_slice(&if big { u.to_be_bytes() } else { u.to_le_bytes() });
    }
    out
}

#[test]
fn cr_only_line_ends_read_like_lf() {
    for (name, text) in [("mac.obj", OBJ), ("mac.off", OFF), ("mac.ply", PLY), ("mac.stl", STL)] {
        let expected = read(name, text.as_bytes()).unwrap();
        assert_eq!((expected.vertex_count(), expected.face_count()), (4, 2), "{name}");
        for end in ["\r", "\r\n"] {
            let bytes = text.replace('\n', end);
            assert_eq!(read(name, bytes.as_bytes()).unwrap(), expected, "{name} with {end:?}");
        }
    }
    // Line numbers count lone CRs as line ends.
    let (at, what) = refused("mac.obj", b"v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 9\r");
    assert_eq!(at, "line 4");
    assert!(what.contains("vertex 9"), "{what}");
    let (at, _) = refused("mac.off", b"OFF\r3 1 0\r0 0 0\r1 0 0\r0 1 0\r3 0 1 7\r");
    assert_eq!(at, "line 6");
}

#[test]
fn utf16_text_is_refused_by_name() {
    for (name, text) in [("u16.obj", OBJ), ("u16.off", OFF), ("u16.ply", PLY), ("u16.stl", STL)] {
        for big in [false, true] {
            let (_, what) = refused(name, &utf16(text, big));
            assert!(what.contains("UTF-16") && what.contains("save it as UTF-8"), "{name}: {what}");
        }
    }
    // Without a byte order mark, an OBJ would read as nothing: it is named too.
    let bytes: Vec<u8> = OBJ.encode_utf16().flat_map(|u| u.to_le_bytes()).collect();
    let (_, what) = refused("u16-nobom.obj", &bytes);
    assert!(what.contains("UTF-16"), "{what}");
}

#[test]
fn a_utf8_byte_order_mark_is_skipped_in_every_text_format() {
    for (name, text) in [("bom.obj", OBJ), ("bom.off", OFF), ("bom.ply", PLY), ("bom.stl", STL)] {
        let mut bytes = b"\xEF\xBB\xBF".to_vec();
        bytes.extend_from_slice(text.as_bytes());
        assert_eq!(counts(name, &bytes), (4, 2), "{name}");
    }
}

#[test]
fn content_that_is_not_obj_is_refused_not_read_as_empty() {
    let (_, what) = refused("really-ply.obj", PLY.as_bytes());
    assert!(what.contains("starts with 'ply'") && what.contains("not OBJ"), "{what}");
    let mesh = read("a.ply", PLY.as_bytes()).unwrap();
    let binary_ply = io::write_bytes(Format::Ply, &mesh, None, &Default::default()).unwrap();
    let (_, what) = refused("binply.obj", &binary_ply);
    assert!(what.contains("PLY"), "{what}");
    let (_, what) = refused("off.obj", OFF.as_bytes());
    assert!(what.contains("OFF file"), "{what}");
    let garbage: Vec<u8> = (0..2000u32).map(|i| (i.wrapping_mul(2654435761) >> 13) as u8).collect();
    let (_, what) = refused("garbage.obj", &garbage);
    assert!(what.contains("binary data"), "{what}");
    let (_, what) = refused("gz.obj", &[0x1f, 0x8b, 8, 0, 0, 0, 0, 0, 0, 3]);
    assert!(what.contains("gzip"), "{what}");
    let (_, what) = refused("prose.obj", b"Dear reader,\nthis is a letter.\n");
    assert!(what.contains("no OBJ statement") && what.contains("Dear reader"), "{what}");
    // Legitimate files stay legitimate: empty, comments only, statements without
    // geometry, and unknown statements next to vertices.
    for ok in ["", "\n\n", "# nothing yet\n", "mtllib a.mtl\no empty\n", "# c\nfoo bar\nv 0 0 0\n"] {
        read("ok.obj", ok.as_bytes()).unwrap_or_else(|e| panic!("{ok:?}: {e}"));
    }
    assert_eq!(counts("ok.obj", b"weird 1 2\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), (3, 1));
}

#[test]
fn other_readers_say_what_the_content_looks_like() {
    let (_, what) = refused("ply.off", PLY.as_bytes());
    assert!(what.contains("OFF keyword") && what.contains("PLY file"), "{what}");
    let (_, what) = refused("obj.ply", OBJ.as_bytes());
    assert!(what.contains("first line must be 'ply'"), "{what}");
    let (_, what) = refused("ply.stl", PLY.as_bytes());
    assert!(what.contains("PLY file"), "{what}");
}

#[test]
fn records_beyond_the_header_counts_are_refused() {
    let extra_face = format!("{OFF}3 1 2 3\n");
    let (at, what) = refused("extra.off", extra_face.as_bytes());
    assert_eq!(at, "line 9");
    assert!(what.contains("after the 4 vertices and 2 faces") && what.contains("'3 1 2 3'"), "{what}");
    // Whitespace and comments after the records are fine.
    assert_eq!(counts("tail.off", format!("{OFF}\n# end\n  \n").as_bytes()), (4, 2));

    let (at, what) = refused("extra.ply", format!("{PLY}3 1 2 3\n").as_bytes());
    assert_eq!(at, "line 16");
    assert!(what.contains("after the last record") && what.contains("'3 1 2 3'"), "{what}");
    assert_eq!(counts("tail.ply", format!("{PLY}\n\n").as_bytes()), (4, 2));

    let mesh = read("a.ply", PLY.as_bytes()).unwrap();
    let mut binary = io::write_bytes(Format::Ply, &mesh, None, &Default::default()).unwrap();
    let len = binary.len();
    binary.extend_from_slice(&[3, 0, 0, 0, 0]);
    let (at, what) = refused("extra-bin.ply", &binary);
    assert_eq!(at, format!("byte {len}"));
    assert!(what.contains("5 bytes"), "{what}");
    binary.truncate(len);
    binary.push(b'\n');
    assert_eq!(counts("tail-bin.ply", &binary), (4, 2));
}

#[test]
fn a_ply_vertex_element_without_coordinates_is_refused() {
    let no_props = "ply\nformat ascii 1.0\nelement vertex 3\nelement face 1\n\
        property list uchar int vertex_indices\nend_header\n3 0 1 2\n";
    let (at, what) = refused("noxyz.ply", no_props.as_bytes());
    assert_eq!(at, "header");
    assert!(what.contains("no 'x' property"), "{what}");
    let no_z = PLY.replace("property float z\n", "property float w\n");
    let (_, what) = refused("noz.ply", no_z.as_bytes());
    assert!(what.contains("the vertex element has no 'z' property"), "{what}");
    // Faces pointing past the vertices are refused.
    let (_, what) = refused("past.ply", PLY.replace("3 0 2 3\n", "3 0 2 4\n").as_bytes());
    assert!(what.contains("vertex 4") && what.contains("4 vertices"), "{what}");
}

#[test]
fn homogeneous_off_coordinates_must_stay_finite_after_the_division() {
    let text = "4OFF\n3 1 0\n0 0 0 1\n1 0 0 1\n0 1 0 1e-45\n3 0 1 2\n";
    let (at, what) = refused("w.off", text.as_bytes());
    assert_eq!(at, "line 5");
    assert!(what.contains("vertex 2") && what.contains("NaN or infinite"), "{what}");
}

#[test]
fn a_ply_cut_inside_its_header_says_so() {
    let full = PLY.as_bytes();
    let end = PLY.find("end_header").unwrap() + "end_header".len();
    for cut in 4..end - 1 {
        let (_, what) = refused("cut.ply", &full[..cut]);
        assert!(what.contains("the header ends before end_header"), "cut at {cut}: {what}");
    }
    // A keyword that is wrong in a complete header is still named as such.
    let (at, what) = refused("kw.ply", PLY.replace("element face", "elemant face").as_bytes());
    assert_eq!(at, "line 7");
    assert!(what.contains("unknown header keyword 'elemant'"), "{what}");
}

#[test]
fn a_nul_byte_in_an_obj_is_shown_visibly() {
    let (at, what) = refused("nul.obj", b"v 0 0 0\nv 1 0 0\nv 0 1\x00 0\nf 1 2 3\n");
    assert_eq!(at, "line 3");
    assert!(what.contains("'1\\0'"), "{what}");
}

/// A glTF with one buffer (embedded) holding three positions and `indices`.
fn gltf(indices: &[u8], stride: Option<u64>) -> Vec<u8> {
    let mut bin = Vec::new();
    for p in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for c in p {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    bin.extend_from_slice(indices);
    let mut pos_view = serde_json::json!({"buffer": 0, "byteOffset": 0, "byteLength": 36});
    if let Some(s) = stride {
        pos_view["byteStride"] = s.into();
    }
    let doc = serde_json::json!({
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": bin.len(), "uri": format!("data:application/octet-stream;base64,{}", encode_base64(&bin))}],
        "bufferViews": [pos_view, {"buffer": 0, "byteOffset": 36, "byteLength": indices.len()}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": if stride.is_some() { 2 } else { 3 }, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5121, "count": indices.len(), "type": "SCALAR"}
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}]
    });
    serde_json::to_vec(&doc).unwrap()
}

#[test]
fn gltf_triangle_index_counts_and_strides_are_checked() {
    assert_eq!(counts("ok.gltf", &gltf(&[0, 1, 2], None)), (3, 1));
    let (at, what) = refused("tail.gltf", &gltf(&[0, 1, 2, 0, 1], None));
    assert_eq!(at, "meshes[0].primitives[0]");
    assert!(what.contains("multiple of 3") && what.contains("index accessor 1") && what.contains("has 5"), "{what}");
    let (at, what) = refused("stride.gltf", &gltf(&[0, 1, 2], Some(8)));
    assert_eq!(at, "accessors[0]");
    assert!(what.contains("byteStride 8") && what.contains("12-byte"), "{what}");
}

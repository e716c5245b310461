//! Stanford PLY: ASCII, binary little-endian and binary big-endian.
//!
//! Read: the `vertex` element's `x`, `y`, `z` (any scalar type) and every other scalar
//! vertex property as an attribute, stored with its own type: `nx ny nz` make `NORMAL`;
//! `s t`, `u v` or `texture_u texture_v` (floats) make `TEXCOORD_0` with `v` stored as
//! `1 - v` (glTF's top-left origin); `red green blue [alpha]` make `COLOR_0`
//! (normalized when integers); a set only when all its names are there with one type,
//! else each is read on its own. Any other property is a one-component attribute of
//! its own name. List properties of vertices are skipped (not kept). The `face`
//! element's `vertex_indices` / `vertex_index` list (any count and index types; other
//! face properties skipped), and the `tristrips` element (one or more int lists in
//! which `-1` ends a strip, decoded by the strip reading rule (docs/metrics.md) with degenerate triangles
//! skipped). Other elements are skipped. Before any element is read, its announced
//! count times its smallest possible record size is checked against the bytes left.
//!
//! Write: binary little-endian (default) or ASCII; `float` x y z, then every attribute
//! with its own type (`NORMAL` as `nx ny nz`, `TEXCOORD_0` as `s t` flipped back,
//! `COLOR_0` as `red green blue [alpha]`, others by name, `name_0`, `name_1`, ... when
//! they have several components), so a file read and written back keeps every scalar
//! vertex property's value bit for bit (texture `v` within one rounding of the flip);
//! faces as `list uchar int vertex_indices` (`list int int` when a face has more than
//! 255 vertices), or with strips one `tristrips` record whose int list ends every
//! strip with `-1`. Face groups are not written (PLY has no materials).

mod body;
mod fast;

use super::common::{
    capped, close_face, index_message, line_at, parse_count, push_strip_triangles, show, sniff, tokens, Lines, Src,
};
use super::obj::{push_f32, push_face_lines, push_u64};
use crate::error::{Error, Result};
use crate::mesh::{Attribute, Mesh, Scalar};
use crate::strip::StripSet;
use body::{parse_type, type_name, Ascii, Binary, Body};
use std::collections::{HashMap, HashSet};
use std::path::Path;

#[derive(Clone, Copy, Debug)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

impl Kind {
    /// The fewest bytes a binary record of this property takes.
    fn min_size(self) -> usize {
        match self {
            Kind::Scalar(s) => s.size(),
            Kind::List { count, .. } => count.size(),
        }
    }
}

#[derive(Debug)]
struct Property {
    name: String,
    kind: Kind,
}

#[derive(Debug)]
struct Element {
    name: String,
    count: u64,
    props: Vec<Property>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    Ascii,
    LittleEndian,
    BigEndian,
}

struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// Byte offset of the body.
    body: usize,
    /// Number of the header's last line (`end_header`).
    lines: usize,
}

fn parse_header(src: Src, data: &[u8]) -> Result<Header> {
    let mut lines = Lines::new(data);
    match lines.next() {
        Some((_, l)) if l.strip_suffix(b" ").unwrap_or(l) == b"ply" => {}
        _ => {
            let looks = sniff(data).map(|w| format!(" ({w})")).unwrap_or_default();
            return Err(src.err("line 1", format!("not a PLY file: the first line must be 'ply'{looks}")));
        }
    }
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut last = 1;
    let end_line;
    loop {
        let Some((ln, line)) = lines.next() else {
            return Err(src.err(
                "header",
                format!("the header ends before end_header (the file stops after line {last}; truncated?)"),
            ));
        };
        last = ln;
        let mut toks = tokens(line);
        let Some(keyword) = toks.next() else { continue };
        // A last line without a line end, other than end_header, is a header cut short
        // (its keyword may be cut too, so say that rather than "unknown keyword").
        let cut = lines.offset() == data.len() && !matches!(data.last(), Some(b'\n' | b'\r'));
        if cut && keyword != b"end_header" {
            return Err(src.err(
                line_at(ln),
                format!(
                    "the header ends before end_header: the file stops inside this line ('{}'; truncated?)",
                    show(line)
                ),
            ));
        }
        match keyword {
            b"end_header" => {
                end_line = ln;
                break;
            }
            b"comment" | b"obj_info" => {}
            b"format" => {
                let kind = toks.next().unwrap_or_default();
                encoding = Some(match kind {
                    b"ascii" => Encoding::Ascii,
                    b"binary_little_endian" => Encoding::LittleEndian,
                    b"binary_big_endian" => Encoding::BigEndian,
                    _ => return Err(src.err(line_at(ln), format!("unknown PLY format '{}'", show(kind)))),
                });
            }
            b"element" => {
                let (Some(name), Some(count)) = (toks.next(), toks.next()) else {
                    return Err(src.err(line_at(ln), "expected 'element <name> <count>'"));
                };
                let count = parse_count(count)
                    .ok_or_else(|| src.err(line_at(ln), format!("malformed element count '{}'", show(count))))?;
                elements.push(Element { name: String::from_utf8_lossy(name).into_owned(), count, props: Vec::new() });
            }
            b"property" => {
                let Some(element) = elements.last_mut() else {
                    return Err(src.err(line_at(ln), "property before any element"));
                };
                let ty = toks.next().unwrap_or_default();
                let scalar = |t: &[u8]| {
                    parse_type(t).ok_or_else(|| src.err(line_at(ln), format!("unknown property type '{}'", show(t))))
                };
                let kind = if ty == b"list" {
                    let count = scalar(toks.next().unwrap_or_default())?;
                    let item = scalar(toks.next().unwrap_or_default())?;
                    if count.is_float() {
                        return Err(src.err(line_at(ln), "a list count must have an integer type"));
                    }
                    Kind::List { count, item }
                } else {
                    Kind::Scalar(scalar(ty)?)
                };
                let name = toks.next().ok_or_else(|| src.err(line_at(ln), "property without a name"))?;
                element.props.push(Property { name: String::from_utf8_lossy(name).into_owned(), kind });
            }
            _ => return Err(src.err(line_at(ln), format!("unknown header keyword '{}'", show(keyword)))),
        }
    }
    let encoding = encoding.ok_or_else(|| src.err("header", "the header has no 'format' line"))?;
    Ok(Header { encoding, elements, body: lines.offset(), lines: end_line })
}

/// Parses a PLY file held in memory; `positions_only`: vertex properties other than
/// x, y, z skipped.
pub(crate) fn read(path: &Path, data: &[u8], positions_only: bool) -> Result<Mesh> {
    let src = Src { path };
    let header = parse_header(src, data)?;
    let body = &data[header.body..];
    match header.encoding {
        Encoding::Ascii => {
            // Line numbers continue from the header.
            let first = header.lines + 1;
            let mut r = Ascii { data: body, pos: 0, line: first, token_line: first };
            read_body(src, &header, &mut r, positions_only)
        }
        Encoding::LittleEndian | Encoding::BigEndian => {
            let mut r = Binary { data, pos: header.body, big: header.encoding == Encoding::BigEndian };
            read_body(src, &header, &mut r, positions_only)
        }
    }
}

/// Reads the body after the header: each element in the header's order, the first
/// `vertex` element into positions and attributes, `face` and `tristrips` into faces,
/// the rest skipped; then checks that the announced vertices were read and nothing
/// follows the last record.
fn read_body<B: Body>(src: Src, header: &Header, r: &mut B, positions_only: bool) -> Result<Mesh> {
    let vertex_count = header.elements.iter().find(|e| e.name == "vertex").map_or(0, |e| e.count);
    if vertex_count > u32::MAX as u64 {
        return Err(src.err("header", format!("{vertex_count} vertices do not fit 32-bit indices")));
    }
    let nv = vertex_count as usize;
    let mut mesh = Mesh::new();
    let mut vertices_read = false;
    for element in &header.elements {
        if element.name == "vertex" && !vertices_read && element.count > 0 {
            // Checked even when the element has no properties at all: its vertices
            // would be counted but never read.
            for name in ["x", "y", "z"] {
                if !element.props.iter().any(|p| p.name == name) {
                    return Err(src.err("header", format!("the vertex element has no '{name}' property")));
                }
            }
        }
        if element.props.is_empty() || element.count == 0 {
            continue; // records without properties take no bytes
        }
        let min_record = check_room(src, element, r, header.encoding != Encoding::Ascii)?;
        match element.name.as_str() {
            "vertex" if !vertices_read => {
                vertices_read = true;
                if !fast::vertices(element, r, positions_only, &mut mesh) {
                    read_vertices(src, element, r, min_record, positions_only, &mut mesh)?;
                }
            }
            "face" => {
                if !fast::faces(element, r, vertex_count, &mut mesh) {
                    read_faces(src, element, r, min_record, vertex_count, &mut mesh)?;
                }
            }
            "tristrips" => read_tristrips(src, element, r, vertex_count, &mut mesh)?,
            _ => {
                for e in 0..element.count {
                    for prop in &element.props {
                        skip_property(r, prop.kind).map_err(|w| src.err(record_at(element, r, e), w))?;
                    }
                }
            }
        }
    }
    if mesh.positions.len() != nv {
        // Faces were checked against the announced count, which must be what was read.
        return Err(src.err("header", format!("{nv} vertices announced but {} read", mesh.positions.len())));
    }
    if let Some((at, what)) = r.extra() {
        let counts: Vec<String> = header.elements.iter().map(|e| format!("{} '{}'", e.count, e.name)).collect();
        return Err(
            src.err(at, format!("data after the last record the header announces ({}): {what}", counts.join(", ")))
        );
    }
    Ok(mesh)
}

/// Where record `record` of `element` is, for errors.
fn record_at<B: Body>(element: &Element, r: &B, record: u64) -> String {
    format!("{} {record} ({})", element.name, r.at())
}

/// Checks that the bytes left can hold the records `element` announces, each at its
/// smallest size, before anything is allocated from the count; returns that size.
fn check_room<B: Body>(src: Src, element: &Element, r: &B, binary: bool) -> Result<usize> {
    let min_record: usize = element.props.iter().map(|p| p.kind.min_size()).sum();
    // An ASCII value takes at least two bytes (a digit and a separator).
    let min_record = if binary { min_record } else { 2 * element.props.len() - 1 };
    let need = (element.count as u128) * (min_record as u128);
    if need > r.remaining() as u128 + u128::from(!binary) {
        return Err(src.err(
            format!("element '{}' ({})", element.name, r.at()),
            format!(
                "the header announces {} '{}' records, at least {need} bytes, but only {} bytes are left",
                element.count,
                element.name,
                r.remaining()
            ),
        ));
    }
    Ok(min_record)
}

/// Reads the vertex element: `x`, `y`, `z` into positions, every other scalar property
/// into its attribute ([`vertex_attributes`]; none with `positions_only`), texture `v`
/// flipped to glTF's top-left origin.
fn read_vertices<B: Body>(
    src: Src,
    element: &Element,
    r: &mut B,
    min_record: usize,
    positions_only: bool,
    mesh: &mut Mesh,
) -> Result<()> {
    let slot = |n: &str| element.props.iter().position(|p| p.name == n);
    let (Some(x), Some(y), Some(z)) = (slot("x"), slot("y"), slot("z")) else {
        return Err(src.err("header", "the vertex element lacks an x, y or z property"));
    };
    if element.props.iter().any(|p| matches!(p.kind, Kind::List { .. }) && ["x", "y", "z"].contains(&p.name.as_str())) {
        return Err(src.err("header", "vertex x, y, z must be scalar properties"));
    }
    let reserve = capped(element.count, r.remaining() + 1, min_record.max(1));
    mesh.positions.reserve_exact(reserve);
    let (mut attributes, slots) = if positions_only {
        (Vec::new(), vec![None; element.props.len()])
    } else {
        vertex_attributes(&element.props, [x, y, z], reserve)
    };
    for v in 0..element.count {
        let mut p = [0.0f32; 3];
        for a in &mut attributes {
            a.data.resize(a.data.len() + a.stride(), 0);
        }
        for (k, prop) in element.props.iter().enumerate() {
            let res = match (prop.kind, slots[k]) {
                (Kind::Scalar(s), _) if k == x => r.real(s).map(|c| p[0] = c),
                (Kind::Scalar(s), _) if k == y => r.real(s).map(|c| p[1] = c),
                (Kind::Scalar(s), _) if k == z => r.real(s).map(|c| p[2] = c),
                (Kind::Scalar(s), Some((a, c))) => {
                    let at = &mut attributes[a];
                    let start = v as usize * at.stride() + c * s.size();
                    r.raw(s, &mut at.data[start..start + s.size()])
                }
                _ => skip_property(r, prop.kind),
            };
            res.map_err(|w| src.err(record_at(element, r, v), w))?;
        }
        mesh.positions.push(p);
    }
    flip_texcoord(&mut attributes);
    mesh.attributes = attributes;
    Ok(())
}

/// Texture `v` flipped to glTF's top-left origin, as read.
fn flip_texcoord(attributes: &mut [Attribute]) {
    for a in attributes {
        if a.name == "TEXCOORD_0" {
            for v in 0..a.len() {
                a.set(v, 1, 1.0 - a.get(v, 1));
            }
        }
    }
}

/// Reads the face element's `vertex_indices` (or `vertex_index`) lists as faces of at
/// least 3 vertices below `vertex_count`; other face properties are skipped.
fn read_faces<B: Body>(
    src: Src,
    element: &Element,
    r: &mut B,
    min_record: usize,
    vertex_count: u64,
    mesh: &mut Mesh,
) -> Result<()> {
    let list = element
        .props
        .iter()
        .position(|p| (p.name == "vertex_indices" || p.name == "vertex_index") && matches!(p.kind, Kind::List { .. }))
        .ok_or_else(|| src.err("header", "the face element has no 'vertex_indices' list"))?;
    let reserve = capped(element.count, r.remaining() + 1, min_record.max(1));
    mesh.face_offsets.reserve(reserve);
    mesh.face_indices.reserve(reserve.saturating_mul(3));
    for f in 0..element.count {
        for (k, prop) in element.props.iter().enumerate() {
            let err = |r: &B, what: String| src.err(record_at(element, r, f), what);
            let (Kind::List { count, item }, true) = (prop.kind, k == list) else {
                skip_property(r, prop.kind).map_err(|w| err(r, w))?;
                continue;
            };
            let n = r.int(count).map_err(|w| err(r, w))?;
            if n < 3 {
                return Err(err(r, format!("face {f} has {n} vertices, needs at least 3")));
            }
            r.check_list(n as u64, item).map_err(|w| err(r, w))?;
            for _ in 0..n {
                let i = r.int(item).map_err(|w| err(r, w))?;
                if i < 0 || i as u64 >= vertex_count {
                    return Err(err(r, index_message(f, i, vertex_count as usize)));
                }
                mesh.face_indices.push(i as u32);
            }
            close_face(mesh).map_err(|w| err(r, w))?;
        }
    }
    Ok(())
}

/// Reads the tristrips element's first list property: strips of vertex ids below
/// `vertex_count`, each ended by `-1` (or all ones in an unsigned type), decoded into
/// triangles with degenerate ones skipped; other properties are skipped.
fn read_tristrips<B: Body>(src: Src, element: &Element, r: &mut B, vertex_count: u64, mesh: &mut Mesh) -> Result<()> {
    let list = element
        .props
        .iter()
        .position(|p| matches!(p.kind, Kind::List { .. }))
        .ok_or_else(|| src.err("header", "the tristrips element has no list property"))?;
    let mut strip: Vec<u32> = Vec::new();
    for s in 0..element.count {
        for (k, prop) in element.props.iter().enumerate() {
            let err = |r: &B, what: String| src.err(record_at(element, r, s), what);
            let (Kind::List { count, item }, true) = (prop.kind, k == list) else {
                skip_property(r, prop.kind).map_err(|w| err(r, w))?;
                continue;
            };
            let n = r.int(count).map_err(|w| err(r, w))?;
            if n < 0 {
                return Err(err(r, format!("negative list length {n}")));
            }
            r.check_list(n as u64, item).map_err(|w| err(r, w))?;
            // A list of n indices draws at most n triangles, and the check above
            // proved the file holds them: the faces are sized once.
            mesh.face_indices.reserve((n as usize).saturating_mul(3));
            mesh.face_offsets.reserve(n as usize);
            strip.clear();
            for _ in 0..n {
                let i = r.int(item).map_err(|w| err(r, w))?;
                // -1 ends a strip (also as all ones in an unsigned type).
                let restart = i == -1
                    || (item == Scalar::U32 && i == u32::MAX as i64)
                    || (item == Scalar::U16 && i == u16::MAX as i64)
                    || (item == Scalar::U8 && i == u8::MAX as i64);
                if restart {
                    push_strip_triangles(mesh, &strip).map_err(|w| err(r, w))?;
                    strip.clear();
                } else if i < 0 || i as u64 >= vertex_count {
                    let what = format!("strip index {i} refers to a vertex but the file has {vertex_count} vertices");
                    return Err(err(r, what));
                } else {
                    strip.push(i as u32);
                }
            }
            push_strip_triangles(mesh, &strip).map_err(|w| err(r, w))?;
            strip.clear();
        }
    }
    Ok(())
}

/// Property names that make one glTF attribute together, tried in this order: the
/// attribute's name and its components' property names.
const KNOWN: &[(&str, &[&str])] = &[
    ("NORMAL", &["nx", "ny", "nz"]),
    ("TEXCOORD_0", &["s", "t"]),
    ("TEXCOORD_0", &["u", "v"]),
    ("TEXCOORD_0", &["texture_u", "texture_v"]),
    ("COLOR_0", &["red", "green", "blue", "alpha"]),
    ("COLOR_0", &["red", "green", "blue"]),
];

/// The attributes of the vertex element's scalar properties other than `x`, `y`, `z`
/// (`xyz` their slots), empty with room for `reserve` vertices, and for each property
/// its attribute and component. A set of [`KNOWN`] names of one type makes one
/// attribute (texture coordinates only as floats; integer colours are normalized);
/// every other scalar property is an attribute of its own name and type. List
/// properties get no slot (they are skipped).
fn vertex_attributes(
    props: &[Property],
    xyz: [usize; 3],
    reserve: usize,
) -> (Vec<Attribute>, Vec<Option<(usize, usize)>>) {
    let mut slots: Vec<Option<(usize, usize)>> = vec![None; props.len()];
    let mut attributes: Vec<Attribute> = Vec::new();
    let scalar = |k: usize| match props[k].kind {
        Kind::Scalar(s) if !xyz.contains(&k) => Some(s),
        _ => None,
    };
    let add = |attributes: &mut Vec<Attribute>, name: String, s: Scalar, comps: usize, normalized: bool| {
        let stride = comps * s.size();
        attributes.push(Attribute {
            name,
            scalar: s,
            components: comps as u8,
            normalized,
            data: Vec::with_capacity(reserve.saturating_mul(stride)),
        });
        attributes.len() - 1
    };
    // The first property of each name, looked up once per known name rather than by a
    // scan of every property (a vertex may have hundreds of thousands).
    let mut first: HashMap<&str, usize> = HashMap::with_capacity(props.len().min(1 << 16));
    for (k, p) in props.iter().enumerate().rev() {
        first.insert(p.name.as_str(), k);
    }
    for &(name, names) in KNOWN {
        if attributes.iter().any(|a| a.name == name) {
            continue;
        }
        let found: Option<Vec<usize>> = names
            .iter()
            .map(|n| first.get(n).copied().filter(|&k| scalar(k).is_some() && slots[k].is_none()))
            .collect();
        let Some(found) = found else { continue };
        let s = scalar(found[0]).unwrap_or(Scalar::F32);
        if found.iter().any(|&k| scalar(k) != Some(s)) || (name == "TEXCOORD_0" && !s.is_float()) {
            continue;
        }
        let a = add(&mut attributes, name.to_string(), s, found.len(), name == "COLOR_0" && !s.is_float());
        for (c, &k) in found.iter().enumerate() {
            slots[k] = Some((a, c));
        }
    }
    // The names taken so far, in a set: a search of the attribute list per property
    // made a vertex with many properties quadratic (50k properties: 3.3 s).
    let known: Vec<String> = attributes.iter().map(|a| a.name.clone()).collect();
    let mut taken: HashSet<&str> = known.iter().map(String::as_str).collect();
    for k in 0..props.len() {
        if let (Some(s), None) = (scalar(k), slots[k]) {
            if !taken.insert(props[k].name.as_str()) {
                continue; // a repeated name: the first is kept
            }
            let a = add(&mut attributes, props[k].name.clone(), s, 1, false);
            slots[k] = Some((a, 0));
        }
    }
    (attributes, slots)
}

/// The PLY property names of an attribute's components (the inverse of [`KNOWN`] and
/// [`vertex_attributes`]): `nx ny nz`, `s t`, `red green blue [alpha]`, the name itself
/// for one component, else `name_0`, `name_1`, ...; spaces become `_`.
fn property_names(a: &Attribute) -> Vec<String> {
    let n = a.components as usize;
    let known: Option<&[&str]> = match (a.name.as_str(), n) {
        ("NORMAL", 3) => Some(&["nx", "ny", "nz"]),
        ("TEXCOORD_0", 2) if a.scalar.is_float() => Some(&["s", "t"]),
        ("COLOR_0", 3 | 4) => Some(&["red", "green", "blue", "alpha"][..n]),
        _ => None,
    };
    if let Some(names) = known {
        return names.iter().map(|s| s.to_string()).collect();
    }
    let base: String = a.name.chars().map(|c| if c.is_whitespace() { '_' } else { c }).collect();
    let base = if base.is_empty() { "attribute".to_string() } else { base };
    if n == 1 {
        vec![base]
    } else {
        (0..n).map(|c| format!("{base}_{c}")).collect()
    }
}

/// The attributes as written: `TEXCOORD_0` flipped back to a bottom-left origin.
fn attributes_to_write(mesh: &Mesh) -> Vec<Attribute> {
    mesh.attributes
        .iter()
        .map(|a| {
            let mut a = a.clone();
            if a.name == "TEXCOORD_0" && a.components == 2 && a.scalar.is_float() {
                for v in 0..a.len() {
                    a.set(v, 1, 1.0 - a.get(v, 1));
                }
            }
            a
        })
        .collect()
}

/// Appends one attribute value as ASCII PLY text (floats in their shortest exact form).
fn push_value(out: &mut Vec<u8>, a: &Attribute, v: usize, c: usize) {
    use std::io::Write;
    let x = a.get(v, c);
    match a.scalar {
        Scalar::F32 => push_f32(out, x as f32),
        Scalar::F64 => {
            let _ = write!(out, "{x:?}");
        }
        _ => {
            let _ = write!(out, "{}", x as i64);
        }
    }
}

fn skip_property<B: Body>(r: &mut B, kind: Kind) -> Result<(), String> {
    match kind {
        Kind::Scalar(s) => r.skip(s),
        Kind::List { count, item } => {
            let n = r.int(count)?;
            if n < 0 {
                return Err(format!("negative list length {n}"));
            }
            r.check_list(n as u64, item)?;
            for _ in 0..n {
                r.skip(item)?;
            }
            Ok(())
        }
    }
}

/// Encodes a mesh (or its strips) as PLY.
pub(crate) fn write(mesh: &Mesh, strips: Option<&StripSet>, ascii: bool) -> Result<Vec<u8>> {
    let nv = mesh.positions.len();
    let format = if ascii { "ascii" } else { "binary_little_endian" };
    let mut header = format!(
        "ply\nformat {format} 1.0\ncomment written by stripkit\nelement vertex {nv}\n\
         property float x\nproperty float y\nproperty float z\n"
    );
    let attributes = attributes_to_write(mesh);
    for a in &attributes {
        for name in property_names(a) {
            header.push_str(&format!("property {} {name}\n", type_name(a.scalar)));
        }
    }
    // The strips' one list is written straight from the set (no copy of it): each
    // non-empty strip's indices, then -1.
    let strip_list: Option<(&StripSet, usize)> = match strips {
        Some(set) => {
            let total = set.indices.len() + set.iter().filter(|s| !s.is_empty()).count();
            if total > i32::MAX as usize {
                return Err(Error::Invalid(format!("{total} strip indices do not fit a PLY int list")));
            }
            header.push_str("element tristrips 1\nproperty list int int vertex_indices\n");
            Some((set, total))
        }
        None => None,
    };
    let wide = mesh.faces().any(|f| f.len() > 255);
    if strip_list.is_none() {
        let count = if wide { "int" } else { "uchar" };
        header.push_str(&format!("element face {}\nproperty list {count} int vertex_indices\n", mesh.face_count()));
    }
    header.push_str("end_header\n");
    // Binary: the exact size, so the buffer is sized once; ASCII: an estimate.
    let attribute_bytes: usize = attributes.iter().map(|a| a.data.len()).sum();
    let capacity = match (ascii, &strip_list) {
        (true, _) => 256 + nv * 12 + mesh.face_indices.len() * 5 + mesh.face_count(),
        (false, Some((_, total))) => 4 + 4 * total,
        (false, None) => mesh.face_indices.len() * 4 + mesh.face_count() * if wide { 4 } else { 1 },
    };
    let mut out = Vec::with_capacity(header.len() + nv * 12 + attribute_bytes + capacity);
    out.extend_from_slice(header.as_bytes());
    if ascii {
        for (v, p) in mesh.positions.iter().enumerate() {
            for (k, &c) in p.iter().enumerate() {
                if k > 0 {
                    out.push(b' ');
                }
                push_f32(&mut out, c);
            }
            for a in &attributes {
                for c in 0..a.components as usize {
                    out.push(b' ');
                    push_value(&mut out, a, v, c);
                }
            }
            out.push(b'\n');
        }
        match &strip_list {
            Some((set, total)) => {
                push_u64(&mut out, *total as u64);
                for i in strip_values(set) {
                    out.push(b' ');
                    if i < 0 {
                        out.extend_from_slice(b"-1");
                    } else {
                        push_u64(&mut out, i as u64);
                    }
                }
                out.push(b'\n');
            }
            None => push_face_lines(&mut out, mesh),
        }
    } else {
        for (v, p) in mesh.positions.iter().enumerate() {
            for &c in p {
                out.extend_from_slice(&c.to_le_bytes());
            }
            for a in &attributes {
                out.extend_from_slice(a.bytes(v));
            }
        }
        match &strip_list {
            Some((set, total)) => {
                out.extend_from_slice(&(*total as i32).to_le_bytes());
                for i in strip_values(set) {
                    out.extend_from_slice(&i.to_le_bytes());
                }
            }
            None => {
                for f in mesh.faces() {
                    if wide {
                        out.extend_from_slice(&(f.len() as i32).to_le_bytes());
                    } else {
                        out.push(f.len() as u8);
                    }
                    for &i in f {
                        out.extend_from_slice(&(i as i32).to_le_bytes());
                    }
                }
            }
        }
    }
    Ok(out)
}

/// The values of PLY's strip list: each non-empty strip's indices, then -1.
fn strip_values(set: &StripSet) -> impl Iterator<Item = i32> + '_ {
    set.iter().filter(|s| !s.is_empty()).flat_map(|s| s.iter().map(|&i| i as i32).chain(std::iter::once(-1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(bytes: &[u8]) -> Result<Mesh> {
        read(Path::new("t.ply"), bytes, false)
    }

    fn format_error(bytes: &[u8]) -> (String, String) {
        match parse(bytes) {
            Err(Error::Format { at, what, .. }) => (at, what),
            other => panic!("expected a format error, got {other:?}"),
        }
    }

    const ASCII: &str = "ply\nformat ascii 1.0\ncomment c\nelement vertex 4\nproperty float x\nproperty float y\n\
        property float z\nproperty float confidence\nproperty list uchar int extra\nelement face 2\n\
        property uchar flags\nproperty list uchar int vertex_indices\nproperty float quality\n\
        element material 1\nproperty list int float values\nend_header\n\
        0 0 0 0.5 2 7 7\n1 0 0 0.5 0\n1 1 0 0.5 1 9\n0 1 0 0.5 0\n\
        1 3 0 1 2 0.5\n1 4 0 1 2 3 0.5\n3 1 2 3\n";

    #[test]
    fn ascii_skips_extra_properties_and_elements() {
        let m = parse(ASCII.as_bytes()).unwrap();
        assert_eq!(m.positions, vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]);
        assert_eq!(m.face(0), &[0, 1, 2]);
        assert_eq!(m.face(1), &[0, 1, 2, 3]);
    }

    #[test]
    fn strips_decode_with_alternating_winding_and_skip_degenerates() {
        let text = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n\
            element tristrips 2\nproperty list int int vertex_indices\nend_header\n\
            0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 2 0\n\
            8 0 1 2 3 -1 3 3 4\n4 2 3 4 -1\n";
        let m = parse(text.as_bytes()).unwrap();
        let faces: Vec<&[u32]> = m.faces().collect();
        // strip 0 1 2 3: (0,1,2) (2,1,3); strip 3 3 4: only degenerates; strip 2 3 4: (2,3,4)
        assert_eq!(faces, vec![&[0, 1, 2][..], &[2, 1, 3], &[2, 3, 4]]);
    }

    #[test]
    fn written_files_read_back_in_both_encodings() {
        let mesh = Mesh::from_polygons(
            vec![[0.1, -2.5, 3.0], [1e-7, 1e30, -0.0], [0.25, 7.0, 12345.678], [4.0, 5.0, 6.0]],
            &[vec![0, 1, 2, 3], vec![2, 1, 0]],
        );
        for ascii in [false, true] {
            let bytes = write(&mesh, None, ascii).unwrap();
            assert_eq!(parse(&bytes).unwrap(), mesh, "ascii={ascii}");
        }
    }

    #[test]
    fn binary_files_are_sized_once() {
        let mut mesh = Mesh::from_polygons(vec![[0.5; 3]; 5], &[vec![0, 1, 2, 3], vec![2, 1, 4]]);
        mesh.attributes.push(Attribute::from_f32("w", 2, &[1.0; 10]));
        let strips = StripSet::from_strips(&[vec![0, 1, 2, 3], vec![], vec![2, 4, 1]]);
        for with in [None, Some(&strips)] {
            let bytes = write(&mesh, with, false).unwrap();
            assert_eq!(bytes.capacity(), bytes.len(), "strips: {}", with.is_some());
        }
        // The strip list skips the empty strip: 4 + 1 + 3 + 1 values.
        let back = parse(&write(&mesh, Some(&strips), false).unwrap()).unwrap();
        assert_eq!(back.faces().collect::<Vec<_>>(), vec![&[0, 1, 2][..], &[2, 1, 3], &[2, 4, 1]]);
    }

    #[test]
    fn header_counts_beyond_the_file_size_are_refused_before_allocating() {
        let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n\
            property float y\nproperty float z\nend_header\n"
            .to_vec();
        bytes.extend_from_slice(&[0u8; 24]);
        let (at, what) = format_error(&bytes);
        assert!(at.contains("vertex"), "{at}");
        assert!(what.contains("4000000000") && what.contains("24 bytes"), "{what}");
    }

    #[test]
    fn header_errors_name_the_line() {
        let (at, what) = format_error(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n");
        assert_eq!(at, "line 4");
        assert!(what.contains("'quad'"), "{what}");
        let (_, what) = format_error(b"obj\n");
        assert!(what.contains("first line"), "{what}");
        let (_, what) = format_error(b"ply\nformat ascii 1.0\nelement vertex 1\n");
        assert!(what.contains("end_header"), "{what}");
    }
}

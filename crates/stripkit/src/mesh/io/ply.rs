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

use super::common::{
    capped, close_face, ends_line, index_message, is_space, line_at, line_end, parse_count, parse_f32, parse_i64,
    push_strip_triangles, show, sniff, tokens, Lines, Src,
};
use super::obj::{push_f32, push_face_lines, push_u64};
use crate::error::{Error, Result};
use crate::mesh::{Attribute, Mesh, Scalar};
use crate::strip::StripSet;
use std::path::Path;

/// The attribute type of a PLY type name (`uchar`, `float32`, ...).
fn parse_type(name: &[u8]) -> Option<Scalar> {
    Some(match name {
        b"char" | b"int8" => Scalar::I8,
        b"uchar" | b"uint8" => Scalar::U8,
        b"short" | b"int16" => Scalar::I16,
        b"ushort" | b"uint16" => Scalar::U16,
        b"int" | b"int32" => Scalar::I32,
        b"uint" | b"uint32" => Scalar::U32,
        b"float" | b"float32" => Scalar::F32,
        b"double" | b"float64" => Scalar::F64,
        _ => return None,
    })
}

/// The PLY name of an attribute type.
fn type_name(s: Scalar) -> &'static str {
    match s {
        Scalar::I8 => "char",
        Scalar::U8 => "uchar",
        Scalar::I16 => "short",
        Scalar::U16 => "ushort",
        Scalar::I32 => "int",
        Scalar::U32 => "uint",
        Scalar::F32 => "float",
        Scalar::F64 => "double",
    }
}

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

/// The body of a PLY file, read value by value.
trait Body {
    /// Reads a value as a coordinate.
    fn real(&mut self, s: Scalar) -> Result<f32, String>;
    /// Reads an integer value (a list count or an index).
    fn int(&mut self, s: Scalar) -> Result<i64, String>;
    /// Skips a value.
    fn skip(&mut self, s: Scalar) -> Result<(), String>;
    /// Reads a value as it is, into `out` (`s.size()` bytes, little-endian).
    fn raw(&mut self, s: Scalar, out: &mut [u8]) -> Result<(), String>;
    /// Where the reader is, for messages: "line N" or "byte N".
    fn at(&self) -> String;
    /// Bytes not yet read.
    fn remaining(&self) -> usize;
    /// Checks that `count` values of type `s` can still follow.
    fn check_list(&self, count: u64, s: Scalar) -> Result<(), String>;
    /// After the last record: where and what the first extra data is, if anything but
    /// whitespace follows.
    fn extra(&mut self) -> Option<(String, String)>;
}

struct Ascii<'a> {
    data: &'a [u8],
    pos: usize,
    line: usize,
    /// Line of the last token read.
    token_line: usize,
}

impl<'a> Ascii<'a> {
    fn token(&mut self) -> Result<&'a [u8], String> {
        let d = self.data;
        while self.pos < d.len() && (is_space(d[self.pos]) || d[self.pos] == b'\n') {
            self.line += ends_line(d, self.pos) as usize;
            self.pos += 1;
        }
        let start = self.pos;
        while self.pos < d.len() && !is_space(d[self.pos]) && d[self.pos] != b'\n' {
            self.pos += 1;
        }
        if start == self.pos {
            // Reported at the line of the last value read.
            return Err("the file ends early (truncated)".into());
        }
        self.token_line = self.line;
        Ok(&d[start..self.pos])
    }
}

impl Body for Ascii<'_> {
    fn real(&mut self, _s: Scalar) -> Result<f32, String> {
        let tok = self.token()?;
        let v = parse_f32(tok).ok_or_else(|| format!("malformed number '{}'", show(tok)))?;
        if !v.is_finite() {
            return Err(format!("coordinate '{}' is NaN or infinite", show(tok)));
        }
        Ok(v)
    }
    fn int(&mut self, s: Scalar) -> Result<i64, String> {
        let tok = self.token()?;
        match parse_i64(tok) {
            Some(v) => Ok(v),
            None if s.is_float() => match super::common::parse_f64(tok) {
                Some(v) if v.fract() == 0.0 && v.abs() < 1e15 => Ok(v as i64),
                _ => Err(format!("'{}' is not an integer", show(tok))),
            },
            None => Err(format!("malformed integer '{}'", show(tok))),
        }
    }
    fn skip(&mut self, _s: Scalar) -> Result<(), String> {
        self.token().map(|_| ())
    }
    fn raw(&mut self, s: Scalar, out: &mut [u8]) -> Result<(), String> {
        let tok = self.token()?;
        let bad = || format!("'{}' is not a {} value", show(tok), type_name(s));
        match s {
            Scalar::F32 => out.copy_from_slice(&parse_f32(tok).ok_or_else(bad)?.to_le_bytes()),
            Scalar::F64 => out.copy_from_slice(&super::common::parse_f64(tok).ok_or_else(bad)?.to_le_bytes()),
            _ => {
                let v = parse_i64(tok).ok_or_else(bad)?;
                let (lo, hi) = match s {
                    Scalar::I8 => (i8::MIN as i64, i8::MAX as i64),
                    Scalar::U8 => (0, u8::MAX as i64),
                    Scalar::I16 => (i16::MIN as i64, i16::MAX as i64),
                    Scalar::U16 => (0, u16::MAX as i64),
                    Scalar::I32 => (i32::MIN as i64, i32::MAX as i64),
                    _ => (0, u32::MAX as i64),
                };
                if v < lo || v > hi {
                    return Err(format!("{v} is out of range for a {} property", type_name(s)));
                }
                out.copy_from_slice(&v.to_le_bytes()[..s.size()]);
            }
        }
        Ok(())
    }
    fn at(&self) -> String {
        line_at(self.token_line)
    }
    fn remaining(&self) -> usize {
        self.data.len() - self.pos
    }
    fn check_list(&self, count: u64, _s: Scalar) -> Result<(), String> {
        // Every value takes at least one digit and one separator (the last may end the file).
        if count.saturating_mul(2) > self.remaining() as u64 + 1 {
            return Err(format!("a list of {count} values cannot fit in the {} bytes left", self.remaining()));
        }
        Ok(())
    }
    fn extra(&mut self) -> Option<(String, String)> {
        let tok = self.token().ok()?;
        let start = tok.as_ptr() as usize - self.data.as_ptr() as usize;
        let rest = &self.data[start..];
        let line = &rest[..line_end(rest).map_or(rest.len(), |(i, _)| i)];
        Some((line_at(self.token_line), format!("'{}'", show(line))))
    }
}

struct Binary<'a> {
    data: &'a [u8],
    pos: usize,
    big: bool,
}

impl<'a> Binary<'a> {
    #[inline]
    fn bytes<const N: usize>(&mut self) -> Result<[u8; N], String> {
        let end = self.pos + N;
        let b: [u8; N] = self
            .data
            .get(self.pos..end)
            .and_then(|s| s.try_into().ok())
            .ok_or_else(|| format!("the file ends early (truncated at byte {})", self.data.len()))?;
        self.pos = end;
        Ok(b)
    }

    #[inline]
    fn value(&mut self, s: Scalar) -> Result<f64, String> {
        macro_rules! num {
            ($t:ty, $n:literal) => {{
                let b = self.bytes::<$n>()?;
                (if self.big { <$t>::from_be_bytes(b) } else { <$t>::from_le_bytes(b) }) as f64
            }};
        }
        Ok(match s {
            Scalar::I8 => num!(i8, 1),
            Scalar::U8 => num!(u8, 1),
            Scalar::I16 => num!(i16, 2),
            Scalar::U16 => num!(u16, 2),
            Scalar::I32 => num!(i32, 4),
            Scalar::U32 => num!(u32, 4),
            Scalar::F32 => num!(f32, 4),
            Scalar::F64 => num!(f64, 8),
        })
    }
}

impl Body for Binary<'_> {
    #[inline]
    fn real(&mut self, s: Scalar) -> Result<f32, String> {
        let v = if s == Scalar::F32 {
            let b = self.bytes::<4>()?;
            if self.big {
                f32::from_be_bytes(b)
            } else {
                f32::from_le_bytes(b)
            }
        } else {
            self.value(s)? as f32
        };
        if !v.is_finite() {
            return Err(format!("coordinate {v} is NaN or infinite"));
        }
        Ok(v)
    }
    #[inline]
    fn int(&mut self, s: Scalar) -> Result<i64, String> {
        macro_rules! int {
            ($t:ty, $n:literal) => {{
                let b = self.bytes::<$n>()?;
                Ok((if self.big { <$t>::from_be_bytes(b) } else { <$t>::from_le_bytes(b) }) as i64)
            }};
        }
        match s {
            Scalar::I8 => int!(i8, 1),
            Scalar::U8 => int!(u8, 1),
            Scalar::I16 => int!(i16, 2),
            Scalar::U16 => int!(u16, 2),
            Scalar::I32 => int!(i32, 4),
            Scalar::U32 => int!(u32, 4),
            Scalar::F32 | Scalar::F64 => {
                let v = self.value(s)?;
                if v.fract() != 0.0 || v.abs() >= 1e15 {
                    return Err(format!("{v} is not an integer"));
                }
                Ok(v as i64)
            }
        }
    }
    #[inline]
    fn skip(&mut self, s: Scalar) -> Result<(), String> {
        let end = self.pos + s.size();
        if end > self.data.len() {
            return Err(format!("the file ends early (truncated at byte {})", self.data.len()));
        }
        self.pos = end;
        Ok(())
    }
    fn raw(&mut self, s: Scalar, out: &mut [u8]) -> Result<(), String> {
        let n = s.size();
        let b = self
            .data
            .get(self.pos..self.pos + n)
            .ok_or_else(|| format!("the file ends early (truncated at byte {})", self.data.len()))?;
        out.copy_from_slice(b);
        if self.big {
            out.reverse();
        }
        self.pos += n;
        Ok(())
    }
    fn at(&self) -> String {
        format!("byte {}", self.pos)
    }
    fn remaining(&self) -> usize {
        self.data.len() - self.pos
    }
    fn check_list(&self, count: u64, s: Scalar) -> Result<(), String> {
        let need = count.saturating_mul(s.size() as u64);
        if need > self.remaining() as u64 {
            return Err(format!(
                "a list of {count} values needs {need} bytes but only {} are left (truncated)",
                self.remaining()
            ));
        }
        Ok(())
    }
    fn extra(&mut self) -> Option<(String, String)> {
        // A trailing line end (some writers add one) is tolerated.
        let rest = &self.data[self.pos..];
        if rest.iter().all(|&b| is_space(b) || b == b'\n') {
            return None;
        }
        Some((format!("byte {}", self.pos), format!("{} bytes", rest.len())))
    }
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

fn read_body<B: Body>(src: Src, header: &Header, r: &mut B, positions_only: bool) -> Result<Mesh> {
    let binary = header.encoding != Encoding::Ascii;
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
        let at = |r: &B, record: u64| format!("{} {record} ({})", element.name, r.at());
        match element.name.as_str() {
            "vertex" if !vertices_read => {
                vertices_read = true;
                let slot = |n: &str| element.props.iter().position(|p| p.name == n);
                let (Some(x), Some(y), Some(z)) = (slot("x"), slot("y"), slot("z")) else {
                    return Err(src.err("header", "the vertex element lacks an x, y or z property"));
                };
                if element
                    .props
                    .iter()
                    .any(|p| matches!(p.kind, Kind::List { .. }) && ["x", "y", "z"].contains(&p.name.as_str()))
                {
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
                        res.map_err(|w| src.err(at(r, v), w))?;
                    }
                    mesh.positions.push(p);
                }
                for a in &mut attributes {
                    if a.name == "TEXCOORD_0" {
                        for v in 0..a.len() {
                            a.set(v, 1, 1.0 - a.get(v, 1));
                        }
                    }
                }
                mesh.attributes = attributes;
            }
            "face" => {
                let list = element
                    .props
                    .iter()
                    .position(|p| {
                        (p.name == "vertex_indices" || p.name == "vertex_index") && matches!(p.kind, Kind::List { .. })
                    })
                    .ok_or_else(|| src.err("header", "the face element has no 'vertex_indices' list"))?;
                let reserve = capped(element.count, r.remaining() + 1, min_record.max(1));
                mesh.face_offsets.reserve(reserve);
                mesh.face_indices.reserve(reserve.saturating_mul(3));
                for f in 0..element.count {
                    for (k, prop) in element.props.iter().enumerate() {
                        match prop.kind {
                            Kind::List { count, item } if k == list => {
                                let n = r.int(count).map_err(|w| src.err(at(r, f), w))?;
                                if n < 3 {
                                    return Err(
                                        src.err(at(r, f), format!("face {f} has {n} vertices, needs at least 3"))
                                    );
                                }
                                r.check_list(n as u64, item).map_err(|w| src.err(at(r, f), w))?;
                                for _ in 0..n {
                                    let i = r.int(item).map_err(|w| src.err(at(r, f), w))?;
                                    if i < 0 || i as u64 >= vertex_count {
                                        return Err(src.err(at(r, f), index_message(f, i, nv)));
                                    }
                                    mesh.face_indices.push(i as u32);
                                }
                                close_face(&mut mesh).map_err(|w| src.err(at(r, f), w))?;
                            }
                            kind => skip_property(r, kind).map_err(|w| src.err(at(r, f), w))?,
                        }
                    }
                }
            }
            "tristrips" => {
                let list = element
                    .props
                    .iter()
                    .position(|p| matches!(p.kind, Kind::List { .. }))
                    .ok_or_else(|| src.err("header", "the tristrips element has no list property"))?;
                let mut strip: Vec<u32> = Vec::new();
                for s in 0..element.count {
                    for (k, prop) in element.props.iter().enumerate() {
                        match prop.kind {
                            Kind::List { count, item } if k == list => {
                                let n = r.int(count).map_err(|w| src.err(at(r, s), w))?;
                                if n < 0 {
                                    return Err(src.err(at(r, s), format!("negative list length {n}")));
                                }
                                r.check_list(n as u64, item).map_err(|w| src.err(at(r, s), w))?;
                                strip.clear();
                                for _ in 0..n {
                                    let i = r.int(item).map_err(|w| src.err(at(r, s), w))?;
                                    // -1 ends a strip (also as all ones in an unsigned type).
                                    let restart = i == -1
                                        || (item == Scalar::U32 && i == u32::MAX as i64)
                                        || (item == Scalar::U16 && i == u16::MAX as i64)
                                        || (item == Scalar::U8 && i == u8::MAX as i64);
                                    if restart {
                                        push_strip_triangles(&mut mesh, &strip).map_err(|w| src.err(at(r, s), w))?;
                                        strip.clear();
                                    } else if i < 0 || i as u64 >= vertex_count {
                                        return Err(src.err(
                                            at(r, s),
                                            format!(
                                                "strip index {i} refers to a vertex but the file has {nv} vertices"
                                            ),
                                        ));
                                    } else {
                                        strip.push(i as u32);
                                    }
                                }
                                push_strip_triangles(&mut mesh, &strip).map_err(|w| src.err(at(r, s), w))?;
                                strip.clear();
                            }
                            kind => skip_property(r, kind).map_err(|w| src.err(at(r, s), w))?,
                        }
                    }
                }
            }
            _ => {
                for e in 0..element.count {
                    for prop in &element.props {
                        skip_property(r, prop.kind).map_err(|w| src.err(at(r, e), w))?;
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
    for &(name, names) in KNOWN {
        if attributes.iter().any(|a| a.name == name) {
            continue;
        }
        let found: Option<Vec<usize>> = names
            .iter()
            .map(|n| props.iter().position(|p| p.name == *n).filter(|&k| scalar(k).is_some() && slots[k].is_none()))
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
    for k in 0..props.len() {
        if let (Some(s), None) = (scalar(k), slots[k]) {
            if attributes.iter().any(|a| a.name == props[k].name) {
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
    let mut out = Vec::with_capacity(256 + nv * 12 + mesh.face_indices.len() * 5 + mesh.face_count());
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
    let strip_list: Option<Vec<i32>> = match strips {
        Some(set) => {
            let total = set.indices.len() + set.len();
            if total > i32::MAX as usize {
                return Err(Error::Invalid(format!("{total} strip indices do not fit a PLY int list")));
            }
            let mut list = Vec::with_capacity(total);
            for s in set.iter().filter(|s| !s.is_empty()) {
                list.extend(s.iter().map(|&i| i as i32));
                list.push(-1);
            }
            header.push_str("element tristrips 1\nproperty list int int vertex_indices\n");
            Some(list)
        }
        None => None,
    };
    let wide = mesh.faces().any(|f| f.len() > 255);
    if strip_list.is_none() {
        let count = if wide { "int" } else { "uchar" };
        header.push_str(&format!("element face {}\nproperty list {count} int vertex_indices\n", mesh.face_count()));
    }
    header.push_str("end_header\n");
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
            Some(list) => {
                push_u64(&mut out, list.len() as u64);
                for &i in list {
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
            Some(list) => {
                out.extend_from_slice(&(list.len() as i32).to_le_bytes());
                for &i in list {
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

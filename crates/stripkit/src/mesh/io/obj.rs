//! Wavefront OBJ: `v x y z` and `f` with `v`, `v/vt`, `v//vn`, `v/vt/vn` corners,
//! 1-based or negative (relative) indices; polygons are kept. Every other statement
//! (`vt`, `vn`, `o`, `g`, `usemtl`, `l`, ...) is ignored.

use super::common::{
    close_face, finite, index_message, is_space, line_at, line_end, parse_f32, parse_i64, show, sniff, Src,
};
use crate::error::Result;
use crate::mesh::Mesh;
use std::path::Path;

/// Walks OBJ text line by line and token by token in a single pass, without
/// allocating; a `#` at the start of a token ends the line's tokens. Lines end at
/// `\n`, `\r\n` or a lone `\r`.
struct Cursor<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Cursor<'a> {
    /// The next token of the current line; `None` at the line's end or at a comment.
    #[inline]
    fn token(&mut self) -> Option<&'a [u8]> {
        let d = self.data;
        while self.pos < d.len() && is_space(d[self.pos]) && d[self.pos] != b'\r' {
            self.pos += 1;
        }
        if self.pos >= d.len() || d[self.pos] == b'\n' || d[self.pos] == b'\r' || d[self.pos] == b'#' {
            return None;
        }
        let start = self.pos;
        while self.pos < d.len() && !is_space(d[self.pos]) && d[self.pos] != b'\n' {
            self.pos += 1;
        }
        Some(&d[start..self.pos])
    }

    /// Moves to the start of the next line.
    #[inline]
    fn next_line(&mut self) {
        let rest = &self.data[self.pos..];
        self.pos += line_end(rest).map_or(rest.len(), |(i, n)| i + n);
    }

    /// True when the cursor stands on a comment.
    fn at_comment(&self) -> bool {
        self.data.get(self.pos) == Some(&b'#')
    }
}

/// Statements of the OBJ specification other than `v` and `f` (read and ignored).
const OTHER_STATEMENTS: &[&[u8]] = &[
    b"vt", b"vn", b"vp", b"l", b"p", b"o", b"g", b"s", b"mg", b"usemtl", b"mtllib", b"usemap", b"maplib",
    b"cstype", b"deg", b"bmat", b"step", b"curv", b"curv2", b"surf", b"parm", b"trim", b"hole", b"scrv",
    b"sp", b"end", b"con", b"lod", b"shadow_obj", b"trace_obj", b"c_interp", b"d_interp", b"bevel",
    b"ctech", b"stech", b"call", b"csh",
];

/// Parses an OBJ file held in memory.
pub(crate) fn read(path: &Path, data: &[u8]) -> Result<Mesh> {
    let src = Src { path };
    let mut mesh = Mesh::new();
    // Faces may name vertices defined later in the file, so positive indices are
    // range-checked once at the end; this is the largest seen (0-based).
    let mut max_index: u64 = 0;
    let mut c = Cursor { data, pos: 0 };
    let mut ln = 0;
    // Whether any comment or known statement was seen: a file without one that gives
    // an empty mesh is not OBJ at all.
    let mut recognised = false;
    while c.pos < data.len() {
        ln += 1;
        match c.token() {
            Some(b"v") => {
                let mut p = [0.0f32; 3];
                for (k, slot) in p.iter_mut().enumerate() {
                    let tok = c.token().ok_or_else(|| {
                        src.err(line_at(ln), format!("vertex has {k} coordinates, needs 3"))
                    })?;
                    let v = parse_f32(tok).ok_or_else(|| {
                        src.err(line_at(ln), format!("malformed number '{}'", show(tok)))
                    })?;
                    *slot = finite(v, tok).map_err(|w| src.err(line_at(ln), w))?;
                }
                if mesh.positions.len() >= u32::MAX as usize {
                    return Err(src.err(line_at(ln), "more than 4294967295 vertices"));
                }
                mesh.positions.push(p);
            }
            Some(b"f") => {
                let first = mesh.face_indices.len();
                let defined = mesh.positions.len() as i64;
                while let Some(tok) = c.token() {
                    let vpart = match tok.iter().position(|&b| b == b'/') {
                        Some(i) => &tok[..i],
                        None => tok,
                    };
                    let idx = parse_i64(vpart).ok_or_else(|| {
                        src.err(line_at(ln), format!("malformed vertex index '{}'", show(tok)))
                    })?;
                    let zero_based = if idx > 0 {
                        idx - 1
                    } else if idx < 0 {
                        let r = defined + idx;
                        if r < 0 {
                            return Err(src.err(
                                line_at(ln),
                                format!(
                                    "relative index {idx} reaches before the first vertex ({defined} vertices defined so far)"
                                ),
                            ));
                        }
                        r
                    } else {
                        return Err(src.err(line_at(ln), "vertex index 0 (OBJ indices start at 1)"));
                    };
                    if zero_based >= u32::MAX as i64 {
                        return Err(src.err(
                            line_at(ln),
                            format!("vertex index {idx} is beyond any vertex the file can hold"),
                        ));
                    }
                    max_index = max_index.max(zero_based as u64);
                    mesh.face_indices.push(zero_based as u32);
                }
                let k = mesh.face_indices.len() - first;
                if k < 3 {
                    return Err(src.err(line_at(ln), format!("face has {k} vertices, needs at least 3")));
                }
                close_face(&mut mesh).map_err(|w| src.err(line_at(ln), w))?;
            }
            Some(tok) => recognised |= OTHER_STATEMENTS.contains(&tok),
            None => recognised |= c.at_comment(),
        }
        c.next_line();
    }
    if mesh.positions.is_empty() && mesh.face_count() == 0 {
        refuse_if_not_obj(src, data, recognised)?;
    }
    let nv = mesh.positions.len();
    if mesh.face_count() > 0 && max_index as usize >= nv {
        // Error path only: find the first offending face and its line.
        let face = mesh.faces().position(|f| f.iter().any(|&i| i as usize >= nv)).unwrap_or(0);
        let bad = mesh.face(face).iter().copied().find(|&i| i as usize >= nv).unwrap_or(0);
        let line = face_line(data, face);
        return Err(src.err(line_at(line), index_message(face as u64, bad as i64 + 1, nv)));
    }
    Ok(mesh)
}

/// An empty result from a file with content: refused when the content looks like
/// something else (another format, UTF-16, binary data) or holds no OBJ statement,
/// instead of reading as an empty mesh. Comments and known statements alone (an OBJ
/// with no geometry) are accepted.
fn refuse_if_not_obj(src: Src, data: &[u8], recognised: bool) -> Result<()> {
    let Some(start) = data.iter().position(|&b| !is_space(b) && b != b'\n') else {
        return Ok(()); // empty or blank
    };
    if let Some(what) = sniff(data) {
        return Err(src.err("line 1", format!("{what}, not OBJ")));
    }
    if !recognised {
        let first = data[start..].split(|&b| b == b'\n' || b == b'\r').next().unwrap_or_default();
        return Err(src.err(
            "line 1",
            format!("no OBJ statement (v, f, ...) in the file, which starts with '{}': not an OBJ file", show(first)),
        ));
    }
    Ok(())
}

/// The line number of the `face`-th `f` statement.
fn face_line(data: &[u8], face: usize) -> usize {
    let mut c = Cursor { data, pos: 0 };
    let mut seen = 0;
    let mut ln = 0;
    while c.pos < data.len() {
        ln += 1;
        if c.token() == Some(b"f") {
            if seen == face {
                return ln;
            }
            seen += 1;
        }
        c.next_line();
    }
    0
}

/// Appends the decimal digits of `v`.
pub(crate) fn push_u64(out: &mut Vec<u8>, mut v: u64) {
    let mut buf = [0u8; 20];
    let mut i = buf.len();
    loop {
        i -= 1;
        buf[i] = b'0' + (v % 10) as u8;
        v /= 10;
        if v == 0 {
            break;
        }
    }
    out.extend_from_slice(&buf[i..]);
}

/// Appends one text line `x y z` per position (OFF and ASCII PLY bodies).
pub(crate) fn push_position_lines(out: &mut Vec<u8>, positions: &[[f32; 3]]) {
    for p in positions {
        for (k, &c) in p.iter().enumerate() {
            if k > 0 {
                out.push(b' ');
            }
            push_f32(out, c);
        }
        out.push(b'\n');
    }
}

/// Appends one text line `k i0 i1 ..` per face (OFF and ASCII PLY bodies).
pub(crate) fn push_face_lines(out: &mut Vec<u8>, mesh: &Mesh) {
    for f in mesh.faces() {
        push_u64(out, f.len() as u64);
        for &i in f {
            out.push(b' ');
            push_u64(out, i as u64);
        }
        out.push(b'\n');
    }
}

/// Appends the shortest decimal text that reads back as exactly `v`.
pub(crate) fn push_f32(out: &mut Vec<u8>, v: f32) {
    use std::io::Write;
    if v == v.trunc() && v.abs() < 1e7 {
        // Integral values: "3" rather than "3.0" keeps files short.
        if v == 0.0 && v.is_sign_negative() {
            out.extend_from_slice(b"-0");
        } else {
            if v < 0.0 {
                out.push(b'-');
            }
            push_u64(out, v.abs() as u64);
        }
    } else {
        // Debug prints the shortest round-trip form, with an exponent for extremes.
        let _ = write!(out, "{v:?}");
    }
}

/// Encodes a mesh as OBJ text (1-based indices, polygons as they are).
pub(crate) fn write(mesh: &Mesh) -> Vec<u8> {
    let mut out = Vec::with_capacity(mesh.positions.len() * 32 + mesh.face_indices.len() * 8 + 64);
    out.extend_from_slice(
        format!(
            "# written by stripkit: {} vertices, {} faces\n",
            mesh.positions.len(),
            mesh.face_count()
        )
        .as_bytes(),
    );
    for p in &mesh.positions {
        out.push(b'v');
        for &c in p {
            out.push(b' ');
            push_f32(&mut out, c);
        }
        out.push(b'\n');
    }
    for f in mesh.faces() {
        out.push(b'f');
        for &i in f {
            out.push(b' ');
            push_u64(&mut out, i as u64 + 1);
        }
        out.push(b'\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    fn parse(text: &str) -> Result<Mesh> {
        read(Path::new("t.obj"), text.as_bytes())
    }

    fn format_error(text: &str) -> (String, String) {
        match parse(text) {
            Err(Error::Format { at, what, .. }) => (at, what),
            other => panic!("expected a format error, got {other:?}"),
        }
    }

    #[test]
    fn all_face_forms_and_negative_indices_read_alike() {
        let text = "# c\nv 0 0 0\nv 1 0 0\nvt 0 0\nvn 0 0 1\nv 1 1 0\nv 0 1 0\n\
                    f 1 2 3\nf 1/1 3/1 4/1\nf 1//1 2//1 4//1\nf 2/1/1 3/1/1 4/1/1\nf -4 -3 -2 -1\n\
                    o name\ng grp\nusemtl m\ns off\nl 1 2\n";
        let m = parse(text).unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.face(0), &[0, 1, 2]);
        assert_eq!(m.face(1), &[0, 2, 3]);
        assert_eq!(m.face(2), &[0, 1, 3]);
        assert_eq!(m.face(3), &[1, 2, 3]);
        assert_eq!(m.face(4), &[0, 1, 2, 3]);
        assert_eq!(m.positions[2], [1.0, 1.0, 0.0]);
    }

    #[test]
    fn relative_indices_refer_to_vertices_defined_so_far() {
        let m = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 5 5 5\nf -4 -3 -1\n").unwrap();
        assert_eq!(m.face(0), &[0, 1, 2]);
        assert_eq!(m.face(1), &[0, 1, 3]);
    }

    #[test]
    fn forward_references_are_allowed() {
        let m = parse("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
        assert_eq!(m.face(0), &[0, 1, 2]);
    }

    #[test]
    fn bad_lines_are_named() {
        let (at, what) = format_error("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 9\n");
        assert_eq!(at, "line 5");
        assert!(what.contains("vertex 9") && what.contains("3 vertices"), "{what}");
        let (at, what) = format_error("v 0 0 0\nv 1 x 0\n");
        assert_eq!(at, "line 2");
        assert!(what.contains("malformed number 'x'"), "{what}");
        let (at, what) = format_error("v 0 0 nan\n");
        assert_eq!(at, "line 1");
        assert!(what.contains("NaN or infinite"), "{what}");
        let (_, what) = format_error("v 0 0 0\nv 0 0 0\nf 1 2\n");
        assert!(what.contains("2 vertices"), "{what}");
        let (_, what) = format_error("v 0 0 0\nf 0 1 1\n");
        assert!(what.contains("index 0"), "{what}");
        let (_, what) = format_error("v 0 0 0\nf -2 1 1\n");
        assert!(what.contains("relative index -2"), "{what}");
        let (_, what) = format_error("v 1 2\n");
        assert!(what.contains("2 coordinates"), "{what}");
        let (_, what) = format_error("v 0 0 0\nf 1 a/1 1\n");
        assert!(what.contains("'a/1'"), "{what}");
    }

    #[test]
    fn written_text_reads_back_exactly() {
        let positions = vec![[0.1, -2.5, 3.0], [1e-7, 1e30, -0.0], [f32::MIN_POSITIVE, 7.0, 12345.678]];
        let mesh = Mesh::from_polygons(positions, &[vec![0, 1, 2], vec![2, 1, 0]]);
        let back = read(Path::new("t.obj"), &write(&mesh)).unwrap();
        assert_eq!(back, mesh);
        for (a, b) in back.positions.iter().flatten().zip(mesh.positions.iter().flatten()) {
            assert_eq!(a.to_bits(), b.to_bits());
        }
    }
}

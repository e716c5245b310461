//! Object File Format: a header keyword `[ST][C][N][4]OFF` (texture coordinates,
//! colours, normals, homogeneous coordinates), counts `V F [E]` on the same or the
//! next line, then one vertex per line and one face `k i0 .. ik-1 [colour]` per line.
//! `#` starts a comment. Values after the first three (four for `4OFF`) on a vertex
//! line and after the `k` indices on a face line are ignored, which covers every
//! colour / normal / texture variant without knowing how many numbers each carries.

use super::common::{
    capped, close_face, ends_line, finite, index_message, is_space, line_at, line_end, parse_count, parse_f32, show,
    sniff, Src,
};
use super::obj::{push_face_lines, push_position_lines};
use crate::error::Result;
use crate::mesh::Mesh;
use std::path::Path;

/// A token cursor over OFF text: skips whitespace, line ends (`\n`, `\r\n` or a lone
/// `\r`) and `#` comments, and can drop the rest of the current line (where optional
/// colours and normals live).
struct Cursor<'a> {
    data: &'a [u8],
    pos: usize,
    line: usize,
    /// Line of the last token found: where an unexpected end of file is reported.
    token_line: usize,
}

impl<'a> Cursor<'a> {
    fn token(&mut self) -> Option<&'a [u8]> {
        let d = self.data;
        while self.pos < d.len() {
            match d[self.pos] {
                b'\n' | b'\r' => self.line += ends_line(d, self.pos) as usize,
                b'#' => {
                    self.skip_line();
                    continue;
                }
                b if is_space(b) => {}
                _ => break,
            }
            self.pos += 1;
        }
        let start = self.pos;
        while self.pos < d.len() && !is_space(d[self.pos]) && d[self.pos] != b'\n' && d[self.pos] != b'#' {
            self.pos += 1;
        }
        if start == self.pos {
            self.line = self.token_line;
            return None;
        }
        self.token_line = self.line;
        Some(&d[start..self.pos])
    }

    /// Moves to the line end (the line end itself is consumed by the next `token`).
    fn skip_line(&mut self) {
        let rest = &self.data[self.pos..];
        self.pos += line_end(rest).map_or(rest.len(), |(i, _)| i);
    }

    /// The rest of the current line from `start`, for messages.
    fn line_from(&self, start: usize) -> &'a [u8] {
        let rest = &self.data[start..];
        &rest[..line_end(rest).map_or(rest.len(), |(i, _)| i)]
    }
}

/// Parses an OFF file held in memory.
///
/// Records may span lines (some files break long faces); values after a vertex's
/// coordinates or a face's indices on the same line (colours, normals, texture
/// coordinates) are ignored.
pub(crate) fn read(path: &Path, data: &[u8]) -> Result<Mesh> {
    let src = Src { path };
    let mut c = Cursor { data, pos: 0, line: 1, token_line: 1 };
    let keyword = c.token().ok_or_else(|| src.err("line 1", "empty file, expected the OFF keyword"))?;
    let homogeneous = parse_keyword(keyword).ok_or_else(|| {
        let looks = sniff(data).map(|w| format!(" ({w})")).unwrap_or_default();
        src.err(
            line_at(c.line),
            format!("expected an OFF keyword such as OFF or COFF, found '{}'{looks}", show(keyword)),
        )
    })?;
    let mut count = |what: &str| {
        let tok = c.token().ok_or_else(|| src.err(line_at(c.line), format!("file ends before the {what} count")))?;
        parse_count(tok).ok_or_else(|| src.err(line_at(c.line), format!("malformed {what} count '{}'", show(tok))))
    };
    let nv = count("vertex")?;
    let nf = count("face")?;
    c.skip_line(); // the edge count, unused
    if nv > u32::MAX as u64 {
        return Err(src.err(line_at(c.line), format!("{nv} vertices do not fit 32-bit indices")));
    }

    let mut mesh = Mesh::new();
    // A vertex takes at least 6 bytes ("0 0 0\n"), a face 8 ("3 0 1 2\n").
    mesh.positions.reserve(capped(nv, data.len(), 6));
    mesh.face_offsets.reserve(capped(nf, data.len(), 8));
    mesh.face_indices.reserve(capped(nf, data.len(), 8) * 3);
    let dims = if homogeneous { 4 } else { 3 };
    for v in 0..nv {
        let mut p = [0.0f32; 4];
        for (k, slot) in p.iter_mut().take(dims).enumerate() {
            let tok = c.token().ok_or_else(|| {
                src.err(line_at(c.line), format!("file ends in vertex {v} of {nv} announced vertices (after {k} coordinates)"))
            })?;
            let x = parse_f32(tok).ok_or_else(|| src.err(line_at(c.line), format!("malformed number '{}'", show(tok))))?;
            *slot = finite(x, tok).map_err(|w| src.err(line_at(c.line), w))?;
        }
        c.skip_line();
        if homogeneous {
            if p[3] == 0.0 {
                return Err(src.err(line_at(c.line), format!("vertex {v} has homogeneous coordinate 0")));
            }
            for k in 0..3 {
                p[k] /= p[3];
            }
            // The division can overflow (w = 1e-45) even though every input was finite.
            if !p[..3].iter().all(|x| x.is_finite()) {
                return Err(src.err(
                    line_at(c.line),
                    format!(
                        "vertex {v}: dividing by its homogeneous coordinate {:e} gives a NaN or infinite coordinate",
                        p[3]
                    ),
                ));
            }
        }
        mesh.positions.push([p[0], p[1], p[2]]);
    }
    for f in 0..nf {
        let ktok = c
            .token()
            .ok_or_else(|| src.err(line_at(c.line), format!("file ends after {f} of {nf} announced faces")))?;
        let k = parse_count(ktok)
            .ok_or_else(|| src.err(line_at(c.line), format!("malformed vertex count '{}'", show(ktok))))?;
        if k < 3 {
            return Err(src.err(line_at(c.line), format!("face {f} has {k} vertices, needs at least 3")));
        }
        for j in 0..k {
            let tok = c.token().ok_or_else(|| {
                src.err(line_at(c.line), format!("file ends in face {f}, which announces {k} vertices but lists {j}"))
            })?;
            let i = parse_count(tok)
                .ok_or_else(|| src.err(line_at(c.line), format!("malformed vertex index '{}'", show(tok))))?;
            if i >= nv {
                return Err(src.err(line_at(c.line), index_message(f, i as i64, nv as usize)));
            }
            mesh.face_indices.push(i as u32);
        }
        c.skip_line();
        close_face(&mut mesh).map_err(|w| src.err(line_at(c.line), w))?;
    }
    // Only whitespace and comments may follow the announced records.
    if let Some(tok) = c.token() {
        let start = tok.as_ptr() as usize - data.as_ptr() as usize;
        return Err(src.err(
            line_at(c.line),
            format!(
                "a record after the {nv} vertices and {nf} faces the header announces: '{}'",
                show(c.line_from(start))
            ),
        ));
    }
    Ok(mesh)
}

/// Checks an OFF keyword; returns whether vertices carry a homogeneous coordinate.
fn parse_keyword(k: &[u8]) -> Option<bool> {
    let mut rest = k.strip_suffix(b"OFF")?;
    if let Some(r) = rest.strip_prefix(b"ST") {
        rest = r;
    }
    for prefix in [&b"C"[..], b"N"] {
        if let Some(r) = rest.strip_prefix(prefix) {
            rest = r;
        }
    }
    let homogeneous = match rest {
        b"" => false,
        b"4" => true,
        _ => return None,
    };
    Some(homogeneous)
}

/// Encodes a mesh as OFF text.
pub(crate) fn write(mesh: &Mesh) -> Vec<u8> {
    let mut out = Vec::with_capacity(mesh.positions.len() * 32 + mesh.face_indices.len() * 8 + 64);
    out.extend_from_slice(format!("OFF\n{} {} 0\n", mesh.positions.len(), mesh.face_count()).as_bytes());
    push_position_lines(&mut out, &mesh.positions);
    push_face_lines(&mut out, mesh);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    fn parse(text: &str) -> Result<Mesh> {
        read(Path::new("t.off"), text.as_bytes())
    }

    fn format_error(text: &str) -> (String, String) {
        match parse(text) {
            Err(Error::Format { at, what, .. }) => (at, what),
            other => panic!("expected a format error, got {other:?}"),
        }
    }

    #[test]
    fn header_variants_comments_and_colours_are_read() {
        let plain = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
        let expected = parse(plain).unwrap();
        assert_eq!(expected.face_count(), 2);
        let variants = [
            "# comment\nOFF 4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n",
            "COFF\n4 2 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n0 1 0 1 1 1 1\n3 0 1 2\n3 0 2 3\n",
            "NOFF\n# normals\n4 2\n0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0 0 0 1 # c\n0 1 0 0 0 1\n3 0 1 2 255 0 0\n3 0 2 3 0.5 0.5 0.5 1\n",
            "CNOFF\n4 2 0\n0 0 0 0 0 1 1 1 1 1\n1 0 0 0 0 1 1 1 1 1\n1 1 0 0 0 1 1 1 1 1\n0 1 0 0 0 1 1 1 1 1\n3 0 1 2\n3 0 2 3\n",
            "STOFF\n4 2 0\n0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n\n3 0 1 2\n3 0 2 3\n",
            "4OFF\n4 2 0\n0 0 0 2\n2 0 0 2\n2 2 0 2\n0 2 0 2\n3 0 1 2\n3 0 2 3\n",
            "OFF\r\n4 2 0\r\n0 0 0\r\n1 0 0\r\n1 1 0\r\n0 1 0\r\n3 0 1 2\r\n3 0 2 3\r\n",
            "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 \n1\n 2\n3 0 2 3 # last\n",
        ];
        for v in variants {
            assert_eq!(parse(v).unwrap(), expected, "{v}");
        }
    }

    #[test]
    fn bad_input_is_named() {
        let (at, what) = format_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
        assert_eq!(at, "line 6");
        assert_eq!(what, "face 0 refers to vertex 7 but the file has 3 vertices");
        let (at, what) = format_error("OFF\n3 1 0\n0 0 0\n1 0 0\n");
        assert_eq!(at, "line 4");
        assert!(what.contains("vertex 2 of 3"), "{what}");
        let (_, what) = format_error("OFF\n3 1000000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
        assert!(what.contains("1 of 1000000000000 announced faces"), "{what}");
        let (_, what) = format_error("OFF\n3 1 0\n0 0 0\n1 0 inf\n0 1 0\n3 0 1 2\n");
        assert!(what.contains("NaN or infinite"), "{what}");
        let (_, what) = format_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
        assert!(what.contains("2 vertices"), "{what}");
        let (_, what) = format_error("PLY\n");
        assert!(what.contains("OFF keyword"), "{what}");
        let (_, what) = format_error("OFF\n3 x 0\n");
        assert!(what.contains("malformed face count"), "{what}");
        let (_, what) = format_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n");
        assert!(what.contains("lists 2"), "{what}");
        let (_, what) = format_error("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 3 4 5\n");
        assert!(what.contains("after 1 of 2"), "{what}");
        let (at, what) = format_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 x\n");
        assert_eq!(at, "line 6");
        assert!(what.contains("'x'"), "{what}");
    }

    #[test]
    fn empty_mesh_round_trips() {
        let m = parse("OFF\n0 0 0\n").unwrap();
        assert_eq!(m, Mesh::new());
        assert_eq!(read(Path::new("t.off"), &write(&m)).unwrap(), m);
    }

    #[test]
    fn written_text_reads_back_exactly() {
        let mesh = Mesh::from_polygons(
            vec![[0.1, -2.5, 3.0], [1e-7, 1e30, -0.0], [0.25, 7.0, 12345.678], [4.0, 5.0, 6.0]],
            &[vec![0, 1, 2, 3], vec![2, 1, 0]],
        );
        assert_eq!(read(Path::new("t.off"), &write(&mesh)).unwrap(), mesh);
    }
}

//! STL, ASCII and binary. STL stores every triangle with its own three corners, so
//! the reader welds bit-identical positions (with `-0.0` equal to `0.0`) into shared
//! vertices, numbered in first-seen order. The writer writes binary STL with polygons
//! fanned from their first vertex and unit face normals.
//!
//! A file is binary when its size is exactly `84 + 50 * n` for the triangle count `n`
//! stored at byte 80, unless it starts with `solid` and its opening bytes read as
//! ASCII STL text (some binary exporters also start their header with `solid`). A UTF-8
//! byte order mark before `solid` is skipped; UTF-16 text is refused by name. Keywords
//! are read without regard to case (`SOLID`, `Facet`, `VERTEX`), as some exporters
//! write them in upper case.

use super::common::{close_face, finite, is_space, line_at, parse_f32, show, sniff, tokens, utf16_bom, Lines, Src};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use std::path::Path;

/// Assigns vertex ids to positions: identical bits give the same id.
struct Welder {
    /// Open addressing table of (position bits, vertex id); id `u32::MAX` is empty.
    /// Keys live in the table so that a probe touches one cache line.
    slots: Vec<([u32; 3], u32)>,
    used: usize,
}

const EMPTY: ([u32; 3], u32) = ([0; 3], u32::MAX);

impl Welder {
    fn with_capacity(vertices: usize) -> Self {
        let size = (vertices.max(8) * 2).next_power_of_two();
        Welder { slots: vec![EMPTY; size], used: 0 }
    }

    fn key(p: [f32; 3]) -> [u32; 3] {
        // Adding 0.0 turns -0.0 into 0.0; coordinates are finite here.
        [(p[0] + 0.0).to_bits(), (p[1] + 0.0).to_bits(), (p[2] + 0.0).to_bits()]
    }

    fn hash(k: [u32; 3]) -> usize {
        let mut h = (k[0] as u64 | (k[1] as u64) << 32).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        h ^= (k[2] as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
        h ^= h >> 31;
        h = h.wrapping_mul(0x94D0_49BB_1331_11EB);
        (h ^ (h >> 29)) as usize
    }

    /// The id of `p`, appending it to `positions` when new.
    #[inline]
    fn id(&mut self, positions: &mut Vec<[f32; 3]>, p: [f32; 3]) -> Result<u32, String> {
        if self.used * 2 >= self.slots.len() {
            self.grow();
        }
        let key = Self::key(p);
        let mask = self.slots.len() - 1;
        let mut i = Self::hash(key) & mask;
        loop {
            let (k, id) = self.slots[i];
            if id == u32::MAX {
                if positions.len() >= u32::MAX as usize {
                    return Err("more than 4294967295 distinct vertices".into());
                }
                let new = positions.len() as u32;
                self.slots[i] = (key, new);
                self.used += 1;
                positions.push(p);
                return Ok(new);
            }
            if k == key {
                return Ok(id);
            }
            i = (i + 1) & mask;
        }
    }

    fn grow(&mut self) {
        let size = self.slots.len() * 2;
        let old = std::mem::replace(&mut self.slots, vec![EMPTY; size]);
        let mask = self.slots.len() - 1;
        for slot in old.into_iter().filter(|s| s.1 != u32::MAX) {
            let mut i = Self::hash(slot.0) & mask;
            while self.slots[i].1 != u32::MAX {
                i = (i + 1) & mask;
            }
            self.slots[i] = slot;
        }
    }
}

/// Parses an STL file held in memory.
pub(crate) fn read(path: &Path, data: &[u8]) -> Result<Mesh> {
    let src = Src { path };
    let announced = if data.len() >= 84 {
        Some(u32::from_le_bytes([data[80], data[81], data[82], data[83]]) as u64)
    } else {
        None
    };
    let size_matches = announced.is_some_and(|n| 84 + 50 * n == data.len() as u64);
    // The size decides for binary; the text checks look past a UTF-8 byte order mark.
    let text = data.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(data);
    let start = text.iter().position(|&b| !is_space(b) && b != b'\n').unwrap_or(text.len());
    let starts_solid = text[start..].get(..5).is_some_and(|w| w.eq_ignore_ascii_case(b"solid"));
    if starts_solid && (!size_matches || looks_ascii(text)) {
        return read_ascii(src, text);
    }
    if !size_matches {
        if let Some(bom) = utf16_bom(data) {
            return Err(src.err("byte 0", format!("the file is UTF-16 ({bom}); save it as UTF-8")));
        }
    }
    // Not binary STL by its size and not ASCII STL: say what it looks like, if anything.
    let looks = || sniff(data).map(|w| format!(" ({w})")).unwrap_or_default();
    let Some(n) = announced else {
        return Err(src.err(
            "byte 0",
            format!("{} bytes is too short for a binary STL (84-byte header) and it is not ASCII STL{}", data.len(), looks()),
        ));
    };
    if !size_matches {
        return Err(src.err(
            "byte 80",
            format!(
                "binary STL announces {n} triangles, which take {} bytes, but the file has {} bytes{}",
                84 + 50 * n,
                data.len(),
                looks()
            ),
        ));
    }
    let n = n as usize; // fits: checked against the file's size
    let mut mesh = Mesh::new();
    let mut welder = Welder::with_capacity(n / 2 + 1);
    mesh.positions.reserve(n / 2 + 3);
    mesh.face_offsets.reserve(n);
    mesh.face_indices.reserve(3 * n);
    for (t, rec) in data[84..].chunks_exact(50).enumerate() {
        for k in 0..3 {
            let mut p = [0.0f32; 3];
            for (c, slot) in p.iter_mut().enumerate() {
                let o = 12 + 12 * k + 4 * c;
                let v = f32::from_le_bytes([rec[o], rec[o + 1], rec[o + 2], rec[o + 3]]);
                if !v.is_finite() {
                    return Err(src.err(
                        format!("triangle {t} (byte {})", 84 + 50 * t + o),
                        format!("coordinate {v} is NaN or infinite"),
                    ));
                }
                *slot = v;
            }
            let id = welder.id(&mut mesh.positions, p).map_err(|w| src.err(format!("triangle {t}"), w))?;
            mesh.face_indices.push(id);
        }
        close_face(&mut mesh).map_err(|w| src.err(format!("triangle {t}"), w))?;
    }
    Ok(mesh)
}

/// True when the first bytes are printable text mentioning STL keywords.
fn looks_ascii(data: &[u8]) -> bool {
    let head = &data[..data.len().min(512)];
    head.iter().all(|&b| b.is_ascii_graphic() || b.is_ascii_whitespace())
        && (head.windows(5).any(|w| w.eq_ignore_ascii_case(b"facet"))
            || head.windows(8).any(|w| w.eq_ignore_ascii_case(b"endsolid")))
}

fn read_ascii(src: Src, data: &[u8]) -> Result<Mesh> {
    let mut mesh = Mesh::new();
    let mut welder = Welder::with_capacity(data.len() / 200);
    // Some(line) while inside `facet` .. `endfacet`.
    let mut facet: Option<usize> = None;
    let mut facets = 0usize;
    for (ln, line) in Lines::new(data) {
        let mut toks = tokens(line);
        let Some(word) = toks.next() else { continue };
        // Keywords are at most 8 bytes ("endsolid", "endfacet"); longer words are unexpected.
        let mut lower = [0u8; 8];
        let keyword: &[u8] = match lower.get_mut(..word.len()) {
            Some(buf) => {
                buf.copy_from_slice(word);
                buf.make_ascii_lowercase();
                buf
            }
            None => word,
        };
        match keyword {
            b"solid" | b"endsolid" | b"outer" | b"endloop" => {
                if keyword == b"solid" && facet.is_some() {
                    return Err(src.err(line_at(ln), "'solid' inside a facet"));
                }
            }
            b"facet" => {
                if facet.is_some() {
                    return Err(src.err(line_at(ln), "'facet' before the previous facet's 'endfacet'"));
                }
                facet = Some(ln);
            }
            b"vertex" => {
                if facet.is_none() {
                    return Err(src.err(line_at(ln), "'vertex' outside a facet"));
                }
                let mut p = [0.0f32; 3];
                for (k, slot) in p.iter_mut().enumerate() {
                    let tok = toks
                        .next()
                        .ok_or_else(|| src.err(line_at(ln), format!("vertex has {k} coordinates, needs 3")))?;
                    let v = parse_f32(tok)
                        .ok_or_else(|| src.err(line_at(ln), format!("malformed number '{}'", show(tok))))?;
                    *slot = finite(v, tok).map_err(|w| src.err(line_at(ln), w))?;
                }
                let id = welder.id(&mut mesh.positions, p).map_err(|w| src.err(line_at(ln), w))?;
                mesh.face_indices.push(id);
            }
            b"endfacet" => {
                if facet.take().is_none() {
                    return Err(src.err(line_at(ln), "'endfacet' without 'facet'"));
                }
                let first = *mesh.face_offsets.last().unwrap_or(&0) as usize;
                let k = mesh.face_indices.len() - first;
                if k < 3 {
                    return Err(src.err(line_at(ln), format!("facet {facets} has {k} vertices, needs at least 3")));
                }
                close_face(&mut mesh).map_err(|w| src.err(line_at(ln), w))?;
                facets += 1;
            }
            _ => {
                return Err(src.err(line_at(ln), format!("unexpected '{}' in ASCII STL", show(word))));
            }
        }
    }
    if let Some(ln) = facet {
        return Err(src.err(line_at(ln), "the file ends inside this facet (truncated)"));
    }
    Ok(mesh)
}

/// Encodes a mesh as binary STL, fanning polygons.
pub(crate) fn write(mesh: &Mesh) -> Result<Vec<u8>> {
    let n = mesh.triangle_count();
    let n32 = u32::try_from(n).map_err(|_| Error::Invalid(format!("{n} triangles do not fit binary STL")))?;
    let mut out = Vec::with_capacity(84 + 50 * n);
    // The header must not start with "solid", which would suggest ASCII STL.
    let mut header = [b' '; 80];
    let title = b"binary STL written by stripkit";
    header[..title.len()].copy_from_slice(title);
    out.extend_from_slice(&header);
    out.extend_from_slice(&n32.to_le_bytes());
    for f in mesh.faces() {
        for i in 1..f.len() - 1 {
            let [a, b, c] = [f[0], f[i], f[i + 1]].map(|v| mesh.positions[v as usize]);
            let nrm = crate::vec3::tri_normal_f32(a, b, c);
            let len = (nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]).sqrt();
            let nrm = if len > 0.0 && len.is_finite() { nrm.map(|x| x / len) } else { [0.0; 3] };
            for x in nrm.iter().chain(a.iter()).chain(b.iter()).chain(c.iter()) {
                out.extend_from_slice(&x.to_le_bytes());
            }
            out.extend_from_slice(&[0, 0]);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn format_error(bytes: &[u8]) -> (String, String) {
        match read(Path::new("t.stl"), bytes) {
            Err(Error::Format { at, what, .. }) => (at, what),
            other => panic!("expected a format error, got {other:?}"),
        }
    }

    #[test]
    fn welding_survives_table_growth_and_keeps_first_seen_order() {
        let mut w = Welder::with_capacity(0);
        let mut positions = Vec::new();
        for i in 0..1000 {
            assert_eq!(w.id(&mut positions, [i as f32, 0.5, -1.0]).unwrap(), i);
        }
        for i in (0..1000).rev() {
            assert_eq!(w.id(&mut positions, [i as f32, 0.5, -1.0]).unwrap(), i);
        }
        assert_eq!(w.id(&mut positions, [-0.0, 0.5, -1.0]).unwrap(), 0);
        assert_eq!(positions.len(), 1000);
    }

    #[test]
    fn binary_and_ascii_errors_name_the_place() {
        let (at, what) = format_error(&[0u8; 40]);
        assert_eq!(at, "byte 0");
        assert!(what.contains("too short"), "{what}");
        let mut bytes = vec![0u8; 84 + 50 * 2];
        bytes[80] = 3;
        let (at, what) = format_error(&bytes);
        assert_eq!(at, "byte 80");
        assert!(what.contains("announces 3 triangles") && what.contains("234 bytes") && what.contains("184 bytes"), "{what}");
        let (at, what) = format_error(b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n");
        assert_eq!(at, "line 7");
        assert!(what.contains("2 vertices"), "{what}");
        let (at, _) = format_error(b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n");
        assert_eq!(at, "line 2");
    }

    #[test]
    fn upper_case_ascii_reads_like_lower_case() {
        let lower: &[u8] = b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n";
        let upper = String::from_utf8(lower.to_vec()).unwrap().to_uppercase();
        let mixed = upper.replacen("FACET NORMAL", "Facet Normal", 1);
        let want = read(Path::new("t.stl"), lower).unwrap();
        for text in [upper.as_str(), mixed.as_str()] {
            let got = read(Path::new("t.stl"), text.as_bytes()).unwrap_or_else(|e| panic!("{text}: {e}"));
            assert_eq!(got.positions, want.positions);
            assert_eq!(got.face_indices, want.face_indices);
            assert_eq!(got.face_offsets, want.face_offsets);
        }
    }

    #[test]
    fn binary_header_starting_with_upper_case_solid_stays_binary() {
        // A binary file whose header reads "SOLID" and whose size matches one triangle.
        let mut bytes = vec![0u8; 84 + 50];
        bytes[..5].copy_from_slice(b"SOLID");
        bytes[80] = 1;
        for (k, v) in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]].iter().enumerate() {
            for (c, x) in v.iter().enumerate() {
                let o = 84 + 12 + 12 * k + 4 * c;
                bytes[o..o + 4].copy_from_slice(&x.to_le_bytes());
            }
        }
        let mesh = read(Path::new("t.stl"), &bytes).unwrap();
        assert_eq!(mesh.positions.len(), 3);
        assert_eq!(mesh.triangle_count(), 1);
    }
}

//! Wavefront OBJ: `v`, `vt`, `vn`, `f` with `v`, `v/vt`, `v//vn`, `v/vt/vn` corners,
//! 1-based or negative (relative) indices; polygons are kept. `g` and `o` (the group
//! name), `usemtl` (the material) and `mtllib` (kept in `Mesh::material_libraries`)
//! are read; every other statement is ignored.
//!
//! Vertices: where no face corner names a `vt` or a `vn`, vertex ids are the file's
//! `v` records, unreferenced ones kept. Otherwise corners are welded into GPU vertices:
//! one vertex per distinct `(v, vt, vn)` triple, numbered in order of first appearance
//! in the faces (so ids are renumbered and unreferenced `v` records dropped), with the
//! attributes `TEXCOORD_0` (2 `f32`, `v` stored as `1 - v`: glTF's top-left origin)
//! and `NORMAL` (3 `f32`); a corner without one in a file that has them gets zeros.
//! A seam (one position with two UVs or two normals) thus gives two vertices.
//!
//! Groups: faces after a `g`/`o` or `usemtl` statement belong to the group of that
//! (name, material) pair, numbered in order of first use; `Group::material` is the
//! `usemtl` name. A file without either (or only with an empty name) has no groups.
//!
//! Write: `mtllib`, `v`, `vt` (from `TEXCOORD_0`, `v` flipped back), `vn` (from
//! `NORMAL`), and faces in their order with `g`/`usemtl` where the group changes;
//! corners `i`, `i/i`, `i//i` or `i/i/i` (one index: every vertex carries its own
//! attributes). A read-back of the text gives the same mesh (texture `v` within one
//! rounding of the flip).

use super::common::{
    close_face, finite, index_message, is_space, line_at, line_end, parse_f32, parse_i64, show, sniff, Src,
};
use crate::error::Result;
use crate::mesh::{Attribute, Group, Mesh};
use std::collections::HashMap;
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

/// Statements of the OBJ specification that are read and ignored.
const OTHER_STATEMENTS: &[&[u8]] = &[
    b"vp",
    b"l",
    b"p",
    b"s",
    b"mg",
    b"usemap",
    b"maplib",
    b"cstype",
    b"deg",
    b"bmat",
    b"step",
    b"curv",
    b"curv2",
    b"surf",
    b"parm",
    b"trim",
    b"hole",
    b"scrv",
    b"sp",
    b"end",
    b"con",
    b"lod",
    b"shadow_obj",
    b"trace_obj",
    b"c_interp",
    b"d_interp",
    b"bevel",
    b"ctech",
    b"stech",
    b"call",
    b"csh",
];

/// No texture coordinate or normal at a corner.
const NONE: u32 = u32::MAX;

/// The group key of an OBJ face: its `g`/`o` name and its `usemtl` material.
type GroupKey = (String, Option<String>);

/// The rest of the line's tokens joined by single spaces (a name may hold spaces).
fn rest_of_line(c: &mut Cursor) -> String {
    let mut out = String::new();
    while let Some(tok) = c.token() {
        if !out.is_empty() {
            out.push(' ');
        }
        out.push_str(&String::from_utf8_lossy(tok));
    }
    out
}

/// Reads `n` finite coordinates of a `v`, `vt` or `vn` statement; coordinates past
/// `required` may be missing (then 0).
fn coords<const N: usize>(src: Src, c: &mut Cursor, ln: usize, what: &str, required: usize) -> Result<[f32; N]> {
    let mut p = [0.0f32; N];
    for (k, slot) in p.iter_mut().enumerate() {
        let Some(tok) = c.token() else {
            if k >= required {
                break;
            }
            return Err(src.err(line_at(ln), format!("{what} has {k} coordinates, needs {required}")));
        };
        let v = parse_f32(tok).ok_or_else(|| src.err(line_at(ln), format!("malformed number '{}'", show(tok))))?;
        *slot = finite(v, tok).map_err(|w| src.err(line_at(ln), w))?;
    }
    Ok(p)
}

/// Resolves one index of a face corner (1-based, or negative: relative to the `defined`
/// records of its kind so far) to 0-based; `what` names the kind in messages.
fn resolve(src: Src, ln: usize, part: &[u8], tok: &[u8], defined: usize, what: &str) -> Result<u32> {
    let idx = parse_i64(part).ok_or_else(|| src.err(line_at(ln), format!("malformed {what} index '{}'", show(tok))))?;
    let zero_based = if idx > 0 {
        idx - 1
    } else if idx < 0 {
        let r = defined as i64 + idx;
        if r < 0 {
            return Err(src.err(
                line_at(ln),
                format!("relative index {idx} reaches before the first {what} ({defined} defined so far)"),
            ));
        }
        r
    } else {
        return Err(src.err(line_at(ln), format!("{what} index 0 (OBJ indices start at 1)")));
    };
    if zero_based >= u32::MAX as i64 {
        return Err(src.err(line_at(ln), format!("{what} index {idx} is beyond any {what} the file can hold")));
    }
    Ok(zero_based as u32)
}

/// Parses an OBJ file held in memory; `positions_only`: no attributes, no groups, the
/// file's vertex ids (see [`super::ReadOptions::positions_only`]).
pub(crate) fn read(path: &Path, data: &[u8], positions_only: bool) -> Result<Mesh> {
    let src = Src { path };
    let mut mesh = Mesh::new();
    let mut uvs: Vec<[f32; 2]> = Vec::new();
    let mut normals: Vec<[f32; 3]> = Vec::new();
    // Per corner, the texture coordinate and normal (NONE where absent); empty until
    // the first corner that has one, then filled up to it.
    let mut corner_vt: Vec<u32> = Vec::new();
    let mut corner_vn: Vec<u32> = Vec::new();
    // Faces may name records defined later in the file, so positive indices are
    // range-checked once at the end; these are the largest seen (0-based).
    let (mut max_index, mut max_vt, mut max_vn) = (0u64, None::<u32>, None::<u32>);
    let mut key: GroupKey = (String::new(), None);
    let mut group_ids: HashMap<GroupKey, u32> = HashMap::new();
    let mut current: Option<u32> = None;
    // The material libraries named so far: a set, so that N `mtllib` names cost O(N)
    // (a search of the list per name took 44 s for 80,000 names).
    let mut libraries: std::collections::HashSet<String> = mesh.material_libraries.iter().cloned().collect();
    let mut c = Cursor { data, pos: 0 };
    let mut ln = 0;
    // Whether any comment or known statement was seen: a file without one that gives
    // an empty mesh is not OBJ at all.
    let mut recognised = false;
    while c.pos < data.len() {
        ln += 1;
        match c.token() {
            Some(b"v") => {
                let p = coords::<3>(src, &mut c, ln, "vertex", 3)?;
                if mesh.positions.len() >= u32::MAX as usize {
                    return Err(src.err(line_at(ln), "more than 4294967295 vertices"));
                }
                mesh.positions.push(p);
            }
            Some(b"vt" | b"vn") if positions_only => recognised = true,
            Some(b"vt") => {
                recognised = true;
                let t = coords::<2>(src, &mut c, ln, "texture coordinate", 1)?;
                if uvs.len() >= u32::MAX as usize - 1 {
                    return Err(src.err(line_at(ln), "more than 4294967294 texture coordinates"));
                }
                uvs.push(t);
            }
            Some(b"vn") => {
                recognised = true;
                let n = coords::<3>(src, &mut c, ln, "normal", 3)?;
                if normals.len() >= u32::MAX as usize - 1 {
                    return Err(src.err(line_at(ln), "more than 4294967294 normals"));
                }
                normals.push(n);
            }
            Some(b"f") => {
                let first = mesh.face_indices.len();
                while let Some(tok) = c.token() {
                    let mut parts = tok.splitn(3, |&b| b == b'/');
                    let vpart = parts.next().unwrap_or_default();
                    let v = resolve(src, ln, vpart, tok, mesh.positions.len(), "vertex")?;
                    max_index = max_index.max(v as u64);
                    let k = mesh.face_indices.len();
                    if positions_only {
                        mesh.face_indices.push(v);
                        continue;
                    }
                    if let Some(p) = parts.next().filter(|p| !p.is_empty()) {
                        let t = resolve(src, ln, p, tok, uvs.len(), "texture coordinate")?;
                        max_vt = max_vt.max(Some(t));
                        corner_vt.resize(k, NONE);
                        corner_vt.push(t);
                    }
                    if let Some(p) = parts.next().filter(|p| !p.is_empty()) {
                        let n = resolve(src, ln, p, tok, normals.len(), "normal")?;
                        max_vn = max_vn.max(Some(n));
                        corner_vn.resize(k, NONE);
                        corner_vn.push(n);
                    }
                    mesh.face_indices.push(v);
                }
                let k = mesh.face_indices.len() - first;
                if k < 3 {
                    return Err(src.err(line_at(ln), format!("face has {k} vertices, needs at least 3")));
                }
                close_face(&mut mesh).map_err(|w| src.err(line_at(ln), w))?;
                let g = match current {
                    Some(g) => g,
                    None => {
                        let n = group_ids.len() as u32;
                        let g = *group_ids.entry(key.clone()).or_insert(n);
                        if g == n {
                            mesh.groups.push(Group { name: key.0.clone(), material: key.1.clone() });
                        }
                        current = Some(g);
                        g
                    }
                };
                mesh.face_groups.push(g);
            }
            Some(b"g" | b"o") => {
                recognised = true;
                key.0 = rest_of_line(&mut c);
                current = None;
            }
            Some(b"usemtl") => {
                recognised = true;
                key.1 = Some(rest_of_line(&mut c)).filter(|m| !m.is_empty());
                current = None;
            }
            Some(b"mtllib") => {
                recognised = true;
                while let Some(tok) = c.token() {
                    let lib = String::from_utf8_lossy(tok).into_owned();
                    if !libraries.contains(&lib) {
                        libraries.insert(lib.clone());
                        mesh.material_libraries.push(lib);
                    }
                }
            }
            Some(tok) => recognised |= OTHER_STATEMENTS.contains(&tok),
            None => recognised |= c.at_comment(),
        }
        c.next_line();
    }
    if mesh.positions.is_empty() && mesh.face_count() == 0 {
        refuse_if_not_obj(src, data, recognised)?;
    }
    let corners =
        [(&corner_vt[..], max_vt, uvs.len(), "texture coordinate"), (&corner_vn[..], max_vn, normals.len(), "normal")];
    check_face_ranges(src, data, &mesh, max_index, corners)?;
    // One group without a name or material says nothing: leave the mesh ungrouped.
    if positions_only || (mesh.groups.len() == 1 && mesh.groups[0] == Group::default()) {
        mesh.groups.clear();
        mesh.face_groups.clear();
    }
    if !corner_vt.is_empty() || !corner_vn.is_empty() {
        weld(&mut mesh, &uvs, &normals, corner_vt, corner_vn);
    }
    Ok(mesh)
}

/// Checks the largest indices the faces gave (`max_index` for vertices; per corner
/// list of texture coordinates and normals, its largest and the number of records)
/// against the records of the whole file, faces being allowed to name records defined
/// later: the first face naming one past the last is the error, with its line.
fn check_face_ranges(
    src: Src,
    data: &[u8],
    mesh: &Mesh,
    max_index: u64,
    corners: [(&[u32], Option<u32>, usize, &str); 2],
) -> Result<()> {
    let nv = mesh.positions.len();
    if mesh.face_count() > 0 && max_index as usize >= nv {
        // Error path only: find the first offending face and its line.
        let face = mesh.faces().position(|f| f.iter().any(|&i| i as usize >= nv)).unwrap_or(0);
        let bad = mesh.face(face).iter().copied().find(|&i| i as usize >= nv).unwrap_or(0);
        let line = face_line(data, face);
        return Err(src.err(line_at(line), index_message(face as u64, bad as i64 + 1, nv)));
    }
    for (corners, max, len, what) in corners {
        if max.is_some_and(|m| m as usize >= len) {
            let at = corners.iter().position(|&t| t != NONE && t as usize >= len).unwrap_or(0);
            let face = mesh.face_offsets.partition_point(|&o| o as usize <= at).saturating_sub(1);
            let line = face_line(data, face);
            return Err(src.err(
                line_at(line),
                format!("face {face} refers to {what} {} but the file has {len}", corners[at] as u64 + 1),
            ));
        }
    }
    Ok(())
}

/// Makes GPU vertices of the corners' `(v, vt, vn)` triples: one vertex per distinct
/// triple, numbered in order of first appearance (unreferenced `v` records go), with
/// `TEXCOORD_0` (v flipped to glTF's top-left origin) where any corner has a `vt` and
/// `NORMAL` where any has a `vn`; a corner without one gets zeros.
fn weld(mesh: &mut Mesh, uvs: &[[f32; 2]], normals: &[[f32; 3]], mut vt: Vec<u32>, mut vn: Vec<u32>) {
    let corners = mesh.face_indices.len();
    let (has_vt, has_vn) = (!vt.is_empty(), !vn.is_empty());
    if has_vt {
        vt.resize(corners, NONE);
    }
    if has_vn {
        vn.resize(corners, NONE);
    }
    let mut ids: HashMap<(u32, u32, u32), u32> = HashMap::new();
    let mut positions = Vec::new();
    let mut uv_out = Vec::new();
    let mut n_out = Vec::new();
    for k in 0..corners {
        let v = mesh.face_indices[k];
        let t = if has_vt { vt[k] } else { NONE };
        let n = if has_vn { vn[k] } else { NONE };
        let next = positions.len() as u32;
        let id = *ids.entry((v, t, n)).or_insert(next);
        if id == next {
            positions.push(mesh.positions[v as usize]);
            if has_vt {
                let [u, w] = if t == NONE { [0.0, 0.0] } else { uvs[t as usize] };
                uv_out.extend_from_slice(&[u, flip_v(w)]);
            }
            if has_vn {
                n_out.extend_from_slice(&if n == NONE { [0.0; 3] } else { normals[n as usize] });
            }
        }
        mesh.face_indices[k] = id;
    }
    mesh.positions = positions;
    if has_vt {
        mesh.attributes.push(Attribute::from_f32("TEXCOORD_0", 2, &uv_out));
    }
    if has_vn {
        mesh.attributes.push(Attribute::from_f32("NORMAL", 3, &n_out));
    }
}

/// `1 - v`, between a file's bottom-left texture origin and glTF's top-left one (its
/// own inverse up to one rounding of `f32`).
pub(crate) fn flip_v(v: f32) -> f32 {
    (1.0 - v as f64) as f32
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

/// Encodes a mesh as OBJ text (1-based indices, polygons as they are): `mtllib`, `v`,
/// `vt` and `vn` from `TEXCOORD_0` and `NORMAL`, faces with `g`/`usemtl` where the
/// group changes.
pub(crate) fn write(mesh: &Mesh) -> Vec<u8> {
    let nv = mesh.positions.len();
    let uv = mesh.attribute("TEXCOORD_0").filter(|a| a.components >= 2 && a.len() == nv);
    let normal = mesh.attribute("NORMAL").filter(|a| a.components == 3 && a.len() == nv);
    let per_vertex = 1 + uv.is_some() as usize + normal.is_some() as usize;
    let mut out = Vec::with_capacity(nv * 32 * per_vertex + mesh.face_indices.len() * 8 * per_vertex + 64);
    out.extend_from_slice(format!("# written by stripkit: {} vertices, {} faces\n", nv, mesh.face_count()).as_bytes());
    for lib in &mesh.material_libraries {
        out.extend_from_slice(format!("mtllib {lib}\n").as_bytes());
    }
    for p in &mesh.positions {
        out.push(b'v');
        for &c in p {
            out.push(b' ');
            push_f32(&mut out, c);
        }
        out.push(b'\n');
    }
    // Components as their value (a normalized integer scaled to its range).
    let value = |a: &Attribute, v: usize, c: usize| (a.get(v, c) * a.unit()) as f32;
    if let Some(a) = uv {
        for v in 0..nv {
            out.extend_from_slice(b"vt ");
            push_f32(&mut out, value(a, v, 0));
            out.push(b' ');
            push_f32(&mut out, flip_v(value(a, v, 1)));
            out.push(b'\n');
        }
    }
    if let Some(a) = normal {
        for v in 0..nv {
            out.extend_from_slice(b"vn");
            for c in 0..3 {
                out.push(b' ');
                push_f32(&mut out, value(a, v, c));
            }
            out.push(b'\n');
        }
    }
    let grouped = !mesh.groups.is_empty();
    let mut last: Option<u32> = None;
    for (f, face) in mesh.faces().enumerate() {
        let g = mesh.group_of(f);
        if grouped && last != Some(g) {
            let group = mesh.groups.get(g as usize).cloned().unwrap_or_default();
            let before = last.and_then(|l| mesh.groups.get(l as usize));
            out.push(b'g');
            if !group.name.is_empty() {
                out.push(b' ');
                out.extend_from_slice(group.name.as_bytes());
            }
            out.push(b'\n');
            match &group.material {
                Some(m) => out.extend_from_slice(format!("usemtl {m}\n").as_bytes()),
                // A bare `usemtl` ends the material of the group before.
                None if before.is_some_and(|b| b.material.is_some()) => out.extend_from_slice(b"usemtl\n"),
                None => {}
            }
            last = Some(g);
        }
        out.push(b'f');
        for &i in face {
            out.push(b' ');
            push_u64(&mut out, i as u64 + 1);
            match (uv.is_some(), normal.is_some()) {
                (false, false) => {}
                (true, false) => {
                    out.push(b'/');
                    push_u64(&mut out, i as u64 + 1);
                }
                (false, true) => {
                    out.extend_from_slice(b"//");
                    push_u64(&mut out, i as u64 + 1);
                }
                (true, true) => {
                    out.push(b'/');
                    push_u64(&mut out, i as u64 + 1);
                    out.push(b'/');
                    push_u64(&mut out, i as u64 + 1);
                }
            }
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
        read(Path::new("t.obj"), text.as_bytes(), false)
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
        // Corners with a vt or vn are welded by their (v, vt, vn) triple: 13 distinct.
        assert_eq!(m.positions.len(), 13);
        let file = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let expect: [&[usize]; 5] = [&[0, 1, 2], &[0, 2, 3], &[0, 1, 3], &[1, 2, 3], &[0, 1, 2, 3]];
        for (f, want) in expect.iter().enumerate() {
            let got: Vec<[f32; 3]> = m.face(f).iter().map(|&v| m.positions[v as usize]).collect();
            let want: Vec<[f32; 3]> = want.iter().map(|&v| file[v]).collect();
            assert_eq!(got, want, "face {f}");
        }
        assert_eq!(m.face(0), &[0, 1, 2]);
        assert_eq!(m.face(4), &[0, 1, 2, 12]);
        let uv = m.attribute("TEXCOORD_0").unwrap();
        assert_eq!(uv.value(m.face(1)[0] as usize), vec![0.0, 1.0]); // vt 0 0, v flipped
        assert_eq!(uv.value(0), vec![0.0, 1.0]); // no vt at this corner: zeros
        assert_eq!(m.attribute("NORMAL").unwrap().value(m.face(2)[1] as usize), vec![0.0, 0.0, 1.0]);
        assert!(m.groups.is_empty() && m.face_groups.is_empty());
    }

    #[test]
    fn groups_and_materials_make_face_groups() {
        let text = "mtllib a.mtl b.mtl
v 0 0 0
v 1 0 0
v 0 1 0
f 1 2 3
g left side
usemtl red
f 1 2 3
\
                    usemtl blue
f 1 2 3
g left side
usemtl red
f 3 2 1
o other
usemtl
f 1 2 3
";
        let m = parse(text).unwrap();
        assert_eq!(m.material_libraries, vec!["a.mtl", "b.mtl"]);
        assert_eq!(m.face_groups, vec![0, 1, 2, 1, 3]);
        let g = |name: &str, mat: Option<&str>| Group { name: name.into(), material: mat.map(String::from) };
        assert_eq!(
            m.groups,
            vec![g("", None), g("left side", Some("red")), g("left side", Some("blue")), g("other", None)]
        );
        let back = parse(std::str::from_utf8(&write(&m)).unwrap()).unwrap();
        assert_eq!(back, m);
    }

    #[test]
    fn bad_texture_and_normal_indices_are_named() {
        let (at, what) = format_error(
            "v 0 0 0
v 1 0 0
v 0 1 0
vt 0 0
\nf 1/1 2/1 3/2
",
        );
        assert_eq!(at, "line 6");
        assert!(what.contains("texture coordinate 2") && what.contains("has 1"), "{what}");
        let (_, what) = format_error(
            "v 0 0 0
v 1 0 0
v 0 1 0
vn 0 0 1
f 1//1 2//-2 3//1
",
        );
        assert!(what.contains("relative index -2") && what.contains("normal"), "{what}");
        let (_, what) = format_error(
            "v 0 0 0
vt 0
vn 0 1
",
        );
        assert!(what.contains("normal has 2 coordinates"), "{what}");
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
        let back = read(Path::new("t.obj"), &write(&mesh), false).unwrap();
        assert_eq!(back, mesh);
        for (a, b) in back.positions.iter().flatten().zip(mesh.positions.iter().flatten()) {
            assert_eq!(a.to_bits(), b.to_bits());
        }
    }
}

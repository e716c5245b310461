//! Small byte-level helpers shared by the readers: error construction, line and token
//! splitting without allocation, number parsing, and checked face building.

use crate::error::Error;
use crate::mesh::Mesh;
use std::path::Path;

/// The file being read, so that every error names it.
#[derive(Clone, Copy)]
pub(crate) struct Src<'a> {
    pub path: &'a Path,
}

impl<'a> Src<'a> {
    /// A `Format` error at `at` saying `what`.
    pub fn err(&self, at: impl Into<String>, what: impl Into<String>) -> Error {
        Error::Format { path: self.path.to_path_buf(), at: at.into(), what: what.into() }
    }
}

/// "line N" for text formats.
pub(crate) fn line_at(line: usize) -> String {
    format!("line {line}")
}

/// Iterates over the lines of a text buffer with 1-based line numbers; `\r` before
/// `\n` is dropped. No allocation.
pub(crate) struct Lines<'a> {
    data: &'a [u8],
    pos: usize,
    line: usize,
}

impl<'a> Lines<'a> {
    pub fn new(data: &'a [u8]) -> Self {
        Lines { data, pos: 0, line: 0 }
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = (usize, &'a [u8]);
    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        if self.pos >= self.data.len() {
            return None;
        }
        let rest = &self.data[self.pos..];
        let (mut line, advance) = match rest.iter().position(|&b| b == b'\n') {
            Some(i) => (&rest[..i], i + 1),
            None => (rest, rest.len()),
        };
        if let [head @ .., b'\r'] = line {
            line = head;
        }
        self.pos += advance;
        self.line += 1;
        Some((self.line, line))
    }
}

#[inline]
pub(crate) fn is_space(b: u8) -> bool {
    b == b' ' || b == b'\t' || b == b'\r' || b == b'\x0c' || b == b'\x0b'
}

/// Whitespace-separated tokens of one line. No allocation.
#[inline]
pub(crate) fn tokens(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    line.split(|&b| is_space(b)).filter(|t| !t.is_empty())
}

/// The line without a trailing `#` comment.
#[inline]
pub(crate) fn strip_comment(line: &[u8]) -> &[u8] {
    match line.iter().position(|&b| b == b'#') {
        Some(i) => &line[..i],
        None => line,
    }
}

/// Shows a token in an error message (lossy, shortened).
pub(crate) fn show(tok: &[u8]) -> String {
    let s = String::from_utf8_lossy(&tok[..tok.len().min(40)]).into_owned();
    if tok.len() > 40 {
        format!("{s}...")
    } else {
        s
    }
}

/// Parses a decimal floating-point token; `None` when it is not a number. NaN and
/// infinities parse (callers reject them with their own message).
#[inline]
pub(crate) fn parse_f64(tok: &[u8]) -> Option<f64> {
    std::str::from_utf8(tok).ok()?.parse::<f64>().ok()
}

/// Parses a float token as `f32`, rounding correctly from its decimal text.
#[inline]
pub(crate) fn parse_f32(tok: &[u8]) -> Option<f32> {
    std::str::from_utf8(tok).ok()?.parse::<f32>().ok()
}

/// Parses a decimal integer with optional sign; `None` on anything else or overflow.
#[inline]
pub(crate) fn parse_i64(tok: &[u8]) -> Option<i64> {
    let (neg, digits) = match tok.first()? {
        b'-' => (true, &tok[1..]),
        b'+' => (false, &tok[1..]),
        _ => (false, tok),
    };
    // More than 18 digits could overflow i64; no mesh file needs them.
    if digits.is_empty() || digits.len() > 18 {
        return None;
    }
    let mut v: i64 = 0;
    for &d in digits {
        if !d.is_ascii_digit() {
            return None;
        }
        v = v * 10 + (d - b'0') as i64;
    }
    Some(if neg { -v } else { v })
}

/// Parses a non-negative decimal count.
pub(crate) fn parse_count(tok: &[u8]) -> Option<u64> {
    let v = parse_i64(tok)?;
    u64::try_from(v).ok()
}

/// Passes a finite coordinate through; NaN and infinities give a message naming the
/// token.
pub(crate) fn finite(v: f32, tok: &[u8]) -> Result<f32, String> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("coordinate '{}' is NaN or infinite", show(tok)))
    }
}

/// Capacity to reserve for `announced` records when the remaining input of `bytes`
/// bytes needs at least `min_bytes_each` per record: never more than the file can hold.
pub(crate) fn capped(announced: u64, bytes: usize, min_bytes_each: usize) -> usize {
    let most = (bytes / min_bytes_each.max(1)) as u64;
    announced.min(most) as usize
}

/// Appends a face to `mesh`, checking the total index count fits `u32`.
#[inline]
pub(crate) fn close_face(mesh: &mut Mesh) -> Result<(), String> {
    let n = mesh.face_indices.len();
    if n > u32::MAX as usize {
        return Err("the file holds more than 4294967295 face indices".into());
    }
    mesh.face_offsets.push(n as u32);
    Ok(())
}

/// Pushes the non-degenerate triangles of a strip (METRICS.md rule) as faces.
pub(crate) fn push_strip_triangles(mesh: &mut Mesh, strip: &[u32]) -> Result<(), String> {
    let mut err = None;
    crate::strip::for_each_triangle(strip, |t| {
        if err.is_none() {
            mesh.face_indices.extend_from_slice(&t);
            if let Err(e) = close_face(mesh) {
                err = Some(e);
            }
        }
    });
    err.map_or(Ok(()), Err)
}

/// Pushes the non-degenerate triangles of a fan `(f[0], f[i+1], f[i+2])` as faces.
pub(crate) fn push_fan_triangles(mesh: &mut Mesh, fan: &[u32]) -> Result<(), String> {
    for i in 1..fan.len().saturating_sub(1) {
        let t = [fan[0], fan[i], fan[i + 1]];
        if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
            mesh.face_indices.extend_from_slice(&t);
            close_face(mesh)?;
        }
    }
    Ok(())
}

/// The message for an index out of range.
pub(crate) fn index_message(face: usize, index: u64, vertices: usize) -> String {
    format!("face {face} refers to vertex {index} but the file has {vertices} vertices")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_number_from_one_and_drop_carriage_returns() {
        let v: Vec<_> = Lines::new(b"a\r\nb\n\nc").collect();
        assert_eq!(v, vec![(1, &b"a"[..]), (2, &b"b"[..]), (3, &b""[..]), (4, &b"c"[..])]);
    }

    #[test]
    fn integers_parse_with_sign_and_reject_junk() {
        assert_eq!(parse_i64(b"-12"), Some(-12));
        assert_eq!(parse_i64(b"+7"), Some(7));
        assert_eq!(parse_i64(b"1x"), None);
        assert_eq!(parse_i64(b"-"), None);
        assert_eq!(parse_i64(b"99999999999999999999999"), None);
    }

    #[test]
    fn reservations_never_exceed_what_the_bytes_can_hold() {
        assert_eq!(capped(u64::MAX, 100, 10), 10);
        assert_eq!(capped(3, 100, 10), 3);
        assert_eq!(capped(5, 100, 0), 5);
    }
}

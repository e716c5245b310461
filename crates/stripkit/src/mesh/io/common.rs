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

/// Iterates over the lines of a text buffer with 1-based line numbers. A line ends at
/// `\n`, `\r\n` or a lone `\r` (old Mac files). No allocation.
pub(crate) struct Lines<'a> {
    data: &'a [u8],
    pos: usize,
    line: usize,
}

impl<'a> Lines<'a> {
    pub fn new(data: &'a [u8]) -> Self {
        Lines { data, pos: 0, line: 0 }
    }

    /// Byte offset of the next line.
    pub fn offset(&self) -> usize {
        self.pos
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
        let (line, advance) = match line_end(rest) {
            Some((i, n)) => (&rest[..i], i + n),
            None => (rest, rest.len()),
        };
        self.pos += advance;
        self.line += 1;
        Some((self.line, line))
    }
}

/// The first line end in `data`: its position and length (1 for `\n` or a lone `\r`,
/// 2 for `\r\n`).
#[inline]
pub(crate) fn line_end(data: &[u8]) -> Option<(usize, usize)> {
    let i = data.iter().position(|&b| b == b'\n' || b == b'\r')?;
    Some((i, if data[i] == b'\r' && data.get(i + 1) == Some(&b'\n') { 2 } else { 1 }))
}

/// True when `data[i]` ends a line: `\n`, or a `\r` not followed by `\n` (the `\n`
/// of `\r\n` ends it). For counting lines while scanning bytes one by one.
#[inline]
pub(crate) fn ends_line(data: &[u8], i: usize) -> bool {
    data[i] == b'\n' || (data[i] == b'\r' && data.get(i + 1) != Some(&b'\n'))
}

/// What the start of `data` looks like when it is not the text a reader expected,
/// for refusing it by name: a UTF-16 byte order mark or layout, another mesh format's
/// signature, compressed or binary data. `None` when nothing stands out.
pub(crate) fn sniff(data: &[u8]) -> Option<String> {
    if let Some(bom) = utf16_bom(data) {
        return Some(format!("the file is UTF-16 ({bom}); save it as UTF-8"));
    }
    let head = &data[..data.len().min(1024)];
    // UTF-16 without a byte order mark: ASCII text with every other byte 0.
    if head.len() >= 8 {
        let pairs = head.len() / 2;
        let zero_odd = head.chunks_exact(2).filter(|p| p[1] == 0 && p[0] != 0).count();
        let zero_even = head.chunks_exact(2).filter(|p| p[0] == 0 && p[1] != 0).count();
        if zero_odd * 10 >= pairs * 9 || zero_even * 10 >= pairs * 9 {
            let order = if zero_odd > zero_even { "little-endian" } else { "big-endian" };
            return Some(format!("the file looks like UTF-16 ({order}, every other byte is 0); save it as UTF-8"));
        }
    }
    if head.starts_with(b"\x1f\x8b") {
        return Some("the file starts with the gzip signature: it is compressed (name it with a .gz suffix)".into());
    }
    if head.starts_with(b"glTF") {
        return Some("the file starts with 'glTF': this is a binary glTF (.glb) file".into());
    }
    let text = head.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(head);
    let start = text.iter().position(|&b| !is_space(b) && b != b'\n').unwrap_or(text.len());
    let first = text[start..].split(|&b| is_space(b) || b == b'\n').next().unwrap_or_default();
    if first == b"ply" {
        return Some("the file starts with 'ply': this is a PLY file".into());
    }
    if first.ends_with(b"OFF") && first.len() <= 6 && first.iter().all(|b| b"STCN4OF".contains(b)) {
        return Some(format!("the file starts with '{}': this is an OFF file", show(first)));
    }
    if first == b"solid" {
        return Some("the file starts with 'solid': this looks like an ASCII STL file".into());
    }
    if text[start..].starts_with(b"{") {
        return Some("the file starts with '{': this looks like JSON (a .gltf file?)".into());
    }
    if let Some(i) = head.iter().position(|&b| b == 0 || (b < 0x20 && !is_space(b) && b != b'\n')) {
        return Some(format!("the file looks like binary data (byte {i} is 0x{:02x}), not text", head[i]));
    }
    None
}

/// "byte order mark FF FE" when `data` starts with a UTF-16 byte order mark.
pub(crate) fn utf16_bom(data: &[u8]) -> Option<&'static str> {
    if data.starts_with(b"\xFF\xFE") {
        Some("little-endian, byte order mark FF FE")
    } else if data.starts_with(b"\xFE\xFF") {
        Some("big-endian, byte order mark FE FF")
    } else {
        None
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

/// Shows a token in an error message (lossy, shortened, control characters such as
/// NUL escaped so that they are visible: `\0`, `\u{1}`).
pub(crate) fn show(tok: &[u8]) -> String {
    let s: String = String::from_utf8_lossy(&tok[..tok.len().min(40)])
        .chars()
        .flat_map(|c| {
            let escaped = c.is_control().then(|| c.escape_debug());
            let plain = (!c.is_control()).then_some(c);
            escaped.into_iter().flatten().chain(plain)
        })
        .collect();
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
    match short_decimal(tok) {
        Some(v) => Some(v),
        None => std::str::from_utf8(tok).ok()?.parse::<f32>().ok(),
    }
}

/// Powers of ten exactly representable in `f32` (5^10 < 2^24).
const POW10_F32: [f32; 11] = [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10];

/// Fast path for the common `[-+]digits[.digits]` with a mantissa below 2^24 and at
/// most ten decimals: mantissa and power of ten are exact in `f32`, so one IEEE
/// division rounds correctly, exactly as the full parser would. `None` otherwise.
#[inline]
fn short_decimal(tok: &[u8]) -> Option<f32> {
    let (neg, digits) = match tok.first()? {
        b'-' => (true, &tok[1..]),
        b'+' => (false, &tok[1..]),
        _ => (false, tok),
    };
    let mut mantissa: u32 = 0;
    let mut decimals: usize = 0;
    let mut seen_digit = false;
    let mut seen_dot = false;
    for &c in digits {
        if c.is_ascii_digit() {
            mantissa = mantissa * 10 + (c - b'0') as u32;
            if mantissa >= 1 << 24 {
                return None;
            }
            seen_digit = true;
            decimals += seen_dot as usize;
        } else if c == b'.' && !seen_dot {
            seen_dot = true;
        } else {
            return None;
        }
    }
    if !seen_digit || decimals > 10 {
        return None;
    }
    let v = mantissa as f32 / POW10_F32[decimals];
    Some(if neg { -v } else { v })
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

/// Pushes the non-degenerate triangles of a strip (the reading rule of docs/metrics.md) as faces.
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
pub(crate) fn index_message(face: u64, index: i64, vertices: usize) -> String {
    format!("face {face} refers to vertex {index} but the file has {vertices} vertices")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_number_from_one_and_drop_carriage_returns() {
        let v: Vec<_> = Lines::new(b"a\r\nb\n\nc").collect();
        assert_eq!(v, vec![(1, &b"a"[..]), (2, &b"b"[..]), (3, &b""[..]), (4, &b"c"[..])]);
        let v: Vec<_> = Lines::new(b"a\rb\r\rc\r").collect();
        assert_eq!(v, vec![(1, &b"a"[..]), (2, &b"b"[..]), (3, &b""[..]), (4, &b"c"[..])]);
    }

    #[test]
    fn control_characters_are_shown_escaped() {
        assert_eq!(show(b"1\x002"), "1\\02");
        assert_eq!(show(b"a\x01"), "a\\u{1}");
        assert_eq!(show("x\u{e9}".as_bytes()), "x\u{e9}");
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
    fn the_float_fast_path_agrees_with_the_full_parser() {
        let mut state = 12345u64;
        let mut tokens: Vec<String> = ["0", "-0", "-0.0", "1.", ".5", "+2.25", "16777215", "16777216", "0.0000000001",
            "1234567.", "0.1234567", "9.999999", "-8388608.5", "1e5", "1.0e-3", "12.34.5", "", "-", ".", "1a"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        for _ in 0..200_000 {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            let m = (state >> 40) % 30_000_000;
            let d = ((state >> 20) % 12) as usize;
            let mut t = m.to_string();
            if d > 0 {
                while t.len() <= d {
                    t.insert(0, '0');
                }
                t.insert(t.len() - d, '.');
            }
            if state & 1 == 1 {
                t.insert(0, '-');
            }
            tokens.push(t);
        }
        for t in &tokens {
            let full = t.parse::<f32>().ok();
            let fast = parse_f32(t.as_bytes());
            assert_eq!(fast.map(f32::to_bits), full.map(f32::to_bits), "{t}");
        }
    }

    #[test]
    fn reservations_never_exceed_what_the_bytes_can_hold() {
        assert_eq!(capped(u64::MAX, 100, 10), 10);
        assert_eq!(capped(3, 100, 10), 3);
        assert_eq!(capped(5, 100, 0), 5);
    }
}

//! The body of a PLY file read value by value, as ASCII text or as binary (little- or
//! big-endian): the one interface the element readers read through; and the PLY names
//! of the value types.

use crate::mesh::io::common::{ends_line, is_space, line_at, line_end, parse_f32, parse_f64, parse_i64, show};
use crate::mesh::Scalar;

/// The attribute type of a PLY type name (`uchar`, `float32`, ...).
pub(super) fn parse_type(name: &[u8]) -> Option<Scalar> {
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
pub(super) fn type_name(s: Scalar) -> &'static str {
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

/// The body of a PLY file, read value by value.
pub(super) trait Body {
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
    /// A binary body's bytes (the whole file), the reading position in them and
    /// whether it is big-endian, for readers that take whole records; `None` for text.
    fn binary(&self) -> Option<(&[u8], usize, bool)> {
        None
    }
    /// Moves a binary body's reading position to `pos` (past records read through
    /// [`Body::binary`]).
    fn seek(&mut self, _pos: usize) {}
}

pub(super) struct Ascii<'a> {
    pub(super) data: &'a [u8],
    pub(super) pos: usize,
    pub(super) line: usize,
    /// Line of the last token read.
    pub(super) token_line: usize,
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
            None if s.is_float() => match parse_f64(tok) {
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
            Scalar::F64 => out.copy_from_slice(&parse_f64(tok).ok_or_else(bad)?.to_le_bytes()),
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

pub(super) struct Binary<'a> {
    pub(super) data: &'a [u8],
    pub(super) pos: usize,
    pub(super) big: bool,
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
        let end = self.pos + s.size();
        let b = self
            .data
            .get(self.pos..end)
            .ok_or_else(|| format!("the file ends early (truncated at byte {})", self.data.len()))?;
        self.pos = end;
        Ok(number(b, s, self.big))
    }
}

/// A binary value of type `s` at the start of `b` (which holds at least `s.size()`
/// bytes), big- or little-endian: the one decoding of a scalar, for the value-by-value
/// reader and the whole-record path alike.
#[inline]
pub(super) fn number(b: &[u8], s: Scalar, big: bool) -> f64 {
    macro_rules! num {
        ($t:ty, $n:literal) => {{
            let bytes: [u8; $n] = b[..$n].try_into().unwrap_or([0; $n]);
            (if big { <$t>::from_be_bytes(bytes) } else { <$t>::from_le_bytes(bytes) }) as f64
        }};
    }
    match s {
        Scalar::I8 => num!(i8, 1),
        Scalar::U8 => num!(u8, 1),
        Scalar::I16 => num!(i16, 2),
        Scalar::U16 => num!(u16, 2),
        Scalar::I32 => num!(i32, 4),
        Scalar::U32 => num!(u32, 4),
        Scalar::F32 => num!(f32, 4),
        Scalar::F64 => num!(f64, 8),
    }
}

impl Body for Binary<'_> {
    fn binary(&self) -> Option<(&[u8], usize, bool)> {
        Some((self.data, self.pos, self.big))
    }
    fn seek(&mut self, pos: usize) {
        self.pos = pos;
    }
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
        // Through the one decoding of a scalar: every integer type of PLY (at most 32
        // bits) is exact as f64; a float must hold a whole number.
        let v = self.value(s)?;
        if matches!(s, Scalar::F32 | Scalar::F64) && (v.fract() != 0.0 || v.abs() >= 1e15) {
            return Err(format!("{v} is not an integer"));
        }
        Ok(v as i64)
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

//! The `EXT_meshopt_compression` codecs, decoded: the vertex codec (version 0), the
//! index codec (triangles, versions 0 and 1), the index-sequence codec, and the
//! octahedral, quaternion and exponential filters, written from the extension's
//! bitstream description (KhronosGroup glTF, `extensions/2.0/Vendor/EXT_meshopt_compression`).
//!
//! Every read is bounds-checked: a hostile stream gives an error naming the byte, never
//! a panic, and the output is exactly `count * stride` bytes, allocated by the caller's
//! decision (the glTF reader charges it to its decoded-bytes budget first). A stream
//! that decodes must end exactly where the format says (the tail), as the reference
//! decoder requires. Checked byte for byte against meshoptimizer's encoder in
//! `stripkit-bench` (`tests/meshopt_codec.rs`).

use crate::error::{Error, Result};
use std::path::PathBuf;

/// How a compressed buffer view is encoded (`mode` of `EXT_meshopt_compression`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum MeshoptMode {
    /// `ATTRIBUTES`: vertex data, `stride` a multiple of 4 up to 256.
    Attributes,
    /// `TRIANGLES`: a triangle list's indices, `stride` 2 or 4, `count` a multiple of 3.
    Triangles,
    /// `INDICES`: any index sequence (strips, lines), `stride` 2 or 4.
    Indices,
}

/// The filter applied after decoding (`filter` of `EXT_meshopt_compression`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum MeshoptFilter {
    /// `NONE`.
    None,
    /// `OCTAHEDRAL`: unit vectors, four 8-bit (stride 4) or 16-bit (stride 8) components.
    Octahedral,
    /// `QUATERNION`: unit quaternions, four 16-bit components (stride 8).
    Quaternion,
    /// `EXPONENTIAL`: floats as 8-bit exponent and 24-bit mantissa (stride a multiple of 4).
    Exponential,
}

impl MeshoptMode {
    /// The mode a glTF file names (`"ATTRIBUTES"`, `"TRIANGLES"`, `"INDICES"`).
    pub fn from_name(name: &str) -> Option<MeshoptMode> {
        match name {
            "ATTRIBUTES" => Some(MeshoptMode::Attributes),
            "TRIANGLES" => Some(MeshoptMode::Triangles),
            "INDICES" => Some(MeshoptMode::Indices),
            _ => None,
        }
    }
}

impl MeshoptFilter {
    /// The filter a glTF file names (`"NONE"`, `"OCTAHEDRAL"`, `"QUATERNION"`, `"EXPONENTIAL"`).
    pub fn from_name(name: &str) -> Option<MeshoptFilter> {
        match name {
            "NONE" => Some(MeshoptFilter::None),
            "OCTAHEDRAL" => Some(MeshoptFilter::Octahedral),
            "QUATERNION" => Some(MeshoptFilter::Quaternion),
            "EXPONENTIAL" => Some(MeshoptFilter::Exponential),
            _ => None,
        }
    }
}

/// Decodes `encoded` into `count` elements of `stride` bytes, then applies `filter`.
/// Errors ([`Error::Format`] at the byte where the stream went wrong) for a stride the
/// mode does not allow, a filter the mode or stride does not allow, an unknown header
/// or version (vertex codec version 1 included), and a stream that runs short or long.
/// Cost: linear in `encoded.len() + count * stride`; the output is allocated once.
pub fn decode_meshopt(
    encoded: &[u8],
    count: usize,
    stride: usize,
    mode: MeshoptMode,
    filter: MeshoptFilter,
) -> Result<Vec<u8>> {
    decode(encoded, count, stride, mode, filter).map_err(|(at, what)| Error::Format {
        path: PathBuf::from("<EXT_meshopt_compression stream>"),
        at,
        what,
    })
}

/// Where a stream went wrong ("byte N") and what is wrong.
pub(crate) type Fault = (String, String);

fn fault(at: usize, what: impl Into<String>) -> Fault {
    (format!("byte {at}"), what.into())
}

/// [`decode_meshopt`] with the fault as (place, message), for the glTF reader to name
/// its buffer view.
pub(crate) fn decode(
    encoded: &[u8],
    count: usize,
    stride: usize,
    mode: MeshoptMode,
    filter: MeshoptFilter,
) -> std::result::Result<Vec<u8>, Fault> {
    let stride_ok = match mode {
        MeshoptMode::Attributes => stride % 4 == 0 && (4..=256).contains(&stride),
        MeshoptMode::Triangles | MeshoptMode::Indices => stride == 2 || stride == 4,
    };
    if !stride_ok {
        return Err(fault(0, format!("byteStride {stride} is not allowed for mode {mode:?}")));
    }
    let filter_ok = match filter {
        MeshoptFilter::None => true,
        MeshoptFilter::Octahedral => mode == MeshoptMode::Attributes && (stride == 4 || stride == 8),
        MeshoptFilter::Quaternion => mode == MeshoptMode::Attributes && stride == 8,
        MeshoptFilter::Exponential => mode == MeshoptMode::Attributes,
    };
    if !filter_ok {
        return Err(fault(0, format!("filter {filter:?} is not allowed with mode {mode:?} and byteStride {stride}")));
    }
    let size = count.checked_mul(stride).ok_or_else(|| fault(0, "count x byteStride overflows"))?;
    let mut out = vec![0u8; size];
    match mode {
        MeshoptMode::Attributes => decode_vertices(encoded, count, stride, &mut out)?,
        MeshoptMode::Triangles => {
            if count % 3 != 0 {
                return Err(fault(0, format!("TRIANGLES needs a multiple of 3 indices, not {count}")));
            }
            let indices = decode_triangles(encoded, count)?;
            store_indices(&indices, stride, &mut out);
        }
        MeshoptMode::Indices => {
            let indices = decode_sequence(encoded, count)?;
            store_indices(&indices, stride, &mut out);
        }
    }
    match filter {
        MeshoptFilter::None => {}
        MeshoptFilter::Octahedral if stride == 4 => filter_octahedral_8(&mut out),
        MeshoptFilter::Octahedral => filter_octahedral_16(&mut out),
        MeshoptFilter::Quaternion => filter_quaternion(&mut out),
        MeshoptFilter::Exponential => filter_exponential(&mut out),
    }
    Ok(out)
}

fn store_indices(indices: &[u32], stride: usize, out: &mut [u8]) {
    for (slot, &i) in out.chunks_exact_mut(stride).zip(indices) {
        if stride == 2 {
            slot.copy_from_slice(&(i as u16).to_le_bytes());
        } else {
            slot.copy_from_slice(&i.to_le_bytes());
        }
    }
}

/// A cursor over a stream that may not read at or past `end`.
struct Reader<'a> {
    data: &'a [u8],
    pos: usize,
    end: usize,
}

impl Reader<'_> {
    fn byte(&mut self) -> std::result::Result<u8, Fault> {
        if self.pos >= self.end {
            return Err(fault(self.pos, "the stream ends too early"));
        }
        self.pos += 1;
        Ok(self.data[self.pos - 1])
    }

    fn take(&mut self, n: usize) -> std::result::Result<&[u8], Fault> {
        if self.end - self.pos < n {
            return Err(fault(self.pos, "the stream ends too early"));
        }
        self.pos += n;
        Ok(&self.data[self.pos - n..self.pos])
    }

    /// A little-endian base-128 integer of at most 5 bytes (the fifth ends it whatever
    /// its top bit; bits past 32 are dropped), as the reference decoder reads it.
    fn varint(&mut self) -> std::result::Result<u32, Fault> {
        let mut v = 0u32;
        for shift in (0..35).step_by(7) {
            let b = self.byte()?;
            v |= ((b & 0x7f) as u32).wrapping_shl(shift);
            if b < 0x80 {
                break;
            }
        }
        Ok(v)
    }

    fn finish(&self) -> std::result::Result<(), Fault> {
        if self.pos != self.end {
            return Err(fault(self.pos, format!("{} bytes are left over before the tail", self.end - self.pos)));
        }
        Ok(())
    }
}

fn unzigzag8(v: u8) -> u8 {
    (v >> 1) ^ (v & 1).wrapping_neg()
}

fn unzigzag32(v: u32) -> u32 {
    (v >> 1) ^ (v & 1).wrapping_neg()
}

/// Vertex codec, version 0 (header 0xA0): blocks of vertices, each byte of the vertex
/// a channel of zigzag deltas from the previous vertex, packed in groups of 16 at
/// 0, 2, 4 or 8 bits. The first "previous vertex" is the stream's last `stride` bytes.
fn decode_vertices(data: &[u8], count: usize, stride: usize, out: &mut [u8]) -> std::result::Result<(), Fault> {
    match data.first() {
        Some(0xA0) => {}
        Some(0xA1) => return Err(fault(0, "vertex codec version 1 is not supported (only version 0)")),
        Some(h) => return Err(fault(0, format!("header byte {h:#04x} is not a vertex stream (0xa0)"))),
        None => return Err(fault(0, "the stream is empty")),
    }
    let tail = stride.max(32);
    if data.len() < 1 + tail {
        return Err(fault(0, format!("{} bytes cannot hold a header and a {tail}-byte tail", data.len())));
    }
    let end = data.len() - tail;
    let mut last = data[data.len() - stride..].to_vec();
    let block = ((8192 / stride) & !15).min(256);
    let mut reader = Reader { data, pos: 1, end };
    let mut deltas = [0u8; 256];
    let mut first = 0;
    while first < count {
        let n = block.min(count - first);
        let aligned = (n + 15) & !15;
        for (k, prev) in last.iter_mut().enumerate() {
            decode_channel(&mut reader, &mut deltas[..aligned])?;
            let mut p = *prev;
            for (i, &d) in deltas[..n].iter().enumerate() {
                p = p.wrapping_add(unzigzag8(d));
                out[(first + i) * stride + k] = p;
            }
            *prev = p;
        }
        first += n;
    }
    reader.finish()
}

/// One channel of a block: 2-bit group modes (4 per byte, low bits first), then each
/// group's bytes: none (zeros), 2 or 4 bits per value (high bits first; the largest
/// value means "read the next byte after the packed ones"), or 16 bytes as they are.
fn decode_channel(reader: &mut Reader, out: &mut [u8]) -> std::result::Result<(), Fault> {
    let groups = out.len() / 16;
    let header = reader.take(groups.div_ceil(4))?.to_vec();
    for (g, group) in out.chunks_exact_mut(16).enumerate() {
        match (header[g / 4] >> ((g % 4) * 2)) & 3 {
            0 => group.fill(0),
            3 => group.copy_from_slice(reader.take(16)?),
            mode => {
                let bits = if mode == 1 { 2 } else { 4 };
                let per_byte = 8 / bits;
                let sentinel = (1u8 << bits) - 1;
                let packed = reader.take(16 / per_byte)?.to_vec();
                for (i, slot) in group.iter_mut().enumerate() {
                    let shift = 8 - bits * (i % per_byte + 1);
                    let v = (packed[i / per_byte] >> shift) & sentinel;
                    *slot = if v == sentinel { reader.byte()? } else { v };
                }
            }
        }
    }
    Ok(())
}

/// Index codec (header 0xE0 or 0xE1): one code byte per triangle, then variable-length
/// data, then a 16-byte table of auxiliary codes. Triangles are rebuilt from a FIFO of
/// 16 recent edges and one of 16 recent vertices.
fn decode_triangles(data: &[u8], count: usize) -> std::result::Result<Vec<u32>, Fault> {
    let version = match data.first() {
        Some(&h) if h & 0xf0 == 0xE0 && h & 0x0f <= 1 => h & 0x0f,
        Some(&h) => return Err(fault(0, format!("header byte {h:#04x} is not a triangle index stream (0xe0, 0xe1)"))),
        None => return Err(fault(0, "the stream is empty")),
    };
    let triangles = count / 3;
    if data.len() < 1 + triangles + 16 {
        return Err(fault(0, format!("{} bytes cannot hold {triangles} triangle codes and the tail", data.len())));
    }
    let end = data.len() - 16;
    let codeaux = &data[end..];
    let codes = &data[1..1 + triangles];
    let mut reader = Reader { data, pos: 1 + triangles, end };
    let mut edges = [[u32::MAX; 2]; 16];
    let mut edge_at = 0usize;
    let mut verts = [u32::MAX; 16];
    let mut vert_at = 0usize;
    let (mut next, mut last) = (0u32, 0u32);
    let fecmax = if version >= 1 { 13 } else { 15 };
    let mut out = Vec::with_capacity(count);
    fn push_vert(verts: &mut [u32; 16], at: &mut usize, v: u32, cond: bool) {
        verts[*at] = v;
        *at = (*at + cond as usize) & 15;
    }
    fn index(reader: &mut Reader, last: u32) -> std::result::Result<u32, Fault> {
        Ok(last.wrapping_add(unzigzag32(reader.varint()?)))
    }
    for &code in codes {
        let (a, b, c);
        if code < 0xf0 {
            let edge = edges[(edge_at.wrapping_sub(1 + (code >> 4) as usize)) & 15];
            (a, b) = (edge[0], edge[1]);
            let fec = (code & 15) as usize;
            if fec < fecmax {
                c = if fec == 0 { next } else { verts[(vert_at.wrapping_sub(1 + fec)) & 15] };
                next += (fec == 0) as u32;
                push_vert(&mut verts, &mut vert_at, c, fec == 0);
            } else {
                c = match fec {
                    13 => last.wrapping_sub(1),
                    14 => last.wrapping_add(1),
                    _ => index(&mut reader, last)?,
                };
                last = c;
                push_vert(&mut verts, &mut vert_at, c, true);
            }
            edges[edge_at] = [c, b];
            edge_at = (edge_at + 1) & 15;
            edges[edge_at] = [a, c];
            edge_at = (edge_at + 1) & 15;
        } else {
            let aux = if code < 0xfe { codeaux[(code & 15) as usize] } else { reader.byte()? };
            let fea = if code == 0xff { 15 } else { 0 };
            let (feb, fec) = ((aux >> 4) as usize, (aux & 15) as usize);
            let fifo = |fe: usize| verts[(vert_at.wrapping_sub(fe)) & 15];
            let mut pick = |fe: usize| {
                if fe == 0 {
                    next += 1;
                    next - 1
                } else {
                    fifo(fe)
                }
            };
            let (mut pa, mut pb, mut pc) = (if fea == 0 { pick(0) } else { 0 }, pick(feb), pick(fec));
            if code >= 0xfe {
                if fea == 15 {
                    pa = index(&mut reader, last)?;
                    last = pa;
                }
                if feb == 15 {
                    pb = index(&mut reader, last)?;
                    last = pb;
                }
                if fec == 15 {
                    pc = index(&mut reader, last)?;
                    last = pc;
                }
            }
            (a, b, c) = (pa, pb, pc);
            let fresh = |fe: usize| fe == 0 || (code >= 0xfe && fe == 15);
            push_vert(&mut verts, &mut vert_at, a, true);
            push_vert(&mut verts, &mut vert_at, b, fresh(feb));
            push_vert(&mut verts, &mut vert_at, c, fresh(fec));
            for e in [[b, a], [c, b], [a, c]] {
                edges[edge_at] = e;
                edge_at = (edge_at + 1) & 15;
            }
        }
        out.extend_from_slice(&[a, b, c]);
    }
    reader.finish()?;
    Ok(out)
}

/// Index-sequence codec (header 0xD0 or 0xD1): per index a variable-length integer whose
/// low bit picks one of two baselines and whose rest is a zigzag delta from it; a 4-byte
/// tail follows.
fn decode_sequence(data: &[u8], count: usize) -> std::result::Result<Vec<u32>, Fault> {
    match data.first() {
        Some(&h) if h & 0xf0 == 0xD0 && h & 0x0f <= 1 => {}
        Some(&h) => return Err(fault(0, format!("header byte {h:#04x} is not an index sequence (0xd0, 0xd1)"))),
        None => return Err(fault(0, "the stream is empty")),
    }
    if data.len() < 1 + 4 {
        return Err(fault(0, format!("{} bytes cannot hold a header and the 4-byte tail", data.len())));
    }
    let mut reader = Reader { data, pos: 1, end: data.len() - 4 };
    let mut baseline = [0u32; 2];
    let mut out = Vec::with_capacity(count.min(data.len()));
    for _ in 0..count {
        let v = reader.varint()?;
        let which = (v & 1) as usize;
        let i = baseline[which].wrapping_add(unzigzag32(v >> 1));
        baseline[which] = i;
        out.push(i);
    }
    reader.finish()?;
    Ok(out)
}

/// Rounds to the nearest integer, halves away from zero, as the reference filters do.
fn round(x: f32) -> i32 {
    (x + if x >= 0.0 { 0.5 } else { -0.5 }) as i32
}

/// Octahedral unit vectors: x and y stored, the third component holds 1.0 at the same
/// bit count; z is rebuilt and the vector normalized to the components' full range.
fn octahedral(x: f32, y: f32, one: f32, max: f32) -> [i32; 3] {
    let (mut x, mut y) = (x, y);
    let z = one - x.abs() - y.abs();
    let t = if z < 0.0 { z } else { 0.0 };
    x += if x >= 0.0 { t } else { -t };
    y += if y >= 0.0 { t } else { -t };
    let l = (x * x + y * y + z * z).sqrt();
    let s = max / l;
    [round(x * s), round(y * s), round(z * s)]
}

fn filter_octahedral_8(data: &mut [u8]) {
    for v in data.chunks_exact_mut(4) {
        let c = |k: usize| v[k] as i8 as f32;
        let r = octahedral(c(0), c(1), c(2), 127.0);
        for k in 0..3 {
            v[k] = r[k] as i8 as u8;
        }
    }
}

fn filter_octahedral_16(data: &mut [u8]) {
    for v in data.chunks_exact_mut(8) {
        let c = |k: usize| i16::from_le_bytes([v[2 * k], v[2 * k + 1]]) as f32;
        let r = octahedral(c(0), c(1), c(2), 32767.0);
        for k in 0..3 {
            v[2 * k..2 * k + 2].copy_from_slice(&(r[k] as i16).to_le_bytes());
        }
    }
}

/// Quaternions: three components stored with the scale of the fourth's top bits, its
/// low two bits naming the component left out, rebuilt as the square root of the rest.
fn filter_quaternion(data: &mut [u8]) {
    // Everything is computed unscaled; the final scale takes the values out of fixed
    // point (1 / sf), renormalizes (1 / sqrt 2) and brings them to 16 bits (32767).
    let scale = 32767.0 / 2f32.sqrt();
    for v in data.chunks_exact_mut(8) {
        let c = |k: usize| i16::from_le_bytes([v[2 * k], v[2 * k + 1]]);
        let w_in = c(3);
        let s = (w_in as i32 | 3) as f32;
        let (x, y, z) = (c(0) as f32, c(1) as f32, c(2) as f32);
        let ww = s * s * 2.0 - x * x - y * y - z * z;
        let w = if ww >= 0.0 { ww } else { 0.0 }.sqrt();
        let ss = scale / s;
        let q = (w_in & 3) as usize;
        let vals = [round(x * ss), round(y * ss), round(z * ss), (w * ss + 0.5) as i32];
        for (k, val) in vals.iter().enumerate() {
            let slot = (q + 1 + k) & 3;
            v[2 * slot..2 * slot + 2].copy_from_slice(&(*val as i16).to_le_bytes());
        }
    }
}

/// Exponential: each 32-bit value is a signed 24-bit mantissa times 2 to a signed
/// 8-bit exponent (the high byte).
fn filter_exponential(data: &mut [u8]) {
    for v in data.chunks_exact_mut(4) {
        let bits = u32::from_le_bytes([v[0], v[1], v[2], v[3]]);
        let m = ((bits << 8) as i32) >> 8;
        let e = (bits as i32) >> 24;
        let scale = f32::from_bits(((e + 127) as u32) << 23);
        v.copy_from_slice(&(scale * m as f32).to_le_bytes());
    }
}

/// Encodes `data` (`count` elements of `stride` bytes, `stride` a multiple of 4 up to
/// 256) with the vertex codec, version 0 (`ATTRIBUTES`): each group of 16 deltas at the
/// fewest bits that hold them. Linear in `data.len()`.
pub(crate) fn encode_vertices(data: &[u8], stride: usize) -> Vec<u8> {
    let count = data.len() / stride;
    let mut out = vec![0xA0];
    let block = ((8192 / stride) & !15).min(256);
    let mut last: Vec<u8> = data[..stride.min(data.len())].to_vec();
    last.resize(stride, 0);
    let first_vertex = last.clone();
    let mut deltas = [0u8; 256];
    let mut first = 0;
    while first < count {
        let n = block.min(count - first);
        let aligned = (n + 15) & !15;
        for (k, prev) in last.iter_mut().enumerate() {
            let mut p = *prev;
            for (i, d) in deltas[..aligned].iter_mut().enumerate() {
                *d = if i < n {
                    let v = data[(first + i) * stride + k];
                    let delta = v.wrapping_sub(p) as i8;
                    p = v;
                    ((delta as u8) << 1) ^ ((delta >> 7) as u8)
                } else {
                    0
                };
            }
            *prev = p;
            encode_channel(&deltas[..aligned], &mut out);
        }
        first += n;
    }
    let tail = stride.max(32);
    out.resize(out.len() + tail - stride, 0);
    out.extend_from_slice(&first_vertex);
    out
}

/// One channel of a block: the 2-bit group modes, then each group at the fewest bytes.
fn encode_channel(deltas: &[u8], out: &mut Vec<u8>) {
    let header_at = out.len();
    out.resize(header_at + (deltas.len() / 16).div_ceil(4), 0);
    for (g, group) in deltas.chunks_exact(16).enumerate() {
        let size = |bits: u32| -> usize {
            match bits {
                0 if group.iter().all(|&d| d == 0) => 0,
                0 => usize::MAX,
                8 => 16,
                _ => {
                    let sentinel = (1u8 << bits) - 1;
                    16 * bits as usize / 8 + group.iter().filter(|&&d| d >= sentinel).count()
                }
            }
        };
        let mode = (0..4u8).min_by_key(|&m| size([0, 2, 4, 8][m as usize])).unwrap_or(3);
        out[header_at + g / 4] |= mode << ((g % 4) * 2);
        match mode {
            0 => {}
            3 => out.extend_from_slice(group),
            _ => {
                let bits = if mode == 1 { 2 } else { 4 };
                let per_byte = 8 / bits;
                let sentinel = (1u8 << bits) - 1;
                let mut rest = Vec::new();
                for chunk in group.chunks_exact(per_byte) {
                    let mut b = 0u8;
                    for (i, &d) in chunk.iter().enumerate() {
                        let v = if d >= sentinel {
                            rest.push(d);
                            sentinel
                        } else {
                            d
                        };
                        b |= v << (8 - bits * (i + 1));
                    }
                    out.push(b);
                }
                out.extend_from_slice(&rest);
            }
        }
    }
}

/// Encodes `indices` with the index-sequence codec (`INDICES`, the mode meant for
/// strips): per index a zigzag delta from one of two baselines, switching to the other
/// when the delta would not fit a byte. Linear in `indices.len()`.
pub(crate) fn encode_sequence(indices: &[u32]) -> Vec<u8> {
    let mut out = vec![0xD1];
    let mut baseline = [0u32; 2];
    let mut current = 0usize;
    for &i in indices {
        let distance = (i.wrapping_sub(baseline[current]) as i32).unsigned_abs();
        if distance >= 30 {
            current ^= 1;
        }
        let d = i.wrapping_sub(baseline[current]);
        let zigzag = (d << 1) ^ ((d as i32 >> 31) as u32);
        let mut v = (zigzag << 1) | current as u32;
        loop {
            if v < 0x80 {
                out.push(v as u8);
                break;
            }
            out.push((v & 0x7f) as u8 | 0x80);
            v >>= 7;
        }
        baseline[current] = i;
    }
    out.extend_from_slice(&[0; 4]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hand_made_index_sequence_decodes() {
        // 0, 1, 2 on baseline 0 (deltas 0, +1, +1), then 0 on baseline 1 (delta 0).
        let stream = [0xD1, 0, 2 << 1, 2 << 1, 1, 0, 0, 0, 0];
        let out = decode(&stream, 4, 2, MeshoptMode::Indices, MeshoptFilter::None).unwrap();
        assert_eq!(out, [0, 0, 1, 0, 2, 0, 0, 0]);
        // One byte short of the tail: refused, named.
        let err = decode(&stream[..8], 4, 2, MeshoptMode::Indices, MeshoptFilter::None).unwrap_err();
        assert!(err.1.contains("too early"), "{err:?}");
    }

    #[test]
    fn a_hand_made_vertex_stream_decodes() {
        // Two vertices of 4 bytes: channel deltas in one group of raw bytes (mode 3)
        // per channel; the tail's last 4 bytes are the previous vertex (1, 2, 3, 4).
        let mut stream = vec![0xA0];
        for k in 0..4u8 {
            stream.push(3);
            let mut group = [0u8; 16];
            group[0] = 2 * k; // +k from the previous vertex's byte
            group[1] = 1; // -1
            stream.extend_from_slice(&group);
        }
        let mut tail = [0u8; 32];
        tail[28..].copy_from_slice(&[1, 2, 3, 4]);
        stream.extend_from_slice(&tail);
        let out = decode(&stream, 2, 4, MeshoptMode::Attributes, MeshoptFilter::None).unwrap();
        assert_eq!(out, [1, 3, 5, 7, 0, 2, 4, 6]);
        // Truncated, wrong version, wrong stride: errors, no panic.
        for n in 0..stream.len() {
            assert!(decode(&stream[..n], 2, 4, MeshoptMode::Attributes, MeshoptFilter::None).is_err());
        }
        stream[0] = 0xA1;
        assert!(decode(&stream, 2, 4, MeshoptMode::Attributes, MeshoptFilter::None).is_err());
        assert!(decode(&stream, 2, 6, MeshoptMode::Attributes, MeshoptFilter::None).is_err());
    }

    #[test]
    fn the_encoders_round_trip() {
        let mut state = 7u32;
        let mut next = || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            state >> 8
        };
        for (count, stride, spread) in [(0, 4, 3), (1, 8, 255), (300, 12, 5), (1000, 32, 255), (40, 256, 1)] {
            let data: Vec<u8> = (0..count * stride).map(|_| (next() % spread) as u8).collect();
            let stream = encode_vertices(&data, stride);
            assert_eq!(decode(&stream, count, stride, MeshoptMode::Attributes, MeshoptFilter::None).unwrap(), data);
        }
        let strip: Vec<u32> = (0..500).map(|k| if k % 50 == 49 { u32::MAX } else { k * 3 + next() % 7 }).collect();
        let stream = encode_sequence(&strip);
        let back = decode(&stream, strip.len(), 4, MeshoptMode::Indices, MeshoptFilter::None).unwrap();
        assert_eq!(back, strip.iter().flat_map(|i| i.to_le_bytes()).collect::<Vec<_>>());
    }

    #[test]
    fn hostile_triangle_streams_are_errors() {
        let mut state = 0x9E37_79B9u32;
        for len in 0..200 {
            let stream: Vec<u8> = (0..len)
                .map(|k| {
                    state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                    if k == 0 {
                        0xE1
                    } else {
                        (state >> 24) as u8
                    }
                })
                .collect();
            let _ = decode(&stream, 30, 4, MeshoptMode::Triangles, MeshoptFilter::None);
            let _ = decode(&stream, 30, 4, MeshoptMode::Indices, MeshoptFilter::None);
        }
        assert!(decode(&[0xE0; 40], 4, 4, MeshoptMode::Triangles, MeshoptFilter::None).is_err());
    }
}

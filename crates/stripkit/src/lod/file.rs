//! The `.sets` file: versioned, little-endian, checksummed, read as untrusted input.
//! The layout is documented in docs/sets-format.md.

mod codes;

use super::sets::{Sets, Version, END};
use codes::{pack_counts, unpack_counts, LabelCoder, COUNT_ESCAPE};
use crate::error::{Error, Result};
use crate::mesh::io::write_checked;
use crate::mesh::{Attribute, Scalar};
use crate::simplify::Placement;
use std::path::Path;

/// The first eight bytes of a `.sets` file.
pub const SETS_MAGIC: &[u8; 8] = b"SKLODSET";
const FORMAT_VERSION: u32 = 1;
/// The version of a file that carries vertex attributes (an attributes section after
/// the positions); files without attributes keep version 1, byte for byte.
const FORMAT_VERSION_ATTRIBUTES: u32 = 2;
/// The version of a `.sets` file with strips made after level 0 (re-stripped,
/// [`Sets::build_restripping`]): the attributes section is always there (it may
/// hold none), and each strip's beginning count carries a bit saying that its
/// level-0 beginning is [`END`] although it has slots. Models without such strips
/// keep version 1 or 2, byte for byte.
const FORMAT_VERSION_RESTRIPS: u32 = 3;
/// Most attributes a file may declare.
const MAX_ATTRIBUTES: u32 = 64;
/// Longest attribute name, in bytes.
const MAX_ATTRIBUTE_NAME: u64 = 256;
const FLAG_OPTIMAL: u32 = 1;
/// The positions section is absent (a model inside a `.lodseq`, whose frames hold
/// the positions); only with endpoint placement.
const FLAG_NO_POSITIONS: u32 = 2;

impl Sets {
    /// The `.sets` encoding (docs/sets-format.md). Level-0 versions and beginnings
    /// are implied by the strips; a later version stores its level step, whether its
    /// label changed (the new label is then the target of the collapse that made the
    /// level) and its successor's distance, as LEB128 varints.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(64 + 12 * self.positions.len() + 3 * self.version_count());
        out.extend_from_slice(SETS_MAGIC);
        let positionless = self.positions.is_empty() && self.input_vertices > 0;
        let flags = if self.placement == Placement::Optimal { FLAG_OPTIMAL } else { 0 }
            | if positionless { FLAG_NO_POSITIONS } else { 0 };
        let restrips = self.has_restrips();
        let version = if restrips {
            FORMAT_VERSION_RESTRIPS
        } else if self.attributes.is_empty() {
            FORMAT_VERSION
        } else {
            FORMAT_VERSION_ATTRIBUTES
        };
        for x in [
            version,
            flags,
            self.input_vertices,
            if positionless { self.input_vertices } else { self.positions.len() as u32 },
            self.levels(),
            self.strip_count() as u32,
            self.slot_count() as u32,
            self.version_count() as u32,
            self.beginning_count() as u32,
            self.triangles0,
        ] {
            out.extend_from_slice(&x.to_le_bytes());
        }
        for p in &self.positions {
            for c in p {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
        if restrips || !self.attributes.is_empty() {
            write_attributes(&mut out, &self.attributes);
        }
        for i in 0..self.targets.len() {
            if self.placement == Placement::Endpoint {
                varint(&mut out, self.targets[i] as u64);
            }
            varint(&mut out, self.removed_triangles[i] as u64);
        }
        for s in 0..self.strip_count() {
            varint(&mut out, (self.strip_slots[s + 1] - self.strip_slots[s]) as u64);
        }
        let label0 = |x: usize| self.versions[self.version_offsets[x] as usize].label;
        if restrips {
            let mut coder = LabelCoder::default();
            for x in 0..self.slot_count() {
                varint(&mut out, coder.code(label0(x)));
            }
            let counts: Vec<usize> = (0..self.slot_count())
                .map(|x| (self.version_offsets[x + 1] - self.version_offsets[x]) as usize - 1)
                .collect();
            pack_counts(&mut out, &counts);
        } else {
            let mut last = 0u32;
            for x in 0..self.slot_count() {
                varint(&mut out, zigzag(label0(x) as i64 - last as i64));
                last = label0(x);
            }
        }
        for x in 0..self.slot_count() {
            let r = self.version_offsets[x] as usize..self.version_offsets[x + 1] as usize;
            match (restrips, r.len() - 1) {
                (false, n) => varint(&mut out, n as u64),
                (true, n) if n >= COUNT_ESCAPE as usize => varint(&mut out, (n - COUNT_ESCAPE as usize) as u64),
                (true, _) => {}
            }
            for w in self.versions[r].windows(2) {
                let (before, v) = (w[0], w[1]);
                varint(&mut out, (v.level - before.level) as u64);
                let next = match v.next {
                    END => 0,
                    y => (y - x as u32) as u64,
                };
                let relabel = v.label != before.label;
                debug_assert!(!relabel || v.label == self.targets[v.level as usize - 1]);
                varint(&mut out, next << 1 | relabel as u64);
            }
        }
        // Version 3: the first beginning of a strip empty at level 0 (a re-stripped
        // one) is stored against the previous such strip's, as they share few levels.
        let mut last_start = 0u32;
        for s in 0..self.strip_count() {
            let r = self.begin_offsets[s] as usize..self.begin_offsets[s + 1] as usize;
            let empty0 = restrips && self.begin_slot[r.start] == END && self.strip_slots[s] < self.strip_slots[s + 1];
            if restrips {
                varint(&mut out, ((r.len() - 1) as u64) << 1 | empty0 as u64);
            } else {
                varint(&mut out, (r.len() - 1) as u64);
            }
            for b in r.start + 1..r.end {
                if empty0 && b == r.start + 1 {
                    varint(&mut out, zigzag(self.begin_level[b] as i64 - last_start as i64));
                    last_start = self.begin_level[b];
                } else {
                    varint(&mut out, (self.begin_level[b] - self.begin_level[b - 1]) as u64);
                }
                let slot = match self.begin_slot[b] {
                    END => 0,
                    y => (y - self.strip_slots[s] + 1) as u64,
                };
                varint(&mut out, slot);
            }
        }
        seal(&mut out);
        out
    }

    /// Writes the `.sets` file atomically, once its bytes read back
    /// ([`Sets::from_bytes`]) to this model (an [`Error::Verification`] otherwise).
    /// Returns the file's size in bytes.
    pub fn write(&self, path: &Path) -> Result<usize> {
        write_checked(path, || Ok(self.to_bytes()), |bytes| read_back(self, Sets::from_bytes(path, bytes)?, "sets"))
    }

    /// Reads a `.sets` file ([`Sets::from_bytes`]).
    pub fn read(path: &Path) -> Result<Sets> {
        let bytes = std::fs::read(path).map_err(|source| Error::Io { path: path.to_path_buf(), source })?;
        Sets::from_bytes(path, &bytes)
    }

    /// Decodes a `.sets` file; `path` names it in errors. The checksum is checked
    /// first; every count is checked against the bytes left before anything is
    /// allocated for it, every vertex, slot and level against its range, levels
    /// ascend, successors move forward within their strip, and the triangle counts
    /// agree with the strips at every level, so that no recovery of the result can
    /// index out of bounds or loop and every level extracts to the triangle count the
    /// file gives. A failure is [`Error::Format`] with the byte offset (or the level
    /// whose count the strips do not draw).
    pub fn from_bytes(path: &Path, bytes: &[u8]) -> Result<Sets> {
        let fmt = |at: usize, what: String| Error::Format { path: path.to_path_buf(), at: format!("byte {at}"), what };
        let (mut r, version) = Reader::open(bytes, SETS_MAGIC, 40, ".sets", FORMAT_VERSION_RESTRIPS, &fmt)?;
        let h = SetsHeader::read(&mut r)?;
        let positions = read_positions(&mut r, if h.positionless { 0 } else { h.position_count })?;
        let attributes = match version {
            FORMAT_VERSION => Vec::new(),
            _ => read_attributes(&mut r, h.position_count, version == FORMAT_VERSION_RESTRIPS)?,
        };
        let (targets, removed_triangles) = h.read_collapses(&mut r)?;
        let strip_slots = h.read_strip_lengths(&mut r)?;
        let v3 = version == FORMAT_VERSION_RESTRIPS;
        let labels = h.read_labels(&mut r, v3)?;
        let (version_offsets, versions) = h.read_versions(&mut r, &labels, &strip_slots, &targets, v3)?;
        let (begin_offsets, begin_level, begin_slot) =
            h.read_beginnings(&mut r, &strip_slots, version == FORMAT_VERSION_RESTRIPS)?;
        let body = r.bytes.len();
        if r.at != body {
            return Err(fmt(r.at, format!("{} bytes follow the last strip beginning", body - r.at)));
        }
        let mut sets = Sets {
            placement: h.placement,
            input_vertices: h.input_vertices,
            positions,
            attributes,
            targets,
            removed_triangles,
            triangles0: h.triangles0,
            strip_slots,
            begin_offsets,
            begin_level,
            begin_slot,
            version_offsets,
            versions,
            change_offsets: Vec::new(),
            change_level: Vec::new(),
            changes: Vec::new(),
            level_offsets: Vec::new(),
            level_strips: Vec::new(),
            snapshots: Default::default(),
            triangles_at: Vec::new(),
        };
        sets.derive().map_err(|e| fmt(body, e.to_string()))?;
        let decoded = crate::strip::decode(&sets.strips_at(0)).len();
        if decoded != h.triangles0 as usize {
            return Err(fmt(
                44,
                format!("the header gives {} triangles at level 0, the strips draw {decoded}", h.triangles0),
            ));
        }
        // Counts that add up can still disagree with the strips at a later level: a bad
        // file, named with the level, not a verification failure at extraction.
        if let Err((level, drawn)) = sets.check_triangle_counts() {
            return Err(Error::Format {
                path: path.to_path_buf(),
                at: format!("level {level}"),
                what: format!(
                    "the collapses leave {} triangles at level {level}, the strips draw {drawn}",
                    sets.triangles_at(level)
                ),
            });
        }
        Ok(sets)
    }
}

/// The header of a `.sets` file after its format version: the flags and the counts
/// every later section is checked against.
struct SetsHeader {
    placement: Placement,
    /// No positions section (a model inside a `.lodseq`).
    positionless: bool,
    input_vertices: u32,
    position_count: u32,
    levels: u32,
    strips: u32,
    slots: u32,
    versions: u32,
    beginnings: u32,
    triangles0: u32,
}

impl SetsHeader {
    /// Reads and checks the flags and counts (bytes 12 to 48).
    fn read(r: &mut Reader) -> Result<SetsHeader> {
        let flags = r.u32()?;
        let positionless = flags & FLAG_NO_POSITIONS != 0;
        if flags & !(FLAG_OPTIMAL | FLAG_NO_POSITIONS) != 0 || (positionless && flags & FLAG_OPTIMAL != 0) {
            return Err(r.fail(12, format!("unknown flags {flags:#x}")));
        }
        let placement = if flags & FLAG_OPTIMAL != 0 { Placement::Optimal } else { Placement::Endpoint };
        let mut h = [0u32; 8];
        for x in &mut h {
            *x = r.u32()?;
        }
        let [input_vertices, position_count, levels, strips, slots, versions, beginnings, triangles0] = h;
        let expected_positions = match placement {
            Placement::Endpoint => input_vertices as u64,
            Placement::Optimal => input_vertices as u64 + levels as u64,
        };
        if position_count as u64 != expected_positions || position_count == END {
            return Err(r.fail(
                20,
                format!("{position_count} positions for {input_vertices} vertices and {levels} levels"),
            ));
        }
        if versions < slots || beginnings < strips || slots == END {
            return Err(r.fail(36, "fewer versions than slots or beginnings than strips".into()));
        }
        Ok(SetsHeader {
            placement,
            positionless,
            input_vertices,
            position_count,
            levels,
            strips,
            slots,
            versions,
            beginnings,
            triangles0,
        })
    }

    /// The collapses: each one's target vertex (stored for endpoint placement, the
    /// next new vertex for optimal) and the triangles it removes.
    fn read_collapses(&self, r: &mut Reader) -> Result<(Vec<u32>, Vec<u32>)> {
        // Every record from here on takes at least one byte: counts are checked
        // against the bytes left before any allocation.
        r.need(self.levels as usize, "the collapses")?;
        let mut targets = Vec::with_capacity(self.levels as usize);
        let mut removed_triangles = Vec::with_capacity(self.levels as usize);
        for i in 0..self.levels {
            let t = match self.placement {
                Placement::Endpoint => r.index(self.position_count, "a collapse's target vertex")?,
                Placement::Optimal => self.input_vertices + i,
            };
            targets.push(t);
            removed_triangles.push(r.index(u32::MAX, "a collapse's removed triangle count")?);
        }
        Ok((targets, removed_triangles))
    }

    /// The strips' lengths, as the offsets of their first slots (and the end), which
    /// must add up to the header's slots.
    fn read_strip_lengths(&self, r: &mut Reader) -> Result<Vec<u32>> {
        let slots = self.slots;
        r.need(self.strips as usize, "the strips")?;
        let mut strip_slots = Vec::with_capacity(self.strips as usize + 1);
        strip_slots.push(0u32);
        for _ in 0..self.strips {
            let len = r.index(u32::MAX, "a strip length")? as u64;
            let end = *strip_slots.last().expect("holds 0") as u64 + len;
            if end > slots as u64 {
                return Err(r.fail(r.at, format!("the strips hold more than the {slots} slots the header gives")));
            }
            strip_slots.push(end as u32);
        }
        if *strip_slots.last().expect("holds 0") != slots {
            return Err(r.fail(r.at, format!("the strips hold fewer than the {slots} slots the header gives")));
        }
        Ok(strip_slots)
    }

    /// The level-0 vertex of every slot: zigzag differences from the previous one, or
    /// with `recent` (version 3) [`LabelCoder`] codes.
    fn read_labels(&self, r: &mut Reader, recent: bool) -> Result<Vec<u32>> {
        let position_count = self.position_count;
        r.need(self.slots as usize, "the level-0 strips")?;
        let mut labels = Vec::with_capacity(self.slots as usize);
        if recent {
            let mut coder = LabelCoder::default();
            for _ in 0..self.slots {
                let code = r.varint("a level-0 vertex")?;
                let v = coder.vertex(code, position_count).ok_or_else(|| {
                    r.fail(r.at, format!("a level-0 strip names no recent vertex or one outside the {position_count} vertices"))
                })?;
                labels.push(v);
            }
            return Ok(labels);
        }
        let mut last = 0i64;
        for _ in 0..self.slots {
            let d = unzigzag(r.varint("a level-0 vertex")?);
            last = last.checked_add(d).filter(|v| (0..position_count as i64).contains(v)).ok_or_else(|| {
                r.fail(r.at, format!("a level-0 strip names a vertex outside the {position_count} vertices"))
            })?;
            labels.push(last as u32);
        }
        Ok(labels)
    }

    /// The versions of every slot (its level-0 version implied by `labels` and the
    /// strips) and their offsets: levels ascend within a slot, successors move
    /// forward within its strip, a relabel takes the target of its level's collapse.
    fn read_versions(
        &self,
        r: &mut Reader,
        labels: &[u32],
        strip_slots: &[u32],
        targets: &[u32],
        packed: bool,
    ) -> Result<(Vec<u32>, Vec<Version>)> {
        let (levels, versions) = (self.levels, self.versions);
        let strip_of = |x: usize| strip_slots.partition_point(|&o| o as usize <= x) - 1;
        let counts = if packed { Some(unpack_counts(r, self.slots as usize)?) } else { None };
        if !packed {
            r.need(self.slots as usize, "the slot versions")?;
        }
        let mut version_offsets = Vec::with_capacity(self.slots as usize + 1);
        version_offsets.push(0u32);
        let cap = (versions as usize).min(r.left());
        let mut all_versions: Vec<Version> = Vec::with_capacity(cap);
        for (x, &label0) in labels.iter().enumerate() {
            let strip_end = strip_slots[strip_of(x) + 1] as usize;
            let extra = match &counts {
                None => r.index(u32::MAX, "a slot's version count")? as usize,
                Some(c) if c[x] == COUNT_ESCAPE => {
                    COUNT_ESCAPE as usize + r.index(u32::MAX - COUNT_ESCAPE as u32, "a slot's version count")? as usize
                }
                Some(c) => c[x] as usize,
            };
            if all_versions.len() + 1 + extra > versions as usize {
                return Err(r.fail(r.at, format!("more slot versions than the {versions} the header gives")));
            }
            r.need(extra * 2, "a slot's versions")?;
            all_versions.push(Version {
                level: 0,
                label: label0,
                next: if x + 1 < strip_end { x as u32 + 1 } else { END },
            });
            for _ in 0..extra {
                let step = r.index(u32::MAX, "a version's level step")?;
                let before = *all_versions.last().expect("pushed above");
                let level = before.level as u64 + step as u64;
                if step == 0 || level > levels as u64 {
                    return Err(r.fail(r.at, format!("slot {x}: version levels must ascend within 1..={levels}")));
                }
                let code = r.varint("a version's successor")?;
                let next = match code >> 1 {
                    0 => END,
                    d => {
                        let y = x as u64 + d;
                        if y >= strip_end as u64 {
                            return Err(r.fail(r.at, format!("slot {x}: its successor leaves its strip")));
                        }
                        y as u32
                    }
                };
                let label = if code & 1 == 1 { targets[level as usize - 1] } else { before.label };
                all_versions.push(Version { level: level as u32, label, next });
            }
            version_offsets.push(all_versions.len() as u32);
        }
        if all_versions.len() != versions as usize {
            return Err(r.fail(r.at, format!("{} slot versions, the header gives {versions}", all_versions.len())));
        }
        Ok((version_offsets, all_versions))
    }

    /// The beginnings of every strip (its level-0 one implied): their offsets, levels
    /// (ascending within a strip) and slots (inside the strip, or [`END`]).
    /// With `restrips` (version 3) the count's low bit says the strip is empty at
    /// level 0.
    fn read_beginnings(
        &self,
        r: &mut Reader,
        strip_slots: &[u32],
        restrips: bool,
    ) -> Result<(Vec<u32>, Vec<u32>, Vec<u32>)> {
        let (levels, beginnings) = (self.levels, self.beginnings);
        r.need(self.strips as usize, "the strip beginnings")?;
        let mut begin_offsets = Vec::with_capacity(self.strips as usize + 1);
        begin_offsets.push(0u32);
        let cap = (beginnings as usize).min(r.left());
        let (mut begin_level, mut begin_slot) = (Vec::with_capacity(cap), Vec::with_capacity(cap));
        let mut last_start = 0i64;
        for s in 0..self.strips as usize {
            let (lo, hi) = (strip_slots[s], strip_slots[s + 1]);
            let code = r.varint("a strip's beginning count")?;
            let (extra, empty0) = if restrips { (code >> 1, code & 1 == 1) } else { (code, false) };
            if extra >= u32::MAX as u64 {
                return Err(r.fail(r.at, format!("strip {s}: {extra} beginnings")));
            }
            let extra = extra as usize;
            if begin_level.len() + 1 + extra > beginnings as usize {
                return Err(r.fail(r.at, format!("more strip beginnings than the {beginnings} the header gives")));
            }
            r.need(extra * 2, "a strip's beginnings")?;
            begin_level.push(0);
            let empty0 = empty0 && lo < hi;
            begin_slot.push(if lo < hi && !empty0 { lo } else { END });
            for k in 0..extra {
                let before = begin_level.last().copied().unwrap_or(0) as i64;
                let (step, level) = if empty0 && k == 0 {
                    // Against the previous re-stripped strip's first beginning.
                    let level = last_start.saturating_add(unzigzag(r.varint("a beginning's level")?));
                    last_start = level;
                    (level - before, level)
                } else {
                    let step = r.index(u32::MAX, "a beginning's level step")? as i64;
                    (step, before + step)
                };
                if step <= 0 || level > levels as i64 {
                    return Err(r.fail(r.at, format!("strip {s}: beginning levels must ascend within 1..={levels}")));
                }
                let slot = match r.varint("a beginning's slot")? {
                    0 => END,
                    d if d <= (hi - lo) as u64 => lo + d as u32 - 1,
                    _ => return Err(r.fail(r.at, format!("strip {s}: a beginning outside the strip"))),
                };
                begin_level.push(level as u32);
                begin_slot.push(slot);
            }
            begin_offsets.push(begin_level.len() as u32);
        }
        if begin_level.len() != beginnings as usize {
            return Err(r.fail(r.at, format!("{} beginnings, the header gives {beginnings}", begin_level.len())));
        }
        Ok((begin_offsets, begin_level, begin_slot))
    }
}

/// `count` positions of 12 bytes each, all finite.
fn read_positions(r: &mut Reader, count: u32) -> Result<Vec<[f32; 3]>> {
    r.need(count as usize * 12, "the positions")?;
    let mut positions = Vec::with_capacity(count as usize);
    for _ in 0..count {
        let p = [r.f32()?, r.f32()?, r.f32()?];
        if !p.iter().all(|c| c.is_finite()) {
            return Err(r.fail(r.at - 12, format!("vertex {} has a NaN or infinite coordinate", positions.len())));
        }
        positions.push(p);
    }
    Ok(positions)
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
    fmt: &'a dyn Fn(usize, String) -> Error,
}

impl<'a> Reader<'a> {
    /// Checks a file's length (the magic, `header` more bytes and the checksum),
    /// its magic, its trailing CRC-32 (before anything else is read, so that damage
    /// says so) and its format version; reads the body after the version.
    fn open(
        bytes: &'a [u8],
        magic: &[u8; 8],
        header: usize,
        kind: &str,
        newest: u32,
        fmt: &'a dyn Fn(usize, String) -> Error,
    ) -> Result<(Reader<'a>, u32)> {
        if bytes.len() < magic.len() + header + 4 {
            return Err(fmt(0, format!("{} bytes is too short for a {kind} file", bytes.len())));
        }
        if &bytes[..8] != magic {
            return Err(fmt(0, format!("not a stripkit {kind} file (bad magic)")));
        }
        let (body, tail) = bytes.split_at(bytes.len() - 4);
        let mut crc = flate2::Crc::new();
        crc.update(body);
        if crc.sum().to_le_bytes() != tail {
            return Err(fmt(body.len(), "checksum mismatch: the file is damaged or truncated".into()));
        }
        let mut r = Reader { bytes: body, at: 8, fmt };
        let version = r.u32()?;
        if !(FORMAT_VERSION..=newest).contains(&version) {
            let known = format!("versions {FORMAT_VERSION} to {newest}");
            return Err(fmt(8, format!("format version {version}; this stripkit reads {known}")));
        }
        Ok((r, version))
    }

    fn left(&self) -> usize {
        self.bytes.len() - self.at
    }

    /// The file's format error at byte `at`.
    fn fail(&self, at: usize, what: String) -> Error {
        (self.fmt)(at, what)
    }

    /// Fails unless at least `n` bytes are left (for `n` records of one byte or more).
    fn need(&self, n: usize, what: &str) -> Result<()> {
        if n > self.left() {
            return Err((self.fmt)(self.at, format!("the file ends before {what} ({n} bytes or more needed)")));
        }
        Ok(())
    }

    fn u32(&mut self) -> Result<u32> {
        self.need(4, "the header")?;
        let b = &self.bytes[self.at..self.at + 4];
        self.at += 4;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    fn f32(&mut self) -> Result<f32> {
        Ok(f32::from_bits(self.u32()?))
    }

    fn varint(&mut self, what: &str) -> Result<u64> {
        let mut v = 0u64;
        for shift in (0..64).step_by(7) {
            let Some(&b) = self.bytes.get(self.at) else {
                return Err((self.fmt)(self.at, format!("the file ends inside {what}")));
            };
            self.at += 1;
            v |= ((b & 0x7f) as u64) << shift;
            if b & 0x80 == 0 {
                return Ok(v);
            }
        }
        Err((self.fmt)(self.at, format!("{what}: a number longer than 64 bits")))
    }

    /// A varint below `limit`.
    fn index(&mut self, limit: u32, what: &str) -> Result<u32> {
        let v = self.varint(what)?;
        if v >= limit as u64 {
            return Err((self.fmt)(self.at, format!("{what} is {v}, not below {limit}")));
        }
        Ok(v as u32)
    }
}

/// Appends the CRC-32 of everything before it.
fn seal(out: &mut Vec<u8>) {
    let mut crc = flate2::Crc::new();
    crc.update(out);
    let sum = crc.sum();
    out.extend_from_slice(&sum.to_le_bytes());
}

fn varint(out: &mut Vec<u8>, mut v: u64) {
    while v >= 0x80 {
        out.push((v as u8) | 0x80);
        v >>= 7;
    }
    out.push(v as u8);
}

fn zigzag(v: i64) -> u64 {
    ((v << 1) ^ (v >> 63)) as u64
}

fn unzigzag(v: u64) -> i64 {
    ((v >> 1) as i64) ^ -((v & 1) as i64)
}

/// The first eight bytes of a `.lodseq` file.
pub const LODSEQ_MAGIC: &[u8; 8] = b"SKLODSEQ";
/// Longest frame name a `.lodseq` holds, in bytes.
const MAX_NAME: u64 = 4096;

impl super::seq::LodSeq {
    /// The `.lodseq` encoding (docs/sets-format.md): frame names and models, every
    /// frame's positions, then each model as a positionless `.sets`.
    pub fn to_bytes(&self) -> Vec<u8> {
        let n = self.positions.first().map_or(0, |p| p.len());
        let mut out = Vec::with_capacity(32 + self.positions.len() * n * 12);
        out.extend_from_slice(LODSEQ_MAGIC);
        let bits = self.quantization.map_or(0, |q| q.bits);
        let version = if self.attributes.is_empty() { FORMAT_VERSION } else { FORMAT_VERSION_ATTRIBUTES };
        for x in [version, self.names.len() as u32, n as u32, self.models.len() as u32, bits] {
            out.extend_from_slice(&x.to_le_bytes());
        }
        for (name, &m) in self.names.iter().zip(&self.frame_model) {
            let name = &name.as_bytes()[..name.len().min(MAX_NAME as usize)];
            varint(&mut out, name.len() as u64);
            out.extend_from_slice(name);
            varint(&mut out, m as u64);
        }
        match self.quantization {
            None => {
                for frame in &self.positions {
                    for p in frame {
                        for c in p {
                            out.extend_from_slice(&c.to_le_bytes());
                        }
                    }
                }
            }
            Some(q) => {
                for x in q.lo.iter().chain(&q.step) {
                    out.extend_from_slice(&x.to_le_bytes());
                }
                // Grid indices: the first frame against the previous vertex, every
                // later frame against the previous frame; zigzag varints, deflated.
                let mut raw = Vec::new();
                for (f, frame) in self.positions.iter().enumerate() {
                    for (i, p) in frame.iter().enumerate() {
                        for d in 0..3 {
                            let base = match (f, i) {
                                (0, 0) => 0,
                                (0, _) => q.index(&frame[i - 1], d),
                                _ => q.index(&self.positions[f - 1][i], d),
                            };
                            varint(&mut raw, zigzag(q.index(p, d) as i64 - base as i64));
                        }
                    }
                }
                let mut z = flate2::write::DeflateEncoder::new(Vec::new(), flate2::Compression::best());
                use std::io::Write;
                let packed = z.write_all(&raw).and_then(|_| z.finish()).unwrap_or_default();
                varint(&mut out, packed.len() as u64);
                out.extend_from_slice(&packed);
            }
        }
        if !self.attributes.is_empty() {
            write_attributes(&mut out, &self.attributes);
        }
        for model in &self.models {
            let bytes = model.to_bytes();
            varint(&mut out, bytes.len() as u64);
            out.extend_from_slice(&bytes);
        }
        seal(&mut out);
        out
    }

    /// Bytes of the models in [`LodSeq::to_bytes`](super::seq::LodSeq::to_bytes), each a
    /// positionless `.sets` with its length prefix: the level-of-detail data (the rest
    /// of the file is the header, the frame names and the positions).
    pub fn model_bytes(&self) -> usize {
        let mut prefix = Vec::new();
        self.models
            .iter()
            .map(|model| {
                let len = model.to_bytes().len();
                prefix.clear();
                varint(&mut prefix, len as u64);
                prefix.len() + len
            })
            .sum()
    }

    /// Writes the `.lodseq` file atomically, once its bytes read back
    /// ([`LodSeq::from_bytes`](super::seq::LodSeq::from_bytes)) to this model (an
    /// [`Error::Verification`] otherwise). Returns the file's size in bytes.
    pub fn write(&self, path: &Path) -> Result<usize> {
        write_checked(path, || Ok(self.to_bytes()), |bytes| read_back(self, Self::from_bytes(path, bytes)?, "lodseq"))
    }

    /// Reads a `.lodseq` file ([`LodSeq::from_bytes`](super::seq::LodSeq::from_bytes)).
    pub fn read(path: &Path) -> Result<super::seq::LodSeq> {
        let bytes = std::fs::read(path).map_err(|source| Error::Io { path: path.to_path_buf(), source })?;
        Self::from_bytes(path, &bytes)
    }

    /// Decodes a `.lodseq` file as untrusted input: the checksum first, every count
    /// against the bytes left, each model as [`Sets::from_bytes`] checks it, every
    /// model positionless over the frames' vertex count with the same strip layout.
    pub fn from_bytes(path: &Path, bytes: &[u8]) -> Result<super::seq::LodSeq> {
        let fmt = |at: usize, what: String| Error::Format { path: path.to_path_buf(), at: format!("byte {at}"), what };
        let (mut r, version) = Reader::open(bytes, LODSEQ_MAGIC, 20, ".lodseq", FORMAT_VERSION_ATTRIBUTES, &fmt)?;
        let (frames, vertices, models, bits) = (r.u32()?, r.u32()?, r.u32()?, r.u32()?);
        if frames == 0 || models == 0 {
            return Err(fmt(12, "a sequence needs at least one frame and one model".into()));
        }
        if bits != 0 && !(8..=20).contains(&bits) {
            return Err(fmt(24, format!("{bits} bits per coordinate (0 for exact positions, else 8 to 20)")));
        }
        let (names, frame_model) = read_frame_names(&mut r, frames, models)?;
        let (positions, quantization) = if bits == 0 {
            (read_frame_positions(&mut r, frames, vertices)?, None)
        } else {
            let (positions, q) = read_quantized_positions(&mut r, frames, vertices, bits)?;
            (positions, Some(q))
        };
        let attributes = match version {
            FORMAT_VERSION => Vec::new(),
            _ => read_attributes(&mut r, vertices, false)?,
        };
        let models = read_models(path, &mut r, models, vertices)?;
        let body = r.bytes.len();
        if r.at != body {
            return Err(fmt(r.at, format!("{} bytes follow the last model", body - r.at)));
        }
        Ok(super::seq::LodSeq { names, positions, frame_model, models, quantization, attributes })
    }
}

/// The frames' names (at most [`MAX_NAME`] bytes each) and models (below `models`).
fn read_frame_names(r: &mut Reader, frames: u32, models: u32) -> Result<(Vec<String>, Vec<u32>)> {
    r.need(frames as usize * 2, "the frame names")?;
    let mut names = Vec::with_capacity(frames as usize);
    let mut frame_model = Vec::with_capacity(frames as usize);
    for _ in 0..frames {
        let len = r.varint("a frame name's length")?;
        if len > MAX_NAME {
            return Err(r.fail(r.at, format!("a frame name of {len} bytes (at most {MAX_NAME})")));
        }
        r.need(len as usize, "a frame name")?;
        let name = String::from_utf8_lossy(&r.bytes[r.at..r.at + len as usize]).into_owned();
        r.at += len as usize;
        names.push(name);
        frame_model.push(r.index(models, "a frame's model")?);
    }
    Ok((names, frame_model))
}

/// Every frame's exact positions, all finite.
fn read_frame_positions(r: &mut Reader, frames: u32, vertices: u32) -> Result<Vec<Vec<[f32; 3]>>> {
    let total = (frames as usize).saturating_mul(vertices as usize);
    r.need(total.saturating_mul(12), "the frames' positions")?;
    let mut positions = Vec::with_capacity(frames as usize);
    for f in 0..frames as usize {
        let mut p = Vec::with_capacity(vertices as usize);
        for _ in 0..vertices {
            let v = [r.f32()?, r.f32()?, r.f32()?];
            if !v.iter().all(|c| c.is_finite()) {
                return Err(r.fail(r.at - 12, format!("frame {f}: a NaN or infinite coordinate")));
            }
            p.push(v);
        }
        positions.push(p);
    }
    Ok(positions)
}

/// Every frame's positions on a `bits`-bit grid: the grid, then the deflated zigzag
/// varint differences [`super::seq::LodSeq::to_bytes`] writes, each inside the grid.
fn read_quantized_positions(
    r: &mut Reader,
    frames: u32,
    vertices: u32,
    bits: u32,
) -> Result<(Vec<Vec<[f32; 3]>>, super::seq::Quantization)> {
    let total = (frames as usize).saturating_mul(vertices as usize);
    let mut grid = [0f32; 6];
    for x in &mut grid {
        *x = r.f32()?;
    }
    let q = super::seq::Quantization { bits, lo: [grid[0], grid[1], grid[2]], step: [grid[3], grid[4], grid[5]] };
    if !grid.iter().all(|x| x.is_finite()) || q.step.iter().any(|&s| s <= 0.0) {
        return Err(r.fail(r.at, "the position grid is not finite and positive".into()));
    }
    // Every grid point must be a finite position: its far corner too.
    let top = (1u32 << bits) - 1;
    if let Some(d) = (0..3).find(|&d| !q.value(top, d).is_finite()) {
        return Err(r.fail(
            r.at - 24,
            format!(
                "the position grid's far corner is not finite (axis {d}: origin {:e} + step {:e} x {top})",
                q.lo[d], q.step[d]
            ),
        ));
    }
    let len = r.varint("the positions' length")?;
    r.need(len as usize, "the positions")?;
    let packed = &r.bytes[r.at..r.at + len as usize];
    r.at += len as usize;
    // At most 64 bytes of positions per byte stored (real animations take 3 to 6): a
    // small file cannot claim a huge mesh.
    if total.saturating_mul(12) > packed.len().saturating_mul(64) + (1 << 20) {
        return Err(r.fail(r.at, format!("{frames} frames of {vertices} vertices cannot come from {len} bytes")));
    }
    let mut raw = Vec::new();
    use std::io::Read;
    flate2::read::DeflateDecoder::new(packed)
        .take(total.saturating_mul(15) as u64)
        .read_to_end(&mut raw)
        .map_err(|e| r.fail(r.at, format!("the positions do not inflate: {e}")))?;
    let mut v = Reader { bytes: &raw, at: 0, fmt: r.fmt };
    let top = (1i64 << bits) - 1;
    let mut positions = Vec::with_capacity(frames as usize);
    let mut prev: Vec<[u32; 3]> = Vec::new();
    for f in 0..frames as usize {
        let mut cur: Vec<[u32; 3]> = Vec::with_capacity((vertices as usize).min(raw.len() / 3 + 1));
        for i in 0..vertices as usize {
            let mut g = [0u32; 3];
            for (d, gd) in g.iter_mut().enumerate() {
                let base = match (f, i) {
                    (0, 0) => 0,
                    (0, _) => cur[i - 1][d],
                    _ => prev[i][d],
                } as i64;
                let x = base + unzigzag(v.varint("a position")?);
                if !(0..=top).contains(&x) {
                    return Err(r.fail(r.at, format!("frame {f}: a position off its {bits}-bit grid")));
                }
                *gd = x as u32;
            }
            cur.push(g);
        }
        positions.push(cur.iter().map(|g| [0, 1, 2].map(|d| q.value(g[d], d))).collect());
        prev = cur;
    }
    if v.at != raw.len() {
        return Err(r.fail(r.at, "bytes follow the last position".into()));
    }
    Ok((positions, q))
}

/// The models, each a length-prefixed `.sets` checked as [`Sets::from_bytes`] checks
/// it (its errors placed at the model's offset), positionless endpoint models over
/// `vertices` vertices with the strip layout of the first.
fn read_models(path: &Path, r: &mut Reader, models: u32, vertices: u32) -> Result<Vec<Sets>> {
    r.need(models as usize, "the models")?;
    let mut sets: Vec<Sets> = Vec::with_capacity(models as usize);
    for m in 0..models {
        let len = r.varint("a model's length")?;
        r.need(len as usize, "a model")?;
        let at = r.at;
        let model = Sets::from_bytes(path, &r.bytes[at..at + len as usize]).map_err(|e| match e {
            Error::Format { at: inner, what, .. } => r.fail(at, format!("model {m}, {inner}: {what}")),
            e => e,
        })?;
        r.at += len as usize;
        if model.input_vertices != vertices
            || !model.positions.is_empty()
            || !model.attributes.is_empty()
            || model.placement != Placement::Endpoint
        {
            return Err(r.fail(at, format!("model {m} is not a positionless endpoint model over {vertices} vertices")));
        }
        if sets.first().is_some_and(|first| first.strip_slots != model.strip_slots) {
            return Err(r.fail(at, format!("model {m} lays its strips out unlike model 0")));
        }
        sets.push(model);
    }
    Ok(sets)
}

const SCALARS: [Scalar; 8] =
    [Scalar::I8, Scalar::U8, Scalar::I16, Scalar::U16, Scalar::I32, Scalar::U32, Scalar::F32, Scalar::F64];

/// The attributes section of a version-2 file (docs/sets-format.md): a `u32` count,
/// then per attribute its name (varint length, UTF-8), scalar type (0 to 7: i8, u8,
/// i16, u16, i32, u32, f32, f64), components and normalized flag (a byte each);
/// then each attribute's values, one per vertex, as stored.
fn write_attributes(out: &mut Vec<u8>, attributes: &[Attribute]) {
    out.extend_from_slice(&(attributes.len() as u32).to_le_bytes());
    for a in attributes {
        varint(out, a.name.len() as u64);
        out.extend_from_slice(a.name.as_bytes());
        let scalar = SCALARS.iter().position(|&x| x == a.scalar).unwrap_or(0) as u8;
        out.extend_from_slice(&[scalar, a.components, a.normalized as u8]);
    }
    for a in attributes {
        out.extend_from_slice(&a.data);
    }
}

/// Reads [`write_attributes`]'s section for `vertices` vertices: at most
/// [`MAX_ATTRIBUTES`] attributes, names of at most [`MAX_ATTRIBUTE_NAME`] bytes, 1 to
/// 4 components of a known type, and every attribute's values present in the bytes
/// left before they are copied.
fn read_attributes(r: &mut Reader, vertices: u32, may_be_empty: bool) -> Result<Vec<Attribute>> {
    let count = r.u32()?;
    if (count == 0 && !may_be_empty) || count > MAX_ATTRIBUTES {
        return Err(r.fail(r.at - 4, format!("{count} attributes (a version-2 file holds 1 to {MAX_ATTRIBUTES})")));
    }
    r.need(count as usize * 4, "the attributes")?;
    let mut attributes = Vec::with_capacity(count as usize);
    for i in 0..count {
        let len = r.varint("an attribute's name length")?;
        if len > MAX_ATTRIBUTE_NAME {
            return Err(r.fail(r.at, format!("attribute {i}: a name of {len} bytes (at most {MAX_ATTRIBUTE_NAME})")));
        }
        r.need(len as usize + 3, "an attribute")?;
        let name = std::str::from_utf8(&r.bytes[r.at..r.at + len as usize])
            .map_err(|_| r.fail(r.at, format!("attribute {i}: its name is not UTF-8")))?
            .to_string();
        r.at += len as usize;
        let (scalar, components, normalized) = (r.bytes[r.at], r.bytes[r.at + 1], r.bytes[r.at + 2]);
        r.at += 3;
        let Some(&scalar) = SCALARS.get(scalar as usize) else {
            return Err(r.fail(r.at - 3, format!("attribute {name}: unknown scalar type {scalar}")));
        };
        if !(1..=4).contains(&components) || normalized > 1 || (normalized == 1 && scalar.is_float()) {
            return Err(r.fail(r.at - 2, format!("attribute {name}: {components} components, normalized {normalized}")));
        }
        attributes.push(Attribute { name, scalar, components, normalized: normalized == 1, data: Vec::new() });
    }
    for a in &mut attributes {
        let size = (vertices as usize).saturating_mul(a.stride());
        r.need(size, "an attribute's values")?;
        a.data = r.bytes[r.at..r.at + size].to_vec();
        r.at += size;
    }
    Ok(attributes)
}

/// The read-back check of a `.EXT` file: the model decoded from its bytes is `model`.
fn read_back<T: PartialEq>(model: &T, back: T, ext: &str) -> Result<()> {
    if back != *model {
        return Err(Error::Verification(format!("the .{ext} bytes do not read back to the model")));
    }
    Ok(())
}


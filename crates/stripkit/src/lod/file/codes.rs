//! The version-3 codes of `.sets` files (docs/sets-format.md): the level-0 vertices
//! coded by their place beside the strip before ([`LabelCoder`]) and the slots'
//! version counts packed two bits each. The rest of the format is in the parent.

use super::super::sets::END;
use super::{unzigzag, zigzag, Reader};
use crate::error::Result;

/// Recent vertices a version-3 level-0 vertex may name by its place.
const RECENT: usize = 64;
/// Slots on each side of an earlier occurrence whose vertices are candidates.
const NEAR: usize = 3;
/// Candidates of a version-3 level-0 vertex: near the earlier occurrences of the two
/// vertices before it.
const CANDIDATES: usize = 4 * NEAR;

/// The version-3 coding of the level-0 vertices, slot after slot. A strip runs
/// beside an earlier one and shares its vertices: the vertex of a slot is most often
/// within [`NEAR`] slots of where the previous slot's or the one before's vertex last
/// occurred before them. Such a vertex is coded as its place among those
/// [`CANDIDATES`] (gathered in a fixed order: previous slot first, nearest first,
/// after before before); else, if among the [`RECENT`] vertices named last (most
/// recent first), as `CANDIDATES` plus its place there; else as `CANDIDATES +
/// RECENT` plus the zigzag difference from the last vertex so coded. Every vertex
/// then becomes the most recent. Most slots take one byte.
#[derive(Default)]
pub(super) struct LabelCoder {
    /// The vertices so far.
    labels: Vec<u32>,
    /// Per slot, the slot where its vertex occurred last before it, or [`END`].
    before: Vec<u32>,
    /// Per vertex, its last slot.
    last: std::collections::HashMap<u32, u32>,
    recent: Vec<u32>,
    last_new: u32,
    candidates: Vec<u32>,
}

impl LabelCoder {
    /// Gathers the candidates of the next slot.
    pub(super) fn gather(&mut self) {
        self.candidates.clear();
        let x = self.labels.len();
        for back in 1..=2 {
            let Some(&p) = x.checked_sub(back).map(|y| &self.before[y]) else { break };
            if p == END {
                continue;
            }
            let p = p as usize;
            for d in 1..=NEAR {
                if p + d < x {
                    self.candidates.push(self.labels[p + d]);
                }
                if p >= d {
                    self.candidates.push(self.labels[p - d]);
                }
            }
        }
    }

    /// The code of the next slot's vertex `v`.
    pub(super) fn code(&mut self, v: u32) -> u64 {
        self.gather();
        let code = if let Some(c) = self.candidates.iter().position(|&w| w == v) {
            c as u64
        } else if let Some(p) = self.recent.iter().position(|&w| w == v) {
            (CANDIDATES + p) as u64
        } else {
            let code = (CANDIDATES + RECENT) as u64 + zigzag(v as i64 - self.last_new as i64);
            self.last_new = v;
            code
        };
        self.push(v);
        code
    }

    /// The next slot's vertex from its `code`, below `vertices`, or `None`.
    pub(super) fn vertex(&mut self, code: u64, vertices: u32) -> Option<u32> {
        self.gather();
        let v = if code < CANDIDATES as u64 {
            *self.candidates.get(code as usize)?
        } else if code < (CANDIDATES + RECENT) as u64 {
            *self.recent.get(code as usize - CANDIDATES)?
        } else {
            let v = (self.last_new as i64).checked_add(unzigzag(code - (CANDIDATES + RECENT) as u64))?;
            let v = u32::try_from(v).ok().filter(|&v| v < vertices)?;
            self.last_new = v;
            v
        };
        self.push(v);
        Some(v)
    }

    pub(super) fn push(&mut self, v: u32) {
        let x = self.labels.len() as u32;
        self.before.push(self.last.insert(v, x).unwrap_or(END));
        self.labels.push(v);
        match self.recent.iter().position(|&w| w == v) {
            Some(p) => self.recent[..=p].rotate_right(1),
            None => {
                self.recent.truncate(RECENT - 1);
                self.recent.insert(0, v);
            }
        }
    }
}

/// A version-3 slot's version count at or past this is stored as a varint of the
/// rest before its versions.
pub(super) const COUNT_ESCAPE: u8 = 3;

/// Version 3: every slot's version count (after level 0), two bits each, four to a
/// byte, low bits first; [`COUNT_ESCAPE`] for three or more.
pub(super) fn pack_counts(out: &mut Vec<u8>, counts: &[usize]) {
    for four in counts.chunks(4) {
        let byte = four.iter().enumerate().fold(0u8, |b, (i, &n)| b | (n.min(COUNT_ESCAPE as usize) as u8) << (2 * i));
        out.push(byte);
    }
}

/// Reads [`pack_counts`]'s bytes for `slots` slots (the unused bits of the last
/// byte must be 0).
pub(super) fn unpack_counts(r: &mut Reader, slots: usize) -> Result<Vec<u8>> {
    let len = slots.div_ceil(4);
    r.need(len, "the slots' version counts")?;
    let bytes = &r.bytes[r.at..r.at + len];
    if slots % 4 != 0 && bytes[len - 1] >> (2 * (slots % 4)) != 0 {
        return Err(r.fail(r.at + len - 1, "bits set past the last slot's version count".into()));
    }
    let counts = (0..slots).map(|x| bytes[x / 4] >> (2 * (x % 4)) & 3).collect();
    r.at += len;
    Ok(counts)
}

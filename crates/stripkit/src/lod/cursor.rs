//! Recovery of levels with coherence.

use super::sets::Sets;
use crate::strip::StripSet;
use std::ops::Range;

/// The strips of one level of a [`Sets`] model, kept up to date as the level changes.
///
/// Every strip owns a fixed range of [`Cursor::buffer`]: its level-0 length plus one,
/// filled with its current vertices and then the restart index (a run of restarts
/// draws nothing). The buffer is ready to upload as a `TRIANGLE_STRIP` index buffer
/// with primitive restart; after [`Cursor::set_level`], only the ranges of the strips
/// it returns changed. [`Cursor::compact`] gives the tight restart buffer instead.
///
/// Coherence: each strip knows the interval of levels over which its sequence stays
/// the same (the paper's validity interval), so a level change re-walks only the
/// strips whose interval does not hold the new level.
///
/// ```
/// use stripkit::{gen, lod, StripOptions};
/// let mesh = gen::icosphere(2);
/// let sets = lod::build(&mesh, &lod::BuildOptions::default(), &mut |_| {})?.sets;
/// let mut cursor = sets.cursor(0);
/// assert_eq!(stripkit::decode(&cursor.strips()).len(), 320);
/// let level = sets.level_for_ratio(0.25);
/// let changed = cursor.set_level(level).len();
/// assert!(changed > 0);
/// assert_eq!(stripkit::decode(&cursor.strips()).len() as u32, sets.triangles_at(level));
/// # Ok::<(), stripkit::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Cursor<'a> {
    sets: &'a Sets,
    level: u32,
    restart: u32,
    /// Per strip: `[lo, hi)` of levels where its current sequence holds.
    valid: Vec<(u32, u32)>,
    lens: Vec<u32>,
    buffer: Vec<u32>,
    changed: Vec<u32>,
}

impl Sets {
    /// A cursor at `level` (clamped to the coarsest), every strip walked once, with
    /// restart index `u32::MAX`.
    pub fn cursor(&self, level: u32) -> Cursor<'_> {
        let strips = self.strip_count();
        let mut c = Cursor {
            sets: self,
            level: level.min(self.levels()),
            restart: crate::strip::DEFAULT_RESTART,
            valid: vec![(0, 0); strips],
            lens: vec![0; strips],
            buffer: vec![crate::strip::DEFAULT_RESTART; self.slot_count() + strips],
            changed: Vec::with_capacity(strips),
        };
        for s in 0..strips {
            c.rewalk(s);
        }
        c
    }
}

impl<'a> Cursor<'a> {
    /// The model.
    pub fn sets(&self) -> &'a Sets {
        self.sets
    }

    /// The current level.
    pub fn level(&self) -> u32 {
        self.level
    }

    /// Moves to `level` (clamped to the coarsest) and returns the strips whose
    /// sequence changed, ascending: the ranges ([`Cursor::strip_range`]) a renderer
    /// must upload again.
    pub fn set_level(&mut self, level: u32) -> &[u32] {
        let level = level.min(self.sets.levels());
        self.changed.clear();
        self.level = level;
        for s in 0..self.valid.len() {
            let (lo, hi) = self.valid[s];
            if level < lo || level >= hi {
                self.rewalk(s);
                self.changed.push(s as u32);
            }
        }
        &self.changed
    }

    /// The strips the last [`Cursor::set_level`] changed (empty for a new cursor).
    pub fn changed(&self) -> &[u32] {
        &self.changed
    }

    /// Walks strip `s` at the current level into its range and updates its validity
    /// interval.
    fn rewalk(&mut self, s: usize) {
        let sets = self.sets;
        let base = sets.strip_slots[s] as usize + s;
        let mut pos = base;
        let buffer = &mut self.buffer;
        sets.walk(s, self.level, |v| {
            buffer[pos] = v;
            pos += 1;
        });
        let len = (pos - base) as u32;
        let old = self.lens[s];
        if len < old {
            buffer[pos..base + old as usize].fill(self.restart);
        }
        self.lens[s] = len;
        let c = &sets.change_level[sets.change_offsets[s] as usize..sets.change_offsets[s + 1] as usize];
        let k = c.partition_point(|&l| l <= self.level);
        self.valid[s] = (c[k - 1], c.get(k).copied().unwrap_or(u32::MAX));
    }

    /// The padded restart buffer (see [`Cursor`]).
    pub fn buffer(&self) -> &[u32] {
        &self.buffer
    }

    /// Strip `s`'s range in [`Cursor::buffer`] (its current vertices, then restarts).
    pub fn strip_range(&self, s: usize) -> Range<usize> {
        let base = self.sets.strip_slots[s] as usize + s;
        base..self.sets.strip_slots[s + 1] as usize + s + 1
    }

    /// Strip `s` at the current level.
    pub fn strip(&self, s: usize) -> &[u32] {
        let base = self.sets.strip_slots[s] as usize + s;
        &self.buffer[base..base + self.lens[s] as usize]
    }

    /// The non-empty strips at the current level.
    pub fn strips(&self) -> StripSet {
        let mut out = StripSet::new();
        for s in 0..self.lens.len() {
            if self.lens[s] > 0 {
                out.push(self.strip(s));
            }
        }
        out
    }

    /// The tight buffer: non-empty strips separated by `restart`.
    pub fn compact(&self, restart: u32, out: &mut Vec<u32>) {
        out.clear();
        for s in 0..self.lens.len() {
            if self.lens[s] > 0 {
                if !out.is_empty() {
                    out.push(restart);
                }
                out.extend_from_slice(self.strip(s));
            }
        }
    }

    /// Indices of the non-empty strips at the current level (without restarts).
    pub fn index_count(&self) -> usize {
        self.lens.iter().map(|&l| l as usize).sum()
    }
}

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
/// strips whose interval does not hold the new level. A move between near levels
/// finds those strips from the model's per-level lists instead of looking at every
/// strip, and re-walks each one only from the first slot that changes between the
/// two levels (the slots before it, and their places in the buffer, stay); a far
/// jump looks at every strip and re-walks the changed ones whole, as a new cursor
/// would. [`Cursor::changed_range`] is what a renderer must upload again.
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
    /// Parallel to `buffer`: the slot each current vertex came from (ascending
    /// within a strip's range), where a partial re-walk resumes.
    slot_at: Vec<u32>,
    /// Per strip: the offsets in its range that the last re-walk wrote.
    written: Vec<(u32, u32)>,
    changed: Vec<u32>,
    /// Per strip: the move that last listed it (a move lists each strip once).
    stamp: Vec<u32>,
    moves: u32,
}

/// A partial re-walk scans the changes (versions and beginnings) between the two
/// levels for the first changed slot while they number at most the strip's current
/// length over this (many changes lie all along a strip, so the walk would resume
/// near its start anyway); past that it re-walks the strip whole.
const PARTIAL_SCAN: usize = 4;

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
            slot_at: vec![super::END; self.slot_count() + strips],
            written: vec![(0, 0); strips],
            changed: Vec::with_capacity(strips),
            stamp: vec![0; strips],
            moves: 0,
        };
        for s in 0..strips {
            c.rewalk(s, 0);
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
    /// sequence changed, ascending: the ranges ([`Cursor::strip_range`], or just
    /// [`Cursor::changed_range`]) a renderer must upload again.
    pub fn set_level(&mut self, level: u32) -> &[u32] {
        let sets = self.sets;
        let level = level.min(sets.levels());
        let old = self.level;
        self.changed.clear();
        self.level = level;
        if level == old {
            return &self.changed;
        }
        let (lo, hi) = (old.min(level) as usize, old.max(level) as usize);
        // The strips that change at a level in (lo, hi]: from the per-level lists
        // when they hold fewer entries than there are strips, else by a scan.
        let listed = (sets.level_offsets[hi + 1] - sets.level_offsets[lo + 1]) as usize;
        if listed < self.valid.len() {
            self.moves = self.moves.wrapping_add(1);
            if self.moves == 0 {
                self.stamp.fill(0);
                self.moves = 1;
            }
            for &s in &sets.level_strips[sets.level_offsets[lo + 1] as usize..sets.level_offsets[hi + 1] as usize] {
                if self.stamp[s as usize] != self.moves {
                    self.stamp[s as usize] = self.moves;
                    self.changed.push(s);
                }
            }
            self.changed.sort_unstable();
        } else {
            for s in 0..self.valid.len() {
                let (a, b) = self.valid[s];
                if level < a || level >= b {
                    self.changed.push(s as u32);
                }
            }
        }
        for i in 0..self.changed.len() {
            let s = self.changed[i] as usize;
            let from = self.first_change(s, lo as u32, hi as u32);
            self.rewalk(s, from);
        }
        &self.changed
    }

    /// The strips the last [`Cursor::set_level`] changed (empty for a new cursor).
    pub fn changed(&self) -> &[u32] {
        &self.changed
    }

    /// The offset in strip `s`'s range from which its walk changes between levels
    /// `lo` and `hi`: the place of the first slot that has a change in `(lo, hi]`
    /// (0 when that is a new beginning, or when too many changes lie between).
    fn first_change(&self, s: usize, lo: u32, hi: u32) -> usize {
        let sets = self.sets;
        let r = sets.change_offsets[s] as usize..sets.change_offsets[s + 1] as usize;
        let levels = &sets.change_level[r.clone()];
        let (a, b) = (levels.partition_point(|&l| l <= lo), levels.partition_point(|&l| l <= hi));
        if (b - a) * PARTIAL_SCAN > self.lens[s] as usize {
            return 0;
        }
        let first = sets.change_slot[r.start + a..r.start + b].iter().copied().min().unwrap_or(0);
        if first <= sets.strip_slots[s] {
            return 0;
        }
        let base = sets.strip_slots[s] as usize + s;
        self.slot_at[base..base + self.lens[s] as usize].partition_point(|&x| x < first)
    }

    /// Walks strip `s` at the current level into its range from offset `from` on
    /// (the slots before it unchanged since the last walk) and updates its validity
    /// interval.
    fn rewalk(&mut self, s: usize, from: usize) {
        let sets = self.sets;
        let base = sets.strip_slots[s] as usize + s;
        let start = if from == 0 {
            sets.head_at(s, self.level)
        } else {
            sets.version_at(self.slot_at[base + from - 1], self.level).next
        };
        let mut pos = base + from;
        let (buffer, slot_at) = (&mut self.buffer, &mut self.slot_at);
        sets.walk_slots(start, self.level, |x, v| {
            buffer[pos] = v;
            slot_at[pos] = x;
            pos += 1;
        });
        let len = (pos - base) as u32;
        let old = self.lens[s];
        if len < old {
            buffer[pos..base + old as usize].fill(self.restart);
        }
        self.lens[s] = len;
        self.written[s] = (from as u32, len.max(old));
        let c = &sets.change_level[sets.change_offsets[s] as usize..sets.change_offsets[s + 1] as usize];
        let k = c.partition_point(|&l| l <= self.level);
        self.valid[s] = (c[k - 1], c.get(k).copied().unwrap_or(u32::MAX));
    }

    /// The part of strip `s`'s range ([`Cursor::strip_range`]) that the last
    /// re-walk of `s` wrote: for a strip the last [`Cursor::set_level`] returned,
    /// what changed (from its first changed vertex to the end of the longer of its
    /// old and new sequences).
    pub fn changed_range(&self, s: usize) -> Range<usize> {
        let base = self.sets.strip_slots[s] as usize + s;
        let (a, b) = self.written[s];
        base + a as usize..base + b as usize
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

//! Recovery of levels with coherence, and the paper's recovery tests.

use super::sets::Sets;
use crate::strip::StripSet;
use std::ops::Range;
use std::time::Instant;

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

/// How [`bench_levels`] spaces the levels it recovers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Spacing {
    /// Equal steps from the finest level to the coarsest.
    Linear,
    /// Level `j` of `n` is `(L + 1)^(j / (n - 1)) - 1` for `L` levels, rounded:
    /// close steps near the finest level, far ones near the coarsest (a model moving
    /// away from the viewer).
    Exponential,
}

/// The paper's recovery test: recover `percent`% of the model's levels (at least
/// two), spaced by `spacing`, from the finest to the coarsest and back, `rounds`
/// times; returns the levels of one pass down and the mean microseconds per level
/// recovered (the cursor's update, with `compact` the tight buffer too).
pub fn bench_levels(sets: &Sets, percent: f64, spacing: Spacing, rounds: usize, compact: bool) -> (usize, f64) {
    let total = sets.levels() as usize + 1;
    let count = ((total as f64 * percent / 100.0).ceil() as usize).clamp(2, total.max(2));
    let max = sets.levels() as f64;
    let mut levels: Vec<u32> = (0..count)
        .map(|j| {
            let f = j as f64 / (count - 1) as f64;
            match spacing {
                Spacing::Linear => (f * max).round() as u32,
                Spacing::Exponential => ((max + 1.0).powf(f) - 1.0).round() as u32,
            }
        })
        .collect();
    levels.dedup();
    let down = levels.len();
    let mut path = levels.clone();
    path.extend(levels.iter().rev().skip(1));
    let mut cursor = sets.cursor(0);
    let mut out = Vec::new();
    let start = Instant::now();
    for _ in 0..rounds.max(1) {
        for &l in &path {
            cursor.set_level(l);
            if compact {
                cursor.compact(u32::MAX, &mut out);
            }
        }
    }
    let us = start.elapsed().as_secs_f64() * 1e6 / (path.len() * rounds.max(1)) as f64;
    (down, us)
}

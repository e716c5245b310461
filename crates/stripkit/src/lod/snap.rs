//! The cursor's state kept at the re-strip levels, so that a move across one is a
//! few copies.
//!
//! A re-strip level ([`super::Sets::build_restripping`]) ends every live strip and
//! begins a new set, a *generation* (generation 0: the level-0 strips; generation
//! `k`: the strips begun at the `k`-th re-strip level `R_k`, numbered after the ones
//! before). One generation is live at any level, the others empty, and a
//! generation's strips change only between its first and its last level. So the
//! cursor at level `R_k` (or `R_k - 1`) is known from a few tables per generation,
//! made once when the model loads (walked there; not stored in the file):
//!
//! * the buffer and slot ranges of the live generation as a cursor holds them (its
//!   walks, then restarts), at its first level and at its last, each one block;
//! * each generation's per-strip state (length, where its change list stands, its
//!   validity interval) before its first level, at its first, at its last and past
//!   its last.
//!
//! A move across re-strip levels ([`Snapshots::crossing`]) then fills the range of
//! the generation live before it with restarts (one fill), copies the block of the
//! generation live at the re-strip level nearest its destination, copies the states
//! of the generations between, and goes on from that level as a near move. A model
//! that breaks the layout above (strips not numbered by generation, a change outside
//! its generation's levels) keeps no tables, and its moves walk.

use crate::strip::DEFAULT_RESTART;
use std::ops::Range;

/// Where a generation stands at a level: before its first level, at its first, at
/// its last, or after its last.
const UNBORN: usize = 0;
const BORN: usize = 1;
const LAST: usize = 2;
const DEAD: usize = 3;
/// "No slot" (the model's `END`): an empty strip's beginning, and the slots of a
/// block past a strip's walk.
const END: u32 = u32::MAX;
/// A table a generation does not have (generation 0 is never unborn, the last one
/// never dead).
const ABSENT: u32 = u32::MAX;

/// A strip's cursor state at a level: its length, the index in the model's change
/// lists of its first change past the level, and its validity interval `[lo, hi)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct KeptState {
    pub(crate) len: u32,
    pub(crate) next: u32,
    pub(crate) lo: u32,
    pub(crate) hi: u32,
}

/// The tables of every generation (see the module): derived on load, not stored in
/// the file.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Snapshots {
    /// The re-strip levels `R_1 < R_2 < ...` (empty: no tables).
    restrip: Vec<u32>,
    /// Generation `k`'s strips are `first[k]..first[k + 1]`, its range in the
    /// cursor's buffer `base[k]..base[k + 1]`.
    first: Vec<u32>,
    base: Vec<u32>,
    /// Per strip: where its range starts in its generation's range.
    offset: Vec<u32>,
    /// Per generation and state (`4 k + UNBORN` ...): where its strips' states start
    /// in `states`, or [`ABSENT`].
    state_at: Vec<u32>,
    states: Vec<KeptState>,
    /// Per generation and state (`BORN`, `LAST`): where its block starts in `labels`
    /// and `slots` (its buffer range's length), or [`ABSENT`].
    block_at: Vec<u32>,
    labels: Vec<u32>,
    slots: Vec<u32>,
}

/// What [`Snapshots::derive`] reads of a model (the `Sets` fields of those names).
pub(crate) struct Model<'a> {
    pub(crate) strip_slots: &'a [u32],
    pub(crate) begin_offsets: &'a [u32],
    pub(crate) begin_level: &'a [u32],
    pub(crate) begin_slot: &'a [u32],
    pub(crate) change_offsets: &'a [u32],
    pub(crate) change_level: &'a [u32],
}

/// One kept walk: its level, vertices and slots.
pub(crate) struct Snapshot<'a> {
    pub(crate) level: u32,
    pub(crate) labels: &'a [u32],
    pub(crate) slots: &'a [u32],
}

impl Snapshots {
    /// The tables of a model (none without re-strip levels or when its strips break
    /// the layout the module describes): its strips and beginnings, change lists,
    /// and `walk(s, level, labels, slots)`, which fills strip `s`'s walk at `level`
    /// (false: the walk left the strip's slots, a damaged model).
    pub(crate) fn derive(sets: Model<'_>, walk: impl FnMut(usize, u32, &mut Vec<u32>, &mut Vec<u32>) -> bool) -> Snapshots {
        Snapshots::try_derive(sets, walk).unwrap_or_default()
    }

    fn try_derive(
        sets: Model<'_>,
        mut walk: impl FnMut(usize, u32, &mut Vec<u32>, &mut Vec<u32>) -> bool,
    ) -> Option<Snapshots> {
        let strips = sets.strip_slots.len() - 1;
        let (mut labels, mut slots) = (Vec::new(), Vec::new());
        let mut empty = |s: usize, level: u32| walk(s, level, &mut labels, &mut slots) && labels.is_empty();
        let begins = |s: usize| sets.begin_offsets[s] as usize..sets.begin_offsets[s + 1] as usize;
        // A strip empty at level 0 is born at its second beginning.
        let born = |s: usize| -> Option<Option<u32>> {
            let b = begins(s);
            if sets.begin_slot[b.start] != END {
                return Some(None);
            }
            let k = b.start + 1;
            (k < b.end && sets.begin_slot[k] != END && sets.begin_level[k] > 0).then(|| Some(sets.begin_level[k]))
        };
        let mut restrip = Vec::new();
        for s in 0..strips {
            if let Some(l) = born(s)? {
                restrip.push(l);
            }
        }
        if restrip.is_empty() {
            return None;
        }
        restrip.sort_unstable();
        restrip.dedup();
        let m = restrip.len();
        // Strips numbered by generation.
        let mut first = vec![0u32; m + 2];
        let mut gen = 0;
        for s in 0..strips {
            let g = match born(s)? {
                None => 0,
                Some(l) => restrip.binary_search(&l).ok()? + 1,
            };
            if g < gen {
                return None;
            }
            while gen < g {
                gen += 1;
                first[gen] = s as u32;
            }
        }
        while gen <= m {
            gen += 1;
            first[gen] = strips as u32;
        }
        let base: Vec<u32> = first.iter().map(|&s| sets.strip_slots[s as usize] + s).collect();
        let from = |k: usize| if k == 0 { 0 } else { restrip[k - 1] };
        let to = |k: usize| restrip.get(k).copied();
        // Every change of a generation's strips lies in its levels, and it is empty
        // outside them.
        for k in 0..=m {
            for s in first[k] as usize..first[k + 1] as usize {
                let levels = &sets.change_level[sets.change_offsets[s] as usize..sets.change_offsets[s + 1] as usize];
                let inside = |l: u32| l == 0 || (l >= from(k) && to(k).is_none_or(|t| l <= t));
                if !levels.iter().all(|&l| inside(l))
                    || (k > 0 && !empty(s, from(k) - 1))
                    || to(k).is_some_and(|t| !empty(s, t))
                {
                    return None;
                }
            }
        }
        let mut out = Snapshots {
            restrip: restrip.clone(),
            state_at: vec![ABSENT; 4 * (m + 1)],
            block_at: vec![ABSENT; 4 * (m + 1)],
            ..Snapshots::default()
        };
        for k in 0..=m {
            let strips = first[k] as usize..first[k + 1] as usize;
            let at = [
                (k > 0).then(|| from(k) - 1),
                (k > 0).then(|| from(k)),
                to(k).map(|t| t - 1),
                to(k),
            ];
            for (what, level) in at.iter().enumerate() {
                let Some(level) = *level else { continue };
                out.state_at[4 * k + what] = out.states.len() as u32;
                let block = what == BORN || what == LAST;
                if block {
                    out.block_at[4 * k + what] = out.labels.len() as u32;
                }
                for s in strips.clone() {
                    if !walk(s, level, &mut labels, &mut slots) {
                        return None;
                    }
                    let (lo, hi) = (sets.strip_slots[s], sets.strip_slots[s + 1]);
                    let r = sets.change_offsets[s] as usize..sets.change_offsets[s + 1] as usize;
                    let levels = &sets.change_level[r.clone()];
                    let next = levels.partition_point(|&l| l <= level);
                    out.states.push(KeptState {
                        len: labels.len() as u32,
                        next: (r.start + next) as u32,
                        lo: levels[next - 1],
                        hi: levels.get(next).copied().unwrap_or(u32::MAX),
                    });
                    if block {
                        let range = (hi - lo) as usize + 1;
                        out.labels.extend_from_slice(&labels);
                        out.labels.resize(out.labels.len() + range - labels.len(), DEFAULT_RESTART);
                        out.slots.extend_from_slice(&slots);
                        out.slots.resize(out.slots.len() + range - slots.len(), END);
                    }
                }
            }
        }
        out.offset = (0..strips)
            .map(|s| {
                let k = first.partition_point(|&f| f as usize <= s) - 1;
                sets.strip_slots[s] + s as u32 - base[k]
            })
            .collect();
        out.first = first;
        out.base = base;
        Some(out)
    }

    /// For a move from `old` to `level` across at least one re-strip level: the
    /// level where the tables put the cursor first, the one nearest `level` (moving
    /// coarser, the last re-strip level at or below `level`; finer, the level
    /// before the first re-strip level above `level`); from there the move crosses
    /// none.
    #[inline]
    pub(crate) fn crossing(&self, old: u32, level: u32) -> Option<u32> {
        if self.restrip.is_empty() || old == level {
            return None;
        }
        let i = self.restrip.partition_point(|&r| r <= level);
        if level > old {
            (i > 0 && self.restrip[i - 1] > old).then(|| self.restrip[i - 1])
        } else {
            (i < self.restrip.len() && self.restrip[i] <= old).then(|| self.restrip[i] - 1)
        }
    }

    /// The re-strip levels the tables are for (empty: none kept).
    #[cfg(test)]
    pub(crate) fn restrip_levels(&self) -> &[u32] {
        &self.restrip
    }

    /// The generation live at `level`.
    pub(crate) fn generation(&self, level: u32) -> usize {
        self.restrip.partition_point(|&r| r <= level)
    }

    /// Generation `k`'s strips.
    pub(crate) fn strips(&self, k: usize) -> Range<usize> {
        self.first[k] as usize..self.first[k + 1] as usize
    }

    /// Generation `k`'s range in the cursor's buffer.
    pub(crate) fn range(&self, k: usize) -> Range<usize> {
        self.base[k] as usize..self.base[k + 1] as usize
    }

    /// Which of its tables holds generation `k` at `level` (`level` a re-strip
    /// level or the one before, or any level where `k` is not live).
    fn which(&self, k: usize, level: u32) -> usize {
        let from = if k == 0 { 0 } else { self.restrip[k - 1] };
        match self.restrip.get(k) {
            _ if k > 0 && level < from => UNBORN,
            _ if k > 0 && level == from => BORN,
            Some(&t) if level >= t => DEAD,
            _ => LAST,
        }
    }

    /// Generation `k`'s strips' states at `level` (see [`Snapshots::which`]).
    pub(crate) fn states(&self, k: usize, level: u32) -> &[KeptState] {
        let at = self.state_at[4 * k + self.which(k, level)] as usize;
        &self.states[at..at + self.strips(k).len()]
    }

    /// Generation `k`'s buffer range and slots at `level` (its first or last level).
    pub(crate) fn block(&self, k: usize, level: u32) -> (&[u32], &[u32]) {
        let at = self.block_at[4 * k + self.which(k, level)] as usize;
        let r = at..at + self.range(k).len();
        (&self.labels[r.clone()], &self.slots[r])
    }

    /// Strip `s`'s kept walk nearest the new level of a move between `lo` and `hi`
    /// (coarser: the highest of its generation's first and last levels in `(lo,
    /// hi]`; finer: the lowest in `[lo, hi)`).
    pub(crate) fn find(&self, s: usize, lo: u32, hi: u32, coarser: bool) -> Option<Snapshot<'_>> {
        if self.restrip.is_empty() {
            return None;
        }
        let k = self.first.partition_point(|&f| f as usize <= s) - 1;
        let born = (k > 0).then(|| self.restrip[k - 1]);
        let last = self.restrip.get(k).map(|&t| t - 1);
        let level = if coarser {
            last.filter(|&l| l > lo && l <= hi).or(born.filter(|&l| l > lo && l <= hi))
        } else {
            born.filter(|&l| l >= lo && l < hi).or(last.filter(|&l| l >= lo && l < hi))
        }?;
        let (labels, slots) = self.block(k, level);
        let at = self.offset[s] as usize;
        let len = self.states(k, level)[s - self.first[k] as usize].len as usize;
        Some(Snapshot { level, labels: &labels[at..at + len], slots: &slots[at..at + len] })
    }

    /// Bytes held.
    pub(crate) fn memory_bytes(&self) -> usize {
        4 * (self.restrip.len()
            + self.first.len()
            + self.base.len()
            + self.offset.len()
            + self.state_at.len()
            + 4 * self.states.len()
            + self.block_at.len()
            + self.labels.len()
            + self.slots.len())
    }
}

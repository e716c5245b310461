//! Recovery of levels with coherence.

use crate::hint::prefetch;
use super::sets::{Sets, Version, AMBIGUOUS_VERSION, NO_VERSION};
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
/// strip, reads each strip's changes from where the last move left it (no search),
/// and re-reads only the slots that change between the two levels: the runs of
/// unchanged slots between them are copied from the old walk (moved within the
/// range where the strip got shorter or longer), and the slots before the first
/// change stay. A far jump (many changes in a strip) re-walks the changed strips
/// whole, as a new cursor would, except a strip that appears whole between the two
/// levels (it begins at a re-strip level, or ends at one when moving finer): it
/// starts from the walk the model keeps for it there, copied in, and moves on from
/// that level as a near move. A move across re-strip levels (which end every live
/// strip and begin new ones) first puts the cursor at the re-strip level nearest its
/// destination with the model's tables (one fill of restarts, one copy of the new
/// strips' ranges and of their states), then moves on as a near move.
/// [`Cursor::changed_range`] is what a renderer must upload again.
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
    /// Per strip, one record (a move reads one cache line of it per strip).
    state: Vec<StripState>,
    buffer: Vec<u32>,
    /// Parallel to `buffer`: the slot each current vertex came from (ascending
    /// within a strip's range), where a partial re-walk resumes.
    slot_at: Vec<u32>,
    changed: Vec<u32>,
    /// Scratch of a move across re-strip levels: the strips its copies changed,
    /// each with the end of what they wrote.
    crossed: Vec<(u32, u32)>,
    moves: u32,
    /// Scratch of a move: the changed slots of every changed strip, ascending
    /// per strip (`span_counts` of them each), with each one's version at the new
    /// level (an index in the model's versions, or [`NO_VERSION`]: look it up),
    /// where each strip's walk starts, the plan of one walk, and the changes of
    /// one strip as (slot, version) keys.
    spans: Vec<u32>,
    span_versions: Vec<u32>,
    span_counts: Vec<u32>,
    todo: Vec<u32>,
    plan: Vec<Piece>,
    keys: Vec<u64>,
    /// Per changed strip, 1 + its length before a kept walk was copied in (0:
    /// none was), and the one of the strip at hand.
    widened: Vec<u32>,
    widen: u32,
}

/// Where a strip stands at the cursor's level.
#[derive(Clone, Copy, Debug, Default)]
struct StripState {
    /// Where its range starts in the buffer.
    base: u32,
    /// Its current length.
    len: u32,
    /// The index in the model's change lists of its first change past the current
    /// level, and the end of its list.
    next: u32,
    end: u32,
    /// `[lo, hi)`: the levels where its current sequence holds (its validity
    /// interval, bounded by the change before `next` and `next`).
    lo: u32,
    hi: u32,
    /// The offsets in its range that its last re-walk wrote.
    written: (u32, u32),
    /// The move that last listed it (a move lists each strip once).
    stamp: u32,
}

/// A piece of a partial re-walk: a slot walked and its vertex, or a run
/// `[start, end)` of the old walk (offsets from where the re-walk starts) reused.
#[derive(Clone, Copy, Debug)]
enum Piece {
    Walked(u32, u32),
    Old(u32, u32),
}

impl Piece {
    fn len(&self) -> usize {
        match *self {
            Piece::Walked(..) => 1,
            Piece::Old(a, b) => (b - a) as usize,
        }
    }
}

/// A partial re-walk reads the changes (changed slots and beginnings) between the
/// two levels while they number at most the strip's current length over this (many
/// changes lie all along a strip, so copying the runs between them would not pay);
/// past that it re-walks the strip whole.
const PARTIAL_SCAN: usize = 4;

/// The most versions of a strip walked whole that a move asks for ahead (every
/// fifth: a cache line holds 5.3 of them).
const WHOLE_PREFETCH: usize = 320;

impl Sets {
    /// A cursor at `level` (clamped to the coarsest), every strip walked once, with
    /// restart index `u32::MAX`.
    pub fn cursor(&self, level: u32) -> Cursor<'_> {
        let strips = self.strip_count();
        let mut c = Cursor {
            sets: self,
            level: level.min(self.levels()),
            restart: crate::strip::DEFAULT_RESTART,
            state: (0..strips)
                .map(|s| StripState {
                    base: self.strip_slots[s] + s as u32,
                    end: self.change_offsets[s + 1],
                    ..StripState::default()
                })
                .collect(),
            buffer: vec![crate::strip::DEFAULT_RESTART; self.slot_count() + strips],
            slot_at: vec![super::END; self.slot_count() + strips],
            changed: Vec::with_capacity(strips),
            crossed: Vec::new(),
            moves: 0,
            spans: Vec::new(),
            span_versions: Vec::new(),
            span_counts: Vec::new(),
            todo: Vec::new(),
            plan: Vec::new(),
            keys: Vec::new(),
            widened: Vec::new(),
            widen: 0,
        };
        for s in 0..strips {
            let r = self.change_offsets[s] as usize..self.change_offsets[s + 1] as usize;
            c.state[s].next = (r.start + self.change_level[r].partition_point(|&l| l <= c.level)) as u32;
            c.rewalk(s, 0, 0..0, true);
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
        if let Some(kept) = sets.snapshots.crossing(old, level) {
            return self.cross(kept, level);
        }
        self.changed.clear();
        self.level = level;
        if level == old {
            return &self.changed;
        }
        let (lo, hi) = (old.min(level) as usize, old.max(level) as usize);
        // The strips that change at a level in (lo, hi]: from the per-level lists
        // when they hold fewer entries than there are strips, else by a scan.
        let listed = (sets.level_offsets[hi + 1] - sets.level_offsets[lo + 1]) as usize;
        if listed < self.state.len() {
            self.moves = self.moves.wrapping_add(1);
            if self.moves == 0 {
                self.state.iter_mut().for_each(|st| st.stamp = 0);
                self.moves = 1;
            }
            for &s in &sets.level_strips[sets.level_offsets[lo + 1] as usize..sets.level_offsets[hi + 1] as usize] {
                let st = &mut self.state[s as usize];
                if st.stamp != self.moves {
                    st.stamp = self.moves;
                    self.changed.push(s);
                }
            }
            self.changed.sort_unstable();
        } else {
            for (s, st) in self.state.iter().enumerate() {
                if level < st.lo || level >= st.hi {
                    self.changed.push(s as u32);
                }
            }
        }
        // Two passes, so that the versions a move reads (what a move waits on)
        // are fetched together: the changed slots of every strip, each with its
        // version at the new level taken from the change lists (one load, asked
        // for ahead); then the walks.
        self.spans.clear();
        self.span_versions.clear();
        self.todo.clear();
        self.span_counts.clear();
        self.widened.clear();
        let sets = self.sets;
        let coarser = level > old;
        for i in 0..self.changed.len() {
            let s = self.changed[i] as usize;
            let start = self.spans.len();
            self.widen = 0;
            let from = self.first_change(s, lo as u32, hi as u32, coarser);
            self.widened.push(self.widen);
            for &v in &self.span_versions[start..] {
                if v != NO_VERSION {
                    prefetch(&sets.versions[v as usize]);
                }
            }
            self.todo.push(from as u32);
        }
        // A strip walked whole reads its slots' versions in order: they lie
        // together, so the first lines of them are asked for.
        for i in 0..self.changed.len() {
            if self.todo[i] == 0 && self.span_counts[i] == 0 {
                let s = self.changed[i] as usize;
                let first = sets.version_offsets[sets.strip_slots[s] as usize] as usize;
                let last = sets.version_offsets[sets.strip_slots[s + 1] as usize] as usize;
                for at in (first..last.min(first + WHOLE_PREFETCH)).step_by(5) {
                    prefetch(&sets.versions[at]);
                }
            }
        }
        let mut start = 0;
        for i in 0..self.changed.len() {
            let s = self.changed[i] as usize;
            let count = self.span_counts[i] as usize;
            self.rewalk(s, self.todo[i] as usize, start..start + count, coarser);
            start += count;
            // A kept walk copied in wrote the range from its start; past the
            // longer of the old and new sequences it is restarts again.
            if self.widened[i] > 0 {
                let st = &mut self.state[s];
                st.written = (0, st.len.max(self.widened[i] - 1));
            }
        }
        &self.changed
    }

    /// The strips the last [`Cursor::set_level`] changed (empty for a new cursor).
    pub fn changed(&self) -> &[u32] {
        &self.changed
    }

    /// Where strip `s`'s walk changes between levels `lo` and `hi`: appends to
    /// `self.spans` the slots that change in `(lo, hi]`, ascending (their count to
    /// `self.span_counts`), moves its next
    /// change past the new level, and returns the offset in its range of the first
    /// changed slot; 0 and no slots (a whole walk) when too many changes lie
    /// between. The changes crossed are read from the strip's next change on, in
    /// the direction of the move, so a near move searches nothing.
    fn first_change(&mut self, s: usize, lo: u32, hi: u32, coarser: bool) -> usize {
        let sets = self.sets;
        let st = self.state[s];
        let levels = &sets.change_level;
        let cap = st.len as usize / PARTIAL_SCAN;
        let at = st.next as usize;
        let end = st.end as usize;
        // The changes crossed: `levels[a..b]`, those in (lo, hi].
        let (mut a, mut b) = (at, at);
        if coarser {
            while b < end && levels[b] <= hi && b - a <= cap {
                b += 1;
            }
            if b - a > cap {
                b += levels[b..end].partition_point(|&l| l <= hi);
            }
            self.state[s].next = b as u32;
        } else {
            // Every list starts at level 0, at or below `lo`: the scan stops there.
            while levels[a - 1] > lo && b - a <= cap {
                a -= 1;
            }
            if b - a > cap {
                let start = sets.change_offsets[s] as usize;
                a = start + levels[start..a].partition_point(|&l| l <= lo);
            }
            self.state[s].next = a as u32;
        }
        let start = self.spans.len();
        if b - a > cap {
            // A strip that appears whole between the two levels (a re-strip level)
            // starts from its kept walk there, then moves on as a near move.
            if let Some(snap) = sets.snapshots.find(s, lo, hi, coarser) {
                let (base, n, prior) = (st.base as usize, snap.labels.len(), st.len as usize);
                self.buffer[base..base + n].copy_from_slice(snap.labels);
                self.slot_at[base..base + n].copy_from_slice(snap.slots);
                if prior > n {
                    self.buffer[base + n..base + prior].fill(self.restart);
                }
                if self.widen == 0 {
                    self.widen = prior as u32 + 1;
                }
                let first = sets.change_offsets[s] as usize;
                let st = &mut self.state[s];
                st.next = (first + levels[first..end].partition_point(|&l| l <= snap.level)) as u32;
                st.len = n as u32;
                let (lo, hi) = if coarser { (snap.level, hi) } else { (lo, snap.level) };
                return self.first_change(s, lo, hi, coarser);
            }
            self.span_counts.push(0);
            return 0;
        }
        // Per changed slot, its version at the new level: coarser, the last one
        // crossed; finer, the one before the first crossed. A slot whose crossed
        // changes start no version (a beginning) or are ambiguous is looked up.
        self.keys.clear();
        self.keys
            .extend((a..b).map(|i| (sets.change_slot[i] as u64) << 32 | sets.change_version[i] as u64));
        self.keys.sort_unstable();
        let mut i = 0;
        while i < self.keys.len() {
            let slot = (self.keys[i] >> 32) as u32;
            let mut j = i;
            while j < self.keys.len() && (self.keys[j] >> 32) as u32 == slot {
                j += 1;
            }
            let first_v = self.keys[i] as u32;
            // Versions ascending, then AMBIGUOUS_VERSION, then NO_VERSION.
            let group = &self.keys[i..j];
            let ambiguous = group.iter().any(|&k| k as u32 == AMBIGUOUS_VERSION);
            let real = group.iter().rev().map(|&k| k as u32).find(|&v| v < AMBIGUOUS_VERSION);
            let v = match real {
                Some(last) if !ambiguous => {
                    if coarser {
                        last
                    } else {
                        first_v - 1
                    }
                }
                _ => NO_VERSION,
            };
            self.spans.push(slot);
            self.span_versions.push(v);
            i = j;
        }
        self.span_counts.push((self.spans.len() - start) as u32);
        let first = self.spans.get(start).copied().unwrap_or(super::END);
        let base = st.base as usize;
        self.slot_at[base..base + st.len as usize].partition_point(|&x| x < first)
    }

    /// Walks strip `s` at the current level into its range from offset `from` on
    /// (the slots before it unchanged since the last walk). With its changed slots,
    /// `self.spans[spans]` (empty: walk the whole
    /// rest), the runs of the old walk between them are copied instead of walked:
    /// a slot outside every span has the same vertex and successor at both levels,
    /// so once the walk meets a slot the old walk had, the two go on alike until
    /// the next span.
    fn rewalk(&mut self, s: usize, from: usize, spans: Range<usize>, coarser: bool) {
        let sets = self.sets;
        let base = self.state[s].base as usize;
        let old = self.state[s].len as usize;
        // The slot before `from` did not change: its successor is the old walk's.
        let mut x = if from == 0 {
            sets.head_at(s, self.level)
        } else if from < old {
            self.slot_at[base + from]
        } else {
            super::END
        };
        let level = self.level;
        let mut pos = base + from;
        if spans.is_empty() {
            // Nothing of the old walk is reused: straight into the range.
            let (buffer, slot_at) = (&mut self.buffer, &mut self.slot_at);
            sets.walk_slots(x, level, |y, v| {
                buffer[pos] = v;
                slot_at[pos] = y;
                pos += 1;
            });
            self.finish_walk(s, from, pos - base, old);
            return;
        }
        // First the plan: the walk's changed slots and the runs of the old walk
        // it reuses, read from the range as it is.
        self.plan.clear();
        let (span_versions, spans) = (&self.span_versions[spans.clone()], &self.spans[spans]);
        let old_slots = &self.slot_at[base + from..base + old];
        let (mut j, mut k, mut len) = (0, 0, from);
        while x != super::END {
            while j < spans.len() && spans[j] < x {
                j += 1;
            }
            if j == spans.len() || x < spans[j] {
                // Unchanged: where the old walk had x, reuse it up to the next
                // changed slot.
                while k < old_slots.len() && old_slots[k] < x {
                    k += 1;
                }
                if k < old_slots.len() && old_slots[k] == x {
                    let end = match spans.get(j) {
                        Some(&next) => k + old_slots[k..].partition_point(|&y| y < next),
                        None => old_slots.len(),
                    };
                    self.plan.push(Piece::Old(k as u32, end as u32));
                    len += end - k;
                    x = old_slots.get(end).copied().unwrap_or(super::END);
                    k = end;
                    continue;
                }
            }
            let v = match span_versions.get(j) {
                Some(&v) if v != NO_VERSION && spans[j] == x => {
                    let v: Version = sets.versions[v as usize];
                    debug_assert_eq!(v, sets.version_at(x, level));
                    v
                }
                _ => sets.version_at(x, level),
            };
            self.plan.push(Piece::Walked(x, v.label));
            len += 1;
            x = v.next;
        }
        // Then the writes, in place: a coarser level keeps a subset of the old
        // slots, each at or before its old place, so front to back; a finer one a
        // superset, each at or after it, so back to front.
        let (buffer, slot_at) = (&mut self.buffer[base..], &mut self.slot_at[base..]);
        // The end of what differs from the old walk (a run left in place does not).
        let mut differs = from;
        let mut put = |piece: &Piece, at: usize| match *piece {
            Piece::Walked(x, v) => {
                buffer[at] = v;
                slot_at[at] = x;
                differs = differs.max(at + 1);
            }
            Piece::Old(a, b) => {
                let src = from + a as usize..from + b as usize;
                if src.start != at {
                    differs = differs.max(at + src.len());
                    buffer.copy_within(src.clone(), at);
                    slot_at.copy_within(src, at);
                }
            }
        };
        if coarser {
            let mut at = from;
            for piece in &self.plan {
                put(piece, at);
                at += piece.len();
            }
        } else {
            let mut at = len;
            for piece in self.plan.iter().rev() {
                at -= piece.len();
                put(piece, at);
            }
        }
        self.finish_walk(s, from, len, old);
        if len == old {
            self.state[s].written.1 = differs as u32;
        }
    }

    /// After a walk of strip `s` from offset `from` to its new length `len`
    /// (`old` before): restarts where it shrank, and what was written.
    fn finish_walk(&mut self, s: usize, from: usize, len: usize, old: usize) {
        let levels = &self.sets.change_level;
        let st = &mut self.state[s];
        let base = st.base as usize;
        if len < old {
            self.buffer[base + len..base + old].fill(self.restart);
        }
        st.len = len as u32;
        st.written = (from as u32, len.max(old) as u32);
        let k = st.next as usize;
        st.lo = levels[k - 1];
        st.hi = if k < st.end as usize { levels[k] } else { u32::MAX };
    }

    /// The part of strip `s`'s range ([`Cursor::strip_range`]) that the last
    /// re-walk of `s` wrote: for a strip the last [`Cursor::set_level`] returned,
    /// what changed (from its first changed vertex to the end of the longer of its
    /// old and new sequences).
    pub fn changed_range(&self, s: usize) -> Range<usize> {
        let base = self.state[s].base as usize;
        let (a, b) = self.state[s].written;
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
        let st = &self.state[s];
        &self.buffer[st.base as usize..(st.base + st.len) as usize]
    }

    /// The non-empty strips at the current level.
    pub fn strips(&self) -> StripSet {
        let mut out = StripSet::new();
        for s in 0..self.state.len() {
            if self.state[s].len > 0 {
                out.push(self.strip(s));
            }
        }
        out
    }

    /// The tight buffer: non-empty strips separated by `restart`.
    pub fn compact(&self, restart: u32, out: &mut Vec<u32>) {
        out.clear();
        for s in 0..self.state.len() {
            if self.state[s].len > 0 {
                if !out.is_empty() {
                    out.push(restart);
                }
                out.extend_from_slice(self.strip(s));
            }
        }
    }

    /// Indices of the non-empty strips at the current level (without restarts).
    pub fn index_count(&self) -> usize {
        self.state.iter().map(|st| st.len as usize).sum()
    }
}

impl<'a> Cursor<'a> {
    /// A move to `level` across re-strip levels (see `snap.rs`): to the level `kept`
    /// by the model's tables (the range of the generation live before filled with
    /// restarts, the block of the one live at `kept` copied in, the states of the
    /// generations between copied), then on to `level` as a near move; the strips
    /// changed by either part, ascending.
    fn cross(&mut self, kept: u32, level: u32) -> &[u32] {
        let snaps = &self.sets.snapshots;
        let (was, now) = (snaps.generation(self.level), snaps.generation(kept));
        self.crossed.clear();
        for k in was.min(now)..=was.max(now) {
            let strips = snaps.strips(k);
            let range = snaps.range(k);
            if k == was {
                for s in strips.clone() {
                    if self.state[s].len > 0 {
                        self.crossed.push((s as u32, self.state[s].len));
                    }
                }
                self.buffer[range.clone()].fill(self.restart);
            } else if k == now {
                let (labels, slots) = snaps.block(k, kept);
                self.buffer[range.clone()].copy_from_slice(labels);
                self.slot_at[range].copy_from_slice(slots);
            }
            for (i, kept_state) in snaps.states(k, kept).iter().enumerate() {
                let st = &mut self.state[strips.start + i];
                if k == now && kept_state.len > 0 {
                    self.crossed.push(((strips.start + i) as u32, kept_state.len));
                }
                st.len = kept_state.len;
                st.next = kept_state.next;
                st.lo = kept_state.lo;
                st.hi = kept_state.hi;
            }
        }
        // The generations ascend with the strips' numbers: sorted, once each.
        if was > now {
            self.crossed.sort_unstable();
        }
        for &(s, end) in &self.crossed {
            self.state[s as usize].written = (0, end);
        }
        self.level = kept;
        self.set_level(level);
        // Both parts' strips, ascending, once each; a strip in both wrote from its
        // start to the furthest end of the two.
        let near = std::mem::take(&mut self.changed);
        let mut merged = Vec::with_capacity(near.len() + self.crossed.len());
        let (mut i, mut j) = (0, 0);
        while i < near.len() || j < self.crossed.len() {
            let a = near.get(i).copied().unwrap_or(u32::MAX);
            let (b, end) = self.crossed.get(j).copied().unwrap_or((u32::MAX, 0));
            if a < b {
                merged.push(a);
                i += 1;
            } else {
                if a == b {
                    let st = &mut self.state[a as usize];
                    st.written = (0, st.written.1.max(end));
                    i += 1;
                }
                merged.push(b);
                j += 1;
            }
        }
        self.changed = merged;
        &self.changed
    }
}

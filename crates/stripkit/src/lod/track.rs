//! A model's strips followed level by level, each level paying for what it changes.
//!
//! A [`crate::lod::Cursor`] re-walks every strip whose sequence changed, so going
//! through every level of a model with one long strip (a flat ribbon: every collapse
//! changes it) costs levels x the strip's length. [`Tracker`] keeps the current walk
//! of every strip as a linked list of slots with each slot's position parity, and at
//! each level re-walks only the stretch around the slots whose version changes there:
//! from two slots before the first one to where the old and the new walk meet again
//! past the last one (the model's successors move forward, so both walks are merged
//! by slot). It reports the triangles that stretch drew before (sign -1) and draws
//! now (sign +1), oriented as [`crate::strip::for_each_triangle`] orients them.
//!
//! Exact for any model the file reader accepts: where the walks meet with their
//! parities differing (an odd removal before the end of a strip: every later
//! triangle flips), the stretch runs to the strip's end when windings matter.

use super::sets::{Sets, END};

impl Sets {
    /// Checks that the strips draw, at every level, the triangle count the model gives
    /// ([`Sets::triangles_at`]): a read file whose counts add up but do not match its
    /// strips is caught here, not when a level is extracted. The strips are followed
    /// up from level 0, each level re-walking only the stretches of strips around its
    /// changes: O(slots + levels + the stretches changed), so a long strip that every
    /// level changes (a flat ribbon) is not walked whole at every level. Returns the
    /// first level that disagrees, with what the strips draw there.
    pub(crate) fn check_triangle_counts(&self) -> std::result::Result<(), (u32, u64)> {
        let mut drawn = 0i64;
        let mut tracker = Tracker::new(self, false, |_, _, by| drawn += by as i64);
        loop {
            let level = tracker.level();
            if drawn != self.triangles_at[level as usize] as i64 {
                return Err((level, drawn.max(0) as u64));
            }
            if level == self.levels() {
                return Ok(());
            }
            tracker.step(|_, _, by| drawn += by as i64);
        }
    }
}

/// The tracked walks and the model's changes bucketed by level.
pub(crate) struct Tracker<'a> {
    sets: &'a Sets,
    level: u32,
    /// Whether triangle windings matter (else only whether a triangle is degenerate).
    winding: bool,
    /// Per slot: its label and successor at the current level.
    label: Vec<u32>,
    next: Vec<u32>,
    /// Per slot on the current walk of its strip: its predecessor and position parity.
    prev: Vec<u32>,
    odd: Vec<bool>,
    on: Vec<bool>,
    /// Per strip: its first slot at the current level.
    head: Vec<u32>,
    slot_strip: Vec<u32>,
    /// `(slot, version index)` of the versions at each level past 0.
    by_level: Vec<u32>,
    versions: Vec<(u32, u32)>,
    /// `(strip, slot)` of the beginnings at each level past 0.
    begins_by_level: Vec<u32>,
    begins: Vec<(u32, u32)>,
    /// Per slot, the level whose change saved its old label and successor.
    saved_at: Vec<u32>,
    old_label: Vec<u32>,
    old_next: Vec<u32>,
    /// Per strip, the level that last changed it, and its bounds then.
    strip_at: Vec<u32>,
    bounds: Vec<(u32, u32, Option<u32>)>,
    touched: Vec<u32>,
    old_walk: Vec<u32>,
    new_walk: Vec<u32>,
}

/// `(items, key)` bucketed by key in `1..=levels`: the offsets and the items.
fn bucket(levels: usize, items: Vec<(u32, (u32, u32))>) -> (Vec<u32>, Vec<(u32, u32)>) {
    let mut offsets = vec![0u32; levels + 2];
    for &(l, _) in &items {
        offsets[l as usize + 1] += 1;
    }
    for i in 1..offsets.len() {
        offsets[i] += offsets[i - 1];
    }
    let mut fill = offsets.clone();
    let mut out = vec![(0, 0); items.len()];
    for (l, v) in items {
        out[fill[l as usize] as usize] = v;
        fill[l as usize] += 1;
    }
    (offsets, out)
}

impl<'a> Tracker<'a> {
    /// Level 0, every strip walked once; `emit(strip, triangle, 1)` for each of its
    /// non-degenerate triangles.
    pub(crate) fn new(sets: &'a Sets, winding: bool, mut emit: impl FnMut(u32, [u32; 3], i32)) -> Tracker<'a> {
        let slots = sets.slot_count();
        let strips = sets.strip_count();
        let levels = sets.levels() as usize;
        let mut label = vec![0u32; slots];
        let mut next = vec![END; slots];
        let mut items = Vec::new();
        for x in 0..slots {
            let r = sets.version_offsets[x] as usize..sets.version_offsets[x + 1] as usize;
            label[x] = sets.versions[r.start].label;
            next[x] = sets.versions[r.start].next;
            for i in r.start + 1..r.end {
                let l = sets.versions[i].level;
                if (1..=levels as u32).contains(&l) {
                    items.push((l, (x as u32, i as u32)));
                }
            }
        }
        let (by_level, versions) = bucket(levels, items);
        let mut slot_strip = vec![0u32; slots];
        let mut head = vec![END; strips];
        let mut items = Vec::new();
        for s in 0..strips {
            slot_strip[sets.strip_slots[s] as usize..sets.strip_slots[s + 1] as usize].fill(s as u32);
            let r = sets.begin_offsets[s] as usize..sets.begin_offsets[s + 1] as usize;
            head[s] = sets.begin_slot[r.start];
            for i in r.start + 1..r.end {
                let l = sets.begin_level[i];
                if (1..=levels as u32).contains(&l) {
                    items.push((l, (s as u32, sets.begin_slot[i])));
                }
            }
        }
        let (begins_by_level, begins) = bucket(levels, items);
        let mut t = Tracker {
            sets,
            level: 0,
            winding,
            label,
            next,
            prev: vec![END; slots],
            odd: vec![false; slots],
            on: vec![false; slots],
            head,
            slot_strip,
            by_level,
            versions,
            begins_by_level,
            begins,
            saved_at: vec![u32::MAX; slots],
            old_label: vec![0; slots],
            old_next: vec![END; slots],
            strip_at: vec![u32::MAX; strips],
            bounds: vec![(0, 0, None); strips],
            touched: Vec::new(),
            old_walk: Vec::new(),
            new_walk: Vec::new(),
        };
        for s in 0..strips {
            let mut walk = Vec::new();
            let mut x = t.head[s];
            while x != END {
                walk.push(x);
                x = t.next[x as usize];
            }
            t.relink(&walk, END, false);
            t.emit_windows(s as u32, &walk, false, 1, &mut emit);
        }
        t
    }

    /// The current level.
    pub(crate) fn level(&self) -> u32 {
        self.level
    }

    /// Moves up one level (no-op at the coarsest), `emit(strip, triangle, sign)` for
    /// every triangle of the re-walked stretches, before (-1) and after (+1); returns
    /// the strips whose sequence the level changes.
    pub(crate) fn step(&mut self, mut emit: impl FnMut(u32, [u32; 3], i32)) -> &[u32] {
        self.touched.clear();
        if self.level >= self.sets.levels() {
            return &self.touched;
        }
        let level = self.level + 1;
        let l = level as usize;
        // Each changed strip's first and last changed slot, whether its head moves,
        // and the old label and successor of each changed slot.
        for i in self.by_level[l] as usize..self.by_level[l + 1] as usize {
            let (x, vi) = self.versions[i];
            let s = self.slot_strip[x as usize];
            self.mark(s, level);
            let b = &mut self.bounds[s as usize];
            b.0 = b.0.min(x);
            b.1 = b.1.max(x);
            let xi = x as usize;
            if self.saved_at[xi] != level {
                self.saved_at[xi] = level;
                self.old_label[xi] = self.label[xi];
                self.old_next[xi] = self.next[xi];
            }
            let v = self.sets.versions[vi as usize];
            self.label[xi] = v.label;
            self.next[xi] = v.next;
        }
        for i in self.begins_by_level[l] as usize..self.begins_by_level[l + 1] as usize {
            let (s, h) = self.begins[i];
            self.mark(s, level);
            self.bounds[s as usize].2 = Some(h);
        }
        let mut touched = std::mem::take(&mut self.touched);
        touched.sort_unstable();
        for &s in &touched {
            self.rewalk(s, level, &mut emit);
        }
        self.touched = touched;
        self.level = level;
        &self.touched
    }

    fn mark(&mut self, s: u32, level: u32) {
        if self.strip_at[s as usize] != level {
            self.strip_at[s as usize] = level;
            self.bounds[s as usize] = (END, 0, None);
            self.touched.push(s);
        }
    }

    /// The successor of `x` on the walk before `level`.
    fn next_before(&self, x: u32, level: u32) -> u32 {
        if self.saved_at[x as usize] == level {
            self.old_next[x as usize]
        } else {
            self.next[x as usize]
        }
    }

    /// Re-walks strip `s` from two slots before its first change (or its head) to
    /// where the old and new walks meet past its last change with the same parity.
    fn rewalk(&mut self, s: u32, level: u32, emit: &mut impl FnMut(u32, [u32; 3], i32)) {
        let (first, last, new_head) = self.bounds[s as usize];
        let old_head = self.head[s as usize];
        // The stretch starts two slots before the first change on the old walk, or at
        // the head (also when the first changed slot is not on the old walk).
        let mut start = None;
        if new_head.is_none() && first != END && self.on[first as usize] {
            let p = self.prev[first as usize];
            if p != END && self.prev[p as usize] != END {
                start = Some(self.prev[p as usize]);
            }
        }
        let (mut o, mut n, odd_old, odd_new) = match start {
            Some(lo) => (lo, lo, self.odd[lo as usize], self.odd[lo as usize]),
            None => (old_head, new_head.unwrap_or(old_head), false, false),
        };
        let mut old_walk = std::mem::take(&mut self.old_walk);
        let mut new_walk = std::mem::take(&mut self.new_walk);
        old_walk.clear();
        new_walk.clear();
        let last = if first == END { None } else { Some(last) };
        loop {
            if o == END && n == END {
                break;
            }
            if o == n && last.is_none_or(|m| o > m) {
                // Past every change: the walks agree from here on, windings too unless
                // the parities differ.
                let po = odd_old ^ (old_walk.len() % 2 == 1);
                let pn = odd_new ^ (new_walk.len() % 2 == 1);
                if !self.winding || po == pn {
                    old_walk.push(o);
                    new_walk.push(n);
                    let z1 = self.next[o as usize];
                    if z1 != END {
                        old_walk.push(z1);
                        new_walk.push(z1);
                    }
                    break;
                }
            }
            if o < n {
                old_walk.push(o);
                o = self.next_before(o, level);
            } else if n < o {
                new_walk.push(n);
                n = self.next[n as usize];
            } else {
                old_walk.push(o);
                new_walk.push(n);
                o = self.next_before(o, level);
                n = self.next[n as usize];
            }
        }
        self.emit_windows_old(s, &old_walk, odd_old, level, emit);
        for &x in &old_walk {
            self.on[x as usize] = false;
        }
        let before = match start {
            Some(lo) => self.prev[lo as usize],
            None => END,
        };
        if start.is_none() {
            self.head[s as usize] = new_walk.first().copied().unwrap_or(END);
        }
        self.relink(&new_walk, before, odd_new);
        self.emit_windows(s, &new_walk, odd_new, 1, emit);
        self.old_walk = old_walk;
        self.new_walk = new_walk;
    }

    /// Marks `walk` as a stretch of the current walk after `before`, the first slot at
    /// parity `odd`.
    fn relink(&mut self, walk: &[u32], before: u32, odd: bool) {
        let mut p = before;
        for (i, &x) in walk.iter().enumerate() {
            let xi = x as usize;
            self.on[xi] = true;
            self.prev[xi] = p;
            self.odd[xi] = odd ^ (i % 2 == 1);
            p = x;
        }
    }

    /// The triangles of `walk` (labels now), the first at parity `odd`.
    fn emit_windows(&self, s: u32, walk: &[u32], odd: bool, sign: i32, emit: &mut impl FnMut(u32, [u32; 3], i32)) {
        self.windows(walk.iter().map(|&x| self.label[x as usize]), odd, |t| emit(s, t, sign));
    }

    /// The triangles of `walk` as it was before `level`, the first at parity `odd`.
    fn emit_windows_old(
        &self,
        s: u32,
        walk: &[u32],
        odd: bool,
        level: u32,
        emit: &mut impl FnMut(u32, [u32; 3], i32),
    ) {
        let label = |x: u32| {
            if self.saved_at[x as usize] == level {
                self.old_label[x as usize]
            } else {
                self.label[x as usize]
            }
        };
        self.windows(walk.iter().map(|&x| label(x)), odd, |t| emit(s, t, -1));
    }

    fn windows(&self, labels: impl Iterator<Item = u32>, odd: bool, mut emit: impl FnMut([u32; 3])) {
        let mut w = [0u32; 3];
        for (i, v) in labels.enumerate() {
            w = [w[1], w[2], v];
            if i >= 2 {
                let t = if odd ^ (i % 2 == 1) { [w[1], w[0], w[2]] } else { w };
                if !crate::strip::is_degenerate(&t) {
                    emit(t);
                }
            }
        }
    }
}

//! Whole walks kept for the strips that begin or end at a re-strip level.
//!
//! A re-strip level ([`super::Sets::build_restripping`]) ends every live strip and
//! begins a new set: a cursor move across it would walk every strip that appears
//! there slot by slot. The walk of each such strip at the level where it appears
//! (its beginning, or the level before its end when moving finer) is made once when
//! the model loads (the model walks them), so such a move copies it and goes
//! on as a near move from there.

/// Per strip, its walks at the levels where it appears whole: derived on load,
/// not stored in the file.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Snapshots {
    /// `level[offsets[s]..offsets[s + 1]]`: strip `s`'s walked levels, ascending;
    /// `starts[i]..starts[i + 1]` the walk's place in `labels` and `slots`.
    offsets: Vec<u32>,
    level: Vec<u32>,
    starts: Vec<u32>,
    /// The walks' vertices and the slots they come from.
    labels: Vec<u32>,
    slots: Vec<u32>,
}

/// One kept walk: its level, vertices and slots.
pub(crate) struct Snapshot<'a> {
    pub(crate) level: u32,
    pub(crate) labels: &'a [u32],
    pub(crate) slots: &'a [u32],
}

impl Snapshots {
    /// No walks for any strip ([`Snapshots::find`] finds none).
    pub(crate) fn none() -> Snapshots {
        Snapshots::default()
    }

    /// Walks to be added strip by strip: [`Snapshots::push`] each walk of a strip
    /// (levels ascending), then [`Snapshots::end_strip`].
    pub(crate) fn start() -> Snapshots {
        Snapshots { offsets: vec![0], starts: vec![0], ..Snapshots::default() }
    }

    /// Adds a walk at `level` of the strip at hand: its vertices and their slots.
    pub(crate) fn push(&mut self, level: u32, labels: &[u32], slots: &[u32]) {
        self.labels.extend_from_slice(labels);
        self.slots.extend_from_slice(slots);
        self.level.push(level);
        self.starts.push(self.labels.len() as u32);
    }

    /// Ends the strip at hand.
    pub(crate) fn end_strip(&mut self) {
        self.offsets.push(self.level.len() as u32);
    }

    /// Strip `s`'s kept walk nearest the new level of a move between `lo` and `hi`
    /// (coarser: the highest level in `(lo, hi]`; finer: the lowest in `[lo, hi)`).
    pub(crate) fn find(&self, s: usize, lo: u32, hi: u32, coarser: bool) -> Option<Snapshot<'_>> {
        if self.offsets.is_empty() {
            return None;
        }
        let r = self.offsets[s] as usize..self.offsets[s + 1] as usize;
        let levels = &self.level[r.clone()];
        let i = if coarser {
            let k = levels.partition_point(|&l| l <= hi);
            (k > 0 && levels[k - 1] > lo).then(|| k - 1)
        } else {
            let k = levels.partition_point(|&l| l < lo);
            (k < levels.len() && levels[k] < hi).then_some(k)
        }?;
        let i = r.start + i;
        let span = self.starts[i] as usize..self.starts[i + 1] as usize;
        Some(Snapshot { level: self.level[i], labels: &self.labels[span.clone()], slots: &self.slots[span] })
    }

    /// Bytes held.
    pub(crate) fn memory_bytes(&self) -> usize {
        4 * (self.offsets.len() + self.level.len() + self.starts.len() + self.labels.len() + self.slots.len())
    }
}

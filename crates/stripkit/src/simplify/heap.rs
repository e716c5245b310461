//! The simplifier's candidate heap: 16-byte entries (cost bits, the two vertices, a
//! tag of versions, placement choice and kind) in a 4-ary min-heap with an O(n)
//! `retain`. Only `collapse` uses it; it lives apart as the one building block of the
//! engine that holds no mesh state.

/// Candidate kinds kept in the heap.
pub(super) const KIND_EDGE: u8 = 0;
/// An edge whose cheaper direction was refused; this is the other direction.
pub(super) const KIND_EDGE_REVERSED: u8 = 1;
/// A non-edge vertex pair (pair contraction).
pub(super) const KIND_PAIR: u8 = 2;

/// A heap entry, 16 bytes (the heap is the hot spot: smaller entries, fewer cache
/// misses). Valid while both vertices still have the versions it was made with; the
/// versions are kept modulo 2^14, and a wrapped stale entry is harmless because the
/// collapse's position is recomputed and the collapse re-checked when popped.
/// Its cost is either a lower bound (placement choice 0) or exact for the placement
/// it names (see `CHOICE_END`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct Entry {
    /// Bits of the non-negative cost as f32: they order like the number.
    pub(super) cost: u32,
    pub(super) removed: u32,
    pub(super) kept: u32,
    /// Removed vertex's version (14 bits), kept vertex's version (14 bits), placement
    /// choice (2 bits), kind (2 bits).
    pub(super) tag: u32,
}

const VERSION_MASK: u32 = 0x3FFF;
/// Tag bits of the placement choice.
pub(super) const CHOICE_MASK: u32 = 0b1100;

pub(super) fn tag(version_removed: u32, version_kept: u32, kind: u8) -> u32 {
    ((version_removed & VERSION_MASK) << 18) | ((version_kept & VERSION_MASK) << 4) | kind as u32
}

/// The placement an entry's exact cost was computed for (tag bits 2 and 3): the kept
/// vertex's position, the midpoint or the quadric's minimiser; 0 for an entry keyed
/// by a lower bound.
pub(super) const CHOICE_END: u32 = 1;
pub(super) const CHOICE_MID: u32 = 2;
pub(super) const CHOICE_MIN: u32 = 3;

/// A 4-ary min-heap: four 16-byte children fill one cache line, and the tree is half
/// as deep as a binary heap's.
#[derive(Default)]
pub(super) struct QuadHeap {
    pub(super) items: Vec<Entry>,
    /// Pushes since the last `retain`.
    pub(super) pushes: usize,
}

impl QuadHeap {
    pub(super) fn push(&mut self, e: Entry) {
        self.pushes += 1;
        let mut i = self.items.len();
        self.items.push(e);
        while i > 0 {
            let parent = (i - 1) / 4;
            if self.items[parent] <= e {
                break;
            }
            self.items[i] = self.items[parent];
            i = parent;
        }
        self.items[i] = e;
    }

    /// Keeps only the entries `keep` accepts and restores the heap order in O(n)
    /// (Floyd's bottom-up construction).
    pub(super) fn retain(&mut self, mut keep: impl FnMut(&Entry) -> bool) {
        self.items.retain(|e| keep(e));
        let n = self.items.len();
        if n < 2 {
            return;
        }
        for i in (0..=(n - 2) / 4).rev() {
            self.sift_down(i);
        }
    }

    /// Moves the entry at `i` down until no child is smaller.
    fn sift_down(&mut self, mut i: usize) {
        let e = self.items[i];
        let n = self.items.len();
        loop {
            let first = 4 * i + 1;
            if first >= n {
                break;
            }
            let end = (first + 4).min(n);
            let mut best = first;
            for c in first + 1..end {
                if self.items[c] < self.items[best] {
                    best = c;
                }
            }
            if self.items[best] >= e {
                break;
            }
            self.items[i] = self.items[best];
            i = best;
        }
        self.items[i] = e;
    }

    pub(super) fn pop(&mut self) -> Option<Entry> {
        let last = self.items.pop()?;
        if self.items.is_empty() {
            return Some(last);
        }
        let top = self.items[0];
        self.items[0] = last;
        self.sift_down(0);
        Some(top)
    }

    /// `push(e)` then `pop()`, with one sift-down.
    pub(super) fn push_pop(&mut self, e: Entry) -> Entry {
        match self.items.first() {
            Some(&top) if top < e => {
                self.items[0] = e;
                self.sift_down(0);
                top
            }
            _ => e,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(x: u64) -> Entry {
        Entry { cost: (x % 1000) as u32, removed: (x >> 10) as u32 & 0xFFFF, kept: 7, tag: (x >> 30) as u32 & 0xFF }
    }

    #[test]
    fn heap_retain_keeps_exactly_the_accepted_entries_in_order() {
        let mut heap = QuadHeap::default();
        let mut all = Vec::new();
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..5000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let e = entry(x);
            heap.push(e);
            all.push(e);
        }
        // Pop some, then drop every entry with an odd removed vertex.
        all.sort();
        for e in all.drain(..1000) {
            assert_eq!(heap.pop(), Some(e));
        }
        heap.retain(|e| e.removed % 2 == 0);
        all.retain(|e| e.removed % 2 == 0);
        assert!(all.len() > 1500 && all.len() < 2500, "{}", all.len());
        assert_eq!(heap.items.len(), all.len());
        let mut popped = Vec::new();
        while let Some(e) = heap.pop() {
            popped.push(e);
        }
        assert_eq!(popped, all);
    }
}

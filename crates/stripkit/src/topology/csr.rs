//! Lists bucketed by a small integer key (compressed sparse rows): the one counting
//! sort behind every "vertex -> its triangles / corners / half-edges" list of the
//! crate.

use crate::strip::is_degenerate;

/// Values bucketed by key: bucket `k` is `values()[offsets()[k]..offsets()[k + 1]]`,
/// its entries in the order they were given. Built by a counting sort in two passes
/// over the entries: O(entries + buckets), two allocations.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Csr<T> {
    /// `buckets + 1` prefix sums (empty only for [`Csr::default`]).
    offsets: Vec<u32>,
    values: Vec<T>,
}

impl<T: Copy + Default> Csr<T> {
    /// Buckets `0..buckets` of the `(key, value)` entries, each bucket in entry order.
    /// `entries` is iterated twice (to count, then to fill), so it must give the same
    /// entries both times; every key must be below `buckets`, and there must be fewer
    /// than `u32::MAX` entries.
    pub fn from_entries<I>(buckets: usize, entries: I) -> Csr<T>
    where
        I: IntoIterator<Item = (usize, T)> + Clone,
    {
        Csr::from_items(buckets, entries, |e| e.0, |e| e.1)
    }

    /// [`Csr::from_entries`] for items whose value costs more than their key:
    /// bucket `key(&item)` gets `value(item)`, and the counting pass computes only the
    /// keys.
    pub fn from_items<I, E>(
        buckets: usize,
        items: I,
        key: impl Fn(&E) -> usize,
        value: impl Fn(E) -> T,
    ) -> Csr<T>
    where
        I: IntoIterator<Item = E> + Clone,
    {
        let mut offsets = vec![0u32; buckets + 1];
        items.clone().into_iter().for_each(|e| offsets[key(&e) + 1] += 1);
        for k in 0..buckets {
            offsets[k + 1] += offsets[k];
        }
        let mut values = vec![T::default(); offsets[buckets] as usize];
        // Each bucket's next free slot; ends up at the bucket's end.
        let mut fill = offsets.clone();
        items.into_iter().for_each(|e| {
            let k = key(&e);
            values[fill[k] as usize] = value(e);
            fill[k] += 1;
        });
        Csr { offsets, values }
    }
}

impl<T> Csr<T> {
    /// Number of buckets.
    #[cfg(test)]
    pub fn buckets(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// Bucket `k`.
    #[inline]
    pub fn bucket(&self, k: usize) -> &[T] {
        &self.values[self.offsets[k] as usize..self.offsets[k + 1] as usize]
    }

    /// Bucket `k`, to reorder in place.
    #[inline]
    pub fn bucket_mut(&mut self, k: usize) -> &mut [T] {
        &mut self.values[self.offsets[k] as usize..self.offsets[k + 1] as usize]
    }

    /// The prefix sums: bucket `k` is `offsets[k]..offsets[k + 1]` of [`Csr::values`].
    pub fn offsets(&self) -> &[u32] {
        &self.offsets
    }

    /// Every bucket's values, bucket after bucket.
    pub fn values(&self) -> &[T] {
        &self.values
    }

    /// The prefix sums and the values.
    pub fn into_parts(self) -> (Vec<u32>, Vec<T>) {
        (self.offsets, self.values)
    }
}

/// Finds the free entries of a [`Csr`]'s buckets while entries are only ever taken
/// (a stripifier's triangles around a vertex): a taken position points past itself for
/// good (`skip`, compressed along the path followed), so every taken position is stepped
/// over O(1) times amortised and a bucket's free entries are found without rescanning
/// its taken ones, whatever the valence.
#[derive(Clone, Debug)]
pub struct FreeCursor {
    skip: Vec<u32>,
}

impl FreeCursor {
    /// A cursor over `len` positions (the length of the `Csr`'s values), all free.
    pub fn new(len: usize) -> Self {
        FreeCursor { skip: (0..len as u32).collect() }
    }

    /// The first position from `start` on, before `end` (the end of `start`'s bucket),
    /// whose value `taken` does not hold, or `end`. `taken` must never turn false again
    /// for a value it once held for.
    #[inline]
    pub fn next_free<T: Copy>(&mut self, start: u32, end: u32, values: &[T], taken: impl Fn(T) -> bool) -> u32 {
        let mut i = start;
        while i < end {
            let s = self.skip[i as usize];
            if s != i {
                i = s;
                continue;
            }
            if !taken(values[i as usize]) {
                break;
            }
            self.skip[i as usize] = i + 1;
            i += 1;
        }
        // Path compression: every position followed from `start` is taken.
        let mut j = start;
        while j < i {
            let next = self.skip[j as usize];
            self.skip[j as usize] = i;
            j = next;
        }
        i
    }

    /// At most `limit` free values of bucket `k` of `csr`, in bucket order.
    pub fn free_in<T: Copy>(&mut self, csr: &Csr<T>, k: usize, limit: usize, taken: impl Fn(T) -> bool, out: &mut Vec<T>) {
        let (start, end) = (csr.offsets()[k], csr.offsets()[k + 1]);
        let mut i = self.next_free(start, end, csr.values(), &taken);
        let mut n = 0;
        while i < end && n < limit {
            out.push(csr.values()[i as usize]);
            n += 1;
            i = self.next_free(i + 1, end, csr.values(), &taken);
        }
    }
}

/// Vertex -> its non-degenerate triangles, each list in increasing triangle id. Every
/// index of `tris` must be below `vertex_count`.
pub fn vertex_triangles(tris: &[[u32; 3]], vertex_count: usize) -> Csr<u32> {
    Csr::from_entries(
        vertex_count,
        tris.iter()
            .enumerate()
            .filter(|(_, t)| !is_degenerate(t))
            .flat_map(|(i, t)| t.map(|v| (v as usize, i as u32))),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buckets_keep_entry_order() {
        let c = Csr::from_entries(4, [(2, 'a'), (0, 'b'), (2, 'c'), (3, 'd'), (2, 'e')]);
        assert_eq!(c.buckets(), 4);
        assert_eq!(c.offsets(), &[0, 1, 1, 4, 5]);
        assert_eq!(c.bucket(0), &['b']);
        assert!(c.bucket(1).is_empty());
        assert_eq!(c.bucket(2), &['a', 'c', 'e']);
        assert_eq!(c.values(), &['b', 'a', 'c', 'e', 'd']);
        let empty = Csr::<u32>::from_entries(0, []);
        assert_eq!((empty.buckets(), empty.values().len()), (0, 0));
        assert_eq!(Csr::<u32>::default().buckets(), 0);
    }

    #[test]
    fn vertex_triangles_skip_degenerate_ones() {
        let c = vertex_triangles(&[[0, 1, 2], [2, 2, 3], [2, 1, 3]], 5);
        assert_eq!(c.bucket(1), &[0, 2]);
        assert_eq!(c.bucket(2), &[0, 2]);
        assert_eq!(c.bucket(3), &[2]);
        assert!(c.bucket(4).is_empty());
    }
}

//! How many threads the library may use, and the one way it uses them.
//!
//! Work is split by the data (files, primitives, groups, frames, candidates), never
//! by the thread count, and results come back in input order, so every output is the
//! same bytes at any [`Threads`] setting. The library runs serially unless a caller
//! asks for more ([`Threads::default`] is one thread); with the `parallel` feature off
//! every setting runs serially.
//!
//! ```
//! use stripkit::parallel::{map_ordered, Threads};
//!
//! let squares = map_ordered(Threads::new(4), &[1, 2, 3], |x| x * x);
//! assert_eq!(squares, [1, 4, 9]);
//! assert_eq!(squares, map_ordered(Threads::SERIAL, &[1, 2, 3], |x| x * x));
//! ```

/// A thread count: 1 is the serial path (the default), 0 means every core.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Threads(usize);

impl Threads {
    /// One thread: everything runs on the caller's thread.
    pub const SERIAL: Threads = Threads(1);
    /// Every core the machine reports.
    pub const ALL: Threads = Threads(0);

    /// `n` threads; 0 means every core.
    pub const fn new(n: usize) -> Threads {
        Threads(n)
    }

    /// The number of threads this setting stands for (at least 1). With the
    /// `parallel` feature off this is always 1.
    pub fn count(self) -> usize {
        if !cfg!(feature = "parallel") {
            return 1;
        }
        match self.0 {
            0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
            n => n,
        }
    }

    /// Whether this setting runs everything on the caller's thread.
    pub fn is_serial(self) -> bool {
        self.count() == 1
    }

    /// Runs `f` with this many threads available to every [`map_ordered`] and
    /// [`join`] inside it (they share one pool instead of each starting its own).
    /// Serial settings call `f` directly.
    pub fn install<R: Send>(self, f: impl FnOnce() -> R + Send) -> R {
        #[cfg(feature = "parallel")]
        if !self.is_serial() && !in_pool() {
            if let Some(pool) = pool(self.count()) {
                return pool.install(f);
            }
        }
        f()
    }
}

impl Default for Threads {
    /// One thread: the library never starts threads a caller did not ask for.
    fn default() -> Threads {
        Threads::SERIAL
    }
}

impl std::fmt::Display for Threads {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.0 {
            0 => write!(f, "all cores"),
            n => write!(f, "{n}"),
        }
    }
}

/// `f` applied to every item, results in the items' order whatever the thread count.
///
/// With more than one thread the items run in parallel (inside an enclosing
/// [`Threads::install`] its pool, else a pool of `threads` made for this call). `f`
/// must not depend on which thread runs it; errors are results like any other (the
/// caller picks the first in input order, so the same error is reported at any count).
pub fn map_ordered<T: Sync, R: Send>(threads: Threads, items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    #[cfg(feature = "parallel")]
    if !threads.is_serial() && items.len() > 1 {
        use rayon::prelude::*;
        return threads.install(|| items.par_iter().map(&f).collect());
    }
    let _ = threads;
    items.iter().map(f).collect()
}

/// [`map_ordered`] over the indices `0..n`.
pub fn map_range<R: Send>(threads: Threads, n: usize, f: impl Fn(usize) -> R + Sync) -> Vec<R> {
    #[cfg(feature = "parallel")]
    if !threads.is_serial() && n > 1 {
        use rayon::prelude::*;
        return threads.install(|| (0..n).into_par_iter().map(&f).collect());
    }
    let _ = threads;
    (0..n).map(f).collect()
}

/// Runs `f(i)` for every `i` of `order`, handing the items out one at a time, in
/// that order, to the pool's threads as each becomes free: put the longest first and
/// no thread is left with a long item at the end (longest first scheduling). Serial
/// settings run them in `order` on the caller's thread. What `f` does with an item
/// must not depend on which thread runs it; results are the caller's to gather.
pub fn for_each_queued(threads: Threads, order: &[usize], f: impl Fn(usize) + Sync) {
    #[cfg(feature = "parallel")]
    if !threads.is_serial() && order.len() > 1 {
        use std::sync::atomic::{AtomicUsize, Ordering};
        let next = AtomicUsize::new(0);
        let work = || loop {
            let k = next.fetch_add(1, Ordering::Relaxed);
            match order.get(k) {
                Some(&i) => f(i),
                None => break,
            }
        };
        threads.install(|| {
            let workers = rayon::current_num_threads().min(order.len());
            rayon::scope(|s| {
                for _ in 1..workers {
                    s.spawn(|_| work());
                }
                work();
            })
        });
        return;
    }
    let _ = threads;
    order.iter().for_each(|&i| f(i));
}

/// Runs `a` and `b`, in parallel when `threads` allows, and returns both results.
pub fn join<A: Send, B: Send>(threads: Threads, a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    #[cfg(feature = "parallel")]
    if !threads.is_serial() {
        return threads.install(|| rayon::join(a, b));
    }
    let _ = threads;
    (a(), b())
}

/// Sorts `v`, in parallel when `threads` allows. Meant for types whose equal values
/// cannot be told apart (integers, arrays of them): the sorted slice is then the same
/// at any thread count.
pub fn sort_unstable<T: Ord + Send>(threads: Threads, v: &mut [T]) {
    #[cfg(feature = "parallel")]
    if !threads.is_serial() && v.len() > PART {
        use rayon::prelude::*;
        return threads.install(|| v.par_sort_unstable());
    }
    let _ = threads;
    v.sort_unstable();
}

/// Sorts `v` by `compare`, in parallel when `threads` allows. `compare` must be a total
/// order in which only indistinguishable items tie: the sorted slice is then the same
/// at any thread count.
pub fn sort_unstable_by<T: Send>(
    threads: Threads,
    v: &mut [T],
    compare: impl Fn(&T, &T) -> std::cmp::Ordering + Sync,
) {
    #[cfg(feature = "parallel")]
    if !threads.is_serial() && v.len() > PART {
        use rayon::prelude::*;
        return threads.install(|| v.par_sort_unstable_by(&compare));
    }
    let _ = threads;
    v.sort_unstable_by(compare);
}

/// Applies `f` to every item in place, in parallel when `threads` allows (parts of
/// [`PART`] items).
pub fn for_each_mut<T: Send>(threads: Threads, v: &mut [T], f: impl Fn(&mut T) + Sync) {
    #[cfg(feature = "parallel")]
    if !threads.is_serial() && v.len() > PART {
        use rayon::prelude::*;
        return threads.install(|| v.par_chunks_mut(PART).for_each(|part| part.iter_mut().for_each(&f)));
    }
    let _ = threads;
    v.iter_mut().for_each(f);
}

/// Items per part where a flat array is cut for parallel work: the cut depends on the
/// array's length only.
pub const PART: usize = 1 << 16;

/// `fill` run on consecutive parts of `out`, in parallel when `threads` allows:
/// part `k` (its first index in `starts[k]`, ascending from 0, the end being
/// `out.len()`) gets `fill(k, &mut out[starts[k]..starts[k + 1]])`.
pub fn fill_parts<T: Send>(threads: Threads, out: &mut [T], starts: &[usize], fill: impl Fn(usize, &mut [T]) + Sync) {
    let mut parts: Vec<&mut [T]> = Vec::with_capacity(starts.len());
    let mut rest = out;
    let mut at = 0;
    for (k, &start) in starts.iter().enumerate() {
        let end = starts.get(k + 1).copied().unwrap_or(at + rest.len());
        debug_assert!(start == at && end >= start);
        let (part, tail) = rest.split_at_mut(end - start);
        parts.push(part);
        rest = tail;
        at = end;
    }
    #[cfg(feature = "parallel")]
    if !threads.is_serial() && parts.len() > 1 {
        use rayon::prelude::*;
        return threads.install(|| parts.into_par_iter().enumerate().for_each(|(k, part)| fill(k, part)));
    }
    let _ = threads;
    for (k, part) in parts.into_iter().enumerate() {
        fill(k, part);
    }
}

/// Whether the caller already runs on one of a pool's threads (nested work then
/// shares that pool).
#[cfg(feature = "parallel")]
fn in_pool() -> bool {
    rayon::current_thread_index().is_some()
}

/// Stack of each pool thread: a main thread's usual 8 MiB, so that work moved onto
/// the pool has the room it had on the caller's thread.
#[cfg(feature = "parallel")]
const STACK_BYTES: usize = 8 << 20;

/// A pool of `n` threads, made for one call; `None` when the system refuses threads
/// (the work then runs serially, with the same results).
#[cfg(feature = "parallel")]
fn pool(n: usize) -> Option<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new().num_threads(n).stack_size(STACK_BYTES).build().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_keep_input_order_at_any_count() {
        let items: Vec<u64> = (0..1000).map(|i| (i * 7919) % 1013).collect();
        let serial = map_ordered(Threads::SERIAL, &items, |&x| x * x + 1);
        for n in [0, 2, 3, 4, 8] {
            assert_eq!(map_ordered(Threads::new(n), &items, |&x| x * x + 1), serial);
            assert_eq!(map_range(Threads::new(n), items.len(), |i| items[i] * items[i] + 1), serial);
        }
    }

    #[test]
    fn nested_maps_and_joins_share_one_pool() {
        let t = Threads::new(3);
        let table = t.install(|| map_range(t, 10, |i| map_range(t, 10, move |j| i * j)));
        assert_eq!(table[7][9], 63);
        let (a, b) = join(t, || map_range(t, 5, |i| i).len(), || 2);
        assert_eq!((a, b), (5, 2));
    }

    #[test]
    fn queued_items_run_once_each_at_any_count() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        let order: Vec<usize> = (0..200).map(|i| (i * 37) % 200).collect();
        for n in [1, 2, 3, 8] {
            let runs: Vec<AtomicUsize> = (0..200).map(|_| AtomicUsize::new(0)).collect();
            let started = std::sync::Mutex::new(Vec::new());
            for_each_queued(Threads::new(n), &order, |i| {
                started.lock().unwrap().push(i);
                runs[i].fetch_add(1, Ordering::Relaxed);
            });
            assert!(runs.iter().all(|r| r.load(Ordering::Relaxed) == 1), "{n} threads");
            let started = started.into_inner().unwrap();
            if n == 1 {
                assert_eq!(started, order, "the serial path runs them in the order given");
            }
            // Handed out in order: the first item given is among the first n started.
            assert!(started[..n.min(200)].contains(&order[0]), "{n} threads");
        }
    }

    #[test]
    fn default_is_serial_and_counts_are_positive() {
        assert_eq!(Threads::default(), Threads::SERIAL);
        assert!(Threads::default().is_serial());
        assert!(Threads::ALL.count() >= 1);
        assert_eq!(Threads::ALL.to_string(), "all cores");
    }
}

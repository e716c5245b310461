//! Free triangles by free degree: the bucket queue of the greedy stripifier, which
//! the cache-aware stripifier uses too for its jumps to a corner of the free region.

use crate::strip::is_degenerate;
use crate::topology::DualGraph;

/// Free triangles bucketed by degree, most recently (re)inserted first.
///
/// The paper keeps one intrusive doubly linked list per degree and moves a triangle to
/// the front of the next lower list when its degree drops. The same order comes out of
/// one stack per degree with lazy deletion: a degree change pushes the triangle on the
/// lower stack (a degree only falls, so a triangle enters each stack at most once) and
/// leaves a stale entry behind, which [`Buckets::lowest`] skips (its degree or freedom no
/// longer matches). Pushes are sequential writes instead of three random ones per move,
/// which on a million triangles halves the running time; the strips are the same.
pub(super) struct Buckets {
    stacks: [Vec<u32>; 4],
    /// Free dual neighbours of each triangle (valid while it is free).
    pub(super) degree: Vec<u8>,
    /// Not yet in a strip (empty when built by [`Buckets::without_flags`], whose user
    /// knows that itself).
    pub(super) free: Vec<bool>,
}

impl Buckets {
    fn new(n: usize) -> Self {
        Buckets {
            stacks: std::array::from_fn(|_| Vec::with_capacity(n)),
            degree: vec![0; n],
            free: Vec::new(),
        }
    }

    /// Every non-degenerate triangle of `tris` free, with its degree in `graph`; each
    /// bucket in input order.
    pub(super) fn of(tris: &[[u32; 3]], graph: &DualGraph) -> Self {
        Self::with_degrees(tris, |t| graph.degree(t) as u8)
    }

    /// As [`Buckets::of`], triangle `t` having `degree(t)` dual neighbours.
    pub(super) fn with_degrees(tris: &[[u32; 3]], degree: impl Fn(usize) -> u8) -> Self {
        let mut b = Self::without_flags(tris, degree);
        b.free = tris.iter().map(|t| !is_degenerate(t)).collect();
        b
    }

    /// As [`Buckets::with_degrees`], without the `free` flags: for a user that knows
    /// which triangles are free and calls [`Buckets::compact_by`] and
    /// [`Buckets::lowest_by`] (one byte per triangle less).
    pub(super) fn without_flags(tris: &[[u32; 3]], degree: impl Fn(usize) -> u8) -> Self {
        let n = tris.len();
        let mut b = Buckets::new(n);
        // Inserted in reverse so that each bucket starts in input order.
        for t in (0..n).rev() {
            if !is_degenerate(&tris[t]) {
                b.push_front(t as u32, degree(t));
            }
        }
        b
    }

    /// Puts free triangle `t` at the front of degree `d`.
    #[inline]
    pub(super) fn push_front(&mut self, t: u32, d: u8) {
        self.stacks[d as usize].push(t);
        self.degree[t as usize] = d;
    }

    /// Entries held, stale ones included.
    pub(super) fn held(&self) -> usize {
        self.stacks.iter().map(Vec::len).sum()
    }

    /// Drops the stale entries (the order of the others kept: [`Buckets::lowest`]
    /// answers as before) and gives back the memory they held; `is_free` says which
    /// triangles are free.
    pub(super) fn compact_by(&mut self, is_free: impl Fn(u32) -> bool) {
        let degree = &self.degree;
        for (d, stack) in self.stacks.iter_mut().enumerate() {
            stack.retain(|&t| is_free(t) && degree[t as usize] as usize == d);
            stack.shrink_to_fit();
        }
    }

    /// The first free triangle of the lowest degree, dropping stale entries on the way.
    pub(super) fn lowest(&mut self) -> Option<u32> {
        let free = std::mem::take(&mut self.free);
        let t = self.lowest_by(|t| free[t as usize]);
        self.free = free;
        t
    }

    /// As [`Buckets::lowest`], `is_free` saying which triangles are free.
    pub(super) fn lowest_by(&mut self, is_free: impl Fn(u32) -> bool) -> Option<u32> {
        for d in 0..4 {
            while let Some(&t) = self.stacks[d].last() {
                if is_free(t) && self.degree[t as usize] as usize == d {
                    return Some(t);
                }
                self.stacks[d].pop();
            }
        }
        None
    }
}

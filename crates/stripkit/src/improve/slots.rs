//! The walks under local search, one per *slot* (the strips in output order), with
//! their encoded strips and the per-triangle index the move generators read in O(1):
//! a triangle's slot, its position in the slot's walk, and the swaps of that walk up
//! to it.

use super::piece::{Piece, NONE};
use crate::strip::{joins_at_vertex, StripSet};
use crate::topology::walks::{inner_swap, walk, walk_swaps};
use crate::topology::{DualGraph, Walks};

pub(super) struct Slots<'a> {
    pub(super) tris: &'a [[u32; 3]],
    pub(super) graph: &'a DualGraph,
    /// Walk and encoded strip per slot (empty: the slot lost its strip).
    pub(super) walks: Vec<Vec<u32>>,
    pub(super) enc: Vec<Vec<u32>>,
    /// Triangle -> slot (NONE: in no walk), position in the slot's walk, and the swaps
    /// its walk needs at inner triangles up to it (see [`Slots::index_walk`]).
    pub(super) slot_of: Vec<u32>,
    pub(super) pos: Vec<u32>,
    pub(super) pre: Vec<u32>,
}

impl<'a> Slots<'a> {
    /// One slot per walk of `walks`, in order, each encoded and indexed.
    pub(super) fn new(tris: &'a [[u32; 3]], graph: &'a DualGraph, walks: &Walks) -> Self {
        let walks: Vec<Vec<u32>> = walks.iter().map(|w| w.to_vec()).collect();
        let mut slot_of = vec![NONE; tris.len()];
        for (k, w) in walks.iter().enumerate() {
            for &t in w {
                slot_of[t as usize] = k as u32;
            }
        }
        let enc = walks
            .iter()
            .map(|w| {
                let mut strip = Vec::with_capacity(w.len() + 4);
                walk(tris, graph, w.len(), |i| w[i], |v| strip.push(v));
                strip
            })
            .collect();
        let mut s = Slots {
            tris,
            graph,
            walks,
            enc,
            slot_of,
            pos: vec![0; tris.len()],
            pre: vec![0; tris.len()],
        };
        for k in 0..s.walks.len() {
            s.index_walk(k);
        }
        s
    }

    /// Number of slots.
    pub(super) fn len(&self) -> usize {
        self.walks.len()
    }

    /// Fills `pos` and `pre` for the walk of slot `k`: `pre[w[j]]` counts the swaps at
    /// `w[2..=j]`. A swap at an inner triangle depends only on it, the triangle after
    /// it and the two before (see [`crate::topology::walks`]): the swaps of a 4-window
    /// less those of its first three triangles.
    pub(super) fn index_walk(&mut self, k: usize) {
        let w = &self.walks[k];
        let mut acc = 0;
        for (j, &t) in w.iter().enumerate() {
            self.pos[t as usize] = j as u32;
            if j >= 2 && j + 1 < w.len() {
                acc += inner_swap(self.tris, self.graph, &w[j - 2..j + 2]);
            }
            self.pre[t as usize] = acc;
        }
    }

    /// Puts `walk`, encoded as `strip`, in slot `k` (index it with
    /// [`Slots::index_walk`] once every slot of a move is set).
    pub(super) fn set(&mut self, k: u32, walk: &[u32], strip: &[u32]) {
        for &t in walk {
            self.slot_of[t as usize] = k;
        }
        let k = k as usize;
        self.walks[k].clear();
        self.walks[k].extend_from_slice(walk);
        self.enc[k].clear();
        self.enc[k].extend_from_slice(strip);
    }

    /// Swaps inside the stored walk of `p` at `w[a..=b]` (none when `b < a`).
    pub(super) fn inner(&self, p: Piece, a: u32, b: u32) -> u32 {
        if b < a {
            return 0;
        }
        let w = &self.walks[p.slot as usize];
        self.pre[w[b as usize] as usize] - self.pre[w[a as usize - 1] as usize]
    }

    /// Swaps of the walk in slot `s` (its reading direction).
    pub(super) fn swaps(&self, s: u32) -> i64 {
        let w = &self.walks[s as usize];
        if w.len() < 3 {
            return 0;
        }
        i64::from(walk_swaps(self.tris, self.graph, &w[..3]) + self.pre[w[w.len() - 2] as usize])
    }

    /// Indices (with the restart) of the strip in slot `s`.
    pub(super) fn indices(&self, s: u32) -> i64 {
        self.enc[s as usize].len() as i64 + 1
    }

    /// Joins at a vertex between consecutive non-empty slots: the strips save that
    /// many restart indices once [`crate::strip::join_shared_ends`] has run.
    pub(super) fn vertex_joins(&self) -> u64 {
        let mut joins = 0;
        let mut prev: Option<&[u32]> = None;
        for s in self.enc.iter().filter(|s| !s.is_empty()) {
            if prev.is_some_and(|p| joins_at_vertex(p, s)) {
                joins += 1;
            }
            prev = Some(s);
        }
        joins
    }

    /// The strips of the non-empty slots, in order.
    pub(super) fn strips(&self) -> StripSet {
        let mut out = StripSet::new();
        for strip in self.enc.iter().filter(|s| !s.is_empty()) {
            out.push(strip);
        }
        out
    }
}

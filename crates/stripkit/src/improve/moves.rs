//! The moves of [`refine`]: new walks for a few slots of the output, written
//! as ranges of a pool, and the simple moves (reversals, joins, chains).
//!
//! [`refine`]: super::refine::refine

use super::piece::{ends, MOVE_SLOTS, NONE};
use super::slots::Slots;
use crate::topology::NO_NEIGHBOR;

/// A move of [`refine`]: up to [`MOVE_SLOTS`] strips (slots in the output order) get
/// new walks, ranges `(slot, start, len)` of a pool (len 0 empties the slot), sorted by
/// slot.
///
/// [`refine`]: super::refine::refine
#[derive(Clone, Copy, Default)]
pub(super) struct Move {
    pub(super) n: u8,
    pub(super) ch: [(u32, u32, u32); MOVE_SLOTS],
}

impl Move {
    pub(super) fn new(list: &[(u32, u32, u32)]) -> Move {
        let mut m = Move {
            n: list.len() as u8,
            ..Move::default()
        };
        m.ch[..list.len()].copy_from_slice(list);
        m.ch[..list.len()].sort_unstable_by_key(|c| c.0);
        m
    }
}

/// The moves generated for one strip: their new walks are ranges of `pool`.
#[derive(Default)]
pub(super) struct MoveList {
    pub(super) pool: Vec<u32>,
    pub(super) moves: Vec<Move>,
}

impl MoveList {
    pub(super) fn clear(&mut self) {
        self.pool.clear();
        self.moves.clear();
    }
}

/// Appends to `pool` each walk that joins `sw` at its end `n` to `xw` at its end `e`
/// (a dual neighbour of `n`), in `sw`'s direction, and calls `found` with its range.
pub(super) fn attach(
    pool: &mut Vec<u32>,
    sw: &[u32],
    n: u32,
    xw: &[u32],
    e: u32,
    mut found: impl FnMut(u32, u32),
) {
    let len = (sw.len() + xw.len()) as u32;
    let forward = xw[0] == e;
    if sw[sw.len() - 1] == n {
        let start = pool.len() as u32;
        pool.extend_from_slice(sw);
        if forward {
            pool.extend_from_slice(xw);
        } else {
            pool.extend(xw.iter().rev());
        }
        found(start, len);
    }
    if sw[0] == n {
        let start = pool.len() as u32;
        if forward {
            pool.extend(xw.iter().rev());
        } else {
            pool.extend_from_slice(xw);
        }
        pool.extend_from_slice(sw);
        found(start, len);
    }
}

/// The simple moves from the strip in slot `xs`: X read backwards; X joined to a strip
/// S whose end triangle is a dual neighbour of an end of X (X appended or prepended,
/// reversed as needed), the joined walk taking the place of S or of X; and, where the
/// neighbour `n` lies inside S = A n B, X joined to `A n` (or `n B`) while the part cut
/// off joins a third strip Z at one of its ends, the two new walks taking the places
/// of two of X, S and Z.
pub(super) fn simple_moves(slots: &Slots, xs: u32, out: &mut MoveList) {
    let x = xs as usize;
    let lx = slots.walks[x].len();
    let (xe, nx) = ends(&slots.walks[x]);
    let MoveList { pool, moves } = out;
    let xw = &slots.walks[x];
    if lx >= 2 {
        let start = pool.len() as u32;
        pool.extend(xw.iter().rev());
        moves.push(Move::new(&[(xs, start, lx as u32)]));
    }
    for &e in &xe[..nx] {
        for &n in &slots.graph.neighbors[e as usize] {
            if n == NO_NEIGHBOR {
                continue;
            }
            let s = slots.slot_of[n as usize];
            if s == xs || s == NONE {
                continue;
            }
            let sw = &slots.walks[s as usize];
            if sw[0] == n || sw[sw.len() - 1] == n {
                attach(pool, sw, n, xw, e, |start, len| {
                    moves.push(Move::new(&[(s, start, len), (xs, 0, 0)]));
                    moves.push(Move::new(&[(xs, start, len), (s, 0, 0)]));
                });
                continue;
            }
            // n inside S = A n B: X joins `A n` (B cut off) or `n B` (A cut
            // off); the part cut off joins a strip Z at one of its ends.
            let i = sw.iter().position(|&t| t == n).unwrap_or(0);
            for (kept, cut) in [(&sw[..=i], &sw[i + 1..]), (&sw[i..], &sw[..i])] {
                let mut joined = [(0u32, 0u32); 2];
                let mut nj = 0;
                attach(pool, kept, n, xw, e, |start, len| {
                    joined[nj] = (start, len);
                    nj += 1;
                });
                let (ce, nc) = ends(cut);
                for &p in &ce[..nc] {
                    for &q in &slots.graph.neighbors[p as usize] {
                        if q == NO_NEIGHBOR {
                            continue;
                        }
                        let z = slots.slot_of[q as usize];
                        if z == xs || z == s || z == NONE {
                            continue;
                        }
                        let zw = &slots.walks[z as usize];
                        if zw[0] != q && zw[zw.len() - 1] != q {
                            continue;
                        }
                        attach(pool, zw, q, cut, p, |zs, zl| {
                            for &(js, jl) in &joined[..nj] {
                                for (a, b, e) in [(s, z, xs), (xs, z, s), (xs, s, z)] {
                                    moves.push(Move::new(&[
                                        (a, js, jl),
                                        (b, zs, zl),
                                        (e, 0, 0),
                                    ]));
                                }
                            }
                        });
                    }
                }
            }
        }
    }
}

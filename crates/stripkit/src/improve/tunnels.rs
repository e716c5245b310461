//! The tunnels of `refine`: alternating paths through up to three strips. Why this
//! is a different search from greedy's tunnelling pass ([`super::tunnel`]) is written
//! at the top of that file.

use super::moves::{Move, MoveList};
use super::piece::{Piece, MOVE_SLOTS, NONE, REFINE_CUTS};
use super::slots::Slots;
use crate::topology::walks::walk_swaps;
use crate::topology::NO_NEIGHBOR;

/// Generates the tunnels of [`refine`] from one strip: alternating paths in the dual
/// graph that start at an end of the strip, cross to a triangle `n` of another strip
/// S = A n B, cut S on one side of `n` (the part with `n` joins the path so far), and
/// go on from the new end of the part cut off, through up to [`REFINE_CUTS`] strips.
/// A path stops at an end of a further strip (joined: one strip fewer) or after any
/// cut (the part cut off stays alone: as many strips, fewer swaps where the cut lies
/// at a swap). The index change of a path is counted in O(1) per strip on it (the
/// swaps inside each part from `pre`, the swaps around each join and at each new
/// start from windows of at most six triangles: a swap depends on four consecutive
/// triangles only, so this is the encoder's count but around non-manifold edges);
/// only paths with no more indices become moves, one per placement of the new walks in
/// the slots of the strips they came from, and `Refiner::eval` then counts their
/// indices (with the joins at a vertex, which the O(1) count does not see) and misses
/// exactly. The paths of as many indices are kept for those joins and for the misses
/// a relink may save (measured: fewer indices and a lower ACMR for about 20% more
/// time). Strips on a path are distinct, so no walk closes a cycle.
///
/// [`refine`]: super::refine::refine
pub(super) struct Tunnels<'a> {
    pub(super) s: &'a Slots<'a>,
    pub(super) out: &'a mut MoveList,
    /// Slots of the strips on the path, and the walks joined so far (the part cut off
    /// from the strip before, the part of the next strip with its crossing triangle).
    pub(super) used: &'a mut Vec<u32>,
    pub(super) joins: &'a mut Vec<(Piece, Piece)>,
}

impl Tunnels<'_> {
    /// Swaps of the walk `a` then `b` (`b` may be empty), each in its direction.
    /// Windows that lie inside one part are the stored walk's (a swap does not depend
    /// on the direction of reading, only the first triangles' does); the others are
    /// walked: the first three triangles and the six around the join.
    fn swaps(&self, a: Piece, b: Option<Piece>) -> u32 {
        let la = a.len();
        let lb = b.map_or(0, |b| b.len());
        let n = la + lb;
        if n < 3 {
            return 0;
        }
        if lb == 0 {
            let head = [
                a.at(&self.s.walks, 0),
                a.at(&self.s.walks, 1),
                a.at(&self.s.walks, 2),
            ];
            return walk_swaps(self.s.tris, self.s.graph, &head)
                + self.s.inner(a, a.lo + 2, a.hi.saturating_sub(2));
        }
        let at = |i: usize| {
            if i < la {
                a.at(&self.s.walks, i)
            } else {
                b.unwrap().at(&self.s.walks, i - la)
            }
        };
        let lo = la.saturating_sub(3);
        let hi = n.min(la + 3);
        let mut win = [0u32; 6];
        for i in lo..hi {
            win[i - lo] = at(i);
        }
        let mut s = walk_swaps(self.s.tris, self.s.graph, &win[..hi - lo]);
        if lo > 0 {
            let head = [at(0), at(1), at(2)];
            s = s + walk_swaps(self.s.tris, self.s.graph, &head) - walk_swaps(self.s.tris, self.s.graph, &win[..3]);
        }
        // Pair windows inside a part: stored positions lo + 2 ..= hi - 2.
        s += self.s.inner(a, a.lo + 2, a.hi.saturating_sub(2));
        if let Some(b) = b {
            s += self.s.inner(b, b.lo + 2, b.hi.saturating_sub(2));
        }
        s
    }

    /// Indices (with the restart) of the walk `a` then `b`.
    fn cost(&self, a: Piece, b: Option<Piece>) -> i64 {
        let len = a.len() + b.map_or(0, |b| b.len());
        (len + 3) as i64 + i64::from(self.swaps(a, b))
    }

    /// Tunnels from strip `x` (every end, every path).
    pub(super) fn search(&mut self, x: u32) {
        let w = &self.s.walks[x as usize];
        let lx = w.len() as u32;
        let nx = if lx >= 2 { 2 } else { lx };
        for j in 0..nx {
            let open = Piece {
                slot: x,
                lo: 0,
                hi: lx,
                rev: j == 0 && nx == 2,
            };
            self.used.clear();
            self.joins.clear();
            self.used.push(x);
            let acc = -self.s.indices(x);
            self.grow(open, 0, acc);
        }
    }

    /// Extends the path whose open walk `open` ends at its new end, after `cuts` cuts;
    /// `acc`: the indices of the joins so far less those of the strips on the path.
    fn grow(&mut self, open: Piece, cuts: usize, acc: i64) {
        let walks = &self.s.walks;
        let p = open.at(walks, open.len() - 1);
        for n in self.s.graph.neighbors[p as usize] {
            if n == NO_NEIGHBOR {
                continue;
            }
            let s = self.s.slot_of[n as usize];
            if s == NONE || self.used.contains(&s) {
                continue;
            }
            let l = walks[s as usize].len() as u32;
            let i = self.s.pos[n as usize];
            let acc = acc - self.s.indices(s);
            if i == 0 || i + 1 == l {
                // An end of S: joined (a single cut is the chain move of `refine`).
                if cuts >= 2 {
                    let q = Piece {
                        slot: s,
                        lo: 0,
                        hi: l,
                        rev: i != 0,
                    };
                    let (a, b) = open.join(q);
                    let di = acc + self.cost(a, Some(b));
                    if di <= 0 {
                        self.joins.push((a, b));
                        self.used.push(s);
                        self.emit(None);
                        self.used.pop();
                        self.joins.pop();
                    }
                }
                continue;
            }
            let sides = [
                (
                    Piece {
                        slot: s,
                        lo: 0,
                        hi: i + 1,
                        rev: true,
                    },
                    Piece {
                        slot: s,
                        lo: i + 1,
                        hi: l,
                        rev: true,
                    },
                ),
                (
                    Piece {
                        slot: s,
                        lo: i,
                        hi: l,
                        rev: false,
                    },
                    Piece {
                        slot: s,
                        lo: 0,
                        hi: i,
                        rev: false,
                    },
                ),
            ];
            for (kept, cut) in sides {
                let (a, b) = open.join(kept);
                let acc = acc + self.cost(a, Some(b));
                self.joins.push((a, b));
                self.used.push(s);
                let di = acc + self.cost(cut.alone(), None);
                if di <= 0 {
                    self.emit(Some(cut.alone()));
                }
                if cuts + 1 < REFINE_CUTS {
                    self.grow(cut, cuts + 1, acc);
                }
                self.used.pop();
                self.joins.pop();
            }
        }
    }

    /// Writes the new walks of the path (the joins, and `alone`, the part cut off last
    /// when the path stops after a cut) to the pool and makes one move per placement.
    fn emit(&mut self, alone: Option<Piece>) {
        let mut ranges = [(0u32, 0u32); MOVE_SLOTS];
        let mut m = 0;
        for &(a, b) in self.joins.iter() {
            let start = self.out.pool.len();
            a.extend(&self.s.walks, &mut self.out.pool);
            b.extend(&self.s.walks, &mut self.out.pool);
            ranges[m] = (start as u32, (self.out.pool.len() - start) as u32);
            m += 1;
        }
        if let Some(c) = alone {
            let start = self.out.pool.len();
            c.extend(&self.s.walks, &mut self.out.pool);
            ranges[m] = (start as u32, (self.out.pool.len() - start) as u32);
            m += 1;
        }
        let u = &self.used[..];
        let mut list = [(0u32, 0u32, 0u32); MOVE_SLOTS];
        if alone.is_none() {
            // m walks in m + 1 slots: walk j comes from slots j and j + 1; the slot
            // left empty is any of them.
            for g in 0..=m {
                for j in 0..m {
                    let k = if j < g { u[j] } else { u[j + 1] };
                    list[j] = (k, ranges[j].0, ranges[j].1);
                }
                list[m] = (u[g], 0, 0);
                self.out.moves.push(Move::new(&list[..=m]));
            }
        } else {
            // m walks in m slots: each joined walk in its first slot (the part cut off
            // in the last), or each in its second (the part cut off in the first).
            for j in 0..m {
                list[j] = (u[j], ranges[j].0, ranges[j].1);
            }
            self.out.moves.push(Move::new(&list[..m]));
            for j in 0..m - 1 {
                list[j] = (u[j + 1], ranges[j].0, ranges[j].1);
            }
            list[m - 1] = (u[0], ranges[m - 1].0, ranges[m - 1].1);
            self.out.moves.push(Move::new(&list[..m]));
        }
    }
}

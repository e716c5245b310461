//! The cache-aware stripifier proper: it grows one strip at a time while it simulates
//! exactly the FIFO of docs/metrics.md (a hit does not reorder, a miss evicts the oldest
//! entry):
//!
//! `evaluate` is about 155 lines long: it scores one candidate walk in one loop whose
//! steps share the walk's FIFO copy and counters, and it is the stripifier's hot path.
//!
//! * **Candidates.** Every free triangle around one of the oldest `scan_entries`
//!   entries of the FIFO that has at least `min_cached` cached vertices, with each of
//!   its three exit edges; and the end of the last strip, which may go on (a turn
//!   instead of a restart). When none of these exists, the scan widens before it
//!   jumps away from the cache: to the triangles around every entry, then to those
//!   with a single cached vertex; only when the cache touches no free triangle at all,
//!   the free triangle of lowest free degree (a corner of the free region, as in the
//!   greedy stripifier). A jump costs three misses at once and starts a region with a
//!   cold cache, so the wider scans pay on meshes whose free region falls apart into
//!   pockets (measured on bunny_res3, cow and bunny). Around one entry only its first
//!   [`FAN_CANDIDATES`] free triangles are offered (all of them on the shared models),
//!   found without rereading its taken ones: a vertex of very high valence costs
//!   O(1) per strip, not O(valence).
//! * **Walks.** From a candidate the strip follows its line through free triangles;
//!   it swaps (one repeated index) where the line is blocked, or where the line's next
//!   vertex would miss the cache while the swap's would hit: that keeps the strip
//!   hugging the cached side of the previous one on irregular meshes. At most
//!   `max_swaps` swaps, `max_len` triangles.
//! * **Choice.** Every prefix of every walk is scored by what it costs per triangle
//!   it covers: `(indices + miss_weight * misses + start_penalty * free neighbours
//!   of the first triangle left behind - finish_bonus * vertices finished) /
//!   triangles`, where `indices` counts the strip's indices and its restart index
//!   (none for going on from the last strip), and `misses` the FIFO misses the prefix
//!   causes after the strips already emitted. The cheapest prefix is emitted. A walk
//!   is abandoned as soon as no longer prefix can beat the best one found.
//!
//! Cost: O(T * c * L) for c candidates per strip (the free triangles around the
//! cache, at most `cache_size * FAN_CANDIDATES`) and walks of at most L triangles,
//! whatever the valences; flat arrays, nothing allocated per step.
//! A step reads the links of one triangle (neighbours and twin slots, see `links.rs`),
//! the vertices of the neighbours it may enter and the records of four vertices; the
//! walk that found the chosen strip is kept, not walked again.
//!
//! Memory (4.4M triangles, 2.2M vertices): the links 12 bytes per triangle, the
//! vertex-to-triangle lists 14 (a list's start kept in its first slot once it moves),
//! the free count per vertex 2 (a walk's own records in a table of about `4 * max_len`
//! slots), marks 8, buckets 6 to 10, the FIFO's stamps 2, the output 5; the walks
//! (4) only where the local search needs them.

use super::links::{nbr, opp, twin};
use super::CacheOptions;
use crate::stripify::buckets::Buckets;
use crate::metrics::Fifo;
use crate::strip::{is_degenerate, StripSet};
use crate::topology::{vertex_bound, vertex_triangles, Csr, Walks};

pub(super) const NONE: u32 = u32::MAX;
/// `mark` of a triangle already in a strip.
pub(super) const TAKEN: u32 = u32::MAX;
/// The bit of `mark` that says a triangle was offered as a candidate (see
/// [`State::consider`]); the other bits hold an epoch, always below `EPOCHS`.
pub(super) const OFFERED: u32 = 1 << 31;
/// The bit of a vertex list's first slot that says the list starts further on, by
/// the distance in the other bits (triangle ids, below 2^30, never have it).
const MOVED: u32 = 1 << 31;
/// [`WalkTable`] fields not set in the walk.
const UNSET: u32 = u32::MAX;
/// Epochs run from 1 to `EPOCHS - 1` (`EPOCHS | OFFERED` would read as TAKEN).
const EPOCHS: u32 = OFFERED - 1;
/// The slot after / before each slot of a triangle.
pub(super) const NEXT: [usize; 3] = [1, 2, 0];
pub(super) const PREV: [usize; 3] = [2, 0, 1];

/// What a walk reads and writes: its own records ([`WalkTable`]), the free triangle
/// count of every vertex, the triangle marks, the walk's epoch, the FIFO (read only:
/// the walk's own pushes go to its private copy in the records) and the walk's pushes
/// so far.
pub(super) struct Walk<'s> {
    pub(super) table: &'s mut WalkTable,
    pub(super) vfree: &'s [u32],
    pub(super) mark: &'s mut [u32],
    pub(super) epoch: u32,
    pub(super) fifo: &'s Fifo,
    pub(super) c: u32,
    pub(super) pushes: u32,
}

/// The records of the vertices one walk has seen, in a small open-addressed table
/// (linear probing, at most half full) rather than one record per vertex of the mesh:
/// a walk sees at most `max_len + 3` vertices. Each slot holds `[epoch, vertex, push,
/// covered]`: a slot of an older epoch is empty; in the walk of its epoch, `push` is
/// the walk's push count when it pushed the vertex in its private copy of the FIFO
/// and `covered` how many of the vertex's free triangles the walk covers (each UNSET
/// until then).
pub(super) struct WalkTable {
    slots: Vec<[u32; 4]>,
    shift: u32,
}

impl WalkTable {
    /// A table for walks of at most `max_len` triangles.
    pub(super) fn new(max_len: u32) -> Self {
        let size = (2 * (max_len as usize + 3)).next_power_of_two().max(16);
        WalkTable {
            slots: vec![[0, 0, UNSET, UNSET]; size],
            shift: 32 - size.trailing_zeros(),
        }
    }

    /// The slot of `v` in the walk of `epoch`, or the empty slot where it goes.
    #[inline(always)]
    fn find(&self, v: u32, epoch: u32) -> usize {
        let mask = self.slots.len() - 1;
        let mut i = (v.wrapping_mul(0x9e37_79b1) >> self.shift) as usize;
        loop {
            let s = &self.slots[i];
            if s[0] != epoch || s[1] == v {
                return i;
            }
            i = (i + 1) & mask;
        }
    }

    /// Empties every slot (when the epochs start again).
    fn clear(&mut self) {
        self.slots.iter_mut().for_each(|s| s[0] = 0);
    }
}

impl Walk<'_> {
    /// Free and not yet in the walk (a triangle or the sentinel of a link).
    #[inline(always)]
    fn is_open(&self, t: u32) -> bool {
        let m = self.mark[t as usize];
        m != TAKEN && m & EPOCHS != self.epoch
    }

    /// Whether `v`, whose slot ([`WalkTable::find`]) is `i`, is in the FIFO after the
    /// walk's pushes so far: a slot of an older walk holds nothing of this one.
    #[inline(always)]
    fn cached_at(&self, i: usize, v: u32) -> bool {
        let [mark, _, local, _] = self.table.slots[i];
        if mark == self.epoch && local != UNSET {
            return self.pushes - local <= self.c;
        }
        self.fifo.contains_after(v, self.pushes)
    }

    /// The slot of `v`'s record in this walk, the record started (nothing pushed,
    /// nothing covered) when new. The walk keeps the slots of its current triangle's
    /// vertices: a slot does not move while the walk lasts (nothing is removed).
    #[inline(always)]
    fn slot(&mut self, v: u32) -> usize {
        let i = self.table.find(v, self.epoch);
        self.start_record(i, v);
        i
    }

    /// Starts the record of `v` in slot `i` (where [`WalkTable::find`] put it, no
    /// record having been made since) unless it holds it already.
    #[inline(always)]
    fn start_record(&mut self, i: usize, v: u32) {
        let e = &mut self.table.slots[i];
        if e[0] != self.epoch {
            *e = [self.epoch, v, UNSET, UNSET];
        }
    }

    /// Feeds `v`, whose record is in slot `i`, to the walk's private copy of the FIFO;
    /// true on a miss.
    #[inline(always)]
    fn touch_at(&mut self, i: usize, v: u32) -> bool {
        if self.cached_at(i, v) {
            return false;
        }
        self.table.slots[i][2] = self.pushes;
        self.pushes += 1;
        true
    }

    /// Starts the covered count of the record in slot `i`, unless started.
    #[inline(always)]
    fn uncover_at(&mut self, i: usize) {
        let e = &mut self.table.slots[i];
        if e[3] == UNSET {
            e[3] = 0;
        }
    }

    /// Counts one more of the free triangles of `v` (its record in slot `i`, its count
    /// started) as covered by the walk; true when that was its last one.
    #[inline(always)]
    fn cover_at(&mut self, i: usize, v: u32) -> bool {
        let free = self.vfree[v as usize];
        let e = &mut self.table.slots[i];
        e[3] += 1;
        e[3] == free
    }
}

/// Where a walk stands after its first step (see [`State::evaluate`]): its cost so far,
/// its new triangles, the triangle it is at, the slot it entered that triangle by,
/// whether the natural exit is `NEXT[entry]`, the triangle's vertices from the
/// entry slot on and the slots of their records in the walk's table.
pub(super) struct Head {
    total: f32,
    len: u32,
    cur: u32,
    entry: usize,
    fwd: bool,
    r: [u32; 3],
    rs: [usize; 3],
}

impl Walk<'_> {
    /// A walk that goes on from the end `(a, b)` of the last strip, `t` (vertices
    /// `tri`) being its last triangle: no restart index, no start indices; the natural
    /// exit is the edge {a, b}, the swap exit the other edge at b.
    fn go_on(&mut self, t: u32, tri: [u32; 3], (a, b): (u32, u32), fb: f32) -> Head {
        let nat = (0..3)
            .find(|&k| {
                let (x, y) = (tri[k], tri[NEXT[k]]);
                (x == a && y == b) || (x == b && y == a)
            })
            .unwrap_or(0);
        let swp = if tri[NEXT[nat]] == b {
            NEXT[nat]
        } else {
            PREV[nat]
        };
        let entry = 3 - nat - swp;
        let s = tri.map(|v| self.slot(v));
        if fb != 0.0 {
            for i in s {
                self.uncover_at(i);
            }
        }
        let order = [entry, NEXT[entry], PREV[entry]];
        Head {
            total: 0.0,
            len: 0,
            cur: t,
            entry,
            fwd: nat == NEXT[entry],
            r: order.map(|k| tri[k]),
            rs: order.map(|k| s[k]),
        }
    }

    /// A new strip at `t` (vertices `tri`) leaving across `slot`: three indices and
    /// the restart, the misses of its vertices at `w` each, `fb` off for each vertex
    /// it finishes, and `penalty` for the free neighbours it leaves behind.
    fn start(&mut self, t: u32, tri: [u32; 3], slot: usize, w: f32, fb: f32, penalty: f32) -> Head {
        let r = start_of(tri, slot);
        let rs = r.map(|v| self.slot(v));
        let mut total = 4.0;
        for k in 0..3 {
            if self.touch_at(rs[k], r[k]) {
                total += w;
            }
        }
        // `t` was offered: `State::consider` set its OFFERED bit.
        self.mark[t as usize] = self.epoch | OFFERED;
        if fb != 0.0 {
            // Each vertex's count apart: the order does not matter.
            for k in 0..3 {
                let i = rs[k];
                self.uncover_at(i);
                if self.cover_at(i, r[k]) {
                    total -= fb;
                }
            }
        }
        total += penalty;
        // The strip [x, u, v] leaves across (u, v) without a swap, or across {x, v}
        // with one: as if entered across (x, u).
        Head {
            total,
            len: 1,
            cur: t,
            entry: PREV[slot],
            fwd: true,
            r,
            rs,
        }
    }
}

/// The first triangle of a strip that leaves `tri` across `slot`, rotated so that the
/// strip's last two indices are that edge.
#[inline]
pub(super) fn start_of(tri: [u32; 3], slot: usize) -> [u32; 3] {
    [tri[PREV[slot]], tri[slot], tri[NEXT[slot]]]
}

/// Most free triangles around one FIFO entry offered per scan (the first ones in the
/// order of the vertex's list). Without a bound a vertex of valence V offers V
/// candidates for every strip while it stays cached: O(V^2) walks around it (a star of
/// 20,000 triangles around one vertex, or 20,000 triangles on one edge, took minutes).
/// 16 is above the highest valence of the shared models (14, cow; 8 to 13 on the
/// others), where a vertex's free triangles are all offered as before; 32 took `balanced`
/// on the star 1.3 s against 0.57 s.
pub(crate) const FAN_CANDIDATES: u32 = 16;

/// `Best::slot` of a walk that goes on from the end of the last strip.
pub(super) const CONTINUE: usize = 3;

/// The best prefix found so far: start triangle, exit slot (or CONTINUE), length in
/// new triangles, cost per triangle.
#[derive(Clone, Copy)]
pub(super) struct Best {
    pub(super) t: u32,
    pub(super) slot: u8,
    pub(super) len: u32,
    pub(super) cost: f32,
}

impl Best {
    const NOTHING: Best = Best {
        t: NONE,
        slot: 0,
        len: 0,
        cost: f32::INFINITY,
    };
}

pub(super) struct State<'a> {
    pub(super) tris: &'a [[u32; 3]],
    /// The links of each triangle (see `links.rs`).
    pub(super) adj: &'a [[u32; 3]],
    pub(super) opt: CacheOptions,
    /// Free triangles by free degree (the greedy stripifier's buckets).
    pub(super) b: Buckets,
    /// Vertex -> its triangles: the list of vertex `v` is `vlist[start..voff[v + 1]]`
    /// ([`State::list_start`]: `voff[v]` moved on past the taken triangles dropped),
    /// in triangle order; it holds every free triangle of `v` (and taken ones not yet
    /// dropped: [`State::scan`] drops those it passes, moving the free ones it
    /// offered up to the rest of the list).
    pub(super) vlist: Vec<u32>,
    pub(super) voff: Vec<u32>,
    /// Per vertex, its free triangles.
    pub(super) vfree: Vec<u32>,
    /// The records of the current walk's vertices.
    pub(super) table: WalkTable,
    /// The FIFO the emitted strips went through; its pushes are their misses.
    pub(super) fifo: Fifo,
    /// TAKEN for triangles in strips, else the epoch of the last walk through them,
    /// with the OFFERED bit.
    pub(super) mark: Vec<u32>,
    pub(super) epoch: u32,
    /// The first epoch of the current strip's round: a triangle whose mark has the
    /// OFFERED bit and an epoch from this one on was offered in this round.
    pub(super) round: u32,
    /// The current walk after its first triangle: (triangle, swap vertex or NONE, the
    /// triangle's new vertex); `bpath`: that of the walk that set the best prefix last
    /// (swapped in when a walk ends having improved it), which `emit` emits.
    pub(super) wpath: Vec<(u32, u32, u32)>,
    pub(super) bpath: Vec<(u32, u32, u32)>,
    /// The last triangle of the last strip (NONE before the first).
    pub(super) last: u32,

    pub(super) out: StripSet,
    /// The strips as walks (triangle ids in output order), recorded after
    /// [`State::keep_walks`] only.
    pub(super) walks: Walks,
    record_walks: bool,
    /// Triangles not yet in a strip.
    free_count: usize,
}

/// The vertex count the stripifier works with for `tris` (at least `vertex_count`),
/// the triangles around each vertex and the links of the triangles.
pub(super) fn prepare(tris: &[[u32; 3]], vertex_count: usize) -> (Csr<u32>, Vec<[u32; 3]>) {
    let vcount = vertex_bound(tris).max(vertex_count);
    let vtris = vertex_triangles(tris, vcount);
    let links = super::links::links(tris, &vtris);
    (vtris, links)
}

impl<'a> State<'a> {
    /// The state for `tris` with their `links` and, when given, their vertex lists as
    /// [`prepare`] returns them (built here when not).
    pub(super) fn new(
        tris: &'a [[u32; 3]],
        links: &'a [[u32; 3]],
        vtris: Option<Csr<u32>>,
        vertex_count: usize,
        opt: &CacheOptions,
    ) -> Self {
        let n = tris.len();
        let vcount = vertex_bound(tris).max(vertex_count);
        let mut opt = *opt;
        opt.cache_size = opt.cache_size.max(3);
        opt.max_len = opt.max_len.max(1);
        opt.scan_entries = opt.scan_entries.clamp(1, opt.cache_size);
        let vtris = vtris.unwrap_or_else(|| vertex_triangles(tris, vcount));
        let (voff, vlist) = vtris.into_parts();
        let degree = |t: usize| links[t].iter().filter(|&&l| l != n as u32).count() as u8;
        // Free is read from the marks.
        let b = Buckets::without_flags(tris, degree);
        let mut out = StripSet::new();
        out.indices.reserve(n + n / 2);
        State {
            tris,
            adj: links,
            opt,
            b,
            vfree: (0..vcount).map(|v| voff[v + 1] - voff[v]).collect(),
            table: WalkTable::new(opt.max_len),
            voff,
            vlist,
            fifo: Fifo::new(opt.cache_size, vcount),
            // The sentinel triangle `n` is TAKEN.
            mark: tris
                .iter()
                .map(|t| if is_degenerate(t) { TAKEN } else { 0 })
                .chain([TAKEN])
                .collect(),
            epoch: 0,
            round: 0,
            wpath: vec![(0, 0, 0); opt.max_len as usize],
            bpath: vec![(0, 0, 0); opt.max_len as usize],
            last: NONE,
            out,
            walks: Walks::new(),
            record_walks: false,
            free_count: tris.iter().filter(|t| !is_degenerate(t)).count(),
        }
    }

    /// Records the strips as walks (for the local search) from here on.
    pub(super) fn keep_walks(&mut self) {
        self.walks = Walks::with_capacity(self.tris.len());
        self.record_walks = true;
    }

    /// Free (a triangle or the sentinel of a link).
    #[inline]
    fn is_free(&self, t: u32) -> bool {
        self.mark[t as usize] != TAKEN
    }

    /// Feeds `v` to the FIFO for real.
    #[inline]
    fn touch(&mut self, v: u32) {
        self.fifo.touch(v);
    }

    /// A new epoch for the next walk (marks and records of older walks then read as
    /// untouched).
    fn next_epoch(&mut self) {
        self.epoch += 1;
        if self.epoch == EPOCHS {
            // The round's offers are forgotten too: a triangle may then be offered
            // twice in this round, which walks the same walks again (no strict
            // improvement: the same strips).
            for m in self.mark.iter_mut().filter(|m| **m != TAKEN) {
                *m = 0;
            }
            self.round = 1;
            self.table.clear();
            self.epoch = 1;
        }
    }

    /// Walks from `t` leaving across `slot` (or, with CONTINUE, from the end of the
    /// last strip, `t` being its last triangle) and offers each prefix to `best`; the
    /// walk is kept in `bpath` when it improved `best`.
    fn evaluate(&mut self, t: u32, slot: usize, best: &mut Best) {
        self.next_epoch();
        let w = self.opt.miss_weight;
        let fb = self.opt.finish_bonus;
        let mut k = Walk {
            table: &mut self.table,
            vfree: &self.vfree,
            mark: &mut self.mark,
            epoch: self.epoch,
            fifo: &self.fifo,
            c: self.opt.cache_size,
            pushes: 0,
        };
        // The walk is at `cur`, entered across slot `entry`; its exits are the other two
        // slots, and `fwd` says the natural one (no swap) is NEXT[entry]. `r` holds the
        // vertices of `cur` from the entry's slot on: `r[0], r[1]` run the entry edge.
        // `total` is the cost so far: indices (and the restart), plus weighed misses.
        // The vertices of `cur` count as covered (with none of their triangles when
        // `cur` is the last strip's end), so a step covers only its new vertex afresh.
        let tri = self.tris[t as usize];
        let Head {
            mut total,
            mut len,
            mut cur,
            mut entry,
            mut fwd,
            mut r,
            mut rs,
        } = if slot == CONTINUE {
            let n = self.out.indices.len();
            let end = (self.out.indices[n - 2], self.out.indices[n - 1]);
            k.go_on(t, tri, end, fb)
        } else {
            let nb = nbr(self.adj[t as usize][slot]);
            let left = self.b.degree[t as usize] as f32 - f32::from(k.mark[nb as usize] != TAKEN);
            k.start(t, tri, slot, w, fb, self.opt.start_penalty * left.max(0.0))
        };
        let adjs = self.adj;
        let tris = self.tris;
        let wpath = &mut self.wpath[..];
        let first = len;
        let round_offered = OFFERED | self.round;
        let mut improved = false;
        let mut swaps = 0u32;
        let max_len = self.opt.max_len;
        let max_swaps = self.opt.max_swaps;
        let limit = max_len as f32;
        let mut bound = (best.cost - 1.0) * limit;
        loop {
            if len > 0 && total < best.cost * len as f32 {
                *best = Best {
                    t,
                    slot: slot as u8,
                    len,
                    cost: total / len as f32,
                };
                bound = (best.cost - 1.0) * limit;
                improved = true;
            }
            if len >= max_len {
                break;
            }
            // No longer prefix can beat `best`: it covers at most `max_len` triangles,
            // and the indices, swaps and misses only grow.
            if total - len as f32 >= bound {
                break;
            }
            let adj = adjs[cur as usize];
            let (nat, swp) = if fwd {
                (NEXT[entry], PREV[entry])
            } else {
                (PREV[entry], NEXT[entry])
            };
            // The exit: `nat` when open, or `swp` (one swap) where `nat` is blocked or
            // where its new vertex would miss and the swap's would hit.
            let nat_ok = k.is_open(nbr(adj[nat]));
            // The table slot of the exit's new vertex where the choice looked it up
            // (no record is made between that lookup and the step's).
            let (e, swap, found) = if swaps >= max_swaps {
                if !nat_ok {
                    break;
                }
                (nat, false, None)
            } else {
                let swp_ok = k.is_open(nbr(adj[swp]));
                if nat_ok && swp_ok {
                    let yn = opp(tris, adj[nat]);
                    let i = k.table.find(yn, k.epoch);
                    if k.cached_at(i, yn) {
                        (nat, false, Some(i))
                    } else {
                        let ys = opp(tris, adj[swp]);
                        let j = k.table.find(ys, k.epoch);
                        if k.cached_at(j, ys) {
                            (swp, true, Some(j))
                        } else {
                            (nat, false, Some(i))
                        }
                    }
                } else if nat_ok {
                    (nat, false, None)
                } else if swp_ok {
                    (swp, true, None)
                } else {
                    break;
                }
            };
            let n = nbr(adj[e]);
            let j = twin(adj[e]);
            // The new vertex of `n`, opposite the edge it shares with `cur`, and its
            // record: in the slot the choice found, else looked up now.
            let y = tris[n as usize][PREV[j]];
            let sy = match found {
                Some(i) => {
                    k.start_record(i, y);
                    i
                }
                None => k.slot(y),
            };
            total += 1.0;
            if swap {
                swaps += 1;
                total += 1.0;
            }
            // Offered in this round (the OFFERED bit with an epoch from the round's
            // first on) stays offered; an older offer is forgotten.
            let offered = if k.mark[n as usize] >= round_offered { OFFERED } else { 0 };
            k.mark[n as usize] = k.epoch | offered;
            // Leaving across NEXT[entry] the exit edge is (r[1], r[2]), across
            // PREV[entry] it is (r[2], r[0]); `n` runs it the other way from slot j.
            let via_next = e == NEXT[entry];
            // The swap vertex: the exit edge's vertex other than the newest (the
            // newest, r[2], is on both exits).
            let p = match (swap, via_next) {
                (false, _) => NONE,
                (true, true) => r[1],
                (true, false) => r[0],
            };
            wpath[(len - first) as usize] = (n, p, y);
            (r, rs) = if via_next {
                ([r[2], r[1], y], [rs[2], rs[1], sy])
            } else {
                ([r[0], r[2], y], [rs[0], rs[2], sy])
            };
            // The other two vertices belong to the triangle just fed, so (but for a
            // hit evicted by that triangle's own pushes, which the emission counts
            // exactly) only `y` can miss.
            if k.touch_at(sy, y) {
                total += w;
            }
            if fb != 0.0 {
                // r[0] and r[1] were vertices of `cur`: already seen by this walk.
                if k.cover_at(rs[0], r[0]) {
                    total -= fb;
                }
                if k.cover_at(rs[1], r[1]) {
                    total -= fb;
                }
                k.uncover_at(sy);
                if k.cover_at(sy, y) {
                    total -= fb;
                }
            }
            len += 1;
            // Leaving across NEXT[entry], the newest vertex of `cur` starts the edge it
            // shares with `n` (as `n` runs it), and the next natural exit is PREV[j].
            fwd = !via_next;
            entry = j;
            cur = n;
        }
        if improved {
            std::mem::swap(&mut self.wpath, &mut self.bpath);
        }
    }

    /// Offers every exit of free triangle `t` (once per round) when at least
    /// `min_cached` of its vertices are cached.
    fn consider(&mut self, t: u32, min_cached: u32, best: &mut Best) {
        let m = self.mark[t as usize];
        if m & OFFERED != 0 && m & EPOCHS >= self.round {
            return;
        }
        // The epoch of the last walk (or this round's first), kept by the walks
        // through `t` this round.
        self.mark[t as usize] = self.epoch | OFFERED;
        if min_cached > 0 {
            let cached = self.tris[t as usize]
                .iter()
                .filter(|&&v| self.fifo.contains(v))
                .count() as u32;
            if cached < min_cached {
                return;
            }
        }
        for slot in 0..3 {
            self.evaluate(t, slot, best);
        }
    }

    fn take(&mut self, t: u32) {
        self.mark[t as usize] = TAKEN;
        self.free_count -= 1;
        // The buckets' stale entries held at most about as many as the free ones.
        if self.b.held() > 2 * self.free_count + (1 << 16) {
            let mark = &self.mark;
            self.b.compact_by(|t| mark[t as usize] != TAKEN);
        }
        for &v in &self.tris[t as usize] {
            self.vfree[v as usize] -= 1;
        }
        for k in 0..3 {
            let m = nbr(self.adj[t as usize][k]);
            if self.is_free(m) {
                let d = self.b.degree[m as usize] - 1;
                self.b.push_front(m, d);
            }
        }
    }

    /// A new round of candidates: an epoch no mark holds yet.
    fn next_round(&mut self) {
        self.next_epoch();
        self.round = self.epoch;
    }

    pub(super) fn run(&mut self) {
        loop {
            self.next_round();
            let mut best = Best::NOTHING;
            if self.opt.join && self.last != NONE {
                self.evaluate(self.last, CONTINUE, &mut best);
                // A new strip costs at least 1 + 3 / max_len per triangle (its start
                // and restart indices); going on that cheaply (a cache hit without a
                // swap) cannot be beaten, and ties keep the first found anyway.
                if best.cost <= 1.0 + 3.0 / self.opt.max_len as f32 {
                    self.emit(best);
                    continue;
                }
            }
            // Oldest entries first: a strip beside the start of the previous one is
            // usually the best, and finding it early cuts the other walks short.
            // Where nothing there qualifies, the whole cache, then triangles with a
            // single cached vertex, before a jump away from the cache.
            let c = self.opt.cache_size;
            let tiers = [
                (self.opt.scan_entries, self.opt.min_cached),
                (c, self.opt.min_cached),
                (c, self.opt.min_cached.min(1)),
            ];
            self.scan(tiers[0].0, tiers[0].1, &mut best);
            for k in 1..tiers.len() {
                if best.t != NONE {
                    break;
                }
                if tiers[k] != tiers[k - 1] {
                    self.next_round();
                    self.scan(tiers[k].0, tiers[k].1, &mut best);
                }
            }
            if best.t == NONE {
                let mark = &self.mark;
                match self.b.lowest_by(|t| mark[t as usize] != TAKEN) {
                    Some(t) => {
                        self.next_round();
                        self.consider(t, 0, &mut best);
                    }
                    None => break,
                }
            }
            self.emit(best);
        }
    }

    /// Offers the free triangles around the oldest `entries` entries of the FIFO
    /// (see [`State::consider`]), oldest first: around each entry, its first
    /// [`FAN_CANDIDATES`] free triangles in the order of its list.
    fn scan(&mut self, entries: u32, min_cached: u32, best: &mut Best) {
        let live = self.fifo.len();
        for i in (live.saturating_sub(entries)..live).rev() {
            let v = self.fifo.newest(i) as usize;
            if self.vfree[v] == 0 {
                continue;
            }
            // The list's taken triangles passed are dropped: the free ones offered
            // move up to the part not read (order kept), so a vertex of high valence
            // costs O(1) per strip, not O(valence).
            let (start, end) = (self.list_start(v), self.voff[v + 1] as usize);
            let (mut read, mut kept) = (start, start);
            let mut offered = 0;
            while read < end && offered < FAN_CANDIDATES {
                let t = self.vlist[read];
                read += 1;
                if self.mark[t as usize] == TAKEN {
                    continue;
                }
                self.vlist[kept] = t;
                kept += 1;
                offered += 1;
                self.consider(t, min_cached, best);
            }
            if kept < read {
                let moved = kept - start;
                self.vlist.copy_within(start..kept, read - moved);
                // The new start is past the list's first slot, no longer read: it
                // holds the distance.
                let base = self.voff[v] as usize;
                self.vlist[base] = MOVED | (read - moved - base) as u32;
            }
        }
    }

    /// Where the list of `v` starts: its first slot, or past it by the distance that
    /// slot holds with the MOVED bit (see [`State::scan`]).
    #[inline]
    fn list_start(&self, v: usize) -> usize {
        let base = self.voff[v] as usize;
        match self.vlist.get(base) {
            Some(&h) if base < self.voff[v + 1] as usize && h & MOVED != 0 => {
                base + (h & !MOVED) as usize
            }
            _ => base,
        }
    }

    /// Emits the chosen prefix as a new strip (or as more of the last one) and feeds
    /// its triangles to the FIFO.
    fn emit(&mut self, best: Best) {
        let t = best.t;
        let slot = best.slot as usize;
        // The walk that found `best` is in `bpath`: its triangles after the first
        // (all of them going on from the last strip).
        let steps = best.len as usize - usize::from(slot != CONTINUE);
        let (mut a, mut b);
        if slot == CONTINUE {
            if self.record_walks {
                self.walks.reopen_last();
            }
            self.out.offsets.pop();
            let n = self.out.indices.len();
            (a, b) = (self.out.indices[n - 2], self.out.indices[n - 1]);
        } else {
            let [x, u, w] = start_of(self.tris[t as usize], slot);
            if self.record_walks {
                self.walks.push_triangle(t);
            }
            self.take(t);
            self.out.indices.extend_from_slice(&[x, u, w]);
            self.touch(x);
            self.touch(u);
            self.touch(w);
            (a, b) = (u, w);
        }
        self.last = t;
        for i in 0..steps {
            let (n, p, y) = self.bpath[i];
            if p != NONE {
                // [.., a, b] -> [.., a, p, b]: the last triangle decodes the same and
                // the strip now ends on its edge {p, b}.
                self.out.indices.pop();
                self.out.indices.extend_from_slice(&[p, b]);
            }
            self.take(n);
            if self.record_walks {
                self.walks.push_triangle(n);
            }
            self.out.indices.push(y);
            // The decoded order of the new triangle (the two old vertices are hits
            // unless that triangle's own pushes evicted one).
            let (first, second) = if p != NONE { (p, b) } else { (a, b) };
            let odd =
                (self.out.indices.len() - *self.out.offsets.last().unwrap_or(&0) as usize) & 1 == 0;
            if odd {
                self.touch(second);
                self.touch(first);
            } else {
                self.touch(first);
                self.touch(second);
            }
            self.touch(y);
            a = b;
            b = y;
            self.last = n;
        }
        let end = self.out.indices.len() as u32;
        self.out.offsets.push(end);
        if self.record_walks {
            self.walks.end_walk();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    /// The walk's operations by vertex, each looking up the vertex's slot: what the
    /// walk does with the slots it keeps, for the table test below.
    impl Walk<'_> {
        /// Whether `v` is in the FIFO after the walk's pushes so far.
        fn cached_after(&self, v: u32) -> bool {
            self.cached_at(self.table.find(v, self.epoch), v)
        }

        /// Feeds `v` to the walk's private copy of the FIFO; true on a miss.
        fn touch(&mut self, v: u32) -> bool {
            let i = self.slot(v);
            self.touch_at(i, v)
        }

        /// Starts the count of `v`'s triangles covered by the walk, unless started.
        fn uncover(&mut self, v: u32) {
            let i = self.slot(v);
            self.uncover_at(i);
        }

        /// Counts one more of `v`'s free triangles as covered by the walk (its count
        /// started); true when that was its last one.
        fn cover(&mut self, v: u32) -> bool {
            let i = self.slot(v);
            self.cover_at(i, v)
        }
    }

    #[test]
    fn the_walk_table_keeps_one_record_per_vertex() {
        // A walk's records in the small table read as one record per vertex did: up to
        // eight vertices in 16 slots (ids chosen to collide), over many epochs (a
        // record of an older walk reads as none), against a map of the same records.
        let (c, vcount) = (4u32, 200usize);
        let mut fifo = Fifo::new(c, vcount);
        for v in [3, 17, 40, 99] {
            fifo.touch(v);
        }
        let vfree: Vec<u32> = (0..vcount as u32).map(|v| 1 + v % 3).collect();
        let mut mark = vec![0u32; 4];
        let mut table = WalkTable::new(1);
        assert_eq!(table.slots.len(), 16);
        let mut seed = 12345u64;
        let mut rand = |n: u64| {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 33) % n
        };
        let mut finished = 0;
        for epoch in 1..200u32 {
            let pool: Vec<u32> = (0..8).map(|_| (rand(12) * 16 + rand(2)) as u32).collect();
            let mut k = Walk {
                table: &mut table,
                vfree: &vfree,
                mark: &mut mark,
                epoch,
                fifo: &fifo,
                c,
                pushes: 0,
            };
            // Per vertex: the walk's push count when pushed, its covered count.
            let mut model: HashMap<u32, (Option<u32>, Option<u32>)> = HashMap::new();
            for _ in 0..30 {
                let v = pool[rand(8) as usize];
                let e = model.entry(v).or_default();
                match rand(3) {
                    0 => {
                        let cached = match e.0 {
                            Some(local) => k.pushes - local <= c,
                            None => fifo.contains_after(v, k.pushes),
                        };
                        if !cached {
                            e.0 = Some(k.pushes);
                        }
                        assert_eq!(k.touch(v), !cached, "epoch {epoch} v {v}");
                    }
                    _ => {
                        k.uncover(v);
                        let n = e.1.unwrap_or(0) + 1;
                        e.1 = Some(n);
                        let last = k.cover(v);
                        assert_eq!(last, n == vfree[v as usize], "epoch {epoch} v {v}");
                        finished += usize::from(last);
                    }
                }
                for &u in &pool {
                    let want = match model.get(&u).and_then(|e| e.0) {
                        Some(local) => k.pushes - local <= c,
                        None => fifo.contains_after(u, k.pushes),
                    };
                    assert_eq!(k.cached_after(u), want, "epoch {epoch} u {u}");
                }
            }
        }
        assert!(finished > 100, "{finished}");
        table.clear();
        assert!(table.slots.iter().all(|s| s[0] == 0));
    }
}

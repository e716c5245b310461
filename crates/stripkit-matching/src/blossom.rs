//! The weighted engine: Edmonds' primal-dual blossom algorithm for a maximum-weight
//! *perfect* matching on a simple sparse graph with even integer weights.
//!
//! One file of about 1,000 lines on purpose: every operation (grow, shrink, expand,
//! augment, dual change) reads and writes the same engine state (trees, nested
//! blossoms, lazy duals, event queues), and the invariants tying them together are
//! easier to check in one place than across files.
//!
//! Written from the textbook algorithm (Edmonds 1965; Galil's survey 1986) with the
//! speed-ups of the sparse implementations (Gabow 1990; Cook & Rohe 1999;
//! Kolmogorov 2009), not from any of their code:
//!
//! * **Greedy dual initialisation.** `y_v = max w / 2`, then every vertex lowers its
//!   dual to its smallest slack and is matched along a tight edge to a free neighbour.
//!   On mesh dual graphs this leaves only a few percent of the vertices exposed.
//! * **All alternating trees grown at once** (one per exposed vertex) with one global
//!   dual change `D`, and *lazy* dual updates: a tree blossom stores the `D` at which
//!   it was labelled, and its true dual is the stored one plus/minus the difference.
//!   Nothing is touched per dual step; when two trees meet they augment and only those
//!   two trees are written back and dissolved.
//! * **One priority queue of events** keyed by the `D` at which they happen (an edge
//!   from a tree to a free vertex becomes tight, an edge between two outer blossoms
//!   becomes tight, an inner blossom's dual reaches zero); entries are checked when
//!   popped (lazy deletion) instead of being updated.
//!
//! * **Blossoms without touching their vertices.** Every node (vertex or blossom)
//!   keeps a *link* to an ancestor, path-compressed on lookup as in union-find, with
//!   the sum of the owed dual offsets (`boff`) in between; a link dies with its
//!   target (a generation number per blossom id, bumped when the blossom is
//!   retired). Forming a blossom costs its number of children and expanding one its
//!   number of children, not its size, however deep the nesting.
//! * **Zero-dual blossoms are dissolved** when their tree has augmented (the classic
//!   end-of-stage expansion), which keeps the nesting shallower under many equal
//!   weights. Ties still build deep nests, so nothing walks a nest level by level
//!   more than once: lookups compress, augmenting a nest walks up from the new base
//!   once, and the certificate's blossom list is built top-down. Ties are *not*
//!   broken by perturbing weights. Measurements and the variants tried:
//!   docs/experiments/matching-ties.md.
//! * **A radix heap** for the event keys, which only grow. Of equal keys, meetings of
//!   two outer blossoms (shrink, augment) come before growth, so that under ties no
//!   tree runs into a region freed by earlier augmentations before it augments.
//!
//! Integrality: the caller doubles the weights, so every weight is even, and the roots'
//! duals are made even at the start. Tree vertices are joined to their root by tight
//! edges and all trees move by the same `D`, so all tree vertices share one dual
//! parity: the slack between two outer vertices is even, every dual change is an
//! integer and the result is exact.
//!
//! Conventions: dual feasibility is `y_u + y_v + sum(z_B : u, v in B) >= w_uv`,
//! `z_B >= 0`; vertex duals are free in sign (perfect matching). An endpoint `p` of
//! edge `e` is `2e` (first end) or `2e + 1` (second end); `p ^ 1` is the other end.

/// A radix heap: a priority queue for monotone integer keys (every key pushed is at
/// least the last key popped, which holds because `D` only grows). Bucket `i` holds
/// keys whose highest bit differing from the last popped key is bit `i - 1`; a pop
/// empties the lowest non-empty bucket into lower ones. Amortised O(log range) per
/// entry, with plain vectors instead of sifting.
///
/// Of the entries with the smallest key, those whose payload is a meeting of two
/// outer blossoms (`EV_BLOSSOM`: shrink or augment) come out first, kept apart in
/// `meet0`; the rest of bucket 0 comes out last in, first out. Growing first let one
/// tree, at one `D` under massive ties, run into the perfectly matched region freed
/// by earlier augmentations (a dead end) before it augmented with the tree beside it,
/// and the next tree swept that region again: a path of 20,000 nodes with weights
/// `i mod 7` labelled 14 million nodes for 1,428 augmentations.
struct RadixHeap {
    last: u64,
    len: usize,
    buckets: Vec<Vec<(u64, u64)>>,
    meet0: Vec<(u64, u64)>,
}

impl RadixHeap {
    fn new() -> RadixHeap {
        RadixHeap { last: 0, len: 0, buckets: (0..65).map(|_| Vec::new()).collect(), meet0: Vec::new() }
    }

    #[inline]
    fn bucket(&self, key: u64) -> usize {
        (64 - (key ^ self.last).leading_zeros()) as usize
    }

    #[inline]
    fn place(&mut self, key: u64, payload: u64) {
        let b = self.bucket(key);
        if b == 0 && payload & 3 == EV_BLOSSOM {
            self.meet0.push((key, payload));
        } else {
            self.buckets[b].push((key, payload));
        }
    }

    #[inline]
    fn push(&mut self, key: u64, payload: u64) {
        debug_assert!(key >= self.last);
        self.place(key, payload);
        self.len += 1;
    }

    fn pop(&mut self) -> Option<(u64, u64)> {
        if self.len == 0 {
            return None;
        }
        if let Some(e) = self.meet0.pop() {
            self.len -= 1;
            return Some(e);
        }
        if self.buckets[0].is_empty() {
            let i = (1..65).find(|&i| !self.buckets[i].is_empty())?;
            let items = std::mem::take(&mut self.buckets[i]);
            self.last = items.iter().map(|&(k, _)| k).min().unwrap_or(self.last);
            for &(k, p) in &items {
                self.place(k, p);
            }
            // Keep the emptied bucket's allocation for later use.
            let mut items = items;
            items.clear();
            if self.buckets[i].is_empty() {
                self.buckets[i] = items;
            }
        }
        self.len -= 1;
        if let Some(e) = self.meet0.pop() {
            return Some(e);
        }
        self.buckets[0].pop()
    }
}

pub(crate) const NONE: u32 = u32::MAX;

const FREE: u8 = 0;
const PLUS: u8 = 1;
const MINUS: u8 = 2;

const EV_GROW: u64 = 0; // edge from an outer vertex to a free vertex is tight
const EV_BLOSSOM: u64 = 1; // edge between two outer blossoms is tight
const EV_EXPAND: u64 = 2; // inner blossom's dual is zero

/// A simple graph for the engine: no self-loops, no parallel edges.
pub(crate) struct SimpleGraph {
    pub n: usize,
    pub ends: Vec<[u32; 2]>,
    /// Even weights (maximised).
    pub w: Vec<i64>,
    /// CSR of remote endpoints: for `p` in `adj[off[v]..off[v+1]]`, `endpoint(p)` is a
    /// neighbour of `v` and `p ^ 1` is `v`'s own end.
    pub off: Vec<u32>,
    pub adj: Vec<u32>,
}

impl SimpleGraph {
    pub fn new(n: usize, ends: Vec<[u32; 2]>, w: Vec<i64>) -> SimpleGraph {
        let mut off = vec![0u32; n + 1];
        for e in &ends {
            off[e[0] as usize + 1] += 1;
            off[e[1] as usize + 1] += 1;
        }
        for v in 0..n {
            off[v + 1] += off[v];
        }
        let mut fill = off.clone();
        let mut adj = vec![0u32; off[n] as usize];
        for (k, e) in ends.iter().enumerate() {
            adj[fill[e[0] as usize] as usize] = 2 * k as u32 + 1;
            fill[e[0] as usize] += 1;
            adj[fill[e[1] as usize] as usize] = 2 * k as u32;
            fill[e[1] as usize] += 1;
        }
        SimpleGraph { n, ends, w, off, adj }
    }

    #[inline]
    fn endpoint(&self, p: u32) -> u32 {
        self.ends[(p >> 1) as usize][(p & 1) as usize]
    }
}

/// The engine's result: a perfect matching and an optimal dual solution.
pub(crate) struct Solution {
    /// Matched edge of each vertex.
    pub mate_edge: Vec<u32>,
    /// Vertex duals.
    pub y: Vec<i64>,
    /// Blossoms with positive dual: (z, parent index or NONE); children come first.
    pub blossoms: Vec<(i64, u32)>,
    /// Innermost listed blossom of each vertex, or NONE.
    pub vertex_blossom: Vec<u32>,
}

/// Work counters of one run (for benchmarks and reports).
#[derive(Clone, Copy, Debug, Default)]
pub struct Stats {
    /// Exposed vertices left by the greedy initialisation.
    pub exposed_after_init: usize,
    /// Augmentations (searches that ended in one).
    pub augmentations: usize,
    /// Blossoms formed.
    pub blossoms_formed: usize,
    /// Inner blossoms expanded (dual reached zero).
    pub blossoms_expanded: usize,
    /// Free blossoms with zero dual dissolved after their tree augmented.
    pub blossoms_dissolved: usize,
    /// Events popped from the queues.
    pub events: usize,
}

pub(crate) struct Engine<'g> {
    g: &'g SimpleGraph,
    n: usize,
    // Per vertex.
    mate: Vec<u32>, // remote endpoint of the matched edge
    y: Vec<i64>,
    /// Per node: a shortcut to a strict ancestor (or NONE), valid while that
    /// ancestor's generation is `lgen`; `lsum` is the sum of `boff` over the nodes
    /// strictly between. Path-compressed on every lookup.
    link: Vec<u32>,
    lsum: Vec<i64>,
    lgen: Vec<u32>,
    /// Per node: bumped when the blossom is retired, which invalidates every link to it.
    gen: Vec<u32>,
    path: Vec<u32>,
    /// Per node: a dual change owed to every vertex inside (written when a top-level
    /// blossom stops being top-level, instead of touching its vertices).
    boff: Vec<i64>,
    // Per node (vertex ids 0..n, blossoms n..).
    parent: Vec<u32>,
    label: Vec<u8>,
    labelend: Vec<u32>,
    tstamp: Vec<i64>,
    base: Vec<u32>,
    mark: Vec<u32>,
    // Per blossom (index node - n).
    childs: Vec<Vec<u32>>,
    endps: Vec<Vec<u32>>,
    z: Vec<i64>,
    alive: Vec<bool>,
    free_blossoms: Vec<u32>,
    // Search state.
    d: i64,
    heap: RadixHeap,
    /// Tree of each labelled top-level node.
    tree_of: Vec<u32>,
    /// Nodes ever labelled in each tree (stale entries are skipped when read).
    trees: Vec<Vec<u32>>,
    live_trees: usize,
    mark_stamp: u32,
    scratch: Vec<u32>,
    stack: Vec<u32>,
    pub stats: Stats,
}

impl<'g> Engine<'g> {
    /// Takes blossom `b` out of every tree and returns its id to the free list.
    fn retire(&mut self, b: u32) {
        let bi = b as usize;
        self.label[bi] = FREE;
        self.labelend[bi] = NONE;
        self.tree_of[bi] = NONE;
        self.parent[bi] = NONE;
        self.alive[bi - self.n] = false;
        self.gen[bi] = self.gen[bi].wrapping_add(1);
        self.link[bi] = NONE;
        self.free_blossoms.push(b);
    }

    pub fn new(g: &'g SimpleGraph) -> Engine<'g> {
        let n = g.n;
        Engine {
            g,
            n,
            mate: vec![NONE; n],
            y: vec![0; n],
            link: vec![NONE; n],
            lsum: vec![0; n],
            lgen: vec![0; n],
            gen: vec![0; n],
            path: Vec::new(),
            boff: vec![0; n],
            parent: vec![NONE; n],
            label: vec![FREE; n],
            labelend: vec![NONE; n],
            tstamp: vec![0; n],
            base: (0..n as u32).collect(),
            mark: vec![0; n],
            childs: Vec::new(),
            endps: Vec::new(),
            z: Vec::new(),
            alive: Vec::new(),
            free_blossoms: Vec::new(),
            d: 0,
            heap: RadixHeap::new(),
            tree_of: vec![NONE; n],
            trees: Vec::new(),
            live_trees: 0,
            mark_stamp: 0,
            scratch: Vec::new(),
            stack: Vec::new(),
            stats: Stats::default(),
        }
    }

    /// Greedy initial duals and matching.
    pub fn init_greedy(&mut self) {
        let g = self.g;
        for v in 0..self.n {
            let mut best = i64::MIN;
            for &p in &g.adj[g.off[v] as usize..g.off[v + 1] as usize] {
                best = best.max(g.w[(p >> 1) as usize]);
            }
            self.y[v] = if best == i64::MIN { 0 } else { best / 2 };
        }
        for v in 0..self.n {
            let range = g.off[v] as usize..g.off[v + 1] as usize;
            let mut min_slack = i64::MAX;
            for &p in &g.adj[range.clone()] {
                let u = g.endpoint(p) as usize;
                let s = self.y[v] + self.y[u] - g.w[(p >> 1) as usize];
                min_slack = min_slack.min(s);
            }
            if min_slack == i64::MAX {
                continue;
            }
            self.y[v] -= min_slack;
            if self.mate[v] != NONE {
                continue;
            }
            for &p in &g.adj[range] {
                let u = g.endpoint(p) as usize;
                if self.mate[u] == NONE && self.y[v] + self.y[u] == g.w[(p >> 1) as usize] {
                    self.mate[v] = p;
                    self.mate[u] = p ^ 1;
                    break;
                }
            }
        }
        self.stats.exposed_after_init = self.mate.iter().filter(|&&m| m == NONE).count();
    }

    /// Grows alternating trees from all exposed vertices at once, with one global dual
    /// change `D`, until every tree has augmented. Returns false when the queue runs
    /// dry with trees left: then the graph has no perfect matching.
    pub fn run(&mut self) -> bool {
        // All tree vertices must share one dual parity (so that the slack between two
        // outer vertices, even of different trees, is even): make the roots' duals
        // even. Raising a dual keeps every constraint satisfied.
        for v in 0..self.n {
            if self.mate[v] == NONE && self.y[v] & 1 != 0 {
                self.y[v] += 1;
            }
        }
        self.d = 0;
        for v in 0..self.n {
            if self.mate[v] == NONE {
                let t = self.trees.len() as u32;
                self.trees.push(Vec::new());
                self.live_trees += 1;
                self.set_label(v as u32, PLUS, NONE, t);
            }
        }
        // Scan after all roots are labelled so that root-root edges are seen as such.
        for v in 0..self.n {
            if self.mate[v] == NONE {
                self.scan_outer(v as u32);
            }
        }
        while self.live_trees > 0 {
            let Some((key, payload)) = self.heap.pop() else { return false };
            self.stats.events += 1;
            self.event(key as i64, payload);
        }
        true
    }

    // ---------------------------------------------------------------- duals

    /// The top-level node containing vertex `v` (compresses its links; afterwards
    /// `lsum[v]` is the `boff` sum strictly between `v` and the top, see [`Self::above`]).
    #[inline]
    fn top(&mut self, v: u32) -> u32 {
        let vi = v as usize;
        let l = self.link[vi];
        if l != NONE && self.lgen[vi] == self.gen[l as usize] {
            if self.parent[l as usize] == NONE {
                return l;
            }
        } else if self.parent[vi] == NONE {
            return v;
        }
        self.find_node(v).0
    }

    /// Sum of `boff` over the blossoms strictly between vertex `v` and its top-level
    /// node `t`, right after `t = self.top(v)`.
    #[inline]
    fn above(&self, v: u32, t: u32) -> i64 {
        if t == v {
            0
        } else {
            self.lsum[v as usize]
        }
    }

    /// The next node above node `x`: its link while valid (with the `boff` sum
    /// strictly between), else its parent (sum 0); NONE at the top.
    #[inline]
    fn up(&self, x: u32) -> (u32, i64) {
        let xi = x as usize;
        let l = self.link[xi];
        if l != NONE && self.lgen[xi] == self.gen[l as usize] {
            (l, self.lsum[xi])
        } else {
            (self.parent[xi], 0)
        }
    }

    /// The top-level node above node `a`, and the sum of `boff` over the nodes strictly
    /// between; compresses the links on the way (every node links to the top). A
    /// blossom's links survive new levels formed above (those only lengthen the walk)
    /// and die with their target (its generation changes when it is retired), so no
    /// node is touched when blossoms form or expand.
    fn find_node(&mut self, a: u32) -> (u32, i64) {
        let mut path = std::mem::take(&mut self.path);
        path.clear();
        let mut x = a;
        loop {
            let (u, _) = self.up(x);
            if u == NONE {
                break;
            }
            path.push(x);
            x = u;
        }
        let r = x;
        let mut acc = 0i64;
        for &p in path.iter().rev() {
            let (u, s) = self.up(p);
            let sum = if u == r { s } else { s + self.boff[u as usize] + acc };
            let pi = p as usize;
            self.link[pi] = r;
            self.lsum[pi] = sum;
            self.lgen[pi] = self.gen[r as usize];
            acc = sum;
        }
        let sum = if path.is_empty() { 0 } else { acc };
        self.path = path;
        (r, sum)
    }

    /// True dual of vertex `v`.
    #[inline]
    fn yv(&mut self, v: u32) -> i64 {
        let b = self.top(v) as usize;
        let y = self.y[v as usize] + self.above(v, b as u32) + if b >= self.n { self.boff[b] } else { 0 };
        match self.label[b] {
            PLUS => y - (self.d - self.tstamp[b]),
            MINUS => y + (self.d - self.tstamp[b]),
            _ => y,
        }
    }

    #[inline]
    fn slack(&mut self, k: usize) -> i64 {
        let [a, b] = self.g.ends[k];
        self.yv(a) + self.yv(b) - self.g.w[k]
    }

    /// True dual of a top-level blossom.
    fn zb(&self, b: u32) -> i64 {
        let bi = b as usize;
        let z = self.z[bi - self.n];
        match self.label[bi] {
            PLUS => z + 2 * (self.d - self.tstamp[bi]),
            MINUS => z - 2 * (self.d - self.tstamp[bi]),
            _ => z,
        }
    }

    /// Collects the vertices of node `b` into `out` (cleared first).
    fn leaves(&mut self, b: u32, out: &mut Vec<u32>) {
        out.clear();
        if (b as usize) < self.n {
            out.push(b);
            return;
        }
        let mut stack = std::mem::take(&mut self.stack);
        stack.clear();
        stack.push(b);
        while let Some(x) = stack.pop() {
            if (x as usize) < self.n {
                out.push(x);
            } else {
                stack.extend_from_slice(&self.childs[x as usize - self.n]);
            }
        }
        self.stack = stack;
    }

    /// Writes the lazy dual change of top-level node `b` into its owed offset (or the
    /// vertex's dual) and its own dual, and restarts its clock at `D`. O(1).
    fn flush(&mut self, b: u32) {
        let bi = b as usize;
        let delta = self.d - self.tstamp[bi];
        self.tstamp[bi] = self.d;
        if delta == 0 || self.label[bi] == FREE {
            return;
        }
        let sign = if self.label[bi] == PLUS { -1 } else { 1 };
        if bi < self.n {
            self.y[bi] += sign * delta;
        } else {
            self.boff[bi] += sign * delta;
            self.z[bi - self.n] -= 2 * sign * delta;
        }
    }

    // ---------------------------------------------------------------- events

    #[inline]
    fn push(&mut self, key: i64, kind: u64, id: u32) {
        debug_assert!(key >= self.d && self.d >= 0);
        self.heap.push(key as u64, (id as u64) << 2 | kind);
    }

    /// Queues the events of the edges of vertex `x`, which has just become outer.
    fn scan_outer(&mut self, x: u32) {
        let g = self.g;
        let bx = self.top(x);
        for &p in &g.adj[g.off[x as usize] as usize..g.off[x as usize + 1] as usize] {
            let u = g.endpoint(p);
            let bu = self.top(u);
            if bu == bx {
                continue;
            }
            let k = (p >> 1) as usize;
            match self.label[bu as usize] {
                FREE => {
                    let s = self.slack(k);
                    self.push(self.d + s, EV_GROW, k as u32);
                }
                PLUS => {
                    let s = self.slack(k);
                    debug_assert!(s >= 0 && s % 2 == 0, "odd slack {s} between outer vertices");
                    self.push(self.d + s / 2, EV_BLOSSOM, k as u32);
                }
                _ => {}
            }
        }
    }

    /// Queues the events of the edges of vertex `x`, which has just become free, from
    /// outer neighbours.
    fn scan_free(&mut self, x: u32) {
        let g = self.g;
        for &p in &g.adj[g.off[x as usize] as usize..g.off[x as usize + 1] as usize] {
            let u = g.endpoint(p);
            let tu = self.top(u) as usize;
            if self.label[tu] == PLUS {
                let k = (p >> 1) as usize;
                let s = self.slack(k);
                self.push(self.d + s, EV_GROW, k as u32);
            }
        }
    }

    fn set_label(&mut self, b: u32, label: u8, labelend: u32, tree: u32) {
        let bi = b as usize;
        self.label[bi] = label;
        self.labelend[bi] = labelend;
        self.tstamp[bi] = self.d;
        self.tree_of[bi] = tree;
        self.trees[tree as usize].push(b);
    }

    /// Labels free top-level node `b` outer and queues its edges.
    fn make_outer(&mut self, b: u32, labelend: u32, tree: u32) {
        self.set_label(b, PLUS, labelend, tree);
        let mut buf = std::mem::take(&mut self.scratch);
        self.leaves(b, &mut buf);
        for &x in &buf {
            self.scan_outer(x);
        }
        self.scratch = buf;
    }

    /// Labels top-level node `b` inner.
    fn make_inner(&mut self, b: u32, labelend: u32, tree: u32) {
        self.set_label(b, MINUS, labelend, tree);
        if b as usize >= self.n {
            let z = self.z[b as usize - self.n];
            debug_assert!(z >= 0 && z % 2 == 0);
            self.push(self.d + z / 2, EV_EXPAND, b);
        }
    }

    // ---------------------------------------------------------------- search

    /// Handles one popped queue entry, after checking that it is still current.
    fn event(&mut self, key: i64, payload: u64) {
        let kind = payload & 3;
        let id = (payload >> 2) as u32;
        if kind == EV_EXPAND {
            let b = id;
            let bi = b as usize;
            if bi < self.n || !self.alive[bi - self.n] || self.parent[bi] != NONE || self.label[bi] != MINUS {
                return;
            }
            let saved = self.d;
            self.d = key;
            if self.zb(b) != 0 {
                self.d = saved;
                return;
            }
            self.expand_inner(b);
            return;
        }
        let k = id as usize;
        let [a, b] = self.g.ends[k];
        let (ba, bb) = (self.top(a), self.top(b));
        if ba == bb {
            return;
        }
        let (la, lb) = (self.label[ba as usize], self.label[bb as usize]);
        // The entry is current when its kind matches the labels now and the edge is
        // tight at its key.
        let current = if kind == EV_GROW {
            (la == PLUS && lb == FREE) || (la == FREE && lb == PLUS)
        } else {
            la == PLUS && lb == PLUS
        };
        if !current {
            return;
        }
        let saved = self.d;
        self.d = key;
        if self.slack(k) != 0 {
            debug_assert!(self.slack(k) > 0, "negative slack");
            self.d = saved;
            return;
        }
        if kind == EV_GROW {
            // Outer end u, free (matched, outside every tree) end v.
            let (u_end, u, v) = if la == PLUS { (2 * k as u32, a, b) } else { (2 * k as u32 + 1, b, a) };
            let tu = self.top(u);
            let tree = self.tree_of[tu as usize];
            let bv = self.top(v);
            let vbase = self.base[bv as usize];
            let mp = self.mate[vbase as usize];
            debug_assert!(mp != NONE, "exposed vertex outside the trees");
            self.make_inner(bv, u_end, tree);
            let m = self.g.endpoint(mp);
            let bm = self.top(m);
            self.make_outer(bm, mp ^ 1, tree);
        } else {
            match self.scan_blossom(a, b) {
                Some(base) => self.add_blossom(base, k),
                None => {
                    let (ta, tb) = (self.tree_of[ba as usize], self.tree_of[bb as usize]);
                    self.augment(k);
                    self.stats.augmentations += 1;
                    self.dissolve(ta);
                    self.dissolve(tb);
                }
            }
        }
    }

    /// Ends tree `t` after its augmentation: writes its lazy duals back, clears its
    /// labels, and queues the edges from other trees' outer vertices into it.
    fn dissolve(&mut self, t: u32) {
        let nodes = std::mem::take(&mut self.trees[t as usize]);
        self.live_trees -= 1;
        let mut freed = Vec::new();
        for &b in &nodes {
            let bi = b as usize;
            if self.label[bi] != FREE
                && self.parent[bi] == NONE
                && self.tree_of[bi] == t
                && (bi < self.n || self.alive[bi - self.n])
            {
                self.flush(b);
                self.label[bi] = FREE;
                self.labelend[bi] = NONE;
                self.tree_of[bi] = NONE;
                freed.push(b);
            }
        }
        let mut buf = std::mem::take(&mut self.scratch);
        for b in freed {
            self.leaves(b, &mut buf);
            if b as usize >= self.n && self.z[b as usize - self.n] == 0 {
                self.expand_free(b);
            }
            for &x in &buf {
                self.scan_free(x);
            }
        }
        self.scratch = buf;
    }

    /// Dissolves free blossom `b` whose dual is zero, and, recursively, its sub-blossoms
    /// with dual zero (as at the end of a stage in the classic algorithm). Keeps nesting
    /// shallow when many weights tie; the matching inside stays as it is.
    fn expand_free(&mut self, b: u32) {
        let mut work = vec![b];
        while let Some(b) = work.pop() {
            self.stats.blossoms_dissolved += 1;
            let bi = b as usize;
            let nb = bi - self.n;
            let owed = std::mem::replace(&mut self.boff[bi], 0);
            let childs = std::mem::take(&mut self.childs[nb]);
            for &s in &childs {
                let si = s as usize;
                self.parent[si] = NONE;
                self.label[si] = FREE;
                self.labelend[si] = NONE;
                self.tree_of[si] = NONE;
                self.tstamp[si] = self.d;
                if si < self.n {
                    self.y[si] += owed;
                    continue;
                }
                // Links into b die with it (retire); those below stay valid.
                self.boff[si] += owed;
                if self.z[si - self.n] == 0 {
                    work.push(s);
                }
            }
            let mut cv = childs;
            cv.clear();
            self.childs[nb] = cv;
            self.endps[nb].clear();
            self.retire(b);
        }
    }

    /// Walks up the tree from outer vertices `v` and `w`; returns the base vertex of the
    /// lowest common outer blossom, or None when they are in different trees.
    fn scan_blossom(&mut self, v: u32, w: u32) -> Option<u32> {
        self.mark_stamp = self.mark_stamp.wrapping_add(1);
        if self.mark_stamp == 0 {
            self.mark.iter_mut().for_each(|m| *m = 0);
            self.mark_stamp = 1;
        }
        let stamp = self.mark_stamp;
        let (mut v, mut w) = (v, w);
        while v != NONE || w != NONE {
            if v != NONE {
                let b = self.top(v);
                if self.mark[b as usize] == stamp {
                    return Some(self.base[b as usize]);
                }
                self.mark[b as usize] = stamp;
                if self.labelend[b as usize] == NONE {
                    v = NONE;
                } else {
                    let t = self.g.endpoint(self.labelend[b as usize]);
                    let bt = self.top(t);
                    v = self.g.endpoint(self.labelend[bt as usize]);
                }
            }
            if w != NONE {
                std::mem::swap(&mut v, &mut w);
            }
        }
        None
    }

    fn alloc_blossom(&mut self) -> u32 {
        if let Some(b) = self.free_blossoms.pop() {
            self.alive[b as usize - self.n] = true;
            return b;
        }
        let b = (self.n + self.childs.len()) as u32;
        self.childs.push(Vec::new());
        self.endps.push(Vec::new());
        self.z.push(0);
        self.alive.push(true);
        self.parent.push(NONE);
        self.label.push(FREE);
        self.labelend.push(NONE);
        self.tstamp.push(0);
        self.boff.push(0);
        self.tree_of.push(NONE);
        self.base.push(NONE);
        self.mark.push(0);
        self.link.push(NONE);
        self.lsum.push(0);
        self.lgen.push(0);
        self.gen.push(0);
        b
    }

    /// Makes a new outer blossom from the cycle closed by tight edge `k` between two
    /// outer blossoms whose paths to the root meet at the blossom of `base`.
    fn add_blossom(&mut self, base: u32, k: usize) {
        self.stats.blossoms_formed += 1;
        let [v, w] = self.g.ends[k];
        let bb = self.top(base);
        let mut bv = self.top(v);
        let mut bw = self.top(w);
        let b = self.alloc_blossom();
        let bi = b as usize;
        let mut path = std::mem::take(&mut self.childs[bi - self.n]);
        let mut endps = std::mem::take(&mut self.endps[bi - self.n]);
        path.clear();
        endps.clear();
        while bv != bb {
            path.push(bv);
            endps.push(self.labelend[bv as usize]);
            let x = self.g.endpoint(self.labelend[bv as usize]);
            bv = self.top(x);
        }
        path.push(bb);
        path.reverse();
        endps.reverse();
        endps.push(2 * k as u32);
        while bw != bb {
            path.push(bw);
            endps.push(self.labelend[bw as usize] ^ 1);
            let x = self.g.endpoint(self.labelend[bw as usize]);
            bw = self.top(x);
        }
        debug_assert!(path.len() % 2 == 1 && path.len() >= 3);
        let labelend_bb = self.labelend[bb as usize];
        let tree = self.tree_of[bb as usize];
        // Flush the children's lazy duals, remember which were inner.
        let mut was_inner = Vec::new();
        for &c in &path {
            self.flush(c);
            if self.label[c as usize] == MINUS {
                was_inner.push(c);
            }
            self.label[c as usize] = FREE;
            self.labelend[c as usize] = NONE;
            self.tree_of[c as usize] = NONE;
            self.parent[c as usize] = b;
        }
        self.base[bi] = base;
        self.z[bi - self.n] = 0;
        self.parent[bi] = NONE;
        self.childs[bi - self.n] = path;
        self.endps[bi - self.n] = endps;
        self.set_label(b, PLUS, labelend_bb, tree);
        // No vertex is touched for the new level: hints find it, offsets carry duals.
        let mut buf = std::mem::take(&mut self.scratch);
        // Vertices of formerly inner children are outer now: queue their edges.
        for c in was_inner {
            self.leaves(c, &mut buf);
            for &x in &buf {
                self.scan_outer(x);
            }
        }
        self.scratch = buf;
    }

    /// Expands inner blossom `b` (dual zero): the even path from its entry child to
    /// its base stays in the tree with alternating labels, the rest becomes free.
    fn expand_inner(&mut self, b: u32) {
        self.stats.blossoms_expanded += 1;
        let bi = b as usize;
        let nb = bi - self.n;
        let tree = self.tree_of[bi];
        self.flush(b);
        let entry_vertex = self.g.endpoint(self.labelend[bi] ^ 1);
        let mut entry = entry_vertex;
        while self.parent[entry as usize] != b {
            entry = self.parent[entry as usize];
        }
        let childs = std::mem::take(&mut self.childs[nb]);
        let endps = std::mem::take(&mut self.endps[nb]);
        let mut buf = std::mem::take(&mut self.scratch);
        // Push b's owed offset down to its children; the links into b die when it is
        // retired below, before any lookup.
        let owed = std::mem::replace(&mut self.boff[bi], 0);
        for &s in &childs {
            self.parent[s as usize] = NONE;
            self.label[s as usize] = FREE;
            self.labelend[s as usize] = NONE;
            self.tstamp[s as usize] = self.d;
            if (s as usize) < self.n {
                self.y[s as usize] += owed;
                continue;
            }
            self.boff[s as usize] += owed;
        }
        let len = childs.len() as i64;
        let at = |j: i64| j.rem_euclid(len) as usize;
        let entry_idx = childs.iter().position(|&c| c == entry).unwrap_or(0) as i64;
        let (mut j, jstep, endptrick) =
            if entry_idx & 1 == 1 { (entry_idx - len, 1i64, 0u32) } else { (entry_idx, -1i64, 1u32) };
        let mut p = self.labelend[bi];
        let mut outer = Vec::new();
        let mut inner = Vec::new();
        while j != 0 {
            inner.push((childs[at(j)], p));
            j += jstep;
            // childs[j] is matched to the inner child before it: it becomes outer.
            p = endps[at(j - endptrick as i64)] ^ endptrick;
            outer.push(childs[at(j)]);
            j += jstep;
        }
        inner.push((childs[0], p));
        // Children strictly between the base and the entry child on the other side
        // become free.
        let mut free = Vec::new();
        let mut jj = j + jstep;
        while childs[at(jj)] != entry {
            free.push(childs[at(jj)]);
            jj += jstep;
        }
        // Retire b.
        self.retire(b);
        let mut cv = childs;
        cv.clear();
        self.childs[nb] = cv;
        let mut ev = endps;
        ev.clear();
        self.endps[nb] = ev;
        // Labels first, then scans, so every scan sees the final labels.
        for &(c, p) in &inner {
            self.make_inner(c, p, tree);
        }
        for &c in &outer {
            // Its base is matched into the inner child before it: that is its parent.
            let mp = self.mate[self.base[c as usize] as usize];
            debug_assert!(mp != NONE);
            self.set_label(c, PLUS, mp, tree);
        }
        for &c in &outer {
            self.leaves(c, &mut buf);
            for &x in &buf {
                self.scan_outer(x);
            }
        }
        for &c in &free {
            self.leaves(c, &mut buf);
            for &x in &buf {
                self.scan_free(x);
            }
        }
        self.scratch = buf;
    }

    // ---------------------------------------------------------------- augmenting

    /// Swaps matched and unmatched edges inside blossom `b` so that vertex `v` becomes
    /// its base.
    fn augment_blossom(&mut self, b: u32, v: u32) {
        // Iterative form of the recursion: a work stack of (blossom, vertex). The
        // blossoms between `v` and `b` all take `v` as their base: they are handled
        // in one walk up from `v` (walking once per level cost depth squared on the
        // deep nests that ties build).
        let mut work = vec![(b, v)];
        let mut chain = std::mem::take(&mut self.stack);
        while let Some((b, v)) = work.pop() {
            chain.clear();
            let mut c = v;
            while c != b {
                c = self.parent[c as usize];
                chain.push(c);
            }
            for lvl in 0..chain.len() {
                let b = chain[lvl];
                let t = if lvl == 0 { v } else { chain[lvl - 1] };
                let nb = b as usize - self.n;
                let len = self.childs[nb].len() as i64;
                let at = |j: i64| j.rem_euclid(len) as usize;
                let i = self.childs[nb].iter().position(|&c| c == t).unwrap_or(0) as i64;
                let (mut j, jstep, endptrick) =
                    if i & 1 == 1 { (i - len, 1i64, 0u32) } else { (i, -1i64, 1u32) };
                while j != 0 {
                    j += jstep;
                    let t1 = self.childs[nb][at(j)];
                    let p = self.endps[nb][at(j - endptrick as i64)] ^ endptrick;
                    if t1 as usize >= self.n {
                        work.push((t1, self.g.endpoint(p)));
                    }
                    j += jstep;
                    let t2 = self.childs[nb][at(j)];
                    if t2 as usize >= self.n {
                        work.push((t2, self.g.endpoint(p ^ 1)));
                    }
                    self.mate[self.g.endpoint(p) as usize] = p ^ 1;
                    self.mate[self.g.endpoint(p ^ 1) as usize] = p;
                }
                let iu = i as usize;
                self.childs[nb].rotate_left(iu);
                self.endps[nb].rotate_left(iu);
                self.base[b as usize] = v;
            }
        }
        self.stack = chain;
    }

    /// Augments along the path through tight edge `k`.
    fn augment(&mut self, k: usize) {
        let [v, w] = self.g.ends[k];
        for (s0, p0) in [(v, 2 * k as u32 + 1), (w, 2 * k as u32)] {
            let (mut s, mut p) = (s0, p0);
            loop {
                let bs = self.top(s);
                if bs as usize >= self.n {
                    self.augment_blossom(bs, s);
                }
                self.mate[s as usize] = p;
                let le = self.labelend[bs as usize];
                if le == NONE {
                    break;
                }
                let t = self.g.endpoint(le);
                let bt = self.top(t);
                let lt = self.labelend[bt as usize];
                s = self.g.endpoint(lt);
                let j = self.g.endpoint(lt ^ 1);
                if bt as usize >= self.n {
                    self.augment_blossom(bt, j);
                }
                self.mate[j as usize] = lt;
                p = lt ^ 1;
            }
        }
    }

    // ---------------------------------------------------------------- output

    pub fn solution(&mut self) -> Solution {
        let n = self.n;
        let mate_edge = self.mate.iter().map(|&p| if p == NONE { NONE } else { p >> 1 }).collect();
        // Blossoms with positive dual, children before parents: a post-order walk from
        // every top-level blossom.
        let mut index = vec![NONE; self.childs.len()];
        let mut blossoms: Vec<(i64, u32)> = Vec::new();
        let mut order = Vec::new();
        for nb in 0..self.childs.len() {
            let b = (n + nb) as u32;
            if !self.alive[nb] || self.parent[b as usize] != NONE {
                continue;
            }
            // Pre-order, then reversed: every parent after its children.
            let mut stack = vec![b];
            let mut pre = Vec::new();
            while let Some(x) = stack.pop() {
                if (x as usize) >= n {
                    pre.push(x);
                    stack.extend_from_slice(&self.childs[x as usize - n]);
                }
            }
            pre.reverse();
            order.extend(pre);
        }
        for &b in &order {
            let nb = b as usize - n;
            if self.z[nb] > 0 {
                index[nb] = blossoms.len() as u32;
                blossoms.push((self.z[nb], NONE));
            }
        }
        // Nearest listed blossom strictly above each node (a blossom's parent, a
        // vertex's innermost listed blossom), top-down in one pass: walking up from
        // every vertex cost the nesting depth each.
        let mut near = vec![NONE; self.childs.len()];
        let mut vertex_blossom = vec![NONE; n];
        for &b in order.iter().rev() {
            let nb = b as usize - n;
            let here = if index[nb] != NONE { index[nb] } else { near[nb] };
            for &c in &self.childs[nb] {
                if (c as usize) < n {
                    vertex_blossom[c as usize] = here;
                } else {
                    near[c as usize - n] = here;
                }
            }
            if index[nb] != NONE {
                blossoms[index[nb] as usize].1 = near[nb];
            }
        }
        let y = (0..n as u32)
            .map(|v| {
                let t = self.top(v) as usize;
                self.y[v as usize] + self.above(v, t as u32) + if t >= n { self.boff[t] } else { 0 }
            })
            .collect();
        Solution { mate_edge, y, blossoms, vertex_blossom }
    }
}

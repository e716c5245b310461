//! Maximum-cardinality matching for the uniform-weight case: Edmonds' blossom
//! algorithm without duals. Karp-Sipser greedy start, then one breadth-first search per exposed
//! vertex; a blossom is contracted by merging the vertex sets of the bases on its
//! cycle, the smaller set relabelled into the larger, so one search costs
//! O(m + n log n) however many blossoms it forms.
//! A search that fails from a vertex can be skipped for good (Edmonds' theorem), so
//! every vertex starts at most one search.

use crate::graph::Graph;

const NONE: u32 = u32::MAX;

/// A maximum-cardinality matching: the partner of each vertex or
/// [`UNMATCHED`](crate::UNMATCHED).
/// Self-loops are ignored. O(n + m) start; each of the remaining searches is a BFS over
/// the region it reaches.
pub fn maximum_cardinality_matching(g: &Graph) -> Vec<u32> {
    maximum_cardinality_matching_bounded(g, 0)
}

/// [`maximum_cardinality_matching`] that stops as soon as only `min_exposed` vertices
/// are left exposed. `min_exposed` must be a lower bound on the exposed vertices of
/// every matching, such as the number of connected components with an odd number of
/// vertices (Tutte-Berge with the empty set); then the result is still maximum, and
/// the last search, which would fail after exploring a whole component, is never run.
pub fn maximum_cardinality_matching_bounded(g: &Graph, min_exposed: usize) -> Vec<u32> {
    search_from(g, vec![NONE; g.node_count()], min_exposed)
}

/// A maximum-cardinality matching grown from `start` (partner of each vertex or
/// [`UNMATCHED`](crate::UNMATCHED); pairs that are not edges of `g`, or not mutual,
/// are dropped): the free vertices are first matched greedily among themselves, then
/// each remaining one starts a breadth-first search for a shortest augmenting path.
/// Every augmentation keeps the matched vertices matched and swaps the edges along one
/// shortest path, so most of `start` survives: a heuristic for a heavy perfect matching
/// when `start` holds the heavy edges.
pub fn maximum_cardinality_matching_from(g: &Graph, start: &[u32]) -> Vec<u32> {
    let n = g.node_count();
    let mut mate = vec![NONE; n];
    for v in 0..n.min(start.len()) {
        let u = start[v];
        if u != NONE
            && (u as usize) < n
            && u as usize != v
            && start.get(u as usize) == Some(&(v as u32))
            && g.adjacency(v).iter().any(|&e| other(g, e, v as u32) == u)
        {
            mate[v] = u;
        }
    }
    search_from(g, mate, 0)
}

fn search_from(g: &Graph, mate: Vec<u32>, min_exposed: usize) -> Vec<u32> {
    let n = g.node_count();
    let ids = || (0..n as u32).collect::<Vec<u32>>();
    let mut s = State {
        mate,
        parent: vec![NONE; n],
        used: vec![false; n],
        in_blossom: vec![false; n],
        stamp: vec![0; n],
        stamp_now: 0,
        touched: Vec::new(),
        queue: std::collections::VecDeque::new(),
        set_of: ids(),
        set_base: ids(),
        set_size: vec![1; n],
        set_head: ids(),
        set_tail: ids(),
        next_member: vec![NONE; n],
        bases: Vec::new(),
    };
    karp_sipser(g, &mut s.mate);
    let mut exposed = s.mate.iter().filter(|&&m| m == NONE).count();

    for v in 0..n as u32 {
        if exposed <= min_exposed {
            break;
        }
        if s.mate[v as usize] == NONE {
            if let Some(end) = s.find_path(g, v) {
                s.augment(end);
                exposed -= 2;
            }
            s.reset();
        }
    }
    s.mate
}

/// A perfect matching (partner of each vertex), ignoring the weights, or `None` when
/// there is none (the maximum-cardinality matching leaves a vertex exposed).
pub fn unweighted_perfect_matching(g: &Graph) -> Option<Vec<u32>> {
    let mate = maximum_cardinality_matching(g);
    if mate.iter().all(|&m| m != NONE) {
        Some(mate)
    } else {
        None
    }
}

/// Karp-Sipser greedy start: a vertex with a single free neighbour is matched to it
/// first (always safe); when none is left, a vertex of least free degree seen so far
/// takes its free neighbour of least free degree. O(n + m); on sparse graphs it
/// leaves few vertices for the searches.
fn karp_sipser(g: &Graph, mate: &mut [u32]) {
    let n = g.node_count();
    let mut deg: Vec<u32> = (0..n)
        .map(|v| {
            if mate[v] != NONE {
                return 0;
            }
            g.adjacency(v)
                .iter()
                .filter(|&&e| {
                    let u = other(g, e, v as u32);
                    u != v as u32 && mate[u as usize] == NONE
                })
                .count() as u32
        })
        .collect();
    let mut ones: Vec<u32> = (0..n as u32).filter(|&v| deg[v as usize] == 1).collect();
    let mut next = 0usize;
    let matched = |v: u32, mate: &mut [u32], deg: &mut [u32], ones: &mut Vec<u32>| {
        for &e in g.adjacency(v as usize) {
            let u = other(g, e, v);
            if u != v && mate[u as usize] == NONE {
                deg[u as usize] -= 1;
                if deg[u as usize] == 1 {
                    ones.push(u);
                }
            }
        }
    };
    loop {
        let v = if let Some(v) = ones.pop() {
            v
        } else {
            // Next free vertex with a free neighbour, in id order.
            while next < n && (mate[next] != NONE || deg[next] == 0) {
                next += 1;
            }
            if next == n {
                break;
            }
            next as u32
        };
        if mate[v as usize] != NONE || deg[v as usize] == 0 {
            continue;
        }
        let mut best = NONE;
        for &e in g.adjacency(v as usize) {
            let u = other(g, e, v);
            if u != v && mate[u as usize] == NONE && (best == NONE || deg[u as usize] < deg[best as usize]) {
                best = u;
            }
        }
        if best == NONE {
            debug_assert!(false, "free degree out of step");
            deg[v as usize] = 0;
            continue;
        }
        mate[v as usize] = best;
        mate[best as usize] = v;
        matched(v, mate, &mut deg, &mut ones);
        matched(best, mate, &mut deg, &mut ones);
    }
}

#[inline]
fn other(g: &Graph, e: u32, v: u32) -> u32 {
    let [a, b] = g.edges()[e as usize];
    if a == v {
        b
    } else {
        a
    }
}

struct State {
    mate: Vec<u32>,
    parent: Vec<u32>,
    used: Vec<bool>,
    /// Marks the bases on a new blossom's cycle (indexed by base vertex).
    in_blossom: Vec<bool>,
    stamp: Vec<u32>,
    stamp_now: u32,
    touched: Vec<u32>,
    queue: std::collections::VecDeque<u32>,
    /// Contracted blossoms as disjoint vertex sets: the set of each vertex, the base
    /// of each set, and each set's members as a linked list with its size.
    set_of: Vec<u32>,
    set_base: Vec<u32>,
    set_size: Vec<u32>,
    set_head: Vec<u32>,
    set_tail: Vec<u32>,
    next_member: Vec<u32>,
    /// Scratch: the bases on the cycle of the blossom being formed.
    bases: Vec<u32>,
}

impl State {
    fn touch(&mut self, v: u32) {
        self.touched.push(v);
    }

    /// The base of the outermost contracted blossom containing `v`.
    #[inline]
    fn base(&self, v: u32) -> u32 {
        self.set_base[self.set_of[v as usize] as usize]
    }

    fn reset(&mut self) {
        for &v in &self.touched {
            let i = v as usize;
            self.parent[i] = NONE;
            self.used[i] = false;
            self.in_blossom[i] = false;
            self.set_of[i] = v;
            self.set_base[i] = v;
            self.set_size[i] = 1;
            self.set_head[i] = v;
            self.set_tail[i] = v;
            self.next_member[i] = NONE;
        }
        self.touched.clear();
        self.queue.clear();
    }

    /// Merges sets `a` and `b` (relabelling the smaller); returns the merged set.
    fn merge(&mut self, a: u32, b: u32) -> u32 {
        let (big, small) = if self.set_size[a as usize] >= self.set_size[b as usize] { (a, b) } else { (b, a) };
        let mut x = self.set_head[small as usize];
        while x != NONE {
            self.set_of[x as usize] = big;
            x = self.next_member[x as usize];
        }
        let tail = self.set_tail[big as usize];
        self.next_member[tail as usize] = self.set_head[small as usize];
        self.set_tail[big as usize] = self.set_tail[small as usize];
        self.set_size[big as usize] += self.set_size[small as usize];
        big
    }

    fn lca(&mut self, a: u32, b: u32) -> u32 {
        self.stamp_now = self.stamp_now.wrapping_add(1);
        if self.stamp_now == 0 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.stamp_now = 1;
        }
        let st = self.stamp_now;
        let mut a = a;
        loop {
            a = self.base(a);
            self.stamp[a as usize] = st;
            if self.mate[a as usize] == NONE {
                break;
            }
            a = self.parent[self.mate[a as usize] as usize];
        }
        let mut b = b;
        loop {
            b = self.base(b);
            if self.stamp[b as usize] == st {
                return b;
            }
            b = self.parent[self.mate[b as usize] as usize];
        }
    }

    fn mark_path(&mut self, mut v: u32, b: u32, mut child: u32) {
        while self.base(v) != b {
            let m = self.mate[v as usize];
            for x in [self.base(v), self.base(m)] {
                if !self.in_blossom[x as usize] {
                    self.in_blossom[x as usize] = true;
                    self.bases.push(x);
                }
            }
            self.parent[v as usize] = child;
            child = m;
            v = self.parent[m as usize];
        }
    }

    fn find_path(&mut self, g: &Graph, root: u32) -> Option<u32> {
        self.used[root as usize] = true;
        self.touch(root);
        self.queue.push_back(root);
        while let Some(v) = self.queue.pop_front() {
            for &e in g.adjacency(v as usize) {
                let to = other(g, e, v);
                if to == v || self.set_of[v as usize] == self.set_of[to as usize] || self.mate[v as usize] == to {
                    continue;
                }
                let to_mate = self.mate[to as usize];
                if to == root || (to_mate != NONE && self.parent[to_mate as usize] != NONE) {
                    let cur = self.lca(v, to);
                    self.bases.clear();
                    self.mark_path(v, cur, to);
                    self.mark_path(to, cur, v);
                    // Merge the sets of the cycle's bases into one with base `cur`.
                    // Every vertex of an earlier blossom is already in the search;
                    // a single-vertex set (an odd vertex) joins it now.
                    let mut set = self.set_of[cur as usize];
                    for i in 0..self.bases.len() {
                        let x = self.bases[i];
                        self.in_blossom[x as usize] = false;
                        let sx = self.set_of[x as usize];
                        if sx == set {
                            continue;
                        }
                        if self.set_size[sx as usize] == 1 && !self.used[x as usize] {
                            self.used[x as usize] = true;
                            self.queue.push_back(x);
                        }
                        set = self.merge(set, sx);
                    }
                    self.set_base[set as usize] = cur;
                } else if self.parent[to as usize] == NONE {
                    self.parent[to as usize] = v;
                    self.touch(to);
                    if to_mate == NONE {
                        return Some(to);
                    }
                    self.used[to_mate as usize] = true;
                    self.touch(to_mate);
                    self.queue.push_back(to_mate);
                }
            }
        }
        None
    }

    fn augment(&mut self, mut v: u32) {
        while v != NONE {
            let pv = self.parent[v as usize];
            let ppv = self.mate[pv as usize];
            self.mate[v as usize] = pv;
            self.mate[pv as usize] = v;
            v = ppv;
        }
    }
}

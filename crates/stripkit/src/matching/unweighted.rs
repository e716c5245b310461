//! Maximum-cardinality matching for the uniform-weight case: Edmonds' blossom
//! algorithm without duals. Karp-Sipser greedy start, then one breadth-first search per exposed
//! vertex; blossoms are contracted by relabelling bases, but only over the vertices
//! the search has touched, so a search costs about its tree size per blossom.
//! A search that fails from a vertex can be skipped for good (Edmonds' theorem), so
//! every vertex starts at most one search.

use super::graph::Graph;

const NONE: u32 = u32::MAX;

/// A maximum-cardinality matching: the partner of each vertex or
/// [`UNMATCHED`](super::UNMATCHED).
/// Self-loops are ignored. O(n + m) start; each of the remaining searches is a BFS over
/// the region it reaches.
pub fn maximum_cardinality_matching(g: &Graph) -> Vec<u32> {
    let n = g.node_count();
    let mut s = State {
        mate: vec![NONE; n],
        parent: vec![NONE; n],
        base: (0..n as u32).collect(),
        used: vec![false; n],
        in_blossom: vec![false; n],
        stamp: vec![0; n],
        stamp_now: 0,
        touched: Vec::new(),
        queue: std::collections::VecDeque::new(),
    };
    karp_sipser(g, &mut s.mate);
    for v in 0..n as u32 {
        if s.mate[v as usize] == NONE {
            if let Some(end) = s.find_path(g, v) {
                s.augment(end);
            }
            s.reset();
        }
    }
    s.mate
}

/// A perfect matching (partner of each vertex) in a graph with uniform weights, or
/// `None` when there is none.
pub fn perfect_matching(g: &Graph) -> Option<Vec<u32>> {
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
        .map(|v| g.adjacency(v).iter().filter(|&&e| other(g, e, v as u32) != v as u32).count() as u32)
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
    base: Vec<u32>,
    used: Vec<bool>,
    in_blossom: Vec<bool>,
    stamp: Vec<u32>,
    stamp_now: u32,
    touched: Vec<u32>,
    queue: std::collections::VecDeque<u32>,
}

impl State {
    fn touch(&mut self, v: u32) {
        self.touched.push(v);
    }

    fn reset(&mut self) {
        for &v in &self.touched {
            self.parent[v as usize] = NONE;
            self.base[v as usize] = v;
            self.used[v as usize] = false;
            self.in_blossom[v as usize] = false;
        }
        self.touched.clear();
        self.queue.clear();
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
            a = self.base[a as usize];
            self.stamp[a as usize] = st;
            if self.mate[a as usize] == NONE {
                break;
            }
            a = self.parent[self.mate[a as usize] as usize];
        }
        let mut b = b;
        loop {
            b = self.base[b as usize];
            if self.stamp[b as usize] == st {
                return b;
            }
            b = self.parent[self.mate[b as usize] as usize];
        }
    }

    fn mark_path(&mut self, mut v: u32, b: u32, mut child: u32) {
        while self.base[v as usize] != b {
            let m = self.mate[v as usize];
            let bv = self.base[v as usize] as usize;
            let bm = self.base[m as usize] as usize;
            self.in_blossom[bv] = true;
            self.in_blossom[bm] = true;
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
                if to == v || self.base[v as usize] == self.base[to as usize] || self.mate[v as usize] == to {
                    continue;
                }
                let to_mate = self.mate[to as usize];
                if to == root || (to_mate != NONE && self.parent[to_mate as usize] != NONE) {
                    let cur = self.lca(v, to);
                    self.mark_path(v, cur, to);
                    self.mark_path(to, cur, v);
                    // Only touched vertices can lie in the blossom.
                    let mut i = 0;
                    while i < self.touched.len() {
                        let x = self.touched[i];
                        let bx = self.base[x as usize] as usize;
                        if self.in_blossom[bx] {
                            self.base[x as usize] = cur;
                            if !self.used[x as usize] {
                                self.used[x as usize] = true;
                                self.queue.push_back(x);
                            }
                        }
                        i += 1;
                    }
                    for i in 0..self.touched.len() {
                        let x = self.touched[i] as usize;
                        self.in_blossom[x] = false;
                    }
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

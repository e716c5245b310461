//! Dual-edge weights for the single-strip builder. A heavy edge is one the strip should
//! not cross: the matching takes it. Every kind gives weights in `[0, 1]`, so that a
//! mix is a plain linear combination.

use super::work::{edge, WorkMesh};
use crate::vec3::{dot, sub};
use super::{cull, Weights};
use crate::matching::splitmix;
use crate::topology::{UnionFind, NO_NEIGHBOR};

/// What the cull weights found: clusters and peaks split.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct CullStats {
    pub clusters: usize,
    pub peaks: usize,
}

/// Sets `w.weight` for `weights`. Cull weights may first split peaks of clusters, so
/// this may change the mesh. `cull_angle` in radians; `cull_noise`: small seeded noise
/// on the in-cluster cull weights. Returns the cull statistics (zero without cull).
pub(crate) fn assign(w: &mut WorkMesh, weights: &Weights, seed: u64, cull_angle: f64, cull_noise: bool) -> CullStats {
    // The mesh changes (cull's peak splits) come first, so every kind sees the final mesh.
    let cull = uses_cull(weights).then(|| cull::cull_weights(w, cull_angle, seed, cull_noise));
    let table = eval(w, weights, seed, cull.as_ref().map(|c| c.weights.as_slice()));
    w.weight = table;
    cull.map(|c| CullStats { clusters: c.clusters, peaks: c.peaks }).unwrap_or_default()
}

fn uses_cull(weights: &Weights) -> bool {
    match weights {
        Weights::Cull => true,
        Weights::Mix(terms) => terms.iter().any(|(_, k)| uses_cull(k)),
        _ => false,
    }
}

fn eval(w: &WorkMesh, weights: &Weights, seed: u64, cull: Option<&[[f64; 3]]>) -> Vec<[f64; 3]> {
    match weights {
        Weights::Uniform => vec![[1.0; 3]; w.len()],
        Weights::Cull => cull.expect("cull weights computed first").to_vec(),
        Weights::Cache => cache_weights(w, seed),
        Weights::Direction(axis) => direction_weights(w, *axis),
        Weights::Mix(terms) => {
            let mut out = vec![[0.0; 3]; w.len()];
            for (c, k) in terms {
                let part = eval(w, k, seed, cull);
                for (o, p) in out.iter_mut().zip(&part) {
                    for j in 0..3 {
                        o[j] += c * p[j];
                    }
                }
            }
            out
        }
    }
}

/// `|cos|` of the angle between the edge and the axis. Edges along the axis weigh most
/// and are matched (not crossed), so the strip crosses the edges that lie across the
/// axis and advances along it.
fn direction_weights(w: &WorkMesh, axis: [f64; 3]) -> Vec<[f64; 3]> {
    let la = dot(axis, axis).sqrt();
    let axis = axis.map(|x| x / la);
    w.tris
        .iter()
        .map(|t| {
            std::array::from_fn(|j| {
                let (a, b) = edge(t, j);
                let d = sub(w.pos[b as usize], w.pos[a as usize]);
                let l = dot(d, d).sqrt();
                if l > 0.0 {
                    (dot(d, axis) / l).abs().min(1.0)
                } else {
                    0.0
                }
            })
        })
        .collect()
}

/// Vertices per breadth-first ball of the cache weights' tree (one source in about
/// this many vertices).
const CACHE_BALL: usize = 64;

/// A randomized breadth-first spanning tree of the mesh's edges, at most one tree edge
/// per triangle: tree edges weigh 1, the rest 0. The matching then takes most tree
/// edges, and the strip winds around the tree like a space-filling curve (section 5
/// of the paper).
///
/// The breadth-first search starts from random sources, one in about [`CACHE_BALL`]
/// vertices, all at once: the tree is compact balls, joined by one edge where two
/// touch. The strip then finishes a ball while its vertices are still cached. One
/// search from a single root (the paper's) gives acmr32 0.695 to 0.701 on horse over
/// four seeds; balls of 64 give 0.682 to 0.685 (fandisk: 0.694 to 0.708 against 0.677
/// to 0.686; docs/experiments/single-strips.md).
fn cache_weights(w: &WorkMesh, seed: u64) -> Vec<[f64; 3]> {
    let nv = w.pos.len();
    // Mesh edges with two triangles, bucketed by both endpoints: (other, t * 3 + j).
    let mut count = vec![0u32; nv + 1];
    for (t, tri) in w.tris.iter().enumerate() {
        for j in 0..3 {
            let u = w.nbr[t][j];
            if u != NO_NEIGHBOR && (t as u32) < u {
                let (a, b) = edge(tri, j);
                count[a as usize] += 1;
                count[b as usize] += 1;
            }
        }
    }
    let mut start = vec![0u32; nv + 1];
    for v in 0..nv {
        start[v + 1] = start[v] + count[v];
    }
    let mut fill = start.clone();
    let mut adj = vec![(0u32, 0u32); start[nv] as usize];
    for (t, tri) in w.tris.iter().enumerate() {
        for j in 0..3 {
            let u = w.nbr[t][j];
            if u != NO_NEIGHBOR && (t as u32) < u {
                let (a, b) = edge(tri, j);
                let s = (t * 3 + j) as u32;
                adj[fill[a as usize] as usize] = (b, s);
                fill[a as usize] += 1;
                adj[fill[b as usize] as usize] = (a, s);
                fill[b as usize] += 1;
            }
        }
    }
    let mut rng = seed ^ 0x5eed_cafe;
    let mut out = vec![[0.0; 3]; w.len()];
    let mut has_tree = vec![false; w.len()];
    let mut seen = vec![false; nv];
    let mut queue: Vec<u32> = Vec::with_capacity(nv);
    // The edge in slot `s % 3` of triangle `s / 3` joins the tree unless one of its two
    // triangles already holds a tree edge.
    let take = |has_tree: &mut [bool], out: &mut [[f64; 3]], s: u32| {
        let (t, j) = ((s / 3) as usize, (s % 3) as usize);
        let u = w.nbr[t][j] as usize;
        if has_tree[t] || has_tree[u] {
            return false;
        }
        has_tree[t] = true;
        has_tree[u] = true;
        out[t][j] = 1.0;
        out[u][w.twin(t, j)] = 1.0;
        true
    };
    {
        let ball = CACHE_BALL;
        // Many sources at once: compact balls of about `ball` vertices, then the balls
        // joined by one edge each where they touch.
        let mut owner = vec![u32::MAX; nv];
        queue.clear();
        for v in 0..nv {
            if count[v] > 0 && splitmix(&mut rng) % ball as u64 == 0 {
                seen[v] = true;
                owner[v] = v as u32;
                queue.push(v as u32);
            }
        }
        let (mut head, mut scan) = (0, 0);
        loop {
            while head < queue.len() {
                let v = queue[head] as usize;
                head += 1;
                let list = &adj[start[v] as usize..start[v + 1] as usize];
                if list.is_empty() {
                    continue;
                }
                let rot = (splitmix(&mut rng) % list.len() as u64) as usize;
                for i in 0..list.len() {
                    let (x, s) = list[(i + rot) % list.len()];
                    if seen[x as usize] {
                        continue;
                    }
                    if !take(&mut has_tree, &mut out, s) {
                        continue;
                    }
                    seen[x as usize] = true;
                    owner[x as usize] = owner[v];
                    queue.push(x);
                }
            }
            // Unreached vertices become sources of their own.
            while scan < nv && (seen[scan] || count[scan] == 0) {
                scan += 1;
            }
            if scan == nv {
                break;
            }
            seen[scan] = true;
            owner[scan] = scan as u32;
            queue.push(scan as u32);
        }
        // Join the balls: a spanning tree over them, one free edge per join.
        let mut balls = UnionFind::new(nv);
        // Breadth-first over balls from the queue order, so joins stay local.
        for &v in queue.iter() {
            let v = v as usize;
            for &(x, s) in &adj[start[v] as usize..start[v + 1] as usize] {
                let (a, b) = (owner[v], owner[x as usize]);
                if a == u32::MAX || b == u32::MAX {
                    continue;
                }
                if balls.find(a) != balls.find(b) && take(&mut has_tree, &mut out, s) {
                    balls.union(a, b);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gen;

    #[test]
    fn cache_tree_has_at_most_one_edge_per_triangle() {
        let m = gen::icosphere(3);
        let w = WorkMesh::new(&m.positions, m.triangulate().tris);
        let t = cache_weights(&w, 7);
        let per: Vec<usize> = t.iter().map(|s| s.iter().filter(|&&x| x > 0.0).count()).collect();
        assert!(per.iter().all(|&c| c <= 1));
        let tree_edges = per.iter().sum::<usize>() / 2;
        // A spanning forest: fewer edges than vertices, and most vertices reached.
        assert!(tree_edges < m.vertex_count());
        assert!(tree_edges * 10 > m.vertex_count() * 7, "{tree_edges} of {}", m.vertex_count());
    }

    #[test]
    fn direction_weights_follow_the_axis() {
        let m = gen::grid(4, 4);
        let w = WorkMesh::new(&m.positions, m.triangulate().tris);
        let d = direction_weights(&w, [1.0, 0.0, 0.0]);
        for (t, s) in w.tris.iter().zip(&d) {
            for (j, &x) in s.iter().enumerate() {
                let (a, b) = edge(t, j);
                let e = sub(w.pos[b as usize], w.pos[a as usize]);
                assert!((x - (e[0].abs() / dot(e, e).sqrt())).abs() < 1e-12);
            }
        }
    }
}

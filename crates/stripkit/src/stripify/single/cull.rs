//! Weights for back-face culling (section 4.1 of the paper).
//!
//! 1. **Clusters** of triangles with nearly parallel normals: a greedy flood under the
//!    normal-deviation bound `max_angle` (a cluster grows across dual edges while a
//!    triangle's normal is within `max_angle` of the cluster's area-weighted average
//!    normal; seeds in index order from a seeded start), then [`LLOYD_ITERATIONS`]
//!    Lloyd iterations of variational shape approximation (Cohen-Steiner, Alliez,
//!    Desbrun 2004) with the L2,1 metric: the proxy of a cluster is its area-weighted
//!    average normal, and the clusters are regrown by priority-queue flooding from each
//!    proxy's best triangle, at distortion `area * |n - N|^2`. Each iteration is
//!    `O(n log n)`; the number of clusters is the greedy one.
//! 2. **Peaks**: a triangle with two cluster-boundary edges whose third neighbour is in
//!    its cluster is split together with that neighbour (the shared edge at its
//!    midpoint, one Steiner vertex); the pieces keep their triangle's cluster and have
//!    one boundary edge each, so the matching can take all of them.
//! 3. **Weights**: a dual edge inside a cluster weighs a small seeded noise in
//!    `[0, NOISE]` (or 0 without noise), which spares the matching the exhaustive
//!    search of many equal zero weights (section 6 of the paper). An edge between two
//!    clusters whose normals are `a` radians apart weighs
//!    `FLOOR + (1 - FLOOR) ln(1 + a / EPS) / ln(1 + pi / EPS)` with `EPS` = 1 degree:
//!    the logarithm of the deviation, as the paper advises, so that boundaries of
//!    clusters that differ less are not ignored beside the sharpest ones; `FLOOR`
//!    (0.005, 5 as an integer weight) keeps every boundary edge heavier than any noisy
//!    in-cluster edge (at most 3 as an integer weight), even between clusters with
//!    equal normals.

use super::work::WorkMesh;
use crate::vec3::{dot, norm, sub, tri_normal, unit};
use crate::matching::splitmix;
use crate::strip::is_degenerate;
use crate::topology::NO_NEIGHBOR;
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::f64::consts::PI;

/// Lloyd iterations of VSA after the greedy clustering.
pub(crate) const LLOYD_ITERATIONS: usize = 4;
/// The most noise on an in-cluster weight (3 as an integer weight).
pub(crate) const NOISE: f64 = 0.003;
/// The least weight of a cluster-boundary edge (5 as an integer weight).
pub(crate) const FLOOR: f64 = 0.005;
/// The angle scale of the logarithm: 1 degree.
const EPS: f64 = PI / 180.0;

/// Cull weights and what it took to make them.
#[derive(Clone, Debug)]
pub(crate) struct Cull {
    /// Per-slot weights of the mesh after the peak splits.
    pub weights: Vec<[f64; 3]>,
    /// Clusters found.
    pub clusters: usize,
    /// Peaks split (one Steiner vertex each).
    pub peaks: usize,
}

/// Per-slot weights in `[0, 1]` for back-face culling, symmetric; splits the peaks of
/// the clusters in `w` first (see the module docs). `max_angle` in radians.
pub(crate) fn cull_weights(w: &mut WorkMesh, max_angle: f64, seed: u64, noise: bool) -> Cull {
    let (normal, area) = normals_and_areas(w);
    let (mut cluster, clusters) = greedy(w, &normal, &area, max_angle, seed);
    let proxy = lloyd(w, &normal, &area, &mut cluster, clusters, LLOYD_ITERATIONS);
    let peaks = split_peaks(w, &mut cluster);
    let weights = weights(w, &cluster, &proxy, noise.then_some(seed));
    Cull { weights, clusters, peaks }
}

/// The boundary weight of two clusters whose normals are `angle` radians apart.
pub(crate) fn boundary_weight(angle: f64) -> f64 {
    let a = angle.clamp(0.0, PI);
    FLOOR + (1.0 - FLOOR) * (a / EPS).ln_1p() / (PI / EPS).ln_1p()
}

/// Unit normals (zero for a zero-area triangle) and areas.
fn normals_and_areas(w: &WorkMesh) -> (Vec<[f64; 3]>, Vec<f64>) {
    let mut normal = Vec::with_capacity(w.len());
    let mut area = Vec::with_capacity(w.len());
    for t in &w.tris {
        let [a, b, c] = t.map(|i| w.pos[i as usize]);
        let n = tri_normal(a, b, c);
        match unit(n) {
            Some(u) => {
                normal.push(u);
                area.push(norm(n) / 2.0);
            }
            None => {
                normal.push([0.0; 3]);
                area.push(0.0);
            }
        }
    }
    (normal, area)
}

/// `v` at unit length, zero for a zero vector.
fn unit_or_zero(v: [f64; 3]) -> [f64; 3] {
    unit(v).unwrap_or([0.0; 3])
}

fn add_scaled(s: &mut [f64; 3], v: [f64; 3], k: f64) {
    for i in 0..3 {
        s[i] += k * v[i];
    }
}

/// Greedy clusters: flood from the first unclustered triangle (in index order from a
/// seeded start) while a triangle's normal is within `max_angle` of the cluster's
/// area-weighted average normal. Zero-area triangles join any cluster that reaches
/// them. Returns each triangle's cluster and the number of clusters.
fn greedy(w: &WorkMesh, normal: &[[f64; 3]], area: &[f64], max_angle: f64, seed: u64) -> (Vec<u32>, usize) {
    let n = w.len();
    let cos_max = max_angle.cos();
    let mut cluster = vec![u32::MAX; n];
    let mut queue: Vec<u32> = Vec::with_capacity(n);
    let mut rng = seed ^ 0xc105_7e25;
    let first = if n == 0 { 0 } else { (splitmix(&mut rng) % n as u64) as usize };
    let mut k = 0u32;
    for s in (first..n).chain(0..first) {
        if cluster[s] != u32::MAX {
            continue;
        }
        cluster[s] = k;
        let mut sum = [0.0; 3];
        add_scaled(&mut sum, normal[s], area[s]);
        queue.clear();
        queue.push(s as u32);
        let mut head = 0;
        while head < queue.len() {
            let t = queue[head] as usize;
            head += 1;
            let c = unit_or_zero(sum);
            let flat = c == [0.0; 3];
            for &u in &w.nbr[t] {
                if u == NO_NEIGHBOR || cluster[u as usize] != u32::MAX {
                    continue;
                }
                let u = u as usize;
                if flat || area[u] == 0.0 || dot(normal[u], c) >= cos_max {
                    cluster[u] = k;
                    add_scaled(&mut sum, normal[u], area[u]);
                    queue.push(u as u32);
                }
            }
        }
        k += 1;
    }
    (cluster, k as usize)
}

/// The L2,1 distortion of `t` against the proxy normal `p`.
#[inline]
fn distortion(normal: &[[f64; 3]], area: &[f64], t: usize, p: [f64; 3]) -> f64 {
    let d = sub(normal[t], p);
    area[t] * dot(d, d)
}

/// Area-weighted average normals of the clusters.
fn fit(normal: &[[f64; 3]], area: &[f64], cluster: &[u32], proxy: &mut [[f64; 3]]) {
    proxy.fill([0.0; 3]);
    for (t, &c) in cluster.iter().enumerate() {
        add_scaled(&mut proxy[c as usize], normal[t], area[t]);
    }
    for p in proxy.iter_mut() {
        *p = unit_or_zero(*p);
    }
}

/// `iterations` Lloyd iterations of VSA on `cluster` (k clusters, each connected);
/// returns the proxies of the final clusters.
fn lloyd(
    w: &WorkMesh,
    normal: &[[f64; 3]],
    area: &[f64],
    cluster: &mut [u32],
    k: usize,
    iterations: usize,
) -> Vec<[f64; 3]> {
    let mut proxy = vec![[0.0; 3]; k];
    let mut best = vec![(f64::INFINITY, u32::MAX); k];
    // (distortion bits, triangle, cluster): distortions are >= 0, so their bits order
    // as the numbers do.
    let mut heap: BinaryHeap<Reverse<(u64, u32, u32)>> = BinaryHeap::with_capacity(w.len());
    for _ in 0..iterations {
        fit(normal, area, cluster, &mut proxy);
        best.fill((f64::INFINITY, u32::MAX));
        for (t, &c) in cluster.iter().enumerate() {
            let e = distortion(normal, area, t, proxy[c as usize]);
            if e < best[c as usize].0 || best[c as usize].1 == u32::MAX {
                best[c as usize] = (e, t as u32);
            }
        }
        cluster.fill(u32::MAX);
        heap.clear();
        let push = |heap: &mut BinaryHeap<_>, cluster: &[u32], t: usize, c: u32, proxy: &[[f64; 3]]| {
            for &u in &w.nbr[t] {
                if u != NO_NEIGHBOR && cluster[u as usize] == u32::MAX {
                    let e = distortion(normal, area, u as usize, proxy[c as usize]);
                    heap.push(Reverse((e.to_bits(), u, c)));
                }
            }
        };
        for (c, &(_, t)) in best.iter().enumerate() {
            cluster[t as usize] = c as u32;
        }
        for (c, &(_, t)) in best.iter().enumerate() {
            push(&mut heap, cluster, t as usize, c as u32, &proxy);
        }
        while let Some(Reverse((_, t, c))) = heap.pop() {
            if cluster[t as usize] != u32::MAX {
                continue;
            }
            cluster[t as usize] = c;
            push(&mut heap, cluster, t as usize, c, &proxy);
        }
    }
    fit(normal, area, cluster, &mut proxy);
    proxy
}

/// Whether `t` is a peak: two dual edges to other clusters and the third to its own.
/// Returns the slot of the in-cluster neighbour.
fn peak_slot(w: &WorkMesh, cluster: &[u32], t: usize) -> Option<usize> {
    let c = cluster[t];
    let (mut boundary, mut inside) = (0, None);
    for (j, &u) in w.nbr[t].iter().enumerate() {
        if u == NO_NEIGHBOR {
            return None;
        }
        if cluster[u as usize] == c {
            inside = Some(j);
        } else {
            boundary += 1;
        }
    }
    if boundary == 2 {
        inside
    } else {
        None
    }
}

/// Peaks of clusters smaller than this are left alone. A noisy scan falls into many
/// small clusters under the normal bound (dragon: 8,593 clusters of 100,000 triangles)
/// and splitting all their peaks grew it by 39% of its vertices; a strip through a
/// small cluster leaves it soon anyway. Dragon: 19,315 -> 5,196 Steiner vertices for
/// 5% more cluster boundaries crossed (15,363 -> 16,166); horse 4,440 -> 3,739 (+4%);
/// fandisk unchanged (docs/experiments/single-strips-cull.md).
const PEAK_MIN_CLUSTER: usize = 32;

/// Splits every peak (of a cluster of at least [`PEAK_MIN_CLUSTER`] triangles) together with its in-cluster neighbour; the pieces keep the
/// clusters of their triangles. Returns the number of splits.
fn split_peaks(w: &mut WorkMesh, cluster: &mut Vec<u32>) -> usize {
    let n = w.len();
    let mut peaks = 0;
    let mut size = vec![0usize; cluster.iter().map(|&c| c as usize + 1).max().unwrap_or(0)];
    for &c in cluster.iter() {
        size[c as usize] += 1;
    }
    // A split leaves every piece with at most one boundary edge and changes no other
    // triangle's count, so one pass over the input triangles finds them all.
    for t in 0..n {
        if is_degenerate(&w.tris[t]) {
            continue;
        }
        let Some(j) = peak_slot(w, cluster, t) else { continue };
        if size[cluster[t] as usize] < PEAK_MIN_CLUSTER {
            continue;
        }
        let u = w.nbr[t][j] as usize;
        if is_degenerate(&w.tris[u]) {
            continue;
        }
        let c = cluster[t];
        w.split(t, j, false);
        cluster.push(c);
        cluster.push(c);
        peaks += 1;
    }
    peaks
}

/// Per-slot weights from the clusters (see the module docs); `noise`: the seed of the
/// in-cluster noise, or none for zeros.
fn weights(w: &WorkMesh, cluster: &[u32], proxy: &[[f64; 3]], noise: Option<u64>) -> Vec<[f64; 3]> {
    let mut out = vec![[0.0; 3]; w.len()];
    let mut rng = noise.unwrap_or(0) ^ 0x0015_e0ff_5e75;
    for t in 0..w.len() {
        for j in 0..3 {
            let u = w.nbr[t][j];
            if u == NO_NEIGHBOR || u < t as u32 {
                continue;
            }
            let u = u as usize;
            let (a, b) = (cluster[t] as usize, cluster[u] as usize);
            let x = if a == b {
                match noise {
                    Some(_) => (splitmix(&mut rng) >> 11) as f64 / (1u64 << 53) as f64 * NOISE,
                    None => 0.0,
                }
            } else {
                boundary_weight(dot(proxy[a], proxy[b]).clamp(-1.0, 1.0).acos())
            };
            out[t][j] = x;
            out[u][w.twin(t, j)] = x;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gen;
    use crate::stripify::single::WEIGHT_SCALE;

    fn work(m: &crate::Mesh) -> WorkMesh {
        WorkMesh::new(&m.positions, m.triangulate().tris)
    }

    /// Clusters and proxies of `w` as `cull_weights` makes them, without the splits.
    fn clusters(w: &WorkMesh, max_angle: f64, seed: u64) -> (Vec<u32>, usize, Vec<[f64; 3]>) {
        let (normal, area) = normals_and_areas(w);
        let (mut cluster, k) = greedy(w, &normal, &area, max_angle, seed);
        let proxy = lloyd(w, &normal, &area, &mut cluster, k, LLOYD_ITERATIONS);
        (cluster, k, proxy)
    }

    fn check_symmetric_unit(w: &WorkMesh, c: &Cull) {
        assert_eq!(c.weights.len(), w.len());
        for t in 0..w.len() {
            for j in 0..3 {
                let x = c.weights[t][j];
                assert!((0.0..=1.0).contains(&x), "{x}");
                let u = w.nbr[t][j];
                if u == NO_NEIGHBOR {
                    assert_eq!(x, 0.0);
                } else {
                    assert_eq!(x, c.weights[u as usize][w.twin(t, j)]);
                }
            }
        }
    }

    #[test]
    fn cube_gives_six_clusters_zero_inside_and_heavy_across() {
        for m in [gen::cube(), gen::cube_grid(4)] {
            let w0 = work(&m);
            let (cluster, k, _) = clusters(&w0, 30f64.to_radians(), 3);
            assert_eq!(k, 6);
            // Every cluster is one face: equal normals inside, none shared across.
            let (normal, _) = normals_and_areas(&w0);
            for t in 0..w0.len() {
                for &u in &w0.nbr[t] {
                    let same = dot(normal[t], normal[u as usize]) > 0.99;
                    assert_eq!(same, cluster[t] == cluster[u as usize]);
                }
            }
            for noise in [false, true] {
                let mut w = w0.clone();
                let c = cull_weights(&mut w, 30f64.to_radians(), 3, noise);
                assert_eq!(c.clusters, 6);
                check_symmetric_unit(&w, &c);
                let (normal, _) = normals_and_areas(&w);
                for t in 0..w.len() {
                    for j in 0..3 {
                        let u = w.nbr[t][j] as usize;
                        let x = c.weights[t][j];
                        if dot(normal[t], normal[u]) > 0.99 {
                            assert!(x <= NOISE, "{x}");
                            if !noise {
                                assert_eq!(x, 0.0);
                            }
                        } else {
                            assert!((x - boundary_weight(PI / 2.0)).abs() < 1e-9, "{x}");
                        }
                    }
                }
            }
        }
        // The plain cube's 12 triangles are all peaks (two face edges on the cube's
        // edges), but its clusters are too small to split them.
        let mut w = work(&gen::cube());
        let c = cull_weights(&mut w, 30f64.to_radians(), 1, true);
        assert_eq!((c.clusters, c.peaks, w.len()), (6, 0, 12));
        // 4 x 4 quads a face: 32 triangles, and a peak at two corners of each face.
        let mut w = work(&gen::cube_grid(4));
        let c = cull_weights(&mut w, 30f64.to_radians(), 1, true);
        assert_eq!((c.clusters, c.peaks), (6, 12));
        assert_eq!((w.len(), w.steiner.len()), (192 + 24, 12));
    }

    #[test]
    fn boundary_weights_grow_with_the_log_of_the_angle_and_beat_the_noise() {
        assert!((boundary_weight(PI) - 1.0).abs() < 1e-12);
        assert_eq!(boundary_weight(0.0), FLOOR);
        assert!((NOISE * WEIGHT_SCALE).round() < (FLOOR * WEIGHT_SCALE).round());
        let mut last = 0.0;
        for d in [1.0, 5.0, 10.0, 30.0, 60.0, 90.0, 180.0] {
            let x = boundary_weight(f64::to_radians(d));
            assert!(x > last);
            last = x;
        }
        // The log gives a 10-degree boundary more than half the weight of a 180-degree one.
        assert!(boundary_weight(10f64.to_radians()) > 0.45);
    }

    #[test]
    fn weights_are_symmetric_and_in_unit_range() {
        for (m, flat) in [(gen::icosphere(3), false), (gen::torus(24, 12, 1.0, 0.3), false), (gen::grid(6, 5), true)] {
            let mut w = work(&m);
            let c = cull_weights(&mut w, 20f64.to_radians(), 5, true);
            assert_eq!(c.clusters == 1, flat, "{} clusters", c.clusters);
            check_symmetric_unit(&w, &c);
        }
    }

    #[test]
    fn peak_splitting_leaves_no_peaks() {
        let m = gen::icosphere(4);
        let w0 = work(&m);
        let angle = 30f64.to_radians();
        let (cluster, _, _) = clusters(&w0, angle, 2);
        let mut size = vec![0; w0.len()];
        cluster.iter().for_each(|&c| size[c as usize] += 1);
        let big = |cl: &[u32], t: usize| size.get(cl[t] as usize).is_some_and(|&s| s >= PEAK_MIN_CLUSTER);
        let before = (0..w0.len()).filter(|&t| big(&cluster, t) && peak_slot(&w0, &cluster, t).is_some()).count();
        assert!(before > 0);
        let mut w = w0.clone();
        let mut cl = cluster.clone();
        let peaks = split_peaks(&mut w, &mut cl);
        assert!(peaks > 0 && peaks <= before, "{peaks} of {before}");
        assert_eq!(w.len(), w0.len() + 2 * peaks);
        assert_eq!(w.steiner.len(), peaks);
        assert_eq!(cl.len(), w.len());
        for t in 0..w.len() {
            assert!(!big(&cl, t) || peak_slot(&w, &cl, t).is_none(), "triangle {t} is still a peak");
        }
        // cull_weights agrees.
        let mut w2 = w0.clone();
        let c = cull_weights(&mut w2, angle, 2, true);
        assert_eq!(c.peaks, peaks);
        assert_eq!(w2.tris, w.tris);
    }

    #[test]
    fn deterministic_for_a_seed() {
        let m = gen::torus(30, 16, 1.0, 0.4);
        let run = |seed| {
            let mut w = work(&m);
            let c = cull_weights(&mut w, 25f64.to_radians(), seed, true);
            (w.tris, c.weights, c.clusters, c.peaks)
        };
        assert_eq!(run(9), run(9));
        assert_ne!(run(9).1, run(10).1);
    }
}

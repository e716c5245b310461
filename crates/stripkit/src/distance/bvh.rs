//! A bounding-volume hierarchy over triangles for exact closest-point queries.

use crate::vec3::{cross, dot, sub, unit, V3};

#[inline]
fn add_scaled(a: V3, b: V3, s: f64) -> V3 {
    [a[0] + b[0] * s, a[1] + b[1] * s, a[2] + b[2] * s]
}

/// Squared distance from `p` to triangle `t` (exact; Ericson's region test).
pub fn point_triangle_distance2(p: V3, t: &[V3; 3]) -> f64 {
    let [a, b, c] = *t;
    let ab = sub(b, a);
    let ac = sub(c, a);
    let ap = sub(p, a);
    let d1 = dot(ab, ap);
    let d2 = dot(ac, ap);
    let q = if d1 <= 0.0 && d2 <= 0.0 {
        a
    } else {
        let bp = sub(p, b);
        let d3 = dot(ab, bp);
        let d4 = dot(ac, bp);
        if d3 >= 0.0 && d4 <= d3 {
            b
        } else {
            let vc = d1 * d4 - d3 * d2;
            if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
                add_scaled(a, ab, d1 / (d1 - d3))
            } else {
                let cp = sub(p, c);
                let d5 = dot(ab, cp);
                let d6 = dot(ac, cp);
                if d6 >= 0.0 && d5 <= d6 {
                    c
                } else {
                    let vb = d5 * d2 - d1 * d6;
                    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
                        add_scaled(a, ac, d2 / (d2 - d6))
                    } else {
                        let va = d3 * d6 - d5 * d4;
                        if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
                            add_scaled(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)))
                        } else {
                            let denom = 1.0 / (va + vb + vc);
                            let v = vb * denom;
                            let w = vc * denom;
                            add_scaled(add_scaled(a, ab, v), ac, w)
                        }
                    }
                }
            }
        }
    };
    let d = sub(p, q);
    dot(d, d)
}

#[derive(Clone, Copy, Debug)]
struct Node {
    lo: V3,
    hi: V3,
    /// 1 + the index of the node's oriented box in `Bvh::oriented`, 0 for none.
    oriented: u32,
    /// Leaf: first triangle; inner: index of the left child (right is left + 1).
    first: u32,
    /// Triangles in a leaf; 0 for an inner node.
    count: u32,
}

/// An oriented box: three orthonormal axes and the range of a node's corners along
/// each. A node of long thin triangles that share a vertex or an edge (a star, a
/// fanned polygon, a book of pages on one edge) is a thin wedge whose axis-aligned
/// box holds much of the other wedges' space: queries visited most triangles of such
/// meshes (issue #16). Built only for meshes with such a vertex (in more than
/// `HUB_TRIANGLES` triangles; other meshes keep the plain hierarchy and its speed),
/// and kept only where it is much tighter than the axis-aligned box (its box
/// surface, or its thinnest extent, under a quarter of the other's).
#[derive(Clone, Copy, Debug)]
struct Obb {
    axes: [V3; 3],
    lo: V3,
    hi: V3,
}

/// A binary BVH (median split on the widest centroid axis, leaves of up to 4
/// triangles) storing the triangles' corners in leaf order.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Node>,
    oriented: Vec<Obb>,
    tris: Vec<[V3; 3]>,
}

const LEAF: usize = 4;

/// A mesh with a vertex in more triangles than this gets oriented boxes (see `Obb`).
const HUB_TRIANGLES: u32 = 256;

/// Axes of an oriented box around `corners`: the direction of an approximate
/// diameter (farthest from a corner, then farthest from that), the direction to the
/// corner farthest from that line, and their cross product (three linear passes).
/// The world axes when the corners are too degenerate for that.
fn oriented_axes(corners: impl Iterator<Item = V3> + Clone) -> [V3; 3] {
    let world = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let Some(p0) = corners.clone().next() else { return world };
    let farthest = |from: V3| {
        corners.clone().fold((from, 0.0), |(b, bd), q| {
            let d = dot(sub(q, from), sub(q, from));
            if d > bd {
                (q, d)
            } else {
                (b, bd)
            }
        })
    };
    let p1 = farthest(p0).0;
    let p2 = farthest(p1).0;
    let Some(a) = unit(sub(p2, p1)) else { return world };
    let off = |q: V3| {
        let w = sub(q, p1);
        add_scaled(w, a, -dot(w, a))
    };
    let (q, _) = corners.clone().fold((p1, 0.0), |(b, bd), q| {
        let d = dot(off(q), off(q));
        if d > bd {
            (q, d)
        } else {
            (b, bd)
        }
    });
    let b = unit(off(q)).or_else(|| {
        // All on a line: any perpendicular.
        let t = if a[0].abs() < 0.9 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
        unit(cross(a, t))
    });
    let Some(b) = b else { return world };
    let Some(c) = unit(cross(a, b)) else { return world };
    // b again from c and a, for orthogonality to rounding.
    let Some(b) = unit(cross(c, a)) else { return world };
    [a, b, c]
}

/// Surface of a box of these extents (up to a factor 2).
fn box_surface(e: V3) -> f64 {
    e[0] * e[1] + e[1] * e[2] + e[2] * e[0]
}

fn box_distance2(p: V3, lo: V3, hi: V3) -> f64 {
    let mut d = 0.0;
    for k in 0..3 {
        let e = (lo[k] - p[k]).max(0.0).max(p[k] - hi[k]);
        d += e * e;
    }
    d
}

impl Bvh {
    /// Builds the hierarchy over `tris` (indices into `positions`, all in range) in
    /// O(n log n).
    pub fn build(positions: &[[f32; 3]], tris: &[[u32; 3]]) -> Bvh {
        let mut items: Vec<([V3; 3], V3)> = tris
            .iter()
            .map(|t| {
                let c = t.map(|v| positions[v as usize].map(|x| x as f64));
                let centroid = [0, 1, 2].map(|k| (c[0][k] + c[1][k] + c[2][k]) / 3.0);
                (c, centroid)
            })
            .collect();
        let mut nodes = Vec::with_capacity(2 * tris.len() / LEAF + 2);
        let blank = Node { lo: [0.0; 3], hi: [0.0; 3], oriented: 0, first: 0, count: 0 };
        nodes.push(blank);
        let mut oriented = Vec::new();
        let mut valence = vec![0u32; positions.len()];
        tris.iter().flatten().for_each(|&v| valence[v as usize] += 1);
        let hubs = valence.iter().any(|&c| c > HUB_TRIANGLES);
        drop(valence);
        // Explicit stack of (node, start, end).
        let mut stack = vec![(0usize, 0usize, items.len())];
        while let Some((node, start, end)) = stack.pop() {
            let slice = &mut items[start..end];
            let mut lo = [f64::INFINITY; 3];
            let mut hi = [f64::NEG_INFINITY; 3];
            let mut clo = [f64::INFINITY; 3];
            let mut chi = [f64::NEG_INFINITY; 3];
            for (c, m) in slice.iter() {
                for p in c {
                    for k in 0..3 {
                        lo[k] = lo[k].min(p[k]);
                        hi[k] = hi[k].max(p[k]);
                    }
                }
                for k in 0..3 {
                    clo[k] = clo[k].min(m[k]);
                    chi[k] = chi[k].max(m[k]);
                }
            }
            nodes[node].lo = lo;
            nodes[node].hi = hi;
            if hubs {
                Self::orient(slice, lo, hi, &mut oriented, &mut nodes[node]);
            }
            if slice.len() <= LEAF {
                nodes[node].first = start as u32;
                nodes[node].count = slice.len() as u32;
                continue;
            }
            let axis = (0..3).max_by(|&a, &b| (chi[a] - clo[a]).total_cmp(&(chi[b] - clo[b]))).unwrap_or(0);
            let mid = slice.len() / 2;
            slice.select_nth_unstable_by(mid, |x, y| x.1[axis].total_cmp(&y.1[axis]));
            let left = nodes.len();
            nodes.push(Node { lo, hi, ..blank });
            nodes.push(Node { lo, hi, ..blank });
            nodes[node].first = left as u32;
            nodes[node].count = 0;
            stack.push((left + 1, start + mid, end));
            stack.push((left, start, start + mid));
        }
        Bvh { nodes, oriented, tris: items.into_iter().map(|(c, _)| c).collect() }
    }

    /// Gives `node` an oriented box when it is much tighter than (lo, hi).
    fn orient(slice: &[([V3; 3], V3)], lo: V3, hi: V3, oriented: &mut Vec<Obb>, node: &mut Node) {
        // Axes from at most 64 of the node's triangles (spread over it): the box
        // is exact whatever the axes, and the build stays about one more pass.
        let step = slice.len().div_ceil(64).max(1);
        let axes = oriented_axes(slice.iter().step_by(step).flat_map(|(c, _)| c.iter().copied()));
        let (mut olo, mut ohi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for (c, _) in slice.iter() {
            for p in c {
                for k in 0..3 {
                    let x = dot(*p, axes[k]);
                    olo[k] = olo[k].min(x);
                    ohi[k] = ohi[k].max(x);
                }
            }
        }
        // Padding against rounding: a millionth of the extent plus a little of the
        // coordinates' size.
        let size = (0..3).map(|k| hi[k].abs().max(lo[k].abs())).fold(0.0, f64::max);
        for k in 0..3 {
            let pad = 1e-6 * (ohi[k] - olo[k]) + 1e-12 * size;
            olo[k] -= pad;
            ohi[k] += pad;
        }
        let extent = |lo: V3, hi: V3| [0, 1, 2].map(|k| hi[k] - lo[k]);
        let (eo, ea) = (extent(olo, ohi), extent(lo, hi));
        let thinnest = |e: V3| e[0].min(e[1]).min(e[2]);
        if box_surface(eo) < 0.25 * box_surface(ea) || thinnest(eo) < 0.25 * thinnest(ea) {
            oriented.push(Obb { axes, lo: olo, hi: ohi });
            node.oriented = oriented.len() as u32;
        }
    }

    /// A lower bound of the squared distance from `p` to anything in `node`: its
    /// axis-aligned box's distance, or where that is under `best` and the node has
    /// an oriented box, the larger of that and the oriented box's (shrunk by a
    /// millionth against rounding in the projections). A lower bound is all pruning
    /// needs: a query's result is the same, only fewer nodes are visited.
    fn bound(&self, p: V3, node: &Node, best: f64) -> f64 {
        let aabb = box_distance2(p, node.lo, node.hi);
        if aabb >= best || node.oriented == 0 {
            return aabb;
        }
        let o = &self.oriented[node.oriented as usize - 1];
        let mut d = 0.0;
        for k in 0..3 {
            let x = dot(p, o.axes[k]);
            let e = (o.lo[k] - x).max(0.0).max(x - o.hi[k]);
            d += e * e;
        }
        aabb.max(d * 0.999_999)
    }

    /// True when there are no triangles.
    pub fn is_empty(&self) -> bool {
        self.tris.is_empty()
    }

    /// Squared distance from `p` to the nearest triangle and that triangle's slot
    /// (leaf order). `hint` (a slot from an earlier, nearby query) starts the search
    /// with a good bound. Infinity for an empty hierarchy.
    pub fn closest(&self, p: V3, hint: usize, stack: &mut Vec<u32>) -> (f64, usize) {
        if self.tris.is_empty() {
            return (f64::INFINITY, 0);
        }
        let hint = hint.min(self.tris.len() - 1);
        let mut best = point_triangle_distance2(p, &self.tris[hint]);
        let mut best_slot = hint;
        stack.clear();
        stack.push(0);
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n as usize];
            if self.bound(p, node, best) >= best {
                continue;
            }
            if node.count > 0 {
                let s = node.first as usize;
                for slot in s..s + node.count as usize {
                    let d = point_triangle_distance2(p, &self.tris[slot]);
                    if d < best {
                        best = d;
                        best_slot = slot;
                    }
                }
            } else {
                let l = node.first;
                let dl = self.bound(p, &self.nodes[l as usize], best);
                let dr = self.bound(p, &self.nodes[l as usize + 1], best);
                // Visit the nearer child first: push it last.
                let (near, far, dfar) = if dl <= dr { (l, l + 1, dr) } else { (l + 1, l, dl) };
                if dfar < best {
                    stack.push(far);
                }
                stack.push(near);
            }
        }
        (best, best_slot)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_triangle_regions() {
        let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert_eq!(point_triangle_distance2([0.2, 0.2, 3.0], &t), 9.0); // face
        assert_eq!(point_triangle_distance2([-1.0, -1.0, 0.0], &t), 2.0); // vertex a
        assert_eq!(point_triangle_distance2([0.5, -2.0, 0.0], &t), 4.0); // edge ab
        assert!((point_triangle_distance2([1.0, 1.0, 0.0], &t) - 0.5).abs() < 1e-15); // edge bc
        assert_eq!(point_triangle_distance2([3.0, 0.0, 4.0], &t), 4.0 + 16.0); // vertex b
    }

    #[test]
    fn bvh_matches_brute_force() {
        let mut positions = Vec::new();
        let mut tris = Vec::new();
        let mut s = 12345u64;
        let mut r = move || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) as f32
        };
        for i in 0..300u32 {
            let c = [r() * 10.0, r() * 10.0, r() * 10.0];
            for _ in 0..3 {
                positions.push([c[0] + r(), c[1] + r(), c[2] + r()]);
            }
            tris.push([3 * i, 3 * i + 1, 3 * i + 2]);
        }
        let bvh = Bvh::build(&positions, &tris);
        let mut stack = Vec::new();
        for _ in 0..200 {
            let p = [r() as f64 * 12.0 - 1.0, r() as f64 * 12.0 - 1.0, r() as f64 * 12.0 - 1.0];
            let brute = tris
                .iter()
                .map(|t| point_triangle_distance2(p, &t.map(|v| positions[v as usize].map(|x| x as f64))))
                .fold(f64::INFINITY, f64::min);
            let (d, _) = bvh.closest(p, 17, &mut stack);
            assert_eq!(d, brute);
        }
    }
}

//! A bounding-volume hierarchy over triangles for exact closest-point queries.

type V3 = [f64; 3];

#[inline]
fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
#[inline]
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
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
    /// Leaf: first triangle; inner: index of the left child (right is left + 1).
    first: u32,
    /// Triangles in a leaf; 0 for an inner node.
    count: u32,
}

/// A binary BVH (median split on the widest centroid axis, leaves of up to 4
/// triangles) storing the triangles' corners in leaf order.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Node>,
    tris: Vec<[V3; 3]>,
}

const LEAF: usize = 4;

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
        nodes.push(Node { lo: [0.0; 3], hi: [0.0; 3], first: 0, count: 0 });
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
            if slice.len() <= LEAF {
                nodes[node].first = start as u32;
                nodes[node].count = slice.len() as u32;
                continue;
            }
            let axis = (0..3).max_by(|&a, &b| (chi[a] - clo[a]).total_cmp(&(chi[b] - clo[b]))).unwrap_or(0);
            let mid = slice.len() / 2;
            slice.select_nth_unstable_by(mid, |x, y| x.1[axis].total_cmp(&y.1[axis]));
            let left = nodes.len();
            nodes.push(Node { lo, hi, first: 0, count: 0 });
            nodes.push(Node { lo, hi, first: 0, count: 0 });
            nodes[node].first = left as u32;
            nodes[node].count = 0;
            stack.push((left + 1, start + mid, end));
            stack.push((left, start, start + mid));
        }
        Bvh { nodes, tris: items.into_iter().map(|(c, _)| c).collect() }
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
            if box_distance2(p, node.lo, node.hi) >= best {
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
                let dl = box_distance2(p, self.nodes[l as usize].lo, self.nodes[l as usize].hi);
                let dr = box_distance2(p, self.nodes[l as usize + 1].lo, self.nodes[l as usize + 1].hi);
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

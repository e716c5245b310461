//! Exhaustive matching search for tiny graphs, shared by the matching tests.

/// The best matching of a graph on `n` vertices by recursion on the lowest unused
/// vertex: it maximises `sign * weight` (sign 1: maximum weight, -1: minimum cost),
/// with `max_card` after the cardinality first. Returns (matched edges, weight); when
/// not `max_card`, the cardinality is that of one optimal matching. Self-loops are
/// skipped; parallel edges each count.
pub fn brute(n: usize, edges: &[[u32; 2]], w: &[i64], sign: i64, max_card: bool) -> (usize, i64) {
    fn rec(v: usize, n: usize, used: &mut [bool], edges: &[[u32; 2]], w: &[i64], sign: i64, mc: bool) -> (usize, i64) {
        let mut v = v;
        while v < n && used[v] {
            v += 1;
        }
        if v == n {
            return (0, 0);
        }
        used[v] = true;
        // Leave v unmatched.
        let mut best = rec(v + 1, n, used, edges, w, sign, mc);
        for (i, e) in edges.iter().enumerate() {
            let u = if e[0] as usize == v {
                e[1] as usize
            } else if e[1] as usize == v {
                e[0] as usize
            } else {
                continue;
            };
            if u == v || used[u] {
                continue;
            }
            used[u] = true;
            let (c, s) = rec(v + 1, n, used, edges, w, sign, mc);
            let cand = (c + 1, s + sign * w[i]);
            if if mc { cand > best } else { cand.1 > best.1 } {
                best = cand;
            }
            used[u] = false;
        }
        used[v] = false;
        best
    }
    let (c, s) = rec(0, n, &mut vec![false; n], edges, w, sign, max_card);
    (c, sign * s)
}

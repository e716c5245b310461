//! The two-state programme shared by the quad stripifiers ([`super::quad`],
//! [`super::quad_single`]): how a quad can be crossed ([`modes`]), the cost of a step
//! ([`step`]), and the strip with the fewest swaps for a whole sequence of adjacent
//! quads ([`emit_quad_sequence`]).

use super::quad_adjacency::{QuadAdjacency, FREE};

/// Local edge marker for "no entry" / "no exit".
pub(super) const NO_EDGE: u8 = 4;
/// An unreachable programme state.
pub(super) const INF: u32 = u32::MAX / 4;

/// How a quad is crossed, given its entry and exit edges.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// Entered through `a b`, left through `c d` (no swap).
    Straight,
    /// Left through `b c` (one swap inside the quad).
    TurnBc,
    /// Left through `d a` (one swap inside the quad).
    TurnDa,
    /// Last quad of a sequence.
    Last,
    /// First quad, strip `a b d c` (diagonal `b d`).
    FirstBd,
    /// First quad, strip `b c a c d` (diagonal `a c`, one swap).
    FirstAc,
}

/// One way to cross a quad. States: 0 = the newer strip vertex on the shared edge is
/// the start `a` of the quad's own half-edge on it, 1 = its end `b`.
#[derive(Clone, Copy, Debug)]
struct Mode {
    kind: Kind,
    /// Required entry state (ignored for first quads).
    need: u8,
    /// State on the next quad's entry half-edge (ignored for last quads).
    out: u8,
    /// Swaps inside the quad.
    cost: u32,
    /// Diagonal used: 0 = v0-v2, 1 = v1-v3.
    diag: u8,
}

/// The ways to cross a quad with entry edge `j` and exit edge `k` (local, or
/// [`NO_EDGE`]), honouring a forced diagonal. At most two.
fn modes(j: u8, k: u8, forced: u8) -> [Option<Mode>; 2] {
    let m = |kind, need, out, cost, diag: u8| Mode {
        kind,
        need,
        out,
        cost,
        diag: diag % 2,
    };
    let list = if j == NO_EDGE {
        [
            Some(m(Kind::FirstBd, 0, 1, 0, k + 1)),
            Some(m(Kind::FirstAc, 0, 0, 1, k)),
        ]
    } else if k == NO_EDGE {
        [
            Some(m(Kind::Last, 0, 0, 0, j)),
            Some(m(Kind::Last, 1, 0, 0, j + 1)),
        ]
    } else {
        match (k + 4 - j) % 4 {
            2 => [
                Some(m(Kind::Straight, 0, 0, 0, j)),
                Some(m(Kind::Straight, 1, 1, 0, j + 1)),
            ],
            1 => [Some(m(Kind::TurnBc, 1, 0, 1, j + 1)), None],
            _ => [Some(m(Kind::TurnDa, 0, 1, 1, j)), None],
        }
    };
    list.map(|o| o.filter(|mode| forced == FREE || mode.diag == forced))
}

/// Programme step: costs at the next quad's entry from costs `f` at this quad's entry.
pub(super) fn step(f: [u32; 2], j: u8, k: u8, forced: u8) -> [u32; 2] {
    let mut out = [INF; 2];
    for mode in modes(j, k, forced).into_iter().flatten() {
        let base = if j == NO_EDGE {
            0
        } else {
            let n = mode.need as usize;
            f[n].min(f[1 - n] + 1)
        };
        let c = base + mode.cost;
        let o = mode.out as usize;
        out[o] = out[o].min(c);
    }
    // A swap at the start of the next quad turns one state into the other.
    [out[0].min(out[1] + 1), out[1].min(out[0] + 1)]
}

/// Turns a sequence of adjacent quads `(quad, entry edge, exit edge)` into one strip
/// (appended to `strip`) with the fewest swaps, by the two-state programme; returns the
/// swaps. Every step must be feasible under the forced diagonals (see [`step`]).
pub(super) fn emit_quad_sequence(
    adj: &QuadAdjacency,
    seq: &[(u32, u8, u8)],
    togo: &mut Vec<[u32; 2]>,
    strip: &mut Vec<u32>,
) -> usize {
    let n = seq.len();
    let mut swaps = 0;
    if n == 0 {
        return 0;
    }
    if n == 1 {
        let q = seq[0].0 as usize;
        let v = &adj.verts[4 * q..4 * q + 4];
        if adj.forced[q] == 0 {
            strip.extend_from_slice(&[v[1], v[2], v[0], v[3]]);
        } else {
            strip.extend_from_slice(&[v[0], v[1], v[3], v[2]]);
        }
        return 0;
    }
    // Cost to go, from the back.
    togo.clear();
    togo.resize(n + 1, [0, 0]);
    for i in (0..n).rev() {
        let (q, j, k) = seq[i];
        let after = togo[i + 1];
        let mut g = [INF; 2];
        for mode in modes(j, k, adj.forced[q as usize]).into_iter().flatten() {
            let rest = mode.cost
                + if k == NO_EDGE {
                    0
                } else {
                    after[mode.out as usize]
                };
            if j == NO_EDGE {
                g[0] = g[0].min(rest);
            } else {
                let need = mode.need as usize;
                g[need] = g[need].min(rest);
                g[1 - need] = g[1 - need].min(rest + 1);
            }
        }
        togo[i] = g;
    }
    // Forward emission.
    let mut state = 0u8;
    for i in 0..n {
        let (q, j, k) = seq[i];
        let after = togo[i + 1];
        let mut best: Option<Mode> = None;
        let mut best_cost = INF;
        for mode in modes(j, k, adj.forced[q as usize]).into_iter().flatten() {
            let swap = if j == NO_EDGE || mode.need == state {
                0
            } else {
                1
            };
            let c = swap
                + mode.cost
                + if k == NO_EDGE {
                    0
                } else {
                    after[mode.out as usize]
                };
            if c < best_cost {
                best_cost = c;
                best = Some(mode);
            }
        }
        let Some(mode) = best else {
            // Callers only pass feasible sequences.
            debug_assert!(false, "no way through quad {q}");
            return swaps;
        };
        let qv = &adj.verts[4 * q as usize..4 * q as usize + 4];
        let at = |o: u8| qv[((if j == NO_EDGE { k + 2 } else { j }) + o) as usize % 4];
        let (a, b, c, d) = (at(0), at(1), at(2), at(3));
        if j != NO_EDGE && mode.need != state {
            // Repeat the second-to-last vertex: the next triangle pivots on the other end.
            let older = strip[strip.len() - 2];
            strip.push(older);
            swaps += 1;
        }
        match mode.kind {
            Kind::FirstBd => strip.extend_from_slice(&[a, b, d, c]),
            Kind::FirstAc => {
                strip.extend_from_slice(&[b, c, a, c, d]);
                swaps += 1;
            }
            Kind::Straight | Kind::Last => {
                if mode.need == 0 {
                    strip.extend_from_slice(&[c, d]);
                } else {
                    strip.extend_from_slice(&[d, c]);
                }
            }
            Kind::TurnBc => {
                strip.extend_from_slice(&[d, b, c]);
                swaps += 1;
            }
            Kind::TurnDa => {
                strip.extend_from_slice(&[c, a, d]);
                swaps += 1;
            }
        }
        state = mode.out;
    }
    swaps
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_costs_match_the_paper_cases() {
        // Straight keeps the state at no cost.
        assert_eq!(step([0, 1], 0, 2, FREE), [0, 1]);
        // Turns cost one swap from the right state, two from the other.
        assert_eq!(step([0, 1], 0, 3, FREE), [2, 1]);
        assert_eq!(step([0, 1], 0, 1, FREE), [2, 3]);
        // First quad: state 1 free, state 0 one swap.
        assert_eq!(step([0, 0], NO_EDGE, 1, FREE), [1, 0]);
    }
}

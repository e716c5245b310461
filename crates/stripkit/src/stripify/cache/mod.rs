//! Cache-aware strips: short strips laid side by side under a simulated FIFO vertex
//! cache, each strip running along the one before it so that half of its vertices are
//! still cached.
//!
//! A strip without swaps is a *line*: once its first triangle and the edge it leaves
//! across are chosen, every next triangle is the one across the edge formed by the
//! last two indices. In a regular region the lines of one direction lie side by side
//! like the rows of a grid, and a line started next to the beginning of the previous
//! strip runs along it and reads the previous strip's far side from the cache.
//!
//! How a mesh flows through this module:
//!
//! 1. [`stripify_mesh`] puts the mesh in a canonical order (`canonical.rs`: vertices
//!    by position in Z-order, faces sorted), so that a shuffled input gives the same
//!    strips, and picks how quads are split ([`Split`]).
//! 2. The stripifier (`fifo_strips.rs`) grows one strip at a time while it simulates
//!    exactly the FIFO of docs/metrics.md ([`crate::metrics`]), choosing among walks from
//!    the free triangles around the cache by their indices and weighed misses per
//!    triangle; `miss_weight` trades indices for misses ([`CacheOptions::cache`] and
//!    [`CacheOptions::balanced`] are two points). It records the strips and the walks
//!    they encode ([`crate::topology::Walks`]).
//! 3. [`stripify_within`] (the `balanced` mode) searches the miss weight for the
//!    fewest indices within an ACMR bound.
//! 4. A strip is joined to the one before it where that one ends, at an even length,
//!    on the vertex it starts with ([`join_shared_ends`]: one restart index fewer).
//! 5. With [`CacheOptions::refine`] or a bound, the walks go through the local search
//!    of `crate::improve` (reversals, joins, chains, tunnels and flips, each scored
//!    on the exact FIFO, the joins of step 4 counted in every move).
//! 6. [`stripify_mesh`] maps the strips back to the input's vertex ids.
//!
//! The input order only breaks ties, so shuffled inputs give about the same figures
//! from [`stripify`]. Steps follow [`DualGraph`] edges only, so every triangle keeps
//! its winding.

mod canonical;
mod fifo_strips;
mod links;
mod partition;

use super::Split;
use crate::improve::{refine, Effort};
use crate::strip::{is_degenerate, join_shared_ends, StripSet};
use crate::topology::{DualGraph, Walks};
use canonical::Canonical;
use fifo_strips::{prepare, State};
pub(crate) use fifo_strips::FAN_CANDIDATES;

/// Settings of the cache-aware stripifier.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CacheOptions {
    /// Entries of the FIFO vertex cache the strips are tuned for (at least 3). The candidate
    /// scan and the walks grow with it: O(triangles x cache_size) at worst (a 100k-triangle
    /// grid, balanced: 3.2 s at 16 entries, 4.1 s at 65,536).
    pub cache_size: u32,
    /// Longest walk, in triangles (a strip that goes on from the last one may end up
    /// longer).
    pub max_len: u32,
    /// Cost of one cache miss, in indices.
    pub miss_weight: f32,
    /// Cost, in indices, of each free neighbour of a strip's first triangle that the
    /// strip does not enter (starting inside the free region cuts it up).
    pub start_penalty: f32,
    /// Swaps allowed per walk.
    pub max_swaps: u32,
    /// Strips start only at triangles with at least this many cached vertices while
    /// there are any (fewer walks, about the same strips).
    pub min_cached: u32,
    /// Candidates are the free triangles around the oldest `scan_entries` entries of
    /// the FIFO (at most `cache_size`); the whole FIFO only where these give none.
    pub scan_entries: u32,
    /// Also offer going on from the end of the last strip.
    pub join: bool,
    /// Taken off a walk's cost, in indices, for each vertex whose last free triangle it
    /// covers: a finished vertex never misses again, one left with a triangle or two
    /// will likely miss again once evicted.
    pub finish_bonus: f32,
    /// Then refine the strips with the local search of [`stripify_within`] (joins,
    /// chains, reversals, tunnels and flips scored by the exact FIFO), a miss costing
    /// `miss_weight` indices and no move adding misses: fewer indices and fewer misses
    /// for many times the time. Used by [`stripify`], [`stripify_with_graph`] and [`stripify_mesh`] without a
    /// bound; [`stripify_within`] always refines.
    pub refine: bool,
    /// Meshes of more triangles than this (after the split of quads) are cut into parts of
    /// about `partition::PART_TRIANGLES` (262,144) triangles, ranges of the canonical (Z-order) triangle
    /// list, stripified on their own (in parallel when the threads allow) and joined
    /// across the part borders; `0` never cuts. The cut depends on the mesh only, so
    /// the strips are the same at any thread count. Without a bound only
    /// ([`stripify_within`] runs on the whole mesh). Default 0.
    pub partition_above: u32,
}

impl CacheOptions {
    /// The `cache` mode: a miss weighs 1.1 indices and finishing a vertex earns one,
    /// walks of at most `cache_size` triangles from around the oldest five eighths of
    /// the cache (bunny: fewer misses and fewer indices than meshoptimizer's cache
    /// order and strips).
    pub fn cache(cache_size: u32) -> Self {
        let cache_size = cache_size.max(3);
        CacheOptions {
            cache_size,
            max_len: cache_size,
            miss_weight: 1.1,
            start_penalty: 1.0,
            max_swaps: 8,
            min_cached: 2,
            // In u64: `cache_size * 5` overflows u32 above 858,993,459 entries.
            scan_entries: (cache_size as u64 * 5 / 8) as u32,
            join: true,
            finish_bonus: 1.0,
            refine: false,
            partition_above: 0,
        }
    }

    /// The `balanced` mode's first try: a miss weighs half an index and finishing a
    /// vertex a quarter (fewer indices, more misses), and strips may start at
    /// triangles with one cached vertex; meant for [`stripify_within`] with a bound
    /// (the CLI's: 0.8 misses per triangle).
    pub fn balanced(cache_size: u32) -> Self {
        CacheOptions {
            miss_weight: 0.5,
            finish_bonus: 0.25,
            min_cached: 1,
            ..CacheOptions::cache(cache_size)
        }
    }
}

impl Default for CacheOptions {
    fn default() -> Self {
        CacheOptions::cache(16)
    }
}

/// Strips for `tris` (indices below `vertex_count`; larger ones are tolerated),
/// ordered for a FIFO vertex cache (see the module docs). Degenerate triangles are
/// dropped; every other triangle appears exactly once with its winding. (The door
/// runs [`stripify_mesh`]; the tests run this on raw triangle lists.)
#[cfg(test)]
pub fn stripify(tris: &[[u32; 3]], vertex_count: usize, options: &CacheOptions) -> StripSet {
    run_once(tris, None, vertex_count, options).0
}

/// As [`stripify`], with the dual graph of `tris` already built.
#[cfg(test)]
pub fn stripify_with_graph(
    tris: &[[u32; 3]],
    vertex_count: usize,
    graph: &DualGraph,
    options: &CacheOptions,
) -> StripSet {
    run_once(tris, Some(graph), vertex_count, options).0
}

/// One run of the stripifier, refined when `options.refine` (on `graph`, the dual
/// graph of `tris`, built here when not given): the strips and their misses in the
/// FIFO of `options.cache_size`. The stripifier's state is dropped before the graph
/// of the refinement is built.
fn run_once(
    tris: &[[u32; 3]],
    graph: Option<&DualGraph>,
    vertex_count: usize,
    options: &CacheOptions,
) -> (StripSet, u64) {
    let (misses, mut out, walks) = {
        let (vtris, links) = prepare(tris, vertex_count);
        let mut s = State::new(tris, &links, Some(vtris), vertex_count, options);
        if options.refine {
            s.keep_walks();
        }
        s.run();
        (u64::from(s.fifo.pushes()), s.out, s.walks)
    };
    join_shared_ends(&mut out);
    if !options.refine {
        return (out, misses);
    }
    let built;
    let graph = match graph {
        Some(g) => g,
        None => {
            built = DualGraph::from_triangles(tris, vertex_count);
            &built
        }
    };
    let cache_size = options.cache_size.max(3) as usize;
    let lambda = f64::from(options.miss_weight);
    let (strips, refined) = refine(
        tris,
        graph,
        &walks,
        cache_size,
        lambda,
        misses,
        CACHE_EFFORT,
    );
    if refined <= misses && strips.restart_len() <= out.restart_len() {
        (strips, refined)
    } else {
        (out, misses)
    }
}

/// Strips as [`stripify`] makes them, with the fewest indices its miss weights give
/// while the ACMR (for a FIFO of `options.cache_size`) stays at most `max_acmr`, then
/// joined further by a local search scored on the exact FIFO.
///
/// The weight starts at `options.miss_weight`. Within the bound there, up to two
/// lower weights (a tenth less each) are tried while they stay within it; outside,
/// the weight grows by a quarter per try until the bound holds (at most eight tries;
/// the last try's strips when none keeps it), and the geometric mean of the last
/// two weights is tried once more. The try with the fewest indices within the bound
/// is then refined: strips are joined end to end (or one into another's inside, the
/// part cut off joining a third), relinked along tunnels through up to three strips,
/// rerouted by flips of alternating cycles and paths, and read backwards wherever
/// that lowers `indices + 0.25 * misses` on the exact FIFO while the misses stay
/// within the bound (or, when no try kept it, do not grow); the refined strips are
/// kept when they have fewer indices. Returns the strips, the weight of the try
/// refined and their ACMR. The refinement takes most of the time.
pub fn stripify_within(
    tris: &[[u32; 3]],
    vertex_count: usize,
    options: &CacheOptions,
    max_acmr: f64,
) -> (StripSet, f32, f64) {
    // The dual graph and the links raise the vertex count themselves for larger indices.
    let graph = DualGraph::from_triangles(tris, vertex_count);
    let links = prepare(tris, vertex_count).1;
    let triangles = tris.iter().filter(|t| !is_degenerate(t)).count();
    let run = |miss_weight: f32| {
        let o = CacheOptions {
            miss_weight,
            ..*options
        };
        let mut s = State::new(tris, &links, None, vertex_count, &o);
        s.keep_walks();
        s.run();
        // The simulated FIFO is the measured one: its pushes are the misses.
        Try {
            miss_weight,
            misses: u64::from(s.fifo.pushes()),
            strips: s.out,
            walks: s.walks,
        }
    };
    let acmr = |misses: u64| {
        if triangles == 0 {
            0.0
        } else {
            misses as f64 / triangles as f64
        }
    };
    let within = |t: &Try| acmr(t.misses) <= max_acmr;
    let keep = |best: &mut Try, next: Try| {
        if within(&next) && next.strips.restart_len() < best.strips.restart_len() {
            *best = next;
        }
    };
    let mut w = options.miss_weight;
    let mut best = run(w);
    'search: {
        if within(&best) {
            for _ in 0..2 {
                w *= 0.9;
                let next = run(w);
                if !within(&next) {
                    break;
                }
                keep(&mut best, next);
            }
            break 'search;
        }
        for _ in 1..8 {
            let failed = w;
            w *= 1.25;
            best = run(w);
            if within(&best) {
                let mid = run((failed * w).sqrt());
                keep(&mut best, mid);
                break 'search;
            }
        }
    }
    // The largest miss count within the bound (or, beyond it, the one reached).
    let budget = ((max_acmr * triangles as f64).floor() as u64).max(best.misses);
    let cache_size = options.cache_size.max(3) as usize;
    let (strips, misses) = refine(
        tris,
        &graph,
        &best.walks,
        cache_size,
        REFINE_LAMBDA,
        budget,
        BALANCED_EFFORT,
    );
    let kept = misses <= best.misses || acmr(misses) <= max_acmr;
    let mut unrefined = best.strips;
    join_shared_ends(&mut unrefined);
    if misses <= budget && kept && strips.restart_len() < unrefined.restart_len() {
        return (strips, best.miss_weight, acmr(misses));
    }
    (unrefined, best.miss_weight, acmr(best.misses))
}

/// One run of the stripifier in [`stripify_within`]: its strips, their misses, and
/// the strips as walks.
struct Try {
    miss_weight: f32,
    misses: u64,
    strips: StripSet,
    walks: Walks,
}

/// What [`stripify_mesh`] returns.
#[derive(Clone, Debug)]
pub struct MeshStrips {
    /// The strips.
    pub strips: StripSet,
    /// The triangles the strips cover, each with its face's winding: the fan of the
    /// mesh, or its quads split along QSTRIP's diagonals.
    pub triangles: Vec<[u32; 3]>,
    /// True when `triangles` split the quads along QSTRIP's diagonals rather than
    /// fanning them (check such strips against the mesh with
    /// [`verify_quads`](crate::stripify::quad_verify::verify_quads)).
    pub qstrip_diagonals: bool,
    /// The miss weight used (see [`stripify_within`]).
    #[cfg_attr(not(test), allow(dead_code))] // read by the tests
    pub miss_weight: f32,
    /// Cache misses per triangle of the strips in the FIFO they were tuned for.
    pub acmr: f64,
}

/// Cache-aware strips for a mesh that may hold quads. With `max_acmr`, the strips of
/// [`stripify_within`] (the `balanced` mode); without, those of [`stripify`].
///
/// A quad may be split along either diagonal, and the split decides which rows of
/// quads become swap-free lines. [`Split::Auto`] tries, on quad-dominant meshes,
/// both the fan and QSTRIP's diagonals and keeps the cheaper result: without a bound
/// the lower `indices_restart + miss_weight * misses`; with one, the fewer indices
/// among the results within the bound, else the lower ACMR. Runs the stripifier
/// twice on such meshes, once on others.
///
/// The stripifier runs on a canonical copy: vertices renumbered by position (in
/// Z-order), triangles starting at their lowest id and sorted, quads given to QSTRIP
/// likewise. The strips therefore do not depend on the order of the faces, the vertex
/// ids or where a triangle or quad starts: a shuffled input gives the same strips,
/// vertex for vertex through the renumbering. (Where a larger polygon, or a quad under
/// the fan, starts decides its fan, so that stays part of the input; vertices at equal
/// positions fall back to their ids.) The copy costs little next to the stripifier.
pub fn stripify_mesh(
    mesh: &crate::mesh::Mesh,
    options: &CacheOptions,
    max_acmr: Option<f64>,
    split: Split,
    threads: crate::parallel::Threads,
) -> MeshStrips {
    let fraction = crate::stripify::quad::quad_fraction(mesh);
    let (fan, qstrip) = match split {
        // Without quads there is nothing to split: the fan it is.
        Split::Qstrip if fraction > 0.0 => (false, true),
        Split::Auto if fraction >= 0.5 => (true, true),
        _ => (true, false),
    };
    // The same strips whatever the order of the faces, their rotation (but for the
    // fan of a polygon, which is another split) and the vertex ids: run in a canonical
    // order, map back.
    let mut canon = Canonical::of(mesh, threads);
    let vc = mesh.vertex_count();
    let fan_tris = fan.then(|| canon.fan(mesh, threads));
    if !qstrip {
        // The new ids have served (the strips go back through the old ones).
        canon.forget_new();
    }
    let canon = canon;
    let run = |tris: Vec<[u32; 3]>, qstrip_diagonals: bool| {
        let (strips, miss_weight, acmr) = match max_acmr {
            Some(bound) => stripify_within(&tris, vc, options, bound),
            None => {
                let ranges = partition::parts(tris.len(), options.partition_above);
                let (strips, misses) = if ranges.len() > 1 {
                    partition::run_parted(&tris, &ranges, options, threads)
                } else {
                    run_once(&tris, None, vc, options)
                };
                let t = tris.iter().filter(|t| !is_degenerate(t)).count().max(1);
                (strips, options.miss_weight, misses as f64 / t as f64)
            }
        };
        MeshStrips {
            strips: canon.strips_back(strips, threads),
            triangles: canon.triangles_back(tris, threads),
            qstrip_diagonals,
            miss_weight,
            acmr,
        }
    };
    // The two candidates are independent: run side by side when threads allow.
    let (a, b) = crate::parallel::join(
        threads,
        || fan_tris.map(|tris| run(tris, false)),
        || {
            qstrip.then(|| {
                let (_, strips) = crate::stripify::quad::qstrip_mesh(
                    &canon.rotated(mesh),
                    &crate::stripify::quad::QuadOptions::default(),
                );
                run(crate::strip::decode(&strips), true)
            })
        },
    );
    match (a, b) {
        (Some(a), Some(b)) => {
            let indices = |m: &MeshStrips| m.strips.restart_len() as f64;
            let better_b = match max_acmr {
                None => {
                    let cost = |m: &MeshStrips| {
                        indices(m)
                            + f64::from(options.miss_weight) * m.acmr * m.triangles.len() as f64
                    };
                    cost(&b) < cost(&a)
                }
                Some(bound) => match (a.acmr <= bound, b.acmr <= bound) {
                    (true, true) => indices(&b) < indices(&a),
                    (ok_a, ok_b) if ok_a != ok_b => ok_b,
                    _ => b.acmr < a.acmr,
                },
            };
            if better_b {
                b
            } else {
                a
            }
        }
        (Some(m), None) | (None, Some(m)) => m,
        (None, None) => unreachable!("at least one triangulation is tried"),
    }
}

/// What one miss costs, in indices, in the refinement of [`stripify_within`]: about
/// the exchange rate along the stripifier's own frontier; 0.25 measured best against
/// 0.2 to 0.3 on the shared models.
const REFINE_LAMBDA: f64 = 0.25;

/// The search of `balanced`, where the index count is the point: five passes, flips
/// of up to four links (measured on the shared models: 0.3% fewer indices than three
/// and three, for 1.8x the time).
const BALANCED_EFFORT: Effort = Effort {
    passes: 5,
    flip_links: 4,
};

/// The search of `cache --refine`: three passes, flips of up to three links (four
/// links and five passes gave 0.15% fewer indices on the shared models for 1.8x the
/// time).
const CACHE_EFFORT: Effort = Effort {
    passes: 3,
    flip_links: 3,
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::{cache_misses, CacheKind};
    use crate::strip::{decode, verify};

    fn grid(w: u32, h: u32) -> (Vec<[u32; 3]>, usize) {
        let mesh = crate::gen::grid(w, h);
        (mesh.triangulate().tris, mesh.vertex_count())
    }

    #[test]
    fn small_meshes_verify() {
        let tris = [
            [0, 1, 2],
            [0, 2, 3],
            [0, 3, 4],
            [0, 4, 5],
            [7, 8, 9],
            [1, 1, 2],
        ];
        for o in [
            CacheOptions::cache(16),
            CacheOptions::balanced(16),
            CacheOptions::cache(3),
        ] {
            assert!(verify(&tris, &stripify(&tris, 10, &o)).ok());
        }
        assert!(verify(&[], &stripify(&[], 0, &CacheOptions::cache(16))).ok());
    }

    use crate::test_support::random_diagonals;

    #[test]
    fn flips_reroute_strips_to_fewer_indices() {
        // The refinement with and without flips, from the same strips and budget: the
        // flips (cycles through swaps, Posa rotations) take indices off where only
        // rerouting the inside of strips can, every output verified, the misses within
        // the budget, and the index count the search keeps that of the joined output.
        let (tris, vc) = random_diagonals(40, 30, 7);
        let graph = DualGraph::from_triangles(&tris, vc);
        let links = prepare(&tris, vc).1;
        let mut s = State::new(&tris, &links, None, vc, &CacheOptions::balanced(16));
        s.keep_walks();
        s.run();
        let budget = ((0.8 * tris.len() as f64) as u64).max(u64::from(s.fifo.pushes()));
        let mut counts = Vec::new();
        for flip_links in [0, 3] {
            let effort = Effort {
                passes: 3,
                flip_links,
            };
            let (strips, misses) = refine(&tris, &graph, &s.walks, 16, REFINE_LAMBDA, budget, effort);
            assert!(verify(&tris, &strips).ok(), "{flip_links}");
            assert!(misses <= budget, "{flip_links}: {misses} > {budget}");
            let measured = cache_misses(&decode(&strips), vc, 16, CacheKind::Fifo);
            assert_eq!(misses as usize, measured, "{flip_links}");
            counts.push(strips.restart_len());
        }
        eprintln!("flips: {counts:?} for {} triangles", tris.len());
        assert!(counts[1] < counts[0], "with flips {} against {}", counts[1], counts[0]);
    }

    #[test]
    fn the_simulated_fifo_is_the_measured_one() {
        // Every decision sees the FIFO the figures measure: after the run, the
        // simulated push count equals the misses of the decoded output.
        let (tris, vc) = grid(23, 17);
        for o in [
            CacheOptions::cache(16),
            CacheOptions::balanced(16),
            CacheOptions::cache(5),
        ] {
            let links = prepare(&tris, vc).1;
            let mut s = State::new(&tris, &links, None, vc, &o);
            s.run();
            let decoded = decode(&s.out);
            let measured = cache_misses(&decoded, vc, o.cache_size as usize, CacheKind::Fifo);
            assert_eq!(s.fifo.pushes() as usize, measured, "{o:?}");
            assert!(verify(&tris, &s.out).ok());
        }
    }
}

//! The independent check of a model: level by level against a replay of the
//! collapses on the triangles, exact (multisets of oriented triangles).

use super::sets::Sets;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::simplify::{CollapseSequence, Placement};
use crate::strip::{canonical, for_each_triangle, verify_triangles};
use std::collections::HashMap;
use std::time::Instant;

/// What [`check_levels`] compared.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct LevelCheck {
    /// Levels whose strips were compared with the replay (every `stride`-th, plus the
    /// coarsest).
    pub levels_checked: usize,
    /// Of those, levels also compared with [`CollapseSequence::replay`] run from
    /// scratch.
    pub replays: usize,
    /// Largest number of strips a checked level change re-walked.
    pub max_changed_strips: usize,
    /// Milliseconds taken.
    pub ms: f64,
}

/// Checks `sets` against `sequence` applied to `mesh` (the triangle mesh it was
/// simplified from, [`crate::lod::Built::mesh`]): at every `stride`-th level (1 for
/// all) and the coarsest, the strips a [`crate::lod::Cursor`] recovers, moving up
/// from level 0, decode to exactly the non-degenerate triangles of the replay at that
/// level, each with its winding (as multisets, so a triangle drawn twice or missing is
/// caught). The replay is this function's own, one collapse at a time; at `replays`
/// levels spread over the range it is also compared with
/// [`CollapseSequence::replay`] from scratch, vertex positions included.
///
/// O(levels x valence + checked levels x the strips they change). The first
/// difference is [`Error::Verification`], naming the level and a triangle.
pub fn check_levels(
    sets: &Sets,
    mesh: &Mesh,
    sequence: &CollapseSequence,
    stride: usize,
    replays: usize,
) -> Result<LevelCheck> {
    let start = Instant::now();
    let tris = mesh.triangulate().tris;
    let n = mesh.positions.len();
    if sequence.len() != sets.levels() as usize || n != sets.input_vertices as usize {
        return Err(Error::Invalid(format!(
            "the model has {} levels over {} vertices, the sequence {} collapses over {n}",
            sets.levels(),
            sets.input_vertices,
            sequence.len()
        )));
    }
    let levels = sets.levels() as usize;
    let stride = stride.max(1);
    let replay_every = levels.checked_div(replays).map_or(usize::MAX, |e| e.max(1));
    // The replay: triangles under the model's vertex names.
    let mut name: Vec<u32> = (0..n as u32).collect();
    let mut cur: Vec<[u32; 3]> = tris.clone();
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut diff = Diff::default();
    let alive = |t: &[u32; 3]| t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
    for (i, t) in tris.iter().enumerate() {
        if alive(t) {
            diff.bump(*t, -1);
            for &v in t {
                adj[v as usize].push(i as u32);
            }
        }
    }
    let mut cursor = sets.cursor(0);
    let mut strip_tris: Vec<Vec<[u32; 3]>> = (0..sets.strip_count())
        .map(|s| {
            let mut v = Vec::new();
            for_each_triangle(cursor.strip(s), |t| v.push(t));
            v
        })
        .collect();
    for ts in &strip_tris {
        for &t in ts {
            diff.bump(t, 1);
        }
    }
    let mut report = LevelCheck::default();
    let mut level = 0usize;
    loop {
        if level % stride == 0 || level == levels {
            let changed = cursor.set_level(level as u32).to_vec();
            report.max_changed_strips = report.max_changed_strips.max(changed.len());
            for &s in &changed {
                for t in std::mem::take(&mut strip_tris[s as usize]) {
                    diff.bump(t, -1);
                }
                let mut v = Vec::new();
                for_each_triangle(cursor.strip(s as usize), |t| v.push(t));
                for &t in &v {
                    diff.bump(t, 1);
                }
                strip_tris[s as usize] = v;
            }
            report.levels_checked += 1;
            if diff.nonzero != 0 {
                let (t, d) = diff.map.iter().find(|(_, &d)| d != 0).map(|(t, d)| (*t, *d)).unwrap_or(([0; 3], 0));
                return Err(Error::Verification(format!(
                    "level {level}: the strips draw triangle {t:?} {} time(s) {} than the replay",
                    d.abs(),
                    if d > 0 { "more" } else { "fewer" }
                )));
            }
            if level % replay_every == 0 || level == levels {
                compare_with_replay(sets, mesh, sequence, level, &name, &cursor.strips())?;
                report.replays += 1;
            }
        }
        if level == levels {
            break;
        }
        // Collapse `level`: the replay's renames under the model's names.
        let c = sequence.collapses[level];
        let (r, k) = (c.removed as usize, c.kept as usize);
        let target = match sets.placement {
            Placement::Endpoint => name[k],
            Placement::Optimal => (n + level) as u32,
        };
        let (old_r, old_k) = (name[r], name[k]);
        name[k] = target;
        let moved = std::mem::take(&mut adj[r]);
        // Endpoint: r's triangles change; optimal: k's too (renamed to the new vertex).
        let both;
        let touched: &[u32] = if sets.placement == Placement::Optimal {
            let mut all = [moved.as_slice(), adj[k].as_slice()].concat();
            all.sort_unstable();
            all.dedup();
            both = all;
            &both
        } else {
            &moved
        };
        for &t in touched {
            let before = cur[t as usize];
            if !alive(&before) {
                continue;
            }
            let after = before.map(|v| if v == old_r || v == old_k { target } else { v });
            if after == before {
                continue;
            }
            diff.bump(before, 1);
            cur[t as usize] = after;
            if alive(&after) {
                diff.bump(after, -1);
            }
        }
        adj[k].extend(moved.into_iter().filter(|&t| alive(&cur[t as usize])));
        if adj[k].len() > 64 {
            let keep: Vec<u32> = adj[k].iter().copied().filter(|&t| alive(&cur[t as usize])).collect();
            adj[k] = keep;
        }
        level += 1;
    }
    report.ms = start.elapsed().as_secs_f64() * 1e3;
    Ok(report)
}

/// Compares the strips at `level` with [`CollapseSequence::replay`] from scratch,
/// renamed by `name` (the model's name of each replay vertex at that level).
fn compare_with_replay(
    sets: &Sets,
    mesh: &Mesh,
    sequence: &CollapseSequence,
    level: usize,
    name: &[u32],
    strips: &crate::strip::StripSet,
) -> Result<()> {
    let replay = sequence.replay(mesh, level)?;
    let expected: Vec<[u32; 3]> = replay.triangles.iter().map(|t| t.map(|v| name[v as usize])).collect();
    let v = verify_triangles(&expected, &crate::strip::decode(strips));
    if !v.ok() {
        return Err(Error::Verification(format!(
            "level {level}: against the replay the strips lose {}, add {} and flip {} triangles",
            v.lost, v.added, v.flipped
        )));
    }
    // A positionless model (inside a `.lodseq`) takes its frames' positions.
    for t in replay.triangles.iter().filter(|_| !sets.positions.is_empty()) {
        for &v in t {
            if sets.positions[name[v as usize] as usize] != replay.positions[v as usize] {
                return Err(Error::Verification(format!(
                    "level {level}: vertex {v} is at {:?} in the replay but the model's vertex {} is at {:?}",
                    replay.positions[v as usize], name[v as usize], sets.positions[name[v as usize] as usize]
                )));
            }
        }
    }
    Ok(())
}

/// Strips minus replay, as a multiset of canonical oriented triangles.
#[derive(Default)]
struct Diff {
    map: HashMap<[u32; 3], i32>,
    /// Entries that are not zero.
    nonzero: usize,
}

impl Diff {
    fn bump(&mut self, t: [u32; 3], by: i32) {
        let e = self.map.entry(canonical(t)).or_insert(0);
        let was = *e != 0;
        *e += by;
        match (was, *e != 0) {
            (false, true) => self.nonzero += 1,
            (true, false) => self.nonzero -= 1,
            _ => {}
        }
    }
}

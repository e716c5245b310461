//! The independent check of a model: level by level against a replay of the
//! collapses on the triangles, exact (multisets of oriented triangles).

use super::sets::Sets;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use super::cursor::Cursor;
use crate::simplify::{Collapse, CollapseSequence, Placement};
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

/// The stride of a check of `levels` levels: every level (`None`), or about
/// `max_levels` spread over the range (at least every level).
pub(super) fn stride(levels: u32, max_levels: Option<usize>) -> usize {
    max_levels.map_or(1, |m| (levels as usize).checked_div(m).unwrap_or(levels as usize).max(1))
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
    let mut diff = Diff::default();
    let mut replay = Replay::new(tris, n, sets.placement, &mut diff);
    let mut drawn = Drawn::new(sets, &mut diff);
    let mut report = LevelCheck::default();
    let mut level = 0usize;
    loop {
        if level % stride == 0 || level == levels {
            let changed = drawn.move_to(level as u32, &mut diff);
            report.max_changed_strips = report.max_changed_strips.max(changed);
            report.levels_checked += 1;
            diff.check(level)?;
            if level % replay_every == 0 || level == levels {
                compare_with_replay(sets, mesh, sequence, level, &replay.name, &drawn.cursor.strips())?;
                report.replays += 1;
            }
        }
        if level == levels {
            break;
        }
        replay.collapse(level, sequence.collapses[level], &mut diff);
        level += 1;
    }
    report.ms = start.elapsed().as_secs_f64() * 1e3;
    Ok(report)
}

fn alive(t: &[u32; 3]) -> bool {
    t[0] != t[1] && t[1] != t[2] && t[0] != t[2]
}

/// The check's own replay of the collapses: the triangles under the model's vertex
/// names, counted out of a [`Diff`] as they change.
struct Replay {
    placement: Placement,
    /// The model's name of each input vertex at the current level.
    name: Vec<u32>,
    /// Every input triangle at the current level.
    cur: Vec<[u32; 3]>,
    /// Triangles around each vertex (some of them dead, pruned now and then).
    adj: Vec<Vec<u32>>,
}

impl Replay {
    /// Level 0 over `n` vertices: `tris` as they are, each live one counted out of
    /// `diff`.
    fn new(tris: Vec<[u32; 3]>, n: usize, placement: Placement, diff: &mut Diff) -> Replay {
        let mut adj: Vec<Vec<u32>> = vec![Vec::new(); n];
        for (i, t) in tris.iter().enumerate() {
            if alive(t) {
                diff.bump(*t, -1);
                for &v in t {
                    adj[v as usize].push(i as u32);
                }
            }
        }
        Replay { placement, name: (0..n as u32).collect(), cur: tris, adj }
    }

    /// Applies collapse `level` (`c`): the replay's renames under the model's names,
    /// each changed triangle moved in `diff`.
    fn collapse(&mut self, level: usize, c: Collapse, diff: &mut Diff) {
        let n = self.name.len();
        let (r, k) = (c.removed as usize, c.kept as usize);
        let target = match self.placement {
            Placement::Endpoint => self.name[k],
            Placement::Optimal => (n + level) as u32,
        };
        let (old_r, old_k) = (self.name[r], self.name[k]);
        self.name[k] = target;
        let moved = std::mem::take(&mut self.adj[r]);
        // Endpoint: r's triangles change; optimal: k's too (renamed to the new vertex).
        let both;
        let touched: &[u32] = if self.placement == Placement::Optimal {
            let mut all = [moved.as_slice(), self.adj[k].as_slice()].concat();
            all.sort_unstable();
            all.dedup();
            both = all;
            &both
        } else {
            &moved
        };
        for &t in touched {
            let before = self.cur[t as usize];
            if !alive(&before) {
                continue;
            }
            let after = before.map(|v| if v == old_r || v == old_k { target } else { v });
            if after == before {
                continue;
            }
            diff.bump(before, 1);
            self.cur[t as usize] = after;
            if alive(&after) {
                diff.bump(after, -1);
            }
        }
        let cur = &self.cur;
        self.adj[k].extend(moved.into_iter().filter(|&t| alive(&cur[t as usize])));
        if self.adj[k].len() > 64 {
            let keep: Vec<u32> = self.adj[k].iter().copied().filter(|&t| alive(&cur[t as usize])).collect();
            self.adj[k] = keep;
        }
    }
}

/// The triangles the model's strips draw, per strip, at a [`Cursor`]'s level,
/// counted into a [`Diff`].
struct Drawn<'a> {
    cursor: Cursor<'a>,
    strip_tris: Vec<Vec<[u32; 3]>>,
}

impl<'a> Drawn<'a> {
    /// Level 0, every strip's triangles counted into `diff`.
    fn new(sets: &'a Sets, diff: &mut Diff) -> Drawn<'a> {
        let cursor = sets.cursor(0);
        let strip_tris: Vec<Vec<[u32; 3]>> = (0..sets.strip_count())
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
        Drawn { cursor, strip_tris }
    }

    /// Moves to `level`, re-counting the strips that changed; returns how many did.
    fn move_to(&mut self, level: u32, diff: &mut Diff) -> usize {
        let changed = self.cursor.set_level(level).to_vec();
        for &s in &changed {
            for t in std::mem::take(&mut self.strip_tris[s as usize]) {
                diff.bump(t, -1);
            }
            let mut v = Vec::new();
            for_each_triangle(self.cursor.strip(s as usize), |t| v.push(t));
            for &t in &v {
                diff.bump(t, 1);
            }
            self.strip_tris[s as usize] = v;
        }
        changed.len()
    }
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
    /// Fails at `level` unless the strips and the replay hold the same triangles.
    fn check(&self, level: usize) -> Result<()> {
        if self.nonzero == 0 {
            return Ok(());
        }
        let (t, d) = self.map.iter().find(|(_, &d)| d != 0).map(|(t, d)| (*t, *d)).unwrap_or(([0; 3], 0));
        Err(Error::Verification(format!(
            "level {level}: the strips draw triangle {t:?} {} time(s) {} than the replay",
            d.abs(),
            if d > 0 { "more" } else { "fewer" }
        )))
    }

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

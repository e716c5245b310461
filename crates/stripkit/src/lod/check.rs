//! The independent check of a model: level by level against a replay of the
//! collapses on the triangles, exact (multisets of oriented triangles).

use crate::parallel::Threads;
use super::sets::Sets;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use super::cursor::Cursor;
use super::track::Tracker;
use crate::simplify::{Collapse, CollapseSequence, Placement};
use crate::strip::{canonical, verify_triangles};
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
/// all) and the coarsest, the strips of the model, followed up from level 0 one
/// level at a time (re-walking only what each level changes), decode to exactly the
/// non-degenerate triangles of the replay at that level, each with its winding (as multisets, so a triangle drawn twice or missing is
/// caught). The replay is this function's own, one collapse at a time; at `replays`
/// levels spread over the range it is also compared with
/// [`CollapseSequence::replay`] from scratch, vertex positions included, through the
/// strips a [`crate::lod::Cursor`] recovers there.
///
/// O(levels x valence + the strip stretches the levels change + replays x the
/// model's size); a long strip that every level changes (a flat ribbon) is not
/// re-walked whole at every level. The first difference is
/// [`Error::Verification`], naming the level and a triangle.
pub fn check_levels(
    sets: &Sets,
    mesh: &Mesh,
    sequence: &CollapseSequence,
    stride: usize,
    replays: usize,
) -> Result<LevelCheck> {
    check_levels_with(sets, mesh, sequence, stride, replays, Threads::SERIAL)
}

/// [`check_levels`] with the replays from scratch run `threads` at a time (the walk
/// itself is one pass). The same checks, and the same first difference, at any count.
pub fn check_levels_with(
    sets: &Sets,
    mesh: &Mesh,
    sequence: &CollapseSequence,
    stride: usize,
    replays: usize,
    threads: Threads,
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
    // Replays waiting to be compared, in level order: (level, names, cursor strips).
    // They are compared a batch at a time, and before any later difference is
    // reported, so the first difference in level order is the error.
    let batch = if threads.is_serial() { 1 } else { 2 * threads.count() };
    let mut pending: Vec<(usize, Vec<u32>, crate::strip::StripSet)> = Vec::new();
    let flush = |pending: &mut Vec<(usize, Vec<u32>, crate::strip::StripSet)>| -> Result<()> {
        let results = crate::parallel::map_ordered(threads, pending, |(level, name, strips)| {
            compare_with_replay(sets, mesh, sequence, *level, name, strips)
        });
        pending.clear();
        results.into_iter().collect()
    };
    loop {
        if level % stride == 0 || level == levels {
            let changed = drawn.move_to(level as u32, &mut diff);
            report.max_changed_strips = report.max_changed_strips.max(changed);
            report.levels_checked += 1;
            if let Err(e) = diff.check(level) {
                flush(&mut pending)?;
                return Err(e);
            }
            if level % replay_every == 0 || level == levels {
                // The extraction's own walk, a cursor, at these levels.
                drawn.cursor.set_level(level as u32);
                pending.push((level, replay.name.clone(), drawn.cursor.strips()));
                report.replays += 1;
                if pending.len() >= batch {
                    flush(&mut pending)?;
                }
            }
        }
        if level == levels {
            flush(&mut pending)?;
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

/// The triangles the model's strips draw at a [`Tracker`]'s level, counted into a
/// [`Diff`]: each level re-walks only the stretches of strips it changes.
struct Drawn<'a> {
    tracker: Tracker<'a>,
    /// Moved only to the levels compared with a replay from scratch.
    cursor: Cursor<'a>,
    changed: Vec<u32>,
    stamp: Vec<u32>,
}

impl<'a> Drawn<'a> {
    /// Level 0, every strip's triangles counted into `diff`.
    fn new(sets: &'a Sets, diff: &mut Diff) -> Drawn<'a> {
        let tracker = Tracker::new(sets, true, |_, t, by| diff.bump(t, by));
        Drawn { tracker, cursor: sets.cursor(0), changed: Vec::new(), stamp: vec![u32::MAX; sets.strip_count()] }
    }

    /// Moves up to `level`, one level at a time; returns how many strips changed.
    fn move_to(&mut self, level: u32, diff: &mut Diff) -> usize {
        self.changed.clear();
        while self.tracker.level() < level {
            let changed = self.tracker.step(|_, t, by| diff.bump(t, by));
            for &s in changed {
                if self.stamp[s as usize] != level {
                    self.stamp[s as usize] = level;
                    self.changed.push(s);
                }
            }
        }
        self.changed.len()
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
    // Every attribute, byte for byte, where the model has them.
    for (a, b) in sets.attributes.iter().zip(&replay.attributes) {
        for &v in replay.triangles.iter().flatten() {
            if a.bytes(name[v as usize] as usize) != b.bytes(v as usize) {
                return Err(Error::Verification(format!(
                    "level {level}: vertex {v}'s {} is {:?} in the replay but the model's vertex {} has {:?}",
                    a.name,
                    b.value(v as usize),
                    name[v as usize],
                    a.value(name[v as usize] as usize)
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

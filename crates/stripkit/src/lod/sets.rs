//! The SETS model and its builder.
//!
//! Every index of the input strips is a *slot*. A level's strip is a subsequence of
//! its level-0 slots (collapses only rename and remove, never insert), each slot
//! carrying the vertex it names at that level. Per slot the model keeps its
//! *versions*: `(level, label, next slot)`, sorted by level, one more each time the
//! slot's vertex or its successor changes; per strip its *beginnings*: `(level, first
//! slot)`. The paper's graph keeps one node per vertex of a strip with the successors
//! of all its occurrences in one arc (and a `shift` to tell the occurrences apart
//! during a walk); a node per occurrence visits each node once per walk, so the shift
//! is always 0 and the successor is a single slot.
//!
//! When a collapse renames vertex `a` to `b`, every slot naming `a` names `b`, and the
//! strips around the renamed slots are shortened by removals that keep every
//! remaining triangle and its winding (the paper's two conditions, made exact):
//! * inside a strip or at its front, an even run of slots whose removal leaves the
//!   multiset of non-degenerate oriented triangles unchanged (an even count keeps
//!   the parity, hence the winding, of every later triangle);
//! * at its end, any run whose triangles are all degenerate;
//! * a strip with no non-degenerate triangle left is emptied.
//!
//! One file of about 1,150 lines on purpose: the model, its builder and the removal
//! rules share the slot and version layout, and the builder's steps (rename, shorten,
//! re-strip past a threshold) and the lists derived on load (change lists, the walks
//! `snap.rs` makes its re-strip tables of) read best beside the invariants above.

use crate::error::{Error, Result};
use crate::mesh::Attribute;
use crate::simplify::{CollapseSequence, Placement};
use crate::strip::{canonical, StripSet};
use super::snap::Snapshots;

/// "No slot": the end of a strip (a version's successor) or an empty strip (a
/// beginning).
pub const END: u32 = u32::MAX;

/// A change entry that starts no version of its slot (a strip's new beginning).
pub(crate) const NO_VERSION: u32 = u32::MAX;
/// A change entry whose slot starts several versions at its level.
pub(crate) const AMBIGUOUS_VERSION: u32 = u32::MAX - 1;

/// Slots gathered on each side of a renamed slot when looking for removals.
const REACH: usize = 8;
/// How much worse than when they were made (indices per triangle) the strips must
/// get before [`Sets::build_restripping`] makes new ones: a mesh too small for any
/// strips under the threshold is not re-stripped at every level.
pub const RESTRIP_MARGIN: f64 = 0.15;

/// The most slots a window holds.
const WINDOW: usize = 2 * REACH + 1;

/// One version of a slot: from `level` on (until the next version), the slot names
/// vertex `label` and is followed by slot `next` (a later slot of the same strip, or
/// [`END`]). One record, so that a walk reads one cache line per slot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Version {
    pub(crate) level: u32,
    pub(crate) label: u32,
    pub(crate) next: u32,
}

/// One entry of a strip's derived change list: at `level`, slot `slot` changes.
/// A walk that moves across the level re-reads these slots; any other slot has the
/// same vertex and successor on both sides, so the old walk's runs of them are
/// reused.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Change {
    pub(crate) level: u32,
    /// The slot whose version changes there (the strip's first slot for a new
    /// beginning).
    pub(crate) slot: u32,
    /// The index in `versions` of the slot's version that starts there
    /// ([`NO_VERSION`] for a beginning alone, [`AMBIGUOUS_VERSION`] when several
    /// start at one level), so that a move reads a changed slot's version with one
    /// load.
    pub(crate) version: u32,
    /// How many slots of the strip's walk at `level - 1` come before `slot`: where
    /// the slot stands in a cursor's range at any level from which a move crosses
    /// this change with no change of a lower slot (the first changed slot of a move),
    /// so that the move finds it without a search (0 for the level-0 entry).
    pub(crate) rank: u32,
}

/// Which level to recover: [`Sets::level_of`], [`crate::lod::SeqCursor::set`],
/// [`crate::lod::Model::extract`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LevelSpec {
    /// Collapses of the frame's sequence applied (past the coarsest: the coarsest).
    Level(u32),
    /// The first level with at most this many triangles.
    Triangles(u64),
    /// The first level with at most `ceil(ratio x triangles)` triangles.
    Ratio(f64),
}

/// A multiresolution strip model: the strips of every level of a collapse sequence.
///
/// Build one with [`Sets::build`] (or [`crate::lod::build`] from a mesh), recover
/// levels with [`Sets::cursor`], store it with [`Sets::to_bytes`].
#[derive(Clone, Debug, PartialEq)]
pub struct Sets {
    pub(crate) placement: Placement,
    /// Vertices of the input mesh; with [`Placement::Optimal`] collapse `i` adds
    /// vertex `input_vertices + i`.
    pub(crate) input_vertices: u32,
    /// Positions of every vertex any level names.
    pub(crate) positions: Vec<[f32; 3]>,
    /// Vertex attributes (UVs, normals, ...) of every vertex any level names, or of
    /// the input vertices for a positionless model; empty when the mesh has none.
    pub(crate) attributes: Vec<Attribute>,
    /// Per collapse: the vertex its renamed slots name afterwards.
    pub(crate) targets: Vec<u32>,
    /// Per collapse: the triangles it removed.
    pub(crate) removed_triangles: Vec<u32>,
    /// Non-degenerate triangles at level 0.
    pub(crate) triangles0: u32,
    /// `strip_slots[s]..strip_slots[s + 1]` are strip `s`'s slots.
    pub(crate) strip_slots: Vec<u32>,
    /// `begin_*[begin_offsets[s]..begin_offsets[s + 1]]`: strip `s`'s beginnings,
    /// levels ascending, the first at level 0.
    pub(crate) begin_offsets: Vec<u32>,
    pub(crate) begin_level: Vec<u32>,
    pub(crate) begin_slot: Vec<u32>,
    /// `versions[version_offsets[x]..version_offsets[x + 1]]`: slot `x`'s versions,
    /// levels ascending, the first at level 0.
    pub(crate) version_offsets: Vec<u32>,
    pub(crate) versions: Vec<Version>,
    /// `change_level[change_offsets[s]..change_offsets[s + 1]]`: the levels where
    /// strip `s`'s sequence changes, ascending (once per slot that changes there),
    /// starting with 0 (derived, not stored).
    pub(crate) change_offsets: Vec<u32>,
    pub(crate) change_level: Vec<u32>,
    /// Parallel to `change_level`: each change as one record ([`Change`]), so that a
    /// move reads a strip's crossed changes from one run of cache lines (derived;
    /// the level is repeated there, `change_level` stays for the searches).
    pub(crate) changes: Vec<Change>,
    /// `level_strips[level_offsets[l]..level_offsets[l + 1]]`: the strips whose
    /// sequence changes at level `l` (derived), so that a move between near levels
    /// finds them without looking at every strip.
    pub(crate) level_offsets: Vec<u32>,
    pub(crate) level_strips: Vec<u32>,
    /// The cursor's state at the re-strip levels, per generation of strips (derived).
    pub(crate) snapshots: Snapshots,
    /// Triangles at each level (derived, not stored).
    pub(crate) triangles_at: Vec<u32>,
}

impl Sets {
    /// Builds the model of `strips` (over `positions`) under `sequence`, whose
    /// collapses are applied in order. With [`Placement::Endpoint`] a collapse renames
    /// its removed vertex to its kept one (the kept vertex keeps its position: use a
    /// sequence simplified with endpoint placement). With [`Placement::Optimal`]
    /// collapse `i` renames both to a new vertex `positions.len() + i` at the
    /// collapse's position, progressive-mesh style, so that every level draws its own
    /// geometry.
    ///
    /// The strips are any stripifier's output over the triangles the sequence was
    /// computed on. O(total strip length + collapses x the slots they rename).
    /// [`Error::Invalid`] when the sequence does not fit the strips (vertex counts,
    /// a vertex collapsed twice) or a strip names a vertex past `positions`.
    pub fn build(
        positions: &[[f32; 3]],
        strips: &StripSet,
        sequence: &CollapseSequence,
        placement: Placement,
    ) -> Result<Sets> {
        Sets::build_with_attributes(positions, &[], strips, sequence, placement)
    }

    /// [`Sets::build`] for a mesh with vertex attributes (`attributes`, one value per
    /// vertex of `positions` each, as [`crate::Mesh::attributes`]): every level's
    /// vertices keep them. With [`Placement::Endpoint`] a level names input vertices
    /// only, with their own values; with [`Placement::Optimal`] the new vertex of each
    /// collapse takes the values the simplifier gave its survivor (blended along the
    /// collapsed edge, see [`crate::simplify`]), so that every level draws exactly
    /// the attributes of [`CollapseSequence::replay`]. The sequence should come from
    /// the simplifier run on the mesh with these attributes (it keeps seam vertices
    /// in place, so that seams stay seams at every level). [`Error::Invalid`] also
    /// when an attribute does not hold one value per vertex.
    pub fn build_with_attributes(
        positions: &[[f32; 3]],
        attributes: &[Attribute],
        strips: &StripSet,
        sequence: &CollapseSequence,
        placement: Placement,
    ) -> Result<Sets> {
        Sets::build_restripping(positions, attributes, strips, sequence, placement, None)
    }

    /// [`Sets::build_with_attributes`] that re-strips as the strips decay: after a
    /// level whose strips take more than `threshold` indices per triangle (restart
    /// buffer, [`crate::strip::StripSet::restart_len`]), and at least
    /// [`RESTRIP_MARGIN`] more than the strips had when they were made, the level's
    /// triangles are stripified again (greedy) into new strips, empty before that
    /// level, and every strip drawn until then ends (its beginning becomes [`END`]).
    /// Every level still draws exactly the replay's triangles; the new strips are
    /// new slots of the same model, so a cursor, the file and the checks treat them
    /// as any strip. `None` never re-strips ([`Sets::build_with_attributes`]).
    pub fn build_restripping(
        positions: &[[f32; 3]],
        attributes: &[Attribute],
        strips: &StripSet,
        sequence: &CollapseSequence,
        placement: Placement,
        threshold: Option<f64>,
    ) -> Result<Sets> {
        let n = positions.len();
        if let Some(a) = attributes.iter().find(|a| a.stride() == 0 || a.data.len() != n * a.stride()) {
            let what = format!("attribute {} does not hold one value for each of the {n} vertices", a.name);
            return Err(Error::Invalid(what));
        }
        let mut all_attributes = attributes.to_vec();
        if sequence.vertex_count as usize != n {
            return Err(Error::Invalid(format!(
                "the collapse sequence is for {} vertices, the strips' mesh has {n}",
                sequence.vertex_count
            )));
        }
        if let Some(&v) = strips.indices.iter().find(|&&v| v as usize >= n) {
            return Err(Error::Invalid(format!("a strip names vertex {v}, past the mesh's {n} vertices")));
        }
        let levels = sequence.len();
        let total = n + if placement == Placement::Optimal { levels } else { 0 };
        if total >= END as usize || strips.indices.len() >= END as usize {
            return Err(Error::Invalid("more than 2^32 - 2 vertices or strip indices".into()));
        }
        let mut b = Builder::new(strips, total);
        let mut live_triangles = strips.iter().map(count_triangles).sum::<usize>();
        b.restrip_threshold = threshold;
        b.fresh_ratio = b.ratio(live_triangles);
        let mut all_positions = positions.to_vec();
        // `name[v]`: what the sequence's vertex `v` is called now (itself, or with
        // optimal placement the new vertex of the last collapse that kept it).
        let mut name: Vec<u32> = (0..n as u32).collect();
        let mut gone = vec![false; n];
        let mut targets = Vec::with_capacity(levels);
        let mut removed_triangles = Vec::with_capacity(levels);
        for (i, c) in sequence.collapses.iter().enumerate() {
            let (r, k) = (c.removed as usize, c.kept as usize);
            if r >= n || k >= n || r == k || gone[r] || gone[k] {
                return Err(Error::Invalid(format!(
                    "collapse {i} merges vertex {r} into {k}, which is not possible at that point"
                )));
            }
            gone[r] = true;
            let level = i as u32 + 1;
            b.start();
            let target = match placement {
                Placement::Endpoint => {
                    b.rename(name[r], name[k]);
                    name[k]
                }
                Placement::Optimal => {
                    let new = (n + i) as u32;
                    let wide = |v: u32| all_positions[v as usize].map(|x: f32| x as f64);
                    let ends = [wide(name[k]), wide(name[r])];
                    let p = c.position.map(|x| x as f64);
                    for a in &mut all_attributes {
                        crate::simplify::attributes::push_carried(a, name[r], name[k], ends, p);
                    }
                    all_positions.push(c.position);
                    b.rename(name[r], new);
                    b.rename(name[k], new);
                    name[k] = new;
                    new
                }
            };
            live_triangles = live_triangles.saturating_sub(sequence.removed_by(i).len());
            b.settle(level, live_triangles);
            targets.push(target);
            removed_triangles.push(sequence.removed_by(i).len() as u32);
        }
        let triangles0 = b.triangles0;
        let mut sets = b.finish(placement, n as u32, all_positions, targets, removed_triangles, triangles0);
        sets.attributes = all_attributes;
        sets.derive()?;
        Ok(sets)
    }

    /// Fills the derived tables (strip change levels, triangles per level) and checks
    /// that the triangle counts never go below zero.
    pub(crate) fn derive(&mut self) -> Result<()> {
        let strips = self.strip_count();
        // (level, slot) of every change of a strip: its beginnings (from its first
        // slot) and its slots' versions.
        let mut events: Vec<(u32, u32, u32)> = Vec::new();
        self.change_offsets = Vec::with_capacity(strips + 1);
        self.change_offsets.push(0);
        self.change_level.clear();
        self.changes.clear();
        let mut walk: Vec<u32> = Vec::new();
        let mut at: Vec<u32> = Vec::new();
        for s in 0..strips {
            events.clear();
            let first = self.strip_slots[s];
            events.extend(
                self.begin_level[self.begin_offsets[s] as usize..self.begin_offsets[s + 1] as usize]
                    .iter()
                    .map(|&l| (l, first, NO_VERSION)),
            );
            let slots = self.strip_slots[s] as usize..self.strip_slots[s + 1] as usize;
            for x in slots {
                let r = self.version_offsets[x] as usize..self.version_offsets[x + 1] as usize;
                events.extend(r.map(|i| (self.versions[i].level, x as u32, i as u32)));
            }
            events.sort_unstable();
            // One entry per (level, slot): the version that starts there, when one
            // and only one does.
            let mut n = 0;
            for i in 0..events.len() {
                let (l, x, v) = events[i];
                if n > 0 && (events[n - 1].0, events[n - 1].1) == (l, x) {
                    if v != NO_VERSION {
                        events[n - 1].2 = if events[n - 1].2 == NO_VERSION { v } else { AMBIGUOUS_VERSION };
                    }
                } else {
                    events[n] = (l, x, v);
                    n += 1;
                }
            }
            events.truncate(n);
            // Level 0 once (every slot has a version there), then every change.
            let at_zero = events.partition_point(|e| e.0 == 0);
            let events = &events[at_zero.saturating_sub(1)..];
            for &(l, x, v) in events {
                self.change_level.push(l);
                self.changes.push(Change { level: l, slot: x, version: v, rank: 0 });
            }
            let here = self.changes.len() - events.len();
            let mut changes = std::mem::take(&mut self.changes);
            self.rank_changes(s, &mut changes[here..], &mut walk, &mut at);
            self.changes = changes;
            self.change_offsets.push(self.change_level.len() as u32);
        }
        // The strips changing at each level past 0, by a counting sort.
        let levels = self.targets.len();
        let mut offsets = vec![0u32; levels + 2];
        for s in 0..strips {
            let mut last = 0;
            for &l in &self.change_level[self.change_offsets[s] as usize..self.change_offsets[s + 1] as usize] {
                if l > last && (l as usize) <= levels {
                    offsets[l as usize + 1] += 1;
                    last = l;
                }
            }
        }
        for l in 0..=levels {
            offsets[l + 1] += offsets[l];
        }
        let mut fill = offsets.clone();
        self.level_strips = vec![0; offsets[levels + 1] as usize];
        for s in 0..strips {
            let mut last = 0;
            for &l in &self.change_level[self.change_offsets[s] as usize..self.change_offsets[s + 1] as usize] {
                if l > last && (l as usize) <= levels {
                    self.level_strips[fill[l as usize] as usize] = s as u32;
                    fill[l as usize] += 1;
                    last = l;
                }
            }
        }
        self.level_offsets = offsets;
        self.triangles_at = Vec::with_capacity(self.targets.len() + 1);
        let mut t = self.triangles0;
        self.triangles_at.push(t);
        for (i, &r) in self.removed_triangles.iter().enumerate() {
            t = t
                .checked_sub(r)
                .ok_or_else(|| Error::Invalid(format!("collapse {i} removes {r} triangles, more than the {t} left")))?;
            self.triangles_at.push(t);
        }
        let model = super::snap::Model {
            strip_slots: &self.strip_slots,
            begin_offsets: &self.begin_offsets,
            begin_level: &self.begin_level,
            begin_slot: &self.begin_slot,
            change_offsets: &self.change_offsets,
            change_level: &self.change_level,
        };
        // A walk that leaves the strip's slots or visits more of them than it has
        // (a damaged model, refused by the later checks) leaves the tables out.
        let snapshots = Snapshots::derive(model, |s, level, labels, slots| {
            labels.clear();
            slots.clear();
            let (first, end) = (self.strip_slots[s], self.strip_slots[s + 1]);
            let mut x = self.head_at(s, level);
            while x != END {
                if x < first || x >= end || slots.len() >= (end - first) as usize {
                    return false;
                }
                let v = self.version_at(x, level);
                labels.push(v.label);
                slots.push(x);
                x = v.next;
            }
            true
        });
        self.snapshots = snapshots;
        Ok(())
    }

    /// Fills the ranks of strip `s`'s change list `list` (levels ascending): the
    /// strip is walked at the level before each level of its changes, from the
    /// lowest slot that changed at the previous one up to the highest slot changing
    /// there, each slot's version read on from where the previous walk left it (the
    /// levels only go up). A walk that leaves the strip's
    /// slots stops there (a damaged model, refused by the later checks).
    fn rank_changes(&self, s: usize, list: &mut [Change], walk: &mut Vec<u32>, at: &mut Vec<u32>) {
        let (first, end) = (self.strip_slots[s] as usize, self.strip_slots[s + 1] as usize);
        at.clear();
        at.extend_from_slice(&self.version_offsets[first..end]);
        walk.clear();
        // The walk at hand holds the slots below `low` at the level before the next
        // level of changes too (nothing below the lowest slot changing at a level
        // moves there): only the rest is walked again.
        let mut low = 0;
        let mut i = 0;
        while i < list.len() {
            let level = list[i].level;
            let mut j = i;
            let (mut top, mut bottom) = (0, END);
            while j < list.len() && list[j].level == level {
                top = top.max(list[j].slot);
                bottom = bottom.min(list[j].slot);
                j += 1;
            }
            if level > 0 {
                let below = level - 1;
                walk.truncate(walk.partition_point(|&y| y < low));
                low = bottom;
                let mut x = match walk.last() {
                    Some(&p) => self.versions[at[p as usize - first] as usize].next,
                    None => self.head_at(s, below),
                };
                while x != END && x < top && (first..end).contains(&(x as usize)) && walk.len() < end - first {
                    let k = x as usize - first;
                    let last = self.version_offsets[x as usize + 1] as usize;
                    if at[k] as usize >= last {
                        break;
                    }
                    while (at[k] as usize) + 1 < last && self.versions[at[k] as usize + 1].level <= below {
                        at[k] += 1;
                    }
                    walk.push(x);
                    x = self.versions[at[k] as usize].next;
                }
                for c in &mut list[i..j] {
                    c.rank = walk.partition_point(|&y| y < c.slot) as u32;
                }
            }
            i = j;
        }
    }

    /// Number of levels beyond level 0 (the collapses): levels are `0..=levels()`,
    /// 0 the finest.
    pub fn levels(&self) -> u32 {
        self.targets.len() as u32
    }

    /// Number of strips (some may be empty at coarse levels).
    pub fn strip_count(&self) -> usize {
        self.strip_slots.len() - 1
    }

    /// Number of slots: the indices of the level-0 strips.
    pub fn slot_count(&self) -> usize {
        self.version_offsets.len() - 1
    }

    /// Number of slot versions (at least one per slot).
    pub fn version_count(&self) -> usize {
        self.versions.len()
    }

    /// Number of strips made after level 0 by re-stripping
    /// ([`Sets::build_restripping`]): strips with slots but no beginning at level 0.
    pub fn restripped_strips(&self) -> usize {
        (0..self.strip_count())
            .filter(|&s| {
                self.begin_slot[self.begin_offsets[s] as usize] == END && self.strip_slots[s] < self.strip_slots[s + 1]
            })
            .count()
    }

    /// Whether any strip was made after level 0 ([`Sets::restripped_strips`]).
    pub(crate) fn has_restrips(&self) -> bool {
        (0..self.strip_count()).any(|s| {
            self.begin_slot[self.begin_offsets[s] as usize] == END && self.strip_slots[s] < self.strip_slots[s + 1]
        })
    }

    /// Number of strip beginnings (at least one per strip).
    pub fn beginning_count(&self) -> usize {
        self.begin_level.len()
    }

    /// Positions of every vertex a level may name (with [`Placement::Optimal`], the
    /// input's followed by one per collapse).
    pub fn positions(&self) -> &[[f32; 3]] {
        &self.positions
    }

    /// Vertex attributes of every vertex a level may name, as [`Sets::positions`]
    /// (for a model inside a `.lodseq`, of the input vertices); empty for a mesh
    /// without attributes.
    pub fn attributes(&self) -> &[Attribute] {
        &self.attributes
    }

    /// The survivor placement the model was built for.
    pub fn placement(&self) -> Placement {
        self.placement
    }

    /// Vertices of the input mesh.
    pub fn input_vertices(&self) -> u32 {
        self.input_vertices
    }

    /// Non-degenerate triangles at `level` (clamped to the coarsest).
    pub fn triangles_at(&self, level: u32) -> u32 {
        self.triangles_at[(level as usize).min(self.triangles_at.len() - 1)]
    }

    /// The first level with at most `triangles` triangles (the coarsest level when
    /// none has so few).
    pub fn level_for_triangles(&self, triangles: u64) -> u32 {
        let l = self.triangles_at.partition_point(|&t| t as u64 > triangles);
        l.min(self.triangles_at.len() - 1) as u32
    }

    /// The first level with at most `ceil(ratio x level-0 triangles)` triangles: where
    /// [`crate::simplify::simplify`] with [`crate::simplify::Target::Ratio`] stops.
    /// `ratio` is clamped to 0..=1.
    pub fn level_for_ratio(&self, ratio: f64) -> u32 {
        let r = if ratio.is_nan() { 1.0 } else { ratio.clamp(0.0, 1.0) };
        self.level_for_triangles(crate::simplify::ratio_target(self.triangles0 as usize, r) as u64)
    }

    /// The level `spec` names (clamped to the coarsest).
    pub fn level_of(&self, spec: LevelSpec) -> u32 {
        match spec {
            LevelSpec::Level(l) => l.min(self.levels()),
            LevelSpec::Triangles(n) => self.level_for_triangles(n),
            LevelSpec::Ratio(r) => self.level_for_ratio(r),
        }
    }

    /// Bytes the model holds in memory (its tables, derived ones included).
    pub fn memory_bytes(&self) -> usize {
        4 * (self.targets.len()
            + self.removed_triangles.len()
            + self.strip_slots.len()
            + self.begin_offsets.len()
            + self.begin_level.len()
            + self.begin_slot.len()
            + self.version_offsets.len()
            + 3 * self.versions.len()
            + self.change_offsets.len()
            + 5 * self.change_level.len()
            + self.level_offsets.len()
            + self.level_strips.len()
            + self.triangles_at.len())
            + self.snapshots.memory_bytes()
            + 12 * self.positions.len()
            + self.attributes.iter().map(|a| a.data.len()).sum::<usize>()
    }

    /// The strips at `level`, walked from scratch (no coherence): a binary search for
    /// each strip's beginning, then one per slot visited. Empty strips are left out.
    pub fn strips_at(&self, level: u32) -> StripSet {
        let mut out = StripSet::new();
        let mut buf = Vec::new();
        for s in 0..self.strip_count() {
            buf.clear();
            self.walk(s, level, |v| buf.push(v));
            if !buf.is_empty() {
                out.push(&buf);
            }
        }
        out
    }

    /// Calls `emit` with the vertices of strip `s` at `level`, in order.
    #[inline]
    pub(crate) fn walk(&self, s: usize, level: u32, mut emit: impl FnMut(u32)) {
        self.walk_slots(self.head_at(s, level), level, |_, v| emit(v));
    }

    /// Strip `s`'s first slot at `level` ([`END`] when empty).
    #[inline]
    pub(crate) fn head_at(&self, s: usize, level: u32) -> u32 {
        let b = self.begin_offsets[s] as usize..self.begin_offsets[s + 1] as usize;
        let k = b.start + self.begin_level[b.clone()].partition_point(|&l| l <= level) - 1;
        self.begin_slot[k]
    }

    /// Slot `x`'s version at `level`.
    #[inline]
    pub(crate) fn version_at(&self, x: u32, level: u32) -> Version {
        let lo = self.version_offsets[x as usize] as usize;
        let hi = self.version_offsets[x as usize + 1] as usize;
        let vs = &self.versions[lo..hi];
        // Most slots have a few versions: the last, then a scan, then a search.
        if vs[vs.len() - 1].level <= level {
            vs[vs.len() - 1]
        } else if vs.len() <= 8 {
            let mut i = 0;
            while vs[i + 1].level <= level {
                i += 1;
            }
            vs[i]
        } else {
            vs[vs.partition_point(|v| v.level <= level) - 1]
        }
    }

    /// Calls `emit(slot, vertex)` for the slots from `x` on at `level`.
    #[inline]
    pub(crate) fn walk_slots(&self, mut x: u32, level: u32, mut emit: impl FnMut(u32, u32)) {
        while x != END {
            let v = self.version_at(x, level);
            emit(x, v.label);
            x = v.next;
        }
    }
}

fn count_triangles(s: &[u32]) -> usize {
    let mut n = 0;
    crate::strip::for_each_triangle(s, |_| n += 1);
    n
}

/// The strips under the collapses so far, as linked lists of live slots.
struct Builder {
    label: Vec<u32>,
    next: Vec<u32>,
    prev: Vec<u32>,
    alive: Vec<bool>,
    strip_of: Vec<u32>,
    head: Vec<u32>,
    /// Occurrence lists per vertex (slots naming it, dead ones dropped lazily).
    occ_head: Vec<u32>,
    occ_tail: Vec<u32>,
    occ_next: Vec<u32>,
    strip_slots: Vec<u32>,
    /// Logs, in level order: (slot, level, label, next) and (strip, level, slot).
    versions: Vec<(u32, u32, u32, u32)>,
    begins: Vec<(u32, u32, u32)>,
    recorded_head: Vec<u32>,
    // Per collapse scratch.
    stamp: u32,
    slot_stamp: Vec<u32>,
    strip_stamp: Vec<u32>,
    dirty: Vec<u32>,
    touched: Vec<u32>,
    changed: Vec<u32>,
    window: Vec<u32>,
    window_labels: Vec<u32>,
    /// Slots of the live strips and the non-empty strips (the restart buffer's
    /// length is their sum minus one).
    live_slots: usize,
    live_strips: usize,
    /// Non-degenerate triangles of the level-0 strips.
    triangles0: u32,
    /// See [`Sets::build_restripping`].
    restrip_threshold: Option<f64>,
    /// Indices per triangle of the strips when they were last made.
    fresh_ratio: f64,
    /// Strips made after level 0 (for the file: their level-0 beginning is [`END`]).
    restrips: usize,
}

impl Builder {
    fn new(strips: &StripSet, vertices: usize) -> Builder {
        let slots = strips.indices.len();
        let mut b = Builder {
            label: strips.indices.clone(),
            next: vec![END; slots],
            prev: vec![END; slots],
            alive: vec![true; slots],
            strip_of: vec![0; slots],
            head: vec![END; strips.len()],
            occ_head: vec![END; vertices],
            occ_tail: vec![END; vertices],
            occ_next: vec![END; slots],
            strip_slots: strips.offsets.clone(),
            versions: Vec::with_capacity(slots * 2),
            begins: Vec::with_capacity(strips.len() * 2),
            recorded_head: vec![END; strips.len()],
            stamp: 0,
            slot_stamp: vec![0; slots],
            strip_stamp: vec![0; strips.len()],
            dirty: Vec::new(),
            touched: Vec::new(),
            changed: Vec::new(),
            window: Vec::new(),
            window_labels: Vec::new(),
            live_slots: slots,
            live_strips: (0..strips.len()).filter(|&s| strips.offsets[s] < strips.offsets[s + 1]).count(),
            triangles0: strips.iter().map(count_triangles).sum::<usize>() as u32,
            restrip_threshold: None,
            fresh_ratio: 0.0,
            restrips: 0,
        };
        for s in 0..strips.len() {
            let r = strips.offsets[s] as usize..strips.offsets[s + 1] as usize;
            for x in r.clone() {
                b.strip_of[x] = s as u32;
                b.prev[x] = if x > r.start { x as u32 - 1 } else { END };
                b.next[x] = if x + 1 < r.end { x as u32 + 1 } else { END };
                b.versions.push((x as u32, 0, b.label[x], b.next[x]));
                let v = b.label[x] as usize;
                if b.occ_tail[v] == END {
                    b.occ_head[v] = x as u32;
                } else {
                    b.occ_next[b.occ_tail[v] as usize] = x as u32;
                }
                b.occ_tail[v] = x as u32;
            }
            let h = if r.is_empty() { END } else { r.start as u32 };
            b.head[s] = h;
            b.recorded_head[s] = h;
            b.begins.push((s as u32, 0, h));
        }
        b
    }

    fn mark_dirty(&mut self, x: u32) {
        if self.slot_stamp[x as usize] != self.stamp {
            self.slot_stamp[x as usize] = self.stamp;
            self.dirty.push(x);
        }
        let s = self.strip_of[x as usize] as usize;
        if self.strip_stamp[s] != self.stamp {
            self.strip_stamp[s] = self.stamp;
            self.changed.push(s as u32);
        }
    }

    /// Starts a collapse: fresh stamps for its dirty slots and changed strips.
    fn start(&mut self) {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.slot_stamp.fill(0);
            self.strip_stamp.fill(0);
            self.stamp = 1;
        }
    }

    /// Renames every live slot naming `a` to `c` and moves `a`'s occurrence list to
    /// `c`'s. Between [`Builder::start`] and [`Builder::settle`].
    fn rename(&mut self, a: u32, c: u32) {
        let mut x = self.occ_head[a as usize];
        let mut last_live = END;
        while x != END {
            let nx = self.occ_next[x as usize];
            if self.alive[x as usize] && self.label[x as usize] == a {
                self.label[x as usize] = c;
                self.mark_dirty(x);
                self.touched.push(x);
                if last_live != END {
                    self.occ_next[last_live as usize] = x;
                } else {
                    self.occ_head[a as usize] = x;
                }
                last_live = x;
            }
            x = nx;
        }
        if last_live == END {
            self.occ_head[a as usize] = END;
            self.occ_tail[a as usize] = END;
            return;
        }
        self.occ_next[last_live as usize] = END;
        // Splice a's (now compact) list after c's.
        let (ah, at) = (self.occ_head[a as usize], last_live);
        if self.occ_tail[c as usize] == END {
            self.occ_head[c as usize] = ah;
        } else {
            self.occ_next[self.occ_tail[c as usize] as usize] = ah;
        }
        self.occ_tail[c as usize] = at;
        self.occ_head[a as usize] = END;
        self.occ_tail[a as usize] = END;
    }

    /// After a collapse's renames: shortens the strips around the renamed slots and
    /// logs what changed at `level`.
    fn settle(&mut self, level: u32, triangles: usize) {
        let touched = std::mem::take(&mut self.touched);
        for &x in &touched {
            if self.alive[x as usize] && self.degenerate_near(x) {
                self.reduce_around(x);
            }
        }
        self.touched = touched;
        self.touched.clear();
        let fresh = match self.restrip_threshold {
            Some(t) if triangles > 0 => {
                let r = self.ratio(triangles);
                if r > t && r > self.fresh_ratio + RESTRIP_MARGIN {
                    self.end_strips()
                } else {
                    None
                }
            }
            _ => None,
        };
        for i in 0..self.dirty.len() {
            let x = self.dirty[i];
            if self.alive[x as usize] {
                self.versions.push((x, level, self.label[x as usize], self.next[x as usize]));
            }
        }
        for i in 0..self.changed.len() {
            let s = self.changed[i] as usize;
            if self.head[s] != self.recorded_head[s] {
                self.recorded_head[s] = self.head[s];
                self.begins.push((s as u32, level, self.head[s]));
            }
        }
        self.dirty.clear();
        self.changed.clear();
        if let Some(tris) = fresh {
            self.add_strips(level, &tris);
            self.fresh_ratio = self.ratio(triangles);
        }
    }

    /// Indices per triangle of the live strips as one restart buffer.
    fn ratio(&self, triangles: usize) -> f64 {
        (self.live_slots + self.live_strips).saturating_sub(1) as f64 / triangles.max(1) as f64
    }

    /// Ends every live strip (its slots die, its head becomes [`END`]) and returns
    /// greedy strips of the triangles they drew, or `None` (nothing ended) when
    /// those strips would not draw them exactly.
    fn end_strips(&mut self) -> Option<StripSet> {
        let mut tris = Vec::new();
        let mut strip = Vec::new();
        for s in 0..self.head.len() {
            strip.clear();
            let mut x = self.head[s];
            while x != END {
                strip.push(self.label[x as usize]);
                x = self.next[x as usize];
            }
            crate::strip::for_each_triangle(&strip, |t| tris.push(t));
        }
        let fresh = crate::stripify::greedy::stripify(&tris, self.occ_head.len(), &Default::default());
        if !crate::strip::verify_triangles(&tris, &crate::strip::decode(&fresh)).ok() {
            return None;
        }
        for s in 0..self.head.len() {
            let mut x = self.head[s];
            while x != END {
                self.alive[x as usize] = false;
                x = self.next[x as usize];
            }
            if self.head[s] != END {
                self.head[s] = END;
                if self.strip_stamp[s] != self.stamp {
                    self.strip_stamp[s] = self.stamp;
                    self.changed.push(s as u32);
                }
            }
        }
        self.live_slots = 0;
        self.live_strips = 0;
        Some(fresh)
    }

    /// Appends `fresh` as new strips beginning at `level` (empty before it).
    fn add_strips(&mut self, level: u32, fresh: &StripSet) {
        for piece in fresh.iter().filter(|p| !p.is_empty()) {
            let s = self.head.len() as u32;
            let first = self.label.len() as u32;
            for (k, &v) in piece.iter().enumerate() {
                let x = first + k as u32;
                let next = if k + 1 < piece.len() { x + 1 } else { END };
                self.label.push(v);
                self.next.push(next);
                self.prev.push(if k > 0 { x - 1 } else { END });
                self.alive.push(true);
                self.strip_of.push(s);
                self.occ_next.push(END);
                self.slot_stamp.push(0);
                if self.occ_tail[v as usize] == END {
                    self.occ_head[v as usize] = x;
                } else {
                    self.occ_next[self.occ_tail[v as usize] as usize] = x;
                }
                self.occ_tail[v as usize] = x;
                self.versions.push((x, 0, v, next));
            }
            self.strip_slots.push(self.label.len() as u32);
            self.head.push(first);
            self.recorded_head.push(first);
            self.strip_stamp.push(0);
            self.begins.push((s, 0, END));
            self.begins.push((s, level, first));
            self.live_slots += piece.len();
            self.live_strips += 1;
            self.restrips += 1;
        }
    }

    /// Whether a triangle through live slot `x` is degenerate.
    fn degenerate_near(&self, x: u32) -> bool {
        let mut v = [END; 5];
        v[2] = self.label[x as usize];
        let mut p = self.prev[x as usize];
        for i in (0..2).rev() {
            if p == END {
                break;
            }
            v[i] = self.label[p as usize];
            p = self.prev[p as usize];
        }
        let mut q = self.next[x as usize];
        for slot in v.iter_mut().skip(3) {
            if q == END {
                break;
            }
            *slot = self.label[q as usize];
            q = self.next[q as usize];
        }
        (0..3).any(|i| {
            let t = [v[i], v[i + 1], v[i + 2]];
            !t.contains(&END) && (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
        })
    }

    /// Gathers up to [`REACH`] live slots on each side of `x` and removes what
    /// [`find_removal`] allows, longest first, until nothing more can go.
    fn reduce_around(&mut self, x: u32) {
        let mut window = std::mem::take(&mut self.window);
        let mut labels = std::mem::take(&mut self.window_labels);
        window.clear();
        let mut p = x;
        for _ in 0..REACH {
            p = self.prev[p as usize];
            if p == END {
                break;
            }
            window.push(p);
        }
        let front = window.last().map_or(self.prev[x as usize], |&l| self.prev[l as usize]) == END;
        window.reverse();
        window.push(x);
        let mut q = x;
        for _ in 0..REACH {
            q = self.next[q as usize];
            if q == END {
                break;
            }
            window.push(q);
        }
        let back = self.next[*window.last().expect("the window holds x") as usize] == END;
        labels.clear();
        labels.extend(window.iter().map(|&y| self.label[y as usize]));
        while let Some((i, len)) = find_removal(&labels, front, back) {
            for &y in &window[i..i + len] {
                self.unlink(y);
            }
            window.drain(i..i + len);
            labels.drain(i..i + len);
        }
        self.window = window;
        self.window_labels = labels;
    }

    fn unlink(&mut self, y: u32) {
        let yi = y as usize;
        self.alive[yi] = false;
        let (p, q) = (self.prev[yi], self.next[yi]);
        let s = self.strip_of[yi] as usize;
        self.live_slots -= 1;
        if p == END && q == END {
            self.live_strips -= 1;
        }
        if p != END {
            self.next[p as usize] = q;
            self.mark_dirty(p);
        } else {
            self.head[s] = q;
            // The strip changed even if no live slot did.
            if self.strip_stamp[s] != self.stamp {
                self.strip_stamp[s] = self.stamp;
                self.changed.push(s as u32);
            }
        }
        if q != END {
            self.prev[q as usize] = p;
        }
    }

    fn finish(
        self,
        placement: Placement,
        input_vertices: u32,
        positions: Vec<[f32; 3]>,
        targets: Vec<u32>,
        removed_triangles: Vec<u32>,
        triangles0: u32,
    ) -> Sets {
        let slots = self.label.len();
        let strips = self.head.len();
        // Counting sort of the logs by slot and by strip; each log is in level order,
        // so every list comes out sorted by level.
        let version_offsets = offsets(slots, self.versions.iter().map(|v| v.0));
        let mut fill = version_offsets.clone();
        let m = self.versions.len();
        let mut versions = vec![Version { level: 0, label: 0, next: END }; m];
        for &(x, level, label, next) in &self.versions {
            let at = fill[x as usize] as usize;
            fill[x as usize] += 1;
            versions[at] = Version { level, label, next };
        }
        let begin_offsets = offsets(strips, self.begins.iter().map(|b| b.0));
        let mut fill = begin_offsets.clone();
        let m = self.begins.len();
        let (mut begin_level, mut begin_slot) = (vec![0; m], vec![0; m]);
        for &(s, level, slot) in &self.begins {
            let at = fill[s as usize] as usize;
            fill[s as usize] += 1;
            begin_level[at] = level;
            begin_slot[at] = slot;
        }
        Sets {
            placement,
            input_vertices,
            positions,
            attributes: Vec::new(),
            targets,
            removed_triangles,
            triangles0,
            strip_slots: self.strip_slots,
            begin_offsets,
            begin_level,
            begin_slot,
            version_offsets,
            versions,
            change_offsets: Vec::new(),
            change_level: Vec::new(),
            changes: Vec::new(),
            level_offsets: Vec::new(),
            level_strips: Vec::new(),
            snapshots: Default::default(),
            triangles_at: Vec::new(),
        }
    }
}

/// CSR offsets of `n` buckets from the bucket of each item.
fn offsets(n: usize, items: impl Iterator<Item = u32>) -> Vec<u32> {
    let mut off = vec![0u32; n + 1];
    for b in items {
        off[b as usize + 1] += 1;
    }
    for i in 0..n {
        off[i + 1] += off[i];
    }
    off
}

/// Triangle `j` of `v` with its winding by the strip rule (parity of `j`), or `None`
/// when degenerate.
#[inline]
fn oriented(v: &[u32], j: usize) -> Option<[u32; 3]> {
    orient([v[j], v[j + 1], v[j + 2]], j % 2 == 1)
}

/// A strip window's triangle, swapped when at an odd position, in canonical rotation;
/// `None` when degenerate.
#[inline]
fn orient(t: [u32; 3], odd: bool) -> Option<[u32; 3]> {
    let t = if odd { [t[1], t[0], t[2]] } else { t };
    (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]).then(|| canonical(t))
}

/// The longest (then leftmost) run `v[i..i + len]` that may be removed from a window
/// of a strip: `front` / `back` say whether the window starts / ends the strip;
/// otherwise its two outer slots on that side are context and stay. A run inside the
/// strip or at its front is even and leaves the multiset of oriented non-degenerate
/// triangles unchanged; a run ending the strip may be odd and removes only
/// degenerate triangles.
pub(crate) fn find_removal(v: &[u32], front: bool, back: bool) -> Option<(usize, usize)> {
    let m = v.len();
    let lo = if front { 0 } else { 2 };
    let hi = if back { m } else { m.saturating_sub(2) };
    if hi <= lo {
        return None;
    }
    let nt = m.saturating_sub(2);
    // prefix[j]: non-degenerate triangles among the first j.
    let mut prefix = [0u8; WINDOW];
    let mut tris = [None; WINDOW];
    for j in 0..nt {
        tris[j] = oriented(v, j);
        prefix[j + 1] = prefix[j] + tris[j].is_some() as u8;
    }
    let count = |a: usize, b: usize| (prefix[b.min(nt)] - prefix[a.min(nt)]) as usize;
    let mut best: Option<(usize, usize)> = None;
    for i in lo..hi {
        for len in (1..=hi - i).rev() {
            if best.is_some_and(|(_, bl)| len <= bl) {
                break;
            }
            let jlo = i.saturating_sub(2);
            let before = count(jlo, i + len);
            if back && i + len == m {
                if before == 0 {
                    best = Some((i, len));
                }
                continue;
            }
            if len % 2 == 1 || before > 2 {
                continue;
            }
            // The triangles left across the gap: j in jlo..i, over v without the run.
            let at = |k: usize| if k < i { v[k] } else { v[k + len] };
            let mut after: [Option<[u32; 3]>; 2] = [None; 2];
            let mut na = 0;
            for j in jlo..i {
                if j + 2 >= m - len {
                    break;
                }
                if let Some(t) = orient([at(j), at(j + 1), at(j + 2)], j % 2 == 1) {
                    after[na] = Some(t);
                    na += 1;
                }
            }
            if na != before {
                continue;
            }
            let mut old: [Option<[u32; 3]>; 2] = [None; 2];
            let mut no = 0;
            for t in tris[jlo..(i + len).min(nt)].iter().flatten() {
                old[no] = Some(*t);
                no += 1;
            }
            old[..no].sort_unstable();
            after[..na].sort_unstable();
            if old[..no] == after[..na] {
                best = Some((i, len));
            }
        }
    }
    best
}

//! Timings of level recovery (the SETS paper's recovery tests, and the same for
//! animations): a bench API, used by `stripkit lod bench`. Every figure is wall-clock
//! microseconds on this machine, so it changes from run to run; the levels and counts
//! do not.

use super::seq::LodSeq;
use super::sets::{LevelSpec, Sets};
use serde::Serialize;
use std::time::Instant;

/// How [`recovery`] spaces the levels it recovers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Spacing {
    /// Equal steps from the finest level to the coarsest.
    Linear,
    /// Level `j` of `n` is `(L + 1)^(j / (n - 1)) - 1` for `L` levels, rounded:
    /// close steps near the finest level, far ones near the coarsest (a model moving
    /// away from the viewer).
    Exponential,
}

/// The paper's recovery test: recover `percent`% of the model's levels (at least
/// two), spaced by `spacing`, from the finest to the coarsest and back, `rounds`
/// times; returns the levels of one pass down and the mean microseconds per level
/// recovered (the cursor's update, with `compact` the tight buffer too).
pub fn recovery(sets: &Sets, percent: f64, spacing: Spacing, rounds: usize, compact: bool) -> (usize, f64) {
    let total = sets.levels() as usize + 1;
    let count = ((total as f64 * percent / 100.0).ceil() as usize).clamp(2, total.max(2));
    let max = sets.levels() as f64;
    let mut levels: Vec<u32> = (0..count)
        .map(|j| {
            let f = j as f64 / (count - 1) as f64;
            match spacing {
                Spacing::Linear => (f * max).round() as u32,
                Spacing::Exponential => ((max + 1.0).powf(f) - 1.0).round() as u32,
            }
        })
        .collect();
    levels.dedup();
    let down = levels.len();
    let mut path = levels.clone();
    path.extend(levels.iter().rev().skip(1));
    let mut cursor = sets.cursor(0);
    let mut out = Vec::new();
    let start = Instant::now();
    for _ in 0..rounds.max(1) {
        for &l in &path {
            cursor.set_level(l);
            if compact {
                cursor.compact(u32::MAX, &mut out);
            }
        }
    }
    let us = start.elapsed().as_secs_f64() * 1e6 / (path.len() * rounds.max(1)) as f64;
    (down, us)
}

/// One recovery test of [`sets`]: its share of the levels, their spacing, how many
/// levels one pass down visits, and the mean microseconds per level recovered.
#[derive(Clone, Debug, Serialize)]
pub struct RecoveryRow {
    /// Percent of the model's levels recovered.
    pub percent: f64,
    /// How the levels are spaced.
    pub spacing: Spacing,
    /// Distinct levels of one pass down.
    pub levels: usize,
    /// Mean microseconds per level recovered.
    pub us_per_level: f64,
}

/// The timings of a `.sets` model ([`sets`]).
#[derive(Clone, Debug)]
pub struct SetsTimings {
    /// The recovery tests: 1, 3, 6, 10, 15 and 20% of the levels, each linear then
    /// exponential.
    pub rows: Vec<RecoveryRow>,
    /// One change from the coarsest level to the finest (every strip re-walked), the
    /// median of the rounds.
    pub coarsest_to_finest_us: f64,
    /// A cursor made at the finest level (every strip walked from scratch), the median
    /// of the rounds.
    pub from_scratch_us: f64,
}

/// The paper's recovery tests on `sets` ([`recovery`] at 1, 3, 6, 10, 15 and 20% of
/// the levels, linear and exponential), `rounds` passes each, with `compact` the tight
/// buffer built after each change; and the worst single change and a cursor from
/// scratch, the median of `rounds`.
pub fn sets(sets: &Sets, rounds: usize, compact: bool) -> SetsTimings {
    let mut rows = Vec::new();
    for percent in [1.0, 3.0, 6.0, 10.0, 15.0, 20.0] {
        for spacing in [Spacing::Linear, Spacing::Exponential] {
            let (levels, us) = recovery(sets, percent, spacing, rounds, compact);
            rows.push(RecoveryRow { percent, spacing, levels, us_per_level: us });
        }
    }
    // The worst single change: coarsest to finest, the median of the rounds.
    let mut cursor = sets.cursor(sets.levels());
    let mut worst = Vec::new();
    let mut scratch = Vec::new();
    for _ in 0..rounds.max(1) {
        cursor.set_level(sets.levels());
        let t = Instant::now();
        cursor.set_level(0);
        worst.push(t.elapsed().as_secs_f64() * 1e6);
        let t = Instant::now();
        let c = sets.cursor(0);
        scratch.push(t.elapsed().as_secs_f64() * 1e6);
        drop(c);
    }
    SetsTimings { rows, coarsest_to_finest_us: median(&mut worst), from_scratch_us: median(&mut scratch) }
}

/// One test of [`seq`].
#[derive(Clone, Debug, Serialize)]
pub struct SeqRow {
    /// What changes: "frame" (every frame of the animation in turn at a fixed
    /// level), "level" (1% of the levels per step, or one level up and back, at a
    /// fixed frame), "play" (the animation plays and the level changes every 24
    /// frames).
    pub test: &'static str,
    /// The fixed ratio of triangles ("frame"), or the frame ("level").
    pub at: String,
    /// Changes timed per round.
    pub changes: usize,
    /// Mean microseconds per change.
    pub mean_us: f64,
    /// Median change (the upper one of an even count), microseconds.
    pub median_us: f64,
    /// 99th percentile of the changes, microseconds.
    pub p99_us: f64,
    /// Slowest change, microseconds.
    pub max_us: f64,
    /// Mean strips re-uploaded per change.
    pub strips_changed: f64,
}

/// The timings of a `.lodseq` animation ([`seq`]).
#[derive(Clone, Debug)]
pub struct SeqTimings {
    /// The tests, in the order [`seq`] runs them.
    pub rows: Vec<SeqRow>,
    /// A cursor made from scratch (every strip walked) at frame 0, full level, the
    /// median of the rounds.
    pub from_scratch_us: f64,
}

/// The figures of one [`seq`] test: every timed change's microseconds, and the
/// strips changed in all.
struct Changes {
    us: Vec<f64>,
    changed: usize,
}

/// Times `cursor.set` over `steps`, `rounds` times. A step whose flag is false only
/// positions the cursor (untimed).
fn time_changes(cursor: &mut super::SeqCursor<'_>, steps: &[(usize, LevelSpec, bool)], rounds: usize) -> Changes {
    let mut out = Changes { us: Vec::with_capacity(steps.len() * rounds.max(1)), changed: 0 };
    for _ in 0..rounds.max(1) {
        for &(f, spec, timed) in steps {
            let t = Instant::now();
            let c = cursor.set(f, spec).len();
            let us = t.elapsed().as_secs_f64() * 1e6;
            if timed {
                out.us.push(us);
                out.changed += c;
            }
        }
    }
    out
}

/// A row of [`seq`] from `time_changes`' figures: mean, median, p99, max, mean
/// strips changed.
fn row(test: &'static str, at: String, changes: usize, mut t: Changes) -> SeqRow {
    let n = t.us.len().max(1) as f64;
    let mean_us = t.us.iter().sum::<f64>() / n;
    let median_us = median(&mut t.us);
    let p99_us = t.us.get((t.us.len() * 99 / 100).min(t.us.len().saturating_sub(1))).copied().unwrap_or(0.0);
    let max_us = t.us.last().copied().unwrap_or(0.0);
    SeqRow { test, at, changes, mean_us, median_us, p99_us, max_us, strips_changed: t.changed as f64 / n }
}

/// Extraction timings of an animation, `rounds` passes each: every frame in turn at
/// 100, 50, 10 and 2% of the triangles; 1% of the levels per step down and back at
/// frames 0 and the middle one; one level down and back at 100 points of frame 0's
/// range; the animation played with the level moving every 24 frames (100% -> 2% ->
/// 100% in ten steps each way, the paper's Fig. 5b); and a cursor from scratch.
pub fn seq(seq: &LodSeq, rounds: usize) -> SeqTimings {
    let frames = seq.frame_count();
    let mut rows = Vec::new();
    // Frame changes at a fixed level: the animation played at each ratio.
    for ratio in [1.0, 0.5, 0.1, 0.02] {
        let spec = LevelSpec::Ratio(ratio);
        let mut cursor = seq.cursor(0, spec);
        let steps: Vec<(usize, LevelSpec, bool)> = (0..frames).map(|f| ((f + 1) % frames, spec, true)).collect();
        time_changes(&mut cursor, &steps, 1); // every model's cursor made once
        rows.push(row("frame", format!("{}%", ratio * 100.0), steps.len(), time_changes(&mut cursor, &steps, rounds)));
    }
    // Level changes at a fixed frame: 1% of the levels per step, down and back.
    for f in [0, frames / 2] {
        let levels = seq.models()[seq.model_of(f)].levels();
        let step = (levels / 100).max(1);
        let mut steps: Vec<(usize, LevelSpec, bool)> =
            (0..=levels).step_by(step as usize).map(|l| (f, LevelSpec::Level(l), true)).collect();
        let back: Vec<_> = steps.iter().rev().skip(1).copied().collect();
        steps.extend(back);
        let mut cursor = seq.cursor(f, LevelSpec::Level(0));
        rows.push(row("level", format!("frame {f}, 1% steps"), steps.len(), time_changes(&mut cursor, &steps, rounds)));
    }
    // One level up and back at 100 points of the range, at frame 0: placed at each
    // point untimed, then one level down and back up, timed.
    let levels = seq.models()[seq.model_of(0)].levels();
    let steps: Vec<(usize, LevelSpec, bool)> = (0..levels)
        .step_by((levels as usize / 100).max(1))
        .flat_map(|l| {
            [(0, LevelSpec::Level(l), false), (0, LevelSpec::Level(l + 1), true), (0, LevelSpec::Level(l), true)]
        })
        .collect();
    let mut cursor = seq.cursor(0, LevelSpec::Level(0));
    rows.push(row("level", "frame 0, one level".into(), 2 * steps.len() / 3, time_changes(&mut cursor, &steps, rounds)));
    // The paper's Fig. 5b: the animation plays, the level moves every 24 frames
    // (100% -> 2% -> 100% in ten steps each way).
    let ratios: Vec<f64> =
        (0..=10).map(|i| 1.0 - 0.098 * i as f64).chain((0..10).rev().map(|i| 1.0 - 0.098 * i as f64)).collect();
    let steps: Vec<(usize, LevelSpec, bool)> =
        (0..ratios.len() * 24).map(|i| (i % frames, LevelSpec::Ratio(ratios[i / 24]), true)).collect();
    let mut cursor = seq.cursor(0, LevelSpec::Ratio(1.0));
    time_changes(&mut cursor, &steps, 1);
    rows.push(row("play", "level every 24 frames".into(), steps.len(), time_changes(&mut cursor, &steps, rounds)));
    let mut scratch = Vec::new();
    for _ in 0..rounds.max(1) {
        let t = Instant::now();
        let c = seq.cursor(0, LevelSpec::Level(0));
        scratch.push(t.elapsed().as_secs_f64() * 1e6);
        drop(c);
    }
    SeqTimings { rows, from_scratch_us: median(&mut scratch) }
}

/// The median (the upper one of an even count; 0 for none).
fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{gen, lod};

    #[test]
    fn recovery_visits_the_spaced_levels_once_down() {
        let sets = lod::build(&gen::icosphere(2), &lod::BuildOptions::default(), &mut |_| {}).unwrap().sets;
        let total = sets.levels() as usize + 1;
        let (down, us) = recovery(&sets, 100.0, Spacing::Linear, 1, true);
        assert_eq!(down, total);
        assert!(us >= 0.0);
        // At least two levels, the finest and the coarsest.
        assert_eq!(recovery(&sets, 0.0, Spacing::Exponential, 1, false).0, 2);
        let t = super::sets(&sets, 1, false);
        assert_eq!(t.rows.len(), 12);
        assert!(t.rows.windows(2).all(|w| w[0].percent <= w[1].percent));
    }
}

//! Strips that stay good when coarse (issue #35): the indices per triangle of a
//! model at every level, and restart labels inside a strip as an optimistic bound
//! computed on a level's strips (the re-stripped models are the library's,
//! [`stripkit::lod::BuildOptions::restrip`]).

use stripkit::lod::{self, Sets};

/// Indices per triangle (restart buffer) at every level of `sets`, level 0 first,
/// kept up to date from the strips each level change re-walks.
pub fn per_level(sets: &Sets) -> Vec<f64> {
    let mut cursor = sets.cursor(0);
    let strips = sets.strip_count();
    let mut lens: Vec<usize> = (0..strips).map(|s| cursor.strip(s).len()).collect();
    let mut total: usize = lens.iter().sum();
    let mut live = lens.iter().filter(|&&l| l > 0).count();
    let ratio = |total: usize, live: usize, tris: u32| (total + live.saturating_sub(1)) as f64 / tris.max(1) as f64;
    let mut out = vec![ratio(total, live, sets.triangles_at(0))];
    for level in 1..=sets.levels() {
        let changed = cursor.set_level(level).to_vec();
        for s in changed {
            let (old, new) = (lens[s as usize], cursor.strip(s as usize).len());
            total = total + new - old;
            live = live + (new > 0) as usize - (old > 0) as usize;
            lens[s as usize] = new;
        }
        out.push(ratio(total, live, sets.triangles_at(level)));
    }
    out
}

/// Indices of the level's strips if each run of degenerate windows were replaced by
/// a restart where that is shorter: a restart costs the restart index, the first two
/// vertices of the next piece and, when the next triangle sits at an odd window, a
/// repeated vertex to keep its winding (an optimistic bound on restart labels: every
/// run is cut where cutting pays, whatever the removal rules allow).
pub fn restart_bound(strip: &[u32]) -> usize {
    let windows = strip.len().saturating_sub(2);
    let degenerate = |j: usize| {
        let (a, b, c) = (strip[j], strip[j + 1], strip[j + 2]);
        a == b || b == c || a == c
    };
    let mut saved = 0;
    let mut last_tri: Option<usize> = None;
    for j in 0..windows {
        if degenerate(j) {
            continue;
        }
        if let Some(a) = last_tri {
            let d = j - a - 1;
            let cost = 3 + j % 2;
            saved += d.saturating_sub(cost);
        }
        last_tri = Some(j);
    }
    strip.len() - saved
}

/// Restart-buffer indices per triangle at `level` with the restart bound.
pub fn restart_ratio(sets: &Sets, cursor: &mut lod::Cursor<'_>, level: u32) -> f64 {
    cursor.set_level(level);
    let mut total = 0;
    let mut live = 0usize;
    for s in 0..sets.strip_count() {
        let strip = cursor.strip(s);
        if !strip.is_empty() {
            total += restart_bound(strip);
            live += 1;
        }
    }
    (total + live.saturating_sub(1)) as f64 / sets.triangles_at(level).max(1) as f64
}

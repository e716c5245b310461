//! Level switches of the `.sets` cursor (issue #35, fast switches): over shuffled
//! random walks of one level, a few levels, 1% of the triangles and far jumps, on
//! kept and re-stripped strips and both placements, the cursor's buffer equals a
//! fresh cursor's (which walks every strip from its beginning) after every move, its
//! strips draw exactly the level, and nothing outside the ranges it reports changed.

mod simplify_meshes;
mod support;

use simplify_meshes::{bumpy_sphere, grid, shuffled};
use stripkit::lod::{self, BuildOptions, Sets};
use stripkit::simplify::Placement;
use stripkit::{gen, Mesh};
use stripkit_testkit::XorShift64;

fn sets(mesh: &Mesh, restrip: Option<f64>, placement: Placement) -> Sets {
    lod::build(mesh, &BuildOptions::default().placement(placement).restrip(restrip), &mut |_| {}).expect("builds").sets
}

/// The next level of a random walk: one level either way, a few, 1% of the
/// triangles either way, or anywhere.
fn next_level(sets: &Sets, level: u32, rng: &mut XorShift64) -> u32 {
    let n = sets.levels();
    let x = rng.next();
    match x % 8 {
        0 | 1 => (level + 1).min(n),
        2 | 3 => level.saturating_sub(1),
        4 => (level + 2 + (x >> 8) as u32 % 6).min(n).saturating_sub((x >> 16) as u32 % 12),
        5 => {
            // 1% of the triangles coarser or finer.
            let t = sets.triangles_at(level) as f64 / sets.triangles_at(0).max(1) as f64;
            let r = if x >> 20 & 1 == 0 { t - 0.01 } else { t + 0.01 };
            sets.level_for_ratio(r.clamp(0.0, 1.0))
        }
        _ => ((x >> 8) % (n as u64 + 1)) as u32,
    }
}

/// Walks `steps` random moves and checks each; returns how many strips were
/// re-walked from a later slot than their first and how many kept their last
/// vertices in place (a range reported shorter than the strip's).
fn random_walk(label: &str, sets: &Sets, seed: u64, steps: usize) -> (usize, usize) {
    let mut rng = XorShift64(seed);
    let mut c = sets.cursor(0);
    let (mut partial, mut short) = (0, 0);
    for step in 0..steps {
        let level = next_level(sets, c.level(), &mut rng);
        let before = c.buffer().to_vec();
        let changed = c.set_level(level).to_vec();
        assert_eq!(c.level(), level);
        let fresh = sets.cursor(level);
        assert_eq!(c.buffer(), fresh.buffer(), "{label}: step {step}, level {level}");
        assert_eq!(c.strips(), sets.strips_at(level), "{label}: step {step}, level {level}");
        let v = stripkit::verify_triangles(&lod_triangles(sets, level), &stripkit::decode(&c.strips()));
        assert!(v.ok(), "{label}: level {level}: {v}");
        assert!(changed.windows(2).all(|w| w[0] < w[1]), "{label}: changed strips ascending, once each");
        for &s in &changed {
            let (whole, r) = (c.strip_range(s as usize), c.changed_range(s as usize));
            assert!(r.start >= whole.start && r.end <= whole.end, "{label}: strip {s}");
            partial += (r.start > whole.start) as usize;
            short += (r.end < whole.start + c.strip(s as usize).len().max(1)) as usize;
        }
        assert_changes_reported(&before, &c, &changed, &format!("{label}: step {step} to level {level}"));
    }
    (partial, short)
}

/// Every buffer index that changed from `before` to the cursor's buffer lies in the
/// reported range of one of the `changed` strips.
fn assert_changes_reported(before: &[u32], c: &lod::Cursor, changed: &[u32], label: &str) {
    let mut written = vec![false; before.len()];
    for &s in changed {
        written[c.changed_range(s as usize)].fill(true);
    }
    for (i, (&a, &z)) in before.iter().zip(c.buffer()).enumerate() {
        assert!(written[i] || a == z, "{label}: buffer index {i} changed unreported");
    }
}

/// The level's triangles as a fresh cursor draws them, counted against the model.
fn lod_triangles(sets: &Sets, level: u32) -> Vec<[u32; 3]> {
    let t = stripkit::decode(&sets.strips_at(level));
    assert_eq!(t.len() as u32, sets.triangles_at(level), "level {level}");
    t
}

#[test]
fn random_walks_equal_fresh_cursors_kept_and_restripped() {
    let meshes = [
        ("bumpy sphere, shuffled", shuffled(&bumpy_sphere(4), 11)),
        ("height field with a border", shuffled(&grid(20, 14, |x, y| 0.2 * (4.0 * x).sin() * (3.0 * y).cos()), 3)),
        ("two pieces", gen::disjoint_union(&[&gen::icosphere(3), &shuffled(&gen::torus(20, 8, 1.0, 0.3), 5)])),
    ];
    for (name, mesh) in &meshes {
        for (restrip, placement) in
            [(None, Placement::Endpoint), (Some(1.5), Placement::Endpoint), (Some(1.6), Placement::Optimal)]
        {
            let sets = sets(mesh, restrip, placement);
            assert!(sets.levels() > 100, "{name}: {} levels", sets.levels());
            let label = format!("{name}, restrip {restrip:?}, {placement:?}");
            let (partial, short) = random_walk(&label, &sets, 0x2545F4914F6CDD1D ^ sets.levels() as u64, 400);
            // The partial re-walks and the runs left in place do happen.
            assert!(partial > 50, "{label}: {partial} strips re-walked from a later slot");
            assert!(short > 5, "{label}: {short} strips with their last vertices left in place");
        }
    }
}

/// One-level steps across the whole range and back touch only a few strips each,
/// and the cursor at each level equals a fresh one.
#[test]
fn one_level_steps_touch_few_strips() {
    let sets = sets(&shuffled(&bumpy_sphere(4), 2), None, Placement::Endpoint);
    let mut c = sets.cursor(0);
    let mut most = 0;
    let path: Vec<u32> = (1..=sets.levels()).chain((0..sets.levels()).rev()).collect();
    for &level in &path {
        most = most.max(c.set_level(level).len());
        if level % 7 == 0 {
            assert_eq!(c.buffer(), sets.cursor(level).buffer(), "level {level}");
        }
    }
    assert!(most <= 8, "a one-level step changed {most} strips");
    assert_eq!(c.buffer(), sets.cursor(0).buffer());
}

/// Steps of 1% of the triangles down to the coarsest and back, and one level at a
/// time around each re-strip level's neighbourhood, on re-stripped strips: they
/// cross every re-strip level both ways (the cursor copies the model's tables there
/// and goes on as a near move), and every step equals a fresh cursor, with ascending
/// changed strips and every changed index reported.
#[test]
fn one_percent_steps_across_restrip_levels_equal_fresh_cursors() {
    let mesh = shuffled(&bumpy_sphere(4), 7);
    for (restrip, placement) in [(Some(1.5), Placement::Endpoint), (Some(1.6), Placement::Optimal)] {
        let sets = sets(&mesh, restrip, placement);
        assert!(sets.restripped_strips() > 0, "{placement:?}: re-stripped");
        let down: Vec<u32> = (0..=100).map(|j| sets.level_for_ratio(1.0 - j as f64 / 100.0)).collect();
        let mut c = sets.cursor(0);
        let mut big = 0;
        for (step, &level) in down.iter().chain(down.iter().rev()).enumerate() {
            let before = c.buffer().to_vec();
            let changed = c.set_level(level).to_vec();
            let fresh = sets.cursor(level);
            assert_eq!(c.buffer(), fresh.buffer(), "{placement:?}: step {step}, level {level}");
            assert!(changed.windows(2).all(|w| w[0] < w[1]), "{placement:?}: changed strips ascending, once each");
            assert_changes_reported(&before, &c, &changed, &format!("{placement:?}: step {step}"));
            let v = stripkit::verify_triangles(&lod_triangles(&sets, level), &stripkit::decode(&c.strips()));
            assert!(v.ok(), "{placement:?}: level {level}: {v}");
            // A step across a re-strip level ends every live strip and begins others.
            big += (changed.len() * 2 > sets.strip_count() / 4) as usize;
        }
        assert!(big >= 2, "{placement:?}: {big} steps across a re-strip level");
    }
}

use super::sets::find_removal;
use super::*;
use crate::simplify::{Collapse, CollapseSequence, Placement};
use crate::strip::StripSet;

/// The paper's Fig. 1 example: vertices a..h are 0..7.
#[test]
fn paper_example_sequences() {
    let strips = StripSet::from_strips(&[[0u32, 1, 2, 3, 4, 5, 6, 7]]);
    let mut seq = CollapseSequence::new(8, 6);
    // c -> d, a -> b, f -> d, g -> h.
    for (r, k) in [(2, 3), (0, 1), (5, 3), (6, 7)] {
        seq.push(Collapse { removed: r, kept: k, position: [0.0; 3], error: 0.0 }, &[0]);
    }
    let positions = vec![[0.0f32; 3]; 8];
    let sets = Sets::build(&positions, &strips, &seq, Placement::Endpoint).unwrap();
    let (a, b, d, e, f, g, h) = (0, 1, 3, 4, 5, 6, 7);
    let _ = (a, b, f, g);
    let want: [&[u32]; 5] =
        [&[0, 1, 2, 3, 4, 5, 6, 7], &[a, b, d, d, e, f, g, h], &[d, d, e, f, g, h], &[e, d, g, h], &[e, d, h]];
    for (level, w) in want.iter().enumerate() {
        assert_eq!(sets.strips_at(level as u32).strip(0), *w, "level {level}");
    }
    // Coherence: a cursor moving across levels agrees with walks from scratch.
    let mut c = sets.cursor(0);
    for level in [4u32, 1, 3, 0, 2, 2, 4] {
        c.set_level(level);
        assert_eq!(c.strips(), sets.strips_at(level));
    }
}

#[test]
fn removals_keep_triangles() {
    // Front: an even run of degenerate triangles.
    assert_eq!(find_removal(&[1, 1, 3, 3, 4, 5], true, true), Some((0, 2)));
    // An odd front run is not allowed (it would flip everything after).
    assert_eq!(find_removal(&[1, 3, 3, 4, 5], true, false), Some((0, 2)));
    assert_eq!(find_removal(&[3, 3, 4, 5, 6, 7], true, false), None);
    // End: any run of degenerate triangles.
    assert_eq!(find_removal(&[4, 3, 7, 7], true, true), Some((3, 1)));
    // A strip of only degenerate triangles goes entirely.
    assert_eq!(find_removal(&[1, 1, 2, 2], true, true), Some((0, 4)));
    // Nothing to remove in a clean strip.
    assert_eq!(find_removal(&[0, 1, 2, 3, 4, 5, 6], true, true), None);
}

/// An empty strip set under an empty sequence: the smallest `.sets` file reads back.
#[test]
fn empty_model_round_trips() {
    let sets = Sets::build(&[], &StripSet::new(), &CollapseSequence::new(0, 0), Placement::Endpoint).unwrap();
    let bytes = sets.to_bytes();
    assert_eq!(bytes.len(), 8 + 40 + 4);
    assert_eq!(Sets::from_bytes(std::path::Path::new("empty.sets"), &bytes).unwrap(), sets);
    assert!(sets.strips_at(0).is_empty());
}

/// A scratch folder of this test process, removed by the caller.
fn scratch(name: &str) -> std::path::PathBuf {
    stripkit_testkit::scratch_dir(&format!("lod-{name}"))
}

/// A file is told apart by its magic: a model reads, anything else is a format error
/// at byte 0 for [`Model::read`] and `None` for [`Model::try_read`].
#[test]
fn model_read_tells_files_by_magic() {
    let dir = scratch("magic");
    let sets = build(&crate::gen::icosphere(1), &BuildOptions::default(), &mut |_| {}).unwrap().sets;
    let model = dir.join("ico.sets");
    sets.write(&model).unwrap();
    assert_eq!(Model::read(&model).unwrap(), Model::Sets(sets));
    for (name, bytes) in [("mesh.off", &b"OFF\n0 0 0\n"[..]), ("short.sets", &b"SKLOD"[..])] {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        assert!(Model::try_read(&path).unwrap().is_none(), "{name}");
        match Model::read(&path) {
            Err(crate::Error::Format { at, what, .. }) => {
                assert_eq!(at, "byte 0");
                assert!(what.contains("bad magic"), "{what}");
            }
            other => panic!("{name}: {other:?}"),
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// One level written in every mesh format reads back to its triangles, each with its
/// winding; a level whose strips disagree with the model's count is refused before
/// anything is written.
#[test]
fn extracted_level_writes_checked() {
    let dir = scratch("extract");
    let sets = build(&crate::gen::icosphere(2), &BuildOptions::default(), &mut |_| {}).unwrap().sets;
    let level = Model::Sets(sets).extract(LevelSpec::Ratio(0.3), None).unwrap();
    let triangles = level.checked_triangles().unwrap();
    assert_eq!(triangles.len(), level.triangles as usize);
    // The files hold the level's vertices only, renumbered by first use.
    let (used, _, renamed) = level.used_vertices(&triangles, &mut []);
    assert!(used.positions.len() < level.positions.len());
    for ext in ["ply", "glb", "gltf", "obj", "off", "ply.gz", "stl"] {
        let path = dir.join(format!("level.{ext}"));
        level.write_file(&path, &crate::mesh::io::WriteOptions::default()).unwrap();
        let back = crate::mesh::io::read(&path).unwrap();
        assert_eq!(back.triangulate().tris.len(), triangles.len(), "{ext}");
        if ext != "stl" {
            // (STL welds its vertices anew: the check inside compared positions.)
            assert_eq!(back.positions, used.positions, "{ext}");
            assert!(crate::strip::verify_triangles(&renamed, &back.triangulate().tris).ok(), "{ext}");
        }
    }
    let json = level.to_json().unwrap();
    assert_eq!(json["level"], level.level);
    assert_eq!(json["strips"].as_array().unwrap().len(), level.strips.len());
    let mut wrong = level.clone();
    wrong.triangles += 1;
    let path = dir.join("wrong.ply");
    assert!(matches!(wrong.write_file(&path, &Default::default()), Err(crate::Error::Verification(_))));
    assert!(!path.exists());
    assert!(matches!(wrong.to_json(), Err(crate::Error::Verification(_))));
    let unknown = level.write_file(dir.join("level.xyz"), &Default::default());
    assert!(matches!(unknown, Err(crate::Error::UnknownFormat { .. })));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The check finds a model that draws a triangle the replay does not: one face of
/// the mesh flipped, caught at level 0.
#[test]
fn check_levels_finds_a_flipped_face() {
    let built = build(&crate::gen::icosphere(1), &BuildOptions::default(), &mut |_| {}).unwrap();
    check_levels(&built.sets, &built.mesh, &built.sequence, 1, 4).unwrap();
    let mut flipped = built.mesh.clone();
    let face = flipped.face_offsets[0] as usize..flipped.face_offsets[1] as usize;
    flipped.face_indices[face].reverse();
    match check_levels(&built.sets, &flipped, &built.sequence, 1, 4) {
        Err(crate::Error::Verification(what)) => assert!(what.starts_with("level 0:"), "{what}"),
        other => panic!("{other:?}"),
    }
}

/// `Built::check` covers every level, or about as many as asked plus the coarsest.
#[test]
fn built_check_covers_the_levels_asked() {
    let built = build(&crate::gen::icosphere(2), &BuildOptions::default(), &mut |_| {}).unwrap();
    let levels = built.sets.levels() as usize;
    assert_eq!(built.check(None).unwrap().levels_checked, levels + 1);
    let sampled = built.check(Some(10)).unwrap().levels_checked;
    assert!((10..=12).contains(&sampled), "{sampled} of {levels}");
}

/// A model whose triangle counts add up but do not match its strips (one collapse's
/// removed count moved to the next, checksum right): refused on reading, naming the file and
/// the first level the strips disagree with, not accepted to fail at extraction.
#[test]
fn counts_that_add_up_but_do_not_match_the_strips_are_a_bad_file() {
    let mesh = crate::gen::icosphere(1);
    let sets = build(&mesh, &BuildOptions::default(), &mut |_| {})
        .unwrap()
        .sets;
    assert!(Sets::from_bytes(std::path::Path::new("good.sets"), &sets.to_bytes()).is_ok());
    // Collapse 1 said to remove nothing and collapse 2 its triangles too: the total
    // holds, level 2 (after collapse 1) is off.
    let i = 1;
    let mut bad = sets.clone();
    let moved = std::mem::take(&mut bad.removed_triangles[i]);
    assert!(moved > 0);
    bad.removed_triangles[i + 1] += moved;
    let path = std::path::Path::new("swapped.sets");
    match Sets::from_bytes(path, &bad.to_bytes()) {
        Err(crate::Error::Format { path: p, at, what }) => {
            assert_eq!(p, path);
            assert_eq!(at, format!("level {}", i + 1), "{what}");
            assert!(what.contains("the strips draw"), "{what}");
        }
        other => panic!("expected a format error, got {other:?}"),
    }
}

/// A flat ribbon of `n` triangles (a row of quads, each cut the same way): every
/// collapse of its simplification changes its one long strip.
pub(crate) fn ribbon(n: u32) -> crate::mesh::Mesh {
    let positions = (0..n / 2 + 2).flat_map(|i| [[i as f32, 0.0, 0.0], [i as f32, 1.0, 0.0]]).collect();
    let tris: Vec<[u32; 3]> = (0..n)
        .map(|i| {
            let a = 2 * (i / 2);
            if i % 2 == 0 {
                [a, a + 2, a + 1]
            } else {
                [a + 1, a + 2, a + 3]
            }
        })
        .collect();
    crate::mesh::Mesh::from_triangles(positions, &tris)
}

/// The tracker's triangles (kept as a multiset from its signed reports) equal a walk
/// from scratch at every level, windings included, and its counts the same.
fn assert_tracker_matches_walks(sets: &Sets) {
    let canon = |t: [u32; 3]| crate::strip::canonical(t);
    let mut held: std::collections::HashMap<[u32; 3], i32> = Default::default();
    let mut bump = |t: [u32; 3], by: i32| *held.entry(canon(t)).or_insert(0) += by;
    let mut tracker = super::track::Tracker::new(sets, true, |_, t, by| bump(t, by));
    loop {
        let level = tracker.level();
        let mut want: std::collections::HashMap<[u32; 3], i32> = Default::default();
        for t in crate::strip::decode(&sets.strips_at(level)) {
            *want.entry(canon(t)).or_insert(0) += 1;
        }
        held.retain(|_, n| *n != 0);
        assert_eq!(held, want, "level {level}");
        if level == sets.levels() {
            break;
        }
        tracker.step(|_, t, by| *held.entry(canon(t)).or_insert(0) += by);
    }
}

#[test]
fn tracker_follows_every_level() {
    for mesh in [ribbon(300), crate::gen::icosphere(2), crate::gen::grid(9, 7), crate::gen::torus(12, 8, 2.0, 0.5)] {
        for placement in [Placement::Endpoint, Placement::Optimal] {
            let built = build(&mesh, &BuildOptions::default().placement(placement), &mut |_| {}).unwrap();
            assert_tracker_matches_walks(&built.sets);
            assert!(built.sets.check_triangle_counts().is_ok());
        }
    }
}

/// Models the builder never makes (one more slot skipped by a successor, a strip
/// beginning moved one slot on: an odd removal that flips every later triangle, or a
/// slot brought back): the tracker still follows the walks from scratch.
#[test]
fn tracker_follows_odd_removals() {
    let sets = build(&ribbon(120), &BuildOptions::default(), &mut |_| {}).unwrap().sets;
    let mut tried = 0;
    for slot in (0..sets.slot_count()).step_by(7) {
        let r = sets.version_offsets[slot] as usize..sets.version_offsets[slot + 1] as usize;
        for i in r.clone().skip(1) {
            let v = sets.versions[i];
            if v.next == END {
                continue;
            }
            // Skip one slot more (forward, within the strip), then bring it back.
            let end = sets.strip_slots[1];
            for next in [v.next + 1, slot as u32 + 1] {
                if next <= slot as u32 || next >= end {
                    continue;
                }
                let mut bad = sets.clone();
                bad.versions[i].next = next;
                assert_tracker_matches_walks(&bad);
                tried += 1;
            }
        }
    }
    let mut bad = sets.clone();
    for k in 1..bad.begin_slot.len() {
        if bad.begin_slot[k] != END && bad.begin_slot[k] + 1 < bad.strip_slots[1] {
            bad.begin_slot[k] += 1;
        }
    }
    assert_tracker_matches_walks(&bad);
    assert!(tried > 10, "{tried}");
}

/// `lod build` on a long flat ribbon: every level checked against the replay (the
/// check the CLI runs by default), the file read back, each level's triangle count
/// what the strips draw.
#[test]
fn ribbon_levels_check() {
    // The kept strips: one strip, never re-stripped.
    let built = build(&ribbon(3000), &BuildOptions::default().restrip(None), &mut |_| {}).unwrap();
    assert_eq!(built.sets.strip_count(), 1);
    let levels = built.sets.levels();
    assert!(levels > 1000, "{levels}");
    let check = built.check(None).unwrap();
    assert_eq!(check.levels_checked, levels as usize + 1);
    let back = Sets::from_bytes(std::path::Path::new("ribbon.sets"), &built.sets.to_bytes()).unwrap();
    assert_eq!(back, built.sets);
    for level in (0..=levels).step_by(97).chain([levels]) {
        let drawn = crate::strip::decode(&back.strips_at(level)).len();
        assert_eq!(drawn as u32, back.triangles_at(level), "level {level}");
    }
}

/// The derived change lists name, per (level, slot) change, the slot's version that
/// starts there: every version past level 0 once, each at its own level and slot.
#[test]
fn change_versions_name_the_version_starting_there() {
    use super::sets::{AMBIGUOUS_VERSION, NO_VERSION};
    let mesh = crate::gen::icosphere(3);
    for restrip in [None, Some(1.6)] {
        let options = BuildOptions { restrip, ..BuildOptions::default() };
        let sets = build(&mesh, &options, &mut |_| {}).unwrap().sets;
        let mut named = vec![0u32; sets.versions.len()];
        for s in 0..sets.strip_count() {
            let r = sets.change_offsets[s] as usize + 1..sets.change_offsets[s + 1] as usize;
            for i in r {
                let c = sets.changes[i];
                let (level, slot, v) = (c.level, c.slot, c.version);
                assert_eq!(level, sets.change_level[i]);
                assert_ne!(v, AMBIGUOUS_VERSION, "one version per level and slot here");
                if v != NO_VERSION {
                    let own = sets.version_offsets[slot as usize]..sets.version_offsets[slot as usize + 1];
                    assert!(own.contains(&v), "strip {s}: version {v} is not slot {slot}'s");
                    assert_eq!(sets.versions[v as usize].level, level);
                    named[v as usize] += 1;
                }
            }
        }
        for x in 0..sets.version_offsets.len() - 1 {
            let r = sets.version_offsets[x] as usize..sets.version_offsets[x + 1] as usize;
            assert_eq!(named[r.start], 0, "level 0 is no change");
            assert!(named[r.start + 1..r.end].iter().all(|&n| n == 1), "slot {x}: a version unnamed or named twice");
        }
    }
}

/// The walks kept for the strips that appear at a re-strip level are those strips'
/// walks there, and cursor moves across each re-strip level (from near and far,
/// both ways) that start from them equal fresh cursors, every changed index
/// reported.
#[test]
fn kept_walks_at_restrip_levels() {
    let mesh = crate::gen::icosphere(3);
    let options = BuildOptions { restrip: Some(1.5), ..BuildOptions::default() };
    let sets = build(&mesh, &options, &mut |_| {}).unwrap().sets;
    let mut restrip: Vec<u32> = (0..sets.strip_count())
        .filter(|&s| sets.begin_slot[sets.begin_offsets[s] as usize] == END)
        .flat_map(|s| sets.begin_level[sets.begin_offsets[s] as usize + 1..sets.begin_offsets[s + 1] as usize].to_vec())
        .collect();
    restrip.sort_unstable();
    restrip.dedup();
    assert!(restrip.len() >= 2, "re-strip levels {restrip:?}");
    let mut kept = 0;
    for s in 0..sets.strip_count() {
        for coarser in [true, false] {
            let Some(snap) = sets.snapshots.find(s, 0, sets.levels() + 1, coarser) else { continue };
            let mut want = Vec::new();
            sets.walk(s, snap.level, |v| want.push(v));
            assert_eq!(snap.labels, &want[..], "strip {s} at level {}", snap.level);
            assert!(restrip.contains(&snap.level) || restrip.contains(&(snap.level + 1)));
            kept += 1;
        }
    }
    assert!(kept > 20, "{kept} kept walks");
    let last = sets.levels();
    for &l in &restrip {
        let (l1, l2, l5) = (l - 1, l.saturating_sub(2), l.saturating_sub(5));
        for (from, to) in [(l1, l), (l, l1), (0, l + 3), (l + 3, l2), (last, l1), (l1, last), (l5, l)] {
            let (from, to) = (from.min(last), to.min(last));
            move_checked(&sets, &mut sets.cursor(from), to, "");
        }
    }
}

/// Moves of 1% of the triangles and of one level, down and back, and jumps, equal fresh cursors,
/// with both ways of listing the changed strips (stamps and a sort for short
/// per-level lists, the bit set for long ones) taken: each move's changed strips
/// ascending, once each, and every strip whose indices changed among them. (The
/// first changed slot of each strip, read from its change entry's rank, is checked
/// against a search by a debug assertion.)
#[test]
fn moves_list_changed_strips_in_order() {
    // Many pieces, so many strips: a 1% move lists fewer entries than strips.
    let piece = crate::gen::icosphere(1);
    let mesh = crate::gen::disjoint_union(&vec![&piece; 300]);
    for restrip in [None, Some(1.6)] {
        let options = BuildOptions { restrip, ..BuildOptions::default() };
        let sets = build(&mesh, &options, &mut |_| {}).unwrap().sets;
        let down: Vec<u32> = (0..=99).map(|j| sets.level_for_ratio(1.0 - j as f64 / 100.0)).collect();
        let mut path: Vec<u32> = down.iter().copied().chain(down.iter().rev().copied()).collect();
        path.extend((1..=10).chain((0..10).rev()));
        path.extend([sets.levels(), 0, sets.levels() / 2, 3]);
        let (mut short, mut long) = (0, 0);
        let mut c = sets.cursor(0);
        for &to in &path {
            let from = c.level();
            let (lo, hi) = (from.min(to) as usize, from.max(to) as usize);
            let listed = (sets.level_offsets[hi + 1] - sets.level_offsets[lo + 1]) as usize;
            if from != to && listed < sets.strip_count() {
                if listed > super::cursor::SMALL_LIST {
                    long += 1;
                } else {
                    short += 1;
                }
            }
            let before: Vec<Vec<u32>> = (0..sets.strip_count()).map(|s| c.strip(s).to_vec()).collect();
            let changed = c.set_level(to).to_vec();
            assert!(changed.windows(2).all(|w| w[0] < w[1]), "{from} -> {to}: changed strips not ascending");
            for (s, b) in before.iter().enumerate() {
                assert!(c.strip(s) == &b[..] || changed.binary_search(&(s as u32)).is_ok(), "{from} -> {to}: strip {s} unlisted");
            }
            assert_eq!(c.buffer(), sets.cursor(to).buffer(), "{from} -> {to}");
        }
        assert!(short > 5 && long > 5, "restrip {restrip:?}: {short} short and {long} long listings of {} strips", sets.strip_count());
    }
}

/// A run's end looked for from a guess is the search's answer for every start,
/// guess (near, far, past the end) and bound.
#[test]
fn run_end_from_any_guess_is_the_search() {
    let old: Vec<u32> = (0..40u32).map(|i| 3 * i + i % 2).collect();
    for k in 0..old.len() {
        for next in old[k] + 1..old[old.len() - 1] + 3 {
            let want = k + old[k..].partition_point(|&y| y < next);
            for guess in 0..old.len() + 3 {
                assert_eq!(super::cursor::run_end(&old, k, guess, next), want, "k {k} next {next} guess {guess}");
            }
        }
    }
}

/// Moves onto, off and across every re-strip level (near and far, both ways, from
/// fresh cursors and in one chain, so that a state the tables set wrongly shows in
/// the moves after) take the tables' path and equal fresh cursors, ascending changed
/// strips, every changed index reported.
#[test]
fn moves_across_restrip_levels_copy_the_tables() {
    let meshes = [(crate::gen::icosphere(3), 1.5, Placement::Endpoint), (crate::gen::icosphere(3), 1.6, Placement::Optimal)];
    for (mesh, threshold, placement) in meshes {
        let options = BuildOptions { restrip: Some(threshold), placement, ..BuildOptions::default() };
        let sets = build(&mesh, &options, &mut |_| {}).unwrap().sets;
        let mut births: Vec<u32> = (0..sets.strip_count())
            .filter(|&s| sets.begin_slot[sets.begin_offsets[s] as usize] == END)
            .map(|s| sets.begin_level[sets.begin_offsets[s] as usize + 1])
            .collect();
        births.sort_unstable();
        births.dedup();
        assert!(births.len() >= 2, "{placement:?}: re-strip levels {births:?}");
        assert_eq!(sets.snapshots.restrip_levels(), &births[..], "{placement:?}: tables kept for every re-strip level");
        let last = sets.levels();
        let check = |c: &mut Cursor, to: u32, crossings: &mut usize| {
            *crossings += sets.snapshots.crossing(c.level(), to).is_some() as usize;
            move_checked(&sets, c, to, &format!("{placement:?}"));
        };
        let mut crossings = 0;
        let mut chain = sets.cursor(0);
        for &l in &births {
            let near = [l - 1, l, l.saturating_sub(6), l + 4, l.saturating_sub(2), l + 1];
            let far = [0, last, births[0], births[births.len() - 1] - 1];
            let stops: Vec<u32> = near.iter().chain(&far).map(|&x| x.min(last)).collect();
            for &from in &stops {
                for &to in &stops {
                    let mut c = sets.cursor(from);
                    check(&mut c, to, &mut crossings);
                }
            }
            for to in [l - 1, l, l - 1, l + 4, l.saturating_sub(6), l, l + 1, l.saturating_sub(2), 0, l, last, l - 1, l + 2] {
                check(&mut chain, to.min(last), &mut crossings);
            }
        }
        assert!(crossings > 60 * births.len(), "{placement:?}: {crossings} moves across re-strip levels");
    }
}

/// Moves `c` to `to` and checks the move: the buffer equals a fresh cursor's, the
/// changed strips ascend (once each), and every buffer index that changed lies in
/// a changed strip's reported range.
fn move_checked(sets: &Sets, c: &mut Cursor, to: u32, label: &str) {
    let from = c.level();
    let before = c.buffer().to_vec();
    let changed = c.set_level(to).to_vec();
    assert_eq!(c.buffer(), sets.cursor(to).buffer(), "{label}: {from} -> {to}");
    assert!(changed.windows(2).all(|w| w[0] < w[1]), "{label}: {from} -> {to}: changed strips ascending, once each");
    let mut written = vec![false; before.len()];
    for &s in &changed {
        written[c.changed_range(s as usize)].fill(true);
    }
    for (i, (&a, &z)) in before.iter().zip(c.buffer()).enumerate() {
        assert!(written[i] || a == z, "{label}: {from} -> {to}: index {i} changed unreported");
    }
}

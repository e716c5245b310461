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
    let dir = std::env::temp_dir().join(format!("stripkit-lod-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
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
    for ext in ["ply", "glb", "gltf", "obj", "off", "ply.gz", "stl"] {
        let path = dir.join(format!("level.{ext}"));
        level.write_file(&path, &crate::mesh::io::WriteOptions::default()).unwrap();
        let back = crate::mesh::io::read(&path).unwrap();
        assert_eq!(back.triangulate().tris.len(), triangles.len(), "{ext}");
        if ext != "stl" {
            // (STL welds its vertices anew: the check inside compared positions.)
            assert!(crate::strip::verify_triangles(&triangles, &back.triangulate().tris).ok(), "{ext}");
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

//! The fuzz targets' committed inputs, replayed on stable: every file under
//! `fuzz/regressions/<target>/` (minimized crash inputs and the seeds of fixed
//! defects) goes through the same check as its target, so a regression fails
//! `cargo test --workspace` without nightly or libFuzzer.

use std::path::{Path, PathBuf};
use stripkit_fuzzcheck::{seeds, TARGETS};

fn regressions() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/regressions")
}

#[test]
fn every_committed_regression_input_passes_its_target_check() {
    let root = regressions();
    let mut replayed = 0;
    for (target, check) in TARGETS {
        let dir = root.join(target);
        let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.unwrap().path())
            .collect();
        files.sort();
        assert!(!files.is_empty(), "{}: no inputs", dir.display());
        for file in files {
            let data = std::fs::read(&file).unwrap();
            let outcome = std::panic::catch_unwind(|| check(&data));
            assert!(
                outcome.is_ok(),
                "{} fails the {target} check",
                file.display()
            );
            replayed += 1;
        }
    }
    assert!(replayed >= 4, "{replayed} inputs");
}

/// Every target named by a folder under fuzz/regressions has a check here.
#[test]
fn every_regression_folder_names_a_target() {
    for entry in std::fs::read_dir(regressions()).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        assert!(
            TARGETS.iter().any(|(t, _)| *t == name),
            "fuzz/regressions/{name} is no target of this crate"
        );
    }
}

/// The seed scenes pass the scene check, and the committed defect inputs are the
/// ones the seed generator writes (so they stay in step with the builder).
#[test]
fn the_seed_scenes_pass_and_the_committed_defects_are_current() {
    for (name, bytes) in seeds::scenes() {
        stripkit_fuzzcheck::scene::check(&bytes);
        if name.starts_with("defect_") {
            let committed = std::fs::read(regressions().join("scene").join(&name)).unwrap();
            assert_eq!(
                committed, bytes,
                "fuzz/regressions/scene/{name} differs from seeds::defects()"
            );
        }
    }
}

/// The defects are refused as format errors (exit 2 in the CLI), and the seeds with
/// skins and morph targets read, strip and keep their targets.
#[test]
fn the_defect_seeds_are_format_errors_and_the_good_seeds_keep_their_targets() {
    use stripkit::io::{Format, ReadOptions};
    use stripkit::scene::Scene;
    let path = Path::new("seed.glb");
    for (name, bytes) in seeds::scenes() {
        let format = if name.ends_with(".glb") {
            Format::Glb
        } else {
            Format::Gltf
        };
        let read = Scene::from_bytes(path, format, &bytes, &ReadOptions::default());
        if name.starts_with("defect_") {
            assert!(
                matches!(read, Err(stripkit::Error::Format { .. })),
                "{name}: {:?}",
                read.map(|_| ())
            );
        } else {
            let scene = read.unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(
                scene
                    .primitives()
                    .iter()
                    .all(|p| p.mesh.triangle_count() > 0),
                "{name}"
            );
            if name.starts_with("skin_morph") {
                assert_eq!(scene.primitives()[0].targets, 2, "{name}");
            }
        }
    }
}

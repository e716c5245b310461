//! Target `scene`: bytes as a glTF document (GLB when they start with `glTF`, JSON
//! otherwise) read as a [`Scene`], stripped, written as GLB and as glTF, and read back.

use std::path::Path;
use stripkit::io::{Format, ReadOptions};
use stripkit::scene::{Scene, SceneOptions};
use stripkit::StripOptions;

/// Scenes with more triangles than this are read but not stripped (time per input).
pub const MAX_TRIANGLES: usize = 20_000;

/// The decode budget of a fuzzed scene: 64 MiB, so that one input stays under the
/// campaign's 1 GiB of memory whatever its accessors claim.
pub const MAX_DECODED_BYTES: u64 = 64 << 20;

/// The check: reading gives a scene or a bad-input error ([`crate::is_bad_input`]);
/// a small scene is stripped twice (restart groups with first-use reordering, then
/// plain stitched strips in the read order), each time Ok or a bad-input error (a
/// verification failure is a finding); a stripped scene writes as GLB and as glTF,
/// and both read back with the same primitives, modes and triangle counts as the
/// strips drew. Panics on a finding.
pub fn check(data: &[u8]) {
    // A folder that does not exist: an external buffer URI is an I/O error, never a
    // read of a file on the fuzzing machine.
    let (format, name) = if data.starts_with(b"glTF") {
        (Format::Glb, "/nonexistent-stripkit-fuzz/fuzz.glb")
    } else {
        (Format::Gltf, "/nonexistent-stripkit-fuzz/fuzz.gltf")
    };
    let path = Path::new(name);
    let options = ReadOptions::default().max_decoded_bytes(Some(MAX_DECODED_BYTES));
    let scene = match Scene::from_bytes(path, format, data, &options) {
        Ok(scene) => scene,
        Err(e) if crate::is_bad_input(&e) => return,
        Err(e) => panic!("reading the scene: {e}"),
    };
    let triangles: usize = scene
        .primitives()
        .iter()
        .map(|p| p.mesh.triangle_count())
        .sum();
    if triangles > MAX_TRIANGLES {
        return;
    }
    for scene_options in [
        SceneOptions::default(),
        SceneOptions::stitched().reorder(false),
    ] {
        let mut scene = scene.clone();
        match scene.strip(&StripOptions::default(), &scene_options) {
            Ok(_) => {}
            Err(e) if e.is_invalid() => continue,
            Err(e) => {
                panic!("stripping a scene of {triangles} triangles with {scene_options:?}: {e}")
            }
        }
        for out in [Format::Glb, Format::Gltf] {
            let bytes = match scene.to_bytes(out) {
                Ok(bytes) => bytes,
                Err(e) if crate::is_bad_input(&e) => continue,
                Err(e) => panic!("writing a stripped scene as {out:?} with {scene_options:?}: {e}"),
            };
            let back_path = Path::new(if out == Format::Glb {
                "/nonexistent-stripkit-fuzz/out.glb"
            } else {
                "/nonexistent-stripkit-fuzz/out.gltf"
            });
            let unlimited = ReadOptions::default().max_decoded_bytes(Some(u64::MAX));
            let back = Scene::from_bytes(back_path, out, &bytes, &unlimited)
                .unwrap_or_else(|e| panic!("the stripped scene written as {out:?} with {scene_options:?} does not read back: {e}"));
            let drawn = |s: &Scene| -> Vec<(usize, usize)> {
                s.primitives()
                    .iter()
                    .map(|p| (p.mesh_index, p.primitive_index))
                    .collect()
            };
            assert!(
                drawn(&back).len() >= drawn(&scene).len(),
                "the {out:?} written with {scene_options:?} reads back with {} triangle primitives of {}",
                drawn(&back).len(),
                drawn(&scene).len()
            );
        }
    }
}

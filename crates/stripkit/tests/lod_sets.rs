//! SETS multiresolution strips through the public API: every level of every model
//! checked against an independent replay, coherence against walks from scratch, the
//! `.sets` file round trip and its refusal of damaged files.

mod simplify_meshes;
mod support;

use simplify_meshes::{bumpy_sphere, grid, shuffled};
use std::path::Path;
use stripkit::lod::{self, BuildOptions, Built};
use stripkit::simplify::{simplify, Options, Placement, Target};
use stripkit::{gen, Algorithm, Mesh, SingleOptions, StripOptions};
use stripkit_testkit::XorShift64;

fn built(mesh: &Mesh, algorithm: Algorithm, placement: Placement) -> Built {
    let options = BuildOptions::default().strip(StripOptions::default().algorithm(algorithm)).placement(placement);
    lod::build(mesh, &options, &mut |_| {}).expect("builds")
}

/// Every level, exactly, plus 25 replays from scratch.
fn check_all(b: &Built) {
    let r = lod::check_levels(&b.sets, &b.mesh, &b.sequence, 1, 25).expect("every level matches the replay");
    assert_eq!(r.levels_checked, b.sets.levels() as usize + 1);
    assert!(r.replays >= 25);
}

fn meshes() -> Vec<(&'static str, Mesh)> {
    vec![
        ("bumpy sphere, shuffled", shuffled(&bumpy_sphere(3), 7)),
        ("height field with a border", grid(12, 9, |x, y| 0.2 * (4.0 * x).sin() * (3.0 * y).cos())),
        ("torus", gen::torus(24, 10, 1.0, 0.3)),
        ("two pieces", gen::disjoint_union(&[&gen::icosphere(2), &shuffled(&gen::icosphere(1), 3)])),
    ]
}

#[test]
fn every_level_draws_the_replay_with_its_winding() {
    for (name, mesh) in meshes() {
        for algorithm in [Algorithm::greedy(), Algorithm::cache(), Algorithm::batch()] {
            let b = built(&mesh, algorithm.clone(), Placement::Endpoint);
            assert!(b.sets.levels() > mesh.triangle_count() as u32 / 4, "{name}: simplified far");
            check_all(&b);
        }
    }
}

#[test]
fn optimal_placement_gives_each_collapse_a_vertex() {
    for (name, mesh) in meshes() {
        let b = built(&mesh, Algorithm::greedy(), Placement::Optimal);
        assert_eq!(
            b.sets.positions().len(),
            mesh.positions.len() + b.sets.levels() as usize,
            "{name}: one new vertex per collapse"
        );
        check_all(&b);
    }
}

#[test]
fn strips_that_change_the_mesh_and_quad_strips_work_too() {
    // Single strips add Steiner vertices and swap edges: the model is built on the
    // mesh the strips draw.
    let mesh = shuffled(&bumpy_sphere(2), 11);
    let b = built(&mesh, Algorithm::Single(SingleOptions::default()), Placement::Endpoint);
    let finest = b.sets.strips_at(0);
    assert_eq!(finest.iter().filter(|s| !s.is_empty()).count(), 1, "one strip for a closed sphere");
    check_all(&b);
    // QSTRIP picks each quad's diagonal: the model uses the triangles it picked.
    let quads = gen::torus_quads(16, 8, 1.0, 0.35);
    let b = built(&quads, Algorithm::qstrip(), Placement::Endpoint);
    check_all(&b);
}

#[test]
fn coherent_levels_equal_walks_from_scratch() {
    let b = built(&shuffled(&bumpy_sphere(3), 5), Algorithm::greedy(), Placement::Endpoint);
    let sets = &b.sets;
    let mut cursor = sets.cursor(0);
    let mut rng = XorShift64(0x2545F4914F6CDD1D);
    let mut previous = cursor.strips();
    for step in 0..300 {
        let x = rng.next();
        // Small steps, big jumps, and staying put.
        let level = match step % 3 {
            0 => (x % (sets.levels() as u64 + 1)) as u32,
            1 => (cursor.level() + (x % 5) as u32).min(sets.levels()),
            _ => cursor.level(),
        };
        let changed = cursor.set_level(level).to_vec();
        let now = sets.strips_at(level);
        assert_eq!(cursor.strips(), now, "level {level}");
        if changed.is_empty() {
            assert_eq!(now, previous, "nothing re-walked, nothing changed");
        }
        // The padded buffer holds each strip in its range, then restarts only.
        for s in 0..sets.strip_count() {
            let range = cursor.strip_range(s);
            let strip = cursor.strip(s);
            assert_eq!(&cursor.buffer()[range.start..range.start + strip.len()], strip);
            assert!(cursor.buffer()[range.start + strip.len()..range.end].iter().all(|&i| i == u32::MAX));
        }
        let mut tight = Vec::new();
        cursor.compact(u32::MAX, &mut tight);
        assert_eq!(stripkit::decode_restart(&tight, u32::MAX), now);
        previous = now;
    }
}

#[test]
fn ratio_levels_stop_where_simplify_stops() {
    let mesh = shuffled(&bumpy_sphere(3), 2);
    let b = built(&mesh, Algorithm::greedy(), Placement::Endpoint);
    for ratio in [0.5, 0.1, 0.013] {
        let s = simplify(&mesh, &Options::default().target(Target::Ratio(ratio)), &mut |_| {}).unwrap();
        let level = b.sets.level_for_ratio(ratio);
        assert_eq!(level as usize, s.sequence.len(), "ratio {ratio}");
        assert_eq!(b.sets.triangles_at(level) as usize, s.triangles_out());
        let drawn = stripkit::decode(&b.sets.strips_at(level));
        let v = stripkit::verify_triangles(&s.mesh.triangulate().tris, &drawn);
        assert!(v.ok(), "ratio {ratio}: {v}");
    }
    assert_eq!(b.sets.level_for_triangles(0), b.sets.levels());
}

#[test]
fn strips_get_shorter_with_the_mesh() {
    let b = built(&bumpy_sphere(4), Algorithm::greedy(), Placement::Endpoint);
    let sets = &b.sets;
    // Renaming alone would keep every level-0 slot; the removals keep the windows'
    // triangles (bumpy sphere, 2,048 triangles: 79% of the slots at 50%, 33% at 10%,
    // 1.63 and 3.39 indices per triangle).
    for (ratio, slots, ipt) in [(0.5, 0.85, 2.0), (0.1, 0.45, 4.0)] {
        let level = sets.level_for_ratio(ratio);
        let strips = sets.strips_at(level);
        let kept = strips.index_count() as f64 / sets.slot_count() as f64;
        let per_triangle = (strips.index_count() + strips.len()) as f64 / sets.triangles_at(level) as f64;
        assert!(kept < slots, "ratio {ratio}: {kept:.3} of the slots kept");
        assert!(per_triangle < ipt, "ratio {ratio}: {per_triangle:.3} indices per triangle");
    }
}

#[test]
fn sets_files_round_trip_and_refuse_damage() {
    for placement in [Placement::Endpoint, Placement::Optimal] {
        let b = built(&shuffled(&bumpy_sphere(2), 9), Algorithm::greedy(), placement);
        let bytes = b.sets.to_bytes();
        let path = Path::new("model.sets");
        let back = lod::Sets::from_bytes(path, &bytes).expect("reads back");
        assert_eq!(back, b.sets);
        // Truncated anywhere.
        for cut in [0, 7, 8, 30, 60, bytes.len() / 2, bytes.len() - 5, bytes.len() - 1] {
            let e = lod::Sets::from_bytes(path, &bytes[..cut]).expect_err("truncated");
            assert!(matches!(e, stripkit::Error::Format { .. }), "{e}");
        }
        // A flipped bit fails the checksum.
        let mut bad = bytes.clone();
        bad[bytes.len() / 3] ^= 0x10;
        let e = lod::Sets::from_bytes(path, &bad).unwrap_err().to_string();
        assert!(e.contains("checksum"), "{e}");
        // Wrong counts, with the checksum made right: refused by the structure checks.
        for field in 0..10 {
            for value in [0u32, 1, 7, u32::MAX / 2, u32::MAX] {
                let mut bad = bytes.clone();
                bad[8 + 4 * field..12 + 4 * field].copy_from_slice(&value.to_le_bytes());
                if bad == bytes {
                    continue;
                }
                reseal(&mut bad);
                assert!(lod::Sets::from_bytes(path, &bad).is_err(), "header field {field} = {value}");
            }
        }
        // Random damage behind a valid checksum: an error or a model, never a panic,
        // and any model read walks every level safely.
        let mut rng = XorShift64(0x9E3779B97F4A7C15);
        for _ in 0..400 {
            let mut bad = bytes.clone();
            for _ in 0..3 {
                let x = rng.next();
                let at = 8 + (x as usize >> 8) % (bad.len() - 12);
                bad[at] = (x & 0xff) as u8;
            }
            reseal(&mut bad);
            if let Ok(s) = lod::Sets::from_bytes(path, &bad) {
                let mut c = s.cursor(s.levels());
                c.set_level(0);
                let _ = s.strips_at(s.levels() / 2);
            }
        }
    }
}

/// Rewrites the trailing CRC-32 over the bytes before it.
fn reseal(bytes: &mut [u8]) {
    let n = bytes.len() - 4;
    let mut crc = flate2::Crc::new();
    crc.update(&bytes[..n]);
    bytes[n..].copy_from_slice(&crc.sum().to_le_bytes());
}

#[test]
fn research_models_at_every_level() {
    let Some(mesh) = support::model("bunny_small.off") else { return };
    let b = built(&mesh, Algorithm::greedy(), Placement::Endpoint);
    check_all(&b);
}

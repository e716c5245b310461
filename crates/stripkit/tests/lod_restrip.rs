//! Re-stripped SETS models (issue #35): new greedy strips where the kept ones decay,
//! every level still exact, the strips' indices per triangle held down at every
//! level, and the `.sets` file's version 3 with the old versions still read.

mod simplify_meshes;
mod support;

use simplify_meshes::{bumpy_sphere, grid, shuffled};
use std::path::Path;
use stripkit::lod::{self, BuildOptions, Built};
use stripkit::simplify::Placement;
use stripkit::{gen, Mesh};

fn built(mesh: &Mesh, restrip: Option<f64>, placement: Placement) -> Built {
    lod::build(mesh, &BuildOptions::default().placement(placement).restrip(restrip), &mut |_| {}).expect("builds")
}

/// Restart-buffer indices per triangle at `level`.
fn per_triangle(b: &Built, level: u32) -> f64 {
    b.sets.strips_at(level).restart_len() as f64 / b.sets.triangles_at(level) as f64
}

#[test]
fn every_level_exact_with_new_strips() {
    let meshes = [
        ("bumpy sphere, shuffled", shuffled(&bumpy_sphere(3), 7)),
        ("height field with a border", grid(12, 9, |x, y| 0.2 * (4.0 * x).sin() * (3.0 * y).cos())),
        ("torus", gen::torus(24, 10, 1.0, 0.3)),
        ("two pieces", gen::disjoint_union(&[&gen::icosphere(2), &shuffled(&gen::icosphere(1), 3)])),
    ];
    for (name, mesh) in meshes {
        for placement in [Placement::Endpoint, Placement::Optimal] {
            let b = built(&mesh, Some(1.5), placement);
            assert!(b.sets.restripped_strips() > 0, "{name}: re-stripped");
            let r = lod::check_levels(&b.sets, &b.mesh, &b.sequence, 1, 25).expect("every level matches the replay");
            assert_eq!(r.levels_checked, b.sets.levels() as usize + 1, "{name}");
            // Coherent moves agree with walks from scratch.
            let mut c = b.sets.cursor(0);
            for level in [b.sets.levels(), 0, b.sets.levels() / 3, b.sets.levels() / 2, 1, b.sets.levels() / 3] {
                c.set_level(level);
                assert_eq!(c.strips(), b.sets.strips_at(level), "{name}: level {level}");
            }
        }
    }
}

/// Bumpy sphere of 8,192 triangles, shuffled: the kept strips take 1.41 to 3.91
/// indices per triangle at 50% to 2%; re-stripped past 1.5, at most 1.6 at every
/// level down to 2% (64 triangles left at 1%, where fresh greedy strips themselves
/// take more).
#[test]
fn restripped_strips_stay_short() {
    let mesh = shuffled(&bumpy_sphere(5), 3);
    let kept = built(&mesh, None, Placement::Endpoint);
    let b = built(&mesh, Some(1.5), Placement::Endpoint);
    assert_eq!(b.sets.triangles_at(0), kept.sets.triangles_at(0));
    let floor = b.sets.level_for_ratio(0.02);
    let mut worst: f64 = 0.0;
    let mut cursor = b.sets.cursor(0);
    for level in 0..=floor {
        cursor.set_level(level);
        let len = cursor.strips().restart_len();
        worst = worst.max(len as f64 / b.sets.triangles_at(level) as f64);
    }
    assert!(worst <= 1.6, "worst level down to 2%: {worst:.3}");
    for (ratio, most_kept) in [(0.1, 2.5), (0.02, 3.0)] {
        let level = b.sets.level_for_ratio(ratio);
        assert!(per_triangle(&kept, level) > most_kept, "kept strips at {ratio}: {:.3}", per_triangle(&kept, level));
        assert!(per_triangle(&b, level) <= 1.6, "re-stripped at {ratio}: {:.3}", per_triangle(&b, level));
    }
}

#[test]
fn version_3_round_trips_and_old_versions_still_read() {
    let mesh = shuffled(&bumpy_sphere(3), 9);
    let path = Path::new("model.sets");
    let version = |bytes: &[u8]| u32::from_le_bytes(bytes[8..12].try_into().unwrap());
    // Without re-stripping the file is version 1 as before, and reads back.
    let old = built(&mesh, None, Placement::Endpoint);
    let bytes = old.sets.to_bytes();
    assert_eq!(version(&bytes), 1);
    assert_eq!(lod::Sets::from_bytes(path, &bytes).unwrap(), old.sets);
    for placement in [Placement::Endpoint, Placement::Optimal] {
        let b = built(&mesh, Some(1.5), placement);
        let bytes = b.sets.to_bytes();
        assert_eq!(version(&bytes), 3);
        let back = lod::Sets::from_bytes(path, &bytes).expect("reads back");
        assert_eq!(back, b.sets);
        assert_eq!(back.restripped_strips(), b.sets.restripped_strips());
        // Damage behind a valid checksum: an error or a model, never a panic.
        let mut rng = stripkit_testkit::XorShift64(0x9E3779B97F4A7C15);
        for _ in 0..300 {
            let bad = support::damaged_with_valid_checksum(&bytes, rng.next());
            if let Ok(s) = lod::Sets::from_bytes(path, &bad) {
                let mut c = s.cursor(s.levels());
                c.set_level(0);
                let _ = s.strips_at(s.levels() / 2);
            }
        }
    }
}

/// Version 3 codes a slot's vertex by where it occurred beside the strip before and
/// packs the version counts in two bits: re-stripped at 1.6, the shuffled bumpy
/// sphere of 8,192 triangles takes 1.060x the kept model's version-1 bytes
/// (vertex numbers shuffled, so no help from the input's order).
#[test]
fn version_3_stays_near_the_kept_size() {
    let mesh = shuffled(&bumpy_sphere(5), 5);
    let kept = built(&mesh, None, Placement::Endpoint).sets.to_bytes().len();
    let b = built(&mesh, Some(1.6), Placement::Endpoint);
    assert!(b.sets.restripped_strips() > 0);
    let bytes = b.sets.to_bytes();
    assert_eq!(lod::Sets::from_bytes(Path::new("model.sets"), &bytes).unwrap(), b.sets);
    let ratio = bytes.len() as f64 / kept as f64;
    println!("kept {kept} bytes, re-stripped {} bytes: {ratio:.3}x", bytes.len());
    assert!(ratio <= 1.10, "{ratio:.3}x the kept model's bytes");
}

/// Moves near and far, on kept and re-stripped strips: the cursor's strips equal
/// walks from scratch after every move, and nothing outside the ranges it reports
/// changed ([`lod::Cursor::changed_range`]) moved in the buffer.
#[test]
fn partial_rewalks_equal_walks_from_scratch() {
    let mesh = shuffled(&bumpy_sphere(4), 5);
    for restrip in [None, Some(1.5)] {
        let b = built(&mesh, restrip, Placement::Endpoint);
        let n = b.sets.levels() as u64;
        let mut rng = stripkit_testkit::XorShift64(0x2545F4914F6CDD1D);
        let mut c = b.sets.cursor(0);
        let mut level = 0u64;
        let mut partial = 0;
        for step in 0..600 {
            let next = match step % 4 {
                0 => rng.next() % (n + 1),
                1 => (level + 1 + rng.next() % 3).min(n),
                2 => level.saturating_sub(1 + rng.next() % 3),
                _ => (level + n / 100).min(n),
            };
            let before = c.buffer().to_vec();
            let changed = c.set_level(next as u32).to_vec();
            assert_eq!(c.strips(), b.sets.strips_at(next as u32), "{restrip:?}: level {next}");
            let mut written = vec![false; before.len()];
            for &s in &changed {
                let r = c.changed_range(s as usize);
                assert!(r.start >= c.strip_range(s as usize).start && r.end <= c.strip_range(s as usize).end);
                partial += (r.start > c.strip_range(s as usize).start) as usize;
                written[r].fill(true);
            }
            for (i, (&a, &z)) in before.iter().zip(c.buffer()).enumerate() {
                assert!(written[i] || a == z, "{restrip:?}: level {level} -> {next}, buffer slot {i} moved");
            }
            level = next;
        }
        assert!(partial > 100, "{restrip:?}: {partial} strips re-walked from a later slot");
    }
}

//! Level-of-detail strips for deforming meshes through the public API: a procedural
//! animation written as frame files, every model checked at every level, the cursor
//! against fresh walks over random (frame, level) moves, the quality guarantee
//! against the reference pose's sequence, the `.lodseq` file and its refusals.

mod support;

use std::path::{Path, PathBuf};
use stripkit::lod::{self, LevelSpec, LodSeq, SeqOptions};
use stripkit::{gen, Mesh};
use stripkit_testkit::XorShift64;

/// A torus that bends and swells over `frames` frames, written as OBJ files (and a
/// reference pose) into a fresh folder.
fn animation(name: &str, frames: usize) -> PathBuf {
    let dir = stripkit_testkit::fresh_scratch_dir(&format!("lodseq-{name}"));
    let base = gen::torus(28, 10, 1.0, 0.3);
    let pose = |t: f32| -> Mesh {
        let mut m = base.clone();
        for p in m.positions.iter_mut() {
            // Bend around the y axis by an angle growing with x, and swell one side.
            let a = t * p[0] * 0.9;
            let (s, c) = a.sin_cos();
            let (x, z) = (p[0], p[2] * (1.0 + 0.4 * t * (p[1] > 0.0) as i32 as f32));
            *p = [c * x - s * z, p[1], s * x + c * z];
        }
        m
    };
    for f in 0..frames {
        let t = f as f32 / (frames - 1).max(1) as f32;
        stripkit::io::write(dir.join(format!("{name}-{f:02}.obj")), &pose(t), None).unwrap();
    }
    stripkit::io::write(dir.join(format!("{name}-reference.obj")), &pose(0.5), None).unwrap();
    dir
}

fn options() -> SeqOptions {
    SeqOptions::default().samples(800)
}

#[test]
fn every_model_draws_its_replay_at_every_level() {
    let dir = animation("levels", 6);
    let frames = lod::read_frames(&dir, &Default::default()).unwrap();
    assert_eq!(frames.positions.len(), 6);
    assert!(frames.reference.is_some());
    let b = lod::build_seq(&frames, &options(), &mut |_| {}).unwrap();
    assert_eq!(b.seq.frame_count(), 6);
    assert_eq!(b.sequences.len(), b.seq.models().len());
    let mesh = Mesh::from_triangles(frames.positions[0].clone(), &b.triangles);
    for (m, (sets, sequence)) in b.seq.models().iter().zip(&b.sequences).enumerate() {
        let r = lod::check_levels(sets, &mesh, sequence, 1, 10).unwrap_or_else(|e| panic!("model {m}: {e}"));
        assert_eq!(r.levels_checked, sets.levels() as usize + 1);
        // All models lay their strips out alike.
        assert_eq!(sets.slot_count(), b.seq.models()[0].slot_count());
    }
    // (a) is never worse than (b), in all four figures: every frame falls back to
    // the reference pose's sequence.
    for q in &b.report.quality {
        for r in 0..2 {
            assert!(q.chosen.hausdorff[r] <= q.reference.hausdorff[r], "{}: {q:?}", q.frame);
            assert!(q.chosen.rms[r] <= q.reference.rms[r], "{}: {q:?}", q.frame);
        }
    }
}

#[test]
fn the_cursor_follows_frames_and_levels() {
    let dir = animation("cursor", 5);
    let frames = lod::read_frames(&dir, &Default::default()).unwrap();
    let b = lod::build_seq(&frames, &options().tolerance(1.0), &mut |_| {}).unwrap();
    let seq = &b.seq;
    assert!(seq.models().len() >= 2, "frames with different sequences: {:?}", b.report.sequences);
    let mut cursor = seq.cursor(0, LevelSpec::Level(0));
    let mut previous = cursor.buffer().to_vec();
    let mut rng = XorShift64(0x9E3779B97F4A7C15);
    for step in 0..200 {
        let x = rng.next();
        let frame = (x % 5) as usize;
        let spec = match step % 4 {
            0 => LevelSpec::Level((x >> 8) as u32 % 700),
            1 => LevelSpec::Ratio(((x >> 16) % 100) as f64 / 100.0),
            2 => LevelSpec::Triangles((x >> 24) % 600),
            _ => LevelSpec::Level(cursor.level()),
        };
        let changed = cursor.set(frame, spec).to_vec();
        let model = &seq.models()[seq.model_of(frame)];
        let level = seq.level(frame, spec);
        assert_eq!(cursor.level(), level);
        let fresh = model.cursor(level);
        assert_eq!(cursor.buffer(), fresh.buffer(), "step {step}: frame {frame}, {spec:?}");
        assert_eq!(cursor.strips(), model.strips_at(level));
        // Exactly the strips whose range differs are reported.
        for s in 0..model.strip_count() {
            let r = fresh.strip_range(s);
            let differs = previous[r.clone()] != cursor.buffer()[r];
            assert_eq!(differs, changed.contains(&(s as u32)), "step {step}: strip {s}");
        }
        previous = cursor.buffer().to_vec();
    }
}

#[test]
fn morphing_between_key_frames() {
    let dir = animation("morph", 3);
    let frames = lod::read_frames(&dir, &Default::default()).unwrap();
    let b = lod::build_seq(&frames, &options(), &mut |_| {}).unwrap();
    let seq = &b.seq;
    let m = seq.morph(1.25);
    for (v, p) in m.iter().enumerate() {
        for (d, &x) in p.iter().enumerate() {
            let want = 0.75 * seq.positions(1)[v][d] + 0.25 * seq.positions(2)[v][d];
            assert!((x - want).abs() < 1e-6);
        }
    }
    assert_eq!(seq.morph(2.0), seq.positions(2));
    assert_eq!(seq.morph(9.0), seq.positions(2), "clamped");
    assert_eq!(seq.nearest_frame(1.25), 1);
    assert_eq!(seq.nearest_frame(1.5), 2);
    assert_eq!(seq.nearest_frame(-3.0), 0);
}

#[test]
fn frames_must_share_their_faces() {
    let dir = animation("faces", 4);
    // A frame with other faces: named in the error.
    let mut other = gen::torus(28, 10, 1.0, 0.3);
    other.face_indices.swap(0, 1);
    stripkit::io::write(dir.join("faces-02.obj"), &other, None).unwrap();
    let e = lod::read_frames(&dir, &Default::default()).unwrap_err().to_string();
    assert!(e.contains("faces-02.obj") && e.contains("face 0"), "{e}");
    // Another vertex count.
    stripkit::io::write(dir.join("faces-02.obj"), &gen::torus(20, 10, 1.0, 0.3), None).unwrap();
    let e = lod::read_frames(&dir, &Default::default()).unwrap_err().to_string();
    assert!(e.contains("faces-02.obj") && e.contains("vertices"), "{e}");
    // Nothing to read.
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    assert!(lod::read_frames(&empty, &Default::default()).is_err());
    assert!(lod::read_frames(Path::new("/no/such/folder"), &Default::default()).is_err());
}

#[test]
fn lodseq_files_round_trip_and_refuse_damage() {
    let dir = animation("file", 4);
    let frames = lod::read_frames(&dir, &Default::default()).unwrap();
    for bits in [None, Some(12)] {
        let b = lod::build_seq(&frames, &options().position_bits(bits), &mut |_| {}).unwrap();
        let bytes = b.seq.to_bytes();
        let path = Path::new("anim.lodseq");
        assert_eq!(LodSeq::from_bytes(path, &bytes).unwrap(), b.seq);
        for cut in [0, 8, 20, bytes.len() / 3, bytes.len() - 1] {
            assert!(LodSeq::from_bytes(path, &bytes[..cut]).is_err(), "cut at {cut}");
        }
        let mut bad = bytes.clone();
        bad[bytes.len() / 2] ^= 4;
        assert!(LodSeq::from_bytes(path, &bad).unwrap_err().to_string().contains("checksum"));
        // A .sets is not a .lodseq, and the other way round.
        assert!(LodSeq::from_bytes(path, &b.seq.models()[0].to_bytes()).is_err());
        assert!(lod::Sets::from_bytes(path, &bytes).is_err());
        // Damage behind a valid checksum: an error or a sequence, never a panic.
        let mut rng = XorShift64(0x2545F4914F6CDD1D);
        for _ in 0..300 {
            let bad = support::damaged_with_valid_checksum(&bytes, rng.next());
            if let Ok(s) = LodSeq::from_bytes(path, &bad) {
                let mut c = s.cursor(0, LevelSpec::Ratio(0.5));
                c.set(s.frame_count() - 1, LevelSpec::Level(u32::MAX));
            }
        }
    }
}

#[test]
fn quantized_positions_round_trip_exactly() {
    let dir = animation("quantized", 4);
    let frames = lod::read_frames(&dir, &Default::default()).unwrap();
    let exact = lod::build_seq(&frames, &options(), &mut |_| {}).unwrap();
    for bits in [8, 12, 16, 20] {
        let b = lod::build_seq(&frames, &options().position_bits(Some(bits)), &mut |_| {}).unwrap();
        let bytes = b.seq.to_bytes();
        let back = LodSeq::from_bytes(Path::new("q.lodseq"), &bytes).unwrap();
        assert_eq!(back, b.seq, "{bits} bits: the file holds exactly the quantized positions");
        // Within half a grid step of the input (the torus spans about 2.6 units).
        let step = 2.7 / ((1u64 << bits) - 1) as f32;
        for f in 0..frames.positions.len() {
            for (p, q) in frames.positions[f].iter().zip(b.seq.positions(f)) {
                for d in 0..3 {
                    assert!((p[d] - q[d]).abs() <= step, "{bits} bits: {p:?} -> {q:?}");
                }
            }
        }
        assert!(bytes.len() < exact.seq.to_bytes().len(), "{bits} bits: smaller than exact positions");
    }
    let e = lod::build_seq(&frames, &options().position_bits(Some(4)), &mut |_| {});
    assert!(e.is_err());
}

#[test]
fn research_sequence_cat() {
    let Some(dir) = support::models_dir().map(|d| d.join("sequences/cat-poses")) else { return };
    if !dir.is_dir() {
        eprintln!("skipped: {} is absent", dir.display());
        return;
    }
    let frames = lod::read_frames(&dir, &Default::default()).unwrap();
    assert_eq!(frames.positions.len(), 9);
    let b = lod::build_seq(&frames, &SeqOptions::default().samples(1000), &mut |_| {}).unwrap();
    let mesh = Mesh::from_triangles(frames.positions[0].clone(), &b.triangles);
    for (sets, sequence) in b.seq.models().iter().zip(&b.sequences) {
        lod::check_levels(sets, &mesh, sequence, 1, 5).unwrap();
    }
}

/// A quantized file whose grid (origin 3e38, a step of 1e35) runs past the largest
/// float: refused on reading, naming the file and the grid's offset, before any
/// position turns infinite (it used to fail later as "vertex 0 has a NaN or infinite
/// coordinate", naming nothing).
#[test]
fn a_grid_past_the_largest_float_names_the_file() {
    let dir = animation("grid", 2);
    let frames = lod::read_frames(&dir, &Default::default()).unwrap();
    let b = lod::build_seq(&frames, &options().position_bits(Some(12)), &mut |_| {}).unwrap();
    let mut bytes = b.seq.to_bytes();
    // The grid follows the 28-byte header and the frame names (length, name, model).
    let mut at = 28;
    for _ in 0..b.seq.frame_count() {
        at += 1 + bytes[at] as usize; // names are short: one-byte lengths
        at += 1; // model index
    }
    let path = Path::new("grid.lodseq");
    let lo = f32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
    assert!(
        lo.is_finite() && lo.abs() < 10.0,
        "the grid's origin is at byte {at}: {lo}"
    );
    bytes[at..at + 4].copy_from_slice(&3e38f32.to_le_bytes());
    bytes[at + 12..at + 16].copy_from_slice(&1e35f32.to_le_bytes());
    let n = bytes.len() - 4;
    let mut crc = flate2::Crc::new();
    crc.update(&bytes[..n]);
    bytes[n..].copy_from_slice(&crc.sum().to_le_bytes());
    match LodSeq::from_bytes(path, &bytes) {
        Err(stripkit::Error::Format {
            path: p,
            at: where_,
            what,
        }) => {
            assert_eq!(p, path);
            assert_eq!(where_, format!("byte {at}"));
            assert!(
                what.contains("grid") && what.contains("not finite"),
                "{what}"
            );
        }
        other => panic!("expected a format error, got {other:?}"),
    }
}

//! The parallel and whole-record paths of reading, welding and checking (issue #32):
//! binary PLY read record by record and read whole agree with the text reading of the
//! same mesh, and a damaged binary file gets the value-by-value reader's message; the
//! weld map and the check give the same results at 1 and 4 threads as a plain
//! reference, on shuffled inputs larger than one part of the parallel cut.

use std::collections::HashMap;
use std::path::Path;
use stripkit::io::{read_bytes, write_bytes, Format, WriteOptions};
use stripkit::parallel::Threads;
use stripkit::{gen, verify, verify_with, weld_map, Attribute, Mesh, Scalar, StripSet};
use stripkit_testkit::XorShift64;

/// An icosphere with a normal, a texture coordinate and an 8-bit colour per vertex.
fn sphere_with_attributes(level: u32) -> Mesh {
    let mut mesh = gen::icosphere(level);
    let n = mesh.vertex_count();
    let normals: Vec<f32> = mesh.positions.iter().flatten().copied().collect();
    let uv: Vec<f32> = (0..n).flat_map(|v| [(v % 7) as f32 / 8.0, (v % 5) as f32 / 4.0]).collect();
    mesh.attributes.push(Attribute::from_f32("NORMAL", 3, &normals));
    mesh.attributes.push(Attribute::from_f32("TEXCOORD_0", 2, &uv));
    let colour: Vec<u8> = (0..n).flat_map(|v| [(v % 251) as u8, (v % 13) as u8, 200]).collect();
    mesh.attributes.push(Attribute { name: "COLOR_0".into(), scalar: Scalar::U8, components: 3, normalized: true, data: colour });
    mesh
}

#[test]
fn binary_ply_read_whole_matches_the_text_reading() {
    let mesh = sphere_with_attributes(4);
    let path = Path::new("mem.ply");
    let binary = write_bytes(Format::Ply, &mesh, None, &WriteOptions::default()).unwrap();
    let text = write_bytes(Format::Ply, &mesh, None, &WriteOptions::default().ply_ascii(true)).unwrap();
    let from_binary = read_bytes(path, Format::Ply, &binary).unwrap();
    let from_text = read_bytes(path, Format::Ply, &text).unwrap();
    assert_eq!(from_binary.vertex_count(), 2562);
    assert_eq!(from_binary.face_count(), 5120);
    assert_eq!(from_binary.positions, mesh.positions);
    assert_eq!(from_binary.face_indices, mesh.face_indices);
    assert_eq!(from_binary.attributes.len(), 3);
    // Text and binary readings agree value for value (texture v within one rounding
    // of its flip, as the writer's documentation says: compared as read).
    assert_eq!(from_binary.positions, from_text.positions);
    assert_eq!(from_binary.face_offsets, from_text.face_offsets);
    assert_eq!(from_binary.face_indices, from_text.face_indices);
    assert_eq!(from_binary.attributes, from_text.attributes);

    // Big-endian: the same file with every value's bytes reversed.
    let header_end = binary.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    let header = String::from_utf8(binary[..header_end].to_vec()).unwrap();
    let mut big = header.replace("binary_little_endian", "binary_big_endian").into_bytes();
    let body = &binary[header_end..];
    let vertex_record = 12 + 12 + 8 + 3;
    for rec in body[..2562 * vertex_record].chunks(vertex_record) {
        for (start, len) in [(0, 4), (4, 4), (8, 4), (12, 4), (16, 4), (20, 4), (24, 4), (28, 4), (32, 1), (33, 1), (34, 1)] {
            big.extend(rec[start..start + len].iter().rev());
        }
    }
    for face in body[2562 * vertex_record..].chunks(13) {
        big.push(face[0]);
        for k in 0..3 {
            big.extend(face[1 + 4 * k..5 + 4 * k].iter().rev());
        }
    }
    let from_big = read_bytes(path, Format::Ply, &big).unwrap();
    assert_eq!(from_big, from_binary);
}

#[test]
fn a_damaged_binary_ply_gets_the_record_readers_message() {
    let mesh = gen::icosphere(2);
    let path = Path::new("mem.ply");
    let bytes = write_bytes(Format::Ply, &mesh, None, &WriteOptions::default()).unwrap();
    let body = bytes.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    let faces = body + 12 * mesh.vertex_count();
    let message = |data: &[u8]| read_bytes(path, Format::Ply, data).unwrap_err().to_string();

    // Face 7's second index out of range.
    let mut bad = bytes.clone();
    bad[faces + 7 * 13 + 5..faces + 7 * 13 + 9].copy_from_slice(&5000i32.to_le_bytes());
    let m = message(&bad);
    assert!(m.contains("face 7 refers to vertex 5000 but the file has 162 vertices"), "{m}");
    // A face of two vertices.
    let mut bad = bytes.clone();
    bad[faces + 3 * 13] = 2;
    let m = message(&bad);
    assert!(m.contains("face 3 has 2 vertices, needs at least 3"), "{m}");
    // A NaN coordinate in vertex 10.
    let mut bad = bytes.clone();
    bad[body + 10 * 12 + 4..body + 10 * 12 + 8].copy_from_slice(&f32::NAN.to_le_bytes());
    let m = message(&bad);
    assert!(m.contains("vertex 10") && m.contains("NaN or infinite"), "{m}");
    // Cut inside the last face.
    let m = message(&bytes[..bytes.len() - 2]);
    assert!(m.contains("truncated"), "{m}");
}

/// The weld map by a hash map of keys, as it was first written: the reference.
fn reference_weld(mesh: &Mesh) -> (Vec<u32>, usize) {
    let mut first: HashMap<Vec<u8>, u32> = HashMap::new();
    let mut merged = 0;
    let map = (0..mesh.vertex_count())
        .map(|v| {
            let mut key: Vec<u8> = mesh.positions[v].iter().flat_map(|x| x.to_bits().to_le_bytes()).collect();
            for a in &mesh.attributes {
                key.extend_from_slice(a.bytes(v));
            }
            let rep = *first.entry(key).or_insert(v as u32);
            merged += usize::from(rep != v as u32);
            rep
        })
        .collect();
    (map, merged)
}

#[test]
fn the_weld_map_is_the_reference_at_1_and_4_threads() {
    // An icosphere(5) unindexed and shuffled: 61,440 corners over 10,242 vertices,
    // with a texture coordinate that splits some of them apart.
    let sphere = gen::icosphere(5);
    let mut tris = sphere.triangulate().tris;
    XorShift64(7).shuffle(&mut tris);
    let corners: Vec<u32> = tris.iter().flatten().copied().collect();
    let mut mesh = Mesh::from_triangles(
        corners.iter().map(|&v| sphere.positions[v as usize]).collect(),
        &(0..tris.len() as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect::<Vec<_>>(),
    );
    let uv: Vec<f32> = corners.iter().enumerate().flat_map(|(k, &v)| [(v % 3) as f32, (k % 2 * (v as usize % 2)) as f32]).collect();
    mesh.attributes.push(Attribute::from_f32("TEXCOORD_0", 2, &uv));
    let want = reference_weld(&mesh);
    assert!(want.1 > 40_000, "{}", want.1);
    assert_eq!(weld_map(&mesh), want);
    assert_eq!(stripkit::weld_map_with(&mesh, Threads::new(4)), want);
}

#[test]
fn the_check_counts_the_same_at_1_and_4_threads() {
    // 150,000 one-triangle strips (more than one part of every cut), shuffled, with
    // some triangles lost, added, flipped and made degenerate.
    let mut rng = XorShift64(11);
    let mut tris: Vec<[u32; 3]> = (0..150_000u32).map(|t| [t, t + 1, t + 2 + (t % 5)]).collect();
    rng.shuffle(&mut tris);
    let mut strips: Vec<Vec<u32>> = tris.iter().map(|t| t.to_vec()).collect();
    for k in 0..40 {
        strips[k * 11] = vec![9_000_000 + k as u32, 1, 2]; // lost and added
        let s = &mut strips[k * 13 + 5];
        s.swap(0, 1); // flipped
    }
    strips.push(vec![4, 4, 5]);
    let set = StripSet::from_strips(&strips);
    let serial = verify(&tris, &set);
    assert!(serial.lost > 0 && serial.added > 0 && serial.flipped > 0, "{serial:?}");
    assert_eq!(verify_with(&tris, &set, Threads::new(4)), serial);
    assert_eq!(verify_with(&tris, &set, Threads::new(3)), serial);
    assert_eq!(stripkit::decode_with(&set, Threads::new(4)), stripkit::decode(&set));
}

/// The check's counts by hashing: the multiset difference of canonical triangles, a
/// lost one matched with an added reversed one being a flip.
fn reference_check(expected: &[[u32; 3]], got: &[[u32; 3]]) -> (usize, usize, usize) {
    let canonical = |t: [u32; 3]| {
        let r = (0..3).min_by_key(|&i| t[i]).unwrap();
        [t[r], t[(r + 1) % 3], t[(r + 2) % 3]]
    };
    let mut diff: HashMap<[u32; 3], i64> = HashMap::new();
    for t in expected.iter().filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) {
        *diff.entry(canonical(*t)).or_default() += 1;
    }
    for t in got.iter().filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) {
        *diff.entry(canonical(*t)).or_default() -= 1;
    }
    let lost: i64 = diff.values().filter(|d| **d > 0).sum();
    let added: i64 = -diff.values().filter(|d| **d < 0).sum::<i64>();
    let flipped: i64 = diff
        .iter()
        .filter(|(_, d)| **d > 0)
        .map(|(t, d)| (*d).min(-diff.get(&canonical([t[0], t[2], t[1]])).copied().unwrap_or(0)).max(0))
        .sum();
    ((lost - flipped) as usize, (added - flipped) as usize, flipped as usize)
}

#[test]
fn the_linear_check_rejects_lost_added_flipped_and_duplicated_triangles() {
    // A grid of 2 x 300 x 300 triangles (one part of the bucket sort and more),
    // decoded triangles shuffled and rotated: accepted; then each kind of error
    // planted alone and all together, counted as the hashing reference counts them,
    // at 1, 2 and 4 threads, from a list (owned and borrowed) and from one-triangle
    // strips.
    let want = gen::grid(300, 300).triangulate().tris;
    assert_eq!(want.len(), 180_000);
    let mut rng = XorShift64(7);
    let mut good = want.clone();
    rng.shuffle(&mut good);
    for t in good.iter_mut() {
        t.rotate_left(rng.below(3));
    }
    let plant = |kind: usize, list: &mut Vec<[u32; 3]>, rng: &mut XorShift64| match kind {
        0 => {
            list.swap_remove(rng.below(list.len())); // lost
        }
        1 => list.push([1_000_000, 5, 6]), // added (an index beyond the mesh)
        2 => {
            let i = rng.below(list.len());
            list[i].swap(1, 2); // flipped
        }
        3 => {
            let i = rng.below(list.len());
            list.push(list[i]); // duplicated
        }
        _ => {
            let i = rng.below(list.len());
            list[i] = [list[i][0], list[i][1], list[(i + 1) % list.len()][2]]; // moved corner
        }
    };
    let cases: Vec<Vec<usize>> = vec![vec![], vec![0], vec![1], vec![2], vec![3], vec![4], vec![0, 1, 2, 3, 4, 2, 0, 3]];
    for kinds in cases {
        let mut got = good.clone();
        for &k in &kinds {
            plant(k, &mut got, &mut rng);
        }
        let (lost, added, flipped) = reference_check(&want, &got);
        let strips = StripSet::from_strips(&got.iter().map(|t| t.to_vec()).collect::<Vec<_>>());
        for threads in [Threads::SERIAL, Threads::new(2), Threads::new(4)] {
            let checks = [
                stripkit::verify_decoded_with(&want, got.clone(), threads),
                verify_with(&want, &strips, threads),
                stripkit::verify_triangles(&want, &got),
            ];
            for v in checks {
                assert_eq!((v.lost, v.added, v.flipped), (lost, added, flipped), "{kinds:?} at {threads} threads");
                assert_eq!(v.ok(), kinds.is_empty(), "{kinds:?}: {v}");
                assert_eq!((v.expected, v.decoded), (180_000, got.len()));
            }
        }
        match kinds.as_slice() {
            [] => assert_eq!((lost, added, flipped), (0, 0, 0)),
            [0] => assert_eq!((lost, added, flipped), (1, 0, 0)),
            [1] | [3] => assert_eq!((lost, added, flipped), (0, 1, 0)),
            [2] => assert_eq!((lost, added, flipped), (0, 0, 1)),
            _ => assert!(lost + added + flipped > 0),
        }
    }
}

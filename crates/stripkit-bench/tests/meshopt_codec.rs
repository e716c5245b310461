//! stripkit's `EXT_meshopt_compression` decoder against meshoptimizer's encoders (the
//! `meshopt` crate, which only this crate may use): random and mesh-like buffers are
//! encoded by meshoptimizer and decoded by stripkit, byte for byte equal to the input
//! (or, for the filters, to meshoptimizer's own decoding of the same stream).

use meshopt::{encode_index_buffer, encode_index_sequence, encode_vertex_buffer_level};
use stripkit::io::{decode_meshopt, MeshoptFilter, MeshoptMode};

/// One seeded generator for the whole file (a 64-bit LCG, high bits out).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u32 {
        self.0 = self.0.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 33) as u32
    }
}

fn as_bytes<const N: usize>(v: &[[u8; N]]) -> Vec<u8> {
    v.iter().flatten().copied().collect()
}

/// Vertex codec version 0 (the one `EXT_meshopt_compression` uses), every stride the
/// extension allows up to 64 bytes, counts around the block sizes, smooth and noisy data.
#[test]
fn vertex_streams_of_meshoptimizer_decode_to_their_input() {
    let mut rng = Rng(7);
    fn check<const N: usize>(rng: &mut Rng, count: usize, noise: u32) {
        let mut v = vec![[0u8; N]; count];
        let mut base = [0u8; N];
        for vert in v.iter_mut() {
            for (k, b) in vert.iter_mut().enumerate() {
                base[k] = base[k].wrapping_add((rng.next() % (noise + 1)) as u8);
                *b = base[k];
            }
        }
        for level in 0..=3 {
            let encoded = encode_vertex_buffer_level(&v, level, Some(0)).unwrap();
            assert_eq!(encoded[0], 0xA0);
            let ours = decode_meshopt(&encoded, count, N, MeshoptMode::Attributes, MeshoptFilter::None).unwrap();
            assert_eq!(ours, as_bytes(&v), "stride {N}, {count} vertices, noise {noise}");
        }
    }
    for count in [0, 1, 15, 16, 17, 255, 256, 257, 1000, 3000] {
        for noise in [0, 2, 20, 255] {
            check::<4>(&mut rng, count, noise);
            check::<8>(&mut rng, count, noise);
            check::<12>(&mut rng, count, noise);
            check::<16>(&mut rng, count, noise);
            check::<36>(&mut rng, count, noise);
            check::<64>(&mut rng, count, noise);
        }
    }
}

/// Triangle lists (a shuffled grid and random triangles) through the index codec, and
/// strips and random sequences through the index-sequence codec, at 2 and 4 bytes.
#[test]
fn index_streams_of_meshoptimizer_decode_to_their_input() {
    let mut rng = Rng(11);
    let grid = |n: u32| -> Vec<u32> {
        let mut t = Vec::new();
        for y in 0..n {
            for x in 0..n {
                let v = y * (n + 1) + x;
                t.extend_from_slice(&[v, v + 1, v + n + 1, v + 1, v + n + 2, v + n + 1]);
            }
        }
        t
    };
    let mut lists = vec![grid(1), grid(10), grid(60)];
    let mut shuffled = grid(30);
    for i in (1..shuffled.len() / 3).rev() {
        let j = rng.next() as usize % (i + 1);
        for k in 0..3 {
            shuffled.swap(3 * i + k, 3 * j + k);
        }
    }
    lists.push(shuffled);
    lists.push((0..3000).map(|_| rng.next() % 500).collect());
    lists.push((0..300).map(|_| rng.next()).collect());
    for list in &lists {
        let vertex_count = list.iter().max().map_or(0, |&m| m as usize + 1);
        let encoded = encode_index_buffer(list, vertex_count).unwrap();
        // The codec may rotate a triangle's corners (its winding kept): the decoded
        // list must equal meshoptimizer's decoding and the input up to rotation.
        let theirs: Vec<u32> = meshopt::decode_index_buffer(&encoded, list.len()).unwrap();
        let ours = decode_meshopt(&encoded, list.len(), 4, MeshoptMode::Triangles, MeshoptFilter::None).unwrap();
        assert_eq!(ours, want_bytes(&theirs), "{} indices", list.len());
        for (a, b) in theirs.chunks_exact(3).zip(list.chunks_exact(3)) {
            assert!((0..3).any(|r| [a[r], a[(r + 1) % 3], a[(r + 2) % 3]] == [b[0], b[1], b[2]]), "{a:?} {b:?}");
        }
        if vertex_count <= 65536 {
            let ours = decode_meshopt(&encoded, list.len(), 2, MeshoptMode::Triangles, MeshoptFilter::None).unwrap();
            let want: Vec<u8> = theirs.iter().flat_map(|&i| (i as u16).to_le_bytes()).collect();
            assert_eq!(ours, want);
        }
        // The sequence codec keeps 30 bits of a delta: equal to the input below that,
        // to meshoptimizer's decoding always.
        let seq = encode_index_sequence(list, vertex_count).unwrap();
        let ours = decode_meshopt(&seq, list.len(), 4, MeshoptMode::Indices, MeshoptFilter::None).unwrap();
        let theirs: Vec<u32> = meshopt::decode_index_sequence(&seq, list.len()).unwrap();
        assert_eq!(ours, want_bytes(&theirs), "sequence of {} indices", list.len());
        if vertex_count < 1 << 29 {
            assert_eq!(theirs, *list);
        }
    }
    // A strip with restart values, as written for EXT_mesh_primitive_restart.
    let strip: Vec<u32> = vec![0, 1, 2, 3, 4, u32::MAX, 5, 6, 7, 8, u32::MAX, 9, 10, 11];
    let seq = encode_index_sequence(&strip, 12).unwrap();
    let ours = decode_meshopt(&seq, strip.len(), 4, MeshoptMode::Indices, MeshoptFilter::None).unwrap();
    assert_eq!(ours, want_bytes(&strip));
}

fn want_bytes(list: &[u32]) -> Vec<u8> {
    list.iter().flat_map(|i| i.to_le_bytes()).collect()
}

/// The filters: meshoptimizer encodes unit vectors, quaternions and floats, its vertex
/// codec packs them, and stripkit's decode (codec then filter) must equal
/// meshoptimizer's own decode of the same stream.
#[test]
fn filtered_streams_decode_as_meshoptimizer_decodes_them() {
    let mut rng = Rng(13);
    let unit = |rng: &mut Rng| -> [f32; 4] {
        let mut v = [0f32; 4];
        for c in v.iter_mut() {
            *c = (rng.next() % 20001) as f32 / 10000.0 - 1.0;
        }
        let l = v.iter().map(|c| c * c).sum::<f32>().sqrt().max(1e-6);
        v.map(|c| c / l)
    };
    let n = 1000;
    let normals: Vec<[f32; 4]> = (0..n).map(|_| unit(&mut rng)).collect();
    let quats: Vec<[f32; 4]> = (0..n).map(|_| unit(&mut rng)).collect();
    let floats: Vec<[f32; 3]> = (0..n).map(|_| std::array::from_fn(|_| (rng.next() as f32 - 2e9) * 1e-5)).collect();

    let oct8: Vec<[i8; 4]> = meshopt::encode_filter_oct(&normals, 8);
    let oct16: Vec<[i16; 4]> = meshopt::encode_filter_oct(&normals, 16);
    let quat = meshopt::encode_filter_quat(&quats, 12);
    let exp = meshopt::encode_filter_exp(&floats, 15, meshopt::EncodeExpMode::Separate);

    // meshoptimizer's SIMD filters scale by an approximate reciprocal square root, so
    // they may land one unit away from the reference formula stripkit follows: the
    // octahedral and quaternion outputs agree within 1 per component.
    let stream = encode_vertex_buffer_level(&oct8, 2, Some(0)).unwrap();
    let ours = decode_meshopt(&stream, n, 4, MeshoptMode::Attributes, MeshoptFilter::Octahedral).unwrap();
    let mut theirs = oct8.clone();
    meshopt::decode_filter_oct(&mut theirs);
    let ours8: Vec<i32> = ours.iter().map(|&b| b as i8 as i32).collect();
    near(&ours8, &theirs.iter().flatten().map(|&c| c as i32).collect::<Vec<_>>());

    let stream = encode_vertex_buffer_level(&oct16, 2, Some(0)).unwrap();
    let ours = decode_meshopt(&stream, n, 8, MeshoptMode::Attributes, MeshoptFilter::Octahedral).unwrap();
    let mut theirs = oct16.clone();
    meshopt::decode_filter_oct(&mut theirs);
    near(&shorts(&ours), &theirs.iter().flatten().map(|&c| c as i32).collect::<Vec<_>>());

    let stream = encode_vertex_buffer_level(&quat, 2, Some(0)).unwrap();
    let ours = decode_meshopt(&stream, n, 8, MeshoptMode::Attributes, MeshoptFilter::Quaternion).unwrap();
    let mut theirs = quat.clone();
    meshopt::decode_filter_quat(&mut theirs);
    near(&shorts(&ours), &theirs.iter().flatten().map(|&c| c as i32).collect::<Vec<_>>());

    let stream = encode_vertex_buffer_level(&exp, 2, Some(0)).unwrap();
    let ours = decode_meshopt(&stream, n, 12, MeshoptMode::Attributes, MeshoptFilter::Exponential).unwrap();
    let mut theirs = exp.clone();
    meshopt::decode_filter_exp(&mut theirs);
    same(&ours, &theirs.iter().flatten().flat_map(|c| c.to_le_bytes()).collect::<Vec<_>>());
}

/// Streams cut short, grown or flipped at random decode to an error or to some bytes,
/// never a panic.
#[test]
fn damaged_streams_never_panic() {
    let mut rng = Rng(17);
    let v: Vec<[u8; 12]> = (0..300).map(|_| std::array::from_fn(|_| (rng.next() % 7) as u8)).collect();
    let tris: Vec<u32> = (0..900).map(|_| rng.next() % 300).collect();
    let streams = [
        (encode_vertex_buffer_level(&v, 2, Some(0)).unwrap(), 300, 12, MeshoptMode::Attributes),
        (encode_index_buffer(&tris, 300).unwrap(), 900, 4, MeshoptMode::Triangles),
        (encode_index_sequence(&tris, 300).unwrap(), 900, 4, MeshoptMode::Indices),
    ];
    for (stream, count, stride, mode) in &streams {
        for cut in 0..stream.len() {
            assert!(decode_meshopt(&stream[..cut], *count, *stride, *mode, MeshoptFilter::None).is_err());
        }
        for _ in 0..2000 {
            let mut bad = stream.clone();
            let at = rng.next() as usize % bad.len();
            bad[at] ^= 1 << (rng.next() % 8);
            let _ = decode_meshopt(&bad, *count, *stride, *mode, MeshoptFilter::None);
        }
    }
}

/// Equal bytes, or a panic naming the first difference.
fn same(ours: &[u8], theirs: &[u8]) {
    assert_eq!(ours.len(), theirs.len());
    if let Some(k) = (0..ours.len()).find(|&k| ours[k] != theirs[k]) {
        panic!("byte {k} differs: {:?} and {:?}", &ours[k & !7..(k & !7) + 8], &theirs[k & !7..(k & !7) + 8]);
    }
}

fn shorts(bytes: &[u8]) -> Vec<i32> {
    bytes.chunks_exact(2).map(|b| i16::from_le_bytes([b[0], b[1]]) as i32).collect()
}

/// Components equal within 1, and most of them equal.
fn near(ours: &[i32], theirs: &[i32]) {
    assert_eq!(ours.len(), theirs.len());
    let off = ours.iter().zip(theirs).filter(|(a, b)| a != b).count();
    for (k, (a, b)) in ours.iter().zip(theirs).enumerate() {
        assert!((a - b).abs() <= 1, "component {k}: {a} and {b}");
    }
    assert!(off * 20 < ours.len(), "{off} of {} components differ", ours.len());
}

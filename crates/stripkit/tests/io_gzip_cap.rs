//! Gzip decompression is capped (issue #16, item 6: a 5 MB gzip of 5 GB of zeros
//! used 5.3 GB of RAM, then read as a valid empty mesh). The cap is
//! `ReadOptions::max_decompressed_bytes`; the error gives it.

use flate2::write::GzEncoder;
use flate2::Compression;
use std::io::Write;
use std::path::PathBuf;
use stripkit::io::{self, ReadOptions, DEFAULT_MAX_DECOMPRESSED_BYTES};
use stripkit::Error;

fn gz_file(name: &str, content: &[u8]) -> PathBuf {
    let dir = stripkit_testkit::scratch_dir("gzip-cap");
    let path = dir.join(name);
    let mut enc = GzEncoder::new(Vec::new(), Compression::best());
    enc.write_all(content).unwrap();
    std::fs::write(&path, enc.finish().unwrap()).unwrap();
    path
}

#[test]
fn decompression_stops_at_the_cap_and_says_so() {
    // 1 MiB of zeros compresses to about 1 KB (PLY may be binary: no early refusal).
    let path = gz_file("zeros.ply.gz", &vec![0u8; 1 << 20]);
    assert!(std::fs::metadata(&path).unwrap().len() < 10_000);
    let options = ReadOptions::default().max_decompressed_bytes(4096);
    let e = io::read_with(&path, &options).unwrap_err();
    assert!(matches!(e, Error::Format { .. }), "{e:?}");
    let text = e.to_string();
    assert!(text.contains("zeros.ply.gz"), "{text}");
    assert!(text.contains("decompresses to more than 4096 bytes"), "{text}");
}

#[test]
fn a_file_at_the_cap_is_read() {
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let path = gz_file("tri.obj.gz", obj);
    let exact = ReadOptions::default().max_decompressed_bytes(obj.len() as u64);
    let m = io::read_with(&path, &exact).unwrap();
    assert_eq!((m.vertex_count(), m.face_count()), (3, 1));
    let short = ReadOptions::default().max_decompressed_bytes(obj.len() as u64 - 1);
    let e = io::read_with(&path, &short).unwrap_err().to_string();
    assert!(e.contains(&format!("decompresses to more than {} bytes", obj.len() - 1)), "{e}");
    // `read` uses the default cap, 4 GiB.
    assert_eq!(DEFAULT_MAX_DECOMPRESSED_BYTES, 4 << 30);
    assert_eq!(ReadOptions::default().max_decompressed_bytes, DEFAULT_MAX_DECOMPRESSED_BYTES);
    assert_eq!(io::read(&path).unwrap().face_count(), 1);
}

#[test]
fn a_compressed_text_format_of_zeros_is_refused_at_its_first_bytes() {
    // Refused from the first 4 KiB, before the rest is decompressed (the issue's
    // 5 GB of zeros took 5.3 GB): the refusal names the NUL byte, not the cap,
    // although the content is 1,000 times the cap.
    let zeros = vec![0u8; 8 << 20];
    let small_cap = ReadOptions::default().max_decompressed_bytes(8192);
    for name in ["zeros.obj.gz", "zeros.off.gz", "zeros.gltf.gz"] {
        let path = gz_file(name, &zeros);
        let text = io::read_with(&path, &small_cap).unwrap_err().to_string();
        assert!(text.contains(name) && text.contains("decompressed byte 0"), "{text}");
        assert!(text.contains("NUL byte") && !text.contains("more than"), "{text}");
    }
    // Text with no NUL in its first 4 KiB is read as before.
    let path = gz_file("tri.off.gz", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    assert_eq!(io::read(&path).unwrap().face_count(), 1);
}

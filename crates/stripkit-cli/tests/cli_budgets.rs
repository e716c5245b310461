//! Resource budgets (issue #16, item 6): counts and arguments that would ask for
//! gigabytes are refused up front with exit 2 and a message that names the limit,
//! and each run stays under a 1 GiB address-space limit and 20 s of processor time.

mod support;

use support::{stripkit_1gib, tmp};

/// Runs under the 1 GiB limit, expects exit 2 and a message containing each of `want`.
fn refused(args: &[&str], want: &[&str]) {
    let (out, _) = stripkit_1gib(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    for w in want {
        assert!(err.contains(w), "{args:?}: want `{w}` in `{err}`");
    }
}

#[test]
fn dimacs_node_count_beyond_the_file_is_refused() {
    // 28 bytes that announced 2e9 nodes: 8 GB of adjacency offsets before the fix.
    let f = tmp("budgets", "huge_nodes.dimacs");
    std::fs::write(&f, "p edge 2000000000 1\ne 1 2 5\n").unwrap();
    let name = f.to_str().unwrap();
    refused(
        &["match", name],
        &[&format!("{name}: line 1: node count 2000000000"), "1048578"],
    );
}

#[test]
fn gen_sizes_are_checked_without_overflow() {
    let out = tmp("budgets", "never.obj");
    let out = out.to_str().unwrap();
    // 24 * 4^31 wrapped to 0 and got past the size check.
    for levels in ["31", "32", "40", "4294967295"] {
        refused(&["gen", "cube", "--levels", levels, "-o", out], &["the requested mesh is too large", "limit 33554432"]);
    }
    refused(&["gen", "cube", "--levels", "31", "-o", out], &["24 face indices x 4^31"]);
    refused(&["gen", "cube", "--levels", "14", "-o", out], &["(6442450944 face indices"]);
    refused(&["gen", "grid", "4294967295", "4294967295", "-o", out], &["the requested mesh is too large"]);
    // 13000 x 13000 squares: 1,014,000,000 face indices, under the earlier 2^30 limit,
    // asked for over 10 GB to build and write.
    refused(&["gen", "grid", "13000", "13000", "-o", out], &["(1014000000 face indices", "limit 33554432"]);
    refused(&["gen", "torus", "--major", "4294967295", "--minor", "4294967295", "-o", out], &["too large"]);
    let sub = tmp("budgets", "tri.obj");
    std::fs::write(&sub, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let sub = sub.to_str().unwrap();
    refused(
        &["gen", "subdivide", sub, "--scheme", "loop", "--levels", "33", "-o", out],
        &[&format!("{sub}: 3 face indices x 4^33")],
    );
    assert!(!std::path::Path::new(out).exists());
}

#[test]
fn distance_samples_are_range_checked() {
    let f = tmp("budgets", "quad.obj");
    std::fs::write(&f, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
    let f = f.to_str().unwrap();
    // 10^11 samples asked for 2.4 TB; 10^8 (the earlier bound) 2.4 GB.
    for n in ["100000000000", "100000000", "10000001", "0"] {
        refused(
            &["distance", f, f, "--samples", n],
            &[&format!("--samples {n} is out of range: 1 to 10000000")],
        );
    }
    // The same bound for the sequences' distances, before the frames are read.
    let out = tmp("budgets", "never.lodseq");
    for n in ["100000000", "0"] {
        refused(
            &["lod", "build-seq", "no-such-folder", "-o", out.to_str().unwrap(), "--samples", n],
            &[&format!("--samples {n} is out of range: 1 to 10000000")],
        );
    }
    assert!(!out.exists());
}

#[test]
fn cull_views_are_range_checked_before_reading() {
    // 10^8 views once asked for over 10 GB of eyes and figures; the mesh need not exist.
    for n in ["100000000", "100001", "0"] {
        refused(&["cull", "no-such-mesh.obj", "--views", n], &[&format!("--views {n} is out of range: 1 to 100000")]);
    }
}

#[test]
fn strip_cache_sizes_are_range_checked() {
    let f = tmp("budgets", "strip_quad.obj");
    std::fs::write(&f, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
    let out = tmp("budgets", "strip_never.ply");
    let (f, o) = (f.to_str().unwrap(), out.to_str().unwrap());
    // 4294967296 once tried 17 GB; 4294967295 panicked in `cache` and `balanced`
    // (`cache_size * 5 / 8` overflowed u32, then the FIFO's own 2^30 assertion).
    for cache in ["4294967296", "4294967295", "858993460", "65537"] {
        for algo in ["cache", "balanced", "greedy", "qstrip"] {
            refused(
                &["strip", f, "-o", o, "--cache", cache, "--algo", algo],
                &[&format!("--cache {cache} is too large (at most 65536 entries)")],
            );
        }
    }
    assert!(!out.exists());
    // The largest size accepted runs in bounded memory with every mode.
    for algo in ["cache", "balanced", "greedy", "qstrip"] {
        let (run, _) = stripkit_1gib(&["strip", f, "-o", o, "--cache", "65536", "--algo", algo]);
        assert!(run.status.success(), "{algo}: {}", String::from_utf8_lossy(&run.stderr));
    }
}

/// The issue's reproducer: a GLB whose 2,000 POSITION accessors all read one view of
/// 100,000 zero positions (1.2 MB), each drawn as points by its own primitive;
/// gzip-compressed it is about 8 KB and described 2.4 GB of vertices.
fn reused_positions_glb_gz(name: &str) -> std::path::PathBuf {
    let (accessors, vertices) = (2000usize, 100_000usize);
    let acc: Vec<String> = (0..accessors)
        .map(|_| format!(r#"{{"bufferView":0,"componentType":5126,"count":{vertices},"type":"VEC3"}}"#))
        .collect();
    let prims: Vec<String> =
        (0..accessors).map(|k| format!(r#"{{"attributes":{{"POSITION":{k}}},"mode":0}}"#)).collect();
    let bin = vec![0u8; 12 * vertices];
    let mut json = format!(
        r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":{}}}],"bufferViews":[{{"buffer":0,"byteLength":{}}}],"accessors":[{}],"meshes":[{{"primitives":[{}]}}]}}"#,
        bin.len(),
        bin.len(),
        acc.join(","),
        prims.join(",")
    )
    .into_bytes();
    json.resize(json.len().div_ceil(4) * 4, b' ');
    let mut glb = b"glTF".to_vec();
    for word in [2, (12 + 8 + json.len() + 8 + bin.len()) as u32, json.len() as u32, 0x4E4F_534A] {
        glb.extend_from_slice(&word.to_le_bytes());
    }
    glb.extend_from_slice(&json);
    glb.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    glb.extend_from_slice(&0x004E_4942u32.to_le_bytes());
    glb.extend_from_slice(&bin);
    let path = tmp("budgets", name);
    stripkit::io::write_encoded(&path, &glb).unwrap(); // gzip-compressed by its name
    path
}

#[test]
fn a_glb_reusing_one_position_view_is_refused_by_every_command_that_reads_meshes() {
    let f = reused_positions_glb_gz("reuse.glb.gz");
    let size = std::fs::metadata(&f).unwrap().len();
    assert!(size < 16 << 10, "{size} bytes");
    let name = f.to_str().unwrap();
    let out = tmp("budgets", "reuse_never.ply");
    let o = out.to_str().unwrap();
    let want = [
        &format!("{name}: meshes[0].primitives[32]: decoding accessors[32]: 100000 vertices") as &str,
        "more than the limit of 39448576 bytes (32 x the file's 1200000 buffer bytes",
        "--max-memory",
    ];
    refused(&["stats", name], &want);
    refused(&["strip", name, "-o", o], &want);
    refused(&["simplify", name, "--ratio", "0.5", "-o", o], &want);
    refused(&["distance", name, name], &want);
    refused(&["gen", "subdivide", name, "--scheme", "loop", "-o", o], &want);
    refused(&["match", "--dual", name], &want);
    assert!(!out.exists());
    // An explicit ceiling replaces the input-relative one, lower or higher.
    refused(
        &["stats", name, "--max-memory", "30M"],
        &["accessors[26]", "more than the limit of 31457280 bytes; ", "--max-memory"],
    );
    refused(&["stats", name, "--max-memory", "64M"], &["accessors[55]", "the limit of 67108864 bytes"]);
    // The same flag caps decompression and names the limit.
    refused(&["stats", name, "--max-memory", "1M"], &["decompresses to more than 1048576 bytes", "--max-memory"]);
}

#[test]
fn max_memory_takes_sizes_and_leaves_valid_files_alone() {
    let f = tmp("budgets", "mm_quad.obj");
    std::fs::write(&f, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
    let glb = tmp("budgets", "mm_quad.glb");
    let f = f.to_str().unwrap();
    let g = glb.to_str().unwrap();
    let (run, _) = stripkit_1gib(&["gen", "subdivide", f, "--scheme", "catmull-clark", "-o", g, "--max-memory", "1K"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    // The figures without the timings.
    let facts = |args: &[&str]| {
        let mut v = support::json(&support::stripkit(args));
        v.as_object_mut().unwrap().retain(|k, _| !k.ends_with("_ms"));
        v
    };
    let plain = facts(&["stats", g, "--json"]);
    assert_eq!(plain["faces"], 8);
    // 9 vertices x 12 + 24 face indices x 4 + 8 faces x 4 = 236 bytes.
    for size in ["236", "1K", "4096", "1GiB", "16T"] {
        assert_eq!(facts(&["stats", g, "--json", "--max-memory", size]), plain, "{size}");
    }
    refused(&["stats", g, "--max-memory", "235"], &["more than the limit of 235 bytes"]);
    for bad in ["1.5G", "12X", "-1", "99999999999T", ""] {
        let (run, _) = stripkit_1gib(&["stats", g, &format!("--max-memory={bad}")]);
        assert_eq!(run.status.code(), Some(2), "{bad}");
        assert!(String::from_utf8_lossy(&run.stderr).contains("--max-memory"), "{bad}");
    }
}

#[test]
fn simplify_pair_distances_are_range_checked_before_reading() {
    // NaN, negative and infinite distances were accepted and silently found no pair.
    let f = tmp("budgets", "pairs_quad.obj");
    std::fs::write(&f, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
    let out = tmp("budgets", "pairs_never.obj");
    let (f, o) = (f.to_str().unwrap(), out.to_str().unwrap());
    for d in ["NaN", "-1", "inf", "-inf", "1e400"] {
        let arg = format!("--pair-distance={d}");
        let shown = d.parse::<f64>().unwrap();
        refused(
            &["simplify", f, "--ratio", "0.5", "-o", o, &arg],
            &[&format!("--pair-distance {shown} is out of range: a finite distance, 0 or more")],
        );
        // Before the mesh is read: a missing file is not what the message says.
        refused(&["simplify", "no-such-mesh.obj", "--ratio", "0.5", "-o", o, &arg], &["--pair-distance"]);
    }
    assert!(!out.exists());
    let (run, _) = stripkit_1gib(&["simplify", f, "--ratio", "0.5", "-o", o, "--pair-distance", "0"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
}

#[test]
fn simplify_pair_distances_that_pair_everything_are_refused() {
    // 3,721 vertices all within the distance: 6.9 million pairs, beyond
    // 32 per vertex + 2^20 = 1,167,648.
    let grid = tmp("budgets", "pairs_grid.obj");
    let g = grid.to_str().unwrap();
    let (run, _) = stripkit_1gib(&["gen", "grid", "60", "60", "-o", g]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let out = tmp("budgets", "pairs_grid_never.obj");
    let o = out.to_str().unwrap();
    refused(
        &["simplify", g, "--ratio", "0.5", "-o", o, "--pair-distance", "1e30"],
        &[g, "finds more than 1167648 vertex pairs (32 per each of the 3721 used vertices", "smaller distance"],
    );
    assert!(!out.exists());
}

#[test]
fn a_sibling_file_listed_by_100_buffers_is_read_once_and_decoded_within_the_budget() {
    // "One sibling file listed 100 times as a buffer used 4.9 GB": each buffer read its
    // own copy. Now the file is read once (4.8 MB here) and 100 accessors decoding it
    // whole are charged against its bytes counted once: refused at the 33rd, 164 MB
    // peak, where --max-memory 8G decodes all 480 MB (790 MB peak).
    let dir = tmp("budgets", "sibling");
    std::fs::create_dir_all(&dir).unwrap();
    let (n, len) = (400_000usize, 4_800_000usize);
    std::fs::write(dir.join("big.bin"), vec![0u8; len]).unwrap();
    let list = |f: &dyn Fn(usize) -> String| (0..100).map(f).collect::<Vec<_>>().join(",");
    let gltf = format!(
        r#"{{"asset":{{"version":"2.0"}},"buffers":[{}],"bufferViews":[{}],"accessors":[{}],"meshes":[{{"primitives":[{}]}}]}}"#,
        list(&|_| format!(r#"{{"byteLength":{len},"uri":"big.bin"}}"#)),
        list(&|b| format!(r#"{{"buffer":{b},"byteLength":{len}}}"#)),
        list(&|v| format!(r#"{{"bufferView":{v},"componentType":5126,"count":{n},"type":"VEC3"}}"#)),
        list(&|k| format!(r#"{{"attributes":{{"POSITION":{k}}},"mode":0}}"#)),
    );
    let path = dir.join("many.gltf");
    std::fs::write(&path, gltf).unwrap();
    let name = path.to_str().unwrap();
    refused(
        &["stats", name],
        &[&format!("{name}: meshes[0].primitives[32]: decoding accessors[32]: 400000 vertices"), "32 x the file's 4800000 buffer bytes"],
    );
    // A ceiling below the file itself refuses the external buffer before reading it.
    refused(&["stats", name, "--max-memory", "4M"], &["buffers[0]", "exceeds the limit of 4194304 bytes", "--max-memory"]);
}

#[test]
fn strip_tunnel_depth_is_range_checked() {
    let spot = support::assets_dir().join("spot.obj");
    let spot = spot.to_str().unwrap();
    let out = tmp("budgets", "strip_tunnel.ply");
    let o = out.to_str().unwrap();
    // The tunnel search is exponential in its depth: `--tunnel 32` on cow ran for
    // minutes before each search's work was bounded; past 32 the depth is refused.
    for n in ["33", "4294967296", "18446744073709551616"] {
        refused(&["strip", spot, "-o", o, "--algo", "greedy", "--tunnel", n], &["--tunnel"]);
    }
    refused(&["strip", spot, "-o", o, "--tunnel", "33"], &["0..=32"]);
    assert!(!out.exists());
    for n in ["0", "4", "32"] {
        let (run, _) = stripkit_1gib(&["strip", spot, "-o", o, "--algo", "greedy", "--tunnel", n, "--json"]);
        assert!(run.status.success(), "--tunnel {n}: {}", String::from_utf8_lossy(&run.stderr));
        let v = support::json(&run);
        assert_eq!((&v["verified"], &v["triangles"]), (&true.into(), &5856.into()), "--tunnel {n}: {v}");
    }
}

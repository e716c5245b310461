//! Resource budgets (issue #16, item 6): counts and arguments that would ask for
//! gigabytes are refused up front with exit 2 and a message that names the limit,
//! and each run stays under a 1 GiB address-space limit and takes well under 2 s.

mod support;

use support::{stripkit_1gib, tmp};

/// Runs under the 1 GiB limit, expects exit 2 and a message containing each of `want`.
fn refused(args: &[&str], want: &[&str]) {
    let (out, secs) = stripkit_1gib(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    for w in want {
        assert!(err.contains(w), "{args:?}: want `{w}` in `{err}`");
    }
    assert!(secs < 2.0, "{args:?} took {secs:.1} s");
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
        refused(&["gen", "cube", "--levels", levels, "-o", out], &["the requested mesh is too large", "limit 1073741824"]);
    }
    refused(&["gen", "cube", "--levels", "31", "-o", out], &["24 face indices x 4^31"]);
    refused(&["gen", "cube", "--levels", "14", "-o", out], &["(6442450944 face indices"]);
    refused(&["gen", "grid", "4294967295", "4294967295", "-o", out], &["the requested mesh is too large"]);
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
    // 10^11 samples asked for 2.4 TB.
    for n in ["100000000000", "100000001", "0"] {
        refused(
            &["distance", f, f, "--samples", n],
            &[&format!("--samples {n} is out of range: 1 to 100000000")],
        );
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
        let (run, secs) = stripkit_1gib(&["strip", f, "-o", o, "--cache", "65536", "--algo", algo]);
        assert!(run.status.success(), "{algo}: {}", String::from_utf8_lossy(&run.stderr));
        assert!(secs < 2.0, "{algo}: {secs:.1} s");
    }
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

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

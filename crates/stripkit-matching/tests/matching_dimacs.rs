//! The DIMACS-style reader: what it accepts, and the errors it gives.

use std::path::Path;
use stripkit_matching::{self as matching, Graph, Objective};
use stripkit_matching::Error;

fn parse(text: &str) -> Result<Graph, Error> {
    Graph::parse_dimacs(text, Path::new("g.dimacs"))
}

fn err(text: &str) -> String {
    match parse(text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => {
            assert!(matches!(e, Error::Format { .. } | Error::Invalid(_)), "{e:?}");
            e.to_string()
        }
    }
}

#[test]
fn reads_comments_blank_lines_and_edges() {
    let g = parse("c a square\n\np edge 4 4\ne 1 2 5\n  e 2 3 -1\nc mid\ne 3 4 5\ne 4 1 0\n").unwrap();
    assert_eq!((g.node_count(), g.edge_count()), (4, 4));
    assert_eq!(g.edges()[1], [1, 2]);
    assert_eq!(g.weights(), &[5, -1, 5, 0]);
    let m = matching::max_weight_perfect_matching(&g).unwrap();
    assert_eq!(m.total_weight, 10);
    let m = matching::min_cost_perfect_matching(&g).unwrap();
    assert_eq!(m.total_weight, -1);
    // Round trip.
    assert_eq!(parse(&g.to_dimacs()).unwrap(), g);
}

#[test]
fn self_loops_are_ignored_and_parallel_edges_keep_the_best() {
    let g = parse("p edge 2 4\ne 1 1 100\ne 1 2 3\ne 2 1 9\ne 1 2 -4\n").unwrap();
    let m = matching::solve(&g, Objective::MaxWeight).unwrap();
    assert_eq!((m.edges.clone(), m.total_weight), (vec![2], 9));
    let m = matching::solve(&g, Objective::MinCost).unwrap();
    assert_eq!((m.edges.clone(), m.total_weight), (vec![3], -4));
    // Certificates cover every parallel edge.
    matching::verify(&g, Objective::MinCost, &m.edges, m.certificate.as_ref().unwrap()).unwrap();
    // A graph of only a self-loop has no perfect matching.
    let g = parse("p edge 2 1\ne 2 2 1\n").unwrap();
    assert!(!matching::max_weight_perfect_matching(&g).unwrap().perfect);
}

#[test]
fn bad_files_get_clear_errors() {
    let cases: &[(&str, &str)] = &[
        ("e 1 2 3\n", "line 1: edge line before the problem line"),
        ("p edge 2 1\ne 1 2\n", "line 2: expected `e U V W`"),
        ("p edge 2 1\ne 1 x 2\n", "line 2: vertex `x` is not a positive integer"),
        ("p edge 2 1\ne 1 2 2.5\n", "line 2: weight `2.5` is not an integer"),
        ("p edge 2 1\ne 0 2 1\n", "line 2: vertex 0 out of range: vertices are 1..=2"),
        ("p edge 2 1\ne 1 3 1\n", "line 2: vertex 3 out of range: vertices are 1..=2"),
        ("p edge 2 2\ne 1 2 1\n", "line 1: problem line announces 2 edges but the file has 1"),
        ("p edge 2 1\ne 1 2 1\ne 2 1 1\n", "line 3: more edge lines than the 1 announced"),
        ("c nothing\n", "end of file: no problem line"),
        ("p edge 2\n", "line 1: expected `p edge N M`"),
        ("p edge -2 1\n", "line 1: node count `-2` is not a non-negative integer"),
        ("p edge 2 0\np edge 2 0\n", "line 2: second problem line"),
        ("p edge 2 1\nx 1 2 1\n", "line 2: unknown line type `x`"),
        ("p edge 2 1\ne 1 2 99999999999999999999\n", "line 2: weight `99999999999999999999` is not an integer"),
        ("p edge 2 1\ne 1 2 2000000000000\n", "line 2: weight 2000000000000 beyond the supported range"),
        // A huge announced count allocates nothing.
        ("p edge 2 18446744073709551615\ne 1 2 1\n", "announces 18446744073709551615 edges but the file has 1"),
    ];
    for (text, want) in cases {
        let e = err(text);
        assert!(e.starts_with("g.dimacs: "), "{e}");
        assert!(e.contains(want), "for {text:?}: got `{e}`, want `{want}`");
    }
    // Missing file: an I/O error naming it.
    let e = Graph::read_dimacs(Path::new("/nonexistent/x.dimacs")).unwrap_err();
    assert!(matches!(e, Error::Io { .. }) && e.to_string().contains("/nonexistent/x.dimacs"));
}

#[test]
fn graph_new_checks_its_input() {
    assert!(Graph::new(2, vec![[0, 2]], vec![1]).is_err());
    assert!(Graph::new(2, vec![[0, 1]], vec![]).is_err());
    assert!(Graph::new(2, vec![[0, 1]], vec![i64::MAX]).is_err());
    let g = Graph::new(3, vec![[0, 1], [1, 1], [2, 1]], vec![1, 2, 3]).unwrap();
    assert_eq!(g.adjacency(1), &[0, 1, 2]);
    assert_eq!(g.adjacency(2), &[2]);
}

#[test]
fn weights_beyond_the_range_are_refused_without_overflow() {
    // i64::MIN: `abs()` wraps to itself (negative) in release builds, so a check
    // written as `w.abs() > MAX_WEIGHT` let it through and the solver reported a
    // "certified" optimum of -9223372036854775808 on a graph whose optimum is 0.
    for w in [i64::MIN, i64::MIN + 1, i64::MAX, -matching::MAX_WEIGHT - 1, matching::MAX_WEIGHT + 1] {
        let e = err(&format!("p edge 2 1\ne 1 2 {w}\n"));
        assert!(e.contains(&format!("g.dimacs: line 2: weight {w} beyond the supported range")), "{e}");
        let e = Graph::new(2, vec![[0, 1]], vec![w]).unwrap_err();
        assert!(matches!(e, Error::Invalid(_)), "{e:?}");
        assert!(e.to_string().contains(&format!("edge 0 has weight {w} beyond the supported range")), "{e}");
    }
    // The limits themselves are accepted, and solved exactly.
    for w in [matching::MAX_WEIGHT, -matching::MAX_WEIGHT] {
        let g = parse(&format!("p edge 2 1\ne 1 2 {w}\n")).unwrap();
        assert_eq!(g.weights(), &[w]);
        assert_eq!(Graph::new(2, vec![[0, 1]], vec![w]).unwrap(), g);
        let m = matching::max_weight_perfect_matching(&g).unwrap();
        assert_eq!((m.perfect, m.total_weight), (true, w));
    }
}

#[test]
fn node_count_is_bounded_by_the_edge_lines() {
    // 2 * M + DIMACS_SPARE_NODES nodes at most: memory follows the file's size.
    let limit = 2 + matching::DIMACS_SPARE_NODES;
    let g = parse(&format!("p edge {limit} 1\ne 1 2 5\n")).unwrap();
    assert_eq!(g.node_count(), limit);
    let e = err(&format!("p edge {} 1\ne 1 2 5\n", limit + 1));
    assert!(e.starts_with("g.dimacs: line 1: node count"), "{e}");
    assert!(e.contains(&format!("= {limit}")), "{e}");
    // The 28-byte reproducer of issue #16: refused quickly, nothing allocated for 2e9.
    let start = std::time::Instant::now();
    let e = err("p edge 2000000000 1\ne 1 2 5\n");
    assert!(e.contains("line 1: node count 2000000000 is more than the 1 edge lines can use"), "{e}");
    assert!(start.elapsed().as_secs_f64() < 1.0);
}

/// Writes `bytes` to a fresh file and reads it as a graph file.
fn read_bytes(name: &str, bytes: &[u8]) -> Result<Graph, Error> {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("matching_dimacs");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    Graph::read_dimacs(&path)
}

#[test]
fn a_utf8_byte_order_mark_is_skipped() {
    // It used to hide the problem line: "line 1: unknown line type `\u{feff}p`".
    let plain = parse("p edge 2 1\ne 1 2 5\n").unwrap();
    assert_eq!(parse("\u{feff}p edge 2 1\ne 1 2 5\n").unwrap(), plain);
    assert_eq!(read_bytes("bom.dimacs", b"\xEF\xBB\xBFp edge 2 1\ne 1 2 5\n").unwrap(), plain);
    assert_eq!(read_bytes("bom_comment.dimacs", b"\xEF\xBB\xBFc first\np edge 2 1\ne 1 2 5\n").unwrap(), plain);
    // Only at the start: elsewhere it is still an unknown line.
    assert!(err("p edge 2 1\n\u{feff}e 1 2 5\n").contains("line 2: unknown line type"));
}

#[test]
fn bytes_that_are_not_utf8_are_refused_naming_their_line() {
    // read_to_string's "stream did not contain valid UTF-8" named no line.
    let e = read_bytes("latin1.dimacs", b"c caf\xE9\np edge 2 1\ne 1 2 5\n").unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, Error::Format { .. }), "{e:?}");
    assert!(msg.contains("latin1.dimacs: line 1: byte 0xE9 at column 6 (file offset 5) is not UTF-8 text"), "{msg}");
    let e = read_bytes("late.dimacs", b"p edge 2 1\r\ne 1 2 5\n\xFF\n").unwrap_err().to_string();
    assert!(e.contains("late.dimacs: line 3: byte 0xFF at column 1 (file offset 20)"), "{e}");
    // A multi-byte sequence cut short by the end of the file.
    let e = read_bytes("cut.dimacs", b"p edge 2 1\ne 1 2 5\nc \xE2\x82").unwrap_err().to_string();
    assert!(e.contains("cut.dimacs: line 3: byte 0xE2 at column 3"), "{e}");
    for (bom, kind) in [(&[0xFFu8, 0xFE], "UTF-16 little-endian"), (&[0xFE, 0xFF], "UTF-16 big-endian")] {
        let mut bytes = bom.to_vec();
        bytes.extend("p edge 2 1\n".bytes().flat_map(|b| [b, 0]));
        let e = read_bytes("wide.dimacs", &bytes).unwrap_err().to_string();
        assert!(e.contains(&format!("wide.dimacs: line 1: the file is {kind} text")), "{e}");
    }
}

#![no_main]
//! `Graph::parse_dimacs` on the bytes (as UTF-8); a small graph is then solved both
//! ways and the result checked: a consistent matching and, when perfect, a
//! certificate that `verify` accepts.

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use stripkit_matching::{solve, verify, Error, Graph, Objective, UNMATCHED};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let Ok(g) = Graph::parse_dimacs(text, Path::new("fuzz.dimacs")) else { return };
    if g.node_count() > 64 || g.edge_count() > 256 {
        return;
    }
    for obj in [Objective::MaxWeight, Objective::MinCost] {
        let m = match solve(&g, obj) {
            Ok(m) => m,
            Err(e @ Error::Verification(_)) => panic!("{obj:?}: {e}"),
            Err(_) => continue,
        };
        assert!(m.certified, "{obj:?}: result not certified");
        assert_eq!(m.mate.len(), g.node_count());
        let mut total = 0i64;
        let mut seen = vec![false; g.node_count()];
        for &e in &m.edges {
            let [a, b] = g.edges()[e as usize];
            assert_ne!(a, b, "{obj:?}: self-loop {e} matched");
            assert!(!seen[a as usize] && !seen[b as usize], "{obj:?}: vertex matched twice");
            seen[a as usize] = true;
            seen[b as usize] = true;
            assert_eq!(m.mate[a as usize], b);
            assert_eq!(m.mate[b as usize], a);
            total += g.weights()[e as usize];
        }
        for (v, &s) in seen.iter().enumerate() {
            assert_eq!(s, m.mate[v] != UNMATCHED, "{obj:?}: mate of {v} disagrees with the edges");
        }
        assert_eq!(total, m.total_weight, "{obj:?}: total weight");
        if m.perfect {
            assert!(seen.iter().all(|&s| s), "{obj:?}: 'perfect' leaves a vertex unmatched");
            let cert = m.certificate.as_ref().expect("a perfect matching carries its certificate");
            if let Err(e) = verify(&g, obj, &m.edges, cert) {
                panic!("{obj:?}: certificate rejected: {e}");
            }
        }
    }
});

//! Target `options`: the values of the CLI options that size memory, turned into the
//! library's options as the CLI turns them, then the library's own bounds check, and
//! only the small part of the work that an accepted small value allows.
//!
//! Byte 0 picks the option; the rest are its value(s): little-endian integers of 8
//! bytes (zero-padded), or UTF-8 text for a named value. The CLI's own parsing of a
//! flag is clap's (`usize`, `u32`) and the library's `FromStr`; every bound on a
//! memory-sizing value is the library's (`gen::check_*`, `MAX_SAMPLES`,
//! `MAX_CACHE_SIZE`, `MAX_TUNNEL_CUTS`, the read budgets), so this target checks those
//! bounds against an exact count in `u128`: accepted exactly when within the limit,
//! and never a panic or an overflow.
//!
//! `check` is one match over the option families, about 170 lines long: each arm is a
//! few lines reading its values and asking the library, and splitting them apart would
//! scatter the table of what byte 0 means.

use stripkit::gen::{self, MAX_ICOSPHERE_LEVEL, MAX_INDICES};
use stripkit::io::{Format, ReadOptions};
use stripkit::{
    Algorithm, CacheModel, Heuristic, Join, Split, StripOptions, Stripifier, MAX_CACHE_SIZE,
    MAX_TUNNEL_CUTS,
};

/// The `i`-th 8-byte little-endian value of `rest` (zero-padded; 0 past the end).
fn value(rest: &[u8], i: usize) -> u64 {
    let mut b = [0u8; 8];
    for (k, x) in rest.iter().skip(8 * i).take(8).enumerate() {
        b[k] = *x;
    }
    u64::from_le_bytes(b)
}

/// A value of `rest` narrowed to the flag's type: clap parses `u32` flags as `u32`, so
/// the high half never reaches the library; a `u32` here keeps the whole range.
fn value32(rest: &[u8], i: usize) -> u32 {
    value(rest, i) as u32 ^ (value(rest, i) >> 32) as u32
}

/// Asserts that a bound check's verdict matches the exact count.
fn agrees(what: &str, accepted: &stripkit::Result<()>, within: bool) {
    match accepted {
        Ok(()) => assert!(within, "{what}: accepted beyond its limit"),
        Err(e) => {
            assert!(
                e.is_invalid(),
                "{what}: refused as {e:?}, not as an invalid request"
            );
            assert!(!within, "{what}: refused within its limit: {e}");
        }
    }
}

/// The check. Panics on a finding.
pub fn check(data: &[u8]) {
    let Some((&which, rest)) = data.split_first() else {
        return;
    };
    let limit = MAX_INDICES as u128;
    match which % 9 {
        // gen grid W H [--quads]
        0 => {
            let (w, h, quads) = (value32(rest, 0), value32(rest, 1), value(rest, 2) & 1 == 1);
            let faces = w as u128 * h as u128;
            let within = faces * if quads { 4 } else { 6 } <= limit
                && (w as u128 + 1) * (h as u128 + 1) <= limit;
            let verdict = gen::check_grid(w, h, quads);
            agrees(&format!("grid {w} {h} quads {quads}"), &verdict, within);
            if verdict.is_ok() && w > 0 && h > 0 && faces <= 256 {
                let mesh = if quads {
                    gen::grid_quads(w, h)
                } else {
                    gen::grid(w, h)
                };
                assert_eq!(
                    mesh.face_count() as u128,
                    faces * if quads { 1 } else { 2 },
                    "grid {w} {h}"
                );
            }
        }
        // gen torus --major M --minor N
        1 => {
            let (major, minor) = (value32(rest, 0), value32(rest, 1));
            let segments = major as u128 * minor as u128;
            agrees(
                &format!("torus {major} {minor}"),
                &gen::check_torus(major, minor),
                segments * 6 <= limit && segments <= limit,
            );
        }
        // gen icosphere LEVEL
        2 => {
            let level = value32(rest, 0);
            agrees(
                &format!("icosphere {level}"),
                &gen::check_icosphere(level),
                level <= MAX_ICOSPHERE_LEVEL,
            );
        }
        // gen ... --subdivide LEVELS (Loop or Catmull-Clark of a mesh of N face indices)
        3 => {
            let (indices, levels) = (value(rest, 0) as usize, value32(rest, 1));
            // An empty mesh stays empty at any level (0 x 4^levels is 0).
            let grown = if indices == 0 {
                Some(0)
            } else {
                4u128.checked_pow(levels).and_then(|f| f.checked_mul(indices as u128))
            };
            let within = grown.is_some_and(|g| g <= limit);
            agrees(
                &format!("subdivide {indices} x {levels}"),
                &gen::check_subdivision(indices, levels, "fuzz"),
                within,
            );
        }
        // strip --cache N [--lru] --algo ALGO: options as the CLI builds them, the
        // door's check, and an icosahedron stripped when accepted.
        4 => {
            let size = value(rest, 0) as usize;
            let algo = match value(rest, 1) % 4 {
                0 => Algorithm::cache(),
                1 => Algorithm::balanced(Algorithm::DEFAULT_MAX_ACMR),
                2 => Algorithm::auto(),
                _ => Algorithm::greedy(),
            };
            let model = if value(rest, 2) & 1 == 1 {
                CacheModel::lru(size)
            } else {
                CacheModel::fifo(size)
            };
            let options = StripOptions::default().algorithm(algo).cache_model(model);
            door(
                &format!("--cache {size}"),
                options,
                (1..=MAX_CACHE_SIZE).contains(&size),
            );
        }
        // strip --tunnel N (clap's range is 0 to MAX_TUNNEL_CUTS; the library's too)
        5 => {
            let n = value(rest, 0) as usize;
            let mut g = stripkit::GreedyOptions::default().heuristic(if n % 2 == 0 {
                Heuristic::Strips
            } else {
                Heuristic::Indices
            });
            g = g.tunnel_cuts(Some(n).filter(|&n| n > 0));
            let options = StripOptions::default().algorithm(Algorithm::Greedy(g));
            door(&format!("--tunnel {n}"), options, n <= MAX_TUNNEL_CUTS);
        }
        // distance --samples N, lod build-seq --samples N: refused outside 1..=MAX_SAMPLES
        // before any sample is taken; a small accepted count runs.
        6 => {
            let n = value(rest, 0) as usize;
            let within = (1..=stripkit::distance::MAX_SAMPLES).contains(&n);
            if !within || n <= 64 {
                let a = gen::icosphere(0);
                let result = stripkit::distance::distance(&a, &a, n)
                    .map(|d| assert!(d.hausdorff.is_finite()));
                agrees(&format!("--samples {n}"), &result, within);
            }
        }
        // --max-memory N: the three read budgets the CLI sets from it, on a small scene
        // and a small mesh; Ok or a bad input, and Ok from 1 MiB up.
        7 => {
            let n = value(rest, 0);
            let options = ReadOptions::default()
                .max_decompressed_bytes(n)
                .max_external_bytes(n)
                .max_decoded_bytes(Some(n));
            let glb = &crate::seeds::skin_morph_glb();
            let path = std::path::Path::new("/nonexistent-stripkit-fuzz/m.glb");
            match stripkit::scene::Scene::from_bytes(path, Format::Glb, glb, &options) {
                Ok(_) => {}
                Err(e) => {
                    assert!(crate::is_bad_input(&e), "--max-memory {n}: {e:?}");
                    assert!(n < 1 << 20, "--max-memory {n}: a 1 KB scene refused: {e}");
                }
            }
            if let Err(e) = stripkit::io::read_bytes_with(
                std::path::Path::new("m.glb"),
                Format::Glb,
                glb,
                &options,
            ) {
                assert!(
                    crate::is_bad_input(&e) && n < 1 << 20,
                    "--max-memory {n}: {e:?}"
                );
            }
        }
        // Named values (--algo, --split, --join, --heuristic, --weights): parsed by the
        // library's FromStr; an accepted algorithm goes through the door's check.
        _ => {
            let Ok(text) = std::str::from_utf8(rest) else {
                return;
            };
            let mut options = StripOptions::default();
            if let Ok(a) = text.parse::<Algorithm>() {
                options = options.algorithm(a);
            }
            if let Ok(s) = text.parse::<Split>() {
                options = options.split(s);
            }
            if let Ok(j) = text.parse::<Join>() {
                options = options.join(j);
            }
            let _ = text.parse::<Heuristic>();
            let _ = text.parse::<stripkit::Weights>();
            let _ = text.parse::<stripkit::simplify::Placement>();
            if let Err(e) = Stripifier::new(options.clone()) {
                assert!(e.is_invalid(), "{text:?}: {e:?}");
                return;
            }
            match stripkit::stripify(&gen::icosphere(0), &options) {
                Ok(_) => {}
                Err(e) => assert!(e.is_invalid(), "{text:?}: {e:?}"),
            }
        }
    }
}

/// Caches larger than this are checked but not run: `balanced` costs time in
/// proportion to the cache size even on 20 triangles (4,096 / 16,384 / 65,536
/// entries: 14 / 34 / 91 ms in release, 40 times that under the fuzzer's
/// instrumentation, past its 2 s timeout), a known cost of the option.
pub const MAX_RUN_CACHE: usize = 1024;

/// The door's check of `options` agrees with `within`; accepted options with a cache
/// of at most [`MAX_RUN_CACHE`] entries strip an icosahedron (Ok or an invalid input,
/// never a panic or a verification failure).
fn door(what: &str, options: StripOptions, within: bool) {
    let verdict = Stripifier::new(options.clone()).map(|_| ());
    agrees(what, &verdict, within);
    if verdict.is_ok() && options.cache.size <= MAX_RUN_CACHE {
        if let Err(e) = stripkit::stripify(&gen::icosphere(0), &options) {
            assert!(e.is_invalid(), "{what}: {e:?}");
        }
    }
}

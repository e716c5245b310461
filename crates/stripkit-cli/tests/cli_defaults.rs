//! The CLI and the library agree on every default: `strip` with no flags makes what
//! `StripOptions::default()` makes, each algorithm named without its flags runs with
//! the library's settings for it, and every default `strip --help` prints is the
//! library's.

mod support;

use std::path::Path;
use stripkit::{
    gen, stripify, Algorithm, GreedyOptions, Heuristic, Join, MatchingMode, SingleOptions, Split, StripOptions,
    Weights,
};
use support::{json, stripkit, tmp, write_mesh};

/// `strip INPUT -o OUT.json --json FLAGS`: the report and the written strips.
fn run(input: &Path, name: &str, flags: &[&str]) -> (serde_json::Value, serde_json::Value) {
    let out = tmp("defaults", name);
    let mut args = vec!["strip", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--json"];
    args.extend_from_slice(flags);
    let report = json(&stripkit(&args));
    let written: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    (report, written)
}

/// The report's figures and the written strips equal the library's for `options`.
fn same_as_library(mesh: &stripkit::Mesh, input: &Path, name: &str, flags: &[&str], options: &StripOptions) {
    let (report, written) = run(input, name, flags);
    let strips = stripify(mesh, options).unwrap();
    let what = format!("{flags:?}");
    assert_eq!(report["algo"], strips.algorithm.name(), "{what}");
    assert_eq!(report["join"], strips.join.name(), "{what}");
    let figures = serde_json::to_value(&strips.figures).unwrap();
    for key in ["strips", "swaps", "indices_restart", "indices_degenerate", "acmr", "acmr16", "acmr32", "cache"] {
        assert_eq!(report[key], figures[key], "{what}: {key}");
    }
    let want = strips.to_json();
    for key in ["join", "strips", "restart_index", "indices"] {
        assert_eq!(written.get(key), want.get(key), "{what}: {key}");
    }
    match &strips.algorithm {
        Algorithm::Greedy(g) => assert_eq!(report["heuristic"], g.heuristic.name(), "{what}"),
        _ => assert!(report.get("heuristic").is_none(), "{what}"),
    }
}

#[test]
fn strip_without_flags_is_the_library_default() {
    for (name, mesh) in [("tris", gen::icosphere(2)), ("quads", gen::grid_quads(6, 5))] {
        let input = tmp("defaults", &format!("{name}.obj"));
        write_mesh(&input, &mesh);
        let d = StripOptions::default();
        same_as_library(&mesh, &input, &format!("{name}-none.json"), &[], &d);
        // Each algorithm named alone runs with the library's settings for it.
        for algo in Algorithm::NAMES {
            let algorithm: Algorithm = algo.parse().unwrap();
            // The CLI refuses qstrip on a mesh without quads; quad-single takes closed
            // quad meshes only; single is run on the closed mesh.
            if matches!(algorithm, Algorithm::QuadSingle)
                || (name == "quads" && matches!(algorithm, Algorithm::Single(_)))
                || (name == "tris" && matches!(algorithm, Algorithm::Qstrip(_)))
            {
                continue;
            }
            let options = d.clone().algorithm(algorithm);
            same_as_library(&mesh, &input, &format!("{name}-{algo}.json"), &["--algo", algo], &options);
        }
    }
}

/// The default `strip --help` prints for `flag` ("... Default X." at the end of its line).
fn help_default(help: &str, flag: &str) -> String {
    let line = help
        .lines()
        .find(|l| l.trim_start().starts_with(&format!("{flag} ")) || l.trim_start().starts_with(&format!("{flag},")))
        .unwrap_or_else(|| panic!("{flag} is not in strip --help"));
    let (_, after) = line.rsplit_once("Default ").unwrap_or_else(|| panic!("{flag} states no default: {line}"));
    after.trim_end().trim_end_matches('.').split_whitespace().next().unwrap().to_string()
}

#[test]
fn every_default_in_help_is_the_library_default() {
    let out = stripkit(&["strip", "--help"]);
    assert!(out.status.success());
    let help = String::from_utf8(out.stdout).unwrap();
    assert!(help.lines().count() <= 60, "strip --help has {} lines", help.lines().count());
    let d = StripOptions::default();
    let greedy = GreedyOptions::default();
    let single = SingleOptions::default();
    let on_off = |b: bool| if b { "on" } else { "off" };
    let expected: Vec<(&str, String)> = vec![
        ("--algo", Algorithm::default().name().into()),
        ("--heuristic", greedy.heuristic.name().into()),
        ("--tunnel", greedy.tunnel_cuts.unwrap_or(0).to_string()),
        ("--cache", d.cache.size.to_string()),
        ("--max-acmr", Algorithm::DEFAULT_MAX_ACMR.to_string()),
        ("--split", d.split.name().into()),
        ("--join", d.join.name().into()),
        ("--restart-index", d.restart_index.to_string()),
        ("--weights", single.weights.to_string()),
        ("--swap-angle", single.swap_angle.map_or("off".into(), |a| a.to_string())),
        ("--cull-angle", single.cull_angle.to_string()),
        ("--cull-noise", on_off(single.cull_noise).into()),
        ("--seed", single.seed.to_string()),
        ("--matching", single.matching.name().into()),
    ];
    for (flag, want) in expected {
        assert_eq!(help_default(&help, flag), want, "{flag}");
    }
    // The defaults named in words are the library's values.
    assert_eq!(Heuristic::default(), Heuristic::Indices);
    assert_eq!((Split::default(), Join::default()), (Split::Auto, Join::Restart));
    assert_eq!((single.weights, MatchingMode::default()), (Weights::Uniform, MatchingMode::Auto));
}

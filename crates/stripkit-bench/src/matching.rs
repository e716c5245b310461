//! The `matching` comparison: stripkit's weighted perfect matching next to LEMON's
//! `MaxWeightedPerfectMatching` on the same graphs, in the same run.
//!
//! LEMON is used only when its header `/usr/include/lemon/matching.h` is present
//! (Debian: `apt-get install liblemon-dev`): a small C++ driver (our own code,
//! [`LEMON_DRIVER`]) is then compiled with `c++ -O2` into a temporary folder at run
//! time; otherwise the LEMON column says "LEMON not installed". Both sides time only
//! the matching itself (not reading the graph); stripkit's time includes checking its
//! certificate.

use anyhow::{bail, Context};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;
use stripkit::matching::{self, DualWeights, Graph, Objective};

/// Arguments of the `matching` comparison.
#[derive(clap::Args)]
pub struct Args {
    /// Icosphere levels whose dual graphs (20 * 4^level nodes) get random weights 1..=1000.
    #[arg(long, value_delimiter = ',', default_value = "6,7,8")]
    levels: Vec<u32>,
    #[command(flatten)]
    models: crate::common::Models,
    /// Loop subdivision levels applied to dragon.obj for the two-valued-weights row
    /// (2 gives 1.6M triangles); negative to skip.
    #[arg(long, default_value_t = 2, allow_negative_numbers = true)]
    dragon_levels: i32,
    /// Timed runs per graph and library; the median is reported.
    #[arg(long, default_value_t = 3)]
    runs: usize,
    /// Skip LEMON even when it is installed.
    #[arg(long)]
    no_lemon: bool,
    /// Keep the generated DIMACS files in this folder (default: a temporary folder).
    #[arg(long)]
    keep: Option<PathBuf>,
    /// Tie robustness instead of the comparison table: the dragon.obj Loop x`--dragon-levels`
    /// dual graph with weights 1|2 drawn with seeds 1..=SEEDS, each in two edge orders
    /// (as generated, and sorted by (u, v)); every instance solved once, per-instance
    /// seconds and min / median / max per order, LEMON on the same instances when
    /// installed. Repeat with `stripkit-bench matching --ties 5`.
    #[arg(long, value_name = "SEEDS")]
    ties: Option<u64>,
}

/// The LEMON driver: reads a DIMACS-style graph, runs MaxWeightedPerfectMatching
/// (weights negated for `min`), prints `perfect weight milliseconds`.
pub const LEMON_DRIVER: &str = r#"
#include <lemon/smart_graph.h>
#include <lemon/matching.h>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <vector>
using namespace lemon;
int main(int argc, char** argv) {
  if (argc < 2) { std::fprintf(stderr, "usage: driver FILE [min]\n"); return 2; }
  bool minimize = argc > 2 && std::strcmp(argv[2], "min") == 0;
  FILE* f = std::fopen(argv[1], "r");
  if (!f) { std::perror(argv[1]); return 2; }
  SmartGraph g;
  SmartGraph::EdgeMap<long long> w(g);
  std::vector<SmartGraph::Node> nodes;
  char line[512];
  while (std::fgets(line, sizeof line, f)) {
    if (line[0] == 'p') {
      char kind[64]; long long n, m;
      if (std::sscanf(line, "p %63s %lld %lld", kind, &n, &m) != 3) return 2;
      g.reserveNode(n); g.reserveEdge(m);
      for (long long i = 0; i < n; ++i) nodes.push_back(g.addNode());
    } else if (line[0] == 'e') {
      long long u, v, x;
      if (std::sscanf(line, "e %lld %lld %lld", &u, &v, &x) != 3) return 2;
      if (u == v) continue;
      SmartGraph::Edge e = g.addEdge(nodes[u - 1], nodes[v - 1]);
      w[e] = minimize ? -x : x;
    }
  }
  std::fclose(f);
  auto t0 = std::chrono::steady_clock::now();
  MaxWeightedPerfectMatching<SmartGraph, SmartGraph::EdgeMap<long long> > mwpm(g, w);
  bool ok = mwpm.run();
  auto t1 = std::chrono::steady_clock::now();
  long long weight = ok ? mwpm.matchingWeight() : 0;
  if (minimize) weight = -weight;
  std::printf("%d %lld %.3f\n", ok ? 1 : 0, weight,
              std::chrono::duration<double, std::milli>(t1 - t0).count());
  return 0;
}
"#;

struct Row {
    name: String,
    graph: Graph,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    v[v.len() / 2]
}

/// Compiles the LEMON driver into `dir`; `Ok(None)` when LEMON is not installed.
fn build_lemon(dir: &Path) -> anyhow::Result<Option<PathBuf>> {
    if !Path::new("/usr/include/lemon/matching.h").exists() {
        return Ok(None);
    }
    let src = dir.join("lemon_driver.cpp");
    let exe = dir.join("lemon_driver");
    std::fs::write(&src, LEMON_DRIVER)?;
    let out = Command::new("c++")
        .args(["-O2", "-DNDEBUG", "-o"])
        .arg(&exe)
        .arg(&src)
        .output()
        .context("running c++ to build the LEMON driver")?;
    if !out.status.success() {
        bail!("building the LEMON driver failed:\n{}", String::from_utf8_lossy(&out.stderr));
    }
    Ok(Some(exe))
}

fn run_lemon(exe: &Path, file: &Path) -> anyhow::Result<(bool, i64, f64)> {
    let out = Command::new(exe).arg(file).output()?;
    if !out.status.success() {
        bail!("LEMON driver failed: {}", String::from_utf8_lossy(&out.stderr));
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let f: Vec<&str> = text.split_whitespace().collect();
    if f.len() != 3 {
        bail!("unexpected LEMON driver output `{text}`");
    }
    Ok((f[0] == "1", f[1].parse()?, f[2].parse()?))
}

/// The two-valued dual graph of the bench: `DualWeights::Random { seed }` folded to
/// weights 1|2 by the parity of the drawn weight.
fn two_valued(mesh: &stripkit::Mesh, seed: u64) -> anyhow::Result<Graph> {
    let g = matching::mesh_dual_graph(mesh, DualWeights::Random { seed })?;
    let w: Vec<i64> = g.weights().iter().map(|&w| 1 + (w & 1)).collect();
    Ok(Graph::new(g.node_count(), g.edges().to_vec(), w)?)
}

/// The same graph with its edges listed in (u, v) order (each edge as u < v).
fn sorted_edges(g: &Graph) -> anyhow::Result<Graph> {
    let mut e: Vec<([u32; 2], i64)> =
        g.edges().iter().zip(g.weights()).map(|(&[a, b], &w)| ([a.min(b), a.max(b)], w)).collect();
    e.sort_unstable();
    Ok(Graph::new(g.node_count(), e.iter().map(|x| x.0).collect(), e.iter().map(|x| x.1).collect())?)
}

fn min_med_max(v: &[f64]) -> String {
    if v.is_empty() {
        return "-".into();
    }
    let mut s = v.to_vec();
    s.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    format!("{:.2} / {:.2} / {:.2}", s[0], s[s.len() / 2], s[s.len() - 1])
}

/// `--ties SEEDS`: the two-valued dragon graph over seeds and edge orders.
fn run_ties(args: &Args, seeds: u64, tmp: &Path) -> anyhow::Result<()> {
    let dir = args.models.dir().context("no models folder (--models)")?;
    let levels = args.dragon_levels.max(0) as u32;
    let mesh = crate::common::read_surface(&dir.join("dragon.obj"))?;
    let mesh = stripkit::gen::subdivide_loop(&mesh, levels)?;
    let lemon = if args.no_lemon { None } else { build_lemon(tmp)? };
    println!("dragon.obj Loop x{levels} dual, weights 1|2; seconds of one solve (certificate checked)");
    println!();
    println!("| seed | order | nodes | edges | weight | stripkit s | exposed after greedy | augmentations | blossoms formed | LEMON s |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let orders = ["generated", "sorted"];
    let mut times = [Vec::new(), Vec::new()];
    let mut ltimes = [Vec::new(), Vec::new()];
    for seed in 1..=seeds {
        let generated = two_valued(&mesh, seed)?;
        let sorted = sorted_edges(&generated)?;
        for (o, g) in [generated, sorted].iter().enumerate() {
            let t = Instant::now();
            let m = matching::solve(g, Objective::MaxWeight)?;
            let secs = t.elapsed().as_secs_f64();
            if !m.certified {
                bail!("seed {seed} {}: certificate not checked", orders[o]);
            }
            times[o].push(secs);
            let lemon_s = match &lemon {
                None if args.no_lemon => "skipped".to_string(),
                None => "LEMON not installed".to_string(),
                Some(exe) => {
                    let file = tmp.join(format!("ties-{seed}-{}.dimacs", orders[o]));
                    std::fs::write(&file, g.to_dimacs())?;
                    let cell = match run_lemon(exe, &file) {
                        Ok((ok, w, ms)) => {
                            if ok && m.perfect && w != m.total_weight {
                                bail!("seed {seed}: LEMON weight {w} differs from stripkit {}", m.total_weight);
                            }
                            ltimes[o].push(ms / 1e3);
                            format!("{:.2}", ms / 1e3)
                        }
                        Err(e) => format!("failed: {}", e.to_string().lines().next().unwrap_or("")),
                    };
                    if args.keep.is_none() {
                        let _ = std::fs::remove_file(&file);
                    }
                    cell
                }
            };
            if args.keep.is_some() && lemon.is_none() {
                std::fs::write(tmp.join(format!("ties-{seed}-{}.dimacs", orders[o])), g.to_dimacs())?;
            }
            println!(
                "| {seed} | {} | {} | {} | {} | {secs:.2} | {} | {} | {} | {lemon_s} |",
                orders[o],
                g.node_count(),
                g.edge_count(),
                m.total_weight,
                m.stats.exposed_after_init,
                m.stats.augmentations,
                m.stats.blossoms_formed,
            );
        }
    }
    println!();
    println!("| order | stripkit s min / median / max | LEMON s min / median / max |");
    println!("|---|---|---|");
    for o in 0..2 {
        println!("| {} | {} | {} |", orders[o], min_med_max(&times[o]), min_med_max(&ltimes[o]));
    }
    let all: Vec<f64> = times.concat();
    let lall: Vec<f64> = ltimes.concat();
    println!("| both | {} | {} |", min_med_max(&all), min_med_max(&lall));
    Ok(())
}

/// Runs the comparison and prints a markdown table.
pub fn run(args: Args) -> anyhow::Result<()> {
    if let Some(seeds) = args.ties {
        let (tmp, remove) = match &args.keep {
            Some(d) => (d.clone(), false),
            None => (std::env::temp_dir().join(format!("stripkit-bench-ties-{}", std::process::id())), true),
        };
        std::fs::create_dir_all(&tmp)?;
        let r = run_ties(&args, seeds.max(1), &tmp);
        if remove {
            let _ = std::fs::remove_dir_all(&tmp);
        }
        return r;
    }
    let runs = args.runs.max(1);
    let mut rows = Vec::new();
    for &level in &args.levels {
        let mesh = stripkit::gen::icosphere(level);
        rows.push(Row {
            name: format!("icosphere {level} dual, random 1..1000"),
            graph: matching::mesh_dual_graph(&mesh, DualWeights::Random { seed: 1 })?,
        });
    }
    let models = args.models.dir();
    if let Some(dir) = &models {
        let bunny = dir.join("bunny.obj");
        if bunny.exists() {
            let mesh = crate::common::read_surface(&bunny)?;
            rows.push(Row {
                name: "bunny.obj dual, random 1..1000".into(),
                graph: matching::mesh_dual_graph(&mesh, DualWeights::Random { seed: 1 })?,
            });
        }
        let dragon = dir.join("dragon.obj");
        if dragon.exists() && args.dragon_levels >= 0 {
            let mesh = crate::common::read_surface(&dragon)?;
            let mesh = stripkit::gen::subdivide_loop(&mesh, args.dragon_levels as u32)?;
            let g = matching::mesh_dual_graph(&mesh, DualWeights::Random { seed: 1 })?;
            // Two-valued weights: 1 or 2.
            let w: Vec<i64> = g.weights().iter().map(|&w| 1 + (w & 1)).collect();
            rows.push(Row {
                name: format!("dragon.obj Loop x{} dual, weights 1|2", args.dragon_levels),
                graph: Graph::new(g.node_count(), g.edges().to_vec(), w)?,
            });
        }
    }
    let tmp = match &args.keep {
        Some(d) => {
            std::fs::create_dir_all(d)?;
            d.clone()
        }
        None => {
            let d = std::env::temp_dir().join(format!("stripkit-bench-matching-{}", std::process::id()));
            std::fs::create_dir_all(&d)?;
            d
        }
    };
    let lemon = if args.no_lemon { None } else { build_lemon(&tmp)? };
    println!("| graph | nodes | edges | perfect | stripkit weight | stripkit ms (median of {runs}) | exposed after greedy | LEMON ms | LEMON weight | stripkit unweighted ms |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (i, row) in rows.iter().enumerate() {
        let g = &row.graph;
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..runs {
            let t = Instant::now();
            let m = matching::solve(g, Objective::MaxWeight)?;
            times.push(t.elapsed().as_secs_f64() * 1e3);
            if !m.certified {
                bail!("{}: certificate not checked", row.name);
            }
            last = Some(m);
        }
        let m = last.context("no run")?;
        let mut ut = Vec::new();
        for _ in 0..runs {
            let t = Instant::now();
            let mate = matching::maximum_cardinality_matching(g);
            ut.push(t.elapsed().as_secs_f64() * 1e3);
            let card = mate.iter().filter(|&&x| x != matching::UNMATCHED).count();
            if card != 2 * m.edges.len() {
                bail!("{}: unweighted cardinality {card} differs from {}", row.name, 2 * m.edges.len());
            }
        }
        let (lemon_ms, lemon_w) = match &lemon {
            None if args.no_lemon => ("skipped".to_string(), "-".to_string()),
            None => ("LEMON not installed".to_string(), "-".to_string()),
            Some(exe) => {
                let file = tmp.join(format!("graph{i}.dimacs"));
                std::fs::write(&file, g.to_dimacs())?;
                let mut lt = Vec::new();
                let mut res = (false, 0, 0.0);
                for _ in 0..runs {
                    res = run_lemon(exe, &file)?;
                    lt.push(res.2);
                }
                if res.0 && m.perfect && res.1 != m.total_weight {
                    bail!("{}: LEMON weight {} differs from stripkit {}", row.name, res.1, m.total_weight);
                }
                if args.keep.is_none() {
                    let _ = std::fs::remove_file(&file);
                }
                (
                    format!("{:.1}", median(lt)),
                    if res.0 { res.1.to_string() } else { "no perfect matching".into() },
                )
            }
        };
        println!(
            "| {} | {} | {} | {} | {} | {:.1} | {} | {} | {} | {} |",
            row.name,
            g.node_count(),
            g.edge_count(),
            m.perfect,
            m.total_weight,
            median(times),
            m.stats.exposed_after_init,
            lemon_ms,
            lemon_w,
            if ut.is_empty() { "-".to_string() } else { format!("{:.1}", median(ut)) }
        );
    }
    if args.keep.is_none() {
        let _ = std::fs::remove_dir_all(&tmp);
    }
    Ok(())
}

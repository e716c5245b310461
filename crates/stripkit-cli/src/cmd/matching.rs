//! `stripkit match`: weighted perfect matching on a DIMACS-style graph file or on a
//! mesh's dual graph, with the optimality certificate checked before anything is
//! printed.

use anyhow::Context;
use std::path::PathBuf;
use std::time::Instant;
use stripkit::matching::{self, DualWeights, Graph, Objective};

/// Arguments of `stripkit match`.
#[derive(clap::Args)]
#[command(after_help = "Graph files: a line `p edge N M`, then M lines `e U V W` (1-based \
vertices, integer weights, |W| <= 2^40); lines starting with `c` are comments. Self-loops are \
ignored; of parallel edges the best one is used.\n\nWhen the graph has no perfect matching the \
result says `perfect: false` and gives a maximum-cardinality matching of best weight.\n\n\
Exit status: 0 done, 1 the certificate check failed, 2 bad input.")]
pub struct Args {
    /// Graph file in DIMACS-style text (`p edge N M`, `e U V W` lines).
    #[arg(required_unless_present = "dual", conflicts_with = "dual")]
    pub file: Option<PathBuf>,
    /// Match the dual graph of this mesh (OBJ, OFF, PLY, STL; `.gz` allowed) instead of
    /// a graph file: one node per triangle, one edge per manifold, consistently
    /// oriented mesh edge.
    #[arg(long, value_name = "MESHFILE")]
    pub dual: Option<PathBuf>,
    /// Edge weights of the dual graph (with --dual; a graph file has its own):
    /// `uniform` (every edge 1), `random` (integers 1..=1000 seeded by --seed) or
    /// `normal-angle` (dihedral angle, round(angle / pi * 1000)). Default `random`.
    #[arg(long, requires = "dual", value_parser = super::named::<DualWeights>(DualWeights::NAMES))]
    pub weights: Option<DualWeights>,
    /// Seed for --weights random (with --dual). Default 1.
    #[arg(long, requires = "dual")]
    pub seed: Option<u64>,
    /// Minimise the total weight (minimum-cost perfect matching) instead of maximising it.
    #[arg(long)]
    pub minimize: bool,
    /// Print one JSON object (nodes, edges, perfect, matched_nodes, total_weight,
    /// certified, ms, ...) instead of text.
    #[arg(long)]
    pub json: bool,
    /// Also write the matched edges, one `U V W` line each (1-based), to this file.
    #[arg(long, short, value_name = "FILE")]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub read: super::ReadArgs,
}

/// Runs the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    // Clap's `requires` lets these through without --dual: say so instead of
    // ignoring them (a graph file carries its own weights).
    anyhow::ensure!(
        args.dual.is_some() || (args.weights.is_none() && args.seed.is_none()),
        "--weights and --seed apply to --dual (a graph file carries its own weights)"
    );
    if let Some(out) = &args.output {
        // A list of matched edges, never a mesh: a mesh name would be read as one.
        if stripkit::io::Format::from_path(out).is_some() {
            return Err(stripkit::Error::Invalid(format!(
                "-o {}: the matched edges (`U V W` lines) are written there, not a mesh; name it .txt",
                out.display()
            ))
            .into());
        }
        let inputs: Vec<(&str, &std::path::Path)> = [("graph file", &args.file), ("--dual mesh", &args.dual)]
            .into_iter()
            .filter_map(|(name, p)| p.as_deref().map(|p| (name, p)))
            .collect();
        super::check_not_inputs(&inputs, &[("-o", out)])?;
        super::check_output_folder(out)?;
    }
    let t0 = Instant::now();
    let (graph, source) = if let Some(mesh_path) = &args.dual {
        let mesh = args.read.read_surface(mesh_path)?;
        anyhow::ensure!(
            args.seed.is_none() || matches!(args.weights, None | Some(DualWeights::Random { .. })),
            "--seed applies to --weights random"
        );
        let mut w = args.weights.unwrap_or_default();
        if let (DualWeights::Random { seed }, Some(s)) = (&mut w, args.seed) {
            *seed = s;
        }
        let g = matching::mesh_dual_graph(&mesh, w)
            .with_context(|| format!("{}: building the dual graph", mesh_path.display()))?;
        (g, mesh_path.display().to_string())
    } else {
        let path = args.file.as_ref().context("no graph file given")?;
        (Graph::read_dimacs(path)?, path.display().to_string())
    };
    let read_ms = t0.elapsed().as_secs_f64() * 1e3;
    let obj = if args.minimize { Objective::MinCost } else { Objective::MaxWeight };
    let spinner = indicatif::ProgressBar::new_spinner();
    spinner.set_draw_target(indicatif::ProgressDrawTarget::stderr());
    spinner.set_message(format!("matching {} nodes, {} edges", graph.node_count(), graph.edge_count()));
    spinner.enable_steady_tick(std::time::Duration::from_millis(120));
    let t1 = Instant::now();
    let result = matching::solve(&graph, obj);
    let ms = t1.elapsed().as_secs_f64() * 1e3;
    spinner.finish_and_clear();
    let m = result?;
    if let Some(out) = &args.output {
        stripkit::io::write_encoded(out, graph.to_edge_lines(&m.edges).as_bytes())
            .with_context(|| format!("{}: cannot write", out.display()))?;
    }
    let matched_nodes = 2 * m.edges.len();
    if args.json {
        let v = serde_json::json!({
            "source": source,
            "objective": if args.minimize { "min-cost" } else { "max-weight" },
            "nodes": graph.node_count(),
            "edges": graph.edge_count(),
            "perfect": m.perfect,
            "matched_nodes": matched_nodes,
            "total_weight": m.total_weight,
            "certified": m.certified,
            "ms": (ms * 1000.0).round() / 1000.0,
            "read_ms": (read_ms * 1000.0).round() / 1000.0,
            "exposed_after_init": m.stats.exposed_after_init,
            "augmentations": m.stats.augmentations,
            "blossoms_formed": m.stats.blossoms_formed,
            "blossoms_expanded": m.stats.blossoms_expanded,
        });
        println!("{v}");
    } else {
        println!("{source}: {} nodes, {} edges", graph.node_count(), graph.edge_count());
        if m.perfect {
            println!(
                "perfect matching, {} {}: total weight {}",
                m.edges.len(),
                if args.minimize { "edges of minimum cost" } else { "edges of maximum weight" },
                m.total_weight
            );
        } else {
            println!(
                "no perfect matching: maximum-cardinality matching of {} edges ({} of {} nodes \
                 matched), {} total weight {}",
                m.edges.len(),
                matched_nodes,
                graph.node_count(),
                if args.minimize { "minimum" } else { "maximum" },
                m.total_weight
            );
        }
        println!(
            "certificate: {}",
            if m.certified { "checked (dual feasible, complementary slackness holds)" } else { "none" }
        );
        println!("time: {ms:.1} ms (reading {read_ms:.1} ms)");
    }
    Ok(())
}

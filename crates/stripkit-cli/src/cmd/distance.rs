//! `stripkit distance`: symmetric Hausdorff and RMS distance between two surfaces.

use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `stripkit distance`.
#[derive(clap::Args)]
pub struct Args {
    /// First mesh (the reference: relative figures use its bounding-box diagonal).
    pub a: PathBuf,
    /// Second mesh.
    pub b: PathBuf,
    /// Points sampled on each surface (area-weighted, fixed seed), each measured
    /// exactly against the other surface. 1 to 10,000,000 (about 480 MB).
    #[arg(long, default_value_t = stripkit::distance::DEFAULT_SAMPLES)]
    pub samples: usize,
    /// Print one JSON object (hausdorff, rms, diagonal, relative figures, both
    /// one-sided figures, ms) on stdout.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: super::ReadArgs,
}

/// Runs the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    // Checked before reading the meshes, so a typo fails at once.
    let max = stripkit::distance::MAX_SAMPLES;
    anyhow::ensure!(
        (1..=max).contains(&args.samples),
        "--samples {} is out of range: 1 to {max} (each sample takes 24 bytes, on both surfaces)",
        args.samples
    );
    let a = args.read.read(&args.a)?;
    let b = args.read.read(&args.b)?;
    let start = Instant::now();
    let d = stripkit::distance::distance_with(&a, &b, args.samples, super::threads())?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    let rel = |x: f64| d.relative(x);
    if args.json {
        let side = |s: &stripkit::distance::OneSided| serde_json::json!({"max": s.max, "rms": s.rms, "mean": s.mean});
        let out = serde_json::json!({
            "hausdorff": d.hausdorff,
            "rms": d.rms,
            "diagonal": d.diagonal,
            "hausdorff_relative": rel(d.hausdorff),
            "rms_relative": rel(d.rms),
            "a_to_b": side(&d.a_to_b),
            "b_to_a": side(&d.b_to_a),
            "samples": args.samples,
            "ms": ms,
        });
        println!("{out}");
    } else {
        println!(
            "hausdorff {:.6e} ({:.4}% of diagonal)\nrms       {:.6e} ({:.4}% of diagonal)\ndiagonal  {:.6e}\n{} samples per surface, {:.1} ms",
            d.hausdorff,
            100.0 * rel(d.hausdorff),
            d.rms,
            100.0 * rel(d.rms),
            d.diagonal,
            args.samples,
            ms
        );
    }
    Ok(())
}

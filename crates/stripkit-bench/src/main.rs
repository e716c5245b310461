//! `stripkit-bench`: stripkit next to other libraries, on a folder of meshes, in one
//! run; writes markdown tables. One module per comparison.

mod batch;
mod cache_race;
mod buffers;
mod common;
mod cull;
mod cull_gpu;
mod batch_strips;
mod probe_variants;
mod gpu;
mod strips;
mod simplify;
mod matching;
mod single;
mod lod;
mod lod_coarse;
mod chart;
mod scale;
mod scale_phase;

use clap::{Parser, Subcommand};

/// Side-by-side comparisons of stripkit with other libraries.
#[derive(Parser)]
#[command(name = "stripkit-bench", about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Stripifiers: stripkit's modes next to meshoptimizer, every figure by stripkit's decoder.
    Strips(strips::Args),
    /// stripkit's `cache` against meshoptimizer's vcache + stripify on one mesh, in turns.
    CacheRace(cache_race::Args),
    /// Simplification: stripkit's QEM next to meshoptimizer's simplify.
    Simplify(simplify::Args),
    /// Draw times on the GPU (or llvmpipe) of every index buffer: lists, meshoptimizer's strips, stripkit's modes.
    Gpu(gpu::Args),
    /// Fits the GPU batch model to invocation counts measured by `gpu --json`.
    GpuModel(batch::Args),
    /// Modelled vertex shading (the H100 batch model) and indices of stripkit's strips next to meshoptimizer's list.
    BatchStrips(batch_strips::Args),
    /// Weighted perfect matching: stripkit next to LEMON (when installed).
    Matching(matching::Args),
    /// Single strips for every weight kind: strips, Steiner vertices, swaps, acmr16/32
    /// next to meshoptimizer's cache order, times.
    Single(single::Args),
    /// Back-face culling along the helix: single strips with segment trees next to greedy strips and meshoptimizer's meshlets.
    Cull(cull::Args),
    /// Frame time along the helix on the GPU (or llvmpipe): single strips (cull, cache,
    /// uniform weights) drawn whole against the segment tree's ranges.
    CullGpu(cull_gpu::Args),
    /// SETS multiresolution strips: size, strips of a level against greedy from scratch, and next
    /// to a discrete LoD chain of meshoptimizer's simplify (memory, levels, switch time, distances).
    Lod(lod::Args),
    /// Time and peak memory per triangle of read, the stripifiers, verify and the writes
    /// on Loop subdivisions 1x-64x, at 1 and N threads, beside meshoptimizer; a log-log PNG.
    Scale(scale::Args),
    /// One phase of `scale` in a process of its own (run by `scale`).
    #[command(hide = true)]
    ScalePhase(scale_phase::Args),
}

fn main() -> anyhow::Result<()> {
    match Cli::parse().command {
        Command::Strips(a) => strips::run(a),
        Command::CacheRace(a) => cache_race::run(a),
        Command::Simplify(a) => simplify::run(a),
        Command::Matching(a) => matching::run(a),
        Command::Gpu(a) => gpu::run(a),
        Command::GpuModel(a) => batch::run(a),
        Command::BatchStrips(a) => batch_strips::run(a),
        Command::Single(a) => single::run(a),
        Command::Cull(a) => cull::run(a),
        Command::CullGpu(a) => cull_gpu::run(a),
        Command::Lod(a) => lod::run(a),
        Command::Scale(a) => scale::run(a),
        Command::ScalePhase(a) => scale_phase::run(a),
    }
}

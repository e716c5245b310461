//! What `stripkit strip` prints: the report of a mesh run (text summary, one line
//! per file in a folder run, or JSON) and of a glTF scene run.

use super::VertexOrder;
use serde::Serialize;
use std::io::Write;
use std::path::Path;
use stripkit::{CacheKind, Figures, Join};

/// The JSON object printed by `--json` (and embedded in `.json` outputs).
#[derive(Serialize)]
pub struct Report<'a> {
    pub input: &'a Path,
    pub output: &'a Path,
    pub algo: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub heuristic: Option<&'static str>,
    pub join: Join,
    pub vertex_order: VertexOrder,
    pub vertices: usize,
    /// Vertices welded onto a bit-identical one before stripping (0 with --no-weld).
    pub welded: usize,
    #[serde(flatten)]
    pub figures: &'a Figures,
    /// Milliseconds of the stripify call alone.
    pub ms: f64,
    /// `cache` and `balanced`: how the quads were split (`fan` or `qstrip`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub diagonals: Option<&'static str>,
    /// QSTRIP only: quads stripped as quads.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub quads: Option<usize>,
    /// QSTRIP only: `indices_restart / quads` (docs/metrics.md).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub indices_per_quad: Option<f64>,
    /// `single` only: Steiner vertices, swaps, pieces merged, times.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub single: Option<&'a stripkit::SingleReport>,
    /// `balanced` only, when its `--max-acmr` was out of reach: the misses per
    /// triangle reached instead (FIFO of `--cache` entries).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_acmr_unreached: Option<f64>,
}


/// What `strip` reports for a glTF scene.
#[derive(Serialize)]
pub struct SceneCliReport<'a> {
    pub input: &'a Path,
    pub output: &'a Path,
    pub join: Join,
    /// Always true: every primitive was verified, and the written file read back and
    /// checked (a failure is an error and writes nothing), as in the mesh report.
    pub verified: bool,
    pub vertex_order: VertexOrder,
    /// Reading and decoding the input, in milliseconds.
    pub read_ms: f64,
    /// Encoding, checking (read back) and writing the output, in milliseconds.
    pub write_ms: f64,
    #[serde(flatten)]
    pub scene: &'a stripkit::scene::SceneReport,
}

/// The text summary of a scene run; `line`: one line for a folder run.
pub fn print_scene(out: &mut impl Write, r: &SceneCliReport, line: bool) -> std::io::Result<()> {
    let s = r.scene;
    if line {
        return writeln!(
            out,
            "{} -> {}: {} triangles, {} primitives, {} indices stitched, {} with restart, {:.1} ms",
            r.input.display(),
            r.output.display(),
            s.triangles,
            s.primitives.len(),
            s.indices_stitched,
            s.indices_drawn_restart,
            s.total_ms
        );
    }
    writeln!(
        out,
        "{} -> {} (scene: {} triangle primitives stripped, {} left as read; {})",
        r.input.display(),
        r.output.display(),
        s.primitives.len(),
        s.skipped,
        if r.join == Join::Restart {
            "EXT_mesh_primitive_restart with stitched fallback"
        } else {
            "stitched strips"
        }
    )?;
    writeln!(out, "verified: {} triangles, 0 lost, 0 added, 0 flipped; written file read back and checked", s.triangles)?;
    writeln!(out, "  welded vertices      {:>10}", s.welded)?;
    if s.kept_as_read > 0 {
        writeln!(
            out,
            "  kept as read         {:>10} (their strips would take more index bytes than their own indices)",
            s.kept_as_read
        )?;
    }
    writeln!(out, "  indices read         {:>10}", s.indices_read)?;
    writeln!(out, "  indices stitched     {:>10}", s.indices_stitched)?;
    if r.join == Join::Restart {
        writeln!(out, "  indices restart      {:>10}", s.indices_drawn_restart)?;
    }
    const SHOWN: usize = 20;
    if s.primitives.len() > SHOWN {
        writeln!(out, "  (the first {SHOWN} of {} primitives; --json lists all)", s.primitives.len())?;
    }
    for p in s.primitives.iter().take(SHOWN) {
        writeln!(
            out,
            "  meshes[{}].primitives[{}]: {} triangles, {} strips, {} -> {} indices{} ({}{}{})",
            p.mesh,
            p.primitive,
            p.figures.triangles,
            p.figures.strips,
            p.indices_read,
            p.indices_stitched,
            p.indices_restart.map(|n| format!(" (restart {n})")).unwrap_or_default(),
            p.algorithm,
            if p.welded > 0 { format!(", {} welded", p.welded) } else { String::new() },
            if p.kept_as_read { ", kept as read: strips were larger" } else { "" }
        )?;
    }
    Ok(())
}

/// A folder run's line for one file.
pub fn print_line(out: &mut impl Write, r: &Report) -> std::io::Result<()> {
    let f = r.figures;
    writeln!(
        out,
        "{} -> {}: {} triangles, {} strips, {} indices ({:.3} per triangle), acmr16 {:.3}, {:.1} ms",
        r.input.display(),
        r.output.display(),
        f.triangles,
        f.strips,
        f.indices_restart,
        f.indices_per_triangle,
        f.acmr16,
        r.ms
    )
}

pub fn print_summary(out: &mut impl Write, r: &Report) -> std::io::Result<()> {
    let f = r.figures;
    writeln!(
        out,
        "{} -> {} ({}{}, join {})",
        r.input.display(),
        r.output.display(),
        r.algo,
        r.heuristic.map(|h| format!(", heuristic {h}")).unwrap_or_default(),
        r.join.name()
    )?;
    writeln!(
        out,
        "verified: {} triangles, 0 lost, 0 added, 0 flipped{}",
        f.triangles,
        if f.dropped_degenerate > 0 {
            format!(
                " ({} degenerate input triangles dropped)",
                f.dropped_degenerate
            )
        } else {
            String::new()
        }
    )?;
    if let Some(s) = r.single.filter(|s| s.triangles_added > 0 || s.swapped_edges > 0) {
        writeln!(
            out,
            "  (against the changed mesh: {} input triangles + {} from edge splits, {} edges swapped)",
            f.triangles - s.triangles_added,
            s.triangles_added,
            s.swapped_edges
        )?;
    }
    let stitched = if r.join == stripkit::Join::Degenerate && f.strips > 1 {
        " (written stitched by degenerate triangles: one strip per material group)".to_string()
    } else {
        String::new()
    };
    writeln!(out, "  welded vertices      {:>10}", r.welded)?;
    writeln!(out, "  strips               {:>10}{stitched}", f.strips)?;
    writeln!(out, "  swaps                {:>10}", f.swaps)?;
    writeln!(out, "  indices_separate     {:>10}", f.indices_separate)?;
    writeln!(out, "  indices_restart      {:>10}", f.indices_restart)?;
    writeln!(out, "  indices_degenerate   {:>10}", f.indices_degenerate)?;
    writeln!(
        out,
        "  indices_per_triangle {:>10.4}",
        f.indices_per_triangle
    )?;
    if let Some(d) = r.diagonals {
        writeln!(out, "  quads split along    {:>10}", d)?;
    }
    if let (Some(q), Some(ipq)) = (r.quads, r.indices_per_quad) {
        writeln!(out, "  quads                {:>10}", q)?;
        writeln!(out, "  indices_per_quad     {:>10.4}", ipq)?;
    }
    writeln!(out, "  acmr16 (FIFO)        {:>10.4}", f.acmr16)?;
    writeln!(out, "  acmr32 (FIFO)        {:>10.4}", f.acmr32)?;
    let kind = match f.cache.kind {
        CacheKind::Fifo => "FIFO",
        CacheKind::Lru => "LRU",
    };
    if !(f.cache.kind == CacheKind::Fifo && (f.cache.size == 16 || f.cache.size == 32)) {
        writeln!(
            out,
            "  acmr{} ({kind}){:>w$.4}",
            f.cache.size,
            f.acmr,
            w = 20usize.saturating_sub(format!("acmr{} ({kind})", f.cache.size).len()) + 11
        )?;
    }
    if let Some(s) = r.single {
        let islands = s.uv_islands.map(|n| format!(", {n} UV island(s)")).unwrap_or_default();
        writeln!(
            out,
            "  pieces               {:>10} (of GPU vertices: one strip each at best; {} surface(s){islands})",
            s.components, s.surfaces
        )?;
        writeln!(out, "  path ends forced     {:>10} (by boundary and seam triangles; a strip has two)", s.forced_ends)?;
        writeln!(out, "  triangles added      {:>10} (edge splits)", s.triangles_added)?;
        writeln!(out, "  vertices added       {:>10} (Steiner vertices)", s.vertices_added)?;
        if s.clusters > 0 {
            writeln!(out, "  cull clusters        {:>10} ({} peaks split)", s.clusters, s.cull_peaks)?;
            if s.boundary_edges > 0 {
                writeln!(out, "  boundary crossings   {:>10} (of {} boundary edges)", s.boundary_crossings, s.boundary_edges)?;
            }
        }
        writeln!(out, "  swapped_edges        {:>10}", s.swapped_edges)?;
        if s.swapped_edges > 0 {
            writeln!(out, "  max swap deviation   {:>10.3e}", s.max_swap_deviation)?;
        }
        writeln!(out, "  pieces merged        {:>10} ({} paths; {} nodal, {} joins, {} attaches)", s.initial_pieces, s.initial_paths, s.nodal, s.joins, s.attaches)?;
        writeln!(
            out,
            "  ms: weights {:.1}, matching {:.1}, merge {:.1}",
            s.weights_ms, s.matching_ms, s.merge_ms
        )?;
    }
    writeln!(out, "  stripify ms          {:>10.2}", r.ms)?;
    Ok(())
}

/// One-line notes on standard error about what other loaders make of the written
/// strips (never in the `--json` data): PLY `tristrips` (`ply`), and the zero-area
/// triangles a stitched strip decodes to (`degenerate` of `triangles`). `restart`: the
/// file also holds EXT_mesh_primitive_restart groups.
pub fn loader_notes(output: &Path, ply: bool, degenerate: usize, triangles: usize, restart: bool) {
    if ply {
        eprintln!(
            "note: {}: PLY `tristrips` element; trimesh and Open3D read it as 0 faces (write .glb or .obj for them)",
            output.display()
        );
    }
    if degenerate > 0 {
        eprintln!(
            "note: {}: the stitched strips add {degenerate} zero-area triangles (swaps and joins) to the {triangles}; \
             loaders that keep every triangle (trimesh, Open3D) count {} faces{}",
            output.display(),
            triangles + degenerate,
            if restart { "; viewers with EXT_mesh_primitive_restart draw its groups instead" } else { "" }
        );
    }
}

//! What `stripkit render` reports: one JSON object, or a short summary.

use super::ColorArg;
use serde::Serialize;
use std::io::Write;
use std::path::Path;

/// The JSON object printed by `--json`.
#[derive(Serialize)]
pub struct Report<'a> {
    pub input: &'a Path,
    /// A `.sets` / `.lodseq` input: the level (and frame) drawn.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lod: Option<String>,
    pub output: &'a Path,
    pub algo: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub heuristic: Option<&'static str>,
    pub color: ColorArg,
    #[serde(serialize_with = "shading_name")]
    pub shading: stripkit_render::Shading,
    pub width: u32,
    pub height: u32,
    pub strips: usize,
    /// Triangles drawn (the strips' triangles without swaps and degenerate ones).
    pub triangles: usize,
    /// `--color cull`: triangles facing the eye.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub front: Option<usize>,
    /// Pixels other than the background.
    pub pixels: usize,
    /// `--wireframe`: edges drawn.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub edges: Option<usize>,
    /// Milliseconds of the stripify call alone.
    pub stripify_ms: f64,
    /// Milliseconds to start the renderer (EGL display, context, shaders).
    pub start_ms: f64,
    /// Milliseconds to upload the triangles, draw them and read the pixels back.
    pub draw_ms: f64,
    /// Milliseconds to encode the PNG and write it.
    pub write_ms: f64,
    /// The renderer, as OpenGL names it (e.g. llvmpipe).
    pub renderer: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub morph: Option<&'a Path>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub t: Option<f32>,
}

/// The text summary of [`Report`].
pub fn print_summary(out: &mut impl Write, r: &Report) -> std::io::Result<()> {
    let name = |v: &dyn std::fmt::Debug| format!("{v:?}").to_lowercase();
    writeln!(
        out,
        "{} -> {} ({}, color {}, {} shading, {}x{}{})",
        r.input.display(),
        r.output.display(),
        r.algo,
        name(&r.color),
        r.shading.name(),
        r.width,
        r.height,
        r.t.map(|t| format!(", morph t = {t}")).unwrap_or_default()
    )?;
    if let Some(l) = &r.lod {
        writeln!(out, "  lod            {l}")?;
    }
    writeln!(out, "  strips         {:>10}", r.strips)?;
    writeln!(out, "  triangles      {:>10}", r.triangles)?;
    if let Some(e) = r.edges {
        writeln!(out, "  edges          {:>10}", e)?;
    }
    if let Some(f) = r.front {
        writeln!(out, "  facing the eye {:>10} ({} culled)", f, r.triangles - f)?;
    }
    let share = 100.0 * r.pixels as f64 / (r.width as f64 * r.height as f64);
    writeln!(out, "  pixels drawn   {:>10} ({share:.1}%)", r.pixels)?;
    writeln!(out, "  stripify ms    {:>10.2}", r.stripify_ms)?;
    writeln!(out, "  start ms       {:>10.2} ({})", r.start_ms, r.renderer)?;
    writeln!(out, "  draw ms        {:>10.2}", r.draw_ms)?;
    writeln!(out, "  write ms       {:>10.2}", r.write_ms)?;
    Ok(())
}

/// The shading as its name in the JSON report (`flat`, `smooth`, `unlit`).
fn shading_name<S: serde::Serializer>(shading: &stripkit_render::Shading, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(shading.name())
}

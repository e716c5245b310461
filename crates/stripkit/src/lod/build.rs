//! From a mesh to a model: the door's strips, the simplifier's full collapse sequence,
//! then [`Sets::build`].

use super::check::{check_levels, stride, LevelCheck};
use super::sets::Sets;
use crate::error::Result;
use crate::mesh::Mesh;
use crate::pipeline::{stripify, StripOptions};
use crate::simplify::{simplify, CollapseSequence, Options, Placement, Target};
use std::time::Instant;

/// Options of [`build`]: the door's defaults, half-edge collapses and re-stripping at
/// [`DEFAULT_RESTRIP`] indices per triangle unless changed with the builder methods.
///
/// ```
/// use stripkit::{lod::BuildOptions, simplify::Placement, Algorithm, StripOptions};
/// let options = BuildOptions::default()
///     .strip(StripOptions::default().algorithm(Algorithm::balanced(0.8)))
///     .placement(Placement::Optimal);
/// assert_eq!(options.placement, Placement::Optimal);
/// ```
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct BuildOptions {
    /// The stripifier of level 0 (any the door runs). Default
    /// [`StripOptions::default`]. Its [`StripOptions::weld`] is not used: the levels
    /// keep the mesh's own faces (the simplifier's collapses weld what they merge).
    pub strip: StripOptions,
    /// Survivor placement of the collapses: [`Placement::Endpoint`] (the default:
    /// half-edge collapses, no new vertices, what `stripkit simplify` does by default)
    /// or [`Placement::Optimal`] (a new vertex per collapse).
    pub placement: Placement,
    /// Re-stripping as the strips decay ([`Sets::build_restripping`]): the indices
    /// per triangle (restart buffer) past which a level's triangles get new greedy
    /// strips, or `None` to keep the level-0 strips at every level. Default
    /// `Some(`[`DEFAULT_RESTRIP`]`)`.
    pub restrip: Option<f64>,
}

/// The default re-strip threshold, in indices per triangle (restart buffer): every
/// level stays at or below it. Against the kept strips on bunny it costs 1.17x the
/// file and about 2x the memory once loaded, and makes 1% steps faster (median 59
/// against 95 us); see `docs/experiments/lod-strips.md`.
pub const DEFAULT_RESTRIP: f64 = 1.6;

impl Default for BuildOptions {
    fn default() -> Self {
        BuildOptions {
            strip: StripOptions::default(),
            placement: Placement::default(),
            restrip: Some(DEFAULT_RESTRIP),
        }
    }
}

impl BuildOptions {
    /// Sets [`BuildOptions::restrip`].
    pub fn restrip(mut self, threshold: Option<f64>) -> Self {
        self.restrip = threshold;
        self
    }

    /// Sets [`BuildOptions::strip`].
    pub fn strip(mut self, strip: StripOptions) -> Self {
        self.strip = strip;
        self
    }

    /// Sets [`BuildOptions::placement`].
    pub fn placement(mut self, placement: Placement) -> Self {
        self.placement = placement;
        self
    }
}

/// What [`build`] did.
#[derive(Clone, Debug, serde::Serialize)]
pub struct BuildReport {
    /// The stripifier that ran.
    pub algorithm: String,
    /// Non-degenerate triangles at level 0.
    pub triangles: u32,
    /// Triangles at the coarsest level.
    pub coarsest_triangles: u32,
    /// Levels beyond level 0 (collapses).
    pub levels: u32,
    /// Strips at level 0.
    pub strips: usize,
    /// Slots (level-0 strip indices).
    pub slots: usize,
    /// Slot versions stored.
    pub versions: usize,
    /// Strip beginnings stored.
    pub beginnings: usize,
    /// Strips made after level 0 by re-stripping ([`Sets::restripped_strips`]).
    pub restripped_strips: usize,
    /// Bytes in memory ([`Sets::memory_bytes`]).
    pub memory_bytes: usize,
    /// Milliseconds of the stripifier.
    pub strip_ms: f64,
    /// Milliseconds of the simplification.
    pub simplify_ms: f64,
    /// Milliseconds of [`Sets::build`].
    pub build_ms: f64,
    /// Milliseconds of the check of 17 levels against the replay.
    pub check_ms: f64,
}

/// A model with what it was built from.
#[derive(Clone, Debug)]
pub struct Built {
    /// The model.
    pub sets: Sets,
    /// The triangle mesh that was simplified: the input's positions and attributes
    /// (plus any vertex the stripifier added, its attributes the blend of the two it
    /// splits) and the triangles the strips draw, in the door's order.
    /// For a triangle mesh stripped without changes this is the input itself, so
    /// `stripkit simplify` on the input gives the same levels.
    pub mesh: Mesh,
    /// The full collapse sequence (down to where no collapse is possible).
    pub sequence: CollapseSequence,
    /// What was done.
    pub report: BuildReport,
}

impl Built {
    /// [`check_levels`] on the model: at every level (`max_levels` `None`) or at
    /// about `max_levels` levels spread over the range, plus the coarsest, 100 of
    /// them also against [`CollapseSequence::replay`] from scratch.
    pub fn check(&self, max_levels: Option<usize>) -> Result<LevelCheck> {
        self.check_with(max_levels, crate::parallel::Threads::SERIAL)
    }

    /// [`Built::check`] with its replays run `threads` at a time
    /// ([`super::check::check_levels_with`]): the same result at any count.
    pub fn check_with(&self, max_levels: Option<usize>, threads: crate::parallel::Threads) -> Result<LevelCheck> {
        let stride = stride(self.sets.levels(), max_levels);
        super::check::check_levels_with(&self.sets, &self.mesh, &self.sequence, stride, 100, threads)
    }
}

/// Strips `mesh` through the door, simplifies the triangles the strips draw as far
/// as the simplifier goes (its defaults, with `options.placement`), and builds the
/// [`Sets`] model of both, checked at 17 levels against the replay
/// ([`check_levels`]; a failure is [`crate::Error::Verification`]). `progress` gets
/// the simplifier's fraction done.
pub fn build(mesh: &Mesh, options: &BuildOptions, progress: &mut dyn FnMut(f64)) -> Result<Built> {
    let t = Instant::now();
    let strips = stripify(mesh, &options.strip.clone().weld(false))?;
    let strip_ms = t.elapsed().as_secs_f64() * 1e3;
    let mut positions = mesh.positions.clone();
    positions.extend_from_slice(&strips.added_positions);
    let mut simplified_mesh = Mesh::from_triangles(positions, &strips.triangles);
    // Every attribute comes along (an added vertex blends the two it splits): the
    // simplifier keeps seam vertices in place and the model stores the values.
    simplified_mesh.attributes = mesh.attributes.clone();
    for a in &mut simplified_mesh.attributes {
        for &[x, y] in &strips.added_from {
            a.push_lerp(x as usize, y as usize, 0.5);
        }
    }
    let t = Instant::now();
    let simplify_options = Options::default().target(Target::Triangles(0)).placement(options.placement);
    let simplified = simplify(&simplified_mesh, &simplify_options, progress)?;
    let simplify_ms = t.elapsed().as_secs_f64() * 1e3;
    let t = Instant::now();
    let sets = Sets::build_restripping(
        &simplified_mesh.positions,
        &simplified_mesh.attributes,
        &strips.strips,
        &simplified.sequence,
        options.placement,
        options.restrip,
    )?;
    let build_ms = t.elapsed().as_secs_f64() * 1e3;
    // Checked before it is returned, as every output of the library: 17 levels
    // spread over the range (and the coarsest) against the replay, 2 of them
    // against a replay from scratch. `check_levels` with a stride of 1 checks all.
    let t = Instant::now();
    check_levels(&sets, &simplified_mesh, &simplified.sequence, (sets.levels() as usize / 16).max(1), 2)?;
    let check_ms = t.elapsed().as_secs_f64() * 1e3;
    let report = BuildReport {
        algorithm: strips.algorithm.name().to_string(),
        triangles: sets.triangles_at(0),
        coarsest_triangles: sets.triangles_at(sets.levels()),
        levels: sets.levels(),
        strips: sets.strip_count(),
        slots: sets.slot_count(),
        versions: sets.version_count(),
        beginnings: sets.beginning_count(),
        restripped_strips: sets.restripped_strips(),
        memory_bytes: sets.memory_bytes(),
        strip_ms,
        simplify_ms,
        build_ms,
        check_ms,
    };
    Ok(Built { sets, mesh: simplified_mesh, sequence: simplified.sequence, report })
}

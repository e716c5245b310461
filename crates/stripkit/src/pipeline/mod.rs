//! The front door: [`stripify`] chooses a stripifier, runs it, verifies what it made
//! and returns the strips with their figures; [`stripify_indices`] and
//! [`unstripify`] do the same for plain index buffers.
//!
//! Every result has passed an independent check before it is returned:
//! * triangle level: the strips decode (the reading rule of docs/metrics.md) to exactly the mesh's fan
//!   triangles, as multisets of oriented triangles (nothing lost, added or flipped);
//! * quad level, where the algorithm split quads along diagonals of its choosing
//!   (QSTRIP, quad-single, cache or balanced on QSTRIP's split): every quad is covered
//!   by two triangles forming it along one diagonal, with its winding, other faces by
//!   their fan; the triangles the strips chose are then the reference;
//! * the joined form ([`Join`]) is encoded, decoded again and checked once more.
//!
//! A failed check is [`Error::Verification`], never a silent result.
//!
//! Files: `options.rs` (the options and their checks), `strips.rs` (the result and
//! its encoders), `indices.rs` (plain index buffers), `groups.rs` (meshes whose faces
//! fall in several groups); this file holds the door itself.

use crate::error::{Error, OptionName, Result};
use crate::mesh::Mesh;
use crate::metrics;
use crate::strip::{self, StripSet};
use crate::stripify::cache::{self, CacheOptions};
use crate::stripify::greedy;
use crate::stripify::single;
use crate::stripify::{quad, quad_single, quad_verify};
use std::time::{Duration, Instant};

mod groups;
mod indices;
mod options;
mod seams;
mod strips;
use groups::run_groups;
use strips::joined;

pub use indices::{stripify_bound, stripify_indices, unstripify};
pub use options::{
    is_quad_dominant, Algorithm, AutoOptions, Join, Split, StripOptions, DEFAULT_PARTITION_ABOVE, MAX_CACHE_SIZE, MAX_TUNNEL_CUTS, QUAD_DOMINANT,
};
pub use strips::Strips;

/// A stripifier with its options checked once, for many meshes.
///
/// ```
/// use stripkit::{gen, Algorithm, StripOptions, Stripifier};
/// let mut s = Stripifier::new(StripOptions::default().algorithm(Algorithm::cache()))?;
/// for n in [4u32, 8] {
///     let strips = s.stripify(&gen::grid(n, n))?;
///     assert_eq!(strips.figures.triangles, (2 * n * n) as usize);
/// }
/// # Ok::<(), stripkit::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Stripifier {
    options: StripOptions,
}

impl Stripifier {
    /// Checks `options` (see [`StripOptions`]) and keeps them.
    pub fn new(options: StripOptions) -> Result<Self> {
        options.check()?;
        Ok(Stripifier { options })
    }

    /// The options in use.
    pub fn options(&self) -> &StripOptions {
        &self.options
    }

    /// [`stripify`] with these options.
    pub fn stripify(&mut self, mesh: &Mesh) -> Result<Strips> {
        run(mesh, &self.options)
    }
}

/// Strips for `mesh`, verified: chooses the algorithm ([`Algorithm::Auto`]), runs it,
/// checks the strips (triangle level, or quad level where the algorithm chose the
/// quads' diagonals) and their joined form, and measures them.
///
/// A mesh without faces gives no strips (verified, all figures 0).
///
/// Errors: [`Error::BadOption`] for options that do not apply (see [`StripOptions`])
/// or a restart index that is a vertex id; [`Error::Invalid`] for a face of fewer
/// than three corners, an index past the vertices, or a mesh quad-single cannot take;
/// [`Error::Verification`] if a check fails (a bug, reported rather than returned).
///
/// Cost: the algorithm's (greedy, QSTRIP and cache O(n) to O(n log n); `balanced` and
/// `cache` with refinement about 30x `cache`), plus an O(n log n) check.
///
/// ```
/// use stripkit::{gen, stripify, StripOptions};
/// let mesh = gen::icosphere(2);
/// let strips = stripify(&mesh, &StripOptions::default())?;
/// assert!(strips.figures.verified);
/// assert_eq!(strips.figures.triangles, mesh.triangle_count());
/// assert_eq!(strips.algorithm.name(), "greedy");
/// # Ok::<(), stripkit::Error>(())
/// ```
pub fn stripify(mesh: &Mesh, options: &StripOptions) -> Result<Strips> {
    options.check()?;
    run(mesh, options)
}

fn fail(what: &str, v: &strip::Verification) -> Error {
    Error::Verification(format!("{what}: {v}"))
}

/// The door's body, with the options already checked: per group where the mesh's
/// faces fall in several. Every parallel step inside shares one pool of
/// `options.threads` (made once here, not once per step).
fn run(mesh: &Mesh, options: &StripOptions) -> Result<Strips> {
    options.threads.install(|| run_in_pool(mesh, options))
}

/// [`run`] inside its pool.
fn run_in_pool(mesh: &Mesh, options: &StripOptions) -> Result<Strips> {
    mesh.check_faces()?;
    if options.weld {
        let start = Instant::now();
        let welded = mesh.welded_with(options.threads);
        let weld_time = start.elapsed();
        let mut strips = match welded {
            Some((welded, moved)) => {
                let mut strips = run_welded(&welded, options)?;
                strips.welded = moved;
                strips
            }
            None => run_welded(mesh, options)?,
        };
        strips.phases.insert(0, ("weld", weld_time));
        return Ok(strips);
    }
    run_welded(mesh, options)
}

/// [`run`] after welding.
fn run_welded(mesh: &Mesh, options: &StripOptions) -> Result<Strips> {
    if mesh.has_groups() {
        return run_groups(mesh, options);
    }
    let mut strips = run_one(mesh, options)?;
    if mesh.group_count() > 1 {
        // Every face in one group (the first face's), the others empty.
        let g = mesh.group_of(0) as usize;
        let n = strips.strips.len();
        strips.group_ranges = (0..mesh.group_count()).map(|k| if k == g { 0..n } else { n..n }).collect();
    }
    Ok(strips)
}

/// Checks the restart index against the mesh's vertex ids and resolves
/// `Algorithm::Auto` (QSTRIP on quad-dominant meshes, else greedy).
fn resolve(mesh: &Mesh, options: &StripOptions) -> Result<Algorithm> {
    check_restart(options, mesh.vertex_count())?;
    Ok(match &options.algorithm {
        Algorithm::Auto(auto) => auto.resolve(mesh),
        other => other.clone(),
    })
}

/// With [`Join::Restart`], the restart index must not be one of `vertex_count` ids.
fn check_restart(options: &StripOptions, vertex_count: usize) -> Result<()> {
    if options.join == Join::Restart && (options.restart_index as usize) < vertex_count {
        return Err(Error::option(
            OptionName::RestartIndex,
            format!(
                "{} is a vertex id of the mesh ({vertex_count} vertices); choose one of at least {vertex_count}",
                options.restart_index
            ),
        ));
    }
    Ok(())
}

/// The door for one group of faces (the whole mesh), its faces already checked.
fn run_one(mesh: &Mesh, options: &StripOptions) -> Result<Strips> {
    let vertex_count = mesh.vertex_count();
    let algorithm = resolve(mesh, options)?;
    if matches!(options.algorithm, Algorithm::Auto(_)) && options.split != Split::Auto {
        // The split must suit the algorithm auto chose (QSTRIP takes no fan).
        StripOptions { algorithm: algorithm.clone(), ..options.clone() }.check()?;
    }
    // The fan is the greedy stripifier's input, made outside its timing.
    let fan = matches!(algorithm, Algorithm::Greedy(_) | Algorithm::Batch(_)).then(|| mesh.triangulate().tris);
    let mut added_positions = Vec::new();
    let mut added_from = Vec::new();
    let mut single_report = None;
    let mut stripify_time_single = None;
    // The input's own fan as the check's reference, made after the stripifier's timing
    // (it is the check's work, not the stripifier's).
    let mut check_against_fan = false;
    let start = Instant::now();
    let (strips, split, quads, fan) = match &algorithm {
        Algorithm::Greedy(g) => {
            let tris = fan.unwrap_or_default();
            let strips = greedy::stripify(&tris, vertex_count, g);
            (strips, Split::Fan, None, Some(tris))
        }
        Algorithm::Batch(model) => {
            let tris = fan.unwrap_or_default();
            let strips = crate::stripify::batch::stripify(&tris, &mesh.positions, vertex_count, model);
            (strips, Split::Fan, None, Some(tris))
        }
        Algorithm::Qstrip(q) => {
            let (qs, strips) = quad::qstrip_mesh(mesh, q);
            (strips, Split::Qstrip, Some(qs.quad_count()), None)
        }
        Algorithm::QuadSingle => {
            let single = quad_single::quad_single(mesh)?;
            (single.strips, Split::Qstrip, Some(single.quads), None)
        }
        Algorithm::Cache { .. } | Algorithm::Balanced { .. } => {
            let size = options.cache.size as u32;
            let (cache_options, bound) = match algorithm {
                Algorithm::Balanced { max_acmr } => (CacheOptions::balanced(size), Some(max_acmr)),
                Algorithm::Cache { refine } => (
                    CacheOptions {
                        refine,
                        partition_above: options.partition_above,
                        ..CacheOptions::cache(size)
                    },
                    None,
                ),
                _ => unreachable!("matched above"),
            };
            let m = cache::stripify_mesh(mesh, &cache_options, bound, options.split, options.threads);
            if m.qstrip_diagonals {
                (m.strips, Split::Qstrip, None, None)
            } else {
                // Checked against the input's own fan, not the triangles the
                // stripifier reports: the check stays independent of it.
                check_against_fan = true;
                (m.strips, Split::Fan, None, None)
            }
        }
        Algorithm::Single(o) => {
            let input = mesh.triangulate().tris;
            let single = single::single_strips(&mesh.positions, input.clone(), o)?;
            stripify_time_single = Some(start.elapsed());
            if let Err(why) = single::check::cover(&input, &single.work) {
                return Err(Error::Verification(format!("the changed mesh of single: {why}")));
            }
            added_positions = single.work.pos[vertex_count..].iter().map(|p| p.map(|x| x as f32)).collect();
            added_from = single.work.steiner.clone();
            let mut report = single.report;
            let drawn = single.work.tris.iter().filter(|t| !strip::is_degenerate(t)).count();
            seams::count(mesh, &input, drawn, &mut report);
            single_report = Some(report);
            (single.strips, Split::Fan, None, Some(single.work.tris))
        }
        Algorithm::Auto(_) => unreachable!("resolved above"),
    };
    let stripify_time = stripify_time_single.unwrap_or_else(|| start.elapsed());
    let check_start = Instant::now();
    let fan = if check_against_fan { Some(mesh.triangulate().tris) } else { fan };
    let triangles = match fan {
        Some(tris) => tris,
        None => {
            // Either diagonal of a quad is right: check at quad level, then the
            // triangles the strips chose are the reference (the check proved them a
            // triangulation of the mesh with its winding).
            quad_verify::verify_quads(mesh, &strips)?;
            strip::decode(&strips)
        }
    };
    let figures = metrics::figures_with(&triangles, &strips, options.cache, options.threads);
    if !figures.verified {
        return Err(fail("the strips", &strip::verify_with(&triangles, &strips, options.threads)));
    }
    let figures_time = check_start.elapsed();
    // The joined form is checked here and rebuilt on demand (`Strips::joined`): for
    // two of the three joins it is the strips themselves.
    // Bound first: the encoded buffer it is read back from is dropped before the check.
    let joined_start = Instant::now();
    let joined_form = joined(&strips, std::slice::from_ref(&(0..strips.len())), options.join, options.restart_index);
    // The strips were just verified: a joined form drawing their triangles strip by
    // strip needs no second sort; any other order gets the full check.
    if !strip::draws_in_order(&strips, &joined_form, options.threads) {
        let v = strip::verify_with(&triangles, &joined_form, options.threads);
        if !v.ok() {
            return Err(fail(&format!("the strips joined by {}", options.join.name()), &v));
        }
    }
    drop(joined_form);
    let phases = vec![("stripify", stripify_time), ("figures", figures_time), ("joined", joined_start.elapsed())];
    let strips_len = strips.len();
    Ok(Strips {
        strips,
        triangles,
        algorithm,
        split,
        quads,
        figures,
        join: options.join,
        restart_index: options.restart_index,
        stripify_time,
        single: single_report,
        added_positions,
        added_from,
        group_ranges: std::iter::once(0..strips_len).collect(),
        welded: 0,
        phases,
    })
}

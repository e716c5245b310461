//! Stripping a glTF scene, above the door: every triangle primitive of an
//! [`io::Scene`](crate::io::Scene) goes through the front door on its own, and the
//! scene is told what to write (the strips, the triangles they were verified against,
//! the first-use vertex order).
//!
//! `mesh::io` reads and writes the document and knows nothing of stripifiers; this
//! module runs them and reports. [`Scene::strip`] is defined here, on the document
//! type of `io`, so that a scene is still read, stripped and written as one value.
//!
//! ```
//! use stripkit::io::Format;
//! use stripkit::scene::{Scene, SceneOptions};
//! use stripkit::{gen, StripOptions};
//!
//! let mut scene = Scene::from_mesh(&gen::icosphere(1))?;
//! let options = SceneOptions::default().restart(false).reorder(true);
//! let report = scene.strip(&StripOptions::default(), &options)?;
//! assert_eq!(report.triangles, 80);
//! assert_eq!(report.indices_drawn_restart, report.indices_stitched); // no restart groups
//! let glb = scene.to_bytes(Format::Glb)?; // read back and checked
//! assert!(!glb.is_empty());
//! # Ok::<(), stripkit::Error>(())
//! ```

use crate::error::{Error, Result};
use crate::mesh::order::first_use;
use crate::mesh::Mesh;
use crate::metrics::Figures;
use crate::pipeline::{Algorithm, Join, StripOptions, Stripifier};
use crate::strip::{self, DEFAULT_RESTART};
use std::time::{Duration, Instant};

pub use crate::mesh::io::{Scene, ScenePrimitive};

/// The glTF writer the library uses for `mesh`'s strips under `options`: the scene
/// of the mesh ([`Scene::from_mesh`]: one primitive per group with its attributes and
/// material, each stripped on its own by [`Scene::strip`] and written with its restart
/// group), or `None` for the plain writer (one stitched strip primitive over the whole
/// mesh, [`Strips::to_file_bytes`](crate::Strips::to_file_bytes)) where a scene cannot
/// hold what `options` ask for: [`Algorithm::Single`] (it adds vertices),
/// [`Join::Separate`] (a primitive per strip), a restart index other than
/// [`DEFAULT_RESTART`], or a mesh without a drawable triangle (no faces, or only
/// faces that repeat a vertex: the plain writer keeps the vertices as a `POINTS`
/// primitive, as the other formats keep them with no faces, where a scene would be
/// left with empty accessors and an empty buffer).
pub fn for_gltf_output(mesh: &Mesh, options: &StripOptions) -> Result<Option<Scene>> {
    for_gltf_output_with(mesh, options, &crate::mesh::io::Materials::default())
}

/// [`for_gltf_output`] with the materials of the mesh's OBJ libraries
/// ([`Scene::from_mesh_with`]); the plain writer writes no materials.
pub fn for_gltf_output_with(
    mesh: &Mesh,
    options: &StripOptions,
    materials: &crate::mesh::io::Materials,
) -> Result<Option<Scene>> {
    let plain = options.join == Join::Separate
        || matches!(options.algorithm, Algorithm::Single(_))
        || options.restart_index != DEFAULT_RESTART
        || mesh.triangulate().tris.iter().all(strip::is_degenerate);
    if plain {
        return Ok(None);
    }
    Scene::from_mesh_with(mesh, materials).map(Some)
}

/// How [`Scene::strip`] writes the strips. Defaults: restart groups on, vertices
/// renumbered in first use, buffer views not compressed.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct SceneOptions {
    /// Add an `EXT_mesh_primitive_restart` group (restart indices) beside each
    /// stitched strip primitive without morph targets. Default `true`; `false` writes
    /// plain stitched strips, one primitive per input primitive, without the extension.
    pub restart: bool,
    /// Renumber each stripped primitive's vertices in their first use by the strips
    /// and leave out those the strips do not use (meshoptimizer's
    /// `optimizeVertexFetch`): its attributes and morph targets are written anew,
    /// gathered in that order (min / max recomputed). Default `true`. A primitive
    /// whose vertex data cannot be decoded (a sparse accessor) keeps its order.
    pub reorder: bool,
    /// Write the index and vertex buffer views compressed with
    /// `EXT_meshopt_compression` (indices with the index-sequence codec, vertex data
    /// with the vertex codec version 0), listed as required; views that would not get
    /// smaller stay plain. Default `false`.
    pub compress: bool,
}

impl Default for SceneOptions {
    fn default() -> Self {
        SceneOptions { restart: true, reorder: true, compress: false }
    }
}

impl SceneOptions {
    /// Plain stitched strips: the defaults with [`SceneOptions::restart`] off (no
    /// `EXT_mesh_primitive_restart`).
    pub fn stitched() -> Self {
        SceneOptions::default().restart(false)
    }

    /// Sets [`SceneOptions::restart`].
    pub fn restart(mut self, on: bool) -> Self {
        self.restart = on;
        self
    }

    /// Sets [`SceneOptions::compress`].
    pub fn compress(mut self, on: bool) -> Self {
        self.compress = on;
        self
    }

    /// Sets [`SceneOptions::reorder`].
    pub fn reorder(mut self, on: bool) -> Self {
        self.reorder = on;
        self
    }
}

/// What [`Scene::strip`] did to one primitive.
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct PrimitiveReport {
    /// Index in the document's `meshes`.
    pub mesh: usize,
    /// Index in that mesh's `primitives`.
    pub primitive: usize,
    /// The mode read (4, 5 or 6).
    pub mode_read: u8,
    /// Indices the primitive had (its vertex count when not indexed).
    pub indices_read: usize,
    /// Indices of the stitched strip written as the primitive's `indices`.
    pub indices_stitched: usize,
    /// Indices of the restart group, where one is written.
    pub indices_restart: Option<usize>,
    /// The algorithm that ran.
    pub algorithm: &'static str,
    /// Vertices welded onto a bit-identical one ([`StripOptions::weld`]; never for a
    /// primitive with morph targets, whose target data the weld does not see).
    pub welded: usize,
    /// The strips would take more index bytes than the primitive's own indices (the
    /// larger of the stitched strip and the restart group, against the indices read,
    /// or for an unindexed primitive a list of its vertices): the primitive is
    /// written as read, and `indices_stitched` / `indices_restart` are what it keeps.
    pub kept_as_read: bool,
    /// Zero-area triangles the stitched strip written as the primitive's `indices`
    /// decodes to besides its triangles (swaps and stitching,
    /// [`degenerate_windows`](crate::degenerate_windows)): loaders without
    /// `EXT_mesh_primitive_restart` that keep every triangle (trimesh) count them as
    /// faces. 0 for a primitive kept as read.
    pub degenerate_stitched: usize,
    /// The figures of the strips (docs/metrics.md).
    pub figures: Figures,
}

/// What [`Scene::strip`] did to the whole scene.
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct SceneReport {
    /// One entry per stripped primitive, in document order.
    pub primitives: Vec<PrimitiveReport>,
    /// Primitives left as they were: points and lines, and triangle primitives that
    /// draw nothing (primitives kept because strips would be larger are counted in
    /// `kept_as_read` instead).
    pub skipped: usize,
    /// Stripped primitives written as read because their strips would take more index
    /// bytes than their own indices ([`PrimitiveReport::kept_as_read`]).
    pub kept_as_read: usize,
    /// Vertices welded, all primitives together ([`PrimitiveReport::welded`]).
    pub welded: usize,
    /// [`PrimitiveReport::degenerate_stitched`], all primitives together.
    pub degenerate_stitched: usize,
    /// Triangles stripped, all primitives together.
    pub triangles: usize,
    /// Indices read, all stripped primitives together.
    pub indices_read: usize,
    /// Stitched indices written, all together.
    pub indices_stitched: usize,
    /// Indices a viewer with primitive restart draws: the restart groups' indices,
    /// plus the stitched ones of primitives without a group.
    pub indices_drawn_restart: usize,
    /// Vertices the stripped primitives write, all together (with
    /// [`SceneOptions::reorder`], those their strips use).
    pub vertices: usize,
    /// Time of the stripifiers alone, all primitives together, in milliseconds.
    pub stripify_ms: f64,
    /// Time of the whole call (door, verification and figures), in milliseconds.
    pub total_ms: f64,
}

impl Scene {
    /// Strips every triangle primitive on its own through the front door
    /// ([`crate::stripify`], which verifies the strips) and sets the strips on the
    /// scene, which [`Scene::to_bytes`] and [`Scene::write`] then write, with `options` (its join and
    /// restart index are the door's business: the written forms are chosen by
    /// `scene_options`, see [`SceneOptions`]). [`Algorithm::Single`] is refused: it
    /// adds vertices, and a scene's vertex data is not rewritten. Errors name the
    /// primitive. Calling it again strips again.
    pub fn strip(&mut self, options: &StripOptions, scene_options: &SceneOptions) -> Result<SceneReport> {
        if matches!(options.algorithm, Algorithm::Single(_)) {
            return Err(Error::Invalid(
                "single adds vertices, and a glTF scene's vertex data is written as read; choose another algorithm"
                    .into(),
            ));
        }
        let start = Instant::now();
        let options = options.clone().join(Join::Restart).restart_index(u32::MAX);
        let stripifier = Stripifier::new(options.clone())?;
        let mut report = SceneReport {
            primitives: Vec::new(),
            skipped: self.other_primitives(),
            kept_as_read: 0,
            welded: 0,
            degenerate_stitched: 0,
            triangles: 0,
            indices_read: 0,
            indices_stitched: 0,
            indices_drawn_restart: 0,
            vertices: 0,
            stripify_ms: 0.0,
            total_ms: 0.0,
        };
        let mut stripify_time = Duration::ZERO;
        // Whether each primitive's vertex accessors can be read back for reordering.
        let readable = self.renumberable();
        let file = self.name().to_path_buf();
        let source_bytes = self.source_index_bytes();
        let no_weld = options.weld.then(|| Stripifier::new(options.clone().weld(false))).transpose()?;
        // Every primitive is stripped on its own (in parallel when the options allow),
        // then the results are taken in primitive order: the same scene at any count.
        let stripped = crate::parallel::map_ordered(options.threads, self.primitives(), |sp| {
            if sp.mesh.face_count() == 0 {
                return None;
            }
            // Morph targets are not in the decoded mesh: a weld could merge vertices
            // that targets move apart.
            Some(match (sp.targets > 0 && options.weld, &no_weld) {
                (true, Some(s)) => s.clone().stripify(&sp.mesh),
                _ => stripifier.clone().stripify(&sp.mesh),
            })
        });
        for (k, ((sp, readable), strips)) in self.primitives_mut().iter_mut().zip(readable).zip(stripped).enumerate() {
            sp.strips = None;
            sp.order = None;
            let Some(strips) = strips else {
                report.skipped += 1;
                continue;
            };
            let name = |e: Error| {
                let place =
                    format!("{}: meshes[{}].primitives[{}]", file.display(), sp.mesh_index, sp.primitive_index);
                match e {
                    Error::Invalid(m) => Error::Invalid(format!("{place}: {m}")),
                    Error::Verification(m) => Error::Verification(format!("{place}: {m}")),
                    other => other,
                }
            };
            let strips = strips.map_err(name)?;
            stripify_time += strips.stripify_time;
            if strips.figures.triangles == 0 {
                // Only degenerate triangles: a strip primitive would hold empty
                // accessors, which glTF forbids; the primitive is written as read.
                report.skipped += 1;
                continue;
            }
            let set = strips.strips;
            let stitched = strip::stitched_len(&set);
            let restart = (scene_options.restart && sp.targets == 0)
                .then(|| set.iter().filter(|s| s.len() >= 3).map(|s| s.len() + 1).sum::<usize>().saturating_sub(1));
            let order = (scene_options.reorder && readable)
                .then(|| first_use(strip::encode_stitched(&set), sp.mesh.vertex_count()));
            let vertices = order.as_ref().map_or(sp.mesh.vertex_count(), Vec::len);
            let strip_bytes = stitched.max(restart.unwrap_or(0)) * index_width(vertices);
            let kept = strip_bytes > source_bytes[k];
            let (stitched, restart) = if kept { (sp.indices_read, None) } else { (stitched, restart) };
            let degenerate_stitched = if kept { 0 } else { strip::degenerate_windows(&strip::encode_stitched(&set)) };
            report.degenerate_stitched += degenerate_stitched;
            report.triangles += strips.figures.triangles;
            report.indices_read += sp.indices_read;
            report.indices_stitched += stitched;
            report.indices_drawn_restart += restart.unwrap_or(stitched);
            report.welded += strips.welded;
            report.kept_as_read += usize::from(kept);
            report.primitives.push(PrimitiveReport {
                mesh: sp.mesh_index,
                primitive: sp.primitive_index,
                mode_read: sp.mode,
                indices_read: sp.indices_read,
                indices_stitched: stitched,
                indices_restart: restart,
                algorithm: strips.algorithm.name(),
                welded: strips.welded,
                kept_as_read: kept,
                degenerate_stitched,
                figures: strips.figures,
            });
            if kept {
                report.vertices += sp.mesh.vertex_count();
                continue;
            }
            sp.order = order;
            sp.strips = Some(set);
            report.vertices += vertices;
            sp.drawn = strips.triangles;
        }
        self.set_restart_groups(scene_options.restart);
        self.set_compress(scene_options.compress);
        self.set_threads(options.threads);
        report.stripify_ms = stripify_time.as_secs_f64() * 1e3;
        report.total_ms = start.elapsed().as_secs_f64() * 1e3;
        Ok(report)
    }
}

/// Bytes of one index the writer writes for a primitive of `vertices` vertices (65535
/// is the 16-bit restart value, never a vertex id).
fn index_width(vertices: usize) -> usize {
    if vertices >= u16::MAX as usize {
        4
    } else {
        2
    }
}

impl Scene {
    /// Each triangle primitive's index bytes as read: its index accessor's count times
    /// its component size, or for a primitive without indices the list of its vertices
    /// the writer would write ([`index_width`]).
    fn source_index_bytes(&self) -> Vec<usize> {
        let json = self.json();
        self.primitives()
            .iter()
            .map(|sp| {
                let prim = &json["meshes"][sp.mesh_index]["primitives"][sp.primitive_index];
                let width = prim["indices"]
                    .as_u64()
                    .and_then(|a| json["accessors"][a as usize]["componentType"].as_u64())
                    .map_or(index_width(sp.mesh.vertex_count()), |c| match c {
                        5121 => 1,
                        5123 => 2,
                        _ => 4,
                    });
                sp.indices_read * width
            })
            .collect()
    }
}

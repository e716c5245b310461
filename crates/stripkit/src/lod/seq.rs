//! Level-of-detail strips for deforming meshes (after Ramos et al., *Level-of-detail
//! triangle strips for deforming meshes*, 2008): one strip connectivity for every
//! frame of an animation, a simplification sequence chosen per frame, and levels
//! recovered for any (frame, level) from the SETS models of those sequences.
//!
//! The paper stores a simplification sequence per frame. Here the frames share a few
//! sequences. Each frame's own sequence is computed, and so is the reference pose's.
//! The distances of every candidate sequence to every frame, at 10% and 2% of the
//! triangles, are measured. A greedy k-center choice then picks the sequences
//! ([`SeqOptions::max_sequences`], until every frame is within
//! [`SeqOptions::tolerance`] of its own sequence). Each frame takes the best chosen
//! sequence among those at least as good as the reference pose's (Hausdorff and RMS,
//! at both ratios), so a frame is never worse than with the reference sequence. Every
//! sequence is a [`Sets`] model over the same level-0 strips, so all models lay their
//! strips out alike in one padded buffer; [`SeqCursor`] moves between frames and
//! levels by updating only what differs.

use super::cursor::Cursor;
use super::sets::{LevelSpec, Sets};
use crate::distance::{Distance, Surface};
use crate::error::{Error, Result};
use crate::mesh::io::{self, Format, ReadOptions};
use crate::mesh::Mesh;
use crate::pipeline::{stripify, StripOptions};
use crate::simplify::{simplify, CollapseSequence, Options, Placement, Target};
use crate::strip::StripSet;
use std::path::Path;
use std::time::Instant;

/// The ratios of triangles at which sequences are compared.
pub const QUALITY_RATIOS: [f64; 2] = [0.1, 0.02];

/// An animation read from a folder: frames with one shared face list.
#[derive(Clone, Debug)]
pub struct Frames {
    /// File names of the animation frames, in order.
    pub names: Vec<String>,
    /// The shared faces (positions of the first frame).
    pub mesh: Mesh,
    /// Positions of every frame.
    pub positions: Vec<Vec<[f32; 3]>>,
    /// The reference pose (a file whose name contains `reference`), when there is one.
    pub reference: Option<Vec<[f32; 3]>>,
}

/// Reads every mesh file of `folder` (any format [`io::read`] takes, `.gz` too), in
/// name order: the animation frames, and a reference pose if one file's name
/// contains `reference`. Every frame must have the first frame's faces and vertex
/// count; the first that does not is named in the error.
pub fn read_frames(folder: &Path, options: &ReadOptions) -> Result<Frames> {
    let entries = std::fs::read_dir(folder).map_err(|source| Error::Io { path: folder.to_path_buf(), source })?;
    let mut files = Vec::new();
    for e in entries {
        let e = e.map_err(|source| Error::Io { path: folder.to_path_buf(), source })?;
        let path = e.path();
        if path.is_file() && Format::from_path(&path).is_some() {
            files.push(path);
        }
    }
    files.sort();
    let mut first: Option<(String, Mesh)> = None;
    let (mut names, mut positions, mut reference) = (Vec::new(), Vec::new(), None);
    for path in &files {
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let mesh = io::read_with(path, options)?;
        match &first {
            None => first = Some((name.clone(), mesh.clone())),
            Some((first_name, m)) => {
                if mesh.positions.len() != m.positions.len() {
                    return Err(Error::Invalid(format!(
                        "frame {name} has {} vertices, {first_name} has {}: the frames of a sequence share one mesh",
                        mesh.positions.len(),
                        m.positions.len()
                    )));
                }
                if mesh.face_offsets != m.face_offsets || mesh.face_indices != m.face_indices {
                    let f = (0..mesh.face_count().min(m.face_count()))
                        .find(|&f| mesh.face(f) != m.face(f))
                        .unwrap_or(mesh.face_count().min(m.face_count()));
                    return Err(Error::Invalid(format!(
                        "frame {name} differs from {first_name} at face {f}: the frames of a sequence share one face list"
                    )));
                }
            }
        }
        if name.to_ascii_lowercase().contains("reference") {
            reference = Some(mesh.positions);
        } else {
            names.push(name);
            positions.push(mesh.positions);
        }
    }
    let Some((_, mut mesh)) = first else {
        return Err(Error::Invalid(format!("{} holds no mesh files", folder.display())));
    };
    if positions.is_empty() {
        return Err(Error::Invalid(format!("{} holds only a reference pose, no frames", folder.display())));
    }
    mesh.positions = positions[0].clone();
    Ok(Frames { names, mesh, positions, reference })
}

/// Options of [`build_seq`]: the defaults below unless changed with the builder
/// methods.
///
/// ```
/// use stripkit::lod::SeqOptions;
/// let options = SeqOptions::default().samples(800).position_bits(Some(12));
/// assert_eq!((options.samples, options.max_sequences, options.position_bits), (800, 16, Some(12)));
/// ```
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct SeqOptions {
    /// The stripifier of the shared level-0 strips (one that adds no vertices).
    /// Default [`StripOptions::default`]. Its [`StripOptions::weld`] is not used:
    /// vertices equal in the first frame may part in later ones. Its
    /// [`StripOptions::threads`] are the build's: frames are simplified and measured
    /// in parallel, with the same model at any count.
    pub strip: StripOptions,
    /// Most sequences to choose (each is one [`Sets`] model), besides the reference
    /// pose's, which is kept too when a frame falls back to it. Default 16.
    pub max_sequences: usize,
    /// Stop adding sequences once every frame's Hausdorff distance is within this
    /// factor of its own sequence's, at both [`QUALITY_RATIOS`]. Default 1.25.
    pub tolerance: f64,
    /// Samples per surface for the distances: 1 to
    /// [`crate::distance::MAX_SAMPLES`] (24 bytes each), checked before any work.
    /// Default 4,000.
    pub samples: usize,
    /// Candidate sequences: every frame's when there are at most this many frames,
    /// else evenly spaced frames, this many; the reference pose's is always one.
    /// Default 24.
    pub candidates: usize,
    /// Store positions quantized to this many bits per coordinate (8 to 20) over the
    /// animation's bounding box, coded as differences from the previous frame and
    /// deflated; the frames are quantized before anything is built, so everything
    /// (sequences, distances, the file) sees the same positions. `None` (default):
    /// exact `f32` positions.
    pub position_bits: Option<u32>,
}

impl Default for SeqOptions {
    fn default() -> Self {
        SeqOptions {
            strip: StripOptions::default(),
            max_sequences: 16,
            tolerance: 1.25,
            samples: 4000,
            candidates: 24,
            position_bits: None,
        }
    }
}

impl SeqOptions {
    /// Sets [`SeqOptions::strip`].
    pub fn strip(mut self, strip: StripOptions) -> Self {
        self.strip = strip;
        self
    }

    /// Sets [`SeqOptions::max_sequences`].
    pub fn max_sequences(mut self, sequences: usize) -> Self {
        self.max_sequences = sequences;
        self
    }

    /// Sets [`SeqOptions::tolerance`].
    pub fn tolerance(mut self, factor: f64) -> Self {
        self.tolerance = factor;
        self
    }

    /// Sets [`SeqOptions::samples`].
    pub fn samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }

    /// Sets [`SeqOptions::candidates`].
    pub fn candidates(mut self, candidates: usize) -> Self {
        self.candidates = candidates;
        self
    }

    /// Sets [`SeqOptions::position_bits`].
    pub fn position_bits(mut self, bits: Option<u32>) -> Self {
        self.position_bits = bits;
        self
    }
}

/// Distances of one frame's simplification at [`QUALITY_RATIOS`] to the frame,
/// relative to its bounding-box diagonal.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct Quality {
    /// Symmetric Hausdorff distance at each ratio.
    pub hausdorff: [f64; 2],
    /// RMS distance at each ratio.
    pub rms: [f64; 2],
}

impl Quality {
    fn from(d: [Distance; 2]) -> Quality {
        Quality {
            hausdorff: d.map(|d| d.hausdorff / d.diagonal.max(f64::MIN_POSITIVE)),
            rms: d.map(|d| d.rms / d.diagonal.max(f64::MIN_POSITIVE)),
        }
    }

    /// At most `other` in all four figures.
    fn within(&self, other: &Quality) -> bool {
        (0..2).all(|r| self.hausdorff[r] <= other.hausdorff[r] && self.rms[r] <= other.rms[r])
    }

    /// The worse ratio of Hausdorff distances to `own`'s.
    fn factor(&self, own: &Quality) -> f64 {
        (0..2).map(|r| self.hausdorff[r] / own.hausdorff[r].max(f64::MIN_POSITIVE)).fold(0.0, f64::max)
    }
}

/// One frame's row of the quality table.
#[derive(Clone, Debug, serde::Serialize)]
pub struct FrameQuality {
    /// Frame name.
    pub frame: String,
    /// The pose whose sequence the frame uses.
    pub sequence: String,
    /// (a) this scheme: the frame with its chosen sequence.
    pub chosen: Quality,
    /// (b) the reference pose's sequence applied to the frame.
    pub reference: Quality,
    /// (c) the frame's own sequence (an independent simplification).
    pub own: Quality,
}

/// What [`build_seq`] did.
#[derive(Clone, Debug, serde::Serialize)]
pub struct SeqReport {
    /// Frames of the animation.
    pub frames: usize,
    /// Vertices per frame.
    pub vertices: usize,
    /// Triangles of the shared connectivity.
    pub triangles: usize,
    /// Strips of the shared connectivity.
    pub strips: usize,
    /// Candidate sequences measured.
    pub candidates: usize,
    /// The poses whose sequences were kept.
    pub sequences: Vec<String>,
    /// Per frame: (a), (b), (c).
    pub quality: Vec<FrameQuality>,
    /// Milliseconds of the simplifications.
    pub simplify_ms: f64,
    /// Milliseconds of the distance matrix.
    pub distance_ms: f64,
    /// Milliseconds of the SETS models (built, and checked at 17 levels each).
    pub model_ms: f64,
}

/// A deforming mesh's level-of-detail strips: per frame its positions and the model
/// of its sequence.
#[derive(Clone, Debug, PartialEq)]
pub struct LodSeq {
    pub(crate) names: Vec<String>,
    pub(crate) positions: Vec<Vec<[f32; 3]>>,
    pub(crate) frame_model: Vec<u32>,
    /// The models, positionless (a frame's positions are its own).
    pub(crate) models: Vec<Sets>,
    /// How the positions are quantized in the file (they are already on its grid).
    pub(crate) quantization: Option<Quantization>,
    /// The vertex attributes of the first frame's file (UVs, normals, ...), shared by
    /// every frame and level; empty when it has none.
    pub(crate) attributes: Vec<crate::mesh::Attribute>,
}

/// Positions on a grid: coordinate `d` is `lo[d] + q * step[d]` for an integer
/// `0 <= q < 2^bits`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Quantization {
    pub(crate) bits: u32,
    pub(crate) lo: [f32; 3],
    pub(crate) step: [f32; 3],
}

impl Quantization {
    /// The grid of `bits` bits over the bounding box of every frame and the reference.
    fn of(frames: &Frames, bits: u32) -> Quantization {
        let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        for p in frames.positions.iter().chain(frames.reference.iter()).flatten() {
            for d in 0..3 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
        let top = ((1u32 << bits) - 1) as f32;
        let step = [0, 1, 2].map(|d| if hi[d] > lo[d] { (hi[d] - lo[d]) / top } else { 1.0 });
        Quantization { bits, lo: lo.map(|x| if x.is_finite() { x } else { 0.0 }), step }
    }

    /// The grid index of coordinate `d` of `p`.
    pub(crate) fn index(&self, p: &[f32; 3], d: usize) -> u32 {
        let top = ((1u64 << self.bits) - 1) as f32;
        ((p[d] - self.lo[d]) / self.step[d]).round().clamp(0.0, top) as u32
    }

    /// The coordinate of grid index `q` along `d` (what the file decodes to).
    pub(crate) fn value(&self, q: u32, d: usize) -> f32 {
        self.lo[d] + q as f32 * self.step[d]
    }

    fn apply(&self, positions: &mut [[f32; 3]]) {
        for p in positions {
            *p = [0, 1, 2].map(|d| self.value(self.index(p, d), d));
        }
    }
}

/// A built sequence model with the sequences it came from (for checks).
#[derive(Clone, Debug)]
pub struct BuiltSeq {
    /// The model.
    pub seq: LodSeq,
    /// The triangles the strips draw (the shared connectivity).
    pub triangles: Vec<[u32; 3]>,
    /// Each model's collapse sequence.
    pub sequences: Vec<CollapseSequence>,
    /// What was done.
    pub report: SeqReport,
}

impl BuiltSeq {
    /// [`crate::lod::check_levels`] on every kept model over the first frame: at
    /// every level (`max_levels` `None`) or at about `max_levels` levels of each
    /// model spread over its range, plus the coarsest, 20 of them also against
    /// [`CollapseSequence::replay`] from scratch. The counts add up over the models
    /// (the largest change is the largest of any); the time is the whole check's.
    pub fn check(&self, max_levels: Option<usize>) -> Result<super::check::LevelCheck> {
        self.check_with(max_levels, crate::parallel::Threads::SERIAL)
    }

    /// [`BuiltSeq::check`] with the models checked `threads` at a time: the same
    /// result at any count (the first failing model in order is the error).
    pub fn check_with(
        &self,
        max_levels: Option<usize>,
        threads: crate::parallel::Threads,
    ) -> Result<super::check::LevelCheck> {
        let start = Instant::now();
        let mesh = Mesh::from_triangles(self.seq.positions[0].clone(), &self.triangles);
        let mut all = super::check::LevelCheck::default();
        let pairs: Vec<_> = self.seq.models().iter().zip(&self.sequences).collect();
        let checks = crate::parallel::map_ordered(threads, &pairs, |(sets, sequence)| {
            let stride = super::check::stride(sets.levels(), max_levels);
            super::check::check_levels(sets, &mesh, sequence, stride, 20)
        });
        for one in checks {
            let one = one?;
            all.levels_checked += one.levels_checked;
            all.replays += one.replays;
            all.max_changed_strips = all.max_changed_strips.max(one.max_changed_strips);
        }
        all.ms = start.elapsed().as_secs_f64() * 1e3;
        Ok(all)
    }
}

/// Strips the shared connectivity once, simplifies every frame (and the reference
/// pose), measures the candidate sequences on every frame and keeps a few (see the
/// module documentation). Each kept model is checked at 17 levels against the
/// replay of its sequence ([`crate::lod::check_levels`]). `progress` gets the
/// fraction done.
pub fn build_seq(frames: &Frames, options: &SeqOptions, progress: &mut dyn FnMut(f64)) -> Result<BuiltSeq> {
    let quantized;
    let (frames, quantization) = match options.position_bits {
        None => (frames, None),
        Some(bits) => {
            if !(8..=20).contains(&bits) {
                return Err(Error::Invalid(format!("{bits} bits per coordinate: 8 to 20")));
            }
            let mut f = frames.clone();
            let q = Quantization::of(&f, bits);
            for p in f.positions.iter_mut().chain(f.reference.iter_mut()) {
                q.apply(p);
            }
            f.mesh.positions = f.positions[0].clone();
            quantized = f;
            (&quantized, Some(q))
        }
    };
    if options.samples == 0 || options.samples > crate::distance::MAX_SAMPLES {
        return Err(Error::Invalid(format!(
            "{} samples per surface is out of range: 1 to {}",
            options.samples,
            crate::distance::MAX_SAMPLES
        )));
    }
    if options.max_sequences == 0 || options.candidates == 0 {
        return Err(Error::Invalid("at least one sequence and one candidate".into()));
    }
    if options.tolerance.is_nan() || options.tolerance < 1.0 {
        return Err(Error::Invalid(format!("tolerance {} is not a factor of 1 or more", options.tolerance)));
    }
    let strips = stripify(&frames.mesh, &options.strip.clone().weld(false))?;
    if strips.changes_mesh() {
        return Err(Error::Invalid(format!(
            "{} strips add vertices or swap edges: frames could not share them; use another stripifier",
            strips.algorithm.name()
        )));
    }
    let tris = strips.triangles.clone();
    // With the first frame's attributes: the simplifier then keeps seam vertices in
    // place, so that seams stay seams at every level of every frame.
    let frame_mesh = |p: &[[f32; 3]]| {
        let mut mesh = Mesh::from_triangles(p.to_vec(), &tris);
        mesh.attributes = frames.mesh.attributes.clone();
        mesh
    };
    let f_count = frames.positions.len();
    // Every frame's own sequence, and the reference pose's (or frame 0's).
    let t = Instant::now();
    let full = Options::default().target(Target::Triangles(0)).placement(Placement::Endpoint);
    let threads = options.strip.threads;
    let own = by_frames(threads, f_count, &mut |done| progress(0.4 * done), |i| {
        Ok(simplify(&frame_mesh(&frames.positions[i]), &full, &mut |_| {})?.sequence)
    })?;
    let reference = match &frames.reference {
        Some(p) => simplify(&frame_mesh(p), &full, &mut |_| {})?.sequence,
        None => own[0].clone(),
    };
    let reference_name = if frames.reference.is_some() { "reference".to_string() } else { frames.names[0].clone() };
    let simplify_ms = t.elapsed().as_secs_f64() * 1e3;
    // Candidates: 0 is the reference; then frames.
    let step = f_count.div_ceil(options.candidates.min(f_count)).max(1);
    // (name, sequence, the pose it was simplified on).
    let reference_pose = frames.reference.as_deref().unwrap_or(&frames.positions[0]);
    let mut candidates: Vec<(String, &CollapseSequence, &[[f32; 3]])> =
        vec![(reference_name.clone(), &reference, reference_pose)];
    candidates.extend((0..f_count).step_by(step).map(|f| (frames.names[f].clone(), &own[f], &frames.positions[f][..])));
    // The distance matrix: quality[c][f], and each frame's own.
    let t = Instant::now();
    // Each frame's column (its own sequence's quality, then every candidate's).
    let columns = by_frames(threads, f_count, &mut |done| progress(0.4 + 0.5 * done), |f| {
        let p = &frames.positions[f];
        let mesh = frame_mesh(p);
        let surface = Surface::new(&mesh, options.samples)?;
        let measure = |seq: &CollapseSequence| -> Result<Quality> {
            let mut d = [Distance::default(); 2];
            for (r, &ratio) in QUALITY_RATIOS.iter().enumerate() {
                let level = seq.level_for_ratio(tris.len(), ratio);
                // Endpoint collapses keep the survivor's own position: the frame's,
                // not the one recorded in the sequence (another pose's).
                let replayed = seq.replay(&mesh, level)?;
                d[r] = surface.distance_to_with(&Mesh::from_triangles(p.clone(), &replayed.triangles), threads)?;
            }
            Ok(Quality::from(d))
        };
        let own_q = measure(&own[f])?;
        let column = candidates.iter().map(|(_, seq, _)| measure(seq)).collect::<Result<Vec<_>>>()?;
        Ok((own_q, column))
    })?;
    let mut quality = vec![vec![Quality::default(); f_count]; candidates.len()];
    let mut own_quality = Vec::with_capacity(f_count);
    for (f, (own_q, column)) in columns.into_iter().enumerate() {
        own_quality.push(own_q);
        for (c, q) in column.into_iter().enumerate() {
            quality[c][f] = q;
        }
    }
    let distance_ms = t.elapsed().as_secs_f64() * 1e3;
    let assign = assign_sequences(&quality, &own_quality, options.max_sequences, options.tolerance);
    let mut used: Vec<usize> = assign.clone();
    used.sort_unstable();
    used.dedup();
    // The models, one per used sequence, over the same strips.
    let t = Instant::now();
    let built = crate::parallel::map_ordered(threads, &used, |&c| {
        let (_, sequence, pose) = candidates[c];
        let mut sets = Sets::build(pose, &strips.strips, sequence, Placement::Endpoint)?;
        // Checked before it is returned: 17 levels against the replay on the pose
        // the sequence was made on (whose positions the replay's survivors keep).
        super::check::check_levels(&sets, &frame_mesh(pose), sequence, (sets.levels() as usize / 16).max(1), 1)?;
        sets.positions = Vec::new();
        Ok((sets, sequence.clone()))
    });
    let (models, sequences): (Vec<Sets>, Vec<CollapseSequence>) = built.into_iter().collect::<Result<Vec<_>>>()?.into_iter().unzip();
    let model_ms = t.elapsed().as_secs_f64() * 1e3;
    progress(1.0);
    let frame_model: Vec<u32> = assign.iter().map(|c| used.binary_search(c).unwrap_or(0) as u32).collect();
    let report = SeqReport {
        frames: f_count,
        vertices: frames.mesh.positions.len(),
        triangles: tris.len(),
        strips: strips.strips.len(),
        candidates: candidates.len(),
        sequences: used.iter().map(|&c| candidates[c].0.clone()).collect(),
        quality: (0..f_count)
            .map(|f| FrameQuality {
                frame: frames.names[f].clone(),
                sequence: candidates[assign[f]].0.clone(),
                chosen: quality[assign[f]][f],
                reference: quality[0][f],
                own: own_quality[f],
            })
            .collect(),
        simplify_ms,
        distance_ms,
        model_ms,
    };
    let seq = LodSeq {
        names: frames.names.clone(),
        positions: frames.positions.clone(),
        frame_model,
        models,
        quantization,
        attributes: frames.mesh.attributes.clone(),
    };
    Ok(BuiltSeq { seq, triangles: tris, sequences, report })
}

/// `f(i)` for every frame `i < n`, results in frame order, in parallel when `threads`
/// allow; `progress` gets the fraction done after each batch of frames (the batches
/// only pace the progress: the results do not depend on them). The first error in
/// frame order is the error.
fn by_frames<R: Send>(
    threads: crate::parallel::Threads,
    n: usize,
    progress: &mut dyn FnMut(f64),
    f: impl Fn(usize) -> Result<R> + Sync,
) -> Result<Vec<R>> {
    let batch = 4 * threads.count().max(1);
    let mut out = Vec::with_capacity(n);
    for start in (0..n).step_by(batch) {
        let end = (start + batch).min(n);
        for r in crate::parallel::map_range(threads, end - start, |i| f(start + i)) {
            out.push(r?);
        }
        progress(end as f64 / n as f64);
    }
    Ok(out)
}

/// The sequence of each frame (an index into the candidates of `quality[c][f]`, 0
/// the reference pose's): at most `max_sequences` candidates chosen besides the
/// reference pose's by greedy k-center on each frame's Hausdorff factor against its
/// own sequence (`own_quality`), stopping once every frame is within `tolerance`; each frame
/// then takes the best chosen one that is no worse than the reference pose's.
fn assign_sequences(quality: &[Vec<Quality>], own_quality: &[Quality], max_sequences: usize, tolerance: f64) -> Vec<usize> {
    let f_count = own_quality.len();
    let candidates = quality.len();
    // Greedy k-center on the worse Hausdorff factor against the frame's own. A
    // sequence counts for a frame only where it is no worse than the reference
    // pose's (candidate 0), which every frame may fall back to; so the objective
    // is the one the assignment below sees.
    let factor = |c: usize, f: usize| {
        if c == 0 || quality[c][f].within(&quality[0][f]) {
            quality[c][f].factor(&own_quality[f])
        } else {
            f64::INFINITY
        }
    };
    let mut chosen: Vec<usize> = Vec::new();
    let mut best: Vec<f64> = (0..f_count).map(|f| factor(0, f)).collect();
    while chosen.len() < max_sequences {
        let worst = best.iter().copied().fold(0.0, f64::max);
        if worst <= tolerance {
            break;
        }
        let score = |c: usize| {
            let v: Vec<f64> = (0..f_count).map(|f| best[f].min(factor(c, f))).collect();
            (v.iter().copied().fold(0.0, f64::max), v.iter().sum::<f64>())
        };
        let Some((c, (max, sum))) = (0..candidates)
            .filter(|c| !chosen.contains(c))
            .map(|c| (c, score(c)))
            .min_by(|a, b| a.1 .0.total_cmp(&b.1 .0).then(a.1 .1.total_cmp(&b.1 .1)))
        else {
            break;
        };
        if max >= worst && sum >= best.iter().sum::<f64>() {
            break;
        }
        chosen.push(c);
        for (f, b) in best.iter_mut().enumerate() {
            *b = b.min(factor(c, f));
        }
    }
    // Each frame: the best of the chosen sequences and the reference pose's.
    (0..f_count)
        .map(|f| {
            chosen
                .iter()
                .copied()
                .chain([0])
                .min_by(|&a, &b| factor(a, f).total_cmp(&factor(b, f)))
                .unwrap_or(0)
        })
        .collect()
}

impl LodSeq {
    /// Number of frames.
    pub fn frame_count(&self) -> usize {
        self.names.len()
    }

    /// Frame names.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Positions of frame `f`.
    pub fn positions(&self, f: usize) -> &[[f32; 3]] {
        &self.positions[f]
    }

    /// The vertex attributes every frame shares (the first frame file's); empty when
    /// it has none.
    pub fn attributes(&self) -> &[crate::mesh::Attribute] {
        &self.attributes
    }

    /// The models (one per kept sequence).
    pub fn models(&self) -> &[Sets] {
        &self.models
    }

    /// The model frame `f` uses.
    pub fn model_of(&self, f: usize) -> usize {
        self.frame_model[f] as usize
    }

    /// Positions at fractional frame `t` (0 to frames - 1): linear between the two
    /// key frames around it, `(1 - u) V(k) + u V(k + 1)`, what the rendering crate's
    /// morph shader computes on the GPU. The level follows the nearest key frame
    /// ([`LodSeq::nearest_frame`]).
    pub fn morph(&self, t: f64) -> Vec<[f32; 3]> {
        let last = self.frame_count() - 1;
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, last as f64) };
        let k = (t.floor() as usize).min(last);
        let u = (t - k as f64) as f32;
        let (a, b) = (&self.positions[k], &self.positions[(k + 1).min(last)]);
        a.iter().zip(b).map(|(p, q)| [0, 1, 2].map(|d| (1.0 - u) * p[d] + u * q[d])).collect()
    }

    /// The key frame whose level a fractional frame uses: the nearest one (its
    /// sequence describes the pose best).
    pub fn nearest_frame(&self, t: f64) -> usize {
        let last = self.frame_count() - 1;
        if t.is_nan() {
            return 0;
        }
        (t.round().max(0.0) as usize).min(last)
    }

    /// Resolves `spec` for frame `f`'s model.
    pub fn level(&self, f: usize, spec: LevelSpec) -> u32 {
        self.models[self.model_of(f)].level_of(spec)
    }

    /// A cursor at frame `f` and `spec`.
    pub fn cursor(&self, f: usize, spec: LevelSpec) -> SeqCursor<'_> {
        let slots = self.models[0].slot_count() + self.models[0].strip_count();
        let mut c = SeqCursor {
            seq: self,
            cursors: (0..self.models.len()).map(|_| None).collect(),
            frame: usize::MAX,
            model: usize::MAX,
            buffer: vec![crate::strip::DEFAULT_RESTART; slots],
            changed: Vec::new(),
        };
        c.set(f, spec);
        c
    }
}

/// The strips of one (frame, level) of a [`LodSeq`], kept current as either moves:
/// [`SeqCursor::set`] updates one padded restart buffer (the layout of
/// [`crate::lod::Cursor`], the same for every frame) and returns the strips whose
/// range changed. Each model keeps its own cursor, so a change of level re-walks only
/// the strips that changed, and a change of frame to another model copies only the
/// strips that differ.
#[derive(Clone, Debug)]
pub struct SeqCursor<'a> {
    seq: &'a LodSeq,
    cursors: Vec<Option<Cursor<'a>>>,
    frame: usize,
    model: usize,
    buffer: Vec<u32>,
    changed: Vec<u32>,
}

impl<'a> SeqCursor<'a> {
    /// Moves to frame `f` (clamped to the last) at `spec`; returns the strips whose
    /// range of [`SeqCursor::buffer`] changed.
    pub fn set(&mut self, f: usize, spec: LevelSpec) -> &[u32] {
        let f = f.min(self.seq.frame_count() - 1);
        let m = self.seq.model_of(f);
        let level = self.seq.level(f, spec);
        let model = &self.seq.models[m];
        self.changed.clear();
        self.frame = f;
        let fresh = self.cursors[m].is_none();
        let cursor = match &mut self.cursors[m] {
            Some(c) => {
                c.set_level(level);
                c
            }
            slot @ None => slot.insert(model.cursor(level)),
        };
        if m == self.model && !fresh {
            // Same model: the cursor's own changes (relative to this buffer).
            for &s in cursor.changed() {
                let r = cursor.changed_range(s as usize);
                self.buffer[r.clone()].copy_from_slice(&cursor.buffer()[r]);
                self.changed.push(s);
            }
        } else {
            for s in 0..model.strip_count() {
                let r = cursor.strip_range(s);
                if self.buffer[r.clone()] != cursor.buffer()[r.clone()] {
                    self.buffer[r.clone()].copy_from_slice(&cursor.buffer()[r]);
                    self.changed.push(s as u32);
                }
            }
            self.model = m;
        }
        &self.changed
    }

    /// The current frame.
    pub fn frame(&self) -> usize {
        self.frame
    }

    /// The current level (of the frame's model).
    pub fn level(&self) -> u32 {
        self.cursors[self.model].as_ref().map_or(0, |c| c.level())
    }

    /// The padded restart buffer: each strip in its range, then restarts.
    pub fn buffer(&self) -> &[u32] {
        &self.buffer
    }

    /// The non-empty strips of the current frame and level.
    pub fn strips(&self) -> StripSet {
        self.cursors[self.model].as_ref().map(|c| c.strips()).unwrap_or_default()
    }
}

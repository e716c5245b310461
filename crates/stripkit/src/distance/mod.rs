//! Surface-to-surface distances: symmetric Hausdorff and RMS distance between two
//! triangle meshes, by area-weighted surface sampling (stratified, fixed seed, so the
//! figures are reproducible) and exact point-to-triangle distances through a
//! [`bvh::Bvh`].

pub mod bvh;

use crate::parallel::Threads;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::vec3;
use bvh::Bvh;

/// Distances from the samples of one surface to the other surface.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OneSided {
    /// Largest sample distance.
    pub max: f64,
    /// Root mean square of the sample distances.
    pub rms: f64,
    /// Mean sample distance.
    pub mean: f64,
}

/// The result of [`distance`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Distance {
    /// Symmetric Hausdorff distance: the larger of the two one-sided maxima.
    pub hausdorff: f64,
    /// RMS distance over the samples of both directions.
    pub rms: f64,
    /// Bounding-box diagonal of the first mesh ([`Distance::relative`] divides by it).
    pub diagonal: f64,
    /// Samples of A against B.
    pub a_to_b: OneSided,
    /// Samples of B against A.
    pub b_to_a: OneSided,
}

impl Distance {
    /// `x` (one of these distances) as a fraction of the first mesh's bounding-box
    /// diagonal; 0 where the diagonal is 0 (a mesh of one point).
    pub fn relative(&self, x: f64) -> f64 {
        if self.diagonal > 0.0 {
            x / self.diagonal
        } else {
            0.0
        }
    }
}

/// Samples used when none are asked for.
pub const DEFAULT_SAMPLES: usize = 100_000;

/// Most points [`distance`] samples on each surface: 10^7, about 480 MB of sample
/// points for the two surfaces (24 bytes each), inside 1 GiB with the meshes and
/// their BVHs. Larger requests are refused before anything is allocated
/// (`--samples 100000000000` once asked for 2.4 TB; 10^8, the earlier bound, 2.4 GB,
/// which aborted under a 1.5 GB address-space cap).
pub const MAX_SAMPLES: usize = 10_000_000;

/// `n` points on the surface of `mesh`, area-weighted: stratified along the
/// cumulative area (point `i` falls in the `i`-th of `n` equal slices), uniform inside
/// its triangle. Deterministic for a given `seed`. Empty when the mesh has no area.
pub fn sample_surface(mesh: &Mesh, n: usize, seed: u64) -> Vec<[f64; 3]> {
    let tris = mesh.triangulate().tris;
    let corners = |t: &[u32; 3]| t.map(|v| mesh.positions[v as usize].map(|x| x as f64));
    let area = |c: &[[f64; 3]; 3]| 0.5 * vec3::norm(vec3::tri_normal(c[0], c[1], c[2]));
    let total: f64 = tris.iter().map(|t| area(&corners(t))).sum();
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // also true for NaN, on purpose
    if n == 0 || !(total > 0.0) {
        return Vec::new();
    }
    let mut rng = SplitMix(seed);
    let mut out = Vec::with_capacity(n);
    let mut t = 0usize;
    let mut c = corners(&tris[0]);
    let mut acc_before = 0.0;
    let mut acc_after = area(&c);
    for i in 0..n {
        let target = (i as f64 + rng.next()) / n as f64 * total;
        while acc_after < target && t + 1 < tris.len() {
            t += 1;
            c = corners(&tris[t]);
            acc_before = acc_after;
            acc_after += area(&c);
        }
        let _ = acc_before;
        let (r1, r2) = (rng.next().sqrt(), rng.next());
        let (wa, wb, wc) = (1.0 - r1, r1 * (1.0 - r2), r1 * r2);
        out.push([0, 1, 2].map(|k| wa * c[0][k] + wb * c[1][k] + wc * c[2][k]));
    }
    out
}

/// A small deterministic generator (SplitMix64).
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E3779B97F4A7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58476D1CE4E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D049BB133111EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Points per part of [`one_sided`]: the parts are fixed by the points alone, and
/// their sums added in order, so the figures are the same bits at any thread count.
const POINTS_PER_PART: usize = 4096;

/// Distances from `points` to the surface in `bvh`, `threads` parts at a time.
fn one_sided(points: &[[f64; 3]], bvh: &Bvh, threads: Threads) -> OneSided {
    if points.is_empty() {
        return OneSided::default();
    }
    let chunks: Vec<&[[f64; 3]]> = points.chunks(POINTS_PER_PART).collect();
    let parts: Vec<(f64, f64, f64)> = crate::parallel::map_ordered(threads, &chunks, |part| {
        let mut stack = Vec::with_capacity(64);
        let (mut max, mut sum2, mut sum) = (0.0f64, 0.0f64, 0.0f64);
        let mut hint = 0;
        for &p in part.iter() {
            let (d2, slot) = bvh.closest(p, hint, &mut stack);
            hint = slot;
            let d = d2.sqrt();
            max = max.max(d);
            sum2 += d2;
            sum += d;
        }
        (max, sum2, sum)
    });
    let n = points.len() as f64;
    let max = parts.iter().map(|p| p.0).fold(0.0, f64::max);
    let sum2: f64 = parts.iter().map(|p| p.1).sum();
    let sum: f64 = parts.iter().map(|p| p.2).sum();
    OneSided { max, rms: (sum2 / n).sqrt(), mean: sum / n }
}

fn check(mesh: &Mesh, name: &str) -> Result<()> {
    let n = mesh.positions.len();
    if mesh.face_indices.iter().any(|&v| v as usize >= n) {
        return Err(Error::Invalid(format!("{name}: a face refers to a vertex beyond its {n} vertices")));
    }
    if mesh.positions.iter().flatten().any(|x| !x.is_finite()) {
        return Err(Error::Invalid(format!("{name}: a vertex position is not a finite number")));
    }
    if mesh.triangle_count() == 0 {
        return Err(Error::Invalid(format!("{name}: the mesh has no faces")));
    }
    Ok(())
}

/// Symmetric Hausdorff and RMS distance between the surfaces of `a` and `b`:
/// `samples` points on each surface (see [`sample_surface`]), each measured exactly
/// against the other surface through a BVH. O((samples + n) log n), on the caller's
/// thread ([`distance_with`] takes more).
///
/// Fails when `samples` is 0 or above [`MAX_SAMPLES`].
pub fn distance(a: &Mesh, b: &Mesh, samples: usize) -> Result<Distance> {
    distance_with(a, b, samples, Threads::SERIAL)
}

/// [`distance`] measuring the samples `threads` at a time: the same bits at any count.
pub fn distance_with(a: &Mesh, b: &Mesh, samples: usize, threads: Threads) -> Result<Distance> {
    Surface::new(a, samples)?.distance_to_with(b, threads)
}

/// One side of [`distance`] prepared once (its BVH and its samples), to measure many
/// other meshes against the same surface: [`Surface::distance_to`] gives exactly what
/// [`distance`] gives with this mesh first.
pub struct Surface {
    bvh: Bvh,
    samples: Vec<[f64; 3]>,
    count: usize,
    diagonal: f64,
}

impl Surface {
    /// Prepares `mesh` with `samples` points (1 to [`MAX_SAMPLES`]).
    pub fn new(mesh: &Mesh, samples: usize) -> Result<Surface> {
        if samples == 0 || samples > MAX_SAMPLES {
            return Err(Error::Invalid(format!(
                "{samples} samples per surface is out of range: 1 to {MAX_SAMPLES} \
                 (each sample takes 24 bytes, on both surfaces)"
            )));
        }
        check(mesh, "first mesh")?;
        let diagonal = mesh
            .bounds()
            .map(|(lo, hi)| (0..3).map(|k| ((hi[k] - lo[k]) as f64).powi(2)).sum::<f64>().sqrt())
            .unwrap_or(0.0);
        Ok(Surface {
            bvh: Bvh::build(&mesh.positions, &mesh.triangulate().tris),
            samples: sample_surface(mesh, samples, 0x5EED_0001),
            count: samples,
            diagonal,
        })
    }

    /// Bounding-box diagonal of the prepared mesh.
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }

    /// [`distance`] from the prepared mesh to `b`, with as many samples on `b`.
    pub fn distance_to(&self, b: &Mesh) -> Result<Distance> {
        self.distance_to_with(b, Threads::SERIAL)
    }

    /// [`Surface::distance_to`] measuring the samples `threads` at a time: the same
    /// bits at any count.
    pub fn distance_to_with(&self, b: &Mesh, threads: Threads) -> Result<Distance> {
        check(b, "second mesh")?;
        let bvh_b = Bvh::build(&b.positions, &b.triangulate().tris);
        let pb = sample_surface(b, self.count, 0x5EED_0002);
        let pa = &self.samples;
        let a_to_b = one_sided(pa, &bvh_b, threads);
        let b_to_a = one_sided(&pb, &self.bvh, threads);
        let total = (pa.len() + pb.len()).max(1) as f64;
        let rms = ((a_to_b.rms.powi(2) * pa.len() as f64 + b_to_a.rms.powi(2) * pb.len() as f64) / total).sqrt();
        Ok(Distance { hausdorff: a_to_b.max.max(b_to_a.max), rms, diagonal: self.diagonal, a_to_b, b_to_a })
    }
}

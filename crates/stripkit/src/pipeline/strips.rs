//! [`Strips`], the door's verified result, and its encoders: joined forms, restart
//! and stitched buffers per group, file bytes (read back and checked), the changed
//! mesh of `single`, JSON.

use super::{fail, Algorithm, Join, Split};
use crate::error::{Error, Result};
use crate::mesh::io::{self, Format, WriteOptions};
use crate::mesh::Mesh;
use crate::metrics::{self, CacheKind, Figures};
use crate::strip::{self, StripSet};
use crate::stripify::single::SingleReport;
use std::borrow::Cow;
use std::ops::Range;
use std::path::Path;
use std::time::Duration;

/// Verified strips and what they were verified against.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Strips {
    /// The strips as the stripifier made them.
    pub strips: StripSet,
    /// The triangles the strips draw, each with its face's winding: the mesh's fan, or
    /// (quad-level verification) the split the strips chose. Degenerate triangles of the
    /// input are left in and counted in [`Figures::dropped_degenerate`].
    pub triangles: Vec<[u32; 3]>,
    /// The algorithm that ran, with its settings ([`Algorithm::Auto`] resolved).
    pub algorithm: Algorithm,
    /// How quads were split: [`Split::Fan`] or [`Split::Qstrip`] (quad-level check).
    pub split: Split,
    /// QSTRIP and quad-single: quads stripped as quads.
    pub quads: Option<usize>,
    /// Every figure of docs/metrics.md, measured against [`Strips::triangles`].
    pub figures: Figures,
    /// The join used.
    pub join: Join,
    /// The restart index of [`Join::Restart`].
    pub restart_index: u32,
    /// Time of the stripifier alone (no verification, no figures).
    pub stripify_time: Duration,
    /// [`Algorithm::Single`]: what the builder did (Steiner vertices, swaps, pieces
    /// merged, times).
    pub single: Option<SingleReport>,
    /// Vertices the algorithm added after the mesh's own (Steiner vertices of
    /// [`Algorithm::Single`], each at the midpoint of the edge it split): the strips
    /// and [`Strips::triangles`] index the mesh's positions followed by these.
    pub added_positions: Vec<[f32; 3]>,
    /// For each added vertex, the two vertices whose midpoint it is (an edge split);
    /// either may itself be an added vertex of a lower number.
    pub added_from: Vec<[u32; 2]>,
    /// For each face group of the mesh ([`Mesh::group_count`]: one for a mesh without
    /// groups), the range of [`Strips::strips`] drawing its faces. A strip never draws
    /// faces of two groups, and the joined forms never join strips of two groups.
    pub group_ranges: Vec<Range<usize>>,
    /// Vertices the faces used that [`StripOptions::weld`](super::StripOptions::weld) moved onto a bit-identical
    /// vertex of lower id (0 with welding off or nothing to weld); they are still in
    /// the mesh, unused by the strips (a first-use order leaves them out).
    pub welded: usize,
    /// Wall time of the door's steps, in order: `weld` (with welding on), `stripify`
    /// ([`Strips::stripify_time`]), `figures` (the figures and the check of the strips)
    /// and `joined` (the joined form encoded, read back and checked); a mesh of several
    /// face groups reports its stripify time alone. For `strip --timings`.
    pub phases: Vec<(&'static str, Duration)>,
}

impl Strips {
    /// The strips as [`Strips::join`] joins them, read back from the encoded form
    /// (the door checked this form too): the strips themselves for
    /// [`Join::Restart`] and [`Join::Separate`], one stitched strip for
    /// [`Join::Degenerate`].
    ///
    /// With several face groups, [`Join::Degenerate`] gives one stitched strip per
    /// group (in group order, empty groups left out), never one across groups.
    pub fn joined(&self) -> StripSet {
        joined(&self.strips, &self.group_ranges, self.join, self.restart_index)
    }

    /// One buffer with [`Strips::restart_index`] between strips (every group; a restart
    /// separates the strips of two groups, but one draw call gives them one material:
    /// see [`Strips::restart_buffer_of`]).
    pub fn restart_buffer(&self) -> Vec<u32> {
        strip::encode_restart(&self.strips, self.restart_index)
    }
    /// One strip, strips stitched by degenerate triangles. With several face groups
    /// this stitches across them; draw [`Strips::stitched_of`] each group instead.
    pub fn stitched(&self) -> Vec<u32> {
        strip::encode_stitched(&self.strips)
    }
    /// Number of face groups the strips are kept apart by (at least 1).
    pub fn group_count(&self) -> usize {
        self.group_ranges.len().max(1)
    }
    /// The strips of face group `g` (empty for a group without faces or past the last).
    pub fn strips_of(&self, g: usize) -> StripSet {
        let range = self.group_ranges.get(g).cloned().unwrap_or(0..0);
        strip_range(&self.strips, range)
    }
    /// The restart buffer of group `g`'s strips alone: one draw call with its material.
    pub fn restart_buffer_of(&self, g: usize) -> Vec<u32> {
        strip::encode_restart(&self.strips_of(g), self.restart_index)
    }
    /// Group `g`'s strips stitched into one by degenerate triangles.
    pub fn stitched_of(&self, g: usize) -> Vec<u32> {
        strip::encode_stitched(&self.strips_of(g))
    }
    /// The group of strip `s` (0 past the last).
    pub fn group_of_strip(&self, s: usize) -> usize {
        self.group_ranges.iter().position(|r| r.contains(&s)).unwrap_or(0)
    }
    /// `indices_restart / quads` of docs/metrics.md, for QSTRIP and quad-single.
    pub fn indices_per_quad(&self) -> Option<f64> {
        self.quads.filter(|&q| q > 0).map(|q| self.figures.indices_restart as f64 / q as f64)
    }

    /// [`Algorithm::Balanced`] whose bound was out of reach on this mesh: the misses
    /// per triangle its strips have (FIFO of [`Figures::cache`]'s size, the cache it
    /// was tuned for), which exceed `max_acmr`. `None` for other algorithms and for a
    /// bound met.
    pub fn max_acmr_unreached(&self) -> Option<f64> {
        let Algorithm::Balanced { max_acmr } = self.algorithm else { return None };
        let cache = self.figures.cache;
        let reached = if cache.kind == CacheKind::Fifo {
            self.figures.acmr
        } else {
            let order = strip::decode(&self.strips);
            let vertices = order.iter().flatten().map(|&v| v as usize + 1).max().unwrap_or(0);
            metrics::acmr(&order, vertices, cache.size, CacheKind::Fifo)
        };
        // A relative slack for the float sums behind the two figures.
        (reached > max_acmr * (1.0 + 1e-9)).then_some(reached)
    }

    /// Where a file of `format` holds stitched strips (glTF unless [`Join::Separate`],
    /// PLY with [`Join::Degenerate`]; see [`Strips::for_format`]): the zero-area
    /// triangles (a repeated index: swaps and stitching) they decode to besides the
    /// mesh's triangles. `None` where the file holds no stitched strip.
    pub fn stitched_degenerate_in(&self, format: Format) -> Option<usize> {
        let stitched = match format {
            Format::Gltf | Format::Glb => self.join != Join::Separate,
            Format::Ply => self.join == Join::Degenerate,
            _ => false,
        };
        let set = self.written_form(format).filter(|_| stitched)?;
        Some(set.iter().map(strip::degenerate_windows).sum())
    }

    /// The strips a file of `format` holds: PLY's `tristrips` ends each strip with -1
    /// (its own restart), or holds the one stitched strip of [`Join::Degenerate`]; core
    /// glTF has no restart index, so it gets the one stitched strip as a
    /// `TRIANGLE_STRIP` primitive, or one primitive per strip with [`Join::Separate`].
    /// `None` for formats that cannot hold strips (OBJ, OFF, STL; for OBJ,
    /// [`Strips::to_file_bytes`] writes the triangles in strip order instead).
    pub fn for_format(&self, format: Format) -> Option<StripSet> {
        self.written_form(format).map(Cow::into_owned)
    }

    /// [`Strips::for_format`], borrowing the strips where the file holds them as they
    /// are (PLY's restart and separate joins): no copy of them on the way out.
    fn written_form(&self, format: Format) -> Option<Cow<'_, StripSet>> {
        match (format, self.join) {
            (Format::Ply, Join::Degenerate) | (Format::Gltf | Format::Glb, Join::Separate) => {
                Some(Cow::Owned(self.joined()))
            }
            (Format::Ply, _) => Some(Cow::Borrowed(&self.strips)),
            (Format::Gltf | Format::Glb, _) => {
                Some(Cow::Owned(joined(&self.strips, &self.group_ranges, Join::Degenerate, self.restart_index)))
            }
            _ => None,
        }
    }

    /// The bytes of a `format` file holding `mesh`'s vertices and these strips (see
    /// [`Strips::for_format`]; OBJ gets the strips' triangles in strip order, group by
    /// group), read back with the library's own reader and checked against
    /// [`Strips::triangles`] before they are returned.
    pub fn to_file_bytes(&self, mesh: &Mesh, format: Format) -> Result<Vec<u8>> {
        self.to_file_bytes_with(mesh, format, &WriteOptions::default())
    }

    /// [`Strips::to_file_bytes`] with write options (ASCII PLY).
    pub fn to_file_bytes_with(&self, mesh: &Mesh, format: Format, options: &WriteOptions) -> Result<Vec<u8>> {
        let (out, to_write) = self.file_content(mesh, format)?;
        io::encode_checked(
            || io::write_bytes(format, &out, to_write.as_deref(), options),
            |bytes| self.check_file(&out, format, bytes, options.threads),
        )
    }

    /// Writes `mesh`'s vertices and these strips to `path`, in the format its extension
    /// names (gzip-compressed for `.gz`): the bytes of [`Strips::to_file_bytes_with`],
    /// read back and checked, then written atomically (the library's one checked write
    /// path). Nothing is written when the check fails.
    pub fn write_file(&self, mesh: &Mesh, path: impl AsRef<Path>, options: &WriteOptions) -> Result<()> {
        let path = path.as_ref();
        let format = Format::from_path(path).map(|(f, _)| f).ok_or_else(|| Error::UnknownFormat {
            path: path.to_path_buf(),
            expected: io::SUPPORTED_EXTENSIONS,
        })?;
        let (out, to_write) = self.file_content(mesh, format)?;
        io::write_checked(
            path,
            || io::write_bytes(format, &out, to_write.as_deref(), options),
            |bytes| self.check_file(&out, format, bytes, options.threads),
        )
        .map(drop)
    }

    /// What a `format` file holds: the mesh the strips draw and [`Strips::for_format`];
    /// for OBJ, which has no strips, the triangles the strips draw, in strip order (what
    /// a vertex cache sees), group by group with their `g`/`usemtl`, over the mesh's
    /// vertices and attributes.
    fn file_content<'a>(&'a self, mesh: &'a Mesh, format: Format) -> Result<(Cow<'a, Mesh>, Option<Cow<'a, StripSet>>)> {
        let mesh = if self.changes_mesh() { Cow::Owned(self.changed_mesh(mesh)) } else { Cow::Borrowed(mesh) };
        if format == Format::Obj {
            let mut out =
                Mesh { face_offsets: vec![0], face_indices: Vec::new(), face_groups: Vec::new(), ..mesh.into_owned() };
            for g in 0..self.group_count() {
                for s in self.strips_of(g).iter() {
                    strip::for_each_triangle(s, |t| {
                        out.push_face(&t);
                        out.face_groups.push(g as u32);
                    });
                }
            }
            if out.groups.is_empty() {
                out.face_groups.clear();
            }
            return Ok((Cow::Owned(out), None));
        }
        match self.written_form(format) {
            Some(to_write) => Ok((mesh, Some(to_write))),
            None => Err(Error::Invalid(format!(
                "{format:?} files cannot hold strips; write PLY, glTF, GLB or OBJ (or JSON)"
            ))),
        }
    }

    /// The read-back check of [`Strips::file_content`] (`out`) written as `bytes`: the
    /// triangles decoded again must be [`Strips::triangles`]; for OBJ, each with its
    /// group too.
    fn check_file(&self, out: &Mesh, format: Format, bytes: &[u8], threads: crate::parallel::Threads) -> Result<()> {
        let name = format!("the {format:?} bytes to be written");
        let back = io::read_bytes(Path::new(&name), format, bytes)?;
        if format != Format::Obj {
            // Only the faces are compared: the rest of what was read back goes first,
            // and the faces are gathered straight into the check's buckets (on meshes
            // of millions of triangles every copy and every pass counts).
            let v = strip::verify_faces_with(&self.triangles, back.into_faces(), threads);
            if !v.ok() {
                return Err(fail(&format!("{name}, read back"), &v));
            }
            return Ok(());
        }
        // Welded on reading (vt or vn written): vertices renumbered by first use.
        let ids: Vec<u32> = if back.attributes.is_empty() {
            (0..out.vertex_count() as u32).collect()
        } else {
            let mut seen = vec![false; out.vertex_count()];
            out.face_indices.iter().copied().filter(|&v| !std::mem::replace(&mut seen[v as usize], true)).collect()
        };
        let tris: Vec<[u32; 3]> = back.triangulate().tris.iter().map(|t| t.map(|i| ids[i as usize])).collect();
        let v = strip::verify_triangles(&self.triangles, &tris);
        let group = |m: &Mesh, f: usize| m.groups.get(m.group_of(f) as usize).cloned().unwrap_or_default();
        let same_groups =
            back.face_count() == out.face_count() && (0..out.face_count()).all(|f| group(&back, f) == group(out, f));
        if !v.ok() || !same_groups {
            return Err(fail(&format!("{name}, read back (groups kept: {same_groups})"), &v));
        }
        Ok(())
    }

    /// Whether the strips draw a changed mesh (Steiner vertices or swapped edges).
    pub fn changes_mesh(&self) -> bool {
        !self.added_positions.is_empty() || self.single.as_ref().is_some_and(|r| r.swapped_edges > 0)
    }

    /// Per-vertex values (`values[v]` for each of the mesh's vertices: positions of
    /// another frame, normals, texture coordinates) extended over the added vertices,
    /// each the mean of the two it splits: what the changed mesh needs of them.
    pub fn with_added_vertices<const N: usize>(&self, values: &[[f32; N]]) -> Vec<[f32; N]> {
        let mut out = values.to_vec();
        out.reserve(self.added_from.len());
        for &[a, b] in &self.added_from {
            let (x, y) = (out[a as usize], out[b as usize]);
            out.push(std::array::from_fn(|d| ((x[d] as f64 + y[d] as f64) / 2.0) as f32));
        }
        out
    }

    /// The mesh the strips draw: `mesh` itself, or, where the algorithm changed it
    /// ([`Algorithm::Single`]), its positions plus [`Strips::added_positions`] and
    /// [`Strips::triangles`] as faces. Attributes follow: an added vertex gets the
    /// blend of the two it splits ([`Attribute::push_lerp`] at one half: integer kinds
    /// take the first one's value), a `NORMAL` (and a `TANGENT`'s direction) made unit
    /// length again, a `TANGENT`'s handedness the first one's; so do the mesh's group
    /// (single takes one) and material libraries. Swapped edges name input vertices,
    /// so their corners keep their values.
    ///
    /// [`Attribute::push_lerp`]: crate::Attribute::push_lerp
    pub fn changed_mesh(&self, mesh: &Mesh) -> Mesh {
        if !self.changes_mesh() {
            return mesh.clone();
        }
        let mut positions = mesh.positions.clone();
        positions.extend_from_slice(&self.added_positions);
        let mut out = Mesh::from_triangles(positions, &self.triangles);
        out.attributes = mesh.attributes.clone();
        for a in &mut out.attributes {
            for &[x, y] in &self.added_from {
                a.push_lerp(x as usize, y as usize, 0.5);
                let v = a.len() - 1;
                unit_direction(a, v, x as usize);
            }
        }
        out.groups = mesh.groups.clone();
        if !out.groups.is_empty() && mesh.face_count() > 0 {
            out.face_groups = vec![mesh.group_of(0); out.face_count()];
        }
        out.material_libraries = mesh.material_libraries.clone();
        out
    }

    /// The strips as JSON: `{"join", "strips": [[..], ..]}` (the joined strips), plus
    /// `"restart_index"` and `"indices"` (the restart buffer) with [`Join::Restart`], and
    /// with several face groups `"groups": [[start, end], ..]`, the entries of
    /// `"strips"` each group draws.
    pub fn to_json(&self) -> serde_json::Map<String, serde_json::Value> {
        let mut obj = serde_json::Map::new();
        obj.insert("join".into(), self.join.name().into());
        let strips: Vec<serde_json::Value> =
            self.joined().iter().map(|s| s.iter().map(|&i| serde_json::Value::from(i)).collect()).collect();
        obj.insert("strips".into(), strips.into());
        if self.group_ranges.len() > 1 {
            let mut next = 0;
            let groups: Vec<serde_json::Value> = self
                .group_ranges
                .iter()
                .map(|r| {
                    // Join::Degenerate stitches each non-empty group into one strip.
                    let n = if self.join == Join::Degenerate { usize::from(!r.is_empty()) } else { r.len() };
                    next += n;
                    serde_json::json!([next - n, next])
                })
                .collect();
            obj.insert("groups".into(), groups.into());
        }
        if self.join == Join::Restart {
            obj.insert("restart_index".into(), self.restart_index.into());
            obj.insert("indices".into(), self.restart_buffer().into());
        }
        obj
    }
}

/// Vertex `v` of a `NORMAL` (3 or 4 float components) or `TANGENT` (4) attribute made
/// a unit vector again after a blend, the fourth component (a tangent's handedness)
/// taken from vertex `from`; a blend of opposite vectors (length 0) keeps `from`'s.
fn unit_direction(a: &mut crate::mesh::Attribute, v: usize, from: usize) {
    let direction = (a.name == "NORMAL" && a.components >= 3) || (a.name == "TANGENT" && a.components == 4);
    if !direction || !(a.scalar.is_float() || a.normalized) {
        return;
    }
    let x = [a.get(v, 0), a.get(v, 1), a.get(v, 2)];
    let len = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
    for c in 0..3 {
        let value = if len > 1e-12 && len.is_finite() { x[c] / len } else { a.get(from, c) };
        a.set(v, c, value);
    }
    if a.components == 4 {
        let w = a.get(from, 3);
        a.set(v, 3, w);
    }
}

/// The strips as `join` joins them, read back from the encoded form; `groups` are the
/// ranges of strips that may be stitched together (one per face group).
pub(super) fn joined(strips: &StripSet, groups: &[Range<usize>], join: Join, restart: u32) -> StripSet {
    match join {
        Join::Restart => strip::decode_restart(&strip::encode_restart(strips, restart), restart),
        Join::Degenerate => {
            let mut out = StripSet::new();
            for r in groups {
                let one = strip::encode_stitched(&strip_range(strips, r.clone()));
                if !one.is_empty() {
                    out.push(&one);
                }
            }
            out
        }
        Join::Separate => StripSet::from_strips(&strip::encode_separate(strips)),
    }
}

/// The strips `range` of a set (clamped to it).
fn strip_range(strips: &StripSet, range: Range<usize>) -> StripSet {
    let end = range.end.min(strips.len());
    let mut out = StripSet::new();
    for s in range.start.min(end)..end {
        out.push(strips.strip(s));
    }
    out
}

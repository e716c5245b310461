//! The collapse sequence as data: what every collapse removed and kept, and a replay
//! that rebuilds the simplifier's mesh after any prefix of it.

use crate::error::{Error, Result};
use crate::mesh::io::{encode_checked, write_checked};
use crate::mesh::{Attribute, Mesh};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// One collapse: vertex `removed` merged into vertex `kept`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Collapse {
    /// The vertex that disappears; every reference to it now names `kept`.
    pub removed: u32,
    /// The surviving vertex; it keeps its id.
    pub kept: u32,
    /// The surviving vertex's position after the collapse (its own position for the
    /// `endpoint` placement).
    pub position: [f32; 3],
    /// The cost of the collapse, a squared distance (area-averaged quadric error plus
    /// the weighted fan distance; see [`crate::simplify`]).
    pub error: f64,
}

/// An ordered sequence of collapses, with the triangles each one removed.
///
/// Triangle ids index the triangle list of the input (`Mesh::triangulate` order).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CollapseSequence {
    /// Vertex records of the input mesh.
    pub vertex_count: u32,
    /// Triangles of the input mesh (`Mesh::triangulate` order).
    pub triangle_count: u32,
    /// The collapses, first to last.
    pub collapses: Vec<Collapse>,
    /// `removed_triangles[removed_offsets[i]..removed_offsets[i + 1]]` are the triangle
    /// ids collapse `i` removed (two for an interior edge, one on a boundary).
    pub removed_offsets: Vec<u32>,
    /// Removed triangle ids of all collapses, concatenated.
    pub removed_triangles: Vec<u32>,
}

/// A mesh state rebuilt by [`CollapseSequence::replay`].
#[derive(Clone, Debug, PartialEq)]
pub struct Replayed {
    /// Positions of all input vertices (removed ones keep their last position).
    pub positions: Vec<[f32; 3]>,
    /// The surviving triangles, in input order, with their current vertices.
    pub triangles: Vec<[u32; 3]>,
    /// The input triangle id of each surviving triangle.
    pub triangle_ids: Vec<u32>,
    /// The input mesh's vertex attributes (UVs, normals, colours, ...) of all input
    /// vertices, the survivors' as the simplifier left them: unchanged with endpoint
    /// placement, blended along each collapsed edge otherwise (the rule of
    /// [`crate::simplify`]'s module documentation).
    pub attributes: Vec<Attribute>,
}

impl Replayed {
    /// The state as a triangle mesh (all vertex ids kept), with its attributes.
    pub fn to_mesh(&self) -> Mesh {
        let mut mesh = Mesh::from_triangles(self.positions.clone(), &self.triangles);
        mesh.attributes = self.attributes.clone();
        mesh
    }
}

const MAGIC: &[u8; 8] = b"SKCOLSQ1";

impl CollapseSequence {
    /// An empty sequence for a mesh of the given size.
    pub fn new(vertex_count: u32, triangle_count: u32) -> Self {
        CollapseSequence { vertex_count, triangle_count, removed_offsets: vec![0], ..Default::default() }
    }

    /// Number of collapses.
    pub fn len(&self) -> usize {
        self.collapses.len()
    }

    /// True when nothing was collapsed.
    pub fn is_empty(&self) -> bool {
        self.collapses.is_empty()
    }

    /// The first level (collapses applied) with at most
    /// [`ratio_target`](super::ratio_target)`(triangles, ratio)` of the `triangles`
    /// non-degenerate input triangles left: where [`super::simplify`] with
    /// [`super::Target::Ratio`] stops. The last level when none has so few.
    pub fn level_for_ratio(&self, triangles: usize, ratio: f64) -> usize {
        let target = super::ratio_target(triangles, ratio);
        let mut live = triangles;
        for i in 0..self.len() {
            if live <= target {
                return i;
            }
            live = live.saturating_sub(self.removed_by(i).len());
        }
        self.len()
    }

    /// The triangles removed by collapse `i`.
    pub fn removed_by(&self, i: usize) -> &[u32] {
        &self.removed_triangles[self.removed_offsets[i] as usize..self.removed_offsets[i + 1] as usize]
    }

    pub(crate) fn push(&mut self, c: Collapse, removed: &[u32]) {
        self.collapses.push(c);
        self.removed_triangles.extend_from_slice(removed);
        self.removed_offsets.push(self.removed_triangles.len() as u32);
    }

    /// Applies the first `k` collapses to `mesh` (the simplifier's input) in
    /// O(vertices + triangles + k): every removed vertex is renamed to its survivor,
    /// survivors take their recorded positions and the attributes the simplifier gave
    /// them (see [`Replayed::attributes`]), and triangles that become degenerate
    /// (and degenerate input triangles) are dropped. Gives exactly the simplifier's
    /// mesh after `k` collapses, attributes included, bit for bit.
    pub fn replay(&self, mesh: &Mesh, k: usize) -> Result<Replayed> {
        let tris = mesh.triangulate().tris;
        if mesh.positions.len() != self.vertex_count as usize || tris.len() != self.triangle_count as usize {
            return Err(Error::Invalid(format!(
                "collapse sequence is for a mesh of {} vertices and {} triangles, this mesh has {} and {}",
                self.vertex_count,
                self.triangle_count,
                mesh.positions.len(),
                tris.len()
            )));
        }
        let k = k.min(self.collapses.len());
        let n = mesh.positions.len();
        let mut positions = mesh.positions.clone();
        let mut parent: Vec<u32> = (0..n as u32).collect();
        mesh.check_attributes()?;
        let mut attributes = mesh.attributes.clone();
        for (i, c) in self.collapses[..k].iter().enumerate() {
            let (r, s) = (c.removed as usize, c.kept as usize);
            if r >= n || s >= n || parent[r] != r as u32 || parent[s] != s as u32 || r == s {
                return Err(Error::Invalid(format!(
                    "collapse {i} merges vertex {r} into {s}, which is not possible at that point"
                )));
            }
            parent[r] = s as u32;
            if !attributes.is_empty() {
                let wide = |p: [f32; 3]| p.map(|x| x as f64);
                let ends = [wide(positions[s]), wide(positions[r])];
                super::attributes::carry(&mut attributes, r as u32, s as u32, ends, wide(c.position));
            }
            positions[s] = c.position;
        }
        // Resolve chains with path compression.
        for v in 0..n {
            let mut root = v;
            while parent[root] as usize != root {
                root = parent[root] as usize;
            }
            let mut x = v;
            while parent[x] as usize != root {
                let next = parent[x] as usize;
                parent[x] = root as u32;
                x = next;
            }
        }
        let mut out = Replayed { positions, triangles: Vec::new(), triangle_ids: Vec::new(), attributes };
        for (t, tri) in tris.iter().enumerate() {
            let m = tri.map(|v| parent[v as usize]);
            if m[0] != m[1] && m[1] != m[2] && m[2] != m[0] {
                out.triangles.push(m);
                out.triangle_ids.push(t as u32);
            }
        }
        Ok(out)
    }

    /// Writes the sequence: JSON for a `.json` path, a compact little-endian binary
    /// otherwise (see [`CollapseSequence::read`]). The bytes are read back and compared
    /// with the sequence before the file is replaced, atomically
    /// ([`crate::io::write_encoded`]): never left half-written, nothing written when the
    /// check fails ([`Error::Verification`]).
    pub fn write(&self, path: &Path) -> Result<()> {
        write_checked(path, || self.encode_unchecked(path), |bytes| self.check_written(path, bytes)).map(drop)
    }

    /// The bytes [`CollapseSequence::write`] would write to `path` (JSON for a `.json`
    /// path, binary otherwise), read back and checked the same way, for callers that
    /// encode every output before writing any.
    pub fn encode(&self, path: &Path) -> Result<Vec<u8>> {
        encode_checked(|| self.encode_unchecked(path), |bytes| self.check_written(path, bytes))
    }

    fn encode_unchecked(&self, path: &Path) -> Result<Vec<u8>> {
        if is_json(path) {
            serde_json::to_vec(self).map_err(|e| Error::Invalid(format!("{}: {e}", path.display())))
        } else {
            Ok(self.to_bytes())
        }
    }

    /// Decodes `bytes` as [`CollapseSequence::read_bytes`] does and compares the result
    /// with this sequence.
    fn check_written(&self, path: &Path, bytes: &[u8]) -> Result<()> {
        if Self::read_bytes(path, bytes)? != *self {
            return Err(Error::Verification(format!(
                "{}, read back: the collapse sequence differs from the one encoded",
                path.display()
            )));
        }
        Ok(())
    }

    /// Reads a sequence written by [`CollapseSequence::write`]: JSON for a `.json`
    /// path, the binary layout below otherwise. See [`CollapseSequence::read_bytes`]
    /// for what is checked.
    ///
    /// Binary layout (little-endian): magic `SKCOLSQ1`, `u32` vertex count, `u32`
    /// triangle count, `u32` collapse count, then per collapse `u32 removed, u32 kept,
    /// 3 x f32 position, f64 error, u32 n, n x u32 removed triangle ids`.
    pub fn read(path: &Path) -> Result<CollapseSequence> {
        let bytes = std::fs::read(path).map_err(|source| Error::Io { path: path.to_path_buf(), source })?;
        Self::read_bytes(path, &bytes)
    }

    /// Decodes the bytes of a sequence file; `path` picks the format (JSON for
    /// `.json`) and names the file in errors. Nothing is allocated beyond what the
    /// bytes hold. Every collapse must name two different vertices below the vertex
    /// count, with a finite position and error, and remove triangle ids below the
    /// triangle count; there are fewer collapses than vertices, and nothing follows
    /// the last collapse. Whether the collapses can happen in that order on a given
    /// mesh is [`CollapseSequence::replay`]'s check.
    pub fn read_bytes(path: &Path, bytes: &[u8]) -> Result<CollapseSequence> {
        let fmt = |at: String, what: &str| Error::Format { path: path.to_path_buf(), at, what: what.to_string() };
        let seq = if is_json(path) {
            let seq: CollapseSequence = serde_json::from_slice(bytes).map_err(|e| {
                Error::Format { path: path.to_path_buf(), at: format!("line {}", e.line()), what: e.to_string() }
            })?;
            if seq.removed_offsets.len() != seq.collapses.len() + 1
                || seq.removed_offsets.first() != Some(&0)
                || seq.removed_offsets.windows(2).any(|w| w[0] > w[1])
                || seq.removed_offsets.last().map(|&x| x as usize) != Some(seq.removed_triangles.len())
            {
                return Err(fmt("removed_offsets".into(), "offsets do not match the collapses and removed triangles"));
            }
            seq
        } else {
            Self::decode_binary(bytes, &fmt)?
        };
        seq.check(&fmt)?;
        Ok(seq)
    }

    fn decode_binary(bytes: &[u8], fmt: &dyn Fn(String, &str) -> Error) -> Result<CollapseSequence> {
        let mut at = 0usize;
        let mut take = |n: usize, what: &str| -> Result<&[u8]> {
            let s = at
                .checked_add(n)
                .and_then(|end| bytes.get(at..end))
                .ok_or_else(|| fmt(format!("byte {at}"), &format!("file ends inside {what}")))?;
            at += n;
            Ok(s)
        };
        if take(8, "the header")? != MAGIC {
            return Err(fmt("byte 0".into(), "not a stripkit collapse sequence (bad magic)"));
        }
        let u32_at = |s: &[u8]| u32::from_le_bytes([s[0], s[1], s[2], s[3]]);
        let vertex_count = u32_at(take(4, "the header")?);
        let triangle_count = u32_at(take(4, "the header")?);
        let count = u32_at(take(4, "the header")?);
        let mut seq = CollapseSequence::new(vertex_count, triangle_count);
        for i in 0..count {
            let what = format!("collapse {i} of {count}");
            let r = take(32, &what)?;
            let f = |o: usize| f32::from_le_bytes([r[o], r[o + 1], r[o + 2], r[o + 3]]);
            let mut e = [0u8; 8];
            e.copy_from_slice(&r[20..28]);
            let c = Collapse {
                removed: u32_at(&r[0..4]),
                kept: u32_at(&r[4..8]),
                position: [f(8), f(12), f(16)],
                error: f64::from_le_bytes(e),
            };
            let n = u32_at(&r[28..32]) as usize;
            let ids = take(n.saturating_mul(4), &what)?;
            seq.collapses.push(c);
            seq.removed_triangles.extend(ids.chunks_exact(4).map(u32_at));
            seq.removed_offsets.push(seq.removed_triangles.len() as u32);
        }
        if at != bytes.len() {
            return Err(fmt(
                format!("byte {at}"),
                &format!("{} bytes follow the last of the {count} collapses", bytes.len() - at),
            ));
        }
        Ok(seq)
    }

    /// The per-collapse checks of [`CollapseSequence::read_bytes`].
    fn check(&self, fmt: &dyn Fn(String, &str) -> Error) -> Result<()> {
        if self.collapses.len() >= (self.vertex_count as usize).max(1) {
            return Err(fmt(
                "collapses".into(),
                &format!("{} collapses for {} vertices (each removes one)", self.collapses.len(), self.vertex_count),
            ));
        }
        for (i, c) in self.collapses.iter().enumerate() {
            let what = if c.removed >= self.vertex_count || c.kept >= self.vertex_count {
                format!("merges vertex {} into {}, past the {} vertices", c.removed, c.kept, self.vertex_count)
            } else if c.removed == c.kept {
                format!("merges vertex {} into itself", c.removed)
            } else if !c.position.iter().all(|x| x.is_finite()) || !c.error.is_finite() {
                "has a NaN or infinite position or error".to_string()
            } else if let Some(t) = self.removed_by(i).iter().find(|&&t| t >= self.triangle_count) {
                format!("removes triangle {t}, past the {} triangles", self.triangle_count)
            } else {
                continue;
            };
            return Err(fmt(format!("collapse {i}"), &what));
        }
        Ok(())
    }

    /// The binary encoding described at [`CollapseSequence::read`].
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(20 + self.collapses.len() * 40);
        out.extend_from_slice(MAGIC);
        for x in [self.vertex_count, self.triangle_count, self.collapses.len() as u32] {
            out.extend_from_slice(&x.to_le_bytes());
        }
        for (i, c) in self.collapses.iter().enumerate() {
            out.extend_from_slice(&c.removed.to_le_bytes());
            out.extend_from_slice(&c.kept.to_le_bytes());
            for x in c.position {
                out.extend_from_slice(&x.to_le_bytes());
            }
            out.extend_from_slice(&c.error.to_le_bytes());
            let ids = self.removed_by(i);
            out.extend_from_slice(&(ids.len() as u32).to_le_bytes());
            for t in ids {
                out.extend_from_slice(&t.to_le_bytes());
            }
        }
        out
    }
}

fn is_json(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sequence(error: f64) -> CollapseSequence {
        let mut seq = CollapseSequence::new(4, 2);
        seq.push(Collapse { removed: 3, kept: 1, position: [0.5, -0.0, 1e-7], error }, &[1]);
        seq
    }

    #[test]
    fn write_reads_back_in_both_layouts_and_writes_nothing_it_cannot_read() {
        let dir = stripkit_testkit::scratch_dir("sequence");
        for name in ["s.seq", "s.json"] {
            let path = dir.join(name);
            sequence(0.25).write(&path).unwrap();
            assert_eq!(CollapseSequence::read(&path).unwrap(), sequence(0.25));
            std::fs::remove_file(&path).unwrap();
            // An infinite error would make a file no reader accepts: refused, nothing written.
            assert!(sequence(f64::INFINITY).write(&path).is_err());
            assert!(sequence(f64::INFINITY).encode(&path).is_err());
            assert!(!path.exists());
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

//! Either kind of level-of-detail file, told apart by its first bytes, and one level
//! (and frame) of it with the positions its strips index, written to a mesh file
//! through the checked write path.

use super::file::{LODSEQ_MAGIC, SETS_MAGIC};
use super::seq::LodSeq;
use super::sets::{LevelSpec, Sets};
use crate::error::{Error, Result};
use crate::mesh::io::{self, Format, WriteOptions};
use crate::mesh::{Attribute, Mesh};
use crate::strip::{decode, encode_stitched, verify_triangles, StripSet};
use std::collections::HashMap;
use std::io::Read;
use std::path::Path;

/// A `.sets` model or a `.lodseq` animation.
// `Sets` holds its derived tables' headers inline (about 600 bytes); a program holds a
// model or a few and moves them rarely, so boxing would only add an indirection.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
pub enum Model {
    /// A SETS model ([`Sets`]).
    Sets(Sets),
    /// An animation ([`LodSeq`]).
    Seq(LodSeq),
}

/// One level (and frame) of a [`Model`]: [`Model::extract`].
#[derive(Clone, Debug, PartialEq)]
pub struct Extracted {
    /// Positions the strips index (an animation's frame, morphed for a fraction).
    pub positions: Vec<[f32; 3]>,
    /// The vertex attributes of the same vertices (UVs, normals, ...; an animation's
    /// are its first frame's); empty when the model has none.
    pub attributes: Vec<Attribute>,
    /// The non-empty strips of the level.
    pub strips: StripSet,
    /// The level (collapses applied), of the frame's model for an animation.
    pub level: u32,
    /// The model's last level.
    pub levels: u32,
    /// Triangles at the level, as the model counts them.
    pub triangles: u32,
    /// An animation: the frame asked for and the key frame whose level was taken.
    pub frame: Option<(f64, usize)>,
}

impl Model {
    /// Reads a `.sets` or `.lodseq` file, the kind told by its first 8 bytes (its
    /// magic) and checked as [`Sets::from_bytes`] and [`LodSeq::from_bytes`] check
    /// it. Any other file is an [`Error::Format`] at byte 0 saying so.
    pub fn read(path: impl AsRef<Path>) -> Result<Model> {
        let path = path.as_ref();
        Model::try_read(path)?.ok_or_else(|| Error::Format {
            path: path.to_path_buf(),
            at: "byte 0".into(),
            what: "not a stripkit .sets or .lodseq file (bad magic)".into(),
        })
    }

    /// [`Model::read`] for a caller that takes meshes too: `Ok(None)` for a file
    /// without either magic, of which only the first 8 bytes are read.
    pub fn try_read(path: impl AsRef<Path>) -> Result<Option<Model>> {
        let path = path.as_ref();
        let io = |source| Error::Io { path: path.to_path_buf(), source };
        let mut file = std::fs::File::open(path).map_err(io)?;
        let mut data = Vec::new();
        (&mut file).take(8).read_to_end(&mut data).map_err(io)?;
        if data != SETS_MAGIC && data != LODSEQ_MAGIC {
            return Ok(None);
        }
        file.read_to_end(&mut data).map_err(io)?;
        Ok(Some(if data.starts_with(SETS_MAGIC) {
            Model::Sets(Sets::from_bytes(path, &data)?)
        } else {
            Model::Seq(LodSeq::from_bytes(path, &data)?)
        }))
    }

    /// The strips at `spec`. An animation needs `frame` (0 to frames - 1; a fraction
    /// morphs the positions between the key frames around it, and the level follows
    /// the nearest one); a single model refuses it. [`Error::Invalid`] otherwise.
    pub fn extract(&self, spec: LevelSpec, frame: Option<f64>) -> Result<Extracted> {
        match self {
            Model::Sets(sets) => {
                if frame.is_some() {
                    return Err(Error::Invalid("a frame applies to animations (.lodseq), not to a .sets model".into()));
                }
                let level = sets.level_of(spec);
                Ok(Extracted {
                    positions: sets.positions().to_vec(),
                    attributes: sets.attributes().to_vec(),
                    strips: sets.cursor(level).strips(),
                    level,
                    levels: sets.levels(),
                    triangles: sets.triangles_at(level),
                    frame: None,
                })
            }
            Model::Seq(seq) => {
                let last = seq.frame_count() - 1;
                let Some(t) = frame else {
                    return Err(Error::Invalid(format!(
                        "an animation (.lodseq) needs a frame: 0 to {last} (fractions morph between key frames)"
                    )));
                };
                if !(t.is_finite() && (0.0..=last as f64).contains(&t)) {
                    return Err(Error::Invalid(format!("frame {t} is out of range: 0 to {last}")));
                }
                let key = seq.nearest_frame(t);
                let model = &seq.models()[seq.model_of(key)];
                let level = model.level_of(spec);
                Ok(Extracted {
                    positions: seq.morph(t),
                    attributes: seq.attributes().to_vec(),
                    strips: model.cursor(level).strips(),
                    level,
                    levels: model.levels(),
                    triangles: model.triangles_at(level),
                    frame: Some((t, key)),
                })
            }
        }
    }
}

impl Extracted {
    /// The triangles the strips draw, each with its winding, once their number is the
    /// one the model gives ([`Extracted::triangles`]); [`Error::Verification`]
    /// naming the level otherwise.
    pub fn checked_triangles(&self) -> Result<Vec<[u32; 3]>> {
        let triangles = decode(&self.strips);
        if triangles.len() != self.triangles as usize {
            return Err(Error::Verification(format!(
                "level {}: the strips draw {} triangles, the model says {}",
                self.level,
                triangles.len(),
                self.triangles
            )));
        }
        Ok(triangles)
    }

    /// Writes the level to `path`, in the mesh format its extension names
    /// (gzip-compressed for `.gz`), with only the vertices the level uses, numbered
    /// in the order its strips first name them, each with its attributes (glTF
    /// through [`io::Scene`], every attribute under its glTF semantic): PLY as `tristrips`, one strip per strip; glTF and
    /// GLB as one stitched `TRIANGLE_STRIP` (core glTF has no restart index); OBJ, OFF
    /// and STL as the strips' triangles. Through the library's one checked write
    /// path: the bytes are read back with the library's own reader and must hold
    /// exactly the strips' triangles ([`Extracted::checked_triangles`]), each with
    /// its winding (STL, which keeps no indices, and OBJ with attributes, which numbers
    /// vertices by their corners, by the corners' positions), before
    /// the file is replaced atomically; nothing is written
    /// otherwise ([`Error::Verification`]). [`Error::UnknownFormat`] for an
    /// extension that names no mesh format; [`Error::Invalid`] for a level without
    /// triangles (a coarsest level collapsed to nothing, a model of degenerate faces):
    /// a mesh file of no faces is one no reader takes back, so none is written.
    pub fn write_file(&self, path: impl AsRef<Path>, options: &WriteOptions) -> Result<()> {
        let path = path.as_ref();
        let (format, _) = Format::from_path(path).ok_or_else(|| Error::UnknownFormat {
            path: path.to_path_buf(),
            expected: io::SUPPORTED_EXTENSIONS,
        })?;
        let triangles = self.checked_triangles()?;
        if triangles.is_empty() {
            return Err(Error::Invalid(format!(
                "{}: level {} has no triangles (the model's last level is {}; choose a finer level)",
                path.display(),
                self.level,
                self.levels
            )));
        }
        let mut written = match format {
            Format::Gltf | Format::Glb => encode_stitched(&self.strips),
            _ => Vec::new(),
        };
        let (mesh, strips, triangles) = self.used_vertices(&triangles, &mut written);
        let to_write = match format {
            Format::Ply => Some(strips.clone()),
            Format::Gltf | Format::Glb => Some(StripSet::from_strips(&[written])),
            Format::Obj | Format::Off | Format::Stl => None,
        };
        io::write_checked(
            path,
            || match format {
                // The plain glTF writer holds positions only; a scene of the mesh
                // takes every attribute (under its glTF semantic), the level's strips
                // set on its one primitive, stitched.
                Format::Gltf | Format::Glb if !mesh.attributes.is_empty() => {
                    let mut scene = io::Scene::from_mesh(&mesh)?;
                    if let [primitive] = scene.primitives_mut() {
                        primitive.strips = Some(strips.clone());
                        primitive.drawn = triangles.clone();
                        primitive.order = None;
                    }
                    scene.set_restart_groups(false);
                    scene.to_bytes(format)
                }
                _ => io::write_bytes(format, &mesh, to_write.as_ref(), options),
            },
            |bytes| {
                let name = format!("the {format:?} bytes of {}", path.display());
                let back = io::read_bytes(Path::new(&name), format, bytes)?;
                let back_triangles = back.triangulate().tris;
                let renumbered = format == Format::Stl || (format == Format::Obj && !mesh.attributes.is_empty());
                let v = if renumbered {
                    // STL keeps no indices: its reader welds equal positions; OBJ
                    // with `vt`/`vn` numbers its vertices by the corners that name
                    // them. So the triangles are compared by their corners' positions.
                    let mut ids = HashMap::new();
                    let expected = by_position(&triangles, &mesh.positions, &mut ids);
                    verify_triangles(&expected, &by_position(&back_triangles, &back.positions, &mut ids))
                } else {
                    verify_triangles(&triangles, &back_triangles)
                };
                if !v.ok() {
                    return Err(Error::Verification(format!("{name}, read back: {v}")));
                }
                Ok(())
            },
        )
        .map(drop)
    }

    /// The vertices the level's strips use, renumbered in the order `written` first
    /// names them (the order glTF asks for; `written` is what the file will hold: the
    /// strips, or their stitched strip, which may read a strip from its end), with their
    /// positions and attributes, as a mesh of `triangles`; and the strips and
    /// `triangles` renumbered the same way (`written` too, in place).
    pub(crate) fn used_vertices(&self, triangles: &[[u32; 3]], written: &mut [u32]) -> (Mesh, StripSet, Vec<[u32; 3]>) {
        let mut new_id = vec![u32::MAX; self.positions.len()];
        let mut order = Vec::new();
        // Then the strips' own order, for vertices `written` leaves out (strips too
        // short to draw).
        for &v in written.iter().chain(&self.strips.indices) {
            if new_id[v as usize] == u32::MAX {
                new_id[v as usize] = order.len() as u32;
                order.push(v);
            }
        }
        let renamed: Vec<[u32; 3]> = triangles.iter().map(|t| t.map(|v| new_id[v as usize])).collect();
        let mut mesh = Mesh::from_triangles(order.iter().map(|&v| self.positions[v as usize]).collect(), &renamed);
        mesh.attributes = self.attributes.iter().map(|a| a.gather(&order)).collect();
        let mut strips = self.strips.clone();
        strips.indices.iter_mut().chain(written.iter_mut()).for_each(|v| *v = new_id[*v as usize]);
        (mesh, strips, renamed)
    }

    /// The level as JSON, once its strips are checked
    /// ([`Extracted::checked_triangles`]): `level`, `frame` (the frame asked for, or
    /// null), `restart_index` (`u32::MAX`) and `strips` (an array of index arrays).
    pub fn to_json(&self) -> Result<serde_json::Value> {
        self.checked_triangles()?;
        Ok(serde_json::json!({
            "level": self.level,
            "frame": self.frame.map(|(t, _)| t),
            "restart_index": u32::MAX,
            "strips": self.strips.iter().collect::<Vec<_>>(),
        }))
    }
}

/// `triangles` over `positions` renamed by position: every corner gets the id of its
/// position's bits in `ids` (`-0.0` as `0.0`, as the STL reader welds), a new one
/// when first met.
fn by_position(triangles: &[[u32; 3]], positions: &[[f32; 3]], ids: &mut HashMap<[u32; 3], u32>) -> Vec<[u32; 3]> {
    triangles
        .iter()
        .map(|t| {
            t.map(|v| {
                let key = positions[v as usize].map(|c| (c + 0.0).to_bits());
                let next = ids.len() as u32;
                *ids.entry(key).or_insert(next)
            })
        })
        .collect()
}

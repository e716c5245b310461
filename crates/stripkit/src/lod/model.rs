//! Either kind of level-of-detail file, told apart by its first bytes, and one level
//! (and frame) of it with the positions its strips index.

use super::file::{LODSEQ_MAGIC, SETS_MAGIC};
use super::seq::LodSeq;
use super::sets::{LevelSpec, Sets};
use crate::error::{Error, Result};
use crate::strip::StripSet;
use std::io::Read;
use std::path::Path;

/// A `.sets` model or a `.lodseq` animation.
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
    /// Reads `path` when it starts with the magic of a `.sets` or a `.lodseq` file
    /// (checked as [`Sets::from_bytes`] and [`LodSeq::from_bytes`] check them);
    /// `Ok(None)` for any other file, of which only the first 8 bytes are read.
    pub fn read(path: &Path) -> Result<Option<Model>> {
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

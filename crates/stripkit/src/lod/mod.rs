//! Level-of-detail strips.
//!
//! [`Sets`] is the SETS model (Belmonte et al., *Triangle strip multiresolution
//! modelling using sorted edges*, 2006): one set of strips from any stripifier plus a
//! collapse sequence from [`crate::simplify`], stored so that the strips of every
//! level (level `L` = the first `L` collapses applied) are recovered by binary searches
//! over data sorted by level. Every level's strips decode to exactly the triangles of
//! [`crate::simplify::CollapseSequence::replay`] at that level, each with its winding,
//! so back-face culling works at every level.
//!
//! * [`build`] runs the door, the simplifier and [`Sets::build`] on a mesh.
//! * [`Cursor`] recovers a level, re-walking only the strips whose sequence changed
//!   since the last level it recovered (coherence), into a buffer where every strip
//!   keeps a fixed range (a renderer re-uploads just the changed ranges).
//! * [`Sets::to_bytes`] / [`Sets::from_bytes`]: the `.sets` file (docs/sets-format.md),
//!   read as untrusted input.
//! * [`check_levels`] proves a model against an independent replay of the collapses,
//!   level by level.
//! * Deforming meshes ([`read_frames`], [`build_seq`], [`LodSeq`], [`SeqCursor`]):
//!   one strip connectivity for every frame of an animation, a few shared
//!   sequences chosen by measuring them on every frame, any (frame, level)
//!   recovered, positions morphed between key frames.
//! * [`timing`]: the paper's recovery tests and the animation's extraction timings (a
//!   bench API, what `stripkit lod bench` prints).

mod build;
mod check;
mod cursor;
mod file;
mod model;
mod seq;
mod sets;
mod snap;
pub mod timing;
mod track;

pub use build::{build, BuildOptions, BuildReport, Built, DEFAULT_RESTRIP};
pub use check::{check_levels, check_levels_with, LevelCheck};
pub use cursor::Cursor;
pub use file::{LODSEQ_MAGIC, SETS_MAGIC};
pub use model::{Extracted, Model};
pub use seq::{
    build_seq, read_frames, BuiltSeq, FrameQuality, Frames, LodSeq, Quality, SeqCursor, SeqOptions,
    SeqReport, QUALITY_RATIOS,
};
pub use sets::{LevelSpec, Sets, END, RESTRIP_MARGIN};

#[cfg(test)]
mod tests;

//! `stripkit strip`: read a mesh, turn it into triangle strips, check them, print their
//! figures and write them out.
//!
//! Every run verifies what it writes: the encoded buffer (after the chosen join) is
//! decoded again and, for PLY and glTF, the written bytes are read back, and the
//! triangles must equal the input's (nothing lost, nothing added, no winding flipped).
//! A failed check writes nothing and exits with status 1.
//!
//! The work is the library's front door ([`stripkit::stripify`]): `args.rs` maps flags
//! to [`stripkit::StripOptions`], `run.rs` calls the door and writes what it returns,
//! `report.rs` prints its figures. A new stripifier needs no change here beyond the
//! flags of its own settings: `--algo` takes the library's names.

mod args;
mod report;
mod run;

pub use args::{heuristic_of, Args, StripArgs, VertexOrder};
pub use run::run;

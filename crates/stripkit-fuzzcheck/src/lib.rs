//! The bodies of the fuzz targets `scene` and `options` (see `fuzz/README.md`),
//! shared by the fuzz crate and this crate's stable replay test, which runs every file
//! under `fuzz/regressions/<target>/` through the same check as its target.
//!
//! Each check panics on a finding: a panic inside the library, an error other than a
//! bad input (exit status 2 in the CLI), or a broken promise (a written scene that does
//! not read back, a size accepted beyond its limit).

pub mod options;
pub mod scene;
pub mod seeds;

/// The checks by target name, for the replay: `fuzz/regressions/<name>/` holds inputs
/// of the target `name`.
pub const TARGETS: &[(&str, fn(&[u8]))] = &[("scene", scene::check), ("options", options::check)];

/// True for an error the CLI reports as a bad input (exit status 2): an invalid input
/// or option, a malformed file, or an unreadable external buffer.
pub fn is_bad_input(e: &stripkit::Error) -> bool {
    use stripkit::Error as E;
    matches!(
        e,
        E::Invalid(_)
            | E::BadOption { .. }
            | E::Format { .. }
            | E::UnknownFormat { .. }
            | E::Io { .. }
    )
}

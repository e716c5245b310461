//! The crate's error type: bad input (with the file and line for graph files) or a
//! failed certificate check.

use std::path::PathBuf;

/// Everything that can go wrong in stripkit-matching.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The operating system refused to read a graph file.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What the system said.
        #[source]
        source: std::io::Error,
    },
    /// A graph file's content is malformed: `at` names the line.
    #[error("{path}: {at}: {what}")]
    Format {
        /// The file.
        path: PathBuf,
        /// Where in the file, e.g. "line 12" or "end of file".
        at: String,
        /// What is wrong, e.g. "vertex 9 out of range: vertices are 1..=8".
        what: String,
    },
    /// An input the operation cannot take (edge out of range, weight too large, ...).
    #[error("{0}")]
    Invalid(String),
    /// A certificate check failed: the matching is not proven optimal (a solver bug,
    /// or a wrong certificate given to [`check_certificate`](crate::check_certificate)).
    #[error("verification failed: {0}")]
    Verification(String),
}

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

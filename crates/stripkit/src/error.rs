//! The library's error type: every failure names the file, the place in it and what
//! is wrong, so that a user can fix the input without reading our code.

use std::path::PathBuf;

/// Everything that can go wrong in stripkit.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The operating system refused to read or write a file.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What the system said.
        #[source]
        source: std::io::Error,
    },
    /// A file's content is malformed: `at` names the line, element or byte offset.
    #[error("{path}: {at}: {what}")]
    Format {
        /// The file.
        path: PathBuf,
        /// Where in the file, e.g. "line 12" or "face 1022".
        at: String,
        /// What is wrong, e.g. "face refers to vertex 40000 but the file has 35947 vertices".
        what: String,
    },
    /// A file name whose extension names no format we know.
    #[error("{path}: unknown mesh format (expected one of {expected})")]
    UnknownFormat {
        /// The file.
        path: PathBuf,
        /// The supported extensions.
        expected: &'static str,
    },
    /// An argument or input that the operation cannot take.
    #[error("{0}")]
    Invalid(String),
    /// An output failed its independent check; never written silently.
    #[error("verification failed: {0}")]
    Verification(String),
    /// An error of the matching solver (bad graph input, graph file errors, or a
    /// failed certificate check); its message is passed through unchanged.
    #[error(transparent)]
    Matching(#[from] stripkit_matching::Error),
}

impl Error {
    /// True for a failed independent check of an output ([`Error::Verification`], or
    /// the matching's own [`stripkit_matching::Error::Verification`]).
    pub fn is_verification(&self) -> bool {
        matches!(self, Error::Verification(_) | Error::Matching(stripkit_matching::Error::Verification(_)))
    }
}

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::Error;

    #[test]
    fn matching_errors_convert_with_their_message_and_kind() {
        let e: Error = stripkit_matching::Error::Verification("dual bound 4, primal 6".into()).into();
        assert_eq!(e.to_string(), "verification failed: dual bound 4, primal 6");
        assert!(e.is_verification());
        let e: Error = stripkit_matching::Error::Invalid("edge 3 joins 0 and 9".into()).into();
        assert_eq!(e.to_string(), "edge 3 joins 0 and 9");
        assert!(!e.is_verification());
        assert!(Error::Verification("x".into()).is_verification());
    }
}

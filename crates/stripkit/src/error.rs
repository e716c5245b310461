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
    /// An option that does not apply, or a value it cannot take: `option` names it, so
    /// that a front end can name its own spelling (a flag) before `message`. Displayed
    /// as the option's own words ([`OptionName::phrase`]), a space, then `message`.
    #[error("{} {message}", option.phrase())]
    BadOption {
        /// The offending option.
        option: OptionName,
        /// What is wrong, to follow the option's name: e.g. "70000 is too large (at
        /// most 65536 entries)" after "the cache size".
        message: String,
    },
    /// An output failed its independent check; never written silently.
    #[error("verification failed: {0}")]
    Verification(String),
    /// An error of the matching solver (bad graph input, graph file errors, or a
    /// failed certificate check); its message is passed through unchanged.
    #[error(transparent)]
    Matching(#[from] stripkit_matching::Error),
}

/// The options [`Error::BadOption`] can name: the settings of
/// [`StripOptions`](crate::StripOptions) and of the algorithms it holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum OptionName {
    /// [`StripOptions::cache`](crate::StripOptions::cache)'s size.
    CacheSize,
    /// The bound of [`Algorithm::Balanced`](crate::Algorithm::Balanced).
    MaxAcmr,
    /// [`GreedyOptions::tunnel_cuts`](crate::GreedyOptions::tunnel_cuts).
    TunnelCuts,
    /// [`StripOptions::split`](crate::StripOptions::split).
    Split,
    /// [`StripOptions::join`](crate::StripOptions::join).
    Join,
    /// [`StripOptions::restart_index`](crate::StripOptions::restart_index).
    RestartIndex,
    /// The model of [`Algorithm::Batch`](crate::Algorithm::Batch).
    BatchModel,
    /// [`QuadOptions::policies`](crate::QuadOptions::policies).
    QuadPolicies,
    /// [`SingleOptions::weights`](crate::SingleOptions::weights).
    Weights,
    /// [`SingleOptions::swap_angle`](crate::SingleOptions::swap_angle).
    SwapAngle,
    /// [`SingleOptions::cull_angle`](crate::SingleOptions::cull_angle).
    CullAngle,
}

impl OptionName {
    /// The option in the library's words, as [`Error::BadOption`] prints it.
    pub fn phrase(self) -> &'static str {
        match self {
            OptionName::CacheSize => "the cache size",
            OptionName::MaxAcmr => "balanced's bound max_acmr",
            OptionName::TunnelCuts => "greedy's tunnel_cuts",
            OptionName::Split => "split",
            OptionName::Join => "join",
            OptionName::RestartIndex => "restart index",
            OptionName::BatchModel => "the batch model",
            OptionName::QuadPolicies => "qstrip's policies",
            OptionName::Weights => "weights",
            OptionName::SwapAngle => "swap angle",
            OptionName::CullAngle => "cull angle",
        }
    }
}

impl Error {
    /// An [`Error::BadOption`].
    pub(crate) fn option(option: OptionName, message: impl Into<String>) -> Error {
        Error::BadOption { option, message: message.into() }
    }

    /// True for an input or argument the operation cannot take ([`Error::Invalid`] or
    /// [`Error::BadOption`]).
    pub fn is_invalid(&self) -> bool {
        matches!(self, Error::Invalid(_) | Error::BadOption { .. })
    }

    /// True for a failed independent check of an output ([`Error::Verification`], or
    /// the matching's own [`stripkit_matching::Error::Verification`]).
    pub fn is_verification(&self) -> bool {
        matches!(self, Error::Verification(_) | Error::Matching(stripkit_matching::Error::Verification(_)))
    }
}

/// The error of parsing a name that is not one of `names`.
pub(crate) fn unknown(what: &str, s: &str, names: &[&str]) -> Error {
    Error::Invalid(format!("unknown {what} `{s}` (expected one of {})", names.join(", ")))
}

/// Implements `name`, `NAMES` and `FromStr` for a field-less enum from one table.
macro_rules! named_enum {
    ($ty:ident, $what:literal, $($variant:ident => $name:literal),+ $(,)?) => {
        impl $ty {
            /// Every value's name, in the order of the variants.
            pub const NAMES: &'static [&'static str] = &[$($name),+];
            /// The lowercase name of this value (one of the `NAMES`).
            pub fn name(self) -> &'static str {
                match self {
                    $($ty::$variant => $name),+
                }
            }
        }
        impl std::str::FromStr for $ty {
            type Err = $crate::error::Error;
            /// The value of this name (one of the `NAMES`).
            fn from_str(s: &str) -> $crate::error::Result<Self> {
                match s {
                    $($name => Ok($ty::$variant),)+
                    _ => Err($crate::error::unknown($what, s, $ty::NAMES)),
                }
            }
        }
    };
}
pub(crate) use named_enum;

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

    #[test]
    fn bad_options_print_the_option_then_the_message() {
        let e = Error::option(super::OptionName::CacheSize, "must be at least 1");
        assert_eq!(e.to_string(), "the cache size must be at least 1");
        assert!(e.is_invalid() && !e.is_verification());
    }
}

//! One module per subcommand; each has an `Args` (clap) and a `run`.

pub mod distance;
pub mod gen;
pub mod matching;
pub mod simplify;
pub mod stats;
pub mod strip;

use std::process::ExitCode;

/// Exit status for an error: 1 for a failed verification, 2 for bad input.
pub fn exit_code(err: &anyhow::Error) -> ExitCode {
    for cause in err.chain() {
        // The matching solver's errors come either as they are or wrapped in stripkit's.
        let failed_check = cause.downcast_ref::<stripkit::Error>().is_some_and(stripkit::Error::is_verification)
            || matches!(
                cause.downcast_ref::<stripkit::matching::Error>(),
                Some(stripkit::matching::Error::Verification(_))
            );
        if failed_check {
            return ExitCode::from(1);
        }
    }
    ExitCode::from(2)
}

/// The error and its causes on one line, skipping a cause whose text the message
/// already holds (library errors often print their source themselves).
pub fn describe(err: &anyhow::Error) -> String {
    let mut message = String::new();
    for cause in err.chain() {
        let text = cause.to_string();
        if message.contains(&text) {
            continue;
        }
        if !message.is_empty() {
            message.push_str(": ");
        }
        message.push_str(&text);
    }
    message
}

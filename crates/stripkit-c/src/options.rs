//! `stripkit_options`: the C side's [`StripOptions`], with a size field so that it can grow.

use crate::boundary::{Failure, Outcome, Status};
use libstripkit::{Algorithm, Join, StripOptions};

/// The header's `stripkit_options`. Field meanings are documented there.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct stripkit_options {
    /// `sizeof(stripkit_options)` of the header the caller was built with.
    pub size: u32,
    /// `stripkit_algorithm`: an index into [`Algorithm::NAMES`].
    pub algorithm: u32,
    /// FIFO entries the cache-aware algorithms tune for.
    pub cache_size: u32,
    /// `stripkit_join`: 0 restart, 1 degenerate.
    pub join: u32,
    /// Restart index of the mesh-level entry (the index-level ones take it as an argument).
    pub restart_index: u32,
    /// Weld bit-identical positions (mesh-level entry only): 0 or 1.
    pub weld: u32,
    /// The bound of `balanced`, misses per triangle.
    pub max_acmr: f64,
}

/// The defaults of [`StripOptions::default`], with `size` set.
#[no_mangle]
pub extern "C" fn stripkit_options_default() -> stripkit_options {
    let d = StripOptions::default();
    stripkit_options {
        size: std::mem::size_of::<stripkit_options>() as u32,
        algorithm: 0,
        cache_size: d.cache.size as u32,
        join: 0,
        restart_index: d.restart_index,
        weld: d.weld as u32,
        max_acmr: Algorithm::DEFAULT_MAX_ACMR,
    }
}

/// The library's options for a C caller's (null: the defaults).
///
/// # Safety
/// A non-null `options` must point to a readable `stripkit_options` of the size it states.
pub(crate) unsafe fn read(options: *const stripkit_options) -> Outcome<StripOptions> {
    let c = if options.is_null() { stripkit_options_default() } else { unsafe { *options } };
    let size = std::mem::size_of::<stripkit_options>() as u32;
    if c.size != size {
        return Err(Failure::new(
            Status::BadOption,
            format!(
                "options.size is {} but this library's stripkit_options has {size} bytes: \
                 initialise options with stripkit_options_default() and build against this library's header",
                c.size
            ),
        ));
    }
    let name = Algorithm::NAMES.get(c.algorithm as usize).ok_or_else(|| {
        Failure::new(
            Status::BadOption,
            format!("algorithm {} is unknown: 0 to {} ({})", c.algorithm, Algorithm::NAMES.len() - 1, Algorithm::NAMES.join(", ")),
        )
    })?;
    let algorithm = match *name {
        "balanced" => Algorithm::balanced(c.max_acmr),
        other => other.parse::<Algorithm>()?,
    };
    let join = match c.join {
        0 => Join::Restart,
        1 => Join::Degenerate,
        other => {
            return Err(Failure::new(
                Status::BadOption,
                format!("join {other} is unknown: 0 (restart) or 1 (degenerate)"),
            ))
        }
    };
    if c.weld > 1 {
        return Err(Failure::new(Status::BadOption, format!("weld is {}: 0 or 1", c.weld)));
    }
    Ok(StripOptions::default()
        .algorithm(algorithm)
        .cache_size(c.cache_size as usize)
        .join(join)
        .restart_index(c.restart_index)
        .weld(c.weld == 1))
}

//! Improving strips after they are built: local searches over *walks* (strips as
//! paths through the [`crate::topology::DualGraph`]) that relink them where that saves
//! indices, keeping every triangle's winding.
//!
//! * [`tunnel`]: Stewart's tunnelling scored by indices alone, the post-pass of the
//!   greedy stripifier.
//! * `refine`: joins, chains, tunnels and flips scored by indices and the exact FIFO
//!   misses, the post-pass of the cache-aware stripifier (`cache --refine`, `balanced`).

mod flips;
mod moves;
mod refine;
mod slots;
pub mod tunnel;
mod tunnels;

pub(crate) use refine::{refine, Effort};

//! Improving strips after they are built: local searches over *walks* (strips as
//! paths through the [`crate::topology::DualGraph`]) that relink them where that saves
//! indices, keeping every triangle's winding.
//!
//! * [`tunnel`]: Stewart's tunnelling scored by indices alone, the post-pass of the
//!   greedy stripifier ([`crate::stripify::greedy`]).
//! * `refine`: a local search scored by indices and the exact FIFO misses, the
//!   post-pass of the cache-aware stripifier ([`crate::stripify::cache`]: `cache
//!   --refine`, `balanced`). Its pieces, each importing only those before it:
//!   `piece.rs` (the sizes of a move, the empty marker and a part of an old walk),
//!   `slots.rs` (the walks in output order and the per-triangle index the generators
//!   read), `moves.rs` (a move: new walks for a few slots; the simple moves:
//!   reversals, joins, chains), `tunnels.rs` (alternating paths through distinct
//!   strips), `flips.rs` (alternating cycles and paths that come back through a
//!   strip), and `refine.rs` (each move replayed on the FIFO from a snapshot, the best
//!   one taken, strip by strip, pass by pass).

mod flips;
mod moves;
mod piece;
mod refine;
mod slots;
pub mod tunnel;
mod tunnels;

pub(crate) use refine::{refine, Effort};

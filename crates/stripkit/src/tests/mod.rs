//! Tests of the stripifiers' internals: custom tuning knobs, raw triangle lists, the
//! dual graph, the quad checker. What a user gets is tested through the front door
//! (`stripkit::stripify`) in `tests/`.

mod cache;
mod dual_graph;
mod quad;
mod quad_single;
mod strip_hashes;
mod support;

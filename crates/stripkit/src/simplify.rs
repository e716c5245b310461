//! Quadric-error-metric edge collapse that records its collapse sequence.
//! (Filled in by the simplification work.)

//! Surface-to-surface distances (Hausdorff, RMS) by sampling and a BVH.
//! (Filled in by the simplification work.)

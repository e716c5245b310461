//! Procedural and derived meshes: grids, icospheres, tori, Loop and Catmull-Clark
//! subdivision.
//! (Filled in by the foundation work.)

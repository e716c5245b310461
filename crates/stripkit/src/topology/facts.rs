//! Facts about a mesh's topology: what `stripkit stats` prints.
//! (Filled in by the foundation work: boundary loops, pinch vertices, components...)

//! Mesh files in and out, chosen by extension: OBJ, PLY, OFF, STL, glTF (`.gltf`,
//! `.glb`); a trailing `.gz` is decompressed transparently.
//! (Filled in by the foundation work.)

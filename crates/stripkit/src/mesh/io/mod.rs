//! Mesh files in and out, chosen by extension: OBJ, PLY, OFF, STL, glTF (`.gltf`,
//! `.glb`); a trailing `.gz` is decompressed transparently.

use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::strip::StripSet;
use std::path::Path;

/// Reads a mesh, choosing the format by the file's extension.
pub fn read(path: &Path) -> Result<Mesh> {
    Err(Error::UnknownFormat { path: path.to_path_buf(), expected: "(readers not built yet)" })
}

/// Writes a mesh, choosing the format by extension. With `strips`, formats that can
/// hold strips (PLY `tristrips`, glTF `TRIANGLE_STRIP`) write them instead of faces.
pub fn write(path: &Path, mesh: &Mesh, strips: Option<&StripSet>) -> Result<()> {
    let _ = (mesh, strips);
    Err(Error::UnknownFormat { path: path.to_path_buf(), expected: "(writers not built yet)" })
}

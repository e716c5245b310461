//! STL (stub).
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use std::path::Path;
pub(crate) fn read(path: &Path, _data: &[u8]) -> Result<Mesh> {
    Err(Error::UnknownFormat { path: path.to_path_buf(), expected: "(STL reader not built yet)" })
}
pub(crate) fn write(_mesh: &Mesh) -> Result<Vec<u8>> {
    Err(Error::Invalid("STL writer not built yet".into()))
}

//! glTF (stub).
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::strip::StripSet;
use std::path::Path;
pub(crate) fn read_gltf(path: &Path, _data: &[u8]) -> Result<Mesh> {
    Err(Error::UnknownFormat { path: path.to_path_buf(), expected: "(glTF reader not built yet)" })
}
pub(crate) fn read_glb(path: &Path, _data: &[u8]) -> Result<Mesh> {
    Err(Error::UnknownFormat { path: path.to_path_buf(), expected: "(glTF reader not built yet)" })
}
pub(crate) fn write_gltf(_mesh: &Mesh, _strips: Option<&StripSet>) -> Result<Vec<u8>> {
    Err(Error::Invalid("glTF writer not built yet".into()))
}
pub(crate) fn write_glb(_mesh: &Mesh, _strips: Option<&StripSet>) -> Result<Vec<u8>> {
    Err(Error::Invalid("glTF writer not built yet".into()))
}

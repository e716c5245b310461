//! PLY (stub).
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::strip::StripSet;
use std::path::Path;
pub(crate) fn read(path: &Path, _data: &[u8]) -> Result<Mesh> {
    Err(Error::UnknownFormat { path: path.to_path_buf(), expected: "(PLY reader not built yet)" })
}
pub(crate) fn write(_mesh: &Mesh, _strips: Option<&StripSet>, _ascii: bool) -> Result<Vec<u8>> {
    Err(Error::Invalid("PLY writer not built yet".into()))
}

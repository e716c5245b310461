//! Mesh files in and out, chosen by extension: OBJ, PLY, OFF, STL, glTF (`.gltf`,
//! `.glb`); a trailing `.gz` is decompressed (or compressed) transparently.
//!
//! Every reader takes the whole file into memory and parses bytes; malformed input
//! gives [`Error::Format`] naming the file, the line (text) or element / byte offset
//! (binary) and what is wrong. Counts announced in headers are checked against the
//! file's size before anything is allocated from them. Vertex ids are the file's:
//! unreferenced vertices are kept (STL, which has no shared vertices, welds identical
//! positions in first-seen order).
//!
//! | format | read | write |
//! |---|---|---|
//! | OBJ | `v`, `f` (all `v/vt/vn` forms, negative indices), polygons kept | `v`, `f` |
//! | PLY | ASCII, binary LE/BE; `face` lists or `tristrips` | ASCII or binary LE; faces or `tristrips` |
//! | OFF | `[ST][C][N][4]OFF`, comments, face colours | `OFF` |
//! | STL | ASCII and binary, identical positions welded | binary, polygons fanned |
//! | glTF | `.gltf` (data URIs, external files), `.glb`; modes 4/5/6 | `.gltf` (embedded), `.glb`; TRIANGLES or one TRIANGLE_STRIP per strip |

mod common;
mod gltf;
mod obj;
mod off;
mod ply;
mod stl;

use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::strip::StripSet;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

/// The extensions [`read`] and [`write()`] understand, as shown in error messages.
pub const SUPPORTED_EXTENSIONS: &str =
    ".obj, .ply, .off, .stl, .gltf, .glb (each optionally followed by .gz)";

/// The extensions [`read`] understands, for help texts and error messages.
pub fn supported_read_extensions() -> &'static str {
    SUPPORTED_EXTENSIONS
}

/// The extensions [`write()`] understands, for help texts and error messages.
pub fn supported_write_extensions() -> &'static str {
    SUPPORTED_EXTENSIONS
}

/// Options for [`write_with`].
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct WriteOptions {
    /// Write PLY as ASCII text instead of binary little-endian (the default).
    pub ply_ascii: bool,
}

/// The default of [`ReadOptions::max_external_bytes`]: 1 GiB.
pub const DEFAULT_MAX_EXTERNAL_BYTES: u64 = 1 << 30;

/// Options for [`read_with`] and [`read_bytes_with`]: where a `.gltf` may load its
/// external buffers from, and how much it may load.
///
/// A `.gltf` buffer's `uri` is accepted only when it is a base64 `data:` URI, or a
/// relative reference (no scheme, not absolute; `%XX` escapes decoded first) that,
/// after removing `.` and `..` segments and then resolving symbolic links, names a
/// regular file inside the asset's own folder or inside one of
/// [`allowed_roots`](Self::allowed_roots). Anything else is refused with the same
/// message whether or not the file exists, so a hostile asset learns nothing about
/// files outside those folders. Directories, devices and pipes are refused without
/// being opened for reading; at most the buffer's declared `byteLength` is read, and a
/// file shorter than that is refused. A file named by several buffers is read once.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReadOptions {
    /// Folders besides the asset's own from which external glTF buffers may be read
    /// (reached through relative URIs such as `../shared/scene.bin`). Each is resolved
    /// (symbolic links followed) when a `.gltf` with external buffers is read; a root
    /// that cannot be resolved is an [`Error::Io`]. Empty by default: only the asset's
    /// own folder (and its subfolders).
    pub allowed_roots: Vec<PathBuf>,
    /// The most bytes read from external glTF buffer files for one asset, counting a
    /// file named by several buffers once; a buffer whose `byteLength` alone exceeds
    /// it is refused before anything is read or allocated. Default
    /// [`DEFAULT_MAX_EXTERNAL_BYTES`] (1 GiB). `data:` URIs and the GLB binary chunk
    /// are part of the input and do not count.
    pub max_external_bytes: u64,
}

impl Default for ReadOptions {
    fn default() -> Self {
        ReadOptions { allowed_roots: Vec::new(), max_external_bytes: DEFAULT_MAX_EXTERNAL_BYTES }
    }
}

/// A mesh file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Wavefront OBJ.
    Obj,
    /// Stanford PLY.
    Ply,
    /// Object File Format.
    Off,
    /// Stereolithography, ASCII or binary.
    Stl,
    /// glTF 2.0 JSON.
    Gltf,
    /// glTF 2.0 binary container.
    Glb,
}

impl Format {
    /// The format named by a file's extension (case-insensitive), and whether the
    /// name ends in `.gz`; `None` for an extension we do not know.
    pub fn from_path(path: &Path) -> Option<(Format, bool)> {
        let name = path.file_name()?.to_str()?.to_ascii_lowercase();
        let (name, gz) = match name.strip_suffix(".gz") {
            Some(inner) => (inner.to_string(), true),
            None => (name, false),
        };
        let ext = name.rsplit_once('.')?.1;
        let format = match ext {
            "obj" => Format::Obj,
            "ply" => Format::Ply,
            "off" => Format::Off,
            "stl" => Format::Stl,
            "gltf" => Format::Gltf,
            "glb" => Format::Glb,
            _ => return None,
        };
        Some((format, gz))
    }
}

fn unknown(path: &Path) -> Error {
    Error::UnknownFormat { path: path.to_path_buf(), expected: SUPPORTED_EXTENSIONS }
}

fn io_error(path: &Path, source: std::io::Error) -> Error {
    Error::Io { path: path.to_path_buf(), source }
}

/// Reads a mesh, choosing the format by the file's extension, with the default
/// [`ReadOptions`] (external glTF buffers only from the asset's own folder).
pub fn read(path: &Path) -> Result<Mesh> {
    read_with(path, &ReadOptions::default())
}

/// [`read`] with options (see [`ReadOptions`] for the rules on external glTF buffers).
pub fn read_with(path: &Path, options: &ReadOptions) -> Result<Mesh> {
    let (format, gz) = Format::from_path(path).ok_or_else(|| unknown(path))?;
    let raw = std::fs::read(path).map_err(|e| io_error(path, e))?;
    let data = if gz { gunzip(path, &raw)? } else { raw };
    read_bytes_with(path, format, &data, options)
}

/// [`read_bytes`] with options: external glTF buffers follow `options` (see
/// [`ReadOptions`]); other formats read exactly as [`read_bytes`] does.
pub fn read_bytes_with(path: &Path, format: Format, data: &[u8], options: &ReadOptions) -> Result<Mesh> {
    match format {
        Format::Gltf => gltf::read_gltf(path, data.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(data), options),
        Format::Glb => gltf::read_glb(path, data, options),
        _ => read_bytes(path, format, data),
    }
}

/// Parses a mesh already in memory (uncompressed) as `format`; `path` names the file
/// in errors and locates external glTF buffers (with the default [`ReadOptions`]; see
/// [`read_bytes_with`]).
pub fn read_bytes(path: &Path, format: Format, data: &[u8]) -> Result<Mesh> {
    // A UTF-8 byte order mark before a text format would hide its first keyword.
    let data = match format {
        Format::Obj | Format::Off | Format::Ply | Format::Gltf => data.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(data),
        Format::Stl | Format::Glb => data,
    };
    match format {
        Format::Obj => obj::read(path, data),
        Format::Ply => ply::read(path, data),
        Format::Off => off::read(path, data),
        Format::Stl => stl::read(path, data),
        Format::Gltf => gltf::read_gltf(path, data, &ReadOptions::default()),
        Format::Glb => gltf::read_glb(path, data, &ReadOptions::default()),
    }
}

fn gunzip(path: &Path, raw: &[u8]) -> Result<Vec<u8>> {
    let mut out = Vec::with_capacity(raw.len().saturating_mul(3));
    flate2::read::MultiGzDecoder::new(raw).read_to_end(&mut out).map_err(|e| Error::Format {
        path: path.to_path_buf(),
        at: format!("gzip stream (after {} decompressed bytes)", out.len()),
        what: format!("cannot decompress: {e}"),
    })?;
    Ok(out)
}

/// Writes a mesh, choosing the format by extension. With `strips`, formats that can
/// hold strips (PLY `tristrips`, glTF `TRIANGLE_STRIP`) write them instead of faces;
/// OBJ, OFF and STL always write the mesh's faces. PLY is binary little-endian; see
/// [`write_with`] for ASCII.
pub fn write(path: &Path, mesh: &Mesh, strips: Option<&StripSet>) -> Result<()> {
    write_with(path, mesh, strips, &WriteOptions::default())
}

/// [`write()`] with options. The mesh is checked first: [`Error::Invalid`] when a face or
/// strip index is out of range or a coordinate is NaN or infinite (no reader would
/// accept the file). A name ending in `.gz` is gzip-compressed.
pub fn write_with(
    path: &Path,
    mesh: &Mesh,
    strips: Option<&StripSet>,
    options: &WriteOptions,
) -> Result<()> {
    let (format, _) = Format::from_path(path).ok_or_else(|| unknown(path))?;
    let bytes = write_bytes(format, mesh, strips, options)?;
    write_encoded(path, &bytes)
}

/// Writes bytes already encoded in the format `path` names (e.g. by
/// [`write_bytes`] or [`crate::Strips::to_file_bytes`]), gzip-compressed when the name
/// ends in `.gz`.
pub fn write_encoded(path: &Path, bytes: &[u8]) -> Result<()> {
    let gz = Format::from_path(path).is_some_and(|(_, gz)| gz);
    if gz {
        let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
        let packed = enc.write_all(bytes).and_then(|_| enc.finish()).map_err(|e| io_error(path, e))?;
        std::fs::write(path, packed).map_err(|e| io_error(path, e))
    } else {
        std::fs::write(path, bytes).map_err(|e| io_error(path, e))
    }
}

/// Encodes a mesh (or its strips) in `format` into memory. glTF output is
/// self-contained (its buffer embedded as a data URI).
pub fn write_bytes(
    format: Format,
    mesh: &Mesh,
    strips: Option<&StripSet>,
    options: &WriteOptions,
) -> Result<Vec<u8>> {
    check_indices(mesh, strips)?;
    match format {
        Format::Obj => Ok(obj::write(mesh)),
        Format::Ply => ply::write(mesh, strips, options.ply_ascii),
        Format::Off => Ok(off::write(mesh)),
        Format::Stl => stl::write(mesh),
        Format::Gltf => gltf::write_gltf(mesh, strips),
        Format::Glb => gltf::write_glb(mesh, strips),
    }
}

fn check_indices(mesh: &Mesh, strips: Option<&StripSet>) -> Result<()> {
    let n = mesh.positions.len();
    if n > u32::MAX as usize {
        return Err(Error::Invalid(format!("{n} vertices do not fit 32-bit indices")));
    }
    if mesh.face_offsets.first().is_some_and(|&o| o != 0)
        || mesh.face_offsets.last().is_some_and(|&o| o as usize != mesh.face_indices.len())
        || mesh.face_offsets.windows(2).any(|w| w[1].saturating_sub(w[0]) < 3)
    {
        return Err(Error::Invalid("mesh faces are malformed (offsets, or a face with fewer than 3 vertices)".into()));
    }
    if let Some(v) = mesh.positions.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        // Every reader refuses these, so writing them would make a file we cannot read.
        return Err(Error::Invalid(format!("vertex {v} has a NaN or infinite coordinate: {:?}", mesh.positions[v])));
    }
    if let Some(f) = mesh.faces().position(|f| f.iter().any(|&i| i as usize >= n)) {
        let bad = mesh.face(f).iter().find(|&&i| i as usize >= n).copied().unwrap_or(0);
        return Err(Error::Invalid(format!("face {f} refers to vertex {bad} but the mesh has {n} vertices")));
    }
    if let Some(s) = strips {
        if s.offsets.first().is_some_and(|&o| o != 0)
            || s.offsets.last().is_some_and(|&o| o as usize != s.indices.len())
            || s.offsets.windows(2).any(|w| w[1] < w[0])
        {
            return Err(Error::Invalid("strip offsets are malformed".into()));
        }
        if let Some(&bad) = s.indices.iter().find(|&&i| i as usize >= n) {
            return Err(Error::Invalid(format!("a strip refers to vertex {bad} but the mesh has {n} vertices")));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_are_chosen_by_extension_case_insensitively() {
        assert_eq!(Format::from_path(Path::new("a/b.OBJ")), Some((Format::Obj, false)));
        assert_eq!(Format::from_path(Path::new("x.ply.GZ")), Some((Format::Ply, true)));
        assert_eq!(Format::from_path(Path::new("horse-gallop-01.obj.gz")), Some((Format::Obj, true)));
        assert_eq!(Format::from_path(Path::new("m.glb")), Some((Format::Glb, false)));
        assert_eq!(Format::from_path(Path::new("m.txt")), None);
        assert_eq!(Format::from_path(Path::new("gz")), None);
        assert_eq!(Format::from_path(Path::new("m.gz")), None);
    }

    #[test]
    fn unknown_extension_lists_the_supported_ones() {
        let e = read(Path::new("mesh.xyz")).unwrap_err();
        let msg = e.to_string();
        assert!(matches!(e, Error::UnknownFormat { .. }));
        assert!(msg.contains("mesh.xyz") && msg.contains(".obj") && msg.contains(".glb"), "{msg}");
    }

    #[test]
    fn a_byte_order_mark_does_not_hide_the_first_line() {
        let text = b"\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let mesh = read_bytes(Path::new("bom.obj"), Format::Obj, text).unwrap();
        assert_eq!((mesh.vertex_count(), mesh.face_count()), (3, 1));
        let text = b"\xEF\xBB\xBFOFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        let mesh = read_bytes(Path::new("bom.off"), Format::Off, text).unwrap();
        assert_eq!((mesh.vertex_count(), mesh.face_count()), (3, 1));
    }

    #[test]
    fn writers_refuse_out_of_range_indices() {
        let mesh = Mesh::from_triangles(vec![[0.0; 3]; 3], &[[0, 1, 3]]);
        let e = write_bytes(Format::Obj, &mesh, None, &WriteOptions::default()).unwrap_err();
        assert!(e.to_string().contains("vertex 3"), "{e}");
        let strips = StripSet::from_strips(&[vec![0, 1, 2, 5]]);
        let ok = Mesh::from_triangles(vec![[0.0; 3]; 3], &[[0, 1, 2]]);
        let e = write_bytes(Format::Ply, &ok, Some(&strips), &WriteOptions::default()).unwrap_err();
        assert!(e.to_string().contains("vertex 5"), "{e}");
        let nan = Mesh::from_triangles(vec![[0.0; 3], [f32::NAN, 0.0, 0.0], [0.0; 3]], &[[0, 1, 2]]);
        let e = write_bytes(Format::Stl, &nan, None, &WriteOptions::default()).unwrap_err();
        assert!(e.to_string().contains("vertex 1 has a NaN"), "{e}");
    }
}

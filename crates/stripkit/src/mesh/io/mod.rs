//! Mesh files in and out, chosen by extension: OBJ, PLY, OFF, STL, glTF (`.gltf`,
//! `.glb`); a trailing `.gz` is decompressed (or compressed) transparently.
//!
//! Every reader takes the whole file into memory and parses bytes; malformed input
//! gives [`Error::Format`] naming the file, the line (text) or element / byte offset
//! (binary) and what is wrong. Counts announced in headers are checked against the
//! file's size before anything is allocated from them. Vertex ids are the file's:
//! unreferenced vertices are kept (STL, which has no shared vertices, welds identical
//! positions in first-seen order; an OBJ whose corners name `vt` or `vn` welds its
//! corners into GPU vertices, one per distinct `(v, vt, vn)` in first-seen order, unless
//! [`ReadOptions::positions_only`]). Vertex attributes (OBJ `vt`/`vn`, every PLY vertex
//! property) and face groups (OBJ `g`/`o`/`usemtl`) come with the mesh; the OBJ and PLY
//! writers write them back.
//!
//! Writing: [`write()`] / [`write_with`] write a mesh (with strips where the format
//! holds them) to a file, [`write_bytes`] encodes one in memory, and
//! [`write_encoded`] / [`write_encoded_all`] write bytes already encoded (one file, or
//! the several outputs of one run all or nothing). Every writer replaces its file
//! atomically: a reader, a crash or a full disk sees the old file or the complete new
//! one, never a partial file.
//!
//! Text is UTF-8 (a byte order mark is skipped; UTF-16 is refused by name) with lines
//! ending in `\n`, `\r\n` or a lone `\r`. Records after the counts an OFF or PLY
//! header announces are an error (trailing whitespace and OFF comments excepted). An
//! OBJ file with content that gives no vertex and no face is refused, saying what the
//! content looks like (another format, binary data), rather than read as an empty mesh.
//!
//! | format | read | write |
//! |---|---|---|
//! | OBJ | `v`, `vt`, `vn`, `f` (all forms, negative indices; corners welded), `g`/`o`, `usemtl`, `mtllib`; polygons kept | `v`, `vt`, `vn`, `f`, `g`, `usemtl`, `mtllib` |
//! | PLY | ASCII, binary LE/BE; every scalar vertex property; `face` lists or `tristrips` | ASCII or binary LE; every attribute; faces or `tristrips` |
//! | OFF | `[ST][C][N][4]OFF`, comments, face colours | `OFF` |
//! | STL | ASCII and binary, identical positions welded | binary, polygons fanned |
//! | glTF | `.gltf` (data URIs, external files), `.glb`; modes 4/5/6 | `.gltf` (embedded), `.glb`; TRIANGLES or one TRIANGLE_STRIP per strip |
//!
//! A whole glTF document (scenes, nodes, materials, skins, animations, ...) is read and
//! written by [`Scene`]: its triangle primitives decoded, the rest kept. Stripping
//! them is [`crate::scene`]'s business, above the door; this module only converts.

mod common;
mod gltf;
mod obj;
mod mtl;
mod off;
mod ply;
mod stl;

pub use gltf::meshopt::{decode_meshopt, MeshoptFilter, MeshoptMode};
pub use gltf::{Scene, ScenePrimitive};
pub use mtl::{Material, Materials, Texture};

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

/// Options for [`write_with`] and [`write_bytes`]. Default: binary little-endian PLY.
///
/// ```
/// let ascii = stripkit::io::WriteOptions::default().ply_ascii(true);
/// assert!(ascii.ply_ascii);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct WriteOptions {
    /// Write PLY as ASCII text instead of binary little-endian. Default `false`.
    pub ply_ascii: bool,
    /// Threads for the read-back check of written strips (the same bytes and result
    /// at any count). Default one.
    pub threads: crate::parallel::Threads,
}

impl WriteOptions {
    /// Sets [`WriteOptions::ply_ascii`].
    pub fn ply_ascii(mut self, on: bool) -> Self {
        self.ply_ascii = on;
        self
    }

    /// Sets [`WriteOptions::threads`].
    pub fn threads(mut self, threads: crate::parallel::Threads) -> Self {
        self.threads = threads;
        self
    }
}

/// The most vertex attributes (besides POSITION) a mesh may carry into glTF: 4,096.
/// Each becomes an accessor and a buffer view of its own, about 4.4 KB of document
/// per attribute while the scene is built, written and checked, so a PLY of 300,000
/// one-byte vertex properties (7.7 MB) would need 1.4 GB; more is refused before any
/// of it is built. Other formats carry any number.
pub const MAX_GLTF_VERTEX_ATTRIBUTES: usize = 4096;

/// The default of [`ReadOptions::max_external_bytes`]: 1 GiB.
pub const DEFAULT_MAX_EXTERNAL_BYTES: u64 = 1 << 30;

/// The default of [`ReadOptions::max_decompressed_bytes`]: 4 GiB.
pub const DEFAULT_MAX_DECOMPRESSED_BYTES: u64 = 4 << 30;

/// How many bytes of decoded mesh a glTF asset may describe per byte of its buffers
/// when [`ReadOptions::max_decoded_bytes`] is `None`: 32. A file whose accessors do not
/// overlap stays within 16 (the worst case, a strip of one-byte indices, gives a
/// 12-byte triangle and a 4-byte face offset per byte); more comes only from many
/// accessors or primitives reading the same bytes again.
pub const DECODED_BYTES_PER_BUFFER_BYTE: u64 = 32;

/// The allowance added to the buffer-relative budget when
/// [`ReadOptions::max_decoded_bytes`] is `None`: 1 MiB, so that small assets that
/// reuse a few accessors are never refused.
pub const DECODED_BYTES_ALLOWANCE: u64 = 1 << 20;

/// Options for [`read_with`] and [`read_bytes_with`]: where a `.gltf` may load its
/// external buffers from, how much it may load, how far a `.gz` file may expand and
/// how large a mesh a glTF asset may decode to.
///
/// A `.gltf` buffer's `uri` is accepted only when it is a base64 `data:` URI, or a
/// relative reference (no scheme, not absolute; `%XX` escapes decoded first) that,
/// after removing `.` and `..` segments and then resolving symbolic links, names a
/// regular file inside the asset's own folder or inside one of
/// [`allowed_roots`](Self::allowed_roots). Anything else is refused with the same
/// message whether or not the file exists, so a hostile asset learns nothing about
/// files outside those folders. The file is opened once (without waiting on a pipe),
/// and its place, type and size are checked on what was opened, so that a folder
/// swapped for a link after the check cannot lead the read elsewhere (on Linux the
/// opened file's own path is checked; elsewhere its device and inode must match the
/// path resolved again). Directories, devices and pipes are refused unread; at most
/// the buffer's declared `byteLength` is read, and a file shorter than that is
/// refused. A file named by several buffers is read once.
///
/// Extensions are decided in one place for every reader: geometry compressed with
/// Draco or meshopt is refused wherever it appears (naming the primitive or buffer
/// view), and a required extension must be one that leaves geometry as plain
/// accessors (materials, textures, lights, instancing, metadata), else it is refused
/// by name.
///
/// Defaults: no extra roots, 1 GiB of external buffers, 4 GiB decompressed, the
/// decoded mesh bounded by the input's buffers, attributes and groups read.
///
/// ```
/// let options = stripkit::io::ReadOptions::default().max_decompressed_bytes(1 << 20).positions_only(true);
/// assert_eq!(options.max_decompressed_bytes, 1 << 20);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
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
    /// The most bytes a gzip-compressed file (`.obj.gz`, `.ply.gz`, ...) may
    /// decompress to; decompression stops one byte past it and the file is refused
    /// ("decompresses to more than N bytes"), so a small file of compressed zeros
    /// cannot exhaust memory. Default [`DEFAULT_MAX_DECOMPRESSED_BYTES`] (4 GiB).
    /// Only [`read_with`] (and [`read`]) decompress; [`read_bytes_with`] takes
    /// uncompressed data and ignores it.
    pub max_decompressed_bytes: u64,
    /// The most bytes the mesh decoded from a glTF asset (`.gltf`, `.glb`) may take,
    /// counting 12 bytes per vertex, 4 per face index and 4 per face. glTF lets any
    /// number of accessors and primitives read the same buffer bytes, so a few
    /// kilobytes of JSON over one buffer could otherwise describe gigabytes of
    /// vertices and faces; each accessor is charged before it is decoded, and the
    /// asset is refused ("the primitives reuse accessors into ...") before the
    /// allocation that would cross the limit. `None` (the default) bounds the mesh by
    /// the input: [`DECODED_BYTES_PER_BUFFER_BYTE`] (32) times the bytes of the
    /// asset's distinct buffers, plus [`DECODED_BYTES_ALLOWANCE`] (1 MiB). `Some(n)`
    /// sets the limit to `n` bytes instead, to raise it for an asset that
    /// legitimately reuses its data many times or to lower it. The other formats need
    /// bytes in the file for every vertex and face index, so their meshes are bounded
    /// by the (decompressed) file's size and this option does not apply to them. The
    /// limit counts the mesh's content; its vectors grow by doubling, so the memory
    /// they reserve can reach twice that while reading.
    pub max_decoded_bytes: Option<u64>,
    /// Read positions and faces only (OBJ and PLY): no attributes, no groups, and OBJ
    /// vertex ids are the file's `v` records even where corners name `vt`/`vn` (no
    /// welding at seams). For work on the surface alone (topology, research figures on
    /// models whose UV seams would cut it). Default `false`.
    pub positions_only: bool,
}

impl Default for ReadOptions {
    fn default() -> Self {
        ReadOptions {
            allowed_roots: Vec::new(),
            max_external_bytes: DEFAULT_MAX_EXTERNAL_BYTES,
            max_decompressed_bytes: DEFAULT_MAX_DECOMPRESSED_BYTES,
            max_decoded_bytes: None,
            positions_only: false,
        }
    }
}

impl ReadOptions {
    /// Sets [`ReadOptions::allowed_roots`].
    pub fn allowed_roots(mut self, roots: Vec<PathBuf>) -> Self {
        self.allowed_roots = roots;
        self
    }
    /// Sets [`ReadOptions::max_external_bytes`].
    pub fn max_external_bytes(mut self, bytes: u64) -> Self {
        self.max_external_bytes = bytes;
        self
    }
    /// Sets [`ReadOptions::max_decompressed_bytes`].
    pub fn max_decompressed_bytes(mut self, bytes: u64) -> Self {
        self.max_decompressed_bytes = bytes;
        self
    }
    /// Sets [`ReadOptions::max_decoded_bytes`] (`None`: bounded by the input).
    pub fn max_decoded_bytes(mut self, bytes: Option<u64>) -> Self {
        self.max_decoded_bytes = bytes;
        self
    }
    /// Sets [`ReadOptions::positions_only`].
    pub fn positions_only(mut self, on: bool) -> Self {
        self.positions_only = on;
        self
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
/// [`ReadOptions`] (external glTF buffers only from the asset's own folder). `path` is
/// anything that names a file: `&str`, `String`, `&Path`, `PathBuf`.
///
/// ```
/// # let dir = stripkit_testkit::scratch_dir("doc-read");
/// # let name = dir.join("triangle.obj").display().to_string();
/// # std::fs::write(&name, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
/// let path: String = name; // a String, as a command line or a config gives it
/// let mesh = stripkit::io::read(&path)?;
/// assert_eq!(mesh.face_count(), 1);
/// # std::fs::remove_dir_all(&dir).unwrap();
/// # Ok::<(), stripkit::Error>(())
/// ```
pub fn read(path: impl AsRef<Path>) -> Result<Mesh> {
    read_with(path, &ReadOptions::default())
}

/// [`read`] with options (see [`ReadOptions`] for the rules on external glTF buffers
/// and the cap on gzip decompression).
pub fn read_with(path: impl AsRef<Path>, options: &ReadOptions) -> Result<Mesh> {
    let path = path.as_ref();
    let (format, gz) = Format::from_path(path).ok_or_else(|| unknown(path))?;
    let raw = std::fs::read(path).map_err(|e| io_error(path, e))?;
    let data = if gz {
        if matches!(format, Format::Obj | Format::Off | Format::Gltf) {
            text_head(path, &raw)?;
        }
        gunzip(path, &raw, options.max_decompressed_bytes)?
    } else {
        raw
    };
    read_bytes_with(path, format, &data, options)
}

/// For a compressed text format: refuses a stream whose first 4 KiB decompressed
/// hold a NUL byte (never text) before decompressing the rest, so that a small gzip
/// of gigabytes of zeros costs neither the time nor the memory up to the cap.
/// Errors in the stream are left to [`gunzip`], which reports them with their place.
fn text_head(path: &Path, raw: &[u8]) -> Result<()> {
    let mut head = Vec::with_capacity(4096);
    let _ = flate2::read::MultiGzDecoder::new(raw).take(4096).read_to_end(&mut head);
    match head.iter().position(|&b| b == 0) {
        Some(i) => Err(Error::Format {
            path: path.to_path_buf(),
            at: format!("decompressed byte {i}"),
            what: "a NUL byte: the content is binary data, not text".into(),
        }),
        None => Ok(()),
    }
}

/// Parses a mesh already in memory (uncompressed) as `format`; `path` names the file
/// in errors and locates external glTF buffers (with the default [`ReadOptions`]; see
/// [`read_bytes_with`]).
pub fn read_bytes(path: &Path, format: Format, data: &[u8]) -> Result<Mesh> {
    read_bytes_with(path, format, data, &ReadOptions::default())
}

/// [`read_bytes`] with options: external glTF buffers follow `options` (see
/// [`ReadOptions`]); other formats do not use them.
pub fn read_bytes_with(path: &Path, format: Format, data: &[u8], options: &ReadOptions) -> Result<Mesh> {
    // A UTF-8 byte order mark before a text format would hide its first keyword; a
    // UTF-16 one means text we do not decode (read as bytes it would give nothing).
    // STL handles both itself, since it may be binary.
    let data = match format {
        Format::Obj | Format::Off | Format::Ply | Format::Gltf => {
            if let Some(bom) = common::utf16_bom(data) {
                return Err(Error::Format {
                    path: path.to_path_buf(),
                    at: "byte 0".into(),
                    what: format!("the file is UTF-16 ({bom}); save it as UTF-8"),
                });
            }
            data.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(data)
        }
        Format::Stl | Format::Glb => data,
    };
    match format {
        Format::Obj => obj::read(path, data, options.positions_only),
        Format::Ply => ply::read(path, data, options.positions_only),
        Format::Off => off::read(path, data),
        Format::Stl => stl::read(path, data),
        Format::Gltf => gltf::read_gltf(path, data, options),
        Format::Glb => gltf::read_glb(path, data, options),
    }
}

/// Decompresses `raw`, reading at most `cap + 1` bytes: one past the cap proves the
/// stream is too large without holding more than the cap.
fn gunzip(path: &Path, raw: &[u8], cap: u64) -> Result<Vec<u8>> {
    let start = raw.len().saturating_mul(3).min(usize::try_from(cap).unwrap_or(usize::MAX));
    let mut out = Vec::with_capacity(start);
    flate2::read::MultiGzDecoder::new(raw)
        .take(cap.saturating_add(1))
        .read_to_end(&mut out)
        .map_err(|e| Error::Format {
            path: path.to_path_buf(),
            at: format!("gzip stream (after {} decompressed bytes)", out.len()),
            what: format!("cannot decompress: {e}"),
        })?;
    if out.len() as u64 > cap {
        return Err(Error::Format {
            path: path.to_path_buf(),
            at: "gzip stream".into(),
            what: format!(
                "decompresses to more than {cap} bytes, the limit (ReadOptions::max_decompressed_bytes; \
                 --max-memory on the command line raises it)"
            ),
        });
    }
    Ok(out)
}

/// Writes a mesh, choosing the format by extension. With `strips`, formats that can
/// hold strips (PLY `tristrips`, glTF `TRIANGLE_STRIP`) write them instead of faces;
/// OBJ, OFF and STL always write the mesh's faces. PLY is binary little-endian; see
/// [`write_with`] for ASCII.
pub fn write(path: impl AsRef<Path>, mesh: &Mesh, strips: Option<&StripSet>) -> Result<()> {
    write_with(path, mesh, strips, &WriteOptions::default())
}

/// [`write()`] with options. The mesh is checked first: [`Error::Invalid`] when a face or
/// strip index is out of range or a coordinate is NaN or infinite (no reader would
/// accept the file). A name ending in `.gz` is gzip-compressed. The file is replaced
/// atomically, as [`write_encoded`] does.
pub fn write_with(
    path: impl AsRef<Path>,
    mesh: &Mesh,
    strips: Option<&StripSet>,
    options: &WriteOptions,
) -> Result<()> {
    let path = path.as_ref();
    let (format, _) = Format::from_path(path).ok_or_else(|| unknown(path))?;
    write_encoded(path, &write_bytes(format, mesh, strips, options)?)
}

/// Writes bytes already encoded (a mesh format's bytes from [`write_bytes`] or
/// [`crate::Strips::to_file_bytes`], or any other file: a table, an image),
/// gzip-compressed when `path` names a mesh format ending in `.gz`.
///
/// The file is replaced atomically: at every moment `path` is its old content (or
/// absent) or the complete new content, never a partial file. The bytes go to a
/// temporary file `.NAME.tmp-PID-N` in the destination's folder, which is synced and
/// then renamed over `path` (on Unix the folder is synced too). On failure the
/// temporary file is removed, `path` is left as it was, and the error ([`Error::Io`])
/// names `path`; only a process killed before the rename may leave a `.NAME.tmp-*`
/// file behind. A symbolic link at `path` is replaced by a regular file; an existing
/// file's permissions are kept.
pub fn write_encoded(path: &Path, bytes: &[u8]) -> Result<()> {
    write_atomic(path, &compress_for(path, bytes)?)
}

/// Writes the several outputs of one run, each as [`write_encoded`] does, all or
/// nothing as far as the file system allows: every file is written in full to its
/// temporary file and synced before any is renamed over its destination, in the order
/// given. A failure while writing (full disk, missing folder, no permission) leaves
/// every destination as it was; only a failing rename itself (rare) can leave the
/// earlier files new and the later ones old, never a partial file. Two destinations
/// that are one file ([`same_destination`]) are refused with [`Error::Invalid`] before
/// anything is written.
pub fn write_encoded_all(files: &[(&Path, &[u8])]) -> Result<()> {
    let packed = files.iter().map(|(path, bytes)| compress_for(path, bytes)).collect::<Result<Vec<_>>>()?;
    let files: Vec<(&Path, &[u8])> = files.iter().zip(&packed).map(|((path, _), bytes)| (*path, &**bytes)).collect();
    write_atomic_all(&files)
}

/// The bytes `encode` makes, once `check` has read them back and found them to be
/// what was meant (its error, typically [`Error::Verification`], otherwise): the
/// first half of [`write_checked`], for outputs that go somewhere other than a file.
pub(crate) fn encode_checked(
    encode: impl FnOnce() -> Result<Vec<u8>>,
    check: impl FnOnce(&[u8]) -> Result<()>,
) -> Result<Vec<u8>> {
    let bytes = encode()?;
    check(&bytes)?;
    Ok(bytes)
}

/// The one write path of checked outputs (strips in a mesh file, a glTF scene, the
/// `.sets` and `.lodseq` files of `lod`, a collapse sequence): `encode` makes the bytes, `check` reads them
/// back and compares them with what was meant, and only then are they written to
/// `path` atomically ([`write_atomic`]: a temporary file beside it, synced, renamed),
/// gzip-compressed when the name is a mesh format's ending in `.gz`. Nothing is
/// written when either step fails. Returns the length of the encoded bytes (before
/// any compression).
pub(crate) fn write_checked(
    path: &Path,
    encode: impl FnOnce() -> Result<Vec<u8>>,
    check: impl FnOnce(&[u8]) -> Result<()>,
) -> Result<usize> {
    let bytes = encode_checked(encode, check)?;
    write_encoded(path, &bytes)?;
    Ok(bytes.len())
}

/// `bytes` gzip-compressed when `path`'s name ends in `.gz`, unchanged otherwise.
fn compress_for<'a>(path: &Path, bytes: &'a [u8]) -> Result<std::borrow::Cow<'a, [u8]>> {
    if Format::from_path(path).is_some_and(|(_, gz)| gz) {
        let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
        let packed = enc.write_all(bytes).and_then(|_| enc.finish()).map_err(|e| io_error(path, e))?;
        Ok(packed.into())
    } else {
        Ok(bytes.into())
    }
}

/// Writes `bytes` to `path` so that `path` is at every moment either its old content
/// (or absent) or the complete new content, never a partial file.
///
/// The bytes go to a temporary file in the destination's folder, named
/// `.NAME.tmp-PID-N` (`NAME` the destination's file name, `PID` this process, `N` a
/// counter), which is flushed and synced to disk (`sync_all`), then renamed over
/// `path`; on Unix the folder is then synced too, so that the rename itself survives
/// a crash (an error of that last step is ignored: the file is already in place).
///
/// On any failure the temporary file is removed, `path` is left as it was, and the
/// error ([`Error::Io`]) names `path`. A process killed between the creation and
/// the rename (SIGKILL, power loss) cannot clean up: it may leave a `.NAME.tmp-*`
/// file beside the destination, never a partial file at the destination's name.
///
/// Every writer of this crate goes through it (the public ones through
/// [`write_encoded`] and [`write_encoded_all`]). If `path` is a symbolic link, the
/// link itself is replaced by a regular file; an existing file's permissions are kept.
pub(crate) fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    Staged::new(path, bytes)?.commit()
}

/// Writes several files of one run as [`write_atomic`] does, all or nothing as far as
/// the file system allows: every file is first written in full to its temporary file
/// and synced; only when all of them are on disk are they renamed over their
/// destinations, in the order given. A failure while writing (full disk, missing
/// folder, no permission) removes every temporary file and leaves every destination
/// as it was. The remaining window is a failure of a rename itself (rare: the
/// temporaries sit in the destinations' folders): the files renamed before it have
/// their new content, the others keep their old content, and no file is ever partial.
///
/// Two destinations that are the same file ([`same_destination`]) are refused with
/// [`Error::Invalid`] before anything is written.
pub(crate) fn write_atomic_all(files: &[(&Path, &[u8])]) -> Result<()> {
    for (i, (a, _)) in files.iter().enumerate() {
        if let Some((b, _)) = files[..i].iter().find(|(b, _)| same_destination(a, b)) {
            return Err(Error::Invalid(format!(
                "{} and {} are the same file: refusing to write one output over another",
                b.display(),
                a.display()
            )));
        }
    }
    let mut staged = Vec::with_capacity(files.len());
    for (path, bytes) in files {
        match Staged::new(path, bytes) {
            Ok(s) => staged.push(s),
            Err(e) => {
                staged.into_iter().for_each(Staged::discard);
                return Err(e);
            }
        }
    }
    let mut staged = staged.into_iter();
    while let Some(s) = staged.next() {
        if let Err(e) = s.commit() {
            staged.for_each(Staged::discard);
            return Err(e);
        }
    }
    Ok(())
}

/// Whether two paths name the same file: the same path, the same file on disk when
/// both exist (on Unix the same device and inode, so hard links, symbolic links, `.`
/// and `..` are all seen through), or the same file once resolved (for a file that
/// does not exist yet, its folder resolved and its name). Paths that cannot be
/// resolved compare as written.
pub fn same_destination(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(x), Ok(y)) = (std::fs::metadata(a), std::fs::metadata(b)) {
            return a == b || (x.dev() == y.dev() && x.ino() == y.ino());
        }
    }
    fn resolved(p: &Path) -> Option<std::path::PathBuf> {
        if let Ok(full) = p.canonicalize() {
            return Some(full);
        }
        let dir = match p.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        Some(dir.canonicalize().ok()?.join(p.file_name()?))
    }
    a == b || matches!((resolved(a), resolved(b)), (Some(x), Some(y)) if x == y)
}

/// A temporary file written in full and synced, waiting to be renamed over `dest`.
struct Staged<'a> {
    dest: &'a Path,
    tmp: std::path::PathBuf,
    dir: &'a Path,
}

impl<'a> Staged<'a> {
    /// Creates `.NAME.tmp-PID-N` beside `dest`, writes, flushes and syncs it; on
    /// failure removes it and returns an error naming `dest`.
    fn new(dest: &'a Path, bytes: &[u8]) -> Result<Staged<'a>> {
        use std::sync::atomic::{AtomicU64, Ordering};
        static COUNTER: AtomicU64 = AtomicU64::new(0);

        let name = dest.file_name().ok_or_else(|| {
            io_error(dest, std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file name"))
        })?;
        let dir = match dest.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        // The rename would refuse it, but only after the whole write (and, in
        // `write_atomic_all`, after earlier files were renamed): refuse it now.
        if dest.is_dir() {
            return Err(io_error(dest, std::io::Error::other("is a folder, not a file")));
        }
        let (tmp, mut file) = loop {
            let n = COUNTER.fetch_add(1, Ordering::Relaxed);
            let mut tmp_name = std::ffi::OsString::from(".");
            tmp_name.push(name);
            tmp_name.push(format!(".tmp-{}-{n}", std::process::id()));
            let tmp = dir.join(tmp_name);
            match std::fs::OpenOptions::new().write(true).create_new(true).open(&tmp) {
                Ok(f) => break (tmp, f),
                // A leftover of a killed process that had our id: take the next number.
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
                Err(e) => return Err(io_error(dest, e)),
            }
        };
        // Keep the mode of the file we replace (a new file gets the usual default).
        if let Ok(meta) = std::fs::metadata(dest) {
            let _ = file.set_permissions(meta.permissions());
        }
        let written = file.write_all(bytes).and_then(|()| file.flush()).and_then(|()| file.sync_all());
        drop(file);
        let staged = Staged { dest, tmp, dir };
        match written {
            Ok(()) => Ok(staged),
            Err(e) => {
                staged.discard();
                Err(io_error(dest, e))
            }
        }
    }

    /// Renames the temporary file over the destination (removing it if that fails),
    /// then syncs the folder where the platform allows, ignoring errors of that sync.
    fn commit(self) -> Result<()> {
        if let Err(e) = std::fs::rename(&self.tmp, self.dest) {
            let dest = self.dest;
            self.discard();
            return Err(io_error(dest, e));
        }
        #[cfg(unix)]
        if let Ok(d) = std::fs::File::open(self.dir) {
            let _ = d.sync_all();
        }
        Ok(())
    }

    fn discard(self) {
        let _ = std::fs::remove_file(&self.tmp);
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
    mesh.check_faces()?;
    let n = mesh.positions.len();
    if let Some(v) = mesh.positions.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        // Every reader refuses these, so writing them would make a file we cannot read.
        return Err(Error::Invalid(format!("vertex {v} has a NaN or infinite coordinate: {:?}", mesh.positions[v])));
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

    fn scratch(name: &str) -> std::path::PathBuf {
        stripkit_testkit::fresh_scratch_dir(&format!("atomic-{name}"))
    }

    fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> =
            std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
        names.sort();
        names
    }

    #[test]
    fn write_atomic_creates_and_replaces_leaving_no_temporary_file() {
        let dir = scratch("replace");
        let dest = dir.join("out.obj");
        write_atomic(&dest, b"first").unwrap();
        assert_eq!(std::fs::read(&dest).unwrap(), b"first");
        write_atomic(&dest, b"second, longer than the first").unwrap();
        assert_eq!(std::fs::read(&dest).unwrap(), b"second, longer than the first");
        write_atomic(&dest, b"").unwrap();
        assert_eq!(std::fs::read(&dest).unwrap(), b"");
        assert_eq!(entries(&dir), ["out.obj"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn write_atomic_keeps_the_replaced_files_permissions() {
        use std::os::unix::fs::PermissionsExt;
        let dir = scratch("mode");
        let dest = dir.join("out.ply");
        std::fs::write(&dest, b"old").unwrap();
        std::fs::set_permissions(&dest, std::fs::Permissions::from_mode(0o640)).unwrap();
        write_atomic(&dest, b"new").unwrap();
        assert_eq!(std::fs::metadata(&dest).unwrap().permissions().mode() & 0o777, 0o640);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn write_atomic_into_a_missing_folder_fails_naming_the_destination() {
        let dir = scratch("missing");
        let dest = dir.join("no-such-folder").join("out.obj");
        let e = write_atomic(&dest, b"bytes").unwrap_err();
        assert!(matches!(e, Error::Io { .. }), "{e:?}");
        assert!(e.to_string().contains(&dest.display().to_string()), "{e}");
        assert!(entries(&dir).is_empty(), "{:?}", entries(&dir));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A rename that fails after the temporary file was written in full (a folder
    /// appeared at the destination meanwhile): the temporary file must go.
    #[test]
    fn a_failed_rename_removes_the_temporary_file() {
        let dir = scratch("rename");
        let dest = dir.join("out.obj");
        let staged = Staged::new(&dest, b"complete bytes").unwrap();
        assert_eq!(entries(&dir).len(), 1, "{:?}", entries(&dir));
        assert!(entries(&dir)[0].starts_with(".out.obj.tmp-"), "{:?}", entries(&dir));
        std::fs::create_dir(&dest).unwrap();
        std::fs::write(dest.join("inside"), b"kept").unwrap();
        let e = staged.commit().unwrap_err();
        assert!(e.to_string().contains(&dest.display().to_string()), "{e}");
        assert_eq!(std::fs::read(dest.join("inside")).unwrap(), b"kept");
        assert_eq!(entries(&dir), ["out.obj"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn write_atomic_over_a_folder_fails_and_leaves_it_and_no_temporary_file() {
        let dir = scratch("isdir");
        let dest = dir.join("out.obj");
        std::fs::create_dir(&dest).unwrap();
        std::fs::write(dest.join("inside"), b"kept").unwrap();
        let e = write_atomic(&dest, b"bytes").unwrap_err();
        assert!(e.to_string().contains(&dest.display().to_string()), "{e}");
        assert!(dest.is_dir());
        assert_eq!(std::fs::read(dest.join("inside")).unwrap(), b"kept");
        assert_eq!(entries(&dir), ["out.obj"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A read-only folder: the temporary file cannot even be created.
    #[cfg(unix)]
    #[test]
    fn write_atomic_in_a_read_only_folder_leaves_the_old_file_unchanged() {
        use std::os::unix::fs::PermissionsExt;
        let dir = scratch("readonly");
        let dest = dir.join("out.off");
        std::fs::write(&dest, b"the old, good file").unwrap();
        std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o555)).unwrap();
        let probe = dir.join("probe");
        let root = std::fs::write(&probe, b"").is_ok(); // root ignores folder permissions
        let _ = std::fs::remove_file(&probe);
        let result = write_atomic(&dest, b"new bytes");
        std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o755)).unwrap();
        if root {
            eprintln!("skipped: running as root, the folder stays writable; nothing to check");
        } else {
            let e = result.unwrap_err();
            assert!(e.to_string().contains(&dest.display().to_string()), "{e}");
            assert_eq!(std::fs::read(&dest).unwrap(), b"the old, good file");
            assert_eq!(entries(&dir), ["out.off"]);
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn write_atomic_all_writes_nothing_when_a_later_file_fails() {
        let dir = scratch("all");
        let first = dir.join("mesh.obj");
        let second = dir.join("sequence.bin");
        std::fs::write(&first, b"old mesh").unwrap();
        std::fs::create_dir(&second).unwrap(); // the second cannot be written
        let e = write_atomic_all(&[(&first, b"new mesh"), (&second, b"new sequence")]).unwrap_err();
        assert!(e.to_string().contains(&second.display().to_string()), "{e}");
        // The first was staged before the second failed: it must not have been renamed.
        assert_eq!(std::fs::read(&first).unwrap(), b"old mesh");
        assert_eq!(entries(&dir), ["mesh.obj", "sequence.bin"]);
        let missing = dir.join("no-such-folder").join("s.bin");
        let e = write_atomic_all(&[(&first, b"new mesh"), (&missing, b"new sequence")]).unwrap_err();
        assert!(e.to_string().contains(&missing.display().to_string()), "{e}");
        assert_eq!(std::fs::read(&first).unwrap(), b"old mesh");
        assert_eq!(entries(&dir), ["mesh.obj", "sequence.bin"]);
        std::fs::remove_dir(&second).unwrap();
        write_atomic_all(&[(&first, b"new mesh"), (&second, b"new sequence")]).unwrap();
        assert_eq!(std::fs::read(&first).unwrap(), b"new mesh");
        assert_eq!(std::fs::read(&second).unwrap(), b"new sequence");
        assert_eq!(entries(&dir), ["mesh.obj", "sequence.bin"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn same_destination_sees_through_hard_and_symbolic_links() {
        let dir = scratch("links");
        let a = dir.join("a.obj");
        std::fs::write(&a, b"v 0 0 0\n").unwrap();
        let hard = dir.join("hard.obj");
        std::fs::hard_link(&a, &hard).unwrap();
        let soft = dir.join("soft.obj");
        std::os::unix::fs::symlink("a.obj", &soft).unwrap();
        let other = dir.join("other.obj");
        std::fs::write(&other, b"v 0 0 0\n").unwrap();
        assert!(same_destination(&a, &hard) && same_destination(&hard, &soft));
        assert!(!same_destination(&a, &other) && !same_destination(&hard, &other));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn write_atomic_all_refuses_two_outputs_that_are_one_file() {
        let dir = scratch("same");
        let a = dir.join("x.obj");
        let b = dir.join(".").join("x.obj"); // not yet existing, same file once resolved
        std::fs::create_dir(dir.join("sub")).unwrap();
        let c = dir.join("sub").join("..").join("x.obj");
        assert!(same_destination(&a, &b) && same_destination(&a, &c));
        assert!(!same_destination(&a, &dir.join("y.obj")));
        let e = write_atomic_all(&[(&a, b"1"), (&c, b"2")]).unwrap_err();
        assert!(matches!(e, Error::Invalid(_)), "{e:?}");
        assert!(!a.exists());
        assert_eq!(entries(&dir), ["sub"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn write_encoded_goes_through_write_atomic() {
        let dir = scratch("encoded");
        let dest = dir.join("m.obj.gz");
        std::fs::create_dir(&dest).unwrap();
        assert!(write_encoded(&dest, b"v 0 0 0\n").is_err());
        assert_eq!(entries(&dir), ["m.obj.gz"]);
        std::fs::remove_dir(&dest).unwrap();
        let mesh = Mesh::from_triangles(vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
        write(&dest, &mesh, None).unwrap();
        assert_eq!(read(&dest).unwrap().face_count(), 1);
        assert_eq!(entries(&dir), ["m.obj.gz"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn write_encoded_all_compresses_gz_names_and_refuses_one_file_twice() {
        let dir = scratch("encoded-all");
        let mesh = Mesh::from_triangles(vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
        let obj = write_bytes(Format::Obj, &mesh, None, &WriteOptions::default()).unwrap();
        let (packed, table) = (dir.join("m.obj.gz"), dir.join("table.md"));
        write_encoded_all(&[(&packed, &obj), (&table, b"| a |\n")]).unwrap();
        assert_eq!(read(&packed).unwrap().face_count(), 1);
        assert_eq!(std::fs::read(&table).unwrap(), b"| a |\n");
        let e = write_encoded_all(&[(&table, b"1"), (&dir.join(".").join("table.md"), b"2")]).unwrap_err();
        assert!(matches!(e, Error::Invalid(_)), "{e:?}");
        assert_eq!(std::fs::read(&table).unwrap(), b"| a |\n");
        assert_eq!(entries(&dir), ["m.obj.gz", "table.md"]);
        std::fs::remove_dir_all(&dir).unwrap();
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

//! glTF 2.0: `.gltf` (JSON with buffers as base64 `data:` URIs or external files
//! beside it) and `.glb` (binary container, buffer 0 in the BIN chunk).
//!
//! External buffer files must lie inside the asset's folder or an allowed root, be
//! regular files, and are read once each up to their `byteLength`, within a byte
//! budget: see [`ReadOptions`] for the rules.
//!
//! Read: every primitive of every mesh is merged into one mesh (node transforms are
//! not applied, except to quantized positions: `KHR_mesh_quantization` integers are
//! dequantized, then moved by the world transform of the first node drawing their mesh,
//! which holds the dequantizing scale and offset in the files gltfpack writes).
//! Buffer views compressed with `EXT_meshopt_compression` are decoded first.
//! Primitives that share a POSITION accessor share vertices, so vertex
//! ids survive a write and read. The other vertex attributes come with them (each run
//! of vertices takes those of the first primitive that names its POSITION); an
//! attribute is kept where every run has one of its name alike (scalar type,
//! components, normalization), since a mesh holds one value per vertex. TRIANGLES (mode 4) give one face per triangle;
//! TRIANGLE_STRIP (5) and TRIANGLE_FAN (6) are turned into triangles with the
//! winding the modes define, degenerate ones skipped; points and lines (0 to 3) only
//! contribute their vertices. Primitives without indices use their vertices in order.
//! Sparse accessors and accessors without a buffer view are refused.
//! The decoded mesh is bounded: every accessor is charged to
//! [`ReadOptions::max_decoded_bytes`] (by default 32 times the asset's buffer bytes
//! plus 1 MiB) before anything is allocated for it, since accessors and primitives may
//! read the same bytes any number of times.
//!
//! Write (`write.rs`, the plain form; a scene and a mesh with attributes or groups go
//! through [`Scene`](scene::Scene), which the library's glTF output uses for every
//! mesh it can): one buffer with the positions (VEC3 float, with min / max),
//! every attribute (as `from_mesh` writes them: glTF semantics where the shape fits,
//! `_NAME` otherwise) and the indices
//! (u16 when there are fewer than 65535 vertices, else u32); without strips one
//! TRIANGLES primitive (polygons fanned), with strips one TRIANGLE_STRIP primitive per
//! strip of at least three indices. A mesh with vertices but nothing to draw gets a
//! POINTS primitive so that its vertices are kept.

use super::common::{close_face, push_fan_triangles, push_strip_triangles, Src};
use super::ReadOptions;
use crate::error::Result;
use crate::mesh::{Attribute, Mesh};
use serde_json::Value;
use std::collections::{HashMap, HashSet};
use std::path::Path;
use std::sync::Arc;

mod buffers;
use buffers::load_buffers;
mod compress;
mod extensions;
mod from_mesh;
mod held;
pub(crate) mod meshopt;
mod nodes;
mod primitive;
mod scene;
mod write;

pub use primitive::ScenePrimitive;
pub use scene::Scene;
use write::glb_container;
pub(crate) use write::{base64_decode, base64_encode, write_glb, write_gltf};

const GLB_MAGIC: &[u8; 4] = b"glTF";
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

/// Parses a `.gltf` file held in memory; external buffers are read beside `path`,
/// following `options` (see [`ReadOptions`]).
pub(crate) fn read_gltf(path: &Path, data: &[u8], options: &ReadOptions) -> Result<Mesh> {
    let src = Src { path };
    let json = parse_json(src, data, 0)?;
    load(src, &json, None, options)
}

/// Parses a `.glb` file held in memory; buffers other than the binary chunk follow
/// `options` as in [`read_gltf`].
pub(crate) fn read_glb(path: &Path, data: &[u8], options: &ReadOptions) -> Result<Mesh> {
    let src = Src { path };
    let (json, bin) = parse_glb(src, data)?;
    load(src, &json, bin, options)
}

/// Splits a `.glb` file into its parsed JSON chunk and its binary chunk, if any.
fn parse_glb<'d>(src: Src, data: &'d [u8]) -> Result<(Value, Option<&'d [u8]>)> {
    let u32_at = |o: usize| -> Option<u32> { Some(u32::from_le_bytes(data.get(o..o + 4)?.try_into().ok()?)) };
    if data.len() < 12 {
        return Err(src.err("byte 0", format!("{} bytes is too short for a GLB header (12 bytes)", data.len())));
    }
    if &data[..4] != GLB_MAGIC {
        return Err(src.err("byte 0", "not a GLB file: it does not start with 'glTF'"));
    }
    let version = u32_at(4).unwrap_or(0);
    if version != 2 {
        return Err(src.err("byte 4", format!("GLB version {version}, only version 2 is supported")));
    }
    let length = u32_at(8).unwrap_or(0) as usize;
    if length > data.len() {
        return Err(src.err(
            "byte 8",
            format!("the header announces {length} bytes but the file has {} (truncated)", data.len()),
        ));
    }
    let data = &data[..length];
    let mut pos = 12;
    let mut json = None;
    let mut bin = None;
    while pos < data.len() {
        let (Some(len), Some(kind)) = (u32_at(pos), u32_at(pos + 4)) else {
            return Err(src.err(format!("byte {pos}"), "truncated chunk header"));
        };
        let start = pos + 8;
        let end = start.checked_add(len as usize).filter(|&e| e <= data.len()).ok_or_else(|| {
            src.err(
                format!("byte {pos}"),
                format!("chunk of {len} bytes runs past the end of the file ({} bytes)", data.len()),
            )
        })?;
        match kind {
            CHUNK_JSON if json.is_none() => json = Some((start, &data[start..end])),
            CHUNK_BIN if bin.is_none() => bin = Some(&data[start..end]),
            _ => {} // unknown chunks are skipped, as the specification asks
        }
        pos = end;
    }
    let (offset, json) = json.ok_or_else(|| src.err("byte 12", "the GLB file has no JSON chunk"))?;
    let json = parse_json(src, json, offset)?;
    Ok((json, bin))
}

fn parse_json(src: Src, bytes: &[u8], offset: usize) -> Result<Value> {
    serde_json::from_slice(bytes).map_err(|e| {
        let at = if offset == 0 {
            format!("line {} column {}", e.line(), e.column())
        } else {
            format!("JSON chunk at byte {offset}, line {} column {}", e.line(), e.column())
        };
        src.err(at, format!("malformed JSON: {e}"))
    })
}

/// A JSON path like `accessors[3]` for messages.
fn at(array: &str, i: usize) -> String {
    format!("{array}[{i}]")
}

fn array<'v>(src: Src, json: &'v Value, key: &str) -> Result<&'v [Value]> {
    match json.get(key) {
        None => Ok(&[]),
        Some(Value::Array(a)) => Ok(a),
        Some(_) => Err(src.err(key, "must be an array")),
    }
}

/// An optional non-negative integer member.
fn uint(src: Src, obj: &Value, key: &str, place: &dyn Fn() -> String) -> Result<Option<u64>> {
    match obj.get(key) {
        None => Ok(None),
        Some(v) => {
            v.as_u64().map(Some).ok_or_else(|| src.err(place(), format!("'{key}' must be a non-negative integer")))
        }
    }
}

fn required(src: Src, obj: &Value, key: &str, place: &dyn Fn() -> String) -> Result<u64> {
    uint(src, obj, key, place)?.ok_or_else(|| src.err(place(), format!("'{key}' is missing")))
}

#[derive(Clone, Debug)]
struct View {
    buffer: usize,
    offset: usize,
    length: usize,
    stride: Option<usize>,
}

struct Accessor {
    offset: usize,
    count: usize,
    component: u64,
    components: usize,
}

impl Accessor {
    fn component_size(&self) -> usize {
        match self.component {
            5120 | 5121 => 1,
            5122 | 5123 => 2,
            _ => 4,
        }
    }
}

/// Bytes that buffers share without a copy: `all[start..end]`. A buffer made for
/// itself holds a whole `Vec` (`From<Vec<u8>>`); a GLB's binary chunk may be a range of
/// the file's bytes, so that the file is not held twice (see `Scene::into_bytes`).
#[derive(Clone, Default)]
struct Shared {
    all: Arc<Vec<u8>>,
    start: usize,
    end: usize,
}

impl Shared {
    /// The range `range` of `all` (which must lie inside it).
    fn range(all: &Arc<Vec<u8>>, range: std::ops::Range<usize>) -> Shared {
        debug_assert!(range.start <= range.end && range.end <= all.len());
        Shared { all: Arc::clone(all), start: range.start, end: range.end }
    }
}

impl From<Vec<u8>> for Shared {
    fn from(bytes: Vec<u8>) -> Shared {
        let end = bytes.len();
        Shared { all: Arc::new(bytes), start: 0, end }
    }
}

impl std::ops::Deref for Shared {
    type Target = [u8];
    fn deref(&self) -> &[u8] {
        &self.all[self.start..self.end]
    }
}

/// A buffer's bytes: the first `len` bytes of `bytes`, which several buffers share
/// when they name the same external file.
#[derive(Clone)]
struct Buffer {
    bytes: Shared,
    len: usize,
}

impl std::ops::Deref for Buffer {
    type Target = [u8];
    fn deref(&self) -> &[u8] {
        &self.bytes[..self.len]
    }
}

struct Doc<'a> {
    src: Src<'a>,
    buffers: Vec<Buffer>,
    views: Vec<View>,
    accessors: &'a [Value],
}

/// Checks the asset's version and extensions ([`extensions::check`]), loads its buffers and
/// buffer views (every view checked against its buffer) and decodes the views compressed
/// with `EXT_meshopt_compression` ([`decode_compressed_views`]), each charged to the
/// decoded-bytes budget returned (which grants `scene_allowance`, see
/// [`Budget::with_scene_allowance`]) before it is allocated.
fn open<'a>(
    src: Src<'a>,
    json: &'a Value,
    bin: Option<Shared>,
    options: &ReadOptions,
    scene_allowance: u64,
) -> Result<(Doc<'a>, Budget)> {
    let version = json.pointer("/asset/version").and_then(Value::as_str).unwrap_or("");
    if !version.starts_with('2') {
        return Err(src.err("asset.version", format!("glTF version '{version}', only 2.x is supported")));
    }
    // Compressed geometry and unknown required extensions: refused here, for every reader.
    extensions::check(src, json)?;
    let buffers = load_buffers(src, json, bin, options)?;
    let mut views = Vec::new();
    for (i, v) in array(src, json, "bufferViews")?.iter().enumerate() {
        let place = || at("bufferViews", i);
        let buffer = required(src, v, "buffer", &place)? as usize;
        let offset = uint(src, v, "byteOffset", &place)?.unwrap_or(0) as usize;
        let length = required(src, v, "byteLength", &place)? as usize;
        let stride = uint(src, v, "byteStride", &place)?.map(|s| s as usize);
        if v.pointer("/extensions/EXT_meshopt_compression").is_some() {
            // Its bytes are decoded below; the buffer it names may be a fallback
            // buffer without data.
            views.push(View { buffer: usize::MAX, offset: 0, length, stride });
            continue;
        }
        let buf_len = buffers
            .get(buffer)
            .ok_or_else(|| src.err(place(), format!("refers to buffer {buffer} but the file has {}", buffers.len())))?
            .len();
        if !matches!(offset.checked_add(length), Some(end) if end <= buf_len) {
            return Err(
                src.err(place(), format!("bytes {offset}..+{length} lie outside buffer {buffer} ({buf_len} bytes)"))
            );
        }
        if stride.is_some_and(|s| !(4..=252).contains(&s)) {
            return Err(src.err(place(), "byteStride must lie in 4..=252"));
        }
        views.push(View { buffer, offset, length, stride });
    }
    let mut doc = Doc { src, buffers, views, accessors: array(src, json, "accessors")? };
    let mut budget = Budget::with_scene_allowance(options, doc.buffer_bytes(), scene_allowance);
    decode_compressed_views(&mut doc, json, &mut budget)?;
    Ok((doc, budget))
}

/// Decodes every buffer view compressed with `EXT_meshopt_compression` into a buffer of
/// its own (the view then reads it from byte 0). Its size is `count` x `byteStride` of
/// the extension, which must equal the view's `byteLength`, and is charged to `budget`
/// before anything is allocated; the compressed bytes must lie inside their buffer.
fn decode_compressed_views(doc: &mut Doc, json: &Value, budget: &mut Budget) -> Result<()> {
    use meshopt::{MeshoptFilter, MeshoptMode};
    let src = doc.src;
    for (i, v) in array(src, json, "bufferViews")?.iter().enumerate() {
        let Some(ext) = v.pointer("/extensions/EXT_meshopt_compression") else { continue };
        let place = || format!("bufferViews[{i}].extensions.EXT_meshopt_compression");
        let buffer = required(src, ext, "buffer", &place)? as usize;
        let offset = uint(src, ext, "byteOffset", &place)?.unwrap_or(0) as usize;
        let length = required(src, ext, "byteLength", &place)? as usize;
        let stride = required(src, ext, "byteStride", &place)? as usize;
        let count = required(src, ext, "count", &place)? as usize;
        let name = |key: &str| ext.get(key).and_then(Value::as_str);
        let mode = name("mode")
            .and_then(MeshoptMode::from_name)
            .ok_or_else(|| src.err(place(), "'mode' must be ATTRIBUTES, TRIANGLES or INDICES"))?;
        let filter = match name("filter") {
            None => MeshoptFilter::None,
            Some(f) => MeshoptFilter::from_name(f).ok_or_else(|| {
                src.err(place(), format!("unknown filter {f:?} (NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL)"))
            })?,
        };
        let view_length = doc.views[i].length;
        if count.checked_mul(stride) != Some(view_length) {
            return Err(src.err(
                place(),
                format!("count {count} x byteStride {stride} must equal the view's byteLength {view_length}"),
            ));
        }
        let data = doc
            .buffers
            .get(buffer)
            .and_then(|b| b.get(offset..offset.checked_add(length)?))
            .ok_or_else(|| src.err(place(), format!("bytes {offset}..+{length} lie outside buffer {buffer}")))?;
        budget.charge(src, &place(), view_length as u64, || format!("bufferViews[{i}]: {view_length} bytes"))?;
        let bytes = meshopt::decode(data, count, stride, mode, filter)
            .map_err(|(at, what)| src.err(format!("{} {at} of its stream", place()), what))?;
        doc.buffers.push(Buffer { len: bytes.len(), bytes: Shared::from(bytes) });
        let stride = doc.views[i].stride;
        doc.views[i] = View { buffer: doc.buffers.len() - 1, offset: 0, length: view_length, stride };
    }
    Ok(())
}

fn load(src: Src, json: &Value, bin: Option<&[u8]>, options: &ReadOptions) -> Result<Mesh> {
    let (doc, mut budget) = open(src, json, bin.map(|b| Shared::from(b.to_vec())), options, 0)?;

    let mut mesh = Mesh::new();
    // POSITION accessor -> (first vertex id, vertex count).
    let mut vertex_base: HashMap<usize, (u32, usize)> = HashMap::new();
    // Per run of vertices (one per POSITION accessor, in order), the other attributes
    // of the primitive that brought it: kept where every run has them alike.
    let mut runs: Vec<Vec<Attribute>> = Vec::new();
    let mut indices: Vec<u32> = Vec::new();
    // Primitives may reuse accessors, so a small file could describe a huge mesh:
    // every accessor is charged to the budget before it is decoded (see
    // ReadOptions::max_decoded_bytes).
    for (m, jm) in array(src, json, "meshes")?.iter().enumerate() {
        let prims = match jm.get("primitives") {
            Some(Value::Array(a)) => a.as_slice(),
            _ => return Err(src.err(at("meshes", m), "'primitives' must be an array")),
        };
        for (p, prim) in prims.iter().enumerate() {
            let place = || format!("meshes[{m}].primitives[{p}]");
            let mode = uint(src, prim, "mode", &place)?.unwrap_or(4);
            if mode > 6 {
                return Err(src.err(place(), format!("unknown primitive mode {mode}")));
            }
            let Some(pos) = prim.pointer("/attributes/POSITION") else {
                return Err(src.err(place(), "the primitive has no POSITION attribute"));
            };
            let pos = pos.as_u64().ok_or_else(|| src.err(place(), "POSITION must be an accessor index"))? as usize;
            let (base, count) = match vertex_base.get(&pos) {
                Some(&bc) => bc,
                None => {
                    let base = mesh.positions.len();
                    let mut charge = |count: usize| {
                        budget
                            .charge(src, &place(), 12 * count as u64, || format!("accessors[{pos}]: {count} vertices"))
                    };
                    doc.read_positions(pos, &mut mesh.positions, &mut charge)?;
                    if quantized(&doc, pos) {
                        // KHR_mesh_quantization: the node drawing the mesh dequantizes.
                        if let Some(world) = nodes::world_of_mesh(json, m) {
                            for p in &mut mesh.positions[base..] {
                                *p = nodes::apply(&world, *p);
                            }
                        }
                    }
                    let count = mesh.positions.len() - base;
                    if mesh.positions.len() > u32::MAX as usize {
                        return Err(src.err(place(), "more than 4294967295 vertices in all"));
                    }
                    vertex_base.insert(pos, (base as u32, count));
                    runs.push(primitive::read_attributes(&doc, prim, count, &place, &mut budget)?);
                    (base as u32, count)
                }
            };
            if mode < 4 {
                continue; // points and lines: their vertices are kept, nothing to draw
            }
            read_primitive_indices(src, &doc, prim, &place, &mut budget, mode, (pos, count), &mut indices)?;
            for i in indices.iter_mut() {
                *i += base;
            }
            push_primitive_faces(src, &place, &mut mesh, mode, &indices)?;
        }
    }
    mesh.attributes = primitive::join_attributes(runs);
    Ok(mesh)
}

/// Whether accessor `a` (already read as positions) holds integers
/// (`KHR_mesh_quantization`).
fn quantized(doc: &Doc, a: usize) -> bool {
    doc.accessors[a].get("componentType").and_then(Value::as_u64) != Some(5126)
}

/// The bytes of mesh decoded so far, against [`ReadOptions::max_decoded_bytes`] (or,
/// by default, the limit relative to the asset's buffer bytes).
/// Reads the indices of a triangle primitive of `mode` (0..count without an accessor)
/// into `indices`, charging `budget` for the faces they will make, and checks them
/// against the `count` vertices of its POSITION accessor `pos` (and TRIANGLES for a
/// whole number of triangles).
#[allow(clippy::too_many_arguments)]
fn read_primitive_indices(
    src: Src,
    doc: &Doc,
    prim: &Value,
    place: &dyn Fn() -> String,
    budget: &mut Budget,
    mode: u64,
    (pos, count): (usize, usize),
    indices: &mut Vec<u32>,
) -> Result<()> {
    indices.clear();
    // A face per 3 indices (TRIANGLES) or up to one per index (strips and fans), 4 bytes
    // per face index and 4 per face offset.
    let face_bytes = |n: usize| -> u64 {
        let n = n as u64;
        if mode == 4 {
            4 * n + 4 * (n / 3)
        } else {
            16 * n.saturating_sub(2)
        }
    };
    match uint(src, prim, "indices", place)? {
        Some(acc) => {
            let mut charge =
                |n: usize| budget.charge(src, &place(), face_bytes(n), || format!("accessors[{acc}]: {n} indices"));
            doc.read_indices(acc as usize, indices, &mut charge)?;
            if let Some((k, &i)) = indices.iter().enumerate().find(|(_, &i)| i as usize >= count) {
                return Err(src.err(
                    place(),
                    format!("index {k} refers to vertex {i} but its POSITION accessor {pos} has {count} vertices"),
                ));
            }
        }
        None => {
            budget.charge(src, &place(), face_bytes(count), || {
                format!("POSITION accessors[{pos}] drawn without indices: {count} vertices")
            })?;
            indices.extend(0..count as u32)
        }
    }
    if mode == 4 && indices.len() % 3 != 0 {
        let source = match uint(src, prim, "indices", place)? {
            Some(acc) => format!("index accessor {acc}"),
            None => format!("POSITION accessor {pos} (no indices)"),
        };
        return Err(src.err(
            place(),
            format!(
                "TRIANGLES needs a multiple of 3 indices but {source} has {} ({} left over)",
                indices.len(),
                indices.len() % 3
            ),
        ));
    }
    Ok(())
}

/// Appends the faces a primitive of `mode` (4, 5 or 6) draws with `indices`, with the
/// winding the mode defines (degenerate strip and fan triangles skipped).
fn push_primitive_faces(
    src: Src,
    place: &dyn Fn() -> String,
    mesh: &mut Mesh,
    mode: u64,
    indices: &[u32],
) -> Result<()> {
    if mode == 4 {
        // A list's faces are its triples: sized once (strips and fans may hold
        // degenerate triangles, so they grow as they decode).
        mesh.face_indices.reserve(indices.len() / 3 * 3);
        mesh.face_offsets.reserve(indices.len() / 3);
    }
    let res = match mode {
        4 => indices.chunks_exact(3).try_for_each(|t| {
            mesh.face_indices.extend_from_slice(t);
            close_face(mesh)
        }),
        5 => push_strip_triangles(mesh, indices),
        _ => push_fan_triangles(mesh, indices),
    };
    res.map_err(|w| src.err(place(), w))
}

struct Budget {
    used: u64,
    limit: u64,
    /// Bytes of per-primitive charges ([`Budget::charge_primitive`]) the default limit
    /// still grants on top of `limit`, for those alone (decoded data never uses them).
    primitive_grant: u64,
    /// How the limit came about, for the message.
    rule: String,
}

impl Budget {
    /// [`Budget::new`] whose default limit (none set in `options`) also grants
    /// `scene_allowance` bytes, for what a scene holds per primitive
    /// ([`primitive::PRIMITIVE_BYTES`]).
    fn with_scene_allowance(options: &ReadOptions, buffer_bytes: u64, scene_allowance: u64) -> Budget {
        use super::{DECODED_BYTES_ALLOWANCE, DECODED_BYTES_PER_BUFFER_BYTE};
        match options.max_decoded_bytes {
            Some(limit) => Budget { used: 0, limit, primitive_grant: 0, rule: format!("the limit of {limit} bytes") },
            None => {
                let limit =
                    buffer_bytes.saturating_mul(DECODED_BYTES_PER_BUFFER_BYTE).saturating_add(DECODED_BYTES_ALLOWANCE);
                let scene = if scene_allowance > 0 {
                    format!(", and {scene_allowance} more for the first primitives of a scene")
                } else {
                    String::new()
                };
                Budget {
                    used: 0,
                    limit,
                    primitive_grant: scene_allowance,
                    rule: format!(
                        "the limit of {limit} bytes ({DECODED_BYTES_PER_BUFFER_BYTE} x the file's {buffer_bytes} \
                         buffer bytes + {DECODED_BYTES_ALLOWANCE}{scene}: the primitives reuse accessors far \
                         beyond what the data holds)"
                    ),
                }
            }
        }
    }

    /// Charges `bytes` held for one primitive, out of the primitives' grant while it
    /// lasts, then as [`Budget::charge`] does.
    fn charge_primitive(&mut self, src: Src, place: &str, bytes: u64, what: impl FnOnce() -> String) -> Result<()> {
        let granted = bytes.min(self.primitive_grant);
        self.primitive_grant -= granted;
        self.charge(src, place, bytes - granted, what)
    }

    /// Adds `bytes` of mesh to decode, or refuses at `place` when the total would
    /// exceed the limit; `what` names the data (called only for the message).
    fn charge(&mut self, src: Src, place: &str, bytes: u64, what: impl FnOnce() -> String) -> Result<()> {
        let total = self.used.saturating_add(bytes);
        if total > self.limit {
            return Err(src.err(
                place,
                format!(
                    "decoding {} would bring the mesh to {total} bytes, more than {}; \
                     ReadOptions::max_decoded_bytes (--max-memory on the command line) raises it",
                    what(),
                    self.rule
                ),
            ));
        }
        self.used = total;
        Ok(())
    }
}

impl Doc<'_> {
    /// The bytes of the asset's buffers, each distinct file or chunk counted once.
    fn buffer_bytes(&self) -> u64 {
        let mut distinct = HashSet::new();
        self.buffers.iter().filter(|b| distinct.insert(b.bytes.as_ptr())).map(|b| b.bytes.len() as u64).sum()
    }

    /// Validates accessor `i` and returns it with the bytes of its view.
    fn accessor(&self, i: usize) -> Result<(Accessor, &[u8], usize)> {
        let src = self.src;
        let place = || at("accessors", i);
        let a = self
            .accessors
            .get(i)
            .ok_or_else(|| src.err(place(), format!("no such accessor (the file has {})", self.accessors.len())))?;
        if a.get("sparse").is_some() {
            return Err(src.err(place(), "sparse accessors are not supported"));
        }
        let view = uint(src, a, "bufferView", &place)?
            .ok_or_else(|| src.err(place(), "accessors without a bufferView are not supported"))?
            as usize;
        let component = required(src, a, "componentType", &place)?;
        if ![5120, 5121, 5122, 5123, 5125, 5126].contains(&component) {
            return Err(src.err(place(), format!("unknown componentType {component}")));
        }
        let components = match a.get("type").and_then(Value::as_str) {
            Some("SCALAR") => 1,
            Some("VEC2") => 2,
            Some("VEC3") => 3,
            Some("VEC4") | Some("MAT2") => 4,
            Some("MAT3") => 9,
            Some("MAT4") => 16,
            _ => return Err(src.err(place(), "missing or unknown 'type'")),
        };
        let acc = Accessor {
            offset: uint(src, a, "byteOffset", &place)?.unwrap_or(0) as usize,
            count: required(src, a, "count", &place)? as usize,
            component,
            components,
        };
        let v = self.views.get(view).ok_or_else(|| {
            src.err(place(), format!("refers to bufferView {view} but the file has {}", self.views.len()))
        })?;
        let elem = acc.component_size() * components;
        if let Some(s) = v.stride.filter(|&s| s < elem) {
            // Elements would overlap: the file is wrong, not something to guess around.
            return Err(src.err(
                place(),
                format!("bufferView {view} has byteStride {s}, smaller than this accessor's {elem}-byte elements"),
            ));
        }
        let stride = v.stride.unwrap_or(elem);
        // The last element must end inside the view; checked before anything is allocated.
        let end = (acc.offset as u128) + (stride as u128) * (acc.count.saturating_sub(1) as u128) + elem as u128;
        if acc.count > 0 && end > v.length as u128 {
            return Err(src.err(
                place(),
                format!(
                    "{} elements of {elem} bytes (stride {stride}) from byte {} need {end} bytes but bufferView {view} has {} (truncated)",
                    acc.count, acc.offset, v.length
                ),
            ));
        }
        let bytes = &self.buffers[v.buffer][v.offset..v.offset + v.length];
        Ok((acc, bytes, stride))
    }

    /// Appends the positions of accessor `i`, calling `charge` with their count
    /// (checked against the accessor's view) before anything is allocated. FLOAT, or
    /// (`KHR_mesh_quantization`) BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT, normalized
    /// (to -1..1 or 0..1 as glTF defines it) or not (the integer as a float).
    fn read_positions(
        &self,
        i: usize,
        out: &mut Vec<[f32; 3]>,
        charge: &mut dyn FnMut(usize) -> Result<()>,
    ) -> Result<()> {
        let (acc, bytes, stride) = self.accessor(i)?;
        if acc.components != 3 || acc.component == 5125 {
            return Err(self.src.err(
                at("accessors", i),
                "POSITION must be a VEC3 of FLOAT, or of BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT \
                 (KHR_mesh_quantization)",
            ));
        }
        let normalized = self.accessors[i].get("normalized").and_then(Value::as_bool).unwrap_or(false);
        let size = acc.component_size();
        charge(acc.count)?;
        out.reserve(acc.count);
        for k in 0..acc.count {
            let o = acc.offset + k * stride;
            let mut p = [0.0f32; 3];
            for (c, slot) in p.iter_mut().enumerate() {
                let b = &bytes[o + size * c..o + size * (c + 1)];
                let v = match acc.component {
                    5126 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
                    component => dequantize(component, b, normalized),
                };
                if !v.is_finite() {
                    return Err(self
                        .src
                        .err(format!("accessors[{i}] element {k}"), format!("coordinate {v} is NaN or infinite")));
                }
                *slot = v;
            }
            out.push(p);
        }
        Ok(())
    }

    /// The elements of accessor `i` packed tightly (the view's stride removed), with
    /// the accessor; `charge` is called with their byte count before anything is
    /// allocated.
    fn read_packed(&self, i: usize, charge: &mut dyn FnMut(usize) -> Result<()>) -> Result<(Accessor, Vec<u8>)> {
        let (acc, bytes, stride) = self.accessor(i)?;
        let elem = acc.component_size() * acc.components;
        // The accessor's elements lie inside its view (checked): no overflow.
        charge(acc.count * elem)?;
        let mut out = Vec::with_capacity(acc.count * elem);
        for k in 0..acc.count {
            let o = acc.offset + k * stride;
            out.extend_from_slice(&bytes[o..o + elem]);
        }
        Ok((acc, out))
    }

    /// Appends the indices of accessor `i`, calling `charge` with their count first,
    /// as [`Doc::read_positions`] does.
    fn read_indices(&self, i: usize, out: &mut Vec<u32>, charge: &mut dyn FnMut(usize) -> Result<()>) -> Result<()> {
        let (acc, bytes, stride) = self.accessor(i)?;
        if acc.components != 1 || ![5121, 5123, 5125].contains(&acc.component) {
            return Err(self
                .src
                .err(at("accessors", i), "indices must be a SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT"));
        }
        charge(acc.count)?;
        out.reserve(acc.count);
        for k in 0..acc.count {
            let o = acc.offset + k * stride;
            out.push(match acc.component {
                5121 => bytes[o] as u32,
                5123 => u16::from_le_bytes([bytes[o], bytes[o + 1]]) as u32,
                _ => u32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]]),
            });
        }
        Ok(())
    }
}

/// The value of one integer component (`component` a glTF component type of 1 or 2
/// bytes, `b` its bytes): normalized as glTF defines it (signed types clamped at -1),
/// else the integer itself.
fn dequantize(component: u64, b: &[u8], normalized: bool) -> f32 {
    let (v, max) = match component {
        5120 => (b[0] as i8 as f32, 127.0),
        5121 => (b[0] as f32, 255.0),
        5122 => (i16::from_le_bytes([b[0], b[1]]) as f32, 32767.0),
        _ => (u16::from_le_bytes([b[0], b[1]]) as f32, 65535.0),
    };
    if normalized {
        (v / max).max(-1.0)
    } else {
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn base64_round_trips_every_length() {
        for n in 0..20 {
            let data: Vec<u8> = (0..n).map(|k| (k * 37 + 11) as u8).collect();
            assert_eq!(base64_decode(base64_encode(&data).as_bytes()).unwrap(), data);
        }
        assert_eq!(base64_encode(b"Man"), "TWFu");
        assert_eq!(base64_encode(b"Ma"), "TWE=");
        assert_eq!(base64_decode(b"TW!u"), Err(2));
    }

    #[test]
    fn strips_and_fans_become_triangles_with_their_winding() {
        let positions: Vec<[f32; 3]> = (0..5).map(|i| [i as f32, (i * i) as f32, 0.0]).collect();
        let bin: Vec<u8> = positions.iter().flatten().flat_map(|c| c.to_le_bytes()).collect();
        let idx: Vec<u8> = [0u8, 1, 2, 3, 3, 4, 0, 1, 2, 3].to_vec();
        let mut all = bin.clone();
        all.extend_from_slice(&idx);
        let json = json!({
            "asset": {"version": "2.0"},
            "buffers": [{"byteLength": all.len(), "uri": format!("data:application/gltf-buffer;base64,{}", base64_encode(&all))}],
            "bufferViews": [{"buffer": 0, "byteLength": 60}, {"buffer": 0, "byteOffset": 60, "byteLength": 10}],
            "accessors": [
                {"bufferView": 0, "componentType": 5126, "count": 5, "type": "VEC3"},
                {"bufferView": 1, "componentType": 5121, "count": 6, "type": "SCALAR"},
                {"bufferView": 1, "byteOffset": 6, "componentType": 5121, "count": 4, "type": "SCALAR"}
            ],
            "meshes": [{"primitives": [
                {"attributes": {"POSITION": 0}, "indices": 1, "mode": 5},
                {"attributes": {"POSITION": 0}, "indices": 2, "mode": 6},
                {"attributes": {"POSITION": 0}, "mode": 1}
            ]}]
        });
        let m = read_gltf(Path::new("t.gltf"), json.to_string().as_bytes(), &ReadOptions::default()).unwrap();
        assert_eq!(m.positions, positions);
        let faces: Vec<&[u32]> = m.faces().collect();
        // strip 0 1 2 3 3 4: (0,1,2) (2,1,3), rest degenerate; fan 0 1 2 3: (0,1,2) (0,2,3)
        assert_eq!(faces, vec![&[0, 1, 2][..], &[2, 1, 3], &[0, 1, 2], &[0, 2, 3]]);
    }
}

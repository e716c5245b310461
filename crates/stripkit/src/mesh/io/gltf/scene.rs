//! glTF scenes in and out: the whole document kept, its triangle primitives decoded,
//! and written back with the strips set on them (issue #15, items 2 and 7).
//!
//! [`Scene::read`] keeps the JSON document as it was read and the bytes of its buffers,
//! and decodes every triangle primitive (modes 4, 5 and 6) into a [`Mesh`]: POSITION,
//! every other vertex attribute with its type and `normalized` flag
//! ([`crate::Attribute`], glTF semantic names), the triangles, and one [`Group`] named
//! after the glTF mesh with the primitive's material. This file converts only:
//! stripping the primitives (`Scene::strip`, through the door) lives above the door in
//! [`crate::scene`], which sets each primitive's strips, the triangles they were
//! verified against and its vertex order; [`Scene::to_bytes`] and [`Scene::write`]
//! write the document back and check it against those.
//!
//! What changes in the written document, and nothing else:
//! - **Primitives.** Each stripped primitive becomes a `TRIANGLE_STRIP` (mode 5)
//!   primitive whose `indices` are its strips stitched by degenerate triangles: core
//!   glTF that every viewer draws. With [`SceneOptions::restart`](crate::scene::SceneOptions::restart) (the default) its mesh
//!   also gets an `EXT_mesh_primitive_restart` primitive group per stripped primitive:
//!   the group names that one primitive and an index accessor holding the strips
//!   separated by the restart value (65535 for `UNSIGNED_SHORT`, 4294967295 for
//!   `UNSIGNED_INT`). Viewers that read the extension draw one restart strip list,
//!   the others draw the stitched fallback. The extension is listed in
//!   `extensionsUsed`, never in `extensionsRequired`. Primitives with morph targets get
//!   no group (the extension forbids them): they keep the stitched strip only.
//!   The specification's example falls back to one primitive per strip, sharing the
//!   restart buffer's bytes; a stitched fallback costs a second index list instead,
//!   but keeps one draw call per primitive for viewers without the extension (bunny
//!   has 1,189 strips).
//! - **Vertex order.** With [`SceneOptions::reorder`](crate::scene::SceneOptions::reorder) (the default) each stripped
//!   primitive's vertices are renumbered in their first use by its strips and those the
//!   strips do not use are left out (meshoptimizer's `optimizeVertexFetch`): its
//!   attributes and morph targets get new accessors with the same properties, the
//!   values gathered in that order and `min` / `max` recomputed (an accessor only that
//!   primitive used keeps its number). Without it, or where an accessor is sparse,
//!   the strips use the primitive's own vertex ids and its vertex data is not touched.
//!   Skins and animations never change.
//! - **Accessors and buffer views** keep their numbers. When every extension the
//!   document uses is one known to name accessors only in the places read here
//!   (materials, texture transforms, lights, KTX2/WebP/AVIF textures, quantization,
//!   animation pointers, XMP; see `Scene::garbage`), an index accessor that only a
//!   stripped primitive used takes that primitive's stitched indices, a buffer view
//!   that only such accessors used takes the new indices, and the old index bytes are
//!   left out of the file. Otherwise (an unknown extension might name an accessor by
//!   number) everything is kept and the new accessors and one buffer view for all new
//!   indices are appended; the old index accessors stay, unreferenced.
//! - **Buffers** are merged into one: the buffer views' bytes one after the other
//!   (or, with an unknown extension, the old buffers whole), each at a 4-byte aligned
//!   offset, the views' `buffer` and `byteOffset` rewritten to match, then the new
//!   indices. In a `.glb` it is the binary chunk; in a `.gltf` a base64 `data:` URI,
//!   so external `.bin` files are embedded. Images keep their `uri` as written: an
//!   image file beside the input must sit beside the output too.
//!
//! Scenes, nodes and transforms, materials, textures, images, samplers, skins,
//! animations, cameras, `extras` and unknown extensions are written as read (object
//! keys come out sorted). Before bytes are returned they are read back: per primitive,
//! the decoded triangles (the stitched fallback and the restart group) must equal the
//! input's as oriented triangles, and the positions and every attribute must be the
//! same bytes, so every corner keeps its values.
//!
//! Reading follows [`ReadOptions`] (external buffers only from the asset's folder or
//! allowed roots, bounded by `byteLength`; every decoded accessor charged to the
//! decoded-bytes budget before it is allocated, and 16 KiB per triangle primitive for
//! what the scene holds for it besides its data, of which the default budget grants
//! 4,096 primitives' worth beyond its buffer-sized part). Every accessor a primitive
//! uses (attributes, skin joints and weights, morph targets) must have as many
//! elements as its POSITION. Sparse accessors and accessors without
//! a buffer view are refused in the primitives' vertex and index data (elsewhere they
//! pass through untouched). Extensions are checked as for every reader
//! (`gltf/extensions.rs`): Draco geometry wherever it is used, and required extensions
//! other than those read or carried through, are refused. `EXT_meshopt_compression`
//! views are decoded on reading and written plain (the extension left out), or, with
//! [`SceneOptions::compress`](crate::scene::SceneOptions::compress), compressed again
//! (`compress.rs`); `KHR_mesh_quantization` attributes are written as stored.

use super::primitive::{bounds, decode_primitive, vertex_accessors, ScenePrimitive, PRIMITIVE_BYTES};
use super::{array, at, glb_container, open, parse_glb, parse_json, Buffer, Doc, Shared, View};
use crate::error::{Error, Result};
use crate::mesh::io::common::Src;
use crate::mesh::io::{encode_checked, write_checked, Format, ReadOptions};
use crate::mesh::order::ids_of;
use crate::mesh::Mesh;
use crate::strip::{self, StripSet};
use serde_json::{json, Value};
use std::borrow::Cow;
use std::collections::{BTreeMap, HashMap, VecDeque};
use std::path::{Path, PathBuf};
use std::sync::Arc;

mod build;

use build::Build;

/// The extension that lets a strip primitive hold restart indices.
pub const RESTART_EXTENSION: &str = "EXT_mesh_primitive_restart";

/// The extension whose compressed buffer views are decoded on reading and written
/// back uncompressed.
const MESHOPT_EXTENSION: &str = "EXT_meshopt_compression";

/// What the default decoded-bytes budget of a scene grants beyond the buffer-sized
/// one for the memory held per triangle primitive ([`PRIMITIVE_BYTES`] each, charged
/// as each is read): 4,096 primitives. More must fit the buffer-sized budget, or
/// `ReadOptions::max_decoded_bytes` (`--max-memory`) be raised; an explicit limit
/// counts them too.
pub(crate) const PRIMITIVES_ALLOWANCE: u64 = 4096 * PRIMITIVE_BYTES;

/// A glTF document with its buffers and its triangle primitives decoded. Writing keeps
/// the document; only the stripped primitives' indices, modes and (reordered) vertex
/// accessors change, `EXT_mesh_primitive_restart` groups are added, and the buffers
/// are merged into one (the GLB binary chunk, or a `data:` URI in `.gltf`).
///
/// ```
/// use stripkit::io::{Format, ReadOptions};
/// use stripkit::scene::{Scene, SceneOptions};
/// use stripkit::{gen, StripOptions};
/// use std::path::Path;
///
/// // A scene (here made from a mesh; Scene::read takes a .gltf or .glb file).
/// let mut scene = Scene::from_mesh(&gen::icosphere(2))?;
/// // Every triangle primitive stripped through the door, each verified.
/// let report = scene.strip(&StripOptions::default(), &SceneOptions::default())?;
/// assert_eq!(report.triangles, 320);
/// assert!(report.indices_stitched < 3 * 320);
/// // Written (read back and checked first): a TRIANGLE_STRIP primitive with an
/// // EXT_mesh_primitive_restart group.
/// let glb = scene.to_bytes(Format::Glb)?;
/// let back = Scene::from_bytes(Path::new("out.glb"), Format::Glb, &glb, &ReadOptions::default())?;
/// assert_eq!(back.primitives()[0].mode, 5);
/// assert_eq!(back.primitives()[0].mesh.triangle_count(), 320);
/// # Ok::<(), stripkit::Error>(())
/// ```
#[derive(Clone)]
pub struct Scene {
    /// Names the file in errors.
    name: PathBuf,
    json: Value,
    buffers: Vec<Buffer>,
    views: Vec<View>,
    primitives: Vec<ScenePrimitive>,
    /// Whether stripped primitives get restart groups ([`Scene::set_restart_groups`]).
    restart_groups: bool,
    /// Whether index and vertex views are written compressed ([`Scene::set_compress`]).
    compress: bool,
    /// Threads for the read-back check of written strips ([`Scene::set_threads`]).
    threads: crate::parallel::Threads,
    notes: Vec<String>,
    /// Views whose bytes are left out of the buffer, made again from the primitives'
    /// meshes when the scene is encoded (a scene made from a mesh; `held.rs`).
    held: Vec<super::held::HeldView>,
    /// With `held`: the views as the document was made (buffer 0 whole).
    made_views: Vec<View>,
}

impl std::fmt::Debug for Scene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Scene")
            .field("name", &self.name)
            .field("buffers", &self.buffers.len())
            .field("primitives", &self.primitives)
            .finish_non_exhaustive()
    }
}

impl Scene {
    /// Reads a `.gltf` or `.glb` file (optionally `.gz`) with the default
    /// [`ReadOptions`].
    pub fn read(path: impl AsRef<Path>) -> Result<Scene> {
        Scene::read_with(path, &ReadOptions::default())
    }

    /// [`Scene::read`] with options (external buffers, budgets; see [`ReadOptions`]).
    pub fn read_with(path: impl AsRef<Path>, options: &ReadOptions) -> Result<Scene> {
        let path = path.as_ref();
        let format = scene_format(path)?;
        let raw = std::fs::read(path).map_err(|e| Error::Io { path: path.to_path_buf(), source: e })?;
        let data = if Format::from_path(path).is_some_and(|(_, gz)| gz) {
            super::super::gunzip(path, &raw, options.max_decompressed_bytes)?
        } else {
            raw
        };
        // A GLB's binary chunk is read in place, not copied beside the file's bytes.
        Scene::from_shared(path, format, &Arc::new(data), options)
    }

    /// Parses a scene held in memory (uncompressed) as `format` (`Gltf` or `Glb`);
    /// `path` names it in errors and locates external buffers.
    pub fn from_bytes(path: &Path, format: Format, data: &[u8], options: &ReadOptions) -> Result<Scene> {
        let src = Src { path };
        let (json, bin) = match format {
            Format::Glb => parse_glb(src, data)?,
            Format::Gltf => (parse_json(src, data.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(data), 0)?, None),
            other => return Err(Error::Invalid(format!("a scene is glTF or GLB, not {other:?}"))),
        };
        Scene::from_document(path, json, bin.map(|b| Shared::from(b.to_vec())), options, true)
    }

    /// [`Scene::from_bytes`] of bytes the scene may share: a GLB's binary chunk is
    /// read in place (its buffer a range of `data`), not copied. Once the scene and
    /// everything read from its buffers are gone, `data` is held by the caller alone.
    fn from_shared(path: &Path, format: Format, data: &Arc<Vec<u8>>, options: &ReadOptions) -> Result<Scene> {
        if !matches!(format, Format::Glb) {
            return Scene::from_bytes(path, format, data, options);
        }
        let (json, bin) = parse_glb(Src { path }, data)?;
        let bin = bin.map(|b| {
            let start = b.as_ptr() as usize - data.as_ptr() as usize;
            Shared::range(data, start..start + b.len())
        });
        Scene::from_document(path, json, bin, options, true)
    }

    /// The scene of a parsed document and its binary chunk (which buffer 0 holds as
    /// given, without a copy); without `faces` the
    /// primitives' faces are not decoded (a document made from a mesh, whose faces the
    /// caller sets).
    fn from_document(
        path: &Path,
        json: Value,
        bin: Option<Shared>,
        options: &ReadOptions,
        faces: bool,
    ) -> Result<Scene> {
        let src = Src { path };
        let (buffers, views, primitives) = {
            let (doc, mut budget) = open(src, &json, bin, options, PRIMITIVES_ALLOWANCE)?;
            let mut primitives = Vec::new();
            for (m, jm) in array(src, &json, "meshes")?.iter().enumerate() {
                let prims = match jm.get("primitives") {
                    Some(Value::Array(a)) => a.as_slice(),
                    _ => return Err(src.err(at("meshes", m), "'primitives' must be an array")),
                };
                for (p, prim) in prims.iter().enumerate() {
                    if let Some(sp) = decode_primitive(&doc, &json, m, p, prim, &mut budget, faces)? {
                        primitives.push(sp);
                    }
                }
            }
            (doc.buffers, doc.views, primitives)
        };
        Ok(Scene {
            name: path.to_path_buf(),
            json,
            buffers,
            views,
            primitives,
            restart_groups: true,
            compress: false,
            threads: crate::parallel::Threads::SERIAL,
            notes: Vec::new(),
            held: Vec::new(),
            made_views: Vec::new(),
        })
    }

    /// A scene of one mesh: one node, one glTF mesh, one TRIANGLES primitive per group
    /// that has faces, with its material (named after the group's), every attribute
    /// under its glTF semantic or as an application-specific `_NAME` one (see
    /// [`Scene::notes`] for those that glTF cannot take). A mesh of one group keeps
    /// its vertex ids; with several groups each primitive holds the vertices its faces
    /// use. Each primitive's [`ScenePrimitive::mesh`] keeps the group's polygons, so
    /// that [`Scene::strip`] may split quads as the algorithm chooses.
    pub fn from_mesh(mesh: &Mesh) -> Result<Scene> {
        Scene::from_mesh_with(mesh, &crate::mesh::io::Materials::default())
    }

    /// [`Scene::from_mesh`] with the materials of an OBJ's libraries
    /// ([`Materials::read_for_obj`](crate::mesh::io::Materials::read_for_obj)): each group's material that
    /// `materials` defines becomes a metallic-roughness material (base colour and alpha,
    /// roughness, base colour and normal textures embedded in the buffer); their notes
    /// join [`Scene::notes`].
    pub fn from_mesh_with(mesh: &Mesh, materials: &crate::mesh::io::Materials) -> Result<Scene> {
        let doc = super::from_mesh::mesh_document(mesh, materials)?;
        let options = ReadOptions::default().max_decoded_bytes(Some(u64::MAX));
        // The document is decoded as a file would be, without a GLB container around it.
        let mut scene =
            Scene::from_document(Path::new("<mesh as glTF>"), doc.json, Some(Shared::from(doc.bin)), &options, false)?;
        // Each primitive's mesh holds its positions and faces: their bytes leave the
        // buffer, to be made again when the scene is encoded (held.rs).
        if scene.buffers.len() == 1 && scene.primitives.len() == doc.group_of_primitive.len() {
            let (buffers, views) = super::held::compact(&scene.buffers, &scene.views, &doc.held);
            scene.made_views = std::mem::replace(&mut scene.views, views);
            scene.buffers = buffers;
            scene.held = doc.held;
        }
        for ((sp, &g), faces) in scene.primitives.iter_mut().zip(&doc.group_of_primitive).zip(doc.faces) {
            let (offsets, indices) = faces.unwrap_or_else(|| (mesh.face_offsets.clone(), mesh.face_indices.clone()));
            sp.mesh.face_offsets = offsets;
            sp.mesh.face_indices = indices;
            if let Some(group) = mesh.groups.get(g as usize) {
                sp.mesh.groups = vec![group.clone()];
            }
        }
        scene.notes = doc.notes;
        scene.notes.extend(materials.notes.iter().cloned());
        Ok(scene)
    }

    /// What could not be kept: attributes [`Scene::from_mesh`] did not write, and why.
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// The JSON document as read.
    pub fn json(&self) -> &Value {
        &self.json
    }

    /// The triangle primitives (modes 4, 5 and 6), in document order. Points and lines
    /// are not listed; they are written back unchanged.
    pub fn primitives(&self) -> &[ScenePrimitive] {
        &self.primitives
    }

    /// The document's primitives that are not listed in [`Scene::primitives`]: points
    /// and lines, written back unchanged.
    pub(crate) fn other_primitives(&self) -> usize {
        array_len(&self.json, "meshes", "primitives") - self.primitives.len()
    }

    /// For each triangle primitive, whether its vertices may be renumbered: its vertex
    /// accessors can be read back (none sparse) and no other triangle primitive names
    /// them. A vertex array several primitives share is kept as it is: each would get
    /// a first-use copy of its own and the shared original would stay behind, unused
    /// (four primitives over one 508-vertex array grew a file from 25,180 to 41,456
    /// bytes).
    pub(crate) fn renumberable(&self) -> Vec<bool> {
        let doc = self.doc();
        let lists: Vec<_> = self.primitives.iter().map(|sp| vertex_accessors(&self.json, sp)).collect();
        let mut users: HashMap<usize, usize> = HashMap::new();
        for (_, _, a) in lists.iter().flatten() {
            *users.entry(*a).or_default() += 1;
        }
        lists
            .iter()
            .map(|list| {
                list.iter().all(|(_, _, a)| {
                    users[a] == 1 && (self.is_held(*a) || doc.read_packed(*a, &mut |_| Ok(())).is_ok())
                })
            })
            .collect()
    }

    /// Whether accessor `a` reads a held-out view (plain data the scene made itself).
    fn is_held(&self, a: usize) -> bool {
        let view = self.json.pointer(&format!("/accessors/{a}/bufferView")).and_then(Value::as_u64);
        self.json.pointer(&format!("/accessors/{a}/sparse")).is_none()
            && view.is_some_and(|v| self.held.iter().any(|h| h.view == v as usize))
    }

    /// The triangle primitives, for the stripping above the door (`crate::scene`) to
    /// set each one's strips, the triangles they were verified against and its vertex
    /// order; the writer checks the written file against those.
    pub(crate) fn primitives_mut(&mut self) -> &mut [ScenePrimitive] {
        &mut self.primitives
    }

    /// Whether stripped primitives without morph targets get an
    /// `EXT_mesh_primitive_restart` group beside their stitched strip (set by the
    /// stripping above the door; `true` for a scene just read).
    pub(crate) fn set_compress(&mut self, on: bool) {
        self.compress = on;
    }

    pub(crate) fn set_restart_groups(&mut self, on: bool) {
        self.restart_groups = on;
    }

    /// Sets the threads the read-back check of the written strips may use (the same
    /// result at any count).
    pub(crate) fn set_threads(&mut self, threads: crate::parallel::Threads) {
        self.threads = threads;
    }

    /// The name of the file (or the stand-in name) the scene came from, for errors.
    pub(crate) fn name(&self) -> &Path {
        &self.name
    }

    /// The document as a `.glb` or `.gltf` file (`format`), read back and checked
    /// (every primitive's triangles, positions and attribute bytes decoded again and
    /// compared) before it is returned. Without [`Scene::strip`] the primitives are
    /// written as read (buffers merged).
    pub fn to_bytes(&self, format: Format) -> Result<Vec<u8>> {
        encode_checked(|| self.encode(format), |bytes| self.check_written(format, bytes))
    }

    /// [`Scene::to_bytes`] for a scene not needed afterwards: once encoded, what the
    /// check of the written bytes does not read (the buffers as read, the stripped
    /// primitives' faces and strips) is let go before the check reads the bytes back,
    /// so the file and its reading back are not held beside them. The same bytes.
    pub fn into_bytes(mut self, format: Format) -> Result<Vec<u8>> {
        // Encoding reads a stripped primitive's strips, not its faces, unless its held
        // index bytes are written again (a view garbage collection keeps): the faces
        // go first, so that they are not held beside the file being made.
        let garbage = self.garbage();
        let mut remade: Vec<usize> = (self.held.iter())
            .filter(|h| matches!(h.held, super::held::Held::Indices { .. }))
            .filter(|h| !garbage.collect || garbage.dead_views.binary_search(&h.view).is_err())
            .map(|h| h.primitive)
            .collect();
        remade.sort_unstable();
        for (k, sp) in self.primitives.iter_mut().enumerate() {
            if sp.strips.is_some() && remade.binary_search(&k).is_err() {
                free_faces(&mut sp.mesh);
            }
        }
        // Shared with the scene read back for the check, whose buffer 0 is its binary
        // chunk in place (no copy of it beside the file); held alone again afterwards.
        let bytes = Arc::new(self.encode(format)?);
        self.buffers = Vec::new();
        // The reference triangles go to the check, which sorts them in place (no
        // sorted copy beside them).
        let mut drawn = Vec::with_capacity(self.primitives.len());
        for sp in self.primitives.iter_mut() {
            drawn.push(sp.strips.is_some().then(|| std::mem::take(&mut sp.drawn)));
            if sp.strips.is_some() {
                sp.strips = Some(StripSet::new());
                free_faces(&mut sp.mesh);
            }
        }
        let (name, options) = read_back(format);
        let back = Scene::from_shared(&name, format, &bytes, &options)?;
        self.check_read_back(&name, back, drawn)?;
        Ok(Arc::try_unwrap(bytes).unwrap_or_else(|shared| shared.to_vec()))
    }

    /// Writes the scene to `path` (`.gltf` or `.glb`, optionally `.gz`), atomically,
    /// after the check of [`Scene::to_bytes`].
    pub fn write(&self, path: impl AsRef<Path>) -> Result<()> {
        let path = path.as_ref();
        let format = scene_format(path)?;
        write_checked(path, || self.encode(format), |bytes| self.check_written(format, bytes)).map(drop)
    }

    /// The document as `format` bytes, unchecked.
    fn encode(&self, format: Format) -> Result<Vec<u8>> {
        let (mut json, mut bin) = self.build()?;
        if self.compress {
            bin = super::compress::compress_views(&mut json, bin);
        }
        Ok(match format {
            Format::Glb => glb_container(&json, bin)?,
            Format::Gltf => {
                if let Some(b) = json.get_mut("buffers").and_then(|b| b.get_mut(0)) {
                    b["uri"] =
                        Value::String(format!("data:application/octet-stream;base64,{}", super::base64_encode(&bin)));
                }
                serde_json::to_vec(&json).map_err(|e| Error::Invalid(format!("cannot encode glTF JSON: {e}")))?
            }
            other => return Err(Error::Invalid(format!("a scene is written as glTF or GLB, not {other:?}"))),
        })
    }

    /// The JSON and the one binary buffer to write: the buffers merged, then the
    /// stripped primitives' reordered vertex data and new indices appended, their
    /// restart groups set, `extensionsUsed` brought up to date and the one buffer
    /// described.
    fn build(&self) -> Result<(Value, Vec<u8>)> {
        let mut out = Build::new(self);
        out.merge_buffers();
        let stripped: Vec<&ScenePrimitive> = self.primitives.iter().filter(|p| p.strips.is_some()).collect();
        if !stripped.is_empty() {
            // Reordered primitives: their vertex data gathered in the strips' order.
            // One reader for all of them (making one copies the views' list).
            let doc = self.doc_over(out.buffers.clone(), out.views.clone());
            let mut remapped: Vec<Option<StripSet>> = Vec::with_capacity(stripped.len());
            for sp in &stripped {
                remapped.push(match &sp.order {
                    Some(order) => Some(out.write_reordered(&doc, sp, order)?),
                    None => None,
                });
            }
            let groups = out.write_indices(&stripped, &remapped);
            out.write_restart_groups(&stripped, &groups);
        }
        out.list_restart_extension();
        out.drop_meshopt();
        Ok(out.finish())
    }

    /// What writing may drop: the index accessors only stripped primitives use
    /// (replaced in place by their stitched indices) and the buffer views only those
    /// use (their bytes left out). Nothing is dropped when the document uses an
    /// extension not known to name accessors only where [`Scene::garbage`] looks, or
    /// when nothing was stripped.
    fn garbage(&self) -> Garbage {
        let none = Garbage { collect: false, reused: Vec::new(), dead_views: Vec::new() };
        let known = |e: &str| {
            e.starts_with("KHR_materials_")
                || matches!(
                    e,
                    "KHR_texture_transform"
                        | "KHR_lights_punctual"
                        | "KHR_texture_basisu"
                        | "EXT_texture_webp"
                        | "EXT_texture_avif"
                        | "KHR_mesh_quantization"
                        | MESHOPT_EXTENSION
                        | "KHR_xmp_json_ld"
                        | "KHR_animation_pointer"
                        | RESTART_EXTENSION
                )
        };
        let used = self.json.get("extensionsUsed").and_then(Value::as_array);
        if used.is_some_and(|l| !l.iter().all(|e| e.as_str().is_some_and(known)))
            || self.primitives.iter().all(|p| p.strips.is_none())
        {
            return none;
        }
        let list = |v: &Value, key: &str| v.get(key).and_then(Value::as_array).cloned().unwrap_or_default();
        let n_acc = list(&self.json, "accessors").len();
        let mut other = vec![0u32; n_acc];
        let mut as_index = vec![0u32; n_acc];
        let count = |counts: &mut Vec<u32>, v: Option<&Value>| {
            if let Some(a) = v.and_then(Value::as_u64).filter(|&a| (a as usize) < n_acc) {
                counts[a as usize] += 1;
            }
        };
        for mesh in list(&self.json, "meshes") {
            for prim in list(&mesh, "primitives") {
                count(&mut as_index, prim.get("indices"));
                for a in prim.get("attributes").and_then(Value::as_object).into_iter().flat_map(|o| o.values()) {
                    count(&mut other, Some(a));
                }
                for t in list(&prim, "targets") {
                    for a in t.as_object().into_iter().flat_map(|o| o.values()) {
                        count(&mut other, Some(a));
                    }
                }
            }
            let groups = mesh.pointer(&format!("/extensions/{RESTART_EXTENSION}/primitiveGroups"));
            for g in groups.and_then(Value::as_array).into_iter().flatten() {
                count(&mut other, g.get("indices"));
            }
        }
        for skin in list(&self.json, "skins") {
            count(&mut other, skin.get("inverseBindMatrices"));
        }
        for anim in list(&self.json, "animations") {
            for s in list(&anim, "samplers") {
                count(&mut other, s.get("input"));
                count(&mut other, s.get("output"));
            }
        }
        let mut reused: Vec<usize> = self
            .primitives
            .iter()
            .filter(|p| p.strips.is_some())
            .filter_map(|p| self.json["meshes"][p.mesh_index]["primitives"][p.primitive_index]["indices"].as_u64())
            .map(|a| a as usize)
            .filter(|&a| a < n_acc && as_index[a] == 1 && other[a] == 0)
            .collect();
        for sp in self.primitives.iter().filter(|p| p.order.is_some()) {
            for (_, _, a) in vertex_accessors(&self.json, sp) {
                if a < n_acc && other[a] + as_index[a] == 1 {
                    reused.push(a);
                }
            }
        }
        reused.sort_unstable();
        reused.dedup();
        let n_views = self.views.len();
        let mut live = vec![false; n_views];
        let mut candidate = vec![false; n_views];
        for (a, acc) in list(&self.json, "accessors").iter().enumerate() {
            let refs = [
                acc.get("bufferView"),
                acc.pointer("/sparse/indices/bufferView"),
                acc.pointer("/sparse/values/bufferView"),
            ];
            for v in refs.into_iter().flatten().filter_map(Value::as_u64).map(|v| v as usize).filter(|&v| v < n_views) {
                if reused.binary_search(&a).is_ok() {
                    candidate[v] = true;
                } else {
                    live[v] = true;
                }
            }
        }
        for image in list(&self.json, "images") {
            if let Some(v) = image.get("bufferView").and_then(Value::as_u64).filter(|&v| (v as usize) < n_views) {
                live[v as usize] = true;
            }
        }
        let dead_views = (0..n_views).filter(|&v| candidate[v] && !live[v]).collect();
        Garbage { collect: true, reused, dead_views }
    }

    /// Reads `bytes` back and compares every primitive with this scene's.
    fn check_written(&self, format: Format, bytes: &[u8]) -> Result<()> {
        let (name, options) = read_back(format);
        let back = Scene::from_bytes(&name, format, bytes, &options)?;
        self.check_read_back(&name, back, Vec::new())
    }

    /// Compares every primitive of `back`, the written bytes read back (under the name
    /// and options of [`read_back`]), with this scene's; per primitive, its reference
    /// triangles are taken out of the scene where `drawn` has them (`None` or missing:
    /// the scene's own). `back` is let go of before this returns.
    fn check_read_back(&self, name: &Path, mut back: Scene, mut drawn: Vec<Option<Vec<[u32; 3]>>>) -> Result<()> {
        let fail = |sp: &ScenePrimitive, what: String| {
            Error::Verification(format!(
                "{}, read back: meshes[{}].primitives[{}]: {what}",
                name.display(),
                sp.mesh_index,
                sp.primitive_index
            ))
        };
        if back.primitives.len() != self.primitives.len() {
            return Err(Error::Verification(format!(
                "{}, read back: {} triangle primitives instead of {}",
                name.display(),
                back.primitives.len(),
                self.primitives.len()
            )));
        }
        // Taken out of the scene read back, so that each one's data can go as soon as
        // it has been compared.
        let mut back_primitives = std::mem::take(&mut back.primitives);
        let doc = back.doc();
        // Each primitive's restart group in the written document: the first group of
        // its mesh naming that primitive alone (looked up once, not per primitive).
        let mut written_groups: HashMap<(usize, usize), &Value> = HashMap::new();
        for (m, mesh) in back.json.get("meshes").and_then(Value::as_array).into_iter().flatten().enumerate() {
            let groups = mesh.pointer(&format!("/extensions/{RESTART_EXTENSION}/primitiveGroups"));
            for g in groups.and_then(Value::as_array).into_iter().flatten() {
                if let Some([p]) = g.get("primitives").and_then(Value::as_array).map(Vec::as_slice) {
                    if let Some(p) = p.as_u64() {
                        written_groups.entry((m, p as usize)).or_insert(g);
                    }
                }
            }
        }
        for (k, (a, b)) in self.primitives.iter().zip(back_primitives.iter_mut()).enumerate() {
            if (a.mesh_index, a.primitive_index) != (b.mesh_index, b.primitive_index) {
                return Err(fail(
                    a,
                    format!("came back as meshes[{}].primitives[{}]", b.mesh_index, b.primitive_index),
                ));
            }
            // With reordering, the written vertices are the input's in `order` (the
            // positions compared in place: no reordered copy of them).
            let (same_positions, attributes) = match &a.order {
                None => (a.mesh.positions == b.mesh.positions, Cow::Borrowed(&a.mesh.attributes)),
                Some(order) => (
                    order.len() == b.mesh.positions.len()
                        && order.iter().zip(&b.mesh.positions).all(|(&v, p)| a.mesh.positions[v as usize] == *p),
                    Cow::Owned(a.mesh.attributes.iter().map(|x| x.gather(order)).collect::<Vec<_>>()),
                ),
            };
            if !same_positions {
                return Err(fail(a, "positions differ".into()));
            }
            if *attributes != b.mesh.attributes {
                return Err(fail(a, "vertex attributes differ".into()));
            }
            drop((std::mem::take(&mut b.mesh.positions), std::mem::take(&mut b.mesh.attributes), attributes));
            let got = take_triangles(&mut b.mesh);
            if a.strips.is_none() {
                let want = a.mesh.triangulate().tris;
                if want != got {
                    return Err(fail(a, "the triangles of a primitive written as read differ".into()));
                }
                continue;
            }
            let taken = drawn.get_mut(k).and_then(Option::take);
            let want: Cow<[[u32; 3]]> = match (&a.order, taken) {
                (None, None) => Cow::Borrowed(&a.drawn),
                (None, Some(list)) => Cow::Owned(list),
                (Some(order), taken) => {
                    let new_id = ids_of(order, a.mesh.vertex_count());
                    Cow::Owned(match taken {
                        Some(mut list) => {
                            list.iter_mut().for_each(|t| *t = t.map(|v| new_id[v as usize]));
                            list
                        }
                        None => a.drawn.iter().map(|t| t.map(|v| new_id[v as usize])).collect(),
                    })
                }
            };
            // Sorted once for both checks below.
            let want = match want {
                Cow::Borrowed(list) => strip::sorted_expected(list, self.threads),
                Cow::Owned(list) => strip::sorted_expected_owned(list, self.threads),
            };
            let v = strip::compare_sorted(&want, got, self.threads);
            if !v.ok() {
                return Err(fail(a, format!("stitched strip: {v}")));
            }
            let group = written_groups.get(&(b.mesh_index, b.primitive_index));
            let expect_group = self.restart_groups && a.targets == 0;
            match (group, expect_group) {
                (Some(g), true) => {
                    let acc = g["indices"].as_u64().ok_or_else(|| fail(a, "restart group without indices".into()))?;
                    let mut list = Vec::new();
                    doc.read_indices(acc as usize, &mut list, &mut |_| Ok(()))?;
                    let n = a.order.as_ref().map_or(a.mesh.vertex_count(), Vec::len);
                    let restart = if n >= u16::MAX as usize { u32::MAX } else { u16::MAX as u32 };
                    if list.iter().any(|&i| i != restart && i as usize >= n) {
                        return Err(fail(a, "restart indices out of range".into()));
                    }
                    // Decoded straight from the list (no strip set of it in between).
                    let mut decoded = Vec::with_capacity(list.len());
                    for s in list.split(|&i| i == restart) {
                        strip::for_each_triangle(s, |t| decoded.push(t));
                    }
                    drop(list);
                    let v = strip::compare_sorted(&want, decoded, self.threads);
                    if !v.ok() {
                        return Err(fail(a, format!("restart group: {v}")));
                    }
                }
                (None, false) => {}
                (Some(_), false) => return Err(fail(a, "a restart group where none belongs".into())),
                (None, true) => return Err(fail(a, "its restart group is missing".into())),
            }
        }
        Ok(())
    }

    /// A reader over the scene's own buffers.
    fn doc(&self) -> Doc<'_> {
        self.doc_over(self.buffers.clone(), self.views.clone())
    }

    /// A reader of this scene's accessors over `buffers` and `views` (the scene's own,
    /// or the merged ones of a file being built).
    fn doc_over(&self, buffers: Vec<Buffer>, views: Vec<View>) -> Doc<'_> {
        Doc {
            src: Src { path: &self.name },
            buffers,
            views,
            accessors: self.json.get("accessors").and_then(Value::as_array).map_or(&[], Vec::as_slice),
        }
    }
}

/// Lets a mesh's faces go (its positions and attributes stay).
fn free_faces(mesh: &mut Mesh) {
    mesh.face_offsets = vec![0];
    mesh.face_indices = Vec::new();
    mesh.face_groups = Vec::new();
}

/// The faces of a mesh read back, as triangles, taken out of it: where every face is
/// a triangle (strips read back) the offsets go first and the indices are regrouped,
/// so at most the indices and the triangles are alive at once; otherwise
/// [`Mesh::triangulate`].
fn take_triangles(mesh: &mut Mesh) -> Vec<[u32; 3]> {
    if !mesh.face_offsets.windows(2).all(|w| w[1].wrapping_sub(w[0]) == 3) {
        return mesh.triangulate().tris;
    }
    drop(std::mem::take(&mut mesh.face_offsets));
    let mut indices = std::mem::take(&mut mesh.face_indices);
    // Taken from the end a part at a time, the list shrunk after each part, so that
    // the list and the triangles are not both held whole (53 MB each on 4.4M
    // triangles); the triangles come out reversed and are turned round at the end.
    const PART: usize = 3 << 18;
    let mut tris = Vec::with_capacity(indices.len() / 3);
    while !indices.is_empty() {
        let start = indices.len().saturating_sub(PART);
        tris.extend(indices[start..].chunks_exact(3).rev().map(|c| [c[0], c[1], c[2]]));
        indices.truncate(start);
        indices.shrink_to_fit();
    }
    tris.reverse();
    tris
}

/// The name the written bytes go by in the messages of their check, and the options
/// they are read back with: the input was accepted under the caller's budget, and the
/// output decodes to the same.
fn read_back(format: Format) -> (PathBuf, ReadOptions) {
    let name = PathBuf::from(format!("the {format:?} bytes to be written"));
    (name, ReadOptions::default().max_decoded_bytes(Some(u64::MAX)))
}

/// See [`Scene::garbage`].
struct Garbage {
    /// Whether views are copied one by one, leaving out the dead ones' bytes.
    collect: bool,
    /// Old index accessors (sorted) whose numbers the stitched indices take.
    reused: Vec<usize>,
    /// Views (sorted) only reused accessors referred to.
    dead_views: Vec<usize>,
}

/// The scene format a path names.
fn scene_format(path: &Path) -> Result<Format> {
    match Format::from_path(path) {
        Some((f @ (Format::Gltf | Format::Glb), _)) => Ok(f),
        _ => Err(Error::Invalid(format!("{}: a scene is a .gltf or .glb file", path.display()))),
    }
}

/// The number of `inner` entries of all `outer` entries (primitives of all meshes).
fn array_len(json: &Value, outer: &str, inner: &str) -> usize {
    json.get(outer)
        .and_then(Value::as_array)
        .map_or(0, |l| l.iter().map(|m| m.get(inner).and_then(Value::as_array).map_or(0, Vec::len)).sum())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::SceneOptions;
    use crate::StripOptions;

    fn stripped() -> Scene {
        let mut scene = Scene::from_mesh(&crate::gen::icosphere(2)).unwrap();
        let report = scene.strip(&StripOptions::default(), &SceneOptions::default()).unwrap();
        assert_eq!(report.triangles, 320);
        scene
    }

    /// The check reads a GLB's binary chunk in place: the buffer read back is a range of
    /// the written bytes, and once the check is over the bytes are held by the caller
    /// alone (so `into_bytes` hands back the same allocation, without a copy).
    #[test]
    fn the_read_back_shares_the_binary_chunk_and_lets_it_go() {
        let scene = stripped();
        let bytes = Arc::new(scene.encode(Format::Glb).unwrap());
        let (name, options) = read_back(Format::Glb);
        let back = Scene::from_shared(&name, Format::Glb, &bytes, &options).unwrap();
        let chunk = back.buffers[0].as_ptr() as usize - bytes.as_ptr() as usize;
        assert_eq!(chunk, 12 + 8 + u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize + 8);
        assert_eq!(back.buffers[0].len(), bytes.len() - chunk);
        assert_eq!(Arc::strong_count(&bytes), 2);
        scene.check_read_back(&name, back, Vec::new()).unwrap();
        assert_eq!(Arc::strong_count(&bytes), 1);
        // The same bytes by either write path.
        let want = scene.to_bytes(Format::Glb).unwrap();
        assert_eq!(*bytes, want);
        assert_eq!(scene.into_bytes(Format::Glb).unwrap(), want);
    }

    /// A wrong index in the written bytes is caught by the check reading the chunk in
    /// place, as by the one reading a copy.
    #[test]
    fn a_wrong_index_in_the_shared_chunk_is_caught() {
        let scene = stripped();
        let mut bytes = scene.encode(Format::Glb).unwrap();
        let (json, bin) = parse_glb(Src { path: Path::new("x.glb") }, &bytes).unwrap();
        let chunk = bin.unwrap().as_ptr() as usize - bytes.as_ptr() as usize;
        let prim = &json["meshes"][0]["primitives"][0];
        assert_eq!(prim["mode"], 5);
        let accessor = &json["accessors"][prim["indices"].as_u64().unwrap() as usize];
        assert_eq!(accessor["componentType"], 5123);
        let view = &json["bufferViews"][accessor["bufferView"].as_u64().unwrap() as usize];
        let at = chunk
            + view.get("byteOffset").and_then(Value::as_u64).unwrap_or(0) as usize
            + accessor.get("byteOffset").and_then(Value::as_u64).unwrap_or(0) as usize;
        // 162 vertices: flipping the lowest bit keeps the index in range.
        bytes[at] ^= 1;
        let bytes = Arc::new(bytes);
        let (name, options) = read_back(Format::Glb);
        let back = Scene::from_shared(&name, Format::Glb, &bytes, &options).unwrap();
        let err = scene.check_read_back(&name, back, Vec::new()).unwrap_err();
        assert!(matches!(err, Error::Verification(_)), "{err}");
        assert!(err.to_string().contains("read back: meshes[0].primitives[0]"), "{err}");
        let err = scene.check_written(Format::Glb, &bytes).unwrap_err();
        assert!(matches!(err, Error::Verification(_)), "{err}");
    }
}

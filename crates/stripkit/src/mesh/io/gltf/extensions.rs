//! Which glTF extensions the reader accepts: the one place that decides, for every
//! command (a mesh read by `stats` or converted to PLY, a scene stripped glTF to
//! glTF), so that a file is read by all of them or refused by all of them.
//!
//! - An extension that stores geometry in a form the reader does not decode
//!   ([`GEOMETRY`]: Draco, and `KHR_meshopt_compression`, whose version 1 vertex codec
//!   is not decoded) is refused wherever the file uses it: a primitive carrying a
//!   Draco block, a buffer view carrying a compressed block, or the extension listed as
//!   required (or, for `KHR_meshopt_compression`, as used). Reading past them would
//!   decode the uncompressed fallback (often absent or zeros) and write the stale
//!   block back pointing at old data.
//! - `EXT_meshopt_compression` is decoded: its buffer views are decompressed when the
//!   file is opened (`decode_compressed_views` in `mod.rs`) and a scene writes them
//!   back plain, the extension left out. `KHR_mesh_quantization` is read: integer
//!   positions are dequantized for the mesh, and a scene writes every attribute back
//!   as stored.
//! - A required extension must be one the reader knows to leave the geometry as
//!   plain accessors ([`CARRIED`], and every `KHR_materials_*`): those are carried
//!   through as written. Any other required extension is refused, named.
//! - Extensions that are only used (not required) and carry no geometry are ignored
//!   by the mesh reader and written back as read by the scene writer.

use super::{array, at};
use crate::error::Result;
use crate::mesh::io::common::Src;
use serde_json::Value;

/// Extensions that hold compressed geometry the reader does not decode.
const GEOMETRY: [&str; 2] = ["KHR_draco_mesh_compression", "KHR_meshopt_compression"];

/// Required extensions the reader honours: quantized attributes and meshopt-compressed
/// views (decoded), and those that leave vertex and index data plain accessors:
/// materials, textures, lights, instancing and metadata, carried through as written
/// (besides every `KHR_materials_*`).
const CARRIED: [&str; 11] = [
    "KHR_mesh_quantization",
    "EXT_meshopt_compression",
    "KHR_texture_transform",
    "KHR_texture_basisu",
    "KHR_lights_punctual",
    "EXT_texture_webp",
    "EXT_texture_avif",
    "EXT_mesh_gpu_instancing",
    "KHR_xmp_json_ld",
    "KHR_animation_pointer",
    super::scene::RESTART_EXTENSION,
];

/// Whether the reader can read a file requiring `name` (see the module's text).
pub(crate) fn carried(name: &str) -> bool {
    name.starts_with("KHR_materials_") || CARRIED.contains(&name)
}

/// Refuses a document that uses an extension the reader cannot honour, naming the
/// extension and where it is used (a primitive, a buffer view, `extensionsRequired`
/// or `extensionsUsed`). Called before anything is decoded, by every reader.
pub(crate) fn check(src: Src, json: &Value) -> Result<()> {
    let has = |v: &Value, name: &str| v.get("extensions").and_then(|e| e.get(name)).is_some();
    let meshes = array(src, json, "meshes")?;
    for (m, mesh) in meshes.iter().enumerate() {
        let prims = mesh.get("primitives").and_then(Value::as_array).map(Vec::as_slice).unwrap_or_default();
        for (p, prim) in prims.iter().enumerate() {
            if let Some(ext) = GEOMETRY.into_iter().find(|e| has(prim, e)) {
                return Err(src.err(
                    format!("meshes[{m}].primitives[{p}]"),
                    format!("its geometry is stored with {ext}, which stripkit does not decode"),
                ));
            }
        }
    }
    for (v, view) in array(src, json, "bufferViews")?.iter().enumerate() {
        if let Some(ext) = GEOMETRY.into_iter().find(|e| has(view, e)) {
            return Err(src.err(
                at("bufferViews", v),
                format!("its bytes are compressed with {ext}, which stripkit does not decode"),
            ));
        }
    }
    for ext in array(src, json, "extensionsRequired")?.iter() {
        let name = ext.as_str().unwrap_or_default();
        if GEOMETRY.contains(&name) {
            return Err(src.err(
                "extensionsRequired",
                format!("the file requires extension {ext}, which stores geometry in a way stripkit does not read"),
            ));
        }
        if !carried(name) {
            return Err(src.err(
                "extensionsRequired",
                format!("the file requires extension {ext}, which stripkit does not read"),
            ));
        }
    }
    if let Some(ext) = array(src, json, "extensionsUsed")?
        .iter()
        .filter_map(Value::as_str)
        .find(|e| *e == "KHR_meshopt_compression")
    {
        return Err(src.err(
            "extensionsUsed",
            format!("the file uses {ext}, whose compressed buffer views stripkit does not rewrite"),
        ));
    }
    Ok(())
}

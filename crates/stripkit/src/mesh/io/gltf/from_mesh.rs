//! A [`Mesh`] with attributes and groups as a glTF document: one mesh, one node, one
//! TRIANGLES primitive per group (with its material, named after the group's), every
//! primitive drawing from the same vertex accessors. [`super::Scene::from_mesh`] makes
//! a scene of it, so that each group is stripped on its own.
//!
//! Attributes go out under their glTF semantics when their shape fits one (`NORMAL`
//! VEC3, `TANGENT` VEC4, `TEXCOORD_n` VEC2, `COLOR_n` VEC3/VEC4, `JOINTS_n` VEC4 of
//! unsigned bytes or shorts, `WEIGHTS_n` VEC4): normalized unsigned bytes and shorts
//! are kept where glTF allows them, anything else becomes FLOAT. Other attributes
//! (a PLY `quality`, or a standard name of the wrong shape) become application-specific
//! attributes, `_` and the name in capitals (`_QUALITY`), in their own type where glTF
//! has it (FLOAT, BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT), as FLOAT otherwise.
//! Attributes of more than 4 components, or whose glTF name another attribute already
//! took, are dropped and named in the notes. Every vertex element is padded to 4 bytes
//! (`byteStride`), as glTF asks of vertex attributes.

use super::held::{fan, Held, HeldView};
use crate::error::{Error, Result};
use crate::mesh::io::mtl::{Material, Materials, Texture};
use crate::mesh::{Attribute, Mesh, Scalar};
use serde_json::{json, Map, Value};

/// The glTF document of a mesh (JSON and binary buffer), and per primitive the group
/// it holds.
pub(super) struct MeshDocument {
    pub json: Value,
    pub bin: Vec<u8>,
    pub group_of_primitive: Vec<u32>,
    /// Per primitive its polygon faces (offsets, indices), over its own vertices;
    /// `None` for the one primitive of a mesh of one group (the mesh's own faces).
    pub faces: Vec<Option<(Vec<u32>, Vec<u32>)>>,
    /// Each primitive's positions and indices views, which its decoded mesh holds
    /// again (`held.rs`).
    pub held: Vec<HeldView>,
    /// Attributes dropped, each with the reason.
    pub notes: Vec<String>,
}

/// An attribute as written: its glTF name, scalar type, normalized flag and bytes.
type Form = (String, Scalar, bool, Vec<u8>);

/// A NORMAL (or TANGENT's xyz) as glTF wants it: unit vectors, as `f32`. Vectors off
/// unit length (a PLY's `nx ny nz` need not be) are rescaled and counted; a zero or
/// non-finite one cannot be, so `None`: the attribute then goes out under its own
/// `_NAME`, unchanged.
fn unit_vectors(a: &Attribute) -> Option<(Vec<u8>, usize)> {
    let comps = a.components as usize;
    let mut data = Vec::with_capacity(a.len() * comps * 4);
    let mut rescaled = 0;
    for v in 0..a.len() {
        let x = [a.get(v, 0), a.get(v, 1), a.get(v, 2)];
        let len = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
        if !(len.is_finite() && len > 1e-12) {
            return None;
        }
        // The validator's tolerance is 0.0005; rescale only what it would reject.
        let scale = if (len - 1.0).abs() > 1e-4 {
            rescaled += 1;
            1.0 / len
        } else {
            1.0
        };
        for c in 0..comps {
            let value = if c < 3 { a.get(v, c) * scale } else { a.get(v, c) };
            data.extend_from_slice(&(value as f32).to_le_bytes());
        }
    }
    Some((data, rescaled))
}

/// The glTF name, scalar type, normalized flag and little-endian values of an
/// attribute, or why it cannot be written; and a note on a repair made on the way.
fn gltf_form(a: &Attribute) -> std::result::Result<(Form, Option<String>), String> {
    let comps = a.components as usize;
    if (a.name == "NORMAL" && comps == 3) || (a.name == "TANGENT" && comps == 4) {
        if let Some((data, rescaled)) = unit_vectors(a) {
            let note = (rescaled > 0).then(|| {
                format!("{rescaled} of {} {} vectors rescaled to unit length, as glTF requires", a.len(), a.name)
            });
            return Ok(((a.name.clone(), Scalar::F32, false, data), note));
        }
        let note =
            format!("{} holds a zero or non-finite vector, which glTF does not allow: written as _{}", a.name, a.name);
        let renamed = Attribute { name: format!("_{}", a.name), ..a.clone() };
        return gltf_form(&renamed).map(|(form, _)| (form, Some(note)));
    }
    gltf_plain_form(a).map(|form| (form, None))
}

/// [`gltf_form`] for everything but unit vectors.
fn gltf_plain_form(a: &Attribute) -> std::result::Result<Form, String> {
    let comps = a.components as usize;
    let numbered =
        |p: &str| a.name.strip_prefix(p).is_some_and(|r| !r.is_empty() && r.bytes().all(|b| b.is_ascii_digit()));
    let unorm = matches!(a.scalar, Scalar::U8 | Scalar::U16) && a.normalized;
    let raw = || (a.name.clone(), a.scalar, a.normalized, a.data.clone());
    let float = |name: String| {
        let mut data = Vec::with_capacity(a.len() * comps * 4);
        for v in 0..a.len() {
            for c in 0..comps {
                data.extend_from_slice(&(a.get(v, c) as f32).to_le_bytes());
            }
        }
        (name, Scalar::F32, false, data)
    };
    Ok(match a.name.as_str() {
        _ if numbered("TEXCOORD_") && comps == 2 => {
            if unorm {
                raw()
            } else {
                float(a.name.clone())
            }
        }
        _ if numbered("COLOR_") && (comps == 3 || comps == 4) => {
            if unorm {
                raw()
            } else {
                float(a.name.clone())
            }
        }
        _ if numbered("WEIGHTS_") && comps == 4 => {
            if unorm {
                raw()
            } else {
                float(a.name.clone())
            }
        }
        _ if numbered("JOINTS_") && comps == 4 && matches!(a.scalar, Scalar::U8 | Scalar::U16) && !a.normalized => {
            raw()
        }
        _ => {
            if comps > 4 {
                return Err(format!("attribute {} has {comps} components; glTF takes at most 4", a.name));
            }
            let name =
                if a.name.starts_with('_') { a.name.clone() } else { format!("_{}", a.name.to_ascii_uppercase()) };
            match a.scalar {
                Scalar::F32 | Scalar::I8 | Scalar::U8 | Scalar::I16 | Scalar::U16 => {
                    (name, a.scalar, a.normalized, a.data.clone())
                }
                _ => float(name),
            }
        }
    })
}

fn component_type(s: Scalar) -> u32 {
    match s {
        Scalar::I8 => 5120,
        Scalar::U8 => 5121,
        Scalar::I16 => 5122,
        Scalar::U16 => 5123,
        Scalar::U32 => 5125,
        _ => 5126,
    }
}

fn type_name(components: usize) -> &'static str {
    ["SCALAR", "VEC2", "VEC3", "VEC4"][components - 1]
}

/// Appends a vertex buffer view of `count` elements of `elem` bytes each (padded to
/// 4 bytes) and returns its index.
fn vertex_view(bin: &mut Vec<u8>, views: &mut Vec<Value>, data: &[u8], elem: usize) -> usize {
    let start = bin.len();
    let stride = elem.next_multiple_of(4);
    for e in data.chunks_exact(elem) {
        bin.extend_from_slice(e);
        bin.resize(bin.len() + stride - elem, 0);
    }
    let mut v = json!({"buffer": 0, "byteOffset": start, "byteLength": bin.len() - start, "target": 34962});
    if stride != elem {
        v["byteStride"] = stride.into();
    }
    views.push(v);
    views.len() - 1
}

/// The faces of group `g` over the vertices they use (kept in their order), or `None`
/// when the group has no face.
fn part(mesh: &Mesh, g: u32) -> Option<Mesh> {
    let faces: Vec<u32> = (0..mesh.face_count() as u32).filter(|&f| mesh.group_of(f as usize) == g).collect();
    if faces.is_empty() {
        return None;
    }
    let (mut out, _) = mesh.submesh(&faces);
    out.groups = mesh.groups.get(g as usize).cloned().into_iter().collect();
    Some(out)
}

/// Refuses a mesh of more than [`MAX_GLTF_VERTEX_ATTRIBUTES`](crate::mesh::io::MAX_GLTF_VERTEX_ATTRIBUTES)
/// attributes before any accessor is built (each is an accessor of its own).
pub(super) fn check_attribute_count(mesh: &Mesh) -> Result<()> {
    let limit = crate::mesh::io::MAX_GLTF_VERTEX_ATTRIBUTES;
    if mesh.attributes.len() > limit {
        return Err(Error::Invalid(format!(
            "the mesh has {} vertex attributes besides its positions; glTF output takes at most {limit} \
             (each is an accessor of its own): write PLY to keep them all",
            mesh.attributes.len()
        )));
    }
    Ok(())
}

/// The vertex accessors of `mesh` (POSITION first), as a primitive's `attributes`;
/// attributes that cannot be written are named in `notes`.
pub(super) fn write_vertices(
    mesh: &Mesh,
    bin: &mut Vec<u8>,
    views: &mut Vec<Value>,
    accessors: &mut Vec<Value>,
    notes: &mut Vec<String>,
) -> Map<String, Value> {
    let nv = mesh.vertex_count();
    let pos: Vec<u8> = mesh.positions.iter().flatten().flat_map(|c| c.to_le_bytes()).collect();
    let view = vertex_view(bin, views, &pos, 12);
    let (lo, hi) = mesh.bounds().unwrap_or(([0.0; 3], [0.0; 3]));
    accessors
        .push(json!({"bufferView": view, "componentType": 5126, "count": nv, "type": "VEC3", "min": lo, "max": hi}));
    let mut attributes = Map::new();
    attributes.insert("POSITION".into(), (accessors.len() - 1).into());
    for a in &mesh.attributes {
        let (name, scalar, normalized, data) = match gltf_form(a) {
            Ok((f, note)) => {
                notes.extend(note);
                f
            }
            Err(why) => {
                notes.push(format!("{why}: not written"));
                continue;
            }
        };
        if attributes.contains_key(&name) {
            notes.push(format!("attribute {} would be written as {name}, which another one took: not written", a.name));
            continue;
        }
        let comps = a.components as usize;
        let view = vertex_view(bin, views, &data, scalar.size() * comps);
        let mut acc = json!({"bufferView": view, "componentType": component_type(scalar), "count": nv,
            "type": type_name(comps)});
        if normalized {
            acc["normalized"] = true.into();
        }
        accessors.push(acc);
        attributes.insert(name, (accessors.len() - 1).into());
    }
    attributes
}

/// The document of `mesh`: one TRIANGLES primitive per group that has faces (faces
/// fanned). A mesh of one group keeps all its vertices and their ids; with several
/// groups each primitive gets the vertices its faces use, in their order. A material
/// `library` defines is written as a metallic-roughness material, its textures
/// embedded in the buffer.
pub(super) fn mesh_document(mesh: &Mesh, library: &Materials) -> Result<MeshDocument> {
    mesh.check_faces()?;
    check_attribute_count(mesh)?;
    let mut bin = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut notes = Vec::new();
    let parts: Vec<(u32, std::borrow::Cow<Mesh>)> = if mesh.group_count() <= 1 {
        vec![(0, std::borrow::Cow::Borrowed(mesh))]
    } else {
        (0..mesh.group_count() as u32).filter_map(|g| part(mesh, g).map(|p| (g, std::borrow::Cow::Owned(p)))).collect()
    };
    let mut materials: Vec<String> = Vec::new();
    let mut primitives = Vec::new();
    let mut group_of_primitive = Vec::new();
    let mut faces = Vec::new();
    let mut held = Vec::new();
    for (g, part) in &parts {
        // The fan's indices go straight into the buffer (no list of them first).
        let count = 3 * part.triangle_count();
        if count == 0 {
            continue;
        }
        let wide = part.vertex_count() >= u16::MAX as usize;
        let attribute_bytes: usize = part.attributes.iter().map(|a| a.data.len()).sum();
        bin.reserve(part.positions.len() * 12 + attribute_bytes + 8 + count * if wide { 4 } else { 2 });
        let primitive = primitives.len();
        held.push(HeldView { primitive, view: views.len(), held: Held::Positions });
        let attributes = write_vertices(part, &mut bin, &mut views, &mut accessors, &mut notes);
        bin.resize(bin.len().next_multiple_of(4), 0);
        let start = bin.len();
        fan(part, wide, &mut bin);
        held.push(HeldView { primitive, view: views.len(), held: Held::Indices { wide } });
        views.push(json!({"buffer": 0, "byteOffset": start, "byteLength": bin.len() - start, "target": 34963}));
        accessors.push(json!({"bufferView": views.len() - 1, "componentType": if wide { 5125 } else { 5123 },
            "count": count, "type": "SCALAR"}));
        let mut prim = json!({"attributes": attributes, "indices": accessors.len() - 1, "mode": 4});
        let group = mesh.groups.get(*g as usize);
        if let Some(m) = group.and_then(|g| g.material.as_ref()) {
            let k = materials.iter().position(|x| x == m).unwrap_or_else(|| {
                materials.push(m.clone());
                materials.len() - 1
            });
            prim["material"] = k.into();
        }
        if let Some(group) = group {
            prim["extras"] = json!({"group": group.name});
        }
        primitives.push(prim);
        group_of_primitive.push(*g);
        faces.push(match part {
            std::borrow::Cow::Borrowed(_) => None,
            std::borrow::Cow::Owned(p) => Some((p.face_offsets.clone(), p.face_indices.clone())),
        });
    }
    notes.sort();
    notes.dedup();
    if primitives.is_empty() {
        return Err(Error::Invalid("the mesh has no faces to write as glTF primitives".into()));
    }
    bin.resize(bin.len().next_multiple_of(4), 0);
    let mut json = json!({
        "asset": {"version": "2.0", "generator": "stripkit"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": primitives}],
        "accessors": accessors,
        "bufferViews": views.clone(),
        "buffers": [{"byteLength": bin.len()}],
    });
    if !materials.is_empty() {
        let mut images = Images { uv: mesh.attribute("TEXCOORD_0").is_some(), ..Images::default() };
        let list: Vec<Value> = materials
            .iter()
            .map(|m| match library.get(m) {
                Some(material) => material_json(material, &mut images, &mut bin, &mut views, &mut notes),
                None => json!({"name": m}),
            })
            .collect();
        json["materials"] = list.into();
        json["bufferViews"] = views.into();
        bin.resize(bin.len().next_multiple_of(4), 0);
        json["buffers"] = json!([{"byteLength": bin.len()}]);
        if !images.images.is_empty() {
            json["images"] = images.images.into();
            json["textures"] = images.textures.into();
            json["samplers"] = json!([{}]);
        }
    }
    Ok(MeshDocument { json, bin, group_of_primitive, faces, held, notes })
}

/// The images and textures of the materials written so far (each file once).
#[derive(Default)]
struct Images {
    /// Whether the mesh has TEXCOORD_0, without which a texture cannot be mapped.
    uv: bool,
    images: Vec<Value>,
    textures: Vec<Value>,
    by_uri: Vec<String>,
}

impl Images {
    /// The texture of `t`, its image embedded in a buffer view on first use.
    fn texture(&mut self, t: &Texture, bin: &mut Vec<u8>, views: &mut Vec<Value>) -> usize {
        if let Some(k) = self.by_uri.iter().position(|u| *u == t.uri) {
            return k;
        }
        bin.resize(bin.len().next_multiple_of(4), 0);
        views.push(json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": t.bytes.len()}));
        bin.extend_from_slice(&t.bytes);
        self.images.push(json!({"bufferView": views.len() - 1, "mimeType": t.mime, "name": t.uri}));
        self.textures.push(json!({"source": self.images.len() - 1, "sampler": 0}));
        self.by_uri.push(t.uri.clone());
        self.textures.len() - 1
    }
}

/// A material of an OBJ library as glTF's metallic-roughness material (metallic 0),
/// alpha blended where its alpha is below 1.
fn material_json(m: &Material, images: &mut Images, bin: &mut Vec<u8>, views: &mut Vec<Value>, notes: &mut Vec<String>) -> Value {
    let mut pbr = json!({"baseColorFactor": m.base_color, "metallicFactor": 0.0});
    if let Some(r) = m.roughness {
        pbr["roughnessFactor"] = r.into();
    }
    let mut out = json!({"name": m.name});
    let textured = m.base_color_texture.is_some() || m.normal_texture.is_some();
    if textured && !images.uv {
        notes.push(format!("material {}: its textures are left out: the mesh has no texture coordinates", m.name));
    } else {
        if let Some(t) = &m.base_color_texture {
            pbr["baseColorTexture"] = json!({"index": images.texture(t, bin, views)});
        }
        if let Some(t) = &m.normal_texture {
            out["normalTexture"] = json!({"index": images.texture(t, bin, views)});
        }
    }
    out["pbrMetallicRoughness"] = pbr;
    if m.base_color[3] < 1.0 {
        out["alphaMode"] = "BLEND".into();
    }
    out
}

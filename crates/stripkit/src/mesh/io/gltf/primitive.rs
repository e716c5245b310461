//! One primitive of a glTF scene: decoding it into a [`Mesh`] (POSITION, every other
//! attribute with its type, the triangles, the material's group), listing its vertex
//! accessors, and the bounds of gathered accessor data, for [`super::scene`]. It
//! defines [`ScenePrimitive`], which the scene holds, so that the two files do not
//! import each other.

use super::{at, uint, Accessor, Budget, Doc};
use crate::error::Result;
use crate::mesh::{Attribute, Group, Mesh, Scalar};
use crate::strip::StripSet;
use serde_json::Value;

/// One triangle primitive of a [`Scene`](super::Scene).
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct ScenePrimitive {
    /// The primitive's mesh: its index in the document's `meshes`.
    pub mesh_index: usize,
    /// Its index in that mesh's `primitives`.
    pub primitive_index: usize,
    /// The mode read: 4 (TRIANGLES), 5 (TRIANGLE_STRIP) or 6 (TRIANGLE_FAN).
    pub mode: u8,
    /// The number of morph targets (`targets`).
    pub targets: usize,
    /// The indices read (the vertex count for a primitive without indices).
    pub indices_read: usize,
    /// The geometry: every vertex of the POSITION accessor (vertex ids are the
    /// primitive's own), every attribute, one face per triangle (strips and fans
    /// turned into triangles with their winding, degenerate ones skipped), and one
    /// group named after the glTF mesh (or `mesh N`), with the material's name (or
    /// `material N`).
    pub mesh: Mesh,
    /// The verified strips once the scene was stripped (`Scene::strip`, in
    /// [`crate::scene`]); the writer writes these instead of the primitive's indices.
    pub strips: Option<StripSet>,
    /// The triangles the strips were verified against (the door's reference: the
    /// faces fanned, or quads split along the diagonals the algorithm chose).
    pub(crate) drawn: Vec<[u32; 3]>,
    /// The written vertices, new id to old id, where the strips renumber them (first
    /// use by the strips; vertices they do not use left out); `None` keeps the
    /// primitive's vertex data as read.
    pub(crate) order: Option<Vec<u32>>,
}

/// The memory a [`Scene`](super::Scene) holds per triangle primitive besides its
/// decoded vertex and index data, charged to the decoded-bytes budget
/// (`ReadOptions::max_decoded_bytes`, `--max-memory`)
/// as each primitive is read: its `Mesh` and the JSON objects stripping and writing it
/// adds (its new index, restart and reordered vertex accessors and views, its restart
/// group), in the written document and in the copy read back to check it. Measured at
/// 9 KB per one-triangle primitive sharing its accessors and 14 KB with accessors and
/// views of its own (docs/experiments/reliability.md).
pub(crate) const PRIMITIVE_BYTES: u64 = 16 << 10;

/// The vertex accessors of a primitive: (morph target or `None`, attribute name,
/// accessor), POSITION and every attribute, then every target's.
pub(super) fn vertex_accessors(json: &Value, sp: &ScenePrimitive) -> Vec<(Option<usize>, String, usize)> {
    let prim = &json["meshes"][sp.mesh_index]["primitives"][sp.primitive_index];
    let mut out = Vec::new();
    let mut add = |target: Option<usize>, map: &Value| {
        for (name, a) in map.as_object().into_iter().flatten() {
            if let Some(a) = a.as_u64() {
                out.push((target, name.clone(), a as usize));
            }
        }
    };
    add(None, &prim["attributes"]);
    for (t, target) in prim.get("targets").and_then(Value::as_array).into_iter().flatten().enumerate() {
        add(Some(t), target);
    }
    out
}

/// The per-component min and max (JSON) of the elements `order` of packed accessor data.
pub(super) fn bounds(acc: &Accessor, data: &[u8], order: &[u32]) -> (Value, Value) {
    let a = Attribute {
        name: String::new(),
        scalar: scalar_of(acc.component),
        components: acc.components as u8,
        normalized: false,
        data: data.to_vec(),
    };
    let mut lo = vec![f64::INFINITY; acc.components];
    let mut hi = vec![f64::NEG_INFINITY; acc.components];
    for &v in order {
        for c in 0..acc.components {
            let x = a.get(v as usize, c);
            lo[c] = lo[c].min(x);
            hi[c] = hi[c].max(x);
        }
    }
    let json = |xs: Vec<f64>| -> Value {
        xs.into_iter().map(|x| if acc.component == 5126 { Value::from(x) } else { Value::from(x as i64) }).collect()
    };
    (json(lo), json(hi))
}

/// The scalar type of a glTF component type (already checked to be one of the six).
fn scalar_of(component: u64) -> Scalar {
    match component {
        5120 => Scalar::I8,
        5121 => Scalar::U8,
        5122 => Scalar::I16,
        5123 => Scalar::U16,
        5125 => Scalar::U32,
        _ => Scalar::F32,
    }
}

/// Checks every morph target of a primitive whose POSITION has `count` elements: each
/// target an object of accessor indices, each accessor in the file with `count`
/// elements (glTF requires it), so that nothing later (the vertex reordering gathers
/// every target's elements by vertex id) reads past a shorter one. Only the accessor's
/// `count` is read: targets are decoded when written, and a sparse one stays valid.
fn check_target_counts(doc: &Doc, targets: &[Value], count: usize, place: &dyn Fn() -> String) -> Result<()> {
    let src = doc.src;
    for (t, target) in targets.iter().enumerate() {
        let Value::Object(map) = target else {
            return Err(src.err(place(), format!("targets[{t}] must be an object")));
        };
        for (name, a) in map {
            let a = a
                .as_u64()
                .ok_or_else(|| src.err(place(), format!("targets[{t}].{name} must be an accessor index")))?
                as usize;
            let acc = doc.accessors.get(a).ok_or_else(|| {
                src.err(
                    place(),
                    format!("targets[{t}].{name} refers to accessors[{a}] but the file has {}", doc.accessors.len()),
                )
            })?;
            let n = uint(src, acc, "count", &|| at("accessors", a))?;
            if n != Some(count as u64) {
                let n = n.map_or("no count".to_string(), |n| format!("{n} values"));
                return Err(src.err(
                    place(),
                    format!("morph target {t} attribute {name} (accessors[{a}]) has {n} but POSITION has {count}"),
                ));
            }
        }
    }
    Ok(())
}

/// The vertex attributes of a primitive other than POSITION, each checked to hold
/// `count` values and charged to `budget` before it is decoded.
pub(super) fn read_attributes(
    doc: &Doc,
    prim: &Value,
    count: usize,
    place: &dyn Fn() -> String,
    budget: &mut Budget,
) -> Result<Vec<Attribute>> {
    let src = doc.src;
    let Some(Value::Object(attributes)) = prim.get("attributes") else {
        return Err(src.err(place(), "'attributes' must be an object"));
    };
    let mut out = Vec::new();
    for (name, acc) in attributes.iter().filter(|(name, _)| *name != "POSITION") {
        let acc = acc.as_u64().ok_or_else(|| src.err(place(), format!("{name} must be an accessor index")))? as usize;
        let mut charge =
            |bytes: usize| budget.charge(src, &place(), bytes as u64, || format!("accessors[{acc}]: attribute {name}"));
        let (a, data) = doc.read_packed(acc, &mut charge)?;
        if a.count != count {
            return Err(src.err(
                place(),
                format!("attribute {name} (accessors[{acc}]) has {} values but POSITION has {count}", a.count),
            ));
        }
        let normalized = doc.accessors[acc].get("normalized").and_then(Value::as_bool).unwrap_or(false);
        let (scalar, components) = (scalar_of(a.component), a.components as u8);
        out.push(Attribute { name: name.clone(), scalar, components, normalized, data });
    }
    Ok(out)
}

/// The attributes of a whole mesh from those of its runs of vertices (in vertex
/// order): an attribute is kept where every run has one of its name with the same
/// scalar type, components and normalization (their bytes joined), and left out
/// otherwise, as a mesh holds one value per vertex.
pub(super) fn join_attributes(runs: Vec<Vec<Attribute>>) -> Vec<Attribute> {
    let mut runs = runs.into_iter();
    let Some(first) = runs.next() else { return Vec::new() };
    let mut joined: Vec<Option<Attribute>> = first.into_iter().map(Some).collect();
    for run in runs {
        for slot in &mut joined {
            let Some(a) = slot else { continue };
            match run.iter().find(|b| b.name == a.name) {
                Some(b) if b.scalar == a.scalar && b.components == a.components && b.normalized == a.normalized => {
                    a.data.extend_from_slice(&b.data);
                }
                _ => *slot = None,
            }
        }
    }
    joined.into_iter().flatten().collect()
}

/// Decodes primitive `p` of mesh `m`; `None` for points and lines.
pub(super) fn decode_primitive(
    doc: &Doc,
    json: &Value,
    m: usize,
    p: usize,
    prim: &Value,
    budget: &mut Budget,
    faces: bool,
) -> Result<Option<ScenePrimitive>> {
    let src = doc.src;
    let place = || format!("meshes[{m}].primitives[{p}]");
    let mode = uint(src, prim, "mode", &place)?.unwrap_or(4);
    if mode > 6 {
        return Err(src.err(place(), format!("unknown primitive mode {mode}")));
    }
    if mode < 4 {
        return Ok(None);
    }
    let Some(Value::Object(attributes)) = prim.get("attributes") else {
        return Err(src.err(place(), "'attributes' must be an object"));
    };
    // What the scene holds for the primitive beyond its decoded data, charged before
    // any of it is made (20,000 primitives over a few shared bytes held 180 MB).
    budget.charge_primitive(src, &place(), PRIMITIVE_BYTES, || {
        format!("one more triangle primitive (counted as {PRIMITIVE_BYTES} bytes each)")
    })?;
    let pos = attributes
        .get("POSITION")
        .ok_or_else(|| src.err(place(), "the primitive has no POSITION attribute"))?
        .as_u64()
        .ok_or_else(|| src.err(place(), "POSITION must be an accessor index"))? as usize;
    let mut mesh = Mesh::new();
    let mut charge = |count: usize| {
        budget.charge(src, &place(), 12 * count as u64, || format!("accessors[{pos}]: {count} vertices"))
    };
    doc.read_positions(pos, &mut mesh.positions, &mut charge)?;
    let count = mesh.positions.len();
    if count > u32::MAX as usize - 1 {
        return Err(src.err(place(), "more than 4294967294 vertices"));
    }
    mesh.attributes = read_attributes(doc, prim, count, &place, budget)?;
    let mut indices = Vec::new();
    let indices_read = if faces {
        super::read_primitive_indices(src, doc, prim, &place, budget, mode, (pos, count), &mut indices)?;
        super::push_primitive_faces(src, &place, &mut mesh, mode, &indices)?;
        // Let go of as soon as it is decoded, not held beside the rest of the primitive.
        let n = indices.len();
        drop(indices);
        n
    } else {
        // A document made from a mesh: the caller sets the faces (its own polygons).
        let accessor = prim.get("indices").and_then(Value::as_u64);
        accessor.and_then(|a| json["accessors"][a as usize]["count"].as_u64()).map_or(count, |n| n as usize)
    };
    let mesh_name = json["meshes"][m].get("name").and_then(Value::as_str).map_or(format!("mesh {m}"), String::from);
    let material = uint(src, prim, "material", &place)?.map(|k| {
        json.get("materials")
            .and_then(|ms| ms.get(k as usize))
            .and_then(|mat| mat.get("name"))
            .and_then(Value::as_str)
            .map_or(format!("material {k}"), String::from)
    });
    mesh.groups = vec![Group { name: mesh_name, material }];
    let targets = match prim.get("targets") {
        None => 0,
        Some(Value::Array(t)) => {
            check_target_counts(doc, t, count, &place)?;
            t.len()
        }
        Some(_) => return Err(src.err(place(), "'targets' must be an array")),
    };
    Ok(Some(ScenePrimitive {
        mesh_index: m,
        primitive_index: p,
        mode: mode as u8,
        targets,
        indices_read,
        mesh,
        strips: None,
        drawn: Vec::new(),
        order: None,
    }))
}

#[cfg(test)]
mod join_tests {
    use super::join_attributes;
    use crate::mesh::{Attribute, Scalar};

    fn attr(name: &str, scalar: Scalar, components: u8, normalized: bool, data: &[u8]) -> Attribute {
        Attribute { name: name.into(), scalar, components, normalized, data: data.to_vec() }
    }

    #[test]
    fn attributes_every_run_has_alike_are_joined_and_the_rest_left_out() {
        let runs = vec![
            vec![
                attr("COLOR_0", Scalar::U8, 4, true, &[1, 2, 3, 4]),
                attr("TEXCOORD_0", Scalar::U16, 2, true, &[0; 4]),
                attr("_ONLY_HERE", Scalar::U8, 1, false, &[9]),
            ],
            vec![
                attr("TEXCOORD_0", Scalar::F32, 2, false, &[0; 8]),
                attr("COLOR_0", Scalar::U8, 4, true, &[5, 6, 7, 8, 9, 10, 11, 12]),
            ],
        ];
        let joined = join_attributes(runs);
        assert_eq!(joined.len(), 1, "{joined:?}");
        assert_eq!(joined[0].name, "COLOR_0");
        assert_eq!(joined[0].data, vec![1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12]);
        assert!(join_attributes(Vec::new()).is_empty());
    }
}

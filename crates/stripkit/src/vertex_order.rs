//! Vertex order for fetching: vertices renumbered in the order the strips first use
//! them, unreferenced ones dropped (what meshoptimizer's `optimizeVertexFetch` does
//! for index buffers). A GPU then reads the vertex buffer nearly front to back.
//!
//! Above the door: it renumbers [`Strips`]. The id lists themselves
//! (`first_use`, `ids_of`) live in `mesh::order`, where the glTF writer uses them too.

use crate::error::{Error, Result};
use crate::mesh::io::Format;
use crate::mesh::order::{first_use, ids_of};
use crate::mesh::Mesh;
use crate::pipeline::Strips;
use crate::strip::StripSet;

/// Renumbers `mesh`'s vertices in the order `strips` first use them. Vertices that
/// only faces use (a degenerate triangle no strip draws) follow in face order; vertices
/// neither uses are dropped. Returns the renumbered mesh (positions, attributes, faces
/// and groups), the strips in the new ids, and for every old vertex its new id
/// (`u32::MAX` where dropped).
///
/// A strip or face index that is not a vertex of `mesh` is [`Error::Invalid`] (a
/// [`StripSet`] keeps its strips apart: no restart index in it).
///
/// ```
/// use stripkit::{gen, first_use_order, stripify, StripOptions};
/// let mut mesh = gen::grid(3, 3);
/// mesh.positions.push([9.0, 9.0, 9.0]); // used by no face
/// let strips = stripify(&mesh, &StripOptions::default())?;
/// let (ordered, set, new_id) = first_use_order(&mesh, &strips.strips)?;
/// assert_eq!(ordered.vertex_count(), 16);
/// assert_eq!(new_id[16], u32::MAX);
/// assert_eq!(set.indices[0], 0);
/// # Ok::<(), stripkit::Error>(())
/// ```
pub fn first_use_order(mesh: &Mesh, strips: &StripSet) -> Result<(Mesh, StripSet, Vec<u32>)> {
    let n = mesh.vertex_count();
    if let Some(&v) = strips.indices.iter().chain(&mesh.face_indices).find(|&&v| v as usize >= n) {
        return Err(Error::Invalid(format!("index {v} is not a vertex of the mesh ({n} vertices)")));
    }
    let new_id = first_use_ids(mesh, &strips.indices);
    let (out, set) = renumbered(mesh, strips, &new_id);
    Ok((out, set, new_id))
}

/// For every vertex of `mesh`, its rank of first use in `stream` then in the faces
/// (`u32::MAX` where neither uses it).
fn first_use_ids(mesh: &Mesh, stream: &[u32]) -> Vec<u32> {
    let order = first_use(stream.iter().chain(&mesh.face_indices).copied(), mesh.vertex_count());
    ids_of(&order, mesh.vertex_count())
}

/// `mesh` and `strips` with vertex `v` renamed `new_id[v]` (a permutation of the ids
/// that are not `u32::MAX`, which every face and strip index is).
fn renumbered(mesh: &Mesh, strips: &StripSet, new_id: &[u32]) -> (Mesh, StripSet) {
    let set = StripSet {
        indices: strips.indices.iter().map(|&v| new_id[v as usize]).collect(),
        offsets: strips.offsets.clone(),
    };
    (mesh.renumbered(new_id), set)
}

impl Strips {
    /// These strips and the mesh they draw, with vertices in the order a `format`
    /// file's index stream ([`Strips::for_format`]: the stitched strip of glTF, for
    /// one) first uses them, unreferenced ones dropped: the mesh the strips draw
    /// ([`Strips::changed_mesh`] where the algorithm added vertices) renumbered, and
    /// strips whose [`Strips::triangles`] and strips use the new ids. Joining does not
    /// look at ids, so the renamed strips join into the renamed stream. The figures
    /// stay: they do not depend on vertex ids. [`Strips::to_file_bytes`] of the result
    /// checks it again.
    pub fn in_first_use_order(&self, mesh: &Mesh, format: Format) -> (Mesh, Strips) {
        let drawn;
        let mesh = if self.changes_mesh() {
            drawn = self.changed_mesh(mesh);
            &drawn
        } else {
            mesh
        };
        let stream = self.for_format(format).unwrap_or_else(|| self.strips.clone());
        let new_id = first_use_ids(mesh, &stream.indices);
        let (ordered, set) = renumbered(mesh, &self.strips, &new_id);
        let mut out = self.clone();
        out.strips = set;
        out.triangles = self.triangles.iter().map(|t| t.map(|v| new_id[v as usize])).collect();
        // The renumbered mesh holds any added vertices itself.
        out.added_positions.clear();
        out.added_from.clear();
        (ordered, out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gen;
    use crate::mesh::Attribute;
    use crate::pipeline::{stripify, StripOptions};

    #[test]
    fn strips_read_the_vertex_buffer_front_to_back() {
        // A grid whose vertices are listed backwards, with an unused vertex in front.
        let grid = gen::grid(6, 4);
        let n = grid.vertex_count() as u32;
        let mut positions = vec![[5.0, 5.0, 5.0]];
        positions.extend(grid.positions.iter().rev());
        let faces: Vec<Vec<u32>> = grid.faces().map(|f| f.iter().map(|&v| n - v).collect()).collect();
        let mut mesh = Mesh::from_polygons(positions, &faces);
        let uv: Vec<f32> = (0..=n).flat_map(|v| [v as f32, 0.5]).collect();
        mesh.attributes.push(Attribute::from_f32("TEXCOORD_0", 2, &uv));
        let strips = stripify(&mesh, &StripOptions::default()).unwrap();
        let (ordered, s) = strips.in_first_use_order(&mesh, Format::Glb);
        assert_eq!(ordered.vertex_count(), n as usize);
        // Each index of the written stream is at most one more than the largest before it.
        let mut next = 0;
        for &v in &s.for_format(Format::Glb).unwrap().indices {
            assert!(v <= next, "{v} before {next}");
            next = next.max(v + 1);
        }
        assert_eq!(next, n);
        // Every new vertex has the position and UV of the old one it came from.
        let new_id = first_use_ids(&mesh, &strips.for_format(Format::Glb).unwrap().indices);
        assert_eq!(new_id[0], u32::MAX);
        let old_uv = mesh.attribute("TEXCOORD_0").unwrap();
        let new_uv = ordered.attribute("TEXCOORD_0").unwrap();
        for (old, &new) in new_id.iter().enumerate().skip(1) {
            assert_eq!(ordered.positions[new as usize], mesh.positions[old]);
            assert_eq!(new_uv.value(new as usize), old_uv.value(old));
        }
        // The same triangles, renamed, and the file bytes pass the read-back check.
        let renamed: Vec<[u32; 3]> = strips.triangles.iter().map(|t| t.map(|v| new_id[v as usize])).collect();
        assert_eq!(s.triangles, renamed);
        assert!(crate::strip::verify_triangles(&ordered.triangulate().tris, &crate::strip::decode(&s.strips)).ok());
        s.to_file_bytes(&ordered, Format::Glb).unwrap();
        // The free function orders by the strips themselves.
        let (_, set, ids) = first_use_order(&mesh, &strips.strips).unwrap();
        assert_eq!(set.indices[0], 0);
        assert_eq!(ids[strips.strips.indices[0] as usize], 0);
        assert_eq!(ids[0], u32::MAX);
        let bad = StripSet::from_strips(&[[0, 1, n + 1]]);
        assert!(first_use_order(&mesh, &bad).unwrap_err().to_string().contains("index"));
    }
}

//! What seams do to `single`: a GPU vertex carries one value of every attribute, so a
//! UV seam splits the surface's vertices and the strips cannot cross it. These counts
//! say how many pieces a surface fell into, for [`SingleReport`].

use crate::mesh::Mesh;
use crate::strip::is_degenerate;
use crate::stripify::single::SingleReport;
use crate::topology::UnionFind;
use std::collections::HashMap;

/// Connected components of the non-degenerate `tris`, two triangles joined across an
/// edge when `same(v)` names its ends alike on both sides (an edge run either way).
fn components(tris: &[[u32; 3]], same: impl Fn(u32) -> Vec<u64>) -> usize {
    let mut sets = UnionFind::new(tris.len());
    let mut first: HashMap<(Vec<u64>, Vec<u64>), u32> = HashMap::new();
    let mut live = 0;
    for (t, tri) in tris.iter().enumerate() {
        if is_degenerate(tri) {
            continue;
        }
        live += 1;
        for j in 0..3 {
            let (a, b) = (same(tri[j]), same(tri[(j + 1) % 3]));
            let key = if a <= b { (a, b) } else { (b, a) };
            let owner = *first.entry(key).or_insert(t as u32);
            if sets.union(owner, t as u32) {
                live -= 1;
            }
        }
    }
    live
}

/// Fills the seam counts of `report` ([`SingleReport::surfaces`],
/// [`SingleReport::uv_islands`], [`SingleReport::triangles_added`],
/// [`SingleReport::vertices_added`]) for `input` (the mesh's fan) and the `drawn`
/// (non-degenerate) triangles of the changed mesh. Cost: a hash map over the edges, twice.
pub(super) fn count(mesh: &Mesh, input: &[[u32; 3]], drawn: usize, report: &mut SingleReport) {
    let position = |v: u32| mesh.positions[v as usize].iter().map(|c| c.to_bits() as u64).collect::<Vec<u64>>();
    report.surfaces = components(input, position);
    report.uv_islands = mesh.attribute("TEXCOORD_0").map(|uv| {
        components(input, |v| {
            let mut key = position(v);
            key.extend(uv.value(v as usize).iter().map(|x| x.to_bits()));
            key
        })
    });
    let live = input.iter().filter(|t| !is_degenerate(t)).count();
    report.triangles_added = drawn.saturating_sub(live);
    report.vertices_added = report.steiner_vertices;
}

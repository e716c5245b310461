//! The door for a mesh whose faces fall in several groups (materials): strips are
//! built, verified and joined group by group, so that none crosses two groups.

use super::*;

/// The door for a mesh whose faces fall in several groups: every group stripped on its
/// own (its faces over its own vertices, renumbered in increasing order so that ties
/// break as on the whole mesh), by the algorithm chosen for the whole mesh, and
/// verified; then the strips, put back on the mesh's vertex ids and concatenated in
/// group order, are measured and verified again as a whole, and when every group used
/// the fan, their triangles are checked against the whole mesh's fan.
pub(super) fn run_groups(mesh: &Mesh, options: &StripOptions) -> Result<Strips> {
    let algorithm = resolve(mesh, options)?;
    if let Algorithm::Single(_) = algorithm {
        return Err(Error::Invalid(format!(
            "single builds one strip per connected component and may add vertices; it does not take a mesh whose \
             faces fall in {} groups (materials): use another algorithm, or drop the groups",
            mesh.group_count()
        )));
    }
    let sub_options = StripOptions { algorithm: algorithm.clone(), ..options.clone() };
    if matches!(options.algorithm, Algorithm::Auto(_)) && options.split != Split::Auto {
        sub_options.check()?;
    }
    let groups = mesh.group_count();
    let mut faces_of: Vec<Vec<u32>> = vec![Vec::new(); groups];
    for f in 0..mesh.face_count() {
        faces_of[mesh.group_of(f) as usize].push(f as u32);
    }
    let mut strips = StripSet::new();
    let mut triangles = Vec::with_capacity(mesh.triangle_count());
    let mut group_ranges = Vec::with_capacity(groups);
    let (mut quads, mut any_quads, mut all_fan) = (0, false, true);
    let mut stripify_time = Duration::ZERO;
    // The groups are stripped independently (in parallel when the options allow), then
    // joined in group order; the first failing group in that order is the error.
    let parts = crate::parallel::map_ordered(options.threads, &faces_of, |faces| {
        if faces.is_empty() {
            return Ok(None);
        }
        // The group's own vertices, in increasing id order so that ties break as on the
        // whole mesh.
        let (sub, map) = mesh.submesh(faces);
        run_one(&sub, &sub_options).map(|part| Some((part, map)))
    });
    for part in parts {
        let start = strips.len();
        let Some((part, map)) = part? else {
            group_ranges.push(start..start);
            continue;
        };
        for s in part.strips.iter() {
            let back: Vec<u32> = s.iter().map(|&i| map[i as usize]).collect();
            strips.push(&back);
        }
        triangles.extend(part.triangles.iter().map(|t| t.map(|i| map[i as usize])));
        group_ranges.push(start..strips.len());
        if let Some(q) = part.quads {
            quads += q;
            any_quads = true;
        }
        all_fan &= part.split == Split::Fan;
        stripify_time += part.stripify_time;
    }
    let figures = metrics::figures(&triangles, &strips, options.cache);
    if !figures.verified {
        return Err(fail("the strips of every group", &strip::verify(&triangles, &strips)));
    }
    if all_fan {
        let v = strip::verify_triangles(&mesh.triangulate().tris, &triangles);
        if !v.ok() {
            return Err(fail("the strips of every group against the whole mesh", &v));
        }
    }
    let joined_form = joined(&strips, &group_ranges, options.join, options.restart_index);
    if !strip::draws_in_order(&strips, &joined_form, options.threads) {
        let v = strip::verify(&triangles, &joined_form);
        if !v.ok() {
            return Err(fail(&format!("the strips joined by {} per group", options.join.name()), &v));
        }
    }
    Ok(Strips {
        strips,
        triangles,
        algorithm,
        split: if all_fan { Split::Fan } else { Split::Qstrip },
        quads: any_quads.then_some(quads),
        figures,
        join: options.join,
        restart_index: options.restart_index,
        stripify_time,
        single: None,
        added_positions: Vec::new(),
        added_from: Vec::new(),
        group_ranges,
        welded: 0,
        phases: vec![("stripify", stripify_time)],
    })
}

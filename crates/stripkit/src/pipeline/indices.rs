//! The door for plain index buffers, meshoptimizer-style: [`stripify_indices`],
//! [`stripify_bound`] and [`unstripify`] take and give slices.

use super::{check_restart, run, Algorithm, Join, StripOptions};
use crate::error::{Error, OptionName, Result};
use crate::mesh::Mesh;
use crate::strip;

/// The most indices [`stripify_indices`] returns for `index_count` input indices, for
/// any options: 7 per input triangle (a lone triangle stitched at an odd position
/// takes 3 indices and 3 to join; a strip's swaps never outnumber its triangles).
/// Checked on every output.
pub fn stripify_bound(index_count: usize) -> usize {
    (index_count / 3).saturating_mul(7)
}

/// Strips for a plain triangle list, meshoptimizer-style: `indices` holds three
/// vertex ids per triangle, all below `vertex_count`. Returns one buffer: strips
/// separated by [`StripOptions::restart_index`] ([`Join::Restart`], which then must
/// not be below `vertex_count`) or one stitched strip ([`Join::Degenerate`]; the
/// restart index unused). At most [`stripify_bound`]`(indices.len())` indices, verified like
/// [`stripify`](super::stripify)'s, which it calls (positions are not needed: vertices are given
/// coincident positions, and orders that would use them fall back to vertex ids;
/// [`StripOptions::weld`] does not apply, as there is no vertex data to compare).
///
/// Errors: an empty list, a length that is not a multiple of 3, an index at or past
/// `vertex_count`, a restart index below `vertex_count`, [`Join::Separate`] (a flat
/// buffer cannot hold it), and everything [`stripify`](super::stripify) refuses.
///
/// ```
/// use stripkit::{stripify_indices, unstripify, StripOptions};
/// // A 2 x 1 quad grid: 4 triangles.
/// let tris = [0, 3, 1, 1, 3, 4, 1, 4, 2, 2, 4, 5];
/// let buf = stripify_indices(&tris, 6, &StripOptions::default())?; // restart u32::MAX
/// assert_eq!(buf.len(), 6); // one strip, no restart
/// let mut back = unstripify(&buf, u32::MAX);
/// assert_eq!(back.len(), tris.len());
/// # Ok::<(), stripkit::Error>(())
/// ```
pub fn stripify_indices(
    indices: &[u32],
    vertex_count: usize,
    options: &StripOptions,
) -> Result<Vec<u32>> {
    if indices.is_empty() {
        return Err(Error::Invalid("the index list is empty: nothing to strip".into()));
    }
    if indices.len() % 3 != 0 {
        return Err(Error::Invalid(format!(
            "{} indices is not a whole number of triangles (a multiple of 3)",
            indices.len()
        )));
    }
    if vertex_count > u32::MAX as usize {
        return Err(Error::Invalid(format!("{vertex_count} vertices do not fit 32-bit indices")));
    }
    if let Some(i) = indices.iter().position(|&v| v as usize >= vertex_count) {
        return Err(Error::Invalid(format!(
            "index {i} (triangle {}) is vertex {} but there are {vertex_count} vertices",
            i / 3,
            indices[i]
        )));
    }
    if options.join == Join::Separate {
        return Err(Error::option(
            OptionName::Join,
            "separate does not fit a flat buffer, which holds restart-separated or stitched strips \
             (join restart or degenerate)",
        ));
    }
    if let Algorithm::Single(_) = options.algorithm {
        return Err(Error::Invalid(
            "single may add vertices (edge splits) and swap edges, which a plain index buffer cannot return; \
             use stripify on a Mesh and read Strips::changed_mesh"
                .into(),
        ));
    }
    // Against the caller's vertex count, not only the vertices used.
    check_restart(options, vertex_count)?;
    options.check()?;
    // Vertices past the largest index are unreferenced: leaving them out changes no
    // strip and keeps the allocation to the input's size.
    let used = indices.iter().map(|&v| v as usize + 1).max().unwrap_or(0);
    let tris: Vec<[u32; 3]> = indices.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let mesh = Mesh::from_triangles(vec![[0.0; 3]; used], &tris);
    // No vertex data: the coincident positions say nothing, so nothing is welded.
    let strips = run(&mesh, &options.clone().weld(false))?;
    let out = match options.join {
        Join::Degenerate => strips.stitched(),
        _ => strips.restart_buffer(),
    };
    if out.len() > stripify_bound(indices.len()) {
        return Err(Error::Verification(format!(
            "{} indices exceed the bound of {} for {} input indices",
            out.len(),
            stripify_bound(indices.len()),
            indices.len()
        )));
    }
    Ok(out)
}

/// The triangle list a strip buffer draws (the reading rule of docs/metrics.md), three indices per
/// triangle, in order; `restart_index` separates strips, degenerate triangles are
/// dropped. For a stitched strip pass any index it does not use (e.g. `u32::MAX`).
/// O(n).
pub fn unstripify(strip_indices: &[u32], restart_index: u32) -> Vec<u32> {
    let mut out = Vec::with_capacity(strip_indices.len().saturating_sub(2) * 3);
    for s in strip_indices.split(|&i| i == restart_index) {
        strip::for_each_triangle(s, |t| out.extend_from_slice(&t));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bound_covers_lone_triangles_stitched() {
        // Three triangles sharing no edge: each its own strip.
        let tris = [0, 1, 2, 3, 4, 5, 6, 7, 8];
        let options = StripOptions::default().join(Join::Degenerate);
        let out = stripify_indices(&tris, 9, &options.restart_index(0)).unwrap();
        assert!(out.len() <= stripify_bound(tris.len()));
        let restart = stripify_indices(&tris, 9, &StripOptions::default().restart_index(9)).unwrap();
        assert_eq!(restart.len(), 11);
    }
}

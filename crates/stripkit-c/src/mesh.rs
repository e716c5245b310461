//! The mesh-level entry point: [`stripify`] on positions and triangles, for every
//! algorithm including `single`, which may add vertices (edge midpoints): the caller
//! gets their positions and the edge each splits, to blend its own attributes.

use crate::boundary::{guard, input, Failure, Outcome, Status};
use crate::options::{self, stripkit_options};
use libstripkit::{stripify, Join, Mesh};
use std::ffi::c_void;

/// The header's `stripkit_mesh_result`: arrays owned by the library until
/// [`stripkit_mesh_result_free`].
#[repr(C)]
#[derive(Debug)]
pub struct stripkit_mesh_result {
    /// The strip buffer (restart-separated or stitched, as the options' join says).
    pub indices: *const u32,
    /// Indices in `indices`.
    pub index_count: usize,
    /// Triangles the strips draw.
    pub triangle_count: usize,
    /// Three floats per added vertex (vertex ids `vertex_count`, `vertex_count + 1`, ...).
    pub added_positions: *const f32,
    /// Two vertex ids per added vertex: the edge whose midpoint it is.
    pub added_from: *const u32,
    /// Vertices added.
    pub added_count: usize,
    /// The library's storage; null once freed.
    pub internal: *mut c_void,
}

struct Owned {
    indices: Vec<u32>,
    added_positions: Vec<f32>,
    added_from: Vec<u32>,
}

impl stripkit_mesh_result {
    const EMPTY: stripkit_mesh_result = stripkit_mesh_result {
        indices: std::ptr::null(),
        index_count: 0,
        triangle_count: 0,
        added_positions: std::ptr::null(),
        added_from: std::ptr::null(),
        added_count: 0,
        internal: std::ptr::null_mut(),
    };
}

/// Strips for a mesh of `vertex_count` positions and `index_count / 3` triangles;
/// fills `result` (free it with [`stripkit_mesh_result_free`]). Returns a status.
///
/// # Safety
/// `positions` readable for `3 * vertex_count` floats, `indices` for `index_count`,
/// `options` null or valid, `result` writable.
#[no_mangle]
pub unsafe extern "C" fn stripkit_stripify_mesh(
    positions: *const f32,
    vertex_count: usize,
    indices: *const u32,
    index_count: usize,
    options: *const stripkit_options,
    result: *mut stripkit_mesh_result,
) -> i32 {
    guard("stripkit_stripify_mesh", || {
        if result.is_null() {
            return Err(Failure::new(Status::NullPointer, "result is null"));
        }
        unsafe { result.write(stripkit_mesh_result::EMPTY) };
        let floats = vertex_count
            .checked_mul(3)
            .ok_or_else(|| Failure::new(Status::Invalid, format!("{vertex_count} vertices do not fit in memory")))?;
        let positions = unsafe { input(positions, floats, "positions") }?;
        let indices = unsafe { input(indices, index_count, "indices") }?;
        let options = unsafe { options::read(options) }?;
        let owned = run(positions, vertex_count, indices, &options)?;
        let triangle_count = owned.1;
        let owned = Box::new(owned.0);
        let r = stripkit_mesh_result {
            indices: owned.indices.as_ptr(),
            index_count: owned.indices.len(),
            triangle_count,
            added_positions: owned.added_positions.as_ptr(),
            added_from: owned.added_from.as_ptr(),
            added_count: owned.added_from.len() / 2,
            internal: Box::into_raw(owned).cast(),
        };
        unsafe { result.write(r) };
        Ok(0)
    })
}

fn run(
    positions: &[f32],
    vertex_count: usize,
    indices: &[u32],
    options: &libstripkit::StripOptions,
) -> Outcome<(Owned, usize)> {
    if indices.len() % 3 != 0 {
        return Err(Failure::new(
            Status::Invalid,
            format!("{} indices is not a whole number of triangles (a multiple of 3)", indices.len()),
        ));
    }
    if let Some(i) = indices.iter().position(|&v| v as usize >= vertex_count) {
        return Err(Failure::new(
            Status::Invalid,
            format!("index {i} (triangle {}) is vertex {} but there are {vertex_count} vertices", i / 3, indices[i]),
        ));
    }
    let points: Vec<[f32; 3]> = positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
    let tris: Vec<[u32; 3]> = indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
    let strips = stripify(&Mesh::from_triangles(points, &tris), options)?;
    let buffer = match strips.join {
        Join::Degenerate => strips.stitched(),
        _ => strips.restart_buffer(),
    };
    let owned = Owned {
        indices: buffer,
        added_positions: strips.added_positions.iter().flatten().copied().collect(),
        added_from: strips.added_from.iter().flatten().copied().collect(),
    };
    Ok((owned, strips.triangles.len()))
}

/// Frees what [`stripkit_stripify_mesh`] gave `result` and empties it; null or an
/// already emptied result is a no-op.
///
/// # Safety
/// `result` null or filled by [`stripkit_stripify_mesh`] (or emptied by this function).
#[no_mangle]
pub unsafe extern "C" fn stripkit_mesh_result_free(result: *mut stripkit_mesh_result) {
    let _ = guard::<i64>("stripkit_mesh_result_free", || {
        if result.is_null() {
            return Ok(0);
        }
        let internal = unsafe { (*result).internal };
        if !internal.is_null() {
            drop(unsafe { Box::from_raw(internal.cast::<Owned>()) });
        }
        unsafe { result.write(stripkit_mesh_result::EMPTY) };
        Ok(0)
    });
}

//! Levels of detail from a `.sets` blob in memory ([`Sets::from_bytes`]): an opaque
//! handle, each level's strips recovered with a [`Sets::cursor`] into the caller's array.

use crate::boundary::{count, guard, input, output, Failure, Outcome, Status};
use libstripkit::lod::Sets;
use std::ffi::c_void;
use std::path::Path;

/// The header's opaque `stripkit_lod`: a decoded, checked `.sets` model.
pub struct stripkit_lod {
    sets: Sets,
}

/// The name a blob goes by in error messages.
const BLOB: &str = "(.sets blob)";

/// Decodes and checks a `.sets` blob; `*lod` gets the handle. Returns a status.
///
/// # Safety
/// `data` readable for `size` bytes, `lod` writable.
#[no_mangle]
pub unsafe extern "C" fn stripkit_lod_open(data: *const c_void, size: usize, lod: *mut *mut stripkit_lod) -> i32 {
    guard("stripkit_lod_open", || {
        if lod.is_null() {
            return Err(Failure::new(Status::NullPointer, "lod is null"));
        }
        unsafe { lod.write(std::ptr::null_mut()) };
        let bytes = unsafe { input(data.cast::<u8>(), size, "data") }?;
        let sets = Sets::from_bytes(Path::new(BLOB), bytes)?;
        unsafe { lod.write(Box::into_raw(Box::new(stripkit_lod { sets }))) };
        Ok(0)
    })
}

/// Frees a handle of [`stripkit_lod_open`]; null is a no-op.
///
/// # Safety
/// `lod` null or a handle not yet freed.
#[no_mangle]
pub unsafe extern "C" fn stripkit_lod_free(lod: *mut stripkit_lod) {
    if !lod.is_null() {
        let _ = guard::<i64>("stripkit_lod_free", || {
            drop(unsafe { Box::from_raw(lod) });
            Ok(0)
        });
    }
}

unsafe fn model<'a>(lod: *const stripkit_lod) -> Outcome<&'a Sets> {
    if lod.is_null() {
        return Err(Failure::new(Status::NullPointer, "lod is null"));
    }
    Ok(unsafe { &(*lod).sets })
}

fn level_in_range(sets: &Sets, level: u32) -> Outcome<()> {
    if level > sets.levels() {
        return Err(Failure::new(
            Status::Invalid,
            format!("level {level} is out of range: 0 to {}", sets.levels()),
        ));
    }
    Ok(())
}

/// The coarsest level (levels are 0, the finest, to this); or a negative status.
///
/// # Safety
/// `lod` null or a live handle.
#[no_mangle]
pub unsafe extern "C" fn stripkit_lod_levels(lod: *const stripkit_lod) -> i64 {
    guard("stripkit_lod_levels", || Ok(unsafe { model(lod) }?.levels() as i64))
}

/// Vertices any level may name (the positions' count); or a negative status.
///
/// # Safety
/// `lod` null or a live handle.
#[no_mangle]
pub unsafe extern "C" fn stripkit_lod_vertex_count(lod: *const stripkit_lod) -> i64 {
    guard("stripkit_lod_vertex_count", || count(unsafe { model(lod) }?.positions().len()))
}

/// Copies the positions (3 floats per vertex) into `destination`; returns the floats
/// written or a negative status.
///
/// # Safety
/// `lod` null or a live handle; `destination` writable for `destination_size` floats.
#[no_mangle]
pub unsafe extern "C" fn stripkit_lod_positions(
    lod: *const stripkit_lod,
    destination: *mut f32,
    destination_size: usize,
) -> i64 {
    guard("stripkit_lod_positions", || {
        let positions = unsafe { model(lod) }?.positions();
        let out = unsafe { output(destination, destination_size, positions.len() * 3, "destination") }?;
        for (o, p) in out.chunks_exact_mut(3).zip(positions) {
            o.copy_from_slice(p);
        }
        count(out.len())
    })
}

/// Triangles at `level`; or a negative status.
///
/// # Safety
/// `lod` null or a live handle.
#[no_mangle]
pub unsafe extern "C" fn stripkit_lod_triangles(lod: *const stripkit_lod, level: u32) -> i64 {
    guard("stripkit_lod_triangles", || {
        let sets = unsafe { model(lod) }?;
        level_in_range(sets, level)?;
        Ok(sets.triangles_at(level) as i64)
    })
}

/// The first level with at most `max_triangles` triangles (the coarsest when none has so
/// few); or a negative status.
///
/// # Safety
/// `lod` null or a live handle.
#[no_mangle]
pub unsafe extern "C" fn stripkit_lod_level_for_triangles(lod: *const stripkit_lod, max_triangles: u64) -> i64 {
    guard("stripkit_lod_level_for_triangles", || Ok(unsafe { model(lod) }?.level_for_triangles(max_triangles) as i64))
}

/// Indices [`stripkit_lod_extract`] writes at `level`; or a negative status.
///
/// # Safety
/// `lod` null or a live handle.
#[no_mangle]
pub unsafe extern "C" fn stripkit_lod_extract_bound(lod: *const stripkit_lod, level: u32) -> i64 {
    guard("stripkit_lod_extract_bound", || {
        let sets = unsafe { model(lod) }?;
        level_in_range(sets, level)?;
        let mut buffer = Vec::new();
        sets.cursor(level).compact(u32::MAX, &mut buffer);
        count(buffer.len())
    })
}

/// The strips of `level`, separated by `restart_index`, into `destination`; returns the
/// indices written or a negative status.
///
/// # Safety
/// `lod` null or a live handle; `destination` writable for `destination_size` items.
#[no_mangle]
pub unsafe extern "C" fn stripkit_lod_extract(
    lod: *const stripkit_lod,
    level: u32,
    destination: *mut u32,
    destination_size: usize,
    restart_index: u32,
) -> i64 {
    guard("stripkit_lod_extract", || {
        let sets = unsafe { model(lod) }?;
        level_in_range(sets, level)?;
        let vertices = sets.positions().len().max(sets.input_vertices() as usize);
        if (restart_index as usize) < vertices {
            return Err(Failure::new(
                Status::BadOption,
                format!("restart index {restart_index} is a vertex id (there are {vertices} vertices)"),
            ));
        }
        let mut buffer = Vec::new();
        sets.cursor(level).compact(restart_index, &mut buffer);
        let out = unsafe { output(destination, destination_size, buffer.len(), "destination") }?;
        out.copy_from_slice(&buffer);
        count(buffer.len())
    })
}

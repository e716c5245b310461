//! The index-buffer entry points, meshoptimizer's shape: [`stripify_indices`],
//! [`stripify_bound`] and [`unstripify`] over caller-owned arrays, 32- and 16-bit.

use crate::boundary::{count, guard, input, output, Failure, Outcome, Status};
use crate::options::{self, stripkit_options};
use libstripkit::{stripify_bound, stripify_indices, unstripify};

/// The most indices `stripkit_stripify` writes for `index_count` input indices.
#[no_mangle]
pub extern "C" fn stripkit_stripify_bound(index_count: usize) -> usize {
    stripify_bound(index_count)
}

/// The most indices `stripkit_unstripify` writes for `index_count` strip indices.
#[no_mangle]
pub extern "C" fn stripkit_unstripify_bound(index_count: usize) -> usize {
    index_count.saturating_sub(2).saturating_mul(3)
}

/// Strips for a triangle list; returns the indices written or a negative status.
///
/// # Safety
/// Pointers as the header states: `indices` readable for `index_count` items,
/// `destination` writable for `destination_size`, `options` null or valid.
#[no_mangle]
pub unsafe extern "C" fn stripkit_stripify(
    destination: *mut u32,
    destination_size: usize,
    indices: *const u32,
    index_count: usize,
    vertex_count: usize,
    restart_index: u32,
    options: *const stripkit_options,
) -> i64 {
    guard("stripkit_stripify", || {
        let indices = unsafe { input(indices, index_count, "indices") }?;
        let strip = strip(indices, vertex_count, restart_index, options)?;
        let out = unsafe { output(destination, destination_size, strip.len(), "destination") }?;
        out.copy_from_slice(&strip);
        count(strip.len())
    })
}

/// [`stripkit_stripify`] for 16-bit indices.
///
/// # Safety
/// As [`stripkit_stripify`].
#[no_mangle]
pub unsafe extern "C" fn stripkit_stripify16(
    destination: *mut u16,
    destination_size: usize,
    indices: *const u16,
    index_count: usize,
    vertex_count: usize,
    restart_index: u16,
    options: *const stripkit_options,
) -> i64 {
    guard("stripkit_stripify16", || {
        let indices = unsafe { input(indices, index_count, "indices") }?;
        if vertex_count > 1 << 16 {
            return Err(Failure::new(Status::Invalid, format!("{vertex_count} vertices do not fit 16-bit indices")));
        }
        let wide: Vec<u32> = indices.iter().map(|&i| i as u32).collect();
        let strip = strip(&wide, vertex_count, restart_index as u32, options)?;
        let out = unsafe { output(destination, destination_size, strip.len(), "destination") }?;
        // Every index is below vertex_count (at most 65,536) or the 16-bit restart index.
        for (o, &i) in out.iter_mut().zip(&strip) {
            *o = i as u16;
        }
        count(strip.len())
    })
}

unsafe fn strip(
    indices: &[u32],
    vertex_count: usize,
    restart_index: u32,
    options: *const stripkit_options,
) -> Outcome<Vec<u32>> {
    let options = unsafe { options::read(options) }?.restart_index(restart_index);
    Ok(stripify_indices(indices, vertex_count, &options)?)
}

/// The triangle list a strip buffer draws; returns the indices written or a negative status.
///
/// # Safety
/// `indices` readable for `index_count` items, `destination` writable for `destination_size`.
#[no_mangle]
pub unsafe extern "C" fn stripkit_unstripify(
    destination: *mut u32,
    destination_size: usize,
    indices: *const u32,
    index_count: usize,
    restart_index: u32,
) -> i64 {
    guard("stripkit_unstripify", || {
        let indices = unsafe { input(indices, index_count, "indices") }?;
        let list = unstripify(indices, restart_index);
        let out = unsafe { output(destination, destination_size, list.len(), "destination") }?;
        out.copy_from_slice(&list);
        count(list.len())
    })
}

/// [`stripkit_unstripify`] for 16-bit indices.
///
/// # Safety
/// As [`stripkit_unstripify`].
#[no_mangle]
pub unsafe extern "C" fn stripkit_unstripify16(
    destination: *mut u16,
    destination_size: usize,
    indices: *const u16,
    index_count: usize,
    restart_index: u16,
) -> i64 {
    guard("stripkit_unstripify16", || {
        let indices = unsafe { input(indices, index_count, "indices") }?;
        let wide: Vec<u32> = indices.iter().map(|&i| i as u32).collect();
        let list = unstripify(&wide, restart_index as u32);
        let out = unsafe { output(destination, destination_size, list.len(), "destination") }?;
        for (o, &i) in out.iter_mut().zip(&list) {
            *o = i as u16;
        }
        count(list.len())
    })
}

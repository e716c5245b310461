//! What every entry point does at the language boundary: status codes, the thread's last
//! error message, panics caught, pointers and lengths checked before they become slices.

use libstripkit::Error;
use std::cell::RefCell;
use std::ffi::{c_char, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// The status codes of the header's `stripkit_status` (negative: an error).
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Success.
    Ok = 0,
    /// A required pointer was null.
    NullPointer = -1,
    /// The input is invalid (an index out of range, a count that is not whole triangles, ...).
    Invalid = -2,
    /// An option is out of its range (or the options' size field is wrong).
    BadOption = -3,
    /// The destination is smaller than the result.
    TooSmall = -4,
    /// A `.sets` blob is malformed.
    Format = -5,
    /// The library's own check of its output failed (a bug: please report it).
    Verification = -6,
    /// The library panicked (a bug: please report it); caught at the boundary.
    Panic = -7,
    /// Any other failure.
    Other = -8,
}

/// An error on its way to the caller: its status and message.
pub(crate) struct Failure {
    pub status: Status,
    pub message: String,
}

impl Failure {
    pub(crate) fn new(status: Status, message: impl Into<String>) -> Self {
        Failure { status, message: message.into() }
    }
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        let status = match &e {
            Error::Invalid(_) => Status::Invalid,
            Error::BadOption { .. } => Status::BadOption,
            Error::Format { .. } | Error::UnknownFormat { .. } => Status::Format,
            Error::Verification(_) => Status::Verification,
            _ => Status::Other,
        };
        Failure::new(status, e.to_string())
    }
}

pub(crate) type Outcome<T> = std::result::Result<T, Failure>;

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

fn set_last_error(function: &str, message: &str) {
    let text = format!("{function}: {message}").replace('\0', " ");
    let text = CString::new(text).unwrap_or_default();
    LAST_ERROR.with(|e| *e.borrow_mut() = text);
}

/// The message of the last failed call on this thread (`""` after a successful one).
/// The pointer stays valid until the thread's next stripkit call.
#[no_mangle]
pub extern "C" fn stripkit_last_error() -> *const c_char {
    LAST_ERROR.with(|e| e.borrow().as_ptr())
}

/// Runs `body` for `function`: its value, or a failure's (or a panic's) status with the
/// message stored for [`stripkit_last_error`].
pub(crate) fn guard<T: From<i32>>(function: &str, body: impl FnOnce() -> Outcome<T>) -> T {
    set_last_error_empty();
    let failure = match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(value)) => return value,
        Ok(Err(failure)) => failure,
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            Failure::new(Status::Panic, format!("internal error (panic: {what}); please report it"))
        }
    };
    set_last_error(function, &failure.message);
    T::from(failure.status as i32)
}

fn set_last_error_empty() {
    LAST_ERROR.with(|e| {
        if !e.borrow().is_empty() {
            *e.borrow_mut() = CString::default();
        }
    });
}

/// `count` items at `ptr` as a slice; null or an impossible length is an error.
///
/// # Safety
/// A non-null `ptr` must point to `count` readable items that outlive the slice.
pub(crate) unsafe fn input<'a, T>(ptr: *const T, count: usize, what: &str) -> Outcome<&'a [T]> {
    if ptr.is_null() {
        return Err(Failure::new(Status::NullPointer, format!("{what} is null")));
    }
    check_len::<T>(count, what)?;
    Ok(unsafe { std::slice::from_raw_parts(ptr, count) })
}

/// `capacity` writable items at `ptr`, once `needed` fit; null or too small is an error.
///
/// # Safety
/// A non-null `ptr` must point to `capacity` writable items that outlive the slice.
pub(crate) unsafe fn output<'a, T>(ptr: *mut T, capacity: usize, needed: usize, what: &str) -> Outcome<&'a mut [T]> {
    if ptr.is_null() {
        return Err(Failure::new(Status::NullPointer, format!("{what} is null")));
    }
    if capacity < needed {
        return Err(Failure::new(
            Status::TooSmall,
            format!("{what} holds {capacity} items but the result has {needed}"),
        ));
    }
    check_len::<T>(capacity, what)?;
    Ok(unsafe { std::slice::from_raw_parts_mut(ptr, needed) })
}

fn check_len<T>(count: usize, what: &str) -> Outcome<()> {
    if count.checked_mul(std::mem::size_of::<T>()).is_none_or(|bytes| bytes > isize::MAX as usize) {
        return Err(Failure::new(Status::Invalid, format!("{what}: {count} items do not fit in memory")));
    }
    Ok(())
}

/// A count as the `int64_t` the counting functions return.
pub(crate) fn count(n: usize) -> Outcome<i64> {
    i64::try_from(n).map_err(|_| Failure::new(Status::Invalid, format!("{n} does not fit int64_t")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::CStr;

    fn last_error() -> String {
        unsafe { CStr::from_ptr(stripkit_last_error()) }.to_str().unwrap().to_string()
    }

    #[test]
    fn a_panic_becomes_a_status_and_a_message() {
        let status: i64 = guard("stripkit_test", || -> Outcome<i64> { panic!("boom at 3") });
        assert_eq!(status, Status::Panic as i64);
        assert_eq!(last_error(), "stripkit_test: internal error (panic: boom at 3); please report it");
        // The next successful call clears the message.
        assert_eq!(guard("stripkit_test", || Ok(5i64)), 5);
        assert_eq!(last_error(), "");
    }

    #[test]
    fn a_library_error_keeps_its_kind() {
        let status: i32 = guard("stripkit_test", || Err(Error::Invalid("no triangles".into()).into()));
        assert_eq!(status, Status::Invalid as i32);
        assert_eq!(last_error(), "stripkit_test: no triangles");
    }

    #[test]
    fn nulls_and_impossible_lengths_are_refused() {
        let status = unsafe { input::<u32>(std::ptr::null(), 3, "indices") }.err().unwrap();
        assert_eq!((status.status, status.message.as_str()), (Status::NullPointer, "indices is null"));
        let data = [1u32, 2, 3];
        let too_long = unsafe { input(data.as_ptr(), usize::MAX / 2, "indices") }.err().unwrap();
        assert_eq!(too_long.status, Status::Invalid);
        let mut out = [0u32; 2];
        let small = unsafe { output(out.as_mut_ptr(), 2, 3, "destination") }.err().unwrap();
        assert_eq!(small.status, Status::TooSmall);
        assert_eq!(small.message, "destination holds 2 items but the result has 3");
    }
}

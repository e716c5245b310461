//! Hints to the processor that change no result: the one prefetch the check's counting
//! sort and the LoD cursor share.

/// A hint that `x` will be read soon (nothing on targets without one).
#[inline(always)]
pub(crate) fn prefetch<T>(x: &T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch hint only loads a cache line and never faults; `x` is a
    // valid reference.
    unsafe {
        std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(x as *const T as *const i8)
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = x;
}

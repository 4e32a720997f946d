//! Hints to the processor, which change no value: memory asked for ahead
//! of its use, where a loop knows the addresses it will read long before
//! the processor's own prefetchers could guess them (the corners of the
//! faces to come, the ring of a vertex just put in a search's heap).

/// Asks the processor to bring the cache line holding `*at` into its
/// caches. Any address may be given, valid or not: a prefetch never faults
/// and changes no value. Nothing on architectures other than x86-64.
#[inline(always)]
pub fn prefetch<T>(at: *const T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: `_mm_prefetch` needs only SSE, which every x86-64 processor
    // has; a prefetch never faults, whatever the address.
    unsafe {
        std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(at.cast::<i8>())
    };
    #[cfg(not(target_arch = "x86_64"))]
    let _ = at;
}

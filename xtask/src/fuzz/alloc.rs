//! A counting global allocator: the bytes currently allocated and the peak
//! since the last [`reset_peak`], so the fuzzer can fail an input that makes a
//! reader allocate far more than its size justifies. Inside [`limited`]
//! (the fuzzer's and the matrix's hostile inputs), requests that would take
//! the total past [`HARD_LIMIT`] above what was allocated when it began are
//! refused (the process aborts with the allocation error) instead of
//! exhausting the machine's memory. The limit counts from that start, not
//! from zero: what earlier work keeps allocated is not the input's doing
//! (faer's matrix products keep a packing buffer of twice the last-level
//! cache per thread that ever multiplied, 960 MiB on a VM that reports a
//! 480 MiB L3, three of them after `validate`'s spectral group). Every other
//! command of xtask (bench and validate on 1e6-vertex meshes) is only
//! counted, never limited. The fuzzer
//! prints how to reproduce the input it was running first (see
//! [`set_context`]). Cost: two relaxed atomic operations per call.

use mesh_kernel::alloc::BlockCache;
use std::alloc::{GlobalAlloc, Layout};
use std::io::Write;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Inside [`limited`], allocations past this many bytes above what was
/// allocated when it began are refused.
pub const HARD_LIMIT: usize = 2 << 30;

static CURRENT: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
/// The largest total allowed: the total when [`limited`] began plus
/// [`HARD_LIMIT`] inside it, no limit (`usize::MAX`) outside.
static CEILING: AtomicUsize = AtomicUsize::new(usize::MAX);

/// Runs `f` with [`HARD_LIMIT`] enforced, counted from the bytes allocated now.
pub fn limited<T>(f: impl FnOnce() -> T) -> T {
    /// Lifts the limit again, also when `f` unwinds.
    struct Lift;
    impl Drop for Lift {
        fn drop(&mut self) {
            CEILING.store(usize::MAX, Ordering::Relaxed);
        }
    }
    CEILING.store(current().saturating_add(HARD_LIMIT), Ordering::Relaxed);
    let _lift = Lift;
    f()
}

/// What to print when an allocation is refused (the current fuzz input).
static CONTEXT: Mutex<[u8; 256]> = Mutex::new([0; 256]);

/// The workspace's allocator (`mesh_kernel::alloc::BlockCache`, as the
/// `mesh` binary uses), counted.
pub struct Counting;

impl Counting {
    fn grow(&self, bytes: usize) -> bool {
        let now = CURRENT.fetch_add(bytes, Ordering::Relaxed) + bytes;
        if now > CEILING.load(Ordering::Relaxed) {
            CURRENT.fetch_sub(bytes, Ordering::Relaxed);
            refused(bytes);
            return false;
        }
        PEAK.fetch_max(now, Ordering::Relaxed);
        true
    }

    /// Counts `bytes`, then allocates with `f` (null, uncounted, when
    /// refused or when the system fails).
    fn counted(&self, bytes: usize, f: impl FnOnce() -> *mut u8) -> *mut u8 {
        if !self.grow(bytes) {
            return std::ptr::null_mut();
        }
        let p = f();
        if p.is_null() {
            CURRENT.fetch_sub(bytes, Ordering::Relaxed);
        }
        p
    }
}

/// Prints the context without allocating (a fixed buffer, stderr unbuffered).
fn refused(bytes: usize) {
    let mut err = std::io::stderr();
    let _ = err.write_all(b"\nfuzz: allocation refused (2 GiB over what was allocated before the input)");
    let _ = write_number(&mut err, bytes);
    if let Ok(context) = CONTEXT.try_lock() {
        let end = context.iter().position(|b| *b == 0).unwrap_or(context.len());
        let _ = err.write_all(b"; input: ");
        let _ = err.write_all(&context[..end]);
    }
    let _ = err.write_all(b"\n");
}

fn write_number(out: &mut impl Write, mut n: usize) -> std::io::Result<()> {
    let mut digits = [0u8; 24];
    let mut i = digits.len();
    loop {
        i -= 1;
        digits[i] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    out.write_all(b" asking for ")?;
    out.write_all(&digits[i..])?;
    out.write_all(b" bytes")
}

// SAFETY: every call is forwarded to `BlockCache` unchanged; only counters are
// updated around it, and a refused request returns null as the trait allows.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        self.counted(layout.size(), || BlockCache.alloc(layout))
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        self.counted(layout.size(), || BlockCache.alloc_zeroed(layout))
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        BlockCache.dealloc(ptr, layout);
        CURRENT.fetch_sub(layout.size(), Ordering::Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let old = layout.size();
        if new_size > old && !self.grow(new_size - old) {
            return std::ptr::null_mut();
        }
        let p = BlockCache.realloc(ptr, layout, new_size);
        if p.is_null() {
            if new_size > old {
                CURRENT.fetch_sub(new_size - old, Ordering::Relaxed);
            }
        } else if new_size < old {
            CURRENT.fetch_sub(old - new_size, Ordering::Relaxed);
        }
        p
    }
}

/// Bytes allocated now.
pub fn current() -> usize {
    CURRENT.load(Ordering::Relaxed)
}

/// Starts a new peak measurement at the current total.
pub fn reset_peak() {
    PEAK.store(current(), Ordering::Relaxed);
}

/// The largest total since [`reset_peak`].
pub fn peak() -> usize {
    PEAK.load(Ordering::Relaxed)
}

/// Sets the text printed if an allocation is refused (truncated to 255 bytes).
pub fn set_context(text: &str) {
    if let Ok(mut buffer) = CONTEXT.lock() {
        let n = text.len().min(buffer.len() - 1);
        buffer[..n].copy_from_slice(&text.as_bytes()[..n]);
        buffer[n] = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn peak_sees_a_large_allocation() {
        reset_peak();
        let base = current();
        let big = vec![1u8; 64 << 20];
        let seen = peak().saturating_sub(base);
        drop(big);
        // Other test threads allocate too: at least ours is counted.
        assert!(seen >= 64 << 20, "peak grew by {seen} bytes");
        assert!(current() < base + (64 << 20));
    }
}

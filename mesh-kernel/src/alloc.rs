//! A global allocator that backs large blocks with transparent huge pages
//! (feature `huge-pages`, Linux; the system allocator everywhere else).
//!
//! A mesh algorithm writes its large outputs (normals, Laplacian entries,
//! half-edge arrays: tens of MB on a 1e6-vertex mesh) into memory it has
//! just allocated. The system allocator maps such blocks fresh from the
//! kernel and returns them when freed, so the first touch of every 4 KiB
//! page is a page fault in which the kernel zeroes that page: measured at
//! 0.46 ms per MB on a 2-core AMD EPYC VM, half of the time of building the
//! half-edges of a 41k-vertex mesh. [`HugePages`] maps every block of at
//! least 4 MiB itself, on a 2 MiB boundary, and asks for transparent huge
//! pages (`madvise(MADV_HUGEPAGE)`): one fault per 2 MiB, 0.04-0.05 ms per
//! MB on the same machine. numpy does the same for its arrays of 4 MiB and
//! more, so this also puts the workspace on an equal footing with peers that
//! return numpy arrays.
//!
//! Smaller blocks, and blocks aligned to more than 2 MiB, go to the system
//! allocator. With glibc, its heap is told once (on the first allocation)
//! to keep them there: below 4 MiB no block gets a fresh mapping of its own
//! (glibc's default threshold starts at 128 KiB and only rises after a
//! larger mapped block is freed, which never happens here), and up to
//! [`KEPT_FREE`] bytes freed at the top of the heap stay for the next
//! allocation instead of going back to the kernel. Without that, a
//! 1-4 MiB array reallocated at every call faults its pages in again each
//! time (the midpoint upsample of a 41k-vertex mesh ran 1.4 times slower). Where the kernel has transparent huge pages turned
//! off (`/sys/kernel/mm/transparent_hugepage/enabled` = `never`) the advice
//! is ignored and a large block costs what it costs under the system
//! allocator. A large block occupies a whole number of 2 MiB pages.
//!
//! A library cannot choose the allocator of the program that uses it: the
//! `mesh` binary, `cargo xtask` and the Python package install this one,
//! and a program of yours can with two lines:
//!
//! ```ignore
//! #[global_allocator]
//! static ALLOCATOR: mesh_kernel::alloc::HugePages = mesh_kernel::alloc::HugePages;
//! ```

use std::alloc::{GlobalAlloc, Layout, System};

/// The global allocator of this module: the system allocator, with blocks
/// of at least [`LARGE_BLOCK`] bytes mapped on huge-page boundaries.
#[derive(Debug, Clone, Copy, Default)]
pub struct HugePages;

/// Blocks of at least this many bytes (4 MiB, numpy's threshold) are mapped
/// on huge pages.
pub const LARGE_BLOCK: usize = 4 << 20;

/// Bytes of freed heap that glibc keeps for reuse (its trim threshold) and
/// adds to each growth of the heap (its top pad), once [`HugePages`] has
/// made its first allocation.
pub const KEPT_FREE: usize = 64 << 20;

/// The transparent huge page size of x86-64 and of aarch64 with 4 KiB base
/// pages; a multiple of every base page size, so mapped lengths rounded to
/// it are whole pages anywhere.
const HUGE_PAGE: usize = 2 << 20;

/// Whether [`HugePages`] maps this block itself (the same answer for the
/// allocation and the release of a block, which see the same layout).
fn mapped(layout: Layout) -> bool {
    cfg!(target_os = "linux") && layout.size() >= LARGE_BLOCK && layout.align() <= HUGE_PAGE
}

/// The length of the mapping behind a mapped block of `size` bytes.
#[cfg_attr(not(target_os = "linux"), allow(dead_code))]
fn mapped_len(size: usize) -> usize {
    size.div_ceil(HUGE_PAGE) * HUGE_PAGE
}

/// Sets glibc's heap thresholds (see the module's documentation) on the
/// first call; one relaxed load on every later one.
fn tune_heap_once() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        use std::sync::atomic::{AtomicBool, Ordering};
        static DONE: AtomicBool = AtomicBool::new(false);
        if !DONE.load(Ordering::Relaxed) && !DONE.swap(true, Ordering::Relaxed) {
            map::tune_heap();
        }
    }
}

#[cfg(target_os = "linux")]
mod map {
    use super::HUGE_PAGE;
    use libc::{c_void, MAP_ANONYMOUS, MAP_FAILED, MAP_PRIVATE, PROT_READ, PROT_WRITE};

    /// `len` (a multiple of [`HUGE_PAGE`]) zeroed bytes on a 2 MiB boundary,
    /// advised to use huge pages; null when the kernel refuses.
    pub(super) fn map(len: usize) -> *mut u8 {
        let Some(total) = len.checked_add(HUGE_PAGE) else { return std::ptr::null_mut() };
        // SAFETY: an anonymous private mapping at an address of the kernel's
        // choosing touches no existing memory. The parts cut away below lie
        // inside it, and the advice only concerns the part kept.
        unsafe {
            let raw =
                libc::mmap(std::ptr::null_mut(), total, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
            if raw == MAP_FAILED {
                return std::ptr::null_mut();
            }
            let head = (raw as usize).next_multiple_of(HUGE_PAGE) - raw as usize;
            let start = raw.cast::<u8>().add(head);
            if head > 0 {
                libc::munmap(raw, head);
            }
            libc::munmap(start.add(len).cast::<c_void>(), total - head - len);
            // Refused advice (huge pages compiled out of the kernel) leaves
            // ordinary pages: nothing to handle.
            libc::madvise(start.cast::<c_void>(), len, libc::MADV_HUGEPAGE);
            start
        }
    }

    /// Grows a mapping made by [`map`] from `old_len` to `new_len` bytes,
    /// moving it (without copying) where it cannot grow in place; the new
    /// address is page-aligned. Null when the kernel refuses (the old
    /// mapping is then untouched).
    ///
    /// # Safety
    /// `ptr..ptr + old_len` must be mapped by [`map`].
    pub(super) unsafe fn remap(ptr: *mut u8, old_len: usize, new_len: usize) -> *mut u8 {
        let new = libc::mremap(ptr.cast::<c_void>(), old_len, new_len, libc::MREMAP_MAYMOVE);
        if new == MAP_FAILED {
            return std::ptr::null_mut();
        }
        libc::madvise(new, new_len, libc::MADV_HUGEPAGE);
        new.cast::<u8>()
    }

    /// glibc's mmap threshold at [`super::LARGE_BLOCK`], its trim
    /// threshold and top pad at [`super::KEPT_FREE`] (the values fit an
    /// `int`). A refused setting leaves glibc's default.
    #[cfg(target_env = "gnu")]
    pub(super) fn tune_heap() {
        use libc::{c_int, M_MMAP_THRESHOLD, M_TOP_PAD, M_TRIM_THRESHOLD};
        const _: () = assert!(super::LARGE_BLOCK <= super::KEPT_FREE && super::KEPT_FREE <= c_int::MAX as usize);
        // SAFETY: `mallopt` only sets parameters of glibc's allocator; it is
        // called outside any allocation (before this allocation's request).
        unsafe {
            libc::mallopt(M_MMAP_THRESHOLD, super::LARGE_BLOCK as c_int);
            libc::mallopt(M_TRIM_THRESHOLD, super::KEPT_FREE as c_int);
            libc::mallopt(M_TOP_PAD, super::KEPT_FREE as c_int);
        }
    }

    /// Returns `len` bytes at `ptr` (a part of a mapping made by [`map`]).
    ///
    /// # Safety
    /// `ptr..ptr + len` must be mapped by [`map`] (or what remains of it) and
    /// no longer used.
    pub(super) unsafe fn unmap(ptr: *mut u8, len: usize) {
        libc::munmap(ptr.cast::<c_void>(), len);
    }
}

// SAFETY: blocks below the threshold are the system allocator's, unchanged.
// A mapped block is `mapped_len(size)` bytes from `map` (page-aligned, and
// 2 MiB-aligned, so every alignment `mapped` accepts holds), released with
// the same length since `dealloc` gets the layout it was allocated with;
// `realloc` keeps the mapping's length equal to `mapped_len` of the new
// size (moving it with `mremap` only for alignments that every page
// address meets), or moves the contents into a block of the other kind.
unsafe impl GlobalAlloc for HugePages {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        tune_heap_once();
        #[cfg(target_os = "linux")]
        if mapped(layout) {
            return map::map(mapped_len(layout.size()));
        }
        System.alloc(layout)
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        tune_heap_once();
        #[cfg(target_os = "linux")]
        if mapped(layout) {
            // Fresh anonymous pages are zero.
            return map::map(mapped_len(layout.size()));
        }
        System.alloc_zeroed(layout)
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        #[cfg(target_os = "linux")]
        if mapped(layout) {
            return map::unmap(ptr, mapped_len(layout.size()));
        }
        System.dealloc(ptr, layout)
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let new_layout = Layout::from_size_align_unchecked(new_size, layout.align());
        match (mapped(layout), mapped(new_layout)) {
            (false, false) => System.realloc(ptr, layout, new_size),
            #[cfg(target_os = "linux")]
            (true, true) if mapped_len(new_size) <= mapped_len(layout.size()) => {
                // Shrinking (or growing within the last huge page): keep the
                // block, return the pages past its new end.
                let (old_len, new_len) = (mapped_len(layout.size()), mapped_len(new_size));
                if new_len < old_len {
                    map::unmap(ptr.add(new_len), old_len - new_len);
                }
                ptr
            }
            #[cfg(target_os = "linux")]
            (true, true) if layout.align() <= 4096 => {
                // Growing: the kernel moves the pages, nothing is copied.
                map::remap(ptr, mapped_len(layout.size()), mapped_len(new_size))
            }
            _ => {
                // Crossing the threshold (or growing a block aligned to more
                // than any base page): a new block of the right kind, the
                // contents copied.
                let new = self.alloc(new_layout);
                if !new.is_null() {
                    std::ptr::copy_nonoverlapping(ptr, new, layout.size().min(new_size));
                    self.dealloc(ptr, layout);
                }
                new
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every path of the allocator through its trait, on blocks below,
    /// at and above the threshold, with the contents checked after each move.
    #[test]
    fn blocks_of_every_size_keep_their_contents() {
        let sizes = [64, LARGE_BLOCK - 8, LARGE_BLOCK, LARGE_BLOCK + 3 * HUGE_PAGE + 24, 3 * LARGE_BLOCK];
        for &from in &sizes {
            for &to in &sizes {
                for align in [8, 64, 4096] {
                    let layout = Layout::from_size_align(from, align).unwrap();
                    // SAFETY: non-zero sizes; each block is released once,
                    // with the layout it has at that moment.
                    unsafe {
                        let zeroed = HugePages.alloc_zeroed(layout);
                        assert!(!zeroed.is_null() && (zeroed as usize).is_multiple_of(align));
                        assert!(std::slice::from_raw_parts(zeroed, from).iter().all(|&b| b == 0));
                        HugePages.dealloc(zeroed, layout);

                        let p = HugePages.alloc(layout);
                        assert!(!p.is_null() && (p as usize).is_multiple_of(align));
                        for i in 0..from {
                            *p.add(i) = (i % 251) as u8;
                        }
                        let q = HugePages.realloc(p, layout, to);
                        assert!(!q.is_null() && (q as usize).is_multiple_of(align), "{from} -> {to}, align {align}");
                        let kept = std::slice::from_raw_parts(q, from.min(to));
                        assert!(kept.iter().enumerate().all(|(i, &b)| b == (i % 251) as u8), "{from} -> {to}");
                        // The whole new block is writable.
                        std::ptr::write_bytes(q, 7, to);
                        HugePages.dealloc(q, Layout::from_size_align(to, align).unwrap());
                    }
                }
            }
        }
    }

    #[test]
    fn large_blocks_are_mapped_on_huge_page_boundaries() {
        let layout = Layout::from_size_align(LARGE_BLOCK + 1, 8).unwrap();
        assert_eq!(mapped(layout), cfg!(target_os = "linux"));
        assert!(!mapped(Layout::from_size_align(LARGE_BLOCK - 1, 8).unwrap()));
        assert!(!mapped(Layout::from_size_align(LARGE_BLOCK, 2 * HUGE_PAGE).unwrap()));
        assert_eq!(mapped_len(LARGE_BLOCK + 1), LARGE_BLOCK + HUGE_PAGE);
        // SAFETY: allocated and released with the same layout.
        unsafe {
            let p = HugePages.alloc(layout);
            assert!(!p.is_null());
            if cfg!(target_os = "linux") {
                assert!((p as usize).is_multiple_of(HUGE_PAGE));
            }
            HugePages.dealloc(p, layout);
        }
    }
}

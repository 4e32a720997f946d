//! A global allocator that keeps freed large blocks for reuse (feature
//! `block-cache`, Linux; the system allocator everywhere else).
//!
//! A mesh algorithm writes its large outputs (normals, Laplacian entries,
//! half-edge arrays, factor storage: tens of MB to GB on a 1e6-vertex mesh)
//! into memory it has just allocated. The system allocator maps such blocks
//! fresh from the kernel and gives them back when they are freed, so every
//! call pays a page fault per 4 KiB page on first touch, in which the kernel
//! zeroes that page: measured at 0.40-0.66 ms per MB on a 2-core AMD EPYC
//! VM, as long as building the half-edges of a 41k-vertex mesh takes.
//! [`BlockCache`] maps every block of at least [`LARGE_BLOCK`] bytes itself
//! and, when it is freed, keeps its pages (up to [`kept_limit`] bytes in
//! all) for the next large allocation, which then costs no fault at all.
//! Freed memory is kept only up to what the program had in use at once: a
//! block mapped afresh first gives kept ones back (smallest first) until
//! kept and used blocks together fit in the most ever in use, so the cache
//! never raises the peak memory of large blocks. A process that wants the
//! kept pages back can call [`release`].
//!
//! Smaller blocks, and blocks aligned to more than 2 MiB, go to the system
//! allocator. With glibc, its heap is told once (on the first allocation)
//! to keep them there: below 4 MiB no block gets a fresh mapping of its own
//! (glibc's default threshold starts at 128 KiB and only rises after a
//! larger mapped block is freed, which never happens here), and up to
//! [`KEPT_FREE`] bytes freed at the top of the heap stay for the next
//! allocation instead of going back to the kernel. Without that, a
//! 1-4 MiB array reallocated at every call faults its pages in again each
//! time (the midpoint upsample of a 41k-vertex mesh ran 1.4 times slower).
//!
//! Transparent huge pages (`madvise(MADV_HUGEPAGE)`, one fault per 2 MiB)
//! were measured and left out. They cost 0.08-0.12 ms per MB where the
//! kernel reuses pages the process had just freed, but 2.2-2.3 ms per MB on
//! a VM whose free memory of 8 MiB blocks goes back to the host (Firecracker
//! with free page reporting), which is where whole huge pages come from: a
//! heat-method factorization of a 470k-vertex mesh took 4.3-4.5 s with them
//! and 3.2-3.4 s without (see BENCHMARKS.md, 2026-12-03).
//!
//! A library cannot choose the allocator of the program that uses it: the
//! `mesh` binary, `cargo xtask` and the Python package install this one,
//! and a program of yours can with two lines:
//!
//! ```ignore
//! #[global_allocator]
//! static ALLOCATOR: mesh_kernel::alloc::BlockCache = mesh_kernel::alloc::BlockCache;
//! ```

use std::alloc::{GlobalAlloc, Layout, System};

/// The global allocator of this module: the system allocator, with blocks
/// of at least [`LARGE_BLOCK`] bytes mapped by hand and kept for reuse when
/// freed.
#[derive(Debug, Clone, Copy, Default)]
pub struct BlockCache;

/// Blocks of at least this many bytes (4 MiB) are mapped by [`BlockCache`]
/// and kept when freed.
pub const LARGE_BLOCK: usize = 4 << 20;

/// Most bytes of freed large blocks kept for reuse (4 GiB), on a machine
/// with at least four times as much physical memory (see [`kept_limit`]).
///
/// A repeated eigensolve of 20 pairs at 470k vertices allocates 1.2-1.5 GB
/// of large blocks per call; with 1 GiB kept, 615 MB of them were mapped
/// and faulted in afresh at every call (BENCHMARKS.md, "Keeping up to 4
/// GiB of freed blocks").
pub const KEPT_LARGE: usize = (1usize << 30).saturating_mul(4);

/// Most bytes of freed large blocks kept for reuse: [`KEPT_LARGE`], or a
/// quarter of the machine's physical memory when that is less (1 GiB when
/// it cannot be read); 0 off Linux, where [`BlockCache`] keeps nothing. A
/// freed block that does not fit makes the largest kept ones go back to
/// the kernel.
pub fn kept_limit() -> usize {
    #[cfg(target_os = "linux")]
    {
        use std::sync::atomic::{AtomicUsize, Ordering};
        // 0: not read yet (reading twice is harmless).
        static LIMIT: AtomicUsize = AtomicUsize::new(0);
        let known = LIMIT.load(Ordering::Relaxed);
        if known != 0 {
            return known;
        }
        let limit = map::physical_memory().map_or(1 << 30, |bytes| (bytes / 4).min(KEPT_LARGE)).max(LARGE_BLOCK);
        LIMIT.store(limit, Ordering::Relaxed);
        limit
    }
    #[cfg(not(target_os = "linux"))]
    {
        0
    }
}

/// Bytes of freed heap that glibc keeps for reuse (its trim threshold) and
/// adds to each growth of the heap (its top pad), once [`BlockCache`] has
/// made its first allocation.
pub const KEPT_FREE: usize = 64 << 20;

/// Large blocks are mapped in whole multiples of this (2 MiB, a multiple of
/// every base page size) and on such a boundary, so that a freed block
/// serves any later request of up to its length and alignment.
const GRANULE: usize = 2 << 20;

/// Most freed blocks kept at once.
const SLOTS: usize = 64;

/// Whether [`BlockCache`] maps this block itself (the same answer for the
/// allocation and the release of a block, which see the same layout).
fn mapped(layout: Layout) -> bool {
    cfg!(target_os = "linux") && layout.size() >= LARGE_BLOCK && layout.align() <= GRANULE
}

/// The length of the mapping behind a mapped block of `size` bytes.
#[cfg_attr(not(target_os = "linux"), allow(dead_code))]
fn mapped_len(size: usize) -> usize {
    size.div_ceil(GRANULE) * GRANULE
}

/// Gives every kept block back to the kernel; returns the bytes released
/// (0 as well when another thread is using the cache at that moment). For
/// long-running programs after a large computation (the kept blocks
/// otherwise stay mapped until they are reused or the process ends).
pub fn release() -> usize {
    #[cfg(target_os = "linux")]
    {
        kept::release()
    }
    #[cfg(not(target_os = "linux"))]
    {
        0
    }
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
    use super::GRANULE;
    use libc::{c_void, MAP_ANONYMOUS, MAP_FAILED, MAP_PRIVATE, PROT_READ, PROT_WRITE};

    /// `len` (a multiple of [`GRANULE`]) zeroed bytes on a [`GRANULE`]
    /// boundary; null when the kernel refuses.
    pub(super) fn map(len: usize) -> *mut u8 {
        let Some(total) = len.checked_add(GRANULE) else { return std::ptr::null_mut() };
        // SAFETY: an anonymous private mapping at an address of the kernel's
        // choosing touches no existing memory; the parts cut away below lie
        // inside it.
        unsafe {
            let raw =
                libc::mmap(std::ptr::null_mut(), total, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
            if raw == MAP_FAILED {
                return std::ptr::null_mut();
            }
            let head = (raw as usize).next_multiple_of(GRANULE) - raw as usize;
            let start = raw.cast::<u8>().add(head);
            if head > 0 {
                libc::munmap(raw, head);
            }
            libc::munmap(start.add(len).cast::<c_void>(), total - head - len);
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

    /// The machine's physical memory in bytes (`sysconf`, which does not
    /// allocate); `None` when it cannot be read.
    pub(super) fn physical_memory() -> Option<usize> {
        // SAFETY: `sysconf` only reads system parameters.
        let (pages, page) = unsafe { (libc::sysconf(libc::_SC_PHYS_PAGES), libc::sysconf(libc::_SC_PAGESIZE)) };
        let (pages, page) = (usize::try_from(pages).ok()?, usize::try_from(page).ok()?);
        pages.checked_mul(page).filter(|&b| b > 0)
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

/// The freed large blocks kept for reuse.
#[cfg(target_os = "linux")]
mod kept {
    use super::{kept_limit, map, SLOTS};
    use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
    use std::sync::Mutex;

    /// Bytes of mapped blocks in use, and the most ever in use at once.
    static IN_USE: AtomicUsize = AtomicUsize::new(0);
    static PEAK: AtomicUsize = AtomicUsize::new(0);

    /// Kept blocks as (address, mapped length); address 0 marks a free slot.
    struct Kept {
        blocks: [(usize, usize); SLOTS],
        bytes: usize,
    }

    /// Only ever `try_lock`ed: a call that finds it busy maps or unmaps
    /// directly instead of waiting. Besides never blocking an allocation,
    /// that keeps a child process forked while another thread held the
    /// lock (Python's `multiprocessing`, Dask) from hanging on its first
    /// large allocation: it bypasses the cache instead.
    static KEPT: Mutex<Kept> = Mutex::new(Kept { blocks: [(0, 0); SLOTS], bytes: 0 });

    impl Kept {
        /// Removes the block in slot `i` from the cache.
        fn remove(&mut self, i: usize) -> (usize, usize) {
            let block = self.blocks[i];
            self.blocks[i] = (0, 0);
            self.bytes -= block.1;
            block
        }

        /// The slot of the largest kept block.
        fn largest(&self) -> Option<usize> {
            (0..SLOTS).filter(|&i| self.blocks[i].0 != 0).max_by_key(|&i| self.blocks[i].1)
        }

        /// The slot of the smallest kept block.
        fn smallest(&self) -> Option<usize> {
            (0..SLOTS).filter(|&i| self.blocks[i].0 != 0).min_by_key(|&i| self.blocks[i].1)
        }
    }

    /// Counts `bytes` more of mapped blocks in use and gives kept blocks
    /// back, smallest first, until kept and used bytes together are at
    /// most the most ever in use at once: keeping freed blocks never
    /// raises the program's peak memory.
    pub(super) fn grow(bytes: usize) {
        let now = IN_USE.fetch_add(bytes, Relaxed).saturating_add(bytes);
        let peak = PEAK.fetch_max(now, Relaxed).max(now);
        let Ok(mut kept) = KEPT.try_lock() else { return };
        while kept.bytes > peak - now {
            let Some(i) = kept.smallest() else { break };
            let (p, l) = kept.remove(i);
            // SAFETY: a kept block is a whole unused mapping.
            unsafe { map::unmap(p as *mut u8, l) };
        }
    }

    /// Counts `bytes` fewer of mapped blocks in use.
    pub(super) fn shrink(bytes: usize) {
        // Every block counted in is counted out once with its length; the
        // saturation only guards the arithmetic.
        let _ = IN_USE.fetch_update(Relaxed, Relaxed, |u| Some(u.saturating_sub(bytes)));
    }

    /// `len` bytes freshly mapped (see [`map::map`]), counted in use.
    pub(super) fn fresh(len: usize) -> *mut u8 {
        grow(len);
        let p = map::map(len);
        if p.is_null() {
            shrink(len);
        }
        p
    }

    /// The smallest kept block of at least `len` bytes at an address
    /// aligned to `align`, cut to `len` bytes (the rest goes back to the
    /// kernel); null when there is none.
    pub(super) fn take(len: usize, align: usize) -> *mut u8 {
        let Ok(mut kept) = KEPT.try_lock() else { return std::ptr::null_mut() };
        let fits = |&(p, l): &(usize, usize)| p != 0 && l >= len && p.is_multiple_of(align);
        let best = (0..SLOTS).filter(|&i| fits(&kept.blocks[i])).min_by_key(|&i| kept.blocks[i].1);
        let Some(i) = best else { return std::ptr::null_mut() };
        let (p, l) = kept.remove(i);
        drop(kept);
        let ptr = p as *mut u8;
        if l > len {
            // SAFETY: the tail of a kept block is mapped and unused.
            unsafe { map::unmap(ptr.add(len), l - len) };
        }
        grow(len);
        ptr
    }

    /// Keeps a freed block of `len` mapped bytes, making room by releasing
    /// the largest kept ones, or releases it when it is larger than
    /// [`kept_limit`].
    ///
    /// # Safety
    /// `ptr..ptr + len` must be a whole mapping made by [`map::map`] (or
    /// grown by [`map::remap`]) and no longer used.
    pub(super) unsafe fn keep(ptr: *mut u8, len: usize) {
        shrink(len);
        let limit = kept_limit();
        if len <= limit {
            if let Ok(mut kept) = KEPT.try_lock() {
                while kept.bytes + len > limit || kept.blocks.iter().all(|b| b.0 != 0) {
                    let Some(i) = kept.largest() else { break };
                    let (p, l) = kept.remove(i);
                    map::unmap(p as *mut u8, l);
                }
                if let Some(slot) = kept.blocks.iter_mut().find(|b| b.0 == 0) {
                    *slot = (ptr as usize, len);
                    kept.bytes += len;
                    return;
                }
            }
        }
        map::unmap(ptr, len);
    }

    /// Holds the cache's lock (tests: what a forked child may find).
    #[cfg(test)]
    pub(super) fn hold() -> std::sync::MutexGuard<'static, impl Sized> {
        KEPT.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Releases every kept block; returns the bytes released.
    pub(super) fn release() -> usize {
        let Ok(mut kept) = KEPT.try_lock() else { return 0 };
        let bytes = kept.bytes;
        for i in 0..SLOTS {
            if kept.blocks[i].0 != 0 {
                let (p, l) = kept.remove(i);
                // SAFETY: a kept block is a whole unused mapping.
                unsafe { map::unmap(p as *mut u8, l) };
            }
        }
        bytes
    }
}

// SAFETY: blocks below the threshold are the system allocator's, unchanged.
// A mapped block is `mapped_len(size)` bytes from `map` (2 MiB-aligned) or
// from the kept blocks (taken only at an address of the requested
// alignment, cut to that length), and is released or kept with the same
// length since `dealloc` gets the layout it was allocated with; `realloc`
// keeps the mapping's length equal to `mapped_len` of the new size (moving
// it with `mremap` only for alignments that every page address meets), or
// moves the contents into a block of the other kind.
unsafe impl GlobalAlloc for BlockCache {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        tune_heap_once();
        #[cfg(target_os = "linux")]
        if mapped(layout) {
            let len = mapped_len(layout.size());
            let reused = kept::take(len, layout.align());
            return if reused.is_null() { kept::fresh(len) } else { reused };
        }
        System.alloc(layout)
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        tune_heap_once();
        #[cfg(target_os = "linux")]
        if mapped(layout) {
            let len = mapped_len(layout.size());
            let reused = kept::take(len, layout.align());
            if reused.is_null() {
                // Fresh anonymous pages are zero.
                return kept::fresh(len);
            }
            std::ptr::write_bytes(reused, 0, layout.size());
            return reused;
        }
        System.alloc_zeroed(layout)
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        #[cfg(target_os = "linux")]
        if mapped(layout) {
            return kept::keep(ptr, mapped_len(layout.size()));
        }
        System.dealloc(ptr, layout)
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let new_layout = Layout::from_size_align_unchecked(new_size, layout.align());
        match (mapped(layout), mapped(new_layout)) {
            (false, false) => System.realloc(ptr, layout, new_size),
            #[cfg(target_os = "linux")]
            (true, true) if mapped_len(new_size) <= mapped_len(layout.size()) => {
                // Shrinking (or growing within the last granule): keep the
                // block, return the pages past its new end.
                let (old_len, new_len) = (mapped_len(layout.size()), mapped_len(new_size));
                if new_len < old_len {
                    map::unmap(ptr.add(new_len), old_len - new_len);
                    kept::shrink(old_len - new_len);
                }
                ptr
            }
            #[cfg(target_os = "linux")]
            (true, true) if layout.align() <= 4096 => {
                // Growing: the kernel moves the pages, nothing is copied.
                let (old_len, new_len) = (mapped_len(layout.size()), mapped_len(new_size));
                kept::grow(new_len - old_len);
                let new = map::remap(ptr, old_len, new_len);
                if new.is_null() {
                    kept::shrink(new_len - old_len);
                }
                new
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

    /// Every path of the allocator through its trait, on blocks below, at
    /// and above the threshold, with the contents checked after each move;
    /// then the reuse of a freed block and [`release`]. One test, since the
    /// kept blocks are shared by the whole process.
    #[test]
    fn blocks_of_every_size_keep_their_contents_and_are_reused() {
        if cfg!(target_os = "linux") {
            // First, while the most in use is known: a larger block than
            // any kept one is mapped afresh and gives the kept one back,
            // since both would exceed the most ever in use.
            let small = Layout::from_size_align(2 * LARGE_BLOCK, 8).unwrap();
            let large = Layout::from_size_align(3 * LARGE_BLOCK, 8).unwrap();
            // SAFETY: each block is released once with its own layout.
            unsafe {
                let p = BlockCache.alloc(small);
                BlockCache.dealloc(p, small);
                let q = BlockCache.alloc(large);
                assert_eq!(release(), 0, "the kept block went back when the larger one was mapped");
                BlockCache.dealloc(q, large);
                assert_eq!(release(), mapped_len(large.size()));
            }
        }
        let sizes = [64, LARGE_BLOCK - 8, LARGE_BLOCK, LARGE_BLOCK + 3 * GRANULE + 24, 3 * LARGE_BLOCK];
        for &from in &sizes {
            for &to in &sizes {
                for align in [8, 64, 4096, GRANULE] {
                    let layout = Layout::from_size_align(from, align).unwrap();
                    // SAFETY: non-zero sizes; each block is released once,
                    // with the layout it has at that moment.
                    unsafe {
                        // Dirty a block first, so that a zeroed one may be a reused one.
                        let dirty = BlockCache.alloc(layout);
                        std::ptr::write_bytes(dirty, 0xAB, from);
                        BlockCache.dealloc(dirty, layout);
                        let zeroed = BlockCache.alloc_zeroed(layout);
                        assert!(!zeroed.is_null() && (zeroed as usize).is_multiple_of(align));
                        assert!(std::slice::from_raw_parts(zeroed, from).iter().all(|&b| b == 0));
                        BlockCache.dealloc(zeroed, layout);

                        let p = BlockCache.alloc(layout);
                        assert!(!p.is_null() && (p as usize).is_multiple_of(align));
                        for i in 0..from {
                            *p.add(i) = (i % 251) as u8;
                        }
                        let q = BlockCache.realloc(p, layout, to);
                        assert!(!q.is_null() && (q as usize).is_multiple_of(align), "{from} -> {to}, align {align}");
                        let kept = std::slice::from_raw_parts(q, from.min(to));
                        assert!(kept.iter().enumerate().all(|(i, &b)| b == (i % 251) as u8), "{from} -> {to}");
                        // The whole new block is writable.
                        std::ptr::write_bytes(q, 7, to);
                        BlockCache.dealloc(q, Layout::from_size_align(to, align).unwrap());
                    }
                }
            }
        }
        let layout = Layout::from_size_align(LARGE_BLOCK + 1, 8).unwrap();
        assert_eq!(mapped(layout), cfg!(target_os = "linux"));
        assert!(!mapped(Layout::from_size_align(LARGE_BLOCK - 1, 8).unwrap()));
        assert!(!mapped(Layout::from_size_align(LARGE_BLOCK, 2 * GRANULE).unwrap()));
        assert_eq!(mapped_len(LARGE_BLOCK + 1), LARGE_BLOCK + GRANULE);
        if cfg!(target_os = "linux") {
            release();
            // SAFETY: allocated and released with the same layout.
            unsafe {
                let p = BlockCache.alloc(layout);
                assert!(!p.is_null() && (p as usize).is_multiple_of(GRANULE));
                BlockCache.dealloc(p, layout);
                let q = BlockCache.alloc(layout);
                assert_eq!(p, q, "a freed block of the same size is reused");
                BlockCache.dealloc(q, layout);
            }
            assert_eq!(release(), mapped_len(layout.size()));
            assert_eq!(release(), 0);
            // With the cache's lock held (as in a child forked while another
            // thread held it), blocks are mapped and unmapped directly.
            {
                let _held = kept::hold();
                // SAFETY: allocated and released with the same layout.
                unsafe {
                    let p = BlockCache.alloc(layout);
                    assert!(!p.is_null());
                    std::ptr::write_bytes(p, 1, layout.size());
                    BlockCache.dealloc(p, layout);
                }
                assert_eq!(release(), 0, "nothing kept, no wait");
            }
            // A block larger than the cache goes straight back (never
            // touched, so it commits no memory).
            let huge = Layout::from_size_align(kept_limit() + 1, 8).unwrap();
            // SAFETY: allocated and released with the same layout.
            unsafe {
                let p = BlockCache.alloc(huge);
                assert!(!p.is_null());
                BlockCache.dealloc(p, huge);
            }
            assert_eq!(release(), 0);
            // Freed blocks beyond the former 1 GiB are kept, up to the
            // limit: of six blocks of about a quarter of it (never touched,
            // so they commit no memory), four freed come back as the same
            // blocks (best fit).
            let limit = kept_limit();
            assert!((LARGE_BLOCK..=KEPT_LARGE).contains(&limit));
            let sizes: Vec<usize> = (0..6).map(|i| (limit / 4 - i * GRANULE).max(LARGE_BLOCK)).collect();
            let layouts: Vec<Layout> = sizes.iter().map(|&s| Layout::from_size_align(s, 8).unwrap()).collect();
            // SAFETY: every block is released once, with its own layout.
            unsafe {
                let first: Vec<*mut u8> = layouts.iter().map(|&l| BlockCache.alloc(l)).collect();
                for (&p, &l) in first.iter().zip(&layouts).take(4) {
                    BlockCache.dealloc(p, l);
                }
                for (&p, &l) in first.iter().zip(&layouts).take(4) {
                    assert_eq!(BlockCache.alloc(l), p, "a kept block of {} bytes", l.size());
                }
                for (&p, &l) in first.iter().zip(&layouts) {
                    BlockCache.dealloc(p, l);
                }
            }
            // Six quarters do not fit: the largest went back.
            let released = release();
            assert!(released <= limit && released >= limit / 2, "{released} of {limit}");
        }
    }
}

//! The command line's allocator: mimalloc, through its plain entry points.
//!
//! The closed-form searches make and drop many small trees: with glibc's allocator, `malloc`
//! and `free` were 22% of the instructions of the PUMA 560's `fk --jacobian` (about 110 per
//! call: its per-thread cache of seven blocks a size overflows into the arena's bins), with
//! mimalloc's free lists per page a fraction of that (callgrind, one thread: 49.9 M
//! instructions with glibc, 42.0 M with mimalloc, the same output). The `mimalloc` crate's
//! allocator asks for every block through `mi_malloc_aligned`, whose generic path cost 1.2 M
//! of those; every block of mimalloc is aligned to a machine word (its size classes are whole
//! words), so layouts aligned to a word or less take `mi_malloc`. The library leaves the
//! choice to its user (the Python module keeps the interpreter's allocator).
//!
//! mimalloc 2 (the `v2` feature), not 3, the crate's default: 3 set up a larger arena and its
//! bitmaps at start, `dqsym -e 1` took 1.20 M instructions and 317 page faults with it and
//! 1.04 M and 286 with 2 (callgrind; `perf stat`: 2.2 against 1.5 ms of CPU), and the PUMA
//! 560's `fk --jacobian` 40.51 M and 40.23 M.
//!
//! Compiled with `MI_USE_ENVIRON=0` (`.cargo/config.toml`): mimalloc reads its ~45 options
//! at start, by default each through a case-insensitive scan of the whole environment, ~120,000
//! instructions of every run (a quarter of `dqsym -e 1`'s); the C library's `getenv` finds the
//! same `MIMALLOC_*` options for about half of that.
//!
//! Built without transparent huge pages (the `no_thp` feature): where the kernel grants them
//! on request (`madvise`, the common setting), mimalloc asked for them on its arenas, and each
//! first touch zeroed 2 MB. The PUMA's report then took 22 MB of resident memory instead of
//! 10 MB and about 12 ms of CPU instead of 8 ms (one thread, `perf stat`), despite its fewer
//! page faults (212 against 633 of 4 KB).

use libmimalloc_sys::{
    mi_free, mi_malloc, mi_malloc_aligned, mi_realloc, mi_realloc_aligned, mi_zalloc,
    mi_zalloc_aligned,
};
use std::alloc::{GlobalAlloc, Layout};
use std::ffi::c_void;

/// The alignment every mimalloc block has: its size classes are multiples of a word.
const WORD: usize = std::mem::size_of::<usize>();

/// mimalloc as the global allocator.
pub(crate) struct MiMalloc;

// SAFETY: every block comes from mimalloc and goes back to it; a layout aligned to more than
// a word is asked for with its alignment, and a word-aligned one gets a block of mimalloc's,
// which are all word-aligned.
unsafe impl GlobalAlloc for MiMalloc {
    #[inline]
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if layout.align() <= WORD {
            mi_malloc(layout.size()).cast()
        } else {
            mi_malloc_aligned(layout.size(), layout.align()).cast()
        }
    }

    #[inline]
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if layout.align() <= WORD {
            mi_zalloc(layout.size()).cast()
        } else {
            mi_zalloc_aligned(layout.size(), layout.align()).cast()
        }
    }

    #[inline]
    unsafe fn dealloc(&self, ptr: *mut u8, _layout: Layout) {
        mi_free(ptr.cast::<c_void>());
    }

    #[inline]
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if layout.align() <= WORD {
            mi_realloc(ptr.cast::<c_void>(), new_size).cast()
        } else {
            mi_realloc_aligned(ptr.cast::<c_void>(), new_size, layout.align()).cast()
        }
    }
}

//! One malloc arena for the studio process (glibc only).
//!
//! Every HTTP request is served on a thread of its own, and glibc gives
//! threads arenas of their own (up to 8 per core), each keeping what it
//! freed for its next allocations instead of returning it. Frames' images
//! are allocated and freed on whichever threads read and encode them, so
//! the studio's resident memory crept up by a few MiB over 1,000 edits
//! while nothing leaked (GPU memory was exactly flat). With a single arena
//! it stays flat (+0.2 MiB from edit 10 to 1,000 against +9.7 MiB, `npr
//! bench studio` with `MALLOC_ARENA_MAX=1`, docs/PERFORMANCE.md); the
//! studio has a handful of threads, and their allocations are few and
//! large, so sharing one arena's lock costs nothing measurable.

/// Limit glibc to one malloc arena; a no-op elsewhere (other allocators
/// have no per-thread arenas of this kind). Call before any thread starts.
pub fn single_arena() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        /// `M_ARENA_MAX` in glibc's `<malloc.h>`.
        const M_ARENA_MAX: std::os::raw::c_int = -8;
        extern "C" {
            fn mallopt(param: std::os::raw::c_int, value: std::os::raw::c_int) -> std::os::raw::c_int;
        }
        // SAFETY: mallopt only sets an allocator parameter; glibc documents
        // it as safe to call at any time, and no other thread exists yet.
        unsafe {
            mallopt(M_ARENA_MAX, 1);
        }
    }
}

//! The allocator, tuned for a window redrawn many times a second. Each frame the
//! software rasteriser allocates and frees buffers of a few megabytes (vertex data,
//! staging, the window's image); glibc's defaults hand such blocks back to the kernel
//! when freed, so the next frame takes them again page by page, zeroed. Measured while
//! a parameter of the wood preset is dragged: the driver's queue thread spent 28% of a
//! core in page faults and page clearing; with freed memory kept, 14%.

/// Blocks up to this size come from the heap (and are reused) instead of being mapped
/// and unmapped each time (glibc's largest allowed on 64-bit systems).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const HEAP_BLOCKS_UP_TO: libc::c_int = 32 << 20;
/// Free memory at the top of a heap is kept up to this much.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const KEEP_FREE: libc::c_int = 256 << 20;

/// Keeps freed memory for the next frame (glibc); other platforms keep their defaults.
pub fn keep_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: `mallopt` takes two integers and only changes the allocator's thresholds;
    // it is called before the window and its threads exist.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, HEAP_BLOCKS_UP_TO);
        libc::mallopt(libc::M_TRIM_THRESHOLD, KEEP_FREE);
    }
}

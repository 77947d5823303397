//! Work the window never waits for yields the cores to it. On a machine of two cores
//! (the software rasteriser drawing the window on one), a 10,000-node graph panned in
//! the real window ran at 24 frames a second with the thumbnails' thread idle and at 15
//! while it compiled the atlas of the nodes just brought on screen; the thumbnails, the
//! big graphs' compiles and their lint therefore run at a lower priority.

/// The nice value such threads take (0 is the default, 19 the lowest).
#[cfg(target_os = "linux")]
const BEHIND_THE_WINDOW: libc::c_int = 10;

/// Lowers the calling thread's priority below the window's (Linux; elsewhere nothing).
/// Threads it starts afterwards (a device's rasteriser threads) inherit it.
pub fn behind_the_window() {
    #[cfg(target_os = "linux")]
    // SAFETY: `gettid` has no preconditions; `setpriority` on this thread's id only
    // changes its scheduling priority, and a failure (refused by the system) is harmless.
    unsafe {
        let thread = libc::gettid() as libc::id_t;
        libc::setpriority(libc::PRIO_PROCESS, thread, BEHIND_THE_WINDOW);
    }
}

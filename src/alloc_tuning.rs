//! Allocator tuning for tensor work on glibc: keep freed blocks instead of returning them to the
//! kernel. Candle allocates a fresh buffer per tensor operation; with glibc's defaults every
//! buffer over 128 KiB is a new `mmap`, so a training step spends a quarter of its time in page
//! faults. Measured on a d128 denoiser step at batch 64: 277 ms → 210 ms.

/// Raises glibc's mmap and trim thresholds (no-op on other platforms). Call once, early.
pub fn tune_allocator_for_tensors() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only changes allocator parameters; called before any threads start.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 1 << 30);
        libc::mallopt(libc::M_TRIM_THRESHOLD, 1 << 30);
        libc::mallopt(libc::M_TOP_PAD, 256 << 20);
    }
}

//! The `ellipgrid` command line: a thin layer over the library (parse → case → pipeline →
//! writer → exit code).

mod cli;

fn main() -> std::process::ExitCode {
    // Die quietly when stdout is a closed pipe (`ellipgrid run … | head`), like other Unix
    // tools, instead of panicking on the failed print.
    #[cfg(unix)]
    // SAFETY: restoring the default disposition of SIGPIPE before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    keep_freed_memory();
    cli::main()
}

/// glibc's allocator keeps what a stage frees for the next one: buffers up to 32 MiB come from
/// the heap instead of fresh mappings, and up to 128 MiB of freed heap is kept instead of
/// given back. Every fresh page costs a page fault on first touch (~1.25–2.5 µs here), and a
/// grid's stages free and allocate buffers of the same sizes again and again (nested levels,
/// Newton steps, blocks). `ellipgrid run`, side by side with the defaults (2 cores, idle):
/// NACA0012 O-grid 4 × 257² 0.85 → 0.79 s (page faults 85 k → 29 k, peak 125 → 127 MB);
/// dented square 1025² 2.00 → 1.97 s (faults 285 k → 239 k, the peak's own pages; peak the
/// same); ONERA M6 four volumes the same time (33 s), faults 508 k → 355 k, peak 465 → 549 MB
/// (the volumes' threads keep freed heap: 680 bytes per node). A mapping threshold alone
/// (without the trim threshold) made the M6 run trim and fault again: 2.05 M faults.
fn keep_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only sets allocator parameters; called before any thread starts.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 32 << 20);
        libc::mallopt(libc::M_TRIM_THRESHOLD, 128 << 20);
    }
}

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
    cli::main()
}

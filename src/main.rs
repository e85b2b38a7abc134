//! The `ellipgrid` command line: a thin layer over the library (parse → case → pipeline →
//! writer → exit code).

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}

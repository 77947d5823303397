//! The `veneer` command line: thin wrappers over the library (see `cli/`).

mod cli;

fn main() -> std::process::ExitCode {
    cli::run()
}

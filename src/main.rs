//! The `rasterlab` command line: wiring only; every algorithm lives in the library.

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}

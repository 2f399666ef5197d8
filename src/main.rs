//! The `rasterlab` command line: wiring only; every algorithm lives in the library.

mod cli;

/// Frames allocate and free large buffers; mimalloc keeps freed memory for
/// reuse instead of returning it to the system, so repeated frames do not
/// pay for page faults again.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> std::process::ExitCode {
    cli::main()
}

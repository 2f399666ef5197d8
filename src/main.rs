//! The `rasterlab` command line: wiring only; every algorithm lives in the library.

mod cli;

/// mimalloc asks Linux for 2 MB pages for all the memory it hands out
/// (the library asks only for its frame buffers'), which spares a frame's
/// scattered reads and writes most TLB misses, so the full dragon drawn
/// frame after frame is faster with it than with the system allocator
/// (docs/performance-log.md, "2026-12-07, `7bdb999` to `cfd7d1e`").
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> std::process::ExitCode {
    cli::main()
}

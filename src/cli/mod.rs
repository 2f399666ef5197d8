//! Command-line parsing and dispatch.

use clap::{Parser, Subcommand};
use rasterlab::{Error, Result};
use std::process::ExitCode;

mod commands;

/// Compare rasterization algorithms: exact back-ends on one shared fragment stage.
#[derive(Parser, Debug)]
#[command(name = "rasterlab", version, about)]
pub struct Cli {
    /// Worker threads for geometry and binned rasterization (default: all
    /// cores, or RAYON_NUM_THREADS).
    #[arg(long, global = true, value_name = "N")]
    threads: Option<usize>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// List every back-end as `NAME KIND DESCRIPTION`, one per line.
    Backends,
    /// Print the fragments a back-end emits for a triangle soup, one `x y t` per line.
    Fragments(commands::FragmentsArgs),
    /// Render a triangle soup or a built-in scene to a PNG file.
    Render(commands::RenderArgs),
    /// Trace one algorithm step by step on a small input, in the course's terms; --picture draws its grid.
    Explain(commands::ExplainArgs),
    /// Run every back-end on one input and write a side-by-side HTML report.
    Compare(commands::CompareArgs),
    /// Render the bundled scenes with every back-end and check the images are identical.
    Demo(commands::DemoArgs),
    /// Time every back-end on the same workloads: table, JSON and bar chart.
    Bench(commands::BenchArgs),
    /// Check a rasterizer (another program, or a back-end) against the
    /// rules on generated cases; a failure is shrunk to a counterexample.
    Check(commands::CheckArgs),
    /// Serve the interactive lab on 127.0.0.1: drag vertices, watch every
    /// back-end's pixels, traces, heat maps and depth buffer update.
    Lab(commands::LabArgs),
}

/// Runs the command line; errors are printed to stderr.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let run = || match &cli.command {
        Command::Backends => commands::backends(),
        Command::Fragments(args) => commands::fragments(args),
        Command::Render(args) => commands::render(args),
        Command::Demo(args) => commands::demo(args),
        Command::Explain(args) => commands::explain(args),
        Command::Compare(args) => commands::compare(args),
        Command::Bench(args) => commands::bench(args),
        Command::Check(args) => commands::check(args),
        Command::Lab(args) => commands::lab(args),
    };
    let result = match cli.threads {
        None => run(),
        Some(threads) => thread_pool(threads).and_then(|pool| pool.install(run)),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // The reader went away (`| head`): stop quietly.
        Err(e @ Error::Write { closed: true, .. }) => ExitCode::from(e.exit_code()),
        Err(e) => {
            eprintln!("rasterlab: error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}

/// More threads than this gain nothing on any machine rasterlab runs on
/// and cost seconds to start.
const MAX_THREADS: usize = 256;

/// A pool of `threads` workers (1 to [`MAX_THREADS`]).
fn thread_pool(threads: usize) -> Result<rayon::ThreadPool> {
    if !(1..=MAX_THREADS).contains(&threads) {
        return Err(Error::InvalidArgument(format!(
            "--threads must be between 1 and {MAX_THREADS}, not {threads}"
        )));
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::InvalidArgument(format!("cannot start {threads} threads: {e}")))
}

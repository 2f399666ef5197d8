//! Command-line parsing and dispatch: one file per subcommand, each a clap
//! `Args` and a few lines that call one library function and print what it
//! returns.

use clap::{Parser, Subcommand};
use rasterlab::{Error, Result};
use std::process::ExitCode;

/// Prints a line on standard output; a closed or full output is an
/// [`Error::Write`], not a panic.
macro_rules! say {
    ($($arg:tt)*) => {
        writeln!(std::io::stdout().lock(), $($arg)*).map_err($crate::cli::print::stdout_error)
    };
}

/// Prints text on standard output, as [`say!`] without the newline.
macro_rules! say_raw {
    ($($arg:tt)*) => {
        write!(std::io::stdout().lock(), $($arg)*).map_err($crate::cli::print::stdout_error)
    };
}

mod args;
mod backends;
mod bench;
mod check;
mod compare;
mod demo;
mod explain;
mod fragments;
mod lab;
mod print;
mod render;

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

// Parsed once per run: the size of the largest arguments does not matter.
#[allow(clippy::large_enum_variant)]
#[derive(Subcommand, Debug)]
enum Command {
    /// List every back-end as `NAME KIND DESCRIPTION`, one per line.
    Backends,
    /// Print the fragments a back-end emits for a triangle soup, one `x y t` per line.
    Fragments(fragments::FragmentsArgs),
    /// Render a triangle soup or a built-in scene to a PNG file.
    Render(render::RenderArgs),
    /// Trace one algorithm step by step on a small input, in the course's terms; --picture draws its grid.
    Explain(explain::ExplainArgs),
    /// Run every back-end on one input and write a side-by-side HTML report.
    Compare(compare::CompareArgs),
    /// Render the bundled scenes with every back-end and check the images are identical.
    Demo(demo::DemoArgs),
    /// Time every back-end on the same workloads: table, JSON and bar chart.
    Bench(bench::BenchArgs),
    /// Check a rasterizer (another program, or a back-end) against the
    /// rules on generated cases; a failure is shrunk to a counterexample.
    ///
    /// The diagnosis names a cause only where the reference confirms it:
    /// a mistake of the catalogue (another fill rule, a culled winding,
    /// small triangles dropped, rounded or coarse vertices, corner
    /// samples, y from the bottom, a short box, floating point, overflow;
    /// for lines another tie rule, the other end, endpoints, a missing
    /// octant swap, 4-connected) that explains every difference on the
    /// failing cases as generated. docs/check.md lists them.
    Check(check::CheckArgs),
    /// Serve the interactive lab on 127.0.0.1: drag vertices, watch every
    /// back-end's pixels, traces, heat maps and depth buffer update.
    Lab(lab::LabArgs),
}

/// Runs the command line; errors are printed to stderr.
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // Help and version are printed as they are; a usage error, like
        // every other error, starts with `rasterlab: error:`.
        Err(e) if !e.use_stderr() => e.exit(),
        Err(e) => {
            eprint!("rasterlab: {}", e.render());
            return ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(2));
        }
    };
    let run = || match &cli.command {
        Command::Backends => backends::run(),
        Command::Fragments(args) => fragments::run(args),
        Command::Render(args) => render::run(args),
        Command::Demo(args) => demo::run(args),
        Command::Explain(args) => explain::run(args),
        Command::Compare(args) => compare::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Check(args) => check::run(args),
        Command::Lab(args) => lab::run(args),
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

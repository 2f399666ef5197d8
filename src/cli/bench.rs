//! `rasterlab bench`: every back-end timed on the same workloads.

use super::args::Size;
use super::print::progress_bar;
use clap::Args;
use rasterlab::Result;
use std::io::Write;
use std::path::{Path, PathBuf};

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Workload set: quick (seconds) or full (the `cargo bench` sizes).
    #[arg(long, default_value = "quick")]
    set: rasterlab::measure::WorkloadSet,
    /// Target size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1920x1080")]
    size: Size,
    /// Timed runs per back-end and workload (median, minimum and maximum
    /// are reported).
    #[arg(long, default_value = "5", value_parser = super::args::samples)]
    samples: usize,
    /// Meshes to render (default: the bundled dragon).
    #[arg(long = "mesh")]
    meshes: Vec<PathBuf>,
    /// Print JSON instead of the table.
    #[arg(long)]
    json: bool,
    /// Directory for bench.json, bench.png and bench.svg.
    #[arg(long, default_value = "bench-output")]
    out: PathBuf,
}

pub fn run(args: &BenchArgs) -> Result<()> {
    use rasterlab::measure::{run, to_json, write_outputs, BenchOptions};
    rasterlab::check_dir(&args.out)?;
    let meshes = if args.meshes.is_empty() {
        vec![Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/dragon_vrip_res4.ply.gz")]
    } else {
        args.meshes.clone()
    };
    let options = BenchOptions {
        set: args.set,
        width: args.size.width,
        height: args.size.height,
        samples: args.samples,
        meshes,
    };
    let bar = progress_bar(0, "");
    let results = run(&options, &mut |p| {
        bar.set_length(p.total as u64);
        bar.set_position(p.done as u64);
        bar.set_message(p.pair.to_string());
    });
    bar.finish_and_clear();
    let report = results?;
    if args.json {
        say!("{}", to_json(&report))?;
    } else {
        say_raw!("{report}")?;
    }
    write_outputs(&report, &args.out)?;
    eprintln!(
        "wrote bench.json, bench.png, bench.svg in {}",
        args.out.display()
    );
    Ok(())
}

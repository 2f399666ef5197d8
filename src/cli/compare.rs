//! `rasterlab compare`: every back-end on one input, side by side in HTML.

use super::args::Size;
use clap::Args;
use rasterlab::teaching::compare::{compare, CompareRequest};
use rasterlab::Result;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct CompareArgs {
    /// A triangle soup or polygon file, a line set file, or a mesh (.ply,
    /// .ply.gz, .obj).
    input: PathBuf,
    /// Target size, WIDTHxHEIGHT.
    #[arg(long, default_value = "64x64")]
    size: Size,
    /// Directory the report (index.html) is written to.
    #[arg(long, default_value = "compare-output")]
    out: PathBuf,
    /// Timed runs per back-end (the median is reported).
    #[arg(long, default_value = "3", value_parser = super::args::samples)]
    samples: usize,
}

pub fn run(args: &CompareArgs) -> Result<()> {
    let summary = compare(&CompareRequest {
        input: &args.input,
        width: args.size.width,
        height: args.size.height,
        samples: args.samples,
        out: &args.out,
    })?;
    super::print::out(summary)
}

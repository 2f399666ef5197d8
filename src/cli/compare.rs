//! `rasterlab compare`: every back-end on one input, side by side in HTML.

use super::args::{msaa, Size};
use clap::Args;
use rasterlab::raster::SamplePattern;
use rasterlab::teaching::{compare, compare_texture_filters, default_compare_size, CompareRequest};
use rasterlab::Result;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct CompareArgs {
    /// A triangle soup or polygon file, a line set file, or a mesh (.ply,
    /// .ply.gz, .obj).
    #[arg(required_unless_present = "textures")]
    input: Option<PathBuf>,
    /// Compare the texture filters instead, on the receding floor (`render
    /// --scene floor`; default 160x100): every pixel filter, level mode,
    /// derivative method and anisotropy against the texture over each
    /// pixel, as a table and a chart (textures.svg).
    #[arg(long, conflicts_with_all = ["input", "msaa"])]
    textures: bool,
    /// With --textures: the ground truth's bilinear samples of level 0
    /// a pixel side (16: 16x16).
    #[arg(long, value_name = "N", default_value_t = 16, requires = "textures")]
    truth: u32,
    /// Target size, WIDTHxHEIGHT (default: 320x240 for a mesh, 64x64
    /// for triangles and lines).
    #[arg(long)]
    size: Option<Size>,
    /// Directory the report (index.html) is written to.
    #[arg(long, default_value = "compare-output")]
    out: PathBuf,
    /// Timed runs per back-end (the median is reported).
    #[arg(long, default_value = "3", value_parser = super::args::samples)]
    samples: usize,
    /// Multisample triangles on the standard pattern of N samples (1, 2,
    /// 4, 8 or 16): each back-end's resolved image, the grids with their
    /// samples.
    #[arg(long, value_name = "N", value_parser = msaa, allow_negative_numbers = true)]
    msaa: Option<SamplePattern>,
}

pub fn run(args: &CompareArgs) -> Result<()> {
    let Some(input) = &args.input else {
        let (width, height) = args.size.map_or((160, 100), |s| (s.width, s.height));
        let summary = compare_texture_filters(width, height, args.truth, args.samples, &args.out)?;
        return super::print::out(summary);
    };
    let (width, height) = args
        .size
        .as_ref()
        .map_or_else(|| default_compare_size(input), |s| (s.width, s.height));
    let summary = compare(&CompareRequest {
        input,
        width,
        height,
        samples: args.samples,
        out: &args.out,
        msaa: args.msaa,
    })?;
    super::print::out(summary)
}

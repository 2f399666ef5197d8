//! `rasterlab fragments`: the fragments a back-end emits for a file.

use super::args::{fill_rule, msaa, rule_for_lines, LineArgs, Size};
use clap::Args;
use rasterlab::geometry::{list_fragments_in_file, FragmentsRequest};
use rasterlab::raster::{backend, Backend, FillRule, SamplePattern};
use rasterlab::Result;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct FragmentsArgs {
    /// Back-end name (see `rasterlab backends`).
    #[arg(long, value_parser = backend)]
    backend: Backend,
    /// Target size, `WxH`.
    #[arg(long)]
    size: Size,
    /// Triangle fill rule (default: top-left; not for a line back-end).
    #[arg(long, value_parser = fill_rule())]
    rule: Option<FillRule>,
    #[command(flatten)]
    line: LineArgs,
    /// Multisample triangles on the standard pattern of N samples (1, 2,
    /// 4, 8 or 16): print `x y id mask`, bit i of the mask for sample i.
    #[arg(long, value_name = "N", value_parser = msaa, allow_negative_numbers = true)]
    msaa: Option<SamplePattern>,
    /// Triangle soup (`x0 y0 x1 y1 x2 y2` per line) or line set (`x0 y0 x1 y1` per line).
    file: PathBuf,
}

pub fn run(args: &FragmentsArgs) -> Result<()> {
    if let (Some(_), Backend::Line(_)) = (args.rule, args.backend) {
        return Err(rule_for_lines());
    }
    let listing = list_fragments_in_file(&FragmentsRequest {
        backend: args.backend,
        file: &args.file,
        width: args.size.width,
        height: args.size.height,
        rule: args.rule.unwrap_or_default(),
        line: args.line.options(),
        msaa: args.msaa,
    })?;
    super::print::out(listing)
}

//! `rasterlab fragments`: the fragments a back-end emits for a file.

use super::args::{LineArgs, Size};
use clap::Args;
use rasterlab::geometry::listing::{list_fragments_in_file, FragmentsRequest};
use rasterlab::{backend, Backend};
use rasterlab::{FillRule, Result};
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct FragmentsArgs {
    /// Back-end name (see `rasterlab backends`).
    #[arg(long, value_parser = backend)]
    backend: Backend,
    /// Target size, `WxH`.
    #[arg(long)]
    size: Size,
    /// Triangle fill rule: top-left, bottom-right, offscreen-point, inclusive, exclusive.
    #[arg(long, default_value = "top-left")]
    rule: FillRule,
    #[command(flatten)]
    line: LineArgs,
    /// Triangle soup (`x0 y0 x1 y1 x2 y2` per line) or line set (`x0 y0 x1 y1` per line).
    file: PathBuf,
}

pub fn run(args: &FragmentsArgs) -> Result<()> {
    let listing = list_fragments_in_file(&FragmentsRequest {
        backend: args.backend,
        file: &args.file,
        width: args.size.width,
        height: args.size.height,
        rule: args.rule,
        line: args.line.options(),
    })?;
    super::print::out(listing)
}

//! `rasterlab fragments`: the fragments a back-end emits for a file.

use super::args::{fill_rule, msaa, rule_for_lines, winding_rule, LineArgs, Size};
use clap::Args;
use rasterlab::geometry::{
    list_fragments_in_file, list_polygon_fragments_in_file, FragmentsRequest,
    PolygonFragmentsRequest,
};
use rasterlab::raster::polygon::{PolygonRasterizer, WindingRule};
use rasterlab::raster::{backend, polygon_backend, Backend, FillRule, SamplePattern};
use rasterlab::{Error, Result};
use std::path::PathBuf;

/// A triangle or line back-end, or a polygon back-end.
#[derive(Clone, Copy)]
enum Chosen {
    Drawing(Backend),
    Polygon(&'static dyn PolygonRasterizer),
}

impl std::fmt::Debug for Chosen {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Chosen::Drawing(b) => b.fmt(f),
            Chosen::Polygon(b) => write!(f, "Polygon({})", b.name()),
        }
    }
}

/// `--backend`: any back-end of the registry, polygon back-ends included.
fn chosen(name: &str) -> Result<Chosen> {
    polygon_backend(name)
        .map(Chosen::Polygon)
        .or_else(|_| backend(name).map(Chosen::Drawing))
}

#[derive(Args, Debug)]
pub struct FragmentsArgs {
    /// Back-end name (see `rasterlab backends`).
    #[arg(long, value_parser = chosen)]
    backend: Chosen,
    /// Target size, `WxH`.
    #[arg(long)]
    size: Size,
    /// Triangle fill rule (default: top-left; not for a line back-end).
    #[arg(long, value_parser = fill_rule())]
    rule: Option<FillRule>,
    /// Winding rule of a polygon back-end (`edge-table`): even-odd or
    /// nonzero; given, polygons whose rings cross are filled too.
    #[arg(long, value_parser = winding_rule())]
    fill: Option<WindingRule>,
    #[command(flatten)]
    line: LineArgs,
    /// Multisample triangles on the standard pattern of N samples (1, 2,
    /// 4, 8 or 16): print `x y id mask`, bit i of the mask for sample i.
    #[arg(long, value_name = "N", value_parser = msaa, allow_negative_numbers = true)]
    msaa: Option<SamplePattern>,
    /// Triangle soup (`x0 y0 x1 y1 x2 y2` per line), polygons, or line set (`x0 y0 x1 y1` per line).
    file: PathBuf,
}

pub fn run(args: &FragmentsArgs) -> Result<()> {
    let backend = match args.backend {
        Chosen::Polygon(backend) => {
            if args.rule.is_some() || args.msaa.is_some() {
                return Err(Error::InvalidArgument(
                    "--rule and --msaa are for triangle back-ends; a polygon back-end settles \
                     ties by the top-left rule, one sample a pixel"
                        .into(),
                ));
            }
            let listing = list_polygon_fragments_in_file(&PolygonFragmentsRequest {
                backend,
                file: &args.file,
                width: args.size.width,
                height: args.size.height,
                fill: args.fill,
            })?;
            return super::print::out(listing);
        }
        Chosen::Drawing(backend) => backend,
    };
    if args.fill.is_some() {
        return Err(Error::InvalidArgument(
            "--fill is the winding rule of a polygon back-end (edge-table); a triangle back-end \
             draws spade's triangulation of simple polygons"
                .into(),
        ));
    }
    if let (Some(_), Backend::Line(_)) = (args.rule, backend) {
        return Err(rule_for_lines());
    }
    let listing = list_fragments_in_file(&FragmentsRequest {
        backend,
        file: &args.file,
        width: args.size.width,
        height: args.size.height,
        rule: args.rule.unwrap_or_default(),
        line: args.line.options(),
        msaa: args.msaa,
    })?;
    super::print::out(listing)
}

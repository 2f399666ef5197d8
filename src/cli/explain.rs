//! `rasterlab explain`: one algorithm traced step by step, and its grid picture.

use super::args::{fill_rule, msaa, rule_for_lines, winding_rule, Size};
use clap::Args;
use rasterlab::raster::line::clip::Clipper;
use rasterlab::raster::polygon::WindingRule;
use rasterlab::raster::{
    backend, default_line_backend, Anisotropic, Backend, Blend, BlendMode, DepthState, Derivatives,
    FillRule, Filter, LevelMode, MixSpace, SamplePattern,
};
use rasterlab::teaching::{explain, Blending, ExplainRequest, GridPicture, Texturing};
use rasterlab::Result;
use std::path::PathBuf;
use std::str::FromStr;

#[derive(Args, Debug)]
pub struct ExplainArgs {
    /// What to trace: bresenham, direct, dda, wu, diamond (a line: x0 y0
    /// x1 y1, pixel indices unless --screen); bbox, naive, scanline,
    /// incremental, tiled (a triangle: x0 y0 x1 y1 x2 y2, in screen
    /// coordinates); depth-buffer (triangles of 7
    /// numbers each, x0 y0 x1 y1 x2 y2 z, or none for the course's
    /// depth-buffer example); clip-triangle (a triangle clipped in clip
    /// space by the pipeline's planes, then its fan: x y z w for each
    /// vertex, or none for a vertex behind the camera); blend (one
    /// pixel's fragments and blends:
    /// x y, a pixel of --scene); texture (one pixel's texture lookup on
    /// the receding floor of `render --scene floor`: x y); edge-table (a
    /// polygon: x y pairs, in screen coordinates, more rings by --ring;
    /// its picture labels each centre's winding number). Any other back-end:
    /// --picture only. With --clip, a line back-end (default bresenham).
    #[arg(long, required_unless_present = "clip")]
    backend: Option<String>,
    /// Clip the line to the grid (--size) first, step by step:
    /// cohen-sutherland (each endpoint's outcode TBRL, the edge chosen,
    /// the new point) or liang-barsky (each boundary's p, q and the t
    /// interval); then the walk's entry and exit columns and its restart.
    #[arg(long, value_parser = Clipper::from_str)]
    clip: Option<Clipper>,
    /// The blend trace's built-in scene (default transparent; see
    /// `render --help`).
    #[arg(long)]
    scene: Option<String>,
    /// The blend trace's blend mode: replace, add, over, over-straight
    /// (default), multiply.
    #[arg(long, default_value = "over-straight", value_parser = BlendMode::from_name)]
    blend: BlendMode,
    /// The blend trace's mixing space: linear (default) or srgb.
    #[arg(long, default_value = "linear", value_parser = MixSpace::from_name)]
    mix_in: MixSpace,
    /// The blend trace's depth test (as `render --depth-test`).
    #[arg(long, default_value = "less", value_parser = DepthState::from_name)]
    depth_test: DepthState,
    /// The blend trace: sort the scene's triangles back to front first.
    #[arg(long)]
    sort: bool,
    /// Triangle fill rule (default: top-left; not for a line back-end).
    #[arg(long, value_parser = fill_rule())]
    rule: Option<FillRule>,
    /// Winding rule of edge-table: even-odd (default) or nonzero.
    #[arg(long, value_parser = winding_rule())]
    fill: Option<WindingRule>,
    /// Another ring of edge-table's polygon: its x y pairs in one
    /// argument (`--ring "5 4 11 4 10 8"`; repeat for more), taken as
    /// given, not turned, so a ring running the same way as the first
    /// winds its inside twice.
    #[arg(long, value_name = "\"X Y X Y ...\"", allow_hyphen_values = true)]
    ring: Vec<Ring>,
    /// Grid size, `WxH` (16x16 for one triangle, 14x9 for the course's
    /// depth-buffer example).
    #[arg(long)]
    size: Option<Size>,
    /// Read line endpoints as screen coordinates, as `rasterlab fragments`
    /// and files do (`0.5 0.5 7.5 3.5`), instead of pixel indices whose
    /// centres the line joins (`0 0 7 3`, the course's convention).
    #[arg(long)]
    screen: bool,
    /// Also write a zoomed grid picture of the same input (`.svg` or
    /// `.png`): the pixels tested and the fragments emitted.
    #[arg(long)]
    picture: Option<PathBuf>,
    /// A triangle's samples too: N samples a pixel on the standard
    /// pattern (1, 2, 4, 8 or 16), each partly covered pixel traced
    /// sample by sample.
    #[arg(long, value_name = "N", value_parser = msaa, allow_negative_numbers = true)]
    msaa: Option<SamplePattern>,
    /// The texture trace's pixel filter: nearest, bilinear (default).
    #[arg(long)]
    filter: Option<Filter>,
    /// The texture trace's level mode: zero, nearest, linear (default).
    #[arg(long)]
    mip: Option<LevelMode>,
    /// The texture trace's most anisotropic probes, 1 (default) to 16.
    #[arg(long, value_name = "N")]
    anisotropy: Option<u32>,
    /// The texture trace's anisotropic filter: probes (default) or ewa.
    #[arg(long)]
    anisotropic: Option<Anisotropic>,
    /// The texture trace's derivative method: analytic (default), quad,
    /// forward. On a triangle back-end, quad counts the helper pixels of
    /// its 2x2 quads, and its picture draws them.
    #[arg(long)]
    derivatives: Option<Derivatives>,
    /// The coordinates.
    #[arg(allow_negative_numbers = true)]
    coordinates: Vec<f64>,
}

pub fn run(args: &ExplainArgs) -> Result<()> {
    let name = match &args.backend {
        Some(name) => name.clone(),
        None => default_line_backend().name().to_string(),
    };
    if args.rule.is_some() && matches!(backend(&name), Ok(Backend::Line(_))) {
        return Err(rule_for_lines());
    }
    if let Some(path) = &args.picture {
        rasterlab::check_file(path, &GridPicture::EXTENSIONS)?;
    }
    let explanation = explain(&ExplainRequest {
        backend: name,
        rule: args.rule.unwrap_or_default(),
        size: args.size.map(|s| (s.width, s.height)),
        screen: args.screen,
        coordinates: args.coordinates.clone(),
        picture: args.picture.is_some(),
        msaa: args.msaa,
        fill: args.fill,
        blending: Blending {
            scene: args.scene.clone(),
            blend: Blend {
                mode: args.blend,
                mix_in: args.mix_in,
                ..Blend::default()
            },
            depth: args.depth_test,
            sort: args.sort,
        },
        texturing: texturing(args),
        clip: args.clip,
        rings: args.ring.iter().map(|r| r.0.clone()).collect(),
    })?;
    if let (Some(path), Some(picture)) = (&args.picture, &explanation.picture) {
        picture.save(path)?;
        eprintln!("picture: {}", path.display());
    }
    if let (Some(path), Some(picture)) = (&args.picture, &explanation.levels) {
        picture.save(path)?;
        eprintln!("picture: {}", path.display());
    }
    super::print::out(explanation.text)
}

/// The texture trace's choices: those given, the others trilinear with
/// analytic derivatives.
fn texturing(args: &ExplainArgs) -> Texturing {
    let d = Texturing::default();
    Texturing {
        sampler: rasterlab::raster::Sampler {
            filter: args.filter.unwrap_or(d.sampler.filter),
            levels: args.mip.unwrap_or(d.sampler.levels),
            anisotropy: args.anisotropy.unwrap_or(d.sampler.anisotropy),
            anisotropic: args.anisotropic.unwrap_or(d.sampler.anisotropic),
            ..d.sampler
        },
        derivatives: args.derivatives.unwrap_or(d.derivatives),
    }
}

/// A ring's numbers, given as one argument.
#[derive(Clone, Debug)]
struct Ring(Vec<f64>);

impl FromStr for Ring {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        s.split(|c: char| c.is_whitespace() || c == ',')
            .filter(|t| !t.is_empty())
            .map(|t| {
                t.parse::<f64>()
                    .map_err(|_| format!("`{t}` is not a number: a ring is x y pairs"))
            })
            .collect::<std::result::Result<Vec<f64>, String>>()
            .map(Ring)
    }
}

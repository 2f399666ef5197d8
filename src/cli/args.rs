//! Argument types several subcommands share.

use clap::builder::TypedValueParser;
use clap::Args;
use rasterlab::raster::line::{Connectivity, Endpoints, LineOptions};
use rasterlab::raster::polygon::WindingRule;
use rasterlab::raster::{FillRule, SamplePattern};

/// A `WxH` size.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Size {
    pub width: u32,
    pub height: u32,
}

impl std::str::FromStr for Size {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (w, h) = s
            .split_once(['x', 'X'])
            .ok_or_else(|| format!("`{s}` is not a size like 640x480"))?;
        let parse = |v: &str| {
            v.trim()
                .parse::<u32>()
                .map_err(|_| format!("`{s}` is not a size like 640x480"))
        };
        Ok(Size {
            width: parse(w)?,
            height: parse(h)?,
        })
    }
}

/// Options of the line back-ends.
#[derive(Args, Debug)]
pub struct LineArgs {
    /// Line connectivity: 8 or 4.
    #[arg(long, default_value = "8")]
    connectivity: Connectivity,
    /// Line endpoints: inclusive or half-open.
    #[arg(long, default_value = "inclusive")]
    endpoints: Endpoints,
    /// Draw lines so the pixels do not depend on the direction of travel.
    #[arg(long)]
    symmetric: bool,
}

impl LineArgs {
    /// The options given.
    pub fn options(&self) -> LineOptions {
        LineOptions {
            connectivity: self.connectivity,
            endpoints: self.endpoints,
            symmetric: self.symmetric,
        }
    }
}

/// More timed runs than this add nothing to a median.
const MAX_SAMPLES: usize = 1000;

/// `--samples`: timed runs of one measurement, 1 to [`MAX_SAMPLES`].
pub fn samples(s: &str) -> Result<usize, String> {
    s.parse::<usize>()
        .ok()
        .filter(|n| (1..=MAX_SAMPLES).contains(n))
        .ok_or_else(|| format!("--samples must be between 1 and {MAX_SAMPLES}, not {s}"))
}

/// `--msaa N`: the standard pattern of N samples (1, 2, 4, 8 or 16).
pub fn msaa(text: &str) -> Result<SamplePattern, String> {
    let n: u32 = text
        .parse()
        .map_err(|_| format!("`{text}` is not a sample count (1, 2, 4, 8 or 16)"))?;
    SamplePattern::standard(n).map_err(|e| e.to_string())
}

/// `--rule` of the commands that draw: one of [`FillRule::ALL`], which
/// `--help` lists as the possible values.
pub fn fill_rule() -> impl TypedValueParser<Value = FillRule> {
    clap::builder::PossibleValuesParser::new(FillRule::ALL.map(FillRule::name))
        .try_map(|name| name.parse::<FillRule>())
}

/// `--fill` of the commands that fill polygons: one of
/// [`WindingRule::ALL`], which `--help` lists as the possible values.
pub fn winding_rule() -> impl TypedValueParser<Value = WindingRule> {
    clap::builder::PossibleValuesParser::new(WindingRule::ALL.map(WindingRule::name))
        .try_map(|name| name.parse::<WindingRule>())
}

/// `--rule` given with a line back-end, which draws by its own
/// convention: refused rather than ignored.
pub fn rule_for_lines() -> rasterlab::Error {
    rasterlab::Error::InvalidArgument(
        "--rule is a triangle fill rule; a line back-end draws by its own convention \
         (see `rasterlab backends`)"
            .into(),
    )
}

//! How a check snaps a case's vertices before judging it (`--snap`).
//!
//! Direct3D and Vulkan hardware snap vertex positions to a sub-pixel grid
//! before any coverage test: 8 fractional bits, 1/256 px, is rasterlab's
//! own grid (see [`crate::raster::fixed`]). The courses' assignments snap
//! nothing: CS184 HW1, CS248 A1 and Scotty3D A1 test pixel centres against
//! edge functions of the vertices as given, in floating point.
//!
//! - `1/256` (the default), or any coarser power of two down to `1`:
//!   every coordinate is rounded to the grid, halfway to even, then judged
//!   in exact integers. A subject must snap the same way.
//! - `none`: the coordinates are judged as given, exactly. The reference
//!   computes on the 1/256 px grid, so under `none` every coordinate a
//!   check makes is a multiple of 1/256 px (there the grid is no rounding
//!   at all), and a case file with a coordinate off that grid is refused.
//!   A floating-point rasterizer passes where its arithmetic is exact: in
//!   `f64`, edge functions of such coordinates are exact while the
//!   coordinates stay below about 2^18 px.
//!
//! ```
//! use rasterlab::check::Snapping;
//! let coarse: Snapping = "1/16".parse().unwrap();
//! // 1/32 px is halfway between two steps of 1/16: to even, that is 0.
//! assert_eq!(coarse.apply((1.0 / 32.0, 3.0 / 32.0)), (0.0, 0.125));
//! assert_eq!("none".parse::<Snapping>().unwrap().apply((0.3, 0.7)), (0.3, 0.7));
//! assert!("1/3".parse::<Snapping>().is_err());
//! ```

use crate::error::{Error, Result};
use crate::raster::fixed::SUBPIXEL_BITS;
use std::fmt;
use std::str::FromStr;

/// A point in screen pixels, as a case writes it.
type Point = (f64, f64);

/// How a case's coordinates are snapped before they are judged.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Snapping {
    /// Rounded to a grid of `1 / 2^bits` px (`bits` from 0 to 8),
    /// halfway to even.
    Grid {
        /// Fractional bits of the grid: 8 is 1/256 px, 0 whole pixels.
        bits: u32,
    },
    /// Not snapped: judged as given (every coordinate on the 1/256 px grid).
    AsGiven,
}

impl Default for Snapping {
    /// 1/256 px, the rules' own grid.
    fn default() -> Snapping {
        Snapping::Grid {
            bits: SUBPIXEL_BITS,
        }
    }
}

impl Snapping {
    /// Every choice, finest grid first, `none` last: the names `--snap`
    /// takes.
    pub fn all() -> Vec<Snapping> {
        (0..=SUBPIXEL_BITS)
            .rev()
            .map(|bits| Snapping::Grid { bits })
            .chain([Snapping::AsGiven])
            .collect()
    }

    /// The point as the check judges it.
    pub fn apply(self, p: Point) -> Point {
        match self {
            Snapping::Grid { bits } => {
                let scale = f64::from(1u32 << bits);
                let round = |v: f64| (v * scale).round_ties_even() / scale;
                (round(p.0), round(p.1))
            }
            Snapping::AsGiven => p,
        }
    }

    /// The size of a grid step in pixels (the 1/256 px grid for `none`,
    /// the finest on which its coordinates lie).
    pub fn step(self) -> f64 {
        match self {
            Snapping::Grid { bits } => 1.0 / f64::from(1u32 << bits),
            Snapping::AsGiven => 1.0 / f64::from(1u32 << SUBPIXEL_BITS),
        }
    }

    /// In words, for reports and hints: `snapped to 1/256 px (halfway to
    /// even)`, or `not snapped: judged as given`.
    pub fn describe(self) -> String {
        match self {
            Snapping::Grid { .. } => format!("snapped to {self} px (halfway to even)"),
            Snapping::AsGiven => "not snapped: judged as given".into(),
        }
    }

    /// Refuses a point the check cannot judge exactly under this
    /// snapping: under `none`, one off the 1/256 px grid.
    pub fn check_exact(self, p: Point) -> Result<()> {
        let on_grid = |v: f64| (v * 256.0).fract() == 0.0;
        if self == Snapping::AsGiven && !(on_grid(p.0) && on_grid(p.1)) {
            return Err(Error::InvalidArgument(format!(
                "({}, {}) is not on the 1/256 px grid: with --snap none the reference judges coordinates as given only where they are multiples of 1/256 px (snap it, or use --snap 1/256)",
                p.0, p.1
            )));
        }
        Ok(())
    }
}

impl fmt::Display for Snapping {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Snapping::Grid { bits: 0 } => f.write_str("1"),
            Snapping::Grid { bits } => write!(f, "1/{}", 1u32 << bits),
            Snapping::AsGiven => f.write_str("none"),
        }
    }
}

impl FromStr for Snapping {
    type Err = Error;
    fn from_str(name: &str) -> Result<Snapping> {
        Snapping::all()
            .into_iter()
            .find(|s| s.to_string() == name.trim())
            .ok_or_else(|| {
                let known: Vec<String> = Snapping::all().iter().map(|s| s.to_string()).collect();
                Error::InvalidArgument(format!(
                    "unknown snapping `{name}`: expected one of {}",
                    known.join(", ")
                ))
            })
    }
}

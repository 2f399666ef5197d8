//! `dda`: the incremental version of direct drawing (the line-drawing slides).
//!
//! ```text
//! y = y0
//! m = (y1 - y0) / (x1 - x0)
//! for all integer x in [x0, x1]:
//!     colorize pixel (x, round(y))
//!     y = y + m
//! ```
//!
//! The multiplication leaves the loop: each column adds the slope `m` to a
//! running `y`. As on the slide, `y` and `m` are floating-point numbers
//! (`f64`), so rounding errors accumulate; where the ideal line passes
//! exactly halfway between two rows, `dda` may pick the other one than
//! `direct`. Every pixel is still within half a pixel (plus that error) of
//! the ideal line, which the property tests check.

use super::{AliasedLine, LineDescriptor, LineWalk, OctantFrame};
use crate::raster::descriptor::{CostClass, Role};
use crate::raster::fixed::SUBPIXEL_SCALE;

/// Digital differential analyser: `y += m` per column.
#[derive(Copy, Clone, Debug, Default)]
pub struct Dda;

impl Dda {
    /// Each column of a frame as `(i, y, k)`: the accumulated `y` (in
    /// pixels, `y += m` per column) and the row it rounds to.
    pub fn columns(frame: &OctantFrame) -> Vec<(i64, f64, i64)> {
        let mut columns = Vec::with_capacity((frame.i1 - frame.i0 + 1).max(0) as usize);
        Dda::each_column(frame, frame.i0, frame.i1, |column| columns.push(column));
        columns
    }

    /// The loop itself, over columns `first..=last` (inside `frame.i0..=
    /// frame.i1`): gives each column's `(i, y, k)` to `visit`. `y` grows
    /// from the first column whatever `first` is, so that each column has
    /// the very `y` (rounding errors included) of the whole walk.
    #[inline(always)]
    fn each_column(
        frame: &OctantFrame,
        first: i64,
        last: i64,
        mut visit: impl FnMut((i64, f64, i64)),
    ) {
        let scale = SUBPIXEL_SCALE as f64;
        let (du, dv) = (frame.du() as f64, frame.dv() as f64);
        let m = if du > 0.0 { dv / du } else { 0.0 };
        // y at the first column's centre, in pixels.
        let mut y = (frame.v0 as f64 + m * (frame.i0 as f64 * scale - frame.u0 as f64)) / scale;
        for _ in frame.i0..first {
            y += m;
        }
        for i in first..=last {
            // Nearest row, ties to the lower row (the start's side).
            visit((i, y, ceil(y - 0.5)));
            y += m;
        }
    }
}

/// `t.ceil() as i64` for the `|t| < 2^52` of a segment in the guard band,
/// without the library call `ceil` is on a baseline x86-64 CPU: the
/// conversion truncates towards zero, which is the ceiling for negative
/// `t` and for whole `t`, and one below it otherwise.
#[inline(always)]
fn ceil(t: f64) -> i64 {
    let truncated = t as i64;
    truncated + i64::from((truncated as f64) < t)
}

impl AliasedLine for Dda {
    const DESCRIPTOR: LineDescriptor = LineDescriptor {
        name: "dda",
        description:
            "incremental (DDA): y += m per column in floating point, no multiplication in the loop",
        walk: LineWalk::Incremental,
        role: Role::Alternative,
        cost: CostClass::FollowsSize,
    };

    #[inline]
    fn walk_columns(frame: &OctantFrame, first: i64, last: i64, mut visit: impl FnMut(i64, i64)) {
        Dda::each_column(frame, first, last, |(i, _, k)| visit(i, k));
    }
}

#[cfg(test)]
mod tests {
    use super::ceil;

    /// The conversion-based ceiling is the library's at whole numbers,
    /// halves, either side of zero and at the ends of the range.
    #[test]
    fn ceil_is_the_library_ceiling() {
        let mut rng = fastrand::Rng::with_seed(3);
        let edges = [
            0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 1e-300, -1e-300, 4.0e15, -4.0e15,
        ];
        let cases = edges
            .into_iter()
            .chain((-400..400).map(|n| f64::from(n) / 4.0))
            .chain((0..10_000).map(|_| (rng.f64() - 0.5) * 2e6));
        for t in cases {
            assert_eq!(ceil(t), t.ceil() as i64, "ceil({t})");
            let next = f64::from_bits(t.to_bits() + 1);
            assert_eq!(ceil(next), next.ceil() as i64, "ceil({next})");
        }
    }
}

//! `direct`: the line-drawing slides' direct drawing, `y = m (x - x0) + y0` at every column.
//!
//! ```text
//! m = (y1 - y0) / (x1 - x0)
//! for all integer x in [x0, x1]:
//!     y = m (x - x0) + y0
//!     round y to the nearest integer
//!     colorize pixel (x, y)
//! ```
//!
//! The slide calls its performance lousy: a multiplication and a rounding
//! at every step. Here `y` is evaluated exactly (as the fraction
//! `(v0 du + dv (u - u0)) / du` in fixed-point units), so the rounding is
//! exact too, ties going to the row nearer the start, and the result is
//! pixel for pixel the same as `bresenham`'s. Other octants by symmetry
//! ([`super::OctantFrame`]).

use super::{AliasedLine, LineDescriptor, LineWalk, OctantFrame};
use crate::raster::descriptor::{CostClass, Role};
use crate::raster::fixed::SUBPIXEL_SCALE;

/// Direct evaluation of `y = m x + b`, rounded, at every column.
#[derive(Copy, Clone, Debug, Default)]
pub struct Direct;

impl Direct {
    /// The walk as a trace shows it, `(i, y, k)`: each column the
    /// back-end walks and its row, with `y` at the column's centre, in
    /// pixels (an `f64`, for display only). A segment of zero length has
    /// its start's `y`.
    pub fn columns(frame: &OctantFrame) -> Vec<(i64, f64, i64)> {
        let y = |i: i64| match frame.du() {
            0 => frame.v0 as f64 / SUBPIXEL_SCALE as f64,
            du => frame.scaled_v_at(i) as f64 / (du * SUBPIXEL_SCALE) as f64,
        };
        let mut columns = Vec::with_capacity((frame.i1 - frame.i0 + 1).max(0) as usize);
        Direct::walk(frame, |i, k| columns.push((i, y(i), k)));
        columns
    }
}

impl AliasedLine for Direct {
    const DESCRIPTOR: LineDescriptor = LineDescriptor {
        name: "direct",
        description: "direct evaluation of y = m(x - x0) + y0, rounded at every column",
        walk: LineWalk::DirectEvaluation,
        role: Role::Alternative,
        cost: CostClass::FollowsSize,
    };

    /// Each column `i` with the row `k` the slide's `y = m (x - x0) + y0`
    /// rounds to there, decided on the exact fraction. Every column is
    /// evaluated on its own, so the walk starts anywhere.
    #[inline]
    fn walk_columns(frame: &OctantFrame, first: i64, last: i64, mut visit: impl FnMut(i64, i64)) {
        (first..=last).for_each(|i| visit(i, frame.nearest_row(i)));
    }
}

//! `bresenham`: the midpoint / Bresenham algorithm (the line-drawing slides).
//!
//! From pixel `(x, y)` the next pixel to the right is either `(x + 1, y)` or
//! `(x + 1, y + 1)`. The choice is made by evaluating the implicit line
//! equation `f` at the midpoint between them, `d = f(x + 1, y + 0.5)`:
//! if `d < 0` the line passes above the midpoint and `y` steps up.
//!
//! ```text
//! y = y0
//! d = f(x0 + 1, y0 + 0.5)
//! for all integer x in [x0, x1]:
//!     colorize pixel (x, y)
//!     if d < 0:  y = y + 1;  d = d + (x1 - x0) + (y0 - y1)
//!     else:                  d = d + (y0 - y1)
//! ```
//!
//! `d` is an integer decision variable: with snapped endpoints, `f` is
//! evaluated in fixed-point units (scaled by 256), so the loop has only
//! integer additions and a sign test, and it chooses exactly the rows
//! `direct` computes (a tie, `d == 0`, keeps `y`: the row nearer the
//! start). Other octants by symmetry ([`super::OctantFrame`]).

use super::{AliasedLine, LineDescriptor, LineWalk, OctantFrame};
use crate::raster::descriptor::{CostClass, Role};
use crate::raster::fixed::{HALF_PIXEL, SUBPIXEL_SCALE};

/// Midpoint / Bresenham with an integer decision variable.
#[derive(Copy, Clone, Debug, Default)]
pub struct Bresenham;

/// One step of the algorithm, for traces.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct BresenhamStep {
    /// Column (frame coordinates).
    pub i: i64,
    /// Row (frame coordinates).
    pub k: i64,
    /// The decision variable `d = f(i + 1, k + 0.5)` before the choice,
    /// in fixed-point units times `du`.
    pub d: i128,
    /// Whether the row steps up for the next column.
    pub step_up: bool,
}

impl Bresenham {
    /// Runs the midpoint loop in a frame, returning each column's step.
    pub fn steps(frame: &OctantFrame) -> Vec<BresenhamStep> {
        let mut steps = Vec::with_capacity((frame.i1 - frame.i0 + 1).max(0) as usize);
        Bresenham::each_step(frame, frame.i0, frame.i1, |step| steps.push(step));
        steps
    }

    /// The steps over columns `first..=last` only (inside `frame.i0..=
    /// frame.i1`), the first started with the row and decision variable
    /// the whole walk has there: how a clipped segment's walk restarts at
    /// its entry column.
    pub fn steps_within(frame: &OctantFrame, first: i64, last: i64) -> Vec<BresenhamStep> {
        let mut steps = Vec::with_capacity((last - first + 1).max(0) as usize);
        Bresenham::each_step(frame, first, last, |step| steps.push(step));
        steps
    }

    /// The loop itself, over columns `first..=last` (inside `frame.i0..=
    /// frame.i1`): gives each column's step to `visit`. Started past `i0`,
    /// it starts with the row and the decision variable it would have had
    /// there (the row is the one nearest the line, as `direct` finds it).
    ///
    /// `d` fits an `i64`: in the guard band `|du|, |v| < 2^25` frame units,
    /// so its start is below `2^59` ([`OctantFrame::scaled_v_at`]) and each
    /// step keeps it within `256 du` of zero.
    #[inline(always)]
    fn each_step(frame: &OctantFrame, first: i64, last: i64, mut visit: impl FnMut(BresenhamStep)) {
        let (du, dv) = (frame.du(), frame.dv());
        let mut k = frame.nearest_row(first);
        // d = f(first + 1, k + 0.5) = du * (midpoint row) - du * v(first + 1)
        let mut d = du * (SUBPIXEL_SCALE * k + HALF_PIXEL) - frame.scaled_v_at(first + 1);
        let (up, across) = (SUBPIXEL_SCALE * (du - dv), SUBPIXEL_SCALE * dv);
        for i in first..=last {
            let step_up = d < 0;
            visit(BresenhamStep {
                i,
                k,
                d: i128::from(d),
                step_up,
            });
            if step_up {
                k += 1;
                d += up;
            } else {
                d -= across;
            }
        }
    }
}

impl AliasedLine for Bresenham {
    const DESCRIPTOR: LineDescriptor = LineDescriptor {
        name: "bresenham",
        description:
            "midpoint / Bresenham: decision variable d = f(x+1, y+0.5), a whole number of 1/65536 px², additions only",
        walk: LineWalk::Midpoint,
        role: Role::Default,
        cost: CostClass::FollowsSize,
    };

    #[inline]
    fn walk_columns(frame: &OctantFrame, first: i64, last: i64, mut visit: impl FnMut(i64, i64)) {
        Bresenham::each_step(frame, first, last, |step| visit(step.i, step.k));
    }
}

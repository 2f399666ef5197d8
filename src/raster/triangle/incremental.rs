//! `incremental`: edge functions stepped by additions (Pineda, 1988).
//!
//! An edge function `E(x, y) = a x + b y + c` is linear, so moving one pixel
//! right adds `a * 256` and moving one pixel down adds `b * 256` (in
//! fixed-point units). The back-end evaluates the three edge functions
//! once, at the first sample of the bounding box, and from then on only
//! adds: the inner loop has no multiplication, just three additions and
//! the sign test. It is the same idea as the line-drawing slides' incremental line
//! algorithm (`y = y + m` instead of `y = m x + b`), and exact because the
//! steps are integers.
//!
//! ```text
//! row = E(first sample of the box)
//! for each row of the box
//!   e = row
//!   for each pixel of the row
//!     if e + bias >= 0 on all edges: add the pixel to the row's span
//!     e += step_x
//!   emit the row's span (one run: the triangle is convex)
//!   row += step_y
//! ```

use super::{TriangleAlgorithm, TriangleDescriptor, TriangleWalk, Walk, WalkObserver};
use crate::raster::descriptor::{CostClass, Role};
use crate::raster::edge::{PixelRect, TriangleSetup};

/// Bounding box with edge functions stepped by additions.
#[derive(Copy, Clone, Debug, Default)]
pub struct Incremental;

impl TriangleAlgorithm for Incremental {
    const DESCRIPTOR: TriangleDescriptor = TriangleDescriptor {
        name: "incremental",
        description: "bounding box with edge functions stepped by additions (Pineda), no multiplication per pixel",
        walk: TriangleWalk::IncrementalEdges,
        role: Role::Alternative,
        cost: CostClass::FollowsSize,
    };

    #[inline]
    fn draw_triangle<O: WalkObserver>(
        &self,
        t: &TriangleSetup,
        viewport: PixelRect,
        walk: &mut Walk<O>,
    ) {
        let r = t.bounds_within(viewport);
        if !r.is_empty() {
            step_over(t, r, walk);
        }
    }
}

/// Walks the pixels of `r` (non-empty) row by row, stepping the edge
/// values by additions, and emits those inside `t`, one span per row (the
/// inside pixels of a row are consecutive, the triangle being convex).
#[inline]
pub(crate) fn step_over<O: WalkObserver>(t: &TriangleSetup, r: PixelRect, walk: &mut Walk<O>) {
    let (step_x, step_y) = t.pixel_steps();
    let mut row = t.edge_values_at_pixel(r.x0, r.y0);
    for y in r.y0..=r.y1 {
        if let Some(run) = run_in_row(row, step_x, r.x0, r.x1, y, walk) {
            walk.span(y, run.first, run.last, run.edges);
        }
        for k in 0..3 {
            row[k] += step_y[k];
        }
    }
}

/// The inside pixels of one row, found by testing each.
pub(crate) struct Run {
    /// First inside column.
    pub first: i64,
    /// Last inside column.
    pub last: i64,
    /// Edge values at `first`.
    pub edges: [i64; 3],
}

/// Tests pixels `x0..=x1` of row `y` whose edge values at `x0` are `e`,
/// left to right, and returns the run of inside pixels, if any. The test
/// stops at the first outside pixel after the run: the triangle is
/// convex, so nothing further right is inside.
#[inline]
pub(crate) fn run_in_row<O: WalkObserver>(
    mut e: [i64; 3],
    step_x: [i64; 3],
    x0: i64,
    x1: i64,
    y: i64,
    walk: &mut Walk<O>,
) -> Option<Run> {
    let mut run: Option<Run> = None;
    for x in x0..=x1 {
        if walk.test(x, y, e) {
            match &mut run {
                Some(r) => r.last = x,
                None => {
                    run = Some(Run {
                        first: x,
                        last: x,
                        edges: e,
                    })
                }
            }
        } else if run.is_some() {
            walk.row_stops(y, x);
            break;
        }
        for k in 0..3 {
            e[k] += step_x[k];
        }
    }
    run
}

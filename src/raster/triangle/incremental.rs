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

use super::{emit_span, TriangleAlgorithm, TriangleDescriptor, TriangleWalk, WalkObserver};
use crate::raster::descriptor::{CostClass, Role};
use crate::raster::edge::{PixelRect, TriangleSetup};
use crate::raster::fragment::{FragmentSink, WorkCounters};

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
        sink: &mut dyn FragmentSink,
        work: &mut WorkCounters,
        observer: &mut O,
    ) {
        let r = t.bounds_within(viewport);
        if !r.is_empty() {
            step_over(t, r, sink, work, observer);
        }
    }
}

/// Walks the pixels of `r` (non-empty) row by row, stepping the edge
/// values by additions, and emits those inside `t`, one span per row (the
/// inside pixels of a row are consecutive, the triangle being convex).
#[inline]
pub(crate) fn step_over<O: WalkObserver>(
    t: &TriangleSetup,
    r: PixelRect,
    sink: &mut dyn FragmentSink,
    work: &mut WorkCounters,
    observer: &mut O,
) {
    let (step_x, step_y) = t.pixel_steps();
    let mut row = t.edge_values_at_pixel(r.x0, r.y0);
    for y in r.y0..=r.y1 {
        let (run, tested) = run_in_row(t, row, step_x, r.x0, r.x1, y, observer);
        report_tested(sink, t, y, r.x0, tested, work);
        if let Some(run) = run {
            work.fragments += (run.last - run.first + 1) as u64;
            emit_span(sink, t, y, run.first, run.last, run.edges);
        }
        for k in 0..3 {
            row[k] += step_y[k];
        }
    }
}

/// Counts `tested` samples from column `x0` of row `y` and reports them
/// to the sink as one tested run.
pub(crate) fn report_tested(
    sink: &mut dyn FragmentSink,
    t: &TriangleSetup,
    y: i64,
    x0: i64,
    tested: u64,
    work: &mut WorkCounters,
) {
    if tested > 0 {
        work.samples_tested += tested;
        let x1 = x0 + tested as i64 - 1;
        sink.samples_tested(t.id, y as u32, x0 as u32, x1 as u32);
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
/// left to right (each sample reported to `observer`), and returns the run of inside pixels, if any, and how many
/// pixels were tested (the walk stops at the first outside pixel after the
/// run: the triangle is convex, so nothing further right is inside).
#[inline]
pub(crate) fn run_in_row<O: WalkObserver>(
    t: &TriangleSetup,
    mut e: [i64; 3],
    step_x: [i64; 3],
    x0: i64,
    x1: i64,
    y: i64,
    observer: &mut O,
) -> (Option<Run>, u64) {
    let mut run: Option<Run> = None;
    let mut tested = 0;
    for x in x0..=x1 {
        tested += 1;
        let inside = t.inside(e);
        observer.sample(x, y, e, inside);
        if inside {
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
            observer.row_stops(y, x);
            break;
        }
        for k in 0..3 {
            e[k] += step_x[k];
        }
    }
    (run, tested)
}

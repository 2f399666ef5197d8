//! `incremental`: edge functions stepped by additions (Pineda, 1988).
//!
//! An edge function `E(x, y) = a x + b y + c` is linear, so moving one pixel
//! right adds `a * 256` and moving one pixel down adds `b * 256` (in
//! fixed-point units). The back-end evaluates the three edge functions
//! once, at the first sample of the bounding box, and from then on only
//! adds: the inner loop has no multiplication, just three additions and
//! the sign test. It is the same idea as seed 004's incremental line
//! algorithm (`y = y + m` instead of `y = m x + b`), and exact because the
//! steps are integers.
//!
//! ```text
//! row = E(first sample of the box)
//! for each row of the box
//!   e = row
//!   for each pixel of the row
//!     if e + bias >= 0 on all edges: emit
//!     e += step_x
//!   row += step_y
//! ```

use super::{emit, TriangleRasterizer};
use crate::edge::{PixelRect, TriangleSetup};
use crate::fixed::SUBPIXEL_SCALE;
use crate::fragment::{FragmentSink, WorkCounters};

/// Bounding box with edge functions stepped by additions.
#[derive(Copy, Clone, Debug, Default)]
pub struct Incremental;

impl TriangleRasterizer for Incremental {
    fn name(&self) -> &'static str {
        "incremental"
    }

    fn description(&self) -> &'static str {
        "bounding box with edge functions stepped by additions (Pineda), no multiplication per pixel"
    }

    fn rasterize(
        &self,
        triangles: &[TriangleSetup],
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> WorkCounters {
        let mut work = WorkCounters::default();
        for t in triangles {
            work.primitives += 1;
            let r = t.bounds_within(viewport);
            if !r.is_empty() {
                step_over(t, r, true, sink, &mut work);
            }
        }
        work
    }
}

/// Walks the pixels of `r` (non-empty) row by row, stepping the edge
/// values by additions, and emits those inside `t`; with `test` false,
/// every pixel is emitted untested (for a rectangle known to lie inside).
pub(crate) fn step_over(
    t: &TriangleSetup,
    r: PixelRect,
    test: bool,
    sink: &mut dyn FragmentSink,
    work: &mut WorkCounters,
) {
    let step_x = t.edges.map(|e| e.a * SUBPIXEL_SCALE);
    let step_y = t.edges.map(|e| e.b * SUBPIXEL_SCALE);
    let mut row = t.edge_values_at_pixel(r.x0, r.y0);
    for y in r.y0..=r.y1 {
        let mut e = row;
        for x in r.x0..=r.x1 {
            if !test || t.inside(e) {
                work.fragments += 1;
                emit(sink, t, x, y, e);
            }
            for k in 0..3 {
                e[k] += step_x[k];
            }
        }
        for k in 0..3 {
            row[k] += step_y[k];
        }
    }
    if test {
        work.samples_tested += r.area();
    }
}

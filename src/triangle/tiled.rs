//! `tiled`: edge functions over 8x8 pixel blocks with trivial reject and
//! trivial accept (hierarchical Pineda, as in Larrabee and llvmpipe).
//!
//! The screen is cut into blocks of [`BLOCK`] x [`BLOCK`] pixels aligned to
//! the pixel grid. An edge function is affine, so over the sample points of
//! a rectangle of pixels its smallest and largest values are at the four
//! corner samples. For each block that the triangle's bounding box touches:
//!
//! * if one edge is negative (after its fill-rule bias) at all four
//!   corners, no sample of the block can be inside: **trivial reject**,
//!   nothing more is tested;
//! * if every edge is non-negative at all four corners, every sample is
//!   inside: **trivial accept**, every pixel of the block is emitted with
//!   its edge values stepped by additions, without a test;
//! * otherwise the block straddles an edge and each of its pixels is
//!   tested by [`incremental`](super::incremental)'s loop.
//!
//! The blocks of one block row are classified first; then each pixel row
//! is walked across them, so that a row's inside pixels (one run, the
//! triangle being convex) reach the fragment stage as one span however
//! many blocks it crosses.
//!
//! Triangles whose bounding box fits in one block skip the block step and
//! go straight to the per-pixel loop (cheap set-up for small triangles).
//! The work counters show the saving: `spans` counts blocks visited,
//! `samples_tested` only the pixels of straddling blocks.
//!
//! ```text
//! for each block B meeting the bounding box
//!   c[k] = E_k + bias_k at B's four corner samples
//!   if some k has all c[k] < 0: skip B
//!   else if every c >= 0:       every pixel of B is inside
//!   else:                       test each pixel of B
//! for each pixel row: emit the run of inside pixels across the blocks
//! ```

use super::incremental::{report_tested, run_in_row, step_over, Run};
use super::{emit_span, TriangleRasterizer, TriangleSelection};
use crate::edge::{PixelRect, TriangleSetup};
use crate::fixed::SUBPIXEL_SCALE;
use crate::fragment::{FragmentSink, WorkCounters};

/// Block side in pixels.
pub const BLOCK: i64 = 8;

/// 8x8 blocks with trivial reject and trivial accept.
#[derive(Copy, Clone, Debug, Default)]
pub struct Tiled;

/// What the corner test says about a block.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum BlockClass {
    /// No sample of the block is inside.
    Outside,
    /// Every sample of the block is inside.
    Inside,
    /// The block straddles an edge: test each sample.
    Partial,
}

/// Classifies the pixels of `r` against triangle `t` from the edge values
/// at `r`'s four corner samples.
pub fn classify_block(t: &TriangleSetup, r: PixelRect) -> BlockClass {
    let corners = [
        t.edge_values_at_pixel(r.x0, r.y0),
        t.edge_values_at_pixel(r.x1, r.y0),
        t.edge_values_at_pixel(r.x0, r.y1),
        t.edge_values_at_pixel(r.x1, r.y1),
    ];
    let mut all_inside = true;
    for k in 0..3 {
        let inside = corners.map(|e| e[k] + t.bias[k] >= 0);
        if inside.iter().all(|i| !i) {
            return BlockClass::Outside;
        }
        all_inside &= inside.iter().all(|i| *i);
    }
    if all_inside {
        BlockClass::Inside
    } else {
        BlockClass::Partial
    }
}

impl TriangleRasterizer for Tiled {
    fn name(&self) -> &'static str {
        "tiled"
    }

    fn description(&self) -> &'static str {
        "8x8 blocks: trivial reject and trivial accept from the corners, per-pixel edge tests only where a block straddles an edge"
    }

    fn rasterize_selection(
        &self,
        triangles: TriangleSelection<'_>,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> WorkCounters {
        let mut work = WorkCounters::default();
        let mut blocks: Vec<(PixelRect, BlockClass)> = Vec::new();
        for t in triangles.iter() {
            work.primitives += 1;
            let r = t.bounds_within(viewport);
            if r.is_empty() {
                continue;
            }
            if r.x1 - r.x0 < BLOCK && r.y1 - r.y0 < BLOCK {
                step_over(t, r, true, sink, &mut work);
                continue;
            }
            let step_x = t.edges.map(|e| e.a * SUBPIXEL_SCALE);
            let step_y = t.edges.map(|e| e.b * SUBPIXEL_SCALE);
            let (bx0, by0) = (r.x0.div_euclid(BLOCK), r.y0.div_euclid(BLOCK));
            let (bx1, by1) = (r.x1.div_euclid(BLOCK), r.y1.div_euclid(BLOCK));
            let mut row = t.edge_values_at_pixel(r.x0, r.y0);
            for by in by0..=by1 {
                // One row of blocks: classify each block once ...
                let y0 = (by * BLOCK).max(r.y0);
                let y1 = (by * BLOCK + BLOCK - 1).min(r.y1);
                blocks.clear();
                for bx in bx0..=bx1 {
                    let block = PixelRect {
                        x0: (bx * BLOCK).max(r.x0),
                        y0,
                        x1: (bx * BLOCK + BLOCK - 1).min(r.x1),
                        y1,
                    };
                    work.spans += 1;
                    blocks.push((block, classify_block(t, block)));
                }
                // ... then walk its pixel rows across the blocks.
                for y in y0..=y1 {
                    let at = |x: i64| {
                        let n = x - r.x0;
                        [0, 1, 2].map(|k| row[k] + step_x[k] * n)
                    };
                    if let Some(run) = row_run(t, y, &blocks, step_x, at, sink, &mut work) {
                        work.fragments += (run.last - run.first + 1) as u64;
                        emit_span(sink, t, y, run.first, run.last, run.edges);
                    }
                    for k in 0..3 {
                        row[k] += step_y[k];
                    }
                }
            }
        }
        work
    }
}

/// The inside pixels of one pixel row, across a row of classified blocks:
/// outside blocks are skipped, inside blocks join the run untested, and
/// only straddling blocks are tested pixel by pixel. `at(x)` gives the
/// edge values at column `x` of the row.
fn row_run(
    t: &TriangleSetup,
    y: i64,
    blocks: &[(PixelRect, BlockClass)],
    step_x: [i64; 3],
    at: impl Fn(i64) -> [i64; 3],
    sink: &mut dyn FragmentSink,
    work: &mut WorkCounters,
) -> Option<Run> {
    let mut run: Option<Run> = None;
    for &(block, class) in blocks {
        let (x0, x1) = (block.x0, block.x1);
        let (first, last, edges) = match class {
            BlockClass::Outside if run.is_some() => break,
            BlockClass::Outside => continue,
            BlockClass::Inside => (x0, x1, None),
            BlockClass::Partial => {
                let (part, tested) = run_in_row(t, at(x0), step_x, x0, x1);
                report_tested(sink, t, y, x0, tested, work);
                match part {
                    Some(p) => (p.first, p.last, Some(p.edges)),
                    None if run.is_some() => break,
                    None => continue,
                }
            }
        };
        match &mut run {
            Some(r) => {
                debug_assert_eq!(first, r.last + 1, "a row's inside pixels are one run");
                r.last = last;
            }
            None => {
                run = Some(Run {
                    first,
                    last,
                    edges: edges.unwrap_or_else(|| at(first)),
                })
            }
        }
        if last < x1 {
            break; // the run ended inside this block
        }
    }
    run
}

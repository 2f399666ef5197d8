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
//! Triangles whose bounding box fits in one block skip the block step and
//! go straight to the per-pixel loop (cheap set-up for small triangles).
//! The work counters show the saving: `spans` counts blocks visited,
//! `samples_tested` only the pixels of straddling blocks.
//!
//! ```text
//! for each block B meeting the bounding box
//!   c[k] = E_k + bias_k at B's four corner samples
//!   if some k has all c[k] < 0: skip B
//!   else if every c >= 0:       emit every pixel of B
//!   else:                       test each pixel of B
//! ```

use super::incremental::step_over;
use super::TriangleRasterizer;
use crate::edge::{PixelRect, TriangleSetup};
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
            if r.is_empty() {
                continue;
            }
            if r.x1 - r.x0 < BLOCK && r.y1 - r.y0 < BLOCK {
                step_over(t, r, true, sink, &mut work);
                continue;
            }
            let (bx0, by0) = (r.x0.div_euclid(BLOCK), r.y0.div_euclid(BLOCK));
            let (bx1, by1) = (r.x1.div_euclid(BLOCK), r.y1.div_euclid(BLOCK));
            for by in by0..=by1 {
                for bx in bx0..=bx1 {
                    let block = PixelRect {
                        x0: bx * BLOCK,
                        y0: by * BLOCK,
                        x1: bx * BLOCK + BLOCK - 1,
                        y1: by * BLOCK + BLOCK - 1,
                    }
                    .intersect(r);
                    work.spans += 1;
                    match classify_block(t, block) {
                        BlockClass::Outside => {}
                        BlockClass::Inside => step_over(t, block, false, sink, &mut work),
                        BlockClass::Partial => step_over(t, block, true, sink, &mut work),
                    }
                }
            }
        }
        work
    }
}

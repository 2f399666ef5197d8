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
//! The blocks of one block row are classified first, neighbouring inside
//! (or outside) blocks merged; then each pixel row is walked across them,
//! so that a row's inside pixels (one run, the triangle being convex) reach
//! the fragment stage as one span however many blocks it crosses.
//!
//! Wide triangles add one level of hierarchy: a block row is first
//! classified in aligned stretches of [`STRETCH`] blocks, and only a
//! straddling stretch is classified block by block, so the inside of a
//! large triangle costs one test per 64 pixels of a block row. The corner
//! test itself needs two corners per edge, not four: the signs of the
//! edge's steps say at which corner it is smallest and largest.
//!
//! Triangles whose bounding box fits in one block skip the block step and
//! go straight to the per-pixel loop (cheap set-up for small triangles);
//! those whose box is at most 2x2 pixels, most of a dense mesh's, have
//! their few samples tested one by one, without the loop.
//! The work counters show the saving: `spans` counts the blocks and
//! stretches classified, `samples_tested` only the pixels of straddling
//! blocks.
//!
//! ```text
//! for each block B meeting the bounding box (stretch by stretch if wide)
//!   c[k] = E_k + bias_k at B's four corner samples
//!   if some k has all c[k] < 0: skip B
//!   else if every c >= 0:       every pixel of B is inside
//!   else:                       test each pixel of B
//! for each pixel row: emit the run of inside pixels across the blocks
//! ```

use super::incremental::{run_in_row, step_over, Run};
use super::BlockClass;
use super::{TriangleAlgorithm, TriangleDescriptor, TriangleWalk, Walk, WalkObserver};
use crate::raster::descriptor::{CostClass, Role};
use crate::raster::edge::{PixelRect, TriangleSetup};

/// Block side in pixels.
pub const BLOCK: i64 = 8;
/// Blocks per stretch: in a triangle at least this many blocks wide, a
/// block row is first classified in stretches of this many blocks (64
/// pixels), and only straddling stretches block by block.
pub const STRETCH: i64 = 8;

/// 8x8 blocks with trivial reject and trivial accept.
#[derive(Copy, Clone, Debug, Default)]
pub struct Tiled;

/// Classifies the pixels of `r` against triangle `t` from the edge values
/// at `r`'s four corner samples.
#[cfg(test)]
fn classify_block(t: &TriangleSetup, r: PixelRect) -> BlockClass {
    let (step_x, step_y) = t.pixel_steps();
    let top_left = t.edge_values_at_pixel(r.x0, r.y0);
    classify_from_corner(t, top_left, step_x, step_y, r.x1 - r.x0, r.y1 - r.y0)
}

/// The tests' `classify_block` for a block `w + 1` by `h + 1` pixels whose top-left
/// sample has edge values `top_left`; `step_x` and `step_y` are the edges'
/// changes per pixel right and per pixel down.
///
/// Of the four corners, the one where edge `k` is smallest is found from
/// the signs of its steps alone (a step that lowers the value is taken),
/// and likewise the largest: two values per edge instead of four.
#[inline]
fn classify_from_corner(
    t: &TriangleSetup,
    top_left: [i64; 3],
    step_x: [i64; 3],
    step_y: [i64; 3],
    w: i64,
    h: i64,
) -> BlockClass {
    let mut all_inside = true;
    for k in 0..3 {
        let (dx, dy) = (step_x[k] * w, step_y[k] * h);
        let base = top_left[k] + t.bias[k];
        if base + dx.max(0) + dy.max(0) < 0 {
            return BlockClass::Outside;
        }
        all_inside &= base + dx.min(0) + dy.min(0) >= 0;
    }
    if all_inside {
        BlockClass::Inside
    } else {
        BlockClass::Partial
    }
}

impl TriangleAlgorithm for Tiled {
    const DESCRIPTOR: TriangleDescriptor = TriangleDescriptor {
        name: "tiled",
        description: "8x8 blocks: trivial reject and trivial accept from the corners, per-pixel edge tests only where a block straddles an edge",
        walk: TriangleWalk::Blocks,
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
        if r.is_empty() {
            return;
        }
        // The path is chosen by the box's whole height, not by the part
        // of it in this viewport: a draw cut into bands of rows (one per
        // thread) tests the same samples as one draw of the target.
        let (w, h) = (r.x1 - r.x0, t.bounds.y1 - t.bounds.y0);
        if w <= 1 && h <= 1 {
            tiny_box(t, r, walk);
            return;
        }
        if w < BLOCK && h < BLOCK {
            step_over(t, r, walk);
            return;
        }
        BLOCK_ROW.with_borrow_mut(|blocks| walk_blocks(t, r, blocks, walk));
    }
}

thread_local! {
    /// One block row's classified blocks, kept from triangle to triangle
    /// (a draw's large triangles share one allocation per thread).
    static BLOCK_ROW: std::cell::RefCell<Vec<(PixelRect, BlockClass)>> =
        const { std::cell::RefCell::new(Vec::new()) };
}

/// The block walk of a triangle whose box `r` (non-empty, within the
/// viewport) is at least a block wide or its whole box a block high:
/// block rows classified, then their pixel rows walked across them;
/// `blocks` is scratch space.
///
/// A block is classified over its rows within the triangle's whole box,
/// not only those within the viewport, so that a band of rows (a thread's
/// part of the target) classifies a block as the whole target does, and
/// the samples tested do not depend on how the target is cut.
fn walk_blocks<O: WalkObserver>(
    t: &TriangleSetup,
    r: PixelRect,
    blocks: &mut Vec<(PixelRect, BlockClass)>,
    walk: &mut Walk<O>,
) {
    let (step_x, step_y) = t.pixel_steps();
    let (bx0, by0) = (r.x0.div_euclid(BLOCK), r.y0.div_euclid(BLOCK));
    let (bx1, by1) = (r.x1.div_euclid(BLOCK), r.y1.div_euclid(BLOCK));
    // Stretches pay only where one can be wholly inside or outside.
    let stretch = if r.x1 - r.x0 >= STRETCH * BLOCK {
        STRETCH
    } else {
        1
    };
    let mut row = t.edge_values_at_pixel(r.x0, r.y0);
    for by in by0..=by1 {
        // One row of blocks: classify each block once, over its rows in
        // the triangle's box ...
        let y0 = (by * BLOCK).max(r.y0);
        let y1 = (by * BLOCK + BLOCK - 1).min(r.y1);
        let class_y0 = (by * BLOCK).max(t.bounds.y0);
        let class_y1 = (by * BLOCK + BLOCK - 1).min(t.bounds.y1);
        blocks.clear();
        // Blocks `b0..=b1` of the row: their pixels, as a rectangle,
        // and its class.
        let classify = |b0: i64, b1: i64| {
            let x0 = (b0 * BLOCK).max(r.x0);
            let x1 = (b1 * BLOCK + BLOCK - 1).min(r.x1);
            let top_left =
                [0, 1, 2].map(|k| row[k] + step_x[k] * (x0 - r.x0) + step_y[k] * (class_y0 - y0));
            let h = class_y1 - class_y0;
            let class = classify_from_corner(t, top_left, step_x, step_y, x1 - x0, h);
            (PixelRect { x0, y0, x1, y1 }, class)
        };
        let mut bx = bx0;
        while bx <= bx1 {
            // A stretch of aligned blocks is classified as a whole
            // first; only a straddling one is looked into.
            let last = ((bx / stretch + 1) * stretch - 1).min(bx1);
            walk.visit();
            let (stretch_rect, class) = classify(bx, last);
            if class != BlockClass::Partial || last == bx {
                walk.block(stretch_rect, class);
                push_merged(blocks, stretch_rect, class);
            } else {
                for b in bx..=last {
                    walk.visit();
                    let (block, class) = classify(b, b);
                    walk.block(block, class);
                    push_merged(blocks, block, class);
                }
            }
            bx = last + 1;
        }
        // ... then walk its pixel rows across the blocks.
        for y in y0..=y1 {
            let at = |x: i64| {
                let n = x - r.x0;
                [0, 1, 2].map(|k| row[k] + step_x[k] * n)
            };
            if let Some(run) = row_run(y, blocks, step_x, at, walk) {
                walk.span(y, run.first, run.last, run.edges);
            }
            for k in 0..3 {
                row[k] += step_y[k];
            }
        }
    }
}

/// The samples of a box of at most 2x2 pixels (most triangles of a dense
/// mesh), tested one by one without a loop: each row's one or two
/// samples, then its run of inside pixels. The same fragments, edge
/// values and counts as [`step_over`] gives (a row of two pixels always
/// has both tested: the walk stops after an outside pixel that follows
/// the run, which here is the last one anyway).
#[inline]
fn tiny_box<O: WalkObserver>(t: &TriangleSetup, r: PixelRect, walk: &mut Walk<O>) {
    let (step_x, step_y) = t.pixel_steps();
    let plus = |e: [i64; 3], step: [i64; 3]| [e[0] + step[0], e[1] + step[1], e[2] + step[2]];
    let mut left = t.edge_values_at_pixel(r.x0, r.y0);
    for y in r.y0..=r.y1 {
        if r.x0 == r.x1 {
            if walk.test(r.x0, y, left) {
                walk.fragment(r.x0, y, left);
            }
        } else {
            let right = plus(left, step_x);
            let l = walk.test(r.x0, y, left);
            let r_in = walk.test(r.x1, y, right);
            if l && !r_in {
                walk.row_stops(y, r.x1);
            }
            let run = match (l, r_in) {
                (true, true) => Some((r.x0, r.x1, left)),
                (true, false) => Some((r.x0, r.x0, left)),
                (false, true) => Some((r.x1, r.x1, right)),
                (false, false) => None,
            };
            if let Some((first, last, edges)) = run {
                walk.span(y, first, last, edges);
            }
        }
        left = plus(left, step_y);
    }
}

/// Appends a classified block to a block row, merged into the previous
/// one when both are inside or both outside, so the row walk steps over
/// them at once.
fn push_merged(blocks: &mut Vec<(PixelRect, BlockClass)>, block: PixelRect, class: BlockClass) {
    match blocks.last_mut() {
        Some((last, c)) if *c == class && class != BlockClass::Partial => last.x1 = block.x1,
        _ => blocks.push((block, class)),
    }
}

/// The inside pixels of one pixel row, across a row of classified blocks
/// (merged where neighbours agree): outside blocks are skipped, inside
/// blocks join the run untested, and
/// only straddling blocks are tested pixel by pixel. `at(x)` gives the
/// edge values at column `x` of the row.
fn row_run<O: WalkObserver>(
    y: i64,
    blocks: &[(PixelRect, BlockClass)],
    step_x: [i64; 3],
    at: impl Fn(i64) -> [i64; 3],
    walk: &mut Walk<O>,
) -> Option<Run> {
    let mut run: Option<Run> = None;
    for &(block, class) in blocks {
        let (x0, x1) = (block.x0, block.x1);
        let (first, last, edges) = match class {
            BlockClass::Outside if run.is_some() => break,
            BlockClass::Outside => continue,
            BlockClass::Inside => (x0, x1, None),
            BlockClass::Partial => match run_in_row(at(x0), step_x, x0, x1, y, walk) {
                Some(p) => (p.first, p.last, Some(p.edges)),
                None if run.is_some() => break,
                None => continue,
            },
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::edge::FillRule;
    use crate::raster::fixed::FixedPoint;
    use crate::raster::fragment::{FragmentList, WorkCounters};
    use crate::raster::triangle::WalkStep;
    use proptest::prelude::*;

    /// What a walk of box `r` by `walk_box` emits, counts and records.
    fn walked(
        t: &TriangleSetup,
        r: PixelRect,
        walk_box: fn(&TriangleSetup, PixelRect, &mut Walk<Vec<WalkStep>>),
    ) -> (FragmentList, WorkCounters, Vec<WalkStep>) {
        let (mut list, mut work, mut steps) = Default::default();
        walk_box(t, r, &mut Walk::new(t, &mut list, &mut work, &mut steps));
        (list, work, steps)
    }

    proptest! {
        #![proptest_config(crate::test_support::proptest_config(3000, "tests/proptest-regressions/src-raster-triangle-tiled.txt"))]

        /// A box of at most 2x2 pixels tested sample by sample gives what
        /// the per-pixel loop gives: the same fragments with the same edge
        /// values, the same counts and the same recorded steps (the
        /// samples tested among them), under every rule.
        #[test]
        fn tiny_boxes_give_what_the_pixel_loop_gives(
            origin in (1i64..5, 1i64..5),
            // Within the box holding two pixel centres each way, and no more.
            v in proptest::array::uniform3((-128i64..640, -128i64..640)),
            rule in proptest::sample::select(FillRule::ALL.to_vec()),
        ) {
            let v = v.map(|(x, y)| FixedPoint::from_raw(x + origin.0 * 256, y + origin.1 * 256).unwrap());
            let Some(t) = TriangleSetup::new(7, v, rule) else { return Ok(()) };
            let r = t.bounds_within(PixelRect::of_target(16, 16));
            prop_assume!(!r.is_empty() && r.x1 - r.x0 <= 1 && r.y1 - r.y0 <= 1);
            let (tiny, tiny_work, tiny_steps) = walked(&t, r, tiny_box);
            let (looped, looped_work, looped_steps) = walked(&t, r, step_over);
            prop_assert_eq!(tiny.triangles, looped.triangles);
            prop_assert_eq!(tiny_work, looped_work);
            prop_assert_eq!(tiny_steps, looped_steps);
        }
    }

    proptest! {
        #![proptest_config(crate::test_support::proptest_config(256, "tests/proptest-regressions/src-raster-triangle-tiled.txt"))]

        /// The two-corner test says what testing every pixel says: a block
        /// is inside exactly when all its pixels are, and no pixel of an
        /// outside block is inside (a straddling block may still hold none:
        /// the test is conservative there).
        #[test]
        fn block_classes_agree_with_the_pixels(
            v in proptest::array::uniform3((-2000i64..6000, -2000i64..6000)),
            (x0, y0) in (-4i64..24, -4i64..24),
            (w, h) in (0i64..20, 0i64..20),
            rule in proptest::sample::select(FillRule::ALL.to_vec()),
        ) {
            let v = v.map(|(x, y)| FixedPoint::from_raw(x, y).unwrap());
            let Some(t) = TriangleSetup::new(0, v, rule) else { return Ok(()) };
            let r = PixelRect { x0, y0, x1: x0 + w, y1: y0 + h };
            let pixels: Vec<bool> = (y0..=r.y1)
                .flat_map(|y| (x0..=r.x1).map(move |x| (x, y)))
                .map(|(x, y)| t.inside(t.edge_values_at_pixel(x, y)))
                .collect();
            let class = classify_block(&t, r);
            prop_assert_eq!(class == BlockClass::Inside, pixels.iter().all(|&p| p));
            if class == BlockClass::Outside {
                prop_assert!(pixels.iter().all(|&p| !p));
            }
        }
    }
}

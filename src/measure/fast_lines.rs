//! The fast line path of the line workloads: Bresenham written straight
//! into the buffers, what the `side_by_side` benchmark sets the line
//! back-ends through the stage against. It is not a back-end: it has no
//! trace, no viewport and no other options.
//!
//! The [`bresenham`](crate::raster::line::bresenham) back-end builds each segment's pixel
//! list and hands every pixel to a [`FragmentSink`](crate::raster::fragment::FragmentSink):
//! clear for teaching and tracing, but a call and a viewport test per pixel.
//! [`draw_lines`] draws the very same pixels (the default
//! [`LineOptions`](crate::raster::line::LineOptions): 8-connected, both endpoints)
//! without that overhead:
//!
//! 1. **clip first**: the segment's frame columns are cut to those whose
//!    pixel lies on the target. The major axis gives a column range
//!    directly; the row of each column, `nearest_row(i)`, only grows with
//!    `i`, so the first and last columns whose row is on the target are
//!    found by binary search. The walk then starts at the first visible
//!    column with the decision variable it would have had there,
//!    `d = du (256 k + 128) - du v(i + 1)`, so no pixel is tested;
//! 2. **step a buffer index**: each column step moves the pixel's index in
//!    the colour buffer by one pixel along the major axis, and a row step by
//!    one along the minor axis too; no coordinates are converted and no
//!    pixel is tested.
//!
//! What is written is what the shared stage writes for a constant colour
//! with the depth test off (`always`, no depth write), through the same
//! merge step: the colour, and one more in the coverage count when the
//! target counts coverage. A test
//! checks both against the `bresenham` back-end through the stage, pixel
//! for pixel.

use crate::raster::edge::PixelRect;
use crate::raster::fixed::{HALF_PIXEL, SUBPIXEL_SCALE};
use crate::raster::line::{LineSetup, OctantFrame};
use crate::raster::stage::{merge_pixel, Blend, Source};
use crate::raster::target::RenderTarget;

/// Draws `lines` with Bresenham's pixels in `color`, clipped to `target`,
/// and returns the number of pixels written.
pub(crate) fn draw_lines(target: &mut RenderTarget, lines: &[LineSetup], color: [u8; 4]) -> u64 {
    let rect = PixelRect::of_target(target.width(), target.height());
    let mut written = 0;
    for line in lines {
        let frame = OctantFrame::new(line.from, line.to);
        let Some((first, last)) = visible_columns(&frame, rect) else {
            continue;
        };
        written += (last - first + 1) as u64;
        walk(target, &frame, first, last, color);
    }
    written
}

/// The frame columns `[first, last]` whose pixels lie in `rect`, the
/// target's pixels.
fn visible_columns(frame: &OctantFrame, rect: PixelRect) -> Option<(i64, i64)> {
    let ((lo, hi), (k_lo, k_hi)) = frame.ranges_within(rect);
    let (mut first, mut last) = (frame.i0.max(lo), frame.i1.min(hi));
    if first > last {
        return None;
    }
    // k grows with i.
    // The common case, found without a division: every column's row lies
    // on the target. Column centres are within half a pixel of the segment's
    // ends and the slope is at most 1, so the ideal line's v over the
    // columns stays within [v0 - 128, v1 + 128], and its nearest rows,
    // ceil((v - 128) / 256), within the bounds below.
    let (rows_from, rows_to) = (
        (frame.v0 - SUBPIXEL_SCALE).div_euclid(SUBPIXEL_SCALE),
        frame.v1.div_euclid(SUBPIXEL_SCALE) + 1,
    );
    if k_lo <= rows_from && rows_to <= k_hi {
        return Some((first, last));
    }
    // k grows with i: when both end columns are on the target, so is every
    // column between them.
    let on_target = |i: i64| (k_lo..=k_hi).contains(&frame.nearest_row(i));
    if on_target(first) && on_target(last) {
        return Some((first, last));
    }
    first = first_column_where(first, last + 1, |i| frame.nearest_row(i) >= k_lo);
    last = first_column_where(first, last + 1, |i| frame.nearest_row(i) > k_hi) - 1;
    (first <= last).then_some((first, last))
}

/// The first `i` in `[lo, hi)` where the monotone `pred` holds, or `hi`.
fn first_column_where(mut lo: i64, mut hi: i64, pred: impl Fn(i64) -> bool) -> i64 {
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if pred(mid) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    lo
}

/// `frame.nearest_row(first)` without its division when `first` is the
/// start's own column (a segment that starts on the target, the common
/// case), which matters when lines are short.
///
/// The start's column centre lies within half a pixel of the start along
/// the major axis and the slope is at most 1, so the ideal line's `v`
/// there is within 128 units of `v0`, and its nearest row,
/// `ceil((v - 128) / 256)`, is `k = ceil((v0 - 256) / 256)` or `k + 1`:
/// `k` when `256 k + 128 >= v`, an exact comparison once multiplied by
/// `du`.
#[inline]
fn first_row(frame: &OctantFrame, first: i64) -> i64 {
    let du = frame.du();
    if first != frame.i0 || du == 0 {
        return frame.nearest_row(first);
    }
    let k = -(SUBPIXEL_SCALE - frame.v0).div_euclid(SUBPIXEL_SCALE);
    if du * (SUBPIXEL_SCALE * k + HALF_PIXEL) >= frame.scaled_v_at(first) {
        k
    } else {
        k + 1
    }
}

/// The midpoint walk over columns `first..=last`, all on the target.
///
/// The pixel is tracked as a buffer index: a column step moves it by
/// `major` (one pixel along the major axis: 1 or the row length, signed by
/// the octant), a row step by `minor` as well. The choice between the two
/// is made with selects rather than a branch, since on a short or
/// steep-ish segment it is a coin toss the branch predictor loses.
fn walk(target: &mut RenderTarget, frame: &OctantFrame, first: i64, last: i64, color: [u8; 4]) {
    let width = target.width() as isize;
    // i64 is exact here, as in OctantFrame::scaled_v_at: |d| < 2^58.
    let s = SUBPIXEL_SCALE;
    let (du, dv) = (frame.du(), frame.dv());
    let k = first_row(frame, first);
    let mut d = du * (s * k + HALF_PIXEL) - frame.scaled_v_at(first + 1);
    let (up, flat) = (s * (du - dv), s * dv);
    let (along_major, along_minor) = if frame.swap { (width, 1) } else { (1, width) };
    let major = if frame.flip_major {
        -along_major
    } else {
        along_major
    };
    let minor = if frame.flip_minor {
        -along_minor
    } else {
        along_minor
    };
    let (x, y) = frame.to_screen(first, k);
    let mut at = y as isize * width + x as isize;
    let count = target.counts_coverage();
    let (colors, coverage) = (&mut target.color, &mut target.coverage);
    for _ in first..=last {
        merge_pixel(
            Blend::REPLACE,
            Source::Rgba8(color),
            &mut colors[at as usize],
            None,
        );
        if count {
            coverage[at as usize] = coverage[at as usize].saturating_add(1);
        }
        let step_up = d < 0;
        at += major + if step_up { minor } else { 0 };
        d += if step_up { up } else { -flat };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::fixed::FixedPoint;

    #[test]
    fn the_first_row_is_the_nearest_row_without_a_division() {
        let mut rng = fastrand::Rng::with_seed(3);
        let mut coordinate = |span: i64| rng.i64(-span..span);
        for n in 0..200_000 {
            let span = if n % 2 == 0 { 1 << 11 } else { 1 << 20 };
            let (a, b) = (
                FixedPoint::from_raw(coordinate(span), coordinate(span)).unwrap(),
                FixedPoint::from_raw(coordinate(span), coordinate(span)).unwrap(),
            );
            let frame = OctantFrame::new(a, b);
            assert_eq!(
                first_row(&frame, frame.i0),
                frame.nearest_row(frame.i0),
                "{a:?} {b:?}"
            );
        }
    }
}

//! `scanline`: the classic scanline algorithm, with exact integer span ends.
//!
//! The triangle is drawn as a series of horizontal spans, one per pixel row
//! (the software-rasterizer article calls this the historical approach):
//!
//! 1. sort the vertices by y: `top`, `mid`, `bottom`;
//! 2. the **long edge** runs from `top` to `bottom` and bounds every row;
//!    the two **short edges** `top-mid` and `mid-bottom` bound the rows
//!    above and below `mid` (both bound the row through `mid` itself);
//! 3. for each row whose sample line `Y = j + 0.5` lies between `top` and
//!    `bottom`, each active edge says where the row **enters** or
//!    **leaves** the triangle, and the pixels in between are filled.
//!
//! Textbook versions step a floating-point x along each edge and round it,
//! which is why they disagree with other rasterizers by a pixel here and
//! there. Here the crossing is solved exactly: on row `Y` the edge's test
//! `a X + b Y + c + bias >= 0` holds for pixel `i` (sample `X = 256 i + 128`)
//! exactly when
//!
//! ```text
//! a > 0:  i >= ceil ( -(a*128 + b*Y + c + bias) / (256 a) )   (a left edge: the span starts)
//! a < 0:  i <= floor(  (a*128 + b*Y + c + bias) / (256 |a|) ) (a right edge: the span ends)
//! a = 0:  every i, or none (a horizontal edge)
//! ```
//!
//! with integer floor and ceiling, so the spans agree with the per-pixel
//! test of the other back-ends to the pixel, fill rule included. No pixel
//! is tested: the work is one solve per active edge per row, and each
//! row's pixels go to the fragment stage as one span.

use super::{Bound, TriangleAlgorithm, TriangleDescriptor, TriangleWalk, Walk, WalkObserver};
use crate::raster::descriptor::{CostClass, Role};
use crate::raster::edge::{EdgeFunction, PixelRect, TriangleSetup};
use crate::raster::fixed::{
    first_sample_at_or_after, last_sample_at_or_before, HALF_PIXEL, SUBPIXEL_SCALE,
};

/// Classic scanline with exact span ends.
#[derive(Copy, Clone, Debug, Default)]
pub struct Scanline;

/// The pixel range `[first, last]` of one row, narrowed edge by edge.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) struct Span {
    /// First pixel column inside.
    pub first: i64,
    /// Last pixel column inside (empty when `last < first`).
    pub last: i64,
}

impl Span {
    /// Narrows the span to the pixels of row sample `y` (fixed units) that
    /// pass edge `e` with tie bias `bias`, and says what the edge alone
    /// bounds.
    pub fn clip_to_edge(&mut self, e: &EdgeFunction, bias: i64, y: i64) -> Bound {
        // Value of E + bias at the sample of pixel i is a*256*i + r.
        let r = e.a * HALF_PIXEL + e.b * y + e.c + bias;
        let step = e.a * SUBPIXEL_SCALE;
        if step > 0 {
            // i >= ceil(-r / step)
            let first = -(r.div_euclid(step));
            self.first = self.first.max(first);
            Bound::First(first)
        } else if step < 0 {
            // i <= floor(r / -step)
            let last = r.div_euclid(-step);
            self.last = self.last.min(last);
            Bound::Last(last)
        } else if r < 0 {
            self.last = self.first - 1;
            Bound::None
        } else {
            Bound::All
        }
    }

    /// True when no pixel is left.
    pub fn is_empty(&self) -> bool {
        self.last < self.first
    }
}

/// The vertex indices of a triangle sorted by (y, x): top, mid, bottom.
///
/// Three compare-and-swaps (a sorting network), each swapping only on a
/// strict `<`, so equal keys keep their order as a stable sort keeps them.
pub(crate) fn sorted_by_y(t: &TriangleSetup) -> [usize; 3] {
    let key = |i: usize| (t.vertices[i].y, t.vertices[i].x);
    let mut order = [0, 1, 2];
    for (a, b) in [(0, 1), (1, 2), (0, 1)] {
        if key(order[b]) < key(order[a]) {
            order.swap(a, b);
        }
    }
    order
}

/// The edges bounding row sample `y`, as indices into `t.edges`
/// (edge `k` is opposite vertex `k`): the long edge, and the short edge(s)
/// spanning `y`.
pub(crate) fn active_edges(
    t: &TriangleSetup,
    order: [usize; 3],
    y: i64,
) -> impl Iterator<Item = usize> {
    let [top, mid, bottom] = order;
    let y_mid = t.vertices[mid].y.raw();
    [
        Some(mid),                      // long edge top-bottom, opposite `mid`
        (y <= y_mid).then_some(bottom), // short edge top-mid, opposite `bottom`
        (y >= y_mid).then_some(top),    // short edge mid-bottom, opposite `top`
    ]
    .into_iter()
    .flatten()
}

/// The span of row `j` (clipped to `viewport` columns), each active
/// edge's bound and the span reported to the walk.
#[inline]
pub(crate) fn row_span<O: WalkObserver>(
    t: &TriangleSetup,
    order: [usize; 3],
    j: i64,
    viewport: PixelRect,
    walk: &mut Walk<O>,
) -> Span {
    let y = j * SUBPIXEL_SCALE + HALF_PIXEL;
    let mut span = Span {
        first: viewport.x0,
        last: viewport.x1,
    };
    for k in active_edges(t, order, y) {
        let bound = span.clip_to_edge(&t.edges[k], t.bias[k], y);
        walk.crossing(j, k, bound);
    }
    walk.row_span(j, span.first, span.last);
    span
}

/// The rows of `viewport` whose sample line lies within the triangle's
/// vertical extent.
pub(crate) fn row_range(t: &TriangleSetup, order: [usize; 3], viewport: PixelRect) -> (i64, i64) {
    let y_top = t.vertices[order[0]].y.raw();
    let y_bottom = t.vertices[order[2]].y.raw();
    (
        first_sample_at_or_after(y_top).max(viewport.y0),
        last_sample_at_or_before(y_bottom).min(viewport.y1),
    )
}

impl TriangleAlgorithm for Scanline {
    const DESCRIPTOR: TriangleDescriptor = TriangleDescriptor {
        name: "scanline",
        description: "classic scanline: sort vertices by y, walk the edges row by row, fill exact integer spans",
        walk: TriangleWalk::Scanline,
        role: Role::Default,
        cost: CostClass::FollowsSize,
    };

    #[inline]
    fn draw_triangle<O: WalkObserver>(
        &self,
        t: &TriangleSetup,
        viewport: PixelRect,
        walk: &mut Walk<O>,
    ) {
        let order = sorted_by_y(t);
        let (first_row, last_row) = row_range(t, order, viewport);
        for j in first_row..=last_row {
            walk.visit();
            let span = row_span(t, order, j, viewport, walk);
            if span.is_empty() {
                continue;
            }
            let e = t.edge_values_at_pixel(span.first, j);
            debug_assert!(
                t.inside(e),
                "span start ({}, {j}) fails the inside test",
                span.first
            );
            walk.span(j, span.first, span.last, e);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::edge::FillRule;
    use crate::raster::fixed::FixedPoint;

    #[test]
    fn the_sorting_network_sorts_as_a_stable_sort() {
        let coords = [0, 256, 512];
        for a in 0..9 {
            for b in 0..9 {
                for c in 0..9 {
                    let p = |k: usize| FixedPoint::from_raw(coords[k % 3], coords[k / 3]).unwrap();
                    let Some(t) = TriangleSetup::new(0, [p(a), p(b), p(c)], FillRule::TopLeft)
                    else {
                        continue;
                    };
                    let mut stable = [0, 1, 2];
                    stable.sort_by_key(|&i| (t.vertices[i].y, t.vertices[i].x));
                    assert_eq!(sorted_by_y(&t), stable, "{:?}", t.vertices);
                }
            }
        }
    }
}

//! A compact inside test for small triangles: the three edge functions in
//! 32-bit integers, relative to the corner of the triangle's bounding box.
//!
//! The exact set-up ([`TriangleSetup`](crate::raster::edge::TriangleSetup))
//! evaluates the course's implicit line equation on snapped coordinates in
//! `i64`: anywhere in the guard band a coordinate needs 24 bits and an edge
//! value about 50. A small triangle needs far fewer. Rewritten around a
//! point `O` (the corner of the box),
//!
//! ```text
//! line(A, B, P) = a * (P.x - O.x) + b * (P.y - O.y) + line(A, B, O)
//! ```
//!
//! and for a sample `P` inside the box of the three vertices its value is
//! twice the signed area of the triangle `(A, B, P)`, whose three corners
//! all lie in the box. A triangle inside a rectangle covers at most half
//! of it, so `|line(A, B, P)|` is at most the box's area, `s^2` for a box
//! at most `s` units on a side. With `s` at most [`MAX_SPAN`] (46,340
//! units, 181 pixels) that is at most 2,147,395,600, inside `i32`
//! (2,147,483,647); one unit more and it is not. The terms on the way
//! may not fit, so they are computed wrapping: arithmetic modulo 2^32
//! gives the exact value whenever the exact value fits, which the bound
//! proves (`tests::the_bound_is_exact` evaluates a triangle at the bound,
//! where its largest value is 2,147,395,600).
//!
//! A production rasterizer sets up the triangles inside one tile so, with
//! narrower integers that a vector unit holds twice as many of. Here the
//! pipeline uses it to drop, before any set-up is stored, the triangles
//! whose bounding box holds a few pixel centres none of which is inside
//! (on a dense mesh most triangles cover zero or one pixel centre):
//! [`SmallTriangle::may_cover_a_sample`].
//!
//! ```
//! use rasterlab::raster::{FixedPoint, SmallTriangle, TriangleSetup};
//!
//! let p = |x, y| FixedPoint::snap(x, y).unwrap();
//! // Around the centre of pixel (2, 1), and a sliver that passes between
//! // the centres of its 2x2 box.
//! let around = [p(2.2, 1.2), p(2.9, 1.5), p(2.4, 1.9)];
//! let sliver = [p(2.1, 1.0), p(4.0, 2.9), p(4.0, 2.8)];
//! let covers = |v| {
//!     let samples = TriangleSetup::sample_bounds(v);
//!     SmallTriangle::new(v).unwrap().may_cover_a_sample(samples)
//! };
//! assert!(covers(around));
//! assert!(!covers(sliver));
//! // Too large for 32 bits: the exact set-up's 64-bit path takes it.
//! assert!(SmallTriangle::new([p(0.0, 0.0), p(200.0, 0.0), p(0.0, 5.0)]).is_none());
//! ```

use crate::raster::edge::PixelRect;
use crate::raster::fixed::{FixedPoint, HALF_PIXEL, SUBPIXEL_SCALE};

/// The widest and tallest bounding box, in fixed-point units (1/256
/// pixel), whose edge values fit in `i32`: `MAX_SPAN^2 <= i32::MAX <
/// (MAX_SPAN + 1)^2`.
pub const MAX_SPAN: i64 = 46_340;

/// A triangle's edge functions in 32 bits, relative to a point of its
/// bounding box, inside-positive (see the module docs).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct SmallTriangle {
    /// The point `O` the values are relative to, in fixed-point units.
    origin: (i64, i64),
    /// Per edge (opposite vertex `i`, as in the exact set-up): `a`, `b`
    /// and the value at `O`.
    edges: [(i32, i32, i32); 3],
}

impl SmallTriangle {
    /// The triangle's edge functions in 32 bits, relative to the top-left
    /// corner of its bounding box and oriented so that its inside is
    /// positive; `None` when the box is wider or taller than [`MAX_SPAN`].
    /// (A triangle of zero area is zero on its line and negative nowhere:
    /// the pipeline drops those before.)
    pub fn new(vertices: [FixedPoint; 3]) -> Option<SmallTriangle> {
        let xs = vertices.map(|v| v.x.raw());
        let ys = vertices.map(|v| v.y.raw());
        let corner = (xs[0].min(xs[1]).min(xs[2]), ys[0].min(ys[1]).min(ys[2]));
        let area = crate::raster::edge::TriangleSetup::signed_area(vertices);
        Self::around(vertices, corner, area)
    }

    /// [`new`](Self::new) relative to the point `origin` (fixed-point
    /// units), which must lie in the triangle's bounding box, for a
    /// triangle whose twice signed area is `signed_area` (known from
    /// culling): the values at `origin`, worked out from the vertices, are
    /// then the only products, and the next samples are additions away.
    #[inline(always)]
    pub(crate) fn around(
        vertices: [FixedPoint; 3],
        origin: (i64, i64),
        signed_area: i64,
    ) -> Option<SmallTriangle> {
        let x = vertices.map(|v| v.x.raw());
        let y = vertices.map(|v| v.y.raw());
        // The coefficients are the differences between the vertices' own
        // coordinates: within the span exactly when the box is.
        let a = [y[2] - y[1], y[0] - y[2], y[1] - y[0]];
        let b = [x[1] - x[2], x[2] - x[0], x[0] - x[1]];
        let widest = a.iter().chain(&b).map(|d| d.abs()).max().unwrap_or(0);
        if widest > MAX_SPAN {
            return None;
        }
        debug_assert!(x.iter().any(|&v| v <= origin.0) && x.iter().any(|&v| v >= origin.0));
        debug_assert!(y.iter().any(|&v| v <= origin.1) && y.iter().any(|&v| v >= origin.1));
        let sign = if signed_area < 0 { -1 } else { 1 };
        // Edge k runs from vertex k + 1 to vertex k + 2: its value at O is
        // a (O.x - from.x) + b (O.y - from.y), twice the area of a
        // triangle in the box (the bound holds).
        let edge = |k: usize| {
            let from = (k + 1) % 3;
            let (ak, bk) = (sign * a[k] as i32, sign * b[k] as i32);
            let (dx, dy) = ((origin.0 - x[from]) as i32, (origin.1 - y[from]) as i32);
            (
                ak,
                bk,
                ak.wrapping_mul(dx).wrapping_add(bk.wrapping_mul(dy)),
            )
        };
        Some(SmallTriangle {
            origin,
            edges: [edge(0), edge(1), edge(2)],
        })
    }

    /// The three inside-positive edge values at fixed-point point `(x, y)`,
    /// which must lie in the triangle's bounding box (else the values may
    /// not fit in 32 bits).
    #[inline(always)]
    pub fn edge_values_at(&self, x: i64, y: i64) -> [i32; 3] {
        let (dx, dy) = ((x - self.origin.0) as i32, (y - self.origin.1) as i32);
        self.edges.map(|(a, b, c)| {
            a.wrapping_mul(dx)
                .wrapping_add(b.wrapping_mul(dy))
                .wrapping_add(c)
        })
    }

    /// Can a pixel of `pixels` (at most 2x2 pixels, whose sample points
    /// lie in the triangle's bounding box) be inside? False only when every
    /// sample is strictly outside one edge; a sample exactly on an edge
    /// counts as possibly inside, since only the fill rule decides it, at
    /// set-up. So a triangle this says no to has no fragment under any
    /// fill rule. The first sample's values are evaluated, the others
    /// stepped from them by additions.
    #[inline(always)]
    pub fn may_cover_a_sample(&self, pixels: PixelRect) -> bool {
        debug_assert!(pixels.x1 - pixels.x0 <= 1 && pixels.y1 - pixels.y0 <= 1);
        let (x, y) = Self::first_sample_of(pixels);
        let first = self.edge_values_at(x, y);
        let step = SUBPIXEL_SCALE as i32;
        let right = self.edges.map(|e| e.0.wrapping_mul(step));
        let down = self.edges.map(|e| e.1.wrapping_mul(step));
        let plus = |e: [i32; 3], d: [i32; 3]| {
            [
                e[0].wrapping_add(d[0]),
                e[1].wrapping_add(d[1]),
                e[2].wrapping_add(d[2]),
            ]
        };
        let inside = |e: [i32; 3]| e[0] | e[1] | e[2] >= 0;
        let (wide, tall) = (pixels.x1 > pixels.x0, pixels.y1 > pixels.y0);
        let (next, below) = (plus(first, right), plus(first, down));
        inside(first)
            || (wide && inside(next))
            || (tall && inside(below))
            || (wide && tall && inside(plus(next, down)))
    }

    /// The sample point of the first pixel of `pixels`, in fixed-point
    /// units: the origin the pipeline sets a triangle up around, so that
    /// [`may_cover_a_sample`](Self::may_cover_a_sample) starts from the
    /// values at the origin, with no product.
    #[inline(always)]
    pub fn first_sample_of(pixels: PixelRect) -> (i64, i64) {
        (
            pixels.x0 * SUBPIXEL_SCALE + HALF_PIXEL,
            pixels.y0 * SUBPIXEL_SCALE + HALF_PIXEL,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::edge::{FillRule, TriangleSetup};
    use proptest::prelude::*;

    fn point(x: i64, y: i64) -> FixedPoint {
        FixedPoint::from_raw(x, y).unwrap()
    }

    /// The 32-bit values against the exact 64-bit set-up's, at the points
    /// given.
    fn agree(v: [FixedPoint; 3], points: &[(i64, i64)]) {
        let small = SmallTriangle::new(v).unwrap();
        let exact = TriangleSetup::new(0, v, FillRule::TopLeft).unwrap();
        for &(x, y) in points {
            let wide = exact.edge_values(point(x, y));
            assert_eq!(
                small.edge_values_at(x, y).map(i64::from),
                wide,
                "{v:?} at {x}, {y}"
            );
        }
    }

    /// At the bound: a box exactly MAX_SPAN on a side, each triangle of
    /// three of its corners, in both windings, evaluated at the four
    /// corners: the largest value an edge function can reach in the box
    /// (MAX_SPAN^2, a corner opposite a diagonal edge) is among them, and
    /// the terms on the way overflow 32 bits. One unit more could not fit,
    /// and is refused.
    #[test]
    fn the_bound_is_exact() {
        let s = MAX_SPAN;
        let (x0, y0) = (-16_000, 5_000);
        let corners = [(x0, y0), (x0 + s, y0), (x0 + s, y0 + s), (x0, y0 + s)];
        let mut largest = 0;
        for skip in 0..4 {
            let c: Vec<(i64, i64)> = (0..4).filter(|&k| k != skip).map(|k| corners[k]).collect();
            for t in [[c[0], c[1], c[2]], [c[0], c[2], c[1]]] {
                let v = t.map(|(x, y)| point(x, y));
                agree(v, &corners);
                let exact = TriangleSetup::new(0, v, FillRule::TopLeft).unwrap();
                for (x, y) in corners {
                    for e in exact.edge_values(point(x, y)) {
                        largest = largest.max(e.abs());
                    }
                }
            }
        }
        assert_eq!(largest, s * s);
        assert!(s * s <= i64::from(i32::MAX));
        assert!((s + 1) * (s + 1) > i64::from(i32::MAX));
        let wider = [point(x0, y0), point(x0 + s + 1, y0), point(x0, y0 + 1)];
        assert!(SmallTriangle::new(wider).is_none());
        let taller = [point(x0, y0), point(x0 + 1, y0), point(x0, y0 + s + 1)];
        assert!(SmallTriangle::new(taller).is_none());
    }

    proptest! {
        // A third of the small triangles drawn have no pixel centre in
        // their box, and are drawn again.
        #![proptest_config(ProptestConfig {
            max_global_rejects: 20_000,
            ..crate::test_support::proptest_config(2000, "tests/proptest-regressions/src-raster-compact.txt")
        })]

        /// Any triangle within the span, anywhere in the guard band: the
        /// same edge values as the exact set-up at every point of its box
        /// tried, whichever point of the box they are relative to.
        #[test]
        fn agrees_with_the_exact_setup(
            origin in (-8_000_000i64..8_000_000, -8_000_000i64..8_000_000),
            span in 1i64..=MAX_SPAN,
            v in proptest::array::uniform3((0.0f64..=1.0, 0.0f64..=1.0)),
            at in proptest::collection::vec((0.0f64..=1.0, 0.0f64..=1.0), 8),
            rule in proptest::sample::select(FillRule::ALL.to_vec()),
        ) {
            let v = v.map(|(x, y)| point(origin.0 + (x * span as f64) as i64, origin.1 + (y * span as f64) as i64));
            let Some(exact) = TriangleSetup::new(0, v, rule) else { return Ok(()) };
            let small = SmallTriangle::new(v).unwrap();
            let (x0, y0) = (v.iter().map(|p| p.x.raw()).min().unwrap(), v.iter().map(|p| p.y.raw()).min().unwrap());
            let (x1, y1) = (v.iter().map(|p| p.x.raw()).max().unwrap(), v.iter().map(|p| p.y.raw()).max().unwrap());
            for (fx, fy) in at {
                let (x, y) = (x0 + (fx * (x1 - x0) as f64) as i64, y0 + (fy * (y1 - y0) as f64) as i64);
                prop_assert_eq!(small.edge_values_at(x, y).map(i64::from), exact.edge_values(point(x, y)));
            }
            let around = SmallTriangle::around(v, (x0, y0), exact.winding.into()).unwrap();
            prop_assert_eq!(around.edge_values_at(x1, y1), small.edge_values_at(x1, y1));
        }

        /// On triangles whose box holds at most 2x2 pixel centres, the
        /// sample test never says no to a triangle the exact test finds a
        /// fragment of, under any rule, and says no to every one without a
        /// sample inside or on an edge.
        #[test]
        fn the_sample_test_is_exact_on_small_boxes(
            origin in (-2_000_000i64..2_000_000, -2_000_000i64..2_000_000),
            v in proptest::array::uniform3((0i64..767, 0i64..767)),
            rule in proptest::sample::select(FillRule::ALL.to_vec()),
        ) {
            let v = v.map(|(x, y)| point(origin.0 + x, origin.1 + y));
            let Some(exact) = TriangleSetup::new(0, v, rule) else { return Ok(()) };
            let samples = exact.bounds;
            prop_assume!(!samples.is_empty() && samples.x1 - samples.x0 <= 1 && samples.y1 - samples.y0 <= 1);
            let corner = SmallTriangle::first_sample_of(samples);
            let small = SmallTriangle::around(v, corner, exact.winding.into()).unwrap();
            let centres: Vec<FixedPoint> = (samples.y0..=samples.y1)
                .flat_map(|j| (samples.x0..=samples.x1).map(move |i| FixedPoint::pixel_centre(i as i32, j as i32)))
                .collect();
            let covered = centres.iter().any(|&c| exact.covers(c));
            let on_or_in = centres.iter().any(|&c| exact.edge_values(c).iter().all(|&e| e >= 0));
            prop_assert_eq!(small.may_cover_a_sample(samples), on_or_in);
            if covered {
                prop_assert!(small.may_cover_a_sample(samples));
            }
        }
    }
}

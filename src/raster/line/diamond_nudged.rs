//! `diamond-nudged`: the diamond-exit rule with CMU Scotty3D's tie-break,
//! the line convention of its assignment A1 (task 2, `rasterize_line`).
//!
//! A pixel is drawn when the segment, travelling from start to end,
//! leaves the pixel's diamond `|x - xc| + |y - yc| < 1/2` (as in
//! [`diamond`](super::diamond)). Where the segment only touches a
//! diamond (along one of its sides, through a corner, or ending on its
//! boundary), Scotty3D settles it by drawing the line *as if both
//! endpoints were moved by `(e, e^2)`*, in its window coordinates with y
//! up, where no smaller `e > 0` gives a different answer. In rasterlab's
//! screen coordinates, y down, the move is `(e, -e^2)`.
//!
//! The move is done symbolically, not with a small number: every
//! coordinate is a polynomial `a + b e + c e^2 + ...` in an infinitesimal
//! `e > 0`, and two of them compare by their first
//! different coefficient, which is how they compare for every small
//! enough `e`. The moved segment touches no diamond's boundary (its
//! direction is a whole vector, so it cannot run along a side moved off
//! by `e - e^2` or `e + e^2`, nor through a corner moved off by `e` or
//! `e^2`), so the open and the closed diamonds give the same answer and
//! no corner needs to be owned. A segment away from every diamond's
//! boundary is drawn as by `diamond`.
//!
//! The tests check Scotty3D's own test cases (its `tests/a1/test.a1.task2.cpp`),
//! and that the symbolic move gives the answer of a concrete move by
//! `(2^-20, -2^-40)` pixels on a grid where that move is small enough.

use super::diamond::{clip_slab, default_options_only, draw_by, walk_candidates, Bound, Exact};
use super::{LineDescriptor, LineOptions, LineRasterizer, LineSetup, LineWalk};
use crate::error::Result;
use crate::raster::descriptor::{CostClass, Role};
use crate::raster::edge::PixelRect;
use crate::raster::fixed::{FixedPoint, HALF_PIXEL, SUBPIXEL_SCALE};
use crate::raster::fragment::{FragmentSink, WorkCounters};
use std::ops::{Add, Mul, Neg, Sub};

/// The diamond-exit rule with the `(e, e^2)` tie-break.
#[derive(Copy, Clone, Debug, Default)]
pub struct DiamondNudged;

/// Degree of the polynomials kept: products of two coordinates that each
/// carry `e` and `e^2` reach `e^4`.
const TERMS: usize = 5;

/// A number `c[0] + c[1] e + c[2] e^2 + ...` with `e` an infinitesimal
/// above zero, in fixed-point units. Ordered by its first different
/// coefficient (the array's own order), which is the order for every
/// small enough `e`.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Nudged([i128; TERMS]);

impl Nudged {
    /// `value + de e + de2 e^2`.
    fn new(value: i64, de: i64, de2: i64) -> Nudged {
        let mut c = [0; TERMS];
        c[0] = i128::from(value);
        c[1] = i128::from(de);
        c[2] = i128::from(de2);
        Nudged(c)
    }
}

impl From<i64> for Nudged {
    fn from(value: i64) -> Nudged {
        Nudged::new(value, 0, 0)
    }
}

impl Add for Nudged {
    type Output = Nudged;
    fn add(self, other: Nudged) -> Nudged {
        Nudged(std::array::from_fn(|i| self.0[i] + other.0[i]))
    }
}

impl Sub for Nudged {
    type Output = Nudged;
    fn sub(self, other: Nudged) -> Nudged {
        Nudged(std::array::from_fn(|i| self.0[i] - other.0[i]))
    }
}

impl Neg for Nudged {
    type Output = Nudged;
    fn neg(self) -> Nudged {
        Nudged(self.0.map(|c| -c))
    }
}

impl Mul for Nudged {
    type Output = Nudged;
    /// The product, exact: the test multiplies a coordinate difference
    /// (up to `e^2`) by a whole number or by another difference, so no
    /// term past `e^4` arises.
    fn mul(self, other: Nudged) -> Nudged {
        let mut c = [0; TERMS];
        for (i, a) in self.0.iter().enumerate() {
            for (j, b) in other.0.iter().enumerate().take(TERMS - i) {
                c[i + j] += a * b;
            }
        }
        Nudged(c)
    }
}

impl Exact for Nudged {
    fn abs(self) -> Nudged {
        if self < Nudged::from(0) {
            -self
        } else {
            self
        }
    }
    fn signum(self) -> Nudged {
        Nudged::from(match self.cmp(&Nudged::from(0)) {
            std::cmp::Ordering::Less => -1,
            std::cmp::Ordering::Equal => 0,
            std::cmp::Ordering::Greater => 1,
        })
    }
}

/// A snapped point moved by `(e, -e^2)` (Scotty3D's `(e, e^2)` with y up).
fn nudged(p: FixedPoint) -> (Nudged, Nudged) {
    (Nudged::new(p.x.raw(), 1, 0), Nudged::new(p.y.raw(), 0, -1))
}

/// The diamond-exit test with the `(e, e^2)` tie-break: does the segment
/// `from -> to`, both ends moved, leave the diamond of pixel `(px, py)`?
pub fn exits_nudged_diamond(from: FixedPoint, to: FixedPoint, px: i64, py: i64) -> bool {
    let (ax, ay) = nudged(from);
    let (bx, by) = nudged(to);
    leaves_diamond(
        (ax, ay),
        (bx, by),
        (
            Nudged::from(px * SUBPIXEL_SCALE + HALF_PIXEL),
            Nudged::from(py * SUBPIXEL_SCALE + HALF_PIXEL),
        ),
        Nudged::from(HALF_PIXEL),
    )
}

/// Does the segment `a -> b` leave the open diamond of centre `c` and
/// half-diagonal `h`: pass through it, and not end inside it?
fn leaves_diamond<T: Exact>(a: (T, T), b: (T, T), c: (T, T), h: T) -> bool {
    if (b.0 - c.0).abs() + (b.1 - c.1).abs() < h {
        return false;
    }
    let (mut lower, mut upper) = Bound::whole_segment();
    // s = x + y within (cx + cy - h, cx + cy + h); d = x - y likewise.
    clip_slab(
        a.0 + a.1,
        (b.0 + b.1) - (a.0 + a.1),
        c.0 + c.1 - h,
        c.0 + c.1 + h,
        &mut lower,
        &mut upper,
    ) && clip_slab(
        a.0 - a.1,
        (b.0 - b.1) - (a.0 - a.1),
        c.0 - c.1 - h,
        c.0 - c.1 + h,
        &mut lower,
        &mut upper,
    ) && lower.below(&upper)
}

impl DiamondNudged {
    /// The walk of one segment, as [`Diamond::walk`](super::diamond::Diamond::walk)
    /// with this rule's test.
    pub fn walk(line: &LineSetup, observe: impl FnMut(i64, i64, bool)) -> Vec<(i64, i64)> {
        let mut pixels = Vec::new();
        walk_candidates(line, exits_nudged_diamond, observe, &mut pixels);
        pixels
    }
}

impl LineRasterizer for DiamondNudged {
    fn descriptor(&self) -> LineDescriptor {
        LineDescriptor {
            name: "diamond-nudged",
            description: "diamond-exit rule, ties settled by moving both ends by (e, e^2) with y up (Scotty3D A1)",
            walk: LineWalk::DiamondExitNudged,
            role: Role::Alternative,
            cost: CostClass::FollowsSize,
        }
    }

    fn check_options(&self, options: &LineOptions) -> Result<()> {
        default_options_only("diamond-nudged", options)
    }

    fn rasterize(
        &self,
        lines: &[LineSetup],
        _options: &LineOptions,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> WorkCounters {
        draw_by(exits_nudged_diamond, lines, viewport, sink)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::line::diamond::exits_diamond;
    use proptest::prelude::*;

    /// The picture of a segment given in Scotty3D's window coordinates
    /// (y up), as Scotty3D's tests draw one: `rows` rows of `columns`
    /// pixels, the top row first, `#` drawn, with the lower-left pixel
    /// (0, 0).
    fn drawn_y_up(from: (f64, f64), to: (f64, f64), [columns, rows]: [usize; 2]) -> Vec<String> {
        // y up to y down: y' = rows - y, so row j (y up) is row rows-1-j.
        let p = |(x, y): (f64, f64)| FixedPoint::snap_f64(x, rows as f64 - y).unwrap();
        let line = LineSetup {
            id: 0,
            from: p(from),
            to: p(to),
        };
        let pixels = DiamondNudged::walk(&line, |_, _, _| {});
        (0..rows as i64)
            .map(|y| {
                (0..columns as i64)
                    .map(|x| if pixels.contains(&(x, y)) { '#' } else { '.' })
                    .collect()
            })
            .collect()
    }

    /// Scotty3D A1's line tests (`tests/a1/test.a1.task2.cpp`), each with
    /// its expected picture: a line inside a diamond and one outside it
    /// draw nothing; the horizontal and vertical lines draw four pixels.
    #[test]
    fn scotty3d_task2_cases() {
        assert_eq!(
            drawn_y_up((1.5, 1.25), (1.25, 1.5), [3, 3]),
            ["...", "...", "..."]
        );
        assert_eq!(
            drawn_y_up((1.125, 1.25), (1.25, 1.125), [3, 3]),
            ["...", "...", "..."]
        );
        assert_eq!(
            drawn_y_up((1.125, 1.125), (4.875, 1.125), [6, 3]),
            ["......", ".####.", "......"]
        );
        assert_eq!(
            drawn_y_up((1.125, 1.125), (1.125, 4.875), [3, 6]),
            ["...", ".#.", ".#.", ".#.", ".#.", "..."]
        );
    }

    /// Lines Scotty3D's notes single out, worked by hand (y up, as in
    /// Scotty3D).
    #[test]
    fn ties_settled_by_the_move() {
        // A 45-degree line from pixel centre (0.5, 0.5) to (3.5, 3.5),
        // which the notes expect to be handled: it leaves diamonds (0,0),
        // (1,1) and (2,2) through their upper-right sides, and ends inside
        // (3,3).
        assert_eq!(
            drawn_y_up((0.5, 0.5), (3.5, 3.5), [4, 4]),
            ["....", "..#.", ".#..", "#..."]
        );
        // A horizontal line along the row boundary y = 1, from x = 0.5 to
        // 3.5, runs through the corners shared by rows 0 and 1. Moved up by
        // e^2 it crosses row 1's diamonds near their bottom corners, and
        // misses row 0's. Moved right by e, it starts just right of
        // (0,1)'s bottom corner, outside that diamond, and ends just
        // right of (3,1)'s, outside too: (1,1), (2,1) and (3,1) are drawn.
        // (The notes' other sentence, that a diamond contains its bottom
        // corner, would draw (0,1) and not (3,1) instead: the move, which
        // the notes call the rule in general, contains the left corners
        // only.)
        assert_eq!(drawn_y_up((0.5, 1.0), (3.5, 1.0), [4, 2]), [".###", "...."]);
        // A vertical line along the column boundary x = 1, moved right by
        // e: column 1's diamonds, the last one holding the end.
        assert_eq!(
            drawn_y_up((1.0, 0.5), (1.0, 2.5), [3, 3]),
            ["...", ".#.", ".#."]
        );
    }

    /// An example of the symbolic numbers' order: `e` is above every
    /// multiple of `e^2` and below every positive whole number.
    #[test]
    fn nudged_numbers_order_as_for_a_small_e() {
        let e = Nudged::new(0, 1, 0);
        let e2 = Nudged::new(0, 0, 1);
        assert!(e > e2 * Nudged::from(1_000_000));
        assert!(e < Nudged::from(1));
        assert!(e * e == e2);
        assert!(Nudged::from(-3).abs() == Nudged::from(3));
        assert!((-e).signum() == Nudged::from(-1));
    }

    proptest! {
        #![proptest_config(crate::test_support::proptest_config(2000, "tests/proptest-regressions/src-raster-line-diamond-nudged.txt"))]

        /// The symbolic move gives the answer of a concrete move by
        /// `(2^-20, -2^-40)` pixels' worth of fixed-point units, on ends
        /// on a grid of 1/4 px within 8 px, where every quantity of the
        /// test is a multiple of 64 units, so that the concrete move is
        /// small enough: computed with every coordinate multiplied by
        /// 2^40, the move is `(2^20, -1)`.
        #[test]
        fn the_symbolic_move_is_a_small_concrete_move(
            ends in proptest::array::uniform4(-32i64..32),
            px in -9i64..9,
            py in -9i64..9,
        ) {
            let raw = ends.map(|v| v * 64);
            let p = |x, y| FixedPoint::from_raw(x, y).unwrap();
            let (from, to) = (p(raw[0], raw[1]), p(raw[2], raw[3]));
            const SCALE: i128 = 1 << 40;
            let moved = |x: i64, y: i64| (i128::from(x) * SCALE + (1 << 20), i128::from(y) * SCALE - 1);
            let centre = |i: i64| i128::from(i * SUBPIXEL_SCALE + HALF_PIXEL) * SCALE;
            let concrete = leaves_diamond(
                moved(raw[0], raw[1]),
                moved(raw[2], raw[3]),
                (centre(px), centre(py)),
                i128::from(HALF_PIXEL) * SCALE,
            );
            prop_assert_eq!(exits_nudged_diamond(from, to, px, py), concrete);
        }

        /// Away from the diamonds' boundaries the move changes nothing:
        /// a segment that touches no side or corner of a pixel's diamond
        /// decides the pixel as `diamond` does.
        #[test]
        fn without_ties_it_is_the_diamond_rule(
            ends in proptest::array::uniform4(-2000i64..2000),
            px in -10i64..10,
            py in -10i64..10,
        ) {
            // Odd x and even y at every end keep the ends off every
            // diamond's boundary, where |x - cx| + |y - cy| = 128.
            let raw = [2 * ends[0] + 1, 2 * ends[1], 2 * ends[2] + 1, 2 * ends[3]];
            let p = |x, y| FixedPoint::from_raw(x, y).unwrap();
            let (from, to) = (p(raw[0], raw[1]), p(raw[2], raw[3]));
            let (dx, dy) = (raw[2] - raw[0], raw[3] - raw[1]);
            // Nor may the line run along a side (dx = +-dy), or through
            // one of the pixel's corners.
            prop_assume!(dx != dy && dx != -dy);
            let (cx, cy) = (px * SUBPIXEL_SCALE + HALF_PIXEL, py * SUBPIXEL_SCALE + HALF_PIXEL);
            let through_corner = [(0, 1), (1, 0), (0, -1), (-1, 0)].iter().any(|(u, v)| {
                dx * (cy + v * HALF_PIXEL - raw[1]) == dy * (cx + u * HALF_PIXEL - raw[0])
            });
            prop_assume!(!through_corner);
            prop_assert_eq!(exits_nudged_diamond(from, to, px, py), exits_diamond(from, to, px, py));
        }
    }
}

//! `diamond`: the Direct3D / Vulkan diamond-exit rule, the reference for
//! aliased lines (the rules in docs/check.md).
//!
//! Each pixel owns the open diamond `|x - xc| + |y - yc| < 1/2` around its
//! centre. A pixel is drawn when the segment, travelling from start to end,
//! **leaves** that diamond: it passes through the diamond and the end point
//! is not inside it. So the end point's own diamond is not drawn (segments
//! joined end to start neither duplicate nor skip a pixel).
//!
//! Open diamonds do not tile the plane: where the ideal line passes exactly
//! halfway between two pixel centres of a column, it only touches the
//! corner the two diamonds share, and an open-diamond rule would draw
//! neither. As Direct3D does with its half-open test area, the diamond here
//! also owns **one corner**: its bottom corner `(xc, yc + 1/2)` for x-major
//! segments (`|dx| >= |dy|`, so exactly 45 degrees is x-major), its right
//! corner `(xc + 1/2, yc)` for y-major ones. Every column (row) the segment
//! crosses then gets exactly one pixel.
//!
//! The test is exact: in the rotated coordinates `s = x + y`, `d = x - y`
//! the diamond is an open square, and the part of the segment inside it is
//! found by clipping the parameter `t` against the square's two slabs with
//! integer fractions (Liang-Barsky), in `i64` while the coordinates are
//! within 2^28 fixed-point units (always, for points inside the guard
//! band), in `i128` beyond. [`exits_diamond`] is that test for one
//! pixel; the back-end applies it to the few pixels near the line in each
//! column (or row), and the tests check it against applying it to every
//! pixel.

use super::{LineDescriptor, LineOptions, LineRasterizer, LineSetup, LineWalk, PixelEmitter};
use crate::error::{Error, Result};
use crate::raster::descriptor::{CostClass, Role};
use crate::raster::edge::PixelRect;
use crate::raster::fixed::{FixedPoint, HALF_PIXEL, SUBPIXEL_SCALE};
use crate::raster::fragment::{FragmentSink, WorkCounters};
use std::cmp::Ordering;
use std::ops::{Add, Mul, Sub};

/// The diamond-exit rule.
#[derive(Copy, Clone, Debug, Default)]
pub struct Diamond;

/// The integers the exact test computes in. Its largest values are
/// products of two coordinate differences: `i64` holds them while every
/// coordinate is under 2^28 fixed-point units (the guard band keeps
/// snapped points under 2^23), `i128` whatever the coordinates.
pub(super) trait Exact:
    Copy + Ord + From<i64> + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self>
{
    fn abs(self) -> Self;
    fn signum(self) -> Self;
}

impl Exact for i64 {
    fn abs(self) -> i64 {
        i64::abs(self)
    }
    fn signum(self) -> i64 {
        i64::signum(self)
    }
}

impl Exact for i128 {
    fn abs(self) -> i128 {
        i128::abs(self)
    }
    fn signum(self) -> i128 {
        i128::signum(self)
    }
}

/// A bound on the segment parameter `t`: the fraction `num / den`
/// (`den > 0`), and whether the bound itself is excluded.
#[derive(Copy, Clone, Debug)]
pub(super) struct Bound<T> {
    pub(super) num: T,
    pub(super) den: T,
    pub(super) strict: bool,
}

impl<T: Exact> Bound<T> {
    /// The range `[0, 1]` of the segment parameter, both ends included.
    pub(super) fn whole_segment() -> (Bound<T>, Bound<T>) {
        let bound = |num| Bound {
            num: T::from(num),
            den: T::from(1),
            strict: false,
        };
        (bound(0), bound(1))
    }

    pub(super) fn cmp_value(&self, other: &Bound<T>) -> Ordering {
        (self.num * other.den).cmp(&(other.num * self.den))
    }

    /// Is the range from this lower bound to `upper` not empty?
    pub(super) fn below(&self, upper: &Bound<T>) -> bool {
        match self.cmp_value(upper) {
            Ordering::Less => true,
            Ordering::Equal => !self.strict && !upper.strict,
            Ordering::Greater => false,
        }
    }
}

/// Does the segment intersect the open slab `lo < s0 + t ds < hi`
/// within the current `[lower, upper]` range of `t`? Narrows the range.
pub(super) fn clip_slab<T: Exact>(
    s0: T,
    ds: T,
    lo: T,
    hi: T,
    lower: &mut Bound<T>,
    upper: &mut Bound<T>,
) -> bool {
    let zero = T::from(0);
    if ds == zero {
        return lo < s0 && s0 < hi;
    }
    let (a, b) = (lo - s0, hi - s0);
    let (enter, leave) = if ds > zero { (a, b) } else { (b, a) };
    let den = ds.abs();
    let sign = ds.signum();
    let enter = Bound {
        num: enter * sign,
        den,
        strict: true,
    };
    let leave = Bound {
        num: leave * sign,
        den,
        strict: true,
    };
    match enter.cmp_value(lower) {
        Ordering::Greater => *lower = enter,
        Ordering::Equal => lower.strict = true,
        Ordering::Less => {}
    }
    match leave.cmp_value(upper) {
        Ordering::Less => *upper = leave,
        Ordering::Equal => upper.strict = true,
        Ordering::Greater => {}
    }
    true
}

/// The corner of pixel `(px, py)`'s diamond that belongs to it, for a
/// segment of the given major axis.
fn owned_corner(px: i64, py: i64, x_major: bool) -> (i64, i64) {
    let cx = px * SUBPIXEL_SCALE + HALF_PIXEL;
    let cy = py * SUBPIXEL_SCALE + HALF_PIXEL;
    if x_major {
        (cx, cy + HALF_PIXEL)
    } else {
        (cx + HALF_PIXEL, cy)
    }
}

/// Is `p` in the diamond test area of pixel `(px, py)`: strictly inside,
/// or on its owned corner?
fn in_test_area(p: FixedPoint, px: i64, py: i64, x_major: bool) -> bool {
    let cx = px * SUBPIXEL_SCALE + HALF_PIXEL;
    let cy = py * SUBPIXEL_SCALE + HALF_PIXEL;
    (p.x.raw() - cx).abs() + (p.y.raw() - cy).abs() < HALF_PIXEL
        || (p.x.raw(), p.y.raw()) == owned_corner(px, py, x_major)
}

/// Does the closed segment `a b` pass through the point `c`?
fn passes_through<T: Exact>(a: FixedPoint, b: FixedPoint, c: (i64, i64)) -> bool {
    let (ax, ay, bx, by) = (
        T::from(a.x.raw()),
        T::from(a.y.raw()),
        T::from(b.x.raw()),
        T::from(b.y.raw()),
    );
    let (cx, cy) = (T::from(c.0), T::from(c.1));
    (bx - ax) * (cy - ay) == (by - ay) * (cx - ax)
        && cx >= ax.min(bx)
        && cx <= ax.max(bx)
        && cy >= ay.min(by)
        && cy <= ay.max(by)
}

/// The diamond-exit test: does the segment `from -> to` leave the diamond
/// test area of pixel `(px, py)`?
pub fn exits_diamond(from: FixedPoint, to: FixedPoint, px: i64, py: i64) -> bool {
    const SMALL: i64 = 1 << 28;
    let small = [from.x, from.y, to.x, to.y]
        .iter()
        .all(|c| c.raw().abs() < SMALL)
        && px.abs() < SMALL / SUBPIXEL_SCALE / 2
        && py.abs() < SMALL / SUBPIXEL_SCALE / 2;
    if small {
        exits_in::<i64>(from, to, px, py)
    } else {
        exits_in::<i128>(from, to, px, py)
    }
}

/// [`exits_diamond`], computed in `T`.
fn exits_in<T: Exact>(from: FixedPoint, to: FixedPoint, px: i64, py: i64) -> bool {
    let x_major = (to.x.raw() - from.x.raw()).abs() >= (to.y.raw() - from.y.raw()).abs();
    if in_test_area(to, px, py, x_major) {
        return false;
    }
    if passes_through::<T>(from, to, owned_corner(px, py, x_major)) {
        return true;
    }
    let cx = T::from(px * SUBPIXEL_SCALE + HALF_PIXEL);
    let cy = T::from(py * SUBPIXEL_SCALE + HALF_PIXEL);
    let h = T::from(HALF_PIXEL);
    let (ax, ay) = (T::from(from.x.raw()), T::from(from.y.raw()));
    let (bx, by) = (T::from(to.x.raw()), T::from(to.y.raw()));
    let (mut lower, mut upper) = Bound::whole_segment();
    // s = x + y within (cx + cy - h, cx + cy + h); d = x - y likewise.
    let ok = clip_slab(
        ax + ay,
        (bx + by) - (ax + ay),
        cx + cy - h,
        cx + cy + h,
        &mut lower,
        &mut upper,
    ) && clip_slab(
        ax - ay,
        (bx - by) - (ax - ay),
        cx - cy - h,
        cx - cy + h,
        &mut lower,
        &mut upper,
    );
    ok && lower.below(&upper)
}

impl Diamond {
    /// The pixels of one segment, in the order of travel, and how many
    /// candidates were tested.
    pub fn pixels(line: &LineSetup) -> (Vec<(i64, i64)>, u64) {
        let mut tested = 0;
        let pixels = Self::walk(line, |_, _, _| tested += 1);
        (pixels, tested)
    }

    /// The walk of one segment: each column's (row's, for a y-major
    /// segment) three candidate pixels around the line, in the order of
    /// travel, each reported to `observe` with the test's answer (`true`:
    /// the segment leaves its diamond, the pixel is drawn); returns the
    /// pixels drawn. The trace records this walk; drawing passes a closure
    /// that only counts.
    pub fn walk(line: &LineSetup, observe: impl FnMut(i64, i64, bool)) -> Vec<(i64, i64)> {
        let mut pixels = Vec::new();
        Self::walk_into(line, observe, &mut pixels);
        pixels
    }

    /// [`walk`](Self::walk) into `pixels` (emptied first), so that a draw
    /// reuses its memory from one segment to the next.
    pub fn walk_into(
        line: &LineSetup,
        observe: impl FnMut(i64, i64, bool),
        pixels: &mut Vec<(i64, i64)>,
    ) {
        walk_candidates(line, exits_diamond, observe, pixels);
    }
}

/// The walk of the diamond-exit rules: in each column (row, for a y-major
/// segment), in the order of travel, the three candidates around the
/// line, each put to `exits` (the rule's test) and reported to `observe`;
/// the pixels drawn go to `pixels` (emptied first). The candidates are
/// those of any rule whose diamonds differ from the open ones by their
/// boundary alone.
pub(super) fn walk_candidates(
    line: &LineSetup,
    exits: impl Fn(FixedPoint, FixedPoint, i64, i64) -> bool,
    mut observe: impl FnMut(i64, i64, bool),
    pixels: &mut Vec<(i64, i64)>,
) {
    pixels.clear();
    let (a, b) = (line.from, line.to);
    let (dx, dy) = (b.x.raw() - a.x.raw(), b.y.raw() - a.y.raw());
    let x_major = dx.abs() >= dy.abs();
    let (a_major, b_major) = if x_major {
        (a.x.raw(), b.x.raw())
    } else {
        (a.y.raw(), b.y.raw())
    };
    let (a_minor, b_minor) = if x_major {
        (a.y.raw(), b.y.raw())
    } else {
        (a.x.raw(), b.x.raw())
    };
    let first = (a_major.min(b_major) - HALF_PIXEL).div_euclid(SUBPIXEL_SCALE) - 1;
    let last = (a_major.max(b_major) + HALF_PIXEL).div_euclid(SUBPIXEL_SCALE) + 1;
    let forward = b_major >= a_major;
    for n in 0..=last - first {
        let i = if forward { first + n } else { last - n };
        // The line's minor coordinate at this column's centre: with
        // |slope| <= 1, any diamond of this column the segment passes
        // through has its centre within half a pixel of it.
        let centre = i * SUBPIXEL_SCALE + HALF_PIXEL;
        let d_major = b_major - a_major;
        // In the guard band both factors are below 2^25 (the
        // columns reach 1.5 pixels past the ends), so the product
        // fits an i64 and the division needs no 128-bit call.
        let minor = if d_major == 0 {
            a_minor
        } else {
            a_minor + (centre - a_major) * (b_minor - a_minor) / d_major
        };
        let k = minor.div_euclid(SUBPIXEL_SCALE);
        let mut rows = [k - 1, k, k + 1];
        if b_minor < a_minor {
            rows.reverse();
        }
        for k in rows {
            let (px, py) = if x_major { (i, k) } else { (k, i) };
            let drawn = exits(a, b, px, py);
            observe(px, py, drawn);
            if drawn {
                pixels.push((px, py));
            }
        }
    }
}

impl LineRasterizer for Diamond {
    fn descriptor(&self) -> LineDescriptor {
        LineDescriptor {
            name: "diamond",
            description:
                "Direct3D / Vulkan diamond-exit rule, exact; the end point's diamond is not drawn",
            walk: LineWalk::DiamondExit,
            role: Role::Reference,
            cost: CostClass::FollowsSize,
        }
    }

    fn check_options(&self, options: &LineOptions) -> Result<()> {
        default_options_only("diamond", options)
    }

    fn rasterize(
        &self,
        lines: &[LineSetup],
        _options: &LineOptions,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> WorkCounters {
        draw_by(exits_diamond, lines, viewport, sink)
    }
}

/// A diamond-exit back-end's options: the defaults only, as the rule
/// fixes connectivity, the end points and the direction.
pub(super) fn default_options_only(name: &str, options: &LineOptions) -> Result<()> {
    if *options != LineOptions::DEFAULT {
        return Err(Error::InvalidArgument(format!(
            "{name} follows the diamond-exit rule: connectivity, endpoint and symmetry options do not apply"
        )));
    }
    Ok(())
}

/// Draws `lines` by a diamond-exit rule whose test is `exits`: each
/// segment's candidates walked ([`walk_candidates`]) and counted, its
/// pixels emitted within `viewport`.
pub(super) fn draw_by(
    exits: impl Fn(FixedPoint, FixedPoint, i64, i64) -> bool + Copy,
    lines: &[LineSetup],
    viewport: PixelRect,
    sink: &mut dyn FragmentSink,
) -> WorkCounters {
    let mut work = WorkCounters::default();
    let mut emitter = PixelEmitter::default();
    let mut pixels = Vec::new();
    for line in lines {
        work.primitives += 1;
        walk_candidates(line, exits, |_, _, _| work.samples_tested += 1, &mut pixels);
        emitter.emit(line, &pixels, viewport, sink, &mut work);
    }
    work
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(crate::test_support::proptest_config(3000, "tests/proptest-regressions/src-raster-line-diamond.txt"))]

        /// Computed in `i64` (the coordinates within the guard band) or
        /// in `i128`, the test gives the same answer, near the segment and
        /// at its ends, on grids fine and coarse.
        #[test]
        fn the_i64_test_is_the_i128_test(
            raw in proptest::array::uniform4(-(1i64 << 23) + 1..(1i64 << 23)),
            near in proptest::array::uniform4(-600i64..600),
            shift in 0u32..16,
            px in -3i64..3,
            py in -3i64..3,
        ) {
            // Coordinates anywhere in the guard band, or a few pixels
            // apart on a grid of 2^shift units, so that ties happen.
            let coarse = near.map(|v| v << shift.min(8));
            let pick = |i: usize| if shift < 8 { coarse[i] } else { raw[i] };
            let p = |x, y| FixedPoint::from_raw(x, y).unwrap();
            let (from, to) = (p(pick(0), pick(1)), p(pick(2), pick(3)));
            let (cx, cy) = (from.x.raw().div_euclid(SUBPIXEL_SCALE), from.y.raw().div_euclid(SUBPIXEL_SCALE));
            for (x, y) in [(cx + px, cy + py), (to.x.raw().div_euclid(SUBPIXEL_SCALE) + px, to.y.raw().div_euclid(SUBPIXEL_SCALE) + py)] {
                prop_assert_eq!(exits_in::<i64>(from, to, x, y), exits_in::<i128>(from, to, x, y));
            }
        }
    }
}

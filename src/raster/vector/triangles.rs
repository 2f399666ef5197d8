//! The first tests of triangle set-up, for eight triangles at once (one
//! per lane of AVX2's registers): the snapped triangle's signed area
//! (zero: degenerate), back-face culling by its sign, whether its
//! bounding box holds a pixel centre of the viewport, and, when the box
//! holds at most 2x2 centres, whether one of them may be inside
//! (the 32-bit test of
//! [`SmallTriangle::may_cover_a_sample`](crate::raster::compact::SmallTriangle::may_cover_a_sample)).
//!
//! On a mesh, most triangles end here: of the full dragon's 871,414,
//! drawn at 1920x1080 turned 30 degrees (`render --azimuth 30`), 461,338
//! are culled, 2,460 degenerate, 102,789 have no pixel centre in their
//! box and 105,183 are small and cover none. One at a time, each of
//! these tests is a branch that goes either way at random; here they are
//! masks. A triangle that passes them all goes on to the one-at-a-time
//! set-up ([`TriangleSetup`](crate::raster::edge::TriangleSetup)) without
//! being tested again.
//!
//! Each test is exact, as there:
//!
//! * twice the signed area is `(x2 - x0)(y1 - y0) - (x1 - x0)(y2 - y0)`,
//!   the set-up's `E0(v0)` written around `v0`; snapped coordinates have
//!   at most 24 bits, their differences 25, each product at most 50: the
//!   products and their difference are exact in `f64`;
//! * the first pixel centre at or after `v` is `ceil((v - 128) / 256)`,
//!   `-((128 - v) >> 8)`, and the last at or before is
//!   `(v - 128) >> 8`, both in `i32`, as `first_sample_at_or_after` and
//!   `last_sample_at_or_before` compute them in `i64`;
//! * a small triangle's edge values at the first centre of its box, and
//!   one pixel right and down, are `SmallTriangle`'s, in the same wrapping
//!   `i32` arithmetic (exact: a box of at most 2x2 centres spans less
//!   than three pixels).

use crate::raster::fixed::{HALF_PIXEL, SUBPIXEL_SCALE};
#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::*;

/// Eight triangles' snapped corners in raw fixed-point units: corner `k`
/// of triangle `i` is `(x[k][i], y[k][i])`.
#[derive(Copy, Clone, Debug, Default)]
pub(crate) struct Corners {
    pub x: [[i32; 8]; 3],
    pub y: [[i32; 8]; 3],
}

/// What the tests compare with, the same for every triangle of a draw.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Rules {
    /// `Some(s)`: the triangles whose twice signed area is positive when
    /// `s` (negative when not) are culled. `None`: none are.
    pub culled_positive: Option<bool>,
    /// The viewport's last pixel column and row.
    pub last: [i32; 2],
}

/// The triangles each test drops, a bit per lane (bit `i` for triangle
/// `i`), each test counting only those the tests before it kept.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Dropped {
    /// Twice the signed area is zero.
    pub degenerate: u8,
    /// Culled by the sign of the area.
    pub culled: u8,
    /// No pixel centre of the viewport in the bounding box.
    pub empty_bounds: u8,
    /// At most 2x2 pixel centres in the bounding box, none inside.
    pub no_sample: u8,
}

/// Tests eight triangles, if this CPU has AVX2 (and the tests allow it);
/// `None` if not.
#[inline]
pub(crate) fn classify(rules: &Rules, corners: &Corners) -> Option<Dropped> {
    #[cfg(target_arch = "x86_64")]
    if super::widest().min(super::allowed()) == super::Width::Avx2 {
        // SAFETY: the CPU has AVX2, checked just above.
        return Some(unsafe { classify_avx2(rules, corners) });
    }
    let _ = (rules, corners);
    None
}

/// Lanes 0..4 (`HALF` 0) or 4..8 (`HALF` 1) of `v`, as `f64`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn widen<const HALF: i32>(v: __m256i) -> __m256d {
    _mm256_cvtepi32_pd(_mm256_extracti128_si256::<HALF>(v))
}

/// The lanes (a bit each) where twice the signed area is zero, and where
/// it is positive: `(x2 - x0)(y1 - y0) - (x1 - x0)(y2 - y0)` for lanes
/// 0..4 or 4..8 of the corners' differences.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn area_signs<const HALF: i32>(d: [__m256i; 4]) -> (i32, i32) {
    let [dx1, dy1, dx2, dy2] = d.map(|v| widen::<HALF>(v));
    let area = _mm256_sub_pd(_mm256_mul_pd(dx2, dy1), _mm256_mul_pd(dx1, dy2));
    let zero = _mm256_setzero_pd();
    (
        _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_EQ_OQ>(area, zero)),
        _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_GT_OQ>(area, zero)),
    )
}

/// [`classify`] on a CPU with AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn classify_avx2(rules: &Rules, c: &Corners) -> Dropped {
    let load = |a: &[i32; 8]| {
        // SAFETY: `a` is eight readable `i32`; the load needs no alignment.
        unsafe { _mm256_loadu_si256(a.as_ptr().cast()) }
    };
    let [x0, x1, x2] = c.x.each_ref().map(load);
    let [y0, y1, y2] = c.y.each_ref().map(load);
    let d = [
        _mm256_sub_epi32(x1, x0),
        _mm256_sub_epi32(y1, y0),
        _mm256_sub_epi32(x2, x0),
        _mm256_sub_epi32(y2, y0),
    ];
    let (zero_low, positive_low) = area_signs::<0>(d);
    let (zero_high, positive_high) = area_signs::<1>(d);
    let degenerate = zero_low | zero_high << 4;
    let positive = positive_low | positive_high << 4;
    let culled = match rules.culled_positive {
        None => 0,
        Some(true) => positive,
        Some(false) => !positive & 0xff,
    } & !degenerate;
    // The pixel centres in the box.
    let half = _mm256_set1_epi32(HALF_PIXEL as i32);
    let shift = SUBPIXEL_SCALE.trailing_zeros() as i32;
    debug_assert_eq!(1 << shift, SUBPIXEL_SCALE);
    let count = _mm_cvtsi32_si128(shift);
    // Per axis, the box's first and last centre, `first = -floor_low`
    // and `last = floor_high`, before the viewport cut.
    let floors = |a, b, c| {
        let low = _mm256_min_epi32(_mm256_min_epi32(a, b), c);
        let high = _mm256_max_epi32(_mm256_max_epi32(a, b), c);
        (
            _mm256_sra_epi32(_mm256_sub_epi32(half, low), count),
            _mm256_sra_epi32(_mm256_sub_epi32(high, half), count),
        )
    };
    let (floor_low_x, floor_high_x) = floors(x0, x1, x2);
    let (floor_low_y, floor_high_y) = floors(y0, y1, y2);
    // Small boxes: at most two centres each way (before the viewport cut),
    // `last - first = floor_high + floor_low` at most 1.
    let two = _mm256_set1_epi32(2);
    let small = _mm256_and_si256(
        _mm256_cmpgt_epi32(two, _mm256_add_epi32(floor_high_x, floor_low_x)),
        _mm256_cmpgt_epi32(two, _mm256_add_epi32(floor_high_y, floor_low_y)),
    );
    // Cut to the viewport.
    let first = |floor_low| {
        let first = _mm256_sub_epi32(_mm256_setzero_si256(), floor_low);
        _mm256_max_epi32(first, _mm256_setzero_si256())
    };
    let (first_x, first_y) = (first(floor_low_x), first(floor_low_y));
    let last_x = _mm256_min_epi32(floor_high_x, _mm256_set1_epi32(rules.last[0]));
    let last_y = _mm256_min_epi32(floor_high_y, _mm256_set1_epi32(rules.last[1]));
    let empty = _mm256_or_si256(
        _mm256_cmpgt_epi32(first_x, last_x),
        _mm256_cmpgt_epi32(first_y, last_y),
    );
    let empty = _mm256_movemask_ps(_mm256_castsi256_ps(empty));
    // The edge functions, inside-positive: each edge's coefficients
    // negated where the area is negative.
    let lane_bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    let negative = _mm256_cmpeq_epi32(
        _mm256_and_si256(_mm256_set1_epi32(!positive), lane_bits),
        lane_bits,
    );
    let signed = |v: __m256i| _mm256_sub_epi32(_mm256_xor_si256(v, negative), negative);
    let a = [
        _mm256_sub_epi32(y2, y1),
        _mm256_sub_epi32(y0, y2),
        _mm256_sub_epi32(y1, y0),
    ]
    .map(signed);
    let b = [
        _mm256_sub_epi32(x1, x2),
        _mm256_sub_epi32(x2, x0),
        _mm256_sub_epi32(x0, x1),
    ]
    .map(signed);
    // Edge k runs from vertex k + 1: its value at the first centre.
    let origin_x = _mm256_add_epi32(_mm256_slli_epi32::<8>(first_x), half);
    let origin_y = _mm256_add_epi32(_mm256_slli_epi32::<8>(first_y), half);
    let from_x = [x1, x2, x0];
    let from_y = [y1, y2, y0];
    let at_origin = [0, 1, 2].map(|k| {
        _mm256_add_epi32(
            _mm256_mullo_epi32(a[k], _mm256_sub_epi32(origin_x, from_x[k])),
            _mm256_mullo_epi32(b[k], _mm256_sub_epi32(origin_y, from_y[k])),
        )
    });
    // Inside (or on an edge) where no value is negative.
    let inside = |e: [__m256i; 3]| {
        _mm256_cmpgt_epi32(
            _mm256_or_si256(_mm256_or_si256(e[0], e[1]), e[2]),
            _mm256_set1_epi32(-1),
        )
    };
    let step = |e: [__m256i; 3], d: [__m256i; 3]| {
        [0, 1, 2].map(|k| _mm256_add_epi32(e[k], _mm256_slli_epi32::<8>(d[k])))
    };
    let wide = _mm256_cmpgt_epi32(last_x, first_x);
    let tall = _mm256_cmpgt_epi32(last_y, first_y);
    let right = step(at_origin, a);
    let may_cover = _mm256_or_si256(
        _mm256_or_si256(inside(at_origin), _mm256_and_si256(wide, inside(right))),
        _mm256_or_si256(
            _mm256_and_si256(tall, inside(step(at_origin, b))),
            _mm256_and_si256(_mm256_and_si256(wide, tall), inside(step(right, b))),
        ),
    );
    let no_sample = _mm256_andnot_si256(may_cover, small);
    let no_sample = _mm256_movemask_ps(_mm256_castsi256_ps(no_sample));
    let gone = degenerate | culled;
    let empty_bounds = empty & !gone;
    Dropped {
        degenerate: degenerate as u8,
        culled: culled as u8,
        empty_bounds: empty_bounds as u8,
        no_sample: (no_sample & !gone & !empty_bounds) as u8,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::compact::SmallTriangle;
    use crate::raster::edge::{PixelRect, TriangleSetup};
    use crate::raster::fixed::{FixedPoint, GUARD_BAND};
    use crate::raster::vector::{self, Width};
    use proptest::prelude::*;

    /// What the one-at-a-time set-up drops triangle `i` for, as a mask.
    fn one_at_a_time(rules: &Rules, c: &Corners, i: usize) -> Dropped {
        let v =
            [0, 1, 2].map(|k| FixedPoint::from_raw(c.x[k][i].into(), c.y[k][i].into()).unwrap());
        let bit = 1 << i;
        let area = TriangleSetup::signed_area(v);
        let viewport = PixelRect {
            x0: 0,
            y0: 0,
            x1: rules.last[0].into(),
            y1: rules.last[1].into(),
        };
        let mut dropped = Dropped::default();
        if area == 0 {
            dropped.degenerate = bit;
        } else if rules.culled_positive.is_some_and(|p| p == (area > 0)) {
            dropped.culled = bit;
        } else {
            let whole = TriangleSetup::sample_bounds(v);
            let bounds = whole.intersect(viewport);
            if bounds.is_empty() {
                dropped.empty_bounds = bit;
            } else if whole.x1 - whole.x0 <= 1 && whole.y1 - whole.y0 <= 1 {
                let small = SmallTriangle::new(v).unwrap();
                if !small.may_cover_a_sample(bounds) {
                    dropped.no_sample = bit;
                }
            }
        }
        dropped
    }

    /// A raw coordinate: near a pixel centre's boundary, anywhere in a
    /// small neighbourhood, or anywhere in the guard band.
    fn coordinate(centre: i32) -> impl Strategy<Value = i32> {
        let band = (GUARD_BAND * SUBPIXEL_SCALE) as i32 - 1;
        prop_oneof![
            3 => (-3i32..4, -1i32..2).prop_map(move |(p, d)| {
                (centre / 256 + p) * 256 + HALF_PIXEL as i32 + d
            }),
            3 => (-1500i32..1500).prop_map(move |d| (centre + d).clamp(-band, band)),
            1 => -band..=band,
        ]
    }

    fn corners() -> impl Strategy<Value = Corners> {
        (-3000i32..600_000, -3000i32..400_000).prop_flat_map(|(cx, cy)| {
            let xs = prop::array::uniform3(prop::array::uniform8(coordinate(cx)));
            let ys = prop::array::uniform3(prop::array::uniform8(coordinate(cy)));
            (xs, ys).prop_map(|(x, y)| Corners { x, y })
        })
    }

    fn rules() -> impl Strategy<Value = Rules> {
        (prop::option::of(any::<bool>()), 0i32..2500, 0i32..1500).prop_map(
            |(culled_positive, w, h)| Rules {
                culled_positive,
                last: [w - 1, h - 1],
            },
        )
    }

    proptest! {
        #![proptest_config(crate::test_support::proptest_config(3000, "tests/proptest-regressions/src-raster-vector-triangles.txt"))]

        /// The lanes drop the triangles the one-at-a-time tests drop, for
        /// the same reason: corners on either side of pixel centres, on
        /// a line (degenerate), off the viewport, anywhere in the guard
        /// band, every culling rule, an empty viewport.
        #[test]
        fn lanes_drop_what_one_at_a_time_drops(rules in rules(), corners in corners()) {
            let Some(lanes) = vector::limited_to(Width::Avx2, || classify(&rules, &corners)) else {
                eprintln!("no AVX2 on this CPU: the lanes are not run, nothing to compare");
                return Ok(());
            };
            let mut expected = Dropped::default();
            for i in 0..8 {
                let d = one_at_a_time(&rules, &corners, i);
                expected.degenerate |= d.degenerate;
                expected.culled |= d.culled;
                expected.empty_bounds |= d.empty_bounds;
                expected.no_sample |= d.no_sample;
            }
            prop_assert_eq!(lanes, expected);
        }
    }

    /// The baseline copy (and a CPU without AVX2) runs no lanes.
    #[test]
    fn the_baseline_runs_no_lanes() {
        let rules = Rules {
            culled_positive: None,
            last: [9, 9],
        };
        let none = vector::limited_to(Width::Baseline, || classify(&rules, &Corners::default()));
        assert_eq!(none, None);
    }
}

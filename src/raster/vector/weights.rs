//! The interpolation weights of eight pixels of a span (steps 2 and 3 of
//! the stage's shaded span loop, [`ShadedSpan`](crate::raster::stage)),
//! one pixel per lane of AVX2's registers:
//!
//! 1. each pixel's three edge values, `E_i + k * step_i` from the group's
//!    first pixel, in `f64` (exact: the loop checked every one is an
//!    integer below 2^53);
//! 2. the barycentrics `E_i / area` rounded to `f32`, as products by the
//!    area's reciprocal wherever those round as the quotient does (the
//!    test on the product's dropped bits the loop's `by_reciprocal`
//!    explains), and as quotients for the whole group where one lane's
//!    product is not sure;
//! 3. with perspective correction, `beta_i / w_i` and their sum
//!    `((0 + w_0) + w_1) + w_2`, and each divided by the sum where the sum
//!    is positive (the screen weight where it is not).
//!
//! Every operation is the loop's, in its order: the same bits. The loop's
//! plain Rust gives them too, and the copy compiled for the baseline uses
//! it; but compiled for AVX2, the compiler spread the three arrays of
//! eight over registers across their boundaries and passed them through
//! memory, and these steps took a sixth of the small dragon's raster.

#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::*;

/// What the weights of a group are found from.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Group {
    /// The edge values at the group's first pixel, exact in `f64`.
    pub edges: [f64; 3],
    /// What they gain per pixel to the right, exact in `f64`.
    pub step: [f64; 3],
    /// The triangle's doubled area, and its reciprocal.
    pub area: f64,
    pub inv_area: f64,
    /// `1 / w` of the three vertices, with perspective correction;
    /// `None` for linear interpolation.
    pub inv_w: Option<[f32; 3]>,
}

/// The weights of the eight pixels, one array per vertex, if this CPU has
/// AVX2 (and the tests allow it); `None` if not.
#[inline(always)]
pub(crate) fn weights(group: &Group) -> Option<[[f32; 8]; 3]> {
    #[cfg(target_arch = "x86_64")]
    if super::widest().min(super::allowed()) == super::Width::Avx2 {
        // SAFETY: the CPU has AVX2, checked just above.
        return Some(unsafe { weights_avx2(group) });
    }
    let _ = group;
    None
}

/// The bits an `f64` has below an `f32`'s 23-bit fraction.
pub(crate) const DROPPED_BITS: u32 = 52 - 23;

/// Where those bits read `1000...0`: a midpoint between two `f32`s.
pub(crate) const MIDPOINT: i64 = 1 << (DROPPED_BITS - 1);

/// How far from [`MIDPOINT`] a product's dropped bits must lie for the
/// product to round as the quotient does.
pub(crate) const MARGIN: i64 = 16;

/// [`weights`] with AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn weights_avx2(group: &Group) -> [[f32; 8]; 3] {
    let lanes = [
        _mm256_set_pd(3.0, 2.0, 1.0, 0.0),
        _mm256_set_pd(7.0, 6.0, 5.0, 4.0),
    ];
    // Edge values: `first + k * step`, as the loop's plain Rust.
    let edge: [[__m256d; 2]; 3] = std::array::from_fn(|i| {
        let (first, step) = (
            _mm256_set1_pd(group.edges[i]),
            _mm256_set1_pd(group.step[i]),
        );
        lanes.map(|k| _mm256_add_pd(first, _mm256_mul_pd(k, step)))
    });
    // Products by the reciprocal, and the lanes where one is not sure.
    let inv_area = _mm256_set1_pd(group.inv_area);
    let dropped_mask = _mm256_set1_epi64x((1 << DROPPED_BITS) - 1);
    let (below, above) = (
        _mm256_set1_epi64x(MIDPOINT - MARGIN),
        _mm256_set1_epi64x(MIDPOINT + MARGIN),
    );
    let mut unsure = _mm256_setzero_si256();
    let mut product = [[_mm256_setzero_pd(); 2]; 3];
    for i in 0..3 {
        for h in 0..2 {
            let p = _mm256_mul_pd(edge[i][h], inv_area);
            let dropped = _mm256_and_si256(_mm256_castpd_si256(p), dropped_mask);
            let near = _mm256_and_si256(
                _mm256_cmpgt_epi64(dropped, below),
                _mm256_cmpgt_epi64(above, dropped),
            );
            unsure = _mm256_or_si256(unsure, near);
            product[i][h] = p;
        }
    }
    if _mm256_testz_si256(unsure, unsure) == 0 {
        let area = _mm256_set1_pd(group.area);
        for i in 0..3 {
            for h in 0..2 {
                product[i][h] = _mm256_div_pd(edge[i][h], area);
            }
        }
    }
    let screen = product.map(|[low, high]| {
        _mm256_insertf128_ps::<1>(
            _mm256_castps128_ps256(_mm256_cvtpd_ps(low)),
            _mm256_cvtpd_ps(high),
        )
    });
    let weights = match group.inv_w {
        None => screen,
        Some(inv_w) => {
            let w: [__m256; 3] =
                std::array::from_fn(|i| _mm256_mul_ps(screen[i], _mm256_set1_ps(inv_w[i])));
            let sum = w
                .iter()
                .fold(_mm256_setzero_ps(), |sum, &w| _mm256_add_ps(sum, w));
            let positive = _mm256_cmp_ps::<_CMP_GT_OQ>(sum, _mm256_setzero_ps());
            std::array::from_fn(|i| _mm256_blendv_ps(screen[i], _mm256_div_ps(w[i], sum), positive))
        }
    };
    weights.map(|w| {
        let mut out = [0.0f32; 8];
        // SAFETY: `out` holds the eight `f32` the unaligned store writes.
        unsafe { _mm256_storeu_ps(out.as_mut_ptr(), w) };
        out
    })
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;
    use crate::raster::primitive::{ShadedVertex, Varyings};
    use crate::raster::stage::{varying_weights, Interpolation};

    /// The weights of lane `k` as the fragment path finds them, with its
    /// own functions: the barycentrics from the pixel's edge values
    /// (`ratios_to_f32`), then `varying_weights`.
    fn one_lane(group: &Group, k: usize) -> [f32; 3] {
        let edges = [0, 1, 2].map(|i| (group.edges[i] + k as f64 * group.step[i]) as i64);
        let screen = super::super::ratios_to_f32(edges, group.area);
        let (interpolation, inv_w) = match group.inv_w {
            Some(inv_w) => (Interpolation::PerspectiveCorrect, inv_w),
            None => (Interpolation::Linear, [1.0; 3]),
        };
        let vertices = inv_w.map(|inv_w| ShadedVertex {
            depth: 0.0,
            inv_w,
            varyings: Varyings::default(),
        });
        varying_weights(interpolation, screen, &vertices)
    }

    /// Whether a lane's product by the reciprocal is not sure, so that the
    /// group divides.
    fn divides(group: &Group) -> bool {
        (0..8).any(|k| {
            (0..3).any(|i| {
                let e = group.edges[i] + k as f64 * group.step[i];
                let dropped = ((e * group.inv_area).to_bits() & ((1 << DROPPED_BITS) - 1)) as i64;
                dropped > MIDPOINT - MARGIN && dropped < MIDPOINT + MARGIN
            })
        })
    }

    /// Lane for lane, the AVX2 weights are the fragment path's, bit for
    /// bit: with products by the reciprocal, with quotients where a
    /// product is not sure (edge values built next to midpoints between
    /// two `f32`, as the loop's `by_reciprocal` test builds them), with
    /// sums of the perspective weights positive, zero and negative, and
    /// without perspective.
    #[test]
    fn the_avx2_weights_are_the_fragment_paths() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            eprintln!("NOT CHECKED: this CPU has no AVX2");
            return;
        }
        let mut rng = fastrand::Rng::with_seed(41);
        let (mut groups, mut dividing) = (0, 0);
        for n in 0..20_000 {
            let near_midpoint = n % 2 == 0;
            let scale: i64 = if near_midpoint { 1 << 51 } else { 1 << 30 };
            let area = rng.i64(scale..2 * scale);
            let e0 = if near_midpoint {
                let below = f32::from_bits(rng.u32(0.01f32.to_bits()..0.5f32.to_bits()));
                let above = f32::from_bits(below.to_bits() + 1);
                let midpoint = (f64::from(below) + f64::from(above)) / 2.0;
                (midpoint * area as f64).round() as i64 + rng.i64(-40..=40)
            } else {
                rng.i64(-scale..scale)
            };
            let e1 = rng.i64(-scale / 2..scale / 2);
            let (s0, s1) = if near_midpoint {
                (rng.i64(-3..=3), rng.i64(-3..=3))
            } else {
                (
                    rng.i64(-scale / 64..scale / 64),
                    rng.i64(-scale / 64..scale / 64),
                )
            };
            let inv_w = |rng: &mut fastrand::Rng| match rng.u8(0..8) {
                0 => 0.0,
                1 => -rng.f32(),
                _ => 0.01 + rng.f32() * 4.0,
            };
            let group = Group {
                edges: [e0, e1, area - e0 - e1].map(|e| e as f64),
                step: [s0, s1, -s0 - s1].map(|s| s as f64),
                area: area as f64,
                inv_area: 1.0 / area as f64,
                inv_w: (n % 5 != 0).then(|| [inv_w(&mut rng), inv_w(&mut rng), inv_w(&mut rng)]),
            };
            groups += 1;
            dividing += usize::from(divides(&group));
            // SAFETY: the CPU has AVX2, checked above.
            let lanes = unsafe { weights_avx2(&group) };
            for k in 0..8 {
                let expected = one_lane(&group, k).map(f32::to_bits);
                let found = lanes.map(|lane| lane[k].to_bits());
                assert_eq!(found, expected, "lane {k} of {group:?}");
            }
        }
        assert!(dividing > 100, "only {dividing} of {groups} groups divided");
    }
}

//! Snapped fixed-point screen coordinates.
//!
//! Before any coverage decision, every screen-space vertex position is
//! **snapped** to a grid of 1/256 pixel (8 fractional bits), rounding to the
//! nearest grid point with ties to even. From then on every inside/outside
//! decision is exact integer arithmetic, which is what lets five different
//! rasterizers agree to the pixel.
//!
//! The **guard band** is the range snapped coordinates must stay in:
//! `|x| < 2^15` and `|y| < 2^15` pixels. Inside it a coordinate needs 24
//! bits, an edge-function coefficient 25 bits and an edge value about 50
//! bits, so edge functions are evaluated in `i64` without any risk of
//! overflow. Coordinates outside it are rejected with
//! [`crate::Error::OutsideGuardBand`] (the 3D
//! pipeline clips against it first, so it never produces them).
//!
//! Pixel `(i, j)` has its sample point at its centre `(i + 0.5, j + 0.5)`,
//! which is `256 i + 128` in fixed point (the rasterization slides write the same centre in
//! normalised device coordinates as `x = (i + 0.5) / w * 2 - 1`).
//!
//! ```
//! use rasterlab::raster::{Fixed, SUBPIXEL_SCALE};
//! let x = Fixed::snap(1.5).unwrap();
//! assert_eq!(x.raw(), 384);
//! // 1/512 px is exactly halfway between two grid points: ties go to even.
//! assert_eq!(Fixed::snap(1.0 / 512.0).unwrap().raw(), 0);
//! assert_eq!(Fixed::snap(3.0 / 512.0).unwrap().raw(), 2);
//! assert_eq!(Fixed::pixel_centre(2).raw(), 2 * SUBPIXEL_SCALE + 128);
//! assert!(Fixed::snap(f32::NAN).is_err());
//! assert!(Fixed::snap(40_000.0).is_err());
//! ```

use crate::error::{Error, Result};

/// Number of fractional bits of a snapped coordinate.
pub const SUBPIXEL_BITS: u32 = 8;
/// Fixed-point units per pixel (`2^SUBPIXEL_BITS`).
pub const SUBPIXEL_SCALE: i64 = 1 << SUBPIXEL_BITS;
/// Half a pixel in fixed-point units: the offset of a pixel's sample point.
pub const HALF_PIXEL: i64 = SUBPIXEL_SCALE / 2;
/// Guard band half-width in pixels: snapped coordinates satisfy `|v| < GUARD_BAND`.
pub const GUARD_BAND: i64 = 1 << 15;

/// A screen coordinate snapped to 1/256 pixel.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash, bytemuck::Zeroable)]
pub struct Fixed(i32);

/// `x` rounded to the nearest integer, ties to even: `f64::round_ties_even`,
/// which the baseline x86-64 target (no SSE4.1 `roundsd`) compiles to a
/// call into the C library, once per coordinate of every vertex. Below
/// 2^51, adding and subtracting 1.5 * 2^52 rounds the same way in two
/// additions (the sum has no bits below 1, and IEEE addition rounds to
/// nearest, ties to even); larger values, far beyond the guard band, take
/// the library's path.
#[inline]
fn round_ties_even(x: f64) -> f64 {
    const SHIFT: f64 = 6_755_399_441_055_744.0; // 1.5 * 2^52
    if x.abs() < 2_251_799_813_685_248.0 {
        // 2^51
        (x + SHIFT) - SHIFT
    } else {
        x.round_ties_even()
    }
}

impl Fixed {
    /// Snaps a coordinate in pixels: round to nearest, ties to even.
    ///
    /// Errors on NaN, infinities and values outside the guard band.
    pub fn snap(pixels: f32) -> Result<Fixed> {
        Self::snap_f64(f64::from(pixels))
    }

    /// [`Fixed::snap`] for an `f64` coordinate.
    pub fn snap_f64(pixels: f64) -> Result<Fixed> {
        if !pixels.is_finite() {
            return Err(Error::NonFinite { value: pixels });
        }
        // Exact for every f32 input: multiplying by a power of two.
        let scaled = round_ties_even(pixels * SUBPIXEL_SCALE as f64);
        let limit = (GUARD_BAND * SUBPIXEL_SCALE) as f64;
        if scaled.abs() >= limit {
            return Err(Error::OutsideGuardBand {
                value: pixels,
                limit: GUARD_BAND,
            });
        }
        Ok(Fixed(scaled as i32))
    }

    /// Builds a coordinate from raw fixed-point units.
    ///
    /// Errors when the value is outside the guard band.
    pub fn from_raw(raw: i64) -> Result<Fixed> {
        if raw.abs() >= GUARD_BAND * SUBPIXEL_SCALE {
            return Err(Error::OutsideGuardBand {
                value: raw as f64 / SUBPIXEL_SCALE as f64,
                limit: GUARD_BAND,
            });
        }
        Ok(Fixed(raw as i32))
    }

    /// A coordinate of `raw` units that a snap computed elsewhere (eight
    /// at a time) found within the guard band, as [`Fixed::snap_f64`] does.
    pub(crate) const fn from_snapped(raw: i32) -> Fixed {
        Fixed(raw)
    }

    /// The sample point (centre) of pixel column or row `i`.
    pub const fn pixel_centre(i: i32) -> Fixed {
        Fixed(i * SUBPIXEL_SCALE as i32 + HALF_PIXEL as i32)
    }

    /// Raw fixed-point units, widened for exact edge arithmetic.
    pub const fn raw(self) -> i64 {
        self.0 as i64
    }

    /// The coordinate in pixels.
    pub fn to_f64(self) -> f64 {
        f64::from(self.0) / SUBPIXEL_SCALE as f64
    }
}

/// A snapped screen-space point.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash, bytemuck::Zeroable)]
pub struct FixedPoint {
    /// Column coordinate (grows right).
    pub x: Fixed,
    /// Row coordinate (grows down).
    pub y: Fixed,
}

impl FixedPoint {
    /// Snaps a point given in pixels.
    pub fn snap(x: f32, y: f32) -> Result<FixedPoint> {
        Self::snap_f64(f64::from(x), f64::from(y))
    }

    /// [`FixedPoint::snap`] for a point read as `f64` (text input,
    /// command-line arguments), so no precision is lost before snapping.
    pub fn snap_f64(x: f64, y: f64) -> Result<FixedPoint> {
        Ok(FixedPoint {
            x: Fixed::snap_f64(x)?,
            y: Fixed::snap_f64(y)?,
        })
    }

    /// Builds a point from raw fixed-point units (checked against the guard band).
    pub fn from_raw(x: i64, y: i64) -> Result<FixedPoint> {
        Ok(FixedPoint {
            x: Fixed::from_raw(x)?,
            y: Fixed::from_raw(y)?,
        })
    }

    /// The sample point of pixel `(i, j)`.
    pub const fn pixel_centre(i: i32, j: i32) -> FixedPoint {
        FixedPoint {
            x: Fixed::pixel_centre(i),
            y: Fixed::pixel_centre(j),
        }
    }

    /// Snaps the centre of pixel `(x, y)`, that is the point
    /// `(x + 0.5, y + 0.5)`: how the course gives line endpoints.
    pub fn snap_centre_of(x: f64, y: f64) -> Result<FixedPoint> {
        FixedPoint::snap_f64(x + 0.5, y + 0.5)
    }

    /// The point in pixels.
    pub fn to_f64(self) -> (f64, f64) {
        (self.x.to_f64(), self.y.to_f64())
    }
}

/// The first pixel index whose sample point is at or after `raw` (fixed units).
pub fn first_sample_at_or_after(raw: i64) -> i64 {
    // ceil((raw - 128) / 256)
    -((HALF_PIXEL - raw).div_euclid(SUBPIXEL_SCALE))
}

/// The last pixel index whose sample point is at or before `raw` (fixed units).
pub fn last_sample_at_or_before(raw: i64) -> i64 {
    // floor((raw - 128) / 256)
    (raw - HALF_PIXEL).div_euclid(SUBPIXEL_SCALE)
}

#[cfg(test)]
mod tests {
    #[test]
    fn two_additions_round_as_round_ties_even() {
        let mut values = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            2.5,
            -2.5,
            1e15 + 0.5,
            2f64.powi(51) - 0.5,
        ];
        for k in -2000..2000 {
            let x = f64::from(k);
            values.extend([x + 0.5, x + 0.25, x - 0.25, x + 0.4999999999, x * 1234.5678]);
        }
        let mut rng = fastrand::Rng::with_seed(7);
        values.extend((0..100_000).map(|_| (rng.f64() - 0.5) * 2f64.powi(rng.i32(0..60))));
        for x in values {
            assert_eq!(super::round_ties_even(x), x.round_ties_even(), "{x}");
        }
    }

    use super::*;

    #[test]
    fn snapping_rounds_half_to_even_and_keeps_negative_zero_at_zero() {
        assert_eq!(Fixed::snap(-0.0).unwrap().raw(), 0);
        assert_eq!(Fixed::snap(0.5 / 256.0).unwrap().raw(), 0);
        assert_eq!(Fixed::snap(1.5 / 256.0).unwrap().raw(), 2);
        assert_eq!(Fixed::snap(-1.5 / 256.0).unwrap().raw(), -2);
        assert_eq!(Fixed::snap(-2.5 / 256.0).unwrap().raw(), -2);
        assert_eq!(Fixed::snap(0.6 / 256.0).unwrap().raw(), 1);
    }

    #[test]
    fn guard_band_is_exclusive() {
        assert!(Fixed::snap(32767.99).is_ok());
        assert!(matches!(
            Fixed::snap(32768.0),
            Err(Error::OutsideGuardBand { .. })
        ));
        assert!(Fixed::snap(-32768.0).is_err());
        assert!(Fixed::snap(f32::INFINITY).is_err());
        assert!(Fixed::snap(f32::NEG_INFINITY).is_err());
        assert!(Fixed::from_raw(GUARD_BAND * SUBPIXEL_SCALE).is_err());
    }

    #[test]
    fn sample_ranges_floor_negative_values_rather_than_truncating() {
        // Sample of pixel -1 is at -128.
        assert_eq!(first_sample_at_or_after(-128), -1);
        assert_eq!(first_sample_at_or_after(-127), 0);
        assert_eq!(first_sample_at_or_after(-129), -1);
        assert_eq!(first_sample_at_or_after(-385), -2);
        assert_eq!(last_sample_at_or_before(-129), -2);
        assert_eq!(last_sample_at_or_before(128), 0);
        assert_eq!(last_sample_at_or_before(127), -1);
        for raw in -2000..2000 {
            let first = first_sample_at_or_after(raw);
            assert!(first * 256 + 128 >= raw && (first - 1) * 256 + 128 < raw);
            let last = last_sample_at_or_before(raw);
            assert!(last * 256 + 128 <= raw && (last + 1) * 256 + 128 > raw);
        }
    }
}

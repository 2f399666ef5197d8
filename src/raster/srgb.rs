//! Where colours are encoded and where they are mixed: the sRGB transfer
//! function (IEC 61966-2-1, 1999) and linear light.
//!
//! Every colour rasterlab stores is **sRGB-encoded**, as image files, CSS
//! and SVG colours are: vertex colours, scene colours, texels, the RGBA8
//! colour buffer and the PNG files written from it (which say so with
//! their `sRGB` chunk). Alpha is never encoded: it is a fraction of the
//! pixel, stored as `alpha * 255`.
//!
//! Encoded values are not proportional to light: 128 is about 22% of the
//! light of 255, not 50%. So wherever colours are **mixed**, the blend,
//! the anti-aliased coverage mix and the multisample resolve, they are
//! first decoded to **linear light**, mixed there, and encoded again
//! ([`MixSpace::Linear`], the default). Mixing the encoded numbers
//! instead ([`MixSpace::Encoded`], what tiny-skia and most 2D libraries
//! do) darkens every partly covered pixel: half-covered white on black
//! gives 128, which looks about a fifth as bright as white, where light
//! gives 188 (`0.5` linear, encoded).
//!
//! Interpolating a colour across a triangle (Gouraud shading) is not a
//! mix of pixels and stays in encoded values, as without an sRGB colour
//! buffer in OpenGL: a colour gradient is drawn as its vertices' numbers
//! say.
//!
//! The decoding of the 256 stored values is a table; the encoding of a
//! linear value is exact, the stored value `round(255 * encode(x))`, found
//! from the 255 linear values where that rounding changes (a table of
//! 4096 buckets and one comparison), so that decoding then encoding gives
//! back each of the 256 values.
//!
//! ```
//! use rasterlab::raster::{linear_to_srgb8, srgb8_to_linear};
//!
//! assert_eq!(linear_to_srgb8(0.5), 188);
//! assert!((srgb8_to_linear(128) - 0.2158605).abs() < 1e-6);
//! assert!((0..=255).all(|v| linear_to_srgb8(srgb8_to_linear(v)) == v));
//! ```

use glam::Vec4;
use std::sync::LazyLock;

/// Where colours are mixed: in linear light or in their stored, encoded
/// values.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum MixSpace {
    /// Decode sRGB to linear light, mix, encode (the physically right
    /// mix; the default).
    #[default]
    Linear,
    /// Mix the sRGB-encoded values as numbers (what tiny-skia, most 2D
    /// libraries and a colour buffer without sRGB do).
    Encoded,
}

impl MixSpace {
    /// The names the command line takes: `linear`, `srgb`.
    pub const NAMES: [&'static str; 2] = ["linear", "srgb"];

    /// The space named `name` (`linear`, or `srgb` for the encoded values).
    pub fn from_name(name: &str) -> Result<MixSpace, String> {
        match name {
            "linear" => Ok(MixSpace::Linear),
            "srgb" | "encoded" => Ok(MixSpace::Encoded),
            _ => Err(format!(
                "unknown colour space `{name}`: expected one of {}",
                MixSpace::NAMES.join(", ")
            )),
        }
    }

    /// Its name, as [`from_name`](Self::from_name) takes it.
    pub fn name(self) -> &'static str {
        match self {
            MixSpace::Linear => "linear",
            MixSpace::Encoded => "srgb",
        }
    }

    /// An RGBA8 colour as the values the mix works on: linear light (or
    /// the encoded values) in `[0, 1]`, and alpha in `[0, 1]`.
    #[inline]
    pub fn decode(self, c: [u8; 4]) -> Vec4 {
        match self {
            MixSpace::Linear => Vec4::new(
                srgb8_to_linear(c[0]),
                srgb8_to_linear(c[1]),
                srgb8_to_linear(c[2]),
                f32::from(c[3]) / 255.0,
            ),
            MixSpace::Encoded => crate::raster::shader::from_rgba8(c),
        }
    }

    /// The RGBA8 colour of the mixed values `c` (clamped to `[0, 1]`):
    /// [`decode`](Self::decode)'s inverse, exact on its 256 values.
    #[inline]
    pub fn encode(self, c: Vec4) -> [u8; 4] {
        match self {
            MixSpace::Linear => {
                let alpha = crate::raster::shader::to_rgba8(Vec4::W * c.w)[3];
                [
                    linear_to_srgb8(c.x),
                    linear_to_srgb8(c.y),
                    linear_to_srgb8(c.z),
                    alpha,
                ]
            }
            MixSpace::Encoded => crate::raster::shader::to_rgba8(c),
        }
    }
}

/// The sRGB decoding of an encoded value `v` in `[0, 1]`, in `f64`.
fn decode_f64(v: f64) -> f64 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// The linear light of each stored value.
static DECODED: LazyLock<[f32; 256]> =
    LazyLock::new(|| std::array::from_fn(|v| decode_f64(v as f64 / 255.0) as f32));

/// `THRESHOLDS[k]`, for `k` in 1..=255, is the linear value from which
/// the stored value is at least `k`: the decoding of `(k - 1/2) / 255`.
/// Entry 0 is minus infinity, so that a search always lands.
static THRESHOLDS: LazyLock<[f32; 256]> = LazyLock::new(|| {
    std::array::from_fn(|k| {
        if k == 0 {
            f32::NEG_INFINITY
        } else {
            decode_f64((k as f64 - 0.5) / 255.0) as f32
        }
    })
});

/// The linear light of the stored sRGB value `v`, in `[0, 1]`.
#[inline]
pub fn srgb8_to_linear(v: u8) -> f32 {
    DECODED[usize::from(v)]
}

/// Buckets of [`linear_to_srgb8`]'s table: the linear range `[0, 1]` cut
/// into this many equal parts. Thresholds lie at least `1 / (12.92 *
/// 255)`, about 1/3366, apart (the slope of the transfer function's
/// linear toe is its smallest), so a bucket of 1/4096 holds at most one.
const BUCKETS: usize = 4096;

/// The stored value at the lower end of each bucket: the number of
/// thresholds at or below `b / BUCKETS`.
static BUCKET_CODES: LazyLock<[u8; BUCKETS]> = LazyLock::new(|| {
    std::array::from_fn(|b| {
        let x = b as f32 / BUCKETS as f32;
        THRESHOLDS[1..].iter().take_while(|t| **t <= x).count() as u8
    })
});

/// The stored sRGB value of linear light `x`: `round(255 * encode(x))`,
/// `x` clamped to `[0, 1]`, NaN giving 0.
///
/// The value at the lower end of `x`'s bucket, plus one if `x` reaches
/// the one threshold the bucket may hold: a lookup and a comparison,
/// exact on every threshold the table was built from.
#[inline]
pub fn linear_to_srgb8(x: f32) -> u8 {
    // NaN fails both comparisons and lands in bucket 0, below every
    // threshold: 0.
    let x = if x > 1.0 {
        1.0
    } else if x >= 0.0 {
        x
    } else {
        0.0
    };
    let bucket = ((x * BUCKETS as f32) as usize).min(BUCKETS - 1);
    let code = BUCKET_CODES[bucket];
    let next = THRESHOLDS[usize::from(code).min(254) + 1];
    code + u8::from(code < 255 && x >= next)
}

/// [`linear_to_srgb8`] by a binary search of all 255 thresholds: the
/// plain form the table is checked against.
#[cfg(test)]
fn linear_to_srgb8_searched(x: f32) -> u8 {
    let thresholds = &*THRESHOLDS;
    let mut k = 0usize;
    for step in [128, 64, 32, 16, 8, 4, 2, 1] {
        if x >= thresholds[k + step] {
            k += step;
        }
    }
    k as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The encoding against the transfer function computed in `f64`, on a
    /// fine sweep of linear values: the same stored value, but where the
    /// value lies within `f32` rounding of a threshold.
    #[test]
    fn encoding_rounds_the_transfer_function() {
        fn encode_f64(x: f64) -> f64 {
            if x <= 0.0031308 {
                x * 12.92
            } else {
                1.055 * x.powf(1.0 / 2.4) - 0.055
            }
        }
        let mut mismatches = 0;
        for i in 0..=100_000 {
            let x = i as f32 / 100_000.0;
            let exact = (255.0 * encode_f64(x as f64)).round() as u8;
            if linear_to_srgb8(x) != exact {
                mismatches += 1;
            }
        }
        assert_eq!(mismatches, 0);
        // The table against the search, at every threshold and either
        // side of it, and on a sweep finer than the buckets.
        for &t in &THRESHOLDS[1..] {
            for x in [t, t.next_down(), t.next_up()] {
                assert_eq!(linear_to_srgb8(x), linear_to_srgb8_searched(x), "{x}");
            }
        }
        for i in 0..=1_000_000 {
            let x = i as f32 / 1_000_000.0;
            assert_eq!(linear_to_srgb8(x), linear_to_srgb8_searched(x), "{x}");
        }
        assert_eq!(linear_to_srgb8(-1.0), 0);
        assert_eq!(linear_to_srgb8(2.0), 255);
        assert_eq!(linear_to_srgb8(f32::NAN), 0);
        assert_eq!(linear_to_srgb8(f32::INFINITY), 255);
    }

    /// Every stored value survives a round trip through linear light, in
    /// both spaces, alpha included.
    #[test]
    fn every_stored_value_round_trips() {
        for v in 0..=255u8 {
            for space in [MixSpace::Linear, MixSpace::Encoded] {
                let c = [v, 255 - v, v / 2, v];
                assert_eq!(space.encode(space.decode(c)), c, "{space:?} {v}");
            }
        }
        // Linear light rises with the stored value.
        assert!((1..=255).all(|v| srgb8_to_linear(v) > srgb8_to_linear(v - 1)));
    }

    /// The names the command line takes, and a clear refusal.
    #[test]
    fn spaces_are_named() {
        for name in MixSpace::NAMES {
            assert_eq!(MixSpace::from_name(name).unwrap().name(), name);
        }
        let error = MixSpace::from_name("rgb").unwrap_err();
        assert!(error.contains("linear, srgb"), "{error}");
    }
}

//! The level of detail: how many texels a pixel covers, and which mip
//! levels that picks.
//!
//! With `u` and `v` in texels of level 0 (the texture coordinate times the
//! texture's width and height), the OpenGL 3.3 specification (section
//! 3.8.11, equation 3.17, without its third coordinate) takes the longer
//! of the two screen-space derivative vectors,
//!
//! ```text
//! rho = max( sqrt((du/dx)^2 + (dv/dx)^2), sqrt((du/dy)^2 + (dv/dy)^2) )
//! lambda = log2(rho)
//! ```
//!
//! so one texel a pixel gives `lambda = 0`, two give 1, four give 2.
//! `lambda` is clamped to `[0, q]`, `q` the last level: where it is at or
//! below 0 the texture is magnified and level 0 is sampled with the pixel
//! filter. The level modes then read (CS184's `L_ZERO`, `L_NEAREST`,
//! `L_LINEAR`; OpenGL's `*_MIPMAP_NEAREST` and `*_MIPMAP_LINEAR`):
//!
//! * zero: level 0 always;
//! * nearest: level `ceil(lambda + 1/2) - 1`, OpenGL's nearest level
//!   (a level's own `lambda` plus or minus one half, ties to the finer);
//! * linear: levels `floor(lambda)` and the next, weighted by the fraction
//!   of `lambda`; with the bilinear pixel filter this is trilinear.
//!
//! Anisotropic filtering follows the example the EXT_texture_filter_anisotropic
//! extension gives: with `P_max` and `P_min` the longer and shorter
//! derivative vector's length in texels,
//! `N = min(ceil(P_max / P_min), max_anisotropy)` probes are taken along
//! the longer one, at `-1/2 + i / (N + 1)` of it for `i = 1..=N`, each at
//! `lambda = log2(P_max / N)`, and averaged.

use glam::Vec2;

/// The largest anisotropy accepted: 16 probes, as GPUs offer.
pub const MAX_ANISOTROPY: u32 = 16;

/// A pixel's footprint in the texture: the screen-space derivatives of
/// `(u, v)` in texels of level 0.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Footprint {
    /// `(du/dx, dv/dx)` in texels: one pixel to the right.
    pub dx: Vec2,
    /// `(du/dy, dv/dy)` in texels: one pixel down.
    pub dy: Vec2,
}

impl Footprint {
    /// The footprint of a texture of `width` x `height` texels for the
    /// derivatives `duv_dx` and `duv_dy` of its texture coordinate (whose
    /// 0 to 1 spans the texture). Non-finite derivatives count as zero.
    pub fn new(duv_dx: Vec2, duv_dy: Vec2, width: u32, height: u32) -> Footprint {
        let size = Vec2::new(width as f32, height as f32);
        let finite = |d: Vec2| if d.is_finite() { d * size } else { Vec2::ZERO };
        Footprint {
            dx: finite(duv_dx),
            dy: finite(duv_dy),
        }
    }

    /// `rho`: the longer derivative vector's length, in texels.
    pub fn rho(&self) -> f32 {
        self.dx.length().max(self.dy.length())
    }

    /// `lambda = log2(rho)`, not yet clamped: minus infinity for a footprint
    /// of zero.
    pub fn lambda(&self) -> f32 {
        log2(self.rho())
    }

    /// The extension's anisotropic probes for at most `max_anisotropy`
    /// (1 to [`MAX_ANISOTROPY`]; other values are clamped into it).
    pub fn probes(&self, max_anisotropy: u32) -> Probes {
        let max = max_anisotropy.clamp(1, MAX_ANISOTROPY);
        let (px, py) = (self.dx.length(), self.dy.length());
        let (p_max, p_min, axis) = if px >= py {
            (px, py, self.dx)
        } else {
            (py, px, self.dy)
        };
        if max == 1 || p_max == 0.0 || !p_max.is_finite() {
            return Probes {
                count: 1,
                lambda: log2(p_max),
                axis,
            };
        }
        // `P_min = 0` gives an infinite ratio: the most probes.
        let count = (p_max / p_min).ceil().min(max as f32) as u32;
        Probes {
            count,
            lambda: log2(p_max / count as f32),
            axis,
        }
    }
}

/// Where the anisotropic filter samples: `count` probes along `axis`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Probes {
    /// `N`, from 1 to [`MAX_ANISOTROPY`].
    pub count: u32,
    /// The level of detail of each probe, `log2(P_max / N)`, not yet
    /// clamped.
    pub lambda: f32,
    /// The longer derivative vector, in texels of level 0.
    pub axis: Vec2,
}

impl Probes {
    /// Probe `i`'s offset along [`axis`](Self::axis), for `i` in
    /// `1..=count`: `i / (N + 1) - 1/2`.
    pub fn offset(&self, i: u32) -> f32 {
        i as f32 / (self.count + 1) as f32 - 0.5
    }
}

/// How the mip levels are used (CS184's level sampling methods).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum LevelMode {
    /// Level 0 only: no mipmapping (CS184's `L_ZERO`).
    #[default]
    Zero,
    /// The level nearest `lambda` (`L_NEAREST`).
    Nearest,
    /// The two levels around `lambda`, blended (`L_LINEAR`).
    Linear,
}

crate::names::named_enum!(
    LevelMode,
    "mip level mode",
    Zero = "zero",
    Nearest = "nearest",
    Linear = "linear"
);

/// The levels one sample reads: `coarse` with weight `weight`, `fine`
/// with `1 - weight`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct LevelChoice {
    /// The finer level.
    pub fine: usize,
    /// The coarser level (`fine` when one level is read).
    pub coarse: usize,
    /// The coarser level's weight, in `[0, 1)`.
    pub weight: f32,
}

impl LevelMode {
    /// The levels read at level of detail `lambda` in a pyramid of
    /// `levels` levels; `lambda` is clamped to `[0, levels - 1]` and a NaN
    /// reads level 0.
    pub fn choose(self, lambda: f32, levels: usize) -> LevelChoice {
        let last = levels.saturating_sub(1);
        let lambda = if lambda.is_nan() {
            0.0
        } else {
            lambda.clamp(0.0, last as f32)
        };
        let one = |level: usize| LevelChoice {
            fine: level,
            coarse: level,
            weight: 0.0,
        };
        // `lambda` is now at least 0: truncation is the floor, and
        // neither it nor `ceil` calls the library, as `f32::floor` and
        // `f32::ceil` do where the build does not assume SSE4.1.
        match self {
            LevelMode::Zero => one(0),
            LevelMode::Nearest => one(ceil(lambda + 0.5).saturating_sub(1).min(last)),
            LevelMode::Linear => {
                let fine = (lambda as usize).min(last);
                let weight = lambda - fine as f32;
                if weight > 0.0 && fine < last {
                    LevelChoice {
                        fine,
                        coarse: fine + 1,
                        weight,
                    }
                } else {
                    one(fine)
                }
            }
        }
    }
}

/// The level of detail `lambda = log2(rho)` of `N` fragments whose
/// derivatives (in texture coordinates) are `dx[k]` and `dy[k]`, on a
/// texture of `width` x `height` texels: lane by lane the `lambda` that
/// [`Footprint::new`] then [`Footprint::probes`] with an anisotropy of 1
/// give, bit for bit, written as plain arithmetic over the lanes so that
/// it runs as vectors.
#[inline(always)]
pub fn isotropic_lambdas<const N: usize>(
    dx: &[Vec2; N],
    dy: &[Vec2; N],
    width: u32,
    height: u32,
) -> [f32; N] {
    let (w, h) = (width as f32, height as f32);
    let mut rho = [0.0f32; N];
    for k in 0..N {
        let length = |d: Vec2| {
            let (x, y) = if d.is_finite() {
                (d.x * w, d.y * h)
            } else {
                (0.0, 0.0)
            };
            (x * x + y * y).sqrt()
        };
        let (px, py) = (length(dx[k]), length(dy[k]));
        rho[k] = if px >= py { px } else { py };
    }
    let mut lambda = rho.map(log2_plain);
    for k in 0..N {
        if !is_plain(rho[k]) {
            lambda[k] = log2_rest(rho[k]);
        }
    }
    lambda
}

/// `log2(x)`, the level of detail's logarithm, within two units in the
/// last place of the exact value, and exact at powers of two (so one,
/// two and four texels a pixel give levels 0, 1 and 2 exactly).
///
/// Written without a branch or a library call for the values a footprint
/// has, positive, normal and finite, so that eight lanes of it run as
/// vectors: `x = 2^k m` with `m` in `[sqrt(1/2), sqrt(2))`, and
/// `ln m = 2 atanh(s)` for `s = (m - 1) / (m + 1)`, its series to `s^9`
/// (`|s| <= 0.172`: the next term is below `2^-25`). Zero, subnormal,
/// infinite and NaN values go to the library's `f32::log2`.
#[inline(always)]
pub fn log2(x: f32) -> f32 {
    if is_plain(x) {
        log2_plain(x)
    } else {
        log2_rest(x)
    }
}

/// Whether [`log2_plain`] takes `x`: positive, normal and finite.
#[inline(always)]
pub(crate) fn is_plain(x: f32) -> bool {
    (f32::MIN_POSITIVE..=f32::MAX).contains(&x)
}

/// [`log2`] of a positive, normal, finite `x`: plain arithmetic, the
/// same in a loop over lanes as alone.
#[inline(always)]
pub(crate) fn log2_plain(x: f32) -> f32 {
    // The bits of sqrt(1/2): subtracting them puts the exponent of
    // `x / sqrt(1/2)` in the top bits.
    const SQRT_HALF: i32 = 0x3f35_04f3;
    let shifted = x.to_bits() as i32 - SQRT_HALF;
    let k = shifted >> 23;
    let m = f32::from_bits(((shifted & 0x007f_ffff) + SQRT_HALF) as u32);
    let s = (m - 1.0) / (m + 1.0);
    let z = s * s;
    let series = 1.0 + z * (1.0 / 3.0 + z * (1.0 / 5.0 + z * (1.0 / 7.0 + z * (1.0 / 9.0))));
    k as f32 + (2.0 * std::f32::consts::LOG2_E) * s * series
}

/// [`log2`] of what [`log2_plain`] does not take: the library's.
#[cold]
pub(crate) fn log2_rest(x: f32) -> f32 {
    x.log2()
}

/// `x.ceil()` as a level, for `x` from 0 up to a pyramid's depth.
#[inline]
fn ceil(x: f32) -> usize {
    let whole = x as usize;
    whole + usize::from((whole as f32) < x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against `f64`'s logarithm over every binade: within two units in
    /// the last place of the result (or 2^-23 near 1, where the result
    /// nears zero), exact at powers of two, and the library's value
    /// where the plain arithmetic does not apply.
    #[test]
    fn log2_is_within_two_ulp_and_exact_at_powers_of_two() {
        let mut rng = fastrand::Rng::with_seed(3);
        let mut worst = 0.0f64;
        for i in 0..2_000_000 {
            let x = if i % 4 == 0 {
                1.0 + (rng.f32() - 0.5) * 1e-3
            } else {
                f32::from_bits(rng.u32(f32::MIN_POSITIVE.to_bits()..=f32::MAX.to_bits()))
            };
            let exact = f64::from(x).log2();
            let ulp = f64::from(f32::EPSILON) * exact.abs().max(1.0);
            let error = (f64::from(log2(x)) - exact).abs() / ulp;
            worst = worst.max(error);
            assert!(error <= 2.0, "log2({x:e}) = {} not {exact}", log2(x));
        }
        assert!(worst > 0.05, "the comparison compared nothing: {worst}");
        for k in -126..=127 {
            assert_eq!(log2(2f32.powi(k)), k as f32);
        }
        for x in [0.0, -0.0, 1e-40, f32::INFINITY, f32::NAN, -1.0] {
            assert_eq!(log2(x).to_bits(), x.log2().to_bits(), "{x}");
        }
    }

    /// Eight lanes at a time give each lane the `lambda` of its own
    /// footprint's probes, bit for bit: random derivatives, zero ones,
    /// ones that overflow to infinity, and non-finite ones.
    #[test]
    fn isotropic_lambdas_are_each_footprints_lambda_bit_for_bit() {
        let mut rng = fastrand::Rng::with_seed(4);
        let special = [0.0, -0.0, 1e38, f32::NAN, f32::INFINITY, 1e-30, 1e-45];
        for n in 0..50_000 {
            let mut d = || {
                let mut f = || match rng.u8(0..10) {
                    0 => special[rng.usize(0..special.len())],
                    _ => (rng.f32() - 0.5) * 10f32.powi(rng.i32(-6..3)),
                };
                Vec2::new(f(), f())
            };
            let dx: [Vec2; 8] = std::array::from_fn(|_| d());
            let dy: [Vec2; 8] = std::array::from_fn(|_| d());
            let (w, h) = (1 << (n % 12), 1 + n % 300);
            let lanes = isotropic_lambdas(&dx, &dy, w, h);
            for k in 0..8 {
                let one = Footprint::new(dx[k], dy[k], w, h).probes(1).lambda;
                assert_eq!(lanes[k].to_bits(), one.to_bits(), "{:?} {:?}", dx[k], dy[k]);
            }
        }
    }

    #[test]
    fn nearest_takes_the_level_within_a_half() {
        let level = |l: f32| LevelMode::Nearest.choose(l, 10).fine;
        assert_eq!(level(-3.0), 0);
        assert_eq!(level(0.5), 0);
        assert_eq!(level(0.51), 1);
        assert_eq!(level(1.5), 1);
        assert_eq!(level(1.6), 2);
        assert_eq!(level(100.0), 9);
        assert_eq!(level(f32::NAN), 0);
        assert_eq!(level(f32::INFINITY), 9);
    }

    #[test]
    fn linear_blends_the_two_levels_around_lambda() {
        let c = LevelMode::Linear.choose(1.25, 4);
        assert_eq!((c.fine, c.coarse, c.weight), (1, 2, 0.25));
        let c = LevelMode::Linear.choose(3.5, 4);
        assert_eq!((c.fine, c.coarse, c.weight), (3, 3, 0.0));
        let c = LevelMode::Linear.choose(f32::NEG_INFINITY, 4);
        assert_eq!((c.fine, c.coarse, c.weight), (0, 0, 0.0));
        assert_eq!(LevelMode::Zero.choose(7.0, 9).fine, 0);
    }

    /// The extension's example: a footprint 8 texels long and 1 wide takes
    /// 8 probes at level 0, or 4 at level 1 when at most 4 are allowed.
    #[test]
    fn anisotropic_probes_follow_the_extension() {
        let f = Footprint {
            dx: Vec2::new(8.0, 0.0),
            dy: Vec2::new(0.0, 1.0),
        };
        let p = f.probes(16);
        assert_eq!((p.count, p.lambda, p.axis), (8, 0.0, Vec2::new(8.0, 0.0)));
        let p = f.probes(4);
        assert_eq!((p.count, p.lambda), (4, 1.0));
        assert!((p.offset(1) + 0.3).abs() < 1e-6);
        assert!((p.offset(4) - 0.3).abs() < 1e-6);
        let line = Footprint {
            dx: Vec2::ZERO,
            dy: Vec2::new(3.0, 4.0),
        };
        assert_eq!(line.probes(16).count, 16);
        assert_eq!(line.probes(0).count, 1);
        let none = Footprint {
            dx: Vec2::ZERO,
            dy: Vec2::ZERO,
        };
        assert_eq!(none.probes(16).count, 1);
        assert_eq!(none.lambda(), f32::NEG_INFINITY);
    }
}

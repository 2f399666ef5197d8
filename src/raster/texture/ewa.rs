//! The elliptical weighted average (EWA), the second anisotropic filter:
//! Greene and Heckbert's (1986), as Heckbert's thesis (1989,
//! "Fundamentals of texture mapping and image warping") derives it and
//! pbrt (Pharr, Jakob and Humphreys, third edition, section 10.4.5)
//! implements it.
//!
//! A pixel's footprint in the texture is the ellipse the two derivative
//! vectors span. Rather than probing along its longer axis (the
//! extension's example, [`Footprint::probes`](super::Footprint::probes)),
//! EWA weights every texel inside the ellipse by a Gaussian of its
//! distance from the centre, measured in the ellipse's own metric:
//!
//! * the longer derivative vector is the major axis and the shorter the
//!   minor one; where the major is more than `max_anisotropy` times the
//!   minor, the minor is lengthened to `major / max_anisotropy`, which
//!   bounds the texels read;
//! * the level of detail is that of the minor axis, `lambda =
//!   log2(|minor|)` in texels of level 0, so the ellipse is a texel or two
//!   wide at its level; the level mode picks the levels as for the other
//!   filters, and each level read is filtered on its own (the pixel
//!   filter, nearest or bilinear, plays no part);
//! * on a level, with the axes `(du0, dv0)` and `(du1, dv1)` in its
//!   texels, the ellipse is `A u^2 + B u v + C v^2 < 1` around the sample
//!   point, where `A = (dv0^2 + dv1^2 + 1) / F`, `B = -2 (du0 dv0 + du1
//!   dv1) / F`, `C = (du0^2 + du1^2 + 1) / F` and `F = A' C' - B'^2 / 4`
//!   of the unscaled ones: the `+ 1` widens it by a texel each way, the
//!   reconstruction filter, so that it always holds a texel;
//! * a texel whose centre is at `r^2 = A u^2 + B u v + C v^2 < 1` weighs
//!   `exp(-2 r^2) - exp(-2)` (a Gaussian brought to zero at the ellipse's
//!   edge), read from a table of [`WEIGHTS`] entries as pbrt does; the
//!   level's colour is the weighted mean; on the last level, 1x1, the
//!   one texel.
//!
//! The level mode must read the pyramid: on level 0 alone (level mode
//! zero) the ellipse of a pixel near the horizon holds thousands of
//! texels, which is why the pyramid was invented; [`Sampler::check`](super::Sampler::check)
//! refuses that pairing (as `render` and `explain` do), and
//! [`Texture::sample_ewa`] given it takes its time.

use super::{Image, LevelMode, Texture, Wrap};
use glam::{Vec2, Vec4};
use std::sync::OnceLock;

/// Entries in the weight table, over `r^2` from 0 to 1.
pub const WEIGHTS: usize = 128;

/// `exp(-2 r^2) - exp(-2)` at `r^2 = i / (WEIGHTS - 1)`.
fn weight_table() -> &'static [f32; WEIGHTS] {
    static TABLE: OnceLock<[f32; WEIGHTS]> = OnceLock::new();
    TABLE.get_or_init(|| {
        std::array::from_fn(|i| {
            let r2 = i as f32 / (WEIGHTS - 1) as f32;
            (-2.0 * r2).exp() - (-2.0f32).exp()
        })
    })
}

/// The ellipse of one lookup: its axes in texels of level 0, the minor
/// one lengthened to bound the eccentricity.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Ellipse {
    /// The major axis.
    pub major: Vec2,
    /// The minor axis.
    pub minor: Vec2,
}

impl Ellipse {
    /// The ellipse of the derivative vectors `dx` and `dy` (in texels of
    /// level 0), its eccentricity at most `max_anisotropy` (at least 1).
    pub fn new(dx: Vec2, dy: Vec2, max_anisotropy: u32) -> Ellipse {
        let (mut major, mut minor) = if dx.length_squared() >= dy.length_squared() {
            (dx, dy)
        } else {
            (dy, dx)
        };
        let max = max_anisotropy.max(1) as f32;
        let (long, short) = (major.length(), minor.length());
        if short * max < long && short > 0.0 {
            minor *= long / (short * max);
        }
        if !major.is_finite() || !minor.is_finite() {
            (major, minor) = (Vec2::ZERO, Vec2::ZERO);
        }
        Ellipse { major, minor }
    }

    /// The level of detail, `log2` of the minor axis's length (minus
    /// infinity for a footprint of zero).
    pub fn lambda(&self) -> f32 {
        self.minor.length().log2()
    }

    /// The weighted mean of `image`'s texels inside the ellipse around
    /// `uv`, the axes scaled to its texels (`scale`: its size over level
    /// 0's); with the number of texels weighted.
    pub fn filter(&self, image: &Image, uv: Vec2, scale: Vec2, wrap: Wrap) -> (Vec4, u32) {
        // Past the pyramid's end the ellipse can cover the one texel of
        // the last level many times over: its mean is that texel.
        if image.width() == 1 && image.height() == 1 {
            return (image.texel(0, 0), 1);
        }
        let size = Vec2::new(image.width() as f32, image.height() as f32);
        let centre = uv * size - 0.5;
        let (a0, a1) = (self.major * scale, self.minor * scale);
        let a = a0.y * a0.y + a1.y * a1.y + 1.0;
        let b = -2.0 * (a0.x * a0.y + a1.x * a1.y);
        let c = a0.x * a0.x + a1.x * a1.x + 1.0;
        let f = a * c - b * b * 0.25;
        let (a, b, c) = (a / f, b / f, c / f);
        // The ellipse's bounding box: half-sides sqrt(C F') and sqrt(A F')
        // of the normalised form, 2 sqrt(det C) / det and 2 sqrt(det A) / det.
        let det = 4.0 * a * c - b * b;
        let (half_u, half_v) = (2.0 * (det * c).sqrt() / det, 2.0 * (det * a).sqrt() / det);
        let (u0, u1) = (
            (centre.x - half_u).ceil() as i64,
            (centre.x + half_u).floor() as i64,
        );
        let (v0, v1) = (
            (centre.y - half_v).ceil() as i64,
            (centre.y + half_v).floor() as i64,
        );
        let table = weight_table();
        let (mut sum, mut total, mut count) = (Vec4::ZERO, 0.0f32, 0u32);
        for v in v0..=v1 {
            let dv = v as f32 - centre.y;
            for u in u0..=u1 {
                let du = u as f32 - centre.x;
                let r2 = a * du * du + b * du * dv + c * dv * dv;
                if r2 < 1.0 {
                    let w = table[((r2 * WEIGHTS as f32) as usize).min(WEIGHTS - 1)];
                    let texel =
                        image.texel(wrap.index(u, image.width()), wrap.index(v, image.height()));
                    sum += texel * w;
                    total += w;
                    count += 1;
                }
            }
        }
        if total > 0.0 {
            (sum / total, count)
        } else {
            // No texel centre weighed anything (a non-finite coordinate):
            // the texel under the point.
            let (x, y) = (centre.x.round() as i64, centre.y.round() as i64);
            let i = (wrap.index(x, image.width()), wrap.index(y, image.height()));
            (image.texel(i.0, i.1), 1)
        }
    }
}

impl Texture {
    /// The texture at `uv` by the elliptical weighted average of the
    /// footprint `dx`, `dy` (in texels of level 0), at most
    /// `max_anisotropy` times longer than wide, on the levels `levels`
    /// picks for the minor axis.
    pub fn sample_ewa(
        &self,
        uv: Vec2,
        (dx, dy): (Vec2, Vec2),
        max_anisotropy: u32,
        levels: LevelMode,
        wrap: Wrap,
    ) -> Vec4 {
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        let ellipse = Ellipse::new(dx, dy, max_anisotropy);
        let choice = levels.choose(ellipse.lambda(), self.levels.len());
        let level0 = Vec2::new(self.width() as f32, self.height() as f32);
        let at = |level: usize| {
            let image = &self.levels[level];
            let scale = Vec2::new(image.width() as f32, image.height() as f32) / level0;
            ellipse.filter(image, uv, scale, wrap).0
        };
        let fine = at(choice.fine);
        if choice.coarse == choice.fine {
            fine
        } else {
            fine.lerp(at(choice.coarse), choice.weight)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::texture::Image;

    /// The weights fall from 1 - e^-2 at the centre to 0 at the edge.
    #[test]
    fn the_weights_fall_to_zero_at_the_edge() {
        let t = weight_table();
        assert!((t[0] - (1.0 - (-2.0f32).exp())).abs() < 1e-6);
        assert!(t[WEIGHTS - 1].abs() < 1e-6);
        assert!(t.windows(2).all(|w| w[0] > w[1]));
    }

    /// A uniform texture filters to its colour under any ellipse; a
    /// footprint of one texel reads a few texels around the point; a long
    /// one is bounded by the anisotropy.
    #[test]
    fn the_ellipse_weighs_the_texels_inside_it() {
        let grey = Vec4::new(0.25, 0.5, 0.75, 1.0);
        let image = Image::new(16, 16, vec![grey; 256]).unwrap();
        let one = Ellipse::new(Vec2::X, Vec2::Y, 16);
        let (c, n) = one.filter(&image, Vec2::splat(0.5), Vec2::ONE, Wrap::Repeat);
        assert!((c - grey).abs().max_element() < 1e-6);
        assert!((4..=16).contains(&n), "{n}");
        let long = Ellipse::new(Vec2::new(12.0, 0.0), Vec2::new(0.0, 0.5), 4);
        assert_eq!(long.minor, Vec2::new(0.0, 3.0));
        assert!((long.lambda() - 3f32.log2()).abs() < 1e-6);
        let (_, n) = long.filter(&image, Vec2::splat(0.5), Vec2::ONE, Wrap::Repeat);
        assert!(n > 30, "{n}");
        let none = Ellipse::new(Vec2::ZERO, Vec2::ZERO, 16);
        assert_eq!(none.lambda(), f32::NEG_INFINITY);
        let (c, _) = none.filter(&image, Vec2::splat(0.5), Vec2::ONE, Wrap::Repeat);
        assert_eq!(c, grey);
    }
}

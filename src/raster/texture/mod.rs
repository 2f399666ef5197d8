//! Textures as the courses teach them: texel addressing, the pixel
//! filters, the mip pyramid, the level of detail and anisotropic
//! filtering.
//!
//! * A texture coordinate `(s, t)` runs from `(0, 0)`, the top-left corner
//!   of texel `(0, 0)`, to `(1, 1)`, the bottom-right corner of the last
//!   texel; `u = s * width` and `v = t * height` are in texels, and texel
//!   centres sit at half-integers.
//! * Outside `[0, 1)` a [`Wrap`] mode picks the texel: repeat, clamp to
//!   the edge, or mirrored repeat (OpenGL 3.3, section 3.8.10).
//! * A [`Filter`] reads one level: nearest takes the texel containing
//!   `(u, v)`; bilinear blends the four texels whose centres surround it.
//! * The mip pyramid (Williams 1983, "Pyramidal parametrics") is built
//!   once, when the [`Texture`] is made: each level box-filtered from the
//!   one before, down to 1x1, odd sides as the [`pyramid`] module states.
//! * The level of detail `lambda = log2(rho)` comes from the screen-space
//!   derivatives of the texture coordinate (OpenGL 3.3, section 3.8.11),
//!   and a [`LevelMode`] reads level 0, the nearest level, or the two
//!   levels around `lambda` (linear; trilinear with the bilinear filter).
//!   See [`lod`].
//! * Anisotropic filtering takes several probes along the footprint's
//!   longer axis, as the EXT_texture_filter_anisotropic extension's
//!   example does ([`Footprint::probes`]), or weighs every texel of the
//!   footprint's ellipse, Heckbert's elliptical weighted average
//!   ([`ewa`]); [`Anisotropic`] chooses.
//!
//! ```
//! use glam::{Vec2, Vec4};
//! use rasterlab::raster::{Anisotropic, Filter, LevelMode, Sampler, Texture, Wrap};
//!
//! // A 4x4 checkerboard of single texels: its 1x1 level is their average.
//! let (black, white) = (Vec4::new(0.0, 0.0, 0.0, 1.0), Vec4::ONE);
//! let texture = Texture::checkerboard(4, 1, black, white);
//! assert_eq!(texture.levels().len(), 3);
//! let sampler = Sampler {
//!     filter: Filter::Bilinear,
//!     levels: LevelMode::Linear,
//!     wrap: Wrap::Repeat,
//!     anisotropy: 1,
//!     anisotropic: Anisotropic::Probes,
//! };
//! // Four texels a pixel: lambda = 2, the last level, grey.
//! let d = 4.0 / 4.0;
//! let grey = texture.sample_grad(Vec2::splat(0.3), Vec2::new(d, 0.0), Vec2::new(0.0, d), &sampler);
//! assert!((grey - Vec4::new(0.5, 0.5, 0.5, 1.0)).abs().max_element() < 1e-6);
//! ```

pub mod ewa;
pub mod lod;
pub mod pyramid;

use crate::error::{Error, Result};
pub use ewa::Ellipse;
use glam::{Vec2, Vec4};
pub use lod::{isotropic_lambdas, Footprint, LevelChoice, LevelMode, Probes, MAX_ANISOTROPY};

/// The longest side a texture may have, in texels.
pub const MAX_TEXTURE_SIDE: u32 = 16384;

/// The most texels level 0 may have (4096 x 4096; 256 MiB of `f32` RGBA).
pub const MAX_TEXTURE_TEXELS: u64 = 1 << 24;

/// How a texture is sampled between texel centres.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Filter {
    /// The texel containing the sample point.
    Nearest,
    /// The four nearest texels, weighted by distance.
    #[default]
    Bilinear,
}

crate::names::named_enum!(
    Filter,
    "texture filter",
    Nearest = "nearest",
    Bilinear = "bilinear"
);

/// Which texel a coordinate outside the texture reads (OpenGL 3.3,
/// section 3.8.10), applied to each texel index a filter reads.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Wrap {
    /// The texture tiles the plane: index `i` reads `i mod n`.
    #[default]
    Repeat,
    /// Indices past an edge read the edge texel.
    ClampToEdge,
    /// The texture tiles the plane mirrored every other copy: indices
    /// `n` to `2n - 1` read `n - 1` down to `0`.
    MirroredRepeat,
}

crate::names::named_enum!(
    Wrap,
    "texture wrap mode",
    Repeat = "repeat",
    ClampToEdge = "clamp",
    MirroredRepeat = "mirror"
);

impl Wrap {
    /// The texel index in `0..n` that index `i` reads.
    #[inline]
    pub fn index(self, i: i64, n: u32) -> u32 {
        let n = i64::from(n);
        // A side of a power of two (the usual one) wraps by a mask, which
        // is the Euclidean remainder in two's complement, without the
        // division.
        let wrap = |i: i64, n: i64| {
            if n & (n - 1) == 0 {
                i & (n - 1)
            } else {
                i.rem_euclid(n)
            }
        };
        let k = match self {
            Wrap::Repeat => wrap(i, n),
            Wrap::ClampToEdge => i.clamp(0, n - 1),
            Wrap::MirroredRepeat => {
                let k = wrap(i, 2 * n);
                if k < n {
                    k
                } else {
                    2 * n - 1 - k
                }
            }
        };
        k as u32
    }
}

/// How a footprint longer than it is wide is filtered.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Anisotropic {
    /// Up to `anisotropy` probes along the longer axis, each filtered as
    /// the level mode and pixel filter say (the extension's example).
    #[default]
    Probes,
    /// The elliptical weighted average ([`ewa`]): every texel of the
    /// ellipse, Gaussian-weighted, on the levels of its minor axis.
    Ewa,
}

crate::names::named_enum!(
    Anisotropic,
    "anisotropic filter",
    Probes = "probes",
    Ewa = "ewa"
);

/// How [`Texture::sample_grad`] samples: the pixel filter, the level mode,
/// the wrap mode, the most anisotropy and how it is filtered.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Sampler {
    /// Nearest or bilinear, within a level.
    pub filter: Filter,
    /// Which levels are read.
    pub levels: LevelMode,
    /// Addressing outside the texture.
    pub wrap: Wrap,
    /// The most probes of the anisotropic filter, 1 (isotropic) to
    /// [`MAX_ANISOTROPY`].
    pub anisotropy: u32,
    /// The extension's probes, or EWA (which reads no pixel filter).
    pub anisotropic: Anisotropic,
}

impl Sampler {
    /// An error unless the sampler is one the commands draw with: an
    /// anisotropy of 1 to [`MAX_ANISOTROPY`], and EWA only on the mip
    /// levels (not with [`LevelMode::Zero`]; see [`ewa`]).
    pub fn check(&self) -> Result<()> {
        if !(1..=MAX_ANISOTROPY).contains(&self.anisotropy) {
            return Err(Error::InvalidArgument(format!(
                "anisotropy must be between 1 and {MAX_ANISOTROPY}, not {}",
                self.anisotropy
            )));
        }
        if self.anisotropic == Anisotropic::Ewa && self.levels == LevelMode::Zero {
            return Err(Error::InvalidArgument(
                "--anisotropic ewa filters from the mip pyramid: give --mip nearest or linear"
                    .into(),
            ));
        }
        Ok(())
    }
}

impl Default for Sampler {
    /// Bilinear, level 0 only, repeating, isotropic: the texture as it
    /// was sampled before mipmaps.
    fn default() -> Self {
        Sampler {
            filter: Filter::Bilinear,
            levels: LevelMode::Zero,
            wrap: Wrap::Repeat,
            anisotropy: 1,
            anisotropic: Anisotropic::Probes,
        }
    }
}

/// One level of a texture: RGBA texels in row-major order.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    width: u32,
    height: u32,
    texels: Vec<Vec4>,
}

fn invalid(width: u64, height: u64, reason: String) -> Error {
    Error::InvalidTexture {
        width,
        height,
        reason,
    }
}

/// An error unless `width` x `height` is a size a texture may have.
fn check_size(width: u32, height: u32) -> Result<()> {
    let (w, h) = (u64::from(width), u64::from(height));
    if width == 0 || height == 0 {
        return Err(invalid(w, h, "both sides must be at least 1 texel".into()));
    }
    if width.max(height) > MAX_TEXTURE_SIDE {
        let reason = format!("a side is longer than {MAX_TEXTURE_SIDE} texels");
        return Err(invalid(w, h, reason));
    }
    if w * h > MAX_TEXTURE_TEXELS {
        let reason = format!("it has more than {MAX_TEXTURE_TEXELS} texels");
        return Err(invalid(w, h, reason));
    }
    Ok(())
}

impl Image {
    /// An image from texels in row-major order. An error when a side is
    /// zero or over [`MAX_TEXTURE_SIDE`], when there are more than
    /// [`MAX_TEXTURE_TEXELS`], or when `texels` does not fill the image.
    pub fn new(width: u32, height: u32, texels: Vec<Vec4>) -> Result<Image> {
        check_size(width, height)?;
        let (w, h) = (u64::from(width), u64::from(height));
        if texels.len() as u64 != w * h {
            let reason = format!("{} texels were given for {}", texels.len(), w * h);
            return Err(invalid(w, h, reason));
        }
        Ok(Image {
            width,
            height,
            texels,
        })
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The texels, row by row.
    pub fn texels(&self) -> &[Vec4] {
        &self.texels
    }

    /// Texel `(x, y)`, which must lie in the image.
    #[inline]
    pub fn texel(&self, x: u32, y: u32) -> Vec4 {
        self.texels[y as usize * self.width as usize + x as usize]
    }

    #[inline]
    fn fetch(&self, x: i64, y: i64, wrap: Wrap) -> Vec4 {
        self.texel(wrap.index(x, self.width), wrap.index(y, self.height))
    }

    /// The image sampled at `uv` with `filter`, addressed by `wrap`.
    /// Non-finite coordinates sample `(0, 0)`.
    pub fn sample(&self, uv: Vec2, filter: Filter, wrap: Wrap) -> Vec4 {
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        let u = f64::from(uv.x) * f64::from(self.width);
        let v = f64::from(uv.y) * f64::from(self.height);
        match filter {
            Filter::Nearest => self.fetch(floor(u) as i64, floor(v) as i64, wrap),
            Filter::Bilinear => {
                // Texel centres sit at half-integers.
                let (u, v) = (u - 0.5, v - 0.5);
                let (x0, y0) = (floor(u), floor(v));
                let (fx, fy) = ((u - x0) as f32, (v - y0) as f32);
                let (x0, y0) = (x0 as i64, y0 as i64);
                // Each of the two columns and two rows wrapped once.
                let [left, right] = [x0, x0 + 1].map(|x| wrap.index(x, self.width) as usize);
                let [above, below] =
                    [y0, y0 + 1].map(|y| wrap.index(y, self.height) as usize * self.width as usize);
                let texel = |row: usize, column: usize| self.texels[row + column];
                let top = texel(above, left).lerp(texel(above, right), fx);
                let bottom = texel(below, left).lerp(texel(below, right), fx);
                top.lerp(bottom, fy)
            }
        }
    }
}

/// `x.floor()`, the same value, without the library call `f64::floor`
/// becomes where the build does not assume SSE4.1: below 2^52 in
/// magnitude, truncation then one step down for a negative fraction.
#[inline]
fn floor(x: f64) -> f64 {
    if x.abs() < 4_503_599_627_370_496.0 {
        let t = x as i64 as f64;
        if t > x {
            t - 1.0
        } else {
            // -0.5 < x <= -0.0 truncates to +0.0; floor keeps the sign.
            t.copysign(x)
        }
    } else {
        x.floor()
    }
}

/// An RGBA texture with its mip pyramid, level 0 first.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    levels: Vec<Image>,
}

impl Texture {
    /// A texture from texels in row-major order, its pyramid built; the
    /// errors of [`Image::new`].
    pub fn new(width: u32, height: u32, texels: Vec<Vec4>) -> Result<Texture> {
        Ok(Texture::from_image(Image::new(width, height, texels)?))
    }

    /// A texture whose level 0 is `image`, its pyramid built.
    pub fn from_image(image: Image) -> Texture {
        let mut levels = vec![image];
        while let Some(last) = levels.last().filter(|l| l.width > 1 || l.height > 1) {
            let next = pyramid::next_level(last);
            levels.push(next);
        }
        Texture { levels }
    }

    /// A texture read from an image file (PNG), its pyramid built: each
    /// 8-bit channel `c` becomes `c / 255`, as the shaders read an RGBA8
    /// colour. Errors: an unreadable or undecodable file (naming
    /// it), and the sizes [`Image::new`] refuses, checked from the file's
    /// header before any texel is decoded.
    pub fn load(path: &std::path::Path) -> Result<Texture> {
        let parse = |e: image::ImageError| Error::Parse {
            path: path.to_path_buf(),
            line: None,
            message: e.to_string(),
        };
        let (width, height) = image::image_dimensions(path).map_err(|e| match e {
            image::ImageError::IoError(io) => Error::io(path, &io),
            other => parse(other),
        })?;
        // The size first: a header claiming a huge image decodes nothing.
        check_size(width, height)?;
        let rgba = image::open(path).map_err(parse)?.to_rgba8();
        let texels = rgba
            .pixels()
            .map(|p| Vec4::from_array(p.0.map(f32::from)) / 255.0)
            .collect();
        Texture::new(rgba.width(), rgba.height(), texels)
    }

    /// A texture with levels of its own (as Scotty3D's tests give them):
    /// an error unless their sizes are those the pyramid rule gives for
    /// the first, down to 1x1.
    pub fn from_levels(levels: Vec<Image>) -> Result<Texture> {
        let Some(first) = levels.first() else {
            return Err(invalid(0, 0, "it has no level".into()));
        };
        let (w, h) = (u64::from(first.width), u64::from(first.height));
        let sizes = pyramid::sizes(first.width, first.height);
        let given: Vec<(u32, u32)> = levels.iter().map(|l| (l.width, l.height)).collect();
        if given != sizes {
            let reason = format!("its levels are {given:?}, the pyramid rule gives {sizes:?}");
            return Err(invalid(w, h, reason));
        }
        Ok(Texture { levels })
    }

    /// A `squares` x `squares` checkerboard of two colours, each square
    /// `texels` texels wide (a side of at most 4096 texels).
    pub fn checkerboard(squares: u32, texels: u32, a: Vec4, b: Vec4) -> Texture {
        let square = texels.max(1);
        let side = squares.saturating_mul(square).clamp(1, 4096);
        let texels = (0..side * side)
            .map(|i| {
                let (x, y) = (i % side, i / side);
                if (x / square + y / square).is_multiple_of(2) {
                    a
                } else {
                    b
                }
            })
            .collect();
        Texture::from_image(Image {
            width: side,
            height: side,
            texels,
        })
    }

    /// Width of level 0 in texels.
    pub fn width(&self) -> u32 {
        self.levels[0].width
    }

    /// Height of level 0 in texels.
    pub fn height(&self) -> u32 {
        self.levels[0].height
    }

    /// The pyramid, level 0 first, down to 1x1.
    pub fn levels(&self) -> &[Image] {
        &self.levels
    }

    /// Level 0 sampled at `uv` with `filter`, repeating outside.
    pub fn sample(&self, uv: Vec2, filter: Filter) -> Vec4 {
        self.levels[0].sample(uv, filter, Wrap::Repeat)
    }

    /// The texture sampled at `uv` at level of detail `lambda` (GLSL's
    /// `textureLod`): the levels `sampler`'s level mode chooses, each
    /// with its pixel filter, blended by the level weight.
    pub fn sample_lod(&self, uv: Vec2, lambda: f32, sampler: &Sampler) -> Vec4 {
        let c = sampler.levels.choose(lambda, self.levels.len());
        let fine = self.levels[c.fine].sample(uv, sampler.filter, sampler.wrap);
        if c.coarse == c.fine {
            fine
        } else {
            let coarse = self.levels[c.coarse].sample(uv, sampler.filter, sampler.wrap);
            fine.lerp(coarse, c.weight)
        }
    }

    /// The texture sampled at `uv` whose screen-space derivatives are
    /// `duv_dx` and `duv_dy` (GLSL's `textureGrad`): the level of detail
    /// from them, and with an anisotropy above 1, the extension's probes
    /// along the longer one, averaged; or the elliptical weighted average
    /// of the footprint ([`Anisotropic::Ewa`]).
    pub fn sample_grad(&self, uv: Vec2, duv_dx: Vec2, duv_dy: Vec2, sampler: &Sampler) -> Vec4 {
        let footprint = Footprint::new(duv_dx, duv_dy, self.width(), self.height());
        if sampler.anisotropic == Anisotropic::Ewa {
            let axes = (footprint.dx, footprint.dy);
            return self.sample_ewa(uv, axes, sampler.anisotropy, sampler.levels, sampler.wrap);
        }
        let probes = footprint.probes(sampler.anisotropy);
        if probes.count == 1 {
            return self.sample_lod(uv, probes.lambda, sampler);
        }
        let size = Vec2::new(self.width() as f32, self.height() as f32);
        let axis = probes.axis / size;
        let mut sum = Vec4::ZERO;
        for i in 1..=probes.count {
            sum += self.sample_lod(uv + axis * probes.offset(i), probes.lambda, sampler);
        }
        sum / probes.count as f32
    }
}

#[cfg(test)]
mod tests;

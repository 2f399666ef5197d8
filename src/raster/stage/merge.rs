//! Step 7 of the stage, the **merge**: where a fragment's colour and depth
//! are written into its pixel, the one place in the crate that does so.
//!
//! Direct3D calls this step the output merger, OpenGL the per-fragment
//! operations after the depth test, and the rasterization slides "update
//! the frame buffer". Every path of the stage ends in [`merge`]: the
//! scalar reference path one pixel at a time, the span loops a group of
//! eight, the lines, the multisampled stage one sample at a time, and the
//! straight-to-the-target line loop of the benchmarks. A blend mode is one
//! variant of [`BlendMode`] and one arm of [`BlendMode::mix`]; what comes
//! before the merge (which pixels pass, at what depth) and after it (the
//! clears of `target`, the multisample resolve) are separate steps.
//!
//! A fragment's colour reaches the merge as RGBA8, sRGB-encoded like the
//! pixel's (the span loops store it so, once a triangle or a group of
//! eight). A fragment that covers its whole pixel under
//! [`BlendMode::Replace`] is copied; any other is mixed: both colours
//! decoded to the [`MixSpace`] (linear light by default), mixed by
//! [`BlendMode::mix`], encoded again, and the channels the write mask
//! leaves out kept as they were.

use crate::raster::shader::to_rgba8;
use crate::raster::srgb::MixSpace;
use glam::Vec4;

/// How a fragment's colour `s` meets the colour `d` already in its pixel
/// (the blend equation of the graphics APIs), both as `[0, 1]` values of
/// the mix space, alpha last. A fragment that covers only `coverage` of
/// its pixel (an anti-aliased line's) counts as that much less opaque.
///
/// The colour buffer holds **premultiplied** colour, as Scotty3D's does:
/// its colour is already scaled by its alpha. A target cleared to opaque
/// black (alpha 1) stays opaque under every mode but `add` and `multiply`.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum BlendMode {
    /// `s` replaces `d`; a partial fragment is mixed by coverage,
    /// `s * coverage + d * (1 - coverage)`.
    #[default]
    Replace,
    /// The fragment's colour scaled by its opacity is added:
    /// `rgb = d.rgb + s.rgb * s.a`, `a = d.a + s.a` (Scotty3D's
    /// `Pipeline_Blend_Add`; OpenGL's `SRC_ALPHA, ONE`), clamped to 1.
    Add,
    /// Porter and Duff's (1984) `over` of a premultiplied fragment:
    /// `s + d * (1 - s.a)` on all four channels (OpenGL's `ONE,
    /// ONE_MINUS_SRC_ALPHA`).
    Over,
    /// `over` of a straight (not premultiplied) fragment into the
    /// premultiplied buffer: `rgb = s.rgb * s.a + d.rgb * (1 - s.a)`,
    /// `a = s.a + d.a * (1 - s.a)` (Scotty3D's `Pipeline_Blend_Over`;
    /// OpenGL's `SRC_ALPHA, ONE_MINUS_SRC_ALPHA` on colour).
    OverStraight,
    /// `s * d` on all four channels: a filter that only darkens (OpenGL's
    /// `DST_COLOR, ZERO`).
    Multiply,
}

impl BlendMode {
    /// Every mode, in the order of [`NAMES`](Self::NAMES).
    pub const ALL: [BlendMode; 5] = [
        BlendMode::Replace,
        BlendMode::Add,
        BlendMode::Over,
        BlendMode::OverStraight,
        BlendMode::Multiply,
    ];

    /// The names the command line takes.
    pub const NAMES: [&'static str; 5] = ["replace", "add", "over", "over-straight", "multiply"];

    /// The mode named `name`.
    pub fn from_name(name: &str) -> Result<BlendMode, String> {
        Self::NAMES
            .iter()
            .position(|n| *n == name)
            .map(|i| Self::ALL[i])
            .ok_or_else(|| {
                format!(
                    "unknown blend mode `{name}`: expected one of {}",
                    Self::NAMES.join(", ")
                )
            })
    }

    /// Its name, as [`from_name`](Self::from_name) takes it.
    pub fn name(self) -> &'static str {
        Self::NAMES[Self::ALL.iter().position(|m| *m == self).unwrap_or(0)]
    }

    /// The blend equation: the pixel's new colour when a fragment of
    /// colour `s` covering `coverage` of it lands on colour `d`. Values
    /// are not clamped here; the merge clamps when it stores.
    ///
    /// ```
    /// use glam::Vec4;
    /// use rasterlab::raster::BlendMode;
    ///
    /// // Half-opaque red over opaque blue, straight: half of each.
    /// let red = Vec4::new(1.0, 0.0, 0.0, 0.5);
    /// let blue = Vec4::new(0.0, 0.0, 1.0, 1.0);
    /// assert_eq!(BlendMode::OverStraight.mix(red, 1.0, blue), Vec4::new(0.5, 0.0, 0.5, 1.0));
    /// // The same red premultiplied is (0.5, 0, 0, 0.5): the same result.
    /// let red_premultiplied = Vec4::new(0.5, 0.0, 0.0, 0.5);
    /// assert_eq!(BlendMode::Over.mix(red_premultiplied, 1.0, blue), Vec4::new(0.5, 0.0, 0.5, 1.0));
    /// ```
    #[inline]
    pub fn mix(self, s: Vec4, coverage: f32, d: Vec4) -> Vec4 {
        match self {
            BlendMode::Replace => s * coverage + d * (1.0 - coverage),
            BlendMode::Add => {
                let a = s.w * coverage;
                d + (s * a).truncate().extend(a)
            }
            BlendMode::Over => {
                let s = s * coverage;
                s + d * (1.0 - s.w)
            }
            BlendMode::OverStraight => {
                let a = s.w * coverage;
                (s * a).truncate().extend(a) + d * (1.0 - a)
            }
            BlendMode::Multiply => s * d * coverage + d * (1.0 - coverage),
        }
    }
}

/// Which channels of the colour buffer a draw writes (the colour write
/// mask of the APIs); the others keep their values.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct WriteMask(pub [bool; 4]);

impl WriteMask {
    /// All four channels.
    pub const ALL: WriteMask = WriteMask([true; 4]);

    /// The mask named by the channels it writes, in order, from `rgba`
    /// (`rgb` keeps alpha, `a` writes only alpha, `none` writes nothing).
    pub fn from_name(name: &str) -> Result<WriteMask, String> {
        if name == "none" {
            return Ok(WriteMask([false; 4]));
        }
        let mut mask = [false; 4];
        let mut last = None;
        for c in name.chars() {
            let i = "rgba".find(c).filter(|&i| last.is_none_or(|l| i > l));
            let Some(i) = i else {
                return Err(format!(
                    "bad colour write mask `{name}`: give the channels written, in the order \
                     of `rgba` (say `rgb` or `a`), or `none`"
                ));
            };
            mask[i] = true;
            last = Some(i);
        }
        if last.is_none() {
            return Err("empty colour write mask: give `none` to write no channel".into());
        }
        Ok(WriteMask(mask))
    }

    /// The mask as the bytes of an RGBA8 pixel, all ones where written.
    #[inline]
    fn bytes(self) -> u32 {
        u32::from_ne_bytes(self.0.map(|w| if w { 0xff } else { 0 }))
    }
}

impl Default for WriteMask {
    fn default() -> Self {
        WriteMask::ALL
    }
}

/// The blend state of a draw: the [`BlendMode`], the space it mixes in,
/// and the colour write mask.
///
/// ```
/// use rasterlab::raster::{Blend, BlendMode, MixSpace};
///
/// // Half-covered white on black: 0.5 of the light, encoded, is 188;
/// // mixing the encoded numbers gives 128.
/// let white = [255, 255, 255, 255];
/// let black = [0, 0, 0, 255];
/// assert_eq!(Blend::default().mix_rgba8(white, 0.5, black), [188, 188, 188, 255]);
/// let encoded = Blend { mix_in: MixSpace::Encoded, ..Blend::default() };
/// assert_eq!(encoded.mix_rgba8(white, 0.5, black), [128, 128, 128, 255]);
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct Blend {
    /// The blend equation.
    pub mode: BlendMode,
    /// Where colours are mixed.
    pub mix_in: MixSpace,
    /// The channels written.
    pub write_mask: WriteMask,
}

/// A fragment's colour as it reaches the merge.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) enum Source {
    /// Shaded and already stored as RGBA8, covering the whole pixel (a
    /// span loop shades once per triangle or per group of eight, and
    /// converts there).
    Rgba8([u8; 4]),
    /// The shader's colour, in `[0, 1]`, covering `coverage` of the pixel.
    Shaded {
        /// The colour, clamped to `[0, 1]`.
        color: Vec4,
        /// How much of the pixel the fragment covers, in `[0, 1]`.
        coverage: f32,
    },
}

impl Blend {
    /// `replace`, in linear light, writing every channel: the default.
    pub const REPLACE: Blend = Blend {
        mode: BlendMode::Replace,
        mix_in: MixSpace::Linear,
        write_mask: WriteMask::ALL,
    };

    /// The pixel's new RGBA8 colour when a fragment of RGBA8 colour `s`
    /// covering `coverage` of it lands on `d`: decoded, mixed by the
    /// mode, encoded, masked. A whole fragment under `replace` is `s`
    /// itself, masked.
    #[inline(always)]
    pub fn mix_rgba8(self, s: [u8; 4], coverage: f32, d: [u8; 4]) -> [u8; 4] {
        if self.is_copy() && coverage >= 1.0 {
            s
        } else {
            self.mix_slowly(s, coverage, d)
        }
    }

    /// Whether a whole fragment's colour is copied as it is: `replace`,
    /// every channel written. The merge's loops test this once a group,
    /// so that the copy stays the plain store it was before blending.
    #[inline(always)]
    fn is_copy(self) -> bool {
        self.mode == BlendMode::Replace && self.write_mask == WriteMask::ALL
    }

    /// [`mix_rgba8`](Self::mix_rgba8) when it mixes: out of line, so that
    /// the copy's loops stay small.
    #[inline(never)]
    fn mix_slowly(self, s: [u8; 4], coverage: f32, d: [u8; 4]) -> [u8; 4] {
        let mixed = if self.mode == BlendMode::Replace && coverage >= 1.0 {
            s
        } else {
            let space = self.mix_in;
            space.encode(self.mode.mix(space.decode(s), coverage, space.decode(d)))
        };
        let mask = self.write_mask.bytes();
        (u32::from_ne_bytes(mixed) & mask | u32::from_ne_bytes(d) & !mask).to_ne_bytes()
    }

    /// [`merge`](Self::merge) where [`is_copy`](Self::is_copy) holds: a
    /// whole fragment's colour as it is, a partial one mixed.
    #[inline(always)]
    fn merge_copying(self, source: Source, dst: [u8; 4]) -> [u8; 4] {
        match source {
            Source::Rgba8(color) => color,
            Source::Shaded { color, coverage } if coverage >= 1.0 => to_rgba8(color),
            Source::Shaded { color, coverage } => self.mix_slowly(to_rgba8(color), coverage, dst),
        }
    }

    /// The colour the pixel holds after a fragment of colour `source`
    /// lands on its colour `dst`.
    #[inline(always)]
    pub(crate) fn merge(self, source: Source, dst: [u8; 4]) -> [u8; 4] {
        match source {
            Source::Rgba8(color) => self.mix_rgba8(color, 1.0, dst),
            Source::Shaded { color, coverage } => self.mix_rgba8(to_rgba8(color), coverage, dst),
        }
    }
}

/// Which pixels of a group passed the tests before the merge.
#[derive(Copy, Clone, Debug)]
pub(crate) enum Passed<'p> {
    /// Every one: the group is written with plain stores.
    All,
    /// Those whose mask is all ones (as a vector compare gives), not those
    /// whose mask is zero. The group is written without a branch, each
    /// pixel's old values kept where it failed, so that the compiler can
    /// run the loop on vectors.
    Where(&'p [u32]),
}

/// The merge of a group of pixels (one, or a span loop's eight): pixel
/// `k` of `colour` becomes [`Blend::merge`] of `source(k)` over it, and,
/// when `WRITE_DEPTH`, its depth in `depth` becomes `z[k]`, for each pixel
/// that `passed` says passed. `depth` and `z` are unused (and may be
/// empty) without `WRITE_DEPTH`.
#[inline(always)]
pub(crate) fn merge<const WRITE_DEPTH: bool>(
    blend: Blend,
    source: impl Fn(usize) -> Source,
    passed: Passed<'_>,
    z: &[f32],
    colour: &mut [[u8; 4]],
    depth: &mut [f32],
) {
    // A copy is decided once for the group, so that its loops are the
    // plain stores (and, under a mask, the vector selects) they were
    // before blending.
    if blend.is_copy() {
        let copy = |k: usize, c: [u8; 4]| blend.merge_copying(source(k), c);
        merge_group::<WRITE_DEPTH>(copy, passed, z, colour, depth);
    } else {
        let mix = |k: usize, c: [u8; 4]| blend.merge(source(k), c);
        merge_group::<WRITE_DEPTH>(mix, passed, z, colour, depth);
    }
}

/// [`merge`]'s loops, pixel `k` of colour `c` becoming `merged(k, c)`.
#[inline(always)]
fn merge_group<const WRITE_DEPTH: bool>(
    merged: impl Fn(usize, [u8; 4]) -> [u8; 4],
    passed: Passed<'_>,
    z: &[f32],
    colour: &mut [[u8; 4]],
    depth: &mut [f32],
) {
    match passed {
        Passed::All => {
            for (k, c) in colour.iter_mut().enumerate() {
                *c = merged(k, *c);
            }
            if WRITE_DEPTH {
                depth.copy_from_slice(z);
            }
        }
        Passed::Where(pass) => {
            for (k, (c, &pass)) in colour.iter_mut().zip(pass).enumerate() {
                let new = u32::from_ne_bytes(merged(k, *c));
                let kept = u32::from_ne_bytes(*c) & !pass;
                *c = (new & pass | kept).to_ne_bytes();
                if WRITE_DEPTH {
                    let d = &mut depth[k];
                    *d = f32::from_bits(z[k].to_bits() & pass | d.to_bits() & !pass);
                }
            }
        }
    }
}

/// [`merge`] of one pixel that passed: its colour `colour`, and with
/// `depth` its depth slot and the depth to write there (the scalar
/// path's call).
#[inline(always)]
pub(crate) fn merge_pixel(
    blend: Blend,
    source: Source,
    colour: &mut [u8; 4],
    depth: Option<(&mut f32, f32)>,
) {
    let colour = std::slice::from_mut(colour);
    match depth {
        Some((slot, z)) => {
            let slot = std::slice::from_mut(slot);
            merge::<true>(blend, |_| source, Passed::All, &[z], colour, slot);
        }
        None => merge::<false>(blend, |_| source, Passed::All, &[], colour, &mut []),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pixel left as it was where its mask is zero, merged where it is
    /// all ones, with and without the depth; the group with every mask set
    /// gives what [`Passed::All`] gives.
    #[test]
    fn a_group_is_merged_where_it_passed_and_kept_elsewhere() {
        let old = [[9, 9, 9, 9], [8, 8, 8, 8], [7, 7, 7, 7]];
        let z = [0.25, 0.5, 0.75];
        let source = |k: usize| Source::Rgba8([k as u8; 4]);
        let (mut colour, mut depth) = (old, [1.0; 3]);
        let pass = [u32::MAX, 0, u32::MAX];
        merge::<true>(
            Blend::REPLACE,
            source,
            Passed::Where(&pass),
            &z,
            &mut colour,
            &mut depth,
        );
        assert_eq!(colour, [[0; 4], [8; 4], [2; 4]]);
        assert_eq!(depth, [0.25, 1.0, 0.75]);
        let (mut kept_depth, mut all) = ([1.0; 3], old);
        merge::<false>(
            Blend::REPLACE,
            source,
            Passed::Where(&[u32::MAX; 3]),
            &z,
            &mut all,
            &mut kept_depth,
        );
        let mut plain = old;
        merge::<false>(
            Blend::REPLACE,
            source,
            Passed::All,
            &[],
            &mut plain,
            &mut [],
        );
        assert_eq!((all, kept_depth), (plain, [1.0; 3]));
        assert_eq!(plain, [[0; 4], [1; 4], [2; 4]]);
    }

    /// `replace` writes a whole fragment's colour as RGBA8 whatever was
    /// there, and mixes a partial one by its coverage: a quarter of white
    /// over black is a quarter of the light, 137 encoded (64 mixing the
    /// encoded values).
    #[test]
    fn replace_mixes_a_partial_fragment_by_its_coverage() {
        let white = Vec4::ONE;
        let whole = Source::Shaded {
            color: white,
            coverage: 1.0,
        };
        let quarter = Source::Shaded {
            color: white,
            coverage: 0.25,
        };
        let black = [0, 0, 0, 255];
        assert_eq!(Blend::REPLACE.merge(whole, black), [255; 4]);
        assert_eq!(Blend::REPLACE.merge(quarter, black), [137, 137, 137, 255]);
        let encoded = Blend {
            mix_in: MixSpace::Encoded,
            ..Blend::REPLACE
        };
        assert_eq!(encoded.merge(quarter, black), [64, 64, 64, 255]);
        assert_eq!(
            Blend::REPLACE.merge(Source::Rgba8([1, 2, 3, 4]), [5; 4]),
            [1, 2, 3, 4]
        );
    }

    /// The write mask keeps the channels it leaves out, under every mode.
    #[test]
    fn the_write_mask_keeps_what_it_leaves_out() {
        let rgb = WriteMask::from_name("rgb").unwrap();
        for mode in BlendMode::ALL {
            let blend = Blend {
                mode,
                write_mask: rgb,
                ..Blend::REPLACE
            };
            assert_eq!(
                blend.mix_rgba8([200, 100, 50, 128], 1.0, [1, 2, 3, 77])[3],
                77
            );
        }
        let none = Blend {
            write_mask: WriteMask::from_name("none").unwrap(),
            ..Blend::REPLACE
        };
        assert_eq!(none.mix_rgba8([9; 4], 1.0, [1, 2, 3, 4]), [1, 2, 3, 4]);
        let alpha = WriteMask::from_name("a").unwrap();
        assert_eq!(alpha, WriteMask([false, false, false, true]));
        for bad in ["", "ar", "rgbx", "rr"] {
            assert!(WriteMask::from_name(bad).is_err(), "{bad}");
        }
    }

    /// Each mode by its name, and a clear refusal of an unknown one.
    #[test]
    fn modes_are_named() {
        for (mode, name) in BlendMode::ALL.into_iter().zip(BlendMode::NAMES) {
            assert_eq!(BlendMode::from_name(name), Ok(mode));
            assert_eq!(mode.name(), name);
        }
        let error = BlendMode::from_name("screen").unwrap_err();
        assert!(error.contains("over-straight"), "{error}");
    }
}

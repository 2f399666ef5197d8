//! Step 7 of the stage, the **merge**: where a fragment's colour and depth
//! are written into its pixel, the one place in the crate that does so.
//!
//! Direct3D calls this step the output merger, OpenGL the per-fragment
//! operations after the depth test, and the rasterization slides "update
//! the frame buffer". Every path of the stage ends in [`merge`]: the
//! scalar reference path one pixel at a time, the span loops a group of
//! eight, the lines, the multisampled stage one sample at a time, and the
//! straight-to-the-target line loop of the benchmarks. A blend mode is one
//! variant of [`Blend`] and one arm of [`Blend::merge`]; what comes before
//! the merge (which pixels pass, at what depth) and after it (the clears
//! of `target`, the multisample resolve) are separate steps.

use crate::raster::shader::{from_rgba8, to_rgba8};
use glam::Vec4;

/// How a fragment's colour is combined with the colour already in its
/// pixel (the blend state of the graphics APIs).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Blend {
    /// The fragment's colour replaces the pixel's; a fragment covering
    /// only part of the pixel (an anti-aliased line's) is mixed in by its
    /// coverage, `c * coverage + dst * (1 - coverage)`, in the stored
    /// RGBA8 values.
    #[default]
    Replace,
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
    /// The colour the pixel holds after a fragment of colour `source`
    /// lands on its colour `dst`.
    #[inline(always)]
    pub(crate) fn merge(self, source: Source, dst: [u8; 4]) -> [u8; 4] {
        match (self, source) {
            (Blend::Replace, Source::Rgba8(color)) => color,
            (Blend::Replace, Source::Shaded { color, coverage }) => {
                if coverage >= 1.0 {
                    to_rgba8(color)
                } else {
                    to_rgba8(color * coverage + from_rgba8(dst) * (1.0 - coverage))
                }
            }
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
    match passed {
        Passed::All => {
            for (k, c) in colour.iter_mut().enumerate() {
                *c = blend.merge(source(k), *c);
            }
            if WRITE_DEPTH {
                depth.copy_from_slice(z);
            }
        }
        Passed::Where(pass) => {
            for (k, (c, &pass)) in colour.iter_mut().zip(pass).enumerate() {
                let merged = u32::from_ne_bytes(blend.merge(source(k), *c));
                let kept = u32::from_ne_bytes(*c) & !pass;
                *c = (merged & pass | kept).to_ne_bytes();
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
            Blend::Replace,
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
            Blend::Replace,
            source,
            Passed::Where(&[u32::MAX; 3]),
            &z,
            &mut all,
            &mut kept_depth,
        );
        let mut plain = old;
        merge::<false>(
            Blend::Replace,
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
    /// over black is 64.
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
        assert_eq!(Blend::Replace.merge(whole, [0, 0, 0, 255]), [255; 4]);
        assert_eq!(
            Blend::Replace.merge(quarter, [0, 0, 0, 255]),
            [64, 64, 64, 255]
        );
        assert_eq!(
            Blend::Replace.merge(Source::Rgba8([1, 2, 3, 4]), [5; 4]),
            [1, 2, 3, 4]
        );
    }
}

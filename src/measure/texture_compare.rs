//! Texture filtering compared: how far each way of sampling a texture
//! lands from what each pixel of the receding floor ([`Floor`]) should
//! show, and what it costs.
//!
//! What a pixel should show is the texture averaged over the pixel's
//! square: the texture's integral over the pixel's preimage under a box
//! filter, the ideal that Heckbert 1989 ("Fundamentals of texture mapping
//! and image warping") measures filters against. [`Floor::ground_truth`] estimates
//! it by `n` x `n` bilinear samples of level 0 on a regular grid in the
//! square, box-filtered; 16 x 16 by default. Every method is drawn by the
//! same back-end and compared on the pixels whose centre the floor covers:
//!
//! | pixel filter | level mode | derivatives | anisotropy |
//! |---|---|---|---|
//! | nearest, bilinear | zero (CS184's `L_ZERO`) | not read | 1 |
//! | nearest, bilinear | nearest, linear (OpenGL 3.3, section 3.8.11) | analytic, quad, forward | 1 |
//! | bilinear | linear | analytic, quad, forward | 2, 4, 8, 16 (the EXT_texture_filter_anisotropic example) |
//! | none (EWA reads texels) | linear | analytic, quad, forward | 2, 4, 8, 16 (Heckbert's elliptical weighted average) |
//!
//! The error is in the stored colour's channels (0 to 1, red, green and
//! blue alike): the root mean square and the worst over the compared
//! pixels. The cost is the fastest of the timed frames (rasterization,
//! derivatives and sampling, on one thread) divided by the fragments
//! drawn: the fastest, since on a shared machine a frame is only ever
//! slowed by the others' work, never sped up.
//!
//! ```
//! use rasterlab::geometry::Floor;
//! use rasterlab::measure::compare_textures;
//!
//! let floor = Floor::new(48, 32).unwrap();
//! let c = compare_textures(&floor, 4, None, 1).unwrap();
//! let rms = |name: &str| c.rows.iter().find(|r| r.method.to_string() == name).unwrap().rms;
//! // Trilinear filtering comes closer to the truth than level 0.
//! assert!(rms("bilinear, linear levels, analytic") < rms("bilinear, level 0"));
//! ```

use crate::error::{Error, Result};
use crate::geometry::Floor;
use crate::measure::timing::time_runs;
use crate::raster::derivatives::Derivatives;
use crate::raster::edge::PixelRect;
use crate::raster::registry::default_triangle_backend;
use crate::raster::target::RenderTarget;
use crate::raster::texture::{Anisotropic, Filter, LevelMode, Sampler, Wrap};
use glam::Vec4;
use serde::Serialize;
use std::fmt;

/// One way of sampling the floor's texture.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct TextureMethod {
    /// The pixel filter.
    pub filter: Filter,
    /// The level mode.
    pub levels: LevelMode,
    /// The derivative method (`None`: level 0 reads none).
    pub derivatives: Option<Derivatives>,
    /// The most anisotropy (1: isotropic).
    pub anisotropy: u32,
    /// How the anisotropy is filtered: the extension's probes or EWA.
    pub anisotropic: Anisotropic,
}

impl TextureMethod {
    /// The sampler the method samples with, repeating.
    pub fn sampler(&self) -> Sampler {
        Sampler {
            filter: self.filter,
            levels: self.levels,
            wrap: Wrap::Repeat,
            anisotropy: self.anisotropy,
            anisotropic: self.anisotropic,
        }
    }

    /// Every method compared: the six filter and level combinations, those
    /// that read derivatives under each method, then anisotropic filtering
    /// from 2x to 16x under each method, by the extension's probes and by
    /// EWA.
    pub fn all() -> Vec<TextureMethod> {
        let methods = [
            Derivatives::Analytic,
            Derivatives::Quad,
            Derivatives::Forward,
        ];
        let mut all = Vec::new();
        for filter in [Filter::Nearest, Filter::Bilinear] {
            for levels in [LevelMode::Zero, LevelMode::Nearest, LevelMode::Linear] {
                let derivatives: Vec<Option<Derivatives>> = match levels {
                    LevelMode::Zero => vec![None],
                    _ => methods.map(Some).to_vec(),
                };
                for derivatives in derivatives {
                    all.push(TextureMethod {
                        filter,
                        levels,
                        derivatives,
                        anisotropy: 1,
                        anisotropic: Anisotropic::Probes,
                    });
                }
            }
        }
        for anisotropic in [Anisotropic::Probes, Anisotropic::Ewa] {
            for anisotropy in [2, 4, 8, 16] {
                for m in methods {
                    all.push(TextureMethod {
                        filter: Filter::Bilinear,
                        levels: LevelMode::Linear,
                        derivatives: Some(m),
                        anisotropy,
                        anisotropic,
                    });
                }
            }
        }
        all
    }
}

impl fmt::Display for TextureMethod {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let levels = match self.levels {
            LevelMode::Zero => "level 0",
            LevelMode::Nearest => "nearest level",
            LevelMode::Linear => "linear levels",
        };
        match self.anisotropic {
            Anisotropic::Probes => write!(f, "{}, {levels}", self.filter)?,
            Anisotropic::Ewa => write!(f, "ewa, {levels}")?,
        }
        if let Some(d) = self.derivatives {
            write!(f, ", {d}")?;
        }
        if self.anisotropy > 1 {
            write!(f, ", {}x", self.anisotropy)?;
        }
        Ok(())
    }
}

impl Serialize for TextureMethod {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// One method's error against the ground truth, and its cost.
#[derive(Clone, Debug, Serialize)]
pub struct TextureRow {
    /// The method.
    pub method: TextureMethod,
    /// Root mean square error over the compared pixels' channels.
    pub rms: f64,
    /// The worst channel error.
    pub worst: f64,
    /// The fastest frame's time divided by its fragments, in nanoseconds.
    pub ns_per_pixel: f64,
}

/// The comparison: every method on the same floor.
#[derive(Clone, Debug, Serialize)]
pub struct TextureComparison {
    /// Target width.
    pub width: u32,
    /// Target height.
    pub height: u32,
    /// The ground truth's samples a side.
    pub truth_samples: u32,
    /// Pixels compared.
    pub pixels: usize,
    /// The back-end that drew every method.
    pub backend: String,
    /// One row per method, in [`TextureMethod::all`]'s order.
    pub rows: Vec<TextureRow>,
}

/// Every method of [`TextureMethod::all`] on `floor`, against the ground
/// truth of `truth_samples` x `truth_samples` samples a pixel, over the
/// pixels of `crop` (all of them: `None`) that the floor covers; each
/// frame timed `rounds` times (at least one) after a warm-up. An error
/// when no pixel is compared.
pub fn compare_textures(
    floor: &Floor,
    truth_samples: u32,
    crop: Option<PixelRect>,
    rounds: usize,
) -> Result<TextureComparison> {
    let whole = PixelRect::of_target(floor.width(), floor.height());
    let crop = crop.map_or(whole, |c| c.intersect(whole));
    let mut pixels = Vec::new();
    let mut truths: Vec<Vec4> = Vec::new();
    for y in crop.y0..=crop.y1 {
        for x in crop.x0..=crop.x1 {
            let (x, y) = (x as u32, y as u32);
            if let Some(truth) = floor.ground_truth(x, y, truth_samples)? {
                pixels.push((x, y));
                truths.push(truth);
            }
        }
    }
    if pixels.is_empty() {
        return Err(Error::InvalidArgument(
            "the floor covers no pixel of the region compared".into(),
        ));
    }
    let backend = default_triangle_backend();
    let mut target = RenderTarget::new(floor.width(), floor.height())?;
    let mut rows = Vec::new();
    for method in TextureMethod::all() {
        let shader = floor.shader(method.sampler(), method.derivatives.unwrap_or_default());
        let (timing, work) = time_runs(rounds, || floor.draw(backend, &shader, &mut target));
        let (mut squares, mut worst) = (0.0f64, 0.0f64);
        for (&(x, y), want) in pixels.iter().zip(&truths) {
            let got = target.color[target.index(x, y)];
            for c in 0..3 {
                let e = (f64::from(got[c]) / 255.0 - f64::from(want[c])).abs();
                squares += e * e;
                worst = worst.max(e);
            }
        }
        rows.push(TextureRow {
            method,
            rms: (squares / (3 * pixels.len()) as f64).sqrt(),
            worst,
            ns_per_pixel: timing.spread.min_ms * 1e6 / work.fragments.max(1) as f64,
        });
    }
    Ok(TextureComparison {
        width: floor.width(),
        height: floor.height(),
        truth_samples,
        pixels: pixels.len(),
        backend: backend.name().to_string(),
        rows,
    })
}

impl fmt::Display for TextureComparison {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "texture filtering on the floor, {}x{} ({} pixels), against the texture over each \
             pixel ({}x{} bilinear samples of level 0); drawn by {}:",
            self.width,
            self.height,
            self.pixels,
            self.truth_samples,
            self.truth_samples,
            self.backend
        )?;
        writeln!(
            f,
            "{:<42} {:>7} {:>7} {:>9}",
            "method", "RMS", "worst", "ns/pixel"
        )?;
        for r in &self.rows {
            writeln!(
                f,
                "{:<42} {:>7.4} {:>7.3} {:>9.0}",
                r.method.to_string(),
                r.rms,
                r.worst,
                r.ns_per_pixel
            )?;
        }
        Ok(())
    }
}

//! What a rendering is asked for, apart from the back-end: the target's
//! size, the camera, the shading and the pipeline's options
//! ([`RenderSettings`]), and the checks a renderer makes of them before
//! it frames a mesh.

use crate::error::{Error, Result};
use crate::geometry::pipeline::PipelineOptions;
use crate::raster::derivatives::Derivatives;
use crate::raster::line::LineRasterizer;
use crate::raster::shader::{DirectionalLight, Filter};
use crate::raster::stage::{Blend, Interpolation};
use crate::raster::target::{DepthState, RenderTarget};
use crate::raster::texture::{Anisotropic, LevelMode, Sampler, Wrap};
use glam::Vec4;

/// How a mesh is coloured.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Shading {
    /// Lit per vertex, one colour per triangle (its first vertex's).
    Flat,
    /// Lit per vertex, colours interpolated (Gouraud).
    Gouraud,
    /// Lit per fragment with the interpolated normal (diffuse, the software-rasterizer article).
    #[default]
    Diffuse,
    /// The interpolated normal as a colour.
    Normals,
    /// A checkerboard texture at the mesh's (or generated) UVs, lit per fragment.
    Texture,
}

crate::names::named_enum!(
    Shading,
    "shading",
    Flat = "flat",
    Gouraud = "gouraud",
    Diffuse = "diffuse",
    Normals = "normals",
    Texture = "texture"
);

/// Everything about a rendering except the back-end.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct RenderSettings {
    /// Target width in pixels.
    pub width: u32,
    /// Target height in pixels.
    pub height: u32,
    /// Camera direction around the vertical axis, degrees (0 = from +Z).
    pub azimuth: f32,
    /// Camera elevation above the horizon, degrees.
    pub elevation: f32,
    /// Zoom factor (1 frames the whole mesh).
    pub zoom: f32,
    /// Colouring.
    pub shading: Shading,
    /// Texture filter for [`Shading::Texture`].
    pub filter: Filter,
    /// Mip level mode for [`Shading::Texture`]: zero (level 0 only, the
    /// default), nearest or linear (trilinear with the bilinear filter).
    pub mip: LevelMode,
    /// Wrap mode for [`Shading::Texture`].
    pub wrap: Wrap,
    /// The most anisotropic probes for [`Shading::Texture`], 1 (the
    /// default, isotropic) to
    /// [`MAX_ANISOTROPY`](crate::raster::texture::MAX_ANISOTROPY).
    pub anisotropy: u32,
    /// How [`Shading::Texture`]'s anisotropy is filtered: the extension's
    /// probes (the default) or EWA.
    pub anisotropic: Anisotropic,
    /// How the texture coordinate's derivatives are computed where the
    /// level mode or the anisotropy reads them.
    pub derivatives: Derivatives,
    /// Perspective-correct or linear varyings.
    pub interpolation: Interpolation,
    /// Fill rule and culling.
    pub pipeline: PipelineOptions,
    /// Depth test and write.
    pub depth: DepthState,
    /// How fragments are merged with the pixels' colours.
    pub blend: Blend,
    /// Surface colour where the mesh has none.
    pub color: Vec4,
    /// The light.
    pub light: DirectionalLight,
    /// Line back-end drawing the triangle edges over the surface, if any.
    pub wireframe: Option<&'static dyn LineRasterizer>,
    /// Background colour.
    pub background: [u8; 4],
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            width: 640,
            height: 480,
            azimuth: 0.0,
            elevation: 15.0,
            zoom: 1.0,
            shading: Shading::Diffuse,
            filter: Filter::Bilinear,
            mip: LevelMode::Zero,
            wrap: Wrap::Repeat,
            anisotropy: 1,
            anisotropic: Anisotropic::Probes,
            derivatives: Derivatives::Analytic,
            interpolation: Interpolation::PerspectiveCorrect,
            pipeline: PipelineOptions::default(),
            depth: DepthState::DEFAULT,
            blend: Blend::REPLACE,
            color: Vec4::new(0.85, 0.78, 0.62, 1.0),
            light: DirectionalLight::default(),
            wireframe: None,
            background: [24, 26, 32, 255],
        }
    }
}

/// The largest zoom a camera accepts: beyond it the view is a fraction of
/// a pixel of the mesh and the projection loses every digit.
pub const MAX_ZOOM: f32 = 1e6;

impl RenderSettings {
    /// Errors unless the settings can frame a mesh: a zero-size or
    /// oversized target, a non-finite angle, a zoom that is not in
    /// `(0, MAX_ZOOM]`, a sampler [`Sampler::check`] refuses.
    pub(super) fn check(&self) -> Result<()> {
        RenderTarget::check_size(self.width, self.height)?;
        for (name, value) in [("azimuth", self.azimuth), ("elevation", self.elevation)] {
            if !value.is_finite() {
                return Err(Error::InvalidArgument(format!(
                    "{name} must be a finite angle in degrees, not {value}"
                )));
            }
        }
        // The anisotropy, and EWA only on the mip levels.
        self.sampler().check()?;
        // NaN fails this test too.
        if !(self.zoom > 0.0 && self.zoom <= MAX_ZOOM) {
            return Err(Error::InvalidArgument(format!(
                "zoom must be > 0 and at most {MAX_ZOOM}, not {}",
                self.zoom
            )));
        }
        Ok(())
    }

    /// The texture's sampler: filter, level mode, wrap and anisotropy.
    pub fn sampler(&self) -> Sampler {
        Sampler {
            filter: self.filter,
            levels: self.mip,
            wrap: self.wrap,
            anisotropy: self.anisotropy,
            anisotropic: self.anisotropic,
        }
    }

    /// Whether texturing goes beyond level 0 with repeating addressing,
    /// the textured frame's fast path: mipmaps, anisotropy or another
    /// wrap mode, which the mipmapped shader draws.
    pub fn mipmapped(&self) -> bool {
        self.shading == Shading::Texture
            && self.sampler()
                != Sampler {
                    filter: self.filter,
                    ..Sampler::default()
                }
    }
}

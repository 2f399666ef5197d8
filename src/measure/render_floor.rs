//! `render --scene floor`: the receding checkerboard floor ([`Floor`])
//! drawn with the texture options a mesh takes (`--filter`, `--mip`,
//! `--wrap`, `--anisotropy`, `--anisotropic`, `--derivatives`,
//! `--texture`), each frame
//! timed whole. Level 0 alone by default, so that the first picture a
//! newcomer draws shows the aliasing the other options remove.

use super::render_request::{DrawingReport, RenderRequest};
use crate::error::{Error, Result};
use crate::geometry::{Floor, FrameTimes};
use crate::raster::derivatives::{count_quad_helpers, Derivatives};
use crate::raster::edge::PixelRect;
use crate::raster::fragment::WorkCounters;
use crate::raster::registry::{backend, default_triangle_backend, Backend};
use crate::raster::stage::Blend;
use crate::raster::target::{DepthState, RenderTarget};
use crate::raster::texture::{Sampler, Texture};
use std::time::Instant;

impl RenderRequest {
    /// The floor drawn frame after frame; the last frame written.
    pub(super) fn render_floor(&self, frame_done: &mut dyn FnMut()) -> Result<DrawingReport> {
        let m = &self.mesh;
        let others = [
            ("--shading", m.shading.is_some()),
            ("--interpolation", m.interpolation.is_some()),
            ("--cull", m.cull.is_some()),
            ("--front-face", m.front_face.is_some()),
            ("--wireframe", m.wireframe.is_some()),
            ("--azimuth", m.azimuth.is_some()),
            ("--elevation", m.elevation.is_some()),
            ("--zoom", m.zoom.is_some()),
            ("--msaa", self.msaa.is_some()),
            ("--sort", self.sort),
            ("--scale", self.scale != 1),
            ("--blend", self.blend != Blend::REPLACE),
            ("--depth-test", self.depth != DepthState::DEFAULT),
        ];
        let refused: Vec<&str> = others.iter().filter(|o| o.1).map(|o| o.0).collect();
        if !refused.is_empty() {
            return Err(Error::InvalidArgument(format!(
                "the floor takes the texture options (--filter, --mip, --wrap, --anisotropy, \
                 --anisotropic, --derivatives, --texture) and --size; not {}",
                refused.join(", ")
            )));
        }
        let (width, height) = self.size.unwrap_or(Floor::SIZE);
        let mut floor = Floor::new(width, height)?;
        if let Some(path) = &m.texture {
            floor = floor.with_texture(Texture::load(path)?);
        }
        let defaults = Sampler::default();
        let sampler = Sampler {
            filter: m.filter.unwrap_or(defaults.filter),
            levels: m.mip.unwrap_or(defaults.levels),
            wrap: m.wrap.unwrap_or(defaults.wrap),
            anisotropy: m.anisotropy.unwrap_or(defaults.anisotropy),
            anisotropic: m.anisotropic.unwrap_or(defaults.anisotropic),
        };
        sampler.check()?;
        let name = self
            .backend
            .as_deref()
            .unwrap_or(default_triangle_backend().name());
        let Backend::Triangle(chosen) = backend(name)? else {
            return Err(Error::InvalidArgument(
                "the floor is drawn by a triangle back-end (see `rasterlab backends`)".into(),
            ));
        };
        let shader = floor.shader(sampler, m.derivatives.unwrap_or_default());
        let mut target = RenderTarget::without_coverage(width, height)?;
        let mut times = Vec::with_capacity(self.frames as usize);
        let mut work = WorkCounters::default();
        for _ in 0..self.frames {
            let start = Instant::now();
            work = floor.draw(chosen, &shader, &mut target);
            let raster = start.elapsed();
            times.push(FrameTimes::new(raster, None, Default::default(), raster));
            frame_done();
        }
        if m.derivatives == Some(Derivatives::Quad) {
            let rect = PixelRect::of_target(width, height);
            work.helpers = count_quad_helpers(&floor.geometry().setups, chosen, rect);
        }
        target.save_png(&self.out)?;
        Ok(DrawingReport {
            backend: name.to_string(),
            samples: 1,
            work,
            frames: self.frames,
            median: FrameTimes::median(&times).unwrap_or_default(),
            out: self.out.clone(),
        })
    }
}

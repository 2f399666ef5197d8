//! Rendering a mesh end to end: camera, vertex shader, pipeline, back-end,
//! fragment shader, optional wireframe. What `rasterlab render` and
//! `rasterlab demo` run.
//!
//! ```
//! use rasterlab::geometry::{Mesh, MeshRenderer, RenderSettings};
//! use rasterlab::raster::triangle_backend;
//! use std::path::Path;
//!
//! let bunny = Mesh::load(Path::new("assets/bunny.ply")).unwrap();
//! let settings = RenderSettings { width: 64, height: 48, ..RenderSettings::default() };
//! let renderer = MeshRenderer::new(&bunny, settings).unwrap();
//! let a = renderer.render(triangle_backend("scanline").unwrap()).unwrap();
//! let b = renderer.render(triangle_backend("incremental").unwrap()).unwrap();
//! assert_eq!(a.target, b.target); // bit-identical colour, depth and coverage
//! assert!(a.stats.work.fragments > 0);
//! ```

mod settings;
mod vertex_order;

pub use settings::{RenderSettings, Shading};
use vertex_order::first_use_order;

use crate::error::{Error, Result};
use crate::geometry::frame_times::FrameTimes;
use crate::geometry::mesh::Mesh;
use crate::geometry::pipeline::vertex::{MeshVertex, Transform};
use crate::geometry::pipeline::Camera;
use crate::geometry::pipeline::{
    self, BatchDraw, DrawInput, Geometry, GeometryInParts, GeometryStats, PipelineOptions, Viewport,
};
use crate::raster::derivatives::{count_quad_helpers, Derivatives};
use crate::raster::edge::PixelRect;
use crate::raster::fragment::WorkCounters;
use crate::raster::line::{LineOptions, LineRasterizer, LineSetup};
use crate::raster::multisample_stage::{draw_multisampled, MultisampleTarget};
use crate::raster::primitive::{ShadedLine, TriangleData};
use crate::raster::shader::FragmentShader;
use crate::raster::shader::{Diffuse, Flat, Gouraud, Mipmapped, NormalColors, Texture, Textured};
use crate::raster::stage::FragmentStage;
use crate::raster::stage::Interpolation;
use crate::raster::target::{Clear, DepthState, DepthTest, RenderTarget};
use crate::raster::triangle::TriangleRasterizer;
use glam::{Mat4, Vec4};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// Triangles assembled per batch when a frame is drawn on one thread
/// ([`GeometryInParts::process_in_batches`]): a batch's set-ups and stage
/// triangles (about a quarter of a dense mesh's triangles are kept, at
/// 200 bytes) stay well inside a core's second-level cache. 1,024 and
/// 16,384 drew the full dragon as fast, within the noise.
const BATCH: usize = 4096;

/// What drawing one frame did and cost.
#[derive(Copy, Clone, Debug)]
pub struct FrameStats {
    /// What the pipeline did with the triangles.
    pub geometry: GeometryStats,
    /// The triangle back-end's work.
    pub work: WorkCounters,
    /// Time in the vertex shader, clipping and set-up.
    pub geometry_time: Duration,
    /// Time clearing, rasterizing and shading (including the wireframe).
    pub raster_time: Duration,
    /// The whole frame, part by part: the geometry and raster times
    /// above (the clear folded into the raster) and the rest, which add
    /// up to the frame's time.
    pub times: FrameTimes,
}

/// One rendered frame: its buffers and what it cost.
#[derive(Clone, Debug)]
pub struct Frame {
    /// The colour, depth and coverage buffers.
    pub target: RenderTarget,
    /// The pipeline's and the back-end's work, and the times.
    pub stats: FrameStats,
}

/// The fragment shader of each [`Shading`], kept as its own type (not
/// behind a `dyn` pointer) so that the draw and its stage are compiled
/// for it ([`FragmentStage`]).
enum MeshShader {
    Flat(Flat),
    Gouraud(Gouraud),
    Diffuse(Diffuse),
    Normals(NormalColors),
    Texture(Textured),
}

/// A mesh prepared for rendering from one view.
pub struct MeshRenderer {
    settings: RenderSettings,
    vertices: Vec<MeshVertex>,
    triangles: Vec<[u32; 3]>,
    edges: Vec<[u32; 2]>,
    transform: Transform,
    shader: MeshShader,
    /// The geometry buffers, filled again for each frame so that a frame
    /// allocates nothing for them once the first is drawn.
    geometry: Mutex<GeometryInParts>,
    /// The same for multisampled frames, whose set-up keeps more
    /// triangles and whose draw reads them as one array.
    multisampled: Mutex<Geometry>,
    /// The same for mipmapped frames, with their shader, made once and
    /// given each frame's triangles.
    mipmapped: Mutex<(Geometry, Option<Mipmapped>)>,
}

impl MeshRenderer {
    /// Frames `mesh` with a camera and prepares its vertices and shaders.
    ///
    /// Errors: a zero-size or oversized target, a non-finite angle, a zoom
    /// that is not in `(0, MAX_ZOOM]`, a vertex index out of range (the
    /// frames do not check the indices again).
    pub fn new(mesh: &Mesh, settings: RenderSettings) -> Result<MeshRenderer> {
        settings.check()?;
        // Checked once here, not in every frame's geometry stages.
        Error::check_indices(mesh.triangles.iter().flatten(), mesh.positions.len())?;
        let aspect = settings.width as f32 / settings.height as f32;
        let camera = Camera::framing(
            mesh.bounds(),
            aspect,
            settings.azimuth,
            settings.elevation,
            settings.zoom,
        );
        let mut transform = Transform::new(Mat4::IDENTITY, camera.view(), camera.projection());
        if matches!(settings.shading, Shading::Flat | Shading::Gouraud) {
            transform = transform.with_vertex_light(settings.light);
        }
        let uvs = (settings.shading == Shading::Texture).then(|| mesh.uvs_or_generated());
        let vertices: Vec<MeshVertex> = (0..mesh.positions.len())
            .map(|i| MeshVertex {
                position: mesh.positions[i],
                normal: mesh.normals[i],
                uv: uvs.as_ref().map_or(glam::Vec2::ZERO, |u| u[i]),
                color: mesh.colors.as_ref().map_or(settings.color, |c| c[i]),
            })
            .collect();
        let shader = match settings.shading {
            Shading::Flat => MeshShader::Flat(Flat),
            Shading::Gouraud => MeshShader::Gouraud(Gouraud),
            Shading::Diffuse => MeshShader::Diffuse(Diffuse(settings.light)),
            Shading::Normals => MeshShader::Normals(NormalColors),
            Shading::Texture => MeshShader::Texture(Textured {
                texture: Texture::checkerboard(16, 8, settings.color, settings.color * 0.35),
                filter: settings.filter,
                light: Some(settings.light),
            }),
        };
        let mut edges = if settings.wireframe.is_some() {
            unique_edges(&mesh.triangles)
        } else {
            Vec::new()
        };
        let mut triangles = mesh.triangles.clone();
        let vertices = match first_use_order(vertices.len(), &triangles) {
            Some(new_index) => {
                for i in triangles
                    .iter_mut()
                    .flatten()
                    .chain(edges.iter_mut().flatten())
                {
                    *i = new_index[*i as usize];
                }
                let mut reordered = vertices.clone();
                for (old, &new) in new_index.iter().enumerate() {
                    reordered[new as usize] = vertices[old];
                }
                reordered
            }
            None => vertices,
        };
        Ok(MeshRenderer {
            settings,
            vertices,
            triangles,
            edges,
            transform,
            shader,
            geometry: Mutex::new(GeometryInParts::default()),
            multisampled: Mutex::new(Geometry::default()),
            mipmapped: Mutex::new((Geometry::default(), None)),
        })
    }

    /// The settings.
    pub fn settings(&self) -> &RenderSettings {
        &self.settings
    }

    /// The vertex shader in use.
    pub fn transform(&self) -> &Transform {
        &self.transform
    }

    fn viewport(&self) -> Viewport {
        Viewport {
            width: self.settings.width,
            height: self.settings.height,
        }
    }

    /// Readies the renderer's per-frame buffers before the first frame:
    /// runs the geometry stages once into the buffers every frame reuses,
    /// so that the first frame, like every later one, finds their memory
    /// allocated and faulted in (about 100 MB for the full dragon, whose
    /// first touch, the kernel zeroing each page, was most of a first
    /// frame's extra time). Returns the time it took, for the caller to
    /// report beside the frames'.
    ///
    /// ```
    /// use rasterlab::geometry::{Mesh, MeshRenderer, RenderSettings};
    /// use rasterlab::raster::triangle_backend;
    /// use std::path::Path;
    ///
    /// let bunny = Mesh::load(Path::new("assets/bunny.ply")).unwrap();
    /// let renderer = MeshRenderer::new(&bunny, RenderSettings::default()).unwrap();
    /// let before = renderer.render(triangle_backend("tiled").unwrap()).unwrap();
    /// renderer.prepare().unwrap();
    /// let after = renderer.render(triangle_backend("tiled").unwrap()).unwrap();
    /// assert_eq!(before.target, after.target);
    /// ```
    pub fn prepare(&self) -> Result<Duration> {
        let start = Instant::now();
        if let Ok(mut geometry) = self.geometry.try_lock() {
            if self.in_batches() {
                // The buffers of a draw batch by batch: one batch's.
                geometry.process_in_batches(&self.draw_input(), BATCH, |_, _| {})?;
            } else {
                geometry.process_into(&self.draw_input())?;
            }
        }
        Ok(start.elapsed())
    }

    /// What the geometry stages take from the renderer.
    fn draw_input(&self) -> DrawInput<'_, MeshVertex, Transform> {
        DrawInput {
            vertices: &self.vertices,
            triangles: &self.triangles,
            shader: &self.transform,
            viewport: self.viewport(),
            options: &self.settings.pipeline,
        }
    }

    /// Whether a frame is assembled and drawn batch by batch
    /// ([`GeometryInParts::process_in_batches`]): on one thread, when the
    /// mesh has more than one batch of triangles.
    fn in_batches(&self) -> bool {
        rayon::current_num_threads() == 1 && self.triangles.len() > BATCH
    }

    /// Runs the geometry stages (vertex shader, clipping, set-up).
    pub fn geometry(&self) -> Result<Geometry> {
        pipeline::process_triangles(
            &self.vertices,
            &self.triangles,
            &self.transform,
            self.viewport(),
            &self.settings.pipeline,
        )
    }

    /// The renderer with `texture` in place of the checkerboard of
    /// [`Shading::Texture`]; an error for any other shading, where it
    /// would do nothing.
    pub fn with_texture(mut self, texture: Texture) -> Result<MeshRenderer> {
        match &mut self.shader {
            MeshShader::Texture(textured) => {
                textured.texture = texture;
                Ok(self)
            }
            _ => Err(Error::InvalidArgument(
                "a texture is drawn with --shading texture".into(),
            )),
        }
    }

    /// Renders one frame with `backend` into a new target that counts
    /// coverage, on rayon's threads ([`draw_binned`](crate::geometry::pipeline::draw_binned)): the image does not
    /// depend on their number.
    pub fn render(&self, backend: &dyn TriangleRasterizer) -> Result<Frame> {
        let mut target = RenderTarget::new(self.settings.width, self.settings.height)?;
        let stats = self.render_into(backend, &mut target)?;
        Ok(Frame { target, stats })
    }

    /// Errors unless a target of `size` is the size the renderer draws.
    fn check_target(&self, (width, height): (u32, u32)) -> Result<()> {
        let drawn = (self.settings.width, self.settings.height);
        if (width, height) != drawn {
            return Err(Error::InvalidArgument(format!(
                "the target is {width}x{height}, the renderer draws {}x{}",
                drawn.0, drawn.1
            )));
        }
        Ok(())
    }

    /// Clears `target` and renders one frame into it, as an application
    /// redraws its framebuffer: the buffers are reused, and a target made
    /// [`without_coverage`](RenderTarget::without_coverage) skips the
    /// coverage count. Errors if `target` is not the size of the settings.
    ///
    /// On one thread a mesh of more than 4,096 triangles is assembled
    /// and drawn a batch at a time, so that each batch's set-ups are read
    /// back from the cache, not from memory (docs/performance-log.md,
    /// "2026-12-07, `3d51a17`: a one-thread frame batch by batch"). The
    /// image is the same bits either way.
    pub fn render_into(
        &self,
        backend: &dyn TriangleRasterizer,
        target: &mut RenderTarget,
    ) -> Result<FrameStats> {
        self.check_target((target.width(), target.height()))?;
        if let MeshShader::Texture(textured) = &self.shader {
            if self.settings.mipmapped() {
                return self.render_mipmapped(textured, backend, target);
            }
        }
        let frame_start = Instant::now();
        // A renderer drawing from several threads at once gives the other
        // threads buffers of their own.
        let mut reused = self.geometry.try_lock().ok();
        let mut own = GeometryInParts::default();
        let geometry = reused.as_deref_mut().unwrap_or(&mut own);
        let lines = if self.edges.is_empty() {
            Vec::new()
        } else {
            pipeline::process_lines(
                &self.vertices,
                &self.edges,
                &self.transform,
                self.viewport(),
            )?
        };
        let (work, mut raster_time) = match &self.shader {
            MeshShader::Flat(s) => self.draw(geometry, backend, s, target),
            MeshShader::Gouraud(s) => self.draw(geometry, backend, s, target),
            MeshShader::Diffuse(s) => self.draw(geometry, backend, s, target),
            MeshShader::Normals(s) => self.draw(geometry, backend, s, target),
            MeshShader::Texture(s) => self.draw(geometry, backend, s, target),
        }?;
        let start = Instant::now();
        if let Some(line_backend) = self.settings.wireframe {
            self.draw_wireframe(line_backend, &lines, target);
        }
        raster_time += start.elapsed();
        let frame_time = frame_start.elapsed();
        let geometry_time = frame_time.saturating_sub(raster_time);
        let geometry_stats = geometry.stats;
        drop(reused);
        Ok(FrameStats {
            geometry: geometry_stats,
            work,
            geometry_time,
            raster_time,
            times: FrameTimes::new(frame_time, None, geometry_time, raster_time),
        })
    }

    /// A textured frame with mipmaps, anisotropy or a wrap mode other
    /// than repeat: the whole geometry, then the [`Mipmapped`] shader made
    /// for its triangles, drawn band by band on rayon's threads; the
    /// wireframe over it.
    fn render_mipmapped(
        &self,
        textured: &Textured,
        backend: &dyn TriangleRasterizer,
        target: &mut RenderTarget,
    ) -> Result<FrameStats> {
        let frame_start = Instant::now();
        // As in `render_into`: other threads drawing at once get their own.
        let mut reused = self.mipmapped.try_lock().ok();
        let mut own = (Geometry::default(), None);
        let (geometry, shader) = reused.as_deref_mut().unwrap_or(&mut own);
        pipeline::process_triangles_into(
            geometry,
            &self.vertices,
            &self.triangles,
            &self.transform,
            self.viewport(),
            &self.settings.pipeline,
        )?;
        let perspective = self.settings.interpolation == Interpolation::PerspectiveCorrect;
        let shader = shader.get_or_insert_with(|| {
            let none = TriangleData::default();
            let sampler = self.settings.sampler();
            let derivatives = self.settings.derivatives;
            let mut shader = Mipmapped::new(
                textured.texture.clone(),
                sampler,
                derivatives,
                &[],
                &none,
                false,
            );
            shader.light = textured.light;
            shader
        });
        shader.set_triangles(&geometry.setups, &geometry.shaded, perspective);
        let geometry = &*geometry;
        let geometry_time = frame_start.elapsed();
        let start = Instant::now();
        let mut work = pipeline::draw_binned_clearing(
            geometry,
            backend,
            &*shader,
            self.settings.depth,
            self.settings.interpolation,
            Clear::all(self.settings.background),
            target,
        );
        if let Some(line_backend) = self.settings.wireframe {
            let lines = pipeline::process_lines(
                &self.vertices,
                &self.edges,
                &self.transform,
                self.viewport(),
            )?;
            self.draw_wireframe(line_backend, &lines, target);
        }
        let raster_time = start.elapsed();
        // Counted after the frame's time is taken: the count rasterizes
        // every triangle again on its own, which a GPU's quads do not.
        if self.settings.derivatives == Derivatives::Quad {
            let rect = PixelRect::of_target(target.width(), target.height());
            work.helpers = count_quad_helpers(&geometry.setups, backend, rect);
        }
        Ok(FrameStats {
            geometry: geometry.stats,
            work,
            geometry_time,
            raster_time,
            times: FrameTimes::new(frame_start.elapsed(), None, geometry_time, raster_time),
        })
    }

    /// Clears `target` and renders one frame into it multisampled, on the
    /// target's sample pattern ([`draw_multisampled`]): the set-up keeps
    /// every triangle that may cover a sample, not only a pixel centre,
    /// and the draw runs on one thread. Resolve the target for the image.
    ///
    /// Errors if `target` is not the size of the settings, and with a
    /// wireframe (lines are not multisampled).
    ///
    /// ```
    /// use rasterlab::geometry::{Mesh, MeshRenderer, RenderSettings};
    /// use rasterlab::raster::{triangle_backend, MultisampleTarget, SamplePattern};
    /// use std::path::Path;
    ///
    /// let bunny = Mesh::load(Path::new("assets/bunny.ply")).unwrap();
    /// let settings = RenderSettings { width: 64, height: 48, ..RenderSettings::default() };
    /// let renderer = MeshRenderer::new(&bunny, settings).unwrap();
    /// let mut target = MultisampleTarget::new(64, 48, SamplePattern::standard(4).unwrap()).unwrap();
    /// renderer.render_multisampled_into(triangle_backend("tiled").unwrap(), &mut target).unwrap();
    /// let image = target.resolve();
    /// assert_eq!((image.width(), image.height()), (64, 48));
    /// ```
    pub fn render_multisampled_into(
        &self,
        backend: &dyn TriangleRasterizer,
        target: &mut MultisampleTarget,
    ) -> Result<FrameStats> {
        self.check_target((target.width(), target.height()))?;
        if self.settings.mipmapped() {
            return Err(Error::InvalidArgument(
                "a multisampled frame samples textures at level 0 with repeat: leave out --msaa, or --mip, --wrap and --anisotropy".into(),
            ));
        }
        if self.settings.wireframe.is_some() {
            return Err(Error::InvalidArgument(
                "a wireframe is drawn with lines, which are not multisampled: leave out --wireframe or --msaa".into(),
            ));
        }
        let frame_start = Instant::now();
        let options = PipelineOptions {
            multisample: true,
            ..self.settings.pipeline
        };
        // A renderer drawing from several threads at once gives the other
        // threads buffers of their own.
        let mut reused = self.multisampled.try_lock().ok();
        let mut own = Geometry::default();
        let geometry = reused.as_deref_mut().unwrap_or(&mut own);
        pipeline::process_triangles_into(
            geometry,
            &self.vertices,
            &self.triangles,
            &self.transform,
            self.viewport(),
            &options,
        )?;
        let geometry = &*geometry;
        let geometry_time = frame_start.elapsed();
        let start = Instant::now();
        target.clear(self.settings.background);
        let (setups, data) = (&geometry.setups, &geometry.shaded);
        let (depth, lerp) = (self.settings.depth, self.settings.interpolation);
        let blend = self.settings.blend;
        let work = match &self.shader {
            MeshShader::Flat(s) => {
                draw_multisampled(setups, data, backend, s, (depth, blend), lerp, target)
            }
            MeshShader::Gouraud(s) => {
                draw_multisampled(setups, data, backend, s, (depth, blend), lerp, target)
            }
            MeshShader::Diffuse(s) => {
                draw_multisampled(setups, data, backend, s, (depth, blend), lerp, target)
            }
            MeshShader::Normals(s) => {
                draw_multisampled(setups, data, backend, s, (depth, blend), lerp, target)
            }
            MeshShader::Texture(s) => {
                draw_multisampled(setups, data, backend, s, (depth, blend), lerp, target)
            }
        };
        let raster_time = start.elapsed();
        Ok(FrameStats {
            geometry: geometry.stats,
            work,
            geometry_time,
            raster_time,
            times: FrameTimes::new(frame_start.elapsed(), None, geometry_time, raster_time),
        })
    }

    /// Runs the geometry stages into `geometry` and draws the triangles
    /// with `shader`, the stage compiled for its type, clearing the target
    /// as it goes (each row just before its first fragment): the work, and
    /// the time spent rasterizing.
    ///
    /// On one thread a mesh of several batches is assembled and drawn
    /// batch by batch ([`GeometryInParts::process_in_batches`]);
    /// otherwise it is assembled whole (in parts, binned on several
    /// threads), then drawn.
    fn draw<S: FragmentShader>(
        &self,
        geometry: &mut GeometryInParts,
        backend: &dyn TriangleRasterizer,
        shader: &S,
        target: &mut RenderTarget,
    ) -> Result<(WorkCounters, Duration)> {
        let pass = pipeline::Pass {
            shader,
            depth: self.settings.depth,
            interpolation: self.settings.interpolation,
            clear: Clear::all(self.settings.background),
            blend: self.settings.blend,
        };
        if !self.in_batches() {
            geometry.process_into(&self.draw_input())?;
            let start = Instant::now();
            let work = pipeline::draw_runs_binned(&geometry.runs(), backend, pass, target);
            return Ok((work, start.elapsed()));
        }
        let mut draw = BatchDraw::new(target, backend, pass);
        let mut raster_time = Duration::ZERO;
        geometry.process_in_batches(&self.draw_input(), BATCH, |shaded, setups| {
            let start = Instant::now();
            draw.draw(shaded, setups);
            raster_time += start.elapsed();
        })?;
        let start = Instant::now();
        let work = draw.finish();
        Ok((work, raster_time + start.elapsed()))
    }

    /// Draws the edges in a contrasting constant colour, depth-tested with
    /// `less-equal` and pulled slightly towards the viewer so the surface
    /// they lie on does not hide them.
    fn draw_wireframe(
        &self,
        backend: &dyn LineRasterizer,
        lines: &[ShadedLine],
        target: &mut RenderTarget,
    ) {
        let setups: Vec<LineSetup> = lines
            .iter()
            .enumerate()
            .map(|(i, l)| LineSetup {
                id: i as u32,
                from: l.from,
                to: l.to,
            })
            .collect();
        let shader = crate::raster::shader::Constant(Vec4::new(0.1, 0.1, 0.12, 1.0));
        let viewport = crate::raster::edge::PixelRect::of_target(target.width(), target.height());
        let mut stage = FragmentStage::new(target, &shader)
            .with_lines(lines)
            .with_depth(DepthState {
                test: DepthTest::LessEqual,
                write: false,
            });
        stage.line_depth_offset = -2e-4;
        backend.rasterize(&setups, &LineOptions::DEFAULT, viewport, &mut stage);
    }
}

/// Every edge of the triangles once, as (smaller index, larger index), in
/// order of first appearance.
pub fn unique_edges(triangles: &[[u32; 3]]) -> Vec<[u32; 2]> {
    let mut seen = std::collections::HashSet::new();
    let mut edges = Vec::new();
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let e = [a.min(b), a.max(b)];
            if seen.insert(e) {
                edges.push(e);
            }
        }
    }
    edges
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::registry::triangle_backends;
    use crate::raster::vector::{self, Width};
    use std::path::Path;

    /// A 160x120 view of the bundled bunny with `shading`, zoomed so that
    /// triangles cross the near and side planes.
    fn clipped_bunny(shading: Shading) -> RenderSettings {
        RenderSettings {
            width: 160,
            height: 120,
            azimuth: 40.0,
            zoom: 6.0,
            shading,
            ..RenderSettings::default()
        }
    }

    /// The geometry loops (vertex shading, assembly and set-up) and the
    /// stage's span loop compiled for AVX2 give the very bits of their
    /// baseline copies: the same geometry and the same frame, for every
    /// shading, clipped triangles included.
    #[test]
    fn every_copy_of_the_vectorized_loops_gives_the_same_frame() {
        let bunny = Mesh::load(Path::new("assets/bunny.ply")).unwrap();
        for shading in [Shading::Flat, Shading::Gouraud, Shading::Diffuse] {
            let settings = clipped_bunny(shading);
            let renderer = MeshRenderer::new(&bunny, settings).unwrap();
            let baseline = vector::limited_to(Width::Baseline, || renderer.geometry().unwrap());
            assert!(baseline.stats.clipped > 0 && baseline.stats.triangles > 100);
            let frames: Vec<_> = triangle_backends()
                .iter()
                .map(|b| vector::limited_to(Width::Baseline, || renderer.render(*b).unwrap()))
                .collect();
            for copy in vector::copies() {
                let geometry = vector::limited_to(copy, || renderer.geometry().unwrap());
                assert_eq!(geometry.setups, baseline.setups, "{shading} {copy:?}");
                assert_eq!(geometry.shaded, baseline.shaded, "{shading} {copy:?}");
                assert_eq!(geometry.stats, baseline.stats, "{shading} {copy:?}");
                for (b, expected) in triangle_backends().iter().zip(&frames) {
                    let frame = vector::limited_to(copy, || renderer.render(*b).unwrap());
                    assert!(
                        frame.target == expected.target,
                        "{shading} {copy:?} {}",
                        b.name()
                    );
                }
            }
        }
    }

    /// The renderer's draw, compiled for each shading's shader type, gives
    /// the bits of the same draw calling that shader through a `dyn`
    /// pointer, on every back-end, clipped triangles included.
    #[test]
    fn a_shader_of_known_type_gives_the_bits_of_one_behind_a_pointer() {
        let bunny = Mesh::load(Path::new("assets/bunny.ply")).unwrap();
        for shading in [
            Shading::Flat,
            Shading::Gouraud,
            Shading::Diffuse,
            Shading::Normals,
            Shading::Texture,
        ] {
            let settings = clipped_bunny(shading);
            let renderer = MeshRenderer::new(&bunny, settings).unwrap();
            let shader: &dyn FragmentShader = match &renderer.shader {
                MeshShader::Flat(s) => s,
                MeshShader::Gouraud(s) => s,
                MeshShader::Diffuse(s) => s,
                MeshShader::Normals(s) => s,
                MeshShader::Texture(s) => s,
            };
            let geometry = renderer.geometry().unwrap();
            assert!(geometry.stats.clipped > 0 && geometry.stats.triangles > 100);
            for &b in triangle_backends() {
                let mut expected = RenderTarget::new(settings.width, settings.height).unwrap();
                expected.clear_color(settings.background);
                pipeline::draw(
                    &geometry,
                    b,
                    shader,
                    settings.depth,
                    settings.interpolation,
                    &mut expected,
                );
                assert!(
                    renderer.render(b).unwrap().target == expected,
                    "{shading} {}",
                    b.name()
                );
            }
        }
    }

    /// A mesh with an index past its last vertex is refused when the
    /// renderer is made, since its frames do not check the indices again.
    #[test]
    fn a_vertex_index_out_of_range_is_refused_up_front() {
        let mut mesh = Mesh::load(Path::new("assets/bunny.ply")).unwrap();
        let count = mesh.positions.len();
        mesh.triangles[7][1] = count as u32;
        let result = MeshRenderer::new(&mesh, RenderSettings::default());
        assert!(
            matches!(result, Err(Error::IndexOutOfRange { index, count: c }) if index == count as u64 && c == count),
            "{:?}",
            result.err()
        );
    }

    /// The renderer's vertex renumbering changes no bit: each back-end
    /// draws the bunny as the pipeline draws it in the file's order.
    #[test]
    fn renumbered_vertices_draw_the_same_image() {
        let mesh = Mesh::load(Path::new("assets/bunny.ply")).unwrap();
        let settings = RenderSettings {
            width: 96,
            height: 72,
            shading: Shading::Gouraud,
            ..RenderSettings::default()
        };
        let renderer = MeshRenderer::new(&mesh, settings).unwrap();
        let in_file_order: Vec<MeshVertex> = (0..mesh.positions.len())
            .map(|i| MeshVertex {
                position: mesh.positions[i],
                normal: mesh.normals[i],
                uv: glam::Vec2::ZERO,
                color: settings.color,
            })
            .collect();
        let viewport = Viewport {
            width: settings.width,
            height: settings.height,
        };
        let geometry = pipeline::process_triangles(
            &in_file_order,
            &mesh.triangles,
            renderer.transform(),
            viewport,
            &settings.pipeline,
        )
        .unwrap();
        assert_ne!(
            renderer.triangles, mesh.triangles,
            "the bunny was renumbered"
        );
        for &b in triangle_backends() {
            let mut expected = RenderTarget::new(settings.width, settings.height).unwrap();
            expected.clear_color(settings.background);
            pipeline::draw(
                &geometry,
                b,
                &Gouraud,
                settings.depth,
                settings.interpolation,
                &mut expected,
            );
            assert!(
                renderer.render(b).unwrap().target == expected,
                "{}",
                b.name()
            );
        }
    }
}

//! One `rasterlab render`, as a value: what to draw (a mesh, a triangle
//! soup, a line set or a built-in scene), the choices given (every other
//! one taken from [`RenderSettings::default`]), and the PNG file to write;
//! [`RenderRequest::run`] draws it frame after frame and returns a
//! [`RenderReport`] that prints as the command does.
//!
//! Every input takes the renderer's fast path: one framebuffer redrawn
//! frame after frame with the clear folded into the draw, no coverage
//! count, and each frame timed whole, so the time per frame is the time
//! an application pays.
//!
//! ```
//! use rasterlab::measure::{RenderInput, RenderReport, RenderRequest};
//!
//! let dir = tempfile::tempdir().unwrap();
//! let out = dir.path().join("pinwheel.png");
//! let mut request = RenderRequest::new(RenderInput::Scene("pinwheel".into()), &out);
//! request.backend = Some("incremental".into());
//! let report = request.run().unwrap();
//! let RenderReport::Drawing(drawing) = &report else { unreachable!() };
//! assert_eq!(drawing.work.primitives, 8);
//! assert!(report.to_string().starts_with("incremental: 8 primitives"));
//! ```

use crate::error::{Error, Result};
use crate::geometry::input::{read_shapes, Shapes};
use crate::geometry::mesh::Mesh;
use crate::geometry::pipeline::{ClipPlanes, CullMode, FrontFace, GeometryStats, PipelineOptions};
use crate::geometry::render::{MeshRenderer, RenderSettings, Shading};
use crate::geometry::scene::Scene2D;
use crate::geometry::Floor;
use crate::geometry::{milliseconds, optional_milliseconds, FrameTimes};
use crate::measure::workload::LineWorkload;
use crate::raster::derivatives::Derivatives;
use crate::raster::descriptor::{within_budget, WorkBudget};
use crate::raster::edge::FillRule;
use crate::raster::fragment::WorkCounters;
use crate::raster::line::LineSetup;
use crate::raster::multisample::SamplePattern;
use crate::raster::multisample_stage::MultisampleTarget;
use crate::raster::registry::{
    backend, default_line_backend, default_triangle_backend, line_backend, Backend,
};
use crate::raster::shader::{Filter, Flat};
use crate::raster::stage::{Blend, Interpolation};
use crate::raster::target::{DepthState, RenderTarget, MAX_TARGET_SIDE};
use crate::raster::texture::{Anisotropic, LevelMode, Texture, Wrap};
use serde::Serialize;
use std::fmt;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The largest `scale`: each pixel drawn as a cell of at most 64 x 64.
pub const MAX_SCALE: u32 = 64;

/// The culling `render` applies when none is given: back faces, hidden
/// behind the front ones on the closed meshes it draws. (A bare
/// [`RenderSettings::default`] culls nothing, which draws any mesh.)
pub const RENDER_CULL: CullMode = CullMode::Back;

/// What a render draws.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RenderInput {
    /// A file: a mesh (`.ply`, `.ply.gz`, `.obj`), or a triangle soup or
    /// line set in the text format of `rasterlab fragments`.
    File(PathBuf),
    /// A built-in scene by name: a 2D one (see [`Scene2D::built_in`]), or
    /// the receding floor ([`Floor::NAME`]).
    Scene(String),
}

/// The mesh options a render was given; each one left out takes
/// [`RenderSettings::default`]'s value. Given for a 2D input, they are an
/// error (they would silently do nothing).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshOverrides {
    /// How the mesh is coloured.
    pub shading: Option<Shading>,
    /// The texture filter of [`Shading::Texture`].
    pub filter: Option<Filter>,
    /// An image (PNG) for [`Shading::Texture`] in place of the checkerboard.
    pub texture: Option<PathBuf>,
    /// The mip level mode of [`Shading::Texture`].
    pub mip: Option<LevelMode>,
    /// The wrap mode of [`Shading::Texture`].
    pub wrap: Option<Wrap>,
    /// The most anisotropic probes of [`Shading::Texture`].
    pub anisotropy: Option<u32>,
    /// How [`Shading::Texture`]'s anisotropy is filtered.
    pub anisotropic: Option<Anisotropic>,
    /// How [`Shading::Texture`]'s derivatives are computed.
    pub derivatives: Option<Derivatives>,
    /// Perspective-correct or linear varyings.
    pub interpolation: Option<Interpolation>,
    /// Back-face culling (`render`'s default: [`RENDER_CULL`]).
    pub cull: Option<CullMode>,
    /// The winding of front faces on screen.
    pub front_face: Option<FrontFace>,
    /// The side planes triangles are clipped at (default the guard band).
    pub clip: Option<ClipPlanes>,
    /// A line back-end drawing the triangle edges over the surface.
    pub wireframe: Option<String>,
    /// Camera angle around the vertical axis, degrees.
    pub azimuth: Option<f32>,
    /// Camera angle above the horizon, degrees.
    pub elevation: Option<f32>,
    /// Zoom factor (1 frames the whole mesh).
    pub zoom: Option<f32>,
}

impl MeshOverrides {
    /// The command-line names of the options given.
    pub fn given(&self) -> Vec<&'static str> {
        [
            ("--shading", self.shading.is_some()),
            ("--filter", self.filter.is_some()),
            ("--texture", self.texture.is_some()),
            ("--mip", self.mip.is_some()),
            ("--wrap", self.wrap.is_some()),
            ("--anisotropy", self.anisotropy.is_some()),
            ("--anisotropic", self.anisotropic.is_some()),
            ("--derivatives", self.derivatives.is_some()),
            ("--interpolation", self.interpolation.is_some()),
            ("--cull", self.cull.is_some()),
            ("--front-face", self.front_face.is_some()),
            ("--clip", self.clip.is_some()),
            ("--wireframe", self.wireframe.is_some()),
            ("--azimuth", self.azimuth.is_some()),
            ("--elevation", self.elevation.is_some()),
            ("--zoom", self.zoom.is_some()),
        ]
        .into_iter()
        .filter_map(|(name, given)| given.then_some(name))
        .collect()
    }

    /// `settings` with the options given put in.
    pub fn apply(&self, settings: RenderSettings) -> Result<RenderSettings> {
        let mut pipeline = settings.pipeline;
        pipeline.cull = self.cull.unwrap_or(pipeline.cull);
        pipeline.front_face = self.front_face.unwrap_or(pipeline.front_face);
        pipeline.clip = self.clip.unwrap_or(pipeline.clip);
        let wireframe = match &self.wireframe {
            Some(name) => Some(line_backend(name)?),
            None => settings.wireframe,
        };
        Ok(RenderSettings {
            azimuth: self.azimuth.unwrap_or(settings.azimuth),
            elevation: self.elevation.unwrap_or(settings.elevation),
            zoom: self.zoom.unwrap_or(settings.zoom),
            shading: self.shading.unwrap_or(settings.shading),
            filter: self.filter.unwrap_or(settings.filter),
            mip: self.mip.unwrap_or(settings.mip),
            wrap: self.wrap.unwrap_or(settings.wrap),
            anisotropy: self.anisotropy.unwrap_or(settings.anisotropy),
            anisotropic: self.anisotropic.unwrap_or(settings.anisotropic),
            derivatives: self.derivatives.unwrap_or(settings.derivatives),
            interpolation: self.interpolation.unwrap_or(settings.interpolation),
            pipeline,
            wireframe,
            ..settings
        })
    }
}

/// One render: the input, the choices, the output file.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderRequest {
    /// What is drawn.
    pub input: RenderInput,
    /// The back-end by name; `None`: the registry's default triangle
    /// back-end, or its default line back-end for a line set.
    pub backend: Option<String>,
    /// The target's size; `None`: 640x480 for a mesh, the scene's own size
    /// for a scene (required for a 2D file).
    pub size: Option<(u32, u32)>,
    /// The fill rule.
    pub rule: FillRule,
    /// The depth test and write ([`DepthState::OFF`]: colour only).
    pub depth: DepthState,
    /// How fragments are merged with the pixels' colours, and the space
    /// colours are mixed in (the multisample resolve's too).
    pub blend: Blend,
    /// Triangles sorted back to front before they are drawn (2D inputs:
    /// by their mean depth), as transparent surfaces must be for `over`.
    pub sort: bool,
    /// Options for meshes only.
    pub mesh: MeshOverrides,
    /// Frames drawn (the input is loaded once); the report gives the
    /// median frame.
    pub frames: u32,
    /// 2D inputs: each pixel written as a `scale` x `scale` cell (framed in
    /// grey from 4 up), 1 to [`MAX_SCALE`].
    pub scale: u32,
    /// Run even when the work is estimated beyond an hour's (the naive
    /// loop on a large mesh).
    pub force: bool,
    /// Multisample triangles on this pattern through the multisampled
    /// stage, and write the resolved image; `None`: one sample per pixel,
    /// the one-sample stage.
    pub msaa: Option<SamplePattern>,
    /// The PNG file written.
    pub out: PathBuf,
}

impl RenderRequest {
    /// A render of `input` to `out` with every choice at its default: one
    /// frame, the top-left rule, the `less` depth test, scale 1.
    pub fn new(input: RenderInput, out: impl AsRef<Path>) -> RenderRequest {
        RenderRequest {
            input,
            backend: None,
            size: None,
            rule: FillRule::TopLeft,
            depth: DepthState::DEFAULT,
            blend: Blend::REPLACE,
            sort: false,
            mesh: MeshOverrides::default(),
            frames: 1,
            scale: 1,
            force: false,
            msaa: None,
            out: out.as_ref().to_path_buf(),
        }
    }

    /// Draws the request's frames and writes the last one to `out`.
    pub fn run(&self) -> Result<RenderReport> {
        self.run_with_progress(&mut || {})
    }

    /// [`run`](Self::run), calling `frame_done` after each frame (for a
    /// progress bar).
    pub fn run_with_progress(&self, frame_done: &mut dyn FnMut()) -> Result<RenderReport> {
        crate::output::check_file(&self.out, &["png"])?;
        if self.frames == 0 {
            return Err(Error::InvalidArgument("--frames must be at least 1".into()));
        }
        match &self.input {
            RenderInput::Scene(name) if name == Floor::NAME => {
                self.render_floor(frame_done).map(RenderReport::Drawing)
            }
            RenderInput::File(path) if Mesh::is_mesh_path(path) => {
                self.render_mesh(path, frame_done).map(RenderReport::Mesh)
            }
            _ => self.render_drawing(frame_done).map(RenderReport::Drawing),
        }
    }

    /// The back-end named, or `default`.
    fn backend(&self, default: &str) -> Result<(String, Backend)> {
        let name = self.backend.as_deref().unwrap_or(default);
        Ok((name.to_string(), backend(name)?))
    }

    fn render_mesh(&self, path: &Path, frame_done: &mut dyn FnMut()) -> Result<MeshReport> {
        if self.sort {
            return Err(Error::InvalidArgument(format!(
                "{}: --sort orders the triangles of 2D inputs (triangle soups and scenes); \
                 a mesh is drawn in its own order",
                path.display()
            )));
        }
        if self.scale != 1 {
            return Err(Error::InvalidArgument(
                "--scale is for triangle soups, line sets and scenes; a mesh is drawn at --size"
                    .into(),
            ));
        }
        let (_, Backend::Triangle(backend)) = self.backend(default_triangle_backend().name())?
        else {
            return Err(Error::InvalidArgument(format!(
                "{}: a mesh is drawn by a triangle back-end; draw its edges with --wireframe LINE-BACKEND",
                path.display()
            )));
        };
        let start = Instant::now();
        let mesh = Mesh::load(path)?;
        let load_time = start.elapsed();
        let defaults = RenderSettings::default();
        let (width, height) = self.size.unwrap_or((defaults.width, defaults.height));
        let settings = self.mesh.apply(RenderSettings {
            width,
            height,
            depth: self.depth,
            blend: self.blend,
            pipeline: PipelineOptions {
                rule: self.rule,
                cull: RENDER_CULL,
                ..defaults.pipeline
            },
            ..defaults
        })?;
        let mut renderer = MeshRenderer::new(&mesh, settings)?;
        if let Some(texture) = &self.mesh.texture {
            renderer = renderer.with_texture(Texture::load(texture)?)?;
        }
        if !self.force {
            // A multisampled frame walks the triangles once per sample.
            let passes = self.msaa.map_or(1, SamplePattern::count);
            let triangles =
                mesh.triangles.len() as u64 * u64::from(self.frames) * u64::from(passes);
            let pixels = u64::from(width) * u64::from(height);
            within_budget(&backend.descriptor(), triangles, pixels, WorkBudget::Run).map_err(
                |e| match e {
                    Error::TooMuchWork(why) if passes > 1 => Error::TooMuchWork(format!(
                        "{why}, or give --force (the primitives are the {} triangles{}, each walked once per sample, {passes} samples per pixel)",
                        mesh.triangles.len(),
                        if self.frames > 1 { format!(" x {} frames", self.frames) } else { String::new() }
                    )),
                    Error::TooMuchWork(why) => {
                        Error::TooMuchWork(format!("{why}, or give --force"))
                    }
                    e => e,
                },
            )?;
        }
        // One framebuffer, redrawn frame after frame as an application
        // does; coverage is not counted (nothing here reads it). The
        // per-frame buffers are readied (and timed) before the frames, so
        // that each frame is a warm one; a single frame readies them
        // itself, which spares a whole geometry pass (docs/performance-log.md,
        // "2026-12-06, `f354b8e` to `b4efcdc`").
        let mut times = Vec::with_capacity(self.frames as usize);
        let mut last = None;
        let prepare_time = match self.msaa {
            None => {
                let mut target = RenderTarget::without_coverage(width, height)?;
                let prepare_time = if self.frames > 1 {
                    Some(renderer.prepare()?)
                } else {
                    None
                };
                for _ in 0..self.frames {
                    let stats = renderer.render_into(backend, &mut target)?;
                    times.push(stats.times);
                    last = Some(stats);
                    frame_done();
                }
                target.save_png(&self.out)?;
                prepare_time
            }
            Some(pattern) => {
                // The sample buffers, allocated (and touched) before the
                // first frame.
                let start = Instant::now();
                let mut target = MultisampleTarget::new(width, height, pattern)?;
                let prepare_time = Some(start.elapsed());
                for _ in 0..self.frames {
                    let stats = renderer.render_multisampled_into(backend, &mut target)?;
                    times.push(stats.times);
                    last = Some(stats);
                    frame_done();
                }
                target.resolve().save_png(&self.out)?;
                prepare_time
            }
        };
        let last = last.expect("at least one frame");
        Ok(MeshReport {
            mesh: path.to_path_buf(),
            vertices: mesh.positions.len(),
            triangles: mesh.triangles.len(),
            load: load_time,
            prepare: prepare_time,
            geometry: last.geometry,
            backend: backend.name().to_string(),
            width,
            height,
            samples: self.msaa.map_or(1, SamplePattern::count),
            work: last.work,
            frames: self.frames,
            median: FrameTimes::median(&times).unwrap_or(last.times),
            out: self.out.clone(),
        })
    }

    fn render_drawing(&self, frame_done: &mut dyn FnMut()) -> Result<DrawingReport> {
        let given = self.mesh.given();
        if !given.is_empty() {
            return Err(Error::InvalidArgument(format!(
                "{} {} to meshes only; this input is {}",
                given.join(", "),
                if given.len() == 1 { "applies" } else { "apply" },
                match self.input {
                    RenderInput::Scene(_) => "a built-in 2D scene",
                    RenderInput::File(_) => "a 2D file",
                }
            )));
        }
        let size = |default: Option<(u32, u32)>| -> Result<(u32, u32)> {
            self.size.or(default).ok_or_else(|| {
                Error::InvalidArgument("--size is required when rendering a file".into())
            })
        };
        let drawing = match &self.input {
            RenderInput::Scene(name) => {
                let scene = Scene2D::built_in(name)?;
                let (width, height) = size(Some((scene.width, scene.height)))?;
                Drawing::Triangles(Scene2D {
                    width,
                    height,
                    ..scene
                })
            }
            RenderInput::File(path) => match read_shapes(path)? {
                Shapes::Triangles {
                    triangles, looks, ..
                } => {
                    let (w, h) = size(None)?;
                    Drawing::Triangles(Scene2D::from_triangles(w, h, triangles).with_looks(&looks))
                }
                Shapes::Lines { segments, .. } => {
                    let (w, h) = size(None)?;
                    Drawing::Lines(
                        w,
                        h,
                        LineWorkload::new("input", LineSetup::numbered(&segments)),
                    )
                }
            },
        };
        let drawing = match drawing {
            Drawing::Triangles(scene) if self.sort => {
                Drawing::Triangles(scene.sorted_back_to_front())
            }
            Drawing::Lines(..) if self.sort => {
                return Err(Error::InvalidArgument(
                    "--sort orders triangles; a line set has none".into(),
                ))
            }
            drawing => drawing,
        };
        let (width, height) = match &drawing {
            Drawing::Triangles(scene) => (scene.width, scene.height),
            Drawing::Lines(w, h, _) => (*w, *h),
        };
        RenderTarget::check_size(width, height)?;
        let scaled = |side: u32| u64::from(side) * u64::from(self.scale);
        let max_side = u64::from(MAX_TARGET_SIDE);
        if self.scale == 0
            || self.scale > MAX_SCALE
            || scaled(width) > max_side
            || scaled(height) > max_side
        {
            return Err(Error::InvalidArgument(format!(
                "--scale must be 1 to {MAX_SCALE} and the picture at most {MAX_TARGET_SIDE} pixels a side ({width}x{height} x {} is {}x{})",
                self.scale,
                scaled(width),
                scaled(height)
            )));
        }
        // The back-end is looked up once, and must draw what the input holds.
        let (name, chosen) = match &drawing {
            Drawing::Triangles(_) => self.backend(default_triangle_backend().name())?,
            Drawing::Lines(..) => self.backend(default_line_backend().name())?,
        };
        let mut times = Vec::with_capacity(self.frames as usize);
        let mut work = WorkCounters::default();
        let image = match (self.msaa, &drawing, chosen) {
            (None, ..) => {
                // An application's framebuffer: colour and depth, no
                // coverage count (nothing here reads it).
                let mut target = RenderTarget::without_coverage(width, height)?;
                for _ in 0..self.frames {
                    let state = (self.depth, self.blend);
                    let (w, t) = drawing.frame(chosen, self.rule, state, &mut target)?;
                    work = w;
                    times.push(t);
                    frame_done();
                }
                target
            }
            (Some(pattern), Drawing::Triangles(scene), Backend::Triangle(b)) => {
                let mut target = MultisampleTarget::new(width, height, pattern)?;
                for _ in 0..self.frames {
                    let (w, t) = scene.render_frame_multisampled(
                        b,
                        self.rule,
                        (self.depth, self.blend),
                        &Flat,
                        RenderTarget::BLACK,
                        &mut target,
                    );
                    work = w;
                    times.push(t);
                    frame_done();
                }
                target.resolve_in(self.blend.mix_in)
            }
            (Some(_), Drawing::Lines(..), _) => {
                let file = match &self.input {
                    RenderInput::File(path) => format!("{}: ", path.display()),
                    RenderInput::Scene(_) => String::new(),
                };
                return Err(Error::InvalidArgument(format!(
                    "{file}--msaa multisamples triangles; a line set is drawn with lines, which are not multisampled"
                )));
            }
            (Some(_), Drawing::Triangles(_), _) => {
                return Err(Error::InvalidArgument(
                    "triangles are drawn by a triangle back-end (see `rasterlab backends`)".into(),
                ))
            }
        };
        crate::output::write_png(&self.out, &image.to_image_scaled(self.scale))?;
        Ok(DrawingReport {
            backend: name,
            samples: self.msaa.map_or(1, SamplePattern::count),
            work,
            frames: self.frames,
            median: FrameTimes::median(&times).unwrap_or_default(),
            out: self.out.clone(),
        })
    }
}

/// What `render` draws when the input is not a mesh.
enum Drawing {
    Triangles(Scene2D),
    Lines(u32, u32, LineWorkload),
}

impl Drawing {
    /// One frame, timed whole: triangles on the renderer's path (set-up,
    /// then the draw with the clear folded in), lines after a clear of
    /// their own.
    fn frame(
        &self,
        chosen: Backend,
        rule: FillRule,
        state: (DepthState, Blend),
        target: &mut RenderTarget,
    ) -> Result<(WorkCounters, FrameTimes)> {
        match (self, chosen) {
            (Drawing::Triangles(scene), Backend::Triangle(b)) => {
                Ok(scene.render_frame(b, rule, state, &Flat, RenderTarget::BLACK, target))
            }
            (Drawing::Lines(_, _, lines), Backend::Line(b)) => {
                let start = Instant::now();
                target.clear();
                let clear = start.elapsed();
                let raster_start = Instant::now();
                let work = lines.run_blended(b, state.1, target);
                let raster = raster_start.elapsed();
                let times = FrameTimes::new(start.elapsed(), Some(clear), Duration::ZERO, raster);
                Ok((work, times))
            }
            (Drawing::Triangles(_), _) => Err(Error::InvalidArgument(
                "triangles are drawn by a triangle back-end (see `rasterlab backends`)".into(),
            )),
            (Drawing::Lines(..), _) => Err(Error::InvalidArgument(
                "a line set is drawn by a line back-end (see `rasterlab backends`)".into(),
            )),
        }
    }
}

/// What a render did: it prints as `rasterlab render` reports.
#[derive(Clone, Debug, Serialize)]
#[serde(tag = "input", rename_all = "snake_case")]
pub enum RenderReport {
    /// A mesh through the 3D pipeline.
    Mesh(MeshReport),
    /// A triangle soup, line set or scene.
    Drawing(DrawingReport),
}

/// A mesh's render.
#[derive(Clone, Debug, Serialize)]
pub struct MeshReport {
    /// The mesh file.
    pub mesh: PathBuf,
    /// Its vertex count.
    pub vertices: usize,
    /// Its triangle count.
    pub triangles: usize,
    /// Time to load it.
    #[serde(serialize_with = "milliseconds")]
    pub load: Duration,
    /// Time to ready the per-frame buffers before the first frame; none
    /// when a single frame readied them itself.
    #[serde(serialize_with = "optional_milliseconds")]
    pub prepare: Option<Duration>,
    /// What the pipeline did with the triangles (last frame).
    pub geometry: GeometryStats,
    /// The triangle back-end.
    pub backend: String,
    /// Target width.
    pub width: u32,
    /// Target height.
    pub height: u32,
    /// Samples per pixel (1 without multisampling).
    pub samples: u32,
    /// The back-end's work (last frame).
    pub work: WorkCounters,
    /// Frames drawn.
    pub frames: u32,
    /// The median frame, in parts.
    pub median: FrameTimes,
    /// The PNG written.
    pub out: PathBuf,
}

/// A 2D input's render.
#[derive(Clone, Debug, Serialize)]
pub struct DrawingReport {
    /// The back-end.
    pub backend: String,
    /// Samples per pixel (1 without multisampling).
    pub samples: u32,
    /// Its work (last frame).
    pub work: WorkCounters,
    /// Frames drawn.
    pub frames: u32,
    /// The median frame, in parts.
    pub median: FrameTimes,
    /// The PNG written.
    pub out: PathBuf,
}

impl fmt::Display for RenderReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderReport::Mesh(r) => {
                let ms = |d: Duration| d.as_secs_f64() * 1e3;
                let g = &r.geometry;
                let readied = match r.prepare {
                    Some(d) => format!("frame buffers readied in {:.0} ms", ms(d)),
                    None => "frame buffers readied by the frame".to_string(),
                };
                writeln!(
                    f,
                    "{}: {} vertices, {} triangles (loaded in {:.0} ms, {readied})",
                    r.mesh.display(),
                    r.vertices,
                    r.triangles,
                    ms(r.load),
                )?;
                writeln!(
                    f,
                    "pipeline: {} rejected, {} clipped, {} culled, {} degenerate, {} with no pixel centre, {} small and covering none, {} rasterized",
                    g.rejected, g.clipped, g.culled, g.degenerate, g.empty_bounds, g.no_sample, g.triangles
                )?;
                writeln!(
                    f,
                    "{} at {}x{}{}: {} samples tested, {} fragments{}",
                    r.backend,
                    r.width,
                    r.height,
                    multisampled(r.samples),
                    r.work.samples_tested,
                    r.work.fragments,
                    helpers(&r.work)
                )?;
                writeln!(f, "time per frame (median of {}): {}", r.frames, r.median)?;
                writeln!(f, "wrote {}", r.out.display())
            }
            RenderReport::Drawing(r) => {
                writeln!(
                    f,
                    "{}{}: {} primitives, {} samples tested, {} fragments{} -> {}",
                    r.backend,
                    multisampled(r.samples),
                    r.work.primitives,
                    r.work.samples_tested,
                    r.work.fragments,
                    helpers(&r.work),
                    r.out.display()
                )?;
                if r.frames > 1 {
                    writeln!(f, "time per frame (median of {}): {}", r.frames, r.median)?;
                }
                Ok(())
            }
        }
    }
}

/// ", N helper pixels (S% of those shaded)" where quads shaded helpers.
fn helpers(work: &WorkCounters) -> String {
    if work.helpers > 0 {
        format!(
            ", {} helper pixels ({:.1}% of those shaded)",
            work.helpers,
            100.0 * work.helper_share()
        )
    } else {
        String::new()
    }
}

/// ", N samples per pixel" after a multisampled draw's back-end.
fn multisampled(samples: u32) -> String {
    if samples > 1 {
        format!(", {samples} samples per pixel")
    } else {
        String::new()
    }
}

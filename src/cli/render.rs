//! `rasterlab render`: a mesh, a triangle soup, a line set or a built-in
//! scene drawn to a PNG file, with the time per frame.

use super::args::Size;
use super::print::progress_bar;
use clap::Args;
use rasterlab::geometry::frame_times::FrameTimes;
use rasterlab::geometry::input::{read_shapes, Shapes};
use rasterlab::geometry::mesh::Mesh;
use rasterlab::geometry::pipeline::PipelineOptions;
use rasterlab::geometry::render::{MeshRenderer, RenderSettings};
use rasterlab::geometry::scene::Scene2D;
use rasterlab::raster::backend::{
    backend, default_line_backend, default_triangle_backend, line_backend, Backend,
};
use rasterlab::raster::descriptor::{within_budget, WorkBudget};
use rasterlab::raster::edge::FillRule;
use rasterlab::raster::fragment::WorkCounters;
use rasterlab::raster::line::LineSetup;
use rasterlab::raster::shader::Flat;
use rasterlab::raster::target::{DepthState, RenderTarget};
use rasterlab::raster::triangle::TriangleRasterizer;
use rasterlab::{Error, Result};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// A mesh (.ply, .ply.gz, .obj), a triangle soup or a line set.
    input: Option<PathBuf>,
    /// Back-end name (see `rasterlab backends`): a triangle back-end
    /// (default scanline), or a line back-end for a line set (default
    /// bresenham).
    #[arg(long)]
    backend: Option<String>,
    /// Target size `WxH` (meshes: 640x480 by default; scenes: their own size).
    #[arg(long)]
    size: Option<Size>,
    /// Fill rule: top-left, bottom-right, offscreen-point, inclusive, exclusive.
    #[arg(long, default_value = "top-left")]
    rule: String,
    /// Depth test: never, less, equal, less-equal, greater, not-equal,
    /// greater-equal, always (each with depth writes), or off (no depth
    /// buffer: nothing read or written, the fastest colour-only fill).
    #[arg(long, default_value = "less")]
    depth_test: String,
    /// Built-in 2D scene instead of a file: depth-example, split-square, pinwheel, fan.
    #[arg(long, conflicts_with = "input")]
    scene: Option<String>,
    /// Output PNG file.
    #[arg(long)]
    out: PathBuf,
    /// Run even when the estimated work is beyond an hour's worth (the
    /// naive loop on a large mesh).
    #[arg(long)]
    force: bool,
    /// Triangle soups, line sets and scenes: enlarge the picture K times,
    /// each pixel a K x K cell with a grey border (from K = 4), so small
    /// scenes can be seen pixel by pixel.
    #[arg(long, default_value_t = 1)]
    scale: u32,
    #[command(flatten)]
    mesh: MeshArgs,
}

/// Options for rendering a mesh.
#[derive(Args, Debug)]
pub struct MeshArgs {
    /// Shading: flat, gouraud, diffuse (default), normals, texture.
    #[arg(long)]
    shading: Option<String>,
    /// Texture filter for --shading texture: nearest, bilinear (default).
    #[arg(long)]
    filter: Option<String>,
    /// Varying interpolation: perspective (correct, default) or linear (to see the difference).
    #[arg(long)]
    interpolation: Option<String>,
    /// Back-face culling: none, back (default), front.
    #[arg(long)]
    cull: Option<String>,
    /// Winding of front faces as seen on screen: ccw (default), cw.
    #[arg(long)]
    front_face: Option<String>,
    /// Draw the triangle edges over the surface with this line back-end (e.g. bresenham).
    #[arg(long)]
    wireframe: Option<String>,
    /// Camera angle around the vertical axis, degrees (default 0).
    #[arg(long, allow_negative_numbers = true)]
    azimuth: Option<f32>,
    /// Camera angle above the horizon, degrees (default 15).
    #[arg(long, allow_negative_numbers = true)]
    elevation: Option<f32>,
    /// Zoom factor; 1 (the default) frames the whole mesh.
    #[arg(long)]
    zoom: Option<f32>,
    /// Render the same view this many times and report the time per frame
    /// (the file is loaded once).
    #[arg(long, default_value_t = 1)]
    frames: u32,
}

impl MeshArgs {
    /// The mesh-only options given on the command line.
    fn given(&self) -> Vec<&'static str> {
        [
            ("--shading", self.shading.is_some()),
            ("--filter", self.filter.is_some()),
            ("--interpolation", self.interpolation.is_some()),
            ("--cull", self.cull.is_some()),
            ("--front-face", self.front_face.is_some()),
            ("--wireframe", self.wireframe.is_some()),
            ("--azimuth", self.azimuth.is_some()),
            ("--elevation", self.elevation.is_some()),
            ("--zoom", self.zoom.is_some()),
        ]
        .into_iter()
        .filter_map(|(name, given)| given.then_some(name))
        .collect()
    }

    fn settings(
        &self,
        size: Option<Size>,
        rule: FillRule,
        depth: DepthState,
    ) -> Result<RenderSettings> {
        let size = size.unwrap_or(Size {
            width: 640,
            height: 480,
        });
        Ok(RenderSettings {
            width: size.width,
            height: size.height,
            azimuth: self.azimuth.unwrap_or(0.0),
            elevation: self.elevation.unwrap_or(15.0),
            zoom: self.zoom.unwrap_or(1.0),
            shading: self.shading.as_deref().unwrap_or("diffuse").parse()?,
            filter: self.filter.as_deref().unwrap_or("bilinear").parse()?,
            interpolation: self
                .interpolation
                .as_deref()
                .unwrap_or("perspective")
                .parse()?,
            pipeline: PipelineOptions {
                rule,
                cull: self.cull.as_deref().unwrap_or("back").parse()?,
                front_face: self.front_face.as_deref().unwrap_or("ccw").parse()?,
            },
            depth,
            wireframe: self.wireframe.as_deref().map(line_backend).transpose()?,
            ..RenderSettings::default()
        })
    }
}

pub fn run(args: &RenderArgs) -> Result<()> {
    rasterlab::output::check_file(&args.out, &["png"])?;
    let rule: FillRule = args.rule.parse()?;
    let depth = DepthState::from_name(&args.depth_test)?;
    let named = |default: &str| backend(args.backend.as_deref().unwrap_or(default));
    if let Some(path) = args.input.as_deref().filter(|p| Mesh::is_mesh_path(p)) {
        if args.scale != 1 {
            return Err(Error::InvalidArgument(
                "--scale is for triangle soups, line sets and scenes; a mesh is drawn at --size"
                    .into(),
            ));
        }
        let Backend::Triangle(backend) = named(default_triangle_backend().name())? else {
            return Err(Error::InvalidArgument(format!(
                "{}: a mesh is drawn by a triangle back-end; draw its edges with --wireframe LINE-BACKEND",
                path.display()
            )));
        };
        return render_mesh(path, backend, args, rule, depth);
    }
    let given = args.mesh.given();
    if !given.is_empty() {
        return Err(Error::InvalidArgument(format!(
            "{} {} to meshes only; this input is {}",
            given.join(", "),
            if given.len() == 1 { "applies" } else { "apply" },
            if args.scene.is_some() {
                "a built-in 2D scene"
            } else {
                "a 2D file"
            }
        )));
    }
    if args.mesh.frames == 0 {
        return Err(Error::InvalidArgument("--frames must be at least 1".into()));
    }
    let size = |default: Option<(u32, u32)>| -> Result<(u32, u32)> {
        args.size
            .map(|s| (s.width, s.height))
            .or(default)
            .ok_or_else(|| {
                Error::InvalidArgument("--size is required when rendering a file".into())
            })
    };
    let shapes = match (&args.scene, &args.input) {
        (Some(name), _) => {
            let scene = Scene2D::built_in(name)?;
            let (w, h) = size(Some((scene.width, scene.height)))?;
            Drawing::Triangles(Scene2D {
                width: w,
                height: h,
                ..scene
            })
        }
        (None, Some(path)) => match read_shapes(path)? {
            Shapes::Triangles { triangles, .. } => {
                let (w, h) = size(None)?;
                Drawing::Triangles(Scene2D::from_triangles(w, h, triangles))
            }
            Shapes::Lines { segments, .. } => {
                let (w, h) = size(None)?;
                Drawing::Lines(
                    w,
                    h,
                    rasterlab::measure::workload::LineWorkload::new(
                        "input",
                        LineSetup::numbered(&segments),
                    ),
                )
            }
        },
        (None, None) => {
            return Err(Error::InvalidArgument(
                "give a mesh, triangle soup or line set file, or --scene NAME".into(),
            ))
        }
    };
    let (w, h) = match &shapes {
        Drawing::Triangles(scene) => (scene.width, scene.height),
        Drawing::Lines(w, h, _) => (*w, *h),
    };
    RenderTarget::check_size(w, h)?;
    let scaled = |side: u32| u64::from(side) * u64::from(args.scale);
    if args.scale == 0 || args.scale > 64 || scaled(w) > 16384 || scaled(h) > 16384 {
        return Err(Error::InvalidArgument(format!(
            "--scale must be 1 to 64 and the picture at most 16384 pixels a side ({w}x{h} x {} is {}x{})",
            args.scale,
            scaled(w),
            scaled(h)
        )));
    }
    // An application's framebuffer: colour and depth, no coverage count
    // (nothing here reads it).
    let mut target = RenderTarget::without_coverage(w, h)?;
    // The back-end is looked up once, and must draw what the input holds.
    let (name, chosen) = match &shapes {
        Drawing::Triangles(_) => {
            let name = args
                .backend
                .as_deref()
                .unwrap_or(default_triangle_backend().name());
            (name, backend(name)?)
        }
        Drawing::Lines(..) => {
            let name = args
                .backend
                .as_deref()
                .unwrap_or(default_line_backend().name());
            (name, backend(name)?)
        }
    };
    // Each frame is timed whole: triangles on the renderer's path (set-up,
    // then the draw with the clear folded in), lines after a clear of
    // their own.
    let draw = |target: &mut RenderTarget| match (&shapes, chosen) {
        (Drawing::Triangles(scene), Backend::Triangle(b)) => {
            Ok(scene.render_frame(b, rule, depth, &Flat, RenderTarget::BLACK, target))
        }
        (Drawing::Lines(_, _, lines), Backend::Line(b)) => {
            let start = Instant::now();
            target.clear();
            let clear = start.elapsed();
            let raster_start = Instant::now();
            let work = lines.run(b, target);
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
    };
    let mut times = Vec::with_capacity(args.mesh.frames as usize);
    let mut work = WorkCounters::default();
    for _ in 0..args.mesh.frames {
        let (w, t) = draw(&mut target)?;
        work = w;
        times.push(t);
    }
    rasterlab::output::write_png(&args.out, &target.to_image_scaled(args.scale))?;
    say!(
        "{name}: {} primitives, {} samples tested, {} fragments -> {}",
        work.primitives,
        work.samples_tested,
        work.fragments,
        args.out.display()
    )?;
    if let Some(median) = FrameTimes::median(&times).filter(|_| args.mesh.frames > 1) {
        say!("time per frame (median of {}): {median}", args.mesh.frames)?;
    }
    Ok(())
}

/// What `render` draws when the input is not a mesh.
enum Drawing {
    Triangles(Scene2D),
    Lines(u32, u32, rasterlab::measure::workload::LineWorkload),
}

fn render_mesh(
    path: &Path,
    backend: &'static dyn TriangleRasterizer,
    args: &RenderArgs,
    rule: FillRule,
    depth: DepthState,
) -> Result<()> {
    if args.mesh.frames == 0 {
        return Err(Error::InvalidArgument("--frames must be at least 1".into()));
    }
    let start = Instant::now();
    let mesh = Mesh::load(path)?;
    let load_time = start.elapsed();
    let renderer = MeshRenderer::new(&mesh, args.mesh.settings(args.size, rule, depth)?)?;
    if !args.force {
        let (width, height) = (renderer.settings().width, renderer.settings().height);
        let triangles = mesh.triangles.len() as u64 * u64::from(args.mesh.frames);
        let pixels = u64::from(width) * u64::from(height);
        within_budget(&backend.descriptor(), triangles, pixels, WorkBudget::Run).map_err(|e| {
            match e {
                Error::TooMuchWork(why) => Error::TooMuchWork(format!("{why}, or give --force")),
                e => e,
            }
        })?;
    }
    // One framebuffer, redrawn frame after frame as an application does;
    // coverage is not counted (nothing here reads it).
    let (width, height) = (renderer.settings().width, renderer.settings().height);
    let mut target = RenderTarget::without_coverage(width, height)?;
    // The per-frame buffers are readied (and timed) before the frames.
    let prepare_time = renderer.prepare()?;
    let mut times = Vec::with_capacity(args.mesh.frames as usize);
    let bar = progress_bar(u64::from(args.mesh.frames), "frames");
    let mut last = renderer.render_into(backend, &mut target)?;
    times.push(last.times);
    bar.inc(1);
    for _ in 1..args.mesh.frames {
        last = renderer.render_into(backend, &mut target)?;
        times.push(last.times);
        bar.inc(1);
    }
    bar.finish_and_clear();
    let median = FrameTimes::median(&times).unwrap_or(last.times);
    target.save_png(&args.out)?;
    let g = last.geometry;
    let s = renderer.settings();
    say!(
        "{}: {} vertices, {} triangles (loaded in {:.0} ms, frame buffers readied in {:.0} ms)",
        path.display(),
        mesh.positions.len(),
        mesh.triangles.len(),
        load_time.as_secs_f64() * 1e3,
        prepare_time.as_secs_f64() * 1e3
    )?;
    say!(
        "pipeline: {} rejected, {} clipped, {} culled, {} degenerate, {} with no pixel centre, {} rasterized",
        g.rejected, g.clipped, g.culled, g.degenerate, g.empty_bounds, g.triangles
    )?;
    say!(
        "{} at {}x{}: {} samples tested, {} fragments",
        backend.name(),
        s.width,
        s.height,
        last.work.samples_tested,
        last.work.fragments
    )?;
    say!("time per frame (median of {}): {median}", args.mesh.frames)?;
    say!("wrote {}", args.out.display())?;
    Ok(())
}

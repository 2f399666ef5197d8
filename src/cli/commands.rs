//! One function per subcommand.

use clap::Args;
use rasterlab::geometry::input::{read_shapes, Shapes};
use rasterlab::geometry::mesh::Mesh;
use rasterlab::geometry::pipeline::{CullMode, PipelineOptions};
use rasterlab::geometry::render::{MeshRenderer, RenderSettings};
use rasterlab::geometry::scene::{setup_triangles, Scene2D};
use rasterlab::raster::backend::{
    all_backends, backend, line_backend, triangle_backend, triangle_backends, Backend,
};
use rasterlab::raster::edge::FillRule;
use rasterlab::raster::edge::PixelRect;
use rasterlab::raster::fragment::FragmentList;
use rasterlab::raster::fragment::WorkCounters;
use rasterlab::raster::line::{Connectivity, Endpoints, LineOptions, LineSetup};
use rasterlab::raster::shader::Flat;
use rasterlab::raster::target::{DepthState, RenderTarget};
use rasterlab::raster::triangle::TriangleRasterizer;
use rasterlab::teaching::grid_picture::GridPicture;
use rasterlab::teaching::report::{CompareInput, Report};
use rasterlab::teaching::trace::LineEnds;
use rasterlab::{Error, Result};
use std::io::Write;
use std::path::Path;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// Prints a line on standard output; a closed or full output is an
/// [`Error::Write`], not a panic.
macro_rules! say {
    ($($arg:tt)*) => {
        writeln!(std::io::stdout().lock(), $($arg)*).map_err(stdout_error)
    };
}

/// Prints text on standard output, as [`say!`] without the newline.
macro_rules! say_raw {
    ($($arg:tt)*) => {
        write!(std::io::stdout().lock(), $($arg)*).map_err(stdout_error)
    };
}

/// A `WxH` size.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Size {
    pub width: u32,
    pub height: u32,
}

impl std::str::FromStr for Size {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (w, h) = s
            .split_once(['x', 'X'])
            .ok_or_else(|| format!("`{s}` is not a size like 640x480"))?;
        let parse = |v: &str| {
            v.trim()
                .parse::<u32>()
                .map_err(|_| format!("`{s}` is not a size like 640x480"))
        };
        Ok(Size {
            width: parse(w)?,
            height: parse(h)?,
        })
    }
}

pub fn backends() -> Result<()> {
    let mut out = std::io::stdout().lock();
    for b in all_backends() {
        writeln!(out, "{} {} {}", b.name, b.kind, b.description).map_err(stdout_error)?;
    }
    Ok(())
}

fn stdout_error(e: std::io::Error) -> Error {
    Error::write("<stdout>", &e)
}

#[derive(Args, Debug)]
pub struct FragmentsArgs {
    /// Back-end name (see `rasterlab backends`).
    #[arg(long)]
    backend: String,
    /// Target size, `WxH`.
    #[arg(long)]
    size: Size,
    /// Triangle fill rule: top-left, bottom-right, offscreen-point, inclusive, exclusive.
    #[arg(long, default_value = "top-left")]
    rule: String,
    #[command(flatten)]
    line: LineArgs,
    /// Triangle soup (`x0 y0 x1 y1 x2 y2` per line) or line set (`x0 y0 x1 y1` per line).
    file: PathBuf,
}

/// Options of the line back-ends.
#[derive(Args, Debug)]
pub struct LineArgs {
    /// Line connectivity: 8 or 4.
    #[arg(long, default_value = "8")]
    connectivity: String,
    /// Line endpoints: inclusive or half-open.
    #[arg(long, default_value = "inclusive")]
    endpoints: String,
    /// Draw lines so the pixels do not depend on the direction of travel.
    #[arg(long)]
    symmetric: bool,
}

impl LineArgs {
    fn options(&self) -> Result<LineOptions> {
        Ok(LineOptions {
            connectivity: self.connectivity.parse::<Connectivity>()?,
            endpoints: self.endpoints.parse::<Endpoints>()?,
            symmetric: self.symmetric,
        })
    }
}

pub fn fragments(args: &FragmentsArgs) -> Result<()> {
    let backend = backend(&args.backend)?;
    let rule: FillRule = args.rule.parse()?;
    let options = args.line.options()?;
    if let Backend::Line(b) = backend {
        b.check_options(&options)?;
    }
    RenderTarget::check_size(args.size.width, args.size.height)?;
    let viewport = PixelRect::of_target(args.size.width, args.size.height);
    let shapes = read_shapes(&args.file)?;
    let mut list = FragmentList::default();
    match (backend, shapes) {
        (Backend::Triangle(b), Shapes::Triangles { triangles, .. }) => {
            b.rasterize(&setup_triangles(&triangles, rule), viewport, &mut list);
        }
        (Backend::Line(b), Shapes::Lines { segments, .. }) => {
            let setups = LineSetup::numbered(&segments);
            b.rasterize(&setups, &options, viewport, &mut list);
        }
        (Backend::Triangle(b), Shapes::Lines { .. }) => {
            return Err(kind_mismatch(
                &args.file,
                b.name(),
                "triangles",
                "line segments",
            ))
        }
        (Backend::Line(b), Shapes::Triangles { .. }) => {
            return Err(kind_mismatch(
                &args.file,
                b.name(),
                "line segments",
                "triangles",
            ))
        }
    }
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    for f in &list.triangles {
        writeln!(out, "{} {} {}", f.x, f.y, f.triangle).map_err(stdout_error)?;
    }
    let weighted = matches!(backend, Backend::Line(b) if b.anti_aliased());
    for f in &list.lines {
        if weighted {
            writeln!(out, "{} {} {} {:.4}", f.x, f.y, f.line, f.coverage).map_err(stdout_error)?;
        } else {
            writeln!(out, "{} {} {}", f.x, f.y, f.line).map_err(stdout_error)?;
        }
    }
    out.flush().map_err(stdout_error)
}

fn kind_mismatch(file: &std::path::Path, name: &str, draws: &str, holds: &str) -> Error {
    Error::InvalidArgument(format!(
        "{}: back-end `{name}` draws {draws}, but the file holds {holds}",
        file.display()
    ))
}

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

pub fn render(args: &RenderArgs) -> Result<()> {
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
        let Backend::Triangle(backend) = named("scanline")? else {
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
    let mut target = RenderTarget::new(w, h)?;
    // The back-end is looked up once, and must draw what the input holds.
    let (name, chosen) = match &shapes {
        Drawing::Triangles(_) => {
            let name = args.backend.as_deref().unwrap_or("scanline");
            (name, backend(name)?)
        }
        Drawing::Lines(..) => {
            let name = args.backend.as_deref().unwrap_or("bresenham");
            (name, backend(name)?)
        }
    };
    let draw = |target: &mut RenderTarget| match (&shapes, chosen) {
        (Drawing::Triangles(scene), Backend::Triangle(b)) => {
            Ok(scene.draw(b, rule, depth, &Flat, target))
        }
        (Drawing::Lines(_, _, lines), Backend::Line(b)) => Ok(lines.run(b, target)),
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
        target.clear();
        let start = Instant::now();
        work = draw(&mut target)?;
        times.push(start.elapsed());
    }
    rasterlab::output::write_png(&args.out, &target.to_image_scaled(args.scale))?;
    say!(
        "{name}: {} primitives, {} samples tested, {} fragments -> {}",
        work.primitives,
        work.samples_tested,
        work.fragments,
        args.out.display()
    )?;
    if args.mesh.frames > 1 {
        times.sort();
        say!(
            "time per frame (median of {}): {:.3} ms",
            args.mesh.frames,
            times[times.len() / 2].as_secs_f64() * 1e3
        )?;
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
        check_estimate(
            backend,
            mesh.triangles.len() as u64 * u64::from(args.mesh.frames),
            u64::from(width) * u64::from(height),
        )?;
    }
    // One framebuffer, redrawn frame after frame as an application does;
    // coverage is not counted (nothing here reads it).
    let (width, height) = (renderer.settings().width, renderer.settings().height);
    let mut target = RenderTarget::without_coverage(width, height)?;
    let mut times: Vec<(Duration, Duration)> = Vec::with_capacity(args.mesh.frames as usize);
    let bar = progress_bar(u64::from(args.mesh.frames), "frames");
    let mut last = renderer.render_into(backend, &mut target)?;
    times.push((last.geometry_time, last.raster_time));
    bar.inc(1);
    for _ in 1..args.mesh.frames {
        last = renderer.render_into(backend, &mut target)?;
        times.push((last.geometry_time, last.raster_time));
        bar.inc(1);
    }
    bar.finish_and_clear();
    let median = |f: &dyn Fn(&(Duration, Duration)) -> Duration| {
        let mut t: Vec<Duration> = times.iter().map(f).collect();
        t.sort();
        t[t.len() / 2]
    };
    let geometry = median(&|t| t.0);
    let raster = median(&|t| t.1);
    let total = median(&|t| t.0 + t.1);
    target.save_png(&args.out)?;
    let g = last.geometry;
    let s = renderer.settings();
    say!(
        "{}: {} vertices, {} triangles (loaded in {:.0} ms)",
        path.display(),
        mesh.positions.len(),
        mesh.triangles.len(),
        load_time.as_secs_f64() * 1e3
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
    say!(
        "time per frame (median of {}): {:.2} ms = geometry {:.2} ms + raster {:.2} ms",
        args.mesh.frames,
        total.as_secs_f64() * 1e3,
        geometry.as_secs_f64() * 1e3,
        raster.as_secs_f64() * 1e3
    )?;
    say!("wrote {}", args.out.display())?;
    Ok(())
}

/// Sample tests a back-end may be asked for without `--force`: about a
/// minute of the naive loop.
const TEST_BUDGET: u64 = 10_000_000_000;

/// Sample tests per second the naive loop manages, for the estimate.
const NAIVE_TESTS_PER_SECOND: f64 = 1e8;

/// Refuses, with an estimate, a run whose tests do not follow the
/// triangles' size and are beyond [`TEST_BUDGET`].
fn check_estimate(backend: &dyn TriangleRasterizer, triangles: u64, pixels: u64) -> Result<()> {
    match backend.tests_whatever_the_size(triangles, pixels) {
        Some(tests) if tests > TEST_BUDGET => Err(Error::TooMuchWork(format!(
            "`{}` would test about {tests:.2e} samples ({triangles} triangles x {pixels} pixels), \
             roughly {:.0} minutes; choose a faster back-end (scanline, tiled) or give --force",
            backend.name(),
            tests as f64 / NAIVE_TESTS_PER_SECOND / 60.0
        ))),
        _ => Ok(()),
    }
}

/// A progress bar on standard error for `total` steps; hidden when the run
/// is short or standard error is not a terminal (indicatif's own check).
fn progress_bar(total: u64, what: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(total);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} {msg} ({eta} left)")
            .expect("a valid progress template"),
    );
    bar.set_message(what.to_string());
    bar
}

#[derive(Args, Debug)]
pub struct DemoArgs {
    /// Directory the pictures are written to.
    #[arg(long, default_value = "demo-output")]
    out: PathBuf,
}

/// The bundled meshes the demo renders, relative to the crate root.
const DEMO_MESHES: [(&str, &str); 2] = [
    ("bunny", "assets/bunny.ply"),
    ("dragon-res4", "assets/dragon_vrip_res4.ply.gz"),
];

pub fn demo(args: &DemoArgs) -> Result<()> {
    rasterlab::output::check_dir(&args.out)?;
    say!(
        "{:<16} {:<12} {:>10} {:>10} {:>9}  identical to naive",
        "scene",
        "back-end",
        "tested",
        "fragments",
        "time"
    )?;
    let mut all_identical = true;
    let mut report = |name: &str,
                      backend: &dyn TriangleRasterizer,
                      work: &WorkCounters,
                      time: Duration,
                      identical: bool|
     -> Result<()> {
        all_identical &= identical;
        say!(
            "{:<16} {:<12} {:>10} {:>10} {:>7.2}ms  {}",
            name,
            backend.name(),
            work.samples_tested,
            work.fragments,
            time.as_secs_f64() * 1e3,
            if identical { "yes" } else { "NO" }
        )
    };
    for name in Scene2D::BUILT_IN {
        let scene = Scene2D::built_in(name)?;
        let mut reference: Option<RenderTarget> = None;
        for backend in triangle_backends() {
            let start = Instant::now();
            let (target, work) = scene.render(*backend, FillRule::TopLeft, &Flat)?;
            let time = start.elapsed();
            report(
                name,
                *backend,
                &work,
                time,
                reference.as_ref().is_none_or(|r| *r == target),
            )?;
            if reference.is_none() {
                target.save_png(&args.out.join(format!("{name}.png")))?;
                reference = Some(target);
            }
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for (name, file) in DEMO_MESHES {
        let mesh = Mesh::load(&root.join(file))?;
        let settings = RenderSettings {
            width: 320,
            height: 240,
            azimuth: 30.0,
            pipeline: PipelineOptions {
                cull: CullMode::Back,
                ..PipelineOptions::default()
            },
            ..RenderSettings::default()
        };
        let renderer = MeshRenderer::new(&mesh, settings)?;
        let mut reference: Option<RenderTarget> = None;
        for backend in triangle_backends() {
            let frame = renderer.render(*backend)?;
            let identical = reference.as_ref().is_none_or(|r| *r == frame.target);
            report(
                name,
                *backend,
                &frame.stats.work,
                frame.stats.raster_time,
                identical,
            )?;
            if reference.is_none() {
                frame
                    .target
                    .save_png(&args.out.join(format!("{name}.png")))?;
                reference = Some(frame.target);
            }
        }
    }
    say!(
        "pictures in {}/ (meshes: Stanford 3D Scanning Repository)",
        args.out.display()
    )?;
    if all_identical {
        say!("every back-end produced bit-identical colour, depth and coverage buffers")?;
        Ok(())
    } else {
        Err(Error::Mismatch(
            "back-ends disagree: see the table above".into(),
        ))
    }
}

#[derive(Args, Debug)]
pub struct ExplainArgs {
    /// What to trace: bresenham, direct, dda, wu, diamond (a line: x0 y0
    /// x1 y1, pixel indices unless --screen); bbox, naive, scanline,
    /// incremental, tiled (a triangle: x0 y0 x1 y1 x2 y2, in screen
    /// coordinates); depth-buffer (triangles of 7
    /// numbers each, x0 y0 x1 y1 x2 y2 z, or none for the course's
    /// depth-buffer example). Any other back-end: --picture only.
    #[arg(long)]
    backend: String,
    /// Fill rule for triangles.
    #[arg(long, default_value = "top-left")]
    rule: String,
    /// Grid size, `WxH` (16x16 for one triangle, 14x9 for the course's
    /// depth-buffer example).
    #[arg(long)]
    size: Option<Size>,
    /// Read line endpoints as screen coordinates, as `rasterlab fragments`
    /// and files do (`0.5 0.5 7.5 3.5`), instead of pixel indices whose
    /// centres the line joins (`0 0 7 3`, the course's convention).
    #[arg(long)]
    screen: bool,
    /// Also write a zoomed grid picture of the same input (`.svg` or
    /// `.png`): the pixels tested and the fragments emitted.
    #[arg(long)]
    picture: Option<PathBuf>,
    /// The coordinates.
    #[arg(allow_negative_numbers = true)]
    coordinates: Vec<f64>,
}

impl ExplainArgs {
    fn size(&self, default: (u32, u32)) -> Result<(u32, u32)> {
        let (w, h) = self.size.map_or(default, |s| (s.width, s.height));
        RenderTarget::check_size(w, h)?;
        Ok((w, h))
    }

    fn want(&self, n: usize, what: &str) -> Result<()> {
        let got = self.coordinates.len();
        if got == n {
            Ok(())
        } else {
            Err(Error::InvalidArgument(format!(
                "{} traces {what}: give {n} numbers, not {got}",
                self.backend
            )))
        }
    }

    fn triangle(&self) -> Result<[(f64, f64); 3]> {
        self.want(6, "a triangle")?;
        let c = &self.coordinates;
        Ok([(c[0], c[1]), (c[2], c[3]), (c[4], c[5])])
    }

    fn line(&self) -> Result<LineEnds> {
        self.want(4, "a line")?;
        let c = &self.coordinates;
        let numbers = [c[0], c[1], c[2], c[3]];
        if self.screen {
            LineEnds::screen(numbers)
        } else {
            LineEnds::pixels(numbers)
        }
    }

    /// The depth-buffer input: the course's example, or triangles of seven
    /// numbers each.
    fn depth_scene(&self) -> Result<Scene2D> {
        if self.coordinates.is_empty() {
            let mut scene = Scene2D::depth_example(true);
            (scene.width, scene.height) = self.size((scene.width, scene.height))?;
            return Ok(scene);
        }
        let (width, height) = self.size(EXPLAIN_GRID)?;
        Scene2D::with_depths(width, height, &self.coordinates)
    }
}

/// The grid `explain` draws on unless `--size` says otherwise.
const EXPLAIN_GRID: (u32, u32) = (16, 16);

pub fn explain(args: &ExplainArgs) -> Result<()> {
    let rule: FillRule = args.rule.parse()?;
    if let Some(path) = &args.picture {
        rasterlab::output::check_file(path, &GridPicture::EXTENSIONS)?;
    }
    let (width, height) = args.size(EXPLAIN_GRID)?;
    let text = match args.backend.as_str() {
        "depth-buffer" => {
            let scene = args.depth_scene()?;
            let text = rasterlab::teaching::trace::depth_buffer_trace(
                &scene,
                triangle_backend("bbox")?,
                rule,
            )?;
            if let Some(path) = &args.picture {
                GridPicture::depth_buffer(&scene, rule)?.save(path)?;
            }
            return say_raw!("{text}");
        }
        name => match backend(name).map_err(|_| Error::UnknownName {
            what: "rasterizer back-end",
            name: name.to_string(),
            known: rasterlab::raster::backend::all_backends()
                .iter()
                .map(|b| b.name)
                .collect::<Vec<_>>()
                .join(", ")
                + "; or depth-buffer, the depth buffer's trace",
        })? {
            Backend::Triangle(b) => rasterlab::teaching::trace::of_triangle_backend(
                b,
                args.triangle()?,
                rule,
                width,
                height,
            )?,
            Backend::Line(b) => rasterlab::teaching::trace::of_line_backend(b, &args.line()?)?,
        },
    };
    if let Some(path) = &args.picture {
        let picture = match backend(&args.backend)? {
            Backend::Triangle(b) => {
                GridPicture::of_triangles(b, &[args.triangle()?], rule, width, height)?
            }
            Backend::Line(b) => {
                GridPicture::of_lines(b, &[args.line()?], &LineOptions::DEFAULT, width, height)?
            }
        };
        picture.save(path)?;
        eprintln!("picture: {}", path.display());
    }
    say_raw!("{text}")
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Workload set: quick (seconds) or full (the `cargo bench` sizes).
    #[arg(long, default_value = "quick")]
    set: rasterlab::measure::benchmark::WorkloadSet,
    /// Target size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1920x1080")]
    size: Size,
    /// Timed runs per back-end and workload (the median is reported).
    #[arg(long, default_value_t = 5)]
    samples: usize,
    /// Meshes to render (default: the bundled dragon).
    #[arg(long = "mesh")]
    meshes: Vec<PathBuf>,
    /// Print JSON instead of the table.
    #[arg(long)]
    json: bool,
    /// Directory for bench.json, bench.png and bench.svg.
    #[arg(long, default_value = "bench-output")]
    out: PathBuf,
}

pub fn bench(args: &BenchArgs) -> Result<()> {
    use rasterlab::measure::benchmark::{self, BenchOptions};
    check_samples(args.samples)?;
    rasterlab::output::check_dir(&args.out)?;
    let meshes = if args.meshes.is_empty() {
        vec![Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/dragon_vrip_res4.ply.gz")]
    } else {
        args.meshes.clone()
    };
    let options = BenchOptions {
        set: args.set,
        width: args.size.width,
        height: args.size.height,
        samples: args.samples,
        meshes,
    };
    let bar = progress_bar(0, "");
    let results = benchmark::run(&options, &mut |p| {
        bar.set_length(p.total as u64);
        bar.set_position(p.done as u64);
        bar.set_message(p.pair.to_string());
    });
    bar.finish_and_clear();
    let results = results?;
    if args.json {
        say!("{}", benchmark::to_json(&results))?;
    } else {
        say_raw!("{}", benchmark::table(&results))?;
    }
    benchmark::write_outputs(&results, &args.out)?;
    eprintln!(
        "threads: {}; wrote bench.json, bench.png, bench.svg in {}",
        rayon::current_num_threads(),
        args.out.display()
    );
    Ok(())
}

/// Timed runs per measurement: at least one, at most [`MAX_SAMPLES`].
fn check_samples(samples: usize) -> Result<()> {
    if (1..=MAX_SAMPLES).contains(&samples) {
        Ok(())
    } else {
        Err(Error::InvalidArgument(format!(
            "--samples must be between 1 and {MAX_SAMPLES}, not {samples}"
        )))
    }
}

/// More timed runs than this add nothing to a median.
const MAX_SAMPLES: usize = 1000;

#[derive(Args, Debug)]
pub struct CompareArgs {
    /// A triangle soup or polygon file, a line set file, or a mesh (.ply,
    /// .ply.gz, .obj).
    input: PathBuf,
    /// Target size, WIDTHxHEIGHT.
    #[arg(long, default_value = "64x64")]
    size: Size,
    /// Directory the report (index.html) is written to.
    #[arg(long, default_value = "compare-output")]
    out: PathBuf,
    /// Timed runs per back-end (the median is reported).
    #[arg(long, default_value_t = 3)]
    samples: usize,
}

pub fn compare(args: &CompareArgs) -> Result<()> {
    let (width, height) = (args.size.width, args.size.height);
    check_samples(args.samples)?;
    Report::check_memory(width, height)?;
    rasterlab::output::check_dir(&args.out)?;
    let input = if Mesh::is_mesh_path(&args.input) {
        CompareInput::Mesh(Box::new(Mesh::load(&args.input)?))
    } else {
        match read_shapes(&args.input)? {
            Shapes::Triangles { triangles, .. } => {
                CompareInput::Triangles(Scene2D::from_triangles(width, height, triangles))
            }
            Shapes::Lines { segments, .. } => CompareInput::Lines(LineSetup::numbered(&segments)),
        }
    };
    let report = Report::compare(&input, width, height, args.samples)?;
    let path = report.write(&args.out)?;
    say!("reference: {}", report.reference_note)?;
    say!(
        "{:<12} {:>10} {:>10} {:>9} {:>10}  differing pixels vs {}",
        "back-end",
        "fragments",
        "tested",
        "tests/frag",
        "time",
        report.reference
    )?;
    for run in &report.runs {
        say!(
            "{:<12} {:>10} {:>10} {:>9} {:>8.3}ms  {}",
            run.name,
            run.work.fragments,
            run.work.samples_tested,
            run.tests_per_fragment_text(),
            run.time.as_secs_f64() * 1e3,
            run.differing_pixels
        )?;
    }
    say!("report: {}", path.display())?;
    Ok(())
}

#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("subject").required(true).args(["exec", "backend"])))]
pub struct CheckArgs {
    /// The program under test: a command line run once per case, with
    /// {input}, {width}, {height} and {rule} replaced; it prints `x y id`
    /// per fragment.
    #[arg(long)]
    exec: Option<String>,
    /// Check a built-in back-end instead (see `rasterlab backends`).
    #[arg(long)]
    backend: Option<String>,
    /// What the cases hold: triangles or lines (default: the back-end's
    /// kind, or triangles).
    #[arg(long)]
    kind: Option<String>,
    /// Triangles: the fill rule the answer must follow exactly, or
    /// `watertight` (no gaps, no double draws, under any consistent rule).
    /// Default: top-left.
    #[arg(long)]
    rule: Option<String>,
    /// Lines: midpoint (exactly `bresenham`), diamond (exactly `diamond`)
    /// or vulkan (Vulkan's tolerance of the diamond rule). Default:
    /// midpoint.
    #[arg(long)]
    convention: Option<String>,
    /// How many cases.
    #[arg(long, default_value_t = 150)]
    cases: u32,
    /// Seed of the case generator (the same seed gives the same cases).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Seconds a program may take on one case.
    #[arg(long, default_value_t = 5.0)]
    timeout: f64,
    /// Directory for counterexample.txt, counterexample.svg and report.html.
    #[arg(long, default_value = "check-output")]
    out: PathBuf,
    /// Print the verdict as JSON on standard output (for autograders).
    #[arg(long)]
    json: bool,
}

/// More cases than this are refused: a check is for minutes, not hours.
const MAX_CHECK_CASES: u32 = 1_000_000;

pub fn check(args: &CheckArgs) -> Result<()> {
    use rasterlab::check::{self, judge::LineConvention, Builtin, CheckOptions, Program, Property};
    let chosen = args.backend.as_deref().map(backend).transpose()?;
    let kind = match (args.kind.as_deref(), chosen) {
        (Some("triangles"), _) | (None, None | Some(Backend::Triangle(_))) => "triangles",
        (Some("lines"), _) | (None, Some(Backend::Line(_))) => "lines",
        (Some(other), _) => {
            return Err(Error::UnknownName {
                what: "kind",
                name: other.to_string(),
                known: "triangles, lines".into(),
            })
        }
    };
    if kind == "lines" && args.rule.is_some() {
        return Err(Error::InvalidArgument(
            "--rule is for triangles; lines are judged by --convention".into(),
        ));
    }
    if kind == "triangles" && args.convention.is_some() {
        return Err(Error::InvalidArgument(
            "--convention is for lines; triangles are judged by --rule".into(),
        ));
    }
    let property = if kind == "lines" {
        Property::Line(match args.convention.as_deref().unwrap_or("midpoint") {
            "midpoint" => LineConvention::Midpoint,
            "diamond" => LineConvention::Diamond,
            "vulkan" => LineConvention::Vulkan,
            other => {
                return Err(Error::UnknownName {
                    what: "line convention",
                    name: other.to_string(),
                    known: "midpoint, diamond, vulkan".into(),
                })
            }
        })
    } else {
        match args.rule.as_deref().unwrap_or("top-left") {
            "watertight" => Property::Watertight,
            rule => Property::Exact(rule.parse()?),
        }
    };
    if !(1..=MAX_CHECK_CASES).contains(&args.cases) {
        return Err(Error::InvalidArgument(format!(
            "--cases must be between 1 and {MAX_CHECK_CASES}, not {}",
            args.cases
        )));
    }
    if !(args.timeout > 0.0 && args.timeout <= 3600.0) {
        return Err(Error::InvalidArgument(format!(
            "--timeout must be between 0 and 3600 seconds, not {}",
            args.timeout
        )));
    }
    rasterlab::output::check_dir(&args.out)?;
    let rule_word = match property {
        Property::Exact(rule) => rule.name(),
        _ => "top-left",
    };
    let mut subject: Box<dyn check::Subject> = match (chosen, &args.exec) {
        (Some(Backend::Triangle(b)), _) if kind == "triangles" => {
            Box::new(Builtin::triangles(b, rule_word.parse()?))
        }
        (Some(Backend::Line(b)), _) if kind == "lines" => Box::new(Builtin::Lines(b)),
        (Some(_), _) => {
            return Err(Error::InvalidArgument(format!(
                "back-end `{}` does not draw {kind}",
                args.backend.as_deref().unwrap_or_default()
            )))
        }
        (None, Some(command)) => {
            let mut program = Program::new(command, rule_word);
            program.timeout = Duration::from_secs_f64(args.timeout);
            Box::new(program)
        }
        (None, None) => {
            return Err(Error::InvalidArgument(
                "give --exec CMD or --backend NAME".into(),
            ))
        }
    };
    let options = CheckOptions {
        cases: args.cases,
        seed: args.seed,
        ..CheckOptions::new(property)
    };
    let bar = progress_bar(u64::from(args.cases), "cases");
    let verdict = check::check_with_progress(&options, subject.as_mut(), &mut |done| {
        bar.set_position(u64::from(done));
    });
    bar.finish_and_clear();
    let counterexample = args.out.join("counterexample.txt");
    match verdict {
        Ok(check::Verdict::Pass { cases }) => {
            if args.json {
                say!(
                    "{}",
                    serde_json::json!({"verdict": "pass", "property": property.to_string(), "cases": cases, "seed": args.seed})
                )
            } else {
                say!("PASS: {cases} cases, {property} (seed {})", args.seed)
            }
        }
        Ok(check::Verdict::Fail {
            case_index,
            original,
            finding,
        }) => {
            rasterlab::output::write_file(
                &counterexample,
                finding.counterexample_text().as_bytes(),
            )?;
            let report = args.out.join("report.html");
            rasterlab::output::write_file(&report, finding.to_html().as_bytes())?;
            rasterlab::output::write_file(
                &args.out.join("counterexample.svg"),
                finding.to_svg().as_bytes(),
            )?;
            if args.json {
                let pixels = |v: &[check::Fragment]| -> Vec<[i64; 3]> {
                    v.iter().map(|f| [f.x, f.y, i64::from(f.id)]).collect()
                };
                say!(
                    "{}",
                    serde_json::json!({
                        "verdict": "fail",
                        "property": property.to_string(),
                        "case": case_index,
                        "seed": args.seed,
                        "problems": finding.problems,
                        "diagnosis": finding.diagnosis,
                        "missing": pixels(&finding.missing),
                        "extra": pixels(&finding.extra),
                        "counterexample": finding.counterexample_text(),
                    })
                )?;
            } else {
                say!(
                    "FAIL: {property}, case {case_index} of seed {}; shrunk from {} to {} primitive(s) on a {}x{} target",
                    args.seed,
                    original.len(),
                    finding.case.len(),
                    finding.case.width,
                    finding.case.height
                )?;
                for p in finding.problems.iter().take(5) {
                    say!("  {p}")?;
                }
                if finding.problems.len() > 5 {
                    say!("  ... and {} more", finding.problems.len() - 5)?;
                }
                say!("# correct   ! extra (or drawn twice)   ? missing")?;
                say_raw!("{}", finding.ascii_grid())?;
                if let Some(d) = &finding.diagnosis {
                    say!("diagnosis: {d}")?;
                }
                say!(
                    "counterexample: {} (rerun: give it to the program as its input)\nreport: {}",
                    counterexample.display(),
                    report.display()
                )?;
            }
            Err(Error::Mismatch(format!(
                "the check failed: {}",
                finding.problems[0]
            )))
        }
        Err(broken) => {
            rasterlab::output::write_file(&counterexample, broken.case.to_text().as_bytes())?;
            if args.json {
                say!(
                    "{}",
                    serde_json::json!({"verdict": "broken", "error": broken.error.to_string(), "input": broken.case.to_text()})
                )?;
            }
            Err(Error::InvalidArgument(format!(
                "{}\nthe input that triggers it ({} primitive(s), {}x{}): {}",
                broken.error,
                broken.case.len(),
                broken.case.width,
                broken.case.height,
                counterexample.display()
            )))
        }
    }
}

#[derive(Args, Debug)]
pub struct LabArgs {
    /// Port on 127.0.0.1 (0: any free port).
    #[arg(long, default_value_t = 7878)]
    port: u16,
    /// A rasterizer of your own to overlay, with the `rasterlab check`
    /// protocol ({input}, {width}, {height}, {rule}; prints `x y id`).
    #[arg(long)]
    exec: Option<String>,
}

pub fn lab(args: &LabArgs) -> Result<()> {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Arc;
    let server = tiny_http::Server::http(("127.0.0.1", args.port)).map_err(|e| {
        Error::InvalidArgument(format!("cannot listen on 127.0.0.1:{}: {e}", args.port))
    })?;
    let port = server.server_addr().to_ip().map_or(args.port, |a| a.port());
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    ctrlc::set_handler(move || flag.store(true, Ordering::Relaxed))
        .map_err(|e| Error::InvalidArgument(format!("cannot catch Ctrl-C: {e}")))?;
    say!("rasterlab lab: http://127.0.0.1:{port}/ (Ctrl-C stops it)")?;
    let program = args
        .exec
        .as_deref()
        .map(|command| rasterlab::check::Program::new(command, "top-left"));
    rasterlab::lab::server::serve(&server, program, &stop);
    eprintln!("rasterlab lab: stopped");
    Ok(())
}

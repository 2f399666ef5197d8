//! One function per subcommand.

use clap::Args;
use rasterlab::backend::{all_backends, backend, triangle_backend, triangle_backends, Backend};
use rasterlab::edge::FillRule;
use rasterlab::edge::PixelRect;
use rasterlab::fragment::FragmentList;
use rasterlab::input::{read_shapes, Shapes};
use rasterlab::line::{Connectivity, Endpoints, LineOptions, LineSetup};
use rasterlab::scene::{setup_triangles, Scene2D};
use rasterlab::shader::Flat;
use rasterlab::target::{DepthState, DepthTest, RenderTarget};
use rasterlab::{Error, Result};
use std::io::Write;
use std::path::PathBuf;

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
    Error::io("<stdout>", &e)
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
    RenderTarget::new(args.size.width, args.size.height)?;
    let viewport = PixelRect::of_target(args.size.width, args.size.height);
    let shapes = read_shapes(&args.file)?;
    let mut list = FragmentList::default();
    match (backend, shapes) {
        (Backend::Triangle(b), Shapes::Triangles { triangles, .. }) => {
            b.rasterize(&setup_triangles(&triangles, rule), viewport, &mut list);
        }
        (Backend::Line(b), Shapes::Lines { segments, .. }) => {
            let setups = line_setups(&segments);
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
    let weighted = matches!(backend, Backend::Line(b) if b.name() == "wu");
    for f in &list.lines {
        if weighted {
            writeln!(out, "{} {} {} {:.4}", f.x, f.y, f.line, f.coverage).map_err(stdout_error)?;
        } else {
            writeln!(out, "{} {} {}", f.x, f.y, f.line).map_err(stdout_error)?;
        }
    }
    out.flush().map_err(stdout_error)
}

fn line_setups(segments: &[[rasterlab::fixed::FixedPoint; 2]]) -> Vec<LineSetup> {
    segments
        .iter()
        .enumerate()
        .map(|(i, s)| LineSetup {
            id: i as u32,
            from: s[0],
            to: s[1],
        })
        .collect()
}

fn kind_mismatch(file: &std::path::Path, name: &str, draws: &str, holds: &str) -> Error {
    Error::InvalidArgument(format!(
        "{}: back-end `{name}` draws {draws}, but the file holds {holds}",
        file.display()
    ))
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Back-end name (see `rasterlab backends`).
    #[arg(long, default_value = "incremental")]
    backend: String,
    /// Target size `WxH` (defaults to the scene's own size).
    #[arg(long)]
    size: Option<Size>,
    /// Fill rule.
    #[arg(long, default_value = "top-left")]
    rule: String,
    /// Depth test: never, less, equal, less-equal, greater, not-equal, greater-equal, always.
    #[arg(long, default_value = "less")]
    depth_test: String,
    /// Built-in scene instead of a file: depth-example, split-square, pinwheel, fan.
    #[arg(long, conflicts_with = "input")]
    scene: Option<String>,
    /// Output PNG file.
    #[arg(long)]
    out: PathBuf,
    /// Triangle soup file.
    input: Option<PathBuf>,
}

pub fn render(args: &RenderArgs) -> Result<()> {
    let backend = triangle_backend(&args.backend)?;
    let rule: FillRule = args.rule.parse()?;
    let depth = DepthState {
        test: args.depth_test.parse::<DepthTest>()?,
        write: true,
    };
    let scene = match (&args.scene, &args.input) {
        (Some(name), _) => Scene2D::built_in(name)?,
        (None, Some(path)) => match read_shapes(path)? {
            Shapes::Triangles { triangles, .. } => {
                let size = args.size.ok_or_else(|| {
                    Error::InvalidArgument("--size is required when rendering a file".into())
                })?;
                Scene2D::from_triangles(size.width, size.height, triangles)
            }
            Shapes::Lines { .. } => {
                return Err(Error::InvalidArgument(format!(
                    "{}: holds line segments; render draws triangles",
                    path.display()
                )))
            }
        },
        (None, None) => {
            return Err(Error::InvalidArgument(
                "give a triangle soup file or --scene NAME".into(),
            ))
        }
    };
    let (w, h) = args
        .size
        .map_or((scene.width, scene.height), |s| (s.width, s.height));
    let mut target = RenderTarget::new(w, h)?;
    let work = scene.draw(backend, rule, depth, &Flat, &mut target);
    target.save_png(&args.out)?;
    eprintln!(
        "{}: {} triangles, {} samples tested, {} fragments -> {}",
        backend.name(),
        work.primitives,
        work.samples_tested,
        work.fragments,
        args.out.display()
    );
    Ok(())
}

#[derive(Args, Debug)]
pub struct DemoArgs {
    /// Directory the pictures are written to.
    #[arg(long, default_value = "demo-output")]
    out: PathBuf,
}

pub fn demo(args: &DemoArgs) -> Result<()> {
    std::fs::create_dir_all(&args.out).map_err(|e| Error::io(&args.out, &e))?;
    println!(
        "{:<16} {:<12} {:>10} {:>10}  identical to naive",
        "scene", "back-end", "tested", "fragments"
    );
    let mut all_identical = true;
    for name in Scene2D::BUILT_IN {
        let scene = Scene2D::built_in(name)?;
        let mut reference: Option<RenderTarget> = None;
        for backend in triangle_backends() {
            let (target, work) = scene.render(*backend, FillRule::TopLeft, &Flat)?;
            let identical = reference.as_ref().is_none_or(|r| *r == target);
            all_identical &= identical;
            println!(
                "{:<16} {:<12} {:>10} {:>10}  {}",
                name,
                backend.name(),
                work.samples_tested,
                work.fragments,
                if identical { "yes" } else { "NO" }
            );
            if reference.is_none() {
                target.save_png(&args.out.join(format!("{name}.png")))?;
                reference = Some(target);
            }
        }
    }
    if all_identical {
        println!("every back-end produced bit-identical colour, depth and coverage buffers");
        Ok(())
    } else {
        Err(Error::InvalidArgument(
            "back-ends disagree: see the table above".into(),
        ))
    }
}

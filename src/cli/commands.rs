//! One function per subcommand.

use clap::Args;
use rasterlab::backend::{all_backends, triangle_backend, triangle_backends};
use rasterlab::edge::FillRule;
use rasterlab::input::{read_shapes, Shapes};
use rasterlab::scene::{collect_fragments, setup_triangles, Scene2D};
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
    /// Fill rule: top-left, bottom-right, offscreen-point, inclusive, exclusive.
    #[arg(long, default_value = "top-left")]
    rule: String,
    /// Triangle soup: one triangle per line, `x0 y0 x1 y1 x2 y2` in pixels.
    file: PathBuf,
}

pub fn fragments(args: &FragmentsArgs) -> Result<()> {
    let backend = triangle_backend(&args.backend)?;
    let rule: FillRule = args.rule.parse()?;
    RenderTarget::new(args.size.width, args.size.height)?;
    let shapes = read_shapes(&args.file)?;
    let Shapes::Triangles { triangles, .. } = shapes else {
        return Err(Error::InvalidArgument(format!(
            "{}: back-end `{}` draws triangles, but the file holds line segments",
            args.file.display(),
            backend.name()
        )));
    };
    let setups = setup_triangles(&triangles, rule);
    let (list, _) = collect_fragments(backend, &setups, args.size.width, args.size.height);
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    for f in &list.triangles {
        writeln!(out, "{} {} {}", f.x, f.y, f.triangle).map_err(stdout_error)?;
    }
    out.flush().map_err(stdout_error)
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

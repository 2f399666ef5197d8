//! The fragments a back-end emits for the shapes of a text file, as
//! `rasterlab fragments` prints them: one `x y t` line per fragment (the
//! pixel and the primitive's index), with the coverage after them for an
//! anti-aliased line back-end. Multisampled (`--msaa N`), a triangle's
//! line is `x y t mask`, `mask` the decimal coverage mask whose bit `i` is
//! sample `i` of the standard pattern, row by row.
//!
//! ```
//! use rasterlab::geometry::{list_fragments, parse_shapes, FragmentsRequest};
//! use rasterlab::raster::{backend, FillRule};
//! use rasterlab::raster::line::LineOptions;
//! use std::path::Path;
//!
//! let shapes = parse_shapes("0 0 2 0 0 2\n", Path::new("one.txt")).unwrap();
//! let request = FragmentsRequest {
//!     backend: backend("scanline").unwrap(),
//!     file: Path::new("one.txt"),
//!     width: 4,
//!     height: 4,
//!     rule: FillRule::TopLeft,
//!     line: LineOptions::DEFAULT,
//!     msaa: None,
//! };
//! let listing = list_fragments(&request, &shapes).unwrap();
//! // The centres (1.5, 0.5) and (0.5, 1.5) lie on the right edge x + y = 2:
//! // the top-left rule leaves them to a neighbour.
//! assert_eq!(listing.to_string(), "0 0 0\n");
//! ```

use crate::error::{Error, Result};
use crate::geometry::input::{read_polygons, read_shapes, Shapes};
use crate::geometry::scene::setup_triangles;
use crate::raster::edge::{FillRule, PixelRect};
use crate::raster::fragment::FragmentList;
use crate::raster::line::{LineOptions, LineSetup};
use crate::raster::multisample::{masks_of, MaskFragment, SamplePattern};
use crate::raster::polygon::{PolygonRasterizer, WindingRule};
use crate::raster::registry::Backend;
use crate::raster::target::RenderTarget;
use std::fmt;
use std::path::Path;

/// What to list: a back-end, the file of shapes it draws, and how.
#[derive(Clone, Copy)]
pub struct FragmentsRequest<'a> {
    /// The back-end; it must draw the kind of shape the file holds.
    pub backend: Backend,
    /// The triangle soup or line set (see [`crate::geometry::read_shapes`]).
    pub file: &'a Path,
    /// Target width in pixels.
    pub width: u32,
    /// Target height in pixels.
    pub height: u32,
    /// Fill rule (triangles).
    pub rule: FillRule,
    /// Line options (lines).
    pub line: LineOptions,
    /// Multisampling (triangles): the coverage mask of each pixel on this
    /// pattern instead of its centre alone.
    pub msaa: Option<SamplePattern>,
}

/// The fragments of one request, in emission order.
#[derive(Clone, Debug, Default)]
pub struct FragmentListing {
    /// The fragments.
    pub fragments: FragmentList,
    /// Whether line fragments carry a coverage weight (an anti-aliased back-end).
    pub weighted: bool,
    /// The coverage masks, when multisampled (then `fragments` is empty).
    pub masks: Option<Vec<MaskFragment>>,
}

/// Checks the request, reads its file, draws the shapes with its back-end
/// and lists the fragments.
pub fn list_fragments_in_file(request: &FragmentsRequest<'_>) -> Result<FragmentListing> {
    check(request)?;
    list_fragments(request, &read_shapes(request.file)?)
}

/// Draws `shapes` (read from the request's file) with the request's
/// back-end and lists the fragments.
pub fn list_fragments(request: &FragmentsRequest<'_>, shapes: &Shapes) -> Result<FragmentListing> {
    check(request)?;
    let viewport = PixelRect::of_target(request.width, request.height);
    let mut listing = FragmentListing::default();
    let sink = &mut listing.fragments;
    match (request.backend, shapes) {
        (Backend::Triangle(b), Shapes::Triangles { triangles, .. }) => {
            let setups = setup_triangles(triangles, request.rule);
            match request.msaa {
                Some(pattern) => listing.masks = Some(masks_of(b, &setups, viewport, &pattern)),
                None => {
                    b.rasterize(&setups, viewport, sink);
                }
            }
        }
        (Backend::Line(b), Shapes::Lines { .. }) if request.msaa.is_some() => {
            return Err(Error::InvalidArgument(format!(
                "{}: --msaa multisamples triangles; `{}` draws lines, which are not multisampled",
                request.file.display(),
                b.name()
            )))
        }
        (Backend::Line(b), Shapes::Lines { segments, .. }) => {
            let setups = LineSetup::numbered(segments);
            b.rasterize(&setups, &request.line, viewport, sink);
            listing.weighted = b.anti_aliased();
        }
        (Backend::Triangle(b), Shapes::Lines { .. }) => {
            return Err(kind_mismatch(
                request.file,
                b.name(),
                "triangles",
                "line segments",
            ))
        }
        (Backend::Line(b), Shapes::Triangles { .. }) => {
            return Err(kind_mismatch(
                request.file,
                b.name(),
                "line segments",
                "triangles",
            ))
        }
    }
    Ok(listing)
}

/// What to list for a polygon back-end: the back-end, the polygon file it
/// fills, and by which winding rule.
#[derive(Clone, Copy)]
pub struct PolygonFragmentsRequest<'a> {
    /// The polygon back-end.
    pub backend: &'static dyn PolygonRasterizer,
    /// The file of triangles and polygons (see [`crate::geometry::read_polygons`]).
    pub file: &'a Path,
    /// Target width in pixels.
    pub width: u32,
    /// Target height in pixels.
    pub height: u32,
    /// The winding rule; given, rings that cross are taken too; `None`:
    /// simple polygons only, filled even-odd (on them both rules agree).
    pub fill: Option<WindingRule>,
}

/// Reads the request's polygon file and lists the fragments its polygon
/// back-end fills, `x y p` (`p` the polygon's index), polygon by polygon.
pub fn list_polygon_fragments_in_file(
    request: &PolygonFragmentsRequest<'_>,
) -> Result<FragmentListing> {
    RenderTarget::check_size(request.width, request.height)?;
    let file = read_polygons(request.file, request.fill)?;
    let setups: Vec<_> = file
        .outlines
        .iter()
        .enumerate()
        .map(|(i, o)| o.setup(i as u32))
        .collect();
    let mut listing = FragmentListing::default();
    let viewport = PixelRect::of_target(request.width, request.height);
    let rule = request.fill.unwrap_or_default();
    request
        .backend
        .rasterize(&setups, rule, viewport, &mut listing.fragments);
    Ok(listing)
}

/// The options suit the back-end and the target size is drawable.
fn check(request: &FragmentsRequest<'_>) -> Result<()> {
    if let Backend::Line(b) = request.backend {
        b.check_options(&request.line)?;
    }
    RenderTarget::check_size(request.width, request.height)
}

fn kind_mismatch(file: &Path, name: &str, draws: &str, holds: &str) -> Error {
    Error::InvalidArgument(format!(
        "{}: back-end `{name}` draws {draws}, but the file holds {holds}",
        file.display()
    ))
}

impl fmt::Display for FragmentListing {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for m in self.masks.iter().flatten() {
            writeln!(f, "{} {} {} {}", m.x, m.y, m.triangle, m.mask)?;
        }
        for t in &self.fragments.triangles {
            writeln!(f, "{} {} {}", t.x, t.y, t.triangle)?;
        }
        for l in &self.fragments.lines {
            if self.weighted {
                writeln!(f, "{} {} {} {:.4}", l.x, l.y, l.line, l.coverage)?;
            } else {
                writeln!(f, "{} {} {}", l.x, l.y, l.line)?;
            }
        }
        Ok(())
    }
}

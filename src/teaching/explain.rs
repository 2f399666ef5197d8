//! `explain`: one algorithm traced step by step on a small input, and its
//! grid picture. The input is given as numbers, as a student types them:
//! a line's two ends (pixel indices whose centres it joins, the course's
//! convention, or screen coordinates), a triangle's three corners in
//! screen coordinates, or triangles with a depth each for the course's
//! depth-buffer example.
//!
//! ```
//! use rasterlab::teaching::{explain, ExplainRequest};
//!
//! let request = ExplainRequest::new("bresenham", vec![0.0, 0.0, 7.0, 3.0]);
//! let explanation = explain(&request).unwrap();
//! assert!(explanation.text.contains("bresenham"));
//! ```

use crate::error::{Error, Result};
use crate::geometry::scene::Scene2D;
use crate::geometry::{ClipPlanes, Floor};
use crate::raster::derivatives::Derivatives;
use crate::raster::edge::FillRule;
use crate::raster::fixed::FixedPoint;
use crate::raster::line::clip::Clipper;
use crate::raster::line::LineOptions;
use crate::raster::multisample::SamplePattern;
use crate::raster::polygon::edge_table::EdgeTable;
use crate::raster::polygon::{PolygonRasterizer, WindingRule};
use crate::raster::registry::{
    all_backends, backend, line_backends, polygon_backend, polygon_backends, triangle_backend,
    Backend,
};
use crate::raster::stage::{Blend, BlendMode};
use crate::raster::target::{DepthState, RenderTarget};
use crate::raster::texture::{LevelMode, Sampler};
use crate::teaching::grid_picture::GridPicture;
use crate::teaching::level_picture::LevelPicture;
use crate::teaching::trace::{self, LineEnds};

/// The name that asks for the depth buffer's trace instead of a back-end's.
pub const DEPTH_BUFFER: &str = "depth-buffer";

/// The name that asks for one pixel's blends ([`trace_blend`](super::trace_blend))
/// instead of a back-end's trace.
pub const BLEND: &str = "blend";

/// The name that asks for a triangle clipped in clip space, plane by
/// plane, and re-triangulated as a fan
/// ([`trace_triangle_clip`](super::trace_triangle_clip)).
pub const CLIP_TRIANGLE: &str = "clip-triangle";

/// The name that asks for one pixel's texture lookup on the receding
/// floor ([`trace_texture`](super::trace_texture)).
pub const TEXTURE: &str = "texture";

/// The scene the blend trace draws unless told otherwise.
pub const BLEND_SCENE: &str = "transparent";

/// The grid `explain` draws on unless told otherwise.
pub const DEFAULT_GRID: (u32, u32) = (16, 16);

/// What to explain.
#[derive(Clone, Debug, PartialEq)]
pub struct ExplainRequest {
    /// A back-end's name, or [`DEPTH_BUFFER`].
    pub backend: String,
    /// The fill rule for triangles.
    pub rule: FillRule,
    /// The grid size; [`DEFAULT_GRID`] (or the course example's own size) when `None`.
    pub size: Option<(u32, u32)>,
    /// Line ends are screen coordinates (`0.5 0.5 7.5 3.5`) rather than
    /// pixel indices whose centres the line joins (`0 0 7 3`).
    pub screen: bool,
    /// The numbers: 4 for a line, 6 for a triangle, 7 per triangle (or
    /// none, the course's example) for the depth buffer.
    pub coordinates: Vec<f64>,
    /// Also draw the grid picture.
    pub picture: bool,
    /// Triangles: also trace their samples on this multisample pattern
    /// ([`trace_samples`](super::trace_samples)).
    pub msaa: Option<SamplePattern>,
    /// The winding rule of a polygon back-end (`edge-table`); `None`
    /// for the others (even-odd when a polygon back-end is traced).
    pub fill: Option<WindingRule>,
    /// The blend trace: the built-in scene drawn ([`BLEND_SCENE`] when
    /// `None`), its blend state and depth state, and whether its
    /// triangles are sorted back to front first.
    pub blending: Blending,
    /// The texture trace: the sampler and the derivative method.
    pub texturing: Texturing,
    /// A line back-end's trace: clip the line to the grid by this
    /// algorithm first ([`trace_clip`](super::trace_clip)).
    pub clip: Option<Clipper>,
    /// A polygon back-end's trace: the polygon's other rings (holes, or
    /// rings running the same way as the first), `x y` pairs each, taken
    /// as given ([`trace_polygon_rings`](super::trace_polygon_rings)).
    pub rings: Vec<Vec<f64>>,
}

/// How the texture trace samples: trilinear, analytic derivatives, unless
/// told otherwise.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Texturing {
    /// Pixel filter, level mode, wrap and anisotropy.
    pub sampler: Sampler,
    /// How the derivatives are computed.
    pub derivatives: Derivatives,
}

impl Default for Texturing {
    fn default() -> Self {
        Texturing {
            sampler: Sampler {
                levels: LevelMode::Linear,
                ..Sampler::default()
            },
            derivatives: Derivatives::Analytic,
        }
    }
}

/// What the blend trace draws, and how.
#[derive(Clone, Debug, PartialEq)]
pub struct Blending {
    /// A built-in scene's name; [`BLEND_SCENE`] when `None`.
    pub scene: Option<String>,
    /// How fragments are merged.
    pub blend: Blend,
    /// The depth test.
    pub depth: DepthState,
    /// Sort the triangles back to front first.
    pub sort: bool,
}

impl Default for Blending {
    fn default() -> Self {
        Blending {
            scene: None,
            blend: Blend {
                mode: BlendMode::OverStraight,
                ..Blend::default()
            },
            depth: DepthState::DEFAULT,
            sort: false,
        }
    }
}

impl ExplainRequest {
    /// A request for `backend` on `coordinates`, under the top-left rule,
    /// on the default grid, without a picture.
    pub fn new(backend: &str, coordinates: Vec<f64>) -> ExplainRequest {
        ExplainRequest {
            backend: backend.to_string(),
            rule: FillRule::TopLeft,
            size: None,
            screen: false,
            coordinates,
            picture: false,
            msaa: None,
            fill: None,
            blending: Blending::default(),
            texturing: Texturing::default(),
            clip: None,
            rings: Vec::new(),
        }
    }

    fn size(&self, default: (u32, u32)) -> Result<(u32, u32)> {
        let (w, h) = self.size.unwrap_or(default);
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

    /// The pixel `x y` of the coordinates, whole numbers from 0.
    fn pixel(&self, what: &str) -> Result<(u32, u32)> {
        self.want(2, what)?;
        let index = |v: f64| {
            (v.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&v))
                .then_some(v as u32)
                .ok_or_else(|| {
                    Error::InvalidArgument(format!(
                        "a pixel index is a whole number from 0, not {v}"
                    ))
                })
        };
        Ok((index(self.coordinates[0])?, index(self.coordinates[1])?))
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
        let (width, height) = self.size(DEFAULT_GRID)?;
        Scene2D::with_depths(width, height, &self.coordinates)
    }
}

/// A trace, and the grid picture when one was asked for.
pub struct Explanation {
    /// The step-by-step trace, as text.
    pub text: String,
    /// The grid picture of the same input.
    pub picture: Option<GridPicture>,
    /// The texture trace's picture: the floor by mip level.
    pub levels: Option<LevelPicture>,
}

/// Traces the request's algorithm on its input.
pub fn explain(request: &ExplainRequest) -> Result<Explanation> {
    let rule = request.rule;
    if let (Some(clipper), false) = (
        request.clip,
        matches!(backend(&request.backend), Ok(Backend::Line(_))),
    ) {
        return Err(Error::InvalidArgument(format!(
            "--clip {clipper} clips a line before a line back-end walks it: give --backend {}, not `{}`",
            line_backends()
                .iter()
                .map(|b| b.name())
                .collect::<Vec<_>>()
                .join(" | "),
            request.backend
        )));
    }
    if request.backend == DEPTH_BUFFER {
        if request.msaa.is_some() {
            return Err(Error::InvalidArgument(
                "--msaa traces one triangle's samples, not the depth buffer".into(),
            ));
        }
        let scene = request.depth_scene()?;
        let text = trace::trace_depth_buffer(&scene, triangle_backend("bbox")?, rule)?.to_text();
        let picture = request
            .picture
            .then(|| GridPicture::depth_buffer(&scene, rule))
            .transpose()?;
        return Ok(Explanation {
            text,
            picture,
            levels: None,
        });
    }
    if request.backend == BLEND {
        return explain_blend(request);
    }
    if request.backend == TEXTURE {
        return explain_texture(request);
    }
    if request.backend == CLIP_TRIANGLE {
        return explain_triangle_clip(request);
    }
    // A triangle back-end takes `--derivatives quad` (its quads and
    // helper pixels); the other texture options are the texture trace's.
    let quads = Texturing {
        derivatives: Derivatives::Quad,
        ..Texturing::default()
    };
    let triangle = matches!(backend(&request.backend), Ok(Backend::Triangle(_)));
    if request.texturing != Texturing::default() && !(triangle && request.texturing == quads) {
        return Err(Error::InvalidArgument(
            "--filter, --mip, --anisotropy and --anisotropic are for the texture trace \
             (--backend texture), and so is --derivatives, but for --derivatives quad on a \
             triangle back-end, which marks its 2x2 quads and helper pixels"
                .into(),
        ));
    }
    if request.blending != Blending::default() {
        return Err(Error::InvalidArgument(
            "--scene, --blend, --mix-in, --depth-test and --sort are for the blend trace (--backend blend)"
                .into(),
        ));
    }
    if let Ok(polygon) = polygon_backend(&request.backend) {
        if polygon.name() != EdgeTable.name() {
            return Err(Error::InvalidArgument(format!(
                "`{}` has no step-by-step trace; explain --backend edge-table traces the book's walk",
                polygon.name()
            )));
        }
        return explain_polygon(request);
    }
    if request.fill.is_some() || !request.rings.is_empty() {
        return Err(Error::InvalidArgument(
            "--fill and --ring are a polygon back-end's winding rule and rings (edge-table)".into(),
        ));
    }
    let chosen = backend(&request.backend).map_err(|_| Error::UnknownName {
        what: "rasterizer back-end",
        name: request.backend.clone(),
        known: all_backends()
            .iter()
            .map(|b| b.name)
            .chain(polygon_backends().iter().map(|b| b.name()))
            .collect::<Vec<_>>()
            .join(", ")
            + "; or depth-buffer, the depth buffer's trace; or clip-triangle, a triangle clipped in clip space; or blend, one pixel's blends; \
               or texture, one pixel's texture lookup",
    })?;
    let (width, height) = request.size(DEFAULT_GRID)?;
    let (text, picture) = match chosen {
        Backend::Triangle(b) => {
            let triangle = request.triangle()?;
            let mut text = trace::trace_triangle(b, triangle, rule, width, height)?.to_text();
            if let Some(pattern) = &request.msaa {
                text.push('\n');
                text.push_str(
                    &super::sample_trace::trace_samples(triangle, rule, width, height, pattern)?
                        .to_text(),
                );
            }
            let [v0, v1, v2] = triangle.map(|(x, y)| FixedPoint::snap_f64(x, y));
            let snapped = [v0?, v1?, v2?];
            let mut picture = request
                .picture
                .then(|| GridPicture::of_triangles(b, &[triangle], rule, width, height))
                .transpose()?;
            if let Some(pattern) = &request.msaa {
                picture = picture.map(|p| p.with_samples(&[snapped], rule, pattern));
            }
            // Under quad derivatives, the quads the triangle is shaded in.
            if request.texturing.derivatives == Derivatives::Quad {
                let quads = GridPicture::of_triangles(b, &[triangle], rule, width, height)?
                    .with_quads(b, &[snapped], rule);
                let helpers = quads.quad_helpers.as_ref().map_or(0, Vec::len);
                text.push_str(&format!(
                    "\nquad derivatives: shaded in 2x2 quads aligned to even pixels, {helpers} \
                     helper pixel(s) beside {} fragment(s), shaded for the differences and \
                     never written\n",
                    quads.inside_cells()
                ));
                picture = picture.map(|p| p.with_quads(b, &[snapped], rule));
            }
            (text, picture)
        }
        Backend::Line(_) if request.msaa.is_some() => {
            return Err(Error::InvalidArgument(
                "--msaa traces a triangle's samples; lines are not multisampled".into(),
            ))
        }
        Backend::Line(b) => {
            let line = request.line()?;
            let text = match request.clip {
                Some(clipper) => trace::trace_clip(clipper, b, &line, width, height)?.to_text(),
                None => trace::trace_line(b, &line)?.to_text(),
            };
            let picture = request
                .picture
                .then(|| GridPicture::of_lines(b, &[line], &LineOptions::DEFAULT, width, height))
                .transpose()?;
            (text, picture)
        }
    };
    Ok(Explanation {
        text,
        picture,
        levels: None,
    })
}

/// The edge table's walk over the polygon the request's numbers give
/// (`x y` pairs, screen coordinates).
fn explain_polygon(request: &ExplainRequest) -> Result<Explanation> {
    if request.msaa.is_some() || request.rule != FillRule::TopLeft {
        return Err(Error::InvalidArgument(
            "edge-table settles ties by the top-left rule on one sample a pixel: \
             --rule and --msaa are for the triangle back-ends"
                .into(),
        ));
    }
    let mut rings = Vec::new();
    for (k, numbers) in std::iter::once(&request.coordinates)
        .chain(&request.rings)
        .enumerate()
    {
        if !numbers.len().is_multiple_of(2) {
            return Err(Error::InvalidArgument(format!(
                "edge-table traces a polygon: give x y pairs, not {} numbers{}",
                numbers.len(),
                if k == 0 {
                    String::new()
                } else {
                    format!(" (--ring {k})")
                }
            )));
        }
        rings.push(numbers.chunks(2).map(|c| (c[0], c[1])).collect::<Vec<_>>());
    }
    let (width, height) = request.size(DEFAULT_GRID)?;
    let rule = request.fill.unwrap_or_default();
    let text = super::trace_polygon_rings(&rings, rule, width, height)?.to_text();
    let picture = if request.picture {
        let snapped = rings
            .iter()
            .map(|ring| {
                ring.iter()
                    .map(|&(x, y)| FixedPoint::snap_f64(x, y))
                    .collect::<Result<Vec<_>>>()
            })
            .collect::<Result<Vec<_>>>()?;
        Some(GridPicture::of_polygon(&snapped, rule, width, height)?)
    } else {
        None
    };
    Ok(Explanation {
        text,
        picture,
        levels: None,
    })
}

/// The clipping of the request's clip-space triangle (or the example's,
/// a vertex behind the camera) by the pipeline's planes.
fn explain_triangle_clip(request: &ExplainRequest) -> Result<Explanation> {
    if request.msaa.is_some()
        || request.picture
        || request.fill.is_some()
        || !request.rings.is_empty()
        || request.blending != Blending::default()
        || request.texturing != Texturing::default()
    {
        return Err(Error::InvalidArgument(
            "clip-triangle prints the clipping of one triangle in clip space: it takes --size and 12 numbers (or none), no other option"
                .into(),
        ));
    }
    let numbers = if request.coordinates.is_empty() {
        trace::BEHIND_THE_CAMERA.to_vec()
    } else {
        request.coordinates.clone()
    };
    let (width, height) = request.size(DEFAULT_GRID)?;
    let text =
        super::trace_triangle_clip(&numbers, ClipPlanes::GuardBand, width, height)?.to_text();
    Ok(Explanation {
        text,
        picture: None,
        levels: None,
    })
}

/// The blend trace of the request's pixel (`x y`) in its scene.
fn explain_blend(request: &ExplainRequest) -> Result<Explanation> {
    if request.msaa.is_some() || request.picture {
        return Err(Error::InvalidArgument(
            "the blend trace prints one pixel's fragments; --msaa and --picture are for the back-ends' traces"
                .into(),
        ));
    }
    let blending = &request.blending;
    let mut scene = Scene2D::built_in(blending.scene.as_deref().unwrap_or(BLEND_SCENE))?;
    if let Some((w, h)) = request.size {
        RenderTarget::check_size(w, h)?;
        (scene.width, scene.height) = (w, h);
    }
    if blending.sort {
        scene = scene.sorted_back_to_front();
    }
    let (x, y) = request.pixel("one pixel's blends (x y, a pixel index)")?;
    let text = super::trace_blend(
        &scene,
        (x, y),
        triangle_backend("bbox")?,
        request.rule,
        blending.depth,
        blending.blend,
    )?
    .to_text();
    Ok(Explanation {
        text,
        picture: None,
        levels: None,
    })
}

/// The texture trace of the request's pixel (`x y`) on the receding
/// floor, and the floor by mip level when a picture is asked for.
fn explain_texture(request: &ExplainRequest) -> Result<Explanation> {
    if request.msaa.is_some() || request.blending != Blending::default() {
        return Err(Error::InvalidArgument(
            "the texture trace takes a pixel of the floor, --size and the texture options \
             (--filter, --mip, --anisotropy, --anisotropic, --derivatives)"
                .into(),
        ));
    }
    let (width, height) = request.size(Floor::SIZE)?;
    let floor = Floor::new(width, height)?;
    let pixel = request.pixel("one pixel's texture lookup (x y, a pixel of the floor)")?;
    let t = request.texturing;
    t.sampler.check()?;
    let text = super::trace_texture(&floor, pixel, t.sampler, t.derivatives)?;
    let levels = request
        .picture
        .then(|| LevelPicture::new(&floor, t.sampler, t.derivatives, Some(pixel)));
    Ok(Explanation {
        text,
        picture: None,
        levels,
    })
}

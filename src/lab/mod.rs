//! The interactive lab: what one update of the page asks, and what the
//! real back-ends answer.
//!
//! `rasterlab lab` serves a page ([`page`]) on the loopback address. Each
//! time a student drags a vertex, the page sends the whole state as a
//! [`LabRequest`] (JSON) and gets a [`LabResponse`]: for every chosen
//! back-end, the pixels it tested and the fragments it emitted, its trace
//! as data ([`Trace`]: the rows `rasterlab explain` prints, each with the
//! pixels it is about, so the page highlights a row by its pixels), the
//! fill rule's heat map (gaps,
//! double draws) when there are several triangles, with `msaa` every
//! sample and the resolve ([`SamplesView`]), with `blend` the triangles
//! composited through the stage at one opacity ([`CompositeView`]), with
//! `texture` the triangles textured and each pixel's level of detail
//! ([`TexturedView`]), and,
//! with `--exec`, the student's own rasterizer against the exact answer.
//!
//! Triangles that carry a depth are the course's depth-buffer example:
//! overlap is what the depth test resolves, not a fill-rule error, so
//! instead of a heat map the answer has a [`DepthView`] (per pixel the
//! depth stored, whose fragment was kept, how many were hidden) and the
//! trace is the depth buffer's ([`trace_depth_buffer`](crate::teaching::trace_depth_buffer), every
//! triangle in turn), as `rasterlab explain --backend depth-buffer`
//! prints it.
//!
//! The page draws with the one palette ([`crate::teaching::Role`]):
//! [`page`] writes its colours, the triangles' line patterns and the
//! legend style in, and each answer carries its legend
//! ([`LabResponse::legend`]), which the page shows under the grid.
//!
//! Requests are input like any other: [`LabRequest::parse`] refuses a
//! malformed, oversized or out-of-range request with a message (the server
//! answers 400), and the work per request is bounded by [`MAX_GRID`] and
//! [`MAX_PRIMITIVES`].
//!
//! ```
//! use rasterlab::lab::{answer, LabRequest};
//! let request = LabRequest::parse(r#"{"width": 8, "height": 8, "kind": "triangles",
//!     "triangles": [[[0.5, 0.5], [6.5, 1.5], [2.5, 6.5]]], "backends": ["bbox", "scanline"]}"#).unwrap();
//! let response = answer(&request, None).unwrap();
//! assert_eq!(response.backends.len(), 2);
//! assert_eq!(response.backends[0].fragments, response.backends[1].fragments);
//! assert!(LabRequest::parse(r#"{"width": 100000, "height": 8, "kind": "triangles"}"#).is_err());
//! ```

use crate::check::judge::{cover, Cover};
use crate::check::{Case, Program, Subject};
use crate::error::{Error, Result};
use crate::geometry::scene::{setup_triangles, Scene2D};
use crate::raster::edge::{FillRule, PixelRect, TriangleSetup};
use crate::raster::fixed::{FixedPoint, HALF_PIXEL, SUBPIXEL_SCALE};
use crate::raster::line::LineOptions;
use crate::raster::multisample::{reference_masks, SamplePattern};
use crate::raster::registry::{backend, line_backends, triangle_backends, Backend};
use crate::teaching::explain::DEPTH_BUFFER;
use crate::teaching::grid_picture::{
    is_fragment_green, DepthCells, GridPicture, INSIDE, TESTED_OUTSIDE,
};
use crate::teaching::palette::{self, triangle_name, Legend, Mark, Role, MAX_TRIANGLES};
use crate::teaching::trace::{self, LineEnds};
use crate::teaching::trace_table::Trace;
use serde::{Deserialize, Serialize};
use trace_of::trace_of;

/// The page the lab serves, before [`page`] writes the registry's
/// back-ends into it: one HTML file, no build step, nothing fetched.
const PAGE: &str = include_str!("page.html");

/// The page the lab serves, with the one palette's colours, labels and
/// legend style, the names of the registry's triangle and line back-ends
/// (every one has a trace), and every fill rule in the rule menu.
pub fn page() -> String {
    let names = |names: Vec<&str>| serde_json::to_string(&names).expect("names serialise");
    PAGE.replacen("/*PALETTE_CSS*/", &palette::css(), 1)
        .replacen("/*PALETTE*/{}", &palette::json(), 1)
        .replacen(
            "/*TRIANGLE_BACKENDS*/[]",
            &names(triangle_backends().iter().map(|b| b.name()).collect()),
            1,
        )
        .replacen(
            "/*LINE_BACKENDS*/[]",
            &names(line_backends().iter().map(|b| b.name()).collect()),
            1,
        )
        .replacen(
            "<!--FILL_RULES-->",
            &FillRule::ALL
                .iter()
                .map(|r| format!("<option>{}</option>", r.name()))
                .collect::<String>(),
            1,
        )
}

mod composite;
#[cfg(feature = "lab")]
mod server;
mod textured;
mod trace_of;

pub use composite::CompositeView;
#[cfg(feature = "lab")]
pub use server::LabServer;
pub use textured::{Lookup, TextureControls, TexturedView};

/// The largest grid side a request may ask for.
pub const MAX_GRID: u32 = 128;
/// The most triangles or lines in one request.
pub const MAX_PRIMITIVES: usize = 16;
/// The largest request body, in bytes.
pub const MAX_REQUEST_BYTES: usize = 64 * 1024;
/// How far outside the grid a vertex may be dragged, in pixels.
const MAX_OFFSET: f64 = 1024.0;

/// One update: the grid, the primitives and what to show.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LabRequest {
    /// Grid width in pixels.
    pub width: u32,
    /// Grid height in pixels.
    pub height: u32,
    /// `triangles` or `lines`.
    pub kind: String,
    /// Triangles, three `[x, y]` points each, in screen pixels.
    #[serde(default)]
    pub triangles: Vec<[[f64; 2]; 3]>,
    /// A depth in `[0, 1]` per triangle, for the depth-buffer view (empty:
    /// no depth view).
    #[serde(default)]
    pub depths: Vec<f64>,
    /// Lines, two `[x, y]` points each, in screen pixels.
    #[serde(default)]
    pub lines: Vec<[[f64; 2]; 2]>,
    /// Back-end names to run.
    #[serde(default)]
    pub backends: Vec<String>,
    /// The fill rule for triangles (default top-left).
    #[serde(default)]
    pub rule: Option<String>,
    /// The back-end whose trace to return, or `depth-buffer` (the default
    /// when the triangles carry depths); otherwise the first back-end.
    #[serde(default)]
    pub trace: Option<String>,
    /// Run the `--exec` program on this input too.
    #[serde(default)]
    pub student: bool,
    /// Triangles: multisample on the standard pattern of this many
    /// samples (2, 4, 8 or 16; 1 or none: one sample at the centre).
    #[serde(default)]
    pub msaa: Option<u32>,
    /// Triangles: composite them with this blend mode (`replace`, `add`,
    /// `over`, `over-straight`, `multiply`) into [`LabResponse::composite`].
    #[serde(default)]
    pub blend: Option<String>,
    /// The triangles' opacity for the compositing view (default 1/2).
    #[serde(default)]
    pub opacity: Option<f64>,
    /// Where the compositing view mixes: `linear` (default) or `srgb`.
    #[serde(default)]
    pub mix_in: Option<String>,
    /// Sort the triangles back to front by depth before compositing.
    #[serde(default)]
    pub sort: bool,
    /// Triangles: texture them into [`LabResponse::textured`].
    #[serde(default)]
    pub texture: Option<TextureControls>,
    /// Lines: clip the first to the grid by `cohen-sutherland` or
    /// `liang-barsky` in its trace, then walk it from its entry column.
    #[serde(default)]
    pub clip: Option<String>,
}

impl LabRequest {
    /// Parses and checks a request: known names, a grid of 1 to
    /// [`MAX_GRID`] on a side, at most [`MAX_PRIMITIVES`] primitives,
    /// finite coordinates within 1024 px of the grid, depths in `[0, 1]`.
    pub fn parse(text: &str) -> Result<LabRequest> {
        if text.len() > MAX_REQUEST_BYTES {
            return Err(Error::InvalidArgument(format!(
                "the request is larger than {MAX_REQUEST_BYTES} bytes"
            )));
        }
        let request: LabRequest = serde_json::from_str(text)
            .map_err(|e| Error::InvalidArgument(format!("malformed request: {e}")))?;
        request.check()?;
        Ok(request)
    }

    fn check(&self) -> Result<()> {
        let bad = |m: String| Err(Error::InvalidArgument(m));
        if !(1..=MAX_GRID).contains(&self.width) || !(1..=MAX_GRID).contains(&self.height) {
            return bad(format!(
                "the grid is {}x{}; each side must be 1 to {MAX_GRID}",
                self.width, self.height
            ));
        }
        if !matches!(self.kind.as_str(), "triangles" | "lines") {
            return bad(format!(
                "kind `{}` is neither triangles nor lines",
                self.kind
            ));
        }
        if self.triangles.len() > MAX_PRIMITIVES || self.lines.len() > MAX_PRIMITIVES {
            return bad(format!("at most {MAX_PRIMITIVES} triangles or lines"));
        }
        if self.backends.len() > 16 {
            return bad("at most 16 back-ends".into());
        }
        if let Some(clipper) = &self.clip {
            clipper.parse::<crate::raster::line::clip::Clipper>()?;
        }
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        let points = self
            .triangles
            .iter()
            .flatten()
            .chain(self.lines.iter().flatten());
        for p in points {
            let ok =
                |v: f64, side: f64| v.is_finite() && (-MAX_OFFSET..=side + MAX_OFFSET).contains(&v);
            if !ok(p[0], w) || !ok(p[1], h) {
                return bad(format!(
                    "point ({:?}, {:?}) is not a finite number within {MAX_OFFSET} px of the grid",
                    p[0], p[1]
                ));
            }
        }
        if !self.depths.is_empty() && self.depths.len() != self.triangles.len() {
            return bad("give one depth per triangle, or none".into());
        }
        if let Some(z) = self.depths.iter().find(|z| !(0.0..=1.0).contains(*z)) {
            return bad(format!("depth {z} is outside [0, 1]"));
        }
        for name in &self.backends {
            backend(name)?;
        }
        if let Some(rule) = &self.rule {
            rule.parse::<FillRule>()?;
        }
        if let Some(n) = self.msaa {
            SamplePattern::standard(n)?;
        }
        composite::check(self)?;
        textured::check(self)
    }

    fn rule(&self) -> FillRule {
        self.rule
            .as_deref()
            .and_then(|r| r.parse().ok())
            .unwrap_or(FillRule::TopLeft)
    }

    /// The request's primitives as a check [`Case`].
    pub fn case(&self) -> Case {
        let p = |q: [f64; 2]| (q[0], q[1]);
        Case {
            width: self.width,
            height: self.height,
            triangles: if self.kind == "triangles" {
                self.triangles.iter().map(|t| t.map(p)).collect()
            } else {
                Vec::new()
            },
            lines: if self.kind == "lines" {
                self.lines.iter().map(|l| l.map(p)).collect()
            } else {
                Vec::new()
            },
            ..Case::default()
        }
    }
}

/// What one back-end did.
#[derive(Clone, Debug, Serialize)]
pub struct BackendView {
    /// Its name.
    pub name: String,
    /// Pixels it tested and rejected, `[x, y]`.
    pub tested: Vec<[u32; 2]>,
    /// Pixels it drew, `[x, y, weight in thousandths]` (1000 but for Wu).
    pub fragments: Vec<[u32; 3]>,
    /// Its caption: samples tested, fragments.
    pub caption: String,
}

/// The student's program against the exact answer.
#[derive(Clone, Debug, Serialize)]
pub struct StudentView {
    /// Pixels it drew that the answer has, `[x, y]`.
    pub correct: Vec<[i64; 2]>,
    /// Pixels it drew that the answer does not have (or twice).
    pub extra: Vec<[i64; 2]>,
    /// Pixels the answer has that it did not draw.
    pub missing: Vec<[i64; 2]>,
    /// How many pixels it got wrong: extra and missing together.
    pub wrong: usize,
    /// An error running it, if any.
    pub error: Option<String>,
    /// The cause of its wrong pixels on this case, where the catalogue
    /// has one that explains them all ([`crate::check::Cause`]), or that
    /// none does.
    pub cause: Option<String>,
}

/// The depth test at every pixel of triangles drawn in order, each with
/// its depth (the course's depth-buffer example): what
/// `rasterlab explain --backend depth-buffer --picture` shows.
#[derive(Clone, Debug, Serialize)]
pub struct DepthView {
    /// The depth stored, row by row (1.0 where nothing was drawn).
    pub depth: Vec<f32>,
    /// Per pixel, row by row, the triangle (from 0, in drawing order)
    /// whose fragment the depth buffer holds; `None` where nothing was
    /// drawn.
    pub stored: Vec<Option<u32>>,
    /// Pixels where the depth test hid fragments, `[x, y, how many]`.
    pub hidden: Vec<[u32; 3]>,
    /// Fragments the depth test kept (nearer than the buffer).
    pub kept_fragments: usize,
    /// Fragments the depth test hid behind nearer ones.
    pub hidden_fragments: usize,
    /// Each triangle's name and depth, `triangle 1 (z = 0.5)`, as the
    /// trace names them.
    pub triangles: Vec<String>,
}

impl DepthView {
    fn of(cells: &DepthCells, depths: &[f64]) -> DepthView {
        let w = cells.width as usize;
        DepthView {
            depth: cells.depth.clone(),
            stored: cells.kept.iter().map(|k| k.last().copied()).collect(),
            hidden: cells
                .hidden
                .iter()
                .enumerate()
                .filter(|(_, h)| !h.is_empty())
                .map(|(i, h)| [(i % w) as u32, (i / w) as u32, h.len() as u32])
                .collect(),
            kept_fragments: cells.kept.iter().map(Vec::len).sum(),
            hidden_fragments: cells.hidden.iter().map(Vec::len).sum(),
            triangles: depths
                .iter()
                .enumerate()
                .map(|(i, z)| format!("triangle {} (z = {z})", i + 1))
                .collect(),
        }
    }
}

/// The answer to one update.
#[derive(Clone, Debug, Serialize)]
pub struct LabResponse {
    /// One view per requested back-end, in request order.
    pub backends: Vec<BackendView>,
    /// The trace of the chosen back-end (or of the depth buffer): the
    /// rows `rasterlab explain` prints, each with its pixels (empty when it
    /// has none for this input; one header line saying why when it cannot
    /// be traced).
    pub trace: Trace,
    /// Whose trace it is: a back-end's name or `depth-buffer`.
    pub trace_backend: String,
    /// Under the rule, for several triangles without depths: pixels
    /// inside the union that no triangle draws, `[x, y]`.
    pub gaps: Vec<[i64; 2]>,
    /// Pixels drawn more than once, `[x, y, times]` (triangles without
    /// depths only: where they carry depths, overlap is the depth test's
    /// business).
    pub doubles: Vec<[i64; 3]>,
    /// The depth test's outcome, when the triangles carry depths.
    pub depth: Option<DepthView>,
    /// The student's program, when asked for and available.
    pub student: Option<StudentView>,
    /// Under `msaa`: every sample and whether a triangle covers it, and
    /// each pixel's resolved coverage.
    pub samples: Option<SamplesView>,
    /// With `blend`: the triangles composited through the stage.
    pub composite: Option<CompositeView>,
    /// With `texture`: the triangles textured, each pixel's lookup.
    pub textured: Option<TexturedView>,
    /// What the answer draws: every (colour, mark) pair with its meaning
    /// (the page leaves out the entries of layers it hides: the heat map
    /// when switched off, pixel centres on cells too small to dot).
    pub legend: Legend,
    /// The same legend as HTML ([`Legend::to_html`]), as the page shows it.
    pub legend_html: String,
}

/// Answers one request with the real back-ends (and `program`, when the
/// request asks for the student's view).
pub fn answer(request: &LabRequest, program: Option<&mut Program>) -> Result<LabResponse> {
    let rule = request.rule();
    let case = request.case();
    let (w, h) = (request.width, request.height);
    let snapped = case.snapped_triangles();
    let mut views = Vec::new();
    for name in &request.backends {
        let picture = match backend(name)? {
            Backend::Triangle(b) if request.kind == "triangles" => {
                GridPicture::of_snapped_triangles(b, &snapped, rule, w, h)?
            }
            Backend::Line(b) if request.kind == "lines" => {
                let ends: Vec<LineEnds> = case
                    .lines
                    .iter()
                    .map(|l| LineEnds::screen([l[0].0, l[0].1, l[1].0, l[1].1]))
                    .collect::<Result<_>>()?;
                GridPicture::of_lines(b, &ends, &LineOptions::DEFAULT, w, h)?
            }
            _ => continue,
        };
        views.push(view(name, &picture));
    }
    let scene = if request.kind == "triangles" && !request.depths.is_empty() {
        let numbers: Vec<f64> = request
            .triangles
            .iter()
            .zip(&request.depths)
            .flat_map(|(t, z)| [t[0][0], t[0][1], t[1][0], t[1][1], t[2][0], t[2][1], *z])
            .collect();
        Some(Scene2D::with_depths(w, h, &numbers)?)
    } else {
        None
    };
    // Every back-end has a trace: the one asked for, else the depth
    // buffer's when there are depths, else the first back-end shown.
    let asked = request
        .trace
        .clone()
        .filter(|t| backend(t).is_ok() || (t == DEPTH_BUFFER && scene.is_some()));
    let trace_backend = asked
        .or_else(|| scene.as_ref().map(|_| DEPTH_BUFFER.to_string()))
        .or_else(|| request.backends.first().cloned())
        .unwrap_or_default();
    let drawing = crate::raster::registry::default_triangle_backend();
    let trace = match &scene {
        _ if trace_backend.is_empty() => Ok(Trace::default()),
        Some(scene) if trace_backend == DEPTH_BUFFER => {
            trace::trace_depth_buffer(scene, drawing, rule)
        }
        _ => trace_of(request, &trace_backend, rule),
    }
    .unwrap_or_else(|e| Trace::saying(e.to_string()));
    let (gaps, doubles) = if request.kind == "triangles" && snapped.len() > 1 && scene.is_none() {
        heat_map(&snapped, rule, w, h)
    } else {
        (Vec::new(), Vec::new())
    };
    let depth = match &scene {
        Some(scene) => Some(DepthView::of(
            &DepthCells::of_scene(scene, drawing, rule)?,
            &request.depths,
        )),
        None => None,
    };
    let student = match (request.student, program) {
        (true, Some(program)) => Some(student_view(request, rule, program)),
        _ => None,
    };
    let samples = match request.msaa {
        Some(n) if n > 1 && request.kind == "triangles" => Some(SamplesView::of(
            &snapped,
            rule,
            w,
            h,
            &SamplePattern::standard(n)?,
        )),
        _ => None,
    };
    let mut legend = legend(
        request,
        (&gaps, &doubles),
        depth.as_ref(),
        student.is_some(),
    );
    if samples.is_some() {
        legend = legend.with(Role::SampleCovered).with(Role::SampleOutside);
    }
    let textured = TexturedView::of(request, rule)?;
    legend
        .entries
        .extend(textured.iter().flat_map(|t| t.legend_entries()));
    Ok(LabResponse {
        backends: views,
        trace,
        trace_backend,
        gaps,
        doubles,
        depth,
        student,
        samples,
        composite: CompositeView::of(request, rule)?,
        textured,
        legend_html: legend.to_html(),
        legend,
    })
}

/// The legend of an answer: what the page draws for it, in the one
/// palette's pairs: the heat map's states that occur, and in the depth
/// view the back-ends' fragments and tests too, which the page shows
/// side by side.
fn legend(
    request: &LabRequest,
    (gaps, doubles): (&[[i64; 2]], &[[i64; 3]]),
    depth: Option<&DepthView>,
    student: bool,
) -> Legend {
    let triangles = if request.kind == "triangles" {
        request.triangles.len()
    } else {
        0
    };
    let names = |i: usize| match depth {
        Some(_) => format!("{} (z = {})", triangle_name(i), request.depths[i]),
        None => triangle_name(i),
    };
    let mut legend = if depth.is_some() {
        Legend::new(&[Role::Kept, Role::Hidden])
    } else if triangles > 0 {
        Legend::new(&[Role::Drawn, Role::TestedOutside])
    } else {
        Legend::new(&[Role::Drawn])
    };
    if depth.is_some() {
        legend = legend.with(Role::Drawn).with(Role::TestedOutside);
    }
    for (role, occurs) in [
        (Role::Gap, !gaps.is_empty()),
        (Role::DoubleDraw, doubles.iter().any(|d| d[2] == 2)),
        (Role::DrawnTwiceMore, doubles.iter().any(|d| d[2] > 2)),
    ] {
        if occurs {
            legend = legend.with(role);
        }
    }
    legend = if (2..=MAX_TRIANGLES).contains(&triangles) {
        legend.with_triangles(&(0..triangles).map(names).collect::<Vec<_>>())
    } else {
        legend.with(Role::Geometry)
    };
    legend = legend.with(Role::PixelCentre);
    if student {
        let mine = |role: Role, how: &str| format!("my rasterizer: {} ({how})", role.label());
        legend = legend
            .with_mark(Role::Missing, Mark::Frame, &mine(Role::Missing, "outlined"))
            .with_mark(Role::Extra, Mark::Cross, &mine(Role::Extra, "crossed"));
    }
    legend
}

/// Multisampling in the lab: each sample of the grid, and what a resolve
/// makes of each pixel.
#[derive(Clone, Debug, Serialize)]
pub struct SamplesView {
    /// Samples a pixel.
    pub count: u32,
    /// Every sample of every pixel, `[x, y, covered]` in pixel
    /// coordinates (`covered` 1 when a triangle covers it, else 0).
    pub points: Vec<[f64; 3]>,
    /// Each pixel with a sample covered, `[x, y, share]`: the share of its
    /// samples covered, which a box-filter resolve gives its colour.
    pub resolved: Vec<[f64; 3]>,
}

impl SamplesView {
    fn of(
        triangles: &[[FixedPoint; 3]],
        rule: FillRule,
        width: u32,
        height: u32,
        pattern: &SamplePattern,
    ) -> SamplesView {
        let setups = setup_triangles(triangles, rule);
        let mut union = vec![0u32; (width * height) as usize];
        for m in reference_masks(&setups, PixelRect::of_target(width, height), pattern) {
            union[(m.y as u32 * width + m.x as u32) as usize] |= m.mask;
        }
        let n = pattern.count();
        let mut points = Vec::with_capacity((width * height * n) as usize);
        let mut resolved = Vec::new();
        for y in 0..height {
            for x in 0..width {
                let mask = union[(y * width + x) as usize];
                for i in 0..n as usize {
                    let (dx, dy) = pattern.offset(i);
                    points.push([
                        f64::from(x) + 0.5 + f64::from(dx) / 16.0,
                        f64::from(y) + 0.5 + f64::from(dy) / 16.0,
                        f64::from(u8::from(mask & (1 << i) != 0)),
                    ]);
                }
                if mask != 0 {
                    resolved.push([
                        f64::from(x),
                        f64::from(y),
                        f64::from(mask.count_ones()) / f64::from(n),
                    ]);
                }
            }
        }
        SamplesView {
            count: n,
            points,
            resolved,
        }
    }
}

/// The tested and drawn cells of a grid picture.
fn view(name: &str, picture: &GridPicture) -> BackendView {
    let mut tested = Vec::new();
    let mut fragments = Vec::new();
    for (i, &c) in picture.cells.iter().enumerate() {
        let (x, y) = (i as u32 % picture.width, i as u32 / picture.width);
        if c == TESTED_OUTSIDE {
            tested.push([x, y]);
        } else if is_fragment_green(c) {
            // The green shade tells the weight (Wu); full green is 1.
            let weight = (255.0 - f32::from(c[0])) / (255.0 - f32::from(INSIDE[0]));
            fragments.push([x, y, (weight.clamp(0.0, 1.0) * 1000.0).round() as u32]);
        }
    }
    BackendView {
        name: name.to_string(),
        tested,
        fragments,
        caption: picture.caption.clone(),
    }
}

/// Gaps and double draws of the triangles under `rule`.
fn heat_map(
    snapped: &[[FixedPoint; 3]],
    rule: FillRule,
    w: u32,
    h: u32,
) -> (Vec<[i64; 2]>, Vec<[i64; 3]>) {
    let setups: Vec<TriangleSetup> = snapped
        .iter()
        .enumerate()
        .filter_map(|(i, v)| TriangleSetup::new(i as u32, *v, rule))
        .collect();
    let mut gaps = Vec::new();
    let mut doubles = Vec::new();
    for y in 0..i64::from(h) {
        for x in 0..i64::from(w) {
            let p = (
                x * SUBPIXEL_SCALE + HALF_PIXEL,
                y * SUBPIXEL_SCALE + HALF_PIXEL,
            );
            let point = FixedPoint::from_raw(p.0, p.1).unwrap_or_default();
            let drawn = setups.iter().filter(|t| t.covers(point)).count() as i64;
            if drawn >= 2 {
                doubles.push([x, y, drawn]);
            } else if drawn == 0 && cover(&setups, p) == Cover::Inside {
                gaps.push([x, y]);
            }
        }
    }
    (gaps, doubles)
}

/// The student's program on this input, against the exact answer.
fn student_view(request: &LabRequest, rule: FillRule, program: &mut Program) -> StudentView {
    let case = request.case();
    let property = if request.kind == "lines" {
        crate::check::Property::Line(crate::check::judge::LineConvention::Midpoint)
    } else {
        crate::check::Property::Exact(rule)
    };
    program.rule = rule.name().to_string();
    let expected: std::collections::BTreeSet<(i64, i64)> = crate::check::reference(property, &case)
        .iter()
        .map(|f| (f.x, f.y))
        .collect();
    match program.draw(&case) {
        Err(e) => StudentView {
            correct: Vec::new(),
            extra: Vec::new(),
            missing: Vec::new(),
            wrong: 0,
            error: Some(e.to_string()),
            cause: None,
        },
        Ok(drawn) => {
            let cause = crate::check::judge::judge(property, &case, &drawn).map(|_| {
                crate::check::cause::diagnose(property, &[(&case, drawn.as_slice())], &[])
                    .map_or_else(
                        || "no cause in the catalogue explains it".to_string(),
                        |d| d.sentence(),
                    )
            });
            let mut seen = std::collections::BTreeSet::new();
            let (mut correct, mut extra) = (Vec::new(), Vec::new());
            for f in drawn {
                if expected.contains(&(f.x, f.y)) && seen.insert((f.x, f.y)) {
                    correct.push([f.x, f.y]);
                } else {
                    extra.push([f.x, f.y]);
                }
            }
            let missing: Vec<[i64; 2]> = expected
                .iter()
                .filter(|p| !seen.contains(p))
                .map(|&(x, y)| [x, y])
                .collect();
            StudentView {
                wrong: extra.len() + missing.len(),
                correct,
                extra,
                missing,
                error: None,
                cause,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{answer, LabRequest};

    #[test]
    fn the_depth_view_reports_kept_and_hidden_fragments_not_double_draws() {
        // The course's depth-buffer example: the z = 0.8 triangle, drawn
        // second, is hidden behind the z = 0.5 one at the 4 pixels where
        // they overlap.
        let request = LabRequest::parse(
            r#"{"width": 14, "height": 9, "kind": "triangles",
                "triangles": [[[2.75, 3], [12.3359375, 3], [1.9296875, 6.9]], [[3.6, 1], [6.8, 1], [10, 9]]],
                "depths": [0.5, 0.8], "backends": ["bbox"]}"#,
        )
        .unwrap();
        let response = answer(&request, None).unwrap();
        assert!(response.doubles.is_empty() && response.gaps.is_empty());
        let depth = response.depth.expect("a depth view");
        assert_eq!((depth.kept_fragments, depth.hidden_fragments), (27, 4));
        assert_eq!(depth.hidden.len(), 4);
        for &[x, y, n] in &depth.hidden {
            let i = (y * 14 + x) as usize;
            assert_eq!((depth.stored[i], depth.depth[i], n), (Some(0), 0.5, 1));
        }
        assert_eq!(response.trace_backend, "depth-buffer");
        assert!(response.trace.header[0].starts_with("depth buffer, 14 x 9"));
        assert!(response
            .trace
            .to_text()
            .contains("triangle 2 (z = 0.8, 0.8, 0.8): 12 fragments, 8 kept"));
        // One row per row of pixels in each of the three matrices.
        let rows = response.trace.rows.iter().filter(|r| r.is_about(5, 4));
        assert_eq!(rows.count(), 3);
        // The same triangles without depths: a heat map, no depth view.
        let flat = LabRequest {
            depths: Vec::new(),
            ..request
        };
        let response = answer(&flat, None).unwrap();
        assert!(response.depth.is_none() && response.doubles.len() == 4);
        assert_eq!(response.trace_backend, "bbox");
    }

    #[test]
    fn the_page_lists_every_back_end_of_the_registry() {
        let page = super::page();
        assert!(!page.contains("/*TRIANGLE_BACKENDS*/") && !page.contains("/*LINE_BACKENDS*/"));
        for name in crate::raster::registry::all_backends()
            .iter()
            .map(|b| b.name)
        {
            assert!(page.contains(&format!("\"{name}\"")), "{name}");
        }
    }
}

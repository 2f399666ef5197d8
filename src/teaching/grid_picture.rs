//! Zoomed pictures of the pixel grid, as in the rasterization slides.
//!
//! Each pixel is drawn as a large cell with its centre marked (the sample
//! point every test is made at), and over the grid the **true** geometry:
//! the snapped triangle edges with their vertices `v0`-`v2` and edges
//! `E0`-`E2` named as the traces name them (edge `Ek` is opposite vertex
//! `vk`), or the ideal line between a line's endpoints. The cells say what
//! a back-end did, in the colours of the one [palette](super::palette):
//!
//! * **bluish green**: a fragment was emitted (for `wu`, the green is as
//!   strong as the fragment's coverage);
//! * **sky blue**: the back-end evaluated the inside test there and it
//!   failed;
//! * **white**: never looked at.
//!
//! So the bounding box shows as a sky-blue rectangle around the green
//! triangle, the naive loop as a sky-blue grid, scanline with no sky blue
//! at all (it solves each row's span instead of testing pixels), and
//! `tiled` sky blue only in the blocks that straddle an edge, each block
//! framed once with its class.
//!
//! [`GridPicture::coverage_heat_map`] draws the fill-rule pictures instead:
//! each pixel's fragment count against a watertight reference, so that
//! the inclusive rule's double draws (vermillion) and the exclusive rule's
//! gaps (orange) on shared edges stand out. [`GridPicture::depth_buffer`]
//! draws the depth buffer: each pixel where the depth test kept a
//! fragment filled, labelled with the stored depth, and marked where a
//! farther fragment was hidden; the triangles are told apart by their
//! edges, each in its colour and line pattern and named `T1`, `T2`, ...
//! (the palette's identities, never its states).
//!
//! Every picture carries its legend, pixel indices on its axes and a
//! caption. Pictures are written as SVG (sharp at any zoom) or PNG (the
//! same SVG rendered with the bundled font: the same labels and legend);
//! cells are enlarged so that the picture's short side is at least
//! [`MIN_SHORT_SIDE`] pixels.
//!
//! ```
//! use rasterlab::raster::{triangle_backend, FillRule};
//! use rasterlab::teaching::GridPicture;
//!
//! let bbox = triangle_backend("bbox").unwrap();
//! let triangle = [(1.0, 1.0), (9.0, 2.0), (3.0, 7.0)];
//! let picture = GridPicture::of_triangles(bbox, &[triangle], FillRule::TopLeft, 10, 8).unwrap();
//! // The pixel centres within the bounding box: 8 x 6; fragments green, the rest red.
//! assert_eq!(picture.inside_cells() + picture.outside_cells(), 8 * 6);
//! assert_eq!(picture.inside_cells(), 24);
//! assert!(picture.to_svg().starts_with("<svg"));
//! ```

use crate::error::{Error, Result};
use crate::geometry::scene::{setup_triangles, Scene2D};
use crate::markup::Markup;
use crate::raster::edge::{FillRule, PixelRect};
use crate::raster::fixed::FixedPoint;
use crate::raster::fragment::{FragmentSink, LineFragment, TriangleFragment, WorkCounters};
use crate::raster::line::{LineOptions, LineRasterizer, LineSetup};
use crate::raster::multisample::{reference_masks, SamplePattern};
use crate::raster::shader::Flat;
use crate::raster::target::{DepthState, RenderTarget};
use crate::raster::triangle::TriangleRasterizer;
use crate::raster::triangle::{BlockClass, WalkStep};
use crate::teaching::palette::{
    colour_hex, triangle_colour, triangle_mark, triangle_name, Legend, Mark, Role, MAX_TRIANGLES,
};
use std::path::Path;

/// A cell no back-end looked at ([`Role::Untested`]).
pub const UNTESTED: [u8; 3] = Role::Untested.rgb();
/// A cell whose inside test failed ([`Role::TestedOutside`]).
pub const TESTED_OUTSIDE: [u8; 3] = Role::TestedOutside.rgb();
/// A cell that became a fragment ([`Role::Drawn`]).
pub const INSIDE: [u8; 3] = Role::Drawn.rgb();
/// Heat map: covered as often as a watertight rule covers it
/// ([`Role::AsReference`]).
pub const AS_REFERENCE: [u8; 3] = Role::AsReference.rgb();
/// Heat map: covered less often than every watertight rule, a gap
/// ([`Role::Gap`]).
pub const GAP: [u8; 3] = Role::Gap.rgb();
/// Heat map: covered once more than any watertight rule, drawn twice
/// ([`Role::DoubleDraw`]).
pub const OVERDRAWN: [u8; 3] = Role::DoubleDraw.rgb();
/// Heat map: covered two or more times more than any watertight rule
/// ([`Role::DrawnTwiceMore`]).
pub const OVERDRAWN_MORE: [u8; 3] = Role::DrawnTwiceMore.rgb();

/// Pixels per cell in the SVG, at least.
const SVG_CELL: f64 = 32.0;
/// Pixels per cell in the SVG, at most (a grid of one cell).
const SVG_CELL_MAX: f64 = 256.0;
/// The longest side of the grid drawn in an SVG picture, in pixels: large
/// grids get smaller cells.
const SVG_GRID_MAX: f64 = 4096.0;
/// The short side of a picture meant for a person, at least (small
/// grids get larger cells).
pub const MIN_SHORT_SIDE: u32 = 256;
/// Largest grid drawn (4096 x 4096 cells).
pub const MAX_CELLS: u32 = 4096 * 4096;

/// A zoomed picture of the pixel grid.
#[derive(Clone, Debug, PartialEq)]
pub struct GridPicture {
    /// Cells across.
    pub width: u32,
    /// Cells down.
    pub height: u32,
    /// Each cell's colour, row by row.
    pub cells: Vec<[u8; 3]>,
    /// Each cell's label, shown in the SVG (empty: no labels).
    pub labels: Vec<String>,
    /// Closed outlines (triangle edges), in pixel coordinates.
    pub outlines: Vec<Vec<(f64, f64)>>,
    /// Open segments (ideal lines), in pixel coordinates.
    pub segments: Vec<[(f64, f64); 2]>,
    /// Blocks a hierarchical back-end classified as a whole, with their
    /// classes (`tiled`'s 8 x 8 blocks), drawn as framed rectangles: one
    /// frame per block, however many triangles classified it.
    pub blocks: Vec<(PixelRect, BlockClass)>,
    /// Pixels where the depth test hid a fragment, with how many.
    pub hidden: Vec<(u32, u32, u32)>,
    /// Multisample points, in pixel coordinates, and whether a triangle
    /// covers each ([`GridPicture::with_samples`]).
    pub samples: Vec<(f64, f64, bool)>,
    /// One line saying what the picture shows.
    pub caption: String,
    /// What the colours say.
    pub legend: Legend,
}

/// Records what a back-end did to each pixel of a small grid.
struct Recorder {
    width: u32,
    tested: Vec<bool>,
    weight: Vec<f32>,
}

impl Recorder {
    fn new(width: u32, height: u32) -> Recorder {
        let n = (width * height) as usize;
        Recorder {
            width,
            tested: vec![false; n],
            weight: vec![0.0; n],
        }
    }

    fn index(&self, x: u32, y: u32) -> usize {
        (y * self.width + x) as usize
    }

    /// Green for fragments (strength = weight), red for tested-outside.
    fn cells(&self) -> Vec<[u8; 3]> {
        self.weight
            .iter()
            .zip(&self.tested)
            .map(|(&w, &tested)| {
                if w > 0.0 {
                    // Faint fragments stay visibly green.
                    mix(UNTESTED, INSIDE, w.clamp(0.1, 1.0))
                } else if tested {
                    TESTED_OUTSIDE
                } else {
                    UNTESTED
                }
            })
            .collect()
    }
}

impl FragmentSink for Recorder {
    fn triangle_fragment(&mut self, f: &TriangleFragment) {
        let i = self.index(f.x, f.y);
        self.weight[i] += 1.0;
    }

    fn line_fragment(&mut self, f: &LineFragment) {
        let i = self.index(f.x, f.y);
        self.weight[i] += f.coverage;
    }
}

impl Recorder {
    /// Marks the samples a triangle walk tested, as its steps recorded
    /// them.
    fn tested_in(&mut self, steps: &[WalkStep]) {
        for step in steps {
            if let WalkStep::Sample { x, y, .. } = *step {
                let i = self.index(x as u32, y as u32);
                self.tested[i] = true;
            }
        }
    }
}

fn mix(a: [u8; 3], b: [u8; 3], t: f32) -> [u8; 3] {
    [0, 1, 2].map(|k| (a[k] as f32 + (b[k] as f32 - a[k] as f32) * t).round() as u8)
}

/// The triangles' edges, in pixels, as closed outlines.
fn outlines(triangles: &[[FixedPoint; 3]]) -> Vec<Vec<(f64, f64)>> {
    triangles
        .iter()
        .map(|t| t.iter().map(|p| p.to_f64()).collect())
        .collect()
}

fn check_grid(width: u32, height: u32) -> Result<()> {
    RenderTarget::check_size(width, height)?;
    if u64::from(width) * u64::from(height) > u64::from(MAX_CELLS) {
        return Err(Error::InvalidArgument(format!(
            "a {width} x {height} grid is too large to draw cell by cell (at most {MAX_CELLS} cells)"
        )));
    }
    Ok(())
}

impl GridPicture {
    fn blank(width: u32, height: u32, caption: String) -> GridPicture {
        let n = (width * height) as usize;
        GridPicture {
            width,
            height,
            cells: vec![UNTESTED; n],
            labels: Vec::new(),
            outlines: Vec::new(),
            segments: Vec::new(),
            blocks: Vec::new(),
            hidden: Vec::new(),
            samples: Vec::new(),
            caption,
            legend: Legend::default(),
        }
    }

    /// The cells a recorder saw: fragments green, failed tests red.
    fn recorded(recorder: &Recorder, width: u32, height: u32, caption: String) -> GridPicture {
        GridPicture {
            cells: recorder.cells(),
            ..Self::blank(width, height, caption)
        }
    }

    /// Triangles (screen pixels) drawn by a triangle back-end under `rule`
    /// on a `width` x `height` grid: tested, emitted and untouched pixels.
    pub fn of_triangles(
        backend: &dyn TriangleRasterizer,
        triangles: &[[(f64, f64); 3]],
        rule: FillRule,
        width: u32,
        height: u32,
    ) -> Result<GridPicture> {
        let snapped = triangles
            .iter()
            .map(|t| {
                Ok([
                    FixedPoint::snap_f64(t[0].0, t[0].1)?,
                    FixedPoint::snap_f64(t[1].0, t[1].1)?,
                    FixedPoint::snap_f64(t[2].0, t[2].1)?,
                ])
            })
            .collect::<Result<Vec<_>>>()?;
        Self::of_snapped_triangles(backend, &snapped, rule, width, height)
    }

    /// [`GridPicture::of_triangles`] for triangles already snapped.
    pub fn of_snapped_triangles(
        backend: &dyn TriangleRasterizer,
        triangles: &[[FixedPoint; 3]],
        rule: FillRule,
        width: u32,
        height: u32,
    ) -> Result<GridPicture> {
        check_grid(width, height)?;
        let mut recorder = Recorder::new(width, height);
        let setups = setup_triangles(triangles, rule);
        // Each triangle's walk, recorded: its fragments go to the
        // recorder, and its steps say which samples it tested and which
        // blocks it classified.
        let grid = PixelRect::of_target(width, height);
        let mut work = WorkCounters::default();
        let mut blocks = Vec::new();
        for t in &setups {
            let (steps, triangle_work) = backend.record(t, grid, &mut recorder);
            work.add(&triangle_work);
            recorder.tested_in(&steps);
            blocks.extend(steps.into_iter().filter_map(|s| match s {
                WalkStep::Block { rect, class } => Some((rect, class)),
                _ => None,
            }));
        }
        let caption = format!(
            "{}, {} rule: {} pixels tested (sky blue: outside), {} fragments (green)",
            backend.name(),
            rule.name(),
            work.samples_tested,
            work.fragments
        );
        let mut picture = Self::recorded(&recorder, width, height, caption);
        picture.outlines = outlines(triangles);
        picture.blocks = merged_blocks(blocks.into_iter());
        let names: Vec<String> = (0..triangles.len()).map(triangle_name).collect();
        picture.legend = with_edges(
            Legend::new(&[Role::Drawn, Role::TestedOutside, Role::Untested]),
            &names,
        )
        .with(Role::PixelCentre);
        if !picture.blocks.is_empty() {
            picture.legend = picture
                .legend
                .with(Role::BlockInside)
                .with(Role::BlockPartial)
                .with(Role::BlockOutside);
        }
        Ok(picture)
    }

    /// This picture with the samples of `pattern` in every pixel: a dot
    /// where one of `triangles` covers the sample under `rule`, a ring
    /// where none does, each decided as a pixel centre is
    /// ([`reference_masks`]). The cells
    /// still say what the back-end did with one sample a pixel.
    pub fn with_samples(
        mut self,
        triangles: &[[FixedPoint; 3]],
        rule: FillRule,
        pattern: &SamplePattern,
    ) -> GridPicture {
        let grid = PixelRect::of_target(self.width, self.height);
        let setups = setup_triangles(triangles, rule);
        let mut covered = vec![0u32; (self.width * self.height) as usize];
        for m in reference_masks(&setups, grid, pattern) {
            covered[(m.y as u32 * self.width + m.x as u32) as usize] |= m.mask;
        }
        let sixteenth = |v: i8| f64::from(v) / 16.0;
        self.samples = (0..self.height)
            .flat_map(|y| (0..self.width).map(move |x| (x, y)))
            .flat_map(|(x, y)| {
                let mask = covered[(y * self.width + x) as usize];
                (0..pattern.count() as usize).map(move |i| {
                    let (dx, dy) = pattern.offset(i);
                    (
                        f64::from(x) + 0.5 + sixteenth(dx),
                        f64::from(y) + 0.5 + sixteenth(dy),
                        mask & (1 << i) != 0,
                    )
                })
            })
            .collect();
        let inside = self.samples.iter().filter(|s| s.2).count();
        self.caption.push_str(&format!(
            "; {} samples a pixel: {inside} of {} covered",
            pattern.count(),
            self.samples.len()
        ));
        for e in &mut self.legend.entries {
            if e.key == Role::PixelCentre.key() {
                e.label = "pixel centre (the one sample without multisampling)".into();
            }
        }
        self.legend = self
            .legend
            .with(Role::SampleCovered)
            .with(Role::SampleOutside);
        self
    }

    /// Lines given by their snapped ends ([`LineEnds`](crate::teaching::trace::LineEnds):
    /// pixel indices or screen coordinates, as `rasterlab explain` reads
    /// them), drawn by a line back-end: the chosen pixels in green (shaded
    /// by coverage for `wu`) under the ideal line.
    pub fn of_lines(
        backend: &dyn LineRasterizer,
        lines: &[crate::teaching::trace::LineEnds],
        options: &LineOptions,
        width: u32,
        height: u32,
    ) -> Result<GridPicture> {
        check_grid(width, height)?;
        backend.check_options(options)?;
        let setups: Vec<LineSetup> = lines
            .iter()
            .enumerate()
            .map(|(i, l)| LineSetup {
                id: i as u32,
                from: l.from,
                to: l.to,
            })
            .collect();
        let mut recorder = Recorder::new(width, height);
        let work = backend.rasterize(
            &setups,
            options,
            PixelRect::of_target(width, height),
            &mut recorder,
        );
        let caption = format!(
            "{}: {} fragments (green) under the ideal line",
            backend.name(),
            work.fragments
        );
        let mut picture = Self::recorded(&recorder, width, height, caption);
        picture.segments = setups
            .iter()
            .map(|s| [s.from.to_f64(), s.to.to_f64()])
            .collect();
        picture.legend = Legend::new(&[
            Role::Drawn,
            Role::Untested,
            Role::Geometry,
            Role::PixelCentre,
        ]);
        Ok(picture)
    }

    /// The rasterization slides' depth buffer after the whole scene: each
    /// cell where the depth test kept a fragment filled ([`Role::Kept`]),
    /// every cell labelled with its depth (1.0 where nothing was drawn),
    /// marked where a farther fragment was hidden, and the triangles'
    /// edges named `T1`, `T2`, ... in their colours and line patterns.
    pub fn depth_buffer(scene: &Scene2D, rule: FillRule) -> Result<GridPicture> {
        let bbox = crate::raster::registry::triangle_backend("bbox")?;
        let cells = DepthCells::of_scene(scene, bbox, rule)?;
        let hidden: usize = cells.hidden.iter().map(Vec::len).sum();
        let kept: usize = cells.kept.iter().map(Vec::len).sum();
        let mut picture = Self::blank(
            scene.width,
            scene.height,
            format!(
                "depth buffer after {} triangles: {kept} fragments kept, {hidden} hidden (1.0 = nothing drawn)",
                scene.triangles.len()
            ),
        );
        picture.labels = cells.depth.iter().map(|z| format!("{z:.1}")).collect();
        for (i, kept) in cells.kept.iter().enumerate() {
            if !kept.is_empty() {
                picture.cells[i] = Role::Kept.rgb();
            }
            if !cells.hidden[i].is_empty() {
                let (x, y) = (i as u32 % scene.width, i as u32 / scene.width);
                picture.hidden.push((x, y, cells.hidden[i].len() as u32));
            }
        }
        picture.outlines = outlines(&scene.triangles);
        let labels: Vec<String> = scene
            .vertices
            .iter()
            .enumerate()
            .map(|(i, v)| format!("{} (z = {})", triangle_name(i), v[0].depth))
            .collect();
        picture.legend =
            with_edges(Legend::new(&[Role::Kept, Role::Hidden]), &labels).with(Role::PixelCentre);
        Ok(picture)
    }

    /// A fill-rule heat map: each pixel's fragment count (`coverage`)
    /// against the counts of watertight rules (`watertight`, for example
    /// top-left and bottom-right). Where those agree the count is what it
    /// must be; where they differ (pixel centres on the outline, which each
    /// watertight rule gives to one side or the other) any count between
    /// them is right. A count within that range is pale green (white where
    /// nothing covers the pixel); below it, a gap (red); above it by one,
    /// drawn twice (orange); by two or more, purple.
    pub fn coverage_heat_map(
        width: u32,
        height: u32,
        coverage: &[u16],
        watertight: &[&[u16]],
        caption: String,
    ) -> Result<GridPicture> {
        check_grid(width, height)?;
        let n = (width * height) as usize;
        if coverage.len() != n || watertight.is_empty() || watertight.iter().any(|w| w.len() != n) {
            return Err(Error::InvalidArgument(format!(
                "a heat map needs coverage buffers of {n} pixels for a {width} x {height} grid, and at least one watertight reference"
            )));
        }
        let mut picture = Self::blank(width, height, caption);
        for (i, &c) in coverage.iter().enumerate() {
            let lo = watertight.iter().map(|w| w[i]).min().unwrap_or(0);
            let hi = watertight.iter().map(|w| w[i]).max().unwrap_or(0);
            picture.cells[i] = if c < lo {
                GAP
            } else if c > hi + 1 {
                OVERDRAWN_MORE
            } else if c > hi {
                OVERDRAWN
            } else if c == 0 {
                UNTESTED
            } else {
                AS_REFERENCE
            };
        }
        // The states that occur, and the pixel centres.
        let roles = [
            Role::AsReference,
            Role::Gap,
            Role::DoubleDraw,
            Role::DrawnTwiceMore,
        ];
        let shown: Vec<Role> = roles
            .into_iter()
            .filter(|r| picture.cells.contains(&r.rgb()))
            .chain([Role::PixelCentre])
            .collect();
        picture.legend = Legend::new(&shown);
        Ok(picture)
    }

    /// Cells with a fragment (any shade of green).
    pub fn inside_cells(&self) -> usize {
        self.cells.iter().filter(|&&c| is_fragment_green(c)).count()
    }

    /// Cells tested and found outside (red).
    pub fn outside_cells(&self) -> usize {
        self.count(TESTED_OUTSIDE)
    }

    /// Cells of exactly colour `c`.
    pub fn count(&self, c: [u8; 3]) -> usize {
        self.cells.iter().filter(|&&x| x == c).count()
    }

    /// Pixels per cell in the SVG: at least 32, more for a small grid (its
    /// short side at least [`MIN_SHORT_SIDE`]), fewer for a grid whose
    /// long side would pass 4096 pixels.
    pub fn svg_cell(&self) -> f64 {
        let short = f64::from(self.width.min(self.height));
        let long = f64::from(self.width.max(self.height));
        (f64::from(MIN_SHORT_SIDE) / short)
            .ceil()
            .clamp(SVG_CELL, SVG_CELL_MAX)
            .min((SVG_GRID_MAX / long).floor())
            .max(1.0)
    }

    /// The picture as a standalone SVG document: caption, pixel indices on
    /// both axes, the grid, and the legend below.
    pub fn to_svg(&self) -> String {
        self.svg(true)
    }

    /// The picture as an SVG document without its caption and legend, for
    /// a page that writes them in HTML (the axes stay).
    pub fn to_svg_bare(&self) -> String {
        self.svg(false)
    }

    fn svg(&self, framed: bool) -> String {
        let s = self.svg_cell();
        let (w, h) = (f64::from(self.width) * s, f64::from(self.height) * s);
        // Room for the row numbers left, the column numbers above.
        let digits = self.width.max(self.height).to_string().len() as f64;
        let left = 8.0 + 7.5 * digits;
        let caption_height = if framed { 26.0 } else { 0.0 };
        let top = caption_height + 18.0;
        let legend_width = (w + left).max(420.0) - 8.0;
        let dots = s >= 12.0;
        let (legend, legend_height) = if framed {
            // Pixel centres are dotted only where the cells are large enough.
            let mut legend = self.legend.clone();
            legend
                .entries
                .retain(|e| dots || e.key != Role::PixelCentre.key());
            legend.to_svg(4.0, top + h + 8.0, legend_width)
        } else {
            (String::new(), 0.0)
        };
        // DejaVu Sans at 15 px: about 8.4 px a character.
        let caption_width = if framed {
            self.caption.chars().count() as f64 * 8.4 + 12.0
        } else {
            0.0
        };
        let width = (left + w + 8.0).max(legend_width + 8.0).max(caption_width);
        let height = top + h + 8.0 + legend_height;
        let mut m = Markup::new();
        m.open(
            "svg",
            &[
                ("xmlns", &"http://www.w3.org/2000/svg"),
                ("width", &width),
                ("height", &height),
                ("viewBox", &format_args!("0 0 {width} {height}")),
                ("font-family", &"DejaVu Sans, sans-serif"),
            ],
        )
        .newline();
        m.element("title", &[], &self.caption).newline();
        m.empty(
            "path",
            &[
                ("d", &format_args!("M0 0H{width}V{height}H0Z")),
                ("fill", &"white"),
            ],
        )
        .newline();
        if framed {
            m.element(
                "text",
                &[
                    ("class", &"caption"),
                    ("x", &4),
                    ("y", &18),
                    ("font-size", &15),
                ],
                &self.caption,
            )
            .newline();
        }
        // Pixel indices: every one while they fit, else every 2nd, 5th, 10th ...
        let step = [1u32, 2, 5, 10, 20, 50, 100, 200, 500, 1000]
            .into_iter()
            .find(|&k| f64::from(k) * s >= 7.0 * digits + 4.0)
            .unwrap_or(1000);
        m.open(
            "g",
            &[("class", &"axes"), ("font-size", &11), ("fill", &"#444")],
        );
        for x in (0..self.width).step_by(step as usize) {
            m.element(
                "text",
                &[
                    ("x", &(left + (f64::from(x) + 0.5) * s)),
                    ("y", &(top - 5.0)),
                    ("text-anchor", &"middle"),
                ],
                &x.to_string(),
            );
        }
        for y in (0..self.height).step_by(step as usize) {
            m.element(
                "text",
                &[
                    ("x", &(left - 4.0)),
                    ("y", &(top + (f64::from(y) + 0.5) * s + 4.0)),
                    ("text-anchor", &"end"),
                ],
                &y.to_string(),
            );
        }
        m.close("g").newline();
        m.open(
            "g",
            &[("transform", &format_args!("translate({left} {top})"))],
        );
        m.open("clipPath", &[("id", &"grid-view")])
            .empty("path", &[("d", &format_args!("M0 0H{w}V{h}H0Z"))])
            .close("clipPath")
            .newline();
        let label_size = format!("{:.1}", (s / 2.9).min(13.0));
        let centre_colour = Role::PixelCentre.hex();
        for y in 0..self.height {
            for x in 0..self.width {
                let i = (y * self.width + x) as usize;
                m.empty(
                    "rect",
                    &[
                        ("x", &(f64::from(x) * s)),
                        ("y", &(f64::from(y) * s)),
                        ("width", &s),
                        ("height", &s),
                        ("fill", &colour_hex(self.cells[i])),
                        ("stroke", &"#9a9a9a"),
                        ("stroke-width", &1),
                    ],
                )
                .newline();
                let (cx, cy) = ((f64::from(x) + 0.5) * s, (f64::from(y) + 0.5) * s);
                let label = self.labels.get(i).filter(|l| !l.is_empty());
                if let Some(label) = label.filter(|_| s >= 20.0) {
                    // Below the centre, so the sample point stays visible.
                    m.element(
                        "text",
                        &[
                            ("x", &cx),
                            ("y", &(cy + s * 0.34)),
                            ("font-size", &label_size),
                            ("text-anchor", &"middle"),
                        ],
                        label,
                    );
                    m.empty(
                        "circle",
                        &[
                            ("cx", &cx),
                            ("cy", &(cy - s * 0.12)),
                            ("r", &1.8),
                            ("fill", &centre_colour),
                        ],
                    )
                    .newline();
                } else if dots {
                    m.empty(
                        "circle",
                        &[
                            ("cx", &cx),
                            ("cy", &cy),
                            ("r", &2.2),
                            ("fill", &centre_colour),
                        ],
                    )
                    .newline();
                }
            }
        }
        let sample_colour = Role::SampleCovered.hex();
        let r = (s * 0.07).clamp(1.2, 4.0);
        for &(x, y, inside) in &self.samples {
            let (fill, stroke) = if inside {
                (sample_colour.as_str(), "none")
            } else {
                ("white", sample_colour.as_str())
            };
            m.empty(
                "circle",
                &[
                    ("class", &if inside { "sample covered" } else { "sample" }),
                    ("cx", &(x * s)),
                    ("cy", &(y * s)),
                    ("r", &r),
                    ("fill", &fill),
                    ("stroke", &stroke),
                    ("stroke-width", &(r * 0.45)),
                ],
            )
            .newline();
        }
        for &(x, y, n) in &self.hidden {
            // A grey corner: a fragment hidden here, with how many.
            let (x0, y0) = (f64::from(x) * s, f64::from(y) * s);
            let k = s * 0.42;
            m.empty(
                "path",
                &[
                    ("class", &"hidden"),
                    ("d", &format_args!("M{} {y0}h{k}v{k}Z", x0 + s - k)),
                    ("fill", &Role::Hidden.hex()),
                ],
            );
            m.element(
                "text",
                &[
                    ("x", &(x0 + s - 2.0)),
                    ("y", &(y0 + k * 0.55)),
                    ("font-size", &format_args!("{:.1}", k * 0.55)),
                    ("text-anchor", &"end"),
                    ("fill", &"white"),
                ],
                &n.to_string(),
            )
            .newline();
        }
        m.open("g", &[("clip-path", &"url(#grid-view)")]).newline();
        for (t, outline) in self.outlines.iter().enumerate() {
            let (colour, mark) = self.edge_style(t);
            let points: Vec<String> = outline
                .iter()
                .map(|(x, y)| format!("{},{}", x * s, y * s))
                .collect();
            m.empty(
                "polygon",
                &[
                    ("class", &"outline"),
                    ("data-mark", &mark),
                    ("points", &points.join(" ")),
                    ("fill", &"none"),
                    ("stroke", &colour_hex(colour)),
                    ("stroke-width", &2.5),
                    ("stroke-dasharray", &mark.dasharray().unwrap_or("none")),
                ],
            )
            .newline();
        }
        for (r, class) in &self.blocks {
            let (role, letter) = block_style(*class);
            let colour = role.hex();
            let (x, y) = (r.x0 as f64 * s, r.y0 as f64 * s);
            m.empty(
                "rect",
                &[
                    ("class", &"block"),
                    ("x", &(x + 2.5)),
                    ("y", &(y + 2.5)),
                    ("width", &((r.x1 - r.x0 + 1) as f64 * s - 5.0)),
                    ("height", &((r.y1 - r.y0 + 1) as f64 * s - 5.0)),
                    ("fill", &"none"),
                    ("stroke", &colour),
                    ("stroke-width", &3),
                    (
                        "stroke-dasharray",
                        &Mark::Block.dasharray().unwrap_or("none"),
                    ),
                ],
            );
            m.element(
                "text",
                &[
                    ("x", &(x + 5.0)),
                    ("y", &(y + 15.0)),
                    ("font-size", &12),
                    ("font-weight", &"bold"),
                    ("fill", &colour),
                ],
                &letter.to_string(),
            )
            .newline();
        }
        for [(x0, y0), (x1, y1)] in &self.segments {
            m.empty(
                "line",
                &[
                    ("x1", &(x0 * s)),
                    ("y1", &(y0 * s)),
                    ("x2", &(x1 * s)),
                    ("y2", &(y1 * s)),
                    ("stroke", &Role::Geometry.hex()),
                    ("stroke-width", &2.5),
                ],
            )
            .newline();
        }
        m.close("g").newline();
        self.geometry_labels(&mut m, s, w, h);
        m.close("g").newline();
        m.raw(&legend);
        m.close("svg").newline();
        m.finish()
    }

    /// The names the traces use, on a picture of one triangle: its
    /// vertices `v0`-`v2` and edges `E0`-`E2` (`Ek` opposite `vk`).
    /// Several triangles are named `T1`, `T2`, ... at their centres
    /// instead, in their colours (up to [`MAX_TRIANGLES`]).
    fn geometry_labels(&self, m: &mut Markup, s: f64, w: f64, h: f64) {
        let label = |m: &mut Markup, (x, y): (f64, f64), text: &str, colour: &str| {
            // Kept inside the grid, on a white halo.
            let (x, y) = (x.clamp(8.0, w - 8.0), y.clamp(12.0, h - 4.0));
            m.halo_label("geometry-label", (x, y), colour, text)
                .newline();
        };
        if self.names_triangles() {
            for (t, outline) in self.outlines.iter().enumerate() {
                let n = outline.len() as f64;
                let (x, y) = outline
                    .iter()
                    .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
                label(
                    m,
                    (x * s, y * s + 5.0),
                    &triangle_name(t),
                    &colour_hex(triangle_colour(t)),
                );
            }
        }
        if let [outline] = self.outlines.as_slice() {
            let n = outline.len() as f64;
            let centre = outline
                .iter()
                .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
            let away = |(x, y): (f64, f64), by: f64| {
                let (dx, dy) = (x - centre.0, y - centre.1);
                let len = (dx * dx + dy * dy).sqrt().max(1e-9);
                (x * s + dx / len * by, y * s + dy / len * by + 5.0)
            };
            let colour = Role::Geometry.hex();
            for (k, &p) in outline.iter().enumerate() {
                let (x, y) = p;
                m.empty(
                    "circle",
                    &[
                        ("class", &"vertex"),
                        ("cx", &(x * s)),
                        ("cy", &(y * s)),
                        ("r", &4),
                        ("fill", &colour),
                    ],
                )
                .newline();
                label(m, away(p, 14.0), &format!("v{k}"), &colour);
                let (a, b) = (outline[(k + 1) % 3], outline[(k + 2) % 3]);
                let mid = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
                label(m, away(mid, 13.0), &format!("E{k}"), &colour);
            }
        }
    }

    /// The grid alone as an image, `zoom` image pixels per grid cell (for
    /// a page that shows the legend beside it; [`GridPicture::save`]
    /// writes the whole picture). At a zoom of 6 or more the cell borders
    /// and centres are drawn too, and the outlines and segments at any
    /// zoom; labels, axes and legend are in [`GridPicture::to_svg`].
    pub fn to_png(&self, zoom: u32) -> Result<image::RgbImage> {
        let zoom = zoom.max(1);
        let (w, h) = (self.width * zoom, self.height * zoom);
        RenderTarget::check_size(w, h)?;
        let mut img = image::RgbImage::from_fn(w, h, |px, py| {
            let c = self.cells[((py / zoom) * self.width + px / zoom) as usize];
            if zoom >= 6 {
                let (ix, iy) = (px % zoom, py % zoom);
                let (mid, r) = (zoom / 2, zoom / 12 + 1);
                if ix == 0 || iy == 0 {
                    return image::Rgb([154, 154, 154]);
                }
                if ix.abs_diff(mid) < r && iy.abs_diff(mid) < r && self.labels.is_empty() {
                    return image::Rgb([51, 51, 51]);
                }
            }
            image::Rgb(c)
        });
        let z = zoom as f64;
        let mut stroke =
            |(x0, y0): (f64, f64), (x1, y1): (f64, f64), color: [u8; 3], mark: Mark| {
                let steps = ((x1 - x0).abs().max((y1 - y0).abs()) * z * 2.0)
                    .ceil()
                    .max(1.0) as u32;
                // The dash pattern, in image pixels, as the SVG draws it.
                let dashes: Vec<f64> = mark
                    .dasharray()
                    .map(|d| d.split(' ').filter_map(|v| v.parse().ok()).collect())
                    .unwrap_or_default();
                let period: f64 = dashes.iter().sum();
                let length = (x1 - x0).hypot(y1 - y0) * z;
                for i in 0..=steps {
                    let t = i as f64 / steps as f64;
                    if period > 0.0 {
                        // In a gap: the odd entries of the pattern.
                        let mut along = (t * length) % period;
                        let mut k = 0;
                        while along >= dashes[k] {
                            along -= dashes[k];
                            k += 1;
                        }
                        if k % 2 == 1 {
                            continue;
                        }
                    }
                    let (x, y) = ((x0 + (x1 - x0) * t) * z, (y0 + (y1 - y0) * t) * z);
                    for (dx, dy) in [(0.0, 0.0), (-1.0, 0.0), (0.0, -1.0), (-1.0, -1.0)] {
                        let (px, py) = ((x + dx).round(), (y + dy).round());
                        if px >= 0.0 && py >= 0.0 && px < w as f64 && py < h as f64 {
                            img.put_pixel(px as u32, py as u32, image::Rgb(color));
                        }
                    }
                }
            };
        for (t, outline) in self.outlines.iter().enumerate() {
            let (colour, mark) = self.edge_style(t);
            for k in 0..outline.len() {
                stroke(outline[k], outline[(k + 1) % outline.len()], colour, mark);
            }
        }
        for &[a, b] in &self.segments {
            stroke(a, b, Role::Geometry.rgb(), Mark::Line);
        }
        for (r, class) in &self.blocks {
            let colour = block_style(*class).0.rgb();
            // Just inside the block, so neighbouring frames do not overlap.
            let inset = 2.0 / z;
            let (x0, y0) = (r.x0 as f64 + inset, r.y0 as f64 + inset);
            let (x1, y1) = ((r.x1 + 1) as f64 - inset, (r.y1 + 1) as f64 - inset);
            for (a, b) in [
                ((x0, y0), (x1, y0)),
                ((x1, y0), (x1, y1)),
                ((x1, y1), (x0, y1)),
                ((x0, y1), (x0, y0)),
            ] {
                stroke(a, b, colour, Mark::Block);
            }
        }
        if zoom >= 8 {
            // Each sample a 3 x 3 square: filled when covered, hollow not.
            let black = image::Rgb(Role::SampleCovered.rgb());
            for &(x, y, inside) in &self.samples {
                let (cx, cy) = ((x * z).round() as i64, (y * z).round() as i64);
                for dy in -1..=1i64 {
                    for dx in -1..=1i64 {
                        let (px, py) = (cx + dx, cy + dy);
                        if (0..i64::from(w)).contains(&px) && (0..i64::from(h)).contains(&py) {
                            let ring = dx != 0 || dy != 0;
                            let c = if inside || ring {
                                black
                            } else {
                                image::Rgb([255, 255, 255])
                            };
                            img.put_pixel(px as u32, py as u32, c);
                        }
                    }
                }
            }
        }
        Ok(img)
    }

    /// Whether the picture tells its triangles apart (2 to
    /// [`MAX_TRIANGLES`] of them): each its colour, line pattern and name.
    fn names_triangles(&self) -> bool {
        (2..=MAX_TRIANGLES).contains(&self.outlines.len())
    }

    /// The colour and line pattern of outline `t`: its triangle's when
    /// the picture tells triangles apart, else the true geometry's.
    fn edge_style(&self, t: usize) -> ([u8; 3], Mark) {
        if self.names_triangles() {
            (triangle_colour(t), triangle_mark(t))
        } else {
            (Role::Geometry.rgb(), Role::Geometry.mark())
        }
    }

    /// The file types [`GridPicture::save`] writes.
    pub const EXTENSIONS: [&'static str; 2] = ["svg", "png"];

    /// The picture as an image: with the `png-text` feature (on by
    /// default), the SVG picture rendered with the bundled font (the same
    /// caption, axes, labels and legend). Without it, or for a grid of
    /// more than [`MAX_LABELLED_CELLS`] cells, the grid is drawn cell by
    /// cell ([`GridPicture::to_png`]) at the SVG's cell size, at most about
    /// 2048 pixels on its long side.
    pub fn to_picture_png(&self) -> Result<image::RgbaImage> {
        let cells = u64::from(self.width) * u64::from(self.height);
        #[cfg(feature = "png-text")]
        if cells <= MAX_LABELLED_CELLS {
            if let Some(picture) = crate::output::svg_to_png(&self.to_svg()) {
                return Ok(picture);
            }
        }
        let zoom = if cells <= MAX_LABELLED_CELLS {
            self.svg_cell() as u32
        } else {
            (2048 / self.width.max(self.height)).max(1)
        };
        Ok(image::DynamicImage::ImageRgb8(self.to_png(zoom)?).into_rgba8())
    }

    /// Writes the picture as SVG or PNG ([`GridPicture::to_picture_png`]),
    /// by the path's extension.
    pub fn save(&self, path: &Path) -> Result<()> {
        crate::output::check_file(path, &Self::EXTENSIONS)?;
        if crate::output::extension(path).as_deref() == Some("svg") {
            crate::output::write_file(path, self.to_svg().as_bytes())
        } else {
            crate::output::write_png(path, &self.to_picture_png()?)
        }
    }
}

/// The scale that enlarges a `width` x `height` image until its short
/// side is at least [`MIN_SHORT_SIDE`] pixels (1 for an image that large
/// already; at most 64).
pub fn scale_for_people(width: u32, height: u32) -> u32 {
    MIN_SHORT_SIDE
        .div_ceil(width.min(height).max(1))
        .clamp(1, 64)
}

/// A rendered target as a picture meant for a person: small scenes
/// enlarged by [`scale_for_people`], each pixel a framed cell
/// ([`RenderTarget::to_image_scaled`]), so that the short side is at least
/// [`MIN_SHORT_SIDE`] pixels.
///
/// ```
/// use rasterlab::geometry::Scene2D;
/// use rasterlab::raster::{triangle_backend, FillRule, Flat};
/// use rasterlab::teaching::{for_people, MIN_SHORT_SIDE};
///
/// let scene = Scene2D::split_square();
/// let (target, _) = scene.render(triangle_backend("bbox")?, FillRule::TopLeft, &Flat)?;
/// let picture = for_people(&target);
/// assert!(picture.width().min(picture.height()) >= MIN_SHORT_SIDE);
/// # Ok::<(), rasterlab::Error>(())
/// ```
pub fn for_people(target: &RenderTarget) -> image::RgbaImage {
    target.to_image_scaled(scale_for_people(target.width(), target.height()))
}

/// The largest grid [`GridPicture::to_picture_png`] renders with its
/// labels and legend (256 x 256 cells).
pub const MAX_LABELLED_CELLS: u64 = 256 * 256;

/// `legend` and the edges of `labels.len()` triangles: each triangle's
/// swatch, named by `labels`, when a picture tells them apart (2 to
/// [`MAX_TRIANGLES`]), else the true geometry's.
fn with_edges(legend: Legend, labels: &[String]) -> Legend {
    if (2..=MAX_TRIANGLES).contains(&labels.len()) {
        legend.with_triangles(labels)
    } else {
        legend.with(Role::Geometry)
    }
}

/// The frame's role and letter of a block class: inside (trivial accept)
/// `I`, outside (trivial reject) `O`, partial (tested pixel by pixel) `P`.
fn block_style(class: BlockClass) -> (Role, char) {
    match class {
        BlockClass::Inside => (Role::BlockInside, 'I'),
        BlockClass::Outside => (Role::BlockOutside, 'O'),
        BlockClass::Partial => (Role::BlockPartial, 'P'),
    }
}

/// One frame per block however many triangles classified it: partial if
/// any triangle's edges cross it, else inside if it is inside any
/// triangle, else outside (so that many triangles' frames do not overlap
/// into a tangle). Blocks keep the order they were first classified in.
fn merged_blocks(
    blocks: impl Iterator<Item = (PixelRect, BlockClass)>,
) -> Vec<(PixelRect, BlockClass)> {
    let rank = |c: BlockClass| match c {
        BlockClass::Outside => 0,
        BlockClass::Inside => 1,
        BlockClass::Partial => 2,
    };
    let mut merged: Vec<(PixelRect, BlockClass)> = Vec::new();
    let mut index = std::collections::HashMap::new();
    for (r, class) in blocks {
        let key = (r.x0, r.y0, r.x1, r.y1);
        match index.get(&key) {
            Some(&i) => {
                let (_, old): &mut (PixelRect, BlockClass) = &mut merged[i];
                if rank(class) > rank(*old) {
                    *old = class;
                }
            }
            None => {
                index.insert(key, merged.len());
                merged.push((r, class));
            }
        }
    }
    merged
}

/// What the depth test did at each pixel of a scene drawn in order: the
/// depth stored, the triangle whose fragment is stored, and the triangles
/// whose fragments were hidden (farther than the depth already stored,
/// or equal to it: the test is `f.z < depthBuffer`). Triangles are
/// numbered from 0 in drawing order.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthCells {
    /// Grid width.
    pub width: u32,
    /// Grid height.
    pub height: u32,
    /// The depth stored, row by row (1.0: nothing drawn).
    pub depth: Vec<f32>,
    /// The triangles whose fragments the depth test kept, per pixel, in
    /// drawing order: the last one's depth and colour are stored (the
    /// others' were kept, then overwritten by a nearer fragment).
    pub kept: Vec<Vec<u32>>,
    /// The triangles whose fragments the depth test hid, per pixel.
    pub hidden: Vec<Vec<u32>>,
}

impl DepthCells {
    /// Draws `scene` by `backend` under `rule` through the shared stage
    /// with the rasterization slides' depth test (`less`, writes on), one
    /// triangle at a time, and records each pixel's outcome.
    pub fn of_scene(
        scene: &Scene2D,
        backend: &dyn TriangleRasterizer,
        rule: FillRule,
    ) -> Result<DepthCells> {
        check_grid(scene.width, scene.height)?;
        let n = (scene.width * scene.height) as usize;
        let mut target = RenderTarget::new(scene.width, scene.height)?;
        let mut kept = vec![Vec::new(); n];
        let mut hidden = vec![Vec::new(); n];
        for (t, (triangle, vertices)) in scene.triangles.iter().zip(&scene.vertices).enumerate() {
            let one = Scene2D {
                triangles: vec![*triangle],
                vertices: vec![*vertices],
                ..scene.clone()
            };
            // The triangle's own fragments, then what the test did to them.
            let (alone, _) = one.render(backend, rule, &Flat)?;
            let before = target.depth.clone();
            one.draw(backend, rule, DepthState::DEFAULT, &Flat, &mut target);
            for i in 0..n {
                if alone.coverage[i] == 0 {
                    continue;
                }
                if target.depth[i].to_bits() != before[i].to_bits() {
                    kept[i].push(t as u32);
                } else {
                    hidden[i].push(t as u32);
                }
            }
        }
        Ok(DepthCells {
            width: scene.width,
            height: scene.height,
            depth: target.depth,
            kept,
            hidden,
        })
    }
}

/// A shade between white (excluded) and [`INSIDE`]: a fragment's cell.
pub fn is_fragment_green(c: [u8; 3]) -> bool {
    if c == UNTESTED {
        return false;
    }
    let t = (255.0 - c[0] as f32) / (255.0 - INSIDE[0] as f32);
    let shade = mix(UNTESTED, INSIDE, t);
    (0.0..=1.0).contains(&t) && (0..3).all(|k| shade[k].abs_diff(c[k]) <= 1)
}

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

mod depth;
mod png;
mod recorder;
mod svg;

pub use depth::DepthCells;
pub use png::{for_people, scale_for_people, MAX_LABELLED_CELLS};

use crate::error::{Error, Result};
use crate::geometry::outline::Outline;
use crate::geometry::scene::{setup_triangles, Scene2D};
use crate::raster::derivatives::{each_triangle_pixels, quad_helper_pixels};
use crate::raster::edge::{FillRule, PixelRect};
use crate::raster::fixed::{FixedPoint, HALF_PIXEL, SUBPIXEL_SCALE};
use crate::raster::fragment::WorkCounters;
use crate::raster::line::{LineOptions, LineRasterizer, LineSetup};
use crate::raster::multisample::{reference_masks, SamplePattern};
use crate::raster::polygon::edge_table::EdgeTable;
use crate::raster::polygon::{PolygonRasterizer, WindingRule};
use crate::raster::target::RenderTarget;
use crate::raster::triangle::TriangleRasterizer;
use crate::raster::triangle::{BlockClass, WalkStep};
use crate::teaching::palette::{
    triangle_colour, triangle_mark, triangle_name, Legend, Mark, Role, MAX_TRIANGLES,
};
use recorder::Recorder;
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

/// The short side of a picture meant for a person, at least (small
/// grids get larger cells).
pub const MIN_SHORT_SIDE: u32 = 256;
/// Largest grid drawn (4096 x 4096 cells).
pub const MAX_CELLS: u32 = 4096 * 4096;

/// A straight stroke from one point to another, in pixel coordinates.
type Stroke = [(f64, f64); 2];

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
    /// Under quad derivatives ([`GridPicture::with_quads`]): the 2x2
    /// quads are drawn, and these pixels, the helpers, crossed.
    pub quad_helpers: Option<Vec<(u32, u32)>>,
    /// One line saying what the picture shows.
    pub caption: String,
    /// What the colours say.
    pub legend: Legend,
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
            quad_helpers: None,
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

    /// A polygon bounded by `rings` (snapped, taken as given: a ring is
    /// not turned against the first) filled by the edge table under
    /// `rule` on a `width` x `height` grid: the pixels filled green, each
    /// pixel centre labelled with its winding number where it is not 0,
    /// and the rings' edges with an arrow at each edge's middle, the way
    /// the ring runs (the winding number counts that way round).
    pub fn of_polygon(
        rings: &[Vec<FixedPoint>],
        rule: WindingRule,
        width: u32,
        height: u32,
    ) -> Result<GridPicture> {
        check_grid(width, height)?;
        let outline = Outline::new(rings.to_vec())?;
        let mut recorder = Recorder::new(width, height);
        let grid = PixelRect::of_target(width, height);
        let work = EdgeTable.rasterize(&[outline.setup(0)], rule, grid, &mut recorder);
        let caption = format!(
            "edge-table, {rule}: {} fragments (green) in {} spans; each pixel centre labelled with its winding number (blank: 0)",
            work.work.fragments, work.runs
        );
        let mut picture = Self::recorded(&recorder, width, height, caption);
        picture.labels = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| {
                let centre = FixedPoint::from_raw(
                    i64::from(x) * SUBPIXEL_SCALE + HALF_PIXEL,
                    i64::from(y) * SUBPIXEL_SCALE + HALF_PIXEL,
                );
                match centre.map(|c| outline.winding_number(c)) {
                    Ok(0) | Err(_) => String::new(),
                    Ok(w) => w.to_string(),
                }
            })
            .collect();
        for ring in rings {
            let points: Vec<(f64, f64)> = ring.iter().map(|p| p.to_f64()).collect();
            for (k, &a) in points.iter().enumerate() {
                let b = points[(k + 1) % points.len()];
                picture.segments.push([a, b]);
                picture.segments.extend(arrow_head(a, b));
            }
        }
        picture.legend = Legend::new(&[Role::Drawn])
            .with_mark(
                Role::Geometry,
                Mark::Line,
                "the rings' edges, each arrow the way its ring runs",
            )
            .with(Role::PixelCentre);
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

    /// This picture with the 2x2 quads a GPU shades `triangles` in (for
    /// their derivatives, aligned to even pixels) drawn, and each quad's
    /// helper pixels crossed: the pixels of a quad that a triangle's
    /// fragments touch that are not its fragments, shaded for the
    /// differences and never written. Each triangle's quads are its own.
    pub fn with_quads(
        mut self,
        backend: &dyn TriangleRasterizer,
        triangles: &[[FixedPoint; 3]],
        rule: FillRule,
    ) -> GridPicture {
        let grid = PixelRect::of_target(self.width, self.height);
        let mut helpers = Vec::new();
        let mut fragments = 0;
        let setups = setup_triangles(triangles, rule);
        each_triangle_pixels(&setups, backend, grid, |_, pixels| {
            fragments += pixels.len();
            helpers.extend(
                quad_helper_pixels(pixels)
                    .into_iter()
                    .filter(|&(x, y)| x < self.width && y < self.height),
            );
        });
        let shaded = fragments + helpers.len();
        self.caption.push_str(&format!(
            "; 2x2 quads: {} helper pixel(s) beside {fragments} fragment(s), {:.0}% of the shading",
            helpers.len(),
            if shaded == 0 {
                0.0
            } else {
                100.0 * helpers.len() as f64 / shaded as f64
            }
        ));
        self.legend = self
            .legend
            .with_mark(
                Role::Geometry,
                Mark::Dashed,
                "2x2 quad: derivatives are differences within one",
            )
            .with_mark(
                Role::Geometry,
                Mark::Cross,
                "helper pixel: shaded for its quad, never written",
            );
        self.quad_helpers = Some(helpers);
        self
    }

    /// The strokes that draw the quads, in pixel coordinates: the lines
    /// between quads (every even column and row inside the grid), then a
    /// diagonal across each helper pixel.
    fn quad_strokes(&self) -> (Vec<Stroke>, Vec<Stroke>) {
        let Some(helpers) = &self.quad_helpers else {
            return (Vec::new(), Vec::new());
        };
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        let lines = (1..self.width.div_ceil(2))
            .map(|k| f64::from(2 * k))
            .map(|x| [(x, 0.0), (x, h)])
            .chain(
                (1..self.height.div_ceil(2))
                    .map(|k| f64::from(2 * k))
                    .map(|y| [(0.0, y), (w, y)]),
            )
            .collect();
        let crosses = helpers
            .iter()
            .map(|&(x, y)| {
                let (x, y) = (f64::from(x), f64::from(y));
                [(x + 0.2, y + 0.2), (x + 0.8, y + 0.8)]
            })
            .collect();
        (lines, crosses)
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

/// Two strokes of an arrow head at the middle of the edge from `a` to
/// `b`, pointing towards `b` (none for an edge too short to hold one).
fn arrow_head(a: (f64, f64), b: (f64, f64)) -> Vec<Stroke> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let length = (dx * dx + dy * dy).sqrt();
    if length < 0.5 {
        return Vec::new();
    }
    let (ux, uy) = (dx / length, dy / length);
    let tip = ((a.0 + b.0) / 2.0 + ux * 0.2, (a.1 + b.1) / 2.0 + uy * 0.2);
    let size = 0.35;
    [1.0, -1.0]
        .into_iter()
        .map(|side| {
            let back = (
                tip.0 - ux * size - uy * size * 0.6 * side,
                tip.1 - uy * size + ux * size * 0.6 * side,
            );
            [back, tip]
        })
        .collect()
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

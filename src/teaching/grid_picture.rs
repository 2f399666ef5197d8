//! Zoomed pictures of the pixel grid, as in the rasterization slides.
//!
//! Each pixel is drawn as a large cell with its centre marked (the sample
//! point every test is made at), and over the grid the **true** geometry:
//! the snapped triangle edges, or the ideal line between a line's
//! endpoints. The cells say what a back-end did:
//!
//! * **green**: a fragment was emitted (for `wu`, the green is as strong as
//!   the fragment's coverage);
//! * **red**: the back-end evaluated the inside test there and it failed;
//! * **white**: never looked at.
//!
//! So the bounding box shows as a red rectangle around the green
//! triangle, the naive loop as a red grid, scanline with no red at all
//! (it solves each row's span instead of testing pixels), and `tiled` red
//! only in the blocks that straddle an edge.
//!
//! [`GridPicture::coverage_heat_map`] draws the fill-rule pictures instead:
//! each pixel's fragment count against a watertight reference, so that
//! the inclusive rule's double draws (orange) and the exclusive rule's gaps
//! (red) on shared edges stand out.
//!
//! Pictures are written as SVG (sharp at any zoom, with labels such as the
//! depth values of [`GridPicture::depth_buffer`]) or PNG.
//!
//! ```
//! use rasterlab::raster::backend::triangle_backend;
//! use rasterlab::raster::edge::FillRule;
//! use rasterlab::teaching::grid_picture::GridPicture;
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
use crate::raster::edge::{FillRule, PixelRect};
use crate::raster::fixed::FixedPoint;
use crate::raster::fragment::{FragmentSink, LineFragment, TriangleFragment};
use crate::raster::line::{LineOptions, LineRasterizer, LineSetup};
use crate::raster::shader::Flat;
use crate::raster::target::RenderTarget;
use crate::raster::triangle::tiled::{blocks, BlockClass};
use crate::raster::triangle::TriangleRasterizer;
use crate::raster::triangle::TriangleWalk;
use std::fmt::Write;
use std::path::Path;

/// A cell no back-end looked at.
pub const UNTESTED: [u8; 3] = [255, 255, 255];
/// A cell whose inside test failed (the rasterization slides' red).
pub const TESTED_OUTSIDE: [u8; 3] = [235, 110, 100];
/// A cell that became a fragment (the rasterization slides' green).
pub const INSIDE: [u8; 3] = [70, 180, 90];
/// Heat map: covered as often as a watertight rule covers it.
pub const AS_REFERENCE: [u8; 3] = [200, 225, 205];
/// Heat map: covered less often than every watertight rule (a gap).
pub const GAP: [u8; 3] = [220, 40, 40];
/// Heat map: covered once more than any watertight rule (drawn twice).
pub const OVERDRAWN: [u8; 3] = [250, 160, 30];
/// Heat map: covered two or more times more than any watertight rule.
pub const OVERDRAWN_MORE: [u8; 3] = [140, 40, 160];

/// Pixels per cell in the SVG.
const SVG_CELL: f64 = 32.0;
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
    /// classes (`tiled`'s 8 x 8 blocks), drawn as framed rectangles.
    pub blocks: Vec<(PixelRect, BlockClass)>,
    /// One line saying what the picture shows.
    pub caption: String,
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

    fn samples_tested(&mut self, _triangle: u32, y: u32, x0: u32, x1: u32) {
        for x in x0..=x1 {
            let i = self.index(x, y);
            self.tested[i] = true;
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
            caption,
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
        let work = backend.rasterize(&setups, PixelRect::of_target(width, height), &mut recorder);
        let caption = format!(
            "{}, {} rule: {} pixels tested (red: outside), {} fragments (green)",
            backend.name(),
            rule.name(),
            work.samples_tested,
            work.fragments
        );
        let mut picture = Self::recorded(&recorder, width, height, caption);
        picture.outlines = outlines(triangles);
        if backend.descriptor().walk == TriangleWalk::Blocks {
            picture.blocks = setups
                .iter()
                .flat_map(|t| blocks(t, PixelRect::of_target(width, height)))
                .collect();
        }
        Ok(picture)
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
        Ok(picture)
    }

    /// The rasterization slides' depth buffer after the whole scene: each cell in the
    /// colour it was drawn, labelled with its depth (1.0 where nothing
    /// was drawn).
    pub fn depth_buffer(scene: &Scene2D, rule: FillRule) -> Result<GridPicture> {
        check_grid(scene.width, scene.height)?;
        let bbox = crate::raster::backend::triangle_backend("bbox")?;
        let (target, _) = scene.render(bbox, rule, &Flat)?;
        let mut picture = Self::blank(
            scene.width,
            scene.height,
            format!(
                "depth buffer after {} triangles (1.0 = nothing drawn)",
                scene.triangles.len()
            ),
        );
        picture.labels = target.depth.iter().map(|z| format!("{z:.1}")).collect();
        for i in 0..target.depth.len() {
            if target.coverage[i] > 0 {
                let [r, g, b, _] = target.color[i];
                picture.cells[i] = mix(UNTESTED, [r, g, b], 0.55);
            }
        }
        picture.outlines = outlines(&scene.triangles);
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

    /// The picture as a standalone SVG document.
    pub fn to_svg(&self) -> String {
        let s = SVG_CELL;
        let (w, h) = (self.width as f64 * s, self.height as f64 * s);
        let caption_height = 28.0;
        let mut out = String::new();
        let _ = writeln!(
            out,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{}" viewBox="0 {} {w} {}" font-family="sans-serif">"#,
            h + caption_height,
            -caption_height,
            h + caption_height
        );
        let _ = writeln!(out, "<title>{}</title>", escape(&self.caption));
        let _ = writeln!(
            out,
            r#"<text x="4" y="-9" font-size="15">{}</text>"#,
            escape(&self.caption)
        );
        for y in 0..self.height {
            for x in 0..self.width {
                let i = (y * self.width + x) as usize;
                let [r, g, b] = self.cells[i];
                let _ = writeln!(
                    out,
                    r##"<rect x="{}" y="{}" width="{s}" height="{s}" fill="#{r:02x}{g:02x}{b:02x}" stroke="#9a9a9a" stroke-width="1"/>"##,
                    x as f64 * s,
                    y as f64 * s
                );
                let (cx, cy) = ((x as f64 + 0.5) * s, (y as f64 + 0.5) * s);
                let label = self.labels.get(i).filter(|l| !l.is_empty());
                if let Some(label) = label {
                    let _ = writeln!(
                        out,
                        r#"<text x="{cx}" y="{}" font-size="11" text-anchor="middle">{}</text>"#,
                        cy + 4.0,
                        escape(label)
                    );
                } else {
                    let _ = writeln!(
                        out,
                        r##"<circle cx="{cx}" cy="{cy}" r="2.2" fill="#333"/>"##
                    );
                }
            }
        }
        for outline in &self.outlines {
            let points: Vec<String> = outline
                .iter()
                .map(|(x, y)| format!("{},{}", x * s, y * s))
                .collect();
            let _ = writeln!(
                out,
                r##"<polygon points="{}" fill="none" stroke="#1b1b1b" stroke-width="2"/>"##,
                points.join(" ")
            );
        }
        for (r, class) in &self.blocks {
            let (colour, letter) = block_style(*class);
            let [cr, cg, cb] = colour;
            let (x, y) = (r.x0 as f64 * s, r.y0 as f64 * s);
            let _ = writeln!(
                out,
                r##"<rect class="block" x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#{cr:02x}{cg:02x}{cb:02x}" stroke-width="3" stroke-dasharray="6 3"/><text x="{}" y="{}" font-size="12" font-weight="bold" fill="#{cr:02x}{cg:02x}{cb:02x}">{letter}</text>"##,
                x + 1.5,
                y + 1.5,
                (r.x1 - r.x0 + 1) as f64 * s - 3.0,
                (r.y1 - r.y0 + 1) as f64 * s - 3.0,
                x + 4.0,
                y + 14.0
            );
        }
        for [(x0, y0), (x1, y1)] in &self.segments {
            let _ = writeln!(
                out,
                r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#1d4ed8" stroke-width="2.5"/>"##,
                x0 * s,
                y0 * s,
                x1 * s,
                y1 * s
            );
        }
        out.push_str("</svg>\n");
        out
    }

    /// The picture as an image, `zoom` image pixels per grid cell. At a
    /// zoom of 6 or more the cell borders and centres are drawn too, and
    /// the outlines and segments at any zoom; labels are in the SVG only.
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
        let mut stroke = |(x0, y0): (f64, f64), (x1, y1): (f64, f64), color: [u8; 3]| {
            let steps = ((x1 - x0).abs().max((y1 - y0).abs()) * z * 2.0)
                .ceil()
                .max(1.0) as u32;
            for i in 0..=steps {
                let t = i as f64 / steps as f64;
                let (x, y) = ((x0 + (x1 - x0) * t) * z, (y0 + (y1 - y0) * t) * z);
                for (dx, dy) in [(0.0, 0.0), (-1.0, 0.0), (0.0, -1.0), (-1.0, -1.0)] {
                    let (px, py) = ((x + dx).round(), (y + dy).round());
                    if px >= 0.0 && py >= 0.0 && px < w as f64 && py < h as f64 {
                        img.put_pixel(px as u32, py as u32, image::Rgb(color));
                    }
                }
            }
        };
        for outline in &self.outlines {
            for k in 0..outline.len() {
                stroke(outline[k], outline[(k + 1) % outline.len()], [27, 27, 27]);
            }
        }
        for &[a, b] in &self.segments {
            stroke(a, b, [29, 78, 216]);
        }
        for (r, class) in &self.blocks {
            let colour = block_style(*class).0;
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
                stroke(a, b, colour);
            }
        }
        Ok(img)
    }

    /// The file types [`GridPicture::save`] writes.
    pub const EXTENSIONS: [&'static str; 2] = ["svg", "png"];

    /// Writes the picture as SVG or PNG (24 pixels per cell), by the
    /// path's extension.
    pub fn save(&self, path: &Path) -> Result<()> {
        crate::output::check_file(path, &Self::EXTENSIONS)?;
        if crate::output::extension(path).as_deref() == Some("svg") {
            crate::output::write_file(path, self.to_svg().as_bytes())
        } else {
            crate::output::write_png(path, &self.to_png(24)?)
        }
    }
}

/// The frame colour and letter of a block class: inside (trivial accept)
/// dark green `I`, outside (trivial reject) grey `O`, partial (tested pixel
/// by pixel) orange `P`.
fn block_style(class: BlockClass) -> ([u8; 3], char) {
    match class {
        BlockClass::Inside => ([20, 110, 40], 'I'),
        BlockClass::Outside => ([120, 120, 120], 'O'),
        BlockClass::Partial => ([220, 120, 0], 'P'),
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

/// Text made safe for XML and HTML.
pub(crate) fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

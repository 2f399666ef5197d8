//! Step-by-step traces of one algorithm on one small input, in the
//! course's terms, as data ([`Trace`]: header lines, a table whose rows
//! carry the pixels they are about, totals) and as the plain-text tables
//! `rasterlab explain` prints. The triangle traces are recordings of the
//! back-ends' real walks.
//!
//! * [`trace_line`] on `bresenham`: the line-drawing slides' midpoint
//!   loop, each column's `x`, `y`, decision variable `d = f(x + 1, y + 1/2)`
//!   and the choice it makes; on `direct` and `dda`: each column's exact
//!   `y` and the row it rounds to; on `wu`: each column's two pixels and
//!   their weights; on `diamond`: the candidate pixels around the line the
//!   back-end's walk tests, in its order, and whether the segment leaves
//!   each one's diamond;
//! * [`trace_triangle`] on `bbox` and `naive`: every pixel tested, its
//!   three edge values, its barycentric coordinates, inside or not, and
//!   why (which edge rejected it, or which tie rule decided); on
//!   `scanline`: the vertices sorted by y, then each row's sample line,
//!   where each active edge crosses it and the span filled; on
//!   `incremental`: the edge values at the box's first sample, the steps
//!   added per pixel and per row, every pixel the walk tests; on `tiled`:
//!   every 8 x 8 block of the box and its class from the corner test
//!   (trivial reject, trivial accept, partial);
//! * [`trace_depth_buffer`]: the rasterization slides' depth buffer, printed as the
//!   slides' matrix after each triangle.
//!
//! Line endpoints are given as [`LineEnds`]: pixel indices, as in the
//! course's hand-worked tables (`0 0 7 3` means from the centre of pixel
//! (0, 0) to the centre of pixel (7, 3)), or screen coordinates, as in
//! files and `rasterlab fragments` (`0.5 0.5 7.5 3.5` is the same line).
//! The trace's first line says which. Every coordinate is read as `f64` and
//! snapped as every other command snaps it. Edge values are printed in
//! square pixels (the fixed-point value divided by 256^2).
//!
//! ```
//! use rasterlab::raster::line_backend;
//! use rasterlab::teaching::{trace_line, LineEnds};
//! let ends = LineEnds::pixels([0.0, 0.0, 7.0, 3.0]).unwrap();
//! let text = trace_line(line_backend("bresenham").unwrap(), &ends).unwrap().to_text();
//! assert!(text.lines().nth(2).unwrap().contains("0.500"));
//! assert_eq!(ends, LineEnds::screen([0.5, 0.5, 7.5, 3.5]).unwrap().snapped_only());
//! ```

use crate::error::{Error, Result};
use crate::geometry::scene::Scene2D;
use crate::raster::edge::{FillRule, PixelRect, TriangleSetup};
use crate::raster::fixed::{FixedPoint, HALF_PIXEL, SUBPIXEL_SCALE};
use crate::raster::fragment::FragmentList;
use crate::raster::line::bresenham::Bresenham;
use crate::raster::line::dda::Dda;
use crate::raster::line::direct::Direct;
use crate::raster::line::{LineRasterizer, LineWalk, OctantFrame};
use crate::raster::shader::Flat;
use crate::raster::target::{DepthState, DepthTest, RenderTarget};
use crate::raster::triangle::scanline::{row_range, sorted_by_y};
use crate::raster::triangle::tiled::BLOCK;
use crate::raster::triangle::{BlockClass, Bound, TriangleRasterizer, TriangleWalk, WalkStep};
use crate::teaching::trace_table::{Column, Trace, TraceRow};

/// The most pixel lines a triangle trace prints, and the most depth-buffer
/// cells the depth-buffer trace prints (about 5 MB of text): a trace is
/// read by a person, and past this it would only fill the memory.
pub const MAX_TRACE_LINES: u64 = 65_536;

/// Refuses a trace that would print more than [`MAX_TRACE_LINES`] lines.
pub(crate) fn check_trace_length(lines: u64, what: &str) -> Result<()> {
    if lines > MAX_TRACE_LINES {
        return Err(Error::TooMuchWork(format!(
            "this trace would print {lines} {what} (at most {MAX_TRACE_LINES}): trace a smaller grid (--size) or triangle"
        )));
    }
    Ok(())
}

/// Square pixels per fixed-point edge unit.
pub(crate) const AREA_UNIT: f64 = (SUBPIXEL_SCALE * SUBPIXEL_SCALE) as f64;

/// A line's two endpoints, snapped, and how they were given.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct LineEnds {
    /// The snapped start.
    pub from: FixedPoint,
    /// The snapped end.
    pub to: FixedPoint,
    /// True when given as pixel indices (their centres), false for screen
    /// coordinates.
    pub pixel_indices: bool,
}

impl LineEnds {
    /// From pixel `(x0, y0)` to pixel `(x1, y1)`: their centres, as in the
    /// course's tables.
    pub fn pixels([x0, y0, x1, y1]: [f64; 4]) -> Result<LineEnds> {
        Ok(LineEnds {
            from: FixedPoint::snap_centre_of(x0, y0)?,
            to: FixedPoint::snap_centre_of(x1, y1)?,
            pixel_indices: true,
        })
    }

    /// From `(x0, y0)` to `(x1, y1)` in screen coordinates, as files and
    /// `rasterlab fragments` read them.
    pub fn screen([x0, y0, x1, y1]: [f64; 4]) -> Result<LineEnds> {
        Ok(LineEnds {
            from: FixedPoint::snap_f64(x0, y0)?,
            to: FixedPoint::snap_f64(x1, y1)?,
            pixel_indices: false,
        })
    }

    /// The same snapped points, marked as given in pixel indices (for
    /// comparing two ways of writing one line).
    pub fn snapped_only(self) -> LineEnds {
        LineEnds {
            pixel_indices: true,
            ..self
        }
    }

    /// "from pixel (0, 0) to pixel (7, 3) (centres ...)" or "from (0.5,
    /// 0.5) to ... in screen coordinates".
    fn describe(&self) -> String {
        let (fx, fy) = self.from.to_f64();
        let (tx, ty) = self.to.to_f64();
        if self.pixel_indices {
            format!(
                "from pixel ({}, {}) to pixel ({}, {}) (pixel indices: the line joins their centres)",
                fx - 0.5,
                fy - 0.5,
                tx - 0.5,
                ty - 0.5
            )
        } else {
            format!("from ({fx}, {fy}) to ({tx}, {ty}) in screen coordinates")
        }
    }
}

fn frame_note(frame: &OctantFrame) -> String {
    let mut notes = Vec::new();
    if frame.swap {
        notes.push("steep: x and y swapped");
    }
    if frame.flip_major {
        notes.push("major axis mirrored");
    }
    if frame.flip_minor {
        notes.push("minor axis mirrored");
    }
    if notes.is_empty() {
        "first octant: no symmetry needed".to_string()
    } else {
        format!(
            "walked in the first octant ({}), pixels mapped back",
            notes.join(", ")
        )
    }
}

/// The line-drawing slides' midpoint / Bresenham loop on one line: each
/// column's `x`, `y`, pixel, decision variable and choice.
fn bresenham(ends: &LineEnds) -> Trace {
    let frame = OctantFrame::new(ends.from, ends.to);
    let mut out = Trace::saying(format!(
        "bresenham (midpoint) {}; {}",
        ends.describe(),
        frame_note(&frame)
    ));
    out.columns = vec![
        Column::right("x", 4, 0),
        Column::right("y", 6, 1),
        Column::right("pixel", 6, 1),
        Column::right("d", 12, 1),
        Column::left("choice", 0, 2),
    ];
    for step in Bresenham::steps(&frame) {
        let (px, py) = frame.to_screen(step.i, step.k);
        let d = step.d as f64 / AREA_UNIT;
        let choice = if step.step_up {
            "d < 0: midpoint below the line, y = y + 1"
        } else {
            "d >= 0: midpoint on or above the line, keep y"
        };
        out.rows.push(TraceRow::at_pixel(
            vec![
                step.i.to_string(),
                step.k.to_string(),
                format!("{px},{py}"),
                format!("{d:.3}"),
                choice.to_string(),
            ],
            px,
            py,
        ));
    }
    out.footer.push(
        "d = f(x + 1, y + 1/2) with f(x, y) = (y0 - y1) x + (x1 - x0) y + x0 y1 - x1 y0, in the walking frame".to_string(),
    );
    out
}

/// The step-by-step trace of a triangle back-end on one triangle given in
/// screen pixels, on a `width` x `height` grid: the recording of its
/// real walk ([`TriangleRasterizer::record`]), every step it reported
/// (samples tested, rows' crossings and spans, blocks' classes), in the
/// form its [walk](crate::raster::descriptor::Descriptor::walk) is taught
/// in, each row with the pixels it is about.
pub fn trace_triangle(
    backend: &dyn TriangleRasterizer,
    vertices: [(f64, f64); 3],
    rule: FillRule,
    width: u32,
    height: u32,
) -> Result<Trace> {
    let walk = backend.descriptor().walk;
    let nothing = match walk {
        TriangleWalk::Scanline => "no row is filled, nothing is drawn",
        TriangleWalk::IncrementalEdges => "nothing is tested",
        TriangleWalk::Blocks => "no block is visited",
        _ => "no pixel is tested, nothing is drawn",
    };
    let grid = PixelRect::of_target(width, height);
    let mut out = Trace::default();
    let Some(t) = snapped_or_say(vertices, rule, &mut out, nothing)? else {
        return Ok(out);
    };
    let region = match walk {
        TriangleWalk::EveryPixel => grid,
        _ => t.bounds_within(grid),
    };
    match walk {
        TriangleWalk::Scanline => {}
        TriangleWalk::Blocks => check_trace_length(region.area() / 8, "block lines")?,
        _ => check_trace_length(region.area(), "pixel lines")?,
    }
    let (steps, _) = backend.record(&t, grid, &mut FragmentList::default());
    let recorded = Recorded {
        name: backend.name(),
        t: &t,
        rule,
        vertices,
        grid,
        region,
        steps: &steps,
    };
    match walk {
        TriangleWalk::Scanline => Ok(recorded.scanline(out)),
        TriangleWalk::IncrementalEdges => Ok(recorded.incremental(out)),
        TriangleWalk::Blocks => Ok(recorded.blocks(out)),
        TriangleWalk::EveryPixel | TriangleWalk::BoundingBox | TriangleWalk::Own(_) => {
            Ok(recorded.per_pixel(out, walk))
        }
    }
}

/// A walk's recording on one triangle, and what its trace's header says.
struct Recorded<'a> {
    name: &'static str,
    t: &'a TriangleSetup,
    rule: FillRule,
    vertices: [(f64, f64); 3],
    grid: PixelRect,
    region: PixelRect,
    steps: &'a [WalkStep],
}

impl Recorded<'_> {
    /// The samples tested, in order: `(x, y, edges, inside, stops)`, where
    /// `stops` says the walk stopped the row after this sample.
    fn samples(&self) -> Vec<(i64, i64, [i64; 3], bool, bool)> {
        let mut out: Vec<(i64, i64, [i64; 3], bool, bool)> = Vec::new();
        for step in self.steps {
            match *step {
                WalkStep::Sample {
                    x,
                    y,
                    edges,
                    inside,
                } => out.push((x, y, edges, inside, false)),
                WalkStep::RowStops { y, x } => {
                    if let Some(last) = out.last_mut().filter(|s| (s.0, s.1) == (x, y)) {
                        last.4 = true;
                    }
                }
                _ => {}
            }
        }
        out
    }

    /// `name, rule: triangle ..., twice its area, winding`, the box (for
    /// the bounding-box loop), the walk's own words, the edges' kinds, then
    /// every sample tested with its edge values, barycentrics and verdict.
    fn per_pixel(&self, mut out: Trace, walk: TriangleWalk) -> Trace {
        let (t, rule, region) = (self.t, self.rule, self.region);
        out.header.push(format!(
            "{}, {} rule: triangle {:?}, twice its area = {:.4} px^2, {}",
            self.name,
            rule.name(),
            self.vertices,
            t.area as f64 / AREA_UNIT,
            if t.winding > 0 {
                "counter-clockwise on screen"
            } else {
                "clockwise on screen (edges flipped so inside is positive)"
            }
        ));
        match walk {
            TriangleWalk::BoundingBox => {
                out.header.push(format!(
                    "bounding box: pixels x {}..={}, y {}..={}",
                    region.x0, region.x1, region.y0, region.y1
                ));
            }
            TriangleWalk::Own(words) => {
                out.header.push(format!(
                    "walk: {words}; the samples it tested, in its order"
                ));
            }
            _ => {}
        }
        for k in 0..3 {
            let e = t.edges[k];
            out.header.push(format!(
                "E{k} (opposite v{k}): {} edge; {}",
                e.kind(),
                rule.explain_tie(&e)
            ));
        }
        out.columns = vec![
            Column::right("x", 4, 0),
            Column::right("y", 4, 1),
            Column::right("E0", 9, 1),
            Column::right("E1", 9, 1),
            Column::right("E2", 9, 1),
            Column::right("alpha", 7, 1),
            Column::right("beta", 7, 1),
            Column::right("gamma", 7, 1),
            Column::left("verdict", 0, 2),
        ];
        let samples = self.samples();
        let mut inside_count = 0;
        for &(x, y, e, inside, _) in &samples {
            let [alpha, beta, gamma] = t.barycentric(e);
            inside_count += usize::from(inside);
            let verdict = verdict(t, e);
            let edge = |k: usize| format!("{:.4}", e[k] as f64 / AREA_UNIT);
            out.rows.push(TraceRow::at_pixel(
                vec![
                    x.to_string(),
                    y.to_string(),
                    edge(0),
                    edge(1),
                    edge(2),
                    format!("{alpha:.3}"),
                    format!("{beta:.3}"),
                    format!("{gamma:.3}"),
                    verdict,
                ],
                x,
                y,
            ));
        }
        out.footer.push(format!(
            "{} pixels tested, {inside_count} fragments",
            samples.len()
        ));
        out
    }

    /// The vertices sorted by y, the rows, then each row's crossings (the
    /// bound each active edge gives) and its span, as the walk solved them.
    fn scanline(&self, mut out: Trace) -> Trace {
        let (t, grid) = (self.t, self.grid);
        let order = sorted_by_y(t);
        let [top, mid, bottom] = order;
        let pixel = |k: usize| {
            let (x, y) = t.vertices[k].to_f64();
            format!("v{k} ({x}, {y})")
        };
        out.header.push(format!(
            "scanline, {} rule: sorted by y, top {}, mid {}, bottom {}",
            self.rule.name(),
            pixel(top),
            pixel(mid),
            pixel(bottom)
        ));
        out.header.push(format!(
            "long edge v{top}-v{bottom} (E{mid}) bounds every row; short edges v{top}-v{mid} (E{bottom}) above mid, v{mid}-v{bottom} (E{top}) below"
        ));
        let (first_row, last_row) = row_range(t, order, grid);
        out.header.push(format!(
            "rows {first_row}..={last_row}: their sample lines y = row + 0.5 lie between top and bottom"
        ));
        out.columns = vec![
            Column::right("row", 4, 0),
            Column::right("sample y", 8, 1),
            Column::left("edge crossings: exact x -> pixel bound", 72, 2),
            Column::left("span", 0, 1),
        ];
        let (mut filled, mut rows) = (0, 0);
        let mut crossings: Vec<String> = Vec::new();
        for step in self.steps {
            match *step {
                WalkStep::Crossing {
                    y: j,
                    edge: k,
                    bound,
                } => {
                    let e = &t.edges[k];
                    let y = j * SUBPIXEL_SCALE + HALF_PIXEL;
                    let bound = match bound {
                        Bound::First(first) => format!("first {}", first.max(grid.x0)),
                        Bound::Last(last) => format!("last {}", last.min(grid.x1)),
                        Bound::All => "all".to_string(),
                        Bound::None => "none".to_string(),
                    };
                    crossings.push(if e.a == 0 {
                        format!("E{k} horizontal -> {bound}")
                    } else {
                        // E = a X + b Y + c = 0 at X = -(b Y + c) / a (fixed units).
                        let x = -((e.b * y + e.c) as f64) / e.a as f64 / SUBPIXEL_SCALE as f64;
                        format!("E{k} x = {x:.4} -> {bound}")
                    });
                }
                WalkStep::Span { y: j, first, last } => {
                    rows += 1;
                    let filled_text = if last < first {
                        "empty".to_string()
                    } else {
                        filled += last - first + 1;
                        format!("{first}..={last} ({} px)", last - first + 1)
                    };
                    let y = j * SUBPIXEL_SCALE + HALF_PIXEL;
                    out.rows.push(
                        TraceRow::new(vec![
                            j.to_string(),
                            format!("{:.3}", y as f64 / SUBPIXEL_SCALE as f64),
                            crossings.join("; "),
                            filled_text,
                        ])
                        .about(grid.x0, j, grid.x1, j),
                    );
                    crossings.clear();
                }
                _ => {}
            }
        }
        out.footer.push(format!(
            "{rows} rows, {filled} fragments; a left edge (E rising to the right) gives the first pixel, a right edge the last"
        ));
        out
    }

    /// The box, the edge values at its first sample and the steps, then
    /// every sample the walk tested with its stepped edge values.
    fn incremental(&self, mut out: Trace) -> Trace {
        let (t, r) = (self.t, self.region);
        let (step_x, step_y) = t.pixel_steps();
        let px = |v: [i64; 3]| v.map(|e| format!("{:+.4}", e as f64 / AREA_UNIT)).join(" ");
        out.header.push(format!(
            "{}, {} rule: bounding box x {}..={}, y {}..={}; E evaluated once, at pixel ({}, {}), then only added to",
            self.name,
            self.rule.name(),
            r.x0,
            r.x1,
            r.y0,
            r.y1,
            r.x0,
            r.y0
        ));
        if r.is_empty() {
            out.header
                .push("no pixel centre of the grid is in the box: nothing is tested".to_string());
            return out;
        }
        out.header.push(format!(
            "per pixel right E += ({})   per row down E += ({})",
            px(step_x),
            px(step_y)
        ));
        out.columns = vec![
            Column::right("x", 4, 0),
            Column::right("y", 4, 1),
            Column::right("E0", 10, 1),
            Column::right("E1", 10, 1),
            Column::right("E2", 10, 1),
            Column::left("verdict", 0, 2),
        ];
        let samples = self.samples();
        let mut fragments = 0;
        for &(x, y, e, inside, stops) in &samples {
            let verdict = if inside {
                fragments += 1;
                "inside"
            } else if stops {
                "outside: past the span, the row stops (the triangle is convex)"
            } else {
                "outside"
            };
            let [a, b, c] = e.map(|v| format!("{:.4}", v as f64 / AREA_UNIT));
            out.rows.push(TraceRow::at_pixel(
                vec![x.to_string(), y.to_string(), a, b, c, verdict.to_string()],
                x,
                y,
            ));
        }
        out.footer.push(format!(
            "{} pixels tested, {fragments} fragments; no multiplication after the first pixel",
            samples.len()
        ));
        out
    }

    /// The box, then every block (or stretch of blocks) the walk
    /// classified, with its class, and the count of pixels it tested.
    fn blocks(&self, mut out: Trace) -> Trace {
        let r = self.region;
        out.header.push(format!(
            "{}, {} rule: the bounding box x {}..={}, y {}..={} in {BLOCK} x {BLOCK} blocks on the grid's block lines; each block classified from its corners",
            self.name,
            self.rule.name(),
            r.x0,
            r.x1,
            r.y0,
            r.y1
        ));
        if r.is_empty() {
            return out;
        }
        let tested = self.samples().len();
        let blocks: Vec<(PixelRect, BlockClass)> = self
            .steps
            .iter()
            .filter_map(|s| match *s {
                WalkStep::Block { rect, class } => Some((rect, class)),
                _ => None,
            })
            .collect();
        if blocks.is_empty() {
            out.header.push(format!(
                "the box is smaller than a block: the back-end skips the corner test and tests its pixels one by one, {tested} of them"
            ));
            return out;
        }
        out.columns = vec![
            Column::right("columns", 15, 0),
            Column::right("rows", 15, 1),
            Column::left("class", 0, 2),
        ];
        let mut counts = [0u64; 3];
        for (block, class) in blocks {
            let what = match class {
                BlockClass::Outside => {
                    counts[0] += 1;
                    "outside: trivial reject, no pixel tested"
                }
                BlockClass::Inside => {
                    counts[1] += 1;
                    "inside: trivial accept, every pixel drawn untested"
                }
                BlockClass::Partial => {
                    counts[2] += 1;
                    "partial: an edge crosses it, each pixel tested"
                }
            };
            out.rows.push(
                TraceRow::new(vec![
                    format!("{}..={}", block.x0, block.x1),
                    format!("{}..={}", block.y0, block.y1),
                    what.to_string(),
                ])
                .about(block.x0, block.y0, block.x1, block.y1),
            );
        }
        out.footer.push(format!(
            "{} outside, {} inside, {} partial blocks or stretches; {tested} pixels tested (a row of a partial block stops past its span)",
            counts[0], counts[1], counts[2]
        ));
        out
    }
}

/// The step-by-step trace of a line back-end on one segment: the trace of
/// the way it [chooses](crate::raster::descriptor::Descriptor::walk) its
/// pixels, each row with the pixels it is about.
pub fn trace_line(backend: &dyn LineRasterizer, ends: &LineEnds) -> Result<Trace> {
    match backend.descriptor().walk {
        LineWalk::DirectEvaluation | LineWalk::Incremental => column_trace(backend, ends),
        LineWalk::Midpoint => Ok(bresenham(ends)),
        LineWalk::AntiAliased => Ok(wu(ends)),
        LineWalk::DiamondExit => diamond(ends),
    }
}

/// [`trace_line`] of a back-end that walks by direct evaluation or the DDA.
fn column_trace(backend: &dyn LineRasterizer, ends: &LineEnds) -> Result<Trace> {
    let name = backend.name();
    let frame = OctantFrame::new(ends.from, ends.to);
    let du = frame.du() as f64;
    let m = if du > 0.0 {
        frame.dv() as f64 / du
    } else {
        0.0
    };
    let walk = backend.descriptor().walk;
    let how = match walk {
        LineWalk::DirectEvaluation => {
            "y = m (x - x0) + y0, evaluated exactly per column, then rounded"
        }
        LineWalk::Incremental => {
            "y starts at y0 and grows by m per column (y = y + m), then rounded"
        }
        _ => {
            return Err(Error::InvalidArgument(format!(
                "no column trace for `{name}` (it is for direct evaluation and the DDA)"
            )))
        }
    };
    let mut out = Trace::saying(format!(
        "{name} {}, m = {m:.4}: {how}; {}",
        ends.describe(),
        frame_note(&frame)
    ));
    out.columns = vec![
        Column::right("x", 4, 0),
        Column::right("exact y", 10, 1),
        Column::right("y", 6, 1),
        Column::right("pixel", 6, 1),
    ];
    // The columns the back-end itself walks, as it walks them.
    let columns: Vec<(i64, f64, i64)> = match walk {
        LineWalk::DirectEvaluation => Direct::columns(&frame),
        _ => Dda::columns(&frame),
    };
    for (i, exact, k) in columns {
        let (px, py) = frame.to_screen(i, k);
        out.rows.push(TraceRow::at_pixel(
            vec![
                i.to_string(),
                format!("{exact:.4}"),
                k.to_string(),
                format!("{px},{py}"),
            ],
            px,
            py,
        ));
    }
    out.footer.push(
        "rounding: the nearest row; a tie (exactly .5) goes to the row nearer the start"
            .to_string(),
    );
    Ok(out)
}

/// The rasterization slides' depth-buffer loop on a scene: each triangle in turn drawn by
/// `backend` through the shared stage (`if f.z < depthBuffer[f.xy]: draw
/// f, depthBuffer[f.xy] = f.z`), and the depth buffer after each, as the
/// slides' matrix: one row of the trace per row of pixels.
pub fn trace_depth_buffer(
    scene: &Scene2D,
    backend: &dyn TriangleRasterizer,
    rule: FillRule,
) -> Result<Trace> {
    let mut target = RenderTarget::new(scene.width, scene.height)?;
    let matrices = scene.triangles.len() as u64 + 1;
    check_trace_length(
        matrices * u64::from(scene.width) * u64::from(scene.height),
        "depth-buffer cells",
    )?;
    let depth = DepthState {
        test: DepthTest::Less,
        write: true,
    };
    let mut out = Trace::saying(format!(
        "depth buffer, {} x {}, initialised with 1.0; each fragment f is kept if f.z < depthBuffer[f.xy]",
        scene.width, scene.height
    ));
    print_matrix(&mut out, &target.depth, scene.width);
    for (i, (triangle, vertices)) in scene.triangles.iter().zip(&scene.vertices).enumerate() {
        let one = Scene2D {
            triangles: vec![*triangle],
            vertices: vec![*vertices],
            ..scene.clone()
        };
        let before = target.depth.clone();
        let work = one.draw(backend, rule, depth, &Flat, &mut target);
        let kept = before
            .iter()
            .zip(&target.depth)
            .filter(|(b, a)| a != b)
            .count();
        let z: Vec<String> = vertices.iter().map(|v| format!("{}", v.depth)).collect();
        out.rows.push(TraceRow::note(String::new()));
        out.rows.push(TraceRow::note(format!(
            "triangle {} (z = {}): {} fragments, {kept} kept (nearer than the buffer), {} hidden",
            i + 1,
            z.join(", "),
            work.fragments,
            work.fragments - kept as u64
        )));
        print_matrix(&mut out, &target.depth, scene.width);
    }
    Ok(out)
}

/// The depth buffer as the slides' matrix, a row of the trace per row of
/// pixels.
fn print_matrix(out: &mut Trace, depth: &[f32], width: u32) {
    for (y, row) in depth.chunks(width as usize).enumerate() {
        let cells: Vec<String> = row.iter().map(|z| format!("{z:.1}")).collect();
        out.rows
            .push(TraceRow::new(cells).about(0, y as i64, i64::from(width) - 1, y as i64));
    }
}

/// The triangle snapped and set up under `rule`, or, when it has zero
/// area once snapped, `None` after writing "the snapped triangle has zero
/// area: {nothing}" to the trace.
/// Why a sample with edge values `e` is inside triangle `t` or not: the
/// edge that rejects it, or the edge whose tie it sits on.
pub(crate) fn verdict(t: &TriangleSetup, e: [i64; 3]) -> String {
    match t.rejecting_edge(e) {
        Some(k) if e[k] < 0 => format!("outside: E{k} < 0"),
        Some(k) => format!(
            "outside: on E{k}, a {} edge that does not own its ties",
            t.edges[k].kind()
        ),
        None => match (0..3).find(|&k| e[k] == 0) {
            Some(k) => format!(
                "inside: on E{k}, a {} edge that owns its ties",
                t.edges[k].kind()
            ),
            None => "inside".to_string(),
        },
    }
}

pub(crate) fn snapped_or_say(
    vertices: [(f64, f64); 3],
    rule: FillRule,
    out: &mut Trace,
    nothing: &str,
) -> Result<Option<TriangleSetup>> {
    let [a, b, c] = vertices.map(|(x, y)| FixedPoint::snap_f64(x, y));
    let t = TriangleSetup::new(0, [a?, b?, c?], rule);
    if t.is_none() {
        out.header
            .push(format!("the snapped triangle has zero area: {nothing}"));
    }
    Ok(t)
}

/// Xiaolin Wu's anti-aliased line: each column's two pixels around the
/// ideal line, with their weights `1 - frac(y)` and `frac(y)`.
fn wu(ends: &LineEnds) -> Trace {
    use crate::raster::line::{wu::Wu, LineOptions, LineSetup};
    let frame = OctantFrame::new(ends.from, ends.to);
    let line = LineSetup {
        id: 0,
        from: ends.from,
        to: ends.to,
    };
    let mut out = Trace::saying(format!(
        "wu (anti-aliased) {}; {}",
        ends.describe(),
        frame_note(&frame)
    ));
    out.columns = vec![
        Column::right("pixel", 12, 0),
        Column::right("weight", 8, 2),
        Column::right("pixel", 12, 2),
        Column::right("weight", 8, 2),
    ];
    let pixels = Wu::pixels(&line, &LineOptions::DEFAULT);
    // Pixels come in columns of one or two (a weight of 0 is not drawn);
    // a column's pixels share the major coordinate.
    let major = |p: (i64, i64)| if frame.swap { p.1 } else { p.0 };
    let mut i = 0;
    while i < pixels.len() {
        let (p, w) = pixels[i];
        let pair = pixels.get(i + 1).filter(|q| major(q.0) == major(p));
        match pair {
            Some(&(q, v)) => {
                out.rows.push(
                    TraceRow::at_pixel(
                        vec![
                            format!("{},{}", p.0, p.1),
                            format!("{w:.4}"),
                            format!("{},{}", q.0, q.1),
                            format!("{v:.4}"),
                        ],
                        p.0,
                        p.1,
                    )
                    .about(q.0, q.1, q.0, q.1),
                );
                i += 2;
            }
            None => {
                out.rows.push(TraceRow::at_pixel(
                    vec![format!("{},{}", p.0, p.1), format!("{w:.4}")],
                    p.0,
                    p.1,
                ));
                i += 1;
            }
        }
    }
    out.footer.push(
        "at each column the ideal line passes between two pixel centres; the nearer one gets more: 1 - frac(y) and frac(y)".to_string(),
    );
    out
}

/// The diamond-exit rule, recorded from the back-end's walk
/// ([`Diamond::walk`](crate::raster::line::diamond::Diamond::walk)): for each column (row, for steep lines) in the order
/// of travel, the three candidate pixels around the line, and whether the
/// segment leaves each pixel's diamond (then the pixel is drawn).
fn diamond(ends: &LineEnds) -> Result<Trace> {
    use crate::raster::line::{diamond::Diamond, LineSetup};
    let (a, b) = (ends.from, ends.to);
    let (dx, dy) = (b.x.raw() - a.x.raw(), b.y.raw() - a.y.raw());
    let x_major = dx.abs() >= dy.abs();
    let mut out = Trace::saying(format!(
        "diamond exit rule {}; {}-major: a pixel is drawn when the segment leaves its diamond |x - cx| + |y - cy| < 1/2 (the end point's diamond is not)",
        ends.describe(),
        if x_major { "x" } else { "y" }
    ));
    // The walk visits at most the major extent's columns and two more on
    // each side, three candidates each.
    let columns = dx.abs().max(dy.abs()) / SUBPIXEL_SCALE + 5;
    check_trace_length(3 * columns as u64, "candidate lines")?;
    out.columns = vec![Column::right("pixel", 12, 0), Column::left("verdict", 0, 2)];
    let line = LineSetup {
        id: 0,
        from: a,
        to: b,
    };
    let drawn = Diamond::walk(&line, |px, py, exits| {
        let verdict = if exits {
            "exits its diamond: drawn"
        } else {
            "does not exit its diamond"
        };
        out.rows.push(TraceRow::at_pixel(
            vec![format!("{px},{py}"), verdict.to_string()],
            px,
            py,
        ));
    })
    .len();
    out.footer.push(format!("{drawn} pixels drawn"));
    Ok(out)
}

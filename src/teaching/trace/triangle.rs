//! The triangle traces: the recording of a back-end's real walk on one
//! triangle, told in the form its walk is taught in. Every pixel tested
//! with its three edge values, barycentrics and verdict (the bounding
//! box, the naive loop, a walk of its own); each row's sample line,
//! active edges' crossings and span (scanline); the edge values stepped
//! from the box's first sample (incremental); each block's class from
//! its corners (tiled). Also why a sample is inside or not (which edge
//! rejects it, which tie rule decides), which the sample traces share.

use super::{check_trace_length, AREA_UNIT};
use crate::error::Result;
use crate::raster::edge::{FillRule, PixelRect, TriangleSetup};
use crate::raster::fixed::{FixedPoint, HALF_PIXEL, SUBPIXEL_SCALE};
use crate::raster::fragment::FragmentList;
use crate::raster::triangle::scanline::{row_range, sorted_by_y};
use crate::raster::triangle::tiled::BLOCK;
use crate::raster::triangle::{BlockClass, Bound, TriangleRasterizer, TriangleWalk, WalkStep};
use crate::teaching::trace_table::{Column, Trace, TraceRow};

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

/// The triangle snapped and set up under `rule`, or, when it has zero
/// area once snapped, `None` after writing "the snapped triangle has zero
/// area: {nothing}" to the trace.
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

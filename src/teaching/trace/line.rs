//! The line traces, one per way a line back-end chooses its pixels: the
//! midpoint (Bresenham) loop with its decision variable, direct
//! evaluation and the DDA with each column's exact `y` and the row it
//! rounds to, Wu's two weighted pixels a column, and the diamond-exit
//! rule's candidate pixels; each walked in the first octant and mapped
//! back, as the line-drawing slides walk it. Endpoints are [`LineEnds`]:
//! pixel indices or screen coordinates, snapped.

use super::{check_trace_length, AREA_UNIT};
use crate::error::{Error, Result};
use crate::raster::fixed::{FixedPoint, SUBPIXEL_SCALE};
use crate::raster::line::bresenham::Bresenham;
use crate::raster::line::dda::Dda;
use crate::raster::line::direct::Direct;
use crate::raster::line::{LineRasterizer, LineWalk, OctantFrame};
use crate::teaching::trace_table::{Column, Trace, TraceRow};

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
    pub(super) fn describe(&self) -> String {
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

/// The names of the walking frame's column and row: `x` and `y` in the
/// first octant, where the frame is the screen; `u` and `v` elsewhere, so
/// that they are not read as screen coordinates (the pixel column gives
/// those).
pub(super) fn frame_axes(frame: &OctantFrame) -> (&'static str, &'static str) {
    if frame.swap || frame.flip_major || frame.flip_minor {
        ("u", "v")
    } else {
        ("x", "y")
    }
}

pub(super) fn frame_note(frame: &OctantFrame) -> String {
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
            "walked in the first octant ({}) as u along the major axis and v along the minor one, pixels mapped back",
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
    let (u, v) = frame_axes(&frame);
    out.columns = vec![
        Column::right(u, 4, 0),
        Column::right(v, 6, 1),
        Column::right("pixel", 6, 1),
        Column::right("d", 12, 1),
        Column::left("choice", 0, 2),
    ];
    let (step_up, keep) = (
        format!("d < 0: the line passes on the midpoint's {v} + 1 side, {v} = {v} + 1"),
        format!("d >= 0: the line meets the midpoint or passes on its {v} side, keep {v}"),
    );
    for step in Bresenham::steps(&frame) {
        let (px, py) = frame.to_screen(step.i, step.k);
        let d = step.d as f64 / AREA_UNIT;
        let choice = if step.step_up { &step_up } else { &keep };
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
    out.footer.push(format!(
        "d = f({u} + 1, {v} + 1/2) with f({u}, {v}) = ({v}0 - {v}1) {u} + ({u}1 - {u}0) {v} + {u}0 {v}1 - {u}1 {v}0, in the walking frame, in px² (the back-end keeps it as a whole number of 1/65536 px²)"
    ));
    out
}

/// The step-by-step trace of a line back-end on one segment: the trace of
/// the way it [chooses](crate::raster::descriptor::Descriptor::walk) its
/// pixels, each row with the pixels it is about.
pub fn trace_line(backend: &dyn LineRasterizer, ends: &LineEnds) -> Result<Trace> {
    match backend.descriptor().walk {
        LineWalk::DirectEvaluation | LineWalk::Incremental => column_trace(backend, ends),
        LineWalk::Midpoint => Ok(bresenham(ends)),
        LineWalk::AntiAliased => Ok(wu(ends)),
        LineWalk::DiamondExit => diamond(ends, false),
        LineWalk::DiamondExitNudged => diamond(ends, true),
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
    let (u, v) = frame_axes(&frame);
    out.columns = vec![
        Column::right(u, 4, 0),
        Column::right(&format!("exact {v}"), 10, 1),
        Column::right(v, 6, 1),
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
/// segment leaves each pixel's diamond (then the pixel is drawn). With
/// `nudged`, the ties are settled as Scotty3D settles them
/// ([`DiamondNudged::walk`](crate::raster::line::diamond_nudged::DiamondNudged::walk)).
fn diamond(ends: &LineEnds, nudged: bool) -> Result<Trace> {
    use crate::raster::line::{diamond::Diamond, diamond_nudged::DiamondNudged, LineSetup};
    let (a, b) = (ends.from, ends.to);
    let (dx, dy) = (b.x.raw() - a.x.raw(), b.y.raw() - a.y.raw());
    let x_major = dx.abs() >= dy.abs();
    let mut out = Trace::saying(format!(
        "diamond exit rule {}; {}-major: a pixel is drawn when the segment leaves its diamond |x - cx| + |y - cy| < 1/2 (the end point's diamond is not)",
        ends.describe(),
        if x_major { "x" } else { "y" }
    ));
    if nudged {
        out.header.push(
            "ties settled as Scotty3D does: both ends moved by (e, e^2) with y up, that is (e, -e^2) on this y-down grid, for the smallest e > 0".to_string(),
        );
    }
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
    let observe = |px, py, exits| {
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
    };
    let drawn = if nudged {
        DiamondNudged::walk(&line, observe)
    } else {
        Diamond::walk(&line, observe)
    }
    .len();
    out.footer.push(format!("{drawn} pixels drawn"));
    Ok(out)
}

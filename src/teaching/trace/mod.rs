//! Step-by-step traces of one algorithm on one small input, in the
//! course's terms, as data ([`Trace`](crate::teaching::Trace): header
//! lines, a table whose rows carry the pixels they are about, totals) and
//! as the plain-text tables `rasterlab explain` prints. The triangle
//! traces are recordings of the back-ends' real walks.
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
//! * [`trace_polygon`] on `edge-table`: the edge table, each edge in the
//!   bucket of its first row, then each row's edges moved into the active
//!   edge table, those removed, the table sorted by x with each crossing's
//!   winding, and the spans filled (Foley and van Dam's §3.6);
//! * [`trace_clip`]: a line clipped to the viewport by Cohen-Sutherland
//!   (each pass's outcodes `TBRL`, the edge chosen, the new point) or
//!   Liang-Barsky (each boundary's `p_k`, `q_k` and the interval `[t0,
//!   t1]` after it), then the entry and exit columns of the walk, the row
//!   and decision variable it restarts with, and the pixels the naive
//!   walk of the rounded clipped segment moves;
//! * [`trace_triangle_clip`]: a triangle clipped in homogeneous clip
//!   space as the 3D pipeline clips it, plane by plane (Sutherland and
//!   Hodgman), then re-triangulated as a fan and mapped to the viewport;
//! * [`trace_depth_buffer`]: the rasterization slides' depth buffer, printed as the
//!   slides' matrix after each triangle;
//! * [`trace_blend`]: one pixel's fragments in order, each one's depth
//!   test and the pixel's colour after each blend.
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

mod blend;
mod clip;
mod clip_triangle;
mod depth_buffer;
mod line;
mod polygon;
mod triangle;

pub use blend::trace_blend;
pub use clip::trace_clip;
pub use clip_triangle::{trace_triangle_clip, BEHIND_THE_CAMERA};
pub use depth_buffer::trace_depth_buffer;
pub use line::{trace_line, LineEnds};
pub use polygon::{trace_polygon, trace_polygon_rings};
pub use triangle::trace_triangle;
pub(crate) use triangle::{snapped_or_say, verdict};

use crate::error::{Error, Result};
use crate::raster::fixed::SUBPIXEL_SCALE;

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

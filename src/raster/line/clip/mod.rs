//! Line clipping before the walk: Cohen-Sutherland and Liang-Barsky, and
//! two ways of walking what they keep.
//!
//! A clipper computes the part of a segment inside a rectangle, the
//! **clip window**, before a line back-end walks it, so that no column
//! off the screen is walked. Two classic algorithms do it, as Foley, van
//! Dam, Feiner and Hughes teach them (*Computer Graphics: Principles and
//! Practice*, 2nd ed., section 3.12):
//!
//! * [`cohen_sutherland`] (Sproull and Sutherland, 1968; Newman and
//!   Sproull, *Principles of Interactive Computer Graphics*, 1973): a
//!   4-bit **outcode** per endpoint says which sides of the window it
//!   lies beyond; a segment whose codes are both zero is trivially
//!   accepted, one whose codes share a bit trivially rejected, and any
//!   other has an outside endpoint moved to the edge its code names, then
//!   is tested again;
//! * [`liang_barsky`] (Liang and Barsky, "A new concept and method for
//!   line clipping", ACM TOG 3(1), 1984): the segment is `P(t) = P0 + t
//!   (P1 - P0)`, and each of the four edges is an inequality `p_k t <=
//!   q_k`; the visible part is the interval `[t0, t1]` that the four
//!   leave of `[0, 1]`, empty when `t0 > t1`.
//!
//! Both are exact here: the endpoints lie on the 1/256 px grid, so each
//! parameter where the segment meets an edge is a fraction `q / p` of two
//! integers ([`Param`]) and each point computed a point with rational
//! coordinates. The two clippers give the same interval on every segment
//! (a property of the `line_clipping` suite); they differ in the work they
//! do ([`ClipWork`]).
//!
//! **Clip, then walk.** A clipped segment is still drawn by a line
//! back-end, and the classic pitfall is in how ([`ClipRestart`]):
//!
//! * [`ClipRestart::KeepDecision`] keeps the **original** segment: its
//!   frame, its slope and its decision variable. Only the columns between
//!   the entry and the exit are walked, and the walk starts at the entry
//!   column with the row and decision variable the whole walk would have
//!   had there ([`AliasedLine::walk_columns`](super::AliasedLine::walk_columns)).
//!   The pixels drawn are exactly the whole segment's pixels on the
//!   screen. The 8-connected aliased walks visit only those columns;
//!   4-connected walks, `wu` and the diamond-exit rules compute the
//!   segment's pixels and keep those of the rectangle ([`walk_rect`])
//!   around the part kept;
//! * [`ClipRestart::RoundEndpoints`] is the naive way: the clipped
//!   endpoints are rounded to the 1/256 px grid and the new, shorter
//!   segment is walked from scratch. Its slope is not the original's, its
//!   first pixel is the one containing the rounded entry point, and its
//!   decision variable starts afresh there: some pixels move by a row.
//!   [`ClipRestart::RoundToPixelCentres`], the textbook's integer
//!   endpoints, moves more. The `line_clipping` suite counts both on a
//!   fixed set of segments.
//!
//! The window [`ClipWindow::around`] a viewport keeps a margin of one
//! pixel beyond the viewport's edges: a pixel on the screen's edge can be
//! chosen by a line passing just outside it (the nearest row to a line
//! half a pixel above the screen is the screen's top row; Wu's second
//! pixel is a row further), and the margin keeps that part of the line.
//! The naive way clips at the viewport's own edges, as the textbooks do.

pub mod cohen_sutherland;
pub mod liang_barsky;

use super::{LineOptions, LineRasterizer, LineSetup, OctantFrame};
use crate::raster::edge::PixelRect;
use crate::raster::fixed::{FixedPoint, SUBPIXEL_SCALE};
use crate::raster::fragment::{FragmentSink, WorkCounters};
use std::cmp::Ordering;

/// A parameter `t = num / den` along a segment, `den > 0`: exact, as the
/// segment meets an edge of the window at the ratio of two integers.
#[derive(Copy, Clone, Debug, Eq)]
pub struct Param {
    /// Numerator.
    pub num: i64,
    /// Denominator, positive.
    pub den: i64,
}

impl Param {
    /// `t = 0`, the start.
    pub const ZERO: Param = Param { num: 0, den: 1 };
    /// `t = 1`, the end.
    pub const ONE: Param = Param { num: 1, den: 1 };

    /// `q / p`, for `p != 0`, with the sign moved to the numerator.
    pub fn ratio(q: i64, p: i64) -> Param {
        debug_assert!(p != 0, "a parameter of a zero denominator");
        if p < 0 {
            Param { num: -q, den: -p }
        } else {
            Param { num: q, den: p }
        }
    }

    /// The parameter as a float, for printing.
    pub fn to_f64(self) -> f64 {
        self.num as f64 / self.den as f64
    }

    /// The point `from + t (to - from)`, exactly, in fixed-point units.
    pub fn point(self, from: FixedPoint, to: FixedPoint) -> ExactPoint {
        let along = |a: i64, b: i64| {
            i128::from(a) * i128::from(self.den) + i128::from(b - a) * i128::from(self.num)
        };
        ExactPoint {
            x: along(from.x.raw(), to.x.raw()),
            y: along(from.y.raw(), to.y.raw()),
            den: i128::from(self.den),
        }
    }
}

impl PartialEq for Param {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Ord for Param {
    fn cmp(&self, other: &Self) -> Ordering {
        // Both denominators are positive: compare cross products, exact in
        // i128 (each factor is below 2^32).
        (i128::from(self.num) * i128::from(other.den))
            .cmp(&(i128::from(other.num) * i128::from(self.den)))
    }
}

impl PartialOrd for Param {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// A point with rational coordinates `(x / den, y / den)` in fixed-point
/// units (1/256 px), `den > 0`: where a segment meets a window's edge.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct ExactPoint {
    /// `x` times `den`.
    pub x: i128,
    /// `y` times `den`.
    pub y: i128,
    /// The common denominator, positive.
    pub den: i128,
}

impl ExactPoint {
    /// The point in pixels, for printing.
    pub fn to_pixels(self) -> (f64, f64) {
        let scale = self.den as f64 * SUBPIXEL_SCALE as f64;
        (self.x as f64 / scale, self.y as f64 / scale)
    }

    /// The pixel containing the point (a point on a pixel boundary
    /// belongs to the pixel after it, as for snapped points).
    pub fn pixel(self) -> (i64, i64) {
        let unit = self.den * i128::from(SUBPIXEL_SCALE);
        (
            self.x.div_euclid(unit) as i64,
            self.y.div_euclid(unit) as i64,
        )
    }

    /// The centre of [the pixel containing](Self::pixel) the point: the
    /// naive clipped endpoint of integer arithmetic.
    pub fn pixel_centre(self) -> FixedPoint {
        let (x, y) = self.pixel();
        let centre = |p: i64| p * SUBPIXEL_SCALE + SUBPIXEL_SCALE / 2;
        FixedPoint::from_raw(centre(x), centre(y))
            .expect("a pixel between two snapped points is within the guard band")
    }

    /// The nearest point of the 1/256 px grid, ties rounded up: the naive
    /// clipped endpoint. It lies between the segment's ends, so within
    /// the guard band.
    pub fn rounded(self) -> FixedPoint {
        let round = |v: i128| (2 * v + self.den).div_euclid(2 * self.den) as i64;
        FixedPoint::from_raw(round(self.x), round(self.y))
            .expect("a point between two snapped points is within the guard band")
    }
}

/// The rectangle a segment is clipped to, closed, in fixed-point units:
/// `x0 <= x <= x1`, `y0 <= y <= y1` (y grows down: `y0` is the top).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct ClipWindow {
    /// Left edge.
    pub x0: i64,
    /// Top edge.
    pub y0: i64,
    /// Right edge.
    pub x1: i64,
    /// Bottom edge.
    pub y1: i64,
}

impl ClipWindow {
    /// The margin, in pixels, [`around`](Self::around) keeps beyond a
    /// viewport's edges.
    pub const MARGIN: i64 = 1;

    /// The viewport's own edges: the outer sides of its border pixels.
    pub fn of_viewport(viewport: PixelRect) -> ClipWindow {
        ClipWindow::grown(viewport, 0)
    }

    /// The viewport's edges moved out by [`MARGIN`](Self::MARGIN) pixels:
    /// every part of a segment that can choose an on-screen pixel lies
    /// inside.
    pub fn around(viewport: PixelRect) -> ClipWindow {
        ClipWindow::grown(viewport, Self::MARGIN)
    }

    fn grown(viewport: PixelRect, margin: i64) -> ClipWindow {
        ClipWindow {
            x0: (viewport.x0 - margin) * SUBPIXEL_SCALE,
            y0: (viewport.y0 - margin) * SUBPIXEL_SCALE,
            x1: (viewport.x1 + 1 + margin) * SUBPIXEL_SCALE,
            y1: (viewport.y1 + 1 + margin) * SUBPIXEL_SCALE,
        }
    }
}

/// The visible part of a segment: `P(t)` for `t0 <= t <= t1`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Clipped {
    /// Where the segment enters the window (0: it starts inside).
    pub t0: Param,
    /// Where it leaves (1: it ends inside).
    pub t1: Param,
}

impl Clipped {
    /// The entry and exit points, exactly.
    pub fn points(&self, line: &LineSetup) -> [ExactPoint; 2] {
        [
            self.t0.point(line.from, line.to),
            self.t1.point(line.from, line.to),
        ]
    }
}

/// The work a clipper did, for comparing the two.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct ClipWork {
    /// Segments clipped.
    pub segments: u64,
    /// Outcodes computed (Cohen-Sutherland: one per endpoint, then one
    /// per point moved to an edge).
    pub outcodes: u64,
    /// Boundary tests `p_k t <= q_k` (Liang-Barsky: up to four a segment).
    pub boundary_tests: u64,
    /// Intersections computed: a point moved to an edge (Cohen-Sutherland)
    /// or a ratio `q_k / p_k` (Liang-Barsky).
    pub intersections: u64,
    /// Segments accepted by the first test, with nothing computed
    /// (Cohen-Sutherland: both outcodes zero).
    pub trivially_accepted: u64,
    /// Segments rejected by the first test (Cohen-Sutherland: the two
    /// outcodes share a bit).
    pub trivially_rejected: u64,
    /// Segments found wholly outside, trivially or not.
    pub rejected: u64,
}

impl std::ops::AddAssign for ClipWork {
    fn add_assign(&mut self, other: ClipWork) {
        self.segments += other.segments;
        self.outcodes += other.outcodes;
        self.boundary_tests += other.boundary_tests;
        self.intersections += other.intersections;
        self.trivially_accepted += other.trivially_accepted;
        self.trivially_rejected += other.trivially_rejected;
        self.rejected += other.rejected;
    }
}

/// A line clipping algorithm.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Clipper {
    /// Outcodes and trivial tests, an endpoint moved to an edge at a time.
    CohenSutherland,
    /// The parameter interval cut by four inequalities.
    LiangBarsky,
}

crate::names::named_enum!(
    Clipper,
    "line clipper",
    CohenSutherland = "cohen-sutherland",
    LiangBarsky = "liang-barsky"
);

impl Clipper {
    /// Both clippers.
    pub const ALL: [Clipper; 2] = [Clipper::CohenSutherland, Clipper::LiangBarsky];

    /// The part of `line` inside `window`, `None` when none is, adding the
    /// work done to `work`.
    pub fn clip(
        self,
        line: &LineSetup,
        window: ClipWindow,
        work: &mut ClipWork,
    ) -> Option<Clipped> {
        match self {
            Clipper::CohenSutherland => {
                cohen_sutherland::clip(line.from, line.to, window, work, |_| {})
            }
            Clipper::LiangBarsky => liang_barsky::clip(line.from, line.to, window, work, |_| {}),
        }
    }
}

/// How a clipped segment is walked.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum ClipRestart {
    /// Walk the original segment's frame from the entry column to the
    /// exit column, the decision variable restarted at the entry column
    /// as the whole walk would have it: the whole segment's on-screen
    /// pixels, exactly.
    KeepDecision,
    /// Round the clipped endpoints to the 1/256 px grid and walk the new
    /// segment from scratch: the naive way, which moves pixels.
    RoundEndpoints,
    /// Move the clipped endpoints (those the clipper moved) to the
    /// centres of the pixels containing them and walk the new segment from scratch: the naive way with the
    /// textbook's integer endpoints, which moves more.
    RoundToPixelCentres,
}

crate::names::named_enum!(
    ClipRestart,
    "clip restart",
    KeepDecision = "keep-decision",
    RoundEndpoints = "round-endpoints",
    RoundToPixelCentres = "round-to-pixel-centres"
);

impl ClipRestart {
    /// Every way.
    pub const ALL: [ClipRestart; 3] = [
        ClipRestart::KeepDecision,
        ClipRestart::RoundEndpoints,
        ClipRestart::RoundToPixelCentres,
    ];
}

/// What a clipped draw did: the clipper's work, and the back-end's.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct ClippedDraw {
    /// The clipper's work.
    pub clip: ClipWork,
    /// The back-end's work on the segments the clipper kept.
    pub walk: WorkCounters,
    /// Columns of the kept segments' frames inside the rectangles they
    /// are drawn in: the columns an 8-connected aliased walk visits.
    pub columns: u64,
}

/// The columns of `line`'s frame whose pixels can lie in `rect`.
pub fn columns_within(line: &LineSetup, rect: PixelRect) -> u64 {
    let frame = OctantFrame::new(line.from, line.to);
    let ((lo, hi), _) = frame.ranges_within(rect);
    (frame.i1.min(hi) - frame.i0.max(lo) + 1).max(0) as u64
}

/// The pixels a [`ClipRestart::KeepDecision`] walk of `line`, clipped to
/// `clipped` inside [`ClipWindow::around`] `viewport`, may draw: the
/// pixels of the entry and exit points and those between, one more on
/// every side, within the viewport. The walk covers the columns of this
/// rectangle only.
pub fn walk_rect(line: &LineSetup, clipped: &Clipped, viewport: PixelRect) -> PixelRect {
    let [(ax, ay), (bx, by)] = clipped.points(line).map(ExactPoint::pixel);
    PixelRect {
        x0: ax.min(bx) - 1,
        y0: ay.min(by) - 1,
        x1: ax.max(bx) + 1,
        y1: ay.max(by) + 1,
    }
    .intersect(viewport)
}

/// Draws `lines` clipped by `clipper` to `viewport`, each kept part walked
/// by `backend` as `restart` says. With [`ClipRestart::KeepDecision`] the
/// fragments are those of `backend.rasterize` on the whole segments, in
/// the same order.
pub fn draw_clipped(
    backend: &dyn LineRasterizer,
    clipper: Clipper,
    restart: ClipRestart,
    lines: &[LineSetup],
    options: &LineOptions,
    viewport: PixelRect,
    sink: &mut dyn FragmentSink,
) -> ClippedDraw {
    let mut draw = ClippedDraw::default();
    if viewport.is_empty() {
        return draw;
    }
    let window = match restart {
        ClipRestart::KeepDecision => ClipWindow::around(viewport),
        ClipRestart::RoundEndpoints | ClipRestart::RoundToPixelCentres => {
            ClipWindow::of_viewport(viewport)
        }
    };
    for line in lines {
        let Some(clipped) = clipper.clip(line, window, &mut draw.clip) else {
            continue;
        };
        let work = match restart {
            ClipRestart::KeepDecision => {
                let rect = walk_rect(line, &clipped, viewport);
                if rect.is_empty() {
                    continue;
                }
                draw.columns += columns_within(line, rect);
                backend.rasterize(std::slice::from_ref(line), options, rect, sink)
            }
            ClipRestart::RoundEndpoints | ClipRestart::RoundToPixelCentres => {
                let round = if restart == ClipRestart::RoundEndpoints {
                    ExactPoint::rounded
                } else {
                    ExactPoint::pixel_centre
                };
                // Only the ends the clipper moved are rounded.
                let [entry, exit] = clipped.points(line);
                let from = if clipped.t0 == Param::ZERO {
                    line.from
                } else {
                    round(entry)
                };
                let to = if clipped.t1 == Param::ONE {
                    line.to
                } else {
                    round(exit)
                };
                let short = LineSetup {
                    id: line.id,
                    from,
                    to,
                };
                draw.columns += columns_within(&short, viewport);
                backend.rasterize(&[short], options, viewport, sink)
            }
        };
        draw.walk.add(&work);
    }
    draw
}

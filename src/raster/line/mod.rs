//! Line rasterizer back-ends.
//!
//! The line-drawing slides' algorithms assume a line with more run than rise, drawn left
//! to right (the first octant, slope in `[0, 1]`); every other direction is
//! handled **by symmetry**: [`OctantFrame`] mirrors and swaps the axes so
//! the segment runs along `+u` with `0 <= dv <= du`, the algorithm picks one
//! pixel per column `u`, and the frame maps each pixel back.
//!
//! In the frame, pixel centres sit on integer multiples of 256 (fixed-point
//! units, like the snapped coordinates), and endpoints are snapped
//! coordinates, not necessarily on a pixel centre. The endpoint pixels are
//! the pixels containing the endpoints, and each column's row is the
//! nearest pixel centre to the ideal line, **ties going to the row nearer
//! the start** (the line-drawing slides' midpoint test: only `d < 0` steps up).
//!
//! Options ([`LineOptions`]): 8- or 4-connected runs, both endpoints drawn
//! or half-open (the end pixel left out, so a polyline's shared vertices
//! are drawn once), and a **symmetric** variant. The plain algorithms walk
//! from the start, so ties (and hence pixels) depend on the direction of
//! travel; the symmetric variant always walks from the endpoint with the
//! smaller major coordinate, so `a -> b` and `b -> a` give the same pixels.
//!
//! `diamond` (the Direct3D / Vulkan diamond-exit rule) is the reference for
//! aliased lines and follows its own rule; `diamond-nudged` is the same
//! rule with Scotty3D's tie-break; `wu` is anti-aliased.

pub mod bresenham;
pub mod clip;
pub mod dda;
pub mod diamond;
pub mod diamond_nudged;
pub mod direct;
pub mod wu;

use crate::error::Result;
use crate::raster::descriptor::Descriptor;
use crate::raster::edge::PixelRect;
use crate::raster::fixed::{FixedPoint, HALF_PIXEL, SUBPIXEL_SCALE};
use crate::raster::fragment::{FragmentSink, LineFragment, WorkCounters};

/// A line segment ready for rasterization: its id and snapped endpoints.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct LineSetup {
    /// The segment's index in the draw (printed as `i` by `rasterlab fragments`).
    pub id: u32,
    /// Start point.
    pub from: FixedPoint,
    /// End point.
    pub to: FixedPoint,
}

impl LineSetup {
    /// Segments numbered in order, as read from a line set file.
    pub fn numbered(segments: &[[FixedPoint; 2]]) -> Vec<LineSetup> {
        segments
            .iter()
            .enumerate()
            .map(|(i, s)| LineSetup {
                id: i as u32,
                from: s[0],
                to: s[1],
            })
            .collect()
    }
}

/// Which neighbours count as connected.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum Connectivity {
    /// Diagonal neighbours count: one pixel per major-axis step.
    #[default]
    Eight,
    /// Only left, right, up and down: a corner pixel is added at every
    /// diagonal step.
    Four,
}

/// Whether the end pixel is drawn.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum Endpoints {
    /// Both endpoint pixels are drawn.
    #[default]
    Inclusive,
    /// The end pixel is left out.
    HalfOpen,
}

/// Options of the line algorithms of the line-drawing slides.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct LineOptions {
    /// 8- or 4-connected.
    pub connectivity: Connectivity,
    /// Inclusive or half-open.
    pub endpoints: Endpoints,
    /// Walk from the endpoint with the smaller major coordinate, so the
    /// pixels do not depend on the direction of travel.
    pub symmetric: bool,
}

impl LineOptions {
    /// 8-connected, both endpoints, direction-dependent: the textbook default.
    pub const DEFAULT: LineOptions = LineOptions {
        connectivity: Connectivity::Eight,
        endpoints: Endpoints::Inclusive,
        symmetric: false,
    };
}

crate::names::named_enum!(Connectivity, "connectivity", Eight = "8", Four = "4");
crate::names::named_enum!(
    Endpoints,
    "endpoint convention",
    Inclusive = "inclusive",
    HalfOpen = "half-open"
);

/// How a line back-end chooses its pixels: what its step-by-step trace
/// ([`crate::teaching::trace_line`]) shows.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum LineWalk {
    /// `y = m x + b` evaluated per column, then rounded.
    DirectEvaluation,
    /// `y` grown by `m` per column (the DDA), then rounded.
    Incremental,
    /// The midpoint decision variable, in integers (Bresenham).
    Midpoint,
    /// Two pixels per column, shaded by their distance to the line (Wu).
    AntiAliased,
    /// The pixels whose diamond the segment leaves (Direct3D, Vulkan).
    DiamondExit,
    /// The diamond-exit rule with both ends moved by an infinitesimal
    /// `(e, e^2)`, y up (Scotty3D).
    DiamondExitNudged,
}

/// A line back-end's facts ([`Descriptor`] of a [`LineWalk`]).
pub type LineDescriptor = Descriptor<LineWalk>;

/// A line rasterization algorithm.
pub trait LineRasterizer: Send + Sync {
    /// The back-end's facts.
    fn descriptor(&self) -> LineDescriptor;
    /// Short name used on the command line (the descriptor's).
    fn name(&self) -> &'static str {
        self.descriptor().name
    }
    /// One-line description (the descriptor's).
    fn description(&self) -> &'static str {
        self.descriptor().description
    }
    /// True for an anti-aliased back-end, whose fragments carry a coverage
    /// weight below 1 (`rasterlab fragments` prints it as a fourth column).
    fn anti_aliased(&self) -> bool {
        self.descriptor().walk == LineWalk::AntiAliased
    }
    /// Errors when the back-end cannot honour `options`.
    fn check_options(&self, options: &LineOptions) -> Result<()> {
        let _ = options;
        Ok(())
    }
    /// Emits the fragments of every segment that lie in `viewport`, in the
    /// order of travel, and returns the work done.
    fn rasterize(
        &self,
        lines: &[LineSetup],
        options: &LineOptions,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> WorkCounters;
}

/// An aliased line algorithm, as its file writes it: its facts and its
/// walk, the row it picks in each column of a segment's
/// [`OctantFrame`]. Turning the rows into pixels (connectivity, symmetry,
/// end points) and drawing them (each segment's pixels clipped to the
/// viewport, coverage 1, counted) is provided once, by the
/// [`LineRasterizer`] every such algorithm is.
pub trait AliasedLine: Send + Sync {
    /// The back-end's name, description, walk, role and cost class.
    const DESCRIPTOR: LineDescriptor;

    /// The walk over columns `first..=last` (a range inside
    /// `frame.i0..=frame.i1`, the columns a draw can see): for each
    /// column `i`, the row `k` the algorithm picks, given to `visit` as
    /// `(i, k)`, the same row whatever the range: an algorithm that grows
    /// its state from the start column grows it over the columns before
    /// `first` too.
    fn walk_columns(frame: &OctantFrame, first: i64, last: i64, visit: impl FnMut(i64, i64));

    /// The whole walk, from `frame.i0` to `frame.i1`.
    #[inline]
    fn walk(frame: &OctantFrame, visit: impl FnMut(i64, i64)) {
        Self::walk_columns(frame, frame.i0, frame.i1, visit);
    }

    /// The pixels of one segment, in the order of travel.
    fn pixels(line: &LineSetup, options: &LineOptions) -> Vec<(i64, i64)> {
        let mut pixels = Vec::new();
        Self::pixels_into(line, options, &mut Vec::new(), &mut pixels);
        pixels
    }

    /// [`pixels`](Self::pixels) into `pixels`, with `rows` for the walk:
    /// both emptied first, so that a draw reuses their memory from one
    /// segment to the next.
    fn pixels_into(
        line: &LineSetup,
        options: &LineOptions,
        rows: &mut Vec<(i64, i64)>,
        pixels: &mut Vec<(i64, i64)>,
    ) {
        let (frame, reversed) = walk_frame(line, options);
        rows.clear();
        Self::walk(&frame, |i, k| rows.push((i, k)));
        finish_pixels(&frame, rows, reversed, options, pixels);
    }
}

impl<A: AliasedLine> LineRasterizer for A {
    fn descriptor(&self) -> LineDescriptor {
        A::DESCRIPTOR
    }

    fn rasterize(
        &self,
        lines: &[LineSetup],
        options: &LineOptions,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> WorkCounters {
        let mut work = WorkCounters::default();
        let mut emitter = PixelEmitter::default();
        let (mut rows, mut pixels) = (Vec::new(), Vec::new());
        for line in lines {
            work.primitives += 1;
            if options.connectivity == Connectivity::Eight {
                // One pixel per column: the walk's rows go to the sink
                // without a pixel list in between.
                emitter.emit_columns::<A>(line, options, viewport, sink, &mut work);
            } else {
                A::pixels_into(line, options, &mut rows, &mut pixels);
                work.samples_tested += pixels.len() as u64;
                emitter.emit(line, &pixels, viewport, sink, &mut work);
            }
        }
        work
    }
}

/// Back-ends are told apart by name (so settings holding one can be
/// compared and printed).
impl std::fmt::Debug for dyn LineRasterizer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl PartialEq for dyn LineRasterizer {
    fn eq(&self, other: &Self) -> bool {
        self.name() == other.name()
    }
}

/// The pixel index containing a snapped coordinate (a coordinate exactly on
/// a pixel boundary belongs to the pixel after it).
pub fn pixel_containing(raw: i64) -> i64 {
    raw.div_euclid(SUBPIXEL_SCALE)
}

/// A segment mirrored and swapped into the first octant.
///
/// Frame coordinates `(u, v)` are fixed-point units relative to pixel
/// centres (pixel `i`'s centre is at `256 i`), with the segment running from
/// `(u0, v0)` to `(u1, v1)`, `0 <= v1 - v0 <= u1 - u0`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct OctantFrame {
    /// Major axis is y (the segment is steep).
    pub swap: bool,
    /// The major axis runs towards negative screen coordinates.
    pub flip_major: bool,
    /// The minor axis runs towards negative screen coordinates.
    pub flip_minor: bool,
    /// Start, in frame units.
    pub u0: i64,
    /// Start, in frame units.
    pub v0: i64,
    /// End, in frame units.
    pub u1: i64,
    /// End, in frame units.
    pub v1: i64,
    /// First column (frame pixel index of the start's pixel).
    pub i0: i64,
    /// Last column (frame pixel index of the end's pixel).
    pub i1: i64,
}

impl OctantFrame {
    /// The frame of the segment `from -> to`, walked from `from`.
    ///
    /// A segment is x-major when `|dx| >= |dy|` (exactly 45 degrees counts
    /// as x-major).
    pub fn new(from: FixedPoint, to: FixedPoint) -> OctantFrame {
        let (dx, dy) = (to.x.raw() - from.x.raw(), to.y.raw() - from.y.raw());
        let swap = dy.abs() > dx.abs();
        let (a_major, a_minor) = major_minor(from, swap);
        let (b_major, b_minor) = major_minor(to, swap);
        let flip_major = b_major < a_major;
        let flip_minor = b_minor < a_minor;
        let to_frame = |c: i64, flip: bool| {
            if flip {
                -(c - HALF_PIXEL)
            } else {
                c - HALF_PIXEL
            }
        };
        let pixel = |c: i64, flip: bool| {
            let p = pixel_containing(c);
            if flip {
                -p
            } else {
                p
            }
        };
        OctantFrame {
            swap,
            flip_major,
            flip_minor,
            u0: to_frame(a_major, flip_major),
            v0: to_frame(a_minor, flip_minor),
            u1: to_frame(b_major, flip_major),
            v1: to_frame(b_minor, flip_minor),
            i0: pixel(a_major, flip_major),
            i1: pixel(b_major, flip_major),
        }
    }

    /// `du = u1 - u0 >= 0`.
    pub fn du(&self) -> i64 {
        self.u1 - self.u0
    }

    /// `dv = v1 - v0`, with `0 <= dv <= du`.
    pub fn dv(&self) -> i64 {
        self.v1 - self.v0
    }

    /// `du * v(i)`: the ideal line's minor coordinate at column `i`'s centre,
    /// times `du` so that it stays an exact integer (the line-drawing slides'
    /// `y = m (x - x0) + y0` with `m = dv / du`).
    ///
    /// Exact in `i64`: snapped coordinates lie within the guard band
    /// (`|raw| < 2^23`), so `|u|, |v|, du, dv < 2^25`, and for any column
    /// within `2^24` pixels of the origin (every column of a segment is
    /// within `2^15`) each product is below `2^58`.
    #[inline]
    pub fn scaled_v_at(&self, i: i64) -> i64 {
        debug_assert!(
            i.abs() < 1 << 24,
            "column {i} is far outside the guard band"
        );
        self.v0 * self.du() + self.dv() * (i * SUBPIXEL_SCALE - self.u0)
    }

    /// The row nearest the ideal line at column `i`, ties to the lower row
    /// (the start's side). For a zero-length segment, the start's row.
    #[inline]
    pub fn nearest_row(&self, i: i64) -> i64 {
        let du = self.du();
        if du == 0 {
            return pixel_containing(self.v0 + HALF_PIXEL);
        }
        // ceil((v - 128) / 256) with v = scaled / du.
        let num = self.scaled_v_at(i) - HALF_PIXEL * du;
        let den = SUBPIXEL_SCALE * du;
        -((-num).div_euclid(den))
    }

    /// The frame's columns `i` and rows `k` whose screen pixels lie in
    /// `rect`, as two ranges `(lo, hi)` (the inverse of
    /// [`to_screen`](Self::to_screen) on its sides; empty when `lo > hi`).
    pub fn ranges_within(&self, rect: PixelRect) -> ((i64, i64), (i64, i64)) {
        let (major, minor) = if self.swap {
            ((rect.y0, rect.y1), (rect.x0, rect.x1))
        } else {
            ((rect.x0, rect.x1), (rect.y0, rect.y1))
        };
        let mirror = |(lo, hi): (i64, i64), flip: bool| if flip { (-hi, -lo) } else { (lo, hi) };
        (
            mirror(major, self.flip_major),
            mirror(minor, self.flip_minor),
        )
    }

    /// Maps a frame pixel `(i, k)` back to a screen pixel.
    pub fn to_screen(&self, i: i64, k: i64) -> (i64, i64) {
        let major = if self.flip_major { -i } else { i };
        let minor = if self.flip_minor { -k } else { k };
        if self.swap {
            (minor, major)
        } else {
            (major, minor)
        }
    }
}

fn major_minor(p: FixedPoint, swap: bool) -> (i64, i64) {
    if swap {
        (p.y.raw(), p.x.raw())
    } else {
        (p.x.raw(), p.y.raw())
    }
}

/// The frame an algorithm of the line-drawing slides walks, given the options: from `from`, or
/// for the symmetric variant from the endpoint with the smaller major
/// coordinate (the pixels are then re-ordered into the direction of travel).
pub(crate) fn walk_frame(line: &LineSetup, options: &LineOptions) -> (OctantFrame, bool) {
    let forward = OctantFrame::new(line.from, line.to);
    if options.symmetric && forward.flip_major {
        (OctantFrame::new(line.to, line.from), true)
    } else {
        (forward, false)
    }
}

/// Turns a frame's column-by-column rows into screen pixels in the order of
/// travel, into `pixels` (emptied first): adds 4-connected corners,
/// reverses walks made backwards by the symmetric variant, drops the end
/// pixel when half-open.
pub(crate) fn finish_pixels(
    frame: &OctantFrame,
    rows: &[(i64, i64)],
    reversed: bool,
    options: &LineOptions,
    pixels: &mut Vec<(i64, i64)>,
) {
    pixels.clear();
    pixels.reserve(rows.len() * 2);
    for (n, &(i, k)) in rows.iter().enumerate() {
        if options.connectivity == Connectivity::Four && n > 0 {
            let (pi, pk) = rows[n - 1];
            if k != pk {
                // Diagonal step: add the corner the ideal line passes first.
                // It crosses the row boundary v = 256 pk + 128 before the
                // column boundary u = 256 pi + 128 when v there is above it.
                let du = frame.du() as i128;
                let v_at_boundary =
                    i128::from(frame.scaled_v_at(pi)) + frame.dv() as i128 * HALF_PIXEL as i128;
                let row_boundary = (SUBPIXEL_SCALE as i128 * pk as i128 + HALF_PIXEL as i128) * du;
                let corner = if v_at_boundary > row_boundary {
                    (pi, k)
                } else {
                    (i, pk)
                };
                pixels.push(frame.to_screen(corner.0, corner.1));
            }
        }
        pixels.push(frame.to_screen(i, k));
    }
    if reversed {
        pixels.reverse();
    }
    if options.endpoints == Endpoints::HalfOpen {
        pixels.pop();
    }
}

/// Hands a segment's pixels that lie in the viewport to a sink in one
/// call ([`FragmentSink::line_fragments`]), through a buffer kept from
/// one segment to the next.
#[derive(Debug, Default)]
pub(crate) struct PixelEmitter {
    fragments: Vec<LineFragment>,
}

impl PixelEmitter {
    /// Emits aliased pixels (coverage 1) of `line` that lie in the
    /// viewport, counting them.
    pub(crate) fn emit(
        &mut self,
        line: &LineSetup,
        pixels: &[(i64, i64)],
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
        work: &mut WorkCounters,
    ) {
        self.emit_weighted(line, pixels.iter().map(|&p| (p, 1.0)), viewport, sink, work);
    }

    /// Emits the pixels of an 8-connected `line` that lie in the
    /// viewport, straight from `A`'s walk, counting them: the pixels
    /// [`AliasedLine::pixels`] gives, one per column, in the same order.
    fn emit_columns<A: AliasedLine>(
        &mut self,
        line: &LineSetup,
        options: &LineOptions,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
        work: &mut WorkCounters,
    ) {
        debug_assert_eq!(options.connectivity, Connectivity::Eight);
        let (frame, reversed) = walk_frame(line, options);
        // The end pixel of travel is the last column walked, or the first
        // when the walk ran backwards.
        let left_out = match options.endpoints {
            Endpoints::Inclusive => None,
            Endpoints::HalfOpen if reversed => Some(frame.i0),
            Endpoints::HalfOpen => Some(frame.i1),
        };
        // Only the columns whose pixels can lie in the viewport are
        // walked: the major axis gives them directly. A walked column's
        // pixel is then in the viewport exactly when its row `k` is in
        // the minor axis's range, tested before the pixel is mapped.
        let ((lo, hi), (k_lo, k_hi)) = frame.ranges_within(viewport);
        let (first, last) = (frame.i0.max(lo), frame.i1.min(hi));
        // The buffer is kept at least as long as the longest segment so
        // far and written by index: no capacity test or growth (a call the
        // loop's registers would be saved around) per pixel.
        let columns = (last - first + 1).max(0) as usize;
        if self.fragments.len() < columns {
            let unused = LineFragment {
                x: 0,
                y: 0,
                line: 0,
                coverage: 0.0,
            };
            self.fragments.resize(columns, unused);
        }
        let slots = &mut self.fragments[..columns];
        let mut drawn = 0;
        let id = line.id;
        if first <= last {
            A::walk_columns(&frame, first, last, |i, k| {
                if (k_lo..=k_hi).contains(&k) {
                    let (x, y) = frame.to_screen(i, k);
                    slots[drawn] = LineFragment {
                        x: x as u32,
                        y: y as u32,
                        line: id,
                        coverage: 1.0,
                    };
                    drawn += 1;
                }
            });
        }
        // The left-out column's pixel, if it was drawn, is the last one
        // walked (or the first, walking backwards): one pixel per column,
        // so its major coordinate tells.
        let mut walked = 0..drawn;
        if let (Some(column), true) = (left_out, drawn > 0) {
            let major_of = |f: &LineFragment| i64::from(if frame.swap { f.y } else { f.x });
            let major = if frame.flip_major { -column } else { column };
            let end = if reversed { 0 } else { drawn - 1 };
            if major_of(&slots[end]) == major {
                if reversed {
                    walked.start += 1;
                } else {
                    walked.end -= 1;
                }
            }
        }
        let fragments = &mut slots[walked];
        if reversed {
            fragments.reverse();
        }
        // The segment's pixels, seen or not, as for a 4-connected line.
        work.samples_tested += (frame.i1 - frame.i0 + 1) as u64 - u64::from(left_out.is_some());
        work.fragments += fragments.len() as u64;
        if !fragments.is_empty() {
            sink.line_fragments(fragments);
        }
    }

    /// Emits pixels of `line` with their coverage that lie in the
    /// viewport, counting them.
    pub(crate) fn emit_weighted(
        &mut self,
        line: &LineSetup,
        pixels: impl IntoIterator<Item = ((i64, i64), f32)>,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
        work: &mut WorkCounters,
    ) {
        self.fragments.clear();
        self.fragments.extend(
            pixels
                .into_iter()
                .filter(|&((x, y), _)| viewport.contains(x, y))
                .map(|((x, y), coverage)| LineFragment {
                    x: x as u32,
                    y: y as u32,
                    line: line.id,
                    coverage,
                }),
        );
        work.fragments += self.fragments.len() as u64;
        if !self.fragments.is_empty() {
            sink.line_fragments(&self.fragments);
        }
    }
}

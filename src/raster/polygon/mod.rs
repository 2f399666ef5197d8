//! Polygon back-ends: a polygon filled directly, beside triangulating it.
//!
//! The triangle back-ends draw a polygon once spade has cut it into
//! triangles. The classic alternative fills it directly, row by row, from
//! its edges (Foley, van Dam, Feiner and Hughes 1990, *Computer Graphics:
//! Principles and Practice*, 2nd ed., §3.6 "Filling polygons"), as every
//! 2D library does. This module holds what the polygon back-ends share:
//!
//! * the **winding rule** ([`WindingRule`]): which points of a plane cut
//!   by the rings are inside, by the **winding number** (how many times the
//!   rings wind around the point): *even-odd* fills an odd one, *nonzero*
//!   any but zero. On a simple polygon whose holes wind against their outer
//!   ring (as the file reader makes them), both rules fill the same points;
//!   they differ where rings cross or overlap;
//! * the **boundary convention**, one for every back-end: pixel `(i, j)`
//!   is filled when its centre, moved right by an infinitesimal `ε` and
//!   down by an infinitesimal `δ ≪ ε`, has a winding number the rule fills.
//!   That is exactly the triangles' top-left rule (a centre on a left edge
//!   or a top edge is inside, on a right or a bottom edge outside): an edge
//!   function `E` with `E = 0` at the centre is positive at the moved point
//!   exactly when the edge is a top or a left edge. So on a simple polygon
//!   the pixels filled are the union of its triangulation's top-left
//!   fragments, each pixel once, and two polygons sharing an edge leave no
//!   gap and draw no pixel twice. In the book's words: the spans are **half
//!   open** (a pixel on a left edge is drawn, one on a right edge is not),
//!   an edge's top vertex (its `ymin`, y growing down) counts and its bottom
//!   vertex does not, and horizontal edges are no edges at all;
//! * the polygon's edges, directed for the scan ([`PolygonEdge`]) with
//!   their exact crossing of a row's sample line, and a polygon's set-up
//!   ([`PolygonSetup`]);
//! * the trait every polygon back-end is ([`PolygonRasterizer`]): the
//!   book's algorithm with its edge table and active edge table
//!   ([`edge_table`]), and the same fill without them, every edge asked on
//!   every row ([`crossings`]).
//!
//! A back-end hands its runs of pixels to the same [`FragmentSink`] as
//! every other, as spans of the polygon's id: its look is flat, so a
//! fragment's edge values are [`FLAT_EDGES`] (barycentrics `(1, 0, 0)`,
//! vertex 0's depth and colour) and the shared stage shades and merges it
//! as it does a triangle's.
//!
//! ```
//! use rasterlab::raster::polygon::{edge_table::EdgeTable, PolygonRasterizer, PolygonSetup, WindingRule};
//! use rasterlab::raster::{FixedPoint, FragmentList, PixelRect};
//! let p = |x: f64, y: f64| FixedPoint::snap_f64(x, y).unwrap();
//! // A pentagram: its centre winds twice, so even-odd leaves it empty.
//! let star = vec![p(5., 0.), p(8., 9.), p(0., 3.5), p(10., 3.5), p(2., 9.)];
//! let setup = PolygonSetup::new(0, &[star]);
//! let count = |rule| {
//!     let mut list = FragmentList::default();
//!     EdgeTable.rasterize(std::slice::from_ref(&setup), rule, PixelRect::of_target(10, 10), &mut list);
//!     list.triangles.len()
//! };
//! assert!(count(WindingRule::EvenOdd) < count(WindingRule::Nonzero));
//! ```

pub mod crossings;
pub mod edge_table;

use crate::raster::descriptor::Descriptor;
use crate::raster::edge::PixelRect;
use crate::raster::fixed::{
    first_sample_at_or_after, last_sample_at_or_before, FixedPoint, HALF_PIXEL, SUBPIXEL_SCALE,
};
use crate::raster::fragment::{FragmentSink, TriangleFragment, TriangleSpan, WorkCounters};
use std::fmt;

/// Which winding numbers are inside.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum WindingRule {
    /// An odd winding number is inside (the ray crosses the rings an odd
    /// number of times): overlaps of two rings are holes.
    #[default]
    EvenOdd,
    /// Any winding number but zero is inside: overlaps are filled.
    Nonzero,
}

impl WindingRule {
    /// Both rules, the default first.
    pub const ALL: [WindingRule; 2] = [WindingRule::EvenOdd, WindingRule::Nonzero];

    /// The name the command line takes (`even-odd`, `nonzero`).
    pub fn name(self) -> &'static str {
        match self {
            WindingRule::EvenOdd => "even-odd",
            WindingRule::Nonzero => "nonzero",
        }
    }

    /// Whether a point of winding number `winding` is inside.
    #[inline]
    pub fn fills(self, winding: i64) -> bool {
        match self {
            WindingRule::EvenOdd => winding % 2 != 0,
            WindingRule::Nonzero => winding != 0,
        }
    }
}

impl fmt::Display for WindingRule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for WindingRule {
    type Err = crate::Error;
    fn from_str(s: &str) -> crate::Result<Self> {
        Self::ALL
            .into_iter()
            .find(|r| r.name() == s)
            .ok_or_else(|| {
                crate::Error::InvalidArgument(format!(
                    "unknown winding rule `{s}`: expected even-odd or nonzero"
                ))
            })
    }
}

/// The edge values a polygon's fragments carry: barycentrics `(1, 0, 0)`,
/// so the stage gives every fragment vertex 0's depth and colour (a
/// polygon's look is flat).
pub const FLAT_EDGES: [i64; 3] = [1, 0, 0];

/// A non-horizontal edge of a polygon's rings, from its top end (smaller
/// y, the book's `ymin`) to its bottom end.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct PolygonEdge {
    /// The end with the smaller y.
    pub top: FixedPoint,
    /// The end with the larger y.
    pub bottom: FixedPoint,
    /// `+1` when the ring runs down along the edge (from `top` to
    /// `bottom`), `-1` when it runs up: what crossing it adds to the
    /// winding number of the points to its left.
    pub winding: i8,
}

impl PolygonEdge {
    /// The edge from `from` to `to` of a ring; `None` when it is
    /// horizontal (a horizontal edge bounds no row: the rows above and
    /// below it are bounded by its neighbours).
    pub fn new(from: FixedPoint, to: FixedPoint) -> Option<PolygonEdge> {
        match from.y.cmp(&to.y) {
            std::cmp::Ordering::Less => Some(PolygonEdge {
                top: from,
                bottom: to,
                winding: 1,
            }),
            std::cmp::Ordering::Greater => Some(PolygonEdge {
                top: to,
                bottom: from,
                winding: -1,
            }),
            std::cmp::Ordering::Equal => None,
        }
    }

    /// The rows whose sample line the edge crosses, `first..=last` (empty
    /// when `last < first`): those with `top.y <= 256 j + 128 < bottom.y`,
    /// the top end counted and the bottom end not.
    pub fn rows(&self) -> (i64, i64) {
        (
            first_sample_at_or_after(self.top.y.raw()),
            last_sample_at_or_before(self.bottom.y.raw() - 1),
        )
    }

    /// The first pixel of row `j` whose centre lies at or right of the
    /// edge's crossing with the row's sample line, exactly: with `X` the
    /// crossing, `ceil((X - 128) / 256)`. The span a crossing starts
    /// begins there, and the span it ends stops just before.
    pub fn first_pixel_at_or_right(&self, j: i64) -> i64 {
        let (numerator, denominator) = self.crossing_offset(j);
        -((-numerator).div_euclid(denominator))
    }

    /// `(X - 128) / 256` at row `j` as a fraction with a positive
    /// denominator `256 dy`.
    fn crossing_offset(&self, j: i64) -> (i64, i64) {
        let (dx, dy) = self.deltas();
        let y = j * SUBPIXEL_SCALE + HALF_PIXEL;
        // X dy = x_top dy + (y - y_top) dx, exact in i64 within the guard band.
        let x_dy = self.top.x.raw() * dy + (y - self.top.y.raw()) * dx;
        (x_dy - HALF_PIXEL * dy, SUBPIXEL_SCALE * dy)
    }

    /// `(dx, dy)` in fixed units, `dy > 0`.
    fn deltas(&self) -> (i64, i64) {
        (
            self.bottom.x.raw() - self.top.x.raw(),
            self.bottom.y.raw() - self.top.y.raw(),
        )
    }
}

/// A polygon set up for a back-end: its id (what its fragments carry) and
/// its non-horizontal edges, from every ring.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PolygonSetup {
    /// The id its fragments carry (its index in the draw).
    pub id: u32,
    /// Every non-horizontal edge of every ring, in ring order.
    pub edges: Vec<PolygonEdge>,
}

impl PolygonSetup {
    /// Sets up the polygon bounded by `rings` (each closed implicitly,
    /// last vertex to first; any shape, crossing or not).
    pub fn new(id: u32, rings: &[Vec<FixedPoint>]) -> PolygonSetup {
        let edges = rings
            .iter()
            .flat_map(|ring| {
                let next = ring.iter().cycle().skip(1);
                ring.iter().zip(next).map(|(&a, &b)| (a, b))
            })
            .filter_map(|(a, b)| PolygonEdge::new(a, b))
            .collect();
        PolygonSetup { id, edges }
    }
}

/// A polygon back-end's facts: a [`Descriptor`] whose walk is said in words.
pub type PolygonDescriptor = Descriptor<&'static str>;

/// The work of a polygon draw: the counters every back-end keeps, and
/// what a scan over edges adds to them.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct PolygonWork {
    /// Polygons drawn, samples tested, fragments, and rows visited (as
    /// `spans`, as the triangles' scanline counts its rows).
    pub work: WorkCounters,
    /// Edges looked at, one per edge per row it was looked at on.
    pub edges_visited: u64,
    /// Runs of pixels handed to the sink (a row of a polygon may hold
    /// several).
    pub runs: u64,
}

/// A polygon rasterization algorithm.
pub trait PolygonRasterizer: Send + Sync {
    /// The back-end's name, description, walk, role and cost class.
    fn descriptor(&self) -> PolygonDescriptor;

    /// Short name used on the command line.
    fn name(&self) -> &'static str {
        self.descriptor().name
    }

    /// Fills every polygon of `polygons` under `rule`, in order, emitting
    /// the fragments whose pixel lies in `viewport` into `sink`, each
    /// polygon's pixels once.
    fn rasterize(
        &self,
        polygons: &[PolygonSetup],
        rule: WindingRule,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> PolygonWork;
}

/// Fills row `y` between `crossings` (each the first pixel at or right of
/// an edge's crossing, and the edge's winding), sorted by x, where `rule`
/// puts the winding number inside: one run per stretch of inside spans,
/// clipped to the viewport, each recorded in `spans` when given.
#[allow(clippy::too_many_arguments)]
#[inline]
fn fill_runs(
    crossings: impl IntoIterator<Item = (i64, i8)>,
    rule: WindingRule,
    y: i64,
    viewport: PixelRect,
    id: u32,
    sink: &mut dyn FragmentSink,
    work: &mut PolygonWork,
    mut spans: Option<&mut Vec<(i64, i64)>>,
) {
    let mut winding = 0i64;
    let mut run_start: Option<i64> = None;
    for (x, direction) in crossings {
        let was_inside = rule.fills(winding);
        winding += i64::from(direction);
        match (was_inside, rule.fills(winding)) {
            (false, true) => run_start = Some(x),
            (true, false) => {
                let first = run_start.take().unwrap_or(x).max(viewport.x0);
                let last = (x - 1).min(viewport.x1);
                if first <= last {
                    work.runs += 1;
                    work.work.fragments += (last - first + 1) as u64;
                    emit_run(sink, id, y, first, last);
                    if let Some(spans) = spans.as_deref_mut() {
                        spans.push((first, last));
                    }
                }
            }
            _ => {}
        }
    }
}

/// Emits pixels `first..=last` of row `y` (inside the viewport) of polygon
/// `id`: one fragment, or one span.
fn emit_run(sink: &mut dyn FragmentSink, id: u32, y: i64, first: i64, last: i64) {
    if first == last {
        sink.triangle_fragment(&TriangleFragment {
            x: first as u32,
            y: y as u32,
            triangle: id,
            edges: FLAT_EDGES,
        });
    } else {
        sink.triangle_span(&TriangleSpan {
            y: y as u32,
            x0: first as u32,
            x1: last as u32,
            triangle: id,
            edges: FLAT_EDGES,
            step: [0; 3],
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edge(x0: i64, y0: i64, x1: i64, y1: i64) -> PolygonEdge {
        let p = |x, y| FixedPoint::from_raw(x, y).unwrap();
        PolygonEdge::new(p(x0, y0), p(x1, y1)).unwrap()
    }

    /// The crossing's first pixel is the smallest `i` whose centre is at
    /// or right of the crossing, checked against a cross product.
    #[test]
    fn the_first_pixel_right_of_a_crossing_is_exact() {
        let mut rng = fastrand::Rng::with_seed(11);
        for _ in 0..20_000 {
            let mut v = || rng.i64(-3000..3000);
            let e = match PolygonEdge::new(
                FixedPoint::from_raw(v(), v()).unwrap(),
                FixedPoint::from_raw(v(), v()).unwrap(),
            ) {
                Some(e) => e,
                None => continue,
            };
            let (first, last) = e.rows();
            for j in first..=last {
                let i = e.first_pixel_at_or_right(j);
                // Sign of (centre - crossing) along x, times dy > 0.
                let right_of = |i: i64| {
                    let (dx, dy) = e.deltas();
                    let (x, y) = (i * 256 + 128, j * 256 + 128);
                    (x - e.top.x.raw()) * dy - (y - e.top.y.raw()) * dx >= 0
                };
                assert!(right_of(i) && !right_of(i - 1), "{e:?} row {j}: {i}");
            }
        }
    }

    #[test]
    fn rows_count_the_top_end_and_not_the_bottom_end() {
        // From y = 0.5 (a sample line) to y = 2.5 (another): rows 0 and 1.
        assert_eq!(edge(0, 128, 0, 640).rows(), (0, 1));
        assert_eq!(edge(0, 129, 0, 641).rows(), (1, 2));
        assert_eq!(edge(0, 0, 0, 128).rows(), (0, -1));
        assert!(PolygonEdge::new(
            FixedPoint::from_raw(0, 5).unwrap(),
            FixedPoint::from_raw(9, 5).unwrap()
        )
        .is_none());
    }

    #[test]
    fn winding_rules_parse_by_name() {
        for rule in WindingRule::ALL {
            assert_eq!(rule.name().parse::<WindingRule>().unwrap(), rule);
        }
        assert!("odd".parse::<WindingRule>().is_err());
        assert!(WindingRule::EvenOdd.fills(-3) && !WindingRule::EvenOdd.fills(2));
        assert!(WindingRule::Nonzero.fills(-2) && !WindingRule::Nonzero.fills(0));
    }
}

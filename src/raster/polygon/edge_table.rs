//! `edge-table`: the scan-line polygon fill with an edge table and an
//! active edge table (Foley, van Dam, Feiner and Hughes 1990, §3.6).
//!
//! The book's algorithm, with y growing down (its `ymin` is an edge's top):
//!
//! ```text
//! build the edge table (ET): each non-horizontal edge in the bucket of
//!   the first row it crosses, with its crossing x and its step 1/m
//! y = the first row of a non-empty bucket; the active edge table (AET) empty
//! repeat until the AET and the ET are empty:
//!   move bucket y of the ET into the AET
//!   remove from the AET the edges whose last row is above y
//!   sort the AET by x
//!   fill the spans between the crossings the winding rule puts inside
//!   y = y + 1
//!   step each edge's x by 1/m
//! ```
//!
//! The rows crossed are the sample lines `Y = j + 0.5`: an edge crosses
//! row `j` when `top.y <= Y < bottom.y` (its top end counts, its bottom
//! end does not), so a vertex shared by two edges is crossed once, or
//! twice at a peak, never by accident. Each span runs **half open** from
//! one crossing to the next: a pixel whose centre lies exactly on the
//! crossing belongs to the span the crossing starts, not to the one it
//! ends (the module [`polygon`](super)'s boundary convention, the
//! triangles' top-left rule).
//!
//! The book steps `x` by `1/m` as a whole part and a fraction kept over
//! the denominator `dy` ("the numerator is incremented by `dx`; when it
//! exceeds the denominator, x is incremented"). Here the same: each active
//! edge holds the first pixel at or right of its crossing and the
//! remainder over `256 dy` that says how far right of the crossing that
//! pixel's centre lies; a row adds `dx / dy` as whole pixels and a
//! remainder, and carries one pixel when the remainder runs out. All of
//! it is `i64` on the 1/256 px grid, so the spans are exact: no pixel is
//! rounded one way here and the other way by the triangle back-ends.
//!
//! The winding number of a span is the sum of the directions of the
//! crossings left of it; even-odd fills it when odd, nonzero when not
//! zero. Spans that meet are handed to the sink as one run.

use super::{
    fill_runs, PolygonDescriptor, PolygonEdge, PolygonRasterizer, PolygonSetup, PolygonWork,
    WindingRule,
};
use crate::raster::descriptor::{CostClass, Role};
use crate::raster::edge::PixelRect;
use crate::raster::fixed::SUBPIXEL_SCALE;
use crate::raster::fragment::FragmentSink;

/// The edge table / active edge table scan conversion.
#[derive(Copy, Clone, Debug, Default)]
pub struct EdgeTable;

/// An edge of the active edge table, at the row being filled.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct ActiveEdge {
    /// Which edge of the polygon's set-up.
    pub edge: usize,
    /// The first pixel whose centre lies at or right of the crossing.
    pub x: i64,
    /// `256 dy` times how far (in pixels) that centre lies right of the
    /// crossing: in `0..256 dy`.
    remainder: i64,
    /// The last row the edge crosses.
    pub last_row: i64,
    /// `+1` or `-1`: the edge's direction ([`PolygonEdge::winding`]).
    pub winding: i8,
    /// Whole pixels `x` moves per row: `floor(dx / dy)`.
    whole: i64,
    /// What the remainder loses per row: `256 (dx mod dy)`.
    fraction: i64,
    /// `256 dy`, the remainder's denominator.
    denominator: i64,
}

impl ActiveEdge {
    /// Edge `edge` entering the active table at row `j`, its crossing
    /// solved there exactly.
    fn enter(edge: usize, e: &PolygonEdge, j: i64, last_row: i64) -> ActiveEdge {
        let (numerator, denominator) = e.crossing_offset(j);
        let x = -((-numerator).div_euclid(denominator));
        let (dx, dy) = e.deltas();
        ActiveEdge {
            edge,
            x,
            remainder: x * denominator - numerator,
            last_row,
            winding: e.winding,
            whole: dx.div_euclid(dy),
            fraction: SUBPIXEL_SCALE * dx.rem_euclid(dy),
            denominator,
        }
    }

    /// The book's `x += 1/m`: the crossing of the next row.
    #[inline]
    fn step(&mut self) {
        self.x += self.whole;
        self.remainder -= self.fraction;
        if self.remainder < 0 {
            self.x += 1;
            self.remainder += self.denominator;
        }
    }
}

/// One row of the walk, as a trace shows it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScanRow {
    /// The row.
    pub y: i64,
    /// Edges that entered the active table on this row.
    pub entered: Vec<usize>,
    /// Edges removed from it on this row (their last row was above).
    pub removed: Vec<usize>,
    /// The active table after sorting: each edge and its crossing's first
    /// pixel.
    pub active: Vec<(usize, i64, i8)>,
    /// The runs filled, `first..=last`, clipped to the viewport.
    pub spans: Vec<(i64, i64)>,
}

impl EdgeTable {
    /// Fills `p` under `rule` as [`PolygonRasterizer::rasterize`] does,
    /// recording every row of the walk: what `explain` shows.
    pub fn trace(
        &self,
        p: &PolygonSetup,
        rule: WindingRule,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> (Vec<ScanRow>, PolygonWork) {
        let (mut rows, mut work) = (Vec::new(), PolygonWork::default());
        fill(p, rule, viewport, sink, &mut work, Some(&mut rows));
        (rows, work)
    }

    /// The edge table of `p` over `viewport`: for each row, the edges that
    /// enter the active table there, as `(row, edges)`, top row first.
    pub fn edge_table(p: &PolygonSetup, viewport: PixelRect) -> Vec<(i64, Vec<usize>)> {
        let mut table: Vec<(i64, Vec<usize>)> = Vec::new();
        let mut entries: Vec<(i64, usize)> = p
            .edges
            .iter()
            .enumerate()
            .filter_map(|(k, e)| clipped_rows(e, viewport).map(|(first, _)| (first, k)))
            .collect();
        entries.sort_unstable();
        for (row, k) in entries {
            match table.last_mut() {
                Some((r, edges)) if *r == row => edges.push(k),
                _ => table.push((row, vec![k])),
            }
        }
        table
    }
}

/// The rows of `viewport` edge `e` crosses, or `None`.
fn clipped_rows(e: &PolygonEdge, viewport: PixelRect) -> Option<(i64, i64)> {
    let (first, last) = e.rows();
    let (first, last) = (first.max(viewport.y0), last.min(viewport.y1));
    (first <= last).then_some((first, last))
}

/// The walk: the edge table, then row by row the active edge table and
/// its spans.
fn fill(
    p: &PolygonSetup,
    rule: WindingRule,
    viewport: PixelRect,
    sink: &mut dyn FragmentSink,
    work: &mut PolygonWork,
    mut trace: Option<&mut Vec<ScanRow>>,
) {
    work.work.primitives += 1;
    let table = EdgeTable::edge_table(p, viewport);
    let mut buckets = table.into_iter().peekable();
    let mut active: Vec<ActiveEdge> = Vec::new();
    let Some(&(mut y, _)) = buckets.peek() else {
        return;
    };
    while !active.is_empty() || buckets.peek().is_some() {
        if active.is_empty() {
            // Nothing active: jump to the next bucket's row.
            y = y.max(buckets.peek().map_or(y, |b| b.0));
        }
        let mut row = trace.as_ref().map(|_| ScanRow {
            y,
            entered: Vec::new(),
            removed: Vec::new(),
            active: Vec::new(),
            spans: Vec::new(),
        });
        if let Some((_, edges)) = buckets.next_if(|b| b.0 == y) {
            for k in edges {
                let e = &p.edges[k];
                let last = clipped_rows(e, viewport).map_or(y, |r| r.1);
                active.push(ActiveEdge::enter(k, e, y, last));
                if let Some(row) = row.as_mut() {
                    row.entered.push(k);
                }
            }
        }
        active.retain(|a| {
            let keep = a.last_row >= y;
            if let (false, Some(row)) = (keep, row.as_mut()) {
                row.removed.push(a.edge);
            }
            keep
        });
        if active.is_empty() {
            continue;
        }
        // Crossings change order only where edges cross: nearly sorted,
        // which the standard sort finds in one pass.
        active.sort_by_key(|a| a.x);
        work.work.spans += 1;
        work.edges_visited += active.len() as u64;
        let crossings = active.iter().map(|a| (a.x, a.winding));
        let spans = row.as_mut().map(|r| &mut r.spans);
        fill_runs(crossings, rule, y, viewport, p.id, sink, work, spans);
        if let (Some(trace), Some(mut row)) = (trace.as_deref_mut(), row) {
            row.active = active.iter().map(|a| (a.edge, a.x, a.winding)).collect();
            trace.push(row);
        }
        y += 1;
        for a in &mut active {
            a.step();
        }
    }
}

impl PolygonRasterizer for EdgeTable {
    fn descriptor(&self) -> PolygonDescriptor {
        PolygonDescriptor {
            name: "edge-table",
            description: "polygon scan conversion: edge table, active edge table sorted by x, half-open spans (Foley & van Dam 3.6)",
            walk: "row by row, the active edges' crossings stepped by 1/m",
            role: Role::Default,
            cost: CostClass::FollowsSize,
        }
    }

    fn rasterize(
        &self,
        polygons: &[PolygonSetup],
        rule: WindingRule,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> PolygonWork {
        let mut work = PolygonWork::default();
        for p in polygons {
            fill(p, rule, viewport, sink, &mut work, None);
        }
        work
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::fixed::FixedPoint;
    use crate::raster::fragment::FragmentList;

    /// Stepping `x` by `1/m` row after row lands where solving each row
    /// afresh lands.
    #[test]
    fn stepping_by_one_over_m_equals_solving_each_row() {
        let mut rng = fastrand::Rng::with_seed(5);
        for _ in 0..5000 {
            let mut v = || rng.i64(-40_000..40_000);
            let Some(e) = PolygonEdge::new(
                FixedPoint::from_raw(v(), v()).unwrap(),
                FixedPoint::from_raw(v(), v()).unwrap(),
            ) else {
                continue;
            };
            let (first, last) = e.rows();
            if first > last {
                continue;
            }
            let mut a = ActiveEdge::enter(0, &e, first, last);
            for j in first..=last {
                assert_eq!(a.x, e.first_pixel_at_or_right(j), "{e:?} row {j}");
                assert!((0..a.denominator).contains(&a.remainder));
                a.step();
            }
        }
    }

    #[test]
    fn a_square_fills_its_half_open_pixels() {
        let p = |x: f64, y: f64| FixedPoint::snap_f64(x, y).unwrap();
        // Corners on pixel centres: the left and top edges' centres are
        // in, the right and bottom edges' out, 3 x 2 pixels.
        let square = vec![p(1.5, 1.5), p(4.5, 1.5), p(4.5, 3.5), p(1.5, 3.5)];
        let setup = PolygonSetup::new(7, &[square]);
        let mut list = FragmentList::default();
        let work = EdgeTable.rasterize(
            std::slice::from_ref(&setup),
            WindingRule::EvenOdd,
            PixelRect::of_target(8, 8),
            &mut list,
        );
        let pixels: Vec<(u32, u32, u32)> = list
            .triangles
            .iter()
            .map(|f| (f.x, f.y, f.triangle))
            .collect();
        let expected: Vec<(u32, u32, u32)> = [1, 2]
            .iter()
            .flat_map(|&y| (1..4).map(move |x| (x, y, 7)))
            .collect();
        assert_eq!(pixels, expected);
        assert_eq!((work.runs, work.edges_visited, work.work.spans), (2, 4, 2));
        let (rows, traced) = EdgeTable.trace(
            &setup,
            WindingRule::EvenOdd,
            PixelRect::of_target(8, 8),
            &mut FragmentList::default(),
        );
        assert_eq!(traced, work);
        assert_eq!(rows[0].entered.len(), 2);
        assert_eq!(rows[1].spans, vec![(1, 3)]);
    }
}

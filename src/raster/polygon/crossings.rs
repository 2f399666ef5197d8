//! `crossings`: the scan-line polygon fill without an active edge table.
//!
//! Foley and van Dam (1990, §3.6) fill a polygon row by row from the
//! crossings of its edges with each scan line: "find the intersections of
//! the scan line with all edges of the polygon, sort the intersections by
//! increasing x coordinate, fill in all pixels between pairs of
//! intersections". This back-end does exactly that, and nothing more: on
//! every row it asks **every** edge whether it crosses the row's sample
//! line, solves each crossing afresh (one exact division, as
//! [`PolygonEdge::first_pixel_at_or_right`] does), sorts them and fills
//! the spans the winding rule puts inside.
//!
//! It fills the same pixels as `edge-table`, by the same half-open spans
//! and the same boundary convention. What the edge table and the active
//! edge table save is what it counts: it visits `edges x rows` edges where
//! the active edge table visits only the edges crossing each row, and it
//! divides once per crossing where the active edge table steps each
//! crossing by `1/m` with an addition. `compare` on a file of polygons
//! shows both counts.

use super::{
    fill_runs, PolygonDescriptor, PolygonEdge, PolygonRasterizer, PolygonSetup, PolygonWork,
    WindingRule,
};
use crate::raster::descriptor::{CostClass, Role};
use crate::raster::edge::PixelRect;
use crate::raster::fragment::FragmentSink;

/// Every edge asked on every row; the crossings solved and sorted.
#[derive(Copy, Clone, Debug, Default)]
pub struct Crossings;

/// Fills polygon `p`: every row of its vertical extent within `viewport`,
/// every edge tested on it.
fn fill(
    p: &PolygonSetup,
    rule: WindingRule,
    viewport: PixelRect,
    sink: &mut dyn FragmentSink,
    work: &mut PolygonWork,
) {
    work.work.primitives += 1;
    let rows: Vec<(i64, i64)> = p.edges.iter().map(PolygonEdge::rows).collect();
    let first = rows.iter().map(|r| r.0).min().unwrap_or(0).max(viewport.y0);
    let last = rows
        .iter()
        .map(|r| r.1)
        .max()
        .unwrap_or(-1)
        .min(viewport.y1);
    let mut crossings: Vec<(i64, i8)> = Vec::new();
    for y in first..=last {
        work.work.spans += 1;
        work.edges_visited += p.edges.len() as u64;
        crossings.clear();
        for (e, &(top, bottom)) in p.edges.iter().zip(&rows) {
            if top <= y && y <= bottom {
                crossings.push((e.first_pixel_at_or_right(y), e.winding));
            }
        }
        crossings.sort_unstable_by_key(|c| c.0);
        fill_runs(
            crossings.iter().copied(),
            rule,
            y,
            viewport,
            p.id,
            sink,
            work,
            None,
        );
    }
}

impl PolygonRasterizer for Crossings {
    fn descriptor(&self) -> PolygonDescriptor {
        PolygonDescriptor {
            name: "crossings",
            description: "polygon scan conversion without an active edge table: every edge asked on every row, crossings solved and sorted",
            walk: "row by row, every edge's crossing solved afresh",
            role: Role::Alternative,
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
            fill(p, rule, viewport, sink, &mut work);
        }
        work
    }
}

//! The edge table's walk over one polygon, in Foley and van Dam's terms
//! (§3.6): the edge table first, each edge in the bucket of the first row
//! it crosses, then for every row the edges moved from the edge table
//! (ET) into the active edge table (AET), those removed, the AET sorted by
//! x with each crossing's winding, and the spans filled.

use super::check_trace_length;
use crate::error::{Error, Result};
use crate::geometry::outline::twice_signed_area;
use crate::raster::edge::PixelRect;
use crate::raster::fixed::FixedPoint;
use crate::raster::fragment::FragmentList;
use crate::raster::polygon::edge_table::EdgeTable;
use crate::raster::polygon::{PolygonSetup, WindingRule};
use crate::teaching::trace_table::{Column, Trace, TraceRow};

/// The edge table's trace of the polygon whose one ring is `points`
/// (screen coordinates, snapped as every command snaps them), filled under
/// `rule` on a `width x height` grid.
///
/// ```
/// use rasterlab::raster::polygon::WindingRule;
/// use rasterlab::teaching::trace_polygon;
/// let square = [(1.5, 1.5), (4.5, 1.5), (4.5, 3.5), (1.5, 3.5)];
/// let text = trace_polygon(&square, WindingRule::EvenOdd, 8, 8).unwrap().to_text();
/// assert!(text.ends_with("2 rows, 4 edges visited, 2 spans, 6 fragments\n"));
/// ```
pub fn trace_polygon(
    points: &[(f64, f64)],
    rule: WindingRule,
    width: u32,
    height: u32,
) -> Result<Trace> {
    trace_polygon_rings(&[points.to_vec()], rule, width, height)
}

/// The edge table's trace of the polygon bounded by `rings` (the first
/// the outer one; each closed implicitly), taken as given: a ring is not
/// turned against the first, so one that runs the same way encloses its
/// points twice, and the winding rules part there.
///
/// ```
/// use rasterlab::raster::polygon::WindingRule;
/// use rasterlab::teaching::trace_polygon_rings;
/// // A square with a square hole, both clockwise on the screen.
/// let outer = vec![(1.0, 1.0), (9.0, 1.0), (9.0, 9.0), (1.0, 9.0)];
/// let inner = vec![(3.0, 3.0), (7.0, 3.0), (7.0, 7.0), (3.0, 7.0)];
/// let rings = [outer, inner];
/// let fragments = |rule| {
///     let text = trace_polygon_rings(&rings, rule, 10, 10).unwrap().to_text();
///     text.lines().last().unwrap().to_string()
/// };
/// assert!(fragments(WindingRule::EvenOdd).ends_with(", 48 fragments"));
/// assert!(fragments(WindingRule::Nonzero).ends_with(", 64 fragments"));
/// ```
pub fn trace_polygon_rings(
    rings: &[Vec<(f64, f64)>],
    rule: WindingRule,
    width: u32,
    height: u32,
) -> Result<Trace> {
    if let Some(short) = rings.iter().find(|r| r.len() < 3) {
        return Err(Error::InvalidArgument(format!(
            "edge-table traces a polygon: give at least 3 points (6 numbers) a ring, not {}",
            short.len()
        )));
    }
    let snapped = rings
        .iter()
        .map(|ring| {
            ring.iter()
                .map(|&(x, y)| FixedPoint::snap_f64(x, y))
                .collect::<Result<Vec<_>>>()
        })
        .collect::<Result<Vec<_>>>()?;
    let viewport = PixelRect::of_target(width, height);
    let setup = PolygonSetup::new(0, &snapped);
    check_trace_length(u64::from(height) + setup.edges.len() as u64, "lines")?;
    let px = |p: FixedPoint| {
        let (x, y) = p.to_f64();
        format!("({x}, {y})")
    };
    let mut trace = Trace::default();
    let vertices: Vec<String> = rings.iter().map(|r| r.len().to_string()).collect();
    trace.header.push(format!(
        "edge-table, {rule}, top-left convention: {}, {} non-horizontal edges",
        match vertices.as_slice() {
            [one] => format!("one ring of {one} vertices"),
            more => format!("{} rings of {} vertices", more.len(), more.join(" and ")),
        },
        setup.edges.len()
    ));
    if snapped.len() > 1 {
        trace.header.push(ring_directions(&snapped));
    }
    trace.header.push(
        "edge table (ET): each edge in the bucket of the first row whose sample line y = row + 0.5 it crosses (top end counted, bottom end not)"
            .into(),
    );
    for (row, edges) in EdgeTable::edge_table(&setup, viewport) {
        let listed: Vec<String> = edges
            .iter()
            .map(|&k| {
                let e = &setup.edges[k];
                let (dx, dy) = (
                    e.bottom.x.raw() - e.top.x.raw(),
                    e.bottom.y.raw() - e.top.y.raw(),
                );
                format!(
                    "e{k} {}-{} {} 1/m = {:.4}, last row {}",
                    px(e.top),
                    px(e.bottom),
                    if e.winding > 0 { "down" } else { "up" },
                    dx as f64 / dy as f64,
                    e.rows().1.min(viewport.y1)
                )
            })
            .collect();
        trace
            .header
            .push(format!("  ET[{row}]: {}", listed.join("; ")));
    }
    trace.header.push(format!(
        "each row: ET[row] into the AET, finished edges out, the AET sorted by x (the first pixel at or right of each crossing, and its winding +1 down, -1 up), spans where the winding number is {}",
        match rule {
            WindingRule::EvenOdd => "odd",
            WindingRule::Nonzero => "not zero",
        }
    ));
    trace.columns = vec![
        Column::right("row", 4, 0),
        Column::left("ET -> AET", 12, 2),
        Column::left("removed", 8, 2),
        Column::left("AET sorted by x: edge x winding", 38, 2),
        Column::left("spans", 0, 2),
    ];
    let names = |edges: &[usize]| match edges {
        [] => "-".to_string(),
        _ => edges
            .iter()
            .map(|k| format!("e{k}"))
            .collect::<Vec<_>>()
            .join(" "),
    };
    let (rows, work) = EdgeTable.trace(&setup, rule, viewport, &mut FragmentList::default());
    for row in &rows {
        let active: Vec<String> = row
            .active
            .iter()
            .map(|&(k, x, w)| format!("e{k} {x} {w:+}"))
            .collect();
        let spans: Vec<String> = row
            .spans
            .iter()
            .map(|&(a, b)| format!("{a}..={b} ({} px)", b - a + 1))
            .collect();
        let mut line = TraceRow::new(vec![
            row.y.to_string(),
            names(&row.entered),
            names(&row.removed),
            active.join(", "),
            if spans.is_empty() {
                "-".into()
            } else {
                spans.join(", ")
            },
        ]);
        for &(a, b) in &row.spans {
            line = line.about(a, row.y, b, row.y);
        }
        trace.rows.push(line);
    }
    trace.footer.push(format!(
        "{} rows, {} edges visited, {} spans, {} fragments",
        work.work.spans, work.edges_visited, work.runs, work.work.fragments
    ));
    Ok(trace)
}

/// Which way each ring runs on the screen (y down), and what that makes
/// of the points inside a ring and the first: rings as given, not turned.
fn ring_directions(rings: &[Vec<FixedPoint>]) -> String {
    let sign = |r: &[FixedPoint]| twice_signed_area(r).signum();
    let way = |s: i128| match s {
        1 => "clockwise",
        -1 => "counter-clockwise",
        _ => "of no area",
    };
    let first = sign(&rings[0]);
    let each: Vec<String> = rings
        .iter()
        .enumerate()
        .map(|(k, r)| {
            let s = sign(r);
            let relation = match (k, s == first) {
                (0, _) => String::new(),
                (_, true) => ", as ring 0: inside both their winding numbers add up to twice ring 0's (even-odd: out, nonzero: in)".into(),
                (_, false) => ", against ring 0: inside both they cancel to 0 (a hole under both rules)".into(),
            };
            format!("ring {k} runs {}{relation}", way(s))
        })
        .collect();
    format!(
        "rings as given, not turned (on the screen, y down): {}",
        each.join("; ")
    )
}

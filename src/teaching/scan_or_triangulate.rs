//! Scan-convert or triangulate: the same polygons filled directly by each
//! polygon back-end, and triangulated by spade then drawn by each triangle
//! back-end, counted side by side (what `compare` prints under its table
//! for a file of polygons).
//!
//! The counts are each method's own work: polygons or triangles set up,
//! rows visited, edges visited (an edge looked at on a row: the active
//! edges of the edge table; the two or three edges whose crossings the
//! triangles' scanline solves on each row of each triangle), samples
//! tested, fragments and runs of pixels handed over. Every row also says
//! how many pixels it fills differently from the triangulation drawn by
//! the reference: none, on simple polygons, by the boundary convention
//! ([`crate::raster::polygon`]).
//!
//! ```
//! use rasterlab::teaching::ScanOrTriangulate;
//! use std::path::Path;
//! let table = ScanOrTriangulate::of_file(Path::new("assets/polygon.txt"), 64, 64, 1)
//!     .unwrap()
//!     .unwrap();
//! assert!(table.rows.iter().all(|r| r.differing_pixels == 0));
//! assert_eq!(table.rows[0].name, "edge-table");
//! ```

use crate::error::Result;
use crate::geometry::input::{parse_polygons, parse_shapes, PolygonFile, Shapes};
use crate::geometry::scene::setup_triangles;
use crate::measure::benchmark::median_time;
use crate::raster::descriptor::{within_budget, WorkBudget};
use crate::raster::edge::{FillRule, PixelRect, TriangleSetup};
use crate::raster::fragment::FragmentList;
use crate::raster::polygon::WindingRule;
use crate::raster::registry::{polygon_backends, triangle_backends};
use crate::raster::triangle::scanline::{active_edges, row_range, sorted_by_y, Scanline};
use std::fmt;
use std::path::Path;
use std::time::Duration;

/// One method's work on the polygons.
#[derive(Clone, Debug, PartialEq)]
pub struct MethodRow {
    /// The back-end, as named on the command line.
    pub name: &'static str,
    /// `true` for a polygon back-end, `false` for a triangle back-end on
    /// the triangulation.
    pub direct: bool,
    /// Polygons or triangles set up.
    pub primitives: u64,
    /// Rows visited (rows with active edges; for the triangles, rows of
    /// each triangle; a tiled walk's rows of blocks).
    pub rows: u64,
    /// Edges visited, where the walk has edges to visit (scan lines).
    pub edges_visited: Option<u64>,
    /// Samples (pixel centres) tested one by one.
    pub samples_tested: u64,
    /// Fragments emitted.
    pub fragments: u64,
    /// Runs of pixels handed to the sink (polygon back-ends).
    pub runs: Option<u64>,
    /// The median time of the fill (not counting spade's triangulation).
    pub time: Duration,
    /// Pixels filled otherwise than by the reference drawing the
    /// triangulation (a pixel counts when its number of fragments differs).
    pub differing_pixels: u64,
}

/// The comparison on one file of polygons.
#[derive(Clone, Debug, PartialEq)]
pub struct ScanOrTriangulate {
    /// Polygons in the file (triangle lines count as polygons of three
    /// vertices).
    pub polygons: usize,
    /// Their vertices, over every ring.
    pub vertices: usize,
    /// Triangles of their triangulation.
    pub triangles: usize,
    /// The median time spade took to triangulate them.
    pub triangulation_time: Duration,
    /// The polygon back-ends first, then the triangle back-ends.
    pub rows: Vec<MethodRow>,
}

impl ScanOrTriangulate {
    /// The comparison for the file at `path` on a `width x height` target,
    /// timed over `samples` runs; `None` when the file holds no `polygon`
    /// line (a triangle soup, a line set), or a polygon whose rings cross
    /// (spade cannot triangulate it).
    pub fn of_file(path: &Path, width: u32, height: u32, samples: usize) -> Result<Option<Self>> {
        let text = std::fs::read_to_string(path).map_err(|e| crate::Error::io(path, &e))?;
        let holds_polygons = text.lines().any(|l| l.trim_start().starts_with("polygon"));
        if !holds_polygons {
            return Ok(None);
        }
        let Ok(file) = parse_polygons(&text, path, None) else {
            return Ok(None);
        };
        let (triangulation_time, shapes) = median_time(samples, || parse_shapes(&text, path).ok());
        let Some(Shapes::Triangles { triangles, .. }) = shapes else {
            return Ok(None);
        };
        let viewport = PixelRect::of_target(width, height);
        let setups = setup_triangles(&triangles, FillRule::TopLeft);
        let pixels = u64::from(width) * u64::from(height);
        let reference = counts(&fill_triangles(&setups, viewport, &Scanline), width, height);
        let mut rows = polygon_rows(&file, viewport, samples, &reference);
        for b in triangle_backends() {
            if within_budget(
                &b.descriptor(),
                setups.len() as u64,
                pixels,
                WorkBudget::Report,
            )
            .is_err()
            {
                continue;
            }
            let (time, (list, work)) = median_time(samples, || {
                let mut list = FragmentList::default();
                let work = b.rasterize(&setups, viewport, &mut list);
                (list, work)
            });
            rows.push(MethodRow {
                name: b.name(),
                direct: false,
                primitives: work.primitives,
                rows: work.spans,
                edges_visited: (b.name() == "scanline")
                    .then(|| scanline_edges_visited(&setups, viewport)),
                samples_tested: work.samples_tested,
                fragments: work.fragments,
                runs: None,
                time,
                differing_pixels: differing(&counts(&list, width, height), &reference),
            });
        }
        Ok(Some(ScanOrTriangulate {
            polygons: file.outlines.len(),
            vertices: file
                .outlines
                .iter()
                .flat_map(|o| &o.rings)
                .map(Vec::len)
                .sum(),
            triangles: triangles.len(),
            triangulation_time,
            rows,
        }))
    }
}

/// Each polygon back-end on the file's polygons.
fn polygon_rows(
    file: &PolygonFile,
    viewport: PixelRect,
    samples: usize,
    reference: &[u32],
) -> Vec<MethodRow> {
    let setups: Vec<_> = (0..file.outlines.len())
        .map(|i| file.outlines[i].setup(i as u32))
        .collect();
    let (width, height) = ((viewport.x1 + 1) as u32, (viewport.y1 + 1) as u32);
    polygon_backends()
        .iter()
        .map(|b| {
            let (time, (list, work)) = median_time(samples, || {
                let mut list = FragmentList::default();
                let work = b.rasterize(&setups, WindingRule::EvenOdd, viewport, &mut list);
                (list, work)
            });
            MethodRow {
                name: b.name(),
                direct: true,
                primitives: work.work.primitives,
                rows: work.work.spans,
                edges_visited: Some(work.edges_visited),
                samples_tested: work.work.samples_tested,
                fragments: work.work.fragments,
                runs: Some(work.runs),
                time,
                differing_pixels: differing(&counts(&list, width, height), reference),
            }
        })
        .collect()
}

fn fill_triangles(
    setups: &[TriangleSetup],
    viewport: PixelRect,
    backend: &dyn crate::raster::triangle::TriangleRasterizer,
) -> FragmentList {
    let mut list = FragmentList::default();
    backend.rasterize(setups, viewport, &mut list);
    list
}

/// The edges the triangles' scanline looks at: on each row of each
/// triangle, the long edge and the short edge or two spanning the row.
fn scanline_edges_visited(setups: &[TriangleSetup], viewport: PixelRect) -> u64 {
    let mut edges = 0;
    for t in setups {
        let order = sorted_by_y(t);
        let (first, last) = row_range(t, order, viewport);
        for j in first..=last {
            let y = j * crate::raster::fixed::SUBPIXEL_SCALE + crate::raster::fixed::HALF_PIXEL;
            edges += active_edges(t, order, y).count() as u64;
        }
    }
    edges
}

/// Fragments per pixel.
fn counts(list: &FragmentList, width: u32, height: u32) -> Vec<u32> {
    let mut counts = vec![0; width as usize * height as usize];
    for f in &list.triangles {
        counts[f.y as usize * width as usize + f.x as usize] += 1;
    }
    counts
}

fn differing(a: &[u32], b: &[u32]) -> u64 {
    a.iter().zip(b).filter(|(a, b)| a != b).count() as u64
}

impl fmt::Display for ScanOrTriangulate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "scan-convert or triangulate: {} polygons ({} vertices) filled directly, even-odd; \
             or spade's {} triangles ({:.3}ms to read and triangulate) drawn top-left",
            self.polygons,
            self.vertices,
            self.triangles,
            self.triangulation_time.as_secs_f64() * 1e3
        )?;
        writeln!(
            f,
            "{:<26} {:>6} {:>6} {:>7} {:>8} {:>9} {:>6} {:>10}  differing pixels",
            "method", "prims", "rows", "edges", "tested", "fragments", "runs", "time"
        )?;
        let opt = |v: Option<u64>| v.map_or("-".to_string(), |v| v.to_string());
        for r in &self.rows {
            let name = if r.direct {
                format!("{} (direct)", r.name)
            } else {
                format!("triangulate + {}", r.name)
            };
            writeln!(
                f,
                "{:<26} {:>6} {:>6} {:>7} {:>8} {:>9} {:>6} {:>8.3}ms  {}",
                name,
                r.primitives,
                r.rows,
                opt(r.edges_visited),
                r.samples_tested,
                r.fragments,
                opt(r.runs),
                r.time.as_secs_f64() * 1e3,
                r.differing_pixels
            )?;
        }
        Ok(())
    }
}

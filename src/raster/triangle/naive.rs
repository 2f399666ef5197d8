//! `naive`: the course's rasterisation pseudocode, literally (the course chapter).
//!
//! ```text
//! for each pixel y in Y dimension
//!   for each pixel x in X dimension
//!     for each triangle t
//!       if pixel x,y is inside triangle t
//!         emit a fragment
//! ```
//!
//! "Inside" is the edge-function test with the fill rule's tie-breaking
//! ([`TriangleSetup::inside`](crate::raster::edge::TriangleSetup::inside)). Every pixel of the target is tested against
//! every triangle: `width x height x triangles` tests. This is the
//! reference every other back-end is checked against, and the red/green
//! picture of the rasterization slides' "checking every pixel" slide.

use super::{emit, TriangleRasterizer, TriangleSelection, TriangleWalk};
use crate::raster::edge::PixelRect;
use crate::raster::fragment::{FragmentSink, WorkCounters};

/// Every pixel tested against every triangle.
#[derive(Copy, Clone, Debug, Default)]
pub struct Naive;

impl TriangleRasterizer for Naive {
    fn walk(&self) -> TriangleWalk {
        TriangleWalk::EveryPixel
    }

    fn is_reference(&self) -> bool {
        true
    }

    fn name(&self) -> &'static str {
        "naive"
    }

    fn description(&self) -> &'static str {
        "course pseudocode: every pixel of the target tested against every triangle"
    }

    fn tests_whatever_the_size(&self, triangles: u64, pixels: u64) -> Option<u64> {
        Some(triangles.saturating_mul(pixels))
    }

    fn rasterize_selection(
        &self,
        triangles: TriangleSelection<'_>,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> WorkCounters {
        let mut work = WorkCounters {
            primitives: triangles.len() as u64,
            ..WorkCounters::default()
        };
        for y in viewport.y0..=viewport.y1 {
            for x in viewport.x0..=viewport.x1 {
                for t in triangles.iter() {
                    work.samples_tested += 1;
                    sink.samples_tested(t.id, y as u32, x as u32, x as u32);
                    let e = t.edge_values_at_pixel(x, y);
                    if t.inside(e) {
                        work.fragments += 1;
                        emit(sink, t, x, y, e);
                    }
                }
            }
        }
        work
    }
}

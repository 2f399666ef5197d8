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
//! Like every back-end, it is written as the step for one triangle (the
//! two outer loops), run for each triangle in turn: the loops exchanged,
//! the same tests, and each pixel's fragments still in triangle order.
//!
//! "Inside" is the edge-function test with the fill rule's tie-breaking
//! ([`TriangleSetup::inside`](crate::raster::edge::TriangleSetup::inside)). Every pixel of the target is tested against
//! every triangle: `width x height x triangles` tests. This is the
//! reference every other back-end is checked against, and the red/green
//! picture of the rasterization slides' "checking every pixel" slide.

use super::{TriangleAlgorithm, TriangleDescriptor, TriangleWalk, Walk, WalkObserver};
use crate::raster::descriptor::{CostClass, Role};
use crate::raster::edge::{PixelRect, TriangleSetup};

/// Every pixel tested against every triangle.
#[derive(Copy, Clone, Debug, Default)]
pub struct Naive;

impl TriangleAlgorithm for Naive {
    const DESCRIPTOR: TriangleDescriptor = TriangleDescriptor {
        name: "naive",
        description: "course pseudocode: every pixel of the target tested against every triangle",
        walk: TriangleWalk::EveryPixel,
        role: Role::Reference,
        cost: CostClass::EveryPixel,
    };

    #[inline]
    fn draw_triangle<O: WalkObserver>(
        &self,
        t: &TriangleSetup,
        viewport: PixelRect,
        walk: &mut Walk<O>,
    ) {
        for y in viewport.y0..=viewport.y1 {
            for x in viewport.x0..=viewport.x1 {
                let e = t.edge_values_at_pixel(x, y);
                if walk.test(x, y, e) {
                    walk.fragment(x, y, e);
                }
            }
        }
    }
}

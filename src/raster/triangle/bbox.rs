//! `bbox`: bounding box, then the edge-function test per pixel (the rasterization slides).
//!
//! Testing every pixel of the screen wastes work on small triangles. The
//! rasterization slides' answer is the **axis-aligned bounding box**: only the pixels whose
//! sample points lie between the triangle's smallest and largest vertex
//! coordinates can be inside, so only those are tested. For each of them
//! the three edge functions (the course chapter's implicit line equation, which give
//! the barycentric coordinates) are evaluated directly, with
//! multiplications, and the pixel is a fragment when all three pass.
//!
//! ```text
//! for each triangle t
//!   for each pixel p in the AABBox of t (clipped to the target)
//!     if p is inside t: emit a fragment
//! ```

use super::{TriangleAlgorithm, TriangleDescriptor, TriangleWalk, Walk, WalkObserver};
use crate::raster::descriptor::{CostClass, Role};
use crate::raster::edge::{PixelRect, TriangleSetup};

/// Bounding box plus a direct edge-function test per pixel.
#[derive(Copy, Clone, Debug, Default)]
pub struct BoundingBox;

impl TriangleAlgorithm for BoundingBox {
    const DESCRIPTOR: TriangleDescriptor = TriangleDescriptor {
        name: "bbox",
        description: "bounding box, then the barycentric / edge-function test evaluated per pixel",
        walk: TriangleWalk::BoundingBox,
        role: Role::Fallback,
        cost: CostClass::FollowsSize,
    };

    #[inline]
    fn draw_triangle<O: WalkObserver>(
        &self,
        t: &TriangleSetup,
        viewport: PixelRect,
        walk: &mut Walk<O>,
    ) {
        let r = t.bounds_within(viewport);
        for y in r.y0..=r.y1 {
            for x in r.x0..=r.x1 {
                let e = t.edge_values_at_pixel(x, y);
                if walk.test(x, y, e) {
                    walk.fragment(x, y, e);
                }
            }
        }
    }
}

//! Triangle rasterizer back-ends.
//!
//! Each back-end is a unit struct named after its algorithm, behind the
//! object-safe [`TriangleRasterizer`] trait, so tools and tests loop over
//! [`crate::raster::backend::triangle_backends`] by name. A back-end only decides
//! *which* pixels each triangle covers; every one of them applies the same
//! exact inside test ([`TriangleSetup::inside`](crate::raster::edge::TriangleSetup::inside)) to the same sample points,
//! so they all emit the same fragments, and differ only in how many samples
//! they test and in what order they visit them.
//!
//! | back-end | idea | tests per pixel |
//! |---|---|---|
//! | [`naive`] | the course pseudocode: every pixel, every triangle | `triangles` |
//! | [`bbox`] | only pixels in the triangle's bounding box, edge functions evaluated directly | 1 inside the box |
//! | [`scanline`] | per row, solve exactly where the row enters and leaves the triangle | 0 |
//! | [`incremental`] | bounding box, edge functions stepped by additions (Pineda) | 1 inside the box |
//! | [`tiled`] | 8x8 blocks, trivial reject / accept from the corners, per-pixel tests only on edges | 1 in straddling blocks, 0 elsewhere |
//!
//! Every back-end emits, for each pixel, that pixel's fragments in
//! ascending triangle order, so the shared stage's depth test resolves ties
//! the same way whichever back-end ran.

pub mod bbox;
pub mod incremental;
pub mod naive;
pub mod scanline;
pub mod tiled;

use crate::raster::edge::{PixelRect, TriangleSetup};
use crate::raster::fragment::{FragmentSink, TriangleFragment, TriangleSpan, WorkCounters};

/// How a triangle back-end walks the pixels: what its step-by-step trace
/// ([`crate::teaching::trace::of_triangle_backend`]) shows.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum TriangleWalk {
    /// Every pixel of the target, each tested on its own (the course's
    /// per-pixel loop).
    EveryPixel,
    /// Every pixel of the triangle's bounding box, each tested on its own.
    BoundingBox,
    /// Row by row, between the edges active on the row.
    Scanline,
    /// Pixel by pixel, the edge values stepped by adding constants.
    IncrementalEdges,
    /// Blocks classified as a whole, partial blocks pixel by pixel.
    Blocks,
}

/// A triangle rasterization algorithm.
pub trait TriangleRasterizer: Send + Sync {
    /// Short name used on the command line.
    fn name(&self) -> &'static str;
    /// One-line description.
    fn description(&self) -> &'static str;
    /// How it walks the pixels, which its trace shows.
    fn walk(&self) -> TriangleWalk;
    /// Whether it is the reference the others are compared with: the
    /// course's loop, testing every sample on its own. One back-end of the
    /// registry says so ([`reference_triangle_backend`](crate::raster::backend::reference_triangle_backend)).
    fn is_reference(&self) -> bool {
        false
    }
    /// Emits every fragment of the selected triangles whose pixel lies in
    /// `viewport`, and returns the work done.
    fn rasterize_selection(
        &self,
        triangles: TriangleSelection<'_>,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> WorkCounters;

    /// A cost hint: the samples this back-end tests to draw `triangles`
    /// triangles on a target of `pixels` pixels, when that does not depend
    /// on the triangles' size (the naive loop: every pixel for every
    /// triangle); `None` (the default) when its work follows the triangles'
    /// area. Tools use it to leave out or refuse runs that would take hours.
    fn tests_whatever_the_size(&self, triangles: u64, pixels: u64) -> Option<u64> {
        let _ = (triangles, pixels);
        None
    }

    /// The blocks this back-end classifies as a whole for triangle `t`
    /// (hierarchical back-ends such as `tiled`), with their classes, for
    /// traces and grid pictures; empty (the default) for back-ends that
    /// visit pixels one by one.
    fn blocks(
        &self,
        t: &TriangleSetup,
        viewport: PixelRect,
    ) -> Vec<(PixelRect, tiled::BlockClass)> {
        let _ = (t, viewport);
        Vec::new()
    }

    /// Whether drawing `triangles` triangles on `pixels` pixels stays
    /// within `budget` sample tests by [`Self::tests_whatever_the_size`].
    fn affordable(&self, triangles: u64, pixels: u64, budget: u64) -> bool {
        self.tests_whatever_the_size(triangles, pixels)
            .is_none_or(|tests| tests <= budget)
    }

    /// Emits every fragment of `triangles` whose pixel lies in `viewport`,
    /// and returns the work done.
    fn rasterize(
        &self,
        triangles: &[TriangleSetup],
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> WorkCounters {
        self.rasterize_selection(TriangleSelection::all(triangles), viewport, sink)
    }
}

/// The triangles a back-end is asked to draw: all of a slice, or those at
/// some indices of it (a bin), in the order given.
#[derive(Copy, Clone, Debug)]
pub struct TriangleSelection<'a> {
    setups: &'a [TriangleSetup],
    indices: Option<&'a [u32]>,
}

impl<'a> TriangleSelection<'a> {
    /// Every triangle of `setups`.
    pub fn all(setups: &'a [TriangleSetup]) -> Self {
        TriangleSelection {
            setups,
            indices: None,
        }
    }

    /// The triangles of `setups` at `indices`, in that order.
    pub fn indexed(setups: &'a [TriangleSetup], indices: &'a [u32]) -> Self {
        TriangleSelection {
            setups,
            indices: Some(indices),
        }
    }

    /// The number of triangles selected.
    pub fn len(&self) -> usize {
        self.indices.map_or(self.setups.len(), <[u32]>::len)
    }

    /// True when nothing is selected.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The selected triangles, in order.
    pub fn iter(&self) -> impl Iterator<Item = &'a TriangleSetup> + 'a {
        let (setups, indices) = (self.setups, self.indices);
        let all = indices.is_none().then(|| setups.iter());
        let some = indices.map(|i| i.iter().map(move |&i| &setups[i as usize]));
        all.into_iter().flatten().chain(some.into_iter().flatten())
    }
}

/// Emits one fragment (pixel indices already inside the viewport).
#[inline]
pub(crate) fn emit(
    sink: &mut dyn FragmentSink,
    triangle: &TriangleSetup,
    x: i64,
    y: i64,
    edges: [i64; 3],
) {
    sink.triangle_fragment(&TriangleFragment {
        x: x as u32,
        y: y as u32,
        triangle: triangle.id,
        edges,
    });
}

/// Emits pixels `x0..=x1` of row `y` (inside the viewport, `x0 <= x1`) as
/// one span, given the edge values `edges` at `x0`; a single pixel (most
/// rows of a small triangle) as a plain fragment, which costs the stage
/// less.
#[inline]
pub(crate) fn emit_span(
    sink: &mut dyn FragmentSink,
    triangle: &TriangleSetup,
    y: i64,
    x0: i64,
    x1: i64,
    edges: [i64; 3],
) {
    if x0 == x1 {
        emit(sink, triangle, x0, y, edges);
        return;
    }
    sink.triangle_span(&TriangleSpan {
        y: y as u32,
        x0: x0 as u32,
        x1: x1 as u32,
        triangle: triangle.id,
        edges,
        step: triangle.pixel_steps().0,
    });
}

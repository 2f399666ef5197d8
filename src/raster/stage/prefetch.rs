//! The stage's prefetch: asking for a triangle's data, and the pixels
//! under its next row, before its fragments come, so that a fragment's
//! depth test and shading do not wait for memory. A mesh's triangles are
//! small, and its vertices and pixels spread over tens of megabytes.

use super::FragmentStage;
use crate::raster::fragment::TriangleSpan;
use crate::raster::shader::FragmentShader;
use crate::raster::vector;

/// How many triangle ids ahead the stage prefetches a triangle's
/// vertices and first pixels (and, for a selection, twice as many ahead
/// the triangle's own stage data, which that prefetch reads).
const PREFETCH_AHEAD: usize = 8;

/// Rows of a triangle's box whose first pixel the stage prefetches.
const PREFETCH_ROWS: i64 = 3;

impl<S: FragmentShader + ?Sized> FragmentStage<'_, S> {
    /// When triangle `id` is not the one whose fragments came last: asks
    /// for the vertices, and the first depth and colour, of the triangle
    /// [`PREFETCH_AHEAD`] ids further on, so that they are in the cache
    /// when its fragments come (each fragment's depth test and shading
    /// otherwise waits for memory: a mesh's triangles are small, and its
    /// vertices and pixels spread over tens of megabytes). With a
    /// selection (a band's triangles), also the stage data of the triangle
    /// twice as far on, which the hardware, following ids with gaps, does
    /// not bring in itself.
    #[inline(always)]
    pub(super) fn prefetch_ahead(&mut self, id: u32) {
        if id == self.current {
            return;
        }
        self.current = id;
        let ahead = if self.selection.is_empty() {
            id as usize + PREFETCH_AHEAD
        } else {
            // Ids come in ascending order: the position only moves on.
            while self.selection.get(self.position).is_some_and(|&s| s < id) {
                self.position += 1;
            }
            // The stage data of a triangle further on, read (for its
            // vertices) when it comes [`PREFETCH_AHEAD`] ids ahead: the
            // selection's ids have gaps the hardware does not follow.
            let further = self.selection.get(self.position + 2 * PREFETCH_AHEAD);
            if let Some(t) = further.and_then(|&f| self.triangles.get(f as usize)) {
                vector::prefetch_all(t);
            }
            match self.selection.get(self.position + PREFETCH_AHEAD) {
                Some(&ahead) => ahead as usize,
                None => return,
            }
        };
        let Some(t) = self.triangles.get(ahead) else {
            return;
        };
        for &v in &t.vertices {
            if let Some(v) = self.vertices.get(v as usize) {
                vector::prefetch(v);
            }
        }
        let (x, y) = (i64::from(t.depth.origin_x), i64::from(t.depth.origin_y));
        let rect = self.target.rect();
        for y in y..y + PREFETCH_ROWS {
            if rect.contains(x, y) {
                let idx = self.target.index(x as u32, y as u32);
                vector::prefetch(&self.target.depth[idx]);
                vector::prefetch(&self.target.color[idx]);
            }
        }
    }

    /// Asks for the depths and colours under the ends of `span` one row
    /// down, where the back-ends that walk a triangle row by row send its
    /// next span: a span's first depth test otherwise waits for memory.
    #[inline(always)]
    pub(super) fn prefetch_next_row(&self, span: &TriangleSpan) {
        let y = i64::from(span.y) + 1;
        if self.target.rect().contains(i64::from(span.x0), y) {
            for x in [span.x0, span.x1] {
                let idx = self.target.index(x, y as u32);
                vector::prefetch(&self.target.depth[idx]);
                vector::prefetch(&self.target.color[idx]);
            }
        }
    }
}

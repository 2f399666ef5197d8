//! The pipeline's result: set-up triangles for a back-end and their data
//! for the fragment stage, joined from the parts the pipeline's tasks
//! assembled in parallel.
//!
//! [`Geometry`] has one layout: triangle `i` is `setups[i]`, its stage data
//! `shaded.triangles[i]`, its source primitive `source[i]`. A renderer on
//! several threads skips the joining: [`GeometryInParts`] leaves the
//! triangles in their parts, which a binned draw reads one after the other.

use super::bands::Bands;
use super::setup::{GeometryStats, Part, ScreenPoint};
use super::Viewport;
use crate::raster::edge::TriangleSetup;
use crate::raster::primitive::{ShadedTriangle, ShadedVertex, TriangleData};
use crate::raster::vector;
use rayon::prelude::*;

/// Triangles ready for a back-end, and their data for the fragment stage.
///
/// A `Geometry` can be filled again and again by [`process_triangles_into`](super::process_triangles_into)
/// (one frame after the other): its buffers keep their memory, so a frame
/// costs no allocation once the first is done.
#[derive(Clone, Debug, Default)]
pub struct Geometry {
    /// Set-up triangles; triangle `i` has id `i`.
    pub setups: Vec<TriangleSetup>,
    /// The fragment stage's data: the vertices, and for triangle id `i`
    /// its vertex indices and depth plane.
    pub shaded: TriangleData,
    /// The assembled primitive each triangle came from.
    pub source: Vec<u32>,
    /// Counts of what happened.
    pub stats: GeometryStats,
    /// Buffers kept from one draw to the next.
    pub(super) scratch: Scratch,
}

impl Geometry {
    /// A draw of screen-space triangles (2D input): `setups` (those of the
    /// `vertices.len()` triangles that are not degenerate) with their vertex
    /// data, `vertices[i]` for triangle id `i`, each its own source.
    pub fn of_screen_triangles(
        setups: Vec<TriangleSetup>,
        vertices: &[[ShadedVertex; 3]],
    ) -> Geometry {
        Geometry {
            shaded: TriangleData::of_triangles(&setups, vertices),
            source: (0..setups.len() as u32).collect(),
            stats: GeometryStats {
                primitives: vertices.len() as u64,
                degenerate: (vertices.len() - setups.len()) as u64,
                triangles: setups.len() as u64,
                ..GeometryStats::default()
            },
            setups,
            scratch: Scratch::default(),
        }
    }

    /// The triangles as a draw reads them: one run.
    pub(crate) fn runs(&self) -> Runs<'_> {
        Runs {
            shaded: &self.shaded,
            runs: vec![TriangleRun {
                setups: &self.setups,
                triangles: &self.shaded.triangles,
            }],
            bins: None,
        }
    }

    /// Empties the triangle arrays, keeping their memory.
    fn clear_triangles(&mut self) {
        self.setups.clear();
        self.shaded.triangles.clear();
        self.source.clear();
    }

    /// Gathers the parts into this geometry, one after the other, with
    /// triangle ids renumbered from 0 and clip vertices appended after the
    /// `mesh_vertices` shaded ones. Each part copies its triangles into its
    /// own range of the result, on rayon's threads. A single part is moved
    /// in without copying.
    pub(super) fn gather(&mut self, mesh_vertices: usize) {
        let mut parts = std::mem::take(&mut self.scratch.parts);
        self.gather_parts(&mut parts, mesh_vertices);
        self.scratch.parts = parts;
    }

    /// [`gather`](Self::gather) from `parts`, taken out of the scratch
    /// buffers while this geometry is written.
    fn gather_parts(&mut self, parts: &mut [Part], mesh_vertices: usize) {
        if let [part] = parts {
            std::mem::swap(&mut self.setups, &mut part.setups);
            std::mem::swap(&mut self.shaded.triangles, &mut part.triangles);
            std::mem::swap(&mut self.source, &mut part.source);
            self.shaded.vertices.extend_from_slice(&part.clip_vertices);
            return;
        }
        // A set-up and its stage triangle to size the arrays with.
        let filler = parts
            .iter()
            .find_map(|p| Some((*p.setups.first()?, *p.triangles.first()?)));
        let total = parts.iter().map(|p| p.setups.len()).sum();
        let Some((setup, triangle)) = filler else {
            self.clear_triangles();
            return;
        };
        // Sized without clearing: from one frame to the next the lengths
        // barely change, so the filler is written only past the old length.
        resize_keeping(&mut self.setups, total, setup);
        resize_keeping(&mut self.shaded.triangles, total, triangle);
        resize_keeping(&mut self.source, total, 0);
        // Each part's range of the three arrays, its first id, and where
        // its clip vertices start.
        let mut ranges = Vec::with_capacity(parts.len());
        let (mut setups, mut triangles, mut source) = (
            &mut self.setups[..],
            &mut self.shaded.triangles[..],
            &mut self.source[..],
        );
        let (mut id, mut clip_start) = (0u32, mesh_vertices as u32);
        for p in parts.iter() {
            let n = p.setups.len();
            let (s, rest_s) = std::mem::take(&mut setups).split_at_mut(n);
            let (t, rest_t) = std::mem::take(&mut triangles).split_at_mut(n);
            let (o, rest_o) = std::mem::take(&mut source).split_at_mut(n);
            (setups, triangles, source) = (rest_s, rest_t, rest_o);
            ranges.push((s, t, o, id, clip_start));
            id += n as u32;
            clip_start += p.clip_vertices.len() as u32;
            self.shaded.vertices.extend_from_slice(&p.clip_vertices);
        }
        let n = mesh_vertices as u32;
        parts.par_iter().zip(ranges).for_each(
            |(p, (setups, triangles, source, first_id, clip_start))| {
                for (k, (d, s)) in setups.iter_mut().zip(&p.setups).enumerate() {
                    *d = TriangleSetup {
                        id: first_id + k as u32,
                        ..*s
                    };
                }
                for (d, t) in triangles.iter_mut().zip(&p.triangles) {
                    *d = ShadedTriangle {
                        vertices: t.vertices.map(|v| index_in_draw(v, n, clip_start)),
                        ..*t
                    };
                }
                source.copy_from_slice(&p.source);
            },
        );
    }
}

/// A part's vertex index `v` in the draw of `n` mesh vertices: those keep
/// their index; the part's clip vertices, numbered from `n` in the part,
/// start at `clip_start` in the draw.
#[inline]
pub(super) fn index_in_draw(v: u32, n: u32, clip_start: u32) -> u32 {
    if v < n {
        v
    } else {
        v - n + clip_start
    }
}

/// Sets the length of `v` to `len`, writing `filler` only into the
/// entries past its old length (which the caller then overwrites).
fn resize_keeping<T: Copy>(v: &mut Vec<T>, len: usize, filler: T) {
    v.truncate(len);
    vector::reserve_in_huge_pages(v, len - v.len());
    v.resize(len, filler);
}

/// A geometry whose triangles stay in the parts the pipeline's tasks
/// assembled, one run per part, instead of being copied into one array
/// (what a renderer drawing band by band on several threads uses). The
/// image drawn from it is the same as from the [`Geometry`] of the same
/// draw.
#[derive(Clone, Debug, Default)]
pub(crate) struct GeometryInParts {
    /// The stage's vertices (the triangles are in the parts).
    pub(super) shaded: TriangleData,
    /// Counts of what happened.
    pub stats: GeometryStats,
    /// The parts, and the buffers kept from one draw to the next.
    pub(super) scratch: Scratch,
    /// When the parts binned their triangles: the bands, and the viewport
    /// they cut.
    pub(super) binned: Option<(Bands, Viewport)>,
}

impl GeometryInParts {
    /// Leaves several parts where they are, for a draw that reads them as
    /// runs: only their clip vertices are appended after the
    /// `mesh_vertices` shaded ones, and the parts' references to them
    /// renumbered. Saves the copy of [`Geometry::gather`]. The parts
    /// binned their triangles into bands of `band_rows` rows of `viewport`.
    pub(super) fn keep_in_parts(
        &mut self,
        mesh_vertices: usize,
        binned: Option<(Bands, Viewport)>,
    ) {
        let n = mesh_vertices as u32;
        let parts = &mut self.scratch.parts;
        for p in parts.iter_mut() {
            if !p.clip_vertices.is_empty() {
                let clip_start = self.shaded.vertices.len() as u32;
                for t in &mut p.triangles {
                    t.vertices = t.vertices.map(|v| index_in_draw(v, n, clip_start));
                }
                self.shaded.vertices.extend_from_slice(&p.clip_vertices);
            }
        }
        self.binned = binned;
    }

    /// The triangles as a draw reads them: one run per part, with the
    /// parts' bins when they binned them.
    pub(crate) fn runs(&self) -> Runs<'_> {
        let parts = &self.scratch.parts;
        Runs {
            shaded: &self.shaded,
            runs: parts
                .iter()
                .map(|p| TriangleRun {
                    setups: &p.setups,
                    triangles: &p.triangles,
                })
                .collect(),
            bins: self.binned.map(|(bands, viewport)| PartBins {
                bands,
                viewport,
                per_run: parts.iter().map(|p| &p.bins[..]).collect(),
            }),
        }
    }
}

/// The working buffers of [`process_triangles_into`](super::process_triangles_into).
#[derive(Clone, Debug, Default)]
pub(super) struct Scratch {
    /// Per vertex: its snapped screen position and clip out-code.
    pub(super) screen: Vec<ScreenPoint>,
    /// What each task made of its chunk of the triangles.
    pub(super) parts: Vec<Part>,
    /// Parts a draw with fewer chunks did not use, kept with their memory
    /// for the next draw with more ([`use_parts`](Self::use_parts)).
    spare: Vec<Part>,
}

impl Scratch {
    /// Gives the scratch `count` parts. Parts it no longer needs are kept
    /// aside, not dropped, and come back first when a draw needs more: a
    /// renderer drawn on one thread and then on two (one part, then 64)
    /// would otherwise free 63 parts' set-ups, bins and stage triangles
    /// and grow new ones from empty, on fresh pages, at every change.
    pub(super) fn use_parts(&mut self, count: usize) {
        if self.parts.len() > count {
            self.spare.extend(self.parts.drain(count..));
        }
        while self.parts.len() < count {
            self.parts.push(self.spare.pop().unwrap_or_default());
        }
    }
}

/// A run of set-up triangles and their stage data: the set-up with id `i`
/// in the run belongs to `triangles[i]`.
#[derive(Copy, Clone, Debug)]
pub(crate) struct TriangleRun<'a> {
    pub setups: &'a [TriangleSetup],
    pub triangles: &'a [ShadedTriangle],
}

/// What a draw reads: the stage's vertices, the triangles in runs in id
/// order (one for a [`Geometry`], one per part for a geometry left in its
/// parts), and the parts' bins when they binned their triangles.
pub(crate) struct Runs<'a> {
    pub shaded: &'a TriangleData,
    pub runs: Vec<TriangleRun<'a>>,
    /// The parts' bins, when they binned their triangles.
    pub bins: Option<PartBins<'a>>,
}

/// The bins the pipeline's parts filled as they kept their triangles.
pub(crate) struct PartBins<'a> {
    /// The bands they binned into.
    pub bands: Bands,
    /// The viewport the bands cut.
    pub viewport: Viewport,
    /// Per run, per band, the indices of the run's triangles meeting it.
    pub per_run: Vec<&'a [Vec<u32>]>,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Parts a draw with fewer chunks leaves are kept with their memory and
    /// come back to the next draw with more, emptied by it as any part is.
    #[test]
    fn parts_left_unused_come_back_with_their_memory() {
        let mut scratch = Scratch::default();
        scratch.use_parts(3);
        for (i, part) in scratch.parts.iter_mut().enumerate() {
            part.source.reserve_exact(1000 * (i + 1));
        }
        let capacities = |s: &Scratch| {
            let mut c: Vec<usize> = s.parts.iter().map(|p| p.source.capacity()).collect();
            c.sort_unstable();
            c
        };
        let before = capacities(&scratch);
        scratch.use_parts(1);
        assert_eq!(scratch.parts.len(), 1);
        assert_eq!(scratch.parts[0].source.capacity(), before[0]);
        scratch.use_parts(3);
        assert_eq!(capacities(&scratch), before);
        scratch.use_parts(4);
        assert_eq!(scratch.parts.len(), 4);
        assert_eq!(scratch.parts[3].source.capacity(), 0);
    }
}

//! Per assembled triangle: clipping against the clip volume, the divide
//! and viewport transform of the cut polygon, back-face culling, and the
//! set-up (the course's step 3, after the vertex shader). Each task of the
//! pipeline does this for a chunk of the triangles into its own [`Part`].

use super::bands::Bands;
use super::clip::{ClipResult, ClipVertex, ClipVolume};
use super::vertex::VertexShader;
use super::viewport::to_screen_vertex;
use super::{CullMode, FrontFace, PipelineOptions, Viewport};
use crate::error::Result;
use crate::raster::compact::SmallTriangle;
use crate::raster::edge::{PixelRect, TriangleSetup};
use crate::raster::fixed::FixedPoint;
use crate::raster::primitive::{DepthPlane, ShadedTriangle, ShadedVertex};
use crate::raster::vector::{
    self,
    triangles::{self, Corners, Rules},
};

/// What happened to the primitives of a draw.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct GeometryStats {
    /// Triangles assembled.
    pub primitives: u64,
    /// Of those, entirely outside the clip volume.
    pub rejected: u64,
    /// Of those, cut by a clip plane (each may give several triangles).
    pub clipped: u64,
    /// Triangles removed by back-face culling.
    pub culled: u64,
    /// Triangles of zero area after snapping.
    pub degenerate: u64,
    /// Cut triangles dropped because their coordinates span more orders of
    /// magnitude than `f64` can intersect exactly enough (e.g. 1e30 and 1e-5).
    pub unresolvable: u64,
    /// Triangles whose bounding box holds no pixel centre of the viewport
    /// (too small to cover a sample, or off-screen): dropped, as they
    /// could not produce a fragment.
    pub empty_bounds: u64,
    /// Triangles whose bounding box holds at most 2x2 pixel centres, none
    /// of them inside (tested in 32 bits, [`crate::raster::SmallTriangle`]):
    /// dropped before their set-up, as they could not produce a fragment.
    pub no_sample: u64,
    /// Triangles handed to the rasterizer.
    pub triangles: u64,
}

impl GeometryStats {
    /// Adds another set of counts to these.
    pub fn add(&mut self, other: &GeometryStats) {
        self.primitives += other.primitives;
        self.rejected += other.rejected;
        self.clipped += other.clipped;
        self.culled += other.culled;
        self.degenerate += other.degenerate;
        self.unresolvable += other.unresolvable;
        self.empty_bounds += other.empty_bounds;
        self.no_sample += other.no_sample;
        self.triangles += other.triangles;
    }
}

/// A vertex's place after the vertex shader: out-code, and when that is 0
/// (inside every clip plane) its snapped screen position and depth (kept
/// here too, so that assembly reads only these 16 bytes per vertex).
#[derive(Copy, Clone, Debug, Default, bytemuck::Zeroable)]
pub(super) struct ScreenPoint {
    pub(super) point: FixedPoint,
    pub(super) depth: f32,
    pub(super) outcode: u8,
}

/// What one task makes of a chunk of the triangles: set-ups with ids
/// counted from 0 in the chunk, the vertices made by clipping in a
/// list of their own (the k-th is vertex `n + k` of a draw of `n`
/// vertices), and, when binning, per band the ids of the triangles whose
/// bounds meet it.
#[derive(Clone, Debug, Default)]
pub(super) struct Part {
    pub(super) setups: Vec<TriangleSetup>,
    pub(super) triangles: Vec<ShadedTriangle>,
    pub(super) source: Vec<u32>,
    pub(super) clip_vertices: Vec<ShadedVertex>,
    pub(super) stats: GeometryStats,
    /// The bands it bins into, if any.
    bands: Option<Bands>,
    /// Per band, the ids of the triangles meeting it.
    pub(super) bins: Vec<Vec<u32>>,
}

impl Part {
    /// Empties the part, keeping its memory, to bin what it keeps into
    /// `bands` (none: no binning).
    pub(super) fn clear(&mut self, bands: Option<Bands>) {
        self.setups.clear();
        self.triangles.clear();
        self.source.clear();
        self.clip_vertices.clear();
        self.stats = GeometryStats::default();
        self.bands = bands;
        let count = bands.map_or(0, Bands::count);
        self.bins.truncate(count);
        self.bins.iter_mut().for_each(Vec::clear);
        self.bins.resize_with(count, Vec::new);
    }

    /// Keeps the triangle with these vertices (indices, snapped positions
    /// and depths) and sets it up, unless it is degenerate, of a winding
    /// other than `winding` (when given), culled, without a pixel sample
    /// of the viewport in its bounding box, or small (at most 2x2 samples
    /// in its box) and without a sample inside.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn push(
        &mut self,
        vertices: [u32; 3],
        points: [FixedPoint; 3],
        depths: [f32; 3],
        source: u32,
        winding: Option<i8>,
        options: &PipelineOptions,
        viewport: PixelRect,
    ) {
        let signed_area = TriangleSetup::signed_area(points);
        let this_winding = signed_area.signum() as i8;
        if signed_area == 0 || winding.is_some_and(|w| w != this_winding) {
            self.stats.degenerate += 1;
            return;
        }
        let facing_viewer =
            (this_winding > 0) == (options.front_face == FrontFace::CounterClockwise);
        let culled = match options.cull {
            CullMode::None => false,
            CullMode::Back => !facing_viewer,
            CullMode::Front => facing_viewer,
        };
        if culled {
            self.stats.culled += 1;
            return;
        }
        let mut whole = TriangleSetup::sample_bounds(points);
        if options.multisample {
            // A sample lies within half a pixel of its centre.
            whole = PixelRect {
                x0: whole.x0 - 1,
                y0: whole.y0 - 1,
                x1: whole.x1 + 1,
                y1: whole.y1 + 1,
            };
        }
        let bounds = whole.intersect(viewport);
        if bounds.is_empty() {
            self.stats.empty_bounds += 1;
            return;
        }
        if options.multisample {
            self.keep(vertices, points, depths, source, bounds, options);
            return;
        }
        // Most triangles of a dense mesh have a box of one to four pixel
        // centres; many of them cover none. Those are found in 32 bits
        // and dropped here, before the set-up is computed and stored.
        if whole.x1 - whole.x0 <= 1 && whole.y1 - whole.y0 <= 1 {
            let origin = SmallTriangle::first_sample_of(bounds);
            let small = SmallTriangle::around(points, origin, signed_area);
            if small.is_some_and(|s| !s.may_cover_a_sample(bounds)) {
                self.stats.no_sample += 1;
                return;
            }
        }
        self.keep(vertices, points, depths, source, bounds, options);
    }

    /// Sets up and keeps a triangle that passed [`push`](Self::push)'s
    /// tests (its area is not zero, it is not culled, and a pixel of
    /// `bounds`, its box within the viewport, may be covered).
    #[inline(always)]
    fn keep(
        &mut self,
        vertices: [u32; 3],
        points: [FixedPoint; 3],
        depths: [f32; 3],
        source: u32,
        bounds: PixelRect,
        options: &PipelineOptions,
    ) {
        let id = self.keep_without_depth(vertices, points, source, bounds, options);
        self.set_depth_plane(id, depths);
    }

    /// [`keep`](Self::keep), but the triangle's depth plane is left
    /// unset, for the caller to set with
    /// [`set_depth_plane`](Self::set_depth_plane); returns its id.
    #[inline(always)]
    fn keep_without_depth(
        &mut self,
        vertices: [u32; 3],
        points: [FixedPoint; 3],
        source: u32,
        bounds: PixelRect,
        options: &PipelineOptions,
    ) -> u32 {
        let id = self.setups.len() as u32;
        if let Some(bands) = self.bands {
            bands.bin(&mut self.bins, bounds, id);
        }
        let Some(setup) = TriangleSetup::new(id, points, options.rule) else {
            unreachable!("the area was checked to be non-zero");
        };
        self.triangles.push(ShadedTriangle {
            vertices,
            depth: DepthPlane::constant(0.0),
        });
        self.setups.push(setup);
        self.source.push(source);
        self.stats.triangles += 1;
        id
    }

    /// Sets the depth plane of kept triangle `id`, whose vertices are at
    /// depths `depths`.
    #[inline(always)]
    fn set_depth_plane(&mut self, id: u32, depths: [f32; 3]) {
        let id = id as usize;
        self.triangles[id].depth = DepthPlane::new(&self.setups[id], depths);
    }
}

/// Triangles assembled per task, at least.
pub(super) const MIN_TRIANGLE_CHUNK: usize = 4096;

/// Chunks of triangles per thread. The cost of a triangle varies along a
/// mesh (culled runs are cheap, kept runs are set up), so a few large
/// chunks leave one thread waiting while the other assembles its last
/// one (docs/performance-log.md, "2026-12-06, `f354b8e` to `b4efcdc`").
pub(super) const TRIANGLE_CHUNKS_PER_THREAD: usize = 32;

/// Chunks of at least this many triangles reserve room for all of them
/// before assembly. A first frame's buffers are fresh memory, which the
/// kernel hands out in 2 MB pages, zeroed when first written. A large
/// chunk's set-ups grown by doubling are copied, and fault in twice what
/// they keep; reserved, only the pages written are faulted in. A small
/// chunk keeps a fraction of its reservation (a fifth of the full
/// dragon's triangles are rasterized) but faults in a whole 2 MB page for
/// it: a first frame's geometry was faster reserved on one thread (one
/// chunk) and faster grown on two (64 chunks; docs/performance-log.md,
/// "2026-12-06, `f354b8e` to `b4efcdc`").
const RESERVE_MIN_CHUNK: usize = 1 << 16;

/// The shaded vertices of a draw, shared by the tasks that assemble its
/// triangles.
pub(super) struct AssemblyInput<'a, V, S> {
    /// The draw's vertices and vertex shader, to shade again the corners
    /// of the (few) triangles that must be clipped.
    pub(super) vertices: &'a [V],
    pub(super) shader: &'a S,
    pub(super) screen: &'a [ScreenPoint],
    /// The number of vertices of the draw: vertices made by clipping are
    /// numbered after them.
    pub(super) mesh_vertices: u32,
    pub(super) clip: &'a ClipVolume,
    pub(super) viewport: &'a Viewport,
    pub(super) options: &'a PipelineOptions,
    /// The bands the parts bin what they keep into, if any.
    pub(super) bands: Option<Bands>,
}

impl<V, S: VertexShader<V>> AssemblyInput<'_, V, S> {
    /// Assembles, clips, culls and sets up `triangles`, the first of which
    /// is primitive number `first` of the draw, into `part`.
    ///
    /// The loop is compiled for the baseline and for AVX2, and the copy the
    /// CPU runs is picked at run time (the same bits either way).
    pub(super) fn process(&self, triangles: &[[u32; 3]], first: usize, part: &mut Part) {
        part.clear(self.bands);
        if triangles.len() >= RESERVE_MIN_CHUNK {
            vector::reserve_in_huge_pages(&mut part.setups, triangles.len());
            vector::reserve_in_huge_pages(&mut part.triangles, triangles.len());
            vector::reserve_in_huge_pages(&mut part.source, triangles.len());
        }
        let assemble = Assemble {
            input: self,
            triangles,
            first,
            part,
        };
        vector::run(assemble);
    }

    /// Assembles triangle `t`, primitive number `source`, whose corners
    /// are at `screen`, into `part`: sets it up when it lies inside the
    /// clip volume (whose `pixels` are the viewport's), rejects it when
    /// outside one plane, clips it otherwise.
    #[inline(always)]
    fn assemble_one(
        &self,
        t: &[u32; 3],
        screen: [ScreenPoint; 3],
        source: usize,
        pixels: PixelRect,
        part: &mut Part,
        polygon: &mut Vec<ClipVertex>,
    ) {
        let source = source as u32;
        let codes = screen.map(|s| s.outcode);
        if codes == [0; 3] {
            part.push(
                *t,
                screen.map(|s| s.point),
                screen.map(|s| s.depth),
                source,
                None,
                self.options,
                pixels,
            );
        } else if codes[0] & codes[1] & codes[2] != 0 {
            part.stats.rejected += 1;
        } else {
            self.clip_and_push(*t, codes, source, part, polygon);
        }
    }

    /// Clips triangle `t` (primitive number `source`), which straddles a
    /// clip plane, and sets up the fan of what is left into `part`.
    #[inline(never)]
    fn clip_and_push(
        &self,
        t: [u32; 3],
        codes: [u8; 3],
        source: u32,
        part: &mut Part,
        polygon: &mut Vec<ClipVertex>,
    ) {
        let (viewport, options) = (self.viewport, self.options);
        let pixels = PixelRect::of_target(viewport.width, viewport.height);
        let corners = t.map(|i| self.shader.shade(&self.vertices[i as usize]));
        let ClipResult::Cut(_) = self.clip.clip_triangle(&corners, codes, polygon) else {
            unreachable!("the out-codes say the triangle straddles a plane");
        };
        part.stats.clipped += 1;
        // A cut vertex can miss its plane when the triangle's
        // coordinates differ by more than f64 resolves (say 1e30
        // next to 1e-5); such a polygon is dropped, never drawn wrong.
        let Ok(screen) = polygon
            .iter()
            .map(|v| to_screen_vertex(viewport, v))
            .collect::<Result<Vec<(FixedPoint, ShadedVertex)>>>()
        else {
            part.stats.unresolvable += 1;
            return;
        };
        let base = self.mesh_vertices + part.clip_vertices.len() as u32;
        part.clip_vertices.extend(screen.iter().map(|(_, v)| *v));
        // The fan of a convex polygon keeps one winding. Cut points
        // that are nearly collinear can snap into a sliver of the
        // opposite winding, which would overlap its neighbour; the
        // polygon's winding (the sign of its area, the sum of its fan
        // triangles' signed areas) decides which slivers are dropped.
        let fan: Vec<[usize; 3]> = (1..screen.len().saturating_sub(1))
            .map(|i| [0, i, i + 1])
            .collect();
        let twice_area: i64 = fan
            .iter()
            .map(|f| TriangleSetup::signed_area(f.map(|k| screen[k].0)))
            .sum();
        let winding = if twice_area < 0 { -1 } else { 1 };
        for f in fan {
            part.push(
                f.map(|k| base + k as u32),
                f.map(|k| screen[k].0),
                f.map(|k| screen[k].1.depth),
                source,
                Some(winding),
                options,
                pixels,
            );
        }
    }
}

/// One task's triangles, to assemble into its part: the loop
/// [`AssemblyInput::process`] compiles twice.
struct Assemble<'i, 'a, V, S> {
    input: &'i AssemblyInput<'a, V, S>,
    triangles: &'i [[u32; 3]],
    first: usize,
    part: &'i mut Part,
}

impl<V, S: VertexShader<V>> vector::Kernel for Assemble<'_, '_, V, S> {
    type Output = ();

    /// Triangles wholly inside the clip volume (nearly all) are set up
    /// here; those outside every point of one plane are rejected; the
    /// rest are clipped out of line. Eight at a time, the first tests of
    /// the set-up (area, culling, bounds, small and covering no sample)
    /// run on vectors ([`triangles::classify`]) and drop most triangles of
    /// a mesh; those they keep are set up one at a time, without being
    /// tested again. When the CPU has no AVX2, every triangle is tested
    /// and set up one at a time.
    #[inline(always)]
    fn run(self) {
        let Assemble {
            input,
            triangles,
            first,
            part,
        } = self;
        let options = input.options;
        let (width, height) = (input.viewport.width, input.viewport.height);
        let pixels = PixelRect::of_target(width, height);
        let counter_clockwise = options.front_face == FrontFace::CounterClockwise;
        let rules = Rules {
            culled_positive: match options.cull {
                CullMode::None => None,
                CullMode::Back => Some(!counter_clockwise),
                CullMode::Front => Some(counter_clockwise),
            },
            last: [width as i32 - 1, height as i32 - 1],
        };
        let mut polygon = Vec::new();
        let corners_of = |t: &[u32; 3]| t.map(|i| input.screen[i as usize]);
        let mut groups = triangles.chunks_exact(8);
        let mut source = first;
        for group in &mut groups {
            let mut corners = Corners::default();
            let mut inside = 0u8;
            for (i, t) in group.iter().enumerate() {
                let mut codes = 0;
                for (k, &v) in t.iter().enumerate() {
                    let s = &input.screen[v as usize];
                    corners.x[k][i] = s.point.x.raw() as i32;
                    corners.y[k][i] = s.point.y.raw() as i32;
                    codes |= s.outcode;
                }
                inside |= u8::from(codes == 0) << i;
            }
            part.stats.primitives += 8;
            // What `push` would have counted, for the triangles inside
            // the clip volume that the vector tests drop.
            // The vector tests drop what covers no pixel centre: not
            // for a multisampled draw.
            let lanes = (!options.multisample).then(|| triangles::classify(&rules, &corners));
            let Some(dropped) = lanes.flatten() else {
                for (i, t) in group.iter().enumerate() {
                    input.assemble_one(t, corners_of(t), source + i, pixels, part, &mut polygon);
                }
                source += 8;
                continue;
            };
            let stats = &mut part.stats;
            stats.degenerate += u64::from((dropped.degenerate & inside).count_ones());
            stats.culled += u64::from((dropped.culled & inside).count_ones());
            stats.empty_bounds += u64::from((dropped.empty_bounds & inside).count_ones());
            stats.no_sample += u64::from((dropped.no_sample & inside).count_ones());
            let gone =
                (dropped.degenerate | dropped.culled | dropped.empty_bounds | dropped.no_sample)
                    & inside;
            // In order: the triangles inside that passed are set up
            // without being tested again; the others are rejected or
            // clipped. The depth planes of those set up here come after,
            // in a loop of their own: each is a chain of conversions and
            // divisions, which the CPU then runs side by side.
            let mut left = !gone;
            let mut planes = [(0u32, [0.0f32; 3]); 8];
            let mut kept = 0;
            while left != 0 {
                let i = left.trailing_zeros() as usize;
                left &= left - 1;
                let t = &group[i];
                let screen = corners_of(t);
                if inside & (1 << i) != 0 {
                    let points = screen.map(|s| s.point);
                    let bounds = TriangleSetup::sample_bounds(points).intersect(pixels);
                    let source = (source + i) as u32;
                    let id = part.keep_without_depth(*t, points, source, bounds, options);
                    planes[kept] = (id, screen.map(|s| s.depth));
                    kept += 1;
                } else {
                    input.assemble_one(t, screen, source + i, pixels, part, &mut polygon);
                }
            }
            for &(id, depths) in &planes[..kept] {
                part.set_depth_plane(id, depths);
            }
            source += 8;
        }
        for t in groups.remainder() {
            part.stats.primitives += 1;
            input.assemble_one(t, corners_of(t), source, pixels, part, &mut polygon);
            source += 1;
        }
    }
}

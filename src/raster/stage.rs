//! The shared fragment stage: every back-end's fragments end here.
//!
//! For each fragment the stage does, in this order (the rasterization slides, the software-rasterizer article):
//!
//! 0. **load**: when the draw clears the target as it goes (a render
//!    pass's load op, [`Clear`](crate::raster::target::Clear)), the
//!    fragment's row is cleared first if no fragment has reached it yet;
//! 1. **coverage count**: the pixel's count in the coverage buffer goes up
//!    by one, before any test, so double draws and gaps can be analysed (a
//!    target made [`without_coverage`](RenderTarget::without_coverage)
//!    skips this step and nothing else);
//! 2. **depth**, linear in screen space: the plane through the three
//!    snapped vertices, `z = z0 + beta (z1 - z0) + gamma (z2 - z0)`, set up
//!    once per triangle as a [`DepthPlane`] and evaluated at the pixel centre
//!    in `f32` in one fixed order (so a back-end that writes whole spans gets
//!    the very same bits, and a constant depth stays exactly constant);
//! 3. **depth test** against the depth buffer (`less` by default); a
//!    fragment that fails costs nothing more;
//! 4. **barycentrics** from the exact edge values: `alpha = E0 / area`,
//!    `beta = E1 / area`, `gamma = E2 / area` with `area = E0 + E1 + E2`
//!    (exact in integers, so nothing from the back-end but the pixel and its
//!    edge values is used);
//! 5. **varyings** (colour, UV, normal), perspective-correct by default:
//!    interpolate `a / w` and `1 / w`, divide per fragment (the software-rasterizer article); or
//!    plain linear, to show the difference;
//! 6. the **fragment shader** computes the colour;
//! 7. **colour write** (blended by the fragment's coverage for anti-aliased
//!    lines) and **depth write** when enabled.
//!
//! For a shader whose colour is uniform over a triangle, a whole span goes
//! through steps 1, 2, 3 and 7 in one loop, written once as plain Rust and
//! compiled both for the baseline vectors and for AVX2, the copy picked at
//! run time (the `raster::vector` module); both give the same bits. Any
//! other shader's spans of six pixels or more go through all seven steps
//! eight pixels at a time ([`FragmentShader::shade_lanes`], the
//! `shaded_span` submodule), again the same bits as one at a time.
//!
//! Because every step is a pure function of the fragment's pixel and
//! integer edge values, back-ends that emit the same fragments in the same
//! per-pixel order produce bit-identical colour, depth and coverage buffers.

use crate::raster::edge::PixelRect;
use crate::raster::fragment::{FragmentSink, LineFragment, TriangleFragment, TriangleSpan};
use crate::raster::primitive::{
    DepthPlane, ShadedLine, ShadedTriangle, ShadedVertex, TriangleData, Varyings,
};
use crate::raster::shader::{from_rgba8, to_rgba8, FragmentInput, FragmentShader};
use crate::raster::target::{DepthState, DepthTest, RenderTarget, TargetRows};
use crate::raster::vector;
use glam::Vec4;
use shaded_span::ShadedSpan;

mod shaded_span;

/// How many triangle ids ahead the stage prefetches a triangle's
/// vertices and first pixels (and, for a selection, twice as many ahead
/// the triangle's own stage data, which that prefetch reads).
const PREFETCH_AHEAD: usize = 8;

/// Rows of a triangle's box whose first pixel the stage prefetches.
const PREFETCH_ROWS: i64 = 3;

/// The shortest span whose fragments a shader that is not uniform per
/// primitive shades eight at a time ([`ShadedSpan`]); shorter spans go
/// fragment by fragment. Both give the same bits. Spans of four and five
/// pixels went faster one by one (`render --threads 1 --azimuth 30
/// --shading gouraud --backend scanline`, three pairs alternated): the
/// full dragon zoomed 2.5x, raster 43.3-45.4 ms with 4, 41.8-43.3 with 6;
/// the bundled dragon 4.71-4.84 and 4.59-4.67 ms. From 2 or 3 it was
/// slower still (53 and 47.5 ms zoomed).
const SHADED_SPAN_MIN: u32 = 6;

/// How varyings are interpolated across a primitive.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Interpolation {
    /// Interpolate `a / w` and `1 / w` linearly, divide per fragment.
    #[default]
    PerspectiveCorrect,
    /// Interpolate `a` linearly in screen space (wrong under perspective).
    Linear,
}

/// The shared fragment stage: a [`FragmentSink`] that depth-tests, shades
/// and writes fragments into a [`RenderTarget`].
///
/// The stage is compiled for the type of its shader `S`: given a shader
/// of a known type (say `&Gouraud`), its `shade` is compiled into the
/// stage's per-fragment code; given a `&dyn FragmentShader` (the default
/// type), each fragment calls it through the pointer. Both give the same
/// bits. On the full dragon with Gouraud shading the known type took the
/// raster part of a frame from 19.0 to 16.1 ms, and zoomed 2.5x from 72.0
/// to 59.2 ms: the call passed the fragment's inputs and its colour
/// through memory, on the chain of work every fragment waits on.
pub struct FragmentStage<'a, S: FragmentShader + ?Sized = dyn FragmentShader> {
    target: TargetRows<'a>,
    shader: &'a S,
    triangles: &'a [ShadedTriangle],
    vertices: &'a [ShadedVertex],
    lines: &'a [ShadedLine],
    /// Depth comparison and write mask.
    pub depth: DepthState,
    /// How varyings are interpolated.
    pub interpolation: Interpolation,
    /// Added to every line fragment's depth, so a wireframe drawn over its
    /// own surface with `less-equal` wins (negative values pull it nearer).
    pub line_depth_offset: f32,
    /// For a shader whose colour is uniform per primitive: the last
    /// triangle whose span was shaded, and its colour, so the next spans
    /// of the same triangle are not shaded again.
    span_colour: Option<(u32, [u8; 4])>,
    /// For a shader whose colour is uniform per primitive, drawing lines
    /// with the depth test off: the last line shaded, and its colour.
    /// (As RGBA8 too, what a fragment of full coverage writes.)
    line_colour: Option<(u32, Vec4, [u8; 4])>,
    /// The last triangle whose fragments arrived: when another begins, the
    /// data of one further ahead is prefetched.
    current: u32,
    /// When the triangles come as a selection (a band's), its ids in
    /// ascending order, and the position in it of the current triangle:
    /// the prefetch looks that far ahead in the selection, not in ids.
    selection: &'a [u32],
    position: usize,
}

impl<'a, S: FragmentShader + ?Sized> FragmentStage<'a, S> {
    /// A stage writing into `target` with `shader`, default depth state and
    /// perspective-correct interpolation, and no primitive data yet.
    pub fn new(target: &'a mut RenderTarget, shader: &'a S) -> Self {
        Self::on_rows(target.rows_mut(), shader)
    }

    /// A stage writing into some rows of a target only (one band of a
    /// binned draw); fragments must lie in those rows.
    pub fn on_rows(target: TargetRows<'a>, shader: &'a S) -> Self {
        FragmentStage {
            target,
            shader,
            triangles: &[],
            vertices: &[],
            lines: &[],
            depth: DepthState::DEFAULT,
            interpolation: Interpolation::PerspectiveCorrect,
            line_depth_offset: 0.0,
            span_colour: None,
            line_colour: None,
            current: u32::MAX,
            selection: &[],
            position: 0,
        }
    }

    /// Vertex data and depth planes of the triangles, indexed by triangle id.
    pub fn with_triangles(mut self, data: &'a TriangleData) -> Self {
        self.triangles = &data.triangles;
        self.vertices = &data.vertices;
        self.span_colour = None;
        self
    }

    /// Switches to another run of triangles over the same vertices: ids
    /// now index `triangles` (see [`crate::geometry::pipeline::Geometry`]).
    pub(crate) fn use_triangles(&mut self, triangles: &'a [ShadedTriangle]) {
        self.triangles = triangles;
        self.span_colour = None;
        self.selection = &[];
        self.current = u32::MAX;
    }

    /// Says that of the triangles in use only those with the ids of
    /// `selection` (ascending) will come, so that the stage prefetches
    /// the data of the selection's next ones.
    pub(crate) fn use_selection(&mut self, selection: &'a [u32]) {
        self.selection = selection;
        self.position = 0;
        self.current = u32::MAX;
    }

    /// Vertex data of the line segments, indexed by line id.
    pub fn with_lines(mut self, lines: &'a [ShadedLine]) -> Self {
        self.lines = lines;
        self.line_colour = None;
        self
    }

    /// Sets the depth state.
    pub fn with_depth(mut self, depth: DepthState) -> Self {
        self.depth = depth;
        self
    }

    /// Sets the interpolation mode.
    pub fn with_interpolation(mut self, interpolation: Interpolation) -> Self {
        self.interpolation = interpolation;
        self
    }

    /// Ends the draw: rows the stage was to clear on their first write
    /// and never wrote are cleared now (see [`Clear`](crate::raster::target::Clear)).
    pub(crate) fn finish(mut self) {
        self.target.finish();
    }

    /// Ends a batch of the draw: gives back the rows, for a stage of the
    /// next batch ([`TargetRows::lend`]).
    pub(crate) fn into_rows(self) -> TargetRows<'a> {
        self.target
    }

    /// The pixels this stage writes, in target coordinates.
    pub fn rect(&self) -> PixelRect {
        self.target.rect()
    }

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
    fn prefetch_ahead(&mut self, id: u32) {
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
    fn prefetch_next_row(&self, span: &TriangleSpan) {
        let y = i64::from(span.y) + 1;
        if self.target.rect().contains(i64::from(span.x0), y) {
            for x in [span.x0, span.x1] {
                let idx = self.target.index(x, y as u32);
                vector::prefetch(&self.target.depth[idx]);
                vector::prefetch(&self.target.color[idx]);
            }
        }
    }

    /// Triangle `id`'s stage data.
    #[inline]
    fn triangle(&self, id: u32) -> Option<&'a ShadedTriangle> {
        let t = self.triangles.get(id as usize);
        debug_assert!(t.is_some(), "no vertex data for triangle {id}");
        t
    }

    /// The three vertices of `t`.
    #[inline]
    fn vertices_of(&self, t: &ShadedTriangle) -> Option<[ShadedVertex; 3]> {
        Some(self.vertex_refs(t)?.map(|v| *v))
    }

    /// The three vertices of `t`, where they lie (so that a loop over a
    /// span can read them for each fragment without holding copies).
    #[inline]
    fn vertex_refs(&self, t: &ShadedTriangle) -> Option<[&'a ShadedVertex; 3]> {
        let vertices: &'a [ShadedVertex] = self.vertices;
        let [a, b, c] = t.vertices.map(|i| vertices.get(i as usize));
        debug_assert!(
            a.is_some() && b.is_some() && c.is_some(),
            "vertex index out of range"
        );
        Some([a?, b?, c?])
    }

    /// Counts a fragment of depth `z` at pixel `(x, y)` and depth-tests it;
    /// the pixel's buffer index when it passes.
    #[inline(always)]
    fn depth_test(&mut self, x: u32, y: u32, z: f32) -> Option<usize> {
        self.target.load_row(y);
        let idx = self.target.index(x, y);
        if self.target.counts_coverage() {
            self.target.coverage[idx] = self.target.coverage[idx].saturating_add(1);
        }
        // `always` (and so no depth buffer) reads nothing.
        let test = self.depth.test;
        (test == DepthTest::Always || test.passes(z, self.target.depth[idx])).then_some(idx)
    }

    /// Shades a sample that passed the depth test at buffer index `idx`
    /// and writes its colour (blended by its coverage) and depth.
    ///
    /// Always inlined: called from the fragment and the span paths, it was
    /// left out of line for the larger shaders (diffuse), and each sample,
    /// its three vertices included, went to it through memory (the full
    /// dragon's diffuse raster took 33.1 ms a frame instead of 22.9).
    #[inline(always)]
    fn write<const N: usize>(&mut self, idx: usize, s: Sample<N>) {
        let color = color_of(self.shader, self.interpolation, &s);
        self.target.color[idx] = blend(color, s.coverage, self.target.color[idx]);
        if self.depth.write {
            self.target.depth[idx] = s.depth;
        }
    }

    /// One fragment of triangle `t`, whose vertices lie at `vertices`:
    /// depth from its plane, then, only if the depth test passes, its
    /// vertices are read and weighted for shading.
    #[inline(always)]
    fn triangle_sample(
        &mut self,
        t: &ShadedTriangle,
        vertices: [&ShadedVertex; 3],
        f: &TriangleFragment,
    ) {
        let z = t.depth.at(f.x, f.y);
        if let Some(idx) = self.depth_test(f.x, f.y, z) {
            self.write(idx, Sample::of_triangle(z, vertices.map(|v| *v), f));
        }
    }

    /// One line fragment: steps 1 to 7 of the stage for a pixel of a
    /// line (its depth and varyings from the pixel centre's projection
    /// onto the segment). Always inlined into the one-fragment and the
    /// many-fragment calls, so that a segment's pixels go through one
    /// loop. With each pixel a call of its own, and each segment's pixels
    /// in new arrays, 1M short lines through the stage took 169 ms with
    /// `bresenham`; 135 ms with both gone (`side_by_side`, `lines`).
    #[inline(always)]
    fn line_sample(&mut self, f: &LineFragment) {
        // With the depth test off and a colour uniform per line, nothing
        // of the line's data depends on the pixel: it is shaded once and
        // its fragments only written (blended by their coverage), the
        // same bits as shading each. 100k short lines through the stage
        // took 44.4 ms with bresenham when each was shaded (the fast line
        // path 3.7 ms).
        let depth_off = self.depth.test == DepthTest::Always && !self.depth.write;
        if depth_off && self.shader.uniform_per_primitive() {
            let (color, rgba8) = match self.line_colour {
                Some((id, color, rgba8)) if id == f.line => (color, rgba8),
                _ => {
                    let Some(line) = self.lines.get(f.line as usize) else {
                        debug_assert!(false, "no vertex data for line {}", f.line);
                        return;
                    };
                    let sample = Sample {
                        x: f.x,
                        y: f.y,
                        primitive: f.line,
                        depth: line.vertices[0].depth,
                        screen: [1.0, 0.0],
                        vertices: line.vertices,
                        coverage: 1.0,
                    };
                    let color = color_of(self.shader, self.interpolation, &sample);
                    let rgba8 = to_rgba8(color);
                    self.line_colour = Some((f.line, color, rgba8));
                    (color, rgba8)
                }
            };
            // The test `always` reads no depth.
            if let Some(idx) = self.depth_test(f.x, f.y, 0.0) {
                self.target.color[idx] = if f.coverage >= 1.0 {
                    rgba8
                } else {
                    blend(color, f.coverage, self.target.color[idx])
                };
            }
            return;
        }
        let Some(line) = self.lines.get(f.line as usize).copied() else {
            debug_assert!(false, "no vertex data for line {}", f.line);
            return;
        };
        // Parameter of the pixel centre's projection onto the snapped segment.
        let (ax, ay) = line.from.to_f64();
        let (bx, by) = line.to.to_f64();
        let (dx, dy) = (bx - ax, by - ay);
        let len2 = dx * dx + dy * dy;
        let (px, py) = (f64::from(f.x) + 0.5, f64::from(f.y) + 0.5);
        let t = if len2 > 0.0 {
            (((px - ax) * dx + (py - ay) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let [v0, v1] = line.vertices;
        let z0 = f64::from(v0.depth);
        let z = (z0 + t * (f64::from(v1.depth) - z0)) as f32 + self.line_depth_offset;
        let Some(idx) = self.depth_test(f.x, f.y, z) else {
            return;
        };
        let screen = [(1.0 - t) as f32, t as f32];
        self.write(
            idx,
            Sample {
                x: f.x,
                y: f.y,
                primitive: f.line,
                depth: z,
                screen,
                vertices: line.vertices,
                coverage: f.coverage,
            },
        );
    }
}

/// The buffers of `target` under `span`, its row loaded (cleared first
/// when the draw clears as it goes). With `depth_to_row_end`, the depths
/// run on to the end of the row: a group of eight pixels at the span's
/// end then loads its stored depths as one vector (the lanes past the
/// span read depths the group does not write).
#[inline(always)]
fn span_rows<'t>(
    target: &'t mut TargetRows<'_>,
    span: &TriangleSpan,
    depth_to_row_end: bool,
) -> SpanRows<'t> {
    target.load_row(span.y);
    let start = target.index(span.x0, span.y);
    let end = start + (span.x1 - span.x0) as usize + 1;
    let depth_end = if depth_to_row_end {
        start - span.x0 as usize + target.width() as usize
    } else {
        end
    };
    let counts = target.counts_coverage();
    SpanRows {
        color: &mut target.color[start..end],
        depth: &mut target.depth[start..depth_end],
        coverage: if counts {
            &mut target.coverage[start..end]
        } else {
            &mut []
        },
    }
}

/// The buffers under one span, for the span loops.
struct SpanRows<'s> {
    color: &'s mut [[u8; 4]],
    depth: &'s mut [f32],
    coverage: &'s mut [u16],
}

impl SpanRows<'_> {
    /// Counts one more fragment at each pixel (nothing when the target
    /// does not count coverage: the slice is then empty).
    #[inline(always)]
    fn count_coverage(&mut self) {
        for c in self.coverage.iter_mut() {
            *c = c.saturating_add(1);
        }
    }

    /// Counts coverage, then writes `color` to every pixel: the span with
    /// no depth buffer.
    #[inline(always)]
    fn fill_colour(mut self, color: [u8; 4]) {
        self.count_coverage();
        self.color.fill(color);
    }

    /// [`fill_writing`](Self::fill_writing) with the depth write on or off:
    /// one loop each, so the loop does not test `write`.
    #[inline(always)]
    fn fill(
        self,
        plane: DepthPlane,
        row: f32,
        x0: u32,
        color: [u8; 4],
        write: bool,
        passes: impl Fn(f32, f32) -> bool,
    ) {
        if write {
            self.fill_writing::<true>(plane, row, x0, color, passes);
        } else {
            self.fill_writing::<false>(plane, row, x0, color, passes);
        }
    }

    /// Counts coverage (when the target counts), then depth-tests each
    /// pixel against the plane (evaluated exactly as [`DepthPlane::at`]
    /// does) and writes `color` (and the depth when `WRITE`) where `passes`.
    ///
    /// Eight pixels at a time: where all eight pass (inside a covered
    /// area, the common case), their colours and depths are stored whole.
    /// Elsewhere each pixel's colour (and depth) is stored without a
    /// branch, the old value where the test fails ([`select_pixel`]), so
    /// the compiler can run it on vectors; but a store that keeps some old
    /// values becomes a masked store, which some CPUs run many times
    /// slower than a plain one. The column offset is counted in `i32`,
    /// whose conversion to `f32` gives the same value as
    /// [`DepthPlane::in_row`]'s `i64` one: both are the same integer,
    /// which the guard band keeps below 2^17.
    #[inline(always)]
    fn fill_writing<const WRITE: bool>(
        mut self,
        plane: DepthPlane,
        row: f32,
        x0: u32,
        color: [u8; 4],
        passes: impl Fn(f32, f32) -> bool,
    ) {
        self.count_coverage();
        let first = (i64::from(x0) - i64::from(plane.origin_x)) as i32;
        let color = u32::from_ne_bytes(color);
        // All ones where the test passes, as a vector compare gives.
        let mask = |z: f32, d: f32| u32::from(passes(z, d)).wrapping_neg();
        let mut depths = self.depth.chunks_exact_mut(LANES);
        let mut colors = self.color.chunks_exact_mut(LANES);
        let mut offset = first;
        for (d, c) in (&mut depths).zip(&mut colors) {
            let mut z = [0f32; LANES];
            let mut passed = [0u32; LANES];
            for (k, ((z, pass), d)) in z.iter_mut().zip(&mut passed).zip(&*d).enumerate() {
                *z = plane.in_row_at_offset(row, (offset + k as i32) as f32);
                *pass = mask(*z, *d);
            }
            if passed.iter().all(|&p| p != 0) {
                c.fill(color.to_ne_bytes());
                if WRITE {
                    d.copy_from_slice(&z);
                }
            } else {
                for ((d, c), (&z, &pass)) in d.iter_mut().zip(c).zip(z.iter().zip(&passed)) {
                    select_pixel::<WRITE>(d, c, z, pass, color);
                }
            }
            offset += LANES as i32;
        }
        let rest = depths
            .into_remainder()
            .iter_mut()
            .zip(colors.into_remainder());
        for (i, (d, c)) in rest.enumerate() {
            let z = plane.in_row_at_offset(row, (offset + i as i32) as f32);
            let pass = mask(z, *d);
            select_pixel::<WRITE>(d, c, z, pass, color);
        }
    }
}

/// Stores `color` (and the depth `z` when `WRITE`) into one pixel where
/// `pass` is all ones, and its old values where it is zero, without a
/// branch.
#[inline(always)]
fn select_pixel<const WRITE: bool>(d: &mut f32, c: &mut [u8; 4], z: f32, pass: u32, color: u32) {
    let keep = u32::from_ne_bytes(*c) & !pass;
    *c = (color & pass | keep).to_ne_bytes();
    if WRITE {
        *d = f32::from_bits(z.to_bits() & pass | d.to_bits() & !pass);
    }
}

/// Pixels the span loop tests at a time: one AVX2 vector of `f32`.
const LANES: usize = 8;

/// A span of one colour, to write into [`SpanRows`]: the stage's span loop,
/// compiled for the baseline vectors and for AVX2 ([`vector`]).
struct SpanFill<'s> {
    rows: SpanRows<'s>,
    depth: DepthState,
    plane: DepthPlane,
    /// The span's row and first column.
    y: u32,
    x0: u32,
    color: [u8; 4],
}

impl vector::Kernel for SpanFill<'_> {
    type Output = ();

    /// Writes the colour over the span, depth-tested and written as the
    /// depth state says against the plane.
    #[inline(always)]
    fn run(self) {
        let SpanFill {
            rows,
            depth,
            plane,
            y,
            x0,
            color,
        } = self;
        if depth.is_off() {
            return rows.fill_colour(color);
        }
        let row = plane.row(y);
        let write = depth.write;
        // One monomorphic loop per comparison, so the compare is not
        // re-dispatched per pixel.
        match depth.test {
            DepthTest::Never => rows.fill(plane, row, x0, color, write, |_, _| false),
            DepthTest::Less => rows.fill(plane, row, x0, color, write, |z, d| z < d),
            DepthTest::Equal => rows.fill(plane, row, x0, color, write, |z, d| z == d),
            DepthTest::LessEqual => rows.fill(plane, row, x0, color, write, |z, d| z <= d),
            DepthTest::Greater => rows.fill(plane, row, x0, color, write, |z, d| z > d),
            DepthTest::NotEqual => rows.fill(plane, row, x0, color, write, |z, d| z != d),
            DepthTest::GreaterEqual => rows.fill(plane, row, x0, color, write, |z, d| z >= d),
            DepthTest::Always => rows.fill(plane, row, x0, color, write, |_, _| true),
        }
    }
}

/// `color` over `dst` by `coverage` (`color` itself from 1 up), as RGBA8.
#[inline(always)]
fn blend(color: Vec4, coverage: f32, dst: [u8; 4]) -> [u8; 4] {
    if coverage >= 1.0 {
        to_rgba8(color)
    } else {
        to_rgba8(color * coverage + from_rgba8(dst) * (1.0 - coverage))
    }
}

/// Interpolation weights for the varyings from screen-space weights.
#[inline]
pub(crate) fn varying_weights<const N: usize>(
    interpolation: Interpolation,
    screen: [f32; N],
    v: &[ShadedVertex; N],
) -> [f32; N] {
    match interpolation {
        Interpolation::Linear => screen,
        Interpolation::PerspectiveCorrect => {
            let mut w = [0.0; N];
            let mut sum = 0.0;
            for i in 0..N {
                w[i] = screen[i] * v[i].inv_w;
                sum += w[i];
            }
            if sum > 0.0 {
                vector::divide_each(w, sum)
            } else {
                screen
            }
        }
    }
}

/// The shader's colour for a sample that passed the depth test, clamped
/// to `[0, 1]`.
#[inline(always)]
fn color_of<S: FragmentShader + ?Sized, const N: usize>(
    shader: &S,
    interpolation: Interpolation,
    s: &Sample<N>,
) -> Vec4 {
    let weights = varying_weights(interpolation, s.screen, &s.vertices);
    let input = FragmentInput {
        x: s.x,
        y: s.y,
        depth: s.depth,
        varyings: Varyings::weighted(&s.vertices.map(|v| v.varyings), weights),
        flat: s.vertices[0].varyings,
        primitive: s.primitive,
    };
    shader.shade(&input).clamp(Vec4::ZERO, Vec4::ONE)
}

/// The colour `shader` gives triangle fragment `f` of a triangle with
/// `vertices`, at depth `depth`: steps 4 to 6 of the stage, as
/// [`FragmentStage`] runs them. The multisampled stage shades once per
/// pixel with it, at the pixel centre, whose edge values `f` carries
/// even when the centre lies outside the triangle (the barycentrics are
/// then extrapolated, as the APIs do).
#[inline]
pub(crate) fn shade_triangle_fragment<S: FragmentShader + ?Sized>(
    shader: &S,
    interpolation: Interpolation,
    vertices: [ShadedVertex; 3],
    depth: f32,
    f: &TriangleFragment,
) -> [u8; 4] {
    to_rgba8(color_of(
        shader,
        interpolation,
        &Sample::of_triangle(depth, vertices, f),
    ))
}

/// A fragment that passed the depth test, with what shading it needs.
struct Sample<const N: usize> {
    x: u32,
    y: u32,
    primitive: u32,
    depth: f32,
    /// Screen-space interpolation weights of the N vertices.
    screen: [f32; N],
    vertices: [ShadedVertex; N],
    coverage: f32,
}

impl Sample<3> {
    /// A triangle fragment's sample at depth `depth` (from the triangle's
    /// plane): barycentrics from its exact edge values.
    #[inline]
    fn of_triangle(depth: f32, vertices: [ShadedVertex; 3], f: &TriangleFragment) -> Sample<3> {
        let area = (f.edges[0] + f.edges[1] + f.edges[2]) as f64;
        Sample {
            x: f.x,
            y: f.y,
            primitive: f.triangle,
            depth,
            screen: vector::ratios_to_f32(f.edges, area),
            vertices,
            coverage: 1.0,
        }
    }
}

impl<S: FragmentShader + ?Sized> FragmentSink for FragmentStage<'_, S> {
    fn triangle_fragment(&mut self, f: &TriangleFragment) {
        self.prefetch_ahead(f.triangle);
        if let Some(t) = self.triangle(f.triangle) {
            if let Some(vertices) = self.vertex_refs(t) {
                self.triangle_sample(t, vertices, f);
            }
        }
    }

    fn triangle_span(&mut self, span: &TriangleSpan) {
        self.prefetch_ahead(span.triangle);
        let Some(t) = self.triangle(span.triangle) else {
            return;
        };
        if !self.shader.uniform_per_primitive() {
            // The vertices found once for the span.
            let Some(vertices) = self.vertex_refs(t) else {
                return;
            };
            self.prefetch_next_row(span);
            let long = span.x1 - span.x0 >= SHADED_SPAN_MIN - 1;
            let Some(area) = long.then(|| shaded_span::exact_area(span)).flatten() else {
                for f in span.fragments() {
                    self.triangle_sample(t, vertices, &f);
                }
                return;
            };
            vector::run(ShadedSpan {
                rows: span_rows(&mut self.target, span, true),
                span,
                plane: t.depth,
                vertices,
                shader: self.shader,
                state: self.depth,
                interpolation: self.interpolation,
                area,
            });
            return;
        }
        // The colour is the same for every pixel of the triangle: shade the
        // first pixel of its first span, and keep the colour for the rest.
        let plane = t.depth;
        let color = match self.span_colour {
            Some((id, color)) if id == span.triangle => color,
            _ => {
                let first = TriangleFragment {
                    x: span.x0,
                    y: span.y,
                    triangle: span.triangle,
                    edges: span.edges,
                };
                let Some(vertices) = self.vertices_of(t) else {
                    return;
                };
                let depth = plane.at(first.x, first.y);
                let color = shade_triangle_fragment(
                    self.shader,
                    self.interpolation,
                    vertices,
                    depth,
                    &first,
                );
                self.span_colour = Some((span.triangle, color));
                color
            }
        };
        let fill = SpanFill {
            rows: span_rows(&mut self.target, span, false),
            depth: self.depth,
            plane,
            y: span.y,
            x0: span.x0,
            color,
        };
        vector::run(fill);
    }

    fn line_fragment(&mut self, f: &LineFragment) {
        self.line_sample(f);
    }

    fn line_fragments(&mut self, fragments: &[LineFragment]) {
        for f in fragments {
            self.line_sample(f);
        }
    }
}

crate::names::named_enum!(
    Interpolation,
    "interpolation",
    PerspectiveCorrect = "perspective",
    Linear = "linear"
);

#[cfg(test)]
mod tests {
    use super::*;

    /// The span loop writes what testing pixel by pixel writes (whole
    /// groups of eight passing, mixed groups and the pixels after the last
    /// group), and the copy compiled for AVX2 the very bits the baseline
    /// copy writes, for every depth state, with and without coverage.
    #[test]
    fn every_copy_of_the_span_loop_writes_the_same_bits() {
        if vector::widest() == vector::Width::Baseline {
            eprintln!("this CPU has no AVX2: the span loop has one copy only");
        }
        let mut rng = fastrand::Rng::with_seed(18);
        let states = DepthTest::ALL
            .into_iter()
            .flat_map(|test| [true, false].map(|write| DepthState { test, write }));
        for depth in states {
            for n in 0..300 {
                let len = rng.usize(1..=70);
                let x0 = rng.u32(0..200);
                let plane = DepthPlane {
                    origin_x: rng.i32(-50..250),
                    origin_y: rng.i32(-50..50),
                    z_origin: rng.f32(),
                    dz_dx: (rng.f32() - 0.5) * 0.02,
                    dz_dy: (rng.f32() - 0.5) * 0.02,
                };
                let y = rng.u32(0..40);
                // Stored depths around the plane's, some exactly on it.
                // Every third span over a cleared row, where whole groups
                // of eight pass.
                let stored: Vec<f32> = (0..len)
                    .map(|i| match rng.u8(0..3) {
                        _ if n % 3 == 0 => 1.0,
                        0 => plane.in_row(plane.row(y), x0 + i as u32),
                        1 => rng.f32(),
                        _ => 1.0,
                    })
                    .collect();
                let color: Vec<[u8; 4]> = (0..len).map(|_| rng.u32(..).to_ne_bytes()).collect();
                let counts = n % 2 == 0;
                let fill_with = |copy| {
                    let (mut c, mut d) = (color.clone(), stored.clone());
                    let mut coverage = vec![7u16; if counts { len } else { 0 }];
                    let rows = SpanRows {
                        color: &mut c,
                        depth: &mut d,
                        coverage: &mut coverage,
                    };
                    let fill = SpanFill {
                        rows,
                        depth,
                        plane,
                        y,
                        x0,
                        color: [1, 2, 3, 4],
                    };
                    vector::limited_to(copy, || vector::run(fill));
                    let bits: Vec<u32> = d.iter().map(|z| z.to_bits()).collect();
                    (c, bits, coverage)
                };
                let baseline = fill_with(vector::Width::Baseline);
                // Pixel by pixel, as the fragment path tests and writes.
                let mut expected = (
                    color.clone(),
                    stored.clone(),
                    vec![8u16; if counts { len } else { 0 }],
                );
                for (i, &old) in stored.iter().enumerate() {
                    let z = plane.in_row(plane.row(y), x0 + i as u32);
                    if depth.test.passes(z, old) {
                        expected.0[i] = [1, 2, 3, 4];
                        if depth.write {
                            expected.1[i] = z;
                        }
                    }
                }
                let expected_bits: Vec<u32> = expected.1.iter().map(|z| z.to_bits()).collect();
                assert_eq!(
                    baseline,
                    (expected.0, expected_bits, expected.2),
                    "{depth:?} {plane:?} y {y} x0 {x0} len {len}"
                );
                for copy in vector::copies() {
                    assert_eq!(
                        fill_with(copy),
                        baseline,
                        "{copy:?} {depth:?} {plane:?} y {y} x0 {x0} len {len}"
                    );
                }
            }
        }
    }
}

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
//! This module is that path, one fragment at a time: the reference the
//! faster paths beside it are checked against, bit for bit. Each of them
//! runs the same steps on more pixels at once, in a file of its own:
//!
//! - `span_fill`: for a shader whose colour is uniform over a triangle, a
//!   whole span through steps 1, 2, 3 and 7 in one loop, written once as
//!   plain Rust and compiled both for the baseline vectors and for AVX2,
//!   the copy picked at run time (the `raster::vector` module);
//! - `shaded_span`: any other shader's spans of six pixels or more, all
//!   seven steps eight pixels at a time ([`FragmentShader::shade_lanes`]);
//! - `lines`: a line's pixels (depth and varyings from the pixel centre's
//!   projection onto the segment);
//! - `prefetch`: asking for a triangle's data before its fragments come.
//!
//! Step 7 is one function for all of them, and for the multisampled
//! stage: the merge (`merge`), where a [`Blend`] says how a fragment's
//! colour meets the pixel's.
//!
//! Because every step is a pure function of the fragment's pixel and
//! integer edge values, back-ends that emit the same fragments in the same
//! per-pixel order produce bit-identical colour, depth and coverage buffers.

use crate::raster::edge::PixelRect;
use crate::raster::fragment::{FragmentSink, LineFragment, TriangleFragment, TriangleSpan};
use crate::raster::primitive::{ShadedLine, ShadedTriangle, ShadedVertex, TriangleData, Varyings};
use crate::raster::shader::{to_rgba8, FragmentInput, FragmentShader};
use crate::raster::target::{DepthState, DepthTest, RenderTarget, TargetRows};
use crate::raster::vector;
use glam::Vec4;
pub(crate) use merge::{merge, merge_pixel, Passed, Source};

pub use merge::{Blend, BlendMode, WriteMask};

mod lines;
mod merge;
mod prefetch;
mod shaded_span;
mod span_fill;

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
/// bits. The known type is the faster: the call through the pointer
/// passes the fragment's inputs and its colour through memory, on the
/// chain of work every fragment waits on (measured in the performance
/// log, docs/performance-log.md).
pub struct FragmentStage<'a, S: FragmentShader + ?Sized = dyn FragmentShader> {
    target: TargetRows<'a>,
    shader: &'a S,
    triangles: &'a [ShadedTriangle],
    vertices: &'a [ShadedVertex],
    lines: &'a [ShadedLine],
    /// Depth comparison and write mask.
    pub depth: DepthState,
    /// How a fragment's colour is merged with the pixel's.
    pub blend: Blend,
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
            blend: Blend::REPLACE,
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

    /// Sets the blend state.
    pub fn with_blend(mut self, blend: Blend) -> Self {
        self.blend = blend;
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
    /// (steps 4 to 6), and merges its colour and depth into the pixel
    /// (step 7).
    ///
    /// Always inlined: called from the fragment and the span paths, it
    /// was otherwise left out of line for the larger shaders (diffuse),
    /// and each sample, its three vertices included, went to it through
    /// memory.
    #[inline(always)]
    fn write<const N: usize>(&mut self, idx: usize, s: Sample<N>) {
        let source = Source::Shaded {
            color: color_of(self.shader, self.interpolation, &s),
            coverage: s.coverage,
        };
        let depth = self
            .depth
            .write
            .then(|| (&mut self.target.depth[idx], s.depth));
        merge_pixel(self.blend, source, &mut self.target.color[idx], depth);
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

    /// A span: through the uniform span loop when the shader's colour is
    /// the same over the triangle (`span_fill`), through the shaded
    /// span loop otherwise (`shaded_span`).
    fn triangle_span(&mut self, span: &TriangleSpan) {
        self.prefetch_ahead(span.triangle);
        let Some(t) = self.triangle(span.triangle) else {
            return;
        };
        if self.shader.uniform_per_primitive() {
            self.fill_span(t, span);
        } else {
            self.shade_span(t, span);
        }
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

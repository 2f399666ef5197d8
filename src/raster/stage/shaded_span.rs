//! The stage's span loop for shaders whose colour changes from pixel to
//! pixel (Gouraud, diffuse, textured): steps 1 to 7 of the stage for
//! eight pixels of a span at a time.
//!
//! For each group of [`LANES`] pixels of the span:
//!
//! 1. the depth of each pixel from the triangle's plane, and the depth
//!    test against the buffer, as a mask; a group where no pixel passes
//!    costs nothing more;
//! 2. the edge values of each pixel, `E_i + k * step_i` from the span's
//!    first pixel, and the barycentrics `E_i / area` in `f64`, found as
//!    products by the area's reciprocal wherever those round to the
//!    quotient's `f32` (checked lane by lane);
//! 3. the perspective-correct weights (`beta / w` divided by their sum),
//!    and the varyings they weigh, one array per component;
//! 4. the shader's [`shade_lanes`](FragmentShader::shade_lanes);
//! 5. the colour clamped and rounded to bytes, and merged with the depth
//!    where the test passed (the stage's one [`merge`](super::merge)).
//!
//! Every step is the scalar stage's equation, in its order, on each lane:
//! the loop is plain Rust over arrays of eight, compiled for the baseline
//! vectors and for AVX2 ([`vector`]), and gives the very bits the
//! fragment-by-fragment path gives. In the copy for AVX2, steps 2 and 3
//! are written lane by lane ([`vector::weights`]): compiled from the
//! plain Rust, they passed their arrays through memory, and took a sixth
//! of the small dragon's raster. The test
//! `every_copy_of_the_shaded_span_loop_writes_the_fragment_paths_bits`
//! compares them.

// The loops over lanes index several arrays by the lane `k`, each
// statement one vector instruction; iterators over one of them would hide
// that shape.
#![allow(clippy::needless_range_loop)]

use super::span_fill::{span_rows, SpanRows};
use super::{merge, Blend, FragmentStage, Interpolation, Passed, Source};
use crate::raster::fragment::TriangleSpan;
use crate::raster::primitive::{DepthPlane, ShadedTriangle, ShadedVertex};
use crate::raster::shader::{ColorLanes, FragmentLanes, FragmentShader, LANES};
use crate::raster::target::{DepthState, DepthTest};
use crate::raster::vector;
use crate::raster::vector::weights::{DROPPED_BITS, MARGIN, MIDPOINT};

/// The shortest span whose fragments this loop shades eight at a time;
/// shorter spans go fragment by fragment, which gives the same bits and
/// measured faster for them (docs/performance-log.md, "spans of four and
/// five pixels shaded one fragment at a time").
const SHADED_SPAN_MIN: u32 = 6;

impl<S: FragmentShader + ?Sized> FragmentStage<'_, S> {
    /// A span of triangle `t` whose colour changes from pixel to pixel:
    /// eight pixels at a time when it is long enough and its edge values
    /// are exact in `f64` ([`exact_area`]), fragment by fragment
    /// otherwise.
    #[inline(always)]
    pub(super) fn shade_span(&mut self, t: &ShadedTriangle, span: &TriangleSpan) {
        // The vertices found once for the span.
        let Some(vertices) = self.vertex_refs(t) else {
            return;
        };
        self.prefetch_next_row(span);
        let long = span.x1 - span.x0 >= SHADED_SPAN_MIN - 1;
        let Some(area) = long.then(|| exact_area(span)).flatten() else {
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
            blend: self.blend,
            interpolation: self.interpolation,
            area,
        });
    }
}

/// The buffers under one span, and what shades it.
struct ShadedSpan<'s, S: FragmentShader + ?Sized> {
    /// Colour, depth and coverage of the span's pixels.
    pub rows: SpanRows<'s>,
    pub span: &'s TriangleSpan,
    pub plane: DepthPlane,
    pub vertices: [&'s ShadedVertex; 3],
    pub shader: &'s S,
    pub state: DepthState,
    pub blend: Blend,
    pub interpolation: Interpolation,
    /// The triangle's doubled area, `E_0 + E_1 + E_2`, the same at every
    /// pixel.
    pub area: f64,
}

/// `e / area` rounded to `f32`, found as `e * inv_area` (`inv_area` the
/// rounded `1 / area`), and `false` where that product may round to
/// another `f32` than the quotient: the lane must then divide.
///
/// A multiplication costs far less than a division: the eight lanes'
/// three quotients are six AVX2 divisions of four `f64`, and on recent
/// Intel cores the divider takes one only every eight cycles or so. The
/// product is within two units in the last place (ulp) of the quotient
/// `e / area` of the same `f64` values: two roundings, each off by at
/// most half a unit relative to the value. Rounding to `f32` drops the
/// [`DROPPED_BITS`] lowest bits, and its only decision points are the
/// midpoints between two `f32`s, where those bits read `1000...0` (ties
/// go to even). Where the product's dropped bits are three units or more
/// from that pattern, no midpoint lies between it and the quotient, and
/// both round alike; the check keeps a margin of [`MARGIN`]. The quotients here
/// are 0 or at least `1 / area`, above 2^-54 (each edge value is at most
/// 2^52), normal in `f32` too, whose rounding is then exactly this. A
/// product rarely fails the check (31 patterns in 2^29).
#[inline(always)]
fn by_reciprocal(e: f64, inv_area: f64) -> (f32, bool) {
    let product = e * inv_area;
    let dropped = (product.to_bits() & ((1 << DROPPED_BITS) - 1)) as i64;
    let sure = (dropped <= MIDPOINT - MARGIN) | (dropped >= MIDPOINT + MARGIN);
    (product as f32, sure)
}

/// The largest edge value the loop finds in `f64`: below 2^53, every
/// integer and every sum of two is exact.
const EXACT_EDGE: u64 = 1 << 52;

/// The triangle's doubled area as `f64` when the loop gives `span` the
/// fragment path's bits: the edge values sum to the same area at every
/// pixel (their steps sum to zero, as edge functions' do), and every edge
/// value the groups reach, up to [`LANES`] pixels past the span's end, is
/// at most [`EXACT_EDGE`]. `None` otherwise: the span then goes fragment
/// by fragment.
fn exact_area(span: &TriangleSpan) -> Option<f64> {
    if span.step.iter().sum::<i64>() != 0 {
        return None;
    }
    let reach = i64::from(span.x1 - span.x0) + LANES as i64;
    for i in 0..3 {
        let last = span.step[i]
            .checked_mul(reach)
            .and_then(|d| d.checked_add(span.edges[i]))?;
        let within = |e: i64| e.unsigned_abs() <= EXACT_EDGE;
        if !within(span.edges[i]) || !within(last) {
            return None;
        }
    }
    Some(span.edges.iter().sum::<i64>() as f64)
}

impl<S: FragmentShader + ?Sized> vector::Kernel for ShadedSpan<'_, S> {
    type Output = ();

    #[inline(always)]
    fn run(self) {
        // One loop per comparison, so the compare is not re-dispatched
        // per pixel.
        match self.state.test {
            DepthTest::Never => self.shade(|_, _| false),
            DepthTest::Less => self.shade(|z, d| z < d),
            DepthTest::Equal => self.shade(|z, d| z == d),
            DepthTest::LessEqual => self.shade(|z, d| z <= d),
            DepthTest::Greater => self.shade(|z, d| z > d),
            DepthTest::NotEqual => self.shade(|z, d| z != d),
            DepthTest::GreaterEqual => self.shade(|z, d| z >= d),
            DepthTest::Always => self.shade(|_, _| true),
        }
    }
}

impl<S: FragmentShader + ?Sized> ShadedSpan<'_, S> {
    /// The span, group by group, with the depth test `passes`.
    #[inline(always)]
    fn shade(mut self, passes: impl Fn(f32, f32) -> bool) {
        self.rows.count_coverage();
        let span = self.span;
        let plane = self.plane;
        let row = plane.row(span.y);
        // The column offset in `i32`, as the uniform span loop counts it:
        // the same integer as `DepthPlane::in_row`'s, which the guard band
        // keeps below 2^17, so the same `f32`.
        let first = (i64::from(span.x0) - i64::from(plane.origin_x)) as i32;
        let reads_depth = self.state.test != DepthTest::Always;
        // Once per span, for the barycentrics ([`by_reciprocal`]).
        let inv_area = 1.0 / self.area;
        let len = self.rows.color.len();
        let mut start = 0;
        while start < len {
            let n = (len - start).min(LANES);
            // The stored depths, whole when the group is: a load the
            // compare reads as one vector.
            let mut stored = [0.0f32; LANES];
            if reads_depth {
                match self.rows.depth.get(start..start + LANES) {
                    Some(whole) => stored.copy_from_slice(whole),
                    None => stored[..n].copy_from_slice(&self.rows.depth[start..start + n]),
                }
            }
            let mut z = [0.0f32; LANES];
            let mut active = [false; LANES];
            for k in 0..LANES {
                z[k] = plane.in_row_at_offset(row, (first + (start + k) as i32) as f32);
                active[k] = passes(z[k], stored[k]) & (k < n);
            }
            if active.iter().any(|&a| a) {
                let lanes = self.lanes(start, z, active, self.vertices, inv_area);
                let colour = to_pixels(self.shader.shade_lanes(&lanes));
                let source = |k: usize| Source::Rgba8(colour[k].to_le_bytes());
                let (blend, write) = (self.blend, self.state.write);
                let colours = &mut self.rows.color[start..start + n];
                let depths = &mut self.rows.depth[start..start + n];
                if n == LANES && active.iter().all(|&a| a) {
                    // The whole group passed: plain stores.
                    if write {
                        merge::<true>(blend, source, Passed::All, &z, colours, depths);
                    } else {
                        merge::<false>(blend, source, Passed::All, &[], colours, depths);
                    }
                } else {
                    // Only the pixels that passed are stored: with shaded
                    // colours a group is partial mostly at a span's ends,
                    // where storing every lane back measured slower.
                    for k in 0..n {
                        if !active[k] {
                            continue;
                        }
                        let (c, d) = (&mut colours[k..=k], &mut depths[k..=k]);
                        let one = |_| source(k);
                        if write {
                            merge::<true>(blend, one, Passed::All, &z[k..=k], c, d);
                        } else {
                            merge::<false>(blend, one, Passed::All, &[], c, d);
                        }
                    }
                }
            }
            start += LANES;
        }
    }

    /// The shader's input for the group of pixels from `start`: steps 4
    /// and 5 of the stage ([`crate::raster::stage`]) on each lane, with
    /// `inv_area` the area's reciprocal ([`by_reciprocal`]). Every loop
    /// runs over the lanes innermost, so that each statement becomes one
    /// vector instruction.
    #[inline(always)]
    fn lanes(
        &self,
        start: usize,
        depth: [f32; LANES],
        active: [bool; LANES],
        v: [&ShadedVertex; 3],
        inv_area: f64,
    ) -> FragmentLanes {
        let span = self.span;
        let first: [i64; 3] = std::array::from_fn(|i| span.edges[i] + start as i64 * span.step[i]);
        let group = vector::weights::Group {
            edges: first.map(|e| e as f64),
            step: span.step.map(|s| s as f64),
            area: self.area,
            inv_area,
            inv_w: (self.interpolation == Interpolation::PerspectiveCorrect)
                .then(|| v.map(|v| v.inv_w)),
        };
        let weights =
            vector::weights::weights(&group).unwrap_or_else(|| self.weights(first, v, inv_area));
        // The varyings, as `Varyings::weighted`: a sum from zero, vertex
        // by vertex.
        let weigh = |component: fn(&ShadedVertex) -> f32| {
            let mut out = [0.0f32; LANES];
            for i in 0..3 {
                let value = component(v[i]);
                for k in 0..LANES {
                    out[k] += value * weights[i][k];
                }
            }
            out
        };
        FragmentLanes {
            x0: span.x0 + start as u32,
            y: span.y,
            depth,
            color: [
                weigh(|v| v.varyings.color.x),
                weigh(|v| v.varyings.color.y),
                weigh(|v| v.varyings.color.z),
                weigh(|v| v.varyings.color.w),
            ],
            uv: [weigh(|v| v.varyings.uv.x), weigh(|v| v.varyings.uv.y)],
            normal: [
                weigh(|v| v.varyings.normal.x),
                weigh(|v| v.varyings.normal.y),
                weigh(|v| v.varyings.normal.z),
            ],
            flat: v[0].varyings,
            primitive: span.triangle,
            active,
        }
    }

    /// The interpolation weights of the group whose first pixel's edge
    /// values are `first`: steps 2 and 3 of the loop, in plain Rust (the
    /// copy for AVX2 has them written lane by lane,
    /// [`vector::weights`]).
    #[inline(always)]
    fn weights(&self, first: [i64; 3], v: [&ShadedVertex; 3], inv_area: f64) -> [[f32; LANES]; 3] {
        let span = self.span;
        // Barycentrics from the exact edge values, as `Sample::of_triangle`:
        // `E_i / area` in `f64`, rounded to `f32`. The edge values are found
        // in `f64`, from the group's first: every one is an integer below
        // 2^53 (`exact_area` checked it), so each sum and product is exact,
        // the very values `E_i as f64` gives. Each is multiplied by the
        // area's reciprocal, and a group where a lane's product might round
        // otherwise than the quotient divides them all ([`by_reciprocal`]).
        let mut screen = [[0.0f32; LANES]; 3];
        let mut edge = [[0.0f64; LANES]; 3];
        let mut sure = [true; LANES];
        for i in 0..3 {
            let first = first[i] as f64;
            let step = span.step[i] as f64;
            for k in 0..LANES {
                edge[i][k] = first + k as f64 * step;
                let (ratio, exact) = by_reciprocal(edge[i][k], inv_area);
                screen[i][k] = ratio;
                sure[k] &= exact;
            }
        }
        if !sure.iter().all(|&s| s) {
            for i in 0..3 {
                for k in 0..LANES {
                    screen[i][k] = (edge[i][k] / self.area) as f32;
                }
            }
        }
        // Interpolation weights, as `varying_weights`.
        match self.interpolation {
            Interpolation::Linear => screen,
            Interpolation::PerspectiveCorrect => {
                let mut w = [[0.0f32; LANES]; 3];
                let mut sum = [0.0f32; LANES];
                for i in 0..3 {
                    for k in 0..LANES {
                        w[i][k] = screen[i][k] * v[i].inv_w;
                        sum[k] += w[i][k];
                    }
                }
                for i in 0..3 {
                    for k in 0..LANES {
                        w[i][k] = if sum[k] > 0.0 {
                            w[i][k] / sum[k]
                        } else {
                            screen[i][k]
                        };
                    }
                }
                w
            }
        }
    }
}

/// The colours clamped to `[0, 1]` (twice, as the stage clamps the
/// shader's colour and [`to_rgba8`](crate::raster::to_rgba8) clamps
/// again; `max` and `min` in the order of SSE's, so a NaN becomes 0),
/// rounded to bytes as `to_rgba8` rounds, and packed as RGBA8 pixels.
#[inline(always)]
fn to_pixels(colour: ColorLanes) -> [u32; LANES] {
    // (Not `map` over the channels: it is left out of line.)
    let (r, g, b, a) = (
        bytes(&colour[0]),
        bytes(&colour[1]),
        bytes(&colour[2]),
        bytes(&colour[3]),
    );
    let mut out = [0u32; LANES];
    for k in 0..LANES {
        out[k] = r[k] | g[k] << 8 | b[k] << 16 | a[k] << 24;
    }
    out
}

/// One channel of [`to_pixels`], lane by lane: each step one vector
/// instruction over the eight lanes.
#[inline(always)]
fn bytes(values: &[f32; LANES]) -> [u32; LANES] {
    let clamp = |v: f32| {
        let v = if v > 0.0 { v } else { 0.0 };
        if v < 1.0 {
            v
        } else {
            1.0
        }
    };
    let mut out = [0u32; LANES];
    for k in 0..LANES {
        out[k] = truncate(clamp(clamp(values[k])) * 255.0 + 0.5);
    }
    out
}

/// `v as u32` for `v` in `[0, 2^22)`, in steps that run on vectors (the
/// conversion itself checks each lane for saturation, one at a time):
/// adding 2^23 rounds `v` to the nearest integer `r` (ties to even) and
/// leaves `r` in the low bits; one less where `r` was rounded up is the
/// truncation.
#[inline(always)]
fn truncate(v: f32) -> u32 {
    const SHIFTER: f32 = 8_388_608.0; // 2^23: one unit in the last place.
    let shifted = v + SHIFTER;
    let rounded = shifted.to_bits() & 0x007f_ffff;
    rounded - u32::from(shifted - SHIFTER > v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::fragment::FragmentSink;
    use crate::raster::primitive::{ShadedTriangle, TriangleData, Varyings};
    use crate::raster::shader::{Diffuse, DirectionalLight, Gouraud, NormalColors};
    use crate::raster::stage::FragmentStage;
    use crate::raster::target::RenderTarget;
    use glam::{Vec2, Vec3, Vec4};

    const WIDTH: u32 = 200;

    /// Where the product by the reciprocal is sure, it rounds to the
    /// quotient's `f32`. The quotients are built around midpoints between
    /// two `f32`s, about two units in the last place apart (an area near
    /// 2^52 and edge values stepped by one), where the product, unchecked,
    /// rounds the other way for some of them: without the check the test
    /// fails.
    #[test]
    fn a_sure_product_by_the_reciprocal_rounds_as_the_quotient() {
        let mut rng = fastrand::Rng::with_seed(40);
        let (mut product_differs, mut sure) = (0, 0);
        for _ in 0..2_000 {
            let area = rng.u64((1 << 51)..(1 << 52)) as f64;
            let below = f32::from_bits(rng.u32(0.5f32.to_bits()..1.0f32.to_bits()));
            let above = f32::from_bits(below.to_bits() + 1);
            let midpoint = (f64::from(below) + f64::from(above)) / 2.0;
            let nearest = (midpoint * area).round();
            for step in -40..=40 {
                let e = nearest + f64::from(step);
                let quotient = (e / area) as f32;
                let (ratio, exact) = by_reciprocal(e, 1.0 / area);
                product_differs += usize::from(ratio != quotient);
                if exact {
                    sure += 1;
                    assert_eq!(ratio.to_bits(), quotient.to_bits(), "{e} / {area}");
                }
            }
        }
        assert!(product_differs > 0, "no product rounded otherwise");
        assert!(sure > 2_000 * 60, "only {sure} products were sure");
        // Away from the midpoints, nearly every product is sure.
        let unsure = (0..100_000)
            .filter(|_| {
                let area = rng.u64(1..(1 << 40)) as f64;
                let e = rng.u64(0..=area as u64) as f64;
                let (ratio, exact) = by_reciprocal(e, 1.0 / area);
                assert!(!exact || ratio == (e / area) as f32, "{e} / {area}");
                !exact
            })
            .count();
        assert!(unsure < 10, "{unsure} of 100,000 products unsure");
    }

    /// A vertex with random varyings, some outside `[0, 1]` (clamped by
    /// the stage) and some normals of zero length.
    fn vertex(rng: &mut fastrand::Rng) -> ShadedVertex {
        let zero_normal = rng.u8(0..8) == 0;
        let scale = [1.0, 0.5, 1e-3, 3.0][rng.usize(0..4)];
        let mut f = || rng.f32() * 1.4 - 0.2;
        ShadedVertex {
            depth: f(),
            inv_w: scale * (0.5 + f()),
            varyings: Varyings {
                color: Vec4::new(f(), f(), f(), f()),
                uv: Vec2::new(f(), f()),
                normal: if zero_normal {
                    Vec3::ZERO
                } else {
                    Vec3::new(f(), f(), f())
                },
            },
        }
    }

    /// A span over row 0 with edge values whose steps sum to zero, as an
    /// edge function's do; every tenth with values past [`EXACT_EDGE`],
    /// which go fragment by fragment.
    fn span(rng: &mut fastrand::Rng, n: usize) -> TriangleSpan {
        let scale = if n.is_multiple_of(10) {
            1 << 54
        } else {
            1 << 30
        };
        let x0 = rng.u32(0..WIDTH - 1);
        let x1 = rng.u32(x0..WIDTH);
        let area = rng.i64(1..scale);
        let (e0, e1) = (rng.i64(-scale..scale), rng.i64(-scale..scale));
        let (s0, s1) = (
            rng.i64(-scale / 64..scale / 64),
            rng.i64(-scale / 64..scale / 64),
        );
        TriangleSpan {
            y: 0,
            x0,
            x1,
            triangle: 0,
            edges: [e0, e1, area - e0 - e1],
            step: [s0, s1, -s0 - s1],
        }
    }

    /// A span through the lanes (on each copy of the loop) writes the bits
    /// its fragments write one by one, for every depth state and both
    /// interpolations, with shaders that write their lanes out
    /// (`Gouraud`, `Diffuse`) and one that does not (`NormalColors`).
    #[test]
    fn every_copy_of_the_shaded_span_loop_writes_the_fragment_paths_bits() {
        let mut rng = fastrand::Rng::with_seed(40);
        let diffuse = Diffuse(DirectionalLight::default());
        let mut spans_in_lanes = 0;
        for n in 0..3000 {
            let span = span(&mut rng, n);
            if exact_area(&span).is_some() && span.x1 - span.x0 >= SHADED_SPAN_MIN - 1 {
                spans_in_lanes += 1;
            }
            let data = TriangleData {
                vertices: (0..3).map(|_| vertex(&mut rng)).collect(),
                triangles: vec![ShadedTriangle {
                    vertices: [0, 1, 2],
                    depth: DepthPlane {
                        origin_x: rng.i32(-50..250),
                        origin_y: 0,
                        z_origin: rng.f32(),
                        dz_dx: (rng.f32() - 0.5) * 0.02,
                        dz_dy: 0.0,
                    },
                }],
            };
            let state = DepthState {
                test: DepthTest::ALL[n % DepthTest::ALL.len()],
                write: n % 3 != 0,
            };
            let interpolation = if n % 4 == 0 {
                Interpolation::Linear
            } else {
                Interpolation::PerspectiveCorrect
            };
            let mut start = RenderTarget::new(WIDTH, 1).unwrap();
            for (d, c) in start.depth.iter_mut().zip(&mut start.color) {
                *d = if rng.bool() { 1.0 } else { rng.f32() };
                *c = rng.u32(..).to_ne_bytes();
            }
            let draw = |shader: &dyn FragmentShader, whole: bool, copy| {
                let mut target = start.clone();
                let mut stage = FragmentStage::new(&mut target, shader)
                    .with_triangles(&data)
                    .with_depth(state)
                    .with_interpolation(interpolation);
                if whole {
                    vector::limited_to(copy, || stage.triangle_span(&span));
                } else {
                    for f in span.fragments() {
                        stage.triangle_fragment(&f);
                    }
                }
                let depth: Vec<u32> = target.depth.iter().map(|z| z.to_bits()).collect();
                (target.color, depth, target.coverage)
            };
            let shaders: [&dyn FragmentShader; 3] = [&Gouraud, &diffuse, &NormalColors];
            for shader in shaders {
                let expected = draw(shader, false, vector::Width::Baseline);
                for copy in vector::copies() {
                    assert_eq!(
                        draw(shader, true, copy),
                        expected,
                        "{copy:?} {state:?} {interpolation:?} {span:?} {data:?}"
                    );
                }
            }
        }
        assert!(spans_in_lanes > 2000, "{spans_in_lanes} spans in lanes");
    }
}

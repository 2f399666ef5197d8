//! The stage's span loop for a colour uniform over a triangle (flat
//! colours, a constant shader): steps 1, 2, 3 and 7 for a whole span in
//! one loop, written once as plain Rust and compiled both for the
//! baseline vectors and for AVX2, the copy picked at run time
//! ([`vector`]); both give the bits the fragment-by-fragment path gives.

use super::{merge, shade_triangle_fragment, Blend, FragmentStage, Passed, Source};
use crate::raster::fragment::{TriangleFragment, TriangleSpan};
use crate::raster::primitive::{DepthPlane, ShadedTriangle};
use crate::raster::shader::FragmentShader;
use crate::raster::target::{DepthState, DepthTest, TargetRows};
use crate::raster::vector;

impl<S: FragmentShader + ?Sized> FragmentStage<'_, S> {
    /// A span of triangle `t` whose colour is the same at every pixel
    /// (the shader is uniform per primitive): the first pixel of the
    /// triangle's first span is shaded, and its colour kept for the rest.
    #[inline(always)]
    pub(super) fn fill_span(&mut self, t: &ShadedTriangle, span: &TriangleSpan) {
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
            blend: self.blend,
            plane,
            y: span.y,
            x0: span.x0,
            color,
        };
        vector::run(fill);
    }
}

/// The buffers of `target` under `span`, its row loaded (cleared first
/// when the draw clears as it goes). With `depth_to_row_end`, the depths
/// run on to the end of the row: a group of eight pixels at the span's
/// end then loads its stored depths as one vector (the lanes past the
/// span read depths the group does not write).
#[inline(always)]
pub(super) fn span_rows<'t>(
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
pub(super) struct SpanRows<'s> {
    pub(super) color: &'s mut [[u8; 4]],
    pub(super) depth: &'s mut [f32],
    pub(super) coverage: &'s mut [u16],
}

impl SpanRows<'_> {
    /// Counts one more fragment at each pixel (nothing when the target
    /// does not count coverage: the slice is then empty).
    #[inline(always)]
    pub(super) fn count_coverage(&mut self) {
        for c in self.coverage.iter_mut() {
            *c = c.saturating_add(1);
        }
    }

    /// Counts coverage, then merges `color` into every pixel: the span
    /// with no depth buffer.
    #[inline(always)]
    fn fill_colour(mut self, blend: Blend, color: [u8; 4]) {
        self.count_coverage();
        let source = |_| Source::Rgba8(color);
        merge::<false>(blend, source, Passed::All, &[], self.color, &mut []);
    }

    /// [`fill_writing`](Self::fill_writing) with the depth write on or off:
    /// one loop each, so the loop does not test `write`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn fill(
        self,
        plane: DepthPlane,
        row: f32,
        x0: u32,
        blend: Blend,
        color: [u8; 4],
        write: bool,
        passes: impl Fn(f32, f32) -> bool,
    ) {
        if write {
            self.fill_writing::<true>(plane, row, x0, blend, color, passes);
        } else {
            self.fill_writing::<false>(plane, row, x0, blend, color, passes);
        }
    }

    /// Counts coverage (when the target counts), then depth-tests each
    /// pixel against the plane (evaluated exactly as [`DepthPlane::at`]
    /// does) and merges `color` (and the depth when `WRITE`) where `passes`.
    ///
    /// Eight pixels at a time: where all eight pass (inside a covered
    /// area, the common case), the group is merged with plain stores
    /// ([`Passed::All`]). Elsewhere each pixel is merged without a branch,
    /// its old values kept where the test fails ([`Passed::Where`]), so
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
        blend: Blend,
        color: [u8; 4],
        passes: impl Fn(f32, f32) -> bool,
    ) {
        self.count_coverage();
        let first = (i64::from(x0) - i64::from(plane.origin_x)) as i32;
        let source = |_| Source::Rgba8(color);
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
            let passed = if passed.iter().all(|&p| p != 0) {
                Passed::All
            } else {
                Passed::Where(&passed)
            };
            merge::<WRITE>(blend, source, passed, &z, c, d);
            offset += LANES as i32;
        }
        let rest = depths
            .into_remainder()
            .iter_mut()
            .zip(colors.into_remainder());
        for (i, (d, c)) in rest.enumerate() {
            let z = plane.in_row_at_offset(row, (offset + i as i32) as f32);
            let pass = [mask(z, *d)];
            let (c, d) = (std::slice::from_mut(c), std::slice::from_mut(d));
            merge::<WRITE>(blend, source, Passed::Where(&pass), &[z], c, d);
        }
    }
}

/// Pixels the span loop tests at a time: one AVX2 vector of `f32`.
const LANES: usize = 8;

/// A span of one colour, to write into [`SpanRows`]: the stage's span loop,
/// compiled for the baseline vectors and for AVX2 ([`vector`]).
struct SpanFill<'s> {
    rows: SpanRows<'s>,
    depth: DepthState,
    blend: Blend,
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
            blend,
            plane,
            y,
            x0,
            color,
        } = self;
        if depth.is_off() {
            return rows.fill_colour(blend, color);
        }
        let row = plane.row(y);
        let write = depth.write;
        // One monomorphic loop per comparison, so the compare is not
        // re-dispatched per pixel.
        match depth.test {
            DepthTest::Never => rows.fill(plane, row, x0, blend, color, write, |_, _| false),
            DepthTest::Less => rows.fill(plane, row, x0, blend, color, write, |z, d| z < d),
            DepthTest::Equal => rows.fill(plane, row, x0, blend, color, write, |z, d| z == d),
            DepthTest::LessEqual => rows.fill(plane, row, x0, blend, color, write, |z, d| z <= d),
            DepthTest::Greater => rows.fill(plane, row, x0, blend, color, write, |z, d| z > d),
            DepthTest::NotEqual => rows.fill(plane, row, x0, blend, color, write, |z, d| z != d),
            DepthTest::GreaterEqual => {
                rows.fill(plane, row, x0, blend, color, write, |z, d| z >= d)
            }
            DepthTest::Always => rows.fill(plane, row, x0, blend, color, write, |_, _| true),
        }
    }
}

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
                        blend: Blend::REPLACE,
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

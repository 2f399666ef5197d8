//! The derivatives of eight pixels of one row at once: what the stage's
//! span loop gives a mipmapped shader ([`FragmentShader::shade_lanes`]),
//! so that its derivatives ride along the span as plane-equation steps
//! rather than one call per fragment.
//!
//! A row's planes are found once (`P0 + Py y`), and each column adds its
//! `Px x`: the very sum [`UvPlanes::derivatives`] makes at one pixel, in
//! its order, so every lane has the bits the one-pixel method gives.
//! The coordinates a group needs are computed once each, not once for
//! every pixel that reads them:
//!
//! * **quad**: the two rows of the group's quads, over the ten columns of
//!   the five quads eight pixels can touch. Each pixel reads four of
//!   them; the one-pixel method computes those four for every pixel.
//! * **forward**: the pixel's row and the row below, over the ten columns
//!   from one left of the group to one right of it; the row above only
//!   when a pixel falls back to the backward difference.
//! * **analytic**: each pixel's own planes.
//!
//! [`FragmentShader::shade_lanes`]: crate::raster::FragmentShader::shade_lanes

// Each loop runs over the lanes or columns innermost, indexing several
// arrays by the same position: one vector instruction per statement.
#![allow(clippy::needless_range_loop)]

use super::{Derivatives, Gradient, Plane, UvPlanes};
use crate::raster::shader::LANES;
use glam::{DVec2, Vec2};

/// The columns a group of [`LANES`] pixels reads: one more on each side.
const COLUMNS: usize = LANES + 2;

/// The texture coordinate at the centres of [`COLUMNS`] pixels of one row,
/// and which of them have `1 / w > 0` (where the coordinate means
/// something; [`UvPlanes::uv_at`] gives `None` elsewhere).
struct Row {
    u: [f64; COLUMNS],
    v: [f64; COLUMNS],
    ok: [bool; COLUMNS],
}

impl Row {
    /// `uv(b) - uv(a)` for columns `a` and `b`, when both have one.
    #[inline(always)]
    fn difference(&self, a: usize, b: usize) -> Option<DVec2> {
        (self.ok[a] & self.ok[b])
            .then(|| DVec2::new(self.u[b], self.v[b]) - DVec2::new(self.u[a], self.v[a]))
    }

    /// `uv` at column `j` of `below` minus `uv` at column `j` of `self`.
    #[inline(always)]
    fn down(&self, below: &Row, j: usize) -> Option<DVec2> {
        (self.ok[j] & below.ok[j])
            .then(|| DVec2::new(below.u[j], below.v[j]) - DVec2::new(self.u[j], self.v[j]))
    }
}

impl UvPlanes {
    /// The planes of row `y`, `P0 + Py (y - y_origin)`: the first two terms
    /// of each of [`planes_at_offset`](Self::planes_at_offset)'s sums.
    #[inline(always)]
    fn row_start(&self, y: i64) -> [f64; 3] {
        let dy = (y - self.origin.1) as f64;
        let start = |p: &Plane| p.at + p.dy * dy;
        [start(&self.u), start(&self.v), start(&self.r)]
    }

    /// The coordinate at the [`COLUMNS`] pixels from `(x, y)` rightwards.
    #[inline(always)]
    fn row(&self, x: i64, y: i64) -> Row {
        let [u0, v0, r0] = self.row_start(y);
        let mut row = Row {
            u: [0.0; COLUMNS],
            v: [0.0; COLUMNS],
            ok: [false; COLUMNS],
        };
        for j in 0..COLUMNS {
            let dx = (x + j as i64 - self.origin.0) as f64;
            let r = r0 + self.r.dx * dx;
            row.ok[j] = r > 0.0;
            row.u[j] = (u0 + self.u.dx * dx) / r;
            row.v[j] = (v0 + self.v.dx * dx) / r;
        }
        row
    }

    /// [`derivatives`](Self::derivatives) by `method` at the pixels
    /// `(x + k, y)` for `k` in `0..LANES`, lane `k` in element `k`, each
    /// the bits the one-pixel method gives.
    ///
    /// ```
    /// use glam::{Vec2, Vec4};
    /// use rasterlab::raster::{Derivatives, FillRule, FixedPoint, ShadedVertex, TriangleSetup, UvPlanes, Varyings};
    ///
    /// let p = [(0.0, 0.0), (40.0, 0.0), (0.0, 40.0)];
    /// let setup = TriangleSetup::new(0, p.map(|(x, y)| FixedPoint::snap_f64(x, y).unwrap()), FillRule::TopLeft).unwrap();
    /// let vertex = |u: f32, v: f32, inv_w: f32| ShadedVertex {
    ///     depth: 0.5,
    ///     inv_w,
    ///     varyings: Varyings { uv: Vec2::new(u, v), ..Varyings::color(Vec4::ONE) },
    /// };
    /// let planes = UvPlanes::new(&setup, [vertex(0.0, 0.0, 1.0), vertex(2.0, 0.0, 0.25), vertex(0.0, 1.0, 1.0)], true);
    /// let lanes = planes.derivatives_lanes(Derivatives::Quad, 3, 5);
    /// for (k, lane) in lanes.iter().enumerate() {
    ///     assert_eq!(*lane, planes.derivatives(Derivatives::Quad, 3 + k as i64, 5));
    /// }
    /// ```
    #[inline(always)]
    pub fn derivatives_lanes(&self, method: Derivatives, x: i64, y: i64) -> [Gradient; LANES] {
        match method {
            Derivatives::Analytic => self.analytic_lanes(x, y),
            Derivatives::Quad => self.quad_lanes(x, y),
            Derivatives::Forward => self.forward_lanes(x, y),
        }
    }

    #[inline(always)]
    fn analytic_lanes(&self, x: i64, y: i64) -> [Gradient; LANES] {
        let [u0, v0, r0] = self.row_start(y);
        let mut out = [Gradient::default(); LANES];
        for k in 0..LANES {
            let dx = (x + k as i64 - self.origin.0) as f64;
            let r = r0 + self.r.dx * dx;
            let uv = DVec2::new(u0 + self.u.dx * dx, v0 + self.v.dx * dx) / r;
            let q_dx = DVec2::new(self.u.dx, self.v.dx);
            let q_dy = DVec2::new(self.u.dy, self.v.dy);
            let (gx, gy) = ((q_dx - uv * self.r.dx) / r, (q_dy - uv * self.r.dy) / r);
            if r > 0.0 {
                out[k] = gradient(gx, gy);
            }
        }
        out
    }

    #[inline(always)]
    fn quad_lanes(&self, x: i64, y: i64) -> [Gradient; LANES] {
        // The group's quads start at the even column at or left of `x`,
        // and their two rows at the even row at or above `y`.
        let (first, top) = (x & !1, y & !1);
        let rows = [self.row(first, top), self.row(first, top + 1)];
        let (own, other) = (&rows[(y - top) as usize], &rows[(top + 1 - y) as usize]);
        let mut out = [Gradient::default(); LANES];
        for k in 0..LANES {
            let column = (x - first) as usize + k;
            let left = column & !1;
            let dx = own
                .difference(left, left + 1)
                .or_else(|| other.difference(left, left + 1));
            let dy = rows[0]
                .down(&rows[1], column)
                .or_else(|| rows[0].down(&rows[1], column ^ 1));
            out[k] = gradient(dx.unwrap_or_default(), dy.unwrap_or_default());
        }
        out
    }

    #[inline(always)]
    fn forward_lanes(&self, x: i64, y: i64) -> [Gradient; LANES] {
        // Column `j` is pixel `x - 1 + j`: lane `k` is column `k + 1`.
        let (row, below) = (self.row(x - 1, y), self.row(x - 1, y + 1));
        let mut above = None;
        let mut out = [Gradient::default(); LANES];
        for k in 0..LANES {
            let j = k + 1;
            let dx = row
                .difference(j, j + 1)
                .or_else(|| row.difference(j - 1, j));
            let dy = row.down(&below, j).or_else(|| {
                let above = above.get_or_insert_with(|| self.row(x - 1, y - 1));
                above.down(&row, j)
            });
            out[k] = gradient(dx.unwrap_or_default(), dy.unwrap_or_default());
        }
        out
    }
}

/// The derivatives in `f32`, as [`UvPlanes::derivatives`] rounds them.
#[inline(always)]
fn gradient(dx: DVec2, dy: DVec2) -> Gradient {
    Gradient {
        dx: Vec2::new(dx.x as f32, dx.y as f32),
        dy: Vec2::new(dy.x as f32, dy.y as f32),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::fixed::FixedPoint;
    use crate::raster::primitive::ShadedVertex;
    use crate::raster::{FillRule, TriangleSetup, Varyings};
    use glam::Vec4;

    /// Random triangles in perspective, some with a vertex far behind the
    /// others so that helpers and neighbours reach past the horizon, and
    /// groups of eight starting on even and odd columns and rows, inside,
    /// across and outside the triangle: every lane is the one-pixel
    /// method's derivatives, bit for bit, under all three methods.
    #[test]
    fn every_lane_is_the_one_pixel_derivative_bit_for_bit() {
        let mut rng = fastrand::Rng::with_seed(59);
        let mut fallbacks = 0;
        for n in 0..4_000 {
            let mut p = || (rng.f64() * 64.0, rng.f64() * 64.0);
            let points = [p(), p(), p()];
            let snapped = points.map(|(x, y)| FixedPoint::snap_f64(x, y).unwrap());
            let Some(setup) = TriangleSetup::new(0, snapped, FillRule::TopLeft) else {
                continue;
            };
            let far = if n % 3 == 0 { 1e-3 } else { 0.05 + rng.f32() };
            let near = 0.5 + rng.f32();
            let mut vertex = |inv_w: f32| ShadedVertex {
                depth: 0.5,
                inv_w,
                varyings: Varyings {
                    uv: Vec2::new(rng.f32() * 4.0 - 1.0, rng.f32() * 4.0 - 1.0),
                    ..Varyings::color(Vec4::ONE)
                },
            };
            let vertices = [vertex(1.0), vertex(far), vertex(near)];
            let planes = UvPlanes::new(&setup, vertices, n % 5 != 0);
            for _ in 0..8 {
                let (x, y) = (rng.i64(-4..70), rng.i64(-4..70));
                for method in [
                    Derivatives::Analytic,
                    Derivatives::Quad,
                    Derivatives::Forward,
                ] {
                    let lanes = planes.derivatives_lanes(method, x, y);
                    for (k, lane) in lanes.iter().enumerate() {
                        let one = planes.derivatives(method, x + k as i64, y);
                        let bits =
                            |g: &Gradient| [g.dx, g.dy].map(|d| d.to_array().map(f32::to_bits));
                        assert_eq!(bits(lane), bits(&one), "{method} ({x}, {y}) lane {k}");
                        fallbacks += usize::from(
                            method == Derivatives::Forward
                                && planes.uv_at(x + k as i64, y + 1).is_none()
                                && planes.uv_at(x + k as i64, y).is_some(),
                        );
                    }
                }
            }
        }
        // The rows above were read: some pixels fell back.
        assert!(fallbacks > 100, "{fallbacks} backward differences");
    }
}

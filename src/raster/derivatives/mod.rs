//! Screen-space derivatives of a triangle's texture coordinate, three
//! ways: what a texture's level of detail is computed from.
//!
//! After the perspective divide, `u / w`, `v / w` and `1 / w` are affine in
//! screen space (the interpolation of the course's perspective-correct
//! attributes), so each is a plane `P(x, y) = P0 + Px x + Py y` through the
//! three snapped vertices, and `u = (u / w) / (1 / w)`. The planes are set
//! up from the triangle's exact edge functions, as the depth plane is, in
//! `f64`: a derivative depends only on the triangle and the pixel, never on
//! the order a back-end walks the pixels in, so every back-end gives the
//! same derivatives and the same image.
//!
//! * [`Derivatives::Analytic`]: the exact derivative at the pixel centre,
//!   `d(q / r)/dx = (qx - (q / r) rx) / r` for `q = u / w`, `r = 1 / w`.
//! * [`Derivatives::Quad`]: as GPUs compute `dFdx` and `dFdy`, by
//!   differences within 2x2 quads aligned to even pixels. They are the
//!   *fine* differences of the OpenGL Shading Language 4.50 specification
//!   (section 8.14.1, `dFdxFine` and `dFdyFine`): `dFdx` is taken on the
//!   pixel's own row of its quad, `dFdy` on its own column. A quad's
//!   pixels outside the triangle run as helper pixels: they extrapolate
//!   the planes and are never written. Where a helper's `1 / w` is at or
//!   below zero (it lies beyond the triangle's horizon, so its coordinate
//!   means nothing), the difference is taken on the quad's other row (for
//!   `dFdx`) or column (for `dFdy`); when that one has such a pixel too,
//!   the derivative is zero, which reads level 0.
//! * [`Derivatives::Forward`]: CS184's, the coordinate at `(x + 1, y)` and
//!   at `(x, y + 1)` minus its value at `(x, y)`. Where the neighbour's
//!   `1 / w` is at or below zero, the backward difference (`(x, y)` minus
//!   `(x - 1, y)`, and the same in `y`) is taken, and zero when that too
//!   fails.
//!
//! ```
//! use glam::{Vec2, Vec4};
//! use rasterlab::raster::{Derivatives, FillRule, FixedPoint, ShadedVertex, TriangleSetup, UvPlanes, Varyings};
//!
//! // A triangle whose uv grows 1/8 a pixel to the right and 1/16 a pixel
//! // down, w = 1: every method gives those exactly.
//! let p = [(0.0, 0.0), (16.0, 0.0), (0.0, 16.0)];
//! let setup = TriangleSetup::new(0, p.map(|(x, y)| FixedPoint::snap_f64(x, y).unwrap()), FillRule::TopLeft).unwrap();
//! let vertex = |u: f32, v: f32| ShadedVertex {
//!     depth: 0.5,
//!     inv_w: 1.0,
//!     varyings: Varyings { uv: Vec2::new(u, v), ..Varyings::color(Vec4::ONE) },
//! };
//! let planes = UvPlanes::new(&setup, [vertex(0.0, 0.0), vertex(2.0, 0.0), vertex(0.0, 1.0)], true);
//! for method in [Derivatives::Analytic, Derivatives::Quad, Derivatives::Forward] {
//!     let d = planes.derivatives(method, 3, 5);
//!     assert_eq!((d.dx, d.dy), (Vec2::new(0.125, 0.0), Vec2::new(0.0, 0.0625)));
//! }
//! ```

use crate::raster::edge::{PixelRect, TriangleSetup};
use crate::raster::fixed::SUBPIXEL_SCALE;
use crate::raster::fragment::FragmentList;
use crate::raster::primitive::ShadedVertex;
use crate::raster::triangle::TriangleRasterizer;
use glam::{DVec2, Vec2};

mod lanes;

/// How the screen-space derivatives of a fragment's texture coordinate
/// are computed.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Derivatives {
    /// Exact, from the triangle's plane equations.
    #[default]
    Analytic,
    /// Fine differences within 2x2 quads, helper pixels extrapolated.
    Quad,
    /// Forward differences to the right and down neighbours (CS184).
    Forward,
}

crate::names::named_enum!(
    Derivatives,
    "derivative method",
    Analytic = "analytic",
    Quad = "quad",
    Forward = "forward"
);

/// The derivatives of the texture coordinate at one pixel.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct Gradient {
    /// `(du/dx, dv/dx)`: one pixel to the right.
    pub dx: Vec2,
    /// `(du/dy, dv/dy)`: one pixel down.
    pub dy: Vec2,
}

/// A plane over pixel centres: its value at the origin pixel and its
/// change per pixel right and down.
#[derive(Copy, Clone, Debug, PartialEq)]
struct Plane {
    at: f64,
    dx: f64,
    dy: f64,
}

/// A triangle's `u / w`, `v / w` and `1 / w` as planes in screen space.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct UvPlanes {
    origin: (i64, i64),
    u: Plane,
    v: Plane,
    r: Plane,
}

impl UvPlanes {
    /// The planes of the triangle `setup` whose vertices (in the set-up's
    /// order) are `vertices`; with `perspective` false the coordinate is
    /// affine in screen space (every `1 / w` taken as 1), as the stage's
    /// linear interpolation has it.
    pub fn new(setup: &TriangleSetup, vertices: [ShadedVertex; 3], perspective: bool) -> UvPlanes {
        let (ox, oy) = (setup.bounds.x0, setup.bounds.y0);
        let e = setup.edge_values_at_pixel(ox, oy);
        let [_, e1, e2] = setup.edges;
        let area = setup.area as f64;
        let scale = SUBPIXEL_SCALE as f64;
        let plane = |a: [f64; 3]| {
            let (d1, d2) = (a[1] - a[0], a[2] - a[0]);
            Plane {
                at: a[0] + (d1 * e[1] as f64 + d2 * e[2] as f64) / area,
                dx: (d1 * e1.a as f64 + d2 * e2.a as f64) * scale / area,
                dy: (d1 * e1.b as f64 + d2 * e2.b as f64) * scale / area,
            }
        };
        let r = vertices.map(|v| if perspective { f64::from(v.inv_w) } else { 1.0 });
        let u = [0, 1, 2].map(|i| f64::from(vertices[i].varyings.uv.x) * r[i]);
        let v = [0, 1, 2].map(|i| f64::from(vertices[i].varyings.uv.y) * r[i]);
        UvPlanes {
            origin: (ox, oy),
            u: plane(u),
            v: plane(v),
            r: plane(r),
        }
    }

    /// The three planes' values at the centre of pixel `(x, y)`.
    fn planes_at(&self, x: i64, y: i64) -> (f64, f64, f64) {
        self.planes_at_offset((x - self.origin.0) as f64, (y - self.origin.1) as f64)
    }

    /// The three planes' values `(dx, dy)` pixels from the origin's centre.
    fn planes_at_offset(&self, dx: f64, dy: f64) -> (f64, f64, f64) {
        let at = |p: &Plane| p.at + p.dy * dy + p.dx * dx;
        (at(&self.u), at(&self.v), at(&self.r))
    }

    /// The coordinate at the screen point `(x, y)` (pixel `(i, j)` covers
    /// `[i, i + 1) x [j, j + 1)`), as [`uv_at`](Self::uv_at) gives it at a
    /// centre: what a ground truth integrates over a pixel's square.
    pub fn uv_at_point(&self, x: f64, y: f64) -> Option<DVec2> {
        let dx = x - 0.5 - self.origin.0 as f64;
        let dy = y - 0.5 - self.origin.1 as f64;
        let (u, v, r) = self.planes_at_offset(dx, dy);
        (r > 0.0).then(|| DVec2::new(u / r, v / r))
    }

    /// The coordinate at the centre of pixel `(x, y)`, inside the triangle
    /// or extrapolated; `None` where `1 / w` is at or below zero.
    pub fn uv_at(&self, x: i64, y: i64) -> Option<DVec2> {
        let (u, v, r) = self.planes_at(x, y);
        (r > 0.0).then(|| DVec2::new(u / r, v / r))
    }

    /// The derivatives at pixel `(x, y)` by `method`.
    pub fn derivatives(&self, method: Derivatives, x: i64, y: i64) -> Gradient {
        let (dx, dy) = match method {
            Derivatives::Analytic => self.analytic(x, y),
            Derivatives::Quad => self.quad(x, y),
            Derivatives::Forward => self.forward(x, y),
        };
        Gradient {
            dx: dx.as_vec2(),
            dy: dy.as_vec2(),
        }
    }

    fn analytic(&self, x: i64, y: i64) -> (DVec2, DVec2) {
        let (u, v, r) = self.planes_at(x, y);
        if r <= 0.0 {
            return (DVec2::ZERO, DVec2::ZERO);
        }
        let uv = DVec2::new(u / r, v / r);
        let q_dx = DVec2::new(self.u.dx, self.v.dx);
        let q_dy = DVec2::new(self.u.dy, self.v.dy);
        ((q_dx - uv * self.r.dx) / r, (q_dy - uv * self.r.dy) / r)
    }

    /// `uv(b) - uv(a)`, when both have `1 / w > 0`.
    fn difference(&self, a: (i64, i64), b: (i64, i64)) -> Option<DVec2> {
        Some(self.uv_at(b.0, b.1)? - self.uv_at(a.0, a.1)?)
    }

    fn quad(&self, x: i64, y: i64) -> (DVec2, DVec2) {
        let (x0, y0) = (x & !1, y & !1);
        let (other_row, other_column) = (y0 + 1 - (y - y0), x0 + 1 - (x - x0));
        let dx = self
            .difference((x0, y), (x0 + 1, y))
            .or_else(|| self.difference((x0, other_row), (x0 + 1, other_row)));
        let dy = self
            .difference((x, y0), (x, y0 + 1))
            .or_else(|| self.difference((other_column, y0), (other_column, y0 + 1)));
        (dx.unwrap_or_default(), dy.unwrap_or_default())
    }

    fn forward(&self, x: i64, y: i64) -> (DVec2, DVec2) {
        let dx = self
            .difference((x, y), (x + 1, y))
            .or_else(|| self.difference((x - 1, y), (x, y)));
        let dy = self
            .difference((x, y), (x, y + 1))
            .or_else(|| self.difference((x, y - 1), (x, y)));
        (dx.unwrap_or_default(), dy.unwrap_or_default())
    }
}

/// The helper pixels one triangle's fragments bring in when shaded in 2x2
/// quads aligned to even pixels: four for each quad the fragments touch,
/// less the fragments (quad overshading). `pixels` are one triangle's
/// fragments, each pixel once.
pub fn quad_helpers(pixels: impl IntoIterator<Item = (u32, u32)>) -> u64 {
    let mut quads: Vec<(u32, u32)> = pixels.into_iter().map(|(x, y)| (y / 2, x / 2)).collect();
    let count = quads.len() as u64;
    quads.sort_unstable();
    quads.dedup();
    4 * quads.len() as u64 - count
}

/// The helper pixels themselves, `(x, y)` in order: the pixels of each
/// 2x2 quad (aligned to even pixels) that one triangle's fragments
/// `pixels` touch, which are not among them. There are
/// [`quad_helpers`] of them.
pub fn quad_helper_pixels(pixels: &[(u32, u32)]) -> Vec<(u32, u32)> {
    let mut quads: Vec<(u32, u32)> = pixels.iter().map(|&(x, y)| (y / 2, x / 2)).collect();
    quads.sort_unstable();
    quads.dedup();
    let drawn: std::collections::HashSet<(u32, u32)> = pixels.iter().copied().collect();
    quads
        .into_iter()
        .flat_map(|(qy, qx)| {
            [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(i, j)| (2 * qx + i, 2 * qy + j))
        })
        .filter(|p| !drawn.contains(p))
        .collect()
}

/// The helper pixels of drawing `setups` with `backend` on the pixels of
/// `rect`: each triangle rasterized on its own and its fragments counted
/// by [`quad_helpers`]. A triangle's fragments are never shaded twice,
/// and two triangles never share a quad's helpers, as on a GPU, where
/// each triangle's quads are shaded apart.
pub fn count_quad_helpers(
    setups: &[TriangleSetup],
    backend: &dyn TriangleRasterizer,
    rect: PixelRect,
) -> u64 {
    let mut helpers = 0;
    each_triangle_pixels(setups, backend, rect, |_, pixels| {
        helpers += quad_helpers(pixels.iter().copied());
    });
    helpers
}

/// Rasterizes each of `setups` on its own with `backend` on the pixels of
/// `rect`, as quads are shaded (a triangle's quads are its own), and
/// gives `visit` the triangle and its fragments' pixels, in the
/// back-end's order.
pub fn each_triangle_pixels(
    setups: &[TriangleSetup],
    backend: &dyn TriangleRasterizer,
    rect: PixelRect,
    mut visit: impl FnMut(&TriangleSetup, &[(u32, u32)]),
) {
    let mut list = FragmentList::default();
    let mut pixels = Vec::new();
    for setup in setups {
        list.triangles.clear();
        backend.rasterize(std::slice::from_ref(setup), rect, &mut list);
        pixels.clear();
        pixels.extend(list.triangles.iter().map(|f| (f.x, f.y)));
        visit(setup, &pixels);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::fixed::FixedPoint;
    use crate::raster::FillRule;
    use glam::Vec4;

    fn vertex(uv: (f32, f32), inv_w: f32) -> ShadedVertex {
        ShadedVertex {
            depth: 0.5,
            inv_w,
            varyings: crate::raster::Varyings {
                uv: Vec2::new(uv.0, uv.1),
                ..crate::raster::Varyings::color(Vec4::ONE)
            },
        }
    }

    fn setup(p: [(f64, f64); 3]) -> TriangleSetup {
        let v = p.map(|(x, y)| FixedPoint::snap_f64(x, y).unwrap());
        TriangleSetup::new(0, v, FillRule::TopLeft).unwrap()
    }

    /// A triangle in perspective (1/w from 1 to 1/8): the analytic
    /// derivative is the limit the differences approach, and the forward
    /// and quad differences are the coordinate's exact change over one
    /// pixel.
    #[test]
    fn the_three_methods_agree_with_the_coordinate() {
        let s = setup([(2.0, 60.0), (62.0, 60.0), (32.0, 4.0)]);
        let planes = UvPlanes::new(
            &s,
            [
                vertex((0.0, 1.0), 1.0),
                vertex((1.0, 1.0), 1.0),
                vertex((0.5, 0.0), 0.125),
            ],
            true,
        );
        let (x, y) = (31, 20);
        let at = |x, y| planes.uv_at(x, y).unwrap().as_vec2();
        let forward = planes.derivatives(Derivatives::Forward, x, y);
        assert_eq!(
            forward.dx,
            (planes.uv_at(x + 1, y).unwrap() - planes.uv_at(x, y).unwrap()).as_vec2()
        );
        assert!((forward.dy - (at(x, y + 1) - at(x, y))).abs().max_element() < 1e-7);
        // Pixel (31, 20) is the right column and top row of its quad (30, 20).
        let quad = planes.derivatives(Derivatives::Quad, x, y);
        assert!((quad.dx - (at(31, 20) - at(30, 20))).abs().max_element() < 1e-7);
        assert!((quad.dy - (at(31, 21) - at(31, 20))).abs().max_element() < 1e-7);
        // The analytic one lies between the backward and forward differences.
        let analytic = planes.derivatives(Derivatives::Analytic, x, y);
        let backward = at(x, y) - at(x, y - 1);
        let (lo, hi) = (backward.y.min(forward.dy.y), backward.y.max(forward.dy.y));
        assert!(lo <= analytic.dy.y && analytic.dy.y <= hi, "{analytic:?}");
    }

    /// A triangle whose 1/w falls from 1 to 0.001 across its 4.5 pixels:
    /// pixel (4, 0) is inside with 1/w = 0.112, its quad's helper (5, 0)
    /// outside with an extrapolated 1/w of -0.11, past the horizon.
    /// `far` is the third vertex's 1/w, which sets how 1/w changes down.
    fn near_the_horizon(far: f32) -> UvPlanes {
        let s = setup([(0.5, 0.5), (5.0, 0.5), (0.5, 8.5)]);
        assert!(s.inside(s.edge_values_at_pixel(4, 0)));
        assert!(!s.inside(s.edge_values_at_pixel(5, 0)));
        let v = [
            vertex((0.0, 0.0), 1.0),
            vertex((1.0, 0.0), 0.001),
            vertex((0.0, 1.0), far),
        ];
        UvPlanes::new(&s, v, true)
    }

    /// Where the helper's row of the quad is past the horizon, the quad's
    /// other row gives dFdx; forward differences fall back to backward.
    #[test]
    fn a_helper_past_the_horizon_gives_way_to_the_other_row() {
        // 1/w grows 0.25 a pixel down: (5, 1) is in front again.
        let planes = near_the_horizon(3.0);
        assert!(planes.uv_at(5, 0).is_none() && planes.uv_at(4, 0).is_some());
        let other_row = planes.uv_at(5, 1).unwrap() - planes.uv_at(4, 1).unwrap();
        let quad = planes.derivatives(Derivatives::Quad, 4, 0);
        assert_eq!(quad.dx, other_row.as_vec2());
        let forward = planes.derivatives(Derivatives::Forward, 4, 0);
        let backward = planes.uv_at(4, 0).unwrap() - planes.uv_at(3, 0).unwrap();
        assert_eq!(forward.dx, backward.as_vec2());
    }

    /// When both rows of the quad reach past the horizon, dFdx is zero
    /// (level 0 is read); dFdy, on the pixel's own column, is not.
    #[test]
    fn with_no_row_in_front_the_derivative_is_zero() {
        // 1/w does not change down: (5, 1) is past the horizon too.
        let planes = near_the_horizon(1.0);
        assert!(planes.uv_at(5, 1).is_none());
        let quad = planes.derivatives(Derivatives::Quad, 4, 0);
        assert_eq!(quad.dx, Vec2::ZERO);
        assert_ne!(quad.dy, Vec2::ZERO);
        let analytic = planes.derivatives(Derivatives::Analytic, 4, 0);
        assert!(analytic.dx.x > 0.0);
    }

    #[test]
    fn helpers_fill_the_quads_a_triangle_touches() {
        assert_eq!(quad_helpers([(0, 0)]), 3);
        assert_eq!(quad_helpers([(0, 0), (1, 0), (0, 1), (1, 1)]), 0);
        assert_eq!(quad_helpers([(1, 1), (2, 1)]), 6);
        assert_eq!(quad_helpers([]), 0);
        assert_eq!(quad_helper_pixels(&[(0, 0)]), [(1, 0), (0, 1), (1, 1)]);
        assert_eq!(
            quad_helper_pixels(&[(1, 1), (2, 1)]),
            [(0, 0), (1, 0), (0, 1), (2, 0), (3, 0), (3, 1)]
        );
    }
}

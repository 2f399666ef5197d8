//! What the fragment stage reads of a draw's primitives: per vertex its
//! screen depth, `1 / w` and varyings; per triangle its vertex indices and
//! depth plane; per line its end points. The pipeline writes them, the
//! stage interpolates them, shaders read the interpolated varyings.

use crate::raster::edge::TriangleSetup;
use crate::raster::fixed::{FixedPoint, SUBPIXEL_SCALE};
use glam::{Vec2, Vec3, Vec4};

/// Per-vertex values interpolated across a primitive.
#[derive(Copy, Clone, Debug, Default, PartialEq, bytemuck::Zeroable)]
pub struct Varyings {
    /// Linear RGBA colour in `[0, 1]`.
    pub color: Vec4,
    /// Texture coordinates.
    pub uv: Vec2,
    /// Normal (world space), not necessarily unit length after interpolation.
    pub normal: Vec3,
}

impl Varyings {
    /// Varyings holding only a colour.
    pub fn color(color: Vec4) -> Varyings {
        Varyings {
            color,
            ..Varyings::default()
        }
    }

    /// The weighted sum `sum(w[i] * v[i])`.
    pub fn weighted<const N: usize>(v: &[Varyings; N], w: [f32; N]) -> Varyings {
        let mut out = Varyings {
            color: Vec4::ZERO,
            uv: Vec2::ZERO,
            normal: Vec3::ZERO,
        };
        for (vi, wi) in v.iter().zip(w) {
            out.color += vi.color * wi;
            out.uv += vi.uv * wi;
            out.normal += vi.normal * wi;
        }
        out
    }
}

/// A vertex as the fragment stage needs it: screen depth, `1 / w` and varyings.
#[derive(Copy, Clone, Debug, PartialEq, bytemuck::Zeroable)]
pub struct ShadedVertex {
    /// Depth in `[0, 1]` after the viewport transform (0 near, 1 far).
    pub depth: f32,
    /// `1 / w` of the clip-space position (1 for 2D input).
    pub inv_w: f32,
    /// Values to interpolate.
    pub varyings: Varyings,
}

impl ShadedVertex {
    /// A 2D vertex (`w = 1`) with a depth and a colour.
    pub fn flat(depth: f32, color: Vec4) -> ShadedVertex {
        ShadedVertex {
            depth,
            inv_w: 1.0,
            varyings: Varyings::color(color),
        }
    }
}

/// A triangle's depth as a plane in screen space.
///
/// Depth is affine in screen space after the perspective divide, so it is
/// the plane through the three snapped vertices. It is set up from the
/// triangle's exact edge functions, relative to the first pixel of its
/// bounding box, and evaluated as `(z_origin + dz_dy * dy) + dz_dx * dx` in
/// `f32`: the row term first, then the column term, always in this order, so
/// every back-end and every code path gets bit-identical depths.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct DepthPlane {
    /// Pixel column of the origin. (Pixel coordinates fit in `i32`
    /// anywhere in the guard band; 64-bit ones made each stage triangle 48
    /// bytes instead of 32.)
    pub origin_x: i32,
    /// Pixel row of the origin.
    pub origin_y: i32,
    /// Depth at the origin pixel's centre.
    pub z_origin: f32,
    /// Change of depth per pixel to the right.
    pub dz_dx: f32,
    /// Change of depth per pixel down.
    pub dz_dy: f32,
}

impl DepthPlane {
    /// The plane through the triangle's snapped vertices at depths `z`
    /// (vertex `i` at depth `z[i]`).
    ///
    /// With `E_i` the edge function opposite vertex `i` and `A` twice the
    /// area, `z = z0 + ((z1 - z0) E1 + (z2 - z0) E2) / A`; its slopes are
    /// the edge functions' coefficients weighted the same way.
    pub fn new(setup: &TriangleSetup, z: [f32; 3]) -> DepthPlane {
        let [z0, z1, z2] = z.map(f64::from);
        let (d1, d2) = (z1 - z0, z2 - z0);
        let area = setup.area as f64;
        let (ox, oy) = (setup.bounds.x0, setup.bounds.y0);
        let e = setup.edge_values_at_pixel(ox, oy);
        let [_, e1, e2] = setup.edges;
        let scale = SUBPIXEL_SCALE as f64;
        // The box's first pixel, found from snapped coordinates that are
        // `i32` in 1/256 pixel: its column and row fit in `i32` as they are.
        DepthPlane {
            origin_x: ox as i32,
            origin_y: oy as i32,
            z_origin: (z0 + (d1 * e[1] as f64 + d2 * e[2] as f64) / area) as f32,
            dz_dx: ((d1 * e1.a as f64 + d2 * e2.a as f64) * scale / area) as f32,
            dz_dy: ((d1 * e1.b as f64 + d2 * e2.b as f64) * scale / area) as f32,
        }
    }

    /// A plane of constant depth.
    pub fn constant(z: f32) -> DepthPlane {
        DepthPlane {
            origin_x: 0,
            origin_y: 0,
            z_origin: z,
            dz_dx: 0.0,
            dz_dy: 0.0,
        }
    }

    /// The depth at the start of row `y`, before the column term.
    #[inline]
    pub fn row(&self, y: u32) -> f32 {
        self.z_origin + self.dz_dy * (i64::from(y) - i64::from(self.origin_y)) as f32
    }

    /// The depth at column `x` of a row whose [`row`](Self::row) value is
    /// `row`, clamped to `[0, 1]` as Direct3D and Vulkan clamp to the
    /// viewport's depth range (rounding in a huge clipped triangle's plane
    /// can otherwise step outside it).
    #[inline]
    pub fn in_row(&self, row: f32, x: u32) -> f32 {
        self.in_row_at_offset(row, (i64::from(x) - i64::from(self.origin_x)) as f32)
    }

    /// [`in_row`](Self::in_row) for the column `dx` pixels right of the
    /// origin (`dx` an integer, given as `f32`).
    #[inline(always)]
    pub(crate) fn in_row_at_offset(&self, row: f32, dx: f32) -> f32 {
        (row + self.dz_dx * dx).clamp(0.0, 1.0)
    }

    /// The depth at the centre of pixel `(x, y)`.
    #[inline]
    pub fn at(&self, x: u32, y: u32) -> f32 {
        self.in_row(self.row(y), x)
    }

    /// The depth `(dx, dy)` pixels from the centre of pixel `(x, y)` (a
    /// multisample's offset), clamped as [`in_row`](Self::in_row). At
    /// offset `(0, 0)` it is the very bits of [`at`](Self::at).
    #[inline]
    pub fn at_offset(&self, x: u32, y: u32, dx: f32, dy: f32) -> f32 {
        let row =
            self.z_origin + self.dz_dy * ((i64::from(y) - i64::from(self.origin_y)) as f32 + dy);
        self.in_row_at_offset(row, (i64::from(x) - i64::from(self.origin_x)) as f32 + dx)
    }
}

/// A triangle as the fragment stage needs it: which vertices, and its
/// depth plane.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ShadedTriangle {
    /// Indices of its three vertices in [`TriangleData::vertices`], in the
    /// order of the set-up.
    pub vertices: [u32; 3],
    /// The depth plane through the snapped vertices.
    pub depth: DepthPlane,
}

impl ShadedTriangle {
    /// Pairs a set-up triangle with its vertices (indices) and their depths.
    pub fn new(setup: &TriangleSetup, vertices: [u32; 3], depths: [f32; 3]) -> ShadedTriangle {
        ShadedTriangle {
            vertices,
            depth: DepthPlane::new(setup, depths),
        }
    }
}

/// The fragment stage's data for the triangles of a draw: the vertices,
/// shared between triangles as in an index buffer, and per triangle id its
/// three vertex indices and depth plane.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleData {
    /// Vertex data, shared by index.
    pub vertices: Vec<ShadedVertex>,
    /// Entry `i` belongs to the triangle with id `i`.
    pub triangles: Vec<ShadedTriangle>,
}

impl TriangleData {
    /// The data for triangles given by their own three vertices each:
    /// `vertices[i]` for the triangle with id `i`. Those without a set-up
    /// (zero area) get a constant depth, as they produce no fragment.
    pub fn of_triangles(setups: &[TriangleSetup], vertices: &[[ShadedVertex; 3]]) -> TriangleData {
        let mut triangles: Vec<ShadedTriangle> = (0..vertices.len() as u32)
            .map(|i| ShadedTriangle {
                vertices: [3 * i, 3 * i + 1, 3 * i + 2],
                depth: DepthPlane::constant(vertices[i as usize][0].depth),
            })
            .collect();
        for s in setups {
            if let Some(slot) = triangles.get_mut(s.id as usize) {
                slot.depth = DepthPlane::new(s, vertices[s.id as usize].map(|v| v.depth));
            }
        }
        TriangleData {
            vertices: vertices.iter().flatten().copied().collect(),
            triangles,
        }
    }
}

/// A line segment as the fragment stage needs it.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ShadedLine {
    /// Snapped start point.
    pub from: FixedPoint,
    /// Snapped end point.
    pub to: FixedPoint,
    /// Start and end vertex data.
    pub vertices: [ShadedVertex; 2],
}

//! Clipping in homogeneous clip space (the software-rasterizer article).
//!
//! A clip-space point `(x, y, z, w)` is inside the view frustum when
//! `-w <= x, y, z <= w` (after the perspective divide the frustum is the
//! cube `[-1, 1]^3`). Tests on these inequalities are linear, so clipping
//! here, *before* the divide, is straightforward and never divides by a
//! `w` that is zero or negative.
//!
//! Planes clipped against, each as `distance(p) >= 0`:
//!
//! * **near** `z + w >= 0` and **far** `w - z >= 0`, exactly as in the software-rasterizer article;
//! * `w >= W_MIN`, so that no vertex with `w <= 0` survives even for
//!   projection matrices without a near plane;
//! * four **guard-band** planes `|x|, |y| <= g w`, placed so that every
//!   surviving vertex lands within [`GUARD_LIMIT_PX`] pixels of the origin
//!   after the viewport transform. The actual screen edges are *not*
//!   clipped against: the rasterizer's bounding box is clamped to the
//!   viewport, as in the software-rasterizer article, so only triangles reaching far outside the
//!   screen are cut, and only to keep their snapped coordinates exact.
//!
//! A triangle with all three vertices inside every plane is accepted as is
//! (the common case); one with all three outside the same plane is
//! rejected; any other is cut by Sutherland-Hodgman, one plane after the
//! other (each edge kept, dropped, or cut at the intersection, with the
//! varyings interpolated linearly in clip space), and the resulting convex
//! polygon (up to 3 + 7 vertices) is split into a fan of triangles sharing
//! its first vertex.

use super::options::ClipPlanes;
use crate::raster::fixed::GUARD_BAND;
use crate::raster::primitive::Varyings;
use glam::Vec4;

/// The smallest `w` kept by clipping.
pub const W_MIN: f32 = 1e-5;

/// How far from the screen origin, in pixels, clipped vertices may land
/// (half the guard band, so snapping never fails after rounding).
pub const GUARD_LIMIT_PX: f32 = (GUARD_BAND / 2) as f32;

/// A vertex in clip space with its varyings (the vertex shader's output).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ClipVertex {
    /// Homogeneous clip-space position.
    pub position: Vec4,
    /// Values to interpolate across the primitive.
    pub varyings: Varyings,
}

impl ClipVertex {
    /// The point `t` of the way from `self` to `other` (linear in clip
    /// space; the position is computed in `f64` so that no intermediate
    /// overflows for finite inputs).
    pub fn lerp(&self, other: &ClipVertex, t: f64) -> ClipVertex {
        let (a, b) = (self.position.as_dvec4(), other.position.as_dvec4());
        let t32 = t as f32;
        ClipVertex {
            position: (a + (b - a) * t).as_vec4(),
            varyings: Varyings::weighted(&[self.varyings, other.varyings], [1.0 - t32, t32]),
        }
    }
}

/// What clipping did with a primitive.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum ClipResult {
    /// Entirely inside: passed on unchanged.
    Inside,
    /// Entirely outside one plane: dropped.
    Outside,
    /// Cut: the polygon has this many vertices (0 when nothing was left).
    Cut(usize),
}

/// The clip volume for a viewport of a given size.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ClipVolume {
    /// Plane `i` keeps the points with `planes[i].dot(p) - offsets[i] >= 0`.
    planes: [Vec4; 7],
    offsets: [f32; 7],
}

/// Names of the planes, in the order of [`ClipVolume`]'s out-codes.
pub const PLANE_NAMES: [&str; 7] = [
    "near",
    "far",
    "w > 0",
    "guard left",
    "guard right",
    "guard top",
    "guard bottom",
];

impl ClipVolume {
    /// The clip volume for a `width` x `height` viewport.
    pub fn new(width: u32, height: u32) -> ClipVolume {
        // x_screen = (x/w + 1) * width / 2 must stay within GUARD_LIMIT_PX
        // of the origin: |x/w| <= 2 GUARD_LIMIT_PX / width - 1 (>= 1).
        let gx = 2.0 * GUARD_LIMIT_PX / width.max(1) as f32 - 1.0;
        let gy = 2.0 * GUARD_LIMIT_PX / height.max(1) as f32 - 1.0;
        ClipVolume {
            planes: [
                Vec4::new(0.0, 0.0, 1.0, 1.0),
                Vec4::new(0.0, 0.0, -1.0, 1.0),
                Vec4::new(0.0, 0.0, 0.0, 1.0),
                Vec4::new(1.0, 0.0, 0.0, gx),
                Vec4::new(-1.0, 0.0, 0.0, gx),
                Vec4::new(0.0, -1.0, 0.0, gy),
                Vec4::new(0.0, 1.0, 0.0, gy),
            ],
            offsets: [0.0, 0.0, W_MIN, 0.0, 0.0, 0.0, 0.0],
        }
    }

    /// The clip volume for a `width` x `height` viewport whose side planes
    /// are `planes`: the guard band's ([`ClipVolume::new`]), or the
    /// viewport's own sides, `|x| <= w` and `|y| <= w`.
    pub fn with_planes(width: u32, height: u32, planes: ClipPlanes) -> ClipVolume {
        let mut volume = ClipVolume::new(width, height);
        if planes == ClipPlanes::Viewport {
            for side in 3..7 {
                volume.planes[side].w = 1.0;
            }
        }
        volume
    }

    /// The guard-band factors `g`: the guard planes keep `|x| <= g[0] w`
    /// and `|y| <= g[1] w`.
    pub(crate) fn guard(&self) -> [f32; 2] {
        [self.planes[3].w, self.planes[5].w]
    }

    /// Signed distance-like value of `p` to plane `plane`, in `f64` so no
    /// finite `f32` input overflows.
    #[inline]
    fn distance(&self, plane: usize, p: Vec4) -> f64 {
        self.planes[plane].as_dvec4().dot(p.as_dvec4()) - f64::from(self.offsets[plane])
    }

    /// Bit `i` is set when `p` is outside plane `i` (Cohen-Sutherland
    /// style out-code). NaN coordinates count as outside every plane.
    #[inline(always)]
    pub fn outcode(&self, p: Vec4) -> u8 {
        let mut code = 0;
        for i in 0..7 {
            // NaN compares as "not greater or equal", so it is outside too.
            if self
                .distance(i, p)
                .partial_cmp(&0.0)
                .is_none_or(|o| o.is_lt())
            {
                code |= 1 << i;
            }
        }
        code
    }

    /// Clips a triangle whose vertices have the out-codes `codes`; when it
    /// must be cut, the convex polygon that is left is written to `polygon`
    /// (cleared first). Vertices must be finite.
    pub fn clip_triangle(
        &self,
        triangle: &[ClipVertex; 3],
        codes: [u8; 3],
        polygon: &mut Vec<ClipVertex>,
    ) -> ClipResult {
        if codes[0] | codes[1] | codes[2] == 0 {
            return ClipResult::Inside;
        }
        if codes[0] & codes[1] & codes[2] != 0 {
            return ClipResult::Outside;
        }
        polygon.clear();
        polygon.extend_from_slice(triangle);
        let mut next = Vec::with_capacity(10);
        for plane in 0..7 {
            if codes.iter().all(|c| c & (1 << plane) == 0) {
                continue;
            }
            self.clip_to_plane(plane, polygon, &mut next);
            std::mem::swap(polygon, &mut next);
            if polygon.len() < 3 {
                polygon.clear();
                return ClipResult::Cut(0);
            }
        }
        ClipResult::Cut(polygon.len())
    }

    /// One step of Sutherland-Hodgman: `polygon` cut by plane `plane`
    /// (an index of [`PLANE_NAMES`]) into `next` (cleared first). Each
    /// edge `a -> b` in turn: `a` is kept when inside (`distance >= 0`),
    /// and where the edge crosses the plane the point at `t = d_a / (d_a -
    /// d_b)` is added, its varyings interpolated.
    #[inline]
    pub fn clip_to_plane(&self, plane: usize, polygon: &[ClipVertex], next: &mut Vec<ClipVertex>) {
        next.clear();
        for i in 0..polygon.len() {
            let a = polygon[i];
            let b = polygon[(i + 1) % polygon.len()];
            let (da, db) = (
                self.distance(plane, a.position),
                self.distance(plane, b.position),
            );
            if da >= 0.0 {
                next.push(a);
            }
            if (da >= 0.0) != (db >= 0.0) {
                next.push(a.lerp(&b, da / (da - db)));
            }
        }
    }

    /// The value of plane `plane` (an index of [`PLANE_NAMES`]) at `p`:
    /// inside when `>= 0`, in `f64`.
    pub fn plane_value(&self, plane: usize, p: Vec4) -> f64 {
        self.distance(plane, p)
    }

    /// Clips a segment (parametric, Liang-Barsky style); `None` when
    /// nothing of it is inside. Vertices must be finite.
    pub fn clip_segment(&self, a: &ClipVertex, b: &ClipVertex) -> Option<[ClipVertex; 2]> {
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for plane in 0..7 {
            let (da, db) = (
                self.distance(plane, a.position),
                self.distance(plane, b.position),
            );
            if da < 0.0 && db < 0.0 {
                return None;
            }
            if da < 0.0 {
                t0 = t0.max(da / (da - db));
            } else if db < 0.0 {
                t1 = t1.min(da / (da - db));
            }
        }
        (t0 <= t1).then(|| [a.lerp(b, t0), a.lerp(b, t1)])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f32, y: f32, z: f32, w: f32) -> ClipVertex {
        ClipVertex {
            position: Vec4::new(x, y, z, w),
            varyings: Varyings::default(),
        }
    }

    #[test]
    fn a_triangle_crossing_the_near_plane_becomes_a_quad() {
        let clip = ClipVolume::new(100, 100);
        let mut poly = Vec::new();
        // One vertex behind the near plane (z < -w).
        let t = [v(0., 0., 0.5, 1.), v(1., 0., 0.5, 1.), v(0., 0., -3., 1.)];
        let codes = t.map(|v| clip.outcode(v.position));
        assert_eq!(clip.clip_triangle(&t, codes, &mut poly), ClipResult::Cut(4));
        for p in &poly {
            assert!(p.position.z >= -p.position.w - 1e-6);
        }
    }

    #[test]
    fn triangles_behind_the_camera_are_rejected() {
        let clip = ClipVolume::new(100, 100);
        let t = [
            v(0., 0., 0.5, -1.),
            v(1., 0., 0.5, -2.),
            v(0., 1., 0.5, -1.),
        ];
        let codes = t.map(|v| clip.outcode(v.position));
        assert_eq!(
            clip.clip_triangle(&t, codes, &mut Vec::new()),
            ClipResult::Outside
        );
    }

    #[test]
    fn nan_vertices_are_outside() {
        let clip = ClipVolume::new(100, 100);
        assert_eq!(clip.outcode(Vec4::NAN), 0x7f);
    }
}

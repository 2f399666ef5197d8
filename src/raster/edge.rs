//! Edge functions, fill rules and triangle set-up: the exact inside test.
//!
//! # The edge function
//!
//! For an edge from `A` to `B` and a sample `P`, the course's *implicit line
//! equation* (the course chapter) is
//!
//! ```text
//! line(A, B, P) = (B.y - A.y) * P.x + (A.x - B.x) * P.y + B.x * A.y - A.x * B.y
//! ```
//!
//! It is zero on the line through `A` and `B`, positive on one side and
//! negative on the other, and equals twice the signed area of the triangle
//! `(A, B, P)` (the rasterization slides' "edge side function"). Evaluated on snapped
//! coordinates (see [`crate::raster::fixed`]) it is an exact `i64`.
//!
//! # Triangle set-up
//!
//! [`TriangleSetup`] stores the three edge functions of a triangle
//! `(v0, v1, v2)`, with edge `i` **opposite** vertex `i`:
//! `E0 = line(v1, v2, P)`, `E1 = line(v2, v0, P)`, `E2 = line(v0, v1, P)`.
//! Then the barycentric coordinates are `alpha = E0 / area`,
//! `beta = E1 / area`, `gamma = E2 / area` with `area = E0(v0) = E1(v1) =
//! E2(v2)`, twice the signed area (the course chapter's `line(B,C,P) / line(B,C,A)`).
//! Triangles of either winding are accepted: when the area is negative, all
//! three edge functions and the area are negated, which leaves the
//! barycentrics unchanged and makes "inside" mean `E >= 0` on every edge.
//! Zero-area triangles (after snapping) produce no fragments.
//!
//! # Ties: fill rules
//!
//! A sample exactly on an edge (`E == 0`) needs a rule, or two triangles
//! sharing that edge would both draw it (or both miss it). Each
//! [`FillRule`] decides, per edge and once at set-up, whether that edge
//! *owns* its ties. The decision becomes an integer **bias**: `0` for an
//! edge that owns its ties, `-1` for one that does not. The inside test is
//! then `E + bias >= 0` on all three edges, the same for every back-end.
//!
//! ```
//! use rasterlab::raster::{FillRule, FixedPoint, TriangleSetup};
//!
//! // the rules' known answer: the 5x5 square split along its diagonal.
//! let p = |x: f32, y: f32| FixedPoint::snap(x, y).unwrap();
//! let upper = TriangleSetup::new(0, [p(0., 0.), p(5., 0.), p(5., 5.)], FillRule::TopLeft).unwrap();
//! let lower = TriangleSetup::new(1, [p(0., 5.), p(0., 0.), p(5., 5.)], FillRule::TopLeft).unwrap();
//! let count = |t: &TriangleSetup| {
//!     (0..5).flat_map(|j| (0..5).map(move |i| (i, j)))
//!         .filter(|&(i, j)| t.covers(FixedPoint::pixel_centre(i, j)))
//!         .count()
//! };
//! assert_eq!((count(&upper), count(&lower)), (15, 10));
//! ```

use crate::raster::fixed::{
    first_sample_at_or_after, last_sample_at_or_before, FixedPoint, SUBPIXEL_SCALE,
};
use std::fmt;

/// The implicit line equation `a * x + b * y + c` of a directed edge, in
/// fixed-point units (see the module docs).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct EdgeFunction {
    /// `B.y - A.y`: the change of `E` per fixed-point unit of x.
    pub a: i64,
    /// `A.x - B.x`: the change of `E` per fixed-point unit of y.
    pub b: i64,
    /// `B.x * A.y - A.x * B.y`.
    pub c: i64,
}

impl EdgeFunction {
    /// The course's `line(A, B, P)` for the directed edge `A -> B`.
    pub fn through(from: FixedPoint, to: FixedPoint) -> EdgeFunction {
        let (ax, ay) = (from.x.raw(), from.y.raw());
        let (bx, by) = (to.x.raw(), to.y.raw());
        EdgeFunction {
            a: by - ay,
            b: ax - bx,
            c: bx * ay - ax * by,
        }
    }

    /// `E(P)`, exactly.
    #[inline]
    pub fn eval(&self, p: FixedPoint) -> i64 {
        self.eval_raw(p.x.raw(), p.y.raw())
    }

    /// `E` at raw fixed-point coordinates (which may lie outside the guard
    /// band, up to `2^28` units, as the off-screen points do).
    #[inline]
    pub fn eval_raw(&self, x: i64, y: i64) -> i64 {
        self.a * x + self.b * y + self.c
    }

    /// The same line with the opposite orientation.
    pub fn negated(self) -> EdgeFunction {
        EdgeFunction {
            a: -self.a,
            b: -self.b,
            c: -self.c,
        }
    }

    /// Is this (inside-positive) edge a *top* or a *left* edge?
    ///
    /// With y growing down, the gradient `(a, b)` points into the triangle.
    /// A top edge is horizontal (`a == 0`) with the triangle below it
    /// (`b > 0`); a left edge is not horizontal and has the triangle to its
    /// right (`a > 0`).
    pub fn is_top_left(&self) -> bool {
        // `|` and `&`, not `||` and `&&`: whether an edge is a left edge is
        // a coin toss from one triangle to the next, and as a branch the
        // CPU guessed it wrong half the time.
        (self.a > 0) | ((self.a == 0) & (self.b > 0))
    }

    /// The kind of edge, for traces and pictures.
    pub fn kind(&self) -> EdgeKind {
        match (self.a.signum(), self.b.signum()) {
            (0, 1) => EdgeKind::Top,
            (0, _) => EdgeKind::Bottom,
            (1, _) => EdgeKind::Left,
            _ => EdgeKind::Right,
        }
    }
}

/// Where an (inside-positive) edge lies on its triangle.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum EdgeKind {
    /// Horizontal, triangle below.
    Top,
    /// Horizontal, triangle above.
    Bottom,
    /// Not horizontal, triangle to the right.
    Left,
    /// Not horizontal, triangle to the left.
    Right,
}

impl fmt::Display for EdgeKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            EdgeKind::Top => "top",
            EdgeKind::Bottom => "bottom",
            EdgeKind::Left => "left",
            EdgeKind::Right => "right",
        })
    }
}

/// How samples exactly on an edge are decided.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum FillRule {
    /// Direct3D / Vulkan / OpenGL: a tie belongs to the triangle when the
    /// edge is a top or a left edge. Watertight.
    #[default]
    TopLeft,
    /// The mirror image: bottom and right edges own their ties. Watertight.
    BottomRight,
    /// Top and right edges own their ties (GDAL's `rasterize` draws so).
    /// Watertight.
    TopRight,
    /// Bottom and left edges own their ties: the top-left rule of a
    /// window whose origin is at the lower left (OpenGL's), seen in y-down
    /// screen coordinates. Watertight.
    BottomLeft,
    /// The line-drawing slides' robust strategy: an edge belongs to the triangle lying on
    /// the same side of it as a chosen off-screen point
    /// ([`OFFSCREEN_POINT`]); when the edge's line runs through that point,
    /// a secondary point ([`SECONDARY_OFFSCREEN_POINT`]) decides. Watertight.
    OffscreenPoint,
    /// Every edge owns its ties (`E >= 0`, the course chapter's `0 <= alpha <= 1`):
    /// shared edges are drawn twice.
    Inclusive,
    /// No edge owns its ties (`E > 0`): shared edges are drawn by neither
    /// triangle, leaving gaps.
    Exclusive,
}

/// The off-screen point of [`FillRule::OffscreenPoint`], in fixed-point
/// units: pixel (-100000, -70000), far outside the guard band.
pub const OFFSCREEN_POINT: (i64, i64) = (-100_000 * SUBPIXEL_SCALE, -70_000 * SUBPIXEL_SCALE);
/// The secondary off-screen point, pixel (-100000, 90000). The line through
/// both points is `x = -100000`, outside the guard band, so no edge can run
/// through both and the rule always decides. Using the secondary point
/// exactly when the edge's line meets the first is the same as nudging the
/// first point an infinitesimal step towards the second, which keeps the
/// rule consistent at shared vertices.
pub const SECONDARY_OFFSCREEN_POINT: (i64, i64) =
    (-100_000 * SUBPIXEL_SCALE, 90_000 * SUBPIXEL_SCALE);

impl FillRule {
    /// Every rule, default first.
    pub const ALL: [FillRule; 7] = [
        FillRule::TopLeft,
        FillRule::BottomRight,
        FillRule::TopRight,
        FillRule::BottomLeft,
        FillRule::OffscreenPoint,
        FillRule::Inclusive,
        FillRule::Exclusive,
    ];

    /// The rules that give every sample of a mesh to exactly one triangle.
    pub const WATERTIGHT: [FillRule; 5] = [
        FillRule::TopLeft,
        FillRule::BottomRight,
        FillRule::TopRight,
        FillRule::BottomLeft,
        FillRule::OffscreenPoint,
    ];

    /// Does the inside-positive edge `e` own the samples lying exactly on it?
    pub fn owns_ties(self, e: &EdgeFunction) -> bool {
        match self {
            FillRule::TopLeft => e.is_top_left(),
            FillRule::BottomRight => !e.is_top_left(),
            // Right edges have the triangle to their left (`a < 0`),
            // bottom edges are horizontal with the triangle above (`b < 0`).
            FillRule::TopRight => e.a < 0 || (e.a == 0 && e.b > 0),
            FillRule::BottomLeft => e.a > 0 || (e.a == 0 && e.b < 0),
            FillRule::OffscreenPoint => {
                let primary = e.eval_raw(OFFSCREEN_POINT.0, OFFSCREEN_POINT.1);
                if primary != 0 {
                    primary > 0
                } else {
                    e.eval_raw(SECONDARY_OFFSCREEN_POINT.0, SECONDARY_OFFSCREEN_POINT.1) > 0
                }
            }
            FillRule::Inclusive => true,
            FillRule::Exclusive => false,
        }
    }

    /// Why an edge does or does not own its ties, in words, for traces.
    pub fn explain_tie(self, e: &EdgeFunction) -> String {
        let owns = self.owns_ties(e);
        let verdict = if owns { "owns" } else { "does not own" };
        match self {
            FillRule::TopLeft
            | FillRule::BottomRight
            | FillRule::TopRight
            | FillRule::BottomLeft => {
                format!("{} edge {verdict} its ties under {}", e.kind(), self.name())
            }
            FillRule::OffscreenPoint => format!(
                "the off-screen point is {} this edge, so it {verdict} its ties",
                if owns { "inside" } else { "outside" }
            ),
            FillRule::Inclusive => "inclusive: every edge owns its ties".to_string(),
            FillRule::Exclusive => "exclusive: no edge owns its ties".to_string(),
        }
    }
}

crate::names::named_enum!(
    FillRule,
    "fill rule",
    TopLeft = "top-left",
    BottomRight = "bottom-right",
    TopRight = "top-right",
    BottomLeft = "bottom-left",
    OffscreenPoint = "offscreen-point",
    Inclusive = "inclusive",
    Exclusive = "exclusive"
);

/// An inclusive rectangle of pixel indices (`x0..=x1`, `y0..=y1`); empty
/// when `x0 > x1` or `y0 > y1`.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct PixelRect {
    /// First column.
    pub x0: i64,
    /// First row.
    pub y0: i64,
    /// Last column (inclusive).
    pub x1: i64,
    /// Last row (inclusive).
    pub y1: i64,
}

impl PixelRect {
    /// The whole of a `width` x `height` target.
    pub fn of_target(width: u32, height: u32) -> PixelRect {
        PixelRect {
            x0: 0,
            y0: 0,
            x1: i64::from(width) - 1,
            y1: i64::from(height) - 1,
        }
    }

    /// The overlap of two rectangles.
    pub fn intersect(self, other: PixelRect) -> PixelRect {
        PixelRect {
            x0: self.x0.max(other.x0),
            y0: self.y0.max(other.y0),
            x1: self.x1.min(other.x1),
            y1: self.y1.min(other.y1),
        }
    }

    /// Is pixel `(x, y)` inside?
    #[inline]
    pub fn contains(self, x: i64, y: i64) -> bool {
        x >= self.x0 && x <= self.x1 && y >= self.y0 && y <= self.y1
    }

    /// True when no pixel is inside.
    pub fn is_empty(self) -> bool {
        self.x0 > self.x1 || self.y0 > self.y1
    }

    /// Number of pixels inside.
    pub fn area(self) -> u64 {
        if self.is_empty() {
            0
        } else {
            ((self.x1 - self.x0 + 1) * (self.y1 - self.y0 + 1)) as u64
        }
    }
}

/// A triangle ready for rasterization: snapped vertices, its three
/// inside-positive edge functions, their fill-rule biases, its area and
/// its bounding box.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct TriangleSetup {
    /// The triangle's index in the draw (printed as `t` by `rasterlab fragments`).
    pub id: u32,
    /// The snapped vertices, in the order given.
    pub vertices: [FixedPoint; 3],
    /// `edges[i]` is the edge opposite `vertices[i]`, oriented so the
    /// triangle's interior is positive.
    pub edges: [EdgeFunction; 3],
    /// `0` where the edge owns its ties under the fill rule, `-1` where not.
    pub bias: [i64; 3],
    /// Twice the triangle's area, always positive: `edges[i].eval(vertices[i])`.
    pub area: i64,
    /// `+1` when the vertices were given counter-clockwise on screen
    /// (y down), `-1` when clockwise.
    pub winding: i8,
    /// The fill rule the biases were computed for.
    pub rule: FillRule,
    /// The pixels whose sample points lie in the triangle's bounding box
    /// (the rasterization slides' AABBox), not yet clipped to any target.
    pub bounds: PixelRect,
}

impl TriangleSetup {
    /// Sets up a triangle; `None` when its snapped area is zero.
    ///
    /// Always inlined: the pipeline sets up every triangle of a mesh, and
    /// as a call its result was built on the stack and copied.
    #[inline(always)]
    pub fn new(id: u32, vertices: [FixedPoint; 3], rule: FillRule) -> Option<TriangleSetup> {
        let [v0, v1, v2] = vertices;
        let mut edges = [
            EdgeFunction::through(v1, v2),
            EdgeFunction::through(v2, v0),
            EdgeFunction::through(v0, v1),
        ];
        let signed_area = Self::signed_area(vertices);
        if signed_area == 0 {
            return None;
        }
        // line(A, B, P) is minus the cross product (B - A) x (P - A); with y
        // growing down, a positive value means the vertices run
        // counter-clockwise as seen on screen.
        let winding = if signed_area > 0 { 1 } else { -1 };
        if signed_area < 0 {
            for e in &mut edges {
                *e = e.negated();
            }
        }
        // Written out rather than with `map`: this runs for every triangle
        // of a mesh, and the compiler left `map` here as a call.
        let bias_of = |e: &EdgeFunction| if rule.owns_ties(e) { 0 } else { -1 };
        let bias = [bias_of(&edges[0]), bias_of(&edges[1]), bias_of(&edges[2])];
        Some(TriangleSetup {
            id,
            vertices,
            edges,
            bias,
            area: signed_area.abs(),
            winding,
            rule,
            bounds: Self::sample_bounds(vertices),
        })
    }

    /// The pixels whose sample points lie in the bounding box of
    /// `vertices`: the set-up's [`bounds`](Self::bounds), known before the
    /// set-up, so that a pipeline can drop a triangle with no pixel centre
    /// on screen without setting it up.
    #[inline]
    pub fn sample_bounds(vertices: [FixedPoint; 3]) -> PixelRect {
        let xs = vertices.map(|v| v.x.raw());
        let ys = vertices.map(|v| v.y.raw());
        let min = |v: [i64; 3]| v[0].min(v[1]).min(v[2]);
        let max = |v: [i64; 3]| v[0].max(v[1]).max(v[2]);
        PixelRect {
            x0: first_sample_at_or_after(min(xs)),
            y0: first_sample_at_or_after(min(ys)),
            x1: last_sample_at_or_before(max(xs)),
            y1: last_sample_at_or_before(max(ys)),
        }
    }

    /// Twice the signed area of the snapped triangle, `E0(v0)`: positive
    /// when the vertices run counter-clockwise on screen (y down), negative
    /// when clockwise, zero when degenerate. What culling looks at before
    /// a triangle is set up.
    #[inline]
    pub fn signed_area(vertices: [FixedPoint; 3]) -> i64 {
        EdgeFunction::through(vertices[1], vertices[2]).eval(vertices[0])
    }

    /// The three edge values at a point.
    #[inline]
    pub fn edge_values(&self, p: FixedPoint) -> [i64; 3] {
        self.edges.map(|e| e.eval(p))
    }

    /// How the three edge values change from one pixel's sample to the
    /// next: per pixel right, and per pixel down (the incremental
    /// evaluation of the rasterization slides).
    #[inline]
    pub fn pixel_steps(&self) -> ([i64; 3], [i64; 3]) {
        (
            self.edges.map(|e| e.a * SUBPIXEL_SCALE),
            self.edges.map(|e| e.b * SUBPIXEL_SCALE),
        )
    }

    /// The three edge values at the sample point of pixel `(i, j)`.
    #[inline]
    pub fn edge_values_at_pixel(&self, i: i64, j: i64) -> [i64; 3] {
        let x = i * SUBPIXEL_SCALE + crate::raster::fixed::HALF_PIXEL;
        let y = j * SUBPIXEL_SCALE + crate::raster::fixed::HALF_PIXEL;
        self.edges.map(|e| e.eval_raw(x, y))
    }

    /// The inside test on already evaluated edge values: `E + bias >= 0`
    /// on every edge.
    #[inline]
    pub fn inside(&self, e: [i64; 3]) -> bool {
        (e[0] + self.bias[0]) | (e[1] + self.bias[1]) | (e[2] + self.bias[2]) >= 0
    }

    /// Does the triangle cover this sample point under its fill rule?
    pub fn covers(&self, p: FixedPoint) -> bool {
        self.inside(self.edge_values(p))
    }

    /// The first edge that rejects these edge values, if any.
    pub fn rejecting_edge(&self, e: [i64; 3]) -> Option<usize> {
        (0..3).find(|&k| e[k] + self.bias[k] < 0)
    }

    /// The bounding box clipped to `clip`.
    pub fn bounds_within(&self, clip: PixelRect) -> PixelRect {
        self.bounds.intersect(clip)
    }

    /// Barycentric coordinates (alpha, beta, gamma) for exact edge values.
    #[inline]
    pub fn barycentric(&self, e: [i64; 3]) -> [f64; 3] {
        let area = self.area as f64;
        [e[0] as f64 / area, e[1] as f64 / area, e[2] as f64 / area]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    fn p(x: f32, y: f32) -> FixedPoint {
        FixedPoint::snap(x, y).unwrap()
    }

    #[test]
    fn the_edge_function_is_twice_the_signed_area() {
        let e = EdgeFunction::through(p(0., 0.), p(4., 0.));
        // (0,0) -> (4,0) -> (0,3): area 6, so E = 12 px^2 = 12 * 256^2 units.
        assert_eq!(e.eval(p(0., 3.)).abs(), 12 * 256 * 256);
        assert_eq!(e.eval(p(2., 0.)), 0);
    }

    #[test]
    fn winding_is_normalised_and_reported() {
        // Right, then down-left: clockwise as seen on a y-down screen.
        let cw =
            TriangleSetup::new(0, [p(0., 0.), p(4., 0.), p(0., 4.)], FillRule::TopLeft).unwrap();
        let ccw =
            TriangleSetup::new(0, [p(0., 0.), p(0., 4.), p(4., 0.)], FillRule::TopLeft).unwrap();
        assert_eq!(cw.area, ccw.area);
        assert_eq!((cw.winding, ccw.winding), (-1, 1));
        for k in 0..3 {
            assert!(cw.edges[k].eval(cw.vertices[k]) > 0);
            assert!(ccw.edges[k].eval(ccw.vertices[k]) > 0);
        }
    }

    #[test]
    fn degenerate_triangles_have_no_setup() {
        assert!(
            TriangleSetup::new(0, [p(0., 0.), p(1., 1.), p(2., 2.)], FillRule::TopLeft).is_none()
        );
        assert!(
            TriangleSetup::new(0, [p(1., 1.), p(1., 1.), p(5., 2.)], FillRule::TopLeft).is_none()
        );
        // Distinct in f32, coincident after snapping.
        let a = p(0.0, 0.0);
        let b = p(0.001, 0.0);
        assert_eq!(a, b);
    }

    #[test]
    fn edge_kinds_follow_the_triangle_side() {
        // Triangle below a horizontal edge: that edge is top.
        let t =
            TriangleSetup::new(0, [p(0., 0.), p(4., 0.), p(2., 3.)], FillRule::TopLeft).unwrap();
        assert_eq!(t.edges[2].kind(), EdgeKind::Top);
        assert_eq!(t.bias[2], 0);
        let kinds: Vec<_> = t.edges.iter().map(|e| e.kind()).collect();
        assert!(kinds.contains(&EdgeKind::Left) && kinds.contains(&EdgeKind::Right));
    }

    #[test]
    fn bottom_right_is_the_complement_of_top_left() {
        let t =
            TriangleSetup::new(0, [p(0.3, 0.), p(4., 1.), p(2., 3.)], FillRule::TopLeft).unwrap();
        for e in t.edges {
            assert_ne!(
                FillRule::TopLeft.owns_ties(&e),
                FillRule::BottomRight.owns_ties(&e)
            );
        }
    }

    #[test]
    fn the_corner_rules_own_the_edges_they_name() {
        // Every edge kind occurs among these triangles' edges.
        for v in [
            [p(0.3, 0.), p(4., 1.), p(2., 3.)],
            [p(0., 0.), p(4., 0.), p(2., 3.)],
            [p(0., 3.), p(4., 3.), p(2., 0.)],
        ] {
            let t = TriangleSetup::new(0, v, FillRule::TopLeft).unwrap();
            for e in t.edges {
                let kind = e.kind();
                assert_eq!(
                    FillRule::TopRight.owns_ties(&e),
                    matches!(kind, EdgeKind::Top | EdgeKind::Right)
                );
                assert_eq!(
                    FillRule::BottomLeft.owns_ties(&e),
                    matches!(kind, EdgeKind::Bottom | EdgeKind::Left)
                );
                assert_ne!(
                    FillRule::TopRight.owns_ties(&e),
                    FillRule::BottomLeft.owns_ties(&e)
                );
            }
        }
    }

    #[test]
    fn fill_rule_names_round_trip() {
        for r in FillRule::ALL {
            assert_eq!(r.name().parse::<FillRule>().unwrap(), r);
        }
        assert!(matches!(
            "diagonal".parse::<FillRule>(),
            Err(Error::UnknownName { .. })
        ));
    }
}

//! The cases a check draws: families of inputs chosen to hit the places
//! where rasterizers go wrong.
//!
//! Triangles, for [`Property::Exact`] (any input) and
//! [`Property::Watertight`] and [`Property::CrackFree`] (meshes: inputs
//! whose triangles share edges and never overlap):
//!
//! | family | what it probes |
//! |---|---|
//! | soup | a few random triangles, any winding (exact only) |
//! | polygon | a star-shaped polygon with a hole, triangulated by `spade` |
//! | fan | triangles around a pixel centre, or one subpixel off it: who owns the shared vertex and the spokes |
//! | grid | a quad grid with jittered shared vertices, cells split along either diagonal |
//! | mesh | the Delaunay triangulation of random points |
//! | needles | long triangles a fraction of a pixel wide |
//! | huge | vertices far outside the target, up to the guard band, and negative |
//! | ties | coordinates halfway between two steps of the snapping's grid (1/512 px for 1/256), where snapping rounds to even; under `--snap none`, on whole and half pixels, so that edges run through pixel centres (exact only) |
//! | zero area | triangles that become segments or points once snapped (under `--snap none`, exactly collinear), beside a normal one (exact only) |
//! | overflow | vertices 1,500 to 30,000 px off the target, on every side, both windings, of which only a corner or a thin band is seen: edge values beyond 32 bits where the few visible pixels are, among them wide corners (the pair within one 64x64 tile at a corner of the target, far edges thousands of px long and away: length times distance past 2^23 px²) |
//!
//! Lines: random segments, segments between pixel centres (the midpoint
//! test's ties), axis-parallel and diagonal segments, long segments from
//! far outside the target, half-subpixel ends, zero-length segments. Under
//! the pixel-index convention: whole-number endpoints, random, axis-parallel
//! and diagonal, from far off the target, slopes with halfway ties, and
//! zero-length.
//!
//! Polygons: the families of `super::polygons` (stars with holes, rings
//! crossing themselves, overlapping holes, collinear and repeated
//! vertices, slivers, huge coordinates, shared edges, ties).
//!
//! A [`Case`] is written and read as the text `rasterlab fragments` reads,
//! with a first line `# size WxH` (see [`super::Case`]).

use super::case::{snap, Case, Point};
use super::judge::Property;
use super::snapping::Snapping;
use crate::raster::fixed::{FixedPoint, GUARD_BAND};
use spade::{DelaunayTriangulation, Point2, Triangulation};
use std::f64::consts::TAU;

/// A coordinate on the 1/256 grid: what the generators produce, unless a
/// family wants ties.
fn on_grid(v: f64) -> f64 {
    (v * 256.0).round() / 256.0
}

/// The families of the exact check, in the order cases cycle through them.
pub const EXACT_FAMILIES: [&str; 10] = [
    "soup",
    "polygon",
    "fan",
    "grid",
    "mesh",
    "needles",
    "huge",
    "ties",
    "zero-area",
    "overflow",
];
/// The families of the mesh checks (watertight, crack-free).
pub const MESH_FAMILIES: [&str; 7] = [
    "polygon", "fan", "grid", "mesh", "needles", "huge", "overflow",
];
/// The families of the line checks on sub-pixel endpoints.
pub const LINE_FAMILIES: [&str; 6] = ["random", "centres", "axis", "far", "ties", "zero-length"];
/// The families of the pixel-index line check.
pub const PIXEL_INDEX_FAMILIES: [&str; 5] = ["random", "axis", "far", "ties", "zero-length"];

/// The families a check of `property` draws from, in order.
pub fn families(property: Property) -> &'static [&'static str] {
    match property {
        Property::Exact(_) => &EXACT_FAMILIES,
        Property::Watertight | Property::CrackFree => &MESH_FAMILIES,
        Property::Line(c) if c.whole_pixels() => &PIXEL_INDEX_FAMILIES,
        Property::Line(_) => &LINE_FAMILIES,
        Property::Polygon(_) => &super::polygons::POLYGON_FAMILIES,
    }
}

/// The family of the `index`-th case of a check of `property`.
pub fn family(property: Property, index: u32) -> &'static str {
    let f = families(property);
    f[index as usize % f.len()]
}

/// The `index`-th case of a check of `property`, from `rng`, snapped to
/// 1/256 px.
pub fn generate_case(property: Property, index: u32, rng: &mut fastrand::Rng) -> Case {
    generate_case_snapped(property, Snapping::default(), index, rng)
}

/// The `index`-th case of a check of `property` under `snapping`, from
/// `rng`. Every coordinate is on the 1/256 px grid but in the ties and
/// zero-area families, which follow the snapping: under a grid, the ties
/// are halfway between two of its steps and the zero-area triangles have
/// zero area once snapped to it; under `none`, the ties are vertices on
/// whole and half pixels (edges through pixel centres) and the zero-area
/// triangles are exactly collinear.
pub fn generate_case_snapped(
    property: Property,
    snapping: Snapping,
    index: u32,
    rng: &mut fastrand::Rng,
) -> Case {
    let width = rng.u32(6..=40);
    let height = rng.u32(6..=40);
    let mut case = Case {
        width,
        height,
        snapping,
        ..Case::default()
    };
    let (w, h) = (f64::from(width), f64::from(height));
    match property {
        Property::Line(c) if c.whole_pixels() => case.lines = pixel_index_lines(index, rng, w, h),
        Property::Line(_) => case.lines = lines(index, rng, w, h, snapping),
        Property::Watertight | Property::CrackFree => {
            // Jitter or clamping can fold a grid or fan over itself; such
            // an input is not watertight, whoever draws it. Keep only
            // inputs the reference draws watertight.
            for _ in 0..50 {
                case.triangles = watertight(index, rng, w, h);
                let reference = super::reference(property, &case);
                if super::judge::judge(property, &case, &reference).is_none() {
                    return case;
                }
            }
            case.triangles = polygon(rng, w, h);
        }
        Property::Exact(_) => case.triangles = exact(index, rng, w, h, snapping),
        Property::Polygon(_) => case.polygons = super::polygons::generate(index, rng, w, h),
    }
    case
}

/// A coordinate from `lo` to `hi` for the ties family: halfway between two
/// steps of the snapping's grid, or under `none` on a whole or half pixel.
fn tie(rng: &mut fastrand::Rng, lo: f64, hi: f64, snapping: Snapping) -> f64 {
    let per_pixel = match snapping {
        Snapping::Grid { .. } => 2.0 / snapping.step(),
        Snapping::AsGiven => 2.0,
    };
    let k = rng.i32((lo * per_pixel) as i32..(hi * per_pixel) as i32);
    f64::from(k) / per_pixel
}

fn coord(rng: &mut fastrand::Rng, lo: f64, hi: f64) -> f64 {
    on_grid(lo + rng.f64() * (hi - lo))
}

fn point(rng: &mut fastrand::Rng, w: f64, h: f64) -> Point {
    (coord(rng, -2.0, w + 2.0), coord(rng, -2.0, h + 2.0))
}

/// Inputs for the exact property: every family.
fn exact(
    index: u32,
    rng: &mut fastrand::Rng,
    w: f64,
    h: f64,
    snapping: Snapping,
) -> Vec<[Point; 3]> {
    match index % 10 {
        0 => (0..rng.usize(1..=4))
            .map(|_| [(); 3].map(|_| point(rng, w, h)))
            .collect(),
        1 => polygon(rng, w, h),
        2 => fan(rng, w, h),
        3 => grid(rng, w, h),
        4 => mesh(rng, w, h),
        5 => needles(rng, w, h),
        6 => huge(rng, w, h),
        7 => (0..rng.usize(1..=3))
            .map(|_| {
                [(); 3].map(|_| {
                    (
                        tie(rng, -1.0, w + 1.0, snapping),
                        tie(rng, -1.0, h + 1.0, snapping),
                    )
                })
            })
            .collect(),
        9 => overflow(rng, w, h),
        _ => {
            // A triangle of zero area once snapped, beside a normal one:
            // its third vertex is a point of the snapping's grid on the
            // line through the first two as snapped (before the first,
            // between them, on one of them or past the second), moved off
            // the grid by less than half a step, so that snapping puts it
            // back. Under `none`, exactly on the line, on the 1/256 grid.
            let a = snapping.apply(point(rng, w, h));
            let b = snapping.apply(point(rng, w, h));
            let t = rng.f64();
            let off = match snapping {
                Snapping::Grid { .. } => (rng.f64() - 0.5) * 0.9 * snapping.step(),
                Snapping::AsGiven => 0.0,
            };
            vec![
                [a, b, collinear_on_grid(a, b, t, off, snapping.step())],
                [a, point(rng, w, h), point(rng, w, h)],
            ]
        }
    }
}

/// A point of the grid of `step` px on the line through `a` and `b`
/// (themselves on the grid), chosen by `t` in [0, 1) among the grid
/// points from one step before `a` to one step past `b`, then moved by
/// `off` (less than half a step) on both axes.
fn collinear_on_grid(a: Point, b: Point, t: f64, off: f64, step: f64) -> Point {
    let steps = |d: f64| (d / step).round() as i64;
    let (dx, dy) = (steps(b.0 - a.0), steps(b.1 - a.1));
    let g = gcd(dx.unsigned_abs(), dy.unsigned_abs()).max(1) as i64;
    // The grid points of the line are a + m (dx, dy) / g for whole m.
    let m = (t * (g + 3) as f64).floor() as i64 - 1;
    (
        a.0 + (m * (dx / g)) as f64 * step + off,
        a.1 + (m * (dy / g)) as f64 * step + off,
    )
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// Inputs for the watertight property: triangles sharing edges, never
/// overlapping.
fn watertight(index: u32, rng: &mut fastrand::Rng, w: f64, h: f64) -> Vec<[Point; 3]> {
    match index % 7 {
        0 => polygon(rng, w, h),
        1 => fan(rng, w, h),
        2 => grid(rng, w, h),
        3 => mesh(rng, w, h),
        4 => needles(rng, w, h),
        5 => huge(rng, w, h),
        _ => overflow(rng, w, h),
    }
}

/// Two triangles sharing an edge, with vertices far off the target (on
/// any side), either winding, of one of three kinds:
///
/// * a thin wedge (a quarter of the cases): a vertex inside the target,
///   the far ends 2,000 to 30,000 px away a few thousandths of a radian
///   apart;
/// * a thin band (a quarter): a long shared edge across the target, the
///   third vertices a pixel or two to either side, near the target or far;
/// * a wide corner (half): a vertex inside the target and the far ends
///   1,500 to 8,000 px away in the quadrant beyond one of the target's
///   corners (left ones three times in four: where a tiled rasterizer's
///   first tile is, top-left in y-down memory, bottom-left in OpenGL's),
///   a quarter of the time along the two axes, as in `10 54 -3000 54 10
///   3064` on 64x64. The pair reaches no farther into the target than
///   its vertex there (for the check's targets, at most 40 px, it lies in
///   the 64x64 tile at that corner), its visible part is the corner, and
///   the edge opposite the vertex, thousands of pixels long and thousands
///   away, has edge values (its length times its distance) of about 2^18
///   to 2^26 px² at the visible pixels: past 2^23 px², what 32 bits of
///   1/256 px² hold, for most. The vertices stay within 8,100 px of the
///   target, so that a viewport 16,384 px wide around it clips nothing.
fn overflow(rng: &mut fastrand::Rng, w: f64, h: f64) -> Vec<[Point; 3]> {
    let limit = (GUARD_BAND - 2) as f64;
    let clamp = |p: Point| {
        (
            on_grid(p.0.clamp(-limit, limit)),
            on_grid(p.1.clamp(-limit, limit)),
        )
    };
    let far = |rng: &mut fastrand::Rng| 2000.0 + rng.f64() * 28000.0;
    let at = |c: Point, r: f64, a: f64| (c.0 + r * a.cos(), c.1 + r * a.sin());
    let [a, b, c, d] = match rng.usize(0..4) {
        0 => {
            // A thin wedge: a vertex inside the target, the far ends a few
            // thousandths of a radian apart.
            let v = (coord(rng, 0.0, w), coord(rng, 0.0, h));
            let angle = rng.f64() * TAU;
            let spread = 0.0003 + rng.f64() * 0.003;
            let far_end = far(rng);
            [
                v,
                at(v, far_end, angle),
                at(v, far(rng), angle + spread),
                at(v, far(rng), angle - spread),
            ]
        }
        1 => {
            // A thin band: a long shared edge across the target, the third
            // vertices a pixel or two to either side near the target, or far.
            let centre = (coord(rng, 0.0, w), coord(rng, 0.0, h));
            let angle = rng.f64() * TAU;
            let (p, q) = (at(centre, far(rng), angle), at(centre, -far(rng), angle));
            let side = |rng: &mut fastrand::Rng, s: f64| {
                let off = s * (0.3 + rng.f64() * 2.0);
                let along = (rng.f64() - 0.5) * if rng.bool() { w.max(h) } else { 40000.0 };
                let base = at(centre, along, angle);
                at(base, off, angle + TAU / 4.0)
            };
            [p, q, side(rng, 1.0), side(rng, -1.0)]
        }
        _ => wide_corner(rng, w, h),
    };
    let (a, b, c, d) = (clamp(a), clamp(b), clamp(c), clamp(d));
    if rng.bool() {
        vec![[a, b, c], [b, a, d]]
    } else {
        vec![[a, c, b], [b, d, a]]
    }
}

/// The overflow family's wide corner (see [`overflow`]): the vertex `v`,
/// the far end `b` of the shared edge, and the far ends `c` and `d` of the
/// two triangles `v b c` and `b v d`, which lie on either side of the ray
/// from `v` through `b`, within a quarter turn, so they never overlap.
fn wide_corner(rng: &mut fastrand::Rng, w: f64, h: f64) -> [Point; 4] {
    let reach = |rng: &mut fastrand::Rng| 1500.0 + rng.f64() * 6500.0;
    // The quadrant: x toward -infinity (the left corners) three times in
    // four, y either way.
    let sx = if rng.u8(0..4) > 0 { -1.0 } else { 1.0 };
    let sy = if rng.bool() { -1.0 } else { 1.0 };
    // The direction `t` in [0, 1] of the quadrant, from its horizontal
    // axis (0) to its vertical one (1).
    let at = |c: Point, r: f64, t: f64| {
        let a = t * TAU / 4.0;
        (c.0 + sx * r * a.cos(), c.1 + sy * r * a.sin())
    };
    let v = (coord(rng, 0.0, w), coord(rng, 0.0, h));
    let (tc, td) = if rng.u8(0..4) == 0 {
        (0.0, 1.0)
    } else {
        (rng.f64() * 0.3, 1.0 - rng.f64() * 0.3)
    };
    let tb = tc + (td - tc) * (0.25 + rng.f64() * 0.5);
    [
        v,
        at(v, reach(rng), tb),
        at(v, reach(rng), tc),
        at(v, reach(rng), td),
    ]
}

/// A star-shaped polygon with a hole around the same centre, triangulated
/// by spade's constrained Delaunay triangulation.
fn polygon(rng: &mut fastrand::Rng, w: f64, h: f64) -> Vec<[Point; 3]> {
    let centre = (w / 2.0, h / 2.0);
    let r = w.min(h) / 2.0 + 2.0;
    let ring = |rng: &mut fastrand::Rng, lo: f64, hi: f64, n: usize| -> Vec<FixedPoint> {
        let mut angles: Vec<f64> = (0..n).map(|_| rng.f64() * TAU).collect();
        angles.sort_by(f64::total_cmp);
        angles.dedup_by(|a, b| (*a - *b).abs() < 1e-3);
        angles
            .iter()
            .map(|a| {
                let radius = lo + rng.f64() * (hi - lo);
                snap((
                    on_grid(centre.0 + radius * a.cos()),
                    on_grid(centre.1 + radius * a.sin()),
                ))
            })
            .collect()
    };
    let n = rng.usize(4..=9);
    let outer = ring(rng, 0.6 * r, r, n);
    let holes = if rng.bool() {
        let n = rng.usize(3..=5);
        vec![ring(rng, 0.1 * r, 0.3 * r, n)]
    } else {
        Vec::new()
    };
    crate::geometry::polygon::Polygon::new(outer, holes)
        .and_then(|p| p.triangulate())
        .map(|ts| ts.iter().map(|t| t.map(|p| p.to_f64())).collect())
        .unwrap_or_else(|_| grid(rng, w, h))
}

/// Triangles around a pixel centre (or a subpixel off it), closing the fan.
fn fan(rng: &mut fastrand::Rng, w: f64, h: f64) -> Vec<[Point; 3]> {
    let shift = [0.0, 1.0 / 256.0, -1.0 / 256.0][rng.usize(0..3)];
    let c = (
        f64::from(rng.i32(1..(w as i32 - 1).max(2))) + 0.5 + shift,
        f64::from(rng.i32(1..(h as i32 - 1).max(2))) + 0.5,
    );
    let n = rng.usize(3..=8);
    let mut angles: Vec<f64> = (0..n)
        .map(|k| (k as f64 + 0.2 + 0.6 * rng.f64()) / n as f64 * TAU)
        .collect();
    angles.sort_by(f64::total_cmp);
    let spokes: Vec<Point> = angles
        .iter()
        .map(|a| {
            // Some spokes through pixel centres too (axis-aligned edges).
            let r = 2.0 + rng.f64() * w.max(h) / 2.0;
            (on_grid(c.0 + r * a.cos()), on_grid(c.1 + r * a.sin()))
        })
        .collect();
    (0..n)
        .map(|k| [c, spokes[k], spokes[(k + 1) % n]])
        .collect()
}

/// A quad grid whose inner vertices are jittered by up to a quarter cell,
/// each cell split along a random diagonal.
fn grid(rng: &mut fastrand::Rng, w: f64, h: f64) -> Vec<[Point; 3]> {
    let (nx, ny) = (rng.usize(1..=4), rng.usize(1..=4));
    let cell = (w / nx as f64, h / ny as f64);
    let origin = (rng.f64() - 0.5, rng.f64() - 0.5);
    let mut v = vec![vec![(0.0, 0.0); ny + 1]; nx + 1];
    for (i, column) in v.iter_mut().enumerate() {
        for (j, p) in column.iter_mut().enumerate() {
            let jitter = |rng: &mut fastrand::Rng, c: f64| (rng.f64() - 0.5) * c / 2.0;
            let mut x = origin.0 + i as f64 * cell.0;
            let mut y = origin.1 + j as f64 * cell.1;
            if rng.u8(0..4) > 0 {
                x += jitter(rng, cell.0);
                y += jitter(rng, cell.1);
            } else {
                // On a pixel centre: ties on every edge through it.
                x = x.floor() + 0.5;
                y = y.floor() + 0.5;
            }
            *p = (on_grid(x), on_grid(y));
        }
    }
    let mut out = Vec::new();
    for i in 0..nx {
        for j in 0..ny {
            let (a, b, c, d) = (v[i][j], v[i + 1][j], v[i + 1][j + 1], v[i][j + 1]);
            if rng.bool() {
                out.push([a, b, c]);
                out.push([a, c, d]);
            } else {
                out.push([a, b, d]);
                out.push([b, c, d]);
            }
        }
    }
    out
}

/// The Delaunay triangulation of random points: a mesh whose union is
/// their convex hull.
fn mesh(rng: &mut fastrand::Rng, w: f64, h: f64) -> Vec<[Point; 3]> {
    let mut dt = DelaunayTriangulation::<Point2<f64>>::new();
    for _ in 0..rng.usize(4..=14) {
        let p = point(rng, w, h);
        let _ = dt.insert(Point2::new(p.0, p.1));
    }
    let out: Vec<[Point; 3]> = dt
        .inner_faces()
        .map(|f| f.vertices().map(|v| (v.position().x, v.position().y)))
        .collect();
    if out.is_empty() {
        grid(rng, w, h)
    } else {
        out
    }
}

/// Long triangles a fraction of a pixel wide, in pairs sharing their long
/// edge.
fn needles(rng: &mut fastrand::Rng, w: f64, h: f64) -> Vec<[Point; 3]> {
    let a = point(rng, w, h);
    let b = point(rng, w, h);
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len = dx.hypot(dy).max(1.0);
    let t = rng.f64();
    let width = 0.05 + rng.f64() * 0.6;
    let side = |s: f64| {
        (
            on_grid(a.0 + t * dx - s * dy / len * width),
            on_grid(a.1 + t * dy + s * dx / len * width),
        )
    };
    vec![[a, b, side(1.0)], [b, a, side(-1.0)]]
}

/// A fan or grid scaled and moved so most vertices lie far outside the
/// target, up to the guard band, at negative coordinates too.
fn huge(rng: &mut fastrand::Rng, w: f64, h: f64) -> Vec<[Point; 3]> {
    let limit = (GUARD_BAND - 2) as f64;
    let scale = [50.0, 500.0, 3000.0][rng.usize(0..3)];
    let c = (w / 2.0 + rng.f64(), h / 2.0 + rng.f64());
    fan(rng, w, h)
        .into_iter()
        .map(|t| {
            t.map(|p| {
                let q = (c.0 + (p.0 - c.0) * scale, c.1 + (p.1 - c.1) * scale);
                (
                    on_grid(q.0.clamp(-limit, limit)),
                    on_grid(q.1.clamp(-limit, limit)),
                )
            })
        })
        .collect()
}

/// Line segments.
fn lines(
    index: u32,
    rng: &mut fastrand::Rng,
    w: f64,
    h: f64,
    snapping: Snapping,
) -> Vec<[Point; 2]> {
    let n = rng.usize(1..=4);
    let centre = |rng: &mut fastrand::Rng, hi: f64| f64::from(rng.i32(0..hi as i32)) + 0.5;
    (0..n)
        .map(|_| match index % 6 {
            0 => [point(rng, w, h), point(rng, w, h)],
            // Between pixel centres: the midpoint test's ties.
            1 => [
                (centre(rng, w), centre(rng, h)),
                (centre(rng, w), centre(rng, h)),
            ],
            2 => {
                // Axis-parallel or diagonal.
                let a = (centre(rng, w), centre(rng, h));
                let k = f64::from(rng.i32(-20..20));
                [
                    a,
                    [
                        (a.0 + k, a.1),
                        (a.0, a.1 + k),
                        (a.0 + k, a.1 + k),
                        (a.0 + k, a.1 - k),
                    ][rng.usize(0..4)],
                ]
            }
            3 => {
                // From far outside the target, through it.
                let far = (GUARD_BAND - 2) as f64;
                let a = (coord(rng, -far, far), coord(rng, -far, far));
                let b = (
                    w - a.0 + coord(rng, -2.0, 2.0),
                    h - a.1 + coord(rng, -2.0, 2.0),
                );
                [a, b]
            }
            4 => [
                (tie(rng, 0.0, w, snapping), tie(rng, 0.0, h, snapping)),
                (tie(rng, 0.0, w, snapping), tie(rng, 0.0, h, snapping)),
            ],
            _ => {
                let a = point(rng, w, h);
                if rng.bool() {
                    [a, a]
                } else {
                    [
                        a,
                        (a.0 + coord(rng, -1.0, 1.0), a.1 + coord(rng, -1.0, 1.0)),
                    ]
                }
            }
        })
        .collect()
}

/// Line segments between whole-number pixel indices.
fn pixel_index_lines(index: u32, rng: &mut fastrand::Rng, w: f64, h: f64) -> Vec<[Point; 2]> {
    let (w, h) = (w as i32, h as i32);
    let pixel =
        |rng: &mut fastrand::Rng| (f64::from(rng.i32(-2..w + 2)), f64::from(rng.i32(-2..h + 2)));
    (0..rng.usize(1..=4))
        .map(|_| match index % 5 {
            0 => [pixel(rng), pixel(rng)],
            1 => {
                let a = pixel(rng);
                let k = f64::from(rng.i32(-20..20));
                [
                    a,
                    [
                        (a.0 + k, a.1),
                        (a.0, a.1 + k),
                        (a.0 + k, a.1 + k),
                        (a.0 + k, a.1 - k),
                    ][rng.usize(0..4)],
                ]
            }
            2 => {
                let far = f64::from(rng.i32(1000..30000));
                let a = pixel(rng);
                let angle = rng.f64() * TAU;
                [
                    a,
                    (
                        (a.0 + far * angle.cos()).round(),
                        (a.1 + far * angle.sin()).round(),
                    ),
                ]
            }
            3 => {
                // Halfway ties: an even run and an odd rise (or the reverse).
                let a = pixel(rng);
                let run = 2 * rng.i32(1..8);
                let rise = 2 * rng.i32(0..run / 2) + 1;
                let (sx, sy) = (
                    if rng.bool() { 1 } else { -1 },
                    if rng.bool() { 1 } else { -1 },
                );
                let (dx, dy) = if rng.bool() { (run, rise) } else { (rise, run) };
                [a, (a.0 + f64::from(sx * dx), a.1 + f64::from(sy * dy))]
            }
            _ => {
                let a = pixel(rng);
                [a, a]
            }
        })
        .collect()
}

//! The cases a check draws: families of inputs chosen to hit the places
//! where rasterizers go wrong.
//!
//! Triangles, for [`Property::Exact`] (any input) and
//! [`Property::Watertight`] (inputs whose triangles share edges and never
//! overlap):
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
//! | ties | coordinates on half a subpixel (1/512 px), where snapping rounds to even (exact only) |
//! | zero area | triangles that become segments or points once snapped, beside a normal one (exact only) |
//!
//! Lines: random segments, segments between pixel centres (the midpoint
//! test's ties), axis-parallel and diagonal segments, long segments from
//! far outside the target, half-subpixel ends, zero-length segments.
//!
//! A [`Case`] is written and read as the text `rasterlab fragments` reads,
//! with a first line `# size WxH` (see [`super::case`]).

use super::case::{snap, Case, Point};
use super::judge::Property;
use crate::raster::fixed::{FixedPoint, GUARD_BAND};
use spade::{DelaunayTriangulation, Point2, Triangulation};
use std::f64::consts::TAU;

/// A coordinate on the 1/256 grid: what the generators produce, unless a
/// family wants ties.
fn on_grid(v: f64) -> f64 {
    (v * 256.0).round() / 256.0
}

/// The `index`-th case of a check of `property`, from `rng`.
pub fn case(property: Property, index: u32, rng: &mut fastrand::Rng) -> Case {
    let width = rng.u32(6..=40);
    let height = rng.u32(6..=40);
    let mut case = Case {
        width,
        height,
        ..Case::default()
    };
    let (w, h) = (f64::from(width), f64::from(height));
    match property {
        Property::Line(_) => case.lines = lines(index, rng, w, h),
        Property::Watertight => {
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
        Property::Exact(_) => case.triangles = exact(index, rng, w, h),
    }
    case
}

fn coord(rng: &mut fastrand::Rng, lo: f64, hi: f64) -> f64 {
    on_grid(lo + rng.f64() * (hi - lo))
}

fn point(rng: &mut fastrand::Rng, w: f64, h: f64) -> Point {
    (coord(rng, -2.0, w + 2.0), coord(rng, -2.0, h + 2.0))
}

/// Inputs for the exact property: every family.
fn exact(index: u32, rng: &mut fastrand::Rng, w: f64, h: f64) -> Vec<[Point; 3]> {
    match index % 9 {
        0 => (0..rng.usize(1..=4))
            .map(|_| [(); 3].map(|_| point(rng, w, h)))
            .collect(),
        1 => polygon(rng, w, h),
        2 => fan(rng, w, h),
        3 => grid(rng, w, h),
        4 => mesh(rng, w, h),
        5 => needles(rng, w, h),
        6 => huge(rng, w, h),
        7 => {
            // Half-subpixel ties: k / 512, snapped to even.
            let tie = |rng: &mut fastrand::Rng, hi: f64| {
                f64::from(rng.i32(-512..(hi as i32 * 512 + 512))) / 512.0
            };
            (0..rng.usize(1..=3))
                .map(|_| [(); 3].map(|_| (tie(rng, w), tie(rng, h))))
                .collect()
        }
        _ => {
            // A triangle of zero area once snapped (its third vertex within
            // half a subpixel of the line through the first two), beside a
            // normal one.
            let a = point(rng, w, h);
            let b = point(rng, w, h);
            let t = rng.f64();
            let off = (rng.f64() - 0.5) / 600.0;
            let c = (
                on_grid(a.0 + t * (b.0 - a.0)) + off,
                a.1 + t * (b.1 - a.1) + off,
            );
            vec![[a, b, c], [a, point(rng, w, h), point(rng, w, h)]]
        }
    }
}

/// Inputs for the watertight property: triangles sharing edges, never
/// overlapping.
fn watertight(index: u32, rng: &mut fastrand::Rng, w: f64, h: f64) -> Vec<[Point; 3]> {
    match index % 5 {
        0 => polygon(rng, w, h),
        1 => fan(rng, w, h),
        2 => grid(rng, w, h),
        3 => mesh(rng, w, h),
        _ => {
            if rng.bool() {
                huge(rng, w, h)
            } else {
                needles(rng, w, h)
            }
        }
    }
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
fn lines(index: u32, rng: &mut fastrand::Rng, w: f64, h: f64) -> Vec<[Point; 2]> {
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
            4 => {
                let tie = |rng: &mut fastrand::Rng, hi: f64| {
                    f64::from(rng.i32(0..(hi as i32 * 512))) / 512.0
                };
                [(tie(rng, w), tie(rng, h)), (tie(rng, w), tie(rng, h))]
            }
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

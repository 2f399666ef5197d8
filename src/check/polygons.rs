//! Polygons in a check (`check --kind polygons`): the reference, the
//! boundary conventions a cause may name, and the case families.
//!
//! The reference is the polygon back-ends' own oracle,
//! [`Outline::winding_number`]: pixel `(i, j)` is filled by polygon `k`
//! when the winding number of its centre, moved right by an infinitesimal
//! `ε` and down by a smaller `δ`, is one the winding rule fills (a centre
//! on a left or top edge inside, on a right or bottom edge outside: the
//! triangles' top-left rule). A polygon is its outer ring and its holes,
//! each hole wound against the outer ring as the polygon file format
//! winds it ([`Outline::with_holes`]), so that a hole inside the outer
//! ring is a hole under both rules.
//!
//! The other conventions a subject may follow are the same oracle on the
//! case mirrored ([`Boundary`]): moving the centre left instead of right
//! is moving it right in the case mirrored in x, and so on; the closed
//! (inclusive) and open (exclusive) sets add or remove the centres on the
//! rings, by [`Outline::on_boundary`]. No second oracle.
//!
//! | family | what it probes |
//! |---|---|
//! | star | a star-shaped polygon with one or two holes inside it |
//! | crossing | rings that cross themselves: a pentagram, random vertices in any order, a ring wound twice |
//! | overlapping-holes | holes that overlap each other or reach out of their outer ring |
//! | collinear | collinear and repeated vertices, edges along rows and columns of pixel centres |
//! | slivers | polygons a fraction of a pixel wide |
//! | huge | vertices far outside the target, up to the guard band |
//! | shared-edges | quads of a jittered grid, each its own polygon, sharing edges |
//! | ties | vertices on whole and half pixels: edges through pixel centres |

use super::case::{Case, Point};
use super::Fragment;
use crate::geometry::Outline;
use crate::raster::edge::PixelRect;
use crate::raster::fixed::{FixedPoint, GUARD_BAND, HALF_PIXEL, SUBPIXEL_SCALE};
use crate::raster::fragment::FragmentList;
use crate::raster::polygon::{PolygonRasterizer, WindingRule};
use std::f64::consts::TAU;

/// The families of the polygon check, in the order cases cycle through
/// them.
pub const POLYGON_FAMILIES: [&str; 8] = [
    "star",
    "crossing",
    "overlapping-holes",
    "collinear",
    "slivers",
    "huge",
    "shared-edges",
    "ties",
];

/// Which centres on a ring count as inside: the infinitesimal move of
/// the centre before its winding number is taken, or the closed or open
/// set.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Boundary {
    /// Moved right and down: a centre on a left or top edge inside (the
    /// reference's).
    TopLeft,
    /// Moved left and down: on a right or top edge inside.
    TopRight,
    /// Moved right and up: on a left or bottom edge inside.
    BottomLeft,
    /// Moved left and up: on a right or bottom edge inside.
    BottomRight,
    /// Every centre on a ring inside (the closed set).
    Inclusive,
    /// No centre on a ring inside (the open set).
    Exclusive,
}

impl Boundary {
    /// Every convention, the reference's first.
    pub const ALL: [Boundary; 6] = [
        Boundary::TopLeft,
        Boundary::TopRight,
        Boundary::BottomLeft,
        Boundary::BottomRight,
        Boundary::Inclusive,
        Boundary::Exclusive,
    ];

    /// Its name: `top-left`, ..., `inclusive`, `exclusive`.
    pub fn name(self) -> &'static str {
        match self {
            Boundary::TopLeft => "top-left",
            Boundary::TopRight => "top-right",
            Boundary::BottomLeft => "bottom-left",
            Boundary::BottomRight => "bottom-right",
            Boundary::Inclusive => "inclusive",
            Boundary::Exclusive => "exclusive",
        }
    }

    /// Its rule in words.
    pub fn words(self) -> &'static str {
        match self {
            Boundary::TopLeft => {
                "a centre on a left or top edge inside, on a right or bottom edge outside"
            }
            Boundary::TopRight => {
                "a centre on a right or top edge inside, on a left or bottom edge outside"
            }
            Boundary::BottomLeft => {
                "a centre on a left or bottom edge inside, on a right or top edge outside"
            }
            Boundary::BottomRight => {
                "a centre on a right or bottom edge inside, on a left or top edge outside"
            }
            Boundary::Inclusive => "every centre on an edge inside (the closed polygon)",
            Boundary::Exclusive => "every centre on an edge outside (the open polygon)",
        }
    }

    /// The mirror (in x, in y) that turns this move into the reference's.
    fn mirror(self) -> (bool, bool) {
        match self {
            Boundary::TopRight => (true, false),
            Boundary::BottomLeft => (false, true),
            Boundary::BottomRight => (true, true),
            _ => (false, false),
        }
    }
}

/// How the reference is asked to fill: the rule, the convention, and
/// whether the holes are left out.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Filling {
    /// The winding rule.
    pub rule: WindingRule,
    /// The boundary convention.
    pub boundary: Boundary,
    /// Every hole left out (the outer rings alone).
    pub without_holes: bool,
}

impl Filling {
    /// The reference's filling under `rule`.
    pub fn reference(rule: WindingRule) -> Filling {
        Filling {
            rule,
            boundary: Boundary::TopLeft,
            without_holes: false,
        }
    }
}

/// Polygon `rings` (snapped) as an outline: the outer ring and its holes
/// wound against it, or `None` when a ring has fewer than 3 vertices.
fn outline(rings: &[Vec<FixedPoint>]) -> Option<Outline> {
    let mut it = rings.iter().cloned();
    Outline::with_holes(it.next()?, it.collect()).ok()
}

/// The case's polygons as outlines, as judged.
pub(crate) fn outlines(case: &Case) -> Vec<Option<Outline>> {
    case.snapped_polygons().iter().map(|r| outline(r)).collect()
}

/// The centre of pixel `(x, y)`, or `None` off the guard band.
fn centre(x: i64, y: i64) -> Option<FixedPoint> {
    FixedPoint::from_raw(
        x * SUBPIXEL_SCALE + HALF_PIXEL,
        y * SUBPIXEL_SCALE + HALF_PIXEL,
    )
    .ok()
}

fn mirrored(p: FixedPoint, (mx, my): (bool, bool)) -> FixedPoint {
    let (x, y) = (p.x.raw(), p.y.raw());
    FixedPoint::from_raw(if mx { -x } else { x }, if my { -y } else { y }).unwrap_or(p)
}

/// The pixels of the target that `filling` fills for each polygon of the
/// case: the reference's answer when `filling` is
/// [`Filling::reference`].
pub fn fill(case: &Case, filling: Filling) -> Vec<Fragment> {
    let mut out = Vec::new();
    let (w, h) = (i64::from(case.width), i64::from(case.height));
    for (id, rings) in case.snapped_polygons().iter().enumerate() {
        let rings: &[Vec<FixedPoint>] = if filling.without_holes {
            &rings[..rings.len().min(1)]
        } else {
            rings
        };
        let Some(o) = outline(rings) else { continue };
        let mirror = filling.boundary.mirror();
        let moved = Outline {
            rings: o
                .rings
                .iter()
                .map(|r| r.iter().map(|&p| mirrored(p, mirror)).collect())
                .collect(),
        };
        // Only the pixels of the polygon's box can be filled.
        let (mut x0, mut y0, mut x1, mut y1) = (i64::MAX, i64::MAX, i64::MIN, i64::MIN);
        for p in o.rings.iter().flatten() {
            x0 = x0.min(p.x.raw());
            y0 = y0.min(p.y.raw());
            x1 = x1.max(p.x.raw());
            y1 = y1.max(p.y.raw());
        }
        let first = |v: i64| (v - HALF_PIXEL).div_euclid(SUBPIXEL_SCALE).max(0);
        let last = |v: i64, n: i64| (v - HALF_PIXEL).div_euclid(SUBPIXEL_SCALE).min(n - 1);
        for y in first(y0)..=last(y1, h) {
            for x in first(x0)..=last(x1, w) {
                let Some(p) = centre(x, y) else { continue };
                let inside = match filling.boundary {
                    Boundary::Inclusive => o.on_boundary(p) || o.covers(p, filling.rule),
                    Boundary::Exclusive => !o.on_boundary(p) && o.covers(p, filling.rule),
                    _ => moved.covers(mirrored(p, mirror), filling.rule),
                };
                if inside {
                    out.push(Fragment::at(x, y, id as u32));
                }
            }
        }
    }
    out.sort();
    out
}

/// Whether pixel `f`'s centre lies exactly on a ring of polygon `f.id`.
pub(crate) fn on_a_ring(outlines: &[Option<Outline>], f: &Fragment) -> bool {
    let Some(Some(o)) = outlines.get(f.id as usize) else {
        return false;
    };
    centre(f.x, f.y).is_some_and(|p| o.on_boundary(p))
}

/// The fragments a polygon back-end draws for the case's polygons under
/// `rule`, each polygon's holes wound against its outer ring.
pub fn polygon_fragments(
    backend: &dyn PolygonRasterizer,
    case: &Case,
    rule: WindingRule,
) -> Vec<Fragment> {
    let setups: Vec<_> = outlines(case)
        .iter()
        .enumerate()
        .filter_map(|(id, o)| o.as_ref().map(|o| o.setup(id as u32)))
        .collect();
    let mut list = FragmentList::default();
    backend.rasterize(
        &setups,
        rule,
        PixelRect::of_target(case.width, case.height),
        &mut list,
    );
    list.triangles
        .iter()
        .map(|f| Fragment::at(i64::from(f.x), i64::from(f.y), f.triangle))
        .collect()
}

/// A coordinate on the 1/256 grid.
fn on_grid(v: f64) -> f64 {
    (v * 256.0).round() / 256.0
}

fn star_ring(
    rng: &mut fastrand::Rng,
    (cx, cy): Point,
    r_min: f64,
    r_max: f64,
    n: std::ops::RangeInclusive<usize>,
) -> Vec<Point> {
    let n = rng.usize(n);
    let start = rng.f64() * TAU;
    (0..n)
        .map(|k| {
            let a = start + TAU * (k as f64 + 0.8 * rng.f64()) / n as f64;
            let r = r_min + rng.f64() * (r_max - r_min);
            (on_grid(cx + r * a.cos()), on_grid(cy + r * a.sin()))
        })
        .collect()
}

/// The `index`-th polygon case (its family `POLYGON_FAMILIES[index % 8]`)
/// on a `w` x `h` target.
pub(crate) fn generate(
    index: u32,
    rng: &mut fastrand::Rng,
    w: f64,
    h: f64,
) -> Vec<Vec<Vec<Point>>> {
    let centre =
        |rng: &mut fastrand::Rng| (w * (0.3 + 0.4 * rng.f64()), h * (0.3 + 0.4 * rng.f64()));
    let size = w.min(h);
    match POLYGON_FAMILIES[index as usize % POLYGON_FAMILIES.len()] {
        "star" => (0..rng.usize(1..=2))
            .map(|_| {
                let c = centre(rng);
                let outer = star_ring(rng, c, size * 0.3, size * 0.6, 5..=12);
                let holes = (0..rng.usize(1..=2))
                    .map(|_| {
                        let d = (
                            c.0 + size * 0.05 * (rng.f64() - 0.5),
                            c.1 + size * 0.05 * (rng.f64() - 0.5),
                        );
                        star_ring(rng, d, size * 0.05, size * 0.2, 3..=6)
                    })
                    .take(1)
                    .collect::<Vec<_>>();
                std::iter::once(outer).chain(holes).collect()
            })
            .collect(),
        "crossing" => (0..rng.usize(1..=2))
            .map(|_| {
                let c = centre(rng);
                let r = size * (0.3 + 0.3 * rng.f64());
                let ring: Vec<Point> = match rng.u32(0..3) {
                    // A pentagram (or a heptagram): its middle winds twice.
                    0 => {
                        let (n, step) = if rng.bool() { (5, 2) } else { (7, 3) };
                        let start = rng.f64() * TAU;
                        (0..n)
                            .map(|k| {
                                let a = start + TAU * ((k * step) % n) as f64 / n as f64;
                                (on_grid(c.0 + r * a.cos()), on_grid(c.1 + r * a.sin()))
                            })
                            .collect()
                    }
                    // Random vertices in random order.
                    1 => (0..rng.usize(4..=9))
                        .map(|_| {
                            (
                                on_grid(-2.0 + rng.f64() * (w + 4.0)),
                                on_grid(-2.0 + rng.f64() * (h + 4.0)),
                            )
                        })
                        .collect(),
                    // A ring wound twice around its middle.
                    _ => {
                        let once = star_ring(rng, c, r * 0.5, r, 3..=6);
                        once.iter().chain(&once).copied().collect()
                    }
                };
                vec![ring]
            })
            .collect(),
        "overlapping-holes" => {
            let c = centre(rng);
            let outer = star_ring(rng, c, size * 0.35, size * 0.55, 4..=8);
            let mut rings = vec![outer];
            for _ in 0..rng.usize(2..=3) {
                let d = (
                    c.0 + size * 0.3 * (rng.f64() - 0.5),
                    c.1 + size * 0.3 * (rng.f64() - 0.5),
                );
                rings.push(star_ring(rng, d, size * 0.1, size * 0.4, 3..=5));
            }
            vec![rings]
        }
        "collinear" => {
            // An axis-aligned rectangle on pixel centres and half pixels,
            // with extra vertices along its edges and one repeated.
            let x0 = f64::from(rng.u32(0..(w as u32 / 2))) + if rng.bool() { 0.5 } else { 0.0 };
            let y0 = f64::from(rng.u32(0..(h as u32 / 2))) + if rng.bool() { 0.5 } else { 0.0 };
            let x1 = x0 + f64::from(rng.u32(2..=(w as u32 / 2)));
            let y1 = y0 + f64::from(rng.u32(2..=(h as u32 / 2)));
            let xm = on_grid(x0 + (x1 - x0) * rng.f64());
            let ym = on_grid(y0 + (y1 - y0) * rng.f64());
            let mut ring = vec![
                (x0, y0),
                (xm, y0),
                (x1, y0),
                (x1, ym),
                (x1, y1),
                (x0, y1),
                (x0, y1),
                (x0, ym),
            ];
            if rng.bool() {
                ring.reverse();
            }
            let mut out = vec![vec![ring]];
            if rng.bool() {
                // A triangle whose long edge is collinear with a corner.
                out.push(vec![vec![
                    (x0, y0),
                    ((x0 + x1) / 2.0, (y0 + y1) / 2.0),
                    (x1, y1),
                    (x1, y0 - 1.0),
                ]]);
            }
            out
        }
        "slivers" => (0..rng.usize(1..=3))
            .map(|_| {
                let a = (on_grid(rng.f64() * w), on_grid(rng.f64() * h));
                let b = (on_grid(rng.f64() * w), on_grid(rng.f64() * h));
                let t = 0.01 + 0.3 * rng.f64();
                let (dx, dy) = (b.0 - a.0, b.1 - a.1);
                let len = (dx * dx + dy * dy).sqrt().max(1.0);
                let (nx, ny) = (-dy / len * t, dx / len * t);
                let m = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
                vec![vec![
                    a,
                    (on_grid(m.0 + nx), on_grid(m.1 + ny)),
                    b,
                    (on_grid(m.0 - nx * 0.5), on_grid(m.1 - ny * 0.5)),
                ]]
            })
            .collect(),
        "huge" => {
            let far = (GUARD_BAND / 2) as f64;
            let v = |rng: &mut fastrand::Rng| on_grid(-far + rng.f64() * 2.0 * far);
            let c = centre(rng);
            let ring: Vec<Point> = (0..rng.usize(3..=6))
                .map(|k| if k == 0 { c } else { (v(rng), v(rng)) })
                .collect();
            let hole = star_ring(rng, c, size * 0.1, size * 0.3, 4..=4);
            vec![vec![ring, hole]]
        }
        "shared-edges" => {
            let (nx, ny) = (rng.usize(2..=4), rng.usize(2..=3));
            let (sx, sy) = (w / nx as f64, h / ny as f64);
            let mut grid = vec![vec![(0.0, 0.0); ny + 1]; nx + 1];
            for (i, col) in grid.iter_mut().enumerate() {
                for (j, p) in col.iter_mut().enumerate() {
                    let jitter = |rng: &mut fastrand::Rng, s: f64| {
                        if rng.bool() {
                            (rng.f64() - 0.5) * s * 0.6
                        } else {
                            0.0
                        }
                    };
                    *p = (
                        on_grid(i as f64 * sx + jitter(rng, sx)),
                        on_grid(j as f64 * sy + jitter(rng, sy)),
                    );
                }
            }
            let mut out = Vec::new();
            for i in 0..nx {
                for j in 0..ny {
                    let mut ring = vec![
                        grid[i][j],
                        grid[i + 1][j],
                        grid[i + 1][j + 1],
                        grid[i][j + 1],
                    ];
                    if rng.bool() {
                        ring.reverse();
                    }
                    out.push(vec![ring]);
                }
            }
            out
        }
        _ => (0..rng.usize(1..=3))
            .map(|_| {
                let v = |rng: &mut fastrand::Rng, n: f64| {
                    f64::from(rng.i32(-2..(2.0 * n) as i32 + 2)) / 2.0
                };
                let ring: Vec<Point> = (0..rng.usize(3..=6))
                    .map(|_| (v(rng, w), v(rng, h)))
                    .collect();
                vec![ring]
            })
            .collect(),
    }
}

/// The shrinker's polygon variants of a case: a polygon left out, a hole
/// left out, a vertex left out of a ring of more than 3.
pub(crate) fn variants(case: &Case) -> Vec<Case> {
    let mut out = Vec::new();
    for (k, rings) in case.polygons.iter().enumerate() {
        for (r, ring) in rings.iter().enumerate().skip(1) {
            let _ = ring;
            let mut c = case.clone();
            c.polygons[k].remove(r);
            out.push(c);
        }
        for (r, ring) in rings.iter().enumerate() {
            if ring.len() > 3 {
                for v in 0..ring.len() {
                    let mut c = case.clone();
                    c.polygons[k][r].remove(v);
                    out.push(c);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::registry::polygon_backends;

    /// Both polygon back-ends draw the reference's pixels on every family,
    /// under both rules; the mirrored conventions agree with the
    /// reference off the rings.
    #[test]
    fn the_back_ends_draw_the_reference() {
        let mut rng = fastrand::Rng::with_seed(5);
        for index in 0..400 {
            let (w, h) = (rng.u32(6..=40), rng.u32(6..=40));
            let case = Case {
                width: w,
                height: h,
                polygons: generate(index, &mut rng, f64::from(w), f64::from(h)),
                ..Case::default()
            };
            for rule in WindingRule::ALL {
                let want = fill(&case, Filling::reference(rule));
                for b in polygon_backends() {
                    let mut got = polygon_fragments(*b, &case, rule);
                    got.sort();
                    assert_eq!(got, want, "{} {rule} on\n{}", b.name(), case.to_text());
                }
                let outlines = outlines(&case);
                for boundary in Boundary::ALL {
                    let other = fill(
                        &case,
                        Filling {
                            boundary,
                            ..Filling::reference(rule)
                        },
                    );
                    for f in other.iter().filter(|f| !want.contains(f)) {
                        assert!(
                            on_a_ring(&outlines, f),
                            "{boundary:?} {f:?}\n{}",
                            case.to_text()
                        );
                    }
                }
            }
        }
    }
}

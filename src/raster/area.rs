//! Exact area coverage: how much of each pixel a triangle covers.
//!
//! Point sampling, whether at one sample per pixel or at several
//! ([`masks_of`](crate::raster::masks_of)), asks *whether* a point is
//! inside. The ideal anti-aliased coverage asks *how much*: the area of
//! the triangle inside the pixel's square `[x, x + 1) x [y, y + 1)`, a
//! number in `[0, 1]`. Every sampling method approximates it, so it is
//! the measure their errors are taken against.
//!
//! **The algorithm.** The triangle (its vertices snapped to 1/256 px, as
//! every back-end takes them) is clipped to each row band
//! `y <= Y < y + 1` it crosses, and the piece to each column of that
//! row: two Sutherland-Hodgman clips against axis-parallel lines, then
//! the shoelace formula for the area of the convex piece left. Only the
//! pixels the triangle crosses are visited.
//!
//! **The error.** The vertices are exact in `f64` (multiples of 1/256
//! within the guard band), and the clips are computed in each pixel's own
//! coordinates, so each area is within about 1e-12 px² of the true one:
//! for every triangle the areas of its pixels sum to its exact area (an
//! integer number of 1/65,536 px², from the integer edge functions)
//! within 1e-9 of it, which the tests check. Ties play no part: an
//! edge has no area. For a mesh (triangles that share edges and never
//! overlap) a pixel's coverage is the sum over its triangles.
//!
//! ```
//! use rasterlab::raster::{area_coverage, FixedPoint, PixelRect};
//!
//! // A right triangle with legs of 2 px covers half of the two pixels
//! // its hypotenuse crosses and all of the one below it.
//! let v = [(0.0, 0.0), (2.0, 0.0), (0.0, 2.0)].map(|(x, y)| FixedPoint::snap_f64(x, y).unwrap());
//! let areas = area_coverage(&[v], PixelRect::of_target(4, 4));
//! let at = |x, y| areas.iter().find(|a| (a.x, a.y) == (x, y)).map_or(0.0, |a| a.area);
//! assert_eq!(at(0, 0), 1.0);
//! assert_eq!((at(1, 0), at(0, 1)), (0.5, 0.5));
//! assert_eq!(at(1, 1), 0.0);
//! ```

use crate::raster::edge::{PixelRect, TriangleSetup};
use crate::raster::fixed::FixedPoint;

/// The area of one triangle inside one pixel.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct AreaFragment {
    /// Row.
    pub y: i64,
    /// Column.
    pub x: i64,
    /// The triangle's index in the input.
    pub triangle: u32,
    /// The area inside the pixel, in px² (0 to 1).
    pub area: f64,
}

/// The area each triangle covers in each pixel of `rect` it crosses, by
/// triangle, then row and column; pixels with no area are left out.
pub fn area_coverage(triangles: &[[FixedPoint; 3]], rect: PixelRect) -> Vec<AreaFragment> {
    let mut out = Vec::new();
    for (id, v) in triangles.iter().enumerate() {
        if TriangleSetup::signed_area(*v) == 0 {
            continue;
        }
        let points: Vec<(f64, f64)> = v.iter().map(|p| p.to_f64()).collect();
        let lo = |f: fn(&(f64, f64)) -> f64| points.iter().map(f).fold(f64::INFINITY, f64::min);
        let hi = |f: fn(&(f64, f64)) -> f64| points.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
        let (y0, y1) = (lo(|p| p.1).floor() as i64, hi(|p| p.1).ceil() as i64 - 1);
        for y in y0.max(rect.y0)..=y1.min(rect.y1) {
            // The row's piece, in coordinates local to the row's top.
            let local: Vec<(f64, f64)> = points.iter().map(|p| (p.0, p.1 - y as f64)).collect();
            let row = clip(&clip(&local, 1, 0.0, true), 1, 1.0, false);
            if row.len() < 3 {
                continue;
            }
            let xs = row.iter().map(|p| p.0);
            let x0 = xs.clone().fold(f64::INFINITY, f64::min).floor() as i64;
            let x1 = xs.fold(f64::NEG_INFINITY, f64::max).ceil() as i64 - 1;
            for x in x0.max(rect.x0)..=x1.min(rect.x1) {
                let cell: Vec<(f64, f64)> = row.iter().map(|p| (p.0 - x as f64, p.1)).collect();
                let piece = clip(&clip(&cell, 0, 0.0, true), 0, 1.0, false);
                let area = shoelace(&piece);
                if area > 0.0 {
                    out.push(AreaFragment {
                        y,
                        x,
                        triangle: id as u32,
                        area: area.min(1.0),
                    });
                }
            }
        }
    }
    out
}

/// The part of the convex polygon `poly` on one side of the line
/// `coordinate axis = at`: where it is `>= at` (`keep_above`) or `<= at`.
fn clip(poly: &[(f64, f64)], axis: usize, at: f64, keep_above: bool) -> Vec<(f64, f64)> {
    let get = |p: &(f64, f64)| if axis == 0 { p.0 } else { p.1 };
    let inside = |p: &(f64, f64)| {
        if keep_above {
            get(p) >= at
        } else {
            get(p) <= at
        }
    };
    let mut out = Vec::with_capacity(poly.len() + 1);
    for (i, a) in poly.iter().enumerate() {
        let b = &poly[(i + 1) % poly.len()];
        if inside(a) {
            out.push(*a);
        }
        if inside(a) != inside(b) {
            let t = (at - get(a)) / (get(b) - get(a));
            let p = (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
            // The crossing lies on the line exactly, whatever the rounding.
            out.push(if axis == 0 { (at, p.1) } else { (p.0, at) });
        }
    }
    out
}

/// The area of a polygon (either winding).
fn shoelace(poly: &[(f64, f64)]) -> f64 {
    let twice: f64 = (0..poly.len())
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum();
    twice.abs() / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::fixed::SUBPIXEL_SCALE;

    fn snap(p: (f64, f64)) -> FixedPoint {
        FixedPoint::snap_f64(p.0, p.1).unwrap()
    }

    /// Each triangle's pixels sum to its exact area (twice the area is an
    /// integer in 1/65,536 px² from the integer edge functions), on
    /// triangles from needles to ones far larger than the target.
    #[test]
    fn the_pixels_of_a_triangle_sum_to_its_exact_area() {
        let mut rng = fastrand::Rng::with_seed(7);
        let everywhere = PixelRect {
            x0: -5000,
            y0: -5000,
            x1: 5000,
            y1: 5000,
        };
        for n in 0..2000 {
            let spread = [0.3, 3.0, 40.0, 700.0][n % 4];
            let v = [0; 3].map(|_| {
                snap((
                    (rng.f64() - 0.5) * spread + 20.0,
                    (rng.f64() - 0.5) * spread + 20.0,
                ))
            });
            let exact = TriangleSetup::signed_area(v).unsigned_abs() as f64
                / (2 * SUBPIXEL_SCALE * SUBPIXEL_SCALE) as f64;
            let sum: f64 = area_coverage(&[v], everywhere).iter().map(|a| a.area).sum();
            assert!(
                (sum - exact).abs() <= 1e-9 * exact.max(1.0),
                "{v:?}: {sum} against {exact}"
            );
        }
    }

    /// Two triangles splitting a square cover each of its pixels once in
    /// all, whichever way the diagonal runs through a pixel.
    #[test]
    fn a_split_square_covers_every_pixel_once() {
        let (a, b, c, d) = ((0.3, 0.7), (5.9, 0.2), (6.1, 5.3), (0.1, 5.8));
        let tris = [[a, b, c].map(snap), [a, c, d].map(snap)];
        let areas = area_coverage(&tris, PixelRect::of_target(8, 8));
        let mut sum = std::collections::BTreeMap::new();
        for f in &areas {
            *sum.entry((f.x, f.y)).or_insert(0.0) += f.area;
        }
        // Pixels wholly inside the quadrilateral.
        for (x, y) in [(2, 2), (3, 3), (1, 4), (4, 1)] {
            assert!((sum[&(x, y)] - 1.0).abs() < 1e-12, "({x}, {y})");
        }
    }
}

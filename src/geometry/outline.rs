//! Outlines: polygons of any shape, filled by a winding rule, and the
//! exact winding-number oracle the polygon back-ends are checked against.
//!
//! A [`Polygon`] must be simple, because spade triangulates only simple
//! polygons. An [`Outline`] is any set of closed rings: they may cross
//! themselves and each other, repeat vertices and run along each other.
//! What they enclose is said by the **winding number** of a point, how
//! many times the rings wind around it, and a
//! [`WindingRule`]: even-odd fills an odd one, nonzero any but zero
//! (Foley, van Dam, Feiner and Hughes 1990, §3.6 and the PostScript and
//! SVG fill rules).
//!
//! [`Outline::winding_number`] is the oracle: it casts the horizontal ray
//! from the point to the left and adds `+1` for every edge crossing it
//! downwards, `-1` for every edge crossing it upwards, each decided by one
//! exact `i128` cross product. It counts the point moved right by an
//! infinitesimal `ε` and down by an infinitesimal `δ ≪ ε`, the polygon
//! back-ends' boundary convention (the triangles' top-left rule): a point
//! on a left or top edge counts as inside it, on a right or bottom edge as
//! outside. The back-ends find the same numbers another way, sorting the
//! crossings of each row and stepping them from row to row.
//!
//! ```
//! use rasterlab::geometry::Outline;
//! use rasterlab::raster::polygon::WindingRule;
//! use rasterlab::raster::FixedPoint;
//! let p = |x: f64, y: f64| FixedPoint::snap_f64(x, y).unwrap();
//! // A ring wound twice around the square (0, 0)-(4, 4): winding number 2.
//! let twice = Outline::new(vec![vec![
//!     p(0., 0.), p(4., 0.), p(4., 4.), p(0., 4.),
//!     p(0., 0.), p(4., 0.), p(4., 4.), p(0., 4.),
//! ]]).unwrap();
//! assert_eq!(twice.winding_number(p(2., 2.)).abs(), 2);
//! assert!(twice.covers(p(2., 2.), WindingRule::Nonzero));
//! assert!(!twice.covers(p(2., 2.), WindingRule::EvenOdd));
//! // The top-left convention: the left edge's points are inside, the right's not.
//! assert!(twice.covers(p(0., 2.), WindingRule::Nonzero));
//! assert!(!twice.covers(p(4., 2.), WindingRule::Nonzero));
//! ```

use crate::error::{Error, Result};
use crate::geometry::polygon::{on_segment, Polygon};
use crate::raster::fixed::FixedPoint;
use crate::raster::polygon::{PolygonSetup, WindingRule};

/// Closed rings of any shape (each implicitly closed, last to first).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Outline {
    /// The rings, in order.
    pub rings: Vec<Vec<FixedPoint>>,
}

/// Twice the signed area of a ring (shoelace formula), exactly.
pub fn twice_signed_area(ring: &[FixedPoint]) -> i128 {
    let n = ring.len();
    (0..n)
        .map(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % n]);
            i128::from(a.x.raw()) * i128::from(b.y.raw())
                - i128::from(b.x.raw()) * i128::from(a.y.raw())
        })
        .sum()
}

impl Outline {
    /// An outline of `rings`, each of at least 3 vertices.
    pub fn new(rings: Vec<Vec<FixedPoint>>) -> Result<Outline> {
        if rings.iter().any(|r| r.len() < 3) {
            return Err(Error::InvalidArgument(
                "every polygon ring needs at least 3 vertices".into(),
            ));
        }
        Ok(Outline { rings })
    }

    /// An outer ring and its holes, each hole wound against the outer ring
    /// (reversed when its signed area has the outer ring's sign), so that
    /// a hole inside the outer ring is a hole under both winding rules.
    pub fn with_holes(outer: Vec<FixedPoint>, holes: Vec<Vec<FixedPoint>>) -> Result<Outline> {
        let sign = twice_signed_area(&outer).signum();
        let holes = holes.into_iter().map(|mut hole| {
            if sign != 0 && twice_signed_area(&hole).signum() == sign {
                hole.reverse();
            }
            hole
        });
        Outline::new(std::iter::once(outer).chain(holes).collect())
    }

    /// The outline of a simple polygon, its holes wound against its outer
    /// ring.
    pub fn of_polygon(polygon: &Polygon) -> Outline {
        Outline::with_holes(polygon.outer.clone(), polygon.holes.clone())
            .expect("a polygon's rings have at least 3 vertices")
    }

    fn edges(&self) -> impl Iterator<Item = (FixedPoint, FixedPoint)> + '_ {
        self.rings.iter().flat_map(|ring| {
            let next = ring.iter().cycle().skip(1);
            ring.iter().zip(next).map(|(&a, &b)| (a, b))
        })
    }

    /// The winding number of `p` moved right by `ε` and down by `δ ≪ ε`
    /// (see the module docs): the sum over the edges crossing the ray from
    /// there to the left of `+1` for an edge running down, `-1` for one
    /// running up. Exact.
    pub fn winding_number(&self, p: FixedPoint) -> i64 {
        let (px, py) = (i128::from(p.x.raw()), i128::from(p.y.raw()));
        let mut winding = 0;
        for (a, b) in self.edges() {
            // The moved point's row y + δ lies between the ends: the top
            // end is at or above y, the bottom end below it.
            if (a.y <= p.y) == (b.y <= p.y) {
                continue;
            }
            let (ax, ay) = (i128::from(a.x.raw()), i128::from(a.y.raw()));
            let (bx, by) = (i128::from(b.x.raw()), i128::from(b.y.raw()));
            let down = by > ay;
            // (crossing x - px) * (by - ay), whose sign with the direction's
            // says which side of p the edge crosses the row y.
            let side = (bx - ax) * (py - ay) - (by - ay) * (px - ax);
            let at_or_left = if down { side <= 0 } else { side >= 0 };
            // A crossing exactly at p is left of p + ε.
            if at_or_left {
                winding += if down { 1 } else { -1 };
            }
        }
        winding
    }

    /// Whether `p` lies on an edge or a vertex of a ring.
    pub fn on_boundary(&self, p: FixedPoint) -> bool {
        self.edges().any(|(a, b)| on_segment(a, b, p))
    }

    /// Whether the polygon back-ends fill the pixel whose centre is `p`
    /// under `rule`.
    pub fn covers(&self, p: FixedPoint, rule: WindingRule) -> bool {
        rule.fills(self.winding_number(p))
    }

    /// The outline set up for a polygon back-end, its fragments carrying
    /// `id`.
    pub fn setup(&self, id: u32) -> PolygonSetup {
        PolygonSetup::new(id, &self.rings)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::polygon::Side;

    fn p(x: i64, y: i64) -> FixedPoint {
        FixedPoint::from_raw(x, y).unwrap()
    }

    /// Off the boundary, a simple polygon's even-odd classification and
    /// the winding number agree: odd inside, zero outside (holes wound
    /// against the outer ring), whatever the rings' orientations.
    #[test]
    fn off_the_boundary_the_winding_number_is_the_even_odd_classification() {
        let outer = vec![p(0, 0), p(2560, 256), p(2304, 2560), p(256, 2048)];
        let hole = vec![p(768, 768), p(1536, 768), p(1280, 1536)];
        for (outer, hole) in [
            (outer.clone(), hole.clone()),
            (outer.iter().rev().copied().collect(), hole.clone()),
            (outer.clone(), hole.iter().rev().copied().collect()),
        ] {
            let polygon = Polygon::new(outer.clone(), vec![hole.clone()]).unwrap();
            let outline = Outline::of_polygon(&polygon);
            for y in (-100..2700).step_by(37) {
                for x in (-100..2700).step_by(41) {
                    let w = outline.winding_number(p(x, y));
                    match polygon.classify(p(x, y)) {
                        Side::Inside => assert_eq!(w.abs(), 1, "({x}, {y})"),
                        Side::Outside => assert_eq!(w, 0, "({x}, {y})"),
                        Side::Boundary => assert!(w.abs() <= 1),
                    }
                }
            }
        }
    }

    #[test]
    fn the_boundary_goes_to_the_left_and_top_edges() {
        // The square (0, 0)-(4, 4) px, either way round.
        let square = vec![p(0, 0), p(1024, 0), p(1024, 1024), p(0, 1024)];
        for ring in [square.clone(), square.iter().rev().copied().collect()] {
            let o = Outline::new(vec![ring]).unwrap();
            let inside = |x, y| o.covers(p(x, y), WindingRule::EvenOdd);
            assert!(inside(0, 512) && !inside(1024, 512), "left in, right out");
            assert!(inside(512, 0) && !inside(512, 1024), "top in, bottom out");
            assert!(inside(0, 0) && !inside(1024, 0) && !inside(0, 1024));
            assert!(o.on_boundary(p(1024, 512)) && !o.on_boundary(p(512, 512)));
        }
        assert!(Outline::new(vec![vec![p(0, 0), p(1, 1)]]).is_err());
    }
}

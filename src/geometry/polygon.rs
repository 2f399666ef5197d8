//! Simple polygons (with holes) and their constrained Delaunay triangulation.
//!
//! The line-drawing slides: "more general polygons can be broken down into triangles and
//! are therefore also covered". A [`Polygon`] is an outer ring and any
//! number of hole rings of snapped points. [`Polygon::triangulate`] hands
//! them to `spade`'s constrained Delaunay triangulation, with every ring
//! edge as a constraint, and keeps the triangles inside the polygon. Those
//! triangles share edges and vertices exactly, which makes them the input
//! of the watertightness property tests.
//!
//! [`Polygon::classify`] is the exact oracle those tests use: whether a
//! point is strictly inside, strictly outside, or on the boundary, decided
//! with integer arithmetic (even-odd rule).
//!
//! ```
//! use rasterlab::geometry::{Polygon, Side};
//! use rasterlab::raster::FixedPoint;
//! let p = |x: f32, y: f32| FixedPoint::snap(x, y).unwrap();
//! let square = Polygon::new(vec![p(0., 0.), p(4., 0.), p(4., 4.), p(0., 4.)], vec![]).unwrap();
//! assert_eq!(square.triangulate().unwrap().len(), 2);
//! assert_eq!(square.classify(p(1., 1.)), Side::Inside);
//! assert_eq!(square.classify(p(4., 1.)), Side::Boundary);
//! ```

use crate::error::{Error, Result};
use crate::raster::fixed::FixedPoint;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

/// Where a point lies relative to a polygon.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Side {
    /// Strictly inside (not in a hole).
    Inside,
    /// Strictly outside, or strictly inside a hole.
    Outside,
    /// On an edge or a vertex of any ring.
    Boundary,
}

/// A simple polygon with optional holes, on the snapped grid.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Polygon {
    /// Outer ring, either orientation, not closed (last != first).
    pub outer: Vec<FixedPoint>,
    /// Hole rings.
    pub holes: Vec<Vec<FixedPoint>>,
}

fn raw(p: FixedPoint) -> (i128, i128) {
    (p.x.raw() as i128, p.y.raw() as i128)
}

/// Sign of the cross product `(b - a) x (c - a)`.
fn orient(a: FixedPoint, b: FixedPoint, c: FixedPoint) -> i128 {
    let (a, b, c) = (raw(a), raw(b), raw(c));
    ((b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)).signum()
}

/// Is `p` on the closed segment `a b`?
pub(crate) fn on_segment(a: FixedPoint, b: FixedPoint, p: FixedPoint) -> bool {
    orient(a, b, p) == 0
        && p.x >= a.x.min(b.x)
        && p.x <= a.x.max(b.x)
        && p.y >= a.y.min(b.y)
        && p.y <= a.y.max(b.y)
}

/// Do closed segments `a b` and `c d` share any point?
fn segments_touch(a: FixedPoint, b: FixedPoint, c: FixedPoint, d: FixedPoint) -> bool {
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    if o1 * o2 < 0 && o3 * o4 < 0 {
        return true;
    }
    on_segment(a, b, c) || on_segment(a, b, d) || on_segment(c, d, a) || on_segment(c, d, b)
}

impl Polygon {
    /// Builds a polygon, checking that every ring has at least three
    /// vertices, that no two edges of any rings touch (except consecutive
    /// edges of one ring at their shared vertex), that every hole lies
    /// inside the outer ring and that no hole lies inside another.
    pub fn new(outer: Vec<FixedPoint>, holes: Vec<Vec<FixedPoint>>) -> Result<Polygon> {
        Self::with_faulty_ring(outer, holes).map_err(|(_, e)| e)
    }

    /// [`Polygon::new`], saying which ring is at fault: 0 for the outer
    /// ring, `k` for the `k`-th hole (so a reader can point at its line).
    pub fn with_faulty_ring(
        outer: Vec<FixedPoint>,
        holes: Vec<Vec<FixedPoint>>,
    ) -> std::result::Result<Polygon, (usize, Error)> {
        let polygon = Polygon { outer, holes };
        let fault = |ring: usize, message: String| (ring, Error::InvalidArgument(message));
        if let Some(r) = polygon.rings().position(|r| r.len() < 3) {
            return Err(fault(
                r,
                "every polygon ring needs at least 3 vertices".into(),
            ));
        }
        polygon.check_edges_apart().map_err(|(r, m)| fault(r, m))?;
        // No two rings touch, so a ring lies wholly on one side of another:
        // one vertex tells which.
        for (k, hole) in polygon.holes.iter().enumerate() {
            let outer_only = Polygon {
                outer: polygon.outer.clone(),
                holes: Vec::new(),
            };
            if outer_only.classify(hole[0]) != Side::Inside {
                return Err(fault(
                    k + 1,
                    format!("hole {} lies outside its polygon", k + 1),
                ));
            }
            for (j, other) in polygon.holes.iter().enumerate() {
                let other_only = Polygon {
                    outer: other.clone(),
                    holes: Vec::new(),
                };
                if j != k && other_only.classify(hole[0]) == Side::Inside {
                    return Err(fault(
                        k + 1,
                        format!("hole {} lies inside hole {}", k + 1, j + 1),
                    ));
                }
            }
        }
        Ok(polygon)
    }

    /// Checks that no two edges touch, but consecutive edges of one ring at
    /// their shared vertex. Edges are swept in order of their smallest x,
    /// and only pairs whose x ranges overlap are tested exactly, so a
    /// polygon of many short edges is checked in about `n log n`.
    fn check_edges_apart(&self) -> std::result::Result<(), (usize, String)> {
        let rings: Vec<&Vec<FixedPoint>> = self.rings().collect();
        let mut edges: Vec<(usize, usize, FixedPoint, FixedPoint)> = rings
            .iter()
            .enumerate()
            .flat_map(|(r, ring)| {
                (0..ring.len()).map(move |i| (r, i, ring[i], ring[(i + 1) % ring.len()]))
            })
            .collect();
        if let Some(&(r, ..)) = edges.iter().find(|e| e.2 == e.3) {
            return Err((r, "polygon has a repeated vertex".into()));
        }
        let min_x = |e: &(usize, usize, FixedPoint, FixedPoint)| e.2.x.min(e.3.x);
        let max_x = |e: &(usize, usize, FixedPoint, FixedPoint)| e.2.x.max(e.3.x);
        edges.sort_by_key(min_x);
        for (k, &(r1, i1, a, b)) in edges.iter().enumerate() {
            let right = max_x(&edges[k]);
            for &(r2, i2, c, d) in edges[k + 1..].iter().take_while(|e| min_x(e) <= right) {
                let n = rings[r1].len();
                let (after, before) = (
                    r1 == r2 && (i1 + 1) % n == i2,
                    r1 == r2 && (i2 + 1) % n == i1,
                );
                let touch = if after || before {
                    // Consecutive edges share one vertex; they must not overlap.
                    let (shared, p, q) = if after { (b, a, d) } else { (a, b, c) };
                    on_segment(shared, p, q) || on_segment(shared, q, p)
                } else {
                    segments_touch(a, b, c, d)
                };
                if touch {
                    return Err((
                        r1.max(r2),
                        "polygon is not simple: two edges touch or cross".into(),
                    ));
                }
            }
        }
        Ok(())
    }

    fn rings(&self) -> impl Iterator<Item = &Vec<FixedPoint>> {
        std::iter::once(&self.outer).chain(self.holes.iter())
    }

    /// Where `p` lies: inside, outside or on the boundary (exact).
    pub fn classify(&self, p: FixedPoint) -> Side {
        let mut inside = false;
        for ring in self.rings() {
            for i in 0..ring.len() {
                let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
                if on_segment(a, b, p) {
                    return Side::Boundary;
                }
                // Even-odd: does the ray from p towards +x cross edge a b?
                if (a.y > p.y) != (b.y > p.y) {
                    let o = orient(a, b, p);
                    if (b.y > a.y && o > 0) || (b.y < a.y && o < 0) {
                        inside = !inside;
                    }
                }
            }
        }
        if inside {
            Side::Inside
        } else {
            Side::Outside
        }
    }

    /// The constrained Delaunay triangulation of the polygon's interior.
    pub fn triangulate(&self) -> Result<Vec<[FixedPoint; 3]>> {
        let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
        // Raw fixed-point units are small integers: exact in f64.
        let to_point = |p: FixedPoint| Point2::new(p.x.raw() as f64, p.y.raw() as f64);
        for ring in self.rings() {
            let handles = ring
                .iter()
                .map(|&p| {
                    cdt.insert(to_point(p)).map_err(|e| {
                        Error::InvalidArgument(format!("cannot triangulate polygon: {e:?}"))
                    })
                })
                .collect::<Result<Vec<_>>>()?;
            for i in 0..handles.len() {
                let (from, to) = (handles[i], handles[(i + 1) % handles.len()]);
                if !cdt.can_add_constraint(from, to) {
                    return Err(Error::InvalidArgument(
                        "polygon is not simple: constraint edges cross".into(),
                    ));
                }
                cdt.add_constraint(from, to);
            }
        }
        // Even-odd over the triangulation: walk from the hull inwards;
        // crossing a constraint (a ring edge) toggles inside and outside.
        // Rings do not touch, so this is the polygon's own even-odd rule.
        let mut inside: Vec<Option<bool>> = vec![None; cdt.num_all_faces()];
        let mut stack = Vec::new();
        for hull_edge in cdt.convex_hull() {
            for e in [hull_edge, hull_edge.rev()] {
                if let Some(face) = e.face().as_inner() {
                    if inside[face.fix().index()].is_none() {
                        inside[face.fix().index()] = Some(e.is_constraint_edge());
                        stack.push(face);
                    }
                }
            }
        }
        while let Some(face) = stack.pop() {
            let here = inside[face.fix().index()] == Some(true);
            for e in face.adjacent_edges() {
                if let Some(next) = e.rev().face().as_inner() {
                    let slot = &mut inside[next.fix().index()];
                    if slot.is_none() {
                        *slot = Some(here != e.is_constraint_edge());
                        stack.push(next);
                    }
                }
            }
        }
        let mut triangles = Vec::new();
        for face in cdt.inner_faces() {
            if inside[face.fix().index()] != Some(true) {
                continue;
            }
            let [a, b, c] = face.vertices().map(|v| {
                let p = v.position();
                FixedPoint::from_raw(p.x as i64, p.y as i64)
            });
            triangles.push([a?, b?, c?]);
        }
        Ok(triangles)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f32, y: f32) -> FixedPoint {
        FixedPoint::snap(x, y).unwrap()
    }

    #[test]
    fn a_square_with_a_hole_triangulates_around_the_hole() {
        let outer = vec![p(0., 0.), p(10., 0.), p(10., 10.), p(0., 10.)];
        let hole = vec![p(3., 3.), p(7., 3.), p(7., 7.), p(3., 7.)];
        let poly = Polygon::new(outer, vec![hole]).unwrap();
        let tris = poly.triangulate().unwrap();
        assert_eq!(tris.len(), 8);
        let twice_area: i128 = tris
            .iter()
            .map(|t| {
                let (a, b, c) = (raw(t[0]), raw(t[1]), raw(t[2]));
                ((b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)).abs()
            })
            .sum();
        assert_eq!(twice_area, 2 * (100 - 16) * 256 * 256);
        assert_eq!(poly.classify(p(5., 5.)), Side::Outside);
        assert_eq!(poly.classify(p(1., 5.)), Side::Inside);
        assert_eq!(poly.classify(p(3., 5.)), Side::Boundary);
    }

    #[test]
    fn self_intersecting_rings_are_rejected() {
        let bowtie = vec![p(0., 0.), p(4., 4.), p(4., 0.), p(0., 4.)];
        assert!(Polygon::new(bowtie, vec![]).is_err());
        let spike = vec![p(0., 0.), p(4., 0.), p(2., 0.), p(2., 3.)];
        assert!(Polygon::new(spike, vec![]).is_err());
        let repeated = vec![p(0., 0.), p(4., 0.), p(4., 0.), p(2., 3.)];
        assert!(Polygon::new(repeated, vec![]).is_err());
    }

    /// Every pair of edges tested, as the check did before it swept.
    fn all_pairs_apart(ring: &[FixedPoint]) -> bool {
        let n = ring.len();
        let edge = |i: usize| (ring[i], ring[(i + 1) % n]);
        (0..n).all(|i| edge(i).0 != edge(i).1)
            && (0..n).all(|i| {
                (i + 1..n).all(|j| {
                    let ((a, b), (c, d)) = (edge(i), edge(j));
                    if j == i + 1 {
                        !(on_segment(b, a, d) || on_segment(b, d, a))
                    } else if i == 0 && j == n - 1 {
                        !(on_segment(a, b, c) || on_segment(a, c, b))
                    } else {
                        !segments_touch(a, b, c, d)
                    }
                })
            })
    }

    proptest::proptest! {
        #![proptest_config(crate::test_support::proptest_config(3000, "tests/proptest-regressions/src-geometry-polygon.txt"))]
        /// The sweep accepts exactly the rings that testing every pair
        /// accepts (small integer rings: many touches and crossings).
        #[test]
        fn the_sweep_agrees_with_testing_every_pair(
            points in proptest::collection::vec((0i32..6, 0i32..6), 3..9)
        ) {
            let ring: Vec<FixedPoint> = points.iter().map(|&(x, y)| p(x as f32, y as f32)).collect();
            let polygon = Polygon { outer: ring.clone(), holes: Vec::new() };
            proptest::prop_assert_eq!(polygon.check_edges_apart().is_ok(), all_pairs_apart(&ring));
        }
    }
}

//! Failures the property tests found and shrank, each kept as a named
//! test of the property it broke, so that it runs on every build whatever
//! proptest's seed files hold. Coordinates are in the subpixel units of
//! the snapping grid (1/256 px), as the shrunk cases were printed.

mod common;

use common::*;
use rasterlab::raster::edge::FillRule;
use rasterlab::raster::fixed::FixedPoint;
use rasterlab::Polygon;
use std::collections::BTreeSet;

fn raw(x: i64, y: i64) -> FixedPoint {
    FixedPoint::from_raw(x, y).expect("inside the guard band")
}

/// A right triangle 23 px wide and 11 px high with its right angle on
/// the target's corner: its legs lie on the target's edges, where the
/// first back-ends disagreed with `naive` on which pixels the rules give.
#[test]
fn a_right_triangle_on_the_target_corner_matches_naive() {
    assert_all_match_naive(&[[raw(5888, 0), raw(0, 0), raw(0, 2816)]]);
}

/// A polygon partly left of and above the target (one vertex at x = -1,
/// one at y = -5), triangulated: every back-end must clip it the same.
#[test]
fn a_triangulated_polygon_crossing_the_target_edges_matches_naive() {
    let polygon = Polygon::new(
        vec![raw(2048, 3072), raw(-256, 3072), raw(768, -1280)],
        vec![],
    )
    .expect("a simple polygon");
    assert_all_match_naive(&triangulation(&polygon));
}

/// A thin right triangle moved down by one whole pixel: its coverage
/// must move by exactly one row under every translation-invariant rule.
#[test]
fn a_thin_triangle_moved_one_pixel_down_moves_its_coverage() {
    let t = [raw(0, 0), raw(0, 3072), raw(6912, 0)];
    let moved = t.map(|p| raw(p.x.raw(), p.y.raw() + 256));
    let pixels = |t: [FixedPoint; 3], rule| -> BTreeSet<(u32, u32)> {
        let list = fragments(&rasterlab::raster::triangle::naive::Naive, &[t], rule);
        list.triangles.iter().map(|f| (f.x, f.y)).collect()
    };
    for rule in [
        FillRule::TopLeft,
        FillRule::BottomRight,
        FillRule::Inclusive,
        FillRule::Exclusive,
    ] {
        assert_all_match_naive(&[t]);
        assert_all_match_naive(&[moved]);
        let expected: BTreeSet<_> = pixels(t, rule)
            .into_iter()
            .map(|(x, y)| (x, y + 1))
            .collect();
        assert_eq!(pixels(moved, rule), expected, "{rule}");
    }
}

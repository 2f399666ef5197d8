//! Coverage invariants (the rules in docs/check.md): rotating the vertex order and reversing
//! the winding change nothing; moving a triangle by whole pixels moves its
//! coverage by the same amount.

mod common;

use common::*;
use proptest::prelude::*;
use rasterlab::raster::{triangle_backends, FillRule, FixedPoint, PixelRect, TriangleSetup};
use std::collections::BTreeSet;

/// The pixels every back-end covers (they must agree), on a 100 x 100 target.
fn pixels(t: [FixedPoint; 3], rule: FillRule) -> BTreeSet<(u32, u32)> {
    let Some(setup) = TriangleSetup::new(0, t, rule) else {
        return BTreeSet::new();
    };
    let mut sets = triangle_backends().iter().map(|b| {
        let mut list = rasterlab::raster::FragmentList::default();
        b.rasterize(&[setup], PixelRect::of_target(100, 100), &mut list);
        list.triangles
            .iter()
            .map(|f| (f.x, f.y))
            .collect::<BTreeSet<_>>()
    });
    let first = sets.next().unwrap();
    for other in sets {
        assert_eq!(other, first);
    }
    first
}

proptest! {
    #![proptest_config(crate::common::proptest_config(3000, "tests/proptest-regressions/triangle_invariants.txt"))]

    #[test]
    fn rotating_vertices_and_reversing_winding_change_nothing(
        t in quantum().prop_flat_map(|q| [point(0.0, 30.0, q), point(0.0, 30.0, q), point(0.0, 30.0, q)])
    ) {
        for rule in FillRule::ALL {
            let base = pixels(t, rule);
            prop_assert_eq!(&pixels([t[1], t[2], t[0]], rule), &base);
            prop_assert_eq!(&pixels([t[2], t[0], t[1]], rule), &base);
            prop_assert_eq!(&pixels([t[0], t[2], t[1]], rule), &base);
            prop_assert_eq!(&pixels([t[2], t[1], t[0]], rule), &base);
        }
    }

    #[test]
    fn translating_by_whole_pixels_translates_the_coverage(
        t in quantum().prop_flat_map(|q| [point(0.0, 30.0, q), point(0.0, 30.0, q), point(0.0, 30.0, q)]),
        dx in 0u32..60,
        dy in 0u32..60,
    ) {
        let moved = t.map(|p| FixedPoint::from_raw(p.x.raw() + i64::from(dx) * 256, p.y.raw() + i64::from(dy) * 256).unwrap());
        // The off-screen point rule is left out on purpose: its point stays
        // where it is, so it is not translation invariant (see
        // offscreen_point_rule_is_not_translation_invariant).
        for rule in [FillRule::TopLeft, FillRule::BottomRight, FillRule::Inclusive, FillRule::Exclusive] {
            let expected: BTreeSet<_> = pixels(t, rule).into_iter().map(|(x, y)| (x + dx, y + dy)).collect();
            prop_assert_eq!(pixels(moved, rule), expected);
        }
    }
}

#[test]
fn offscreen_point_rule_is_not_translation_invariant() {
    // An edge whose line runs close to the off-screen point (-100000,
    // -70000): direction (10, 7). Moving the triangle by one pixel moves
    // the line to the other side of the point, and the pixel centres on
    // that edge change hands.
    let t = [snap(0.5, 0.5), snap(20.5, 14.5), snap(0.5, 14.5)];
    let rule = rasterlab::raster::FillRule::OffscreenPoint;
    let here = pixels(t, rule);
    let moved = t.map(|p| FixedPoint::from_raw(p.x.raw() + 256, p.y.raw()).unwrap());
    let there: BTreeSet<_> = pixels(moved, rule)
        .into_iter()
        .map(|(x, y)| (x - 1, y))
        .collect();
    // The diagonal edge runs through the centres of pixels (0, 0), (10, 7)
    // and (20, 14). (10, 7) lies on the diagonal only, and changes hands;
    // (20, 14) also lies on the bottom edge y = 14.5, which owns its ties
    // (the off-screen point is on its inner side), so it follows the
    // diagonal; (0, 0) also lies on the vertical edge x = 0.5, which does
    // not own its ties, so it is never drawn.
    let changed: Vec<_> = here.symmetric_difference(&there).copied().collect();
    assert_eq!(changed, vec![(10, 7), (20, 14)]);
}

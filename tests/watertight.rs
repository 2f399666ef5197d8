//! No gaps and no double-drawn pixels on shared edges: polygons with and
//! without holes, triangulated by spade, drawn by every back-end under the
//! watertight fill rules; and the counterexamples that show the inclusive
//! and exclusive rules are not watertight.

mod common;

use common::*;
use proptest::prelude::*;
use proptest::test_runner::{Config, TestCaseError, TestError, TestRunner};
use rasterlab::geometry::{Polygon, Side};
use rasterlab::raster::triangle::naive::Naive;
use rasterlab::raster::triangle::TriangleRasterizer;
use rasterlab::raster::{triangle_backends, FillRule, FixedPoint};

/// The watertightness property: every pixel covered at most once, every
/// pixel centre strictly inside the polygon exactly once, nothing strictly
/// outside.
fn check_watertight(
    backend: &dyn TriangleRasterizer,
    poly: &Polygon,
    rule: FillRule,
) -> Result<(), String> {
    let counts = coverage_counts(&fragments(backend, &triangulation(poly), rule));
    for y in 0..SIZE {
        for x in 0..SIZE {
            let n = counts[(y * SIZE + x) as usize];
            let side = poly.classify(FixedPoint::pixel_centre(x as i32, y as i32));
            let ok = match side {
                Side::Inside => n == 1,
                Side::Outside => n == 0,
                Side::Boundary => n <= 1,
            };
            if !ok {
                return Err(format!(
                    "{} under {rule}: pixel ({x}, {y}) is {side:?} and was drawn {n} times",
                    backend.name()
                ));
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(crate::common::proptest_config(3000, "tests/proptest-regressions/watertight.txt"))]

    #[test]
    fn spade_triangulated_polygons_are_drawn_exactly_once(poly in polygon()) {
        for rule in FillRule::WATERTIGHT {
            for backend in triangle_backends() {
                check_watertight(*backend, &poly, rule).map_err(TestCaseError::fail)?;
            }
        }
    }
}

/// Runs the watertightness property under a rule that should break it and
/// returns proptest's shrunk counterexample.
fn find_counterexample(rule: FillRule) -> (Polygon, String) {
    let mut runner = TestRunner::new(Config {
        cases: 3000,
        failure_persistence: None,
        ..Config::default()
    });
    let result = runner.run(&polygon(), |poly| {
        check_watertight(&Naive, &poly, rule).map_err(TestCaseError::fail)
    });
    match result {
        Err(TestError::Fail(reason, poly)) => (poly, reason.to_string()),
        other => panic!("{rule} was expected to fail the watertightness property, got {other:?}"),
    }
}

#[test]
fn the_inclusive_rule_double_draws_shared_edges() {
    let (poly, reason) = find_counterexample(FillRule::Inclusive);
    eprintln!("inclusive counterexample: {reason}\n{poly:?}");
    let counts = coverage_counts(&fragments(
        &Naive,
        &triangulation(&poly),
        FillRule::Inclusive,
    ));
    assert!(counts.iter().any(|&n| n >= 2), "{reason}");
    // The same polygon is drawn exactly once under top-left.
    assert_eq!(check_watertight(&Naive, &poly, FillRule::TopLeft), Ok(()));
}

#[test]
fn the_exclusive_rule_leaves_gaps() {
    let (poly, reason) = find_counterexample(FillRule::Exclusive);
    eprintln!("exclusive counterexample: {reason}\n{poly:?}");
    let counts = coverage_counts(&fragments(
        &Naive,
        &triangulation(&poly),
        FillRule::Exclusive,
    ));
    let gap = (0..SIZE * SIZE).any(|i| {
        counts[i as usize] == 0
            && poly.classify(FixedPoint::pixel_centre(
                (i % SIZE) as i32,
                (i / SIZE) as i32,
            )) == Side::Inside
    });
    assert!(gap, "{reason}");
    assert_eq!(check_watertight(&Naive, &poly, FillRule::TopLeft), Ok(()));
}

#[test]
fn the_split_square_shows_both_failures_on_its_diagonal() {
    let square = Polygon::new(
        vec![snap(0., 0.), snap(5., 0.), snap(5., 5.), snap(0., 5.)],
        vec![],
    )
    .unwrap();
    let diagonal_split = vec![
        [snap(0., 0.), snap(5., 0.), snap(5., 5.)],
        [snap(0., 5.), snap(0., 0.), snap(5., 5.)],
    ];
    let count = |rule| coverage_counts(&fragments(&Naive, &diagonal_split, rule));
    let diagonal: Vec<usize> = (0..5).map(|i| (i * SIZE + i) as usize).collect();
    assert!(diagonal.iter().all(|&i| count(FillRule::Inclusive)[i] == 2));
    assert!(diagonal.iter().all(|&i| count(FillRule::Exclusive)[i] == 0));
    for rule in FillRule::WATERTIGHT {
        assert!(diagonal.iter().all(|&i| count(rule)[i] == 1), "{rule}");
    }
    assert_eq!(square.triangulate().unwrap().len(), 2);
}

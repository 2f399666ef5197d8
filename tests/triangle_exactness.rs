//! Every triangle back-end emits exactly the fragments of the `naive`
//! reference, under every fill rule, on random triangles, random meshes
//! (spade triangulations of random polygons) and the rules' adversarial cases.

mod common;

use common::*;
use proptest::prelude::*;
use rasterlab::raster::FixedPoint;

proptest! {
    #![proptest_config(crate::common::proptest_config(3000, "tests/proptest-regressions/triangle_exactness.txt"))]

    #[test]
    fn every_backend_matches_naive_on_random_triangles(soup in triangle_soup(4)) {
        assert_all_match_naive(&soup);
    }

    #[test]
    fn every_backend_matches_naive_on_random_meshes(poly in polygon()) {
        assert_all_match_naive(&triangulation(&poly));
    }
}

#[test]
fn every_backend_matches_naive_on_the_adversarial_cases() {
    for (name, triangles) in adversarial_cases() {
        eprintln!("adversarial case: {name}");
        assert_all_match_naive(&triangles);
    }
}

/// the rules' "adversarial cases worth generating", by name.
pub fn adversarial_cases() -> Vec<(&'static str, Vec<[FixedPoint; 3]>)> {
    let s = 1.0 / 256.0;
    let c = (20.5f32, 20.5f32);
    let ring = [
        (16.5, 16.5),
        (20.5, 16.5),
        (24.5, 16.5),
        (24.5, 20.5),
        (24.5, 24.5),
        (20.5, 24.5),
        (16.5, 24.5),
        (16.5, 20.5),
    ];
    let pinwheel: Vec<_> = (0..8)
        .map(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % 8]);
            [snap(c.0, c.1), snap(a.0, a.1), snap(b.0, b.1)]
        })
        .collect();
    let reversed: Vec<_> = pinwheel.iter().map(|t| [t[0], t[2], t[1]]).collect();
    let mut cases = vec![
        ("pinwheel around a pixel centre", pinwheel),
        ("pinwheel, reversed winding", reversed),
        (
            "horizontal shared edge on pixel centres",
            vec![
                [snap(2.5, 10.5), snap(30.5, 10.5), snap(16.5, 2.5)],
                [snap(30.5, 10.5), snap(2.5, 10.5), snap(16.5, 20.5)],
            ],
        ),
        (
            "vertical shared edge on pixel centres",
            vec![
                [snap(10.5, 2.5), snap(10.5, 30.5), snap(2.5, 16.5)],
                [snap(10.5, 30.5), snap(10.5, 2.5), snap(20.5, 16.5)],
            ],
        ),
        (
            "vertices one subpixel off a pixel centre",
            vec![
                [snap(5.5 + s, 5.5), snap(25.5, 5.5 - s), snap(5.5, 25.5 + s)],
                [
                    snap(25.5, 5.5 - s),
                    snap(25.5 - s, 25.5),
                    snap(5.5, 25.5 + s),
                ],
            ],
        ),
        (
            "floats exactly halfway between subpixel steps",
            vec![[
                snap(3.0 + 0.5 * s, 3.0 + 1.5 * s),
                snap(30.0 + 2.5 * s, 4.0 - 0.5 * s),
                snap(10.0 - 1.5 * s, 31.0 + 3.5 * s),
            ]],
        ),
        (
            "negative zero and negative coordinates",
            vec![
                [snap(-0.0, -0.0), snap(12.0, -0.0), snap(-0.0, 12.0)],
                [snap(-7.3, -2.2), snap(6.6, -9.1), snap(3.2, 8.8)],
            ],
        ),
        (
            "degenerate only after snapping",
            vec![
                [
                    snap(1.0, 1.0),
                    snap(20.0, 20.0),
                    snap(10.0, 10.0 + 0.25 * s),
                ],
                [snap(4.0, 4.0), snap(4.0 + 0.3 * s, 4.0), snap(30.0, 30.0)],
            ],
        ),
        (
            "collinear and coincident vertices",
            vec![
                [snap(1.0, 1.0), snap(5.0, 5.0), snap(9.0, 9.0)],
                [snap(3.0, 7.0), snap(3.0, 7.0), snap(20.0, 1.0)],
            ],
        ),
        (
            "needle one subpixel wide, thousands of pixels long",
            vec![
                [
                    snap(-3000.0, 20.0),
                    snap(3000.0, 20.5),
                    snap(3000.0, 20.5 + s),
                ],
                [
                    snap(20.25, -3000.0),
                    snap(20.25 + s, 3000.0),
                    snap(20.25, 3000.0),
                ],
            ],
        ),
        (
            "guard band corners: the largest edge values",
            vec![
                [
                    snap(-32767.99, -32767.99),
                    snap(32767.99, -32767.0),
                    snap(-32767.0, 32767.99),
                ],
                [
                    snap(32767.99, 32767.99),
                    snap(-32767.99, 32767.0),
                    snap(32767.0, -32767.99),
                ],
            ],
        ),
    ];
    // A fan of thin slivers with non-integer steps.
    let centre = (1.3f32, 38.7f32);
    let fan = (0..40)
        .map(|i| {
            let a = |k: f32| k * 0.0391;
            let p = |t: f32| snap(centre.0 + 50.0 * t.cos(), centre.1 - 50.0 * t.sin());
            [
                snap(centre.0, centre.1),
                p(a(i as f32)),
                p(a(i as f32 + 1.0)),
            ]
        })
        .collect();
    cases.push(("fan of slivers with non-integer steps", fan));
    cases
}

mod images {
    use super::common::*;
    use glam::Vec4;
    use proptest::prelude::*;
    use rasterlab::geometry::Scene2D;
    use rasterlab::raster::{
        triangle_backends, DepthState, DepthTest, FillRule, Gouraud, RenderTarget, ShadedVertex,
    };

    proptest! {
        #![proptest_config(crate::common::proptest_config(500, "tests/proptest-regressions/triangle_exactness.txt"))]

        /// The shared stage turns equal fragments into equal images:
        /// Gouraud colours and random depths, depth test on, every rule.
        #[test]
        fn images_are_bit_identical_across_backends(
            poly in polygon(),
            seed in proptest::collection::vec((0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0), 64),
            test in prop_oneof![Just(DepthTest::Less), Just(DepthTest::LessEqual), Just(DepthTest::Always)],
        ) {
            let triangles = triangulation(&poly);
            let vertices = triangles.iter().enumerate().map(|(i, _)| {
                std::array::from_fn(|k| {
                    let (z, g, b) = seed[(3 * i + k) % seed.len()];
                    ShadedVertex::flat(z, Vec4::new(1.0 - z, g, b, 1.0))
                })
            }).collect();
            let scene = Scene2D { width: SIZE, height: SIZE, triangles, vertices };
            for rule in FillRule::ALL {
                let render = |b| {
                    let mut t = RenderTarget::new(SIZE, SIZE).unwrap();
                    scene.draw(b, rule, DepthState { test, write: true }, &Gouraud, &mut t);
                    t
                };
                let reference = render(triangle_backends()[0]);
                for b in &triangle_backends()[1..] {
                    prop_assert!(render(*b) == reference, "{} under {}", b.name(), rule);
                }
            }
        }
    }
}

mod bands {
    use super::common::*;
    use proptest::prelude::*;
    use rasterlab::geometry::setup_triangles;
    use rasterlab::raster::{triangle_backends, FillRule, FragmentList, PixelRect, WorkCounters};

    proptest! {
        #![proptest_config(crate::common::proptest_config(1000, "tests/proptest-regressions/triangle_exactness.txt"))]

        /// A draw cut into bands of rows (one per thread) tests the same
        /// samples and emits the same fragments as one draw of the
        /// target, whatever the cuts: the samples tested are the
        /// algorithm's, not the threads'.
        #[test]
        fn the_samples_tested_do_not_depend_on_the_bands(
            soup in triangle_soup(4),
            cuts in proptest::collection::btree_set(1i64..SIZE as i64, 1..4),
        ) {
            let setups = setup_triangles(&soup, FillRule::TopLeft);
            let whole = viewport();
            let mut starts: Vec<i64> = std::iter::once(0).chain(cuts).collect();
            starts.push(whole.y1 + 1);
            for b in triangle_backends() {
                let one = b.rasterize(&setups, whole, &mut FragmentList::default());
                let mut banded = WorkCounters::default();
                for w in starts.windows(2) {
                    let band = PixelRect { y0: w[0], y1: w[1] - 1, ..whole };
                    banded.add(&b.rasterize(&setups, band, &mut FragmentList::default()));
                }
                prop_assert_eq!(
                    (banded.samples_tested, banded.fragments),
                    (one.samples_tested, one.fragments),
                    "{} with bands starting at {:?}", b.name(), starts
                );
            }
        }
    }
}

//! Anti-aliasing: supersampling gives every back-end the reference's
//! sample counts, the exact area of each triangle's pixels adds up to its
//! area and a mesh's pixels to at most one, and the comparison of the
//! methods against the exact area gives known answers (conflation
//! included).

mod common;

use common::*;
use proptest::prelude::*;
use rasterlab::measure::{compare_antialiasing, coverage_error, coverage_of, Coverage, Method};
use rasterlab::raster::{
    area_coverage, supersample, triangle_backend, triangle_backends, FillRule, FixedPoint,
    PixelRect, SampleCount, TriangleSetup, SUBPIXEL_SCALE,
};
use std::collections::BTreeMap;

/// The samples each triangle covers at `k x k` a pixel, every sample
/// point tested directly with the triangle's own edge functions (the
/// sample `((x k + i + 1/2) / k, (y k + j + 1/2) / k)`, in fixed point
/// the centre of fine pixel `(x k + i, y k + j)` of the triangle scaled by
/// `k`).
fn reference_counts(triangles: &[[FixedPoint; 3]], rule: FillRule, k: i64) -> Vec<SampleCount> {
    let mut counts: BTreeMap<(i64, i64, u32), u32> = BTreeMap::new();
    for (id, v) in triangles.iter().enumerate() {
        let scaled = v.map(|p| FixedPoint::from_raw(p.x.raw() * k, p.y.raw() * k).unwrap());
        let Some(t) = TriangleSetup::new(id as u32, scaled, rule) else {
            continue;
        };
        for fy in 0..SIZE as i64 * k {
            for fx in 0..SIZE as i64 * k {
                if t.inside(t.edge_values_at_pixel(fx, fy)) {
                    *counts
                        .entry((fy.div_euclid(k), fx.div_euclid(k), id as u32))
                        .or_default() += 1;
                }
            }
        }
    }
    counts
        .into_iter()
        .map(|((y, x, triangle), count)| SampleCount {
            y,
            x,
            triangle,
            count,
        })
        .collect()
}

proptest! {
    #![proptest_config(crate::common::proptest_config(120, "tests/proptest-regressions/antialias.txt"))]

    /// Every triangle back-end, drawing the triangles scaled by k, counts
    /// the samples the reference counts, under every fill rule.
    #[test]
    fn every_backend_supersamples_as_the_reference(
        soup in triangle_soup(4),
        k in 2i64..=4,
    ) {
        for rule in FillRule::ALL {
            let want = reference_counts(&soup, rule, k);
            for b in triangle_backends() {
                let got = supersample(*b, &soup, rule, viewport(), k as u32).unwrap();
                prop_assert_eq!(&got, &want, "{} under {}, k = {}", b.name(), rule, k);
            }
        }
    }

    /// A spade-triangulated polygon: no pixel is covered more than once
    /// in all (the areas of its triangles there sum to at most 1), and
    /// every triangle's pixels sum to its exact area.
    #[test]
    fn a_mesh_covers_each_pixel_at_most_once(poly in polygon()) {
        let triangles = triangulation(&poly);
        let everywhere = PixelRect { x0: -64, y0: -64, x1: 128, y1: 128 };
        let areas = area_coverage(&triangles, everywhere);
        let mut pixel: BTreeMap<(i64, i64), f64> = BTreeMap::new();
        let mut per_triangle = vec![0.0; triangles.len()];
        for a in &areas {
            *pixel.entry((a.x, a.y)).or_default() += a.area;
            per_triangle[a.triangle as usize] += a.area;
        }
        for (p, sum) in pixel {
            prop_assert!(sum <= 1.0 + 1e-9, "pixel {:?} covered {}", p, sum);
        }
        for (t, sum) in triangles.iter().zip(per_triangle) {
            let exact = TriangleSetup::signed_area(*t).unsigned_abs() as f64
                / (2 * SUBPIXEL_SCALE * SUBPIXEL_SCALE) as f64;
            prop_assert!((sum - exact).abs() <= 1e-9 * exact.max(1.0));
        }
    }
}

/// A star-shaped polygon of 40 vertices, triangulated by spade.
fn star() -> Vec<[FixedPoint; 3]> {
    let ring: Vec<FixedPoint> = (0..40)
        .map(|i| {
            let a = i as f64 / 40.0 * std::f64::consts::TAU;
            let r = if i % 2 == 0 { 27.0 } else { 12.3 };
            FixedPoint::snap_f64(32.0 + r * a.cos(), 32.0 + r * a.sin()).unwrap()
        })
        .collect();
    let poly = rasterlab::geometry::Polygon::new(ring, Vec::new()).unwrap();
    triangulation(&poly)
}

/// On a triangulated star, the error against the exact area falls as the
/// samples grow, within each family of patterns (the standard patterns,
/// the regular grids), and the exact area's own error is nil. The worst
/// error of one sample is at least 1/2: a pixel whose centre is just
/// outside a triangle covering nearly half of it.
#[test]
fn more_samples_come_closer_to_the_exact_area() {
    let rows = compare_antialiasing(&star(), 64, 64, FillRule::TopLeft).unwrap();
    let rms = |m: Method| {
        rows.iter()
            .find(|r| r.method == m)
            .unwrap()
            .per_triangle
            .rms
    };
    let msaa: Vec<f64> = [1, 2, 4, 8, 16]
        .map(|n| rms(Method::Multisample(n)))
        .to_vec();
    assert!(msaa.windows(2).all(|w| w[1] < w[0]), "{msaa:?}");
    let ssaa: Vec<f64> = [2, 3, 4, 8].map(|k| rms(Method::Supersample(k))).to_vec();
    assert!(ssaa.windows(2).all(|w| w[1] < w[0]), "{ssaa:?}");
    let area = rows.iter().find(|r| r.method == Method::Area).unwrap();
    assert_eq!((area.per_triangle.rms, area.picture.worst), (0.0, 0.0));
    let one = rows
        .iter()
        .find(|r| r.method == Method::Multisample(1))
        .unwrap();
    assert!(one.per_triangle.worst >= 0.5, "{one:?}");
}

/// Conflation: two triangles splitting a square, each drawn with its
/// exact coverage and blended over the other (`a + b (1 - a)`), leave
/// each pixel the diagonal crosses at 3/4 where the exact sum is 1. The
/// per-triangle error is nil, the picture's 1/4.
#[test]
fn blending_exact_coverage_triangle_by_triangle_loses_a_quarter_on_a_shared_edge() {
    let p = |x: f64, y: f64| FixedPoint::snap_f64(x, y).unwrap();
    let halves = [
        [p(0.0, 0.0), p(4.0, 0.0), p(4.0, 4.0)],
        [p(0.0, 0.0), p(4.0, 4.0), p(0.0, 4.0)],
    ];
    let rect = PixelRect::of_target(4, 4);
    let scanline = triangle_backend("scanline").unwrap();
    let exact = coverage_of(Method::Area, scanline, &halves, rect, FillRule::TopLeft).unwrap();
    let mut blended: BTreeMap<(i64, i64), f64> = BTreeMap::new();
    for c in &exact {
        let a = blended.entry((c.y, c.x)).or_default();
        *a += c.value * (1.0 - *a);
    }
    let (per_triangle, picture) = coverage_error(&exact, &exact, Some(&blended));
    assert_eq!(per_triangle.worst, 0.0);
    assert_eq!(picture.worst, 0.25);
    assert_eq!(picture.count, 16);
    // A coverage that names a pixel the exact area leaves empty counts
    // in full.
    let stray = [Coverage {
        x: 3,
        y: 0,
        triangle: 1,
        value: 0.5,
    }];
    let (one, _) = coverage_error(&stray, &[], None);
    assert_eq!((one.count, one.worst), (1, 0.5));
}

/// `compare` draws a triangle reaching 5,000 px off a 16 x 16 target
/// (inside the guard band) with every back-end, and says why its
/// anti-aliasing is not compared: 8 x 8 supersampling would take the
/// vertex out of the guard band.
#[test]
fn compare_says_why_it_leaves_anti_aliasing_out() {
    use rasterlab::geometry::Scene2D;
    use rasterlab::teaching::{CompareInput, Report};
    let far = Scene2D::from_triangles(
        16,
        16,
        vec![[(0.5, 0.5), (5000.0, 1.5), (0.5, 20.0)]
            .map(|(x, y)| FixedPoint::snap_f64(x, y).unwrap())],
    );
    let report = Report::compare(&CompareInput::Triangles(far), 16, 16, 1).unwrap();
    assert!(report.runs.iter().all(|r| r.differing_pixels == 0));
    assert!(report.antialias.is_none());
    let why = report.antialias_skipped.unwrap();
    assert!(why.contains("guard band when scaled by 8"), "{why}");
}

/// compare's anti-aliasing section charts every method of its table, one
/// point each, with its cost and error, and names it.
#[test]
fn compare_charts_each_method_error_against_cost() {
    use rasterlab::geometry::Scene2D;
    use rasterlab::teaching::{CompareInput, Report};
    let report =
        Report::compare(&CompareInput::Triangles(Scene2D::split_square()), 16, 16, 1).unwrap();
    let aa = report.antialias.as_ref().expect("compared");
    assert!(aa.rows.iter().all(|r| r.ns_per_pair > 0.0));
    let html = report.to_html();
    let figure = html.find("<figure class=\"chart\">").expect("the chart");
    let chart = &html[figure..figure + html[figure..].find("</figure>").unwrap()];
    assert_eq!(
        chart.matches("<circle class=\"point\"").count(),
        aa.rows.len()
    );
    for r in &aa.rows {
        assert!(
            chart.contains(&format!(">{}</text>", r.name)),
            "{} not named",
            r.name
        );
    }
}

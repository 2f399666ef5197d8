//! Failures the property tests found and shrank, each kept as a named
//! test of the property it broke, so that it runs on every build whatever
//! proptest's seed files hold (those are kept beside this file, in
//! `tests/proptest-regressions/`). Coordinates are in the subpixel units
//! of the snapping grid (1/256 px), as the shrunk cases were printed.

mod common;
#[path = "properties/parallel.rs"]
mod parallel;
#[path = "properties/pictures.rs"]
mod pictures;
#[path = "properties/pipeline.rs"]
mod pipeline;

use common::*;
use rasterlab::geometry::Polygon;
use rasterlab::raster::{FillRule, FixedPoint};
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

/// Clip-space triangles the pipeline's properties shrank to: each must be
/// drawn exactly where it is visible and, with extreme coordinates, be no
/// error. A case from the range both properties draw from runs both.
mod clipping {
    use super::pipeline::{
        clipping_draws_exactly_the_visible_part, extreme_coordinates_never_fail, ClipTriangle,
    };

    fn both(t: ClipTriangle) {
        clipping_draws_exactly_the_visible_part(t).unwrap();
        extreme_coordinates_never_fail(t).unwrap();
    }

    /// Two vertices at the origin with w = 0 and one at w = 1e30: nothing
    /// to draw, and nothing may fail.
    #[test]
    fn two_vertices_at_w_zero_and_one_at_w_1e30() {
        extreme_coordinates_never_fail([
            (0.0, 0.0, 0.0, 0.0),
            (0.0, 0.0, 0.0, 0.0),
            (0.0, 0.0, 0.0, 1e30),
        ])
        .unwrap();
    }

    /// Vertices at x = -1e30 and y = 1e30 with w = 0, and one ordinary.
    #[test]
    fn vertices_at_1e30_with_w_zero() {
        extreme_coordinates_never_fail([
            (-1e30, 0.0, 1e30, 0.0),
            (0.0, 1e30, 0.0, 0.0),
            (0.0, 1.909922, 0.0, 1.5878407),
        ])
        .unwrap();
    }

    /// Coordinates from 1e-30 to f32::MAX in one triangle, some w negative.
    #[test]
    fn coordinates_from_1e_minus_30_to_f32_max() {
        extreme_coordinates_never_fail([
            (1e30, 1e30, 1e30, -3.4028235e38),
            (1e-30, 1e-30, -3.4028235e38, 3.4028235e38),
            (1e30, 1e-30, 3.4028235e38, 1e30),
        ])
        .unwrap();
    }

    /// One vertex at w = 0 (on the camera's plane), two in front of it.
    #[test]
    fn a_vertex_on_the_cameras_plane() {
        both([
            (-1.2198987, 0.0, 0.0, 0.0),
            (0.0, 0.0, -2.8675845, 1.0883697),
            (0.0, 0.80198634, 0.0, 0.8871113),
        ]);
    }

    /// A vertex behind the camera (w = 0) and two crossing the near plane.
    #[test]
    fn a_vertex_behind_the_camera_and_two_across_the_near_plane() {
        both([
            (-2.7202687, 0.5258993, 0.0, 0.0),
            (0.66660595, -1.158189, 0.0, 2.9193134),
            (0.0, -0.72356486, 0.0, 2.8196368),
        ]);
    }

    /// A sliver: two vertices a millionth of a unit off the x axis, one of
    /// them behind the camera.
    #[test]
    fn a_sliver_a_millionth_off_the_axis() {
        clipping_draws_exactly_the_visible_part([
            (-0.18087348, 0.0, 0.0, 0.0),
            (0.0, -9.875913e-7, 0.0, 2.5187917),
            (2.7744963, -7.7449096e-7, 0.0, -2.098718),
        ])
        .unwrap();
    }

    /// One vertex far away (w = 59688), one behind the camera.
    #[test]
    fn a_vertex_far_away_and_one_behind_the_camera() {
        clipping_draws_exactly_the_visible_part([
            (0.0, -0.5772273, 0.0, 59688.594),
            (-0.638286, -0.050384615, 0.0, 0.52742136),
            (0.0, 0.0, 0.0, -1.3590423),
        ])
        .unwrap();
    }

    /// A vertex behind the camera with z = -245262, far beyond the far
    /// plane in the other direction: the part in front is cut by all
    /// three planes at once.
    #[test]
    fn a_vertex_behind_the_camera_with_a_huge_negative_z() {
        clipping_draws_exactly_the_visible_part([
            (-1.953988, -0.06673906, 1.3433396, 0.13046871),
            (2.3196874, 0.0, 0.19172992, 1.574061),
            (0.0, 0.0, -245262.08, -0.9012618),
        ])
        .unwrap();
    }
}

/// A triangle of zero area at the target's corner, in the grid picture
/// under top-left: no green cell, no fragment, for every back-end.
#[test]
fn a_point_triangle_at_the_corner_has_no_green_cell() {
    let t = [raw(0, 0), raw(0, 0), raw(0, 0)];
    pictures::green_cells_are_the_fragments_and_red_cells_the_failed_tests(t, 0).unwrap();
}

/// A right triangle with a leg on the target's left edge and its third
/// vertex a third of a pixel left of the target: its picture's green and
/// red cells are the fragments and the failed tests.
#[test]
fn a_triangle_reaching_left_of_the_target_pictures_its_tests() {
    let t = [raw(0, 0), raw(0, 2992), raw(-85, 0)];
    pictures::green_cells_are_the_fragments_and_red_cells_the_failed_tests(t, 0).unwrap();
}

/// A triangle of zero area at the origin, drawn with the clear folded in
/// and no coverage buffer: the target must still be cleared as an eager
/// clear leaves it, though no row receives a fragment.
#[test]
fn a_clear_folded_into_a_draw_with_no_fragment_still_clears() {
    let soup = [[raw(0, 0), raw(0, 0), raw(0, 0)]];
    parallel::clears_folded_into_the_draw_equal_a_clear_then_the_draw(&soup, &[0.0], 0, false)
        .unwrap();
}

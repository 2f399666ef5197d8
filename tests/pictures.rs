//! Grid pictures and fill-rule heat maps, checked by counting cells: the
//! green cells are the fragments, the red ones the failed tests.

mod common;
#[path = "properties/pictures.rs"]
mod properties;

use common::{point, quantum, SIZE};
use proptest::prelude::*;
use rasterlab::geometry::Scene2D;
use rasterlab::raster::line::LineOptions;
use rasterlab::raster::{
    line_backends, triangle_backend, FillRule, FixedPoint, Flat, FragmentList, PixelRect,
};
use rasterlab::teaching::{
    is_fragment_green, GridPicture, AS_REFERENCE, GAP, OVERDRAWN, OVERDRAWN_MORE,
};

proptest! {
    #![proptest_config(crate::common::proptest_config(200, "tests/proptest-regressions/pictures.txt"))]

    /// One triangle, every back-end: as many green cells as fragments, red
    /// cells exactly where a test failed, and the PNG shows the same cells.
    #[test]
    fn green_cells_are_the_fragments_and_red_cells_the_failed_tests(
        t in quantum().prop_flat_map(|q| {
            let p = point(-4.0, SIZE as f32 + 4.0, q);
            [p.clone(), p.clone(), p]
        }),
        rule_index in 0usize..5,
    ) {
        properties::green_cells_are_the_fragments_and_red_cells_the_failed_tests(t, rule_index)?;
    }

    /// Lines between pixel centres, every line back-end: a cell per pixel
    /// chosen, and the ideal line drawn over them.
    #[test]
    fn line_pictures_show_one_green_cell_per_pixel_chosen(
        x0 in 0u32..SIZE, y0 in 0u32..SIZE, x1 in 0u32..SIZE, y1 in 0u32..SIZE,
    ) {
        let line = rasterlab::teaching::LineEnds::pixels([x0, y0, x1, y1].map(f64::from)).unwrap();
        for backend in line_backends() {
            let picture = GridPicture::of_lines(*backend, &[line], &LineOptions::DEFAULT, SIZE, SIZE).unwrap();
            let mut list = FragmentList::default();
            let setup = rasterlab::raster::line::LineSetup {
                id: 0,
                from: FixedPoint::snap(x0 as f32 + 0.5, y0 as f32 + 0.5).unwrap(),
                to: FixedPoint::snap(x1 as f32 + 0.5, y1 as f32 + 0.5).unwrap(),
            };
            backend.rasterize(&[setup], &LineOptions::DEFAULT, PixelRect::of_target(SIZE, SIZE), &mut list);
            let mut pixels: Vec<(u32, u32)> = list
                .lines
                .iter()
                .filter(|f| f.coverage > 0.0)
                .map(|f| (f.x, f.y))
                .collect();
            pixels.sort_unstable();
            pixels.dedup();
            prop_assert_eq!(picture.inside_cells(), pixels.len(), "{}", backend.name());
            prop_assert_eq!(picture.segments.len(), 1);
        }
    }
}

/// Shrunk by proptest: a sliver just left of the target (x from -0.33 to
/// 0) has an empty clipped bounding box, so the bounding box tests
/// nothing and reports no tested run (it once reported rows 0..=11 with
/// an empty column range, which wrapped around).
#[test]
fn a_triangle_left_of_the_target_is_not_tested_by_the_bounding_box() {
    let bbox = triangle_backend("bbox").unwrap();
    let sliver = [(0.0, 0.0), (0.0, 11.6875), (-0.33203125, 0.0)];
    let p = GridPicture::of_triangles(bbox, &[sliver], FillRule::TopLeft, SIZE, SIZE).unwrap();
    assert_eq!((p.inside_cells(), p.outside_cells()), (0, 0));
    assert!(p
        .caption
        .starts_with("bbox, top-left rule: 0 pixels tested"));
}

#[test]
fn the_bounding_box_picture_is_a_red_frame_around_the_fragments() {
    let bbox = triangle_backend("bbox").unwrap();
    let p = GridPicture::of_triangles(
        bbox,
        &[[(0.5, 0.5), (4.5, 0.5), (0.5, 3.5)]],
        FillRule::TopLeft,
        6,
        4,
    )
    .unwrap();
    // The same 20 pixels and 9 fragments as `explain --backend bbox`.
    assert_eq!(p.inside_cells(), 9);
    assert_eq!(p.outside_cells(), 11);
    let svg = p.to_svg();
    // One rect per cell above the legend (whose swatches are drawn too).
    let grid = svg.split("<g class=\"legend\"").next().unwrap();
    assert_eq!(grid.matches("<rect").count(), 24);
    assert_eq!(svg.matches("<polygon").count(), 1);
    assert!(svg.contains("bbox, top-left rule: 20 pixels tested"));
}

/// The rasterization slides' depth buffer as a picture: every cell labelled with its
/// depth, as on the slides.
#[test]
fn the_depth_buffer_picture_labels_every_cell() {
    let p = GridPicture::depth_buffer(&Scene2D::depth_example(true), FillRule::TopLeft).unwrap();
    let labels = |z: &str| p.labels.iter().filter(|l| *l == z).count();
    assert_eq!(
        (labels("0.5"), labels("0.8"), labels("1.0")),
        (19, 8, 14 * 9 - 27)
    );
    assert_eq!(p.to_svg().matches(">0.5</text>").count(), 19);
}

/// The line-drawing slides' edge-drawing problem on the pinwheel (a 9 x 9 square of
/// pixel centres, eight triangles around the hub (4, 4), every edge through
/// pixel centres). Top-left covers the 8 x 8 block away from the square's
/// right and bottom sides, bottom-right the block away from its left and
/// top sides. Worked by hand:
///
/// * inclusive, one draw too many (orange): the 3 inner centres of each of
///   the 8 spokes (24), and the six outline pixels where two triangles
///   meet and a watertight rule draws one of them, (0, 0), (4, 0), (0, 4),
///   (8, 8), (8, 4), (4, 8): 30. Two or more too many (purple): the hub (8
///   draws) and the corners (8, 0) and (0, 8), drawn twice where no
///   watertight rule draws them: 3;
/// * exclusive, gaps (red): the spokes' inner centres (24) and the hub: 25;
/// * the off-screen point rule, watertight too, matches everywhere.
#[test]
fn fill_rule_heat_maps_show_seed_004s_double_draws_and_gaps() {
    let scene = Scene2D::pinwheel();
    let bbox = triangle_backend("bbox").unwrap();
    let coverage = |rule| scene.render(bbox, rule, &Flat).unwrap().0.coverage;
    let top_left = coverage(FillRule::TopLeft);
    let bottom_right = coverage(FillRule::BottomRight);
    let map = |rule: FillRule| {
        GridPicture::coverage_heat_map(
            scene.width,
            scene.height,
            &coverage(rule),
            &[&top_left, &bottom_right],
            rule.name().into(),
        )
        .unwrap()
    };
    let inclusive = map(FillRule::Inclusive);
    assert_eq!(inclusive.count(GAP), 0);
    assert_eq!(inclusive.count(OVERDRAWN), 30);
    assert_eq!(inclusive.count(OVERDRAWN_MORE), 3);
    let exclusive = map(FillRule::Exclusive);
    assert_eq!(exclusive.count(GAP), 25);
    assert_eq!(
        exclusive.count(OVERDRAWN) + exclusive.count(OVERDRAWN_MORE),
        0
    );
    for rule in [
        FillRule::TopLeft,
        FillRule::BottomRight,
        FillRule::OffscreenPoint,
    ] {
        let m = map(rule);
        assert_eq!(m.count(AS_REFERENCE), 64, "{}", rule.name());
        assert_eq!(
            m.count(GAP) + m.count(OVERDRAWN) + m.count(OVERDRAWN_MORE),
            0
        );
    }
}

/// `tiled`'s picture frames its 8 x 8 blocks with their classes: every
/// pixel of an inside block is a fragment, none of an outside block, and
/// back-ends that visit pixels one by one have no blocks.
#[test]
fn the_tiled_picture_frames_its_blocks_by_class() {
    use rasterlab::raster::triangle::BlockClass;
    let triangle = [(1.0, 1.0), (60.0, 2.0), (3.0, 46.0)];
    let tiled = rasterlab::raster::triangle_backend("tiled").unwrap();
    let picture = GridPicture::of_triangles(tiled, &[triangle], FillRule::TopLeft, 64, 48).unwrap();
    assert!(picture.blocks.len() >= 9, "{}", picture.blocks.len());
    for (r, class) in &picture.blocks {
        let green = (r.y0..=r.y1)
            .flat_map(|y| (r.x0..=r.x1).map(move |x| (x, y)))
            .filter(|&(x, y)| is_fragment_green(picture.cells[(y * 64 + x) as usize]))
            .count() as u64;
        match class {
            BlockClass::Inside => assert_eq!(green, r.area()),
            BlockClass::Outside => assert_eq!(green, 0),
            BlockClass::Partial => {}
        }
    }
    assert!(picture.blocks.iter().any(|b| b.1 == BlockClass::Inside));
    assert!(picture.to_svg().contains("class=\"block\""));
    let bbox = rasterlab::raster::triangle_backend("bbox").unwrap();
    let picture = GridPicture::of_triangles(bbox, &[triangle], FillRule::TopLeft, 64, 48).unwrap();
    assert!(picture.blocks.is_empty());
}

/// A grid picture names what the traces name: pixel indices on both axes,
/// the vertices v0-v2 and the edges E0-E2, and carries the palette's
/// legend for what its colours say.
#[test]
fn a_grid_picture_has_axes_vertex_and_edge_labels_and_its_legend() {
    use rasterlab::teaching::Role;
    let bbox = triangle_backend("bbox").unwrap();
    let p = GridPicture::of_triangles(
        bbox,
        &[[(1.0, 1.0), (9.0, 2.0), (3.0, 7.0)]],
        FillRule::TopLeft,
        10,
        8,
    )
    .unwrap();
    let svg = p.to_svg();
    for label in ["v0", "v1", "v2", "E0", "E1", "E2"] {
        assert_eq!(
            svg.matches(&format!(">{label}</text>")).count(),
            1,
            "{label}"
        );
    }
    let axes = svg.split("<g class=\"axes\"").nth(1).unwrap();
    let axes = &axes[..axes.find("</g>").unwrap()];
    for i in 0..10 {
        assert!(axes.contains(&format!(">{i}</text>")), "column {i}");
    }
    assert_eq!(axes.matches("</text>").count(), 10 + 8);
    for role in [Role::Drawn, Role::TestedOutside, Role::Geometry] {
        assert!(p.legend.has(role), "{role:?}");
        assert!(svg.contains(role.label()), "{role:?}");
    }
    assert!(!p.legend.has(Role::BlockPartial));
    // Several triangles: told apart by colour, no vertex names.
    let two = GridPicture::of_triangles(
        bbox,
        &[
            [(1.0, 1.0), (9.0, 2.0), (3.0, 7.0)],
            [(9.0, 2.0), (9.0, 7.0), (3.0, 7.0)],
        ],
        FillRule::TopLeft,
        10,
        8,
    )
    .unwrap();
    assert!(!two.to_svg().contains(">v0</text>"));
}

/// Pictures meant for a person are at least 256 pixels on their short
/// side, however small the grid; a large grid keeps its cells at 32
/// pixels.
#[test]
fn pictures_are_large_enough_to_see() {
    use rasterlab::teaching::{for_people, MIN_SHORT_SIDE};
    let bbox = triangle_backend("bbox").unwrap();
    for (w, h) in [(1, 1), (5, 5), (9, 9), (14, 9), (3, 40), (64, 48)] {
        let p = GridPicture::of_triangles(
            bbox,
            &[[(0.5, 0.5), (4.5, 0.5), (0.5, 3.5)]],
            FillRule::TopLeft,
            w,
            h,
        )
        .unwrap();
        let png = p.to_picture_png().unwrap();
        assert!(
            png.width().min(png.height()) >= MIN_SHORT_SIDE,
            "{w}x{h}: {}x{}",
            png.width(),
            png.height()
        );
        assert!(p.svg_cell() >= 32.0);
    }
    for name in Scene2D::BUILT_IN {
        let scene = Scene2D::built_in(name).unwrap();
        let (target, _) = scene.render(bbox, FillRule::TopLeft, &Flat).unwrap();
        let picture = for_people(&target);
        assert!(
            picture.width().min(picture.height()) >= MIN_SHORT_SIDE,
            "{name}"
        );
        // Enlarged by a whole number: every pixel one framed cell.
        assert_eq!(picture.width() % target.width(), 0, "{name}");
    }
}

/// The depth-buffer picture of the course's example: each pixel in the
/// colour of the triangle kept there, the 4 pixels where the red
/// triangle's fragments lost to the blue one marked hidden, and the PNG
/// showing the depths the SVG shows (drawing it without its labels
/// changes it).
#[test]
fn the_depth_buffer_picture_shows_kept_and_hidden_fragments_and_its_numbers() {
    use rasterlab::teaching::{DepthCells, Role};
    let scene = Scene2D::depth_example(true);
    let bbox = triangle_backend("bbox").unwrap();
    let cells = DepthCells::of_scene(&scene, bbox, FillRule::TopLeft).unwrap();
    let kept = |t: u32| cells.kept.iter().filter(|k| k.last() == Some(&t)).count();
    assert_eq!((kept(0), kept(1)), (19, 8));
    let hidden: Vec<usize> = (0..cells.hidden.len())
        .filter(|&i| !cells.hidden[i].is_empty())
        .collect();
    assert_eq!(hidden.len(), 4);
    assert!(hidden
        .iter()
        .all(|&i| cells.hidden[i] == [1] && cells.kept[i] == [0]));
    // Drawn the other way round, the red fragments are kept, then
    // overwritten: nothing is hidden, the same buffer results.
    let red_first = Scene2D::depth_example(false);
    let other = DepthCells::of_scene(&red_first, bbox, FillRule::TopLeft).unwrap();
    assert_eq!(other.depth, cells.depth);
    assert!(other.hidden.iter().all(Vec::is_empty));
    assert_eq!(other.kept.iter().filter(|k| k.len() == 2).count(), 4);

    let p = GridPicture::depth_buffer(&scene, FillRule::TopLeft).unwrap();
    assert_eq!(p.hidden.len(), 4);
    assert!(p.legend.has(Role::Hidden));
    assert!(p.caption.contains("27 fragments kept, 4 hidden"));
    assert_eq!(p.to_svg().matches("class=\"hidden\"").count(), 4);
    let with_numbers = p.to_picture_png().unwrap();
    let without = GridPicture {
        labels: Vec::new(),
        ..p.clone()
    }
    .to_picture_png()
    .unwrap();
    assert_eq!(with_numbers.dimensions(), without.dimensions());
    let differing = with_numbers
        .pixels()
        .zip(without.pixels())
        .filter(|(a, b)| a != b)
        .count();
    // Text in every one of the 126 cells.
    assert!(differing > 126 * 10, "{differing}");
}

/// Many triangles over one grid: `tiled` frames each block once, with
/// the strongest class any triangle gave it, not one frame per triangle.
#[test]
fn tiled_frames_each_block_once_for_many_triangles() {
    use rasterlab::raster::triangle::BlockClass;
    let tiled = triangle_backend("tiled").unwrap();
    let scene = Scene2D::pinwheel();
    let triangles: Vec<[(f64, f64); 3]> = scene
        .triangles
        .iter()
        .map(|t| t.map(|p| p.to_f64()))
        .map(|t| t.map(|(x, y)| (x * 4.0, y * 4.0)))
        .collect();
    let p = GridPicture::of_triangles(tiled, &triangles, FillRule::TopLeft, 36, 36).unwrap();
    let mut rects: Vec<_> = p
        .blocks
        .iter()
        .map(|(r, _)| (r.x0, r.y0, r.x1, r.y1))
        .collect();
    let n = rects.len();
    rects.sort_unstable();
    rects.dedup();
    assert_eq!(rects.len(), n, "a block framed twice");
    assert!(p.blocks.iter().any(|b| b.1 == BlockClass::Partial));
    assert_eq!(p.to_svg().matches("class=\"block\"").count(), n);
}

//! Traces checked against answers worked by hand from the course notes.

mod common;

use proptest::prelude::*;
use rasterlab::raster::line::LineRasterizer;
use rasterlab::raster::triangle::TriangleRasterizer;
use rasterlab::raster::{line_backend, triangle_backend, FillRule};
use rasterlab::teaching::{trace_line, trace_triangle, LineEnds};
use rasterlab::Result;

/// A triangle back-end's trace as text, as `rasterlab explain` prints it.
fn triangle_text(
    backend: &dyn TriangleRasterizer,
    vertices: [(f64, f64); 3],
    rule: FillRule,
    width: u32,
    height: u32,
) -> Result<String> {
    trace_triangle(backend, vertices, rule, width, height).map(|t| t.to_text())
}

/// [`triangle_text`] of the back-end named `name`.
fn triangle_trace(
    name: &str,
    vertices: [(f64, f64); 3],
    rule: FillRule,
    width: u32,
    height: u32,
) -> Result<String> {
    triangle_text(triangle_backend(name)?, vertices, rule, width, height)
}

/// A line back-end's trace as text, as `rasterlab explain` prints it.
fn line_text(backend: &dyn LineRasterizer, ends: &LineEnds) -> Result<String> {
    trace_line(backend, ends).map(|t| t.to_text())
}

/// [`line_text`] of the back-end named `name`.
fn line_trace(name: &str, ends: &LineEnds) -> Result<String> {
    line_text(line_backend(name)?, ends)
}

/// The line-drawing slides' midpoint loop on (0, 0) -> (7, 3): f(x, y) = -3 x + 7 y, so
/// d starts at f(1, 1/2) = 0.5 and then adds -3 (keep y) or -3 + 7 (step).
#[test]
fn bresenham_0_0_7_3_matches_the_hand_worked_table() {
    let expected = "\
bresenham (midpoint) from pixel (0, 0) to pixel (7, 3) (pixel indices: the line joins their centres); first octant: no symmetry needed
   x      y  pixel            d  choice
   0      0    0,0        0.500  d >= 0: the line meets the midpoint or passes on its y side, keep y
   1      0    1,0       -2.500  d < 0: the line passes on the midpoint's y + 1 side, y = y + 1
   2      1    2,1        1.500  d >= 0: the line meets the midpoint or passes on its y side, keep y
   3      1    3,1       -1.500  d < 0: the line passes on the midpoint's y + 1 side, y = y + 1
   4      2    4,2        2.500  d >= 0: the line meets the midpoint or passes on its y side, keep y
   5      2    5,2       -0.500  d < 0: the line passes on the midpoint's y + 1 side, y = y + 1
   6      3    6,3        3.500  d >= 0: the line meets the midpoint or passes on its y side, keep y
   7      3    7,3        0.500  d >= 0: the line meets the midpoint or passes on its y side, keep y
d = f(x + 1, y + 1/2) with f(x, y) = (y0 - y1) x + (x1 - x0) y + x0 y1 - x1 y0, in the walking frame, in px² (the back-end keeps it as a whole number of 1/65536 px²)
";
    let ends = LineEnds::pixels([0.0, 0.0, 7.0, 3.0]).unwrap();
    assert_eq!(line_trace("bresenham", &ends).unwrap(), expected);
    // Walked the other way, the walking frame is mirrored: its columns are
    // u and v, not read as screen coordinates, beside the screen pixel.
    let reversed = line_trace(
        "bresenham",
        &LineEnds::pixels([7.0, 3.0, 0.0, 0.0]).unwrap(),
    )
    .unwrap();
    let lines: Vec<&str> = reversed.lines().collect();
    assert!(lines[0].ends_with("walked in the first octant (major axis mirrored, minor axis mirrored) as u along the major axis and v along the minor one, pixels mapped back"), "{reversed}");
    assert_eq!(lines[1], "   u      v  pixel            d  choice");
    assert!(lines[2].starts_with("  -7     -3    7,3        0.500  d >= 0: the line meets the midpoint or passes on its v side, keep v"), "{reversed}");
    assert!(
        lines.last().unwrap().starts_with("d = f(u + 1, v + 1/2)"),
        "{reversed}"
    );
    // The same line in screen coordinates draws the same table, and its
    // first line says how the endpoints were read.
    let screen = line_trace(
        "bresenham",
        &LineEnds::screen([0.5, 0.5, 7.5, 3.5]).unwrap(),
    )
    .unwrap();
    assert_eq!(
        screen.lines().next().unwrap(),
        "bresenham (midpoint) from (0.5, 0.5) to (7.5, 3.5) in screen coordinates; first octant: no symmetry needed"
    );
    assert_eq!(
        screen.lines().skip(1).collect::<Vec<_>>(),
        expected.lines().skip(1).collect::<Vec<_>>()
    );
}

/// y = 3/7 x: exact values k * 3/7 and their nearest rows, the same rows
/// for direct evaluation and for the incremental DDA.
#[test]
fn direct_and_dda_round_the_exact_y() {
    for backend in ["direct", "dda"] {
        let text = line_trace(backend, &LineEnds::pixels([0.0, 0.0, 7.0, 3.0]).unwrap()).unwrap();
        let rows: Vec<(String, String)> = text
            .lines()
            .skip(2)
            .take(8)
            .map(|l| {
                let f: Vec<&str> = l.split_whitespace().collect();
                (f[1].to_string(), f[2].to_string())
            })
            .collect();
        let expected = [
            ("0.0000", "0"),
            ("0.4286", "0"),
            ("0.8571", "1"),
            ("1.2857", "1"),
            ("1.7143", "2"),
            ("2.1429", "2"),
            ("2.5714", "3"),
            ("3.0000", "3"),
        ];
        for (got, want) in rows.iter().zip(expected) {
            assert_eq!((got.0.as_str(), got.1.as_str()), want, "{backend}");
        }
    }
}

/// The bounding-box trace of a right triangle: its box (5 x 4 pixels) tested, and the
/// verdicts name the edge and the tie rule.
#[test]
fn bbox_trace_counts_and_explains() {
    let text = triangle_trace(
        "bbox",
        [(0.5, 0.5), (4.5, 0.5), (0.5, 3.5)],
        FillRule::TopLeft,
        6,
        4,
    )
    .unwrap();
    // Box 5 x 4; inside: 4 + 3 + 2 (row 3 only touches v2, on the right edge).
    assert!(text.ends_with("20 pixels tested, 9 fragments\n"), "{text}");
    assert!(text.contains("   4    0    0.0000   12.0000    0.0000   0.000   1.000   0.000  outside: on E0, a right edge that does not own its ties"));
    assert!(text.contains(
        "   3    1   -1.0000    9.0000    4.0000  -0.083   0.750   0.333  outside: E0 < 0"
    ));
    let naive = triangle_trace(
        "naive",
        [(0.5, 0.5), (4.5, 0.5), (0.5, 3.5)],
        FillRule::TopLeft,
        6,
        4,
    )
    .unwrap();
    assert!(
        naive.ends_with("24 pixels tested, 9 fragments\n"),
        "{naive}"
    );
}

/// Classic scanline on the right triangle (0.5, 0.5), (4.5, 0.5), (0.5, 3.5)
/// under the top-left rule, worked by hand: the long edge x = 0.5 runs
/// through the centres of column 0 (a left edge: it owns the tie, first =
/// 0); the hypotenuse x = 4.5 - 4/3 (y - 0.5) crosses row 0 at a centre (a
/// right edge: no tie, last = 3) and row 3 at x = 0.5 (last = -1: empty).
#[test]
fn scanline_trace_matches_the_hand_worked_rows() {
    let expected = "\
scanline, top-left rule: sorted by y, top v0 (0.5, 0.5), mid v1 (4.5, 0.5), bottom v2 (0.5, 3.5)
long edge v0-v2 (E1) bounds every row; short edges v0-v1 (E2) above mid, v1-v2 (E0) below
rows 0..=3: their sample lines y = row + 0.5 lie between top and bottom
 row sample y  edge crossings: exact x -> pixel bound                                   span
   0    0.500  E1 x = 0.5000 -> first 0; E2 horizontal -> all; E0 x = 4.5000 -> last 3  0..=3 (4 px)
   1    1.500  E1 x = 0.5000 -> first 0; E0 x = 3.1667 -> last 2                        0..=2 (3 px)
   2    2.500  E1 x = 0.5000 -> first 0; E0 x = 1.8333 -> last 1                        0..=1 (2 px)
   3    3.500  E1 x = 0.5000 -> first 0; E0 x = 0.5000 -> last -1                       empty
4 rows, 9 fragments; a left edge (E rising to the right) gives the first pixel, a right edge the last
";
    assert_eq!(
        triangle_trace(
            "scanline",
            [(0.5, 0.5), (4.5, 0.5), (0.5, 3.5)],
            FillRule::TopLeft,
            6,
            4
        )
        .unwrap(),
        expected
    );
}

proptest! {
    #![proptest_config(crate::common::proptest_config(300, "tests/proptest-regressions/traces.txt"))]
    /// The scanline trace fills exactly the pixels the bbox trace finds
    /// inside, on any triangle and fill rule.
    #[test]
    fn scanline_trace_fills_what_the_bbox_trace_finds_inside(
        v in proptest::array::uniform6(-2.0f64..18.0),
        rule in prop_oneof![
            Just(FillRule::TopLeft),
            Just(FillRule::BottomRight),
            Just(FillRule::OffscreenPoint),
            Just(FillRule::Inclusive),
            Just(FillRule::Exclusive),
        ],
    ) {
        let triangle = [(v[0], v[1]), (v[2], v[3]), (v[4], v[5])];
        let scan = triangle_trace("scanline", triangle, rule, 16, 16).unwrap();
        let bbox = triangle_trace("bbox", triangle, rule, 16, 16).unwrap();
        let count = |text: &str, marker: &str| -> Option<String> {
            let last = text.lines().last()?;
            let at = last.find(marker)?;
            Some(last[..at].split_whitespace().last()?.to_string())
        };
        let from_bbox = count(&bbox, " fragments");
        let from_scan = count(&scan, " fragments");
        if bbox.starts_with("the snapped triangle has zero area") {
            prop_assert!(scan.starts_with("the snapped triangle has zero area"));
        } else {
            prop_assert!(from_bbox.is_some());
            prop_assert_eq!(from_bbox, from_scan, "{}\n{}", bbox, scan);
        }
    }
}

mod newer_traces {
    use super::{line_trace, triangle_trace};
    use proptest::prelude::*;
    use rasterlab::geometry::setup_triangles;
    use rasterlab::raster::line::{LineOptions, LineSetup};
    use rasterlab::raster::{
        line_backend, triangle_backend, FillRule, FixedPoint, FragmentList, PixelRect,
    };
    use rasterlab::teaching::LineEnds;
    use std::collections::HashSet;

    fn fragments(name: &str, v: [(f64, f64); 3], size: u32) -> (HashSet<(i64, i64)>, u64) {
        let t = v.map(|(x, y)| FixedPoint::snap_f64(x, y).unwrap());
        let mut list = FragmentList::default();
        let work = triangle_backend(name).unwrap().rasterize(
            &setup_triangles(&[t], FillRule::TopLeft),
            PixelRect::of_target(size, size),
            &mut list,
        );
        (
            list.triangles
                .iter()
                .map(|f| (i64::from(f.x), i64::from(f.y)))
                .collect(),
            work.samples_tested,
        )
    }

    fn line(ends: &LineEnds, name: &str) -> Vec<(i64, i64)> {
        let mut list = FragmentList::default();
        line_backend(name).unwrap().rasterize(
            &[LineSetup {
                id: 0,
                from: ends.from,
                to: ends.to,
            }],
            &LineOptions::DEFAULT,
            PixelRect::of_target(64, 64),
            &mut list,
        );
        list.lines
            .iter()
            .filter(|f| f.coverage > 0.0)
            .map(|f| (i64::from(f.x), i64::from(f.y)))
            .collect()
    }

    /// The diamond trace records the back-end's walk: its candidates in
    /// the order of travel (here right to left and bottom to top), as many
    /// as the back-end counts, its drawn pixels in the order drawn.
    #[test]
    fn the_diamond_trace_is_the_walk_in_its_order() {
        use rasterlab::teaching::trace_line;
        for ends in [
            [7.0, 3.0, 0.0, 0.0],
            [2.0, 9.0, 4.0, 1.0],
            [0.0, 0.0, 7.0, 3.0],
        ] {
            let ends = LineEnds::pixels(ends).unwrap();
            let backend = line_backend("diamond").unwrap();
            let trace = trace_line(backend, &ends).unwrap();
            let drawn: Vec<(i64, i64)> = trace
                .rows
                .iter()
                .filter(|r| r.cells[1].ends_with(": drawn"))
                .map(|r| (r.about[0][0], r.about[0][1]))
                .collect();
            assert_eq!(drawn, line(&ends, "diamond"), "{ends:?}");
            let mut list = FragmentList::default();
            let line = LineSetup {
                id: 0,
                from: ends.from,
                to: ends.to,
            };
            let work = backend.rasterize(
                &[line],
                &LineOptions::DEFAULT,
                PixelRect::of_target(64, 64),
                &mut list,
            );
            assert_eq!(trace.rows.len() as u64, work.samples_tested, "{ends:?}");
        }
    }

    proptest! {
        #![proptest_config(crate::common::proptest_config(200, "tests/proptest-regressions/traces.txt"))]
        /// The incremental trace lists exactly the pixels the back-end tests
        /// and draws; every inside or outside block of the tiled trace is
        /// wholly drawn or wholly empty.
        #[test]
        fn the_triangle_traces_agree_with_their_back_ends(v in proptest::array::uniform6(-2.0f64..34.0)) {
            let v = [(v[0], v[1]), (v[2], v[3]), (v[4], v[5])];
            let (drawn, tested) = fragments("incremental", v, 32);
            let text = triangle_trace("incremental", v, FillRule::TopLeft, 32, 32).unwrap();
            let rows: Vec<Vec<&str>> = text.lines().skip(3).map(|l| l.split_whitespace().collect()).filter(|w: &Vec<&str>| w.len() >= 6 && w[0].parse::<i64>().is_ok() && w[1].parse::<i64>().is_ok()).collect();
            let inside: HashSet<(i64, i64)> = rows.iter().filter(|w| w[5] == "inside").map(|w| (w[0].parse().unwrap(), w[1].parse().unwrap())).collect();
            prop_assert_eq!(&inside, &drawn);
            if !drawn.is_empty() {
                prop_assert_eq!(rows.len() as u64, tested, "{}", text);
            }
            let tiled = triangle_trace("tiled", v, FillRule::TopLeft, 32, 32).unwrap();
            for l in tiled.lines().skip(2) {
                let w: Vec<&str> = l.split_whitespace().collect();
                if w.len() < 3 || !w[0].contains("..=") { continue; }
                let range = |s: &str| { let (a, b) = s.split_once("..=").unwrap(); (a.parse::<i64>().unwrap(), b.parse::<i64>().unwrap()) };
                let ((x0, x1), (y0, y1)) = (range(w[0]), range(w[1]));
                let count = (y0..=y1).flat_map(|y| (x0..=x1).map(move |x| (x, y))).filter(|p| drawn.contains(p)).count() as i64;
                match w[2] {
                    "inside:" => prop_assert_eq!(count, (x1 - x0 + 1) * (y1 - y0 + 1)),
                    "outside:" => prop_assert_eq!(count, 0),
                    _ => {}
                }
            }
        }

        /// The Wu trace lists Wu's pixels, and a column's two weights sum
        /// to one; the diamond trace draws what the diamond back-end draws.
        #[test]
        fn the_line_traces_agree_with_their_back_ends(c in proptest::array::uniform4(0i32..40)) {
            let ends = LineEnds::pixels(c.map(f64::from)).unwrap();
            let text = line_trace("wu", &ends).unwrap();
            let mut listed = Vec::new();
            for l in text.lines().skip(2) {
                let w: Vec<&str> = l.split_whitespace().collect();
                if !w.first().is_some_and(|p| p.contains(',')) { continue; }
                let mut sum = 0.0;
                for pair in w.chunks(2) {
                    let (x, y) = pair[0].split_once(',').unwrap();
                    listed.push((x.parse::<i64>().unwrap(), y.parse::<i64>().unwrap()));
                    sum += pair[1].parse::<f64>().unwrap();
                }
                prop_assert!((sum - 1.0).abs() < 2e-4, "{}", l);
            }
            let mut wu = line(&ends, "wu");
            listed.sort();
            wu.sort();
            prop_assert_eq!(listed, wu);
            let text = line_trace("diamond", &ends).unwrap();
            let mut drawn: Vec<(i64, i64)> = text.lines().filter(|l| l.ends_with(": drawn")).map(|l| {
                let (x, y) = l.split_whitespace().next().unwrap().split_once(',').unwrap();
                (x.parse().unwrap(), y.parse().unwrap())
            }).collect();
            let mut diamond = line(&ends, "diamond");
            drawn.sort();
            diamond.sort();
            prop_assert_eq!(drawn, diamond);
        }
    }
}

/// A back-end from outside the registry is traced by the way it walks,
/// not looked up by its name.
#[test]
fn an_outside_back_end_is_traced_by_its_walk() {
    use rasterlab::raster::triangle::bbox::BoundingBox;
    use rasterlab::raster::triangle::{
        TriangleAlgorithm, TriangleDescriptor, TriangleWalk, Walk, WalkObserver,
    };
    use rasterlab::raster::{CostClass, PixelRect, Role, TriangleSetup};

    struct MyBox;
    impl TriangleAlgorithm for MyBox {
        const DESCRIPTOR: TriangleDescriptor = TriangleDescriptor {
            name: "my-box",
            description: "the bounding-box loop, under another name",
            walk: TriangleWalk::BoundingBox,
            role: Role::Alternative,
            cost: CostClass::FollowsSize,
        };
        fn draw_triangle<O: WalkObserver>(
            &self,
            t: &TriangleSetup,
            viewport: PixelRect,
            walk: &mut Walk<O>,
        ) {
            BoundingBox.draw_triangle(t, viewport, walk)
        }
    }
    let triangle = [(0.5, 0.5), (4.5, 0.5), (0.5, 3.5)];
    let mine = triangle_text(&MyBox, triangle, FillRule::TopLeft, 6, 4).unwrap();
    let bbox = triangle_trace("bbox", triangle, FillRule::TopLeft, 6, 4).unwrap();
    assert!(mine.starts_with("my-box, top-left rule"), "{mine}");
    assert_eq!(mine.replacen("my-box", "bbox", 1), bbox);
}

/// Traces are recordings of the walk that draws: a back-end added from
/// outside the crate, with a walk of its own, is drawn, traced, checked
/// and benchmarked with no code but its algorithm, and a mutation of a
/// walk shows in its trace.
mod recordings {
    use super::{triangle_text, triangle_trace};
    use rasterlab::check::{check, Builtin, CheckOptions, Property, Verdict};
    use rasterlab::geometry::Scene2D;
    use rasterlab::measure::sized;
    use rasterlab::raster::triangle::bbox::BoundingBox;
    use rasterlab::raster::triangle::{
        TriangleAlgorithm, TriangleDescriptor, TriangleWalk, Walk, WalkObserver,
    };
    use rasterlab::raster::{CostClass, FillRule, PixelRect, RenderTarget, Role, TriangleSetup};

    /// The bounding box walked column by column, right to left: a walk no
    /// back-end of the crate makes.
    struct Columns;

    impl TriangleAlgorithm for Columns {
        const DESCRIPTOR: TriangleDescriptor = TriangleDescriptor {
            name: "columns",
            description: "the bounding box, column by column from the right",
            walk: TriangleWalk::Own("the bounding box, column by column from the right"),
            role: Role::Alternative,
            cost: CostClass::FollowsSize,
        };
        fn draw_triangle<O: WalkObserver>(
            &self,
            t: &TriangleSetup,
            viewport: PixelRect,
            walk: &mut Walk<O>,
        ) {
            let r = t.bounds_within(viewport);
            for x in (r.x0..=r.x1).rev() {
                for y in r.y0..=r.y1 {
                    let e = t.edge_values_at_pixel(x, y);
                    if walk.test(x, y, e) {
                        walk.fragment(x, y, e);
                    }
                }
            }
        }
    }

    /// `bbox`, mutated: the last column of its box is never tested.
    struct ShortRows;

    impl TriangleAlgorithm for ShortRows {
        const DESCRIPTOR: TriangleDescriptor = TriangleDescriptor {
            name: "bbox",
            ..BoundingBox::DESCRIPTOR
        };
        fn draw_triangle<O: WalkObserver>(
            &self,
            t: &TriangleSetup,
            viewport: PixelRect,
            walk: &mut Walk<O>,
        ) {
            let r = t.bounds_within(viewport);
            let shorter = PixelRect {
                x1: r.x1 - 1,
                ..viewport
            };
            BoundingBox.draw_triangle(t, shorter, walk)
        }
    }

    const TRIANGLE: [(f64, f64); 3] = [(0.5, 0.5), (4.5, 0.5), (0.5, 3.5)];

    #[test]
    fn a_back_end_with_a_walk_of_its_own_is_drawn_traced_checked_and_benchmarked() {
        // Drawn: the depth-buffer example, as every back-end draws it.
        let scene = Scene2D::depth_example(true);
        let rule = FillRule::TopLeft;
        let flat = &rasterlab::raster::Flat;
        let mine = scene.render(&Columns, rule, flat).unwrap().0;
        let bbox = scene.render(&BoundingBox, rule, flat).unwrap().0;
        assert!(mine == bbox, "the images differ");
        // Traced: its own steps, in its own order (the rightmost column
        // first), the verdicts of the bounding-box loop.
        let text = triangle_text(&Columns, TRIANGLE, rule, 6, 4).unwrap();
        let rows: Vec<&str> = text.lines().collect();
        assert!(rows[0].starts_with("columns, top-left rule"), "{text}");
        assert!(rows[1].starts_with("walk: the bounding box, column by column"));
        assert!(rows[6].starts_with("   4    0 "), "{text}");
        assert!(text.ends_with("20 pixels tested, 9 fragments\n"), "{text}");
        let mut by_pixel: Vec<&str> = rows[6..26].to_vec();
        by_pixel.sort_by_key(|l| {
            let w: Vec<i64> = l
                .split_whitespace()
                .take(2)
                .map(|n| n.parse().unwrap())
                .collect();
            (w[1], w[0])
        });
        let bbox_text = triangle_trace("bbox", TRIANGLE, rule, 6, 4).unwrap();
        let bbox_rows: Vec<&str> = bbox_text.lines().skip(6).take(20).collect();
        assert_eq!(by_pixel, bbox_rows);
        // Checked: exact under the top-left rule.
        let options = CheckOptions {
            cases: 100,
            ..CheckOptions::new(Property::Exact(rule))
        };
        let verdict = check(&options, &mut Builtin::triangles(&Columns, rule)).unwrap();
        assert!(matches!(verdict, Verdict::Pass { cases: 100 }));
        // Benchmarked: a workload runs it as it runs the built-in ones.
        let work = sized(128, 128, 16.0);
        assert!(work.suits(&Columns));
        let mut target = RenderTarget::new(128, 128).unwrap();
        let fragments = work.run(&Columns, &mut target);
        assert_eq!(fragments, work.run(&BoundingBox, &mut target));
    }

    #[test]
    fn a_mutation_in_a_walk_changes_its_trace() {
        let rule = FillRule::TopLeft;
        let bbox = triangle_trace("bbox", TRIANGLE, rule, 6, 4).unwrap();
        let mutant = triangle_text(&ShortRows, TRIANGLE, rule, 6, 4).unwrap();
        assert_ne!(mutant, bbox);
        // Column 4 is no longer tested: 16 pixels, the same 9 fragments.
        assert!(
            mutant.ends_with("16 pixels tested, 9 fragments\n"),
            "{mutant}"
        );
        assert!(!mutant.lines().any(|l| l.starts_with("   4 ")), "{mutant}");
        assert!(bbox.lines().any(|l| l.starts_with("   4    0 ")));
    }
}

/// A trace is data: each row carries the pixel it is about (the one its
/// cells name), its text is what `explain` prints, and it goes to the lab
/// as JSON.
#[test]
fn every_row_carries_the_pixels_it_is_about() {
    let vertices = [(1.5, 1.25), (13.75, 4.5), (4.25, 13.5)];
    let rule = FillRule::TopLeft;
    for name in ["naive", "bbox", "incremental"] {
        let b = triangle_backend(name).unwrap();
        let trace = trace_triangle(b, vertices, rule, 16, 16).unwrap();
        assert_eq!(
            trace.to_text(),
            triangle_text(b, vertices, rule, 16, 16).unwrap()
        );
        let tested: usize = trace.footer[0].split(' ').next().unwrap().parse().unwrap();
        assert_eq!(trace.rows.len(), tested, "{name}");
        for row in &trace.rows {
            let x: i64 = row.cells[0].parse().unwrap();
            let y: i64 = row.cells[1].parse().unwrap();
            assert_eq!(row.about, vec![[x, y, x, y]], "{name}");
        }
    }
    // Scanline: a row of the table is a row of pixels, the grid's width.
    let trace = trace_triangle(
        triangle_backend("scanline").unwrap(),
        vertices,
        rule,
        16,
        16,
    )
    .unwrap();
    for row in &trace.rows {
        let y: i64 = row.cells[0].parse().unwrap();
        assert_eq!(row.about, vec![[0, y, 15, y]]);
    }
    // Bresenham: each column's pixel.
    let ends = LineEnds::pixels([0.0, 0.0, 7.0, 3.0]).unwrap();
    let b = line_backend("bresenham").unwrap();
    let trace = trace_line(b, &ends).unwrap();
    assert_eq!(trace.to_text(), line_text(b, &ends).unwrap());
    for row in &trace.rows {
        let (x, y) = row.cells[2].split_once(',').unwrap();
        let (x, y): (i64, i64) = (x.parse().unwrap(), y.parse().unwrap());
        assert!(row.is_about(x, y) && !row.is_about(x + 1, y));
    }
    let json = serde_json::to_value(&trace).unwrap();
    assert_eq!(json["rows"][3]["about"], serde_json::json!([[3, 1, 3, 1]]));
    assert_eq!(json["columns"][4]["name"], "choice");
}

/// The blend trace of one pixel of the `transparent` scene: drawn as
/// listed with the depth test, the two farther triangles fail it there
/// and the pixel keeps the nearest alone; sorted, all three pass. Either
/// way the trace ends at the colour `render` writes there.
#[test]
fn the_blend_trace_follows_one_pixel_through_every_fragment() {
    use rasterlab::geometry::Scene2D;
    use rasterlab::raster::{Blend, BlendMode, DepthState, Flat, RenderTarget};
    let over = Blend {
        mode: BlendMode::OverStraight,
        ..Blend::default()
    };
    let bbox = rasterlab::raster::triangle_backend("bbox").unwrap();
    for (scene, verdicts) in [
        (Scene2D::transparent(), ["passes", "fails", "fails"]),
        (
            Scene2D::transparent().sorted_back_to_front(),
            ["passes", "passes", "passes"],
        ),
    ] {
        let trace = rasterlab::teaching::trace_blend(
            &scene,
            (20, 18),
            bbox,
            FillRule::TopLeft,
            DepthState::DEFAULT,
            over,
        )
        .unwrap();
        let rows: Vec<_> = trace.rows.iter().filter(|r| !r.note).collect();
        assert_eq!(rows.len(), 3);
        for (row, verdict) in rows.iter().zip(verdicts) {
            assert!(row.cells[1].ends_with(verdict), "{:?}", row.cells);
        }
        let mut target = RenderTarget::new(scene.width, scene.height).unwrap();
        scene.draw_blended(
            bbox,
            FillRule::TopLeft,
            (DepthState::DEFAULT, over),
            &Flat,
            &mut target,
        );
        let [r, g, b, a] = target.color[target.index(20, 18)];
        assert_eq!(
            rows[2].cells.last().unwrap(),
            &format!("({r}, {g}, {b}, {a})")
        );
        assert!(trace.footer[0].ends_with(&format!("({r}, {g}, {b}, {a})")));
    }
    // A pixel outside the scene is refused.
    let scene = Scene2D::transparent();
    let outside = rasterlab::teaching::trace_blend(
        &scene,
        (48, 0),
        bbox,
        FillRule::TopLeft,
        DepthState::DEFAULT,
        over,
    );
    assert!(outside
        .unwrap_err()
        .to_string()
        .contains("outside the 48 x 32 scene"));
}

/// `explain --clip`: the line (-2.3, 1.7) -> (12.4, 6.1) on an 8 x 8 grid,
/// worked by hand. Snapped, it runs from (-589, 435) to (3174, 1562) in
/// 1/256 px, `dx = 3763`; the window (one pixel beyond the grid) is
/// `-256..=2304` both ways. Cohen-Sutherland: P0 is left (0001), P1 right
/// (0010); P0 moves to `x = -256` at `t = 333/3763`, P1 to `x = 2304` at
/// `t = 2893/3763`. Liang-Barsky: `p1 = -dx`, `q1 = x0 - xmin = -333`
/// (-14.699 and -1.301 px), the same interval. The walk restarts at
/// column 0 with the decision variable the whole walk has there.
#[test]
fn clip_traces_worked_by_hand() {
    use rasterlab::raster::line::bresenham::Bresenham;
    use rasterlab::raster::line::clip::Clipper;
    use rasterlab::raster::line::OctantFrame;
    use rasterlab::teaching::trace_clip;
    let ends = LineEnds::screen([-2.3, 1.7, 12.4, 6.1]).unwrap();
    assert_eq!((ends.from.x.raw(), ends.from.y.raw()), (-589, 435));
    assert_eq!((ends.to.x.raw(), ends.to.y.raw()), (3174, 1562));
    let bresenham = line_backend("bresenham").unwrap();
    let cs = trace_clip(Clipper::CohenSutherland, bresenham, &ends, 8, 8)
        .unwrap()
        .to_text();
    for line in [
        "   1     0001     0010  P0 is outside: move it to the left edge, t = 333/3763 = 0.0885, P0 = (-1.000, 2.089), code 0000",
        "   2     0000     0010  P1 is outside: move it to the right edge, t = 2893/3763 = 0.7688, P1 = (9.000, 5.084), code 0000",
        "   3     0000     0000  accept: both codes 0000, the segment between them is inside",
        "work: 4 outcodes, 2 intersections computed",
    ] {
        assert!(cs.lines().any(|l| l == line), "{line}\nnot in\n{cs}");
    }
    let lb = trace_clip(Clipper::LiangBarsky, bresenham, &ends, 8, 8)
        .unwrap()
        .to_text();
    let row = lb.lines().find(|l| l.starts_with("1  left")).unwrap();
    let cells: Vec<&str> = row.split_whitespace().collect();
    assert_eq!(
        &cells[2..7],
        ["-14.69921875", "-1.30078125", "0.0885", "0.0885", "1.0000"]
    );
    // Both keep the same interval and walk the same columns.
    let tail = |t: &str| {
        t.lines()
            .skip_while(|l| !l.starts_with("kept"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(tail(&cs), tail(&lb));
    // The restarted decision variable is the whole walk's at column 0.
    let frame = OctantFrame::new(ends.from, ends.to);
    let at_0 = Bresenham::steps(&frame)
        .into_iter()
        .find(|s| s.i == 0)
        .unwrap();
    let d = at_0.d as f64 / 65536.0;
    assert!(
        cs.contains(&format!(
            "restarted there: d = f(x + 1, y + 1/2) = {d:.3} px²"
        )),
        "{cs}"
    );
    assert!(cs.contains("walks x = 0..7 only"), "{cs}");
    assert!(cs.contains("round-to-pixel-centres): clipped at the viewport's own edges, moved to their pixels' centres, (0.5, 2.5) -> (8.5, 4.5), walked afresh: 8 fragments, 6 drawn"), "{cs}");
}

/// `explain --backend clip-triangle`: the example's vertex behind the
/// camera is outside the near plane and `w > 0`; the near plane cuts its
/// two edges at the t worked by hand (`d_a / (d_a - d_b)`, 2.0202 against
/// -3.0303: 0.4), leaving a quadrilateral that the later planes pass
/// whole, and its fan from v0 is two triangles whose new vertices lie on
/// the near plane (depth 0). The traced polygon is the pipeline's own
/// (the trace errs otherwise). Bad input is refused with exit 2.
#[test]
fn the_near_plane_cuts_the_example_into_a_fan_of_two() {
    use rasterlab::geometry::ClipPlanes;
    use rasterlab::teaching::{trace_triangle_clip, BEHIND_THE_CAMERA};
    let text = trace_triangle_clip(&BEHIND_THE_CAMERA, ClipPlanes::GuardBand, 16, 16)
        .unwrap()
        .to_text();
    assert!(
        text.contains("v2 = (0.000, 1.000, -2.530, -0.500): out-code 1111101, outside near, w > 0"),
        "{text}"
    );
    assert!(text.contains("the edge leaves the plane at t = 0.4000: new vertex p0 = (0.600, -0.200, -1.000, 1.000)"), "{text}");
    assert!(text.contains("the edge enters the plane at t = 0.6000: new vertex p1 = (-0.600, -0.200, -1.000, 1.000)"), "{text}");
    assert!(
        text.contains("after near: 4 vertices, v0 v1 p0 p1"),
        "{text}"
    );
    assert!(
        text.contains("a fan of 2 triangles, (v0 v1 p0), (v0 p0 p1)"),
        "{text}"
    );
    assert!(
        text.contains(
            "p0: divided by w = 1.000 and mapped to the viewport: (12.801, 9.602) px, depth 0.0000"
        ),
        "{text}"
    );
    // Inside every plane, and behind the camera altogether.
    let inside = [0.0, 0.0, 0.5, 1.0, 0.5, 0.0, 0.5, 1.0, 0.0, 0.5, 0.5, 1.0];
    let text = trace_triangle_clip(&inside, ClipPlanes::Viewport, 8, 8)
        .unwrap()
        .to_text();
    assert!(text.contains("the triangle goes on as it is"), "{text}");
    let behind = [
        0.0, 0.0, 0.5, -1.0, 0.5, 0.0, 0.5, -1.0, 0.0, 0.5, 0.5, -1.0,
    ];
    let text = trace_triangle_clip(&behind, ClipPlanes::GuardBand, 8, 8)
        .unwrap()
        .to_text();
    assert!(text.contains("the triangle is rejected"), "{text}");
    let out = common::rasterlab(&["explain", "--backend", "clip-triangle"]);
    assert!(out.status.success());
    for bad in [
        &["explain", "--backend", "clip-triangle", "1", "2", "3"][..],
        &[
            "explain",
            "--backend",
            "clip-triangle",
            "--picture",
            "p.svg",
        ],
        &["explain", "--backend", "clip-triangle", "--size", "0x4"],
    ] {
        assert_eq!(common::rasterlab(bad).status.code(), Some(2), "{bad:?}");
    }
}

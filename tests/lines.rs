//! Line back-ends: connectivity, one pixel per step, endpoints, distance to
//! the ideal line, octant symmetry, the symmetric variant, half-open
//! polylines, direct = bresenham, the diamond rule against brute force and
//! Vulkan's tolerance, and `line_drawing` as an outside oracle.

mod common;

use proptest::prelude::*;
use rasterlab::measure::LineWorkload;
use rasterlab::raster::line::bresenham::Bresenham;
use rasterlab::raster::line::dda::Dda;
use rasterlab::raster::line::diamond::{exits_diamond, Diamond};
use rasterlab::raster::line::direct::Direct;
use rasterlab::raster::line::wu::Wu;
use rasterlab::raster::line::{
    AliasedLine, Connectivity, Endpoints, LineOptions, LineRasterizer, LineSetup, OctantFrame,
};
use rasterlab::raster::{FixedPoint, FragmentList, PixelRect, RenderTarget};
use rasterlab::teaching::{ascii_mark, ascii_rows};
use std::collections::BTreeSet;

type Pixels = Vec<(i64, i64)>;
/// An algorithm of the line-drawing slides: its pixel function.
type PixelsOf = fn(&LineSetup, &LineOptions) -> Pixels;
/// An octant case: start, end, grid size, expected pattern.
type OctantCase = ((f32, f32), (f32, f32), (i64, i64), &'static [&'static str]);

fn snap(x: f32, y: f32) -> FixedPoint {
    FixedPoint::snap(x, y).unwrap()
}

/// A point from its raw 1/256-pixel coordinates.
fn raw(x: i64, y: i64) -> FixedPoint {
    FixedPoint::from_raw(x, y).unwrap()
}

fn seg(a: FixedPoint, b: FixedPoint) -> LineSetup {
    LineSetup {
        id: 0,
        from: a,
        to: b,
    }
}

/// The three aliased algorithms of the line-drawing slides, by name.
fn aliased() -> [(&'static str, PixelsOf); 3] {
    [
        ("direct", Direct::pixels),
        ("dda", Dda::pixels),
        ("bresenham", Bresenham::pixels),
    ]
}

/// Endpoints: pixel centres (many exact ties), or random floats, never
/// exactly on a pixel boundary (where "the pixel containing" is one-sided).
fn endpoint() -> impl Strategy<Value = FixedPoint> {
    prop_oneof![
        (-20i32..60, -20i32..60).prop_map(|(x, y)| snap(x as f32 + 0.5, y as f32 + 0.5)),
        (-20.0f32..60.0, -20.0f32..60.0)
            .prop_map(|(x, y)| snap(x, y))
            .prop_filter("not on a pixel boundary", |p| p.x.raw() % 256 != 0
                && p.y.raw() % 256 != 0),
    ]
}

/// Endpoints on pixel centres: the seed's integer endpoints, where the
/// endpoint pixels are exactly the pixels containing the endpoints.
fn centre_endpoint() -> impl Strategy<Value = FixedPoint> {
    (-20i32..60, -20i32..60).prop_map(|(x, y)| snap(x as f32 + 0.5, y as f32 + 0.5))
}

fn options() -> impl Strategy<Value = LineOptions> {
    (any::<bool>(), any::<bool>(), any::<bool>()).prop_map(|(four, half, symmetric)| LineOptions {
        connectivity: if four {
            Connectivity::Four
        } else {
            Connectivity::Eight
        },
        endpoints: if half {
            Endpoints::HalfOpen
        } else {
            Endpoints::Inclusive
        },
        symmetric,
    })
}

fn end_pixel(p: FixedPoint) -> (i64, i64) {
    (p.x.raw().div_euclid(256), p.y.raw().div_euclid(256))
}

/// Distance, along the minor axis, from a pixel centre to the ideal line.
fn minor_distance(line: &LineSetup, (x, y): (i64, i64)) -> f64 {
    let (ax, ay) = line.from.to_f64();
    let (bx, by) = line.to.to_f64();
    let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
    if (bx - ax).abs() >= (by - ay).abs() {
        if bx == ax {
            return (cy - ay).abs();
        }
        (ay + (by - ay) * (cx - ax) / (bx - ax) - cy).abs()
    } else {
        (ax + (bx - ax) * (cy - ay) / (by - ay) - cx).abs()
    }
}

proptest! {
    #![proptest_config(crate::common::proptest_config(4000, "tests/proptest-regressions/lines.txt"))]

    #[test]
    fn aliased_lines_have_the_properties_their_options_promise(a in endpoint(), b in endpoint(), opt in options()) {
        options_are_kept(a, b, opt)?;
    }

    #[test]
    fn an_aliased_line_draws_the_pixels_it_lists(a in endpoint(), b in endpoint(), opt in options()) {
        drawn_as_listed(a, b, opt)?;
    }

    /// Octant symmetry of the textbook (direction-dependent) algorithms. The
    /// symmetric variant starts from the smaller major coordinate, which a
    /// mirror changes, so at ties it is direction-free but not mirror-free.
    #[test]
    fn reflecting_the_input_reflects_the_output(a in endpoint(), b in endpoint(), opt in options()) {
        reflections_are_kept(a, b, opt)?;
    }

    #[test]
    fn the_symmetric_variant_does_not_depend_on_direction(a in endpoint(), b in endpoint(), four in any::<bool>()) {
        let opt = LineOptions {
            symmetric: true,
            connectivity: if four { Connectivity::Four } else { Connectivity::Eight },
            ..LineOptions::DEFAULT
        };
        for (name, pixels_of) in aliased() {
            let forward: BTreeSet<_> = pixels_of(&seg(a, b), &opt).into_iter().collect();
            let backward: BTreeSet<_> = pixels_of(&seg(b, a), &opt).into_iter().collect();
            prop_assert_eq!(forward, backward, "{}", name);
        }
        let wu = |l: &LineSetup| {
            let mut v: Vec<_> = Wu::pixels(l, &opt_eight_symmetric()).into_iter().map(|(p, c)| (p, (c * 1e6) as i64)).collect();
            v.sort();
            v
        };
        prop_assert_eq!(wu(&seg(a, b)), wu(&seg(b, a)));
    }

    #[test]
    fn bresenham_equals_direct(a in endpoint(), b in endpoint(), opt in options()) {
        bresenham_is_direct(a, b, opt)?;
    }

    #[test]
    fn half_open_polylines_draw_shared_vertices_once_without_gaps(
        points in proptest::collection::vec(centre_endpoint(), 3..8),
        symmetric in any::<bool>(),
    ) {
        half_open_polyline_holds(points, symmetric)?;
    }

    #[test]
    fn diamond_matches_brute_force_over_every_pixel(a in endpoint(), b in endpoint()) {
        let (fast, _) = Diamond::pixels(&seg(a, b));
        let fast: BTreeSet<_> = fast.into_iter().collect();
        let brute: BTreeSet<_> = (-22..62)
            .flat_map(|y| (-22..62).map(move |x| (x, y)))
            .filter(|&(x, y)| exits_diamond(a, b, x, y))
            .collect();
        prop_assert_eq!(fast, brute);
    }

    /// With the seed's integer (pixel-centre) endpoints. Off-centre
    /// endpoints can cost two fragments: the seed algorithms always draw the
    /// endpoints' columns, the diamond rule only diamonds the segment passes.
    #[test]
    fn aliased_backends_are_within_vulkans_tolerance_of_diamond(a in centre_endpoint(), b in centre_endpoint(), symmetric in any::<bool>()) {
        within_vulkans_tolerance(a, b, symmetric)?;
    }

    #[test]
    fn wu_coverage_sums_to_one_per_column(a in endpoint(), b in endpoint()) {
        let px = Wu::pixels(&seg(a, b), &LineOptions::DEFAULT);
        let frame = OctantFrame::new(a, b);
        let mut sums = std::collections::BTreeMap::new();
        for ((x, y), c) in px {
            prop_assert!(c > 0.0 && c <= 1.0);
            *sums.entry(if frame.swap { y } else { x }).or_insert(0.0f64) += f64::from(c);
        }
        prop_assert_eq!(sums.len() as i64, frame.i1 - frame.i0 + 1);
        for s in sums.values() {
            prop_assert!((s - 1.0).abs() < 1e-6);
        }
    }
}

fn opt_eight_symmetric() -> LineOptions {
    LineOptions {
        symmetric: true,
        ..LineOptions::DEFAULT
    }
}

/// splitmix64, so the measured figure below does not depend on any crate's RNG.
fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[test]
fn plain_bresenham_draws_a_to_b_and_b_to_a_differently_this_often() {
    // 10,000 random lines between pixel centres of a 64 x 64 grid.
    let mut state = 2026;
    let mut differ = 0;
    for _ in 0..10_000 {
        let mut c = || (splitmix(&mut state) % 64) as f32 + 0.5;
        let (a, b) = (snap(c(), c()), snap(c(), c()));
        let forward: BTreeSet<_> = Bresenham::pixels(&seg(a, b), &LineOptions::DEFAULT)
            .into_iter()
            .collect();
        let backward: BTreeSet<_> = Bresenham::pixels(&seg(b, a), &LineOptions::DEFAULT)
            .into_iter()
            .collect();
        if forward != backward {
            differ += 1;
        }
    }
    eprintln!("plain bresenham: a->b != b->a for {differ} of 10000 lines");
    assert_eq!(differ, MEASURED_ASYMMETRIC_LINES);
}

/// Measured by the test above (a third of all lines); the symmetric
/// variant makes it 0 (`the_symmetric_variant_does_not_depend_on_direction`).
const MEASURED_ASYMMETRIC_LINES: usize = 3382;

#[test]
fn line_drawing_crate_bresenham_is_our_midpoint_rule_moved_half_a_pixel() {
    // The crate steps when its error `dy - dx + k dy - n dx` reaches 0: row
    // floor(m k), not the nearest row. That is our midpoint rule applied to
    // the same line moved 127/256 px towards the start's side of its minor
    // axis, exactly, for lines up to 256 pixels long.
    let mut state = 7;
    for _ in 0..10_000 {
        let mut c = || (splitmix(&mut state) % 256) as i32 - 128;
        let (x0, y0, x1, y1) = (c(), c(), c(), c());
        let theirs: Pixels = line_drawing::Bresenham::new((x0, y0), (x1, y1))
            .map(|(x, y)| (x as i64, y as i64))
            .collect();
        let a = snap(x0 as f32 + 0.5, y0 as f32 + 0.5);
        let b = snap(x1 as f32 + 0.5, y1 as f32 + 0.5);
        let frame = OctantFrame::new(a, b);
        let shift = if frame.flip_minor { 127 } else { -127 };
        let moved = |p: FixedPoint| {
            if frame.swap {
                FixedPoint::from_raw(p.x.raw() + shift, p.y.raw()).unwrap()
            } else {
                FixedPoint::from_raw(p.x.raw(), p.y.raw() + shift).unwrap()
            }
        };
        let ours = Bresenham::pixels(&seg(moved(a), moved(b)), &LineOptions::DEFAULT);
        assert_eq!(ours, theirs, "({x0}, {y0}) -> ({x1}, {y1})");
    }
}

fn ascii(pixels: &[(i64, i64)], w: i64, h: i64) -> Vec<String> {
    ascii_rows(0..w, 0..h, |x, y| ascii_mark(pixels.contains(&(x, y))))
}

#[test]
fn one_small_case_per_octant_as_ascii_art() {
    let c = |x: f32, y: f32| snap(x + 0.5, y + 0.5);
    let cases: [OctantCase; 8] = [
        (
            (0., 0.),
            (6., 2.),
            (7, 3),
            &["##.....", "..###..", ".....##"],
        ),
        (
            (0., 0.),
            (2., 6.),
            (3, 7),
            &["#..", "#..", ".#.", ".#.", ".#.", "..#", "..#"],
        ),
        (
            (2., 0.),
            (0., 6.),
            (3, 7),
            &["..#", "..#", ".#.", ".#.", ".#.", "#..", "#.."],
        ),
        (
            (6., 0.),
            (0., 2.),
            (7, 3),
            &[".....##", "..###..", "##....."],
        ),
        (
            (6., 2.),
            (0., 0.),
            (7, 3),
            &["##.....", "..###..", ".....##"],
        ),
        (
            (2., 6.),
            (0., 0.),
            (3, 7),
            &["#..", "#..", ".#.", ".#.", ".#.", "..#", "..#"],
        ),
        (
            (0., 6.),
            (2., 0.),
            (3, 7),
            &["..#", "..#", ".#.", ".#.", ".#.", "#..", "#.."],
        ),
        (
            (0., 2.),
            (6., 0.),
            (7, 3),
            &[".....##", "..###..", "##....."],
        ),
    ];
    for (a, b, (w, h), expected) in cases {
        for (name, pixels_of) in aliased() {
            let px = pixels_of(&seg(c(a.0, a.1), c(b.0, b.1)), &LineOptions::DEFAULT);
            assert_eq!(ascii(&px, w, h), expected, "{name} {a:?} -> {b:?}");
        }
    }
}

#[test]
fn a_tie_shows_the_asymmetry_and_the_symmetric_variant_removes_it() {
    let c = |x: f32, y: f32| snap(x + 0.5, y + 0.5);
    // At x = 1 the line from (0,0) to (2,1) passes exactly between rows 0 and 1.
    let plain = LineOptions::DEFAULT;
    let sym = opt_eight_symmetric();
    let draw = |a, b, o: &LineOptions| ascii(&Bresenham::pixels(&seg(a, b), o), 3, 2);
    assert_eq!(draw(c(0., 0.), c(2., 1.), &plain), ["##.", "..#"]);
    assert_eq!(draw(c(2., 1.), c(0., 0.), &plain), ["#..", ".##"]);
    assert_eq!(draw(c(0., 0.), c(2., 1.), &sym), ["##.", "..#"]);
    assert_eq!(draw(c(2., 1.), c(0., 0.), &sym), ["##.", "..#"]);
    // Four-connected: a corner at every diagonal step.
    let four = LineOptions {
        connectivity: Connectivity::Four,
        ..plain
    };
    assert_eq!(
        ascii(&Bresenham::pixels(&seg(c(0., 0.), c(6., 2.)), &four), 7, 3),
        ["###....", "..####.", ".....##"]
    );
}

#[test]
fn line_backends_clip_to_the_viewport_and_reject_options_they_cannot_honour() {
    let line = seg(snap(-50.0, 2.5), snap(50.0, 2.5));
    let vp = PixelRect::of_target(10, 5);
    for &b in rasterlab::raster::line_backends() {
        let mut list = FragmentList::default();
        b.rasterize(&[line], &LineOptions::DEFAULT, vp, &mut list);
        assert_eq!(list.lines.len(), 10, "{}", b.name());
        assert!(list.lines.iter().all(|f| f.x < 10 && f.y == 2));
    }
    let four = LineOptions {
        connectivity: Connectivity::Four,
        ..LineOptions::DEFAULT
    };
    assert!(Wu.check_options(&four).is_err());
    assert!(Diamond.check_options(&four).is_err());
    assert!(Bresenham.check_options(&four).is_ok());
}

#[test]
fn lines_are_depth_tested_against_triangles_in_the_shared_stage() {
    use glam::Vec4;
    use rasterlab::geometry::Scene2D;
    use rasterlab::raster::{
        triangle_backends, DepthState, FillRule, FragmentStage, Gouraud, RenderTarget, ShadedLine,
        ShadedVertex,
    };

    // A square at depth 0.5, and a horizontal line across it whose depth
    // goes from 0.2 (left, in front) to 0.8 (right, behind).
    let square = Scene2D {
        width: 20,
        height: 5,
        triangles: vec![
            [snap(0., 0.), snap(20., 0.), snap(20., 5.)],
            [snap(0., 0.), snap(20., 5.), snap(0., 5.)],
        ],
        vertices: vec![[ShadedVertex::flat(0.5, Vec4::new(0., 0., 1., 1.)); 3]; 2],
    };
    let red = Vec4::new(1., 0., 0., 1.);
    let line = ShadedLine {
        from: snap(0.5, 2.5),
        to: snap(19.5, 2.5),
        vertices: [ShadedVertex::flat(0.2, red), ShadedVertex::flat(0.8, red)],
    };
    for tri_backend in triangle_backends() {
        let mut target = RenderTarget::new(20, 5).unwrap();
        square.draw(
            *tri_backend,
            FillRule::TopLeft,
            DepthState::DEFAULT,
            &Gouraud,
            &mut target,
        );
        let lines = [line];
        let mut stage = FragmentStage::new(&mut target, &Gouraud).with_lines(&lines);
        let setup = LineSetup {
            id: 0,
            from: line.from,
            to: line.to,
        };
        Bresenham.rasterize(
            &[setup],
            &LineOptions::DEFAULT,
            PixelRect::of_target(20, 5),
            &mut stage,
        );
        let row: Vec<bool> = (0..20)
            .map(|x| target.color[target.index(x, 2)] == [255, 0, 0, 255])
            .collect();
        // Depth 0.2 + 0.6 * t is below 0.5 for t < 0.5: pixels 0..=9 (centres 0.5 ..= 9.5).
        let visible: Vec<bool> = (0..20).map(|x| x <= 9).collect();
        assert_eq!(row, visible, "{}", tri_backend.name());
        assert!((0..20).all(|x| target.coverage[target.index(x, 2)] == 2));
    }
}

#[test]
fn the_cli_prints_line_fragments_and_wu_weights() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("lines.txt");
    std::fs::write(&file, "# the line-drawing slides\n0.5 0.5 7.5 3.5\n").unwrap();
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_rasterlab"))
            .args(args)
            .arg(&file)
            .output()
            .unwrap()
    };
    let out = run(&["fragments", "--backend", "bresenham", "--size", "8x4"]);
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        "0 0 0\n1 0 0\n2 1 0\n3 1 0\n4 2 0\n5 2 0\n6 3 0\n7 3 0\n"
    );
    let out = run(&[
        "fragments",
        "--backend",
        "bresenham",
        "--size",
        "8x4",
        "--endpoints",
        "half-open",
        "--connectivity",
        "4",
    ]);
    assert_eq!(String::from_utf8(out.stdout).unwrap().lines().count(), 10);
    let out = run(&["fragments", "--backend", "wu", "--size", "8x4"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.lines().all(|l| l.split(' ').count() == 4), "{text}");
    assert!(text.starts_with("0 0 0 1.0000\n1 0 0 0.5714\n"), "{text}");
    let out = run(&[
        "fragments",
        "--backend",
        "diamond",
        "--size",
        "8x4",
        "--connectivity",
        "4",
    ]);
    assert!(!out.status.success());
    let out = run(&["fragments", "--backend", "naive", "--size", "8x4"]);
    assert!(String::from_utf8(out.stderr)
        .unwrap()
        .contains("draws triangles, but the file holds line segments"));
}

proptest! {
    #![proptest_config(crate::common::proptest_config(3000, "tests/proptest-regressions/lines.txt"))]

    /// The fast path writes exactly the pixels the `bresenham` back-end
    /// sends through the stage (colour and coverage), lines partly or wholly
    /// off the target included; into a target without coverage count, the
    /// same colours.
    #[test]
    fn fast_path_equals_bresenham_through_the_stage(
        lines in proptest::collection::vec((endpoint(), endpoint()), 1..14),
        (w, h) in (1u32..48, 1u32..48),
    ) {
        fast_path_matches(lines, (w, h))?;
    }
}

/// Long lines far outside the target are clipped, not walked.
#[test]
fn fast_path_clips_lines_crossing_the_guard_band() {
    let a = snap(-16000.25, -9000.5);
    let b = snap(16000.75, 9010.5);
    let work = LineWorkload::new("guard band", vec![seg(a, b)]);
    let mut expected = RenderTarget::new(64, 48).unwrap();
    work.run(&Bresenham, &mut expected);
    let mut fast = RenderTarget::new(64, 48).unwrap();
    let written = work.run_fast(&mut fast);
    assert_eq!(written, 64);
    assert!(fast == expected);
}

/// Segments from corner to corner of the guard band: every line back-end
/// draws them without overflowing (the test build checks overflow), and
/// `diamond` draws in the target exactly the pixels whose diamond the
/// segment leaves, tested one by one.
#[test]
fn segments_across_the_whole_guard_band_are_drawn_exactly() {
    let edge = 32767.996;
    let segments = [
        (snap(-edge, -edge), snap(edge, edge)),
        (snap(edge, -edge), snap(-edge, edge)),
        (snap(-edge, 10.3), snap(edge, 20.6)),
        (snap(30.2, edge), snap(10.7, -edge)),
    ];
    let viewport = PixelRect::of_target(64, 48);
    let mut total = 0;
    for (a, b) in segments {
        for &backend in rasterlab::raster::line_backends() {
            let mut list = FragmentList::default();
            backend.rasterize(&[seg(a, b)], &LineOptions::DEFAULT, viewport, &mut list);
            assert!(list.lines.iter().all(|f| f.x < 64 && f.y < 48));
        }
        let mut list = FragmentList::default();
        Diamond.rasterize(&[seg(a, b)], &LineOptions::DEFAULT, viewport, &mut list);
        let drawn: BTreeSet<_> = list
            .lines
            .iter()
            .map(|f| (i64::from(f.x), i64::from(f.y)))
            .collect();
        let brute: BTreeSet<_> = (0..64)
            .flat_map(|x| (0..48).map(move |y| (x, y)))
            .filter(|&(x, y)| exits_diamond(a, b, x, y))
            .collect();
        assert_eq!(drawn, brute, "{a:?} -> {b:?}");
        total += brute.len();
    }
    // Three of the four cross the target from side to side.
    assert!(total >= 3 * 48, "{total} pixels");
}

// The properties as functions of their input: the property tests above
// call them on generated input, the named regression tests below on the
// cases they once shrank to.

/// Endpoints, connectivity, pixel count and distance to the ideal line as
/// The midpoint walk and the exact direct evaluation draw the same pixels.
fn bresenham_is_direct(
    a: FixedPoint,
    b: FixedPoint,
    opt: LineOptions,
) -> Result<(), TestCaseError> {
    prop_assert_eq!(
        Bresenham::pixels(&seg(a, b), &opt),
        Direct::pixels(&seg(a, b), &opt)
    );
    Ok(())
}

/// Drawing a segment hands the sink its pixels, in order, those outside
/// the viewport left out, and counts them: for an 8-connected line the
/// draw goes from the walk to the sink without the pixel list, so this
/// compares the two ways.
fn drawn_as_listed(a: FixedPoint, b: FixedPoint, opt: LineOptions) -> Result<(), TestCaseError> {
    // A viewport that cuts most segments of the strategies.
    let viewport = PixelRect {
        x0: 2,
        y0: 3,
        x1: 30,
        y1: 25,
    };
    let line = LineSetup { id: 7, ..seg(a, b) };
    let backends: [(&dyn LineRasterizer, PixelsOf); 3] = [
        (&Direct, Direct::pixels),
        (&Dda, Dda::pixels),
        (&Bresenham, Bresenham::pixels),
    ];
    for (backend, pixels_of) in backends {
        let listed = pixels_of(&line, &opt);
        let mut drawn = FragmentList::default();
        let work = backend.rasterize(&[line], &opt, viewport, &mut drawn);
        let expected: Vec<_> = listed
            .iter()
            .copied()
            .filter(|&(x, y)| viewport.contains(x, y))
            .collect();
        let got: Vec<_> = drawn
            .lines
            .iter()
            .map(|f| (i64::from(f.x), i64::from(f.y)))
            .collect();
        prop_assert_eq!(&got, &expected, "{} draws other pixels", backend.name());
        prop_assert!(drawn.lines.iter().all(|f| f.line == 7 && f.coverage == 1.0));
        prop_assert_eq!(work.samples_tested, listed.len() as u64);
        prop_assert_eq!(work.fragments, expected.len() as u64);
    }
    Ok(())
}

/// Every property of one segment drawn with `opt`: options kept,
/// reflections, Bresenham equal to direct, and each drawn as listed.
fn segment_properties_hold(
    a: FixedPoint,
    b: FixedPoint,
    opt: LineOptions,
) -> Result<(), TestCaseError> {
    options_are_kept(a, b, opt)?;
    reflections_are_kept(a, b, opt)?;
    bresenham_is_direct(a, b, opt)?;
    drawn_as_listed(a, b, opt)
}

/// `opt` promises, for the three aliased algorithms.
fn options_are_kept(a: FixedPoint, b: FixedPoint, opt: LineOptions) -> Result<(), TestCaseError> {
    let line = seg(a, b);
    let frame = OctantFrame::new(a, b);
    let steps = (frame.i1 - frame.i0) as usize;
    for (name, pixels_of) in aliased() {
        let px = pixels_of(&line, &opt);
        // Endpoints present or absent as the convention says.
        // (The endpoint columns are the endpoints' pixels; the row is the
        // one nearest the line at the column centre, which is the
        // endpoint's own pixel when the endpoint is a pixel centre.)
        let full = pixels_of(
            &line,
            &LineOptions {
                endpoints: Endpoints::Inclusive,
                ..opt
            },
        );
        let major = |p: (i64, i64)| if frame.swap { p.1 } else { p.0 };
        prop_assert_eq!(
            full.first().map(|&p| major(p)),
            Some(major(end_pixel(a))),
            "{} start",
            name
        );
        prop_assert_eq!(
            full.last().map(|&p| major(p)),
            Some(major(end_pixel(b))),
            "{} end",
            name
        );
        let centred = |p: FixedPoint| p.x.raw() % 256 == 128 && p.y.raw() % 256 == 128;
        if centred(a) && centred(b) {
            prop_assert_eq!(
                full.first().copied(),
                Some(end_pixel(a)),
                "{} start pixel",
                name
            );
            prop_assert_eq!(
                full.last().copied(),
                Some(end_pixel(b)),
                "{} end pixel",
                name
            );
        }
        if opt.endpoints == Endpoints::HalfOpen {
            prop_assert_eq!(
                &px[..],
                &full[..full.len() - 1],
                "{} half-open drops the end",
                name
            );
        }
        // Runs: 8-connected steps, or 4-connected steps.
        for w in full.windows(2) {
            let (dx, dy) = ((w[1].0 - w[0].0).abs(), (w[1].1 - w[0].1).abs());
            match opt.connectivity {
                Connectivity::Eight => {
                    prop_assert!(dx.max(dy) == 1, "{} not 8-connected: {:?}", name, w)
                }
                Connectivity::Four => {
                    prop_assert!(dx + dy == 1, "{} not 4-connected: {:?}", name, w)
                }
            }
        }
        // Pixel count: one per major step (plus a corner per minor step).
        let minor_steps = full
            .windows(2)
            .filter(|w| {
                if frame.swap {
                    w[0].0 != w[1].0
                } else {
                    w[0].1 != w[1].1
                }
            })
            .count();
        let expected = match opt.connectivity {
            Connectivity::Eight => steps + 1,
            Connectivity::Four => steps + 1 + minor_steps,
        };
        prop_assert_eq!(full.len(), expected, "{} pixel count", name);
        // Every column's pixel is the nearest to the ideal line (half a pixel),
        // give or take float error for dda.
        if opt.connectivity == Connectivity::Eight && a != b {
            for &p in &full {
                prop_assert!(
                    minor_distance(&line, p) <= 0.5 + 1e-9,
                    "{} {:?} too far",
                    name,
                    p
                );
            }
        }
    }
    Ok(())
}

/// Mirroring and transposing the input mirrors and transposes the output
/// of the textbook (direction-dependent) algorithms.
fn reflections_are_kept(
    a: FixedPoint,
    b: FixedPoint,
    opt: LineOptions,
) -> Result<(), TestCaseError> {
    let opt = LineOptions {
        symmetric: false,
        ..opt
    };
    // Mirror about x = 20 (pixel i -> 39 - i) and about y = 20.
    let mx = |p: FixedPoint| FixedPoint::from_raw(40 * 256 - p.x.raw(), p.y.raw()).unwrap();
    let my = |p: FixedPoint| FixedPoint::from_raw(p.x.raw(), 40 * 256 - p.y.raw()).unwrap();
    for (name, pixels_of) in [
        ("direct", Direct::pixels as PixelsOf),
        ("bresenham", Bresenham::pixels),
    ] {
        let base = pixels_of(&seg(a, b), &opt);
        let x_mirrored: Pixels = base.iter().map(|&(x, y)| (39 - x, y)).collect();
        let y_mirrored: Pixels = base.iter().map(|&(x, y)| (x, 39 - y)).collect();
        prop_assert_eq!(
            pixels_of(&seg(mx(a), mx(b)), &opt),
            x_mirrored,
            "{} x mirror",
            name
        );
        prop_assert_eq!(
            pixels_of(&seg(my(a), my(b)), &opt),
            y_mirrored,
            "{} y mirror",
            name
        );
        // Transposing x and y (not for exact diagonals, which are x-major both ways).
        let (dx, dy) = (b.x.raw() - a.x.raw(), b.y.raw() - a.y.raw());
        if dx.abs() != dy.abs() {
            let t = |p: FixedPoint| FixedPoint { x: p.y, y: p.x };
            let transposed: Pixels = base.iter().map(|&(x, y)| (y, x)).collect();
            prop_assert_eq!(
                pixels_of(&seg(t(a), t(b)), &opt),
                transposed,
                "{} transpose",
                name
            );
        }
    }
    Ok(())
}

/// A half-open polyline draws each shared vertex once (by the segment
/// leaving it) and leaves no gap.
fn half_open_polyline_holds(points: Vec<FixedPoint>, symmetric: bool) -> Result<(), TestCaseError> {
    // A repeated point is a zero-length segment, which half-open draws as nothing.
    let mut points = points;
    points.dedup();
    prop_assume!(points.len() >= 3);
    let opt = LineOptions {
        endpoints: Endpoints::HalfOpen,
        symmetric,
        ..LineOptions::DEFAULT
    };
    for (name, pixels_of) in aliased() {
        let segments: Vec<Pixels> = points
            .windows(2)
            .map(|w| pixels_of(&seg(w[0], w[1]), &opt))
            .collect();
        for (k, w) in points.windows(2).enumerate() {
            let shared = end_pixel(w[1]);
            // The shared vertex is drawn by the next segment, not by this one.
            prop_assert!(
                w[0] == w[1] || !segments[k].contains(&shared),
                "{} draws its end vertex",
                name
            );
            if k + 1 < segments.len() {
                prop_assert_eq!(
                    segments[k + 1].first().copied(),
                    Some(shared),
                    "{} next segment starts at the vertex",
                    name
                );
            }
        }
        // No gaps: the concatenation is 8-connected.
        let all: Pixels = segments.concat();
        for w in all.windows(2) {
            prop_assert!(
                (w[1].0 - w[0].0).abs() <= 1 && (w[1].1 - w[0].1).abs() <= 1,
                "{} gap at {:?}",
                name,
                w
            );
        }
    }
    Ok(())
}

/// The aliased algorithms draw within one pixel of the diamond rule's
/// fragments, one per major step, with at most one fragment more or less.
fn within_vulkans_tolerance(
    a: FixedPoint,
    b: FixedPoint,
    symmetric: bool,
) -> Result<(), TestCaseError> {
    let (reference, _) = Diamond::pixels(&seg(a, b));
    let x_major = (b.x.raw() - a.x.raw()).abs() >= (b.y.raw() - a.y.raw()).abs();
    let major = |p: &(i64, i64)| if x_major { p.0 } else { p.1 };
    let per_major = |px: &Pixels| {
        let mut seen = BTreeSet::new();
        px.iter().all(|p| seen.insert(major(p)))
    };
    prop_assert!(
        per_major(&reference),
        "diamond draws two pixels in one column/row"
    );
    let opt = LineOptions {
        endpoints: Endpoints::HalfOpen,
        symmetric,
        ..LineOptions::DEFAULT
    };
    for (name, pixels_of) in aliased() {
        let px = pixels_of(&seg(a, b), &opt);
        prop_assert!(
            (px.len() as i64 - reference.len() as i64).abs() <= 1,
            "{}: {} vs {} fragments",
            name,
            px.len(),
            reference.len()
        );
        prop_assert!(
            per_major(&px),
            "{} draws two pixels in one column/row",
            name
        );
        for p in &px {
            prop_assert!(
                reference
                    .iter()
                    .any(|r| (r.0 - p.0).abs() <= 1 && (r.1 - p.1).abs() <= 1)
                    || reference.is_empty(),
                "{}: {:?} is not within one pixel of a diamond fragment",
                name,
                p
            );
        }
    }
    Ok(())
}

/// The fast path writes the colours and coverage of `bresenham` through
/// the stage, into counting and non-counting targets alike.
fn fast_path_matches(
    lines: Vec<(FixedPoint, FixedPoint)>,
    (w, h): (u32, u32),
) -> Result<(), TestCaseError> {
    let lines: Vec<LineSetup> = lines
        .into_iter()
        .enumerate()
        .map(|(i, (a, b))| LineSetup {
            id: i as u32,
            ..seg(a, b)
        })
        .collect();
    let work = LineWorkload::new("random", lines);
    let mut expected = RenderTarget::new(w, h).unwrap();
    work.run(&Bresenham, &mut expected);
    let mut fast = RenderTarget::new(w, h).unwrap();
    let written = work.run_fast(&mut fast);
    prop_assert!(fast == expected);
    let counted: u64 = expected.coverage.iter().map(|&c| u64::from(c)).sum();
    prop_assert_eq!(written, counted);
    // Into a target that does not count: the same colours.
    let mut uncounted = RenderTarget::without_coverage(w, h).unwrap();
    prop_assert_eq!(work.run_fast(&mut uncounted), written);
    prop_assert!(uncounted.color == expected.color);
    Ok(())
}

/// Shrunk from `aliased_lines_have_the_properties_their_options_promise`:
/// a steep line between off-centre endpoints, (1.07, 1.75) to
/// (35.02, 58.07), 8-connected, both endpoints drawn.
#[test]
fn regression_a_steep_off_centre_line_keeps_its_promises() {
    let (a, b) = (raw(274, 449), raw(8966, 14866));
    let opt = LineOptions::DEFAULT;
    assert_eq!(
        (opt.connectivity, opt.endpoints, opt.symmetric),
        (Connectivity::Eight, Endpoints::Inclusive, false)
    );
    segment_properties_hold(a, b, opt).unwrap();
}

/// Shrunk from `aliased_lines_have_the_properties_their_options_promise`:
/// a shallow line drawn right to left, (29.5, -12.5) to (8.5, -7.5),
/// 4-connected and symmetric (so drawn from its left end).
#[test]
fn regression_a_leftward_four_connected_symmetric_line_keeps_its_promises() {
    let (a, b) = (raw(7552, -3200), raw(2176, -1920));
    let opt = LineOptions {
        connectivity: Connectivity::Four,
        endpoints: Endpoints::Inclusive,
        symmetric: true,
    };
    segment_properties_hold(a, b, opt).unwrap();
}

/// Shrunk from `aliased_backends_are_within_vulkans_tolerance_of_diamond`:
/// a line from a pixel centre left of and above the origin, (-13.5, -13.5)
/// to (26.5, 20.5).
#[test]
fn regression_a_line_from_negative_coordinates_is_within_vulkans_tolerance() {
    within_vulkans_tolerance(raw(-3456, -3456), raw(6784, 5248), false).unwrap();
}

/// Shrunk from `half_open_polylines_draw_shared_vertices_once_without_gaps`:
/// a polyline whose last point repeats, p = (0.5, 0.5), q = (-19.5, 20.5),
/// q. The repeated point is a zero-length segment, which a half-open
/// segment draws as nothing, and p to q leaves q to the segment after
/// it; (p, q, q, p), which the property reads as (p, q, p), holds.
#[test]
fn regression_a_repeated_point_is_a_zero_length_segment_drawing_nothing() {
    let (p, q) = (raw(128, 128), raw(-4992, 5248));
    let half_open = LineOptions {
        endpoints: Endpoints::HalfOpen,
        ..LineOptions::DEFAULT
    };
    for (name, pixels_of) in aliased() {
        assert_eq!(pixels_of(&seg(q, q), &half_open), vec![], "{name}");
        let first = pixels_of(&seg(p, q), &half_open);
        assert_eq!(first.first(), Some(&(0, 0)), "{name}");
        assert!(!first.contains(&(-20, 20)), "{name} draws its end vertex");
        assert_eq!(first.len(), 20, "{name}");
    }
    half_open_polyline_holds(vec![p, q, q, p], false).unwrap();
}

/// Shrunk from `fast_path_equals_bresenham_through_the_stage`: one line
/// from (30.5, 17.5), right of a 5 x 42 target, to (4.17, 42.99), below
/// it, passing diagonally outside the corner pixel (4, 41): clipped on
/// both sides, it must leave no pixel, as `bresenham` leaves none.
#[test]
fn regression_a_line_crossing_a_narrow_target_takes_the_fast_path_exactly() {
    let (a, b) = (raw(7808, 4480), raw(1067, 11006));
    fast_path_matches(vec![(a, b)], (5, 42)).unwrap();
    let mut target = RenderTarget::new(5, 42).unwrap();
    let written = LineWorkload::new("corner", vec![seg(a, b)]).run_fast(&mut target);
    assert_eq!(written, 0);
}

/// Flat's colour, but not said to be uniform per primitive: the stage
/// shades every fragment of a line with it.
struct FlatEveryFragment;

impl rasterlab::raster::FragmentShader for FlatEveryFragment {
    fn shade(&self, input: &rasterlab::raster::FragmentInput) -> glam::Vec4 {
        input.flat.color
    }
}

/// Lines of random colours drawn over a coloured target, depth test off:
/// with a shader uniform per line the stage shades each line once; the
/// colours it writes (blended by Wu's coverage) are those of shading
/// every fragment, for every line back-end.
fn shaded_once_as_every_fragment(
    segments: &[(FixedPoint, FixedPoint, [f32; 3])],
) -> Result<(), String> {
    use rasterlab::raster::{
        line_backends, DepthState, DepthTest, FragmentStage, ShadedLine, ShadedVertex,
    };
    let setups: Vec<LineSetup> = segments
        .iter()
        .enumerate()
        .map(|(i, &(from, to, _))| LineSetup {
            id: i as u32,
            from,
            to,
        })
        .collect();
    let shaded: Vec<ShadedLine> = segments
        .iter()
        .map(|&(from, to, [r, g, b])| ShadedLine {
            from,
            to,
            vertices: [ShadedVertex::flat(0.5, glam::Vec4::new(r, g, b, 1.0)); 2],
        })
        .collect();
    let off = DepthState {
        test: DepthTest::Always,
        write: false,
    };
    for b in line_backends() {
        let draw = |shader: &dyn rasterlab::raster::FragmentShader| {
            let mut target = RenderTarget::new(24, 24).unwrap();
            target.color.fill([40, 90, 200, 255]);
            let mut stage = FragmentStage::new(&mut target, shader)
                .with_lines(&shaded)
                .with_depth(off);
            b.rasterize(
                &setups,
                &LineOptions::DEFAULT,
                PixelRect::of_target(24, 24),
                &mut stage,
            );
            target
        };
        let once = draw(&rasterlab::raster::Flat);
        let every = draw(&FlatEveryFragment);
        if once != every {
            return Err(format!(
                "{}: shading once per line differs from shading each fragment",
                b.name()
            ));
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(crate::common::proptest_config(300, "tests/proptest-regressions/lines.txt"))]

    #[test]
    fn a_line_shaded_once_writes_what_shading_each_fragment_writes(
        segments in proptest::collection::vec(
            (
                common::point(-3.0, 27.0, None),
                common::point(-3.0, 27.0, None),
                [0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0],
            ),
            1..8,
        ),
    ) {
        shaded_once_as_every_fragment(&segments).map_err(TestCaseError::fail)?;
    }
}

/// Lines of random colours and depths drawn by every line back-end into
/// the stage twice: as the back-end hands them over (a segment's pixels
/// in one call, [`FragmentSink::line_fragments`]) and one fragment per
/// call, in the same order. With the depth test on, and off with
/// Gouraud's colours, the buffers are the same.
///
/// [`FragmentSink::line_fragments`]: rasterlab::raster::FragmentSink::line_fragments
fn segments_at_once_as_one_fragment_at_a_time(
    segments: &[(FixedPoint, FixedPoint, [f32; 3])],
) -> Result<(), String> {
    use rasterlab::raster::{
        line_backends, DepthState, DepthTest, FragmentSink, FragmentStage, Gouraud, ShadedLine,
        ShadedVertex,
    };
    let setups: Vec<LineSetup> = segments
        .iter()
        .enumerate()
        .map(|(i, &(from, to, _))| LineSetup {
            id: i as u32,
            from,
            to,
        })
        .collect();
    let shaded: Vec<ShadedLine> = segments
        .iter()
        .map(|&(from, to, [r, g, b])| ShadedLine {
            from,
            to,
            vertices: [
                ShadedVertex::flat(r, glam::Vec4::new(r, g, b, 1.0)),
                ShadedVertex::flat(b, glam::Vec4::new(b, r, g, 1.0)),
            ],
        })
        .collect();
    let states = [
        DepthState::DEFAULT,
        DepthState {
            test: DepthTest::Always,
            write: false,
        },
    ];
    let rect = PixelRect::of_target(24, 24);
    for b in line_backends() {
        let mut fragments = FragmentList::default();
        b.rasterize(&setups, &LineOptions::DEFAULT, rect, &mut fragments);
        for depth in states {
            let target = || {
                let mut target = RenderTarget::new(24, 24).unwrap();
                target.color.fill([40, 90, 200, 255]);
                target
            };
            let mut at_once = target();
            let mut stage = FragmentStage::new(&mut at_once, &Gouraud)
                .with_lines(&shaded)
                .with_depth(depth);
            b.rasterize(&setups, &LineOptions::DEFAULT, rect, &mut stage);
            let mut each = target();
            let mut stage = FragmentStage::new(&mut each, &Gouraud)
                .with_lines(&shaded)
                .with_depth(depth);
            for f in &fragments.lines {
                stage.line_fragment(f);
            }
            if at_once != each {
                return Err(format!(
                    "{} ({depth:?}): a segment's pixels at once differ from one at a time",
                    b.name()
                ));
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(crate::common::proptest_config(300, "tests/proptest-regressions/lines.txt"))]

    #[test]
    fn a_segment_s_pixels_at_once_write_what_one_at_a_time_writes(
        segments in proptest::collection::vec(
            (
                common::point(-3.0, 27.0, None),
                common::point(-3.0, 27.0, None),
                [0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0],
            ),
            1..8,
        ),
    ) {
        segments_at_once_as_one_fragment_at_a_time(&segments).map_err(TestCaseError::fail)?;
    }
}

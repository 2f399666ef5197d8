//! Line clipping: Cohen-Sutherland and Liang-Barsky keep the same part of
//! every segment, exactly; clipping then walking from the entry column
//! with the original segment's decision variable draws every line
//! back-end's on-screen pixels exactly; rounding the clipped endpoints and
//! walking the short segment afresh moves pixels, counted per back-end.

mod common;

use proptest::prelude::*;
use rasterlab::raster::line::clip::cohen_sutherland::Outcode;
use rasterlab::raster::line::clip::{
    draw_clipped, ClipRestart, ClipWindow, ClipWork, Clipper, ExactPoint, Param,
};
use rasterlab::raster::line::{
    Connectivity, Endpoints, LineOptions, LineRasterizer, LineSetup, LineWalk,
};
use rasterlab::raster::{line_backends, FixedPoint, FragmentList, PixelRect};

/// A fragment as a comparable tuple: pixel, segment and coverage bits.
type Frag = (u32, u32, u32, u32);

fn fragments_of(list: &FragmentList) -> Vec<Frag> {
    list.lines
        .iter()
        .map(|f| (f.x, f.y, f.line, f.coverage.to_bits()))
        .collect()
}

/// The whole segments drawn, their pixels restricted to the viewport.
fn whole(
    backend: &dyn LineRasterizer,
    lines: &[LineSetup],
    options: &LineOptions,
    viewport: PixelRect,
) -> Vec<Frag> {
    let mut list = FragmentList::default();
    backend.rasterize(lines, options, viewport, &mut list);
    fragments_of(&list)
}

/// The segments clipped by `clipper`, then walked as `restart` says.
fn clipped(
    backend: &dyn LineRasterizer,
    clipper: Clipper,
    restart: ClipRestart,
    lines: &[LineSetup],
    options: &LineOptions,
    viewport: PixelRect,
) -> Vec<Frag> {
    let mut list = FragmentList::default();
    draw_clipped(
        backend, clipper, restart, lines, options, viewport, &mut list,
    );
    fragments_of(&list)
}

fn raw(x: i64, y: i64) -> FixedPoint {
    FixedPoint::from_raw(x, y).unwrap()
}

/// The options a back-end can take: `wanted` when it accepts them, the
/// defaults otherwise (the diamond-exit rules take no others).
fn options_for(backend: &dyn LineRasterizer, wanted: LineOptions) -> LineOptions {
    if backend.check_options(&wanted).is_ok() {
        wanted
    } else {
        LineOptions::DEFAULT
    }
}

/// A coordinate along an axis of `size` pixels: well inside, just
/// outside either side, far outside, or on a pixel centre, a pixel edge or
/// a half-edge (ties for every rule), in 1/256 px.
fn coordinate(size: i64) -> impl Strategy<Value = i64> {
    let s = size * 256;
    prop_oneof![
        (0..s),
        (-3 * 256i64..256),
        (s - 256..s + 3 * 256),
        (-40 * 256i64..s + 40 * 256),
        (-6i64..size + 6).prop_map(|p| p * 256 + 128),
        (-6i64..size + 6).prop_map(|p| p * 256),
        (-12i64..2 * size + 12).prop_map(|p| p * 128 + 64),
    ]
}

/// A viewport and a segment about it: crossing sides and corners, wholly
/// inside, wholly outside.
fn case() -> impl Strategy<Value = (PixelRect, LineSetup)> {
    (1i64..24, 1i64..24).prop_flat_map(|(w, h)| {
        (
            Just(PixelRect {
                x0: 0,
                y0: 0,
                x1: w - 1,
                y1: h - 1,
            }),
            (coordinate(w), coordinate(h), coordinate(w), coordinate(h)).prop_map(
                |(ax, ay, bx, by)| LineSetup {
                    id: 7,
                    from: raw(ax, ay),
                    to: raw(bx, by),
                },
            ),
        )
    })
}

fn line_options() -> impl Strategy<Value = LineOptions> {
    (any::<bool>(), any::<bool>(), any::<bool>()).prop_map(|(four, open, symmetric)| LineOptions {
        connectivity: if four {
            Connectivity::Four
        } else {
            Connectivity::Eight
        },
        endpoints: if open {
            Endpoints::HalfOpen
        } else {
            Endpoints::Inclusive
        },
        symmetric,
    })
}

/// Checks the property on one case: every back-end, both clippers.
fn keeps_every_pixel(viewport: PixelRect, line: LineSetup, wanted: LineOptions) {
    for &backend in line_backends() {
        let options = options_for(backend, wanted);
        // wu takes 8-connected lines only.
        let options = if backend.descriptor().walk == LineWalk::AntiAliased {
            LineOptions {
                connectivity: Connectivity::Eight,
                ..options
            }
        } else {
            options
        };
        let expected = whole(backend, &[line], &options, viewport);
        for clipper in Clipper::ALL {
            let got = clipped(
                backend,
                clipper,
                ClipRestart::KeepDecision,
                &[line],
                &options,
                viewport,
            );
            assert_eq!(
                got,
                expected,
                "{} clipped by {clipper} ({options:?}) on {viewport:?}, {line:?}",
                backend.name()
            );
        }
    }
}

proptest! {
    #![proptest_config(common::proptest_config(1000, "tests/proptest-regressions/line_clipping.txt"))]

    /// Clip, then walk from the entry column keeping the original
    /// decision variable: for every line back-end, the whole segment's
    /// pixels in the viewport, with their coverage, in the same order,
    /// under both clippers.
    #[test]
    fn clipped_walk_keeps_every_backends_pixels((viewport, line) in case(), options in line_options()) {
        keeps_every_pixel(viewport, line, options);
    }

    /// Cohen-Sutherland and Liang-Barsky keep the same interval, exactly;
    /// its ends are inside the window, and just beyond them the segment
    /// is outside (or ended).
    #[test]
    fn both_clippers_keep_the_same_part((viewport, line) in case(), margin in any::<bool>()) {
        let window = if margin { ClipWindow::around(viewport) } else { ClipWindow::of_viewport(viewport) };
        let mut work = ClipWork::default();
        let cs = Clipper::CohenSutherland.clip(&line, window, &mut work);
        let lb = Clipper::LiangBarsky.clip(&line, window, &mut work);
        prop_assert_eq!(cs, lb);
        if let Some(kept) = cs {
            prop_assert!(kept.t0 <= kept.t1);
            for t in [kept.t0, kept.t1] {
                prop_assert!(Outcode::of(t.point(line.from, line.to), window).is_inside());
            }
            // A step of 1/2^20 of the segment before t0 and after t1
            // leaves the window unless the segment ends there.
            let step = Param { num: 1, den: 1 << 20 };
            let before = Param { num: kept.t0.num * step.den - kept.t0.den, den: kept.t0.den * step.den };
            let after = Param { num: kept.t1.num * step.den + kept.t1.den, den: kept.t1.den * step.den };
            if kept.t0 > Param::ZERO {
                prop_assert!(!Outcode::of(before.point(line.from, line.to), window).is_inside());
            }
            if kept.t1 < Param::ONE {
                prop_assert!(!Outcode::of(after.point(line.from, line.to), window).is_inside());
            }
        } else {
            // Nothing inside: no point of the segment is, at 65 samples.
            for n in 0..=64 {
                let t = Param { num: n, den: 64 };
                prop_assert!(!Outcode::of(t.point(line.from, line.to), window).is_inside());
            }
        }
    }
}

/// A fixed set of `n` segments about a 32 x 24 viewport, from a seeded
/// generator: endpoints up to 16 px beyond each side, a third of them on
/// pixel centres.
fn seeded_segments(n: usize) -> Vec<LineSetup> {
    let mut state: u64 = 0x6a09_e667_f3bc_c908;
    let mut next = move |range: i64| {
        // xorshift64*
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as i64 % range
    };
    (0..n)
        .map(|i| {
            let mut point = |w: i64, h: i64| {
                let (x, y) = (
                    next((w + 32) * 256) - 16 * 256,
                    next((h + 32) * 256) - 16 * 256,
                );
                if next(3) == 0 {
                    raw(x.div_euclid(256) * 256 + 128, y.div_euclid(256) * 256 + 128)
                } else {
                    raw(x, y)
                }
            };
            LineSetup {
                id: i as u32,
                from: point(32, 24),
                to: point(32, 24),
            }
        })
        .collect()
}

/// How many of `lines` a back-end draws differently when the clipped
/// segment is walked as `restart` says.
fn segments_moved(
    backend: &dyn LineRasterizer,
    clipper: Clipper,
    restart: ClipRestart,
    lines: &[LineSetup],
    viewport: PixelRect,
) -> usize {
    let options = LineOptions::DEFAULT;
    lines
        .iter()
        .filter(|line| {
            let one = std::slice::from_ref(*line);
            whole(backend, one, &options, viewport)
                != clipped(backend, clipper, restart, one, &options, viewport)
        })
        .count()
}

/// The naive ways, counted: on 2,000 seeded segments about a 32 x 24
/// viewport, rounding the clipped endpoints to the 1/256 px grid, or
/// moving them to their pixels' centres, and walking the short segment
/// from scratch changes the pixels of some segments for every back-end
/// (the coverage, for wu), while the restarted walk changes none. The
/// counts are printed (`--nocapture`).
#[test]
fn rounding_the_clipped_endpoints_moves_pixels() {
    let viewport = PixelRect::of_target(32, 24);
    let lines = seeded_segments(2000);
    // Segments the clipper leaves whole cannot move; the others (cut,
    // or rejected while passing near enough to draw an edge pixel) can.
    let whole_inside = lines
        .iter()
        .filter(|l| {
            let mut work = ClipWork::default();
            Clipper::LiangBarsky
                .clip(l, ClipWindow::of_viewport(viewport), &mut work)
                .is_some_and(|c| c.t0 == Param::ZERO && c.t1 == Param::ONE)
        })
        .count();
    let crossing = lines.len() - whole_inside;
    println!(
        "{} segments, {crossing} not wholly inside the viewport; segments drawn differently:",
        lines.len()
    );
    println!(
        "{:<16} {:>14} {:>14} {:>22}",
        "back-end", "keep-decision", "round-endpoints", "round-to-pixel-centres"
    );
    for &backend in line_backends() {
        let mut counts = Vec::new();
        for restart in ClipRestart::ALL {
            let [cs, lb] =
                Clipper::ALL.map(|c| segments_moved(backend, c, restart, &lines, viewport));
            // The two clippers keep the same points, so they round alike.
            assert_eq!(cs, lb, "{} {restart}", backend.name());
            assert!(
                cs <= crossing,
                "{} {restart}: a segment wholly inside moved",
                backend.name()
            );
            counts.push(cs);
        }
        println!(
            "{:<16} {:>14} {:>14} {:>22}",
            backend.name(),
            counts[0],
            counts[1],
            counts[2]
        );
        assert_eq!(
            counts[0],
            0,
            "{}: the restarted walk moved pixels",
            backend.name()
        );
        for (restart, &count) in ClipRestart::ALL.iter().zip(&counts).skip(1) {
            assert!(
                count > 0,
                "{}: {restart} moved no pixel on {} segments",
                backend.name(),
                lines.len()
            );
        }
        for clipper in Clipper::ALL {
            let options = LineOptions::DEFAULT;
            assert_eq!(
                clipped(
                    backend,
                    clipper,
                    ClipRestart::KeepDecision,
                    &lines,
                    &options,
                    viewport
                ),
                whole(backend, &lines, &options, viewport),
                "{} under {clipper}",
                backend.name()
            );
        }
    }
}

/// A rounded endpoint is the nearest grid point, ties up.
#[test]
fn a_clipped_point_rounds_to_the_nearest_grid_point() {
    let p = ExactPoint {
        x: 2561,
        y: -3,
        den: 2,
    };
    assert_eq!(p.rounded(), raw(1281, -1));
    assert_eq!(ExactPoint { x: 7, y: 5, den: 3 }.rounded(), raw(2, 2));
    assert_eq!(p.pixel(), (5, -1));
    assert_eq!(p.pixel_centre(), raw(5 * 256 + 128, -128));
}

/// Regression: a segment ending just above the screen, `(0.2, -1.6) ->
/// (3.2, -0.1)`, lies wholly outside the viewport's own edges, yet its
/// last column's centre (x = 3.5) is where the line, extended, has
/// crossed into row 0: `bresenham` draws pixel (3, 0). Clipping at the
/// viewport's edges rejects the segment and loses the pixel; the window
/// with its one-pixel margin keeps it.
#[test]
fn a_segment_ending_above_the_screen_still_draws_its_edge_pixel() {
    let viewport = PixelRect::of_target(8, 8);
    let line = LineSetup {
        id: 0,
        from: FixedPoint::snap(0.2, -1.6).unwrap(),
        to: FixedPoint::snap(3.2, -0.1).unwrap(),
    };
    let bresenham = rasterlab::raster::line_backend("bresenham").unwrap();
    let options = LineOptions::DEFAULT;
    let expected = whole(bresenham, &[line], &options, viewport);
    assert_eq!(expected, vec![(3, 0, 0, 1.0f32.to_bits())]);
    for clipper in Clipper::ALL {
        let mut work = ClipWork::default();
        assert_eq!(
            clipper.clip(&line, ClipWindow::of_viewport(viewport), &mut work),
            None
        );
        assert!(clipper
            .clip(&line, ClipWindow::around(viewport), &mut work)
            .is_some());
        let keep = ClipRestart::KeepDecision;
        assert_eq!(
            clipped(bresenham, clipper, keep, &[line], &options, viewport),
            expected
        );
        for round in [
            ClipRestart::RoundEndpoints,
            ClipRestart::RoundToPixelCentres,
        ] {
            assert!(clipped(bresenham, clipper, round, &[line], &options, viewport).is_empty());
        }
    }
}

/// `explain --clip`: both clippers' traces print, and bad input is
/// refused with a clear message and exit code 2, never a panic.
#[test]
fn explain_clip_traces_and_refuses_bad_input() {
    let ok = common::rasterlab(&[
        "explain",
        "--clip",
        "liang-barsky",
        "--size",
        "8x8",
        "--screen",
        "-2.3",
        "1.7",
        "12.4",
        "6.1",
    ]);
    assert!(ok.status.success());
    let text = String::from_utf8(ok.stdout).unwrap();
    assert!(text.contains("4  bottom"), "{text}");
    assert!(text.contains("bresenham: 8 fragments on screen"), "{text}");
    for (args, message) in [
        (
            &["--clip", "sutherland", "0", "0", "1", "1"][..],
            "unknown line clipper",
        ),
        (
            &[
                "--clip",
                "liang-barsky",
                "--backend",
                "scanline",
                "0",
                "0",
                "1",
                "1",
            ],
            "line back-end",
        ),
        (
            &[
                "--clip",
                "cohen-sutherland",
                "--screen",
                "nan",
                "0",
                "1",
                "1",
            ],
            "not a finite number",
        ),
        (
            &[
                "--clip",
                "cohen-sutherland",
                "--screen",
                "1e9",
                "0",
                "1",
                "1",
            ],
            "guard band",
        ),
        (
            &["--clip", "cohen-sutherland", "0", "0", "1"],
            "give 4 numbers",
        ),
    ] {
        let out = common::rasterlab(&[&["explain"][..], args].concat());
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(message), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

/// The two clippers' cost on the same 2,000 seeded segments about a 32 x
/// 24 viewport, clipped to the window the restarted walk uses, and the
/// columns the walk then visits against the whole segments' columns. The
/// table is printed (`--nocapture`). Both reject the same segments;
/// Cohen-Sutherland decides some by its first test alone, and computes at
/// most four intersections a segment, Liang-Barsky at most four ratios.
#[test]
fn the_clippers_costs_compared() {
    let viewport = PixelRect::of_target(32, 24);
    let lines = seeded_segments(2000);
    let n = lines.len() as u64;
    let bresenham = rasterlab::raster::line_backend("bresenham").unwrap();
    let whole_columns: u64 = lines
        .iter()
        .map(|l| {
            rasterlab::raster::line::clip::columns_within(
                l,
                PixelRect {
                    x0: -1 << 20,
                    y0: -1 << 20,
                    x1: 1 << 20,
                    y1: 1 << 20,
                },
            )
        })
        .sum();
    // Without a clipper, an 8-connected walk already skips the columns
    // beyond the viewport's sides along the major axis.
    let major_only: u64 = lines
        .iter()
        .map(|l| rasterlab::raster::line::clip::columns_within(l, viewport))
        .sum();
    println!(
        "{n} segments, {whole_columns} columns in all, {major_only} within the viewport's major range"
    );
    println!(
        "{:<17} {:>8} {:>9} {:>13} {:>8} {:>8} {:>8} {:>8}",
        "clipper",
        "outcodes",
        "p/q tests",
        "intersections",
        "trivial+",
        "trivial-",
        "rejected",
        "columns"
    );
    let mut rejected = Vec::new();
    for clipper in Clipper::ALL {
        let mut list = FragmentList::default();
        let draw = draw_clipped(
            bresenham,
            clipper,
            ClipRestart::KeepDecision,
            &lines,
            &LineOptions::DEFAULT,
            viewport,
            &mut list,
        );
        let w = draw.clip;
        println!(
            "{:<17} {:>8} {:>9} {:>13} {:>8} {:>8} {:>8} {:>8}",
            clipper.name(),
            w.outcodes,
            w.boundary_tests,
            w.intersections,
            w.trivially_accepted,
            w.trivially_rejected,
            w.rejected,
            draw.columns
        );
        assert_eq!(w.segments, n);
        assert!(w.intersections <= 4 * n && w.boundary_tests <= 4 * n);
        assert!(w.trivially_rejected <= w.rejected);
        assert!(
            draw.columns < whole_columns,
            "{clipper}: clipping saved no column"
        );
        rejected.push(w.rejected);
        match clipper {
            Clipper::CohenSutherland => {
                assert_eq!(w.outcodes, 2 * n + w.intersections);
                assert!(w.trivially_accepted > 0 && w.trivially_rejected > 0);
            }
            Clipper::LiangBarsky => assert_eq!(w.outcodes, 0),
        }
    }
    assert_eq!(rejected[0], rejected[1]);
}

/// Regression, shrunk by proptest from the window without its margin: a
/// steep segment `(3.75, -5.168) -> (0.523, 2.070)` passing beside a
/// one-pixel screen. Clipped at the screen's own edges, the part kept
/// chooses a smaller rectangle than the whole segment's pixels need, and
/// some back-end loses a fragment; with the one-pixel margin every
/// back-end keeps them all.
#[test]
fn a_steep_segment_beside_a_one_pixel_screen_keeps_its_fragments() {
    use rasterlab::raster::line::clip::walk_rect;
    let viewport = PixelRect::of_target(1, 1);
    let line = LineSetup {
        id: 7,
        from: raw(960, -1323),
        to: raw(134, 530),
    };
    let options = LineOptions::DEFAULT;
    let mut lost_without_margin = 0;
    for &backend in line_backends() {
        let expected = whole(backend, &[line], &options, viewport);
        for clipper in Clipper::ALL {
            let keep = ClipRestart::KeepDecision;
            assert_eq!(
                clipped(backend, clipper, keep, &[line], &options, viewport),
                expected,
                "{} under {clipper}",
                backend.name()
            );
            // The same walk in the rectangle of a clip at the screen's
            // own edges.
            let mut work = ClipWork::default();
            let tight = clipper
                .clip(&line, ClipWindow::of_viewport(viewport), &mut work)
                .map(|kept| walk_rect(&line, &kept, viewport));
            let got = match tight {
                Some(rect) if !rect.is_empty() => whole(backend, &[line], &options, rect),
                _ => Vec::new(),
            };
            lost_without_margin += usize::from(got != expected);
        }
    }
    assert!(
        lost_without_margin > 0,
        "the margin is needed on this segment"
    );
}

//! Every cause of the catalogue has a subject of its own, written here
//! without the library's rasterizers: a per-pixel loop over a bounding box
//! with its own edge functions, tie rule and snapping, and one mistake.
//! `check` must name that mistake, and no cause before it in the
//! catalogue's order.

use rasterlab::check::{
    catalogue, check, Case, CheckOptions, Fragment, LineConvention, Property, Subject,
    SubjectError, Verdict,
};
use rasterlab::raster::FillRule;

/// How a student's triangle rasterizer goes wrong (all `false`/`None`: it
/// is right).
#[derive(Clone, Copy, Default)]
struct Mistakes {
    /// Ties drawn whatever the edge.
    inclusive_ties: bool,
    /// Ties given to bottom and right edges instead of top and left.
    bottom_right_ties: bool,
    /// Culls triangles of negative (`-1`) or positive (`+1`) signed area
    /// as the subject computes it (positive: counter-clockwise on screen).
    cull: Option<i8>,
    /// Skips triangles of area below this.
    min_area: f64,
    /// Rounds vertices to this grid step instead of 1/256.
    grid: Option<f64>,
    /// Snaps to 1/256 with a tie rounded up (`floor(x + 0.5)`).
    ties_up: bool,
    /// Tests the pixel's corner (x, y) instead of its centre.
    corners: bool,
    /// Measures rows up from the bottom of the target.
    y_up: bool,
    /// Stops the box loop one row early.
    box_short_bottom: bool,
    /// Stops the box loop one column early on the right.
    box_short_right: bool,
    /// Starts the box loop one row late.
    box_short_top: bool,
    /// Starts the box loop one column late.
    box_short_left: bool,
    /// Edge functions in `f32` on the vertices as given.
    float32: bool,
    /// Edge values kept in 32 bits (the low 8 bits of the 1/65536 px²
    /// products dropped).
    wrap32: bool,
    /// No clipping to the target.
    no_clip: bool,
    /// The first pixel of each triangle listed twice.
    duplicate_first: bool,
}

/// Rounds half to even, as the rules snap.
fn snap(v: f64) -> i64 {
    (v * 256.0).round_ties_even() as i64
}

fn student(m: Mistakes) -> impl FnMut(&Case) -> Result<Vec<Fragment>, SubjectError> {
    move |case: &Case| {
        let (w, h) = (i64::from(case.width), i64::from(case.height));
        let mut out = Vec::new();
        for (id, t) in case.triangles.iter().enumerate() {
            // The vertices in 1/256 px, after the subject's own rounding.
            let v: Vec<(i64, i64)> = t
                .iter()
                .map(|&(x, y)| {
                    let (x, y) = match m.grid {
                        Some(g) => ((x / g).round() * g, (y / g).round() * g),
                        None => (x, y),
                    };
                    if m.ties_up {
                        let up = |v: f64| (v * 256.0 + 0.5).floor() as i64;
                        return (up(x), up(y));
                    }
                    (snap(x), snap(y))
                })
                .collect();
            let e = |a: (i64, i64), b: (i64, i64), p: (i64, i64)| -> i64 {
                (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0)
            };
            // Positive: counter-clockwise on screen (y down).
            let signed = -e(v[0], v[1], v[2]);
            if signed == 0 {
                continue;
            }
            if m.cull.is_some_and(|c| i64::from(c) == signed.signum()) {
                continue;
            }
            if (signed.abs() as f64) / 2.0 / 65536.0 < m.min_area {
                continue;
            }
            // Oriented so that the interior is positive; `order` maps the
            // oriented vertices back to the given ones.
            let order = if e(v[0], v[1], v[2]) > 0 {
                [0, 1, 2]
            } else {
                [0, 2, 1]
            };
            let (a, b, c) = (v[order[0]], v[order[1]], v[order[2]]);
            let edges = [(a, b, c), (b, c, a), (c, a, b)];
            // The same edges on the vertices as given, in f32.
            let g: Vec<(f32, f32)> = order
                .iter()
                .map(|&k| (t[k].0 as f32, t[k].1 as f32))
                .collect();
            let float_edges = [(g[0], g[1]), (g[1], g[2]), (g[2], g[0])];
            // Top: horizontal with the triangle below; left: the triangle
            // to its right.
            let owns = |(p, q, r): ((i64, i64), (i64, i64), (i64, i64))| {
                if p.1 == q.1 {
                    r.1 > p.1
                } else {
                    ((r.0 - p.0) * (q.1 - p.1) - (r.1 - p.1) * (q.0 - p.0)) * (q.1 - p.1).signum()
                        > 0
                }
            };
            let value = |k: usize, s: (i64, i64)| -> i64 {
                let (p, q, _) = edges[k];
                if m.float32 {
                    let ((px, py), (qx, qy)) = float_edges[k];
                    let (sx, sy) = (s.0 as f32 / 256.0, s.1 as f32 / 256.0);
                    let v = (qx - px) * (sy - py) - (qy - py) * (sx - px);
                    if v > 0.0 {
                        1
                    } else if v < 0.0 {
                        -1
                    } else {
                        0
                    }
                } else if m.wrap32 {
                    let exact = e(p, q, s);
                    let kept = (exact >> 8) as i32;
                    if kept == 0 {
                        exact.signum()
                    } else {
                        i64::from(kept.signum())
                    }
                } else {
                    e(p, q, s)
                }
            };
            let min_y = v.iter().map(|p| p.1).min().unwrap_or(0).div_euclid(256);
            let max_y = v.iter().map(|p| p.1).max().unwrap_or(0).div_euclid(256);
            let min_x = v.iter().map(|p| p.0).min().unwrap_or(0).div_euclid(256);
            let max_x = v.iter().map(|p| p.0).max().unwrap_or(0).div_euclid(256);
            let (mut y_end, mut x_end) = (max_y, max_x);
            let y_start = min_y + i64::from(m.box_short_top);
            let x_start = min_x + i64::from(m.box_short_left);
            if m.box_short_bottom {
                y_end -= 1;
            }
            if m.box_short_right {
                x_end -= 1;
            }
            let (y0, y1, x0, x1) = if m.no_clip {
                (y_start - 1, y_end + 1, x_start - 1, x_end + 1)
            } else {
                (
                    y_start.max(0),
                    y_end.min(h - 1),
                    x_start.max(0),
                    x_end.min(w - 1),
                )
            };
            let mut first = true;
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let half = if m.corners { 0 } else { 128 };
                    let s = (x * 256 + half, y * 256 + half);
                    let inside = (0..3).all(|k| {
                        let v = value(k, s);
                        let tie_owned = owns(edges[k]) != m.bottom_right_ties;
                        v > 0 || (v == 0 && (m.inclusive_ties || tie_owned))
                    });
                    if inside {
                        let row = if m.y_up { h - 1 - y } else { y };
                        let f = Fragment {
                            x,
                            y: row,
                            id: id as u32,
                            mask: 0,
                        };
                        out.push(f);
                        if first && m.duplicate_first {
                            out.push(f);
                        }
                        first = false;
                    }
                }
            }
        }
        Ok(out)
    }
}

/// The causes `check` names for a subject: the finding's cause ids.
fn named(property: Property, subject: &mut dyn Subject) -> Vec<String> {
    let options = CheckOptions {
        cases: 300,
        ..CheckOptions::new(property)
    };
    match check(&options, subject).unwrap() {
        Verdict::Fail { finding, .. } => {
            let cause = finding
                .cause
                .as_ref()
                .unwrap_or_else(|| panic!("no cause named: {:?}", finding.diagnosis));
            assert!(cause.confirmed_on >= 1);
            assert!(cause.confirmed_on <= cause.failing_cases);
            // The shrunk counterexample still shows the cause.
            assert!(
                cause
                    .explains(property, &finding.case, &finding.drawn)
                    .is_some(),
                "the shrunk case lost its cause: {}",
                finding.case.to_text()
            );
            assert!(finding.diagnosis.as_ref().unwrap().starts_with("cause: "));
            eprintln!(
                "{}\n{}",
                finding.diagnosis.as_ref().unwrap(),
                finding.case.to_text()
            );
            cause.causes.clone()
        }
        Verdict::Pass { .. } => panic!("the mistake went unseen"),
    }
}

const TOP_LEFT: Property = Property::Exact(FillRule::TopLeft);

fn triangles_get(m: Mistakes, expected: &[&str]) {
    let got = named(TOP_LEFT, &mut student(m));
    assert_eq!(got, expected, "named {got:?}");
}

#[test]
fn the_students_loop_without_a_mistake_passes() {
    let options = CheckOptions {
        cases: 300,
        ..CheckOptions::new(TOP_LEFT)
    };
    let verdict = check(&options, &mut student(Mistakes::default())).unwrap();
    assert!(matches!(verdict, Verdict::Pass { cases: 300 }), "{verdict}");
}

#[test]
fn ties_drawn_on_every_edge_are_the_inclusive_rule() {
    triangles_get(
        Mistakes {
            inclusive_ties: true,
            ..Mistakes::default()
        },
        &["fill-rule:inclusive"],
    );
}

#[test]
fn ties_given_to_bottom_and_right_edges_are_the_bottom_right_rule() {
    triangles_get(
        Mistakes {
            bottom_right_ties: true,
            ..Mistakes::default()
        },
        &["fill-rule:bottom-right"],
    );
}

#[test]
fn one_winding_culled_is_named_with_its_winding() {
    triangles_get(
        Mistakes {
            cull: Some(-1),
            ..Mistakes::default()
        },
        &["culls:clockwise"],
    );
    triangles_get(
        Mistakes {
            cull: Some(1),
            ..Mistakes::default()
        },
        &["culls:counter-clockwise"],
    );
}

#[test]
fn small_triangles_skipped_are_named_with_the_area() {
    triangles_get(
        Mistakes {
            min_area: 1.0,
            ..Mistakes::default()
        },
        &["drops-below:1"],
    );
}

#[test]
fn the_tutorial_renderer_culls_by_signed_area_below_one() {
    // The tutorial's `if (total_area < 1) return;`: one winding culled and
    // the other below 1 px² dropped, two causes together. Its shoelace
    // area is positive for a triangle clockwise on the screen (y down),
    // so given screen coordinates it culls the counter-clockwise ones.
    triangles_get(
        Mistakes {
            cull: Some(1),
            min_area: 1.0,
            ..Mistakes::default()
        },
        &["culls:counter-clockwise", "drops-below:1"],
    );
}

#[test]
fn vertices_rounded_to_whole_pixels() {
    triangles_get(
        Mistakes {
            grid: Some(1.0),
            ..Mistakes::default()
        },
        &["rounded-to-pixels"],
    );
}

#[test]
fn a_coarser_snap_is_named_with_its_grid() {
    triangles_get(
        Mistakes {
            grid: Some(1.0 / 16.0),
            ..Mistakes::default()
        },
        &["coarse-snap:16"],
    );
}

#[test]
fn a_snap_rounding_ties_up_is_named() {
    // JavaScript's `Math.round(x * 256)`: right but at a coordinate
    // exactly halfway between two 1/256 px steps.
    triangles_get(
        Mistakes {
            ties_up: true,
            ..Mistakes::default()
        },
        &["snap-ties"],
    );
}

#[test]
fn samples_at_pixel_corners() {
    triangles_get(
        Mistakes {
            corners: true,
            ..Mistakes::default()
        },
        &["corner-samples"],
    );
}

#[test]
fn y_measured_from_the_bottom() {
    triangles_get(
        Mistakes {
            y_up: true,
            ..Mistakes::default()
        },
        &["y-flipped"],
    );
}

#[test]
fn a_box_loop_one_row_or_column_short() {
    triangles_get(
        Mistakes {
            box_short_bottom: true,
            ..Mistakes::default()
        },
        &["box-short:bottom"],
    );
    triangles_get(
        Mistakes {
            box_short_right: true,
            ..Mistakes::default()
        },
        &["box-short:right"],
    );
    triangles_get(
        Mistakes {
            box_short_top: true,
            ..Mistakes::default()
        },
        &["box-short:top"],
    );
    triangles_get(
        Mistakes {
            box_short_left: true,
            ..Mistakes::default()
        },
        &["box-short:left"],
    );
}

#[test]
fn floating_point_edge_functions() {
    triangles_get(
        Mistakes {
            float32: true,
            ..Mistakes::default()
        },
        &["float-edges"],
    );
}

#[test]
fn edge_values_that_wrap_in_32_bits_are_overflow() {
    triangles_get(
        Mistakes {
            wrap32: true,
            ..Mistakes::default()
        },
        &["overflow"],
    );
}

#[test]
fn no_clipping_and_duplicates() {
    triangles_get(
        Mistakes {
            no_clip: true,
            ..Mistakes::default()
        },
        &["off-target"],
    );
    triangles_get(
        Mistakes {
            duplicate_first: true,
            ..Mistakes::default()
        },
        &["duplicates"],
    );
}

#[test]
fn under_watertight_a_consistent_other_rule_is_no_cause() {
    // Culling under watertight: the subject's ties may follow any
    // consistent rule; culling is still named.
    let got = named(
        Property::Watertight,
        &mut student(Mistakes {
            cull: Some(1),
            ..Mistakes::default()
        }),
    );
    assert_eq!(got, ["culls:counter-clockwise"]);
}

#[test]
fn a_subject_no_cause_explains_says_so() {
    // Every pixel of every fourth triangle shifted right by one: no cause
    // in the catalogue.
    let mut odd = |case: &Case| -> Result<Vec<Fragment>, SubjectError> {
        let mut out = student(Mistakes::default())(case)?;
        for f in &mut out {
            if f.id % 4 == 1 {
                f.x += 1;
            }
        }
        out.retain(|f| f.x < i64::from(case.width));
        Ok(out)
    };
    let options = CheckOptions {
        cases: 300,
        ..CheckOptions::new(TOP_LEFT)
    };
    let Verdict::Fail { finding, .. } = check(&options, &mut odd).unwrap() else {
        panic!("the shift went unseen");
    };
    assert!(finding.cause.is_none(), "{:?}", finding.cause);
    assert!(
        finding
            .diagnosis
            .as_ref()
            .unwrap()
            .starts_with("no cause in the catalogue explains it"),
        "{:?}",
        finding.diagnosis
    );
}

// --- Lines -----------------------------------------------------------

/// How a student's whole-pixel line drawer goes wrong.
#[derive(Clone, Copy, Default)]
struct LineMistakes {
    /// `D >= 0` steps: a tie goes toward the end.
    tie_toward_end: bool,
    /// The first-octant loop used for every line (no octant swap).
    no_octant_swap: bool,
    /// The last pixel left out.
    half_open: bool,
    /// The first pixel left out.
    first_left_out: bool,
    /// The last pixel listed twice.
    last_twice: bool,
    /// A step in x, then a step in y (4-connected).
    four_connected: bool,
}

fn line_student(m: LineMistakes) -> impl FnMut(&Case) -> Result<Vec<Fragment>, SubjectError> {
    move |case: &Case| {
        let (w, h) = (i64::from(case.width), i64::from(case.height));
        let mut out = Vec::new();
        for (id, l) in case.lines.iter().enumerate() {
            let (x0, y0) = (l[0].0 as i64, l[0].1 as i64);
            let (x1, y1) = (l[1].0 as i64, l[1].1 as i64);
            let (dx, dy) = ((x1 - x0).abs(), (y1 - y0).abs());
            let (sx, sy) = ((x1 - x0).signum(), (y1 - y0).signum());
            let steep = dy > dx && !m.no_octant_swap;
            let (n, k) = if steep { (dy, dx) } else { (dx, dy) };
            let mut d = 2 * k - n;
            let (mut x, mut y) = (x0, y0);
            let mut pixels = Vec::new();
            for i in 0..=n {
                pixels.push((x, y));
                if i == n {
                    break;
                }
                let step = if m.tie_toward_end { d >= 0 } else { d > 0 };
                if step {
                    if m.four_connected {
                        if steep {
                            y += sy;
                        } else {
                            x += sx;
                        }
                        pixels.push((x, y));
                        if steep {
                            x += sx;
                        } else {
                            y += sy;
                        }
                    } else {
                        x += sx;
                        y += sy;
                    }
                    d -= 2 * n;
                } else if steep {
                    y += sy;
                } else {
                    x += sx;
                }
                d += 2 * k;
            }
            if m.half_open && pixels.len() > 1 {
                pixels.pop();
            }
            if m.first_left_out && pixels.len() > 1 {
                pixels.remove(0);
            }
            if m.last_twice {
                if let Some(&p) = pixels.last() {
                    pixels.push(p);
                }
            }
            out.extend(
                pixels
                    .into_iter()
                    .filter(|&(x, y)| (0..w).contains(&x) && (0..h).contains(&y))
                    .map(|(x, y)| Fragment {
                        x,
                        y,
                        id: id as u32,
                        mask: 0,
                    }),
            );
        }
        Ok(out)
    }
}

const PIXEL_INDEX: Property = Property::Line(LineConvention::PixelIndex);

fn lines_get(m: LineMistakes, expected: &[&str]) {
    let got = named(PIXEL_INDEX, &mut line_student(m));
    assert_eq!(got, expected, "named {got:?}");
}

#[test]
fn the_students_line_drawer_without_a_mistake_passes() {
    let options = CheckOptions {
        cases: 300,
        ..CheckOptions::new(PIXEL_INDEX)
    };
    let verdict = check(&options, &mut line_student(LineMistakes::default())).unwrap();
    assert!(matches!(verdict, Verdict::Pass { cases: 300 }), "{verdict}");
}

#[test]
fn a_tie_broken_the_other_way_is_the_other_convention() {
    lines_get(
        LineMistakes {
            tie_toward_end: true,
            ..LineMistakes::default()
        },
        &["convention:pixel-index-toward-end"],
    );
}

#[test]
fn a_first_octant_loop_draws_one_pixel_per_column() {
    lines_get(
        LineMistakes {
            no_octant_swap: true,
            ..LineMistakes::default()
        },
        &["one-per-column"],
    );
}

#[test]
fn endpoint_pixels_missing_or_doubled() {
    lines_get(
        LineMistakes {
            half_open: true,
            ..LineMistakes::default()
        },
        &["endpoint-missing:last"],
    );
    lines_get(
        LineMistakes {
            first_left_out: true,
            ..LineMistakes::default()
        },
        &["endpoint-missing:first"],
    );
    lines_get(
        LineMistakes {
            last_twice: true,
            ..LineMistakes::default()
        },
        &["endpoint-doubled:last"],
    );
}

#[test]
fn a_staircase_is_four_connected() {
    lines_get(
        LineMistakes {
            four_connected: true,
            ..LineMistakes::default()
        },
        &["four-connected"],
    );
}

#[test]
fn a_line_drawn_from_its_other_end() {
    // The midpoint rule walked from the second endpoint.
    let midpoint = Property::Line(LineConvention::Midpoint);
    let backend = rasterlab::raster::line_backend("bresenham").unwrap();
    let mut reversed = |case: &Case| -> Result<Vec<Fragment>, SubjectError> {
        let mut flipped = case.clone();
        for l in &mut flipped.lines {
            l.swap(0, 1);
        }
        Ok(rasterlab::check::line_fragments(backend, &flipped))
    };
    assert_eq!(named(midpoint, &mut reversed), ["reversed"]);
}

#[test]
fn the_catalogue_names_each_cause_once() {
    for property in [
        TOP_LEFT,
        Property::Watertight,
        PIXEL_INDEX,
        Property::Line(LineConvention::Midpoint),
    ] {
        let ids: Vec<String> = catalogue(property).iter().map(|c| c.id()).collect();
        let mut unique = ids.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), ids.len(), "{ids:?}");
    }
}

/// The most common student rasterizer: three edge functions in `f64` on
/// the vertices as given (no snapping), a centre drawn when all three
/// are `>= 0`.
fn inclusive_in_floating_point(case: &Case) -> Result<Vec<Fragment>, SubjectError> {
    let edge = |a: (f64, f64), b: (f64, f64), p: (f64, f64)| {
        (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0)
    };
    let mut out = Vec::new();
    for (id, t) in case.triangles.iter().enumerate() {
        let area = edge(t[0], t[1], t[2]);
        if area == 0.0 {
            continue;
        }
        for y in 0..i64::from(case.height) {
            for x in 0..i64::from(case.width) {
                let p = (x as f64 + 0.5, y as f64 + 0.5);
                if (0..3).all(|i| edge(t[i], t[(i + 1) % 3], p) * area.signum() >= 0.0) {
                    out.push(Fragment::at(x, y, id as u32));
                }
            }
        }
    }
    Ok(out)
}

#[test]
fn inclusive_edges_in_floating_point_name_the_inclusive_rule_first() {
    // A difference exactly on an edge always lies within a hair of it:
    // the rule that explains the differences comes before that condition.
    let got = named(TOP_LEFT, &mut inclusive_in_floating_point);
    assert_eq!(got[0], "fill-rule:inclusive", "named {got:?}");
    assert!(got[1..].iter().all(|c| c == "float-edges"), "named {got:?}");
}

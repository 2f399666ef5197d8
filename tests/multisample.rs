//! Multisampling: every triangle back-end gives the coverage masks the
//! reference gives, sample for sample, under every fill rule, on the
//! standard patterns; a spade-triangulated polygon covers each sample
//! inside it exactly once under the watertight rules; and a sample lying
//! on an edge goes to the triangle whose edge owns its ties. `check
//! --msaa N` passes every back-end, judges masks exactly and names the
//! classic multisampling mistakes by the reference.

mod common;

use common::*;
use proptest::prelude::*;
use rasterlab::check::{
    check, run, triangle_fragments, Case, CheckOptions, CheckRequest, FailureKind, Fragment,
    Property, RuleChoice, Subject, SubjectError, SubjectSpec, Verdict, VerdictWord,
};
use rasterlab::geometry::{setup_triangles, Polygon, Side};
use rasterlab::raster::{
    masks_of, reference_masks, triangle_backend, triangle_backends, FillRule, FixedPoint,
    MaskFragment, SamplePattern, SAMPLE_COUNTS,
};

/// Every back-end's masks against the reference's, for one rule and pattern.
fn check_masks(
    triangles: &[[FixedPoint; 3]],
    rule: FillRule,
    pattern: &SamplePattern,
) -> Result<(), String> {
    let setups = setup_triangles(triangles, rule);
    let reference = reference_masks(&setups, viewport(), pattern);
    for b in triangle_backends() {
        let masks = masks_of(*b, &setups, viewport(), pattern);
        if masks != reference {
            let first = masks
                .iter()
                .zip(&reference)
                .find(|(m, r)| m != r)
                .map(|(m, r)| format!("{m:?} against the reference's {r:?}"))
                .unwrap_or_else(|| format!("{} masks against {}", masks.len(), reference.len()));
            return Err(format!(
                "{} under {rule}, {} samples: {first}",
                b.name(),
                pattern.count()
            ));
        }
    }
    Ok(())
}

/// A soup whose vertices lie on the 1/16 px grid of the sample offsets as
/// often as not, so that edges run through samples and ties decide.
fn sample_grid_soup() -> impl Strategy<Value = Vec<[FixedPoint; 3]>> {
    prop_oneof![
        Just(Some(1.0 / 16.0)),
        Just(Some(1.0 / 8.0)),
        quantum().prop_map(|q| q)
    ]
    .prop_flat_map(|q| {
        let p = point(-4.0, SIZE as f32 + 4.0, q);
        proptest::collection::vec([p.clone(), p.clone(), p], 1..=6)
    })
}

/// Per pixel and sample, how many triangles cover it.
fn sample_counts(masks: &[MaskFragment], samples: u32) -> Vec<u32> {
    let mut counts = vec![0; (SIZE * SIZE * samples) as usize];
    for m in masks {
        for i in 0..samples {
            if m.mask & (1 << i) != 0 {
                counts[((m.y as u32 * SIZE + m.x as u32) * samples + i) as usize] += 1;
            }
        }
    }
    counts
}

/// Every sample strictly inside the polygon is covered exactly once, none
/// outside it, and none on its outline twice.
fn check_sample_watertight(
    poly: &Polygon,
    rule: FillRule,
    pattern: &SamplePattern,
) -> Result<(), String> {
    let setups = setup_triangles(&triangulation(poly), rule);
    let backends = triangle_backends();
    // One back-end per pattern, in turn (the first property compares them
    // all with the reference).
    let b = backends[pattern.count() as usize % backends.len()];
    let counts = sample_counts(&masks_of(b, &setups, viewport(), pattern), pattern.count());
    for y in 0..SIZE as i64 {
        for x in 0..SIZE as i64 {
            for i in 0..pattern.count() as usize {
                let (px, py) = pattern.sample_point(x, y, i);
                let side = poly.classify(FixedPoint::from_raw(px, py).unwrap());
                let n =
                    counts[((y as u32 * SIZE + x as u32) * pattern.count() + i as u32) as usize];
                let ok = match side {
                    Side::Inside => n == 1,
                    Side::Outside => n == 0,
                    Side::Boundary => n <= 1,
                };
                if !ok {
                    return Err(format!(
                        "{} under {rule}: sample {i} of pixel ({x}, {y}) is {side:?} and covered {n} times",
                        b.name()
                    ));
                }
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(crate::common::proptest_config(300, "tests/proptest-regressions/multisample.txt"))]

    /// Random soups, vertices on the sample grid or off it: every
    /// back-end's masks equal the reference's under all 7 rules.
    #[test]
    fn every_backend_gives_the_reference_masks(
        triangles in sample_grid_soup(),
        count in proptest::sample::select(&SAMPLE_COUNTS[1..]),
    ) {
        let pattern = SamplePattern::standard(count).unwrap();
        for rule in FillRule::ALL {
            check_masks(&triangles, rule, &pattern).map_err(TestCaseError::fail)?;
            check_masks(&triangles, rule, &pattern.mirrored_y()).map_err(TestCaseError::fail)?;
        }
    }

    /// Spade triangulations of polygons with and without holes: under the
    /// watertight rules, every sample inside is covered exactly once.
    #[test]
    fn samples_of_spade_meshes_are_covered_exactly_once(
        poly in polygon(),
        count in proptest::sample::select(&[4u32, 8, 16][..]),
    ) {
        let pattern = SamplePattern::standard(count).unwrap();
        for rule in FillRule::WATERTIGHT {
            check_sample_watertight(&poly, rule, &pattern).map_err(TestCaseError::fail)?;
        }
    }
}

/// Two rectangles, each of two triangles, side by side along x = 0.375:
/// the line runs through sample 0 of pixel (0, 0) under the 4-sample
/// pattern, at (0.375, 0.125). The top-left rule gives it to the right
/// rectangle (the edge is its left edge), the bottom-right rule to the
/// left one, `inclusive` to both and `exclusive` to neither.
#[test]
fn a_sample_on_a_shared_edge_goes_to_the_edge_that_owns_ties() {
    let p = |x: f32, y: f32| snap(x, y);
    let left = [
        [p(-4.0, -4.0), p(0.375, -4.0), p(0.375, 8.0)],
        [p(-4.0, -4.0), p(0.375, 8.0), p(-4.0, 8.0)],
    ];
    let right = [
        [p(0.375, -4.0), p(5.0, -4.0), p(5.0, 8.0)],
        [p(0.375, -4.0), p(5.0, 8.0), p(0.375, 8.0)],
    ];
    let triangles: Vec<_> = left.iter().chain(&right).copied().collect();
    let pattern = SamplePattern::standard(4).unwrap();
    let side_masks = |rule: FillRule| {
        let setups = setup_triangles(&triangles, rule);
        let masks = reference_masks(&setups, viewport(), &pattern);
        let of = |ids: std::ops::Range<u32>| {
            masks
                .iter()
                .filter(|m| (m.x, m.y) == (0, 0) && ids.contains(&m.triangle))
                .fold(0, |acc, m| acc | m.mask)
        };
        for b in triangle_backends() {
            assert_eq!(
                masks_of(*b, &setups, viewport(), &pattern),
                masks,
                "{}",
                b.name()
            );
        }
        (of(0..2), of(2..4))
    };
    // Samples: 0 on the edge, 1 (0.875, 0.375) and 3 (0.625, 0.875)
    // right of it, 2 (0.125, 0.625) left of it.
    assert_eq!(side_masks(FillRule::TopLeft), (0b0100, 0b1011));
    assert_eq!(side_masks(FillRule::BottomRight), (0b0101, 0b1010));
    assert_eq!(side_masks(FillRule::Inclusive), (0b0101, 0b1011));
    assert_eq!(side_masks(FillRule::Exclusive), (0b0100, 0b1010));
}

/// One sample is the centre: the 1-sample masks are the single-sample
/// fragments, every bit 1.
#[test]
fn one_sample_is_the_pixel_centre() {
    let triangles = [[snap(0.5, 0.5), snap(30.0, 4.0), snap(7.0, 33.0)]];
    let setups = setup_triangles(&triangles, FillRule::TopLeft);
    let masks = reference_masks(&setups, viewport(), &SamplePattern::standard(1).unwrap());
    let list = fragments(triangle_backends()[0], &triangles, FillRule::TopLeft);
    let mut centres: Vec<(i64, i64)> = list
        .triangles
        .iter()
        .map(|f| (i64::from(f.y), i64::from(f.x)))
        .collect();
    centres.sort();
    assert_eq!(
        masks.iter().map(|m| (m.y, m.x)).collect::<Vec<_>>(),
        centres
    );
    assert!(masks.iter().all(|m| m.mask == 1));
}

/// `fragments --msaa 4` on two triangles splitting a 5 x 5 square: each
/// pixel of the diagonal is shared, samples 0 and 1 (mask 3) to the
/// first triangle and 2 and 3 (mask 12) to the second, and the square's
/// 100 samples are each covered once; a count with no standard pattern
/// and a line set are refused with exit 2.
#[test]
fn fragments_prints_masks() {
    let tmp = tempfile::tempdir().unwrap();
    let square = tmp.path().join("square.txt");
    std::fs::write(&square, "0 0 5 0 5 5\n0 5 0 0 5 5\n").unwrap();
    let square = square.to_str().unwrap();
    let out = rasterlab(&[
        "fragments",
        "--backend",
        "tiled",
        "--size",
        "5x5",
        "--msaa",
        "4",
        square,
    ]);
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8(out.stdout).unwrap();
    let mut samples = [0u32; 2];
    for line in text.lines() {
        let v: Vec<u32> = line.split(' ').map(|w| w.parse().unwrap()).collect();
        let [x, y, id, mask] = v[..] else {
            panic!("{line}")
        };
        samples[id as usize] += mask.count_ones();
        if x == y {
            assert_eq!(mask, if id == 0 { 3 } else { 12 }, "{line}");
        } else {
            assert_eq!(mask, 15, "{line}");
        }
    }
    assert_eq!(samples, [50, 50]);
    let three = rasterlab(&[
        "fragments",
        "--backend",
        "tiled",
        "--size",
        "5x5",
        "--msaa",
        "3",
        square,
    ]);
    assert_eq!(three.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&three.stderr).contains("1, 2, 4, 8 and 16"));
    let lines = rasterlab(&[
        "fragments",
        "--backend",
        "bresenham",
        "--size",
        "8x8",
        "--msaa",
        "4",
        "assets/lines.txt",
    ]);
    assert_eq!(lines.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&lines.stderr).contains("not multisampled"));
}

/// `check --msaa N` (the library's request) passes every triangle
/// back-end under every fill rule, on 4, 8 and 16 samples: the back-ends'
/// masks, one pass of their own walk per sample, against the reference's
/// sample-by-sample test, on the check's adversarial families.
#[test]
fn check_msaa_passes_every_backend_under_every_rule() {
    for backend in triangle_backends() {
        for rule in FillRule::ALL {
            for n in [4, 8, 16] {
                let request = CheckRequest {
                    rule: Some(RuleChoice::Exact(rule)),
                    msaa: Some(n),
                    cases: 60,
                    seed: u64::from(n),
                    ..CheckRequest::new(SubjectSpec::Backend(backend.name().into()))
                };
                let report = run(&request).unwrap();
                assert_eq!(
                    report.verdict,
                    VerdictWord::Pass,
                    "{} under {rule}, {n} samples: {:?}",
                    backend.name(),
                    report.counterexample
                );
                assert_eq!(report.samples, n);
                assert!(report
                    .description
                    .contains(&format!("{n} samples per pixel")));
            }
        }
    }
}

/// The cause `check` names for a multisampling subject under `rule`, and
/// the kind of the shrunk failure.
fn named_cause(rule: FillRule, n: u32, subject: &mut impl Subject) -> (Vec<String>, FailureKind) {
    let options = CheckOptions {
        samples: SamplePattern::standard(n).ok(),
        ..CheckOptions::new(Property::Exact(rule))
    };
    match check(&options, subject).unwrap() {
        Verdict::Fail { finding, .. } => {
            let cause = finding.cause.as_ref().expect("a cause is named");
            (cause.causes.clone(), finding.kind())
        }
        Verdict::Pass { .. } => panic!("the mistake passed"),
    }
}

/// The mistakes a multisampling rasterizer makes, each caught and named:
/// every sample decided at the pixel centre (a full mask, the done-when
/// case of a "multisampler" that is not one), OpenGL's y-up pattern used
/// on a y-down screen, a sample on an edge given by the top-left rule
/// where the bottom-right rule is asked for, and a mask with the bits of
/// samples 0 and 1 swapped, which no cause explains.
#[test]
fn check_msaa_names_the_classic_mistakes() {
    let tiled = triangle_backend("tiled").unwrap();
    let mut centre = |c: &Case| -> Result<Vec<Fragment>, SubjectError> {
        let full = c.samples.unwrap().full_mask();
        let one = Case {
            samples: None,
            ..c.clone()
        };
        Ok(triangle_fragments(tiled, &one, FillRule::TopLeft)
            .into_iter()
            .map(|f| Fragment { mask: full, ..f })
            .collect())
    };
    let (causes, _) = named_cause(FillRule::TopLeft, 4, &mut centre);
    assert_eq!(causes, ["centre-for-every-sample"]);

    let mut mirrored = |c: &Case| -> Result<Vec<Fragment>, SubjectError> {
        let gl = Case {
            samples: c.samples.map(SamplePattern::mirrored_y),
            ..c.clone()
        };
        Ok(triangle_fragments(tiled, &gl, FillRule::TopLeft))
    };
    let (causes, _) = named_cause(FillRule::TopLeft, 8, &mut mirrored);
    assert_eq!(causes, ["mirrored-pattern"]);

    let mut top_left = |c: &Case| -> Result<Vec<Fragment>, SubjectError> {
        Ok(triangle_fragments(tiled, c, FillRule::TopLeft))
    };
    let (causes, _) = named_cause(FillRule::BottomRight, 16, &mut top_left);
    assert_eq!(causes, ["fill-rule:top-left"]);

    let mut swapped = |c: &Case| -> Result<Vec<Fragment>, SubjectError> {
        Ok(triangle_fragments(tiled, c, FillRule::TopLeft)
            .into_iter()
            .map(|f| {
                let (b0, b1) = (f.mask & 1, (f.mask >> 1) & 1);
                Fragment {
                    mask: (f.mask & !3) | (b0 << 1) | b1,
                    ..f
                }
            })
            .collect())
    };
    let options = CheckOptions {
        samples: SamplePattern::standard(4).ok(),
        ..CheckOptions::new(Property::Exact(FillRule::TopLeft))
    };
    match check(&options, &mut swapped).unwrap() {
        Verdict::Fail { finding, .. } => {
            assert_eq!(finding.kind(), FailureKind::Mask);
            assert!(finding.cause.is_none(), "{:?}", finding.cause);
            let text = &finding.problems[0];
            assert!(text.contains("another mask than the rule's"), "{text}");
        }
        Verdict::Pass { .. } => panic!("swapped samples passed"),
    }
}

/// The example multisampler passes `check --msaa 4 --persistent`, and
/// with a mistake asked for fails (exit 1) with the cause named; the
/// counterexample file says `# msaa 4`, so `--case` reruns it without
/// `--msaa`, and a case that says another count than `--msaa` is refused.
#[test]
fn check_msaa_runs_a_program_and_names_its_mistake() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().to_str().unwrap();
    let example = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/student/multisample.py"
    );
    let command = |mistake: &str| format!("python3 {example} {{msaa}} {mistake}");
    let right = rasterlab(&[
        "check",
        "--msaa",
        "4",
        "--persistent",
        "--exec",
        &command(""),
        "--out",
        out,
    ]);
    assert!(right.status.success(), "{right:?}");
    let stdout = String::from_utf8_lossy(&right.stdout);
    assert!(stdout.contains("4 samples per pixel"), "{stdout}");

    let wrong = rasterlab(&[
        "check",
        "--msaa",
        "4",
        "--persistent",
        "--exec",
        &command("centre"),
        "--out",
        out,
    ]);
    assert_eq!(wrong.status.code(), Some(1), "{wrong:?}");
    let stdout = String::from_utf8_lossy(&wrong.stdout);
    assert!(
        stdout.contains("every sample decided at the pixel centre"),
        "{stdout}"
    );
    let file = tmp.path().join("counterexample.txt");
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(text.starts_with("# size 1x1\n# msaa 4\n"), "{text}");
    assert!(text.contains("mask 15"), "{text}");
    let case = Case::from_text(&text).unwrap();
    assert_eq!(case.samples, SamplePattern::standard(4).ok());

    let rerun = rasterlab(&[
        "check",
        "--case",
        file.to_str().unwrap(),
        "--backend",
        "scanline",
        "--out",
        out,
    ]);
    assert!(rerun.status.success(), "{rerun:?}");
    assert!(String::from_utf8_lossy(&rerun.stdout).contains("4 samples per pixel"));
    let other = rasterlab(&[
        "check",
        "--case",
        file.to_str().unwrap(),
        "--msaa",
        "8",
        "--backend",
        "scanline",
    ]);
    assert_eq!(other.status.code(), Some(2), "{other:?}");
    assert!(String::from_utf8_lossy(&other.stderr).contains("says `# msaa 4`"));
}

/// `--msaa` is refused, exit 2, where it does not apply or names no
/// standard pattern: lines, watertight, crack-free, `any`, a count of 3,
/// a word; and a case file with `# msaa 3`.
#[test]
fn check_msaa_refuses_what_it_cannot_judge() {
    let tmp = tempfile::tempdir().unwrap();
    let bad_case = tmp.path().join("three.txt");
    std::fs::write(&bad_case, "# size 4x4\n# msaa 3\n0 0 4 0 0 4\n").unwrap();
    let bad_case = bad_case.to_str().unwrap();
    for args in [
        &["--msaa", "4", "--kind", "lines"][..],
        &["--msaa", "4", "--rule", "watertight"],
        &["--msaa", "4", "--rule", "crack-free"],
        &["--msaa", "4", "--rule", "any"],
        &["--msaa", "3"],
        &["--msaa", "four"],
        &["--case", bad_case],
    ] {
        let mut all = vec!["check", "--backend", "scanline"];
        all.extend_from_slice(args);
        let out = rasterlab(&all);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {out:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("msaa") || err.contains("sample"),
            "{args:?}: {err}"
        );
    }
}

/// `explain --msaa 4` traces the partly covered pixels of a triangle
/// sample by sample: its masks are those `fragments --msaa 4` prints,
/// each sample's verdict agrees with its bit, and lines and the depth
/// buffer are refused (exit 2).
#[test]
fn explain_traces_the_samples_fragments_prints() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("one.txt");
    std::fs::write(&file, "0.3 0.2 9.6 2.9 2.1 7.7\n").unwrap();
    let fragments = rasterlab(&[
        "fragments",
        "--backend",
        "tiled",
        "--size",
        "12x10",
        "--msaa",
        "4",
        file.to_str().unwrap(),
    ]);
    assert!(fragments.status.success(), "{fragments:?}");
    let partial: Vec<(i64, i64, u32)> = String::from_utf8(fragments.stdout)
        .unwrap()
        .lines()
        .map(|l| {
            let v: Vec<i64> = l.split(' ').map(|w| w.parse().unwrap()).collect();
            (v[0], v[1], v[3] as u32)
        })
        .filter(|&(_, _, m)| m != 15)
        .collect();
    let explain = rasterlab(&[
        "explain",
        "--backend",
        "bbox",
        "--size",
        "12x10",
        "--msaa",
        "4",
        "0.3",
        "0.2",
        "9.6",
        "2.9",
        "2.1",
        "7.7",
    ]);
    assert!(explain.status.success(), "{explain:?}");
    let text = String::from_utf8(explain.stdout).unwrap();
    let mut traced = Vec::new();
    let mut lines = text.lines().skip_while(|l| !l.starts_with("multisampling"));
    while let Some(line) = lines.next() {
        let Some(rest) = line.strip_prefix("pixel (") else {
            continue;
        };
        let (xy, mask) = rest.split_once("): mask ").unwrap();
        let (x, y) = xy.split_once(", ").unwrap();
        let mask: u32 = mask.split(' ').next().unwrap().parse().unwrap();
        // Its four sample rows: "inside" exactly where the bit is set.
        for i in 0..4 {
            let row = lines.next().unwrap();
            assert_eq!(row.contains("inside"), mask & (1 << i) != 0, "{row}");
        }
        traced.push((x.parse().unwrap(), y.parse().unwrap(), mask));
    }
    assert!(!traced.is_empty());
    assert_eq!(traced, partial);
    // The picture: a dot or a ring for each of the 4 x 12 x 10 samples,
    // the dots as many as the masks' bits, and both in the legend.
    let svg = tmp.path().join("samples.svg");
    let pictured = rasterlab(&[
        "explain",
        "--backend",
        "bbox",
        "--size",
        "12x10",
        "--msaa",
        "4",
        "--picture",
        svg.to_str().unwrap(),
        "0.3",
        "0.2",
        "9.6",
        "2.9",
        "2.1",
        "7.7",
    ]);
    assert!(pictured.status.success(), "{pictured:?}");
    let svg = std::fs::read_to_string(svg).unwrap();
    let covered_bits: u32 = String::from_utf8(
        rasterlab(&[
            "fragments",
            "--backend",
            "bbox",
            "--size",
            "12x10",
            "--msaa",
            "4",
            file.to_str().unwrap(),
        ])
        .stdout,
    )
    .unwrap()
    .lines()
    .map(|l| {
        l.rsplit(' ')
            .next()
            .unwrap()
            .parse::<u32>()
            .unwrap()
            .count_ones()
    })
    .sum();
    assert_eq!(
        svg.matches("class=\"sample covered\"").count() as u32,
        covered_bits
    );
    assert_eq!(svg.matches("class=\"sample").count(), 4 * 12 * 10);
    for role in ["sample-covered", "sample-outside"] {
        assert!(svg.contains(&format!("data-role=\"{role}\"")), "{role}");
    }
    for args in [
        &[
            "explain",
            "--backend",
            "bresenham",
            "--msaa",
            "4",
            "0",
            "0",
            "5",
            "3",
        ][..],
        &["explain", "--backend", "depth-buffer", "--msaa", "4"],
        &[
            "explain",
            "--backend",
            "bbox",
            "--msaa",
            "5",
            "0",
            "0",
            "4",
            "0",
            "0",
            "4",
        ],
    ] {
        let out = rasterlab(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {out:?}");
    }
}

/// Regressions of `check --msaa`, each found by trying it as a newcomer:
/// a pixel listed twice is a listed-twice problem only (its first line
/// judged, not counted missing); a subject that breaks only on far
/// vertices is broken on some inputs, not on every one (the simplest
/// case it is tried on is multisampled as the check is); and the JSON
/// report's pixels carry their masks.
#[test]
fn check_msaa_regressions() {
    let four = SamplePattern::standard(4).ok();
    let tiled = triangle_backend("tiled").unwrap();
    let case = Case {
        samples: four,
        ..Case::from_text("# size 3x3\n0.2 0.1 2.9 0.4 0.3 2.8\n").unwrap()
    };
    let mut drawn = triangle_fragments(tiled, &case, FillRule::TopLeft);
    drawn.push(drawn[0]);
    let finding = rasterlab::check::judge(Property::Exact(FillRule::TopLeft), &case, &drawn)
        .expect("a pixel listed twice fails");
    assert_eq!(
        finding.kinds,
        [FailureKind::ListedTwice],
        "{:?}",
        finding.problems
    );

    let mut far_breaks = |c: &Case| -> Result<Vec<Fragment>, SubjectError> {
        if c.samples.is_none() {
            return Err(SubjectError::Start("no # msaa line".into()));
        }
        if c.triangles
            .iter()
            .flatten()
            .any(|p| p.0.abs().max(p.1.abs()) > 1000.0)
        {
            return Err(SubjectError::Start("too far".into()));
        }
        Ok(triangle_fragments(tiled, c, FillRule::TopLeft))
    };
    let options = CheckOptions {
        samples: four,
        ..CheckOptions::new(Property::Exact(FillRule::TopLeft))
    };
    let broken = check(&options, &mut far_breaks).expect_err("far vertices break it");
    assert!(!broken.on_every_input, "{broken}");

    let tmp = tempfile::tempdir().unwrap();
    let json = rasterlab(&[
        "check",
        "--msaa",
        "4",
        "--format",
        "json",
        "--out",
        tmp.path().to_str().unwrap(),
        "--persistent",
        "--exec",
        concat!(
            "python3 ",
            env!("CARGO_MANIFEST_DIR"),
            "/examples/student/multisample.py {msaa} centre"
        ),
    ]);
    assert_eq!(json.status.code(), Some(1), "{json:?}");
    let report: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    let c = &report["counterexample"];
    // The centre's full mask drawn, the rule's mask missing.
    assert_eq!(c["extra"][0][3], 15, "{c}");
    assert!(c["missing"][0][3].as_i64().unwrap() < 15, "{c}");
    assert_eq!(report["samples"], 4);
}

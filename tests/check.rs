//! `rasterlab::check` checked: the built-in back-ends pass on many seeds,
//! mutants of them are caught with counterexamples of at most three
//! primitives, and an outside program passes and fails as it should
//! through `rasterlab check --exec`.

mod common;
use common::rasterlab;

use rasterlab::check::{
    check, line_fragments, run, triangle_fragments, Builtin, Case, CheckOptions, CheckRequest,
    ConventionChoice, Fragment, Kind, LineConvention, Property, RuleChoice, SubjectError,
    SubjectSpec, Verdict,
};
use rasterlab::raster::{line_backend, triangle_backend, triangle_backends, FillRule};
use std::process::Command;

fn options(property: Property, cases: u32, seed: u64) -> CheckOptions {
    CheckOptions {
        cases,
        seed,
        ..CheckOptions::new(property)
    }
}

fn passes(verdict: Verdict) -> bool {
    match verdict {
        Verdict::Pass { .. } => true,
        Verdict::Fail { finding, .. } => {
            eprintln!("{}", finding.counterexample_text());
            false
        }
    }
}

#[test]
fn every_triangle_back_end_passes_the_exact_check_under_every_rule() {
    for b in triangle_backends() {
        for rule in FillRule::ALL {
            for seed in 0..3 {
                let verdict = check(
                    &options(Property::Exact(rule), 200, seed),
                    &mut Builtin::triangles(*b, rule),
                )
                .unwrap();
                assert!(passes(verdict), "{} {}", b.name(), rule.name());
            }
        }
    }
}

#[test]
fn the_watertight_rules_pass_and_inclusive_and_exclusive_fail() {
    for b in triangle_backends() {
        for rule in [
            FillRule::TopLeft,
            FillRule::BottomRight,
            FillRule::OffscreenPoint,
        ] {
            for seed in 0..3 {
                let verdict = check(
                    &options(Property::Watertight, 200, seed),
                    &mut Builtin::triangles(*b, rule),
                )
                .unwrap();
                assert!(passes(verdict), "{} {}", b.name(), rule.name());
            }
        }
    }
    let scanline = triangle_backend("scanline").unwrap();
    for (rule, word) in [
        (FillRule::Inclusive, "double draw"),
        (FillRule::Exclusive, "gap"),
    ] {
        let verdict = check(
            &options(Property::Watertight, 200, 0),
            &mut Builtin::triangles(scanline, rule),
        )
        .unwrap();
        let Verdict::Fail { finding, .. } = verdict else {
            panic!("{} passed the watertight check", rule.name());
        };
        assert!(
            finding.problems[0].starts_with(word),
            "{:?}",
            finding.problems
        );
        // A gap at the shared vertex of a closed fan needs the whole fan
        // (at most eight triangles): without one of them the vertex is on
        // the boundary, where a gap is allowed.
        assert!(finding.case.len() <= 8, "{}", finding.counterexample_text());
    }
}

#[test]
fn line_back_ends_pass_their_conventions() {
    let bresenham = line_backend("bresenham").unwrap();
    let diamond = line_backend("diamond").unwrap();
    for seed in 0..2 {
        let midpoint = Property::Line(LineConvention::Midpoint);
        assert!(passes(
            check(
                &options(midpoint, 300, seed),
                &mut Builtin::Lines(bresenham)
            )
            .unwrap()
        ));
        for convention in [LineConvention::Diamond, LineConvention::Vulkan] {
            let property = Property::Line(convention);
            assert!(passes(
                check(&options(property, 300, seed), &mut Builtin::Lines(diamond)).unwrap()
            ));
        }
    }
}

/// Runs a mutant under the exact top-left check and returns the shrunk
/// counterexample's problems, asserting it has at most three primitives.
fn caught(property: Property, mut mutant: impl FnMut(&Case) -> Vec<Fragment>) -> Vec<String> {
    let verdict = check(&options(property, 300, 7), &mut |c: &Case| -> Result<
        Vec<Fragment>,
        SubjectError,
    > { Ok(mutant(c)) })
    .unwrap();
    let Verdict::Fail {
        finding, original, ..
    } = verdict
    else {
        panic!("the mutant passed");
    };
    eprintln!(
        "mutant caught under {}: {} -> {} primitive(s), {}x{}: {}",
        property,
        original.len(),
        finding.case.len(),
        finding.case.width,
        finding.case.height,
        finding.problems[0]
    );
    assert!(
        finding.case.len() <= 3,
        "counterexample of {} primitives:\n{}",
        finding.case.len(),
        finding.counterexample_text()
    );
    finding.problems
}

#[test]
fn mutants_are_caught_with_at_most_three_primitives() {
    let exact = Property::Exact(FillRule::TopLeft);
    let scanline = triangle_backend("scanline").unwrap();
    // The wrong tie rule.
    caught(exact, |c| {
        triangle_fragments(scanline, c, FillRule::BottomRight)
    });
    // An off-by-one span: the last pixel of every row of every triangle dropped.
    caught(exact, |c| {
        let mut f = triangle_fragments(scanline, c, FillRule::TopLeft);
        f.sort_by_key(|f| (f.id, f.y, f.x));
        let keep: Vec<bool> = (0..f.len())
            .map(|i| i + 1 < f.len() && (f[i + 1].id, f[i + 1].y) == (f[i].id, f[i].y))
            .collect();
        f.into_iter()
            .zip(keep)
            .filter(|(_, k)| *k)
            .map(|(f, _)| f)
            .collect()
    });
    // One winding skipped: clockwise triangles are not drawn.
    caught(exact, |c| {
        let keep: Vec<bool> = c
            .snapped_triangles()
            .iter()
            .map(|t| rasterlab::raster::TriangleSetup::signed_area(*t) > 0)
            .collect();
        triangle_fragments(scanline, c, FillRule::TopLeft)
            .into_iter()
            .filter(|f| keep[f.id as usize])
            .collect()
    });
    // Coarser snapping: 1/16 pixel instead of 1/256.
    caught(exact, |c| {
        let mut coarse = c.clone();
        for t in &mut coarse.triangles {
            for p in t.iter_mut() {
                *p = ((p.0 * 16.0).round() / 16.0, (p.1 * 16.0).round() / 16.0);
            }
        }
        triangle_fragments(scanline, &coarse, FillRule::TopLeft)
    });
    // A fragment off the target.
    let problems = caught(exact, |c| {
        let mut f = triangle_fragments(scanline, c, FillRule::TopLeft);
        f.push(Fragment {
            x: i64::from(c.width),
            y: 0,
            id: 0,
            mask: 0,
        });
        f
    });
    assert!(problems[0].contains("outside the"), "{problems:?}");
    // The same mutants under the watertight property, where it applies:
    // an off-by-one row leaves gaps.
    caught(Property::Watertight, |c| {
        triangle_fragments(scanline, c, FillRule::TopLeft)
            .into_iter()
            .filter(|f| f.y != 0)
            .collect()
    });
    // Lines: the last pixel of every line dropped.
    let bresenham = line_backend("bresenham").unwrap();
    caught(Property::Line(LineConvention::Midpoint), |c| {
        let mut f = line_fragments(bresenham, c);
        let last: std::collections::HashMap<u32, usize> =
            f.iter().enumerate().map(|(i, f)| (f.id, i)).collect();
        let drop: std::collections::HashSet<usize> = last.values().copied().collect();
        f = f
            .into_iter()
            .enumerate()
            .filter(|(i, _)| !drop.contains(i))
            .map(|(_, f)| f)
            .collect();
        f
    });
    // Lines: the midpoint rule is not the diamond rule, but is within
    // Vulkan's tolerance of it.
    let diamond = Property::Line(LineConvention::Diamond);
    caught(diamond, |c| line_fragments(bresenham, c));
}

/// The folder `name` in `dir` (a test's own temporary folder, removed
/// when the test ends, whether it passes or panics), as text.
fn out_dir(dir: &std::path::Path, name: &str) -> String {
    dir.join(name).to_str().unwrap().to_string()
}

#[test]
fn an_outside_program_passes_and_fails_through_exec() {
    let tmp = tempfile::tempdir().unwrap();
    let bin = env!("CARGO_BIN_EXE_rasterlab");
    let good = format!(
        "{bin} fragments --backend scanline --rule {{rule}} --size {{width}}x{{height}} {{input}}"
    );
    let out = rasterlab(&[
        "check",
        "--exec",
        &good,
        "--cases",
        "60",
        "--out",
        &out_dir(tmp.path(), "good"),
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("PASS: 60 cases"));
    let out = rasterlab(&[
        "check",
        "--exec",
        &good,
        "--rule",
        "bottom-right",
        "--cases",
        "60",
        "--out",
        &out_dir(tmp.path(), "br"),
    ]);
    assert_eq!(out.status.code(), Some(0));
    // Inclusive drawing checked as watertight: a double draw, shrunk,
    // written out, and the written counterexample fails again when rerun.
    let inclusive = format!(
        "{bin} fragments --backend scanline --rule inclusive --size {{width}}x{{height}} {{input}}"
    );
    let dir = out_dir(tmp.path(), "inclusive");
    let out = rasterlab(&[
        "check",
        "--exec",
        &inclusive,
        "--rule",
        "watertight",
        "--out",
        &dir,
    ]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(stdout.contains("double draw"), "{stdout}");
    assert!(
        stdout.contains("diagnosis: cause: ties decided by the inclusive rule"),
        "{stdout}"
    );
    let text = std::fs::read_to_string(format!("{dir}/counterexample.txt")).unwrap();
    assert!(text.starts_with("# size "), "{text}");
    let case = Case::from_text(&text).unwrap();
    assert!(case.len() <= 3);
    let html = std::fs::read_to_string(format!("{dir}/report.html")).unwrap();
    assert!(html.contains("class=\"cell\""));
    let size = format!("{}x{}", case.width, case.height);
    let counter = format!("{dir}/counterexample.txt");
    let rerun = rasterlab(&[
        "fragments",
        "--backend",
        "scanline",
        "--rule",
        "inclusive",
        "--size",
        &size,
        &counter,
    ]);
    let drawn =
        rasterlab::check::parse_fragments(&String::from_utf8(rerun.stdout).unwrap(), None).unwrap();
    assert!(rasterlab::check::judge(Property::Watertight, &case, &drawn).is_some());
    // JSON for autograders.
    let out = rasterlab(&[
        "check",
        "--exec",
        &inclusive,
        "--rule",
        "watertight",
        "--json",
        "--out",
        &dir,
    ]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["verdict"], "fail");
    assert!(!v["counterexample"]["extra"].as_array().unwrap().is_empty());
}

#[test]
fn a_broken_program_exits_2_with_the_input_that_breaks_it() {
    let tmp = tempfile::tempdir().unwrap();
    for (command, message) in [
        ("exit 3", "the program failed"),
        ("echo hello world", "is not `x y id`"),
        ("/nonexistent/program {input}", "the program failed"),
        ("sleep 30", "longer than 0.5 s"),
    ] {
        let dir = out_dir(tmp.path(), "broken");
        let out = rasterlab(&[
            "check",
            "--exec",
            command,
            "--timeout",
            "0.5",
            "--cases",
            "3",
            "--out",
            &dir,
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{command}: {err}");
        assert!(err.contains(message), "{command}: {err}");
        assert!(err.contains("counterexample.txt"), "{err}");
    }
    // A program printing without end is cut off by the time limit or the
    // output cap, not read into memory.
    let out = rasterlab(&[
        "check",
        "--exec",
        "yes 1 2 0",
        "--timeout",
        "1",
        "--cases",
        "1",
        "--out",
        &out_dir(tmp.path(), "yes"),
    ]);
    assert_eq!(out.status.code(), Some(2));
    // Huge and negative numbers are defects of the program, reported (the
    // program is given its case, which it ignores).
    let out = rasterlab(&[
        "check",
        "--exec",
        "echo 99999999999999999999999 -5 0; : {input}",
        "--cases",
        "1",
        "--out",
        &out_dir(tmp.path(), "huge"),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stdout).contains("outside the"));
}

// ---------------------------------------------------------------------
// Regression tests: each failed before its fix.

fn frag(x: i64, y: i64, id: u32) -> Fragment {
    Fragment::at(x, y, id)
}

fn case_of(width: u32, height: u32, triangles: Vec<[(f64, f64); 3]>) -> Case {
    Case {
        width,
        height,
        triangles,
        lines: Vec::new(),
        ..Case::default()
    }
}

#[test]
fn an_extra_pixel_is_diagnosed_by_the_edges_it_lies_beyond_and_its_true_distance() {
    let exact = Property::Exact(FillRule::TopLeft);
    // Far from the triangle: once said "91.8 px inside edge ...".
    let far = case_of(8, 8, vec![[(150.0, 5.0), (160.0, 5.0), (155.0, 15.0)]]);
    let finding = rasterlab::check::judge(exact, &far, &[frag(0, 0, 0)]).unwrap();
    let d = finding.diagnosis.unwrap();
    let distance = (149.5f64).hypot(4.5);
    assert!(
        d.contains(&format!("{distance:.5} px outside triangle 0")),
        "{d}"
    );
    assert!(d.contains("beyond edge"), "{d}");
    assert!(!d.contains("inside"), "{d}");
    // On the line of an edge, beyond its end: once said "0.00000 px outside".
    let beside = case_of(8, 8, vec![[(2.0, 0.5), (5.0, 0.5), (3.0, 3.0)]]);
    let finding = rasterlab::check::judge(exact, &beside, &[frag(0, 0, 0)]).unwrap();
    let d = finding.diagnosis.unwrap();
    assert!(d.contains("1.50000 px outside triangle 0"), "{d}");
    assert!(d.contains("beyond edge (3, 3)-(2, 0.5)"), "{d}");
    // A pixel missing from deep inside is inside, by its nearest edge.
    let big = case_of(8, 8, vec![[(0.0, 0.0), (8.0, 0.0), (0.0, 8.0)]]);
    let mut drawn = triangle_fragments(triangle_backend("naive").unwrap(), &big, FillRule::TopLeft);
    drawn.retain(|f| (f.x, f.y) != (1, 1));
    let finding = rasterlab::check::judge(exact, &big, &drawn).unwrap();
    let d = finding.diagnosis.unwrap();
    assert!(d.contains("1.50000 px inside triangle 0"), "{d}");
}

#[test]
fn negative_zero_is_never_printed() {
    let case = case_of(8, 8, vec![[(2.0, -0.0), (5.0, -0.0), (-0.0, 3.0)]]);
    let finding =
        rasterlab::check::judge(Property::Exact(FillRule::TopLeft), &case, &[frag(7, 7, 0)])
            .unwrap();
    let d = finding.diagnosis.clone().unwrap();
    assert!(!d.contains("-0"), "{d}");
    assert!(!finding.counterexample_text().contains("-0"));
}

#[test]
fn a_double_draw_names_as_extra_the_fragment_the_rule_does_not_give() {
    // The README's example: top-left gives pixel (0, 0) to triangle 1.
    let case = case_of(
        1,
        1,
        vec![
            [(0.5, 0.5), (9.0, -2.5), (9.0, -2.0)],
            [(0.5, 0.5), (9.0, -2.0), (8.0, 9.0)],
        ],
    );
    for property in [Property::Watertight, Property::CrackFree] {
        let finding =
            rasterlab::check::judge(property, &case, &[frag(0, 0, 0), frag(0, 0, 1)]).unwrap();
        assert_eq!(finding.extra, vec![frag(0, 0, 0)]);
        let d = finding.diagnosis.as_deref().unwrap();
        assert!(d.contains("only triangle 1"), "{d}");
        assert!(finding.counterexample_text().contains("# extra: (0,0) t0"));
    }
}

/// A double draw is placed where the centre really is: on the vertex or
/// the edge both triangles share, or on an edge of each. The README's
/// student case (the centre on the vertex both triangles share) was said
/// to lie "on the shared edge (0.5, 0.5)-(-9, 9)", an edge of triangle 0
/// only.
#[test]
fn a_double_draw_names_the_vertex_or_edge_the_triangles_really_share() {
    let finding = |triangles| {
        let case = case_of(1, 1, triangles);
        rasterlab::check::judge(Property::Watertight, &case, &[frag(0, 0, 0), frag(0, 0, 1)])
            .unwrap()
    };
    let judge = |triangles| finding(triangles).diagnosis.unwrap();
    let student = finding(vec![
        [(0.25, -0.25), (0.5, 0.5), (-9.0, 9.0)],
        [(0.25, -0.25), (12.0, -34.0), (0.5, 0.5)],
    ]);
    let on_vertex = student.diagnosis.clone().unwrap();
    assert!(
        on_vertex.contains("on the vertex (0.5, 0.5) both triangles share"),
        "{on_vertex}"
    );
    assert!(!on_vertex.contains("(-9, 9)"), "{on_vertex}");
    // Its report page said "0 expected": watertightness has no one answer.
    let page = student.to_html();
    assert!(page.contains("no single answer expected"), "{page}");
    assert!(!page.contains("0 expected"), "{page}");
    let on_edge = judge(vec![
        [(0.5, 0.5), (9.0, -2.5), (9.0, -2.0)],
        [(0.5, 0.5), (9.0, -2.0), (8.0, 9.0)],
    ]);
    assert!(on_edge.contains("on the vertex (0.5, 0.5)"), "{on_edge}");
    // The centre inside a shared edge, between its ends.
    let mid_edge = judge(vec![
        [(0.0, 0.0), (1.0, 1.0), (0.0, 1.0)],
        [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)],
    ]);
    assert!(
        mid_edge.contains("on the shared edge (1, 1)-(0, 0)")
            || mid_edge.contains("on the shared edge (0, 0)-(1, 1)"),
        "{mid_edge}"
    );
}

/// A subject as a boxed closure.
type DrawFn = dyn FnMut(&Case) -> Result<Vec<Fragment>, SubjectError>;

/// The first words of a problem, which name its kind.
fn kind_words(problem: &str) -> String {
    problem
        .split(':')
        .next()
        .unwrap()
        .split_whitespace()
        .take(2)
        .collect::<Vec<_>>()
        .join(" ")
        .replace(|c: char| c.is_ascii_digit(), "#")
}

#[test]
fn shrinking_keeps_the_kind_of_failure() {
    let scanline = triangle_backend("scanline").unwrap();
    // Odd triangles drawn one pixel to the right: extra pixels, gaps and
    // double draws in one case; the shrunk case fails as the original
    // did first.
    let shifted = |c: &Case| -> Result<Vec<Fragment>, SubjectError> {
        Ok(triangle_fragments(scanline, c, FillRule::TopLeft)
            .into_iter()
            .map(|f| {
                if f.id % 2 == 1 {
                    frag(f.x + 1, f.y, f.id)
                } else {
                    f
                }
            })
            .filter(|f| f.x < i64::from(c.width))
            .collect())
    };
    let bresenham = line_backend("bresenham").unwrap();
    let four: &'static rasterlab::raster::line::LineOptions =
        &rasterlab::raster::line::LineOptions {
            connectivity: rasterlab::raster::line::Connectivity::Four,
            ..rasterlab::raster::line::LineOptions::DEFAULT
        };
    let staircase = |c: &Case| -> Result<Vec<Fragment>, SubjectError> {
        let mut list = rasterlab::raster::FragmentList::default();
        bresenham.rasterize(
            &rasterlab::raster::line::LineSetup::numbered(&c.snapped_lines()),
            four,
            rasterlab::raster::PixelRect::of_target(c.width, c.height),
            &mut list,
        );
        Ok(list
            .lines
            .iter()
            .map(|f| frag(i64::from(f.x), i64::from(f.y), f.line))
            .collect())
    };
    let mut subjects: Vec<(Property, Box<DrawFn>)> = vec![
        (Property::Watertight, Box::new(shifted)),
        (Property::CrackFree, Box::new(shifted)),
        (
            Property::Line(LineConvention::Midpoint),
            Box::new(staircase),
        ),
    ];
    for (property, subject) in &mut subjects {
        for seed in 0..4 {
            let verdict = check(&options(*property, 100, seed), subject).unwrap();
            let Verdict::Fail {
                original, finding, ..
            } = verdict
            else {
                panic!("{property} passed");
            };
            let first = rasterlab::check::judge(*property, &original, &subject(&original).unwrap())
                .unwrap();
            assert_eq!(
                kind_words(&first.problems[0]),
                kind_words(&finding.problems[0]),
                "{property}: {:?} shrunk to {:?}",
                first.problems[0],
                finding.problems
            );
            assert_eq!(first.kind(), finding.kind());
            assert_eq!(finding.original_problem.as_ref(), Some(&first.problems[0]));
            assert!(finding
                .counterexample_text()
                .contains(&format!("# the case as generated: {}", first.problems[0])));
        }
    }
}

/// The folders a check leaves in `tmp`.
fn leftovers(tmp: &std::path::Path) -> Vec<String> {
    std::fs::read_dir(tmp)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

#[test]
fn temporary_files_are_removed_on_every_exit() {
    let tmp = tempfile::tempdir().unwrap();
    let bin = env!("CARGO_BIN_EXE_rasterlab");
    let good = format!(
        "{bin} fragments --backend scanline --rule {{rule}} --size {{width}}x{{height}} {{input}}"
    );
    let bad = format!(
        "{bin} fragments --backend scanline --rule inclusive --size {{width}}x{{height}} {{input}}"
    );
    for (command, status) in [(good.as_str(), 0), (bad.as_str(), 1), ("exit 3", 2)] {
        let out = Command::new(bin)
            .args(["check", "--exec", command, "--cases", "12", "--out"])
            .arg(tmp.path().join("out"))
            .env("TMPDIR", tmp.path())
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(status), "{command}");
        assert_eq!(leftovers(tmp.path()), ["out"], "{command}");
    }
}

#[test]
fn a_program_that_fails_on_every_input_is_broken_at_once() {
    let mut runs = 0;
    let verdict = check(
        &options(Property::Exact(FillRule::TopLeft), 20, 0),
        &mut |_: &Case| -> Result<Vec<Fragment>, SubjectError> {
            runs += 1;
            Err(SubjectError::Failed {
                status: "exit status: 127".into(),
                stderr: "sh: 1: nosuchprogram: not found".into(),
            })
        },
    );
    let broken = verdict.unwrap_err();
    assert!(broken.on_every_input);
    assert!(runs <= 2, "{runs} runs: it was shrunk");
    assert!(broken.to_string().contains("on every input"), "{broken}");
    // As a `Box<dyn Error>`.
    let boxed: Box<dyn std::error::Error> = broken;
    assert!(boxed.source().is_some());
    let mut request = CheckRequest::new(SubjectSpec::Exec("nosuchprogram {input}".into()));
    request.cases = 5;
    let report = run(&request).unwrap();
    assert_eq!(report.exit_code(), 2);
    let error = report.error.as_ref().unwrap();
    assert!(error.on_every_input);
    assert!(!report.to_string().contains("the input that triggers it"));
}

#[test]
fn the_rule_placeholder_says_what_is_asked() {
    for (rule, convention, word) in [
        (Some(RuleChoice::Watertight), None, "watertight"),
        (Some(RuleChoice::CrackFree), None, "crack-free"),
        (
            Some(RuleChoice::Exact(FillRule::BottomLeft)),
            None,
            "bottom-left",
        ),
        (
            None,
            Some(ConventionChoice::Exact(LineConvention::PixelIndex)),
            "pixel-index",
        ),
    ] {
        let mut request =
            CheckRequest::new(SubjectSpec::Exec("echo rule={rule} >&2; exit 3".into()));
        request.rule = rule;
        request.convention = convention;
        request.kind = convention.map(|_| Kind::Lines);
        request.cases = 1;
        let report = run(&request).unwrap();
        let message = &report.error.as_ref().unwrap().message;
        assert!(
            message.contains(&format!("rule={word}\n"))
                || message.ends_with(&format!("rule={word}")),
            "{message}"
        );
    }
    let err = "nosuch".parse::<RuleChoice>().unwrap_err().to_string();
    for name in [
        "top-left",
        "top-right",
        "bottom-left",
        "watertight",
        "crack-free",
        "any",
    ] {
        assert!(err.contains(name), "{err}");
    }
}

#[test]
fn a_line_failure_is_diagnosed() {
    let bresenham = line_backend("bresenham").unwrap();
    let case = Case {
        width: 8,
        height: 8,
        triangles: Vec::new(),
        lines: vec![[(0.5, 0.5), (6.5, 3.5)]],
        ..Case::default()
    };
    let mut drawn = line_fragments(bresenham, &case);
    drawn.retain(|f| f.x != 3);
    drawn.push(frag(3, 5, 0));
    let finding =
        rasterlab::check::judge(Property::Line(LineConvention::Midpoint), &case, &drawn).unwrap();
    let d = finding.diagnosis.unwrap();
    assert!(d.contains("in column 3"), "{d}");
    assert!(d.contains("the subject drew (3, 5)"), "{d}");
}

#[test]
fn the_midpoint_convention_is_the_documented_one() {
    // Endpoints on pixel corners: the columns of the pixels containing the
    // ends' x; each column's row nearest the line, a tie to the smaller
    // row for a horizontal line (the statement of docs/check.md).
    let bresenham = line_backend("bresenham").unwrap();
    let pixels = |line: [(f64, f64); 2]| {
        let mut f = line_fragments(
            bresenham,
            &Case {
                width: 8,
                height: 8,
                triangles: Vec::new(),
                lines: vec![line],
                ..Case::default()
            },
        );
        f.sort();
        f.iter().map(|f| (f.x, f.y)).collect::<Vec<_>>()
    };
    assert_eq!(
        pixels([(0.0, 2.0), (3.0, 2.0)]),
        [(0, 1), (1, 1), (2, 1), (3, 1)]
    );
    assert_eq!(
        pixels([(1.0, 0.0), (1.0, 3.0)]),
        [(0, 0), (0, 1), (0, 2), (0, 3)]
    );
}

#[test]
fn the_readme_states_the_protocol() {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let section = readme
        .split("## Check your own rasterizer")
        .nth(1)
        .unwrap()
        .split("\n## ")
        .next()
        .unwrap();
    assert!(!section.contains("`x y t`"));
    assert!(section.contains("`x y id`"));
    assert!(section.contains("`x0 y0 x1 y1 x2 y2`"));
    assert!(section.contains("y down"));
    assert!(section.contains("pixel centres at +0.5"));
    assert!(!section.contains("the text format of `rasterlab fragments`"));
}

// ---------------------------------------------------------------------
// Which rule, crack-free, graders' options, pixel-index lines, overflow.

#[test]
fn the_rule_table_names_each_of_the_seven_rules_and_none() {
    for rule in FillRule::ALL {
        let mut request = CheckRequest::new(SubjectSpec::Exec(format!(
            "{} fragments --backend scanline --rule {} --size {{width}}x{{height}} {{input}}",
            env!("CARGO_BIN_EXE_rasterlab"),
            rule.name()
        )));
        request.rule = Some(RuleChoice::Any);
        request.cases = 60;
        request.jobs = 2;
        let report = run(&request).unwrap();
        let table = report.rules.as_ref().unwrap();
        assert_eq!(table.followed, [rule.name()], "{report}");
        let watertight = FillRule::WATERTIGHT.contains(&rule);
        assert_eq!(
            table.watertight.as_ref().map(|r| r.agreeing == r.total),
            Some(watertight)
        );
        assert_eq!(
            table.crack_free.as_ref().map(|r| r.agreeing == r.total),
            Some(watertight)
        );
        assert_eq!(report.exit_code(), 0);
    }
    // Top-left for even triangles, bottom-right for odd ones: no rule.
    let scanline = triangle_backend("scanline").unwrap();
    let mixed = |c: &Case| -> Result<Vec<Fragment>, SubjectError> {
        let tl = triangle_fragments(scanline, c, FillRule::TopLeft);
        let br = triangle_fragments(scanline, c, FillRule::BottomRight);
        Ok(tl
            .into_iter()
            .filter(|f| f.id % 2 == 0)
            .chain(br.into_iter().filter(|f| f.id % 2 == 1))
            .collect())
    };
    let mut request = CheckRequest::new(SubjectSpec::Backend("mixed".into()));
    request.rule = Some(RuleChoice::Any);
    request.cases = 60;
    request.shrink_runs = 40;
    let report = rasterlab::check::run_with(&request, "mixed", &move || {
        Box::new(mixed) as Box<dyn rasterlab::check::Subject + Send>
    })
    .unwrap();
    let table = report.rules.as_ref().unwrap();
    assert!(table.followed.is_empty(), "{report}");
    assert!(report.to_string().contains("follows: none"), "{report}");
    let shrunk = report.counterexample.as_ref().unwrap();
    assert!(shrunk.primitives <= 3, "{report}");
    assert_eq!(report.exit_code(), 1);
}

#[test]
fn crack_free_asks_only_about_shared_edges() {
    let scanline = triangle_backend("scanline").unwrap();
    // Only the pixels whose centre lies on an edge of their triangle: no
    // crack, but the insides are empty.
    let edges_only = |c: &Case| -> Result<Vec<Fragment>, SubjectError> {
        let snapped = c.snapped_triangles();
        Ok(triangle_fragments(scanline, c, FillRule::TopLeft)
            .into_iter()
            .filter(|f| {
                let t = rasterlab::raster::TriangleSetup::new(
                    f.id,
                    snapped[f.id as usize],
                    FillRule::TopLeft,
                )
                .unwrap();
                t.edge_values_at_pixel(f.x, f.y).contains(&0)
            })
            .collect())
    };
    assert!(passes(
        check(&options(Property::CrackFree, 150, 0), &mut { edges_only }).unwrap()
    ));
    let Verdict::Fail { finding, .. } =
        check(&options(Property::Watertight, 150, 0), &mut { edges_only }).unwrap()
    else {
        panic!("an empty inside passed as watertight");
    };
    assert!(
        finding.problems[0].starts_with("gap"),
        "{:?}",
        finding.problems
    );
    for (rule, word) in [
        (FillRule::Inclusive, "double draw"),
        (FillRule::Exclusive, "gap"),
    ] {
        let Verdict::Fail { finding, .. } = check(
            &options(Property::CrackFree, 150, 0),
            &mut Builtin::triangles(scanline, rule),
        )
        .unwrap() else {
            panic!("{rule} passed as crack-free");
        };
        assert!(
            finding.problems[0].starts_with(word),
            "{:?}",
            finding.problems
        );
    }
    for rule in FillRule::WATERTIGHT {
        assert!(passes(
            check(
                &options(Property::CrackFree, 150, 1),
                &mut Builtin::triangles(scanline, rule)
            )
            .unwrap()
        ));
    }
}

/// A rasterizer that truncates its edge values to 32 bits, as a production
/// rasterizer with 32-bit edge functions does; exact otherwise (top-left).
fn thirty_two_bits(c: &Case) -> Result<Vec<Fragment>, SubjectError> {
    let mut out = Vec::new();
    for (id, t) in c.snapped_triangles().iter().enumerate() {
        let Some(setup) = rasterlab::raster::TriangleSetup::new(id as u32, *t, FillRule::TopLeft)
        else {
            continue;
        };
        for y in 0..i64::from(c.height) {
            for x in 0..i64::from(c.width) {
                let e = setup.edge_values_at_pixel(x, y);
                if (0..3).all(|k| i64::from(e[k] as i32) + setup.bias[k] >= 0) {
                    out.push(frag(x, y, id as u32));
                }
            }
        }
    }
    Ok(out)
}

#[test]
fn the_overflow_family_finds_32_bit_edge_functions() {
    let Verdict::Fail { .. } =
        check(&options(Property::CrackFree, 70, 0), &mut thirty_two_bits).unwrap()
    else {
        panic!("32-bit edge functions passed");
    };
    // Every failure of 32-bit edge functions is in the families with far
    // vertices, and the overflow family fails most.
    let mut failing = std::collections::BTreeMap::new();
    let options = options(Property::Watertight, 140, 0);
    let mut rng = fastrand::Rng::with_seed(options.seed);
    for index in 0..options.cases {
        let case = rasterlab::check::generate_case(Property::Watertight, index, &mut rng);
        let drawn = thirty_two_bits(&case).unwrap();
        if rasterlab::check::judge(Property::Watertight, &case, &drawn).is_some() {
            *failing
                .entry(rasterlab::check::family(Property::Watertight, index))
                .or_insert(0) += 1;
        }
    }
    eprintln!("32-bit failures by family: {failing:?}");
    assert!(
        failing.keys().all(|f| ["huge", "overflow"].contains(f)),
        "{failing:?}"
    );
    assert!(
        failing.get("overflow").copied().unwrap_or(0) >= 10,
        "{failing:?}"
    );
}

#[test]
fn integer_bresenham_passes_the_pixel_index_convention() {
    for name in ["bresenham", "direct"] {
        let mut request = CheckRequest::new(SubjectSpec::Backend(name.into()));
        request.convention = Some(ConventionChoice::Exact(LineConvention::PixelIndex));
        request.cases = 300;
        let report = run(&request).unwrap();
        assert_eq!(report.exit_code(), 0, "{report}");
    }
    // The midpoint rule on the same numbers (corners, not centres) fails.
    let mut request = CheckRequest::new(SubjectSpec::Exec(format!(
        "{} fragments --backend bresenham --size {{width}}x{{height}} {{input}}",
        env!("CARGO_BIN_EXE_rasterlab")
    )));
    request.kind = Some(Kind::Lines);
    request.convention = Some(ConventionChoice::Exact(LineConvention::PixelIndex));
    request.cases = 60;
    request.shrink_runs = 30;
    let report = run(&request).unwrap();
    assert_eq!(report.exit_code(), 1, "{report}");
    assert!(report.counterexample.as_ref().unwrap().diagnosis.is_some());
}

fn schema() -> jsonschema::Validator {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/docs/check-report.schema.json"
    ))
    .unwrap();
    jsonschema::validator_for(&serde_json::from_str(&text).unwrap()).unwrap()
}

fn valid(schema: &jsonschema::Validator, json: &serde_json::Value) {
    let errors: Vec<String> = schema
        .iter_errors(json)
        .map(|e| format!("{e} at {}", e.instance_path()))
        .collect();
    assert!(errors.is_empty(), "{errors:#?}\n{json:#}");
}

#[test]
fn every_report_validates_against_the_schema_and_jobs_change_nothing() {
    let schema = schema();
    let bin = env!("CARGO_BIN_EXE_rasterlab");
    let dir = tempfile::tempdir().unwrap();
    let inclusive = format!(
        "{bin} fragments --backend scanline --rule inclusive --size {{width}}x{{height}} {{input}}"
    );
    let mut requests = Vec::new();
    let mut base = CheckRequest::new(SubjectSpec::Exec(inclusive.clone()));
    base.cases = 40;
    base.out = Some(dir.path().to_path_buf());
    base.command = "rasterlab check --exec ...".into();
    requests.push(base.clone());
    let mut keep = base.clone();
    keep.keep_going = true;
    keep.rule = Some(RuleChoice::Watertight);
    requests.push(keep.clone());
    let mut keep2 = keep.clone();
    keep2.jobs = 2;
    requests.push(keep2);
    let mut any = base.clone();
    any.rule = Some(RuleChoice::Any);
    any.keep_going = true;
    requests.push(any);
    let mut pass = CheckRequest::new(SubjectSpec::Backend("tiled".into()));
    pass.cases = 30;
    requests.push(pass.clone());
    let mut lines = CheckRequest::new(SubjectSpec::Backend("bresenham".into()));
    lines.convention = Some(ConventionChoice::Exact(LineConvention::Vulkan));
    lines.cases = 30;
    requests.push(lines);
    let mut broken = CheckRequest::new(SubjectSpec::Exec("echo hello".into()));
    broken.cases = 3;
    broken.out = Some(dir.path().join("broken"));
    requests.push(broken);
    let mut reports = Vec::new();
    for r in &requests {
        let report = run(r).unwrap();
        let json = serde_json::to_value(&report).unwrap();
        valid(&schema, &json);
        reports.push(json);
    }
    // Keep-going: per family, a score; the same with two jobs.
    let (one, two) = (&reports[1], &reports[2]);
    assert_eq!(one["cases_run"], 40);
    assert!(one["families"].as_array().unwrap().len() >= 5);
    assert!(one["score"].as_f64().unwrap() < 1.0);
    for key in [
        "verdict",
        "cases_run",
        "passed",
        "score",
        "families",
        "failing_cases",
        "counterexample",
    ] {
        assert_eq!(one[key], two[key], "{key}");
    }
    // Provenance in the files.
    let text = std::fs::read_to_string(dir.path().join("counterexample.txt")).unwrap();
    assert!(
        text.contains("# command: rasterlab check --exec ..."),
        "{text}"
    );
    assert!(text.contains("# seed 0, case "), "{text}");
    let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    assert!(html.contains("rasterlab check --exec ..."));
    assert!(html.contains("family"));
}

#[test]
fn a_case_file_is_judged_alone() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("case.txt");
    std::fs::write(&path, "# size 1x1\n0.5 0.5 9 -2.5 9 -2\n0.5 0.5 9 -2 8 9\n").unwrap();
    let mut request = CheckRequest::new(SubjectSpec::Exec(
        "python3 examples/student/rasterizer.py {input} {width} {height}".into(),
    ));
    request.rule = Some(RuleChoice::Watertight);
    request.case_file = Some(path.clone());
    let report = run(&request).unwrap();
    assert_eq!(report.cases_run, 1);
    assert_eq!(report.exit_code(), 1);
    assert_eq!(report.counterexample.as_ref().unwrap().family, "file");
    request.rule = Some(RuleChoice::Exact(FillRule::TopLeft));
    request.subject = SubjectSpec::Backend("scanline".into());
    assert_eq!(run(&request).unwrap().exit_code(), 0);
    request.kind = Some(Kind::Lines);
    request.rule = None;
    assert!(run(&request).is_err());
}

#[test]
fn ctrl_c_removes_the_temporary_files_and_a_missing_program_is_not_shrunk() {
    let tmp = tempfile::tempdir().unwrap();
    let bin = env!("CARGO_BIN_EXE_rasterlab");
    let mut child = Command::new(bin)
        .args([
            "check",
            "--exec",
            "sleep 20",
            "--timeout",
            "60",
            "--cases",
            "3",
            "--out",
        ])
        .arg(tmp.path().join("out"))
        .env("TMPDIR", tmp.path())
        .spawn()
        .unwrap();
    // Wait until the input folder exists, then interrupt.
    let start = std::time::Instant::now();
    while leftovers(tmp.path()).len() < 2 && start.elapsed().as_secs() < 30 {
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    assert_eq!(
        leftovers(tmp.path()).len(),
        2,
        "{:?}",
        leftovers(tmp.path())
    );
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130));
    assert_eq!(leftovers(tmp.path()), ["out"]);
    let out = rasterlab(&[
        "check",
        "--exec",
        "nosuchprogram {input}",
        "--out",
        &out_dir(tmp.path(), "missing"),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("on every input"), "{err}");
    assert!(!err.contains("the input that triggers it"), "{err}");
    let out = rasterlab(&["check", "--backend", "scanline", "--rule", "nosuch"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("watertight"));
}

#[test]
fn keep_going_json_validates_against_the_schema() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args([
            "check",
            "--exec",
            "python3 examples/student/rasterizer.py {input} {width} {height}",
            "--rule",
            "watertight",
            "--keep-going",
            "--jobs",
            "2",
            "--cases",
            "21",
            "--json",
            "--out",
        ])
        .arg(dir.path())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    valid(&schema(), &json);
    assert_eq!(json["cases_run"], 21);
    assert_eq!(json["keep_going"], true);
    assert!(json["command"].as_str().unwrap().contains("--keep-going"));
}

/// The Python adapters of `examples/adapters/`, the module each needs.
const ADAPTERS: [(&str, &str); 8] = [
    ("pillow", "PIL"),
    ("scikit_image", "skimage"),
    ("opencv", "cv2"),
    ("matplotlib_path", "matplotlib"),
    ("skia_path", "skia"),
    ("cairo_fill", "cairo"),
    ("rasterio_gdal", "rasterio"),
    ("protocol", "sys"),
];

#[test]
fn the_python_adapters_are_judged_not_broken() {
    let require = std::env::var("RASTERLAB_REQUIRE_PYTHON").is_ok_and(|v| v == "1");
    let schema = schema();
    for (adapter, module) in ADAPTERS.iter().filter(|a| a.0 != "protocol") {
        let present = Command::new("python3")
            .args(["-c", &format!("import numpy, {module}")])
            .output()
            .is_ok_and(|o| o.status.success());
        if !present {
            // pycairo needs cairo's headers to build: not required.
            assert!(
                !require || *module == "cairo",
                "RASTERLAB_REQUIRE_PYTHON=1 but python3 cannot import {module}"
            );
            eprintln!("SKIPPED: the {adapter} adapter (python3 cannot import {module})");
            continue;
        }
        let mut request = CheckRequest::new(SubjectSpec::Exec(format!(
            "python3 examples/adapters/{adapter}.py {{input}} {{width}} {{height}}"
        )));
        request.rule = Some(RuleChoice::Any);
        request.cases = 10;
        request.shrink_runs = 3;
        let json = serde_json::to_value(run(&request).unwrap()).unwrap();
        valid(&schema, &json);
        assert_ne!(json["verdict"], "broken", "{adapter}: {json:#}");
        eprintln!("{adapter}: follows {}", json["rules"]["followed"]);
    }
}

/// The `peer_adapters` example beside this test's executable: `cargo
/// test` builds it, as does `cargo build --release --example
/// peer_adapters`.
fn peer_adapters() -> Option<std::path::PathBuf> {
    let exe = std::env::current_exe().ok()?;
    let profile = exe.parent()?.parent()?;
    let path = profile
        .join("examples")
        .join(format!("peer_adapters{}", std::env::consts::EXE_SUFFIX));
    path.is_file().then_some(path)
}

#[test]
fn opengl_through_egl_follows_the_bottom_left_rule() {
    const TEST: &str = "opengl_through_egl_follows_the_bottom_left_rule";
    const REQUIRED: &str = "RASTERLAB_REQUIRE_MESA";
    let Some(adapter) = peer_adapters() else {
        common::part_missing(
            TEST,
            "the peer_adapters example (cargo build --release --example peer_adapters)",
            REQUIRED,
        );
        return;
    };
    // One triangle first: is there an OpenGL at all? Pixel (0, 0)'s
    // centre is inside, (1, 0)'s on the hypotenuse (a right edge).
    let dir = tempfile::tempdir().unwrap();
    let probe = dir.path().join("probe.txt");
    std::fs::write(&probe, "# size 2x2\n0 0 2 0 0 2\n").unwrap();
    let out = Command::new(&adapter)
        .arg("opengl")
        .arg(&probe)
        .args(["2", "2"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    if !out.status.success() {
        assert!(err.contains("OpenGL unavailable"), "{err}");
        common::part_missing(
            TEST,
            &format!("OpenGL through EGL ({})", err.trim()),
            REQUIRED,
        );
        return;
    }
    assert_eq!(String::from_utf8_lossy(&out.stdout), "0 0 0\n");
    let out = rasterlab(&[
        "check",
        "--rule",
        "any",
        "--cases",
        "60",
        "--jobs",
        "2",
        "--json",
        "--exec",
        // 60 cases: six of each exact family, overflow included.
        &format!(
            "{} opengl {{input}} {{width}} {{height}}",
            adapter.display()
        ),
        "--out",
        dir.path().join("out").to_str().unwrap(),
    ]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    valid(&schema(), &json);
    assert_eq!(out.status.code(), Some(0), "{json:#}");
    let rules = &json["rules"];
    assert_eq!(
        rules["followed"],
        serde_json::json!(["bottom-left"]),
        "{json:#}"
    );
    for property in ["watertight", "crack_free"] {
        assert_eq!(
            rules[property]["agreeing"], rules[property]["total"],
            "{json:#}"
        );
    }
}

/// Every coordinate of the primitives' paths in a picture.
fn primitive_coordinates(svg: &str) -> Vec<f64> {
    svg.split("<path class=\"primitive\"")
        .skip(1)
        .flat_map(|p| {
            let start = p.find(" d=\"").unwrap() + 4;
            let end = start + p[start..].find('"').unwrap();
            p[start..end]
                .split([' ', ',', 'M', 'L'])
                .filter(|v| !v.is_empty())
                .map(|v| v.parse::<f64>().unwrap())
                .collect::<Vec<_>>()
        })
        .collect()
}

#[test]
fn the_counterexample_picture_labels_clips_and_uses_the_palette() {
    use rasterlab::check::judge;
    use rasterlab::teaching::{triangle_colour, Role};
    let scanline = triangle_backend("scanline").unwrap();
    // Two triangles sharing a diagonal; one fragment missing, one drawn
    // off the target, left of it.
    let case = Case::from_text("# size 3x2\n0 0 3 0 0 2\n3 0 3 2 0 2\n").unwrap();
    let mut drawn = triangle_fragments(scanline, &case, FillRule::TopLeft);
    let gone = drawn.remove(0);
    drawn.push(Fragment::at(-1, 0, 1));
    let finding = judge(Property::Exact(FillRule::TopLeft), &case, &drawn).unwrap();
    let svg = finding.to_svg();
    // The palette's colours, none of the old private ones.
    for role in [Role::Correct, Role::Extra, Role::Missing, Role::OffTarget] {
        assert!(svg.contains(&role.hex()), "{role:?}");
    }
    for old in ["#86c98a", "#e0524d", "#f2b233", "#1d4ed8", "#e8e8e8"] {
        assert!(!svg.contains(old), "{old}");
    }
    assert!(svg.contains(&format!(
        "data-x=\"{}\" data-y=\"{}\" data-role=\"missing\"",
        gone.x, gone.y
    )));
    assert!(svg.contains("data-x=\"-1\" data-y=\"0\" data-role=\"extra\""));
    // A colour and a label per triangle and per vertex.
    for (i, name) in ["t0", "t1"].iter().enumerate() {
        let [r, g, b] = triangle_colour(i);
        let colour = format!("#{r:02x}{g:02x}{b:02x}");
        assert!(
            svg.contains(&format!("stroke=\"{colour}\"")),
            "{name} {colour}"
        );
        assert!(svg.contains(&format!("fill=\"{colour}\" stroke=\"white\" stroke-width=\"3\" paint-order=\"stroke\">{name}</text>")));
    }
    assert_ne!(triangle_colour(0), triangle_colour(1));
    assert_eq!(svg.matches("class=\"vertex-label\"").count(), 6);
    for k in 0..3 {
        assert_eq!(svg.matches(&format!(">v{k}</text>")).count(), 2, "v{k}");
    }
    // Pixel indices on both axes, over the target and its margin of 3.
    assert_eq!(svg.matches("class=\"column\"").count(), 3 + 6);
    assert_eq!(svg.matches("class=\"row\"").count(), 2 + 6);
    assert!(svg.contains(">-3</text>") && svg.contains(">5</text>"));
    // The legend, in the picture: the cell colours and the triangles.
    assert!(svg.contains("<g class=\"legend\" data-palette=\"okabe-ito\">"));
    assert!(svg.contains("t0: v0 (0, 0), v1 (3, 0), v2 (0, 2)"), "{svg}");
    assert!(svg.contains("t1: v0 (3, 0), v1 (3, 2), v2 (0, 2)"), "{svg}");
    assert!(svg.contains(Role::OffTarget.label()));
    // Big enough for a person.
    let size = |attribute: &str| -> f64 {
        let start = svg.find(&format!("{attribute}=\"")).unwrap() + attribute.len() + 2;
        svg[start..start + svg[start..].find('"').unwrap()]
            .parse()
            .unwrap()
    };
    assert!(size("width") >= 256.0 && size("height") >= 256.0);
    // The page shows the picture and its legend.
    let html = finding.to_html();
    assert!(html.contains(&svg));

    // A triangle of the overflow family, vertices 9,000 px off a 1x1
    // target: clipped to the view (40 px cells, 3 of margin), its
    // vertices named in the legend.
    let far = Case::from_text(
        "# size 1x1\n-9075 -73.5 -9073.66796875 -73.59375 3991.6953125 33.08984375\n",
    )
    .unwrap();
    let finding = judge(
        Property::Exact(FillRule::BottomLeft),
        &far,
        &[Fragment::at(0, 0, 0)],
    )
    .unwrap();
    let svg = finding.to_svg();
    let coordinates = primitive_coordinates(&svg);
    assert!(!coordinates.is_empty(), "{svg}");
    assert!(
        coordinates.iter().all(|v| (-120.0..=160.0).contains(v)),
        "{coordinates:?}"
    );
    // v0 and v1 lie 0.17 px apart, 9,000 px to the left: one label.
    assert!(svg.contains(">v0, v1 (off view)</text>"), "{svg}");
    assert!(svg.contains(">v2 (off view)</text>"), "{svg}");
    assert!(svg.contains("v0 (-9075, -73.5), v1 (-9073.66796875, -73.59375)"));
}

/// Twice the signed area of a snapped triangle, in subpixel units squared.
fn snapped_area(t: &[rasterlab::raster::FixedPoint; 3]) -> i128 {
    let p = |k: usize| (i128::from(t[k].x.raw()), i128::from(t[k].y.raw()));
    let ((ax, ay), (bx, by), (cx, cy)) = (p(0), p(1), p(2));
    (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
}

#[test]
fn the_zero_area_family_makes_triangles_of_zero_snapped_area() {
    let property = Property::Exact(FillRule::TopLeft);
    let at = rasterlab::check::families(property)
        .iter()
        .position(|f| *f == "zero-area")
        .unwrap() as u32;
    let (mut made, mut off_grid, mut between) = (0, 0, 0);
    for seed in 0..50 {
        let mut rng = fastrand::Rng::with_seed(seed);
        for k in 0..40 {
            let case = rasterlab::check::generate_case(property, at + 10 * k, &mut rng);
            let snapped = case.snapped_triangles();
            assert_eq!(
                snapped_area(&snapped[0]),
                0,
                "seed {seed}, case {}: {}",
                at + 10 * k,
                case.to_text()
            );
            // The other triangle is a normal one, most of the time.
            made += 1;
            let c = case.triangles[0][2];
            if (c.0 * 256.0).fract() != 0.0 {
                off_grid += 1;
            }
            let [a, b, s] = snapped[0];
            let inside = |p: i64, q: i64, r: i64| p.min(q) < r && r < p.max(q);
            if inside(a.x.raw(), b.x.raw(), s.x.raw()) || inside(a.y.raw(), b.y.raw(), s.y.raw()) {
                between += 1;
            }
        }
    }
    // Not a degenerate family: the third vertex is given off the grid,
    // and often lies strictly between the first two.
    assert_eq!(made, 2000);
    assert!(off_grid > 1900, "{off_grid}");
    assert!(between > 50, "{between}");
}

/// A case file is input like any other: a vertex that is not a finite
/// number, or lies past the guard band, is an error naming the file and
/// its line (exit 2), not a case to judge (a NaN would pass any subject,
/// and a vertex 40,000 px out would blame a correct one for overflow);
/// so are a target of zero pixels and one past the size limit, each
/// named as such.
#[test]
fn a_case_file_with_a_vertex_no_subject_can_draw_is_refused() {
    let dir = std::env::temp_dir().join(format!("rasterlab-bad-case-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text, says) in [
        (
            "nan.txt",
            "# size 4x3\n0.5 0.5 3.5 NaN 0.5 2.5\n",
            "line 2: ",
        ),
        (
            "inf.txt",
            "# size 4x3\n# a comment\n0.5 0.5 inf 0.5 0.5 2.5\n",
            "line 3: ",
        ),
        (
            "far.txt",
            "# size 4x3\n0.5 0.5 40000 0.5 0.5 2.5\n",
            "line 2: ",
        ),
        (
            "zero.txt",
            "# size 0x3\n0.5 0.5 3.5 0.5 0.5 2.5\n",
            "at least one pixel",
        ),
        (
            "huge.txt",
            "# size 99999x99999\n0.5 0.5 3.5 0.5 0.5 2.5\n",
            "huge.txt",
        ),
    ] {
        refused_naming_the_file(&dir, "--case", name, text, says);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `check --backend scanline OPTION FILE`, FILE `name` in `dir` holding
/// `text`: refused with exit 2, the file and `says` named, no panic.
fn refused_naming_the_file(
    dir: &std::path::Path,
    option: &str,
    name: &str,
    text: &str,
    says: &str,
) {
    let file = dir.join(name);
    std::fs::write(&file, text).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args(["check", "--backend", "scanline", option])
        .arg(&file)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{name}: {err}");
    assert!(err.contains(name) && err.contains(says), "{name}: {err}");
    assert!(!err.contains("panicked"), "{err}");
}

/// A value a configuration names wrongly is reported as that file's
/// error (exit 2), not as an option the user never gave.
#[test]
fn a_wrong_value_in_a_configuration_names_its_file() {
    let dir = std::env::temp_dir().join(format!("rasterlab-bad-config-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text, says) in [
        ("rule.json", r#"{"rule": "top-lef"}"#, "top-lef"),
        ("timeout.json", r#"{"timeout": 0}"#, "timeout"),
    ] {
        refused_naming_the_file(&dir, "--config", name, text, says);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

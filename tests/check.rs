//! `rasterlab::check` checked: the built-in back-ends pass on many seeds,
//! mutants of them are caught with counterexamples of at most three
//! primitives, and an outside program passes and fails as it should
//! through `rasterlab check --exec`.

mod common;
use common::rasterlab;

use rasterlab::check::judge::LineConvention;
use rasterlab::check::{
    check, line_fragments, triangle_fragments, Builtin, Case, CheckOptions, Fragment, Property,
    SubjectError, Verdict,
};
use rasterlab::raster::backend::{line_backend, triangle_backend, triangle_backends};
use rasterlab::raster::edge::FillRule;

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
            .map(|t| rasterlab::raster::edge::TriangleSetup::signed_area(*t) > 0)
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

fn out_dir(name: &str) -> String {
    let dir = std::env::temp_dir().join(format!("rasterlab-check-{}-{name}", std::process::id()));
    dir.to_str().unwrap().to_string()
}

#[test]
fn an_outside_program_passes_and_fails_through_exec() {
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
        &out_dir("good"),
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
        &out_dir("br"),
    ]);
    assert_eq!(out.status.code(), Some(0));
    // Inclusive drawing checked as watertight: a double draw, shrunk,
    // written out, and the written counterexample fails again when rerun.
    let inclusive = format!(
        "{bin} fragments --backend scanline --rule inclusive --size {{width}}x{{height}} {{input}}"
    );
    let dir = out_dir("inclusive");
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
    assert!(stdout.contains("diagnosis: double draw"), "{stdout}");
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
        rasterlab::check::program::parse_fragments(&String::from_utf8(rerun.stdout).unwrap())
            .unwrap();
    assert!(rasterlab::check::judge::judge(Property::Watertight, &case, &drawn).is_some());
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
    assert!(!v["extra"].as_array().unwrap().is_empty());
}

#[test]
fn a_broken_program_exits_2_with_the_input_that_breaks_it() {
    for (command, message) in [
        ("exit 3", "the program failed"),
        ("echo hello world", "is not `x y id`"),
        ("/nonexistent/program {input}", "the program failed"),
        ("sleep 30", "longer than 0.5 s"),
    ] {
        let dir = out_dir("broken");
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
        &out_dir("yes"),
    ]);
    assert_eq!(out.status.code(), Some(2));
    // Huge and negative numbers are defects of the program, reported.
    let out = rasterlab(&[
        "check",
        "--exec",
        "echo 99999999999999999999999 -5 0",
        "--cases",
        "1",
        "--out",
        &out_dir("huge"),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stdout).contains("outside the"));
}

//! `check --format gradescope` and `--format junit` against the shapes
//! their readers document: Gradescope's `results.json` (a top-level
//! `score`, `output` and `tests`; each test `name`, `number`, `score`,
//! `max_score`, `status`, `output`) and JUnit XML as Jenkins and GitLab
//! read it (`testsuites` > `testsuite` with `tests`, `failures`, `errors`
//! and `skipped` > `testcase` with `classname` and `name`, holding a
//! `failure` or an `error` with `message` and `type`). Each is checked on
//! a passing subject, a failing one, one that crashes on some cases
//! (partial credit: the crash costs those cases only) and one broken on
//! every input.

mod common;

use common::{part_missing, rasterlab};
use rasterlab::check::{
    generate_case, gradescope, junit, run_with, Builtin, Case, CheckReport, CheckRequest,
    FailureKind, Fragment, Property, Subject, SubjectError, SubjectSpec, VerdictWord,
};
use rasterlab::raster::{triangle_backend, FillRule};
use std::process::Command;

/// Gradescope's `results.json` fields as its autograder documentation
/// lists them (those this report uses; no other key allowed).
fn gradescope_schema() -> jsonschema::Validator {
    let schema = serde_json::json!({
        "type": "object",
        "additionalProperties": false,
        "required": ["score", "output", "tests"],
        "properties": {
            "score": { "type": "number", "minimum": 0 },
            "output": { "type": "string" },
            "tests": {
                "type": "array",
                "items": {
                    "type": "object",
                    "additionalProperties": false,
                    "required": ["name", "number", "score", "max_score", "status", "output"],
                    "properties": {
                        "name": { "type": "string" },
                        "number": { "type": "string" },
                        "score": { "type": "number", "minimum": 0 },
                        "max_score": { "type": "number", "minimum": 0 },
                        "status": { "enum": ["passed", "failed"] },
                        "output": { "type": "string" }
                    }
                }
            }
        }
    });
    jsonschema::validator_for(&schema).unwrap()
}

/// A report of 60 cases, every case run, of the subject `make` makes.
fn report(make: &(dyn Fn() -> Box<dyn Subject + Send> + Sync)) -> CheckReport {
    let mut request = CheckRequest::new(SubjectSpec::Backend(String::new()));
    request.cases = 60;
    request.keep_going = true;
    request.command =
        "rasterlab check --exec ./mine --format gradescope --out /autograder/results/check".into();
    run_with(&request, "mine", make).unwrap()
}

fn passing() -> CheckReport {
    let bbox = triangle_backend("bbox").unwrap();
    report(&move || Box::new(Builtin::triangles(bbox, FillRule::TopLeft)))
}

fn failing() -> CheckReport {
    let bbox = triangle_backend("bbox").unwrap();
    report(&move || Box::new(Builtin::triangles(bbox, FillRule::Inclusive)))
}

/// Broken on every input: it fails whatever it is given.
fn broken() -> CheckReport {
    report(&|| {
        Box::new(|_: &Case| -> Result<Vec<Fragment>, SubjectError> {
            Err(SubjectError::Failed {
                status: "exit status: 1".into(),
                stderr: "IndexError: <list> & \u{7} index out of range".into(),
            })
        })
    })
}

/// True when some triangle of the case has zero area once snapped.
fn has_zero_snapped_area(case: &Case) -> bool {
    case.snapped_triangles().iter().any(|[a, b, c]| {
        let (ax, ay) = (i128::from(a.x.raw()), i128::from(a.y.raw()));
        let (bx, by) = (i128::from(b.x.raw()), i128::from(b.y.raw()));
        let (cx, cy) = (i128::from(c.x.raw()), i128::from(c.y.raw()));
        (bx - ax) * (cy - ay) - (by - ay) * (cx - ax) == 0
    })
}

/// The student of the issue: correct (the top-left rule, exactly), but it
/// divides by the snapped area, so it crashes on every case holding a
/// triangle of zero snapped area.
fn divides_by_the_area() -> Box<dyn Subject + Send> {
    let bbox = triangle_backend("bbox").unwrap();
    Box::new(move |c: &Case| -> Result<Vec<Fragment>, SubjectError> {
        if has_zero_snapped_area(c) {
            return Err(SubjectError::Failed {
                status: "exit status: 1".into(),
                stderr: "ZeroDivisionError: float division by zero".into(),
            });
        }
        Builtin::triangles(bbox, FillRule::TopLeft).draw(c)
    })
}

/// The cases of the 60 that hold a triangle of zero snapped area.
fn zero_area_cases() -> Vec<u32> {
    let property = Property::Exact(FillRule::TopLeft);
    let mut rng = fastrand::Rng::with_seed(0);
    (0..60)
        .filter(|&i| has_zero_snapped_area(&generate_case(property, i, &mut rng)))
        .collect()
}

#[test]
fn a_crash_costs_its_case_only_in_every_format() {
    let crashing = zero_area_cases();
    assert!(!crashing.is_empty() && crashing.len() < 30, "{crashing:?}");
    let report = report(&divides_by_the_area);
    let held = 60 - crashing.len() as u32;
    // The report: every other case scored, each crash a failed case.
    assert_eq!(report.verdict, VerdictWord::Fail);
    assert_eq!(report.exit_code(), 1);
    assert!(report.error.is_none());
    assert_eq!(report.passed, held);
    let failed: Vec<u32> = report.failing_cases.iter().map(|f| f.case_index).collect();
    assert_eq!(failed, crashing);
    for f in &report.failing_cases {
        assert_eq!(f.kind, FailureKind::NoAnswer);
        assert!(f.problem.contains("ZeroDivisionError"), "{}", f.problem);
        // Shown with its input, which crashes it again.
        let input = Case::from_text(f.input.as_deref().unwrap()).unwrap();
        assert!(has_zero_snapped_area(&input));
    }
    // Each failing family has its shrunk input: one triangle of zero area.
    let families: Vec<&str> = report
        .families
        .iter()
        .filter(|t| t.passed < t.total)
        .map(|t| t.family.as_str())
        .collect();
    assert!(!families.is_empty());
    assert_eq!(report.counterexamples.len(), families.len());
    for (c, family) in report.counterexamples.iter().zip(&families) {
        assert_eq!(c.family, *family);
        assert_eq!(c.kind, FailureKind::NoAnswer);
        assert_eq!(c.primitives, 1, "{}", c.input);
        assert!(has_zero_snapped_area(&Case::from_text(&c.input).unwrap()));
    }
    // Text, JSON, Gradescope and JUnit agree on the score.
    let text = report.to_string();
    assert!(text.contains(&format!("score: {held}/60 cases")), "{text}");
    assert!(
        text.contains(&format!("no answer on {} case(s)", crashing.len())),
        "{text}"
    );
    let json: serde_json::Value = serde_json::to_value(&report).unwrap();
    assert_eq!(json["passed"], held);
    let results = gradescope(&report);
    assert_eq!(results["score"].as_f64().unwrap(), f64::from(held));
    let tests = results["tests"].as_array().unwrap();
    assert_eq!(tests.len(), report.families.len());
    for t in tests {
        let out = t["output"].as_str().unwrap();
        let family = t["name"].as_str().unwrap().trim_start_matches("family ");
        if families.contains(&family) {
            assert_eq!(t["status"], "failed");
            assert!(out.contains("ZeroDivisionError"), "{out}");
            assert!(out.contains("shrunk counterexample"), "{out}");
        } else {
            assert_eq!(t["status"], "passed", "{out}");
        }
    }
    let xml = junit(&report);
    let doc = roxmltree::Document::parse(&xml).unwrap();
    let failures = doc
        .descendants()
        .filter(|n| n.has_tag_name("failure"))
        .count();
    assert_eq!(failures, families.len(), "{xml}");
    assert_eq!(
        doc.descendants()
            .filter(|n| n.has_tag_name("error"))
            .count(),
        0
    );
}

#[test]
fn every_failing_family_shows_its_own_shrunk_counterexample() {
    // The inclusive rule under top-left fails in several families.
    let report = failing();
    let families: Vec<&str> = report
        .families
        .iter()
        .filter(|t| t.passed < t.total)
        .map(|t| t.family.as_str())
        .collect();
    assert!(families.len() >= 2, "{families:?}");
    let shown: Vec<&str> = report
        .counterexamples
        .iter()
        .map(|c| c.family.as_str())
        .collect();
    assert_eq!(shown, families);
    let results = gradescope(&report);
    for t in results["tests"].as_array().unwrap() {
        if t["status"] == "failed" {
            let out = t["output"].as_str().unwrap();
            assert!(out.contains("shrunk counterexample (case "), "{out}");
            assert!(out.contains("# size "), "{out}");
        }
    }
    // The text lists the other families' counterexamples too.
    let text = report.to_string();
    for family in &families[1..] {
        assert!(text.contains(&format!("family {family}: case ")), "{text}");
    }
}

#[test]
fn gradescope_results_have_gradescopes_fields_a_test_per_family() {
    let schema = gradescope_schema();
    for (what, report) in [
        ("passing", passing()),
        ("failing", failing()),
        ("broken", broken()),
    ] {
        let results = gradescope(&report);
        if let Err(e) = schema.validate(&results) {
            panic!("{what}: {e}\n{results:#}");
        }
        let tests = results["tests"].as_array().unwrap();
        let sum: f64 = tests.iter().map(|t| t["score"].as_f64().unwrap()).sum();
        assert_eq!(results["score"].as_f64().unwrap(), sum, "{what}");
        for t in tests {
            let passed = t["score"] == t["max_score"];
            assert_eq!(t["status"] == "passed", passed, "{what}: {t}");
        }
        match what {
            "passing" => {
                assert_eq!(sum, 60.0);
                assert_eq!(tests.len(), report.families.len());
                assert!(tests.iter().all(|t| t["status"] == "passed"));
            }
            "failing" => {
                assert_eq!(sum, f64::from(report.passed));
                let failed: Vec<&serde_json::Value> =
                    tests.iter().filter(|t| t["status"] == "failed").collect();
                assert!(!failed.is_empty());
                for t in &failed {
                    let out = t["output"].as_str().unwrap();
                    // The cause, where it explains this family's failures,
                    // and the command that reruns it without the format.
                    assert!(
                        out.contains("cause: ties decided by the inclusive rule"),
                        "{out}"
                    );
                    assert!(
                        out.contains("rerun: rasterlab check --exec ./mine\n")
                            || out.ends_with("rerun: rasterlab check --exec ./mine"),
                        "{out}"
                    );
                }
                // The shrunk counterexample sits in its family's test.
                let family = &report.counterexample.as_ref().unwrap().family;
                let own = tests
                    .iter()
                    .find(|t| t["name"] == format!("family {family}"))
                    .unwrap();
                assert!(
                    own["output"].as_str().unwrap().contains("# size 1x1"),
                    "{own}"
                );
            }
            _ => {
                assert_eq!(tests.len(), 1);
                assert_eq!(tests[0]["name"], "the program runs");
                assert_eq!(tests[0]["status"], "failed");
                assert!(tests[0]["output"].as_str().unwrap().contains("IndexError"));
            }
        }
    }
}

#[test]
fn junit_xml_has_the_elements_jenkins_and_gitlab_read() {
    for (what, report) in [
        ("passing", passing()),
        ("failing", failing()),
        ("broken", broken()),
    ] {
        let xml = junit(&report);
        let doc = roxmltree::Document::parse(&xml).unwrap_or_else(|e| panic!("{what}: {e}\n{xml}"));
        let root = doc.root_element();
        assert_eq!(root.tag_name().name(), "testsuites", "{what}");
        let suites: Vec<_> = root.children().filter(|n| n.is_element()).collect();
        assert_eq!(suites.len(), 1, "{what}");
        let suite = suites[0];
        assert_eq!(suite.tag_name().name(), "testsuite");
        let number = |n: roxmltree::Node, a: &str| -> usize {
            n.attribute(a)
                .unwrap_or_else(|| panic!("{what}: no {a}"))
                .parse()
                .unwrap()
        };
        let cases: Vec<_> = suite
            .children()
            .filter(|n| n.has_tag_name("testcase"))
            .collect();
        assert_eq!(number(suite, "tests"), cases.len(), "{what}");
        assert_eq!(number(root, "tests"), cases.len(), "{what}");
        assert_eq!(number(suite, "skipped"), 0);
        let with = |tag: &str| {
            cases
                .iter()
                .filter(|c| c.children().any(|n| n.has_tag_name(tag)))
                .count()
        };
        assert_eq!(number(suite, "failures"), with("failure"), "{what}");
        assert_eq!(number(suite, "errors"), with("error"), "{what}");
        for c in &cases {
            assert!(c
                .attribute("classname")
                .is_some_and(|n| n.starts_with("rasterlab.check.")));
            assert!(c.attribute("name").is_some());
            for f in c.children().filter(|n| n.is_element()) {
                assert!(f.attribute("message").is_some() && f.attribute("type").is_some());
            }
        }
        match what {
            "passing" => assert_eq!(with("failure") + with("error"), 0),
            "failing" => {
                assert!(with("failure") > 0 && with("error") == 0);
                let failure = cases
                    .iter()
                    .flat_map(|c| c.children())
                    .find(|n| n.has_tag_name("failure"))
                    .unwrap();
                assert!(failure.text().unwrap().contains("cause:"), "{xml}");
            }
            _ => {
                assert_eq!((with("failure"), with("error")), (0, 1));
                // Escaped, and the control character XML forbids left out.
                let error = cases[0]
                    .children()
                    .find(|n| n.has_tag_name("error"))
                    .unwrap();
                let text = error.text().unwrap();
                assert!(text.contains("IndexError: <list> &"), "{xml}");
                assert!(!text.contains('\u{7}'), "{xml}");
            }
        }
    }
}

#[test]
fn the_command_line_prints_each_format_and_runs_every_case() {
    for format in ["gradescope", "junit", "json", "text"] {
        let out = rasterlab(&[
            "check",
            "--backend",
            "scanline",
            "--rule",
            "inclusive",
            "--cases",
            "30",
            "--format",
            format,
            "--out",
            tempfile::tempdir().unwrap().path().to_str().unwrap(),
        ]);
        assert_eq!(out.status.code(), Some(0), "{format}");
        let text = String::from_utf8_lossy(&out.stdout);
        match format {
            "gradescope" => {
                let v: serde_json::Value = serde_json::from_str(&text).unwrap();
                assert_eq!(v["score"], 30.0);
            }
            "junit" => assert!(text.starts_with("<?xml") && text.contains("tests=\"")),
            "json" => assert!(text.contains("rasterlab-check-report/2")),
            _ => assert!(text.starts_with("PASS")),
        }
    }
    // A failing subject under a grader format (it draws nothing): every
    // case is run and scored, exit 1.
    let out = rasterlab(&[
        "check",
        "--exec",
        "true {input}",
        "--cases",
        "30",
        "--format",
        "gradescope",
        "--out",
        tempfile::tempdir().unwrap().path().to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let max: f64 = v["tests"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["max_score"].as_f64().unwrap())
        .sum();
    assert_eq!(max, 30.0);
    assert!(v["score"].as_f64().unwrap() < 30.0);
    // Without {input} or --persistent the program is not given the case:
    // said so, exit 2, not a diagnosis of what it drew.
    let out = rasterlab(&[
        "check",
        "--exec",
        "cat",
        "--cases",
        "10",
        "--out",
        tempfile::tempdir().unwrap().path().to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("not given the case") && err.contains("--persistent"),
        "{err}"
    );
    assert!(!err.contains("cause:"), "{err}");
    // The lab says the same, before it serves anything, and takes
    // --persistent (only with --exec).
    let lab = rasterlab(&["lab", "--port", "0", "--exec", "cat"]);
    assert_eq!(lab.status.code(), Some(2));
    let err = String::from_utf8_lossy(&lab.stderr);
    assert!(
        err.contains("{input}") && err.contains("--persistent"),
        "{err}"
    );
    let lab = rasterlab(&["lab", "--port", "0", "--persistent"]);
    assert_eq!(lab.status.code(), Some(2));
    let mut served = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args(["lab", "--port", "0", "--persistent", "--exec", "cat"])
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    std::io::BufRead::read_line(
        &mut std::io::BufReader::new(served.stdout.take().unwrap()),
        &mut first,
    )
    .unwrap();
    served.kill().unwrap();
    served.wait().unwrap();
    assert!(
        first.starts_with("rasterlab lab: http://127.0.0.1:"),
        "{first}"
    );
    let bad = rasterlab(&["check", "--backend", "bbox", "--format", "xml"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("gradescope"));
    let both = rasterlab(&["check", "--backend", "bbox", "--format", "junit", "--json"]);
    assert_eq!(both.status.code(), Some(2));
}

/// The Python starter as shipped, checked through the command line with
/// a configuration of `examples/graders/configs/`; its Gradescope
/// results.
fn starter_under(config: &str) -> serde_json::Value {
    let out = rasterlab(&[
        "check",
        "--config",
        &format!(
            "{}/examples/graders/configs/{config}",
            env!("CARGO_MANIFEST_DIR")
        ),
        "--persistent",
        "--exec",
        &format!(
            "python3 {}/examples/starters/python/rasterizer.py",
            env!("CARGO_MANIFEST_DIR")
        ),
        "--format",
        "gradescope",
        "--out",
        tempfile::tempdir().unwrap().path().to_str().unwrap(),
    ]);
    assert!(
        matches!(out.status.code(), Some(0 | 1)),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn the_example_configurations_weigh_the_families_and_score_the_starter() {
    let python = Command::new("python3")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !python {
        part_missing(
            "the example configurations against the Python starter",
            "python3",
            "RASTERLAB_REQUIRE_STARTERS",
        );
        return;
    }
    // The scores docs/check.md states.
    for (config, max, score) in [
        ("top-left.json", 100.0, 81.0),
        ("y-up.json", 100.0, 81.0),
        ("inclusive.json", 100.0, 100.0),
    ] {
        let results = starter_under(config);
        let tests = results["tests"].as_array().unwrap();
        let total: f64 = tests.iter().map(|t| t["max_score"].as_f64().unwrap()).sum();
        assert!((total - max).abs() < 1e-9, "{config}: {results:#}");
        let got = results["score"].as_f64().unwrap();
        assert!((got - score).abs() < 0.01, "{config}: {got}\n{results:#}");
    }
}

#[test]
fn a_configuration_sets_the_rule_cases_and_weights() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("course.json");
    std::fs::write(
        &path,
        r#"{ "rule": "inclusive", "cases": 40, "seed": 2, "weights": { "fan": 30, "ties": 0 } }"#,
    )
    .unwrap();
    let out = rasterlab(&[
        "check",
        "--config",
        path.to_str().unwrap(),
        "--backend",
        "bbox",
        "--format",
        "gradescope",
        "--out",
        dir.path().join("out").to_str().unwrap(),
    ]);
    // A back-end draws under the rule checked: the configuration's.
    assert_eq!(out.status.code(), Some(0));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let tests = v["tests"].as_array().unwrap();
    let test = |name: &str| tests.iter().find(|t| t["name"] == name).unwrap();
    assert_eq!(test("family fan")["max_score"], 30.0);
    assert_eq!(test("family ties")["max_score"], 0.0);
    assert_eq!(test("family ties")["score"], 0.0);
    // A family left out: one point a case (40 cases over 10 families).
    assert_eq!(test("family soup")["max_score"], 4.0);
    assert!(v["output"]
        .as_str()
        .unwrap()
        .contains("of 40 cases of seed 2"));
    // The command line wins over the file.
    let out = rasterlab(&[
        "check",
        "--config",
        path.to_str().unwrap(),
        "--rule",
        "top-left",
        "--cases",
        "20",
        "--backend",
        "bbox",
        "--out",
        dir.path().join("out").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("PASS: 20 cases"));
    // Mistakes are refused with what was expected, exit 2.
    for (text, expected) in [
        (r#"{ "rules": "top-left" }"#, "unknown field"),
        (r#"{ "weights": { "soups": 3 } }"#, "soup"),
        (r#"{ "weights": { "fan": -1 } }"#, "from 0 to"),
        (r#"{ "rule": "sideways" }"#, "top-left"),
        (r#"{ "timeout": 0 }"#, "--timeout"),
        (r#"{ "cases": "many" }"#, "u32"),
        ("{", "EOF"),
    ] {
        std::fs::write(&path, text).unwrap();
        let out = rasterlab(&[
            "check",
            "--config",
            path.to_str().unwrap(),
            "--backend",
            "bbox",
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{text}: {err}");
        assert!(err.contains(expected), "{text}: {err}");
        assert!(!err.contains("panicked"), "{text}: {err}");
    }
    let out = rasterlab(&["check", "--config", "no/such.json", "--backend", "bbox"]);
    assert_eq!(out.status.code(), Some(2));
}

//! The report in the formats graders read: Gradescope's `results.json`
//! and JUnit XML.
//!
//! Both give one test per case family (random soups, polygons, meshes,
//! needles, ...), scored by the cases of the family that hold, so that a
//! student sees which kind of input breaks their rasterizer; a failing
//! family's output carries its first problem, the named cause where it
//! explains that family's failures, its own shrunk counterexample (every
//! failing family has one) and the command that reruns it. A case the
//! program gave no answer to (it crashed, hung, answered `error` or
//! printed nonsense there) is one failed case of its family, shown with
//! the input that triggers it, shrunk; only a program that breaks so on
//! every input, the simplest included, is one failed test (JUnit: an
//! `error`) with what went wrong.
//!
//! - Gradescope (`results.json`, as its autograder documentation
//!   describes it): a top-level `score`, `output` and `tests`, each test
//!   with `name`, `number`, `score`, `max_score`, `status` (`passed` or
//!   `failed`) and `output`. A family is worth one point a case, or the
//!   points a teacher's configuration gives it (`check --config`), shared
//!   among its cases.
//! - JUnit XML, as Jenkins and GitLab read it: `testsuites`, one
//!   `testsuite` with `tests`, `failures`, `errors` and `skipped`, a
//!   `testcase` per family (`classname`, `name`), a failing one holding a
//!   `failure` with its `message` and `type` (the failure kind) and the
//!   details as text.
//!
//! ```
//! use rasterlab::check::{gradescope, junit, run, CheckRequest, SubjectSpec};
//!
//! let mut request = CheckRequest::new(SubjectSpec::Backend("bbox".into()));
//! request.cases = 20;
//! request.keep_going = true;
//! let report = run(&request).unwrap();
//! let results = gradescope(&report);
//! assert_eq!(results["score"], 20.0);
//! assert!(junit(&report).contains(r#"failures="0""#));
//! ```

use super::judge::FailureKind;
use super::request::{CheckReport, VerdictWord};
use crate::markup::escape;
use serde_json::{json, Value};
use std::fmt::Write as _;

/// How `rasterlab check` prints its report.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum ReportFormat {
    /// The text a person reads (the default).
    Text,
    /// rasterlab's JSON report (`docs/check-report.schema.json`).
    Json,
    /// Gradescope's `results.json`.
    Gradescope,
    /// JUnit XML.
    Junit,
}

crate::names::named_enum!(
    ReportFormat,
    "report format",
    Text = "text",
    Json = "json",
    Gradescope = "gradescope",
    Junit = "junit"
);

impl ReportFormat {
    /// Whether a grader reads it: such a check runs every case.
    pub fn for_graders(self) -> bool {
        matches!(self, ReportFormat::Gradescope | ReportFormat::Junit)
    }
}

/// One test of a grader's report.
pub(crate) struct GraderTest {
    pub(crate) name: String,
    pub(crate) passed: u32,
    pub(crate) total: u32,
    /// The points the test is worth, shared among its cases.
    pub(crate) points: f64,
    /// What a failure says in one line (JUnit's `message`).
    pub(crate) message: String,
    /// The failure kind (JUnit's `type`).
    pub(crate) kind: String,
    /// The details, several lines.
    pub(crate) output: String,
}

/// The tests: one per family; a broken subject is one test of its own.
fn tests(report: &CheckReport) -> Vec<GraderTest> {
    if let Some(e) = &report.error {
        return vec![GraderTest {
            name: "the program runs".into(),
            passed: 0,
            total: 1,
            points: 1.0,
            message: e
                .message
                .lines()
                .map(str::trim)
                .filter(|l| !l.is_empty())
                .collect::<Vec<_>>()
                .join(" "),
            kind: "broken".into(),
            output: format!(
                "{}\non case {} (family {}){}\nthe input that triggers it:\n{}",
                e.message,
                e.case_index,
                e.family,
                if e.on_every_input {
                    ", and on every input, the simplest included"
                } else {
                    ""
                },
                e.input
            ),
        }];
    }
    let cause = report
        .counterexample
        .as_ref()
        .and_then(|c| c.cause.as_ref());
    report
        .families
        .iter()
        .map(|t| {
            let failing: Vec<_> = report
                .failing_cases
                .iter()
                .filter(|f| f.family == t.family)
                .collect();
            let mut output = format!("{} of {} cases hold\n", t.passed, t.total);
            let (mut message, mut kind) = (String::new(), String::new());
            let unanswered = failing
                .iter()
                .filter(|f| f.kind == FailureKind::NoAnswer)
                .count();
            let own = report.counterexamples.iter().find(|c| c.family == t.family);
            if let Some(first) = failing.first() {
                message = format!("case {}: {}", first.case_index, first.problem);
                kind = first.kind.name().to_string();
                let _ = writeln!(output, "first failing case: {message}");
                if unanswered > 0 {
                    let _ = writeln!(
                        output,
                        "the program gave no answer on {unanswered} of this family's {} failing case(s); each costs only itself",
                        failing.len()
                    );
                }
                match (cause, t.explained_by_cause) {
                    (Some(c), Some(n)) if n > 0 => {
                        let _ = writeln!(
                            output,
                            "cause: {} (explains {n} of this family's {} failing case(s))",
                            c.description,
                            failing.len()
                        );
                    }
                    _ if unanswered == failing.len() => {}
                    _ if own.and_then(|c| c.cause.as_ref()).is_some() => {}
                    _ => {
                        let _ = writeln!(
                            output,
                            "cause: none in the catalogue explains this family's failures"
                        );
                    }
                }
            }
            let own = own.or(report
                .counterexample
                .as_ref()
                .filter(|c| c.family == t.family));
            if let Some(c) = own {
                if let Some(d) = &c.diagnosis {
                    let _ = writeln!(output, "diagnosis of its shrunk counterexample: {d}");
                }
                let _ = writeln!(
                    output,
                    "shrunk counterexample (case {}, {}; {} primitive(s) on {}x{}):\n{}",
                    c.case_index,
                    c.problems.first().map_or("", String::as_str),
                    c.primitives,
                    c.width,
                    c.height,
                    c.input
                );
            }
            if !failing.is_empty() {
                let _ = writeln!(output, "rerun: {}", rerun_command(&report.command));
            }
            GraderTest {
                name: format!("family {}", t.family),
                passed: t.passed,
                total: t.total,
                points: t.points,
                message,
                kind,
                output: output.trim_end().to_string(),
            }
        })
        .collect()
}

/// The command that reruns the check as a person reads it: the recorded
/// command without its grader format (so it stops at the first failure
/// and shrinks it) and without the grader's `--out` folder (the files go
/// to `check-output` where it is run).
pub(crate) fn rerun_command(command: &str) -> String {
    let words: Vec<&str> = command.split(' ').collect();
    let mut kept = Vec::new();
    let mut skip = false;
    for w in words {
        if skip {
            skip = false;
        } else if w == "--format" || w == "--out" {
            skip = true;
        } else if !w.starts_with("--format=") && !w.starts_with("--out=") {
            kept.push(w);
        }
    }
    kept.join(" ")
}

/// The summary line of the whole check.
fn summary(report: &CheckReport) -> String {
    let mut s = format!(
        "rasterlab check of {}: {} ({}), {} of {} cases of seed {} hold",
        report.subject,
        report.property,
        report.description,
        report.passed,
        report.cases_run,
        report.seed
    );
    if let Some(d) = report
        .counterexample
        .as_ref()
        .and_then(|c| c.diagnosis.as_ref())
    {
        let _ = write!(s, "\ndiagnosis: {d}");
    }
    if report.verdict == VerdictWord::Broken {
        s.push_str("\nthe program could not be judged");
    }
    s
}

/// Gradescope's `results.json`: a test per family, worth one point a
/// case or the family's weight ([`CheckConfig`](super::CheckConfig)).
pub fn gradescope(report: &CheckReport) -> Value {
    gradescope_of(tests(report), summary(report))
}

/// `results.json` of these tests under this summary.
pub(crate) fn gradescope_of(tests: Vec<GraderTest>, summary: String) -> Value {
    let tests: Vec<Value> = tests
        .into_iter()
        .enumerate()
        .map(|(i, t)| {
            json!({
                "name": t.name,
                "number": (i + 1).to_string(),
                "score": t.points * f64::from(t.passed) / f64::from(t.total.max(1)),
                "max_score": t.points,
                "status": if t.passed == t.total { "passed" } else { "failed" },
                "output": t.output,
            })
        })
        .collect();
    let score: f64 = tests
        .iter()
        .map(|t| t["score"].as_f64().unwrap_or(0.0))
        .sum();
    json!({
        "score": score,
        "output": summary,
        "tests": tests,
    })
}

/// XML text: escaped, and without the control characters XML 1.0 does
/// not allow (a program's standard error may hold any byte).
fn xml(text: &str) -> String {
    escape(
        &text
            .chars()
            .filter(|&c| !c.is_control() || matches!(c, '\n' | '\t' | '\r'))
            .collect::<String>(),
    )
}

/// JUnit XML: a testsuite of one testcase per family.
pub fn junit(report: &CheckReport) -> String {
    junit_of(
        &tests(report),
        &report.property,
        &summary(report),
        report.verdict == VerdictWord::Broken,
    )
}

/// JUnit XML of these tests, for the property named.
pub(crate) fn junit_of(
    tests: &[GraderTest],
    property: &str,
    summary: &str,
    broken: bool,
) -> String {
    let failed = tests.iter().filter(|t| t.passed < t.total).count();
    let (failures, errors) = if broken { (0, failed) } else { (failed, 0) };
    let suite = format!("rasterlab check: {property}");
    let mut out = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        out,
        "<testsuites name=\"rasterlab check\" tests=\"{}\" failures=\"{failures}\" errors=\"{errors}\">",
        tests.len()
    );
    let _ = writeln!(
        out,
        "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{failures}\" errors=\"{errors}\" skipped=\"0\">",
        xml(&suite),
        tests.len()
    );
    let _ = writeln!(out, "    <system-out>{}</system-out>", xml(summary));
    for t in tests {
        // The name stays the same from run to run (CI tracks a test by
        // it); the counts are in the failure's message.
        let _ = write!(
            out,
            "    <testcase classname=\"rasterlab.check.{}\" name=\"{}\"",
            xml(property),
            xml(&t.name),
        );
        if t.passed == t.total {
            out.push_str("/>\n");
            continue;
        }
        let tag = if broken { "error" } else { "failure" };
        let _ = writeln!(
            out,
            ">\n      <{tag} message=\"{}\" type=\"{}\">{}</{tag}>\n    </testcase>",
            xml(&format!(
                "{} of {} cases hold; {}",
                t.passed, t.total, t.message
            )),
            xml(&t.kind),
            xml(&t.output)
        );
    }
    out.push_str("  </testsuite>\n</testsuites>\n");
    out
}

//! The report as text: what `rasterlab check` prints.

use super::case::Origin;
use super::judge::FailureKind;
use super::property::with_samples;
use super::request::{CheckReport, VerdictWord};
use std::fmt::{self, Write as _};

/// The most lines of another family's counterexample printed.
const INPUT_LINES_SHOWN: usize = 12;

impl fmt::Display for CheckReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut out = String::new();
        if let Some(table) = &self.rules {
            match &table.watertight {
                Some(w) => {
                    let _ = writeln!(
                        out,
                        "Which rule: {} cases of seed {} (watertight and crack-free on the {} mesh cases)",
                        self.cases_run, self.seed, w.total
                    );
                }
                None => {
                    let _ = writeln!(
                        out,
                        "Which convention: {} cases of seed {} (screen conventions on the cases in screen coordinates, whole-pixel ones on the cases whose endpoints are pixel indices)",
                        self.cases_run, self.seed
                    );
                }
            }
            let lines = table.watertight.is_none();
            let _ = writeln!(
                out,
                "{:<26} {:>16}  {:<12} first disagreeing case",
                if lines { "convention" } else { "rule" },
                "cases agreeing",
                "cases"
            );
            for r in table
                .rows
                .iter()
                .chain(table.watertight.iter())
                .chain(table.crack_free.iter())
            {
                let _ = writeln!(
                    out,
                    "{:<26} {:>16}  {:<12} {}",
                    r.rule,
                    format!("{}/{}", r.agreeing, r.total),
                    r.cases,
                    r.first_disagreeing
                        .map_or_else(|| "-".to_string(), |i| i.to_string())
                );
            }
            let _ = writeln!(
                out,
                "follows: {}",
                if table.followed.is_empty() {
                    "none".to_string()
                } else {
                    table.followed.join(", ")
                }
            );
            if table.followed.is_empty() {
                let _ = writeln!(out, "closest: {}", table.closest);
            }
        }
        if self.keep_going {
            let _ = writeln!(
                out,
                "score: {}/{} cases ({:.1}%)",
                self.passed,
                self.cases_run,
                self.score * 100.0
            );
            for t in &self.families {
                let _ = writeln!(out, "  {:<12} {}/{}", t.family, t.passed, t.total);
            }
            let unanswered: Vec<_> = self
                .failing_cases
                .iter()
                .filter(|f| f.kind == FailureKind::NoAnswer)
                .collect();
            if let Some(first) = unanswered.first() {
                let _ = writeln!(
                    out,
                    "no answer on {} case(s), each counted as a failed case; the first, case {} (family {}): {}",
                    unanswered.len(),
                    first.case_index,
                    first.family,
                    first.problem.lines().next().unwrap_or("")
                );
            }
        }
        match self.verdict {
            VerdictWord::Pass if self.rules.is_none() => {
                let _ = writeln!(
                    out,
                    "PASS: {} cases, {} (seed {})",
                    self.cases_run, self.description, self.seed
                );
            }
            VerdictWord::Broken => {
                if let Some(e) = &self.error {
                    let _ = writeln!(out, "BROKEN: {}", e.message);
                    if e.on_every_input {
                        let _ = writeln!(
                            out,
                            "it breaks so on every input, the simplest included (first seen on case {}, family {})",
                            e.case_index, e.family
                        );
                    } else {
                        let _ = writeln!(
                            out,
                            "the input that triggers it (case {}, family {}{}):",
                            e.case_index,
                            e.family,
                            if e.shrunk { ", shrunk" } else { "" }
                        );
                    }
                    for file in &e.files {
                        let _ = writeln!(out, "input: {file}");
                    }
                }
            }
            _ => {}
        }
        if let (Some(c), Some(finding)) = (&self.counterexample, &self.finding) {
            let _ = writeln!(
                out,
                "FAIL: {}, case {} of seed {} (family {}); shrunk from {} to {} primitive(s) on a {}x{} target",
                with_samples(finding.property.to_string(), finding.case.samples),
                c.case_index,
                self.seed,
                c.family,
                c.original_primitives,
                c.primitives,
                c.width,
                c.height
            );
            let _ = writeln!(out, "  as generated: {}", c.original_problem);
            let _ = writeln!(out, "  shrunk ({}):", c.kind);
            for p in c.problems.iter().take(5) {
                let _ = writeln!(out, "  {p}");
            }
            if c.problems.len() > 5 {
                let _ = writeln!(out, "  ... and {} more", c.problems.len() - 5);
            }
            let _ = writeln!(
                out,
                "# correct   ! extra (or drawn twice{})   ? missing",
                if finding.case.samples.is_some() {
                    ", or with another mask"
                } else {
                    ""
                }
            );
            out.push_str(&finding.ascii_grid());
            if let Some(note) = finding.coordinates_note() {
                let _ = writeln!(out, "  ({note}, as the grid numbers its rows)");
            }
            if let Some(d) = &c.diagnosis {
                let _ = writeln!(out, "diagnosis: {d}");
            }
            if let Some(file) = c.files.first() {
                let seen = match finding.origin {
                    Origin::TopLeft => "",
                    Origin::BottomLeft => ", y up as it is given the case",
                };
                let _ = writeln!(
                    out,
                    "counterexample: {file} (rerun: give it to the program as its input{seen}, or --case {file})"
                );
            }
            if let Some(file) = c.files.iter().find(|f| f.ends_with(".html")) {
                let _ = writeln!(out, "report: {file}");
            }
        }
        if self.verdict == VerdictWord::Fail
            && self.counterexample.is_none()
            && self.rules.is_none()
        {
            let _ = writeln!(
                out,
                "FAIL: {} of {} cases hold, {} (seed {})",
                self.passed, self.cases_run, self.description, self.seed
            );
        }
        let first = self.counterexample.as_ref().map(|c| c.case_index);
        for c in self
            .counterexamples
            .iter()
            .filter(|c| Some(c.case_index) != first)
        {
            let _ = writeln!(
                out,
                "family {}: case {}, shrunk from {} to {} primitive(s) on a {}x{} target: {}",
                c.family,
                c.case_index,
                c.original_primitives,
                c.primitives,
                c.width,
                c.height,
                c.problems.first().map_or("", String::as_str)
            );
            if let Some(d) = &c.diagnosis {
                let _ = writeln!(out, "  diagnosis: {d}");
            }
            let lines: Vec<&str> = c
                .input
                .lines()
                .filter(|l| !l.starts_with("# command"))
                .collect();
            for line in lines.iter().take(INPUT_LINES_SHOWN) {
                let _ = writeln!(out, "  {line}");
            }
            if lines.len() > INPUT_LINES_SHOWN {
                let _ = writeln!(
                    out,
                    "  ... and {} more line(s)",
                    lines.len() - INPUT_LINES_SHOWN
                );
            }
        }
        f.write_str(out.trim_end())
    }
}

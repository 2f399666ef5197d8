//! The run: the cases drawn and judged batch by batch, a first failure
//! confirmed on more cases, the tallies by family, and the report put
//! together around the cause found and the shrunk counterexample.

use super::mode::{row_name, table_rows, Mode, Outcome};
use super::subjects::Subjects;
use super::{Progress, CONFIRMING_CASES, CONFIRMING_FAILURES};
use crate::check::case::Case;
use crate::check::cause::Diagnosis;
use crate::check::generate;
use crate::check::judge::{judge, FailureKind, Finding};
use crate::check::property::{with_samples, with_snapping, Property};
use crate::check::request::{
    CaseFailure, CheckReport, CheckRequest, FamilyTally, RuleTable, VerdictWord,
};
use crate::check::{simplest_case, Broken, Fragment, Subject, SubjectError};
use crate::error::Result;
use crate::raster::multisample::SamplePattern;

/// One run of the engine: the report, and for [`check`](crate::check::check)
/// the first failing case as generated and a broken subject.
pub(crate) struct Run {
    pub(crate) report: CheckReport,
    pub(crate) original: Option<Case>,
    pub(crate) broken: Option<Broken>,
}

/// The engine, for one request and what it judges by.
pub(crate) struct Checker<'a> {
    pub(crate) request: &'a CheckRequest,
    pub(crate) mode: Mode,
    /// The samples per pixel of every case (`--msaa N`).
    pub(crate) samples: Option<SamplePattern>,
}

/// The cases of a run as drawn and judged.
struct Judged {
    /// Each case judged, in order: its index, the case, what the subject
    /// drew, and what it came to.
    outcomes: Vec<(u32, Case, Vec<Fragment>, Outcome)>,
    /// Failures drawn after the run stopped, to confirm the cause.
    confirming: Vec<Finding>,
    /// The case that broke the subject, and how.
    broken_at: Option<(u32, Case, SubjectError)>,
    /// Under `keep_going`, the cases the subject gave no answer to (it
    /// crashed, hung, refused or printed nonsense there but not on every
    /// input): each a failed case, the run going on.
    pub(super) errored: Vec<(u32, Case, SubjectError)>,
    /// The first failure, where the run stopped short of its cases.
    stopped_at: Option<u32>,
}

/// What the cause is looked for on: the failures of the property (or the
/// closest row of the table) in the order found, the failures drawn to
/// confirm the first, and the passing cases with what was drawn there.
pub(super) struct Evidence<'j> {
    pub(super) failures: Vec<(u32, &'j Case, &'j Finding)>,
    pub(super) confirming: &'j [Finding],
    pub(super) passing: Vec<(&'j Case, &'j [Fragment])>,
}

impl Checker<'_> {
    /// The case `index` of `property`'s families, with the check's samples
    /// per pixel and snapping.
    pub(super) fn generate(&self, property: Property, index: u32, rng: &mut fastrand::Rng) -> Case {
        Case {
            samples: self.samples,
            ..generate::generate_case_snapped(property, self.request.snapping, index, rng)
        }
    }

    /// Runs the cases (or the one `given`), confirms and shrinks.
    pub(crate) fn check(
        &self,
        given: Option<Case>,
        subjects: &mut Subjects<'_>,
        progress: &mut dyn FnMut(Progress),
    ) -> Result<Run> {
        let from_file = given.is_some();
        let mut judged = self.draw_and_judge(given, subjects, progress);
        if let (Some(at), None, false) = (judged.stopped_at, &judged.broken_at, from_file) {
            self.confirm_in_family(at, subjects, &mut judged.confirming, progress);
        }
        let subject = subjects.first();
        let mut report = self.empty_report((judged.outcomes.len() + judged.errored.len()) as u32);
        let broken = match judged.broken_at.take() {
            Some((index, case, error)) => {
                Some(self.report_broken(&mut report, index, &case, error, from_file, subject)?)
            }
            None => None,
        };
        let table = match self.mode {
            Mode::One(_) => None,
            _ => Some(self.mode.rule_table(&judged.outcomes)),
        };
        let evidence = self.tally(&judged, table.as_ref(), from_file, &mut report);
        let original =
            self.report_first_failure(&mut report, &evidence, from_file, subject, progress)?;
        if self.request.keep_going && report.verdict == VerdictWord::Fail {
            self.report_each_family(&mut report, &evidence, &judged.errored, subject, progress);
        }
        if let Some(table) = table {
            report_rule_table(&mut report, table);
        }
        progress(Progress::Done);
        Ok(Run {
            report,
            original,
            broken,
        })
    }

    /// Draws and judges the cases (or the one `given`) a batch at a time.
    /// Without `keep_going` the run stops at the first failure, drawing up
    /// to [`CONFIRMING_CASES`] more to confirm it; it stops at a case that
    /// breaks the subject.
    fn draw_and_judge(
        &self,
        given: Option<Case>,
        subjects: &mut Subjects<'_>,
        progress: &mut dyn FnMut(Progress),
    ) -> Judged {
        let request = self.request;
        let from_file = given.is_some();
        let total = if from_file { 1 } else { request.cases };
        let mut rng = fastrand::Rng::with_seed(request.seed);
        let mut judged = Judged {
            outcomes: Vec::new(),
            confirming: Vec::new(),
            broken_at: None,
            errored: Vec::new(),
            stopped_at: None,
        };
        // The errors tried on the simplest input, and whether it broke so.
        let mut tried: Vec<(std::mem::Discriminant<SubjectError>, bool)> = Vec::new();
        let mut next = 0;
        'cases: while next < total {
            let limit = match judged.stopped_at {
                None => total,
                Some(at) => total.min(at + 1 + CONFIRMING_CASES),
            };
            if next >= limit || judged.confirming.len() + 1 >= CONFIRMING_FAILURES {
                break;
            }
            let end = (next + subjects.batch()).min(limit);
            let cases: Vec<(u32, Case)> = (next..end)
                .map(|i| {
                    let case = match &given {
                        Some(c) => c.clone(),
                        None => {
                            let (p, k) = self.mode.case_property(i);
                            self.generate(p, k, &mut rng)
                        }
                    };
                    (i, case)
                })
                .collect();
            let drawn = subjects.draw_all(&cases);
            // One subject stops a batch at the case that breaks it.
            next = cases[0].0 + drawn.len() as u32;
            for ((index, case), drawn) in cases.into_iter().zip(drawn) {
                if let Some(at) = judged.stopped_at {
                    progress(Progress::Confirming {
                        done: index - at,
                        total: CONFIRMING_CASES,
                    });
                    // A case that breaks the subject confirms nothing.
                    let Ok(drawn) = drawn else { break 'cases };
                    if let Outcome::One(Some(f)) = self.judge(index, from_file, &case, &drawn) {
                        judged.confirming.push(*f);
                    }
                    continue;
                }
                progress(Progress::Cases {
                    done: index + 1,
                    total,
                });
                let drawn = match drawn {
                    Ok(d) => d,
                    Err(e) if self.costs_one_case(&e, from_file, &mut tried, subjects) => {
                        judged.errored.push((index, case, e));
                        continue;
                    }
                    Err(e) => {
                        judged.broken_at = Some((index, case, e));
                        break 'cases;
                    }
                };
                let outcome = self.judge(index, from_file, &case, &drawn);
                let failed = matches!(outcome, Outcome::One(Some(_)));
                judged.outcomes.push((index, case, drawn, outcome));
                if failed && !request.keep_going {
                    judged.stopped_at = Some(index);
                }
            }
        }
        judged
    }

    /// Whether an error costs only its case: under `keep_going`, for a
    /// check of one property, when the subject does not break the same
    /// way on the simplest input (tried once for each kind of error, and
    /// remembered in `tried`). A subject broken on every input is
    /// reported broken, as without `keep_going`.
    fn costs_one_case(
        &self,
        error: &SubjectError,
        from_file: bool,
        tried: &mut Vec<(std::mem::Discriminant<SubjectError>, bool)>,
        subjects: &mut Subjects<'_>,
    ) -> bool {
        let Mode::One(property) = self.mode else {
            return false;
        };
        if !self.request.keep_going || from_file {
            return false;
        }
        let kind = std::mem::discriminant(error);
        if let Some(&(_, every)) = tried.iter().find(|(k, _)| *k == kind) {
            return !every;
        }
        let simplest = Case {
            samples: self.samples,
            ..simplest_case(property.is_lines())
        };
        let every = subjects
            .first()
            .draw(&simplest)
            .err()
            .is_some_and(|e| std::mem::discriminant(&e) == kind);
        tried.push((kind, every));
        !every
    }

    /// The report before any case is counted: what was asked, and how
    /// many cases were run.
    fn empty_report(&self, cases_run: u32) -> CheckReport {
        let request = self.request;
        CheckReport {
            schema: "rasterlab-check-report/2",
            verdict: VerdictWord::Pass,
            property: self.mode.id(),
            description: with_snapping(
                with_samples(self.mode.description(), self.samples),
                self.request.snapping,
            ),
            samples: self.samples.map_or(1, SamplePattern::count),
            origin: request.origin.to_string(),
            subject: String::new(),
            command: request.command.clone(),
            seed: request.seed,
            cases: request.cases,
            keep_going: request.keep_going,
            cases_run,
            passed: 0,
            score: 0.0,
            families: Vec::new(),
            failing_cases: Vec::new(),
            counterexample: None,
            counterexamples: Vec::new(),
            error: None,
            rules: None,
            finding: None,
        }
    }

    /// Tallies the judged cases by family (under a table, by its closest
    /// row) into the report: its failing cases, passes and score; and
    /// gathers them as the evidence the cause is looked for on.
    fn tally<'j>(
        &self,
        cases: &'j Judged,
        table: Option<&RuleTable>,
        from_file: bool,
        report: &mut CheckReport,
    ) -> Evidence<'j> {
        let mut tally: Vec<FamilyTally> = self
            .mode
            .families()
            .iter()
            .map(|f| FamilyTally {
                family: (*f).to_string(),
                passed: 0,
                total: 0,
                explained_by_cause: None,
                points: 0.0,
            })
            .collect();
        let closest = table.map_or(0, |t| {
            table_rows(self.mode)
                .iter()
                .position(|(p, _)| row_name(*p) == t.closest)
                .unwrap_or(0)
        });
        let mut failures: Vec<(u32, &Case, &Finding)> = Vec::new();
        let mut passing: Vec<(&Case, &[Fragment])> = Vec::new();
        for (index, case, drawn, outcome) in &cases.outcomes {
            let verdict = match outcome {
                Outcome::One(f) => Some(f.as_deref()),
                Outcome::Table(per) => per[closest].as_ref().map(|f| f.as_deref()),
            };
            let Some(verdict) = verdict else { continue };
            let family = self.family_of(*index, from_file);
            let t = tally_for(&mut tally, family);
            t.total += 1;
            match verdict {
                None => {
                    t.passed += 1;
                    passing.push((case, drawn.as_slice()));
                }
                Some(f) => {
                    report.failing_cases.push(CaseFailure {
                        case_index: *index,
                        family: family.to_string(),
                        kind: f.kind(),
                        problem: f.problems[0].clone(),
                        input: None,
                    });
                    failures.push((*index, case, f));
                }
            }
        }
        for (index, case, error) in &cases.errored {
            let family = self.family_of(*index, from_file);
            tally_for(&mut tally, family).total += 1;
            report.failing_cases.push(CaseFailure {
                case_index: *index,
                family: family.to_string(),
                kind: FailureKind::NoAnswer,
                problem: format!("no answer: {error}"),
                input: Some(case.to_text()),
            });
        }
        report.failing_cases.sort_by_key(|f| f.case_index);
        if !cases.errored.is_empty() && report.verdict == VerdictWord::Pass {
            report.verdict = VerdictWord::Fail;
        }
        if !self.request.keep_going {
            report.failing_cases.truncate(1);
        }
        tally.retain(|t| t.total > 0);
        for t in &mut tally {
            t.points = self
                .request
                .weights
                .iter()
                .find(|(f, _)| *f == t.family)
                .map_or(f64::from(t.total), |(_, w)| *w);
        }
        report.passed = tally.iter().map(|t| t.passed).sum();
        // Under a table, the closest row judges only the cases of its kind.
        let judged: u32 = tally.iter().map(|t| t.total).sum();
        report.score = if judged == 0 {
            0.0
        } else {
            f64::from(report.passed) / f64::from(judged)
        };
        report.families = tally;
        Evidence {
            failures,
            confirming: &cases.confirming,
            passing,
        }
    }

    /// Finds the cause of the run's first failure, shrinks it and puts it
    /// in the report as its counterexample; the failing case as generated.
    fn report_first_failure(
        &self,
        report: &mut CheckReport,
        evidence: &Evidence<'_>,
        from_file: bool,
        subject: &mut dyn Subject,
        progress: &mut dyn FnMut(Progress),
    ) -> Result<Option<Case>> {
        // A broken subject's report is the input that breaks it (in
        // `counterexample.txt`): a failure found before it is listed, not
        // shrunk over that file.
        let first_failure = evidence
            .failures
            .first()
            .filter(|_| report.verdict != VerdictWord::Broken);
        let Some(&(index, case, first)) = first_failure else {
            return Ok(None);
        };
        if report.verdict == VerdictWord::Pass {
            report.verdict = VerdictWord::Fail;
        }
        let diagnosis = self.find_cause(first.property, evidence, subject);
        let shrunk = self.shrink(
            first.clone(),
            diagnosis,
            self.request.shrink_runs,
            subject,
            progress,
        );
        if let Some(cause) = &shrunk.cause {
            self.count_explained(&mut report.families, cause, &evidence.failures, from_file);
        }
        let shrunk = self.write_counterexample(report, shrunk, index, case.len())?;
        report.finding = Some(Box::new(shrunk));
        Ok(Some(case.clone()))
    }

    /// Where the cause holds, family by family (a grader's test per family
    /// names it only where it explains).
    fn count_explained(
        &self,
        families: &mut [FamilyTally],
        cause: &Diagnosis,
        failures: &[(u32, &Case, &Finding)],
        from_file: bool,
    ) {
        for t in families {
            let mut family_failures = failures
                .iter()
                .filter(|(i, _, _)| self.family_of(*i, from_file) == t.family)
                .peekable();
            if family_failures.peek().is_some() {
                t.explained_by_cause = Some(
                    family_failures
                        .filter(|(_, c, f)| cause.explains(f.property, c, &f.drawn).is_some())
                        .count() as u32,
                );
            }
        }
    }

    /// The family of case `index`: `file` for a case given in a file.
    pub(super) fn family_of(&self, index: u32, from_file: bool) -> &'static str {
        if from_file {
            "file"
        } else {
            self.mode.family(index)
        }
    }

    /// Draws cases of the family of case `at` (a run's first failure) to
    /// confirm its cause, adding the failing ones to `confirming`.
    fn confirm_in_family(
        &self,
        at: u32,
        subjects: &mut Subjects<'_>,
        confirming: &mut Vec<Finding>,
        progress: &mut dyn FnMut(Progress),
    ) {
        let Mode::One(property) = self.mode else {
            return;
        };
        let cycle = generate::families(property).len().max(1) as u32;
        let mut done = 0;
        while done < CONFIRMING_CASES && confirming.len() + 1 < CONFIRMING_FAILURES {
            let batch = subjects.batch().min(CONFIRMING_CASES - done);
            let cases: Vec<(u32, Case)> = (done..done + batch)
                .map(|j| {
                    let index = at + (j + 1) * cycle;
                    let mut rng = fastrand::Rng::with_seed(
                        self.request.seed ^ 0x9e37_79b9_7f4a_7c15 ^ u64::from(index),
                    );
                    (index, self.generate(property, index, &mut rng))
                })
                .collect();
            done += batch;
            for ((index, case), drawn) in cases.iter().zip(subjects.draw_all(&cases)) {
                progress(Progress::Confirming {
                    done,
                    total: CONFIRMING_CASES,
                });
                let Ok(drawn) = drawn else { return };
                if let Outcome::One(Some(f)) = self.judge(*index, false, case, &drawn) {
                    confirming.push(*f);
                }
            }
        }
    }

    /// Judges one drawn case.
    fn judge(&self, index: u32, from_file: bool, case: &Case, drawn: &[Fragment]) -> Outcome {
        match self.mode {
            Mode::One(p) => Outcome::One(judge(p, case, drawn).map(Box::new)),
            _ => Outcome::Table(
                table_rows(self.mode)
                    .into_iter()
                    .map(|(p, mesh_only)| {
                        self.mode
                            .judges(p, mesh_only, index, from_file)
                            .then(|| judge(p, case, drawn).map(Box::new))
                    })
                    .collect(),
            ),
        }
    }
}

/// Puts a table mode's table in the report; unless the subject broke,
/// the verdict is whether some row agreed on every case it judged.
fn report_rule_table(report: &mut CheckReport, table: RuleTable) {
    if report.verdict != VerdictWord::Broken {
        report.verdict = if table.followed.is_empty() {
            VerdictWord::Fail
        } else {
            VerdictWord::Pass
        };
    }
    report.rules = Some(table);
}

fn tally_for<'t>(tally: &'t mut Vec<FamilyTally>, family: &str) -> &'t mut FamilyTally {
    if let Some(k) = tally.iter().position(|t| t.family == family) {
        &mut tally[k]
    } else {
        tally.push(FamilyTally {
            family: family.to_string(),
            passed: 0,
            total: 0,
            explained_by_cause: None,
            points: 0.0,
        });
        tally.last_mut().expect("just pushed")
    }
}

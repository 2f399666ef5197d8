//! The counterexample: the first failure shrunk, keeping its kind and
//! the cause found, then written out (its files under `--out`, and the
//! report's counterexample); for a broken subject, the input that breaks
//! it, shrunk as far as it still does.

use super::checker::{Checker, Evidence};
use super::Progress;
use crate::check::case::Case;
use crate::check::case::Origin;
use crate::check::cause::{self, Cause, Diagnosis};
use crate::check::judge::{FailureKind, Finding, Provenance};
use crate::check::property::Property;
use crate::check::request::{BrokenReport, CheckReport, Counterexample, VerdictWord};
use crate::check::{broken, shrink, Broken, Fragment, Subject, SubjectError};
use crate::error::Result;
use crate::raster::edge::FillRule;

/// The other failing families' counterexamples are shrunk with this
/// share of the first one's runs each: a program started once per case
/// pays its start on every run, and a check may fail in every family.
const FAMILY_SHRINK_SHARE: u32 = 4;

impl Checker<'_> {
    /// Shrinks the case that broke the subject, writes it out and puts it
    /// in the report, whose verdict it makes `broken`.
    pub(super) fn report_broken(
        &self,
        report: &mut CheckReport,
        index: u32,
        case: &Case,
        error: SubjectError,
        from_file: bool,
        subject: &mut dyn Subject,
    ) -> Result<Broken> {
        let request = self.request;
        let b = broken(error, case, index, subject, request.shrink_runs);
        let mut files = Vec::new();
        let family = self.family_of(index, from_file).to_string();
        let input = self.input_text(&b.case, index);
        if let Some(out) = &request.out {
            let path = out.join("counterexample.txt");
            crate::output::write_file(&path, input.as_bytes())?;
            files.push(path.display().to_string());
        }
        report.verdict = VerdictWord::Broken;
        report.error = Some(BrokenReport {
            message: b.error.to_string(),
            case_index: index,
            family,
            on_every_input: b.on_every_input,
            shrunk: b.shrunk,
            input,
            files,
        });
        Ok(b)
    }

    /// Shrinks the first failure, keeping its kind and the cause found,
    /// and words the cause (or its absence) on the shrunk case.
    pub(super) fn shrink(
        &self,
        first: Finding,
        diagnosis: Option<Diagnosis>,
        budget: u32,
        subject: &mut dyn Subject,
        progress: &mut dyn FnMut(Progress),
    ) -> Finding {
        let property = first.property;
        let keep = |f: &Finding| {
            diagnosis
                .as_ref()
                .is_none_or(|d| d.explains(property, &f.case, &f.drawn).is_some())
        };
        let mut shrunk = shrink::shrink(first, subject, budget, &keep, &mut |runs| {
            progress(Progress::Shrinking { runs, budget })
        });
        match diagnosis {
            Some(mut d) => {
                if let Some(e) = d.explains(property, &shrunk.case, &shrunk.drawn) {
                    d.evidence = e;
                }
                self.name_a_flipped_y(property, &mut d);
                shrunk.diagnosis = Some(d.sentence());
                shrunk.cause = Some(d);
            }
            None => {
                let facts = shrunk.diagnosis.take();
                shrunk.diagnosis = Some(match facts {
                    Some(f) => format!("no cause in the catalogue explains it; {f}"),
                    None => "no cause in the catalogue explains it".into(),
                });
            }
        }
        shrunk
    }

    /// Names the y direction where the rule found is the one checked,
    /// mirrored top to bottom (bottom-left for top-left, ...): what a
    /// program whose y grows the other way than the check's `--origin`
    /// draws, for a rule the picture names by its top and bottom.
    fn name_a_flipped_y(&self, property: Property, d: &mut Diagnosis) {
        let Property::Exact(rule) = property else {
            return;
        };
        let mirror = match rule {
            FillRule::TopLeft => FillRule::BottomLeft,
            FillRule::BottomLeft => FillRule::TopLeft,
            FillRule::TopRight => FillRule::BottomRight,
            FillRule::BottomRight => FillRule::TopRight,
            _ => return,
        };
        if d.found != [Cause::FillRule(mirror)] {
            return;
        }
        let (other, option) = match self.request.origin {
            Origin::TopLeft => ("up", "with --origin bottom-left"),
            Origin::BottomLeft => ("down", "without --origin bottom-left"),
        };
        d.description = format!(
            "{}: the {rule} rule with y flipped, as a program whose y grows {other} draws it \
             (check such a program {option})",
            d.description
        );
    }

    /// Records where the shrunk case came from, writes its files and puts
    /// its counterexample in the report.
    pub(super) fn write_counterexample(
        &self,
        report: &mut CheckReport,
        mut shrunk: Finding,
        index: u32,
        original_primitives: usize,
    ) -> Result<Finding> {
        self.record_provenance(&mut shrunk, index);
        let mut files = Vec::new();
        if let Some(out) = &self.request.out {
            for (name, body) in [
                ("counterexample.txt", shrunk.counterexample_text()),
                ("counterexample.svg", shrunk.to_svg()),
                ("report.html", shrunk.to_html()),
            ] {
                let path = out.join(name);
                crate::output::write_file(&path, body.as_bytes())?;
                files.push(path.display().to_string());
            }
        }
        report.counterexample = Some(counterexample_of(&shrunk, original_primitives, files));
        Ok(shrunk)
    }

    /// Records in the shrunk case where it came from: the command, the
    /// seed, the case and its family.
    fn record_provenance(&self, shrunk: &mut Finding, index: u32) {
        let request = self.request;
        shrunk.origin = request.origin;
        shrunk.provenance = Some(Provenance {
            command: request.command.clone(),
            seed: request.seed,
            case_index: index,
            family: self
                .family_of(index, request.case_file.is_some())
                .to_string(),
        });
    }

    /// Under `keep_going`, puts in the report the first failure of each
    /// failing family, shrunk (the run's first failure is already shrunk
    /// and is reused): a failure whose cause is looked for among that
    /// family's failures alone (not probed further), or a case the
    /// program gave no answer to, shrunk as far as it still gives none,
    /// each with a share of the shrinking runs
    /// ([`FAMILY_SHRINK_SHARE`]). Nothing is written: the files are the
    /// first failure's.
    pub(super) fn report_each_family(
        &self,
        report: &mut CheckReport,
        evidence: &Evidence<'_>,
        errored: &[(u32, Case, SubjectError)],
        subject: &mut dyn Subject,
        progress: &mut dyn FnMut(Progress),
    ) {
        let from_file = self.request.case_file.is_some();
        let failing: Vec<String> = report
            .families
            .iter()
            .filter(|t| t.passed < t.total)
            .map(|t| t.family.clone())
            .collect();
        for family in failing {
            let of_family = |i: &u32| self.family_of(*i, from_file) == family;
            let failure = evidence.failures.iter().find(|(i, _, _)| of_family(i));
            let error = errored.iter().find(|(i, _, _)| of_family(i));
            let own = match (failure, error) {
                (Some(&(index, case, finding)), e) if e.is_none_or(|(j, _, _)| index < *j) => {
                    match &report.counterexample {
                        Some(c) if c.case_index == index => Some(c.clone()),
                        _ => {
                            let failing: Vec<(&Case, &[Fragment])> = evidence
                                .failures
                                .iter()
                                .filter(|(i, _, _)| of_family(i))
                                .map(|(_, c, f)| (*c, f.drawn.as_slice()))
                                .collect();
                            let diagnosis =
                                cause::diagnose(finding.property, &failing, &evidence.passing);
                            let mut shrunk = self.shrink(
                                finding.clone(),
                                diagnosis,
                                self.request.shrink_runs / FAMILY_SHRINK_SHARE,
                                subject,
                                progress,
                            );
                            self.record_provenance(&mut shrunk, index);
                            Some(counterexample_of(&shrunk, case.len(), Vec::new()))
                        }
                    }
                }
                (_, Some((index, case, error))) => {
                    let b = broken(
                        error.clone(),
                        case,
                        *index,
                        subject,
                        self.request.shrink_runs,
                    );
                    let problem = format!("no answer: {}", b.error);
                    Some(Counterexample {
                        property: self.mode.id(),
                        case_index: *index,
                        family: family.clone(),
                        original_problem: format!("no answer: {error}"),
                        original_primitives: case.len(),
                        kind: FailureKind::NoAnswer,
                        primitives: b.case.len(),
                        width: b.case.width,
                        height: b.case.height,
                        problems: vec![problem],
                        diagnosis: None,
                        cause: None,
                        missing: Vec::new(),
                        extra: Vec::new(),
                        input: self.input_text(&b.case, *index),
                        files: Vec::new(),
                    })
                }
                _ => None,
            };
            report.counterexamples.extend(own);
        }
    }

    /// The file a case that broke the subject is given in: where it came
    /// from in comments, then the case.
    fn input_text(&self, case: &Case, index: u32) -> String {
        let request = self.request;
        let provenance = Provenance {
            command: request.command.clone(),
            seed: request.seed,
            case_index: index,
            family: self
                .family_of(index, request.case_file.is_some())
                .to_string(),
        };
        format!(
            "{}{}",
            provenance_comment(&provenance, case),
            case.to_text_for(request.origin)
                .split_once('\n')
                .map_or("", |(_, r)| r)
        )
    }
}

/// The report's counterexample of a shrunk failure whose provenance is
/// recorded, with the files written for it.
fn counterexample_of(
    shrunk: &Finding,
    original_primitives: usize,
    files: Vec<String>,
) -> Counterexample {
    let provenance = shrunk.provenance.clone().unwrap_or_default();
    let multisampled = shrunk.case.samples.is_some();
    let pixels = |v: &[Fragment]| -> Vec<Vec<i64>> {
        v.iter()
            .map(|f| {
                let mut p = vec![f.x, f.y, i64::from(f.id)];
                if multisampled {
                    p.push(i64::from(f.mask));
                }
                p
            })
            .collect()
    };
    Counterexample {
        property: shrunk.property.id(),
        case_index: provenance.case_index,
        family: provenance.family,
        original_problem: shrunk.original_problem.clone().unwrap_or_default(),
        original_primitives,
        kind: shrunk.kind(),
        primitives: shrunk.case.len(),
        width: shrunk.case.width,
        height: shrunk.case.height,
        problems: shrunk.problems.clone(),
        diagnosis: shrunk.diagnosis.clone(),
        cause: shrunk.cause.clone(),
        missing: pixels(&shrunk.missing),
        extra: pixels(&shrunk.extra),
        input: shrunk.counterexample_text(),
        files,
    }
}

/// The comment lines that record where a case came from.
fn provenance_comment(p: &Provenance, case: &Case) -> String {
    format!(
        "# size {}x{}\n# command: {}\n# seed {}, case {} (family {})\n",
        case.width, case.height, p.command, p.seed, p.case_index, p.family
    )
}

//! The counterexample: the first failure shrunk, keeping its kind and
//! the cause found, then written out (its files under `--out`, and the
//! report's counterexample); for a broken subject, the input that breaks
//! it, shrunk as far as it still does.

use super::checker::Checker;
use super::Progress;
use crate::check::case::Case;
use crate::check::cause::Diagnosis;
use crate::check::judge::{Finding, Provenance};
use crate::check::request::{BrokenReport, CheckReport, Counterexample, VerdictWord};
use crate::check::{broken, shrink, Broken, Fragment, Subject, SubjectError};
use crate::error::Result;

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
        let provenance = Provenance {
            command: request.command.clone(),
            seed: request.seed,
            case_index: index,
            family: family.clone(),
        };
        let input = format!(
            "{}{}",
            provenance_comment(&provenance, &b.case),
            b.case.to_text().split_once('\n').map_or("", |(_, r)| r)
        );
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
        subject: &mut dyn Subject,
        progress: &mut dyn FnMut(Progress),
    ) -> Finding {
        let budget = self.request.shrink_runs;
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

    /// Records where the shrunk case came from, writes its files and puts
    /// its counterexample in the report.
    pub(super) fn write_counterexample(
        &self,
        report: &mut CheckReport,
        mut shrunk: Finding,
        index: u32,
        original_primitives: usize,
    ) -> Result<Finding> {
        let request = self.request;
        let family = if request.case_file.is_some() {
            "file"
        } else {
            self.mode.family(index)
        };
        shrunk.provenance = Some(Provenance {
            command: request.command.clone(),
            seed: request.seed,
            case_index: index,
            family: family.to_string(),
        });
        let mut files = Vec::new();
        if let Some(out) = &request.out {
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
        report.counterexample = Some(Counterexample {
            property: shrunk.property.id(),
            case_index: index,
            family: family.to_string(),
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
        });
        Ok(shrunk)
    }
}

/// The comment lines that record where a case came from.
fn provenance_comment(p: &Provenance, case: &Case) -> String {
    format!(
        "# size {}x{}\n# command: {}\n# seed {}, case {} (family {})\n",
        case.width, case.height, p.command, p.seed, p.case_index, p.family
    )
}

//! Probing a named cause: more cases are generated, drawn by the
//! reference under the cause and under each of its rivals, and those
//! where they draw differently are given to the subject; the cause is
//! then looked for again with what the subject drew there.

use super::checker::{Checker, Evidence};
use crate::check::case::Case;
use crate::check::cause::{self, Diagnosis};
use crate::check::judge::{judge, Finding};
use crate::check::property::Property;
use crate::check::{Fragment, Subject};

/// Cases generated (and drawn by the reference only) to find ones that
/// tell a named cause from its rivals ([`cause::rivals`]).
const PROBE_CASES: u32 = 100;
/// Of those, the most the subject draws.
const PROBE_RUNS: usize = 12;

impl Checker<'_> {
    /// The cause of the run's failures: diagnosed on the failing cases
    /// (the first one the case to be shrunk) against the passing ones,
    /// then, once a cause is named, again with the probes the subject
    /// drew.
    pub(super) fn find_cause(
        &self,
        property: Property,
        evidence: &Evidence<'_>,
        subject: &mut dyn Subject,
    ) -> Option<Diagnosis> {
        let failing: Vec<(&Case, &[Fragment])> = evidence
            .failures
            .iter()
            .map(|(_, _, f)| f)
            .copied()
            .chain(evidence.confirming.iter())
            .map(|f| (&f.case, f.drawn.as_slice()))
            .collect();
        let diagnosis = cause::diagnose(property, &failing, &evidence.passing)?;
        let (more_failing, more_passing) = self.probe(&diagnosis, property, subject);
        if more_failing.is_empty() && more_passing.is_empty() {
            return Some(diagnosis);
        }
        let failing: Vec<(&Case, &[Fragment])> = failing
            .iter()
            .copied()
            .chain(more_failing.iter().map(|f| (&f.case, f.drawn.as_slice())))
            .collect();
        let passing: Vec<(&Case, &[Fragment])> = more_passing
            .iter()
            .map(|(c, d)| (c, d.as_slice()))
            .chain(evidence.passing.iter().copied())
            .collect();
        cause::diagnose(property, &failing, &passing)
    }

    /// Cases that tell the named cause from its rivals, drawn by the
    /// subject: those that fail, and those that pass with what was drawn.
    fn probe(
        &self,
        diagnosis: &Diagnosis,
        property: Property,
        subject: &mut dyn Subject,
    ) -> (Vec<Finding>, Vec<(Case, Vec<Fragment>)>) {
        let rivals = cause::rivals(diagnosis, property, self.samples.is_some());
        let (mut failing, mut passing) = (Vec::new(), Vec::new());
        if rivals.is_empty() || self.request.case_file.is_some() {
            return (failing, passing);
        }
        let mut rng = fastrand::Rng::with_seed(self.request.seed ^ 0x5851_f42d_4c95_7f2d);
        // Rivals no drawn case has refuted yet.
        let mut alive = rivals;
        let mut runs = 0;
        for index in 0..PROBE_CASES {
            if runs == PROBE_RUNS || alive.is_empty() {
                break;
            }
            let case = if property.is_lines() || index % 2 == 0 {
                self.generate(property, index / 2, &mut rng)
            } else {
                Case {
                    samples: self.samples,
                    ..small_triangles(&mut rng)
                }
            };
            let sorted = |mut v: Vec<Fragment>| {
                v.sort();
                v
            };
            let Some(named) = cause::predict(&diagnosis.found, property, &case).map(sorted) else {
                break;
            };
            let predictions: Vec<Option<Vec<Fragment>>> = alive
                .iter()
                .map(|r| cause::predict(r, property, &case).map(sorted))
                .collect();
            if !predictions
                .iter()
                .any(|p| p.as_ref().is_some_and(|p| *p != named))
            {
                continue;
            }
            runs += 1;
            let Ok(drawn) = subject.draw(&case) else {
                break;
            };
            let seen = sorted(drawn.clone());
            let mut k = 0;
            alive.retain(|_| {
                let keep = predictions[k].as_ref().is_some_and(|p| *p == seen);
                k += 1;
                keep
            });
            match judge(property, &case, &drawn) {
                Some(f) => failing.push(f),
                None => passing.push((case, drawn)),
            }
        }
        (failing, passing)
    }
}

/// A probe case of small triangles of either winding, each over a pixel
/// centre, of areas around a square pixel: what tells a cause from the
/// same cause with small triangles dropped.
fn small_triangles(rng: &mut fastrand::Rng) -> Case {
    let on_grid = |v: f64| (v * 256.0).round() / 256.0;
    let triangles = (0..6)
        .map(|k| {
            let centre = (f64::from(k % 3) * 3.0 + 1.5, f64::from(k / 3) * 3.0 + 1.5);
            let size = 0.6 + rng.f64() * 1.6;
            let corner = |a: f64| {
                (
                    on_grid(centre.0 + size * a.cos()),
                    on_grid(centre.1 + size * a.sin()),
                )
            };
            let a = rng.f64() * std::f64::consts::TAU;
            let turn = if rng.bool() { 1.0 } else { -1.0 } * std::f64::consts::TAU / 3.0;
            [corner(a), corner(a + turn), corner(a + 2.0 * turn)]
        })
        .collect();
    Case {
        width: 9,
        height: 6,
        triangles,
        lines: Vec::new(),
        ..Case::default()
    }
}

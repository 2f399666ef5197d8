//! The diagnosis of a run's failures: each cause of the catalogue, then
//! each pair, is tried on the first failing case as generated, held
//! against the passing cases, and counted on the other failing cases; the
//! one confirmed on the most is named, and the others that fit as well
//! are listed. A named cause's rivals (it together with another change)
//! are what probing tells it from.

use super::explain::{explains, predict};
use super::{catalogue, catalogue_multisampled, float_edges_words, Cause, Role};
use crate::check::case::Case;
use crate::check::property::Property;
use crate::check::Fragment;
use serde::Serialize;

/// The cause a run's failures point to: one cause of the catalogue, or
/// two together, confirmed by the reference.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Diagnosis {
    /// The cause's identifiers ([`Cause::id`]): one, or two together.
    pub causes: Vec<String>,
    /// The cause in words.
    pub description: String,
    /// What the reference showed on the shrunk counterexample.
    pub evidence: String,
    /// Failing cases of the run (as generated) that the cause explains.
    pub confirmed_on: u32,
    /// Failing cases of the run tried.
    pub failing_cases: u32,
    /// Other causes (or pairs) that explain the first failing case as
    /// well, on as many cases, named later in the catalogue's order.
    pub also_fits: Vec<Vec<String>>,
    /// The causes themselves, for the shrinker.
    #[serde(skip)]
    pub(crate) found: Vec<Cause>,
}

impl Diagnosis {
    /// The one-line explanation: the cause, its evidence, where it was
    /// confirmed, and the causes that fit as well.
    pub fn sentence(&self) -> String {
        let mut s = format!(
            "cause: {} ({}); confirmed on {} of {} failing case(s) as generated",
            self.description, self.evidence, self.confirmed_on, self.failing_cases
        );
        if !self.also_fits.is_empty() {
            let others: Vec<String> = self.also_fits.iter().map(|c| c.join(" + ")).collect();
            s.push_str(&format!("; also fits: {}", others.join(", ")));
        }
        s
    }

    /// Whether the named cause explains `drawn` on `case`, and how.
    pub fn explains(&self, property: Property, case: &Case, drawn: &[Fragment]) -> Option<String> {
        explains(&self.found, property, case, drawn)
    }
}

/// The catalogue for the cases of a check: [`catalogue_multisampled`]
/// when they are multisampled.
fn catalogue_for(property: Property, case: &Case) -> Vec<Cause> {
    if case.samples.is_some() {
        catalogue_multisampled(property)
    } else {
        catalogue(property)
    }
}

/// Whether the changes among `causes` draw `drawn` on a case the subject
/// passed: a change that would have drawn something else there is refuted
/// (conditions on the differences say nothing of a case without any).
fn agrees_where_right(
    causes: &[Cause],
    property: Property,
    case: &Case,
    drawn: &[Fragment],
) -> bool {
    let models: Vec<Cause> = causes
        .iter()
        .filter(|c| c.role() == Role::Model)
        .copied()
        .collect();
    models.is_empty() || explains(&models, property, case, drawn).is_some()
}

/// The hypotheses a named cause competes with on cases not seen yet: the
/// cause together with each other change of the catalogue. A case where
/// they draw differently tells them apart (a subject that culls one
/// winding may drop small triangles too, which no failure seen so far
/// showed).
pub(crate) fn rivals(
    diagnosis: &Diagnosis,
    property: Property,
    multisampled: bool,
) -> Vec<Vec<Cause>> {
    if diagnosis.found.len() != 1 || diagnosis.found[0].role() != Role::Model {
        return Vec::new();
    }
    let named = diagnosis.found[0];
    let catalogue = if multisampled {
        catalogue_multisampled(property)
    } else {
        catalogue(property)
    };
    catalogue
        .into_iter()
        .filter(|c| *c != named && c.role() == Role::Model)
        .map(|c| vec![named, c])
        .filter(|pair| predict(pair, property, &Case::default()).is_some())
        .collect()
}

/// Passing cases a cause is held against, at most.
const PASSING_TRIED: usize = 40;

/// The cause that explains the failing cases, each `(case, drawn)` as
/// generated, the first one the case to be shrunk, and agrees with what
/// the subject drew on the `passing` cases; `None` when no cause or pair
/// of the catalogue does.
pub(crate) fn diagnose(
    property: Property,
    failing: &[(&Case, &[Fragment])],
    passing: &[(&Case, &[Fragment])],
) -> Option<Diagnosis> {
    let (first, rest) = failing.split_first()?;
    let passing = &passing[..passing.len().min(PASSING_TRIED)];
    let catalogue = catalogue_for(property, first.0);
    let confirmations = |causes: &[Cause]| -> u32 {
        1 + rest
            .iter()
            .filter(|(c, d)| explains(causes, property, c, d).is_some())
            .count() as u32
    };
    let explaining_first = |candidates: Vec<Vec<Cause>>| -> Vec<(Vec<Cause>, u32)> {
        candidates
            .into_iter()
            .filter(|c| explains(c, property, first.0, first.1).is_some())
            .filter(|c| {
                passing
                    .iter()
                    .all(|(case, drawn)| agrees_where_right(c, property, case, drawn))
            })
            .map(|c| {
                let n = confirmations(&c);
                (c, n)
            })
            .collect()
    };
    let n = failing.len() as u32;
    let mut fits = explaining_first(catalogue.iter().map(|c| vec![*c]).collect());
    let best_single = fits.iter().map(|f| f.1).max().unwrap_or(0);
    if best_single < n {
        let mut pairs = Vec::new();
        for (i, a) in catalogue.iter().enumerate() {
            for b in &catalogue[i + 1..] {
                pairs.push(vec![*a, *b]);
            }
        }
        let pair_fits = explaining_first(pairs);
        if pair_fits.iter().map(|f| f.1).max().unwrap_or(0) > best_single {
            fits = pair_fits;
        }
    }
    let best = fits.iter().map(|f| f.1).max()?;
    // Floating point, a condition every difference on an edge meets,
    // explains little alone: a model that alone explains at least half
    // the failing cases, with floating point for the rest, explaining as
    // many, is named before it ("the inclusive rule, evaluated in
    // floating point").
    if fits
        .iter()
        .find(|f| f.1 == best)
        .is_some_and(|f| f.0 == [Cause::FloatEdges])
    {
        let condition = Cause::FloatEdges;
        let single = |m: Cause| {
            failing
                .iter()
                .filter(|(c, d)| explains(&[m], property, c, d).is_some())
                .count()
        };
        let mut models: Vec<(Cause, usize)> = catalogue
            .iter()
            .filter(|m| m.role() == Role::Model)
            .map(|&m| (m, single(m)))
            .filter(|&(_, n)| n > 0)
            .collect();
        let most = models.iter().map(|m| m.1).max().unwrap_or(0);
        if 2 * most < failing.len() {
            models.clear();
        }
        let pairs: Vec<Vec<Cause>> = models
            .iter()
            .filter(|m| m.1 == most)
            .map(|m| vec![m.0, condition])
            .collect();
        let mut pair_fits = explaining_first(pairs);
        pair_fits.retain(|f| f.1 == best);
        if !pair_fits.is_empty() {
            fits = pair_fits;
        }
    }
    let mut best_fits = fits.into_iter().filter(|f| f.1 == best);
    let (found, confirmed_on) = best_fits.next()?;
    let also_fits = best_fits
        .map(|(c, _)| c.iter().map(Cause::id).collect())
        .collect();
    let evidence = explains(&found, property, first.0, first.1).unwrap_or_default();
    Some(Diagnosis {
        causes: found.iter().map(Cause::id).collect(),
        description: found
            .iter()
            .map(|c| match c {
                Cause::FloatEdges => float_edges_words(first.0.snapping),
                _ => c.to_string(),
            })
            .collect::<Vec<_>>()
            .join(", and "),
        evidence,
        confirmed_on,
        failing_cases: n,
        also_fits,
        found,
    })
}

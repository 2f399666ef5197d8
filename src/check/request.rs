//! What a check is asked and what it answers: a [`CheckRequest`] in, a
//! [`CheckReport`] out (the engine between them is `engine/`, the
//! report's text `text.rs`).
//!
//! The request names the subject (an outside program or a built-in
//! back-end), what the cases hold and what they must satisfy, how many
//! cases and from which seed (or one case from a file), how many run at
//! once, and whether to stop at the first failure (the default) or run
//! every case and score it per family (`keep_going`). The report is the
//! same value for a pass, a failure and a broken subject: text through
//! `Display`, one JSON shape through `Serialize`, which
//! `docs/check-report.schema.json` describes.
//!
//! With [`RuleChoice::Any`] the subject is judged on the same cases against
//! every fill rule at once (even cases from the exact check's families,
//! odd ones from the mesh families), and also for watertightness and
//! crack-freedom on the meshes: the report's rule table says, for each
//! rule, how many cases agree with it and the first that does not, names
//! the rule it follows (or none), and shrinks the closest rule's first
//! failure. [`ConventionChoice::Any`] does the same for lines: every line
//! convention, the screen-coordinate ones judged on cases in screen
//! coordinates (even cases), the whole-pixel ones on cases whose endpoints
//! are pixel indices (odd cases).
//!
//! ```
//! use rasterlab::check::{run, CheckRequest, RuleChoice, SubjectSpec};
//!
//! let mut request = CheckRequest::new(SubjectSpec::Backend("scanline".into()));
//! request.rule = Some(RuleChoice::Any);
//! request.cases = 40;
//! let report = run(&request).unwrap();
//! assert_eq!(report.rules.as_ref().unwrap().followed, ["top-left"]);
//! assert_eq!(report.exit_code(), 0);
//! ```

use super::case::Origin;
use super::cause::Diagnosis;
use super::judge::{FailureKind, Finding, LineConvention};
use super::snapping::Snapping;
use crate::error::{Error, Result};
use crate::raster::edge::FillRule;
use crate::raster::polygon::WindingRule;
use serde::Serialize;
use std::path::PathBuf;
use std::str::FromStr;
use std::time::Duration;

/// The rasterizer a check judges.
#[derive(Clone, Debug, PartialEq)]
pub enum SubjectSpec {
    /// An outside program: a command line run once per case (see
    /// [`Program`](super::Program)).
    Exec(String),
    /// An outside program started once, reading case after case on its
    /// standard input (see [`Program::persistent`](super::Program::persistent)).
    Persistent(String),
    /// A built-in back-end, by name.
    Backend(String),
}

/// What the cases hold.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Triangles.
    Triangles,
    /// Line segments.
    Lines,
    /// Polygons, with holes, crossing themselves or not.
    Polygons,
}

crate::names::named_enum!(
    Kind,
    "kind",
    Triangles = "triangles",
    Lines = "lines",
    Polygons = "polygons"
);

/// What triangles are judged by.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum RuleChoice {
    /// Exactly this fill rule's fragments.
    Exact(FillRule),
    /// Watertight, under any consistent tie rule.
    Watertight,
    /// Crack-free.
    CrackFree,
    /// Every rule at once: which one does the subject follow?
    Any,
}

impl RuleChoice {
    /// The choice's command-line name.
    pub fn name(self) -> &'static str {
        match self {
            RuleChoice::Exact(rule) => rule.name(),
            RuleChoice::Watertight => "watertight",
            RuleChoice::CrackFree => "crack-free",
            RuleChoice::Any => "any",
        }
    }
}

impl FromStr for RuleChoice {
    type Err = Error;
    fn from_str(s: &str) -> Result<RuleChoice> {
        match s {
            "watertight" => Ok(RuleChoice::Watertight),
            "crack-free" => Ok(RuleChoice::CrackFree),
            "any" => Ok(RuleChoice::Any),
            _ => s.parse().map(RuleChoice::Exact).map_err(|_| {
                let mut known: Vec<&str> = FillRule::ALL.iter().map(|r| r.name()).collect();
                known.extend(["watertight", "crack-free", "any"]);
                Error::UnknownName {
                    what: "rule",
                    name: s.to_string(),
                    known: known.join(", "),
                }
            }),
        }
    }
}

/// What lines are judged by.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum ConventionChoice {
    /// Exactly this convention's pixels.
    Exact(LineConvention),
    /// Every convention at once: which one does the subject follow?
    Any,
}

impl FromStr for ConventionChoice {
    type Err = Error;
    fn from_str(s: &str) -> Result<ConventionChoice> {
        if s == "any" {
            return Ok(ConventionChoice::Any);
        }
        s.parse().map(ConventionChoice::Exact).map_err(|_| {
            let mut known: Vec<&str> = LineConvention::ALL.iter().map(|c| c.name()).collect();
            known.push("any");
            Error::UnknownName {
                what: "line convention",
                name: s.to_string(),
                known: known.join(", "),
            }
        })
    }
}

/// What a check is asked to do.
#[derive(Clone, Debug)]
pub struct CheckRequest {
    /// The rasterizer under test.
    pub subject: SubjectSpec,
    /// What the cases hold (default: the back-end's kind, or triangles).
    pub kind: Option<Kind>,
    /// Triangles: what they are judged by (default: exact under top-left).
    pub rule: Option<RuleChoice>,
    /// Lines: the convention (default: midpoint).
    pub convention: Option<ConventionChoice>,
    /// Polygons: the winding rule they are filled by (default: even-odd).
    pub fill: Option<WindingRule>,
    /// How many cases.
    pub cases: u32,
    /// The generator's seed.
    pub seed: u64,
    /// How long a program may take on one case.
    pub timeout: Duration,
    /// How many cases run at once.
    pub jobs: usize,
    /// Run every case and score them, instead of stopping at the first
    /// failure.
    pub keep_going: bool,
    /// Judge this one case (a counterexample file, a teacher's own case)
    /// instead of generated ones.
    pub case_file: Option<PathBuf>,
    /// Where `counterexample.txt`, `counterexample.svg` and `report.html`
    /// are written (nothing is written when `None`).
    pub out: Option<PathBuf>,
    /// The command line that asked for the check, recorded in the report.
    pub command: String,
    /// The most runs of the subject while shrinking.
    pub shrink_runs: u32,
    /// Triangles under one fill rule: the samples per pixel (1, 2, 4, 8
    /// or 16, on the standard pattern) whose coverage masks are judged
    /// (`--msaa N`); `None` for one sample at the pixel centre.
    pub msaa: Option<u32>,
    /// Points per family in a grader's report, by family name (a
    /// teacher's configuration, [`CheckConfig`](super::CheckConfig));
    /// a family not named is worth one point a case.
    pub weights: Vec<(String, f64)>,
    /// Which way the subject's y grows ([`Origin`]).
    pub origin: Origin,
    /// How the cases' vertices are snapped before they are judged
    /// ([`Snapping`]: 1/256 px by default).
    pub snapping: Snapping,
}

impl CheckRequest {
    /// 150 cases of seed 0, one at a time, 5 s a case, stopping at the
    /// first failure; nothing written, no progress shown.
    pub fn new(subject: SubjectSpec) -> CheckRequest {
        CheckRequest {
            subject,
            kind: None,
            rule: None,
            convention: None,
            fill: None,
            cases: 150,
            seed: 0,
            timeout: Duration::from_secs(5),
            jobs: 1,
            keep_going: false,
            case_file: None,
            out: None,
            command: String::new(),
            shrink_runs: 150,
            msaa: None,
            weights: Vec::new(),
            origin: Origin::TopLeft,
            snapping: Snapping::default(),
        }
    }
}

/// More cases than this are refused: a check is for minutes, not hours.
pub const MAX_CASES: u32 = 1_000_000;
/// More parallel cases than this are refused.
pub const MAX_JOBS: usize = 256;

/// Pass, fail or broken.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum VerdictWord {
    /// Every case held (under `any`: some rule is followed on every case).
    Pass,
    /// Some case failed.
    Fail,
    /// The subject could not be judged: it did not start, failed, hung or
    /// printed something that is not fragments.
    Broken,
}

/// Cases of one family: how many passed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FamilyTally {
    /// The family's name.
    pub family: String,
    /// Cases that held.
    pub passed: u32,
    /// Cases run.
    pub total: u32,
    /// The family's failing cases that the named cause explains (`None`
    /// when no cause was named or the family has no failure; all of a
    /// family's failures are known only under `keep_going`).
    pub explained_by_cause: Option<u32>,
    /// The points the family is worth in a grader's report, shared among
    /// its cases: its weight in the request, or one a case.
    pub points: f64,
}

/// One failing case, as found (not shrunk).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CaseFailure {
    /// The case's 0-based index.
    pub case_index: u32,
    /// Its family.
    pub family: String,
    /// The kind of its first problem.
    pub kind: FailureKind,
    /// Its first problem (for a case without an answer, what went
    /// wrong).
    pub problem: String,
    /// For a case the program gave no answer to
    /// ([`FailureKind::NoAnswer`]), the case as generated, which the
    /// program can be rerun on; `None` for the others.
    pub input: Option<String>,
}

/// The shrunk counterexample of a failure.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Counterexample {
    /// The property it fails.
    pub property: String,
    /// The index of the case it was shrunk from.
    pub case_index: u32,
    /// That case's family.
    pub family: String,
    /// That case's first problem, before shrinking.
    pub original_problem: String,
    /// Primitives in the case before shrinking.
    pub original_primitives: usize,
    /// The kind of failure (kept while shrinking).
    pub kind: FailureKind,
    /// Primitives in the shrunk case.
    pub primitives: usize,
    /// The shrunk case's target width.
    pub width: u32,
    /// The shrunk case's target height.
    pub height: u32,
    /// Every problem of the shrunk case.
    pub problems: Vec<String>,
    /// The explanation in one line: the cause, with its evidence and the
    /// failing cases it was confirmed on, or "no cause in the catalogue
    /// explains it" and the facts.
    pub diagnosis: Option<String>,
    /// The cause the reference confirmed, if any.
    pub cause: Option<Diagnosis>,
    /// Pixels missing, as `[x, y, primitive]`; under `--msaa`,
    /// `[x, y, primitive, mask]` with the rule's mask.
    pub missing: Vec<Vec<i64>>,
    /// Fragments extra, as `[x, y, primitive]`; under `--msaa`,
    /// `[x, y, primitive, mask]` with the mask drawn (a pixel drawn with
    /// another mask is both missing and extra).
    pub extra: Vec<Vec<i64>>,
    /// The counterexample file's text (an input the program can be rerun
    /// on).
    pub input: String,
    /// The files written.
    pub files: Vec<String>,
}

/// A subject that could not be judged.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BrokenReport {
    /// What went wrong.
    pub message: String,
    /// The case on which it first broke.
    pub case_index: u32,
    /// That case's family.
    pub family: String,
    /// True when it breaks on every input, the simplest included.
    pub on_every_input: bool,
    /// True when `input` was shrunk (a hang or endless output is not
    /// rerun to shrink it).
    pub shrunk: bool,
    /// The input that triggers it (shrunk, unless it breaks on every
    /// input).
    pub input: String,
    /// The files written.
    pub files: Vec<String>,
}

/// One fill rule of the rule table.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RuleRow {
    /// The rule (or line convention), or `watertight` / `crack-free` for
    /// the two mesh properties.
    pub rule: String,
    /// The cases it is judged on: `all`, `mesh` (the mesh cases), and for
    /// lines `screen` (endpoints in screen coordinates) or `whole-pixel`
    /// (endpoints that are pixel indices).
    pub cases: String,
    /// Cases on which the subject draws exactly what the rule does (or,
    /// for the mesh properties, which hold).
    pub agreeing: u32,
    /// Cases judged (the mesh properties: only mesh cases).
    pub total: u32,
    /// The first case that does not agree.
    pub first_disagreeing: Option<u32>,
}

/// The answer to "which rule does it follow?".
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RuleTable {
    /// Every fill rule.
    pub rows: Vec<RuleRow>,
    /// The rules agreeing on every case (empty: none).
    pub followed: Vec<String>,
    /// The rule agreeing on the most cases (the first of them in
    /// `FillRule::ALL`'s order), whose first failure is shrunk when it is
    /// not followed.
    pub closest: String,
    /// The watertight verdict on the mesh cases (triangles only).
    pub watertight: Option<RuleRow>,
    /// The crack-free verdict on the mesh cases (triangles only).
    pub crack_free: Option<RuleRow>,
}

/// The outcome of [`run`](super::run): printed as text (`Display`) or JSON
/// (`Serialize`, the same shape for every verdict).
#[derive(Clone, Debug, Serialize)]
pub struct CheckReport {
    /// The shape's name and version: `rasterlab-check-report/2`.
    pub schema: &'static str,
    /// Pass, fail or broken.
    pub verdict: VerdictWord,
    /// The property's stable identifier (`exact-top-left`, `watertight`,
    /// `crack-free`, `line-midpoint`, ..., or `any`).
    pub property: String,
    /// The property in words.
    pub description: String,
    /// Samples per pixel: 1, or under `--msaa N` the N whose coverage
    /// masks were judged.
    pub samples: u32,
    /// Where the subject's origin is (`top-left`, or `bottom-left`: y
    /// up). The pixels of the report (`missing`, `extra`, the failing
    /// cases' sentences) are always the protocol's, y down; a
    /// counterexample's `input` is as the subject was given it.
    pub origin: String,
    /// The subject: its command line, or `backend NAME`.
    pub subject: String,
    /// The check's own command line, as recorded by the caller.
    pub command: String,
    /// The generator's seed.
    pub seed: u64,
    /// Cases asked for.
    pub cases: u32,
    /// Whether every case was run (`keep_going`), not only up to the
    /// first failure.
    pub keep_going: bool,
    /// Cases run.
    pub cases_run: u32,
    /// Cases that held (under `any`: agreeing with the closest rule).
    pub passed: u32,
    /// `passed / cases_run` (0 when no case ran).
    pub score: f64,
    /// Per family, in the order the families cycle.
    pub families: Vec<FamilyTally>,
    /// The failing cases found, unshrunk (all of them under
    /// `keep_going`, else the first).
    pub failing_cases: Vec<CaseFailure>,
    /// The shrunk counterexample of the first failure.
    pub counterexample: Option<Counterexample>,
    /// Under `keep_going`: the first failure of each failing family,
    /// shrunk, in the order of the families (the first failure's own is
    /// also `counterexample`), so that a grader's test per family shows
    /// its own; empty otherwise.
    pub counterexamples: Vec<Counterexample>,
    /// Why the subject could not be judged.
    pub error: Option<BrokenReport>,
    /// Under `--rule any` or `--convention any`: the table.
    pub rules: Option<RuleTable>,
    /// The shrunk finding itself, for its grid and picture.
    #[serde(skip)]
    pub finding: Option<Box<Finding>>,
}

impl CheckReport {
    /// The exit status the command gives: 0 pass, 1 fail, 2 broken.
    pub fn exit_code(&self) -> i32 {
        match self.verdict {
            VerdictWord::Pass => 0,
            VerdictWord::Fail => 1,
            VerdictWord::Broken => 2,
        }
    }

    /// The verdict as a result, for a program's exit: `Ok` on a pass; on
    /// a fail, [`Error::Mismatch`] with the shrunk case's first problem
    /// (exit status 1); on a broken subject, [`Error::InvalidArgument`]
    /// with what went wrong, whether it fails so on every input, and the
    /// file holding the shrunk input that triggers it (exit status 2).
    pub fn outcome(&self) -> Result<()> {
        match self.verdict {
            VerdictWord::Pass => Ok(()),
            // The shrunk case's problem, which the report has just shown.
            VerdictWord::Fail => Err(Error::Mismatch(format!(
                "the check failed: {}",
                self.counterexample
                    .as_ref()
                    .and_then(|c| c.problems.first())
                    .or(self.failing_cases.first().map(|f| &f.problem))
                    .map_or("no rule is followed", String::as_str)
            ))),
            VerdictWord::Broken => Err(Error::InvalidArgument(self.error.as_ref().map_or_else(
                || "the subject is broken".to_string(),
                |e| {
                    let mut m = e.message.clone();
                    if e.on_every_input {
                        m.push_str(
                            "\nit fails so on every input, the simplest included: broken, not wrong",
                        );
                    } else {
                        m.push_str(if e.shrunk {
                            "\nthe input that triggers it (shrunk)"
                        } else {
                            "\nthe input that triggers it"
                        });
                    }
                    if let Some(f) = e.files.first() {
                        m.push_str(&format!(": {f}"));
                    }
                    m
                },
            ))),
        }
    }
}

/// A program's time limit on one case from seconds, as `--timeout` gives
/// it: more than 0 and at most an hour (NaN and infinities are refused).
pub fn timeout_from_seconds(seconds: f64) -> Result<Duration> {
    if !(seconds > 0.0 && seconds <= 3600.0) {
        return Err(Error::InvalidArgument(format!(
            "--timeout must be more than 0 and at most 3600 seconds, not {seconds}"
        )));
    }
    Ok(Duration::from_secs_f64(seconds))
}

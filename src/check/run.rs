//! The whole check, as `rasterlab check` runs it: a [`CheckRequest`] in, a
//! [`CheckReport`] out.
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
//! failure.
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

use super::case::Case;
use super::generate;
use super::judge::{judge, FailureKind, Finding, LineConvention, Property, Provenance};
use super::program::Program;
use super::{broken, shrink, Builtin, Fragment, Subject, SubjectError};
use crate::error::{Error, Result};
use crate::raster::backend::{backend, Backend};
use crate::raster::edge::FillRule;
use serde::Serialize;
use std::fmt::{self, Write as _};
use std::path::PathBuf;
use std::str::FromStr;
use std::time::Duration;

/// The rasterizer a check judges.
#[derive(Clone, Debug, PartialEq)]
pub enum SubjectSpec {
    /// An outside program: a command line run once per case (see
    /// [`Program`]).
    Exec(String),
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
}

crate::names::named_enum!(Kind, "kind", Triangles = "triangles", Lines = "lines");

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
    pub convention: Option<LineConvention>,
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
    /// Show progress bars on standard error (when it is a terminal; with
    /// the `cli` feature).
    pub progress: bool,
    /// The most runs of the subject while shrinking.
    pub shrink_runs: u32,
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
            cases: 150,
            seed: 0,
            timeout: Duration::from_secs(5),
            jobs: 1,
            keep_going: false,
            case_file: None,
            out: None,
            command: String::new(),
            progress: false,
            shrink_runs: 150,
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
    /// Its first problem.
    pub problem: String,
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
    /// The explanation, where one can be given.
    pub diagnosis: Option<String>,
    /// Pixels missing, as `[x, y, primitive]`.
    pub missing: Vec<[i64; 3]>,
    /// Fragments extra, as `[x, y, primitive]`.
    pub extra: Vec<[i64; 3]>,
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
    /// The input that triggers it (shrunk, unless it breaks on every
    /// input).
    pub input: String,
    /// The files written.
    pub files: Vec<String>,
}

/// One fill rule of the rule table.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RuleRow {
    /// The rule, or `watertight` / `crack-free` for the two mesh
    /// properties.
    pub rule: String,
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
    /// The watertight verdict on the mesh cases.
    pub watertight: RuleRow,
    /// The crack-free verdict on the mesh cases.
    pub crack_free: RuleRow,
}

/// The outcome of [`run`]: printed as text (`Display`) or JSON
/// (`Serialize`, the same shape for every verdict).
#[derive(Clone, Debug, Serialize)]
pub struct CheckReport {
    /// The shape's name and version: `rasterlab-check-report/1`.
    pub schema: &'static str,
    /// Pass, fail or broken.
    pub verdict: VerdictWord,
    /// The property's stable identifier (`exact-top-left`, `watertight`,
    /// `crack-free`, `line-midpoint`, ..., or `any`).
    pub property: String,
    /// The property in words.
    pub description: String,
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
    /// Why the subject could not be judged.
    pub error: Option<BrokenReport>,
    /// Under `any`: the rule table.
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
                        m.push_str("\nthe input that triggers it (shrunk)");
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

/// What the check judges by.
#[derive(Copy, Clone, Debug, PartialEq)]
enum Mode {
    One(Property),
    Any,
}

impl Mode {
    /// The property whose generator makes case `index`, and its family.
    fn case_property(self, index: u32) -> (Property, u32) {
        match self {
            Mode::One(p) => (p, index),
            Mode::Any if index.is_multiple_of(2) => (Property::Exact(FillRule::TopLeft), index / 2),
            Mode::Any => (Property::Watertight, index / 2),
        }
    }

    fn family(self, index: u32) -> &'static str {
        let (p, i) = self.case_property(index);
        generate::family(p, i)
    }

    /// Every family, in order, each once.
    fn families(self) -> Vec<&'static str> {
        let mut out: Vec<&'static str> = Vec::new();
        let lists: Vec<&[&str]> = match self {
            Mode::One(p) => vec![generate::families(p)],
            Mode::Any => vec![
                generate::families(Property::Exact(FillRule::TopLeft)),
                generate::families(Property::Watertight),
            ],
        };
        for f in lists.into_iter().flatten() {
            if !out.contains(f) {
                out.push(f);
            }
        }
        out
    }
}

/// One subject per worker.
type Factory<'a> = Box<dyn Fn() -> Box<dyn Subject + Send> + Sync + 'a>;

type Custom<'a> = Option<(&'a str, &'a (dyn Fn() -> Box<dyn Subject + Send> + Sync))>;

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

fn run_inner(request: &CheckRequest, custom: Custom<'_>) -> Result<CheckReport> {
    let chosen = match (&request.subject, custom) {
        (SubjectSpec::Backend(name), None) => Some(backend(name)?),
        _ => None,
    };
    let kind = match (request.kind, chosen) {
        (Some(k), _) => k,
        (None, Some(Backend::Line(_))) => Kind::Lines,
        (None, _) => Kind::Triangles,
    };
    if kind == Kind::Lines && request.rule.is_some() {
        return Err(Error::InvalidArgument(
            "--rule is for triangles; lines are judged by --convention".into(),
        ));
    }
    if kind == Kind::Triangles && request.convention.is_some() {
        return Err(Error::InvalidArgument(
            "--convention is for lines; triangles are judged by --rule".into(),
        ));
    }
    let mode = match kind {
        Kind::Lines => Mode::One(Property::Line(
            request.convention.unwrap_or(LineConvention::Midpoint),
        )),
        Kind::Triangles => match request.rule.unwrap_or(RuleChoice::Exact(FillRule::TopLeft)) {
            RuleChoice::Exact(rule) => Mode::One(Property::Exact(rule)),
            RuleChoice::Watertight => Mode::One(Property::Watertight),
            RuleChoice::CrackFree => Mode::One(Property::CrackFree),
            RuleChoice::Any => Mode::Any,
        },
    };
    if !(1..=MAX_CASES).contains(&request.cases) {
        return Err(Error::InvalidArgument(format!(
            "--cases must be between 1 and {MAX_CASES}, not {}",
            request.cases
        )));
    }
    if !(1..=MAX_JOBS).contains(&request.jobs) {
        return Err(Error::InvalidArgument(format!(
            "--jobs must be between 1 and {MAX_JOBS}, not {}",
            request.jobs
        )));
    }
    timeout_from_seconds(request.timeout.as_secs_f64())?;
    let given = match &request.case_file {
        Some(path) => {
            let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
                path: path.clone(),
                message: e.to_string(),
            })?;
            let case = Case::from_text(&text).map_err(|e| Error::Parse {
                path: path.clone(),
                line: None,
                message: e.to_string(),
            })?;
            crate::raster::target::RenderTarget::check_size(case.width, case.height)?;
            let fits = match kind {
                Kind::Lines => case.triangles.is_empty() && !case.lines.is_empty(),
                Kind::Triangles => case.lines.is_empty() && !case.triangles.is_empty(),
            };
            if !fits {
                return Err(Error::InvalidArgument(format!(
                    "{}: the case must hold {} only",
                    path.display(),
                    if kind == Kind::Lines {
                        "line segments (four numbers a line)"
                    } else {
                        "triangles (six numbers a line)"
                    }
                )));
            }
            Some(case)
        }
        None => None,
    };
    if let Some(out) = &request.out {
        crate::output::check_dir(out)?;
    }
    let (subject_name, factory) = match custom {
        Some((name, make)) => (name.to_string(), Box::new(make) as Factory<'_>),
        None => subject_factory(request, chosen, kind, mode)?,
    };
    let mut report = Checker {
        request,
        mode,
        factory,
    }
    .check(given)?;
    report.subject = subject_name;
    Ok(report)
}

/// [`run`] on a subject of the caller's (a closure, a rasterizer in the
/// caller's own crate): `make` makes one subject per job; `name` is the
/// subject's name in the report. The request's `subject` is not used
/// (its `kind` says what the cases hold).
pub fn run_with(
    request: &CheckRequest,
    name: &str,
    make: &(dyn Fn() -> Box<dyn Subject + Send> + Sync),
) -> Result<CheckReport> {
    run_inner(request, Some((name, make)))
}

/// Runs a check.
///
/// Errors are mistakes in the request (an unknown back-end, a rule given
/// for lines, too many cases, an unreadable case file, an output folder
/// that cannot be written); what the subject does is the report.
pub fn run(request: &CheckRequest) -> Result<CheckReport> {
    run_inner(request, None)
}

/// The subject's name in the report, and a maker of subjects.
fn subject_factory<'a>(
    request: &'a CheckRequest,
    chosen: Option<Backend>,
    kind: Kind,
    mode: Mode,
) -> Result<(String, Factory<'a>)> {
    let rule = match mode {
        Mode::One(Property::Exact(rule)) => rule,
        _ => FillRule::TopLeft,
    };
    Ok(match (chosen, &request.subject) {
        (Some(Backend::Triangle(b)), SubjectSpec::Backend(name)) if kind == Kind::Triangles => (
            format!("backend {name}"),
            Box::new(move || Box::new(Builtin::triangles(b, rule)) as Box<dyn Subject + Send>),
        ),
        (Some(Backend::Line(b)), SubjectSpec::Backend(name)) if kind == Kind::Lines => {
            let pixel_index = mode == Mode::One(Property::Line(LineConvention::PixelIndex));
            (
                format!("backend {name}"),
                Box::new(move || {
                    if pixel_index {
                        // Pixel indices name pixels: the segment runs
                        // between their centres.
                        Box::new(
                            move |c: &Case| -> std::result::Result<Vec<Fragment>, SubjectError> {
                                let mut centred = c.clone();
                                for l in &mut centred.lines {
                                    *l = l.map(|p| (p.0.round() + 0.5, p.1.round() + 0.5));
                                }
                                Builtin::Lines(b).draw(&centred)
                            },
                        ) as Box<dyn Subject + Send>
                    } else {
                        Box::new(Builtin::Lines(b)) as Box<dyn Subject + Send>
                    }
                }),
            )
        }
        (Some(_), SubjectSpec::Backend(name)) => {
            return Err(Error::InvalidArgument(format!(
                "back-end `{name}` does not draw {}",
                if kind == Kind::Lines {
                    "lines"
                } else {
                    "triangles"
                }
            )))
        }
        (_, SubjectSpec::Exec(command)) => {
            let word = match mode {
                Mode::One(Property::Exact(rule)) => rule.name(),
                Mode::One(Property::Watertight) => "watertight",
                Mode::One(Property::CrackFree) => "crack-free",
                Mode::One(Property::Line(c)) => c.name(),
                Mode::Any => "any",
            };
            let mut program = Program::new(command, word);
            program.timeout = request.timeout;
            (
                command.clone(),
                Box::new(move || Box::new(program.clone()) as Box<dyn Subject + Send>),
            )
        }
        (None, SubjectSpec::Backend(_)) => unreachable!("a back-end name was resolved"),
    })
}

/// What one case came to.
enum Outcome {
    /// Under one property: the finding, if it fails.
    One(Option<Box<Finding>>),
    /// Under `any`: per rule (in `FillRule::ALL` order), then watertight
    /// and crack-free (mesh cases only), the finding if it fails.
    Any(Vec<Option<Box<Finding>>>, bool),
}

struct Checker<'a> {
    request: &'a CheckRequest,
    mode: Mode,
    factory: Factory<'a>,
}

impl Checker<'_> {
    fn check(&self, given: Option<Case>) -> Result<CheckReport> {
        let request = self.request;
        let total = if given.is_some() { 1 } else { request.cases };
        let family_of = |index: u32| -> &'static str {
            if given.is_some() {
                "file"
            } else {
                self.mode.family(index)
            }
        };
        let mut rng = fastrand::Rng::with_seed(request.seed);
        let bar = progress_bar(request.progress, u64::from(total), "cases");
        let mut subjects: Vec<Box<dyn Subject + Send>> =
            (0..request.jobs).map(|_| (self.factory)()).collect();
        let chunk = (request.jobs * 4).max(8) as u32;
        let mut outcomes: Vec<(u32, Case, Outcome)> = Vec::new();
        let mut broken_at: Option<(u32, Case, SubjectError)> = None;
        let mut next = 0;
        'cases: while next < total {
            let end = (next + chunk).min(total);
            let cases: Vec<(u32, Case)> = (next..end)
                .map(|i| {
                    let case = match &given {
                        Some(c) => c.clone(),
                        None => {
                            let (p, k) = self.mode.case_property(i);
                            generate::case(p, k, &mut rng)
                        }
                    };
                    (i, case)
                })
                .collect();
            next = end;
            let drawn = draw_all(&mut subjects, &cases);
            for ((index, case), drawn) in cases.into_iter().zip(drawn) {
                bar.inc(1);
                let drawn = match drawn {
                    Ok(d) => d,
                    Err(e) => {
                        broken_at = Some((index, case, e));
                        break 'cases;
                    }
                };
                let outcome = self.judge(index, &case, &drawn);
                let failed = match &outcome {
                    Outcome::One(f) => f.is_some(),
                    Outcome::Any(..) => false,
                };
                outcomes.push((index, case, outcome));
                if failed && !request.keep_going {
                    break 'cases;
                }
            }
        }
        bar.finish_and_clear();
        let subject = subjects.first_mut().expect("at least one job");
        let mut report = CheckReport {
            schema: "rasterlab-check-report/1",
            verdict: VerdictWord::Pass,
            property: match self.mode {
                Mode::One(p) => p.id(),
                Mode::Any => "any".into(),
            },
            description: match self.mode {
                Mode::One(p) => p.to_string(),
                Mode::Any => "which fill rule: every rule, and watertight and crack-free".into(),
            },
            subject: String::new(),
            command: request.command.clone(),
            seed: request.seed,
            cases: request.cases,
            keep_going: request.keep_going,
            cases_run: outcomes.len() as u32,
            passed: 0,
            score: 0.0,
            families: Vec::new(),
            failing_cases: Vec::new(),
            counterexample: None,
            error: None,
            rules: None,
            finding: None,
        };
        if let Some((index, case, error)) = broken_at {
            let b = broken(error, &case, index, subject.as_mut(), request.shrink_runs);
            let mut files = Vec::new();
            let family = family_of(index).to_string();
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
                input,
                files,
            });
        }
        // The first failure to shrink, and the tallies.
        let families = self.mode.families();
        let mut tally: Vec<FamilyTally> = families
            .iter()
            .map(|f| FamilyTally {
                family: (*f).to_string(),
                passed: 0,
                total: 0,
            })
            .collect();
        let mut first: Option<(u32, Box<Finding>, usize)> = None;
        match self.mode {
            Mode::One(_) => {
                for (index, case, outcome) in &outcomes {
                    let Outcome::One(f) = outcome else { continue };
                    let family = family_of(*index);
                    let t = tally_for(&mut tally, family);
                    t.total += 1;
                    match f {
                        None => t.passed += 1,
                        Some(f) => {
                            report.failing_cases.push(CaseFailure {
                                case_index: *index,
                                family: family.to_string(),
                                kind: f.kind(),
                                problem: f.problems[0].clone(),
                            });
                            if first.is_none() {
                                first = Some((*index, f.clone(), case.len()));
                            }
                        }
                    }
                }
            }
            Mode::Any => {
                let table = self.rule_table(&outcomes);
                let closest = FillRule::ALL
                    .iter()
                    .position(|r| r.name() == table.closest)
                    .unwrap_or(0);
                for (index, case, outcome) in &outcomes {
                    let Outcome::Any(per_rule, _) = outcome else {
                        continue;
                    };
                    let family = family_of(*index);
                    let t = tally_for(&mut tally, family);
                    t.total += 1;
                    match &per_rule[closest] {
                        None => t.passed += 1,
                        Some(f) => {
                            report.failing_cases.push(CaseFailure {
                                case_index: *index,
                                family: family.to_string(),
                                kind: f.kind(),
                                problem: f.problems[0].clone(),
                            });
                            if first.is_none() {
                                first = Some((*index, f.clone(), case.len()));
                            }
                        }
                    }
                }
                if !request.keep_going {
                    report.failing_cases.truncate(1);
                }
                report.rules = Some(table);
            }
        }
        tally.retain(|t| t.total > 0);
        report.passed = tally.iter().map(|t| t.passed).sum();
        report.score = if report.cases_run == 0 {
            0.0
        } else {
            f64::from(report.passed) / f64::from(report.cases_run)
        };
        report.families = tally;
        if let Some((index, finding, original_primitives)) = first {
            if report.verdict == VerdictWord::Pass {
                report.verdict = VerdictWord::Fail;
            }
            let shrink_bar = progress_bar(
                request.progress,
                u64::from(request.shrink_runs),
                "shrinking runs",
            );
            let mut shrunk = shrink::shrink(
                *finding,
                subject.as_mut(),
                request.shrink_runs,
                &mut |runs| shrink_bar.set_position(u64::from(runs)),
            );
            shrink_bar.finish_and_clear();
            shrunk.provenance = Some(Provenance {
                command: request.command.clone(),
                seed: request.seed,
                case_index: index,
                family: family_of(index).to_string(),
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
            let pixels = |v: &[Fragment]| -> Vec<[i64; 3]> {
                v.iter().map(|f| [f.x, f.y, i64::from(f.id)]).collect()
            };
            report.counterexample = Some(Counterexample {
                property: shrunk.property.id(),
                case_index: index,
                family: family_of(index).to_string(),
                original_problem: shrunk.original_problem.clone().unwrap_or_default(),
                original_primitives,
                kind: shrunk.kind(),
                primitives: shrunk.case.len(),
                width: shrunk.case.width,
                height: shrunk.case.height,
                problems: shrunk.problems.clone(),
                diagnosis: shrunk.diagnosis.clone(),
                missing: pixels(&shrunk.missing),
                extra: pixels(&shrunk.extra),
                input: shrunk.counterexample_text(),
                files,
            });
            report.finding = Some(Box::new(shrunk));
        }
        if let Some(table) = &report.rules {
            if report.verdict != VerdictWord::Broken {
                report.verdict = if table.followed.is_empty() {
                    VerdictWord::Fail
                } else {
                    VerdictWord::Pass
                };
            }
        }
        Ok(report)
    }

    /// Judges one drawn case.
    fn judge(&self, index: u32, case: &Case, drawn: &[Fragment]) -> Outcome {
        match self.mode {
            Mode::One(p) => Outcome::One(judge(p, case, drawn).map(Box::new)),
            Mode::Any => {
                let mesh = self.request.case_file.is_none() && index % 2 == 1;
                let mut per: Vec<Option<Box<Finding>>> = FillRule::ALL
                    .iter()
                    .map(|&r| judge(Property::Exact(r), case, drawn).map(Box::new))
                    .collect();
                if mesh {
                    for p in [Property::Watertight, Property::CrackFree] {
                        per.push(judge(p, case, drawn).map(Box::new));
                    }
                }
                Outcome::Any(per, mesh)
            }
        }
    }

    /// The rule table of an `any` check.
    fn rule_table(&self, outcomes: &[(u32, Case, Outcome)]) -> RuleTable {
        let row = |name: &str, k: usize, mesh_only: bool| {
            let mut r = RuleRow {
                rule: name.to_string(),
                agreeing: 0,
                total: 0,
                first_disagreeing: None,
            };
            for (index, _, outcome) in outcomes {
                let Outcome::Any(per, mesh) = outcome else {
                    continue;
                };
                if mesh_only && !mesh {
                    continue;
                }
                r.total += 1;
                if per.get(k).is_some_and(Option::is_none) {
                    r.agreeing += 1;
                } else if r.first_disagreeing.is_none() {
                    r.first_disagreeing = Some(*index);
                }
            }
            r
        };
        let rows: Vec<RuleRow> = FillRule::ALL
            .iter()
            .enumerate()
            .map(|(k, r)| row(r.name(), k, false))
            .collect();
        let n = FillRule::ALL.len();
        let followed = rows
            .iter()
            .filter(|r| r.total > 0 && r.agreeing == r.total)
            .map(|r| r.rule.clone())
            .collect();
        let best = rows.iter().map(|r| r.agreeing).max().unwrap_or(0);
        let closest = rows
            .iter()
            .find(|r| r.agreeing == best)
            .map_or_else(String::new, |r| r.rule.clone());
        RuleTable {
            rows,
            followed,
            closest,
            watertight: row("watertight", n, true),
            crack_free: row("crack-free", n + 1, true),
        }
    }
}

fn tally_for<'t>(tally: &'t mut Vec<FamilyTally>, family: &str) -> &'t mut FamilyTally {
    if let Some(k) = tally.iter().position(|t| t.family == family) {
        &mut tally[k]
    } else {
        tally.push(FamilyTally {
            family: family.to_string(),
            passed: 0,
            total: 0,
        });
        tally.last_mut().expect("just pushed")
    }
}

/// Draws the cases, `subjects.len()` at a time, each worker with its own
/// subject; the results in the order of the cases.
fn draw_all(
    subjects: &mut [Box<dyn Subject + Send>],
    cases: &[(u32, Case)],
) -> Vec<std::result::Result<Vec<Fragment>, SubjectError>> {
    if subjects.len() == 1 {
        return cases.iter().map(|(_, c)| subjects[0].draw(c)).collect();
    }
    let next = std::sync::atomic::AtomicUsize::new(0);
    let mut results: Vec<Option<std::result::Result<Vec<Fragment>, SubjectError>>> =
        (0..cases.len()).map(|_| None).collect();
    let slots = std::sync::Mutex::new(&mut results);
    std::thread::scope(|scope| {
        for subject in subjects.iter_mut() {
            let (next, slots) = (&next, &slots);
            scope.spawn(move || loop {
                let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some((_, case)) = cases.get(k) else {
                    break;
                };
                let r = subject.draw(case);
                if let Ok(mut s) = slots.lock() {
                    s[k] = Some(r);
                }
            });
        }
    });
    results
        .into_iter()
        .map(|r| r.unwrap_or_else(|| Err(SubjectError::Start("a worker stopped".into()))))
        .collect()
}

/// A progress bar on standard error, hidden when not asked for or when
/// standard error is not a terminal (with the `cli` feature; without it,
/// nothing is shown).
#[cfg(feature = "cli")]
fn progress_bar(show: bool, len: u64, what: &str) -> indicatif::ProgressBar {
    if !show {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    if let Ok(style) =
        indicatif::ProgressStyle::with_template("{msg} {bar:30} {pos}/{len} {elapsed}")
    {
        bar.set_style(style);
    }
    bar.set_message(what.to_string());
    bar
}

/// Progress not shown: the library alone has no progress bars.
#[cfg(not(feature = "cli"))]
fn progress_bar(_show: bool, _len: u64, _what: &str) -> NoBar {
    NoBar
}

/// A progress bar that shows nothing.
#[cfg(not(feature = "cli"))]
struct NoBar;

#[cfg(not(feature = "cli"))]
impl NoBar {
    fn inc(&self, _: u64) {}
    fn set_position(&self, _: u64) {}
    fn finish_and_clear(&self) {}
}

/// The comment lines that record where a case came from.
fn provenance_comment(p: &Provenance, case: &Case) -> String {
    format!(
        "# size {}x{}\n# command: {}\n# seed {}, case {} (family {})\n",
        case.width, case.height, p.command, p.seed, p.case_index, p.family
    )
}

impl fmt::Display for CheckReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut out = String::new();
        if let Some(table) = &self.rules {
            let _ = writeln!(
                out,
                "Which rule: {} cases of seed {} (watertight and crack-free on the {} mesh cases)",
                self.cases_run, self.seed, table.watertight.total
            );
            let _ = writeln!(
                out,
                "{:<16} {:>16}  first disagreeing case",
                "rule", "cases agreeing"
            );
            for r in table
                .rows
                .iter()
                .chain([&table.watertight, &table.crack_free])
            {
                let _ = writeln!(
                    out,
                    "{:<16} {:>16}  {}",
                    r.rule,
                    format!("{}/{}", r.agreeing, r.total),
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
                            "the input that triggers it (case {}, family {}, shrunk):",
                            e.case_index, e.family
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
                finding.property,
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
            let _ = writeln!(out, "# correct   ! extra (or drawn twice)   ? missing");
            out.push_str(&finding.ascii_grid());
            if let Some(d) = &c.diagnosis {
                let _ = writeln!(out, "diagnosis: {d}");
            }
            if let Some(file) = c.files.first() {
                let _ = writeln!(
                    out,
                    "counterexample: {file} (rerun: give it to the program as its input, or --case {file})"
                );
            }
            if let Some(file) = c.files.iter().find(|f| f.ends_with(".html")) {
                let _ = writeln!(out, "report: {file}");
            }
        }
        f.write_str(out.trim_end())
    }
}

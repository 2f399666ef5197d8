//! The engine of every check: generate the cases, draw them, judge them,
//! find the cause of the failures, shrink the first.
//!
//! [`run`] (the `rasterlab check` command) and [`check`](super::check)
//! (a rasterizer in a `#[test]`) are this one engine: the first with the
//! [`CheckRequest`] a command line gives and a pool of subjects for
//! `--jobs`, the second with one property and the caller's subject. What
//! the engine is doing is told to a callback ([`Progress`]), which the
//! command line turns into progress bars.
//!
//! In order:
//!
//! 1. **Cases.** Case `i` comes from the families of the property (under
//!    `--rule any`, even cases from the exact families and odd ones from
//!    the mesh families; under `--convention any`, even cases in screen
//!    coordinates and odd ones with whole-pixel endpoints), from one
//!    seeded generator, so a seed names the same cases in every run.
//! 2. **Judgement.** Each drawn case is judged; without `keep_going` the
//!    run stops at the first failure.
//! 3. **Confirmation.** A run that stopped at its first failure draws up
//!    to [`CONFIRMING_CASES`] more cases, then as many of the first
//!    failure's family (from a generator seeded by the seed and the case's
//!    index), until [`CONFIRMING_FAILURES`] fail, so that a cause is tried
//!    on more than one failure and two causes that fit one case can be
//!    told apart. They are not scored.
//! 4. **Cause.** [`cause::diagnose`] tries the
//!    catalogue on the failing cases as generated, and holds each change
//!    against the passing cases. A cause named so far is then probed:
//!    of [`PROBE_CASES`] more cases, those where it and one of its rivals
//!    (it together with another change) draw differently are given to the
//!    subject ([`PROBE_RUNS`] at most), and the cause is looked for again
//!    with what the subject drew there.
//! 5. **Shrinking.** The first failure is shrunk, keeping its kind and the
//!    cause found, and written out.

use super::case::Case;
use super::cause::{self, Diagnosis};
use super::generate;
use super::judge::{judge, Finding, LineConvention, Property, Provenance};
use super::program::Program;
use super::property::with_samples;
use super::request::{
    timeout_from_seconds, BrokenReport, CaseFailure, CheckReport, CheckRequest, ConventionChoice,
    Counterexample, FamilyTally, Kind, RuleChoice, RuleRow, RuleTable, SubjectSpec, VerdictWord,
    MAX_CASES, MAX_JOBS,
};
use super::{broken, shrink, Broken, Builtin, Fragment, Subject, SubjectError};
use crate::error::{Error, Result};
use crate::raster::edge::FillRule;
use crate::raster::multisample::SamplePattern;
use crate::raster::registry::{backend, Backend};

/// Cases drawn after the first failure, at most, to confirm its cause:
/// the next ones of the run, then as many more of the first failure's
/// family.
pub const CONFIRMING_CASES: u32 = 30;
/// Failing cases, the first included, after which confirmation stops.
pub const CONFIRMING_FAILURES: usize = 10;
/// Cases generated (and drawn by the reference only) to find ones that
/// tell a named cause from its rivals ([`cause::rivals`]).
pub const PROBE_CASES: u32 = 100;
/// Of those, the most the subject draws.
pub const PROBE_RUNS: usize = 12;

/// What the engine is doing, told to the caller's callback.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Progress {
    /// `done` of `total` cases drawn and judged.
    Cases {
        /// Cases done.
        done: u32,
        /// Cases asked for.
        total: u32,
    },
    /// Cases drawn after the first failure to confirm its cause.
    Confirming {
        /// Cases done.
        done: u32,
        /// At most this many.
        total: u32,
    },
    /// Runs of the subject spent shrinking.
    Shrinking {
        /// Runs spent.
        runs: u32,
        /// At most this many.
        budget: u32,
    },
    /// The run is over.
    Done,
}

/// What the check judges by.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) enum Mode {
    One(Property),
    /// Every fill rule, and watertight and crack-free on the meshes.
    AnyRule,
    /// Every line convention, each on its kind of case.
    AnyConvention,
}

/// The rows of a table mode: the property each judges by, and whether it
/// is judged on mesh cases only (watertight, crack-free).
fn table_rows(mode: Mode) -> Vec<(Property, bool)> {
    match mode {
        Mode::One(_) => Vec::new(),
        Mode::AnyRule => FillRule::ALL
            .iter()
            .map(|&r| (Property::Exact(r), false))
            .chain([(Property::Watertight, true), (Property::CrackFree, true)])
            .collect(),
        Mode::AnyConvention => LineConvention::ALL
            .iter()
            .map(|&c| (Property::Line(c), false))
            .collect(),
    }
}

impl Mode {
    /// The property whose generator makes case `index`, and its index
    /// within that property's families.
    fn case_property(self, index: u32) -> (Property, u32) {
        match self {
            Mode::One(p) => (p, index),
            Mode::AnyRule if index.is_multiple_of(2) => {
                (Property::Exact(FillRule::TopLeft), index / 2)
            }
            Mode::AnyRule => (Property::Watertight, index / 2),
            Mode::AnyConvention if index.is_multiple_of(2) => {
                (Property::Line(LineConvention::Midpoint), index / 2)
            }
            Mode::AnyConvention => (Property::Line(LineConvention::PixelIndex), index / 2),
        }
    }

    /// Whether the table row `property` judges case `index` (`mesh_only`
    /// rows only the mesh cases; line conventions only cases of their
    /// kind of endpoints).
    fn judges(self, property: Property, mesh_only: bool, index: u32, from_file: bool) -> bool {
        match (self, property) {
            (Mode::AnyRule, _) => !mesh_only || (!from_file && index % 2 == 1),
            (Mode::AnyConvention, Property::Line(c)) => {
                from_file || c.whole_pixels() == (index % 2 == 1)
            }
            _ => true,
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
            Mode::AnyRule => vec![
                generate::families(Property::Exact(FillRule::TopLeft)),
                generate::families(Property::Watertight),
            ],
            Mode::AnyConvention => vec![
                generate::families(Property::Line(LineConvention::Midpoint)),
                generate::families(Property::Line(LineConvention::PixelIndex)),
            ],
        };
        for f in lists.into_iter().flatten() {
            if !out.contains(f) {
                out.push(f);
            }
        }
        out
    }

    /// The stable identifier of what is judged.
    fn id(self) -> String {
        match self {
            Mode::One(p) => p.id(),
            Mode::AnyRule => "any".into(),
            Mode::AnyConvention => "line-any".into(),
        }
    }

    fn description(self) -> String {
        match self {
            Mode::One(p) => p.to_string(),
            Mode::AnyRule => "which fill rule: every rule, and watertight and crack-free".into(),
            Mode::AnyConvention => "which line convention: every convention, the screen ones on cases in screen coordinates, the whole-pixel ones on cases whose endpoints are pixel indices".into(),
        }
    }
}

/// The subjects drawing the cases: the caller's one, or a pool of one per
/// job.
pub(crate) enum Subjects<'s> {
    /// One subject, drawing every case in turn.
    One(&'s mut dyn Subject),
    /// One subject per worker thread.
    Pool(Vec<Box<dyn Subject + Send>>),
}

impl Subjects<'_> {
    /// The subject that shrinks and confirms.
    fn first(&mut self) -> &mut dyn Subject {
        match self {
            Subjects::One(s) => &mut **s,
            Subjects::Pool(v) => v[0].as_mut(),
        }
    }

    /// How many cases are worth drawing at once.
    fn batch(&self) -> u32 {
        match self {
            Subjects::One(_) => 1,
            Subjects::Pool(v) => (v.len() * 4).max(8) as u32,
        }
    }

    /// Draws the cases, the pool's subjects in parallel; the results in
    /// the order of the cases.
    fn draw_all(
        &mut self,
        cases: &[(u32, Case)],
    ) -> Vec<std::result::Result<Vec<Fragment>, SubjectError>> {
        let subjects = match self {
            Subjects::One(s) => return draw_until_broken(&mut **s, cases),
            Subjects::Pool(v) if v.len() == 1 => return draw_until_broken(v[0].as_mut(), cases),
            Subjects::Pool(v) => v,
        };
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
}

/// The cases drawn one after another, up to the first that breaks the
/// subject (the engine stops there: a program that hangs is not made to
/// hang on the rest of the batch too).
fn draw_until_broken(
    subject: &mut dyn Subject,
    cases: &[(u32, Case)],
) -> Vec<std::result::Result<Vec<Fragment>, SubjectError>> {
    let mut out = Vec::with_capacity(cases.len());
    for (_, case) in cases {
        let result = subject.draw(case);
        let broken = result.is_err();
        out.push(result);
        if broken {
            break;
        }
    }
    out
}

/// One subject per worker.
type Factory<'a> = Box<dyn Fn() -> Box<dyn Subject + Send> + Sync + 'a>;

type Custom<'a> = Option<(&'a str, &'a (dyn Fn() -> Box<dyn Subject + Send> + Sync))>;

fn run_inner(
    request: &CheckRequest,
    custom: Custom<'_>,
    progress: &mut dyn FnMut(Progress),
) -> Result<CheckReport> {
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
        Kind::Lines => match request.convention {
            None => Mode::One(Property::Line(LineConvention::Midpoint)),
            Some(ConventionChoice::Exact(c)) => Mode::One(Property::Line(c)),
            Some(ConventionChoice::Any) => Mode::AnyConvention,
        },
        Kind::Triangles => match request.rule.unwrap_or(RuleChoice::Exact(FillRule::TopLeft)) {
            RuleChoice::Exact(rule) => Mode::One(Property::Exact(rule)),
            RuleChoice::Watertight => Mode::One(Property::Watertight),
            RuleChoice::CrackFree => Mode::One(Property::CrackFree),
            RuleChoice::Any => Mode::AnyRule,
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
    let mut samples = match request.msaa {
        None => None,
        Some(n) => {
            if !matches!(mode, Mode::One(Property::Exact(_))) {
                return Err(Error::InvalidArgument(
                    "--msaa judges the coverage masks of triangles under one fill rule \
                     (--rule top-left, bottom-right, ...): not lines, watertight, crack-free \
                     or any"
                        .into(),
                ));
            }
            Some(SamplePattern::standard(n)?)
        }
    };
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
            match (case.samples, samples) {
                (Some(a), Some(b)) if a != b => {
                    return Err(Error::InvalidArgument(format!(
                        "{} says `# msaa {}`, but --msaa {} was given",
                        path.display(),
                        a.count(),
                        b.count()
                    )))
                }
                (Some(_), None) if !matches!(mode, Mode::One(Property::Exact(_))) => {
                    return Err(Error::InvalidArgument(format!(
                        "{} is multisampled (`# msaa N`): it is judged under one fill rule",
                        path.display()
                    )))
                }
                (Some(a), None) => samples = Some(a),
                _ => {}
            }
            Some(Case { samples, ..case })
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
    let mut subjects = Subjects::Pool((0..request.jobs).map(|_| factory()).collect());
    let mut report = Checker {
        request,
        mode,
        samples,
    }
    .check(given, &mut subjects, progress)?
    .report;
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
    run_inner(request, Some((name, make)), &mut |_| {})
}

/// Runs a check.
///
/// Errors are mistakes in the request (an unknown back-end, a rule given
/// for lines, too many cases, an unreadable case file, an output folder
/// that cannot be written); what the subject does is the report.
pub fn run(request: &CheckRequest) -> Result<CheckReport> {
    run_inner(request, None, &mut |_| {})
}

/// [`run`], telling `progress` what it is doing (the command line's
/// progress bars).
pub fn run_with_progress(
    request: &CheckRequest,
    progress: &mut dyn FnMut(Progress),
) -> Result<CheckReport> {
    run_inner(request, None, progress)
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
            let pixel_index = matches!(mode, Mode::One(Property::Line(c)) if c.whole_pixels());
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
        (_, SubjectSpec::Exec(command) | SubjectSpec::Persistent(command)) => {
            let word = match mode {
                Mode::One(Property::Exact(rule)) => rule.name(),
                Mode::One(Property::Watertight) => "watertight",
                Mode::One(Property::CrackFree) => "crack-free",
                Mode::One(Property::Line(c)) => c.name(),
                Mode::AnyRule | Mode::AnyConvention => "any",
            };
            let mut program = if matches!(request.subject, SubjectSpec::Persistent(_)) {
                Program::persistent(command, word)?
            } else {
                Program::new(command, word)
            };
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
    /// Under a table mode, per row ([`table_rows`]): `None` where the row
    /// does not judge the case, else the finding if it fails.
    Table(Vec<Option<Option<Box<Finding>>>>),
}

/// One run of the engine: the report, and for [`check`](super::check)
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

impl Checker<'_> {
    /// The case `index` of `property`'s families, with the check's samples
    /// per pixel.
    fn generate(&self, property: Property, index: u32, rng: &mut fastrand::Rng) -> Case {
        Case {
            samples: self.samples,
            ..generate::generate_case(property, index, rng)
        }
    }

    /// Runs the cases (or the one `given`), confirms and shrinks.
    pub(crate) fn check(
        &self,
        given: Option<Case>,
        subjects: &mut Subjects<'_>,
        progress: &mut dyn FnMut(Progress),
    ) -> Result<Run> {
        let request = self.request;
        let from_file = given.is_some();
        let total = if from_file { 1 } else { request.cases };
        let family_of = |index: u32| -> &'static str {
            if from_file {
                "file"
            } else {
                self.mode.family(index)
            }
        };
        let mut rng = fastrand::Rng::with_seed(request.seed);
        let mut outcomes: Vec<(u32, Case, Vec<Fragment>, Outcome)> = Vec::new();
        // Failures drawn after the run stopped, to confirm the cause.
        let mut confirming: Vec<Finding> = Vec::new();
        let mut broken_at: Option<(u32, Case, SubjectError)> = None;
        let mut stopped_at: Option<u32> = None;
        let mut next = 0;
        'cases: while next < total {
            let limit = match stopped_at {
                None => total,
                Some(at) => total.min(at + 1 + CONFIRMING_CASES),
            };
            if next >= limit || confirming.len() + 1 >= CONFIRMING_FAILURES {
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
            next = end;
            let drawn = subjects.draw_all(&cases);
            for ((index, case), drawn) in cases.into_iter().zip(drawn) {
                if let Some(at) = stopped_at {
                    progress(Progress::Confirming {
                        done: index - at,
                        total: CONFIRMING_CASES,
                    });
                    // A case that breaks the subject confirms nothing.
                    let Ok(drawn) = drawn else { break 'cases };
                    if let Outcome::One(Some(f)) = self.judge(index, from_file, &case, &drawn) {
                        confirming.push(*f);
                    }
                    continue;
                }
                progress(Progress::Cases {
                    done: index + 1,
                    total,
                });
                let drawn = match drawn {
                    Ok(d) => d,
                    Err(e) => {
                        broken_at = Some((index, case, e));
                        break 'cases;
                    }
                };
                let outcome = self.judge(index, from_file, &case, &drawn);
                let failed = matches!(outcome, Outcome::One(Some(_)));
                outcomes.push((index, case, drawn, outcome));
                if failed && !request.keep_going {
                    stopped_at = Some(index);
                }
            }
        }
        if let (Some(at), None, false) = (stopped_at, &broken_at, from_file) {
            self.confirm_in_family(at, subjects, &mut confirming, progress);
        }
        let subject = subjects.first();
        let mut report = CheckReport {
            schema: "rasterlab-check-report/2",
            verdict: VerdictWord::Pass,
            property: self.mode.id(),
            description: with_samples(self.mode.description(), self.samples),
            samples: self.samples.map_or(1, SamplePattern::count),
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
        let mut broken_subject = None;
        if let Some((index, case, error)) = broken_at {
            let b = broken(error, &case, index, subject, request.shrink_runs);
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
                shrunk: b.shrunk,
                input,
                files,
            });
            broken_subject = Some(b);
        }
        // The tallies, and the failures of the property (or the closest
        // row of the table) in the order found.
        let mut tally: Vec<FamilyTally> = self
            .mode
            .families()
            .iter()
            .map(|f| FamilyTally {
                family: (*f).to_string(),
                passed: 0,
                total: 0,
                explained_by_cause: None,
            })
            .collect();
        let table = match self.mode {
            Mode::One(_) => None,
            _ => Some(self.rule_table(&outcomes)),
        };
        let closest = table.as_ref().map_or(0, |t| {
            table_rows(self.mode)
                .iter()
                .position(|(p, _)| row_name(*p) == t.closest)
                .unwrap_or(0)
        });
        let mut failures: Vec<(u32, &Case, &Finding)> = Vec::new();
        let mut passing: Vec<(&Case, &[Fragment])> = Vec::new();
        for (index, case, drawn, outcome) in &outcomes {
            let verdict = match outcome {
                Outcome::One(f) => Some(f.as_deref()),
                Outcome::Table(per) => per[closest].as_ref().map(|f| f.as_deref()),
            };
            let Some(verdict) = verdict else { continue };
            let family = family_of(*index);
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
                    });
                    failures.push((*index, case, f));
                }
            }
        }
        if !request.keep_going {
            report.failing_cases.truncate(1);
        }
        tally.retain(|t| t.total > 0);
        report.passed = tally.iter().map(|t| t.passed).sum();
        // Under a table, the closest row judges only the cases of its kind.
        let judged: u32 = tally.iter().map(|t| t.total).sum();
        report.score = if judged == 0 {
            0.0
        } else {
            f64::from(report.passed) / f64::from(judged)
        };
        report.families = tally;
        let mut original = None;
        // A broken subject's report is the input that breaks it (in
        // `counterexample.txt`): a failure found before it is listed, not
        // shrunk over that file.
        let first_failure = failures
            .first()
            .filter(|_| report.verdict != VerdictWord::Broken);
        if let Some(&(index, case, first)) = first_failure {
            if report.verdict == VerdictWord::Pass {
                report.verdict = VerdictWord::Fail;
            }
            original = Some(case.clone());
            let original_primitives = case.len();
            let evidence: Vec<(&Case, &[Fragment])> = failures
                .iter()
                .map(|(_, _, f)| f)
                .copied()
                .chain(confirming.iter())
                .map(|f| (&f.case, f.drawn.as_slice()))
                .collect();
            let mut diagnosis = cause::diagnose(first.property, &evidence, &passing);
            if let Some(d) = &diagnosis {
                let (more_failing, more_passing) = self.probe(d, first.property, subject);
                if !more_failing.is_empty() || !more_passing.is_empty() {
                    let evidence: Vec<(&Case, &[Fragment])> = evidence
                        .iter()
                        .copied()
                        .chain(more_failing.iter().map(|f| (&f.case, f.drawn.as_slice())))
                        .collect();
                    let passing: Vec<(&Case, &[Fragment])> = more_passing
                        .iter()
                        .map(|(c, d)| (c, d.as_slice()))
                        .chain(passing.iter().copied())
                        .collect();
                    diagnosis = cause::diagnose(first.property, &evidence, &passing);
                }
            }
            let shrunk = self.shrink(first.clone(), diagnosis, subject, progress);
            if let Some(cause) = &shrunk.cause {
                // Where the cause holds, family by family (a grader's
                // test per family names it only where it explains).
                for t in &mut report.families {
                    let mut family_failures = failures
                        .iter()
                        .filter(|(i, _, _)| family_of(*i) == t.family)
                        .peekable();
                    if family_failures.peek().is_some() {
                        t.explained_by_cause = Some(
                            family_failures
                                .filter(|(_, c, f)| {
                                    cause.explains(f.property, c, &f.drawn).is_some()
                                })
                                .count() as u32,
                        );
                    }
                }
            }
            let shrunk =
                self.write_counterexample(&mut report, shrunk, index, original_primitives)?;
            report.finding = Some(Box::new(shrunk));
        }
        if let Some(table) = table {
            if report.verdict != VerdictWord::Broken {
                report.verdict = if table.followed.is_empty() {
                    VerdictWord::Fail
                } else {
                    VerdictWord::Pass
                };
            }
            report.rules = Some(table);
        }
        progress(Progress::Done);
        Ok(Run {
            report,
            original,
            broken: broken_subject,
        })
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

    /// Shrinks the first failure, keeping its kind and the cause found,
    /// and words the cause (or its absence) on the shrunk case.
    fn shrink(
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
    fn write_counterexample(
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

    /// The table of a table mode: each row's agreeing cases.
    fn rule_table(&self, outcomes: &[(u32, Case, Vec<Fragment>, Outcome)]) -> RuleTable {
        let rows_of = table_rows(self.mode);
        let mut rows: Vec<(RuleRow, bool)> = rows_of
            .iter()
            .map(|&(p, mesh_only)| {
                (
                    RuleRow {
                        rule: row_name(p),
                        cases: match (p, mesh_only) {
                            (_, true) => "mesh".into(),
                            (Property::Line(c), _) if c.whole_pixels() => "whole-pixel".into(),
                            (Property::Line(_), _) => "screen".into(),
                            _ => "all".into(),
                        },
                        agreeing: 0,
                        total: 0,
                        first_disagreeing: None,
                    },
                    mesh_only,
                )
            })
            .collect();
        for (index, _, _, outcome) in outcomes {
            let Outcome::Table(per) = outcome else {
                continue;
            };
            for ((row, _), verdict) in rows.iter_mut().zip(per) {
                let Some(verdict) = verdict else { continue };
                row.total += 1;
                if verdict.is_none() {
                    row.agreeing += 1;
                } else if row.first_disagreeing.is_none() {
                    row.first_disagreeing = Some(*index);
                }
            }
        }
        let mut mesh_rows = rows.iter().filter(|r| r.1).map(|r| r.0.clone());
        let (watertight, crack_free) = (mesh_rows.next(), mesh_rows.next());
        let rows: Vec<RuleRow> = rows.into_iter().filter(|r| !r.1).map(|r| r.0).collect();
        let followed = rows
            .iter()
            .filter(|r| r.total > 0 && r.agreeing == r.total)
            .map(|r| r.rule.clone())
            .collect();
        let share = |r: &RuleRow| {
            if r.total == 0 {
                0.0
            } else {
                f64::from(r.agreeing) / f64::from(r.total)
            }
        };
        let best = rows.iter().map(share).fold(0.0, f64::max);
        let closest = rows
            .iter()
            .find(|r| share(r) == best)
            .map_or_else(String::new, |r| r.rule.clone());
        RuleTable {
            rows,
            followed,
            closest,
            watertight,
            crack_free,
        }
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
        samples: None,
    }
}

/// A table row's name: the fill rule, `watertight`, `crack-free`, or the
/// line convention.
fn row_name(p: Property) -> String {
    match p {
        Property::Exact(r) => r.name().into(),
        Property::Watertight => "watertight".into(),
        Property::CrackFree => "crack-free".into(),
        Property::Line(c) => c.name().into(),
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
            explained_by_cause: None,
        });
        tally.last_mut().expect("just pushed")
    }
}

/// The comment lines that record where a case came from.
fn provenance_comment(p: &Provenance, case: &Case) -> String {
    format!(
        "# size {}x{}\n# command: {}\n# seed {}, case {} (family {})\n",
        case.width, case.height, p.command, p.seed, p.case_index, p.family
    )
}

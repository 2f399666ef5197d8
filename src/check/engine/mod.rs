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
//! 4. **Cause.** [`cause::diagnose`](super::cause::diagnose) tries the
//!    catalogue on the failing cases as generated, and holds each change
//!    against the passing cases. A cause named so far is then probed:
//!    of [`PROBE_CASES`](probe::PROBE_CASES) more cases, those where it
//!    and one of its rivals (it together with another change) draw
//!    differently are given to the subject
//!    ([`PROBE_RUNS`](probe::PROBE_RUNS) at most), and the cause is
//!    looked for again with what the subject drew there.
//! 5. **Shrinking.** The first failure is shrunk, keeping its kind and the
//!    cause found, and written out.
//!
//! Here are the entry points and the request's checks; `mode` is what the
//! check judges by, `subjects` who draws the cases, `checker` the run
//! itself (steps 1 to 3 and the report), `probe` the search for the cause
//! (step 4) and `counterexample` the shrinking and the files written
//! (step 5).

mod checker;
mod counterexample;
mod mode;
mod probe;
mod subjects;

pub(crate) use checker::Checker;
pub(crate) use mode::Mode;
pub(crate) use subjects::Subjects;

use super::case::Case;
use super::case::Origin;
use super::property::Property;
use super::request::{
    timeout_from_seconds, BrokenReport, CheckReport, CheckRequest, Kind, SubjectSpec, VerdictWord,
    MAX_CASES, MAX_JOBS,
};
use super::snapping::Snapping;
use super::Subject;
use crate::error::{Error, Result};
use crate::raster::multisample::SamplePattern;
use crate::raster::registry::{backend, polygon_backend, Backend};
use std::path::Path;
use subjects::{subject_factory, Factory};

/// Cases drawn after the first failure, at most, to confirm its cause:
/// the next ones of the run, then as many more of the first failure's
/// family.
pub const CONFIRMING_CASES: u32 = 30;
/// Failing cases, the first included, after which confirmation stops.
pub const CONFIRMING_FAILURES: usize = 10;

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

/// A subject of the caller's: its name in the report, and a maker of one
/// per job.
type Custom<'a> = Option<(&'a str, &'a (dyn Fn() -> Box<dyn Subject + Send> + Sync))>;

/// The engine behind [`run`], [`run_with`] and [`run_with_progress`]:
/// the request checked, its subjects made, and the check run.
fn run_inner(
    request: &CheckRequest,
    custom: Custom<'_>,
    progress: &mut dyn FnMut(Progress),
) -> Result<CheckReport> {
    // A polygon back-end is no triangle or line back-end: its subject is
    // made from its name.
    let polygon_named = custom.is_none()
        && matches!(&request.subject, SubjectSpec::Backend(name) if polygon_backend(name).is_ok());
    let chosen = match (&request.subject, custom) {
        (SubjectSpec::Backend(name), None) if !polygon_named => Some(backend(name)?),
        _ => None,
    };
    let kind = match (request.kind, chosen) {
        (Some(k), _) => k,
        (None, Some(Backend::Line(_))) => Kind::Lines,
        (None, None) if polygon_named => Kind::Polygons,
        (None, _) => Kind::Triangles,
    };
    let mode = Mode::of_request(request, kind)?;
    check_limits(request)?;
    let mut samples = samples_asked(request, mode)?;
    let given = match &request.case_file {
        Some(path) => {
            let case = read_case_file(path, kind, mode, samples, request.snapping)?;
            samples = case.samples;
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
    let factory: Factory<'_> = match request.origin {
        Origin::TopLeft => factory,
        Origin::BottomLeft => {
            Box::new(move || Box::new(subjects::YUp(factory())) as Box<dyn Subject + Send>)
        }
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
    if let SubjectSpec::Exec(command) = &request.subject {
        if !command.contains("{input}") {
            not_given_the_case(&mut report);
        }
    }
    Ok(report)
}

/// A program run once per case without `{input}` in its command line is
/// not given the case (its standard input is empty): when it fails, that
/// is the reason, not a cause of the catalogue, and the subject is
/// reported broken (exit status 2) with what to do instead.
fn not_given_the_case(report: &mut CheckReport) {
    if report.verdict != VerdictWord::Fail {
        return;
    }
    let first = report.failing_cases.first();
    report.verdict = VerdictWord::Broken;
    report.error = Some(BrokenReport {
        message: "the program is not given the case: its command line has no {input} \
                  (the path of the case's file), and its standard input is empty. \
                  A program that reads case after case on its standard input runs \
                  with --persistent; one that reads a file takes {input}"
            .into(),
        case_index: first.map_or(0, |f| f.case_index),
        family: first
            .map(|f| f.family.clone())
            .or_else(|| report.families.first().map(|t| t.family.clone()))
            .unwrap_or_else(|| "file".into()),
        on_every_input: true,
        shrunk: false,
        input: String::new(),
        files: Vec::new(),
    });
}

/// Checks the request's numbers: cases, jobs and the time limit.
fn check_limits(request: &CheckRequest) -> Result<()> {
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
    Ok(())
}

/// The samples per pixel asked for (`--msaa N`), which only a check of
/// triangles under one fill rule takes.
fn samples_asked(request: &CheckRequest, mode: Mode) -> Result<Option<SamplePattern>> {
    Ok(match request.msaa {
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
    })
}

/// The case given in a file (`--case`), which must hold the kind of
/// primitives checked, with the samples per pixel it says or is given.
fn read_case_file(
    path: &Path,
    kind: Kind,
    mode: Mode,
    samples: Option<SamplePattern>,
    snapping: Snapping,
) -> Result<Case> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let case = Case::from_text(&text).map_err(|e| Error::Parse {
        path: path.to_path_buf(),
        line: None,
        message: e.to_string(),
    })?;
    crate::raster::target::RenderTarget::check_size(case.width, case.height).map_err(|e| {
        Error::Parse {
            path: path.to_path_buf(),
            line: None,
            message: e.to_string(),
        }
    })?;
    let fits = match kind {
        Kind::Lines => {
            case.triangles.is_empty() && case.polygons.is_empty() && !case.lines.is_empty()
        }
        Kind::Triangles => {
            case.lines.is_empty() && case.polygons.is_empty() && !case.triangles.is_empty()
        }
        Kind::Polygons => {
            case.triangles.is_empty() && case.lines.is_empty() && !case.polygons.is_empty()
        }
    };
    if !fits {
        return Err(Error::InvalidArgument(format!(
            "{}: the case must hold {} only",
            path.display(),
            match kind {
                Kind::Lines => "line segments (four numbers a line)",
                Kind::Triangles => "triangles (six numbers a line)",
                Kind::Polygons => "polygons (`polygon x0 y0 x1 y1 ...` lines, each followed by its `hole ...` lines)",
            }
        )));
    }
    let samples = match (case.samples, samples) {
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
        (Some(a), None) => Some(a),
        (_, asked) => asked,
    };
    // A snapping asked for wins over the file's `# snap` line; without
    // one, the file's (a counterexample's own) stands.
    let snapping = if snapping == Snapping::default() {
        case.snapping
    } else {
        snapping
    };
    for (i, p) in case.points().enumerate() {
        snapping
            .check_exact(p)
            .map_err(|e| Error::InvalidArgument(format!("{}: vertex {i}: {e}", path.display())))?;
    }
    Ok(Case {
        samples,
        snapping,
        ..case
    })
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

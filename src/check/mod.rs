//! Check any rasterizer against the rules, with shrunk counterexamples.
//!
//! The same machinery proves rasterlab's own back-ends and checks anyone
//! else's: a rasterizer written for an assignment in any language (through
//! [`Program`], the `rasterlab check --exec` protocol), a published crate
//! behind a small adapter, or a closure in a user's own `#[test]`.
//!
//! A check runs many [`Case`]s (a target size and some triangles or line
//! segments, from the case families ([`families`]): random soups, triangulated
//! polygons with holes, fans and pinwheels around pixel centres, jittered
//! quad grids, needles, huge and negative coordinates, half-subpixel ties,
//! triangles of zero area after snapping, meshes). Each case is drawn by
//! the rasterizer under test and judged by a [`Property`]:
//!
//! * [`Property::Exact`]: the fragments are exactly those of the rules
//!   (1/256 snapping with ties to even, integer edge functions, pixel
//!   centres at +0.5, the fill rule's tie-breaking), as the naive
//!   reference draws them;
//! * [`Property::Watertight`]: whatever consistent tie rule is used, every
//!   pixel centre inside the union of the triangles is drawn exactly once,
//!   nothing outside is drawn, a triangle draws only centres it touches,
//!   and centres on the union's boundary at most once;
//! * [`Property::CrackFree`]: every centre on a shared edge or shared
//!   vertex inside a mesh drawn exactly once, no pixel drawn twice,
//!   whatever is drawn at the mesh's outline (the two side by side in
//!   [`judge()`]);
//! * [`Property::Line`]: lines drawn by the midpoint rule or the diamond
//!   exit rule exactly, within Vulkan's tolerance of the diamond rule, or
//!   by integer Bresenham between pixel-index endpoints
//!   ([`LineConvention::PixelIndex`]).
//!
//! Under [`Property::Exact`] a case may be multisampled
//! ([`Case::samples`], `check --msaa N`): each fragment then carries the
//! coverage mask of its pixel's samples on the standard pattern
//! ([`Fragment::mask`]), judged exactly, and the catalogue of causes
//! gains the classic multisampling mistakes ([`catalogue_multisampled`]).
//!
//! A failure's cause is named only where the reference confirms it: the
//! catalogue's hypotheses ([`Cause`], [`catalogue`]) are each a change to
//! the case or the reference, or a condition on the differences, tried on
//! every failing case as generated ([`Diagnosis`]).
//!
//! [`run`] is the whole check as the `rasterlab check` command runs it:
//! a [`CheckRequest`] in, a [`CheckReport`] out (text through `Display`,
//! the one JSON shape through `Serialize`, described by
//! `docs/check-report.schema.json`), which may also ask which fill rule a
//! rasterizer follows (the rule table of [`RuleChoice::Any`]).
//!
//! Always: a fragment outside the target, or one pixel listed twice for
//! one primitive, is a failure. A failing case is shrunk (primitives
//! dropped, vertices moved toward the pixel grid and toward each other,
//! the target cut down) to a small counterexample failing the same way
//! (the same [`FailureKind`]), which
//! [`Finding::ascii_grid`] and [`Finding::counterexample_text`] show.
//!
//! ```
//! use rasterlab::check::{check, CheckOptions, Property, Verdict};
//! use rasterlab::raster::{triangle_backend, FillRule};
//!
//! let scanline = triangle_backend("scanline").unwrap();
//! let options = CheckOptions { cases: 50, ..CheckOptions::new(Property::Exact(FillRule::TopLeft)) };
//! let verdict = check(&options, &mut rasterlab::check::Builtin::triangles(scanline, FillRule::TopLeft)).unwrap();
//! assert!(matches!(verdict, Verdict::Pass { cases: 50 }));
//! ```

mod case;
pub(crate) mod cause;
mod config;
// Some of it only the program calls: unused without the `cli` feature.
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
mod engine;
pub(crate) mod generate;
// Some of it only the program calls: unused without the `cli` feature.
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
mod grader;
// Some of it only the program calls: unused without the `cli` feature.
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
mod image;
mod image_diff;
pub(crate) mod judge;
mod persistent;
mod pixel_index;
mod polygons;
mod preset;
mod process;
// Some of it only the program calls: unused without the `cli` feature.
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
pub(crate) mod program;
mod property;
pub(crate) mod report;
mod request;
mod shrink;
mod snapping;
mod text;

pub use case::{Case, Origin};
pub use cause::{
    catalogue, catalogue_multisampled, Cause, Diagnosis, End, Side, Winding, FAR_OFF_TARGET,
    NEAR_AN_EDGE,
};
pub use config::CheckConfig;
pub use engine::{run, run_with, Progress, CONFIRMING_CASES};
pub use generate::{families, family, generate_case, generate_case_snapped};
pub use grader::{gradescope, junit};
pub use image::{
    image_gradescope, image_junit, run_images, ImageConfig, ImageOutcome, ImageReport,
    ImageRequest, ImageResult, ImageTest, ImageTestConfig, ImageThresholds, ThresholdConfig,
    DEFAULT_IMAGE_SCENES,
};
pub use image_diff::{diff_image, diff_svg, ImageMetrics};
pub use judge::{judge, FailureKind, Finding, Provenance};
pub use polygons::{
    fill as polygon_reference, polygon_fragments, Boundary, Filling, POLYGON_FAMILIES,
};
pub use preset::{preset, presets, Preset};
pub use process::parse_fragments;
pub use program::{shell_words, Program};
pub use property::{LineConvention, Property};
pub use request::{
    BrokenReport, CaseFailure, CheckReport, CheckRequest, ConventionChoice, Counterexample,
    FamilyTally, Kind, RuleChoice, RuleRow, RuleTable, SubjectSpec, VerdictWord, MAX_CASES,
};
pub use snapping::Snapping;
// What only the `rasterlab` program uses; absent without the `cli` feature.
#[cfg(feature = "cli")]
pub use self::{
    engine::run_with_progress, grader::ReportFormat, program::remove_live_input_folders,
    request::timeout_from_seconds,
};

use crate::geometry::scene::setup_triangles;
use crate::raster::edge::{FillRule, PixelRect};
use crate::raster::fragment::FragmentList;
use crate::raster::line::{LineOptions, LineRasterizer, LineSetup, LineWalk};
use crate::raster::multisample::{masks_of, SamplePattern};
use crate::raster::registry::{line_backends, reference_triangle_backend};
use crate::raster::triangle::TriangleRasterizer;
use std::fmt;

/// One fragment a rasterizer reports: a pixel and the index of the
/// primitive (triangle or line, 0-based, in input order) that covers it,
/// and for a multisampled case the samples it covers.
/// Coordinates are `i64` so that output off the target can be judged.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Fragment {
    /// Column.
    pub x: i64,
    /// Row.
    pub y: i64,
    /// The primitive's index.
    pub id: u32,
    /// Under `--msaa N`, the coverage mask: bit `i` set when the primitive
    /// covers sample `i` of the pattern. 0 for a case with one sample.
    pub mask: u32,
}

impl Fragment {
    /// A fragment of a case with one sample per pixel.
    pub fn at(x: i64, y: i64, id: u32) -> Fragment {
        Fragment { x, y, id, mask: 0 }
    }
}

/// Why a rasterizer under test could not be judged: it is broken in a way
/// no property describes (the CLI exits 2).
#[derive(Clone, Debug, PartialEq)]
pub enum SubjectError {
    /// The program could not be started.
    Start(String),
    /// It ran past the time limit and was stopped.
    Timeout {
        /// The limit, in seconds.
        seconds: f64,
    },
    /// It exited with a failure status.
    Failed {
        /// The exit status as text.
        status: String,
        /// The start of its standard error.
        stderr: String,
    },
    /// A line of its output is not `x y id` (under `--msaa`, `x y id
    /// mask`).
    Malformed {
        /// The 1-based output line.
        line: usize,
        /// The text of that line.
        text: String,
    },
    /// It answered that it cannot draw the case (`error MESSAGE` under
    /// the persistent protocol), with its message and what it had written
    /// on standard error meanwhile (a traceback, say).
    Refused {
        /// The message of its `error` line.
        message: String,
        /// The end of its standard error.
        stderr: String,
    },
    /// It printed more than the output cap.
    TooMuchOutput {
        /// The cap, in bytes.
        bytes: usize,
    },
}

impl std::error::Error for SubjectError {}

impl fmt::Display for SubjectError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SubjectError::Start(e) => write!(f, "the program could not be started: {e}"),
            SubjectError::Timeout { seconds } => {
                write!(f, "the program ran longer than {seconds} s and was stopped")
            }
            SubjectError::Failed { status, stderr } => {
                write!(f, "the program failed ({status})")?;
                if !stderr.is_empty() {
                    write!(f, "; its standard error:\n{stderr}")?;
                }
                Ok(())
            }
            SubjectError::Malformed { line, text } => write!(
                f,
                "output line {line} is not `x y id` (whole numbers; under --msaa N, `x y id mask` with a mask from 1 to 2^N - 1): `{text}`"
            ),
            SubjectError::Refused { message, stderr } => {
                write!(f, "the program answered `error`: {message}")?;
                if !stderr.is_empty() {
                    write!(f, "\nits standard error:\n{stderr}")?;
                }
                Ok(())
            }
            SubjectError::TooMuchOutput { bytes } => {
                write!(f, "the program printed more than {bytes} bytes")
            }
        }
    }
}

/// A rasterizer under test: draws a case, returns its fragments.
///
/// Any closure or function from a [`Case`] to fragments is one, so a
/// rasterizer of one's own is checked in a `#[test]` like this one, which
/// draws every pixel centre inside *or on* an edge, in `f64`. Its mistake,
/// a centre on an edge drawn whatever the edge (the top-left rule draws it
/// only on a top or left edge, so that two triangles sharing the edge do
/// not both draw it), is found and shrunk, here to one triangle on a 1x1
/// target:
///
/// ```
/// use rasterlab::check::{check, Case, CheckOptions, FailureKind, Fragment, Property, SubjectError, Verdict};
/// use rasterlab::raster::FillRule;
///
/// fn my_rasterizer(case: &Case) -> Result<Vec<Fragment>, SubjectError> {
///     let edge = |a: (f64, f64), b: (f64, f64), p: (f64, f64)| {
///         (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0)
///     };
///     let mut fragments = Vec::new();
///     for (id, t) in case.triangles.iter().enumerate() {
///         let area = edge(t[0], t[1], t[2]);
///         if area == 0.0 {
///             continue;
///         }
///         for y in 0..i64::from(case.height) {
///             for x in 0..i64::from(case.width) {
///                 let p = (x as f64 + 0.5, y as f64 + 0.5);
///                 if (0..3).all(|i| edge(t[i], t[(i + 1) % 3], p) * area.signum() >= 0.0) {
///                     fragments.push(Fragment::at(x, y, id as u32));
///                 }
///             }
///         }
///     }
///     Ok(fragments)
/// }
///
/// let options = CheckOptions {
///     cases: 100,
///     ..CheckOptions::new(Property::Exact(FillRule::TopLeft))
/// };
/// match check(&options, &mut my_rasterizer).unwrap() {
///     Verdict::Fail { finding, .. } => {
///         println!("{}\n{}", finding.problems[0], finding.ascii_grid());
///         assert_eq!(finding.kind(), FailureKind::Tie);
///     }
///     Verdict::Pass { .. } => panic!("a shared edge drawn twice went unseen"),
/// }
/// ```
pub trait Subject {
    /// The fragments drawn for `case`, in any order.
    fn draw(&mut self, case: &Case) -> Result<Vec<Fragment>, SubjectError>;
}

/// Any closure from a case to fragments is a subject.
impl<F> Subject for F
where
    F: FnMut(&Case) -> Result<Vec<Fragment>, SubjectError>,
{
    fn draw(&mut self, case: &Case) -> Result<Vec<Fragment>, SubjectError> {
        self(case)
    }
}

/// A built-in back-end as a subject (triangles under a fill rule, or
/// lines with the default options).
#[derive(Copy, Clone)]
pub enum Builtin {
    /// A triangle back-end and the rule it draws with.
    Triangles(&'static dyn TriangleRasterizer, FillRule),
    /// A line back-end.
    Lines(&'static dyn LineRasterizer),
}

impl Builtin {
    /// A triangle back-end under `rule`.
    pub fn triangles(backend: &'static dyn TriangleRasterizer, rule: FillRule) -> Builtin {
        Builtin::Triangles(backend, rule)
    }
}

impl Subject for Builtin {
    fn draw(&mut self, case: &Case) -> Result<Vec<Fragment>, SubjectError> {
        Ok(match self {
            Builtin::Triangles(b, rule) => triangle_fragments(*b, case, *rule),
            Builtin::Lines(b) => line_fragments(*b, case),
        })
    }
}

/// The fragments `backend` draws for the case's triangles under `rule`;
/// for a multisampled case, each with its coverage mask
/// ([`masks_of`]: the back-end's own walk, once
/// per sample).
pub fn triangle_fragments(
    backend: &dyn TriangleRasterizer,
    case: &Case,
    rule: FillRule,
) -> Vec<Fragment> {
    let setups = setup_triangles(&case.snapped_triangles(), rule);
    let rect = PixelRect::of_target(case.width, case.height);
    if let Some(pattern) = &case.samples {
        return masks_of(backend, &setups, rect, pattern)
            .into_iter()
            .map(|m| Fragment {
                x: m.x,
                y: m.y,
                id: m.triangle,
                mask: m.mask,
            })
            .collect();
    }
    let mut list = FragmentList::default();
    backend.rasterize(&setups, rect, &mut list);
    list.triangles
        .iter()
        .map(|f| Fragment::at(i64::from(f.x), i64::from(f.y), f.triangle))
        .collect()
}

/// The fragments `backend` draws for the case's lines (default options;
/// Wu's zero-weight pixels left out).
pub fn line_fragments(backend: &dyn LineRasterizer, case: &Case) -> Vec<Fragment> {
    let mut list = FragmentList::default();
    backend.rasterize(
        &LineSetup::numbered(&case.snapped_lines()),
        &LineOptions::DEFAULT,
        PixelRect::of_target(case.width, case.height),
        &mut list,
    );
    list.lines
        .iter()
        .filter(|f| f.coverage > 0.0)
        .map(|f| Fragment::at(i64::from(f.x), i64::from(f.y), f.line))
        .collect()
}

/// What a check is asked to do.
#[derive(Clone, Debug)]
pub struct CheckOptions {
    /// The property every case must satisfy.
    pub property: Property,
    /// How many cases to draw.
    pub cases: u32,
    /// The seed of the case generator: the same seed, the same cases.
    pub seed: u64,
    /// The most times the subject is run while shrinking a failure.
    pub shrink_runs: u32,
    /// The samples per pixel of every case, for a multisampling subject
    /// under [`Property::Exact`]: its fragments carry coverage masks
    /// ([`Fragment::mask`]). `None`: one sample, at the pixel centre.
    pub samples: Option<SamplePattern>,
}

impl CheckOptions {
    /// 150 cases, seed 0, up to 150 shrinking runs, one sample per pixel.
    pub fn new(property: Property) -> CheckOptions {
        CheckOptions {
            property,
            cases: 150,
            seed: 0,
            shrink_runs: 150,
            samples: None,
        }
    }
}

/// The outcome of a check.
#[derive(Clone, Debug)]
pub enum Verdict {
    /// Every case held.
    Pass {
        /// Cases run.
        cases: u32,
    },
    /// A case failed; the finding is about the shrunk case.
    Fail {
        /// The 0-based index of the first failing case.
        case_index: u32,
        /// The failing case as generated, before shrinking.
        original: Case,
        /// What is wrong with the shrunk case.
        finding: Box<Finding>,
    },
}

impl fmt::Display for Verdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Verdict::Pass { cases } => write!(f, "PASS: {cases} cases"),
            Verdict::Fail {
                case_index,
                original,
                finding,
            } => {
                write!(
                    f,
                    "FAIL: {}, case {case_index}; shrunk from {} to {} primitive(s) on a {}x{} target",
                    finding.property,
                    original.len(),
                    finding.case.len(),
                    finding.case.width,
                    finding.case.height
                )?;
                for p in finding.problems.iter().take(5) {
                    write!(f, "\n  {p}")?;
                }
                if let Some(d) = &finding.diagnosis {
                    write!(f, "\ndiagnosis: {d}")?;
                }
                Ok(())
            }
        }
    }
}

/// A subject that broke, with the (shrunk) case that broke it.
#[derive(Clone, Debug)]
pub struct Broken {
    /// What went wrong.
    pub error: SubjectError,
    /// The smallest case found that triggers it.
    pub case: Case,
    /// The 0-based index of the case on which it first broke.
    pub case_index: u32,
    /// True when it breaks the same way on the simplest input too (a
    /// program that cannot start, or fails whatever it is given): the
    /// case is then the first one, not shrunk.
    pub on_every_input: bool,
    /// True when the case was shrunk (a program that hangs or prints
    /// without end is not rerun to shrink it: each run would cost the
    /// time limit).
    pub shrunk: bool,
}

impl fmt::Display for Broken {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.error)?;
        if self.on_every_input {
            write!(
                f,
                "\nit breaks so on every input, the simplest included: broken, not wrong"
            )
        } else {
            write!(
                f,
                "\nthe input that triggers it: {} primitive(s), {}x{}",
                self.case.len(),
                self.case.width,
                self.case.height
            )
        }
    }
}

impl std::error::Error for Broken {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

/// The simplest input: a 1x1 target and one small triangle (or line)
/// over its pixel. A subject that breaks on it breaks on every input.
pub fn simplest_case(lines: bool) -> Case {
    Case {
        width: 1,
        height: 1,
        triangles: if lines {
            Vec::new()
        } else {
            vec![[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]]
        },
        lines: if lines {
            vec![[(0.0, 0.0), (1.0, 0.0)]]
        } else {
            Vec::new()
        },
        ..Case::default()
    }
}

/// What a subject that failed on `case` amounts to: broken on every input
/// (it fails the same way on [`simplest_case`]; not shrunk), broken on
/// some (shrunk), or, for a timeout or a flood of output, reported as it
/// is (each run costs seconds).
pub(crate) fn broken(
    error: SubjectError,
    case: &Case,
    case_index: u32,
    subject: &mut dyn Subject,
    runs: u32,
) -> Broken {
    let same = |e: &SubjectError| std::mem::discriminant(e) == std::mem::discriminant(&error);
    let (case, on_every_input, shrunk) = match error {
        SubjectError::Timeout { .. } | SubjectError::TooMuchOutput { .. } => {
            (case.clone(), false, false)
        }
        _ if subject
            .draw(&Case {
                // Multisampled as the case is: the subject reads masks.
                samples: case.samples,
                ..simplest_case(!case.lines.is_empty())
            })
            .as_ref()
            .err()
            .is_some_and(same) =>
        {
            (case.clone(), true, false)
        }
        _ => (shrink::shrink_broken(case, subject, runs), false, true),
    };
    Broken {
        error,
        case,
        case_index,
        on_every_input,
        shrunk,
    }
}

/// Runs the check: `options.cases` generated cases, stopping at the first
/// failure, whose cause is looked for (on a few more cases, see
/// [`CONFIRMING_CASES`]) and which is shrunk. `progress` is told what the
/// engine is doing. The same engine as [`run`], with the caller's subject.
pub fn check_with_progress(
    options: &CheckOptions,
    subject: &mut dyn Subject,
    progress: &mut dyn FnMut(Progress),
) -> Result<Verdict, Box<Broken>> {
    let request = CheckRequest {
        cases: options.cases,
        seed: options.seed,
        shrink_runs: options.shrink_runs,
        ..CheckRequest::new(SubjectSpec::Backend(String::new()))
    };
    let checker = engine::Checker {
        request: &request,
        mode: engine::Mode::One(options.property),
        samples: options.samples,
    };
    let run = checker
        .check(None, &mut engine::Subjects::One(subject), progress)
        .map_err(|e| {
            // Nothing is written and nothing read: the engine's only
            // errors are the request's, and this request is valid.
            Box::new(Broken {
                error: SubjectError::Start(e.to_string()),
                case: simplest_case(options.property.is_lines()),
                case_index: 0,
                on_every_input: false,
                shrunk: false,
            })
        })?;
    if let Some(b) = run.broken {
        return Err(Box::new(b));
    }
    match (run.report.finding, run.original, run.report.counterexample) {
        (Some(finding), Some(original), Some(c)) => Ok(Verdict::Fail {
            case_index: c.case_index,
            original,
            finding,
        }),
        _ => Ok(Verdict::Pass {
            cases: run.report.cases_run,
        }),
    }
}

/// [`check_with_progress`] without progress reports.
pub fn check(options: &CheckOptions, subject: &mut dyn Subject) -> Result<Verdict, Box<Broken>> {
    check_with_progress(options, subject, &mut |_| {})
}

/// The reference fragments of a case under a property: what an exact
/// rasterizer draws (for [`Property::Watertight`] and
/// [`Property::CrackFree`], the top-left rule's answer, one of the many
/// that pass).
pub fn reference(property: Property, case: &Case) -> Vec<Fragment> {
    match property {
        Property::Exact(rule) => triangle_fragments(reference_triangle_backend(), case, rule),
        Property::Watertight | Property::CrackFree => {
            triangle_fragments(reference_triangle_backend(), case, FillRule::TopLeft)
        }
        Property::Line(judge::LineConvention::Midpoint) => {
            line_fragments(line_backend_walking(LineWalk::Midpoint), case)
        }
        Property::Line(c) if c.whole_pixels() => pixel_index::fragments(
            case,
            c.walk().unwrap_or(pixel_index::WholePixelWalk::TowardStart),
        ),
        Property::Line(judge::LineConvention::DiamondNudged) => {
            line_fragments(line_backend_walking(LineWalk::DiamondExitNudged), case)
        }
        Property::Line(_) => line_fragments(line_backend_walking(LineWalk::DiamondExit), case),
        Property::Polygon(rule) => polygons::fill(case, Filling::reference(rule)),
    }
}

/// The built-in line back-end that chooses its pixels by `walk`.
fn line_backend_walking(walk: LineWalk) -> &'static dyn LineRasterizer {
    line_backends()
        .iter()
        .copied()
        .find(|b| b.descriptor().walk == walk)
        .expect("the registry has a back-end for each line rule")
}

//! What a back-end is, as data: one [`Descriptor`] per back-end (its name,
//! description, walk, role and cost class), and the one work budget every
//! tool applies to it ([`within_budget`]).
//!
//! A back-end's file states its descriptor once, as a constant; the
//! registry ([`crate::raster::backend`]) finds the reference, the fallback
//! and the default by their [`Role`], and every tool that must refuse or
//! leave out a run that would take hours asks [`within_budget`], with the
//! [`WorkBudget`] of what it is doing.
//!
//! ```
//! use rasterlab::raster::{triangle_backend, within_budget, WorkBudget};
//!
//! // The course's loop tests every pixel for every triangle: a 100,000
//! // triangle mesh on a 1920 x 1080 target is beyond a report's budget,
//! // while the bounding-box loop's work follows the triangles' size.
//! let pixels = 1920 * 1080;
//! let naive = triangle_backend("naive").unwrap().descriptor();
//! let bbox = triangle_backend("bbox").unwrap().descriptor();
//! assert!(within_budget(&naive, 100_000, pixels, WorkBudget::Report).is_err());
//! assert!(within_budget(&bbox, 100_000, pixels, WorkBudget::Report).is_ok());
//! // Two triangles covering the target cost the naive loop two tests a
//! // pixel: within a timing's budget.
//! assert!(within_budget(&naive, 2, pixels, WorkBudget::Timing).is_ok());
//! ```

use crate::error::{Error, Result};
use std::fmt;

/// A back-end's facts: what the registry lists and every tool reads.
///
/// `W` is the kind of walk: [`TriangleWalk`](crate::raster::triangle::TriangleWalk)
/// for triangle back-ends, [`LineWalk`](crate::raster::line::LineWalk) for
/// line back-ends.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Descriptor<W> {
    /// Short name used on the command line.
    pub name: &'static str,
    /// One-line description.
    pub description: &'static str,
    /// How it walks the pixels (what its trace is headed with).
    pub walk: W,
    /// What the tools use it for.
    pub role: Role,
    /// How its work grows.
    pub cost: CostClass,
}

/// What the tools use a back-end for. The registry holds, of each kind,
/// exactly one [`Role::Default`], and of the triangle back-ends exactly
/// one [`Role::Reference`] and one [`Role::Fallback`].
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Role {
    /// The reference the others are compared with: the course's loop,
    /// testing every sample on its own.
    Reference,
    /// The reference where the reference is beyond the budget: it also
    /// tests every sample it looks at on its own, but only within each
    /// triangle's bounding box.
    Fallback,
    /// What a tool draws with when no back-end is named.
    Default,
    /// One more algorithm to compare.
    Alternative,
}

/// How a back-end's work grows with its input.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum CostClass {
    /// With the size of the primitives (the pixels they cover, or their
    /// bounding boxes): drawing many small triangles costs what drawing a
    /// few large ones does.
    FollowsSize,
    /// Every pixel of the target for every primitive, whatever its size
    /// (the course's per-pixel loop).
    EveryPixel,
}

impl CostClass {
    /// The samples a back-end of this class tests to draw `primitives`
    /// primitives on `pixels` pixels when that does not depend on their
    /// size; `None` for [`CostClass::FollowsSize`].
    pub fn tests_whatever_the_size(self, primitives: u64, pixels: u64) -> Option<u64> {
        match self {
            CostClass::FollowsSize => None,
            CostClass::EveryPixel => Some(primitives.saturating_mul(pixels)),
        }
    }
}

/// How much sample testing a tool lets a back-end do, whatever the
/// primitives' size: one policy, with one budget per kind of use.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum WorkBudget {
    /// A timed run (the benchmarks): at most two tests per pixel of the
    /// target, what the two-triangle fill costs every back-end, so that
    /// the naive loop is timed only where its figure compares.
    Timing,
    /// A report or a picture: at most 5e7 tests (under a second of the
    /// naive loop), above which the report leaves the back-end out.
    Report,
    /// A run a user asked for: at most 1e10 tests (about a minute and a
    /// half of the naive loop), above which the run is refused unless
    /// forced.
    Run,
}

impl WorkBudget {
    /// The sample tests this budget allows on a target of `pixels` pixels.
    pub fn tests(self, pixels: u64) -> u64 {
        match self {
            WorkBudget::Timing => pixels.saturating_mul(2),
            WorkBudget::Report => 50_000_000,
            WorkBudget::Run => 10_000_000_000,
        }
    }
}

impl fmt::Display for WorkBudget {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            WorkBudget::Timing => "a timing's budget (two tests a pixel)",
            WorkBudget::Report => "a report's budget",
            WorkBudget::Run => "a run's budget",
        })
    }
}

/// Sample tests per second the naive loop manages, for the estimate in
/// [`within_budget`]'s error.
const NAIVE_TESTS_PER_SECOND: f64 = 1e8;

/// Whether the back-end described by `backend` may draw `primitives`
/// primitives on `pixels` pixels within `budget`: `Ok` when its work
/// follows the primitives' size, or when the tests it would do whatever
/// their size are within the budget; otherwise an
/// [`Error::TooMuchWork`] saying how many tests, against what budget, and
/// about how long they would take.
pub fn within_budget<W>(
    backend: &Descriptor<W>,
    primitives: u64,
    pixels: u64,
    budget: WorkBudget,
) -> Result<()> {
    let allowed = budget.tests(pixels);
    match backend.cost.tests_whatever_the_size(primitives, pixels) {
        Some(tests) if tests > allowed => Err(Error::TooMuchWork(format!(
            "`{}` would test about {tests:.2e} samples ({primitives} primitives x {pixels} pixels), \
             beyond {budget} of {allowed:.0e}, roughly {:.0} minutes; choose a back-end whose work \
             follows the primitives' size",
            backend.name,
            tests as f64 / NAIVE_TESTS_PER_SECOND / 60.0
        ))),
        _ => Ok(()),
    }
}

//! Causes: hypotheses about a rasterizer's mistake, named only where the
//! reference confirms them.
//!
//! A failing case says *that* a subject is wrong. To say *why*, `check`
//! keeps a catalogue of the classic mistakes, each a hypothesis that can
//! be tested against what the subject drew:
//!
//! * a **change to the case or to the reference** (another fill rule, one
//!   winding culled, small triangles dropped, vertices rounded or snapped
//!   to a coarser grid, samples at pixel corners, y measured from the
//!   bottom; for lines another tie rule, the walk from the other end, an
//!   endpoint pixel left out or doubled): the reference draws the changed
//!   case, and the hypothesis holds when its answer is, fragment for
//!   fragment, what the subject drew;
//! * a **condition on the differences** that no changed case expresses
//!   (fragments off the target, pixels listed twice, the bounding box one
//!   row or column short, every difference within a hair of an edge,
//!   every difference on triangles reaching far off the target; for
//!   lines one pixel per column on a steep line, a 4-connected
//!   staircase).
//!
//! A cause is named only when it explains **every** difference of the
//! failing case as generated, before shrinking; it is then tried on every
//! other failing case of the run, and the diagnosis says on how many it
//! held. Where no single cause explains a case, pairs are tried (a subject
//! may cull one winding *and* drop small triangles). Where several explain
//! the same differences, the first in the catalogue's order
//! ([`catalogue`]) is named and the others are listed as also fitting.
//! The shrinker then keeps only smaller cases that the named cause still
//! explains, so the counterexample shows the cause, not something else.

mod lines;
mod triangles;

use super::case::Case;
use super::property::{LineConvention, Property};
use super::Fragment;
use crate::raster::edge::FillRule;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt;

pub use triangles::{FAR_OFF_TARGET, NEAR_AN_EDGE};

/// A side of a triangle's bounding box.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Side {
    /// The last row (largest y).
    Bottom,
    /// The last column (largest x).
    Right,
    /// The first row.
    Top,
    /// The first column.
    Left,
}

/// An end of a line: its start, its end, or both.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum End {
    /// The pixel of the line's second endpoint.
    Last,
    /// The pixel of its first endpoint.
    First,
    /// Both.
    Both,
}

/// A winding on screen (y down).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Winding {
    /// Clockwise as seen on screen: negative signed area.
    Clockwise,
    /// Counter-clockwise as seen on screen.
    CounterClockwise,
}

/// One mistake of the catalogue.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Cause {
    /// Fragments off the target: the subject does not clip.
    OffTarget,
    /// One pixel listed twice for one primitive.
    Duplicates,
    /// Ties decided by this fill rule.
    FillRule(FillRule),
    /// Triangles of this winding culled.
    Culls(Winding),
    /// Triangles of area below this many square pixels dropped.
    DropsBelow(f64),
    /// Vertices rounded to whole pixels.
    RoundedToPixels,
    /// Samples at pixel corners `(x, y)`, not centres `(x + 0.5, y + 0.5)`.
    CornerSamples,
    /// y measured up from the bottom of the target: the picture flipped.
    FlippedY,
    /// Vertices snapped to 1/n px, not 1/256.
    CoarseSnap(u32),
    /// Vertices snapped to 1/256 px, but a coordinate exactly halfway
    /// rounded up or away from zero, not to even.
    SnapTies,
    /// The bounding-box loop one row or column short on this side.
    BoxShort(Side),
    /// Floating-point edge functions: every difference within
    /// [`NEAR_AN_EDGE`] of an edge.
    FloatEdges,
    /// Overflow: every difference on triangles reaching more than
    /// [`FAR_OFF_TARGET`] px off the target.
    Overflow,
    /// Lines: another convention's ties.
    Convention(LineConvention),
    /// Lines: walked from the other end.
    Reversed,
    /// Lines: an endpoint pixel left out.
    EndpointMissing(End),
    /// Lines: an endpoint pixel drawn twice.
    EndpointDoubled(End),
    /// Lines: a steep line drawn one pixel per column.
    OnePerColumn,
    /// Lines: drawn 4-connected.
    FourConnected,
    /// Multisampling: every sample decided at the pixel centre (a full
    /// mask wherever the centre is covered).
    CentreForEverySample,
    /// Multisampling: the sample pattern mirrored in y.
    MirroredPattern,
}

impl Cause {
    /// A stable identifier, for JSON and tests: `fill-rule:inclusive`,
    /// `culls:clockwise`, `drops-below:1`, `coarse-snap:16`,
    /// `box-short:bottom`, `convention:pixel-index-toward-end`, ...
    pub fn id(&self) -> String {
        let side = |s: Side| match s {
            Side::Bottom => "bottom",
            Side::Right => "right",
            Side::Top => "top",
            Side::Left => "left",
        };
        let end = |e: End| match e {
            End::Last => "last",
            End::First => "first",
            End::Both => "both",
        };
        match *self {
            Cause::OffTarget => "off-target".into(),
            Cause::Duplicates => "duplicates".into(),
            Cause::FillRule(r) => format!("fill-rule:{}", r.name()),
            Cause::Culls(Winding::Clockwise) => "culls:clockwise".into(),
            Cause::Culls(Winding::CounterClockwise) => "culls:counter-clockwise".into(),
            Cause::DropsBelow(a) => format!("drops-below:{a}"),
            Cause::RoundedToPixels => "rounded-to-pixels".into(),
            Cause::CornerSamples => "corner-samples".into(),
            Cause::FlippedY => "y-flipped".into(),
            Cause::CoarseSnap(n) => format!("coarse-snap:{n}"),
            Cause::SnapTies => "snap-ties".to_string(),
            Cause::BoxShort(s) => format!("box-short:{}", side(s)),
            Cause::FloatEdges => "float-edges".into(),
            Cause::Overflow => "overflow".into(),
            Cause::Convention(c) => format!("convention:{}", c.name()),
            Cause::Reversed => "reversed".into(),
            Cause::EndpointMissing(e) => format!("endpoint-missing:{}", end(e)),
            Cause::EndpointDoubled(e) => format!("endpoint-doubled:{}", end(e)),
            Cause::OnePerColumn => "one-per-column".into(),
            Cause::FourConnected => "four-connected".into(),
            Cause::CentreForEverySample => "centre-for-every-sample".into(),
            Cause::MirroredPattern => "mirrored-pattern".into(),
        }
    }

    /// What the cause changes: the fragments drawn (off the target,
    /// duplicates), the answer (a model), or a condition the differences
    /// must meet.
    fn role(&self) -> Role {
        match self {
            Cause::OffTarget | Cause::Duplicates => Role::Strip,
            Cause::BoxShort(_)
            | Cause::FloatEdges
            | Cause::Overflow
            | Cause::OnePerColumn
            | Cause::FourConnected => Role::Condition,
            _ => Role::Model,
        }
    }
}

impl fmt::Display for Cause {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let side = |s: Side| match s {
            Side::Bottom => "one row short at the bottom",
            Side::Right => "one column short on the right",
            Side::Top => "one row short at the top",
            Side::Left => "one column short on the left",
        };
        let end = |e: End| match e {
            End::Last => "the last endpoint's pixel",
            End::First => "the first endpoint's pixel",
            End::Both => "both endpoints' pixels",
        };
        match *self {
            Cause::OffTarget => f.write_str("fragments off the target: it does not clip to the target"),
            Cause::Duplicates => f.write_str("pixels listed twice for one primitive"),
            Cause::FillRule(r) => write!(f, "ties decided by the {} rule", r.name()),
            Cause::Culls(Winding::Clockwise) => {
                f.write_str("triangles wound clockwise on screen culled")
            }
            Cause::Culls(Winding::CounterClockwise) => {
                f.write_str("triangles wound counter-clockwise on screen culled")
            }
            Cause::DropsBelow(a) => write!(f, "triangles of area below {a} square pixel(s) dropped"),
            Cause::RoundedToPixels => f.write_str("vertices rounded to whole pixels"),
            Cause::CornerSamples => f.write_str(
                "samples at pixel corners (x, y) instead of centres (x + 0.5, y + 0.5): the half-pixel offset",
            ),
            Cause::FlippedY => {
                f.write_str("y measured up from the bottom of the target: the picture flipped")
            }
            Cause::CoarseSnap(n) => write!(f, "vertices snapped to 1/{n} px instead of 1/256"),
            Cause::SnapTies => write!(
                f,
                "vertices snapped to 1/256 px with a coordinate exactly halfway rounded up \
                 or away from zero (`floor(x + 0.5)`, C's `round`, JavaScript's `Math.round`), \
                 not to even"
            ),
            Cause::BoxShort(s) => write!(f, "the bounding box {}", side(s)),
            Cause::FloatEdges => f.write_str(
                "floating-point edge functions (or vertices not snapped to 1/256 px): every difference lies within a hair of an edge",
            ),
            Cause::Overflow => f.write_str(
                "overflow: every difference is on triangles reaching far off the target",
            ),
            Cause::Convention(c) => write!(f, "the {} convention's pixels", c.name()),
            Cause::Reversed => f.write_str("each line drawn from its other end"),
            Cause::EndpointMissing(e) => write!(f, "{} left out", end(e)),
            Cause::EndpointDoubled(e) => write!(f, "{} drawn twice", end(e)),
            Cause::OnePerColumn => f.write_str(
                "a steep line drawn one pixel per column: the walk along x used for a line that runs along y (the octant swap is missing)",
            ),
            Cause::FourConnected => {
                f.write_str("drawn 4-connected: a step along one axis at a time")
            }
            Cause::CentreForEverySample => f.write_str(
                "every sample decided at the pixel centre: a full mask wherever the centre is covered, \
                 none elsewhere (one sample per pixel, not multisampling)",
            ),
            Cause::MirroredPattern => f.write_str(
                "the sample pattern mirrored in y: OpenGL's sample positions, which are given with y up, \
                 used in y-down screen coordinates",
            ),
        }
    }
}

#[derive(Copy, Clone, PartialEq, Eq)]
enum Role {
    Strip,
    Model,
    Condition,
}

/// The catalogue for a property, in its stated order: the order in which
/// causes that explain the same differences are preferred, simplest first.
///
/// Triangles: fragments off the target; pixels listed twice; each other
/// fill rule (under watertight and crack-free only the two that are not
/// watertight, inclusive and exclusive, since any consistent rule passes
/// there); one winding culled (clockwise, then counter-clockwise);
/// triangles below an area dropped (1, 1/2, 2, 1/4 and 4 px²); vertices
/// rounded to whole pixels; samples at pixel corners; y flipped; vertices
/// snapped to 1/2 ... 1/128 px; the bounding box one row or column short
/// (bottom, right, top, left); floating-point edge functions; overflow.
///
/// Lines: fragments off the target; each other convention taking the
/// same kind of endpoints (whole pixel indices, or screen coordinates);
/// the walk from the other end; an endpoint pixel left out (the last, the
/// first, both) or drawn twice (before pixels listed twice in general);
/// pixels listed twice; one pixel per column on steep lines; 4-connected.
///
/// A box one row *longer* than needed is not in the catalogue: the pixels
/// it adds are tested and rejected, so it draws what the rules draw.
///
/// Under `--msaa` ([`catalogue_multisampled`]) the triangle causes that
/// change the case or the reference stay (each then decides every
/// sample), the conditions about pixel centres go, and two come first:
/// every sample decided at the centre, and the pattern mirrored in y.
pub fn catalogue(property: Property) -> Vec<Cause> {
    let mut out = vec![Cause::OffTarget];
    match property {
        Property::Line(base) => {
            for c in LineConvention::ALL {
                if c != base
                    && c.whole_pixels() == base.whole_pixels()
                    && c != LineConvention::Vulkan
                {
                    out.push(Cause::Convention(c));
                }
            }
            out.push(Cause::Reversed);
            for e in [End::Last, End::First, End::Both] {
                out.push(Cause::EndpointMissing(e));
            }
            for e in [End::Last, End::First, End::Both] {
                out.push(Cause::EndpointDoubled(e));
            }
            out.extend([Cause::Duplicates, Cause::OnePerColumn, Cause::FourConnected]);
        }
        _ => {
            out.push(Cause::Duplicates);
            let mesh = property.needs_mesh();
            for r in FillRule::ALL {
                let other = match property {
                    Property::Exact(base) => r != base,
                    _ => !FillRule::WATERTIGHT.contains(&r),
                };
                if other && (!mesh || !FillRule::WATERTIGHT.contains(&r)) {
                    out.push(Cause::FillRule(r));
                }
            }
            out.extend([
                Cause::Culls(Winding::Clockwise),
                Cause::Culls(Winding::CounterClockwise),
            ]);
            for a in [1.0, 0.5, 2.0, 0.25, 4.0] {
                out.push(Cause::DropsBelow(a));
            }
            out.extend([
                Cause::RoundedToPixels,
                Cause::CornerSamples,
                Cause::FlippedY,
            ]);
            for n in [2, 4, 8, 16, 32, 64, 128] {
                out.push(Cause::CoarseSnap(n));
            }
            out.push(Cause::SnapTies);
            for s in [Side::Bottom, Side::Right, Side::Top, Side::Left] {
                out.push(Cause::BoxShort(s));
            }
            out.extend([Cause::FloatEdges, Cause::Overflow]);
        }
    }
    out
}

/// The catalogue for a multisampled check (`check --msaa N`) of
/// `property`: see [`catalogue`].
pub fn catalogue_multisampled(property: Property) -> Vec<Cause> {
    let mut out = catalogue(property);
    out.retain(|c| c.role() != Role::Condition);
    let at = out
        .iter()
        .position(|c| *c == Cause::Duplicates)
        .map_or(0, |i| i + 1);
    out.splice(
        at..at,
        [Cause::CentreForEverySample, Cause::MirroredPattern],
    );
    out
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

/// The differences between what was drawn and an answer, as multisets:
/// fragments drawn more often than the answer has them, and fragments of
/// the answer drawn less often.
fn differences(drawn: &[Fragment], answer: &[Fragment]) -> (Vec<Fragment>, Vec<Fragment>) {
    let mut count: BTreeMap<Fragment, i64> = BTreeMap::new();
    for f in drawn {
        *count.entry(*f).or_default() += 1;
    }
    for f in answer {
        *count.entry(*f).or_default() -= 1;
    }
    let (mut extra, mut missing) = (Vec::new(), Vec::new());
    for (f, n) in count {
        for _ in 0..n.max(0) {
            extra.push(f);
        }
        for _ in 0..(-n).max(0) {
            missing.push(f);
        }
    }
    (extra, missing)
}

/// Whether `causes` together explain every difference between `drawn`
/// and the rules' answer on `case`; the evidence when they do.
pub fn explains(
    causes: &[Cause],
    property: Property,
    case: &Case,
    drawn: &[Fragment],
) -> Option<String> {
    let lines = property.is_lines();
    let (w, h) = (i64::from(case.width), i64::from(case.height));
    let mut kept = drawn.to_vec();
    let mut notes: Vec<String> = Vec::new();
    for c in causes.iter().filter(|c| c.role() == Role::Strip) {
        let before = kept.len();
        match c {
            Cause::OffTarget => {
                let off: Vec<Fragment> = kept
                    .iter()
                    .filter(|f| !(0..w).contains(&f.x) || !(0..h).contains(&f.y))
                    .copied()
                    .collect();
                kept.retain(|f| (0..w).contains(&f.x) && (0..h).contains(&f.y));
                if let Some(first) = off.first() {
                    notes.push(format!(
                        "{} fragment(s) off the {}x{} target, first ({}, {})",
                        off.len(),
                        case.width,
                        case.height,
                        first.x,
                        first.y
                    ));
                }
            }
            _ => {
                let mut seen = BTreeSet::new();
                kept.retain(|f| seen.insert(*f));
                notes.push(format!("{} pixel(s) listed twice", before - kept.len()));
            }
        }
        if kept.len() == before {
            return None;
        }
    }
    let conditions: Vec<&Cause> = causes
        .iter()
        .filter(|c| c.role() == Role::Condition)
        .collect();
    // The conditions are about pixel centres: not a multisampled case's.
    if conditions.len() > 1 || (!conditions.is_empty() && case.samples.is_some()) {
        return None;
    }
    // The answer under the model's changes; under watertight and
    // crack-free any watertight rule may be the subject's.
    let bases: Vec<Option<FillRule>> = match property {
        Property::Exact(r) => vec![Some(r)],
        Property::Watertight | Property::CrackFree => {
            FillRule::WATERTIGHT.iter().map(|&r| Some(r)).collect()
        }
        Property::Line(_) => vec![None],
    };
    for base in bases {
        let answers = if lines {
            let Property::Line(convention) = property else {
                return None;
            };
            let base = if convention == LineConvention::Vulkan {
                LineConvention::Diamond
            } else {
                convention
            };
            let mut model = lines::Model::default();
            for c in causes.iter().filter(|c| c.role() == Role::Model) {
                if !model.add(c) {
                    return None;
                }
            }
            vec![model.fragments(case, base)]
        } else {
            let mut model = triangles::Model::default();
            for c in causes.iter().filter(|c| c.role() == Role::Model) {
                if !model.add(c) {
                    return None;
                }
            }
            // A rounding's tie (exactly halfway) goes one of three ways
            // in the wild: any of them may be the subject's.
            model
                .rounding_ties()
                .into_iter()
                .map(|m| m.fragments(case, base.unwrap_or(FillRule::TopLeft)))
                .collect()
        };
        for answer in answers {
            let (extra, missing) = differences(&kept, &answer);
            let explained = match conditions.first() {
                None => extra.is_empty() && missing.is_empty(),
                Some(c) => {
                    let differing: BTreeSet<u32> =
                        extra.iter().chain(&missing).map(|f| f.id).collect();
                    !differing.is_empty()
                        && match c {
                            Cause::BoxShort(side) => {
                                extra.is_empty() && triangles::box_short(*side, &answer, &missing)
                            }
                            Cause::FloatEdges => extra.iter().chain(&missing).all(|f| {
                                case.triangles.get(f.id as usize).is_some_and(|t| {
                                    triangles::distance_to_an_edge(t, f.x, f.y) <= NEAR_AN_EDGE
                                })
                            }),
                            Cause::Overflow => differing.iter().all(|id| {
                                case.triangles.get(*id as usize).is_some_and(|t| {
                                    triangles::reach_off_target(case, t) > FAR_OFF_TARGET
                                })
                            }),
                            Cause::OnePerColumn => {
                                let Property::Line(c) = property else {
                                    return None;
                                };
                                lines::one_per_column(case, c.whole_pixels(), &kept, &differing)
                            }
                            Cause::FourConnected => {
                                let Property::Line(c) = property else {
                                    return None;
                                };
                                lines::four_connected(case, c, &kept, &answer, &differing)
                            }
                            _ => false,
                        }
                }
            };
            if explained {
                notes.extend(evidence(causes, case, &answer, &extra, &missing));
                return Some(notes.join("; "));
            }
        }
    }
    None
}

/// What each cause showed on a case it explains.
fn evidence(
    causes: &[Cause],
    case: &Case,
    answer: &[Fragment],
    extra: &[Fragment],
    missing: &[Fragment],
) -> Vec<String> {
    let ids_with = |pred: &dyn Fn(u32) -> bool| -> Vec<u32> {
        (0..case.triangles.len() as u32)
            .filter(|&i| pred(i))
            .collect()
    };
    let drew = |id: u32| answer.iter().any(|f| f.id == id);
    let list = |v: &[u32]| v.iter().map(u32::to_string).collect::<Vec<_>>().join(", ");
    let differing = extra.len() + missing.len();
    let mut out = Vec::new();
    for c in causes {
        match c {
            Cause::Culls(w) => {
                let cw = *w == Winding::Clockwise;
                let culled = ids_with(&|i| {
                    triangles::clockwise(&case.triangles[i as usize]) == cw
                        && triangles::area(&case.triangles[i as usize]) > 0.0
                });
                if !culled.is_empty() {
                    out.push(format!(
                        "triangle(s) {} wound {} drew nothing",
                        list(&culled),
                        if cw { "clockwise" } else { "counter-clockwise" }
                    ));
                }
            }
            Cause::DropsBelow(a) => {
                let areas: Vec<String> = ids_with(&|i| {
                    let s = triangles::area(&case.triangles[i as usize]);
                    s > 0.0 && s < *a
                })
                .iter()
                .map(|&i| {
                    format!(
                        "{} ({} px²)",
                        i,
                        round4(triangles::area(&case.triangles[i as usize]))
                    )
                })
                .collect();
                let smallest_drawn = (0..case.triangles.len() as u32)
                    .filter(|&i| drew(i))
                    .map(|i| triangles::area(&case.triangles[i as usize]))
                    .fold(f64::INFINITY, f64::min);
                if !areas.is_empty() {
                    let mut s = format!("triangle(s) {} drew nothing", areas.join(", "));
                    if smallest_drawn.is_finite() {
                        s.push_str(&format!(
                            ", the smallest drawn has {} px²",
                            round4(smallest_drawn)
                        ));
                    }
                    out.push(s);
                }
            }
            Cause::BoxShort(_) => {
                let lost: BTreeSet<u32> = missing.iter().map(|f| f.id).collect();
                out.push(format!(
                    "the {} missing pixel(s) are that whole row or column of triangle(s) {}",
                    missing.len(),
                    list(&lost.into_iter().collect::<Vec<_>>())
                ));
            }
            Cause::FloatEdges => {
                let worst = extra
                    .iter()
                    .chain(missing)
                    .filter_map(|f| {
                        case.triangles
                            .get(f.id as usize)
                            .map(|t| triangles::distance_to_an_edge(t, f.x, f.y))
                    })
                    .fold(0.0, f64::max);
                out.push(format!(
                    "all {differing} difference(s) lie within {} px of an edge, the farthest {} px",
                    NEAR_AN_EDGE,
                    round6(worst)
                ));
            }
            Cause::Overflow => {
                let ids: BTreeSet<u32> = extra.iter().chain(missing).map(|f| f.id).collect();
                let reach = ids
                    .iter()
                    .filter_map(|&i| case.triangles.get(i as usize))
                    .map(|t| triangles::reach_off_target(case, t))
                    .fold(0.0, f64::max);
                out.push(format!(
                    "all {differing} difference(s) are on triangle(s) {} reaching up to {} px off the target",
                    list(&ids.into_iter().collect::<Vec<_>>()),
                    round4(reach)
                ));
            }
            Cause::OnePerColumn | Cause::FourConnected => {
                let ids: BTreeSet<u32> = extra.iter().chain(missing).map(|f| f.id).collect();
                out.push(format!(
                    "line(s) {} drawn so",
                    list(&ids.into_iter().collect::<Vec<_>>())
                ));
            }
            _ => {}
        }
    }
    if causes.iter().any(|c| c.role() == Role::Model) {
        out.push(format!(
            "with it the reference draws exactly the subject's {} fragment(s)",
            answer.len() + extra.len() - missing.len()
        ));
    }
    out
}

fn round4(v: f64) -> f64 {
    (v * 1e4).round() / 1e4 + 0.0
}

fn round6(v: f64) -> f64 {
    (v * 1e6).round() / 1e6 + 0.0
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

/// What the changes among `causes` draw on `case` (the reference's answer
/// with them), or `None` when they hold no change or conflict.
pub fn predict(causes: &[Cause], property: Property, case: &Case) -> Option<Vec<Fragment>> {
    let models: Vec<&Cause> = causes.iter().filter(|c| c.role() == Role::Model).collect();
    if models.is_empty() {
        return None;
    }
    match property {
        Property::Line(convention) => {
            let mut model = lines::Model::default();
            for c in models {
                if !model.add(c) {
                    return None;
                }
            }
            let base = if convention == LineConvention::Vulkan {
                LineConvention::Diamond
            } else {
                convention
            };
            Some(model.fragments(case, base))
        }
        Property::Exact(rule) => {
            let mut model = triangles::Model::default();
            for c in models {
                if !model.add(c) {
                    return None;
                }
            }
            Some(model.fragments(case, rule))
        }
        // Any watertight rule may be the subject's: no one answer.
        Property::Watertight | Property::CrackFree => None,
    }
}

/// The hypotheses a named cause competes with on cases not seen yet: the
/// cause together with each other change of the catalogue. A case where
/// they draw differently tells them apart (a subject that culls one
/// winding may drop small triangles too, which no failure seen so far
/// showed).
pub fn rivals(diagnosis: &Diagnosis, property: Property, multisampled: bool) -> Vec<Vec<Cause>> {
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
pub fn diagnose(
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
            .map(|c| c.to_string())
            .collect::<Vec<_>>()
            .join(", and "),
        evidence,
        confirmed_on,
        failing_cases: n,
        also_fits,
        found,
    })
}

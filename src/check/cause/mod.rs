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
//!
//! Here is the catalogue; `explain` tests a cause on one case, `diagnosis`
//! names the cause of a run's failures, and `triangles` and `lines` hold
//! what each family of causes changes.

mod diagnosis;
mod explain;
mod lines;
mod polygons;
mod triangles;

use super::polygons::Boundary;
use super::property::{LineConvention, Property};
use super::snapping::Snapping;
use crate::raster::edge::FillRule;
use crate::raster::polygon::WindingRule;
use std::fmt;

pub use diagnosis::Diagnosis;
pub(crate) use diagnosis::{diagnose, rivals};
pub(crate) use explain::predict;
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
    /// Polygons: filled by the other winding rule.
    OtherFill(WindingRule),
    /// Polygons: a centre on an edge decided by another boundary
    /// convention.
    Boundary(Boundary),
    /// Polygons: the holes ignored (each polygon filled as its outer ring
    /// alone).
    HoleIgnored,
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
            Cause::OtherFill(r) => format!("fill:{}", r.name()),
            Cause::Boundary(b) => format!("boundary:{}", b.name()),
            Cause::HoleIgnored => "hole-ignored".into(),
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
            Cause::FloatEdges => f.write_str(&float_edges_words(Snapping::default())),
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
            Cause::OtherFill(r) => write!(
                f,
                "the other fill rule: filled by the {} rule (they differ where rings cross or overlap)",
                r.name()
            ),
            Cause::Boundary(b) => write!(
                f,
                "the boundary convention: a centre on an edge decided by the {} convention ({})",
                b.name(),
                b.words()
            ),
            Cause::HoleIgnored => f.write_str(
                "a hole ignored: each polygon filled as its outer ring alone",
            ),
        }
    }
}

/// The floating-point cause in words, for vertices snapped as given:
/// on a grid, the vertices may also not have been snapped to it; judged
/// as given (`--snap none`), nothing was to be snapped.
pub(crate) fn float_edges_words(snapping: Snapping) -> String {
    let unsnapped = match snapping {
        Snapping::Grid { .. } => format!(" (or vertices not snapped to {snapping} px)"),
        Snapping::AsGiven => String::new(),
    };
    format!(
        "floating-point edge functions{unsnapped}: every difference lies within a hair of an edge"
    )
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
/// Polygons: fragments off the target; pixels listed twice; the other
/// winding rule; each other boundary convention (top-right, bottom-left,
/// bottom-right, inclusive, exclusive); the holes ignored.
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
        Property::Polygon(base) => {
            out.push(Cause::Duplicates);
            out.extend(polygons::catalogue(base));
        }
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

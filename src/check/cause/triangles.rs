//! The triangle causes: what a rasterizer would draw had it made one
//! mistake (or two), computed by the reference on a changed case, and the
//! conditions on the differences that no changed case can express.
//!
//! A changed case is exact: snapping to a coarser grid rounds the
//! vertices before the reference snaps them to 1/256 px (where the coarse
//! grid's points are exact); sampling at pixel corners moves every vertex
//! by half a pixel, which the reference's 1/256 grid holds exactly; y
//! measured from the bottom draws the rules' pixels, each in the row
//! mirrored (row `r` written as row `height - 1 - r`: the centre tested is
//! the mirrored one, so ties go as the rule says in the given
//! coordinates); a culled or dropped triangle is replaced by a point,
//! which draws nothing and keeps the others' indices. Under
//! multisampling the reference draws masks on the changed case; every
//! sample decided at the centre is the one-sample answer with full masks,
//! and the mirrored pattern is
//! [`SamplePattern::mirrored_y`](crate::raster::SamplePattern::mirrored_y).

use super::{Cause, Side, Winding};
use crate::check::case::{Case, Point};
use crate::check::{triangle_fragments, Fragment};
use crate::raster::edge::FillRule;
use crate::raster::registry::reference_triangle_backend;
use std::collections::{BTreeMap, BTreeSet};

/// How far a vertex must lie off the target for its triangle to count as
/// reaching far off it (the overflow cause), in pixels.
pub const FAR_OFF_TARGET: f64 = 1024.0;

/// The widest band around an edge, in pixels, within which every
/// difference must lie for the floating-point cause.
pub const NEAR_AN_EDGE: f64 = 1.0 / 64.0;

/// The changes a hypothesis makes to the case or to the reference.
#[derive(Clone, Debug, Default)]
pub(super) struct Model {
    rule: Option<FillRule>,
    /// Grid step the vertices are rounded to (1.0: whole pixels).
    grid: Option<f64>,
    /// Which way that rounding breaks a tie.
    tie: RoundingTie,
    /// Only the ways other than to even (the rules' own snap at 1/256).
    tie_not_even: bool,
    corner_samples: bool,
    flip_y: bool,
    /// Triangles of this winding (`+1` counter-clockwise on screen, `-1`
    /// clockwise) draw nothing.
    cull: Option<i8>,
    /// Triangles of area below this (px²) draw nothing.
    drop_below: Option<f64>,
    /// A multisampled case: every sample decided at the pixel centre.
    centre_for_every_sample: bool,
    /// A multisampled case: the pattern mirrored in y.
    mirrored_pattern: bool,
}

/// How a rounding breaks a tie (a coordinate exactly halfway between
/// two grid points): C's `round` away from zero, Python's `round` and
/// numpy's to even (as the rules' own snapping does), JavaScript's
/// `Math.round` and `floor(x + 0.5)` up.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub(super) enum RoundingTie {
    #[default]
    ToEven,
    AwayFromZero,
    Up,
}

impl RoundingTie {
    fn round(self, v: f64) -> f64 {
        match self {
            RoundingTie::ToEven => v.round_ties_even(),
            RoundingTie::AwayFromZero => v.round(),
            RoundingTie::Up => (v + 0.5).floor(),
        }
    }
}

impl Model {
    /// The model once per way of breaking a rounding's tie, when it
    /// rounds the vertices; itself alone otherwise.
    pub(super) fn rounding_ties(&self) -> Vec<Model> {
        if self.grid.is_none() {
            return vec![self.clone()];
        }
        [
            RoundingTie::ToEven,
            RoundingTie::AwayFromZero,
            RoundingTie::Up,
        ]
        .into_iter()
        .filter(|&t| !(self.tie_not_even && t == RoundingTie::ToEven))
        .map(|tie| Model {
            tie,
            ..self.clone()
        })
        .collect()
    }

    /// Adds a cause's change; false when the cause is not a change to the
    /// case or the reference, or conflicts with one already made.
    pub(super) fn add(&mut self, cause: &Cause) -> bool {
        fn set<T>(slot: &mut Option<T>, v: T) -> bool {
            if slot.is_some() {
                return false;
            }
            *slot = Some(v);
            true
        }
        match *cause {
            Cause::FillRule(r) => set(&mut self.rule, r),
            Cause::RoundedToPixels => set(&mut self.grid, 1.0),
            Cause::CoarseSnap(n) => set(&mut self.grid, 1.0 / f64::from(n)),
            Cause::SnapTies => {
                self.tie_not_even = true;
                set(&mut self.grid, 1.0 / 256.0)
            }
            Cause::CornerSamples => !std::mem::replace(&mut self.corner_samples, true),
            Cause::FlippedY => !std::mem::replace(&mut self.flip_y, true),
            Cause::Culls(w) => set(&mut self.cull, if w == Winding::Clockwise { -1 } else { 1 }),
            Cause::DropsBelow(a) => set(&mut self.drop_below, a),
            Cause::CentreForEverySample => {
                !std::mem::replace(&mut self.centre_for_every_sample, true)
            }
            Cause::MirroredPattern => !std::mem::replace(&mut self.mirrored_pattern, true),
            _ => false,
        }
    }

    /// What the reference draws for `case` under `rule` with these changes.
    pub(super) fn fragments(&self, case: &Case, rule: FillRule) -> Vec<Fragment> {
        let point = |p: Point| -> Point {
            let mut q = p;
            if let Some(step) = self.grid {
                let round = |v: f64| self.tie.round(v / step) * step;
                q = (round(q.0), round(q.1));
            }
            if self.corner_samples {
                q = (q.0 + 0.5, q.1 + 0.5);
            }
            q
        };
        // Under multisampling, a picture measured from the bottom takes
        // its pattern upside down too.
        let samples = case.samples.map(|p| {
            if self.mirrored_pattern != self.flip_y {
                p.mirrored_y()
            } else {
                p
            }
        });
        let mut changed = Case {
            triangles: case.triangles.iter().map(|t| t.map(point)).collect(),
            lines: Vec::new(),
            samples: if self.centre_for_every_sample {
                None
            } else {
                samples
            },
            ..case.clone()
        };
        for t in &mut changed.triangles {
            // The subject's own view of its triangle: winding and area as
            // its (changed) vertices give them.
            let twice = signed_twice_area(t);
            let culled = self
                .cull
                .is_some_and(|w| twice != 0.0 && f64::from(w) == twice.signum());
            let small = self.drop_below.is_some_and(|a| twice.abs() / 2.0 < a);
            if culled || small {
                *t = [(0.0, 0.0); 3];
            }
        }
        let mut out = triangle_fragments(
            reference_triangle_backend(),
            &changed,
            self.rule.unwrap_or(rule),
        );
        if self.flip_y {
            let last = i64::from(case.height) - 1;
            for f in &mut out {
                f.y = last - f.y;
            }
        }
        if let (true, Some(p)) = (self.centre_for_every_sample, case.samples) {
            for f in &mut out {
                f.mask = p.full_mask();
            }
        }
        out
    }
}

/// Twice the signed area of a triangle as given (`+` counter-clockwise on
/// screen, y down, as [`TriangleSetup::signed_area`](crate::raster::edge::TriangleSetup::signed_area) has it).
fn signed_twice_area(t: &[Point; 3]) -> f64 {
    let [a, b, c] = *t;
    -((b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0))
}

/// A triangle's area in px², as given.
pub(super) fn area(t: &[Point; 3]) -> f64 {
    signed_twice_area(t).abs() / 2.0
}

/// Whether the triangle was given clockwise on screen.
pub(super) fn clockwise(t: &[Point; 3]) -> bool {
    signed_twice_area(t) < 0.0
}

/// How far the farthest vertex of `t` lies outside the target, in pixels.
pub(super) fn reach_off_target(case: &Case, t: &[Point; 3]) -> f64 {
    let (w, h) = (f64::from(case.width), f64::from(case.height));
    t.iter()
        .map(|p| {
            let dx = (-p.0).max(p.0 - w).max(0.0);
            let dy = (-p.1).max(p.1 - h).max(0.0);
            dx.max(dy)
        })
        .fold(0.0, f64::max)
}

/// The distance from pixel `(x, y)`'s centre to the nearest edge line of
/// triangle `t`, in pixels.
pub(super) fn distance_to_an_edge(t: &[Point; 3], x: i64, y: i64) -> f64 {
    let c = (x as f64 + 0.5, y as f64 + 0.5);
    (0..3)
        .filter_map(|k| {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let len = (b.0 - a.0).hypot(b.1 - a.1);
            (len > 0.0).then(|| ((b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)).abs() / len)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Whether every pixel of `missing` (all of one triangle's) lies on its
/// triangle's extreme row or column `side` of the answer, and that whole
/// row or column is missing.
pub(super) fn box_short(side: Side, answer: &[Fragment], missing: &[Fragment]) -> bool {
    let mut by_id: BTreeMap<u32, Vec<Fragment>> = BTreeMap::new();
    for f in missing {
        by_id.entry(f.id).or_default().push(*f);
    }
    by_id.iter().all(|(id, lost)| {
        let mine: Vec<&Fragment> = answer.iter().filter(|f| f.id == *id).collect();
        let key = |f: &Fragment| match side {
            Side::Top | Side::Bottom => f.y,
            Side::Left | Side::Right => f.x,
        };
        let extreme = match side {
            Side::Top | Side::Left => mine.iter().map(|f| key(f)).min(),
            Side::Bottom | Side::Right => mine.iter().map(|f| key(f)).max(),
        };
        let Some(extreme) = extreme else {
            return false;
        };
        let edge: BTreeSet<Fragment> = mine
            .iter()
            .filter(|f| key(f) == extreme)
            .map(|f| **f)
            .collect();
        let lost: BTreeSet<Fragment> = lost.iter().copied().collect();
        lost == edge
    })
}

//! The polygon causes: the other fill rule, another boundary convention,
//! the holes ignored. Each is a change to the reference, drawn by the
//! same oracle ([`fill`]) under the changed [`Filling`].

use super::Cause;
use crate::check::case::Case;
use crate::check::polygons::{fill, Boundary, Filling};
use crate::check::Fragment;
use crate::raster::polygon::WindingRule;

/// The changes a hypothesis makes to the reference's polygons.
#[derive(Clone, Debug, Default)]
pub(super) struct Model {
    rule: Option<WindingRule>,
    boundary: Option<Boundary>,
    without_holes: bool,
}

impl Model {
    /// Adds a cause's change; false when it is not a change to the
    /// polygons' reference, or conflicts with one already made.
    pub(super) fn add(&mut self, cause: &Cause) -> bool {
        match *cause {
            Cause::OtherFill(r) if self.rule.is_none() => {
                self.rule = Some(r);
                true
            }
            Cause::Boundary(b) if self.boundary.is_none() => {
                self.boundary = Some(b);
                true
            }
            Cause::HoleIgnored => !std::mem::replace(&mut self.without_holes, true),
            _ => false,
        }
    }

    /// What the reference fills with these changes, `base` the rule
    /// checked.
    pub(super) fn fragments(&self, case: &Case, base: WindingRule) -> Vec<Fragment> {
        fill(
            case,
            Filling {
                rule: self.rule.unwrap_or(base),
                boundary: self.boundary.unwrap_or(Boundary::TopLeft),
                without_holes: self.without_holes,
            },
        )
    }
}

/// The polygon causes for a check under `base`, in the catalogue's
/// order: the other fill rule, each other boundary convention, the holes
/// ignored.
pub(super) fn catalogue(base: WindingRule) -> Vec<Cause> {
    let mut out: Vec<Cause> = WindingRule::ALL
        .into_iter()
        .filter(|&r| r != base)
        .map(Cause::OtherFill)
        .collect();
    out.extend(
        Boundary::ALL
            .into_iter()
            .filter(|&b| b != Boundary::TopLeft)
            .map(Cause::Boundary),
    );
    out.push(Cause::HoleIgnored);
    out
}

//! What a check judges by: one property, or a table of them (every fill
//! rule under `--rule any`, every line convention under
//! `--convention any`), and which family each case comes from.

use crate::check::case::Case;
use crate::check::generate;
use crate::check::judge::Finding;
use crate::check::property::{LineConvention, Property};
use crate::check::request::{CheckRequest, ConventionChoice, Kind, RuleChoice, RuleRow, RuleTable};
use crate::check::Fragment;
use crate::error::{Error, Result};
use crate::raster::edge::FillRule;

/// What one case came to.
pub(super) enum Outcome {
    /// Under one property: the finding, if it fails.
    One(Option<Box<Finding>>),
    /// Under a table mode, per row ([`table_rows`]): `None` where the row
    /// does not judge the case, else the finding if it fails.
    Table(Vec<Option<Option<Box<Finding>>>>),
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
pub(super) fn table_rows(mode: Mode) -> Vec<(Property, bool)> {
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
    /// What the request judges by: its rule (triangles) or convention
    /// (lines), top-left and midpoint when it names none.
    pub(super) fn of_request(request: &CheckRequest, kind: Kind) -> Result<Mode> {
        if kind == Kind::Lines && request.rule.is_some() {
            return Err(Error::InvalidArgument(
                "--rule is for triangles; lines are judged by --convention".into(),
            ));
        }
        if kind != Kind::Polygons && request.fill.is_some() {
            return Err(Error::InvalidArgument(
                "--fill is for polygons (--kind polygons); triangles are judged by --rule".into(),
            ));
        }
        if kind == Kind::Polygons && (request.rule.is_some() || request.convention.is_some()) {
            return Err(Error::InvalidArgument(
                "--rule and --convention are for triangles and lines; polygons are judged by --fill"
                    .into(),
            ));
        }
        if kind == Kind::Triangles && request.convention.is_some() {
            return Err(Error::InvalidArgument(
                "--convention is for lines; triangles are judged by --rule".into(),
            ));
        }
        Ok(match kind {
            Kind::Polygons => Mode::One(Property::Polygon(request.fill.unwrap_or_default())),
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
        })
    }

    /// The property whose generator makes case `index`, and its index
    /// within that property's families.
    pub(super) fn case_property(self, index: u32) -> (Property, u32) {
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
    pub(super) fn judges(
        self,
        property: Property,
        mesh_only: bool,
        index: u32,
        from_file: bool,
    ) -> bool {
        match (self, property) {
            (Mode::AnyRule, _) => !mesh_only || (!from_file && index % 2 == 1),
            (Mode::AnyConvention, Property::Line(c)) => {
                from_file || c.whole_pixels() == (index % 2 == 1)
            }
            _ => true,
        }
    }

    pub(super) fn family(self, index: u32) -> &'static str {
        let (p, i) = self.case_property(index);
        generate::family(p, i)
    }

    /// Every family, in order, each once.
    pub(super) fn families(self) -> Vec<&'static str> {
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
    pub(super) fn id(self) -> String {
        match self {
            Mode::One(p) => p.id(),
            Mode::AnyRule => "any".into(),
            Mode::AnyConvention => "line-any".into(),
        }
    }

    pub(super) fn description(self) -> String {
        match self {
            Mode::One(p) => p.to_string(),
            Mode::AnyRule => "which fill rule: every rule, and watertight and crack-free".into(),
            Mode::AnyConvention => "which line convention: every convention, the screen ones on cases in screen coordinates, the whole-pixel ones on cases whose endpoints are pixel indices".into(),
        }
    }

    /// The table of a table mode: each row's agreeing cases.
    pub(super) fn rule_table(self, outcomes: &[(u32, Case, Vec<Fragment>, Outcome)]) -> RuleTable {
        let rows_of = table_rows(self);
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

/// A table row's name: the fill rule, `watertight`, `crack-free`, or the
/// line convention.
pub(super) fn row_name(p: Property) -> String {
    match p {
        Property::Exact(r) => r.name().into(),
        Property::Watertight => "watertight".into(),
        Property::CrackFree => "crack-free".into(),
        Property::Line(c) => c.name().into(),
        Property::Polygon(r) => r.name().into(),
    }
}

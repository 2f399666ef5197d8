//! The properties, and the judgement of one drawn case.
//!
//! Watertightness is judged without a tie rule: at a pixel centre `p`,
//! each triangle whose closed area contains `p` on its boundary covers a
//! wedge around `p` between two rays (along its edge, or its two edges at
//! a vertex). The union of the triangles covers a whole neighbourhood of
//! `p` exactly when some triangle holds `p` strictly inside, or every ray
//! direction occurs an even number of times (each wedge's side is matched
//! by a neighbour's).
//!
//! Two properties of a mesh (triangles that share edges and never overlap)
//! are judged so, side by side:
//!
//! | | watertight | crack-free |
//! |---|---|---|
//! | a centre on a shared edge or shared vertex, inside the mesh | drawn exactly once | drawn exactly once |
//! | a centre strictly inside one triangle | drawn exactly once | anything but twice |
//! | a centre on the mesh's outline | at most once | at most once |
//! | a centre outside every triangle | never | at most once |
//! | a triangle draws a centre outside its closed area | never | allowed, unless the pixel is then drawn twice |
//! | any pixel drawn twice | never | never |
//!
//! Watertight is the contract of an exact rasterizer with some consistent
//! tie rule. Crack-free asks only "is my mesh drawn without cracks?": a
//! rasterizer that misses a centre 0.004 px inside the mesh's outline
//! (floating point, anti-aliasing coverage thresholds) is not watertight
//! but can be crack-free.
//!
//! Every failure found has a [`FailureKind`]; the shrinker keeps the kind
//! of the failure it started from.

mod facts;
mod lines;
mod mesh;

use facts::diagnose;
use lines::{one_per_step, vulkan};
pub use mesh::{cover, Cover};
use mesh::{crack_free, watertight};

use super::case::{Case, Origin};
use super::cause::Diagnosis;
pub(crate) use super::property::{with_samples, LineConvention, Property};
use super::{reference, Fragment};
use crate::raster::edge::{FillRule, TriangleSetup};
use crate::raster::fixed::{FixedPoint, HALF_PIXEL, SUBPIXEL_SCALE};
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;

/// The kind of a failure: what the shrinker keeps while it shrinks.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FailureKind {
    /// A fragment outside the target.
    OffTarget,
    /// A fragment naming a primitive the input does not have.
    UnknownPrimitive,
    /// One pixel listed twice for one primitive.
    ListedTwice,
    /// A pixel the rule draws was not drawn (its centre off every edge).
    Missing,
    /// A pixel was drawn that the rule does not draw (its centre off every
    /// edge), or a triangle drew a centre it does not touch.
    Extra,
    /// A pixel whose centre lies exactly on an edge, decided against the
    /// rule.
    Tie,
    /// A centre inside the triangles left undrawn.
    Gap,
    /// A pixel drawn by two triangles.
    DoubleDraw,
    /// A line drawn with two pixels in one step of its major axis.
    Connectivity,
    /// A line with too many or too few fragments.
    Count,
    /// Under `--msaa`: a pixel drawn with another coverage mask than the
    /// rule's.
    Mask,
    /// The program gave no answer to the case: it crashed, ran past its
    /// time limit, answered `error` or printed something that is not
    /// fragments. Under `keep_going` such a case costs only itself.
    NoAnswer,
}

crate::names::named_enum!(
    FailureKind,
    "failure kind",
    OffTarget = "off-target",
    UnknownPrimitive = "unknown-primitive",
    ListedTwice = "listed-twice",
    Missing = "missing",
    Extra = "extra",
    Tie = "tie",
    Gap = "gap",
    DoubleDraw = "double-draw",
    Connectivity = "connectivity",
    Count = "count",
    Mask = "mask",
    NoAnswer = "no-answer"
);

/// Where a case came from: recorded in the counterexample file, the
/// report page and the JSON.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Provenance {
    /// The check's command line.
    pub command: String,
    /// The generator's seed.
    pub seed: u64,
    /// The 0-based index of the case.
    pub case_index: u32,
    /// The family the case was drawn from (or `file` for `--case FILE`).
    pub family: String,
}

/// What is wrong with one drawn case.
#[derive(Clone, Debug)]
pub struct Finding {
    /// The property that failed.
    pub property: Property,
    /// The case (shrunk, once the check has shrunk it).
    pub case: Case,
    /// What the subject drew.
    pub drawn: Vec<Fragment>,
    /// What an exact rasterizer draws (under watertight and crack-free:
    /// the top-left answer, one of those that pass).
    pub expected: Vec<Fragment>,
    /// Pixels that should have been drawn and were not.
    pub missing: Vec<Fragment>,
    /// Fragments that should not have been drawn (outside the target,
    /// listed twice, wrong pixels; of a double draw, the fragment of the
    /// triangle that the top-left rule (under an exact check, its rule)
    /// does not give the pixel to).
    pub extra: Vec<Fragment>,
    /// One sentence per problem found.
    pub problems: Vec<String>,
    /// The kind of each problem, in the same order.
    pub kinds: Vec<FailureKind>,
    /// A one-line explanation of the first problem, where one can be given.
    pub diagnosis: Option<String>,
    /// For a shrunk finding: the first problem of the case as generated.
    pub original_problem: Option<String>,
    /// Where the case came from, when a check records it.
    pub provenance: Option<Provenance>,
    /// The cause the reference confirmed, once a check has looked for one
    /// ([`Cause`](super::Cause)).
    pub cause: Option<Diagnosis>,
    /// Where the program checked puts its origin: under
    /// [`Origin::BottomLeft`] the counterexample file gives the case and
    /// the missing and extra pixels as the program sees them (y up), and
    /// the picture numbers its rows so, while the sentences keep the
    /// protocol's y down.
    pub origin: Origin,
    /// The pixel each problem is about, in the same order.
    at: Vec<Option<Fragment>>,
}

impl Finding {
    /// The kind of the first problem.
    pub fn kind(&self) -> FailureKind {
        self.kinds.first().copied().unwrap_or(FailureKind::Extra)
    }

    /// The pixel the first problem is about.
    pub fn focus(&self) -> Option<Fragment> {
        self.at
            .first()
            .copied()
            .flatten()
            .or_else(|| self.extra.first().or(self.missing.first()).copied())
    }

    fn add(&mut self, kind: FailureKind, at: Option<Fragment>, text: String) {
        self.problems.push(text);
        self.kinds.push(kind);
        self.at.push(at);
    }

    /// Puts the first problem of `kind` first and explains it; false when
    /// the finding has no problem of that kind.
    pub(crate) fn lead_with(&mut self, kind: FailureKind) -> bool {
        let Some(k) = self.kinds.iter().position(|&c| c == kind) else {
            return false;
        };
        if k > 0 {
            let p = self.problems.remove(k);
            self.problems.insert(0, p);
            let c = self.kinds.remove(k);
            self.kinds.insert(0, c);
            let a = self.at.remove(k);
            self.at.insert(0, a);
            self.diagnosis = diagnose(self);
        }
        true
    }
}

/// Judges what a subject drew for a case; `None` when the property holds.
pub fn judge(property: Property, case: &Case, drawn: &[Fragment]) -> Option<Finding> {
    let expected = reference(property, case);
    let mut finding = Finding {
        property,
        case: case.clone(),
        drawn: drawn.to_vec(),
        expected,
        missing: Vec::new(),
        extra: Vec::new(),
        problems: Vec::new(),
        kinds: Vec::new(),
        diagnosis: None,
        original_problem: None,
        provenance: None,
        cause: None,
        origin: Origin::TopLeft,
        at: Vec::new(),
    };
    always(case, drawn, &mut finding);
    match property {
        Property::Exact(_) | Property::Polygon(_) => exact(case, drawn, &mut finding),
        Property::Line(LineConvention::Vulkan) => vulkan(case, drawn, &mut finding),
        Property::Line(LineConvention::PixelIndexOpenCv4) => exact(case, drawn, &mut finding),
        Property::Line(_) => {
            one_per_step(case, drawn, &mut finding);
            exact(case, drawn, &mut finding);
        }
        Property::Watertight => watertight(case, drawn, &mut finding),
        Property::CrackFree => crack_free(case, drawn, &mut finding),
    }
    if finding.problems.is_empty() {
        return None;
    }
    finding.missing.sort();
    finding.missing.dedup();
    finding.extra.sort();
    finding.diagnosis = diagnose(&finding);
    Some(finding)
}

/// Checks every property shares: on the target, a known primitive, each
/// pixel once per primitive.
fn always(case: &Case, drawn: &[Fragment], finding: &mut Finding) {
    let (w, h) = (i64::from(case.width), i64::from(case.height));
    let count = case.len() as u32;
    let mut seen = BTreeSet::new();
    for &f in drawn {
        if !(0..w).contains(&f.x) || !(0..h).contains(&f.y) {
            finding.add(
                FailureKind::OffTarget,
                Some(f),
                format!(
                    "fragment ({}, {}) of primitive {} is outside the {}x{} target",
                    f.x, f.y, f.id, case.width, case.height
                ),
            );
            finding.extra.push(f);
        } else if f.id >= count {
            finding.add(
                FailureKind::UnknownPrimitive,
                Some(f),
                format!(
                    "fragment ({}, {}) names primitive {}, but the input has {count}",
                    f.x, f.y, f.id
                ),
            );
            finding.extra.push(f);
        } else if !seen.insert((f.x, f.y, f.id)) {
            finding.add(
                FailureKind::ListedTwice,
                Some(f),
                format!(
                    "pixel ({}, {}) is listed twice for primitive {}",
                    f.x, f.y, f.id
                ),
            );
            finding.extra.push(f);
        }
    }
}

/// Whether pixel `f`'s centre lies exactly on an edge of triangle `f.id`
/// (in its closed area).
fn on_an_edge(snapped: &[[FixedPoint; 3]], f: &Fragment) -> bool {
    let Some(v) = snapped.get(f.id as usize) else {
        return false;
    };
    let Some(t) = TriangleSetup::new(f.id, *v, FillRule::TopLeft) else {
        return false;
    };
    let p = centre(f.x, f.y);
    let Ok(point) = FixedPoint::from_raw(p.0, p.1) else {
        return false;
    };
    let e = t.edge_values(point);
    e.iter().all(|&v| v >= 0) && e.contains(&0)
}

/// The fragment set must equal the reference's. Triangle fragments whose
/// centre lies on an edge are ties; the others are missing or extra. In a
/// multisampled case a pixel drawn with another mask than the rule's is a
/// mask problem, and ties are told apart sample by sample in its text.
fn exact(case: &Case, drawn: &[Fragment], finding: &mut Finding) {
    if case.samples.is_some() {
        return masks(case, drawn, finding);
    }
    let want: BTreeSet<Fragment> = finding.expected.iter().copied().collect();
    let got: BTreeSet<Fragment> = drawn.iter().copied().collect();
    let already: BTreeSet<Fragment> = finding.extra.iter().copied().collect();
    let missing: Vec<Fragment> = want.difference(&got).copied().collect();
    let extra: Vec<Fragment> = got
        .difference(&want)
        .copied()
        .filter(|f| !already.contains(f))
        .collect();
    let snapped = case.snapped_triangles();
    let outlines = super::polygons::outlines(case);
    let tie = |f: &Fragment| {
        (!case.triangles.is_empty() && on_an_edge(&snapped, f))
            || (!case.polygons.is_empty() && super::polygons::on_a_ring(&outlines, f))
    };
    let rule = match finding.property {
        Property::Exact(rule) => rule.name(),
        Property::Polygon(_) => "top-left",
        _ => "",
    };
    let ties: Vec<Fragment> = extra
        .iter()
        .chain(&missing)
        .copied()
        .filter(|f| tie(f))
        .collect();
    let plain_extra: Vec<Fragment> = extra.iter().copied().filter(|f| !tie(f)).collect();
    let plain_missing: Vec<Fragment> = missing.iter().copied().filter(|f| !tie(f)).collect();
    if let Some(&f) = plain_extra.first() {
        finding.add(
            FailureKind::Extra,
            Some(f),
            format!(
                "{} fragment(s) drawn by the program but not by the reference (extra), first ({}, {}) of primitive {}",
                plain_extra.len(),
                f.x,
                f.y,
                f.id
            ),
        );
    }
    if let Some(&f) = ties.first() {
        finding.add(
            FailureKind::Tie,
            Some(f),
            format!(
                "{} fragment(s) whose centre lies exactly on an edge decided against the {rule} rule, first ({}, {}) of primitive {} ({})",
                ties.len(),
                f.x,
                f.y,
                f.id,
                if got.contains(&f) { "drawn" } else { "not drawn" }
            ),
        );
    }
    if let Some(&f) = plain_missing.first() {
        finding.add(
            FailureKind::Missing,
            Some(f),
            format!(
                "{} fragment(s) drawn by the reference but not by the program (missing), first ({}, {}) of primitive {}",
                plain_missing.len(),
                f.x,
                f.y,
                f.id
            ),
        );
    }
    finding.missing.extend(missing);
    finding.extra.extend(extra);
}

/// [`exact`] for a multisampled case: pixels missing, pixels extra, and
/// pixels whose mask differs from the rule's, each sample that differs
/// named and, where it lies exactly on an edge, called a tie.
fn masks(case: &Case, drawn: &[Fragment], finding: &mut Finding) {
    let Some(pattern) = case.samples else {
        return;
    };
    let key = |f: &Fragment| (f.x, f.y, f.id);
    let want: BTreeMap<(i64, i64, u32), Fragment> =
        finding.expected.iter().map(|f| (key(f), *f)).collect();
    // Off the target, unknown or listed twice: already reported.
    let already: BTreeSet<Fragment> = finding.extra.iter().copied().collect();
    // A pixel listed twice is judged by its first line.
    let mut got: BTreeMap<(i64, i64, u32), Fragment> = BTreeMap::new();
    for f in drawn {
        got.entry(key(f)).or_insert(*f);
    }
    let missing: Vec<Fragment> = want
        .iter()
        .filter(|(k, _)| !got.contains_key(k))
        .map(|(_, f)| *f)
        .collect();
    let extra: Vec<Fragment> = got
        .iter()
        .filter(|(k, f)| !want.contains_key(k) && !already.contains(f))
        .map(|(_, f)| *f)
        .collect();
    let wrong: Vec<(Fragment, Fragment)> = got
        .iter()
        .filter_map(|(k, f)| want.get(k).filter(|w| w.mask != f.mask).map(|w| (*f, *w)))
        .collect();
    let rule = match finding.property {
        Property::Exact(rule) => rule,
        _ => FillRule::TopLeft,
    };
    let snapped = case.snapped_triangles();
    // The samples of `bits` in pixel `f` that lie exactly on an edge of
    // its triangle.
    let on_an_edge = |f: &Fragment, bits: u32| -> Vec<usize> {
        let Some(t) = snapped
            .get(f.id as usize)
            .and_then(|v| TriangleSetup::new(f.id, *v, rule))
        else {
            return Vec::new();
        };
        (0..pattern.count() as usize)
            .filter(|i| bits & (1 << i) != 0)
            .filter(|&i| {
                let (px, py) = pattern.sample_point(f.x, f.y, i);
                let e = t.edges.map(|e| e.eval_raw(px, py));
                e.iter().all(|&v| v >= 0) && e.contains(&0)
            })
            .collect()
    };
    let samples = |bits: u32| -> String {
        let list: Vec<String> = (0..32)
            .filter(|i| bits & (1 << i) != 0)
            .map(|i: u32| i.to_string())
            .collect();
        list.join(", ")
    };
    if let Some(&f) = extra.first() {
        finding.add(
            FailureKind::Extra,
            Some(f),
            format!(
                "{} pixel(s) drawn that the rule leaves uncovered, first ({}, {}) of primitive {} (mask {})",
                extra.len(),
                f.x,
                f.y,
                f.id,
                f.mask
            ),
        );
    }
    if let Some(&(f, w)) = wrong.first() {
        let (more, fewer) = (f.mask & !w.mask, w.mask & !f.mask);
        let mut parts = Vec::new();
        if more != 0 {
            parts.push(format!("sample(s) {} drawn but not covered", samples(more)));
        }
        if fewer != 0 {
            parts.push(format!(
                "sample(s) {} covered but not drawn",
                samples(fewer)
            ));
        }
        let ties = on_an_edge(&f, more | fewer);
        if !ties.is_empty() {
            let list: Vec<String> = ties.iter().map(usize::to_string).collect();
            parts.push(format!(
                "sample(s) {} lie exactly on an edge: a tie decided against the {} rule",
                list.join(", "),
                rule.name()
            ));
        }
        finding.add(
            FailureKind::Mask,
            Some(f),
            format!(
                "{} pixel(s) drawn with another mask than the rule's, first ({}, {}) of primitive {}: mask {:#0width$b}, the rule's {:#0width$b} ({})",
                wrong.len(),
                f.x,
                f.y,
                f.id,
                f.mask,
                w.mask,
                parts.join("; "),
                width = pattern.count() as usize + 2
            ),
        );
    }
    if let Some(&f) = missing.first() {
        finding.add(
            FailureKind::Missing,
            Some(f),
            format!(
                "{} pixel(s) missing, first ({}, {}) of primitive {} (the rule's mask {})",
                missing.len(),
                f.x,
                f.y,
                f.id,
                f.mask
            ),
        );
    }
    finding.missing.extend(missing);
    finding.missing.extend(wrong.iter().map(|w| w.1));
    finding.extra.extend(extra);
    finding.extra.extend(wrong.iter().map(|w| w.0));
}

/// The fixed-point sample point of pixel `(x, y)`.
pub(super) fn centre(x: i64, y: i64) -> (i64, i64) {
    (
        x * SUBPIXEL_SCALE + HALF_PIXEL,
        y * SUBPIXEL_SCALE + HALF_PIXEL,
    )
}

/// A number as text, `-0` written as `0`.
pub(super) fn num(v: f64) -> f64 {
    v + 0.0
}

/// A snapped point as text, `(x, y)` in pixels.
pub(super) fn px(v: FixedPoint) -> String {
    let (x, y) = v.to_f64();
    format!("({}, {})", num(x), num(y))
}

impl Finding {
    /// The target as text, one character a pixel: `#` drawn and expected,
    /// `!` drawn and not expected (or drawn twice), `?` expected and
    /// missing, `.` neither. Cut to 80 x 40 around the problems.
    pub fn ascii_grid(&self) -> String {
        let extra: BTreeSet<(i64, i64)> = self.extra.iter().map(|f| (f.x, f.y)).collect();
        let missing: BTreeSet<(i64, i64)> = self.missing.iter().map(|f| (f.x, f.y)).collect();
        let drawn: BTreeSet<(i64, i64)> = self.drawn.iter().map(|f| (f.x, f.y)).collect();
        let focus = self
            .extra
            .iter()
            .chain(&self.missing)
            .next()
            .map_or((0, 0), |f| (f.x, f.y));
        let (w, h) = (i64::from(self.case.width), i64::from(self.case.height));
        let x0 = (focus.0 - 40).clamp(0, (w - 80).max(0));
        let y0 = (focus.1 - 20).clamp(0, (h - 40).max(0));
        let mut out = String::new();
        let _ = writeln!(out, "     x {x0}..{}", (x0 + 80).min(w) - 1);
        for y in y0..(y0 + 40).min(h) {
            let _ = write!(out, "{:>4}  ", self.program_row(y));
            for x in x0..(x0 + 80).min(w) {
                out.push(if extra.contains(&(x, y)) {
                    '!'
                } else if missing.contains(&(x, y)) {
                    '?'
                } else if drawn.contains(&(x, y)) {
                    '#'
                } else {
                    '.'
                });
            }
            out.push('\n');
        }
        out
    }

    /// The counterexample file: `# size WxH`, comment lines naming the
    /// failed property, the problems and the missing and extra pixels,
    /// then the primitives, so that the program can be run on it again.
    pub fn counterexample_text(&self) -> String {
        let mut out = format!("# size {}x{}\n", self.case.width, self.case.height);
        if let Some(note) = self.coordinates_note() {
            let _ = writeln!(out, "# origin {}", self.origin);
            let _ = writeln!(
                out,
                "# {note}; the missing and extra pixels and the primitives below are the \
                 program's, y up, as it is given the case"
            );
        }
        if let Some(p) = self.case.samples {
            let _ = writeln!(out, "# msaa {}", p.count());
        }
        let (id, words) = (
            self.property.id(),
            with_samples(self.property.to_string(), self.case.samples),
        );
        if id == words {
            let _ = writeln!(out, "# property: {id}");
        } else {
            let _ = writeln!(out, "# property: {id} ({words})");
        }
        if let Some(p) = &self.provenance {
            let _ = writeln!(out, "# command: {}", p.command);
            let _ = writeln!(
                out,
                "# seed {}, case {} (family {})",
                p.seed, p.case_index, p.family
            );
        }
        if let Some(original) = &self.original_problem {
            let _ = writeln!(out, "# the case as generated: {original}");
        }
        let _ = writeln!(out, "# failure kind: {}", self.kind());
        for p in self.problems.iter().take(20) {
            let _ = writeln!(out, "# {p}");
        }
        let list = |v: &[Fragment]| -> String {
            v.iter()
                .take(40)
                .map(|f| (f, self.program_row(f.y)))
                .map(|(f, y)| match self.case.samples {
                    Some(_) => format!("({},{y}) t{} mask {}", f.x, f.id, f.mask),
                    None => format!("({},{y}) t{}", f.x, f.id),
                })
                .collect::<Vec<_>>()
                .join(" ")
        };
        let _ = writeln!(out, "# missing: {}", list(&self.missing));
        let _ = writeln!(out, "# extra: {}", list(&self.extra));
        if let Some(d) = &self.diagnosis {
            let _ = writeln!(out, "# diagnosis: {d}");
        }
        let body = self.case.to_text_for(self.origin);
        let header = ["# size ", "# origin ", "# msaa "];
        out.extend(
            body.split_inclusive('\n')
                .filter(|line| !header.iter().any(|h| line.starts_with(h))),
        );
        out
    }

    /// The row the program checked names pixel row `y` by: `y` itself,
    /// or under [`Origin::BottomLeft`] counted up from the bottom row.
    pub fn program_row(&self, y: i64) -> i64 {
        match self.origin {
            Origin::TopLeft => y,
            Origin::BottomLeft => i64::from(self.case.height) - 1 - y,
        }
    }

    /// Under [`Origin::BottomLeft`], which way the pixels of the
    /// sentences count: the protocol's, y down.
    pub fn coordinates_note(&self) -> Option<String> {
        (self.origin == Origin::BottomLeft).then(|| {
            format!(
                "the pixels (x, y) of the sentences count y down from the top edge, as the \
                 protocol does; the program counts rows up from the bottom: its row is \
                 height - 1 - y = {} - y",
                i64::from(self.case.height) - 1
            )
        })
    }
}

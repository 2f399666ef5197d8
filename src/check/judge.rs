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

use super::case::Case;
use super::cause::Diagnosis;
use super::pixel_index;
pub use super::property::{LineConvention, Property};
use super::{reference, Fragment};
use crate::raster::edge::{FillRule, TriangleSetup};
use crate::raster::fixed::{FixedPoint, HALF_PIXEL, SUBPIXEL_SCALE};
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet, HashMap};
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
    Count = "count"
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
    /// ([`cause`](super::cause)).
    pub cause: Option<Diagnosis>,
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
        at: Vec::new(),
    };
    always(case, drawn, &mut finding);
    match property {
        Property::Exact(_) => exact(case, drawn, &mut finding),
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
        } else if !seen.insert(f) {
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
/// centre lies on an edge are ties; the others are missing or extra.
fn exact(case: &Case, drawn: &[Fragment], finding: &mut Finding) {
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
    let tie = |f: &Fragment| !case.triangles.is_empty() && on_an_edge(&snapped, f);
    let rule = match finding.property {
        Property::Exact(rule) => rule.name(),
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
                "{} fragment(s) not in the answer, first ({}, {}) of primitive {}",
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
                "{} fragment(s) missing, first ({}, {}) of primitive {}",
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

/// The fixed-point sample point of pixel `(x, y)`.
fn centre(x: i64, y: i64) -> (i64, i64) {
    (
        x * SUBPIXEL_SCALE + HALF_PIXEL,
        y * SUBPIXEL_SCALE + HALF_PIXEL,
    )
}

/// How a pixel centre lies against a set of triangles.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Cover {
    /// No triangle's closed area holds it.
    Outside,
    /// On the boundary of the union: may be drawn once, or not.
    Boundary,
    /// In the union's interior: must be drawn exactly once.
    Inside,
}

/// Where the centre `p` lies against the set-up triangles.
pub fn cover(setups: &[TriangleSetup], p: (i64, i64)) -> Cover {
    let point = FixedPoint::from_raw(p.0, p.1).unwrap_or_default();
    let mut rays: HashMap<(i64, i64), u32> = HashMap::new();
    let mut touched = false;
    for t in setups {
        let e = t.edge_values(point);
        if e.iter().any(|&v| v < 0) {
            continue;
        }
        touched = true;
        if e.iter().all(|&v| v > 0) {
            return Cover::Inside;
        }
        let zero: Vec<usize> = (0..3).filter(|&k| e[k] == 0).collect();
        let v = t.vertices.map(|v| (v.x.raw(), v.y.raw()));
        let ends: [usize; 2] = if zero.len() == 2 {
            // At the vertex shared by the two zero edges: its two edges.
            let at = 3 - zero[0] - zero[1];
            [(at + 1) % 3, (at + 2) % 3]
        } else {
            // On edge k, which runs between the other two vertices.
            [(zero[0] + 1) % 3, (zero[0] + 2) % 3]
        };
        for end in ends {
            *rays
                .entry(direction(v[end].0 - p.0, v[end].1 - p.1))
                .or_default() += 1;
        }
    }
    if !touched {
        Cover::Outside
    } else if rays.values().all(|n| n % 2 == 0) {
        Cover::Inside
    } else {
        Cover::Boundary
    }
}

/// Whether some triangle holds the centre `p` strictly inside.
fn strictly_inside(setups: &[TriangleSetup], p: (i64, i64)) -> bool {
    let point = FixedPoint::from_raw(p.0, p.1).unwrap_or_default();
    setups
        .iter()
        .any(|t| t.edge_values(point).iter().all(|&v| v > 0))
}

/// A direction reduced to lowest terms.
fn direction(dx: i64, dy: i64) -> (i64, i64) {
    let (mut a, mut b) = (dx.abs(), dy.abs());
    while b != 0 {
        (a, b) = (b, a % b);
    }
    let g = a.max(1);
    (dx / g, dy / g)
}

/// The triangles drawing each pixel of the target.
type ByPixel = BTreeMap<(i64, i64), Vec<u32>>;

/// The set-up triangles of a case (zero-area ones left out), and the
/// fragments drawn on the target by pixel.
fn mesh_view(case: &Case, drawn: &[Fragment]) -> (Vec<TriangleSetup>, ByPixel) {
    let setups: Vec<TriangleSetup> = case
        .snapped_triangles()
        .iter()
        .enumerate()
        .filter_map(|(i, v)| TriangleSetup::new(i as u32, *v, FillRule::TopLeft))
        .collect();
    let (w, h) = (i64::from(case.width), i64::from(case.height));
    let mut at: ByPixel = BTreeMap::new();
    for f in drawn {
        if (0..w).contains(&f.x) && (0..h).contains(&f.y) {
            at.entry((f.x, f.y)).or_default().push(f.id);
        }
    }
    (setups, at)
}

/// A double draw of pixel `(x, y)` by `ids`: the problem, and as extra
/// every fragment but the one of the triangle the reference gives the
/// pixel to (the first, when the reference gives it to none of them).
fn double_draw(finding: &mut Finding, x: i64, y: i64, ids: &[u32], owner: Option<u32>) {
    let keep = owner
        .and_then(|o| ids.iter().position(|&i| i == o))
        .unwrap_or(0);
    let extra: Vec<Fragment> = ids
        .iter()
        .enumerate()
        .filter(|&(k, _)| k != keep)
        .map(|(_, &id)| Fragment { x, y, id })
        .collect();
    finding.add(
        FailureKind::DoubleDraw,
        extra.first().copied(),
        format!(
            "double draw: pixel ({x}, {y}) is drawn {} times (by triangles {ids:?})",
            ids.len()
        ),
    );
    finding.extra.extend(extra);
}

/// Rule-agnostic watertightness.
fn watertight(case: &Case, drawn: &[Fragment], finding: &mut Finding) {
    let (setups, at) = mesh_view(case, drawn);
    let by_id: HashMap<u32, &TriangleSetup> = setups.iter().map(|t| (t.id, t)).collect();
    let (w, h) = (i64::from(case.width), i64::from(case.height));
    let reference_at: HashMap<(i64, i64), u32> = finding
        .expected
        .iter()
        .map(|f| ((f.x, f.y), f.id))
        .collect();
    for y in 0..h {
        for x in 0..w {
            let p = centre(x, y);
            let ids = at.get(&(x, y)).map(Vec::as_slice).unwrap_or(&[]);
            for &id in ids {
                let touches = by_id.get(&id).is_some_and(|t| {
                    let point = FixedPoint::from_raw(p.0, p.1).unwrap_or_default();
                    t.edge_values(point).iter().all(|&v| v >= 0)
                });
                if !touches && id < case.len() as u32 {
                    let f = Fragment { x, y, id };
                    finding.add(
                        FailureKind::Extra,
                        Some(f),
                        format!(
                            "triangle {id} draws pixel ({x}, {y}), whose centre it does not touch"
                        ),
                    );
                    finding.extra.push(f);
                }
            }
            let c = cover(&setups, p);
            match (c, ids.len()) {
                (Cover::Inside, 0) => {
                    let id = reference_at.get(&(x, y)).copied().unwrap_or(0);
                    let f = Fragment { x, y, id };
                    finding.add(
                        FailureKind::Gap,
                        Some(f),
                        format!("gap: pixel ({x}, {y}) is inside the triangles and not drawn"),
                    );
                    finding.missing.push(f);
                }
                (Cover::Inside | Cover::Boundary, n) if n >= 2 => {
                    double_draw(finding, x, y, ids, reference_at.get(&(x, y)).copied());
                }
                _ => {}
            }
        }
    }
}

/// Crack-freedom: centres on shared edges and vertices inside the mesh
/// drawn exactly once, no pixel drawn twice.
fn crack_free(case: &Case, drawn: &[Fragment], finding: &mut Finding) {
    let (setups, at) = mesh_view(case, drawn);
    let (w, h) = (i64::from(case.width), i64::from(case.height));
    let reference_at: HashMap<(i64, i64), u32> = finding
        .expected
        .iter()
        .map(|f| ((f.x, f.y), f.id))
        .collect();
    for y in 0..h {
        for x in 0..w {
            let p = centre(x, y);
            let ids = at.get(&(x, y)).map(Vec::as_slice).unwrap_or(&[]);
            if ids.len() >= 2 {
                double_draw(finding, x, y, ids, reference_at.get(&(x, y)).copied());
            } else if ids.is_empty()
                && cover(&setups, p) == Cover::Inside
                && !strictly_inside(&setups, p)
            {
                let id = reference_at.get(&(x, y)).copied().unwrap_or(0);
                let f = Fragment { x, y, id };
                finding.add(
                    FailureKind::Gap,
                    Some(f),
                    format!(
                        "gap: pixel ({x}, {y})'s centre lies on a shared edge or vertex inside the mesh and is not drawn (a crack)"
                    ),
                );
                finding.missing.push(f);
            }
        }
    }
}

/// Whether a line runs along x (`|dx| >= |dy|`).
fn x_major(line: &[(f64, f64); 2]) -> bool {
    (line[1].0 - line[0].0).abs() >= (line[1].1 - line[0].1).abs()
}

/// Lines: one fragment per step along the major axis.
fn one_per_step(case: &Case, drawn: &[Fragment], finding: &mut Finding) {
    let mut seen: BTreeMap<(u32, i64), i64> = BTreeMap::new();
    let mut unique: BTreeSet<Fragment> = BTreeSet::new();
    for f in drawn {
        let Some(line) = case.lines.get(f.id as usize) else {
            continue;
        };
        if !unique.insert(*f) {
            continue;
        }
        let major = x_major(line);
        let (step, other) = if major { (f.x, f.y) } else { (f.y, f.x) };
        if let Some(&first) = seen.get(&(f.id, step)) {
            finding.add(
                FailureKind::Connectivity,
                Some(*f),
                format!(
                    "line {}: two fragments in {} {step} ({} {first} and {other}); the rule draws one per step along the major axis",
                    f.id,
                    if major { "column" } else { "row" },
                    if major { "rows" } else { "columns" },
                ),
            );
        } else {
            seen.insert((f.id, step), other);
        }
    }
}

/// Vulkan's line tolerance against the diamond-exit answer.
fn vulkan(case: &Case, drawn: &[Fragment], finding: &mut Finding) {
    let snapped = case.snapped_lines();
    for (id, line) in snapped.iter().enumerate() {
        let id = id as u32;
        let want: Vec<Fragment> = finding
            .expected
            .iter()
            .filter(|f| f.id == id)
            .copied()
            .collect();
        let want: Vec<&Fragment> = want.iter().collect();
        let got: Vec<&Fragment> = drawn.iter().filter(|f| f.id == id).collect();
        if want.len().abs_diff(got.len()) > 1 {
            finding.add(
                FailureKind::Count,
                got.first().or(want.first()).map(|f| **f),
                format!(
                    "line {id} has {} fragments; the diamond rule gives {} (at most one more or fewer)",
                    got.len(),
                    want.len()
                ),
            );
        }
        for &&f in &got {
            if !want
                .iter()
                .any(|r| (r.x - f.x).abs() <= 1 && (r.y - f.y).abs() <= 1)
            {
                finding.add(
                    FailureKind::Extra,
                    Some(f),
                    format!(
                        "line {id}: pixel ({}, {}) is more than one pixel from the diamond rule's pixels",
                        f.x, f.y
                    ),
                );
                finding.extra.push(f);
            }
        }
        let x_major =
            (line[1].x.raw() - line[0].x.raw()).abs() >= (line[1].y.raw() - line[0].y.raw()).abs();
        let mut steps = BTreeSet::new();
        for f in &got {
            if !steps.insert(if x_major { f.x } else { f.y }) {
                finding.add(
                    FailureKind::Connectivity,
                    Some(**f),
                    format!(
                        "line {id}: two fragments at {} {} (one per step along the major axis)",
                        if x_major { "column" } else { "row" },
                        if x_major { f.x } else { f.y }
                    ),
                );
                finding.extra.push(**f);
            }
        }
        for &&r in &want {
            if !got
                .iter()
                .any(|f| (r.x - f.x).abs() <= 1 && (r.y - f.y).abs() <= 1)
            {
                finding.missing.push(r);
            }
        }
    }
}

/// A number as text, `-0` written as `0`.
fn num(v: f64) -> f64 {
    v + 0.0
}

/// A snapped point as text, `(x, y)` in pixels.
fn px(v: FixedPoint) -> String {
    let (x, y) = v.to_f64();
    format!("({}, {})", num(x), num(y))
}

/// A one-line explanation of the first problem, where one can be given:
/// a fragment off the target, a double draw or a gap on a shared edge, a
/// tie on one edge, a centre off every edge (with its true distance to the
/// triangle), a line's pixel in one step of its major axis.
fn diagnose(finding: &Finding) -> Option<String> {
    let case = &finding.case;
    let pixel = finding.focus()?;
    if pixel.x < 0
        || pixel.y < 0
        || pixel.x >= i64::from(case.width)
        || pixel.y >= i64::from(case.height)
    {
        return Some(format!(
            "fragment ({}, {}) lies outside the {}x{} target: clip to the target (columns 0..{}, rows 0..{})",
            pixel.x, pixel.y, case.width, case.height, case.width, case.height
        ));
    }
    if !case.lines.is_empty() {
        return diagnose_line(finding, pixel);
    }
    if case.triangles.is_empty() {
        return None;
    }
    let snapped = case.snapped_triangles();
    let p = centre(pixel.x, pixel.y);
    let point = FixedPoint::from_raw(p.0, p.1).ok()?;
    // The triangles with the centre exactly on one of their edges.
    let mut on_edge = Vec::new();
    for (id, v) in snapped.iter().enumerate() {
        let Some(t) = TriangleSetup::new(id as u32, *v, FillRule::TopLeft) else {
            continue;
        };
        let e = t.edge_values(point);
        if e.iter().all(|&x| x >= 0) {
            if let Some(k) = (0..3).find(|&k| e[k] == 0) {
                on_edge.push((id, t, k));
            }
        }
    }
    let doubled = finding.kind() == FailureKind::DoubleDraw;
    let gap = finding.kind() == FailureKind::Gap;
    let rule = match finding.property {
        Property::Exact(rule) => rule,
        _ => FillRule::TopLeft,
    };
    match on_edge.as_slice() {
        [(a, ta, _), (b, tb, _), ..] if doubled || gap => {
            let place = shared_place(point, ta, tb, *a, *b);
            let owns = |t: &TriangleSetup| {
                TriangleSetup::new(t.id, t.vertices, rule).is_some_and(|s| s.covers(point))
            };
            let owner = if owns(ta) {
                a
            } else if owns(tb) {
                b
            } else {
                a
            };
            let why = if rule == FillRule::TopLeft {
                ", the one whose edge is a top or left edge there,".to_string()
            } else {
                String::new()
            };
            Some(format!(
                "{} at pixel ({}, {}) {place}: {}; under {} only triangle {owner}{why} does{}",
                if doubled { "double draw" } else { "gap" },
                pixel.x,
                pixel.y,
                if doubled {
                    format!("both triangles {a} and {b} own it")
                } else {
                    format!("neither triangle {a} nor {b} owns it")
                },
                rule.name(),
                if doubled {
                    ", so the fragment of the other is the extra one".to_string()
                } else {
                    String::new()
                },
            ))
        }
        _ if on_edge.iter().any(|(id, _, _)| *id == pixel.id as usize) => {
            let (id, t, k) = on_edge.iter().find(|(id, _, _)| *id == pixel.id as usize)?;
            let (from, to) = (t.vertices[(k + 1) % 3], t.vertices[(k + 2) % 3]);
            let owns =
                TriangleSetup::new(*id as u32, t.vertices, rule).is_some_and(|s| s.covers(point));
            Some(format!(
                "pixel ({}, {})'s centre lies exactly on edge {}-{} of triangle {id}: the {} rule {} it to that triangle",
                pixel.x,
                pixel.y,
                px(from),
                px(to),
                rule.name(),
                if owns { "gives" } else { "does not give" }
            ))
        }
        _ => off_edge(finding, pixel, &snapped),
    }
}

/// Where a centre lying on an edge of both triangles `a` and `b` is: on a
/// vertex they share, on an edge they share (the same two vertices), or
/// on an edge of each that they do not share.
fn shared_place(
    point: FixedPoint,
    ta: &TriangleSetup,
    tb: &TriangleSetup,
    a: usize,
    b: usize,
) -> String {
    if ta.vertices.contains(&point) && tb.vertices.contains(&point) {
        return format!("on the vertex {} both triangles share", px(point));
    }
    // The edges of a triangle through the centre, as their two ends.
    let through = |t: &TriangleSetup| -> Vec<(FixedPoint, FixedPoint)> {
        let e = t.edge_values(point);
        (0..3)
            .filter(|&k| e[k] == 0)
            .map(|k| (t.vertices[(k + 1) % 3], t.vertices[(k + 2) % 3]))
            .collect()
    };
    let (edges_a, edges_b) = (through(ta), through(tb));
    let same = |(p, q): (FixedPoint, FixedPoint), (r, s): (FixedPoint, FixedPoint)| {
        (p, q) == (r, s) || (p, q) == (s, r)
    };
    if let Some(&(from, to)) = edges_a
        .iter()
        .find(|&&ea| edges_b.iter().any(|&eb| same(ea, eb)))
    {
        return format!("on the shared edge {}-{}", px(from), px(to));
    }
    match (edges_a.first(), edges_b.first()) {
        (Some(&(p, q)), Some(&(r, s))) => format!(
            "on edge {}-{} of triangle {a} and edge {}-{} of triangle {b}",
            px(p),
            px(q),
            px(r),
            px(s)
        ),
        _ => "on an edge of each triangle".to_string(),
    }
}

/// The diagnosis of a pixel whose centre is on no edge of its triangle:
/// how far outside (the edges whose half-plane it violates, the true
/// distance to the triangle) or inside (the distance to the nearest edge).
fn off_edge(finding: &Finding, pixel: Fragment, snapped: &[[FixedPoint; 3]]) -> Option<String> {
    let id = pixel.id as usize;
    if snapped.get(id).map(|v| TriangleSetup::signed_area(*v)) == Some(0) {
        return Some(format!(
            "triangle {id} has zero area once snapped to 1/256 px: it covers no pixel, yet pixel ({}, {}) is drawn for it",
            pixel.x, pixel.y
        ));
    }
    let t = finding.case.triangles.get(id)?;
    let c = (pixel.x as f64 + 0.5, pixel.y as f64 + 0.5);
    // Signed distance from the centre to the line of edge k (from vertex
    // k to k + 1), positive on the side of the third vertex.
    let side = |k: usize| -> Option<f64> {
        let (a, b, o) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
        let cross = |p: (f64, f64)| (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
        let len = (b.0 - a.0).hypot(b.1 - a.1);
        (len > 0.0).then(|| cross(c) / len * cross(o).signum())
    };
    // Distance from the centre to the segment of edge k.
    let to_segment = |k: usize| -> f64 {
        let (a, b) = (t[k], t[(k + 1) % 3]);
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len2 = dx * dx + dy * dy;
        let s = if len2 > 0.0 {
            (((c.0 - a.0) * dx + (c.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (c.0 - a.0 - s * dx).hypot(c.1 - a.1 - s * dy)
    };
    let edge = |k: usize| {
        let (a, b) = (t[k], t[(k + 1) % 3]);
        format!("({}, {})-({}, {})", num(a.0), num(a.1), num(b.0), num(b.1))
    };
    let sides: Vec<(usize, f64)> = (0..3).filter_map(|k| side(k).map(|d| (k, d))).collect();
    let violated: Vec<usize> = sides.iter().filter(|s| s.1 < 0.0).map(|s| s.0).collect();
    let outside = !violated.is_empty();
    let distance = if outside {
        (0..3).map(to_segment).fold(f64::MAX, f64::min)
    } else {
        sides.iter().map(|s| s.1).fold(f64::MAX, f64::min)
    };
    let on_grid = t
        .iter()
        .all(|p| (p.0 * 256.0).fract() == 0.0 && (p.1 * 256.0).fract() == 0.0);
    if distance < 1.0 / 256.0 && !on_grid {
        let k = if outside {
            violated[0]
        } else {
            sides.iter().min_by(|a, b| a.1.total_cmp(&b.1))?.0
        };
        return Some(format!(
            "pixel ({}, {})'s centre is within 1/256 px of edge {} of triangle {id} as given: snap the vertices to 1/256 px (ties to even) before testing",
            pixel.x,
            pixel.y,
            edge(k)
        ));
    }
    let why = if distance < 0.01 {
        "floating point or coarse fixed point errs this close"
    } else if distance <= 2.0 {
        "the edges drawn are not the edges given (vertices moved, rounded to whole pixels?)"
    } else {
        "it is nowhere near the triangle: is the fragment's position or triangle index wrong?"
    };
    if outside {
        let beyond: Vec<String> = violated.iter().map(|&k| edge(k)).collect();
        Some(format!(
            "pixel ({}, {})'s centre is {:.5} px outside triangle {id}, beyond edge {}: no tie rule decides it, the exact edge function does; {why}",
            pixel.x,
            pixel.y,
            num(distance),
            beyond.join(" and edge ")
        ))
    } else {
        let k = sides.iter().min_by(|a, b| a.1.total_cmp(&b.1))?.0;
        Some(format!(
            "pixel ({}, {})'s centre is {:.5} px inside triangle {id}, from its nearest edge {}: no tie rule decides it, the exact edge function does; {why}",
            pixel.x,
            pixel.y,
            num(distance),
            edge(k)
        ))
    }
}

/// The diagnosis of a line's pixel: what the convention draws in that step
/// of the major axis, and why.
fn diagnose_line(finding: &Finding, pixel: Fragment) -> Option<String> {
    let id = pixel.id;
    let line = finding.case.lines.get(id as usize)?;
    let convention = match finding.property {
        Property::Line(c) => c,
        _ => return None,
    };
    let major = x_major(line);
    let step = if major { pixel.x } else { pixel.y };
    let in_step = |v: &[Fragment]| -> Vec<String> {
        let mut out: Vec<String> = v
            .iter()
            .filter(|f| f.id == id && (if major { f.x } else { f.y }) == step)
            .map(|f| format!("({}, {})", f.x, f.y))
            .collect();
        out.sort();
        out.dedup();
        out
    };
    let list = |v: Vec<String>| {
        if v.is_empty() {
            "nothing".to_string()
        } else {
            v.join(" and ")
        }
    };
    let (a, b) = if convention.whole_pixels() {
        // Pixel indices: the ideal line runs through the pixels' centres.
        let (a, b) = pixel_index::endpoints(line);
        (
            (a.0 as f64 + 0.5, a.1 as f64 + 0.5),
            (b.0 as f64 + 0.5, b.1 as f64 + 0.5),
        )
    } else {
        let s = finding.case.snapped_lines();
        let l = s.get(id as usize)?;
        (l[0].to_f64(), l[1].to_f64())
    };
    let (axis, other) = if major { ("column", "y") } else { ("row", "x") };
    let ideal = {
        let (d_major, d_minor, a_major, a_minor) = if major {
            (b.0 - a.0, b.1 - a.1, a.0, a.1)
        } else {
            (b.1 - a.1, b.0 - a.0, a.1, a.0)
        };
        if d_major == 0.0 {
            a_minor
        } else {
            a_minor + (step as f64 + 0.5 - a_major) * d_minor / d_major
        }
    };
    let rule = match convention {
        LineConvention::Midpoint => {
            "the pixel whose centre is nearest the ideal line, a tie going to the start's side"
        }
        LineConvention::PixelIndex => {
            "integer Bresenham: the pixel nearest the ideal line through the endpoint pixels' centres, a tie going toward the start"
        }
        LineConvention::PixelIndexTowardEnd => {
            "integer Bresenham: the pixel nearest the ideal line through the endpoint pixels' centres, a tie going toward the end"
        }
        LineConvention::PixelIndexOpenCv => {
            "OpenCV's LINE_8: clipped to the target, walked from the endpoint with the smaller x, the pixel nearest the ideal line through the endpoint pixels' centres, a tie toward that endpoint"
        }
        LineConvention::PixelIndexOpenCv4 => {
            "OpenCV's LINE_4: clipped to the target, a 4-connected staircase from the endpoint with the smaller x"
        }
        LineConvention::PixelIndexLeftToRight => {
            "the course's midpoint walk: along the major axis increasing, the pixel nearest the ideal line through the endpoint pixels' centres, a tie staying on the current row or column"
        }
        LineConvention::Diamond | LineConvention::Vulkan => {
            "the pixels whose diamond the segment exits"
        }
    };
    // Halfway between two pixel centres: the ideal line on a pixel
    // boundary.
    let tie = (ideal - ideal.round()).abs() < 1e-9;
    let tie_note = if tie {
        format!(
            "; this step is a tie (the ideal line passes exactly halfway between two pixels, at the boundary {other} = {}), which the {} rule breaks {}",
            num(ideal.round()),
            convention.name(),
            match convention {
                LineConvention::PixelIndex | LineConvention::Midpoint => "toward the start",
                LineConvention::PixelIndexTowardEnd => "toward the end",
                LineConvention::PixelIndexLeftToRight => "toward the endpoint with the smaller major coordinate",
                LineConvention::PixelIndexOpenCv | LineConvention::PixelIndexOpenCv4 => "toward the endpoint with the smaller x",
                LineConvention::Diamond | LineConvention::Vulkan => "by the diamonds' half-open sides",
            }
        )
    } else {
        String::new()
    };
    Some(format!(
        "line {id} from ({}, {}) to ({}, {}) is {}-major: in {axis} {step} the ideal line is at {other} = {:.4}; the {} rule ({rule}) draws {}, the subject drew {}{tie_note}",
        num(a.0),
        num(a.1),
        num(b.0),
        num(b.1),
        if major { "x" } else { "y" },
        num(ideal),
        convention.name(),
        list(in_step(&finding.expected)),
        list(in_step(&finding.drawn)),
    ))
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
            let _ = write!(out, "{y:>4}  ");
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
        let (id, words) = (self.property.id(), self.property.to_string());
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
                .map(|f| format!("({},{}) t{}", f.x, f.y, f.id))
                .collect::<Vec<_>>()
                .join(" ")
        };
        let _ = writeln!(out, "# missing: {}", list(&self.missing));
        let _ = writeln!(out, "# extra: {}", list(&self.extra));
        if let Some(d) = &self.diagnosis {
            let _ = writeln!(out, "# diagnosis: {d}");
        }
        let body = self.case.to_text();
        out.push_str(body.split_once('\n').map_or("", |(_, rest)| rest));
        out
    }
}

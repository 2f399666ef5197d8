//! The properties, and the judgement of one drawn case.
//!
//! Watertightness is judged without a tie rule: at a pixel centre `p`,
//! each triangle whose closed area contains `p` on its boundary covers a
//! wedge around `p` between two rays (along its edge, or its two edges at
//! a vertex). The union of the triangles covers a whole neighbourhood of
//! `p` exactly when some triangle holds `p` strictly inside, or every ray
//! direction occurs an even number of times (each wedge's side is matched
//! by a neighbour's). Those centres must be drawn exactly once; centres on
//! the union's boundary at most once; a triangle may only draw centres in
//! its closed area.

use super::case::Case;
use super::{reference, Fragment};
use crate::raster::edge::{FillRule, TriangleSetup};
use crate::raster::fixed::{FixedPoint, HALF_PIXEL, SUBPIXEL_SCALE};
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::fmt::{self, Write};

/// How lines are judged.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum LineConvention {
    /// Exactly the midpoint (Bresenham) rule of the `bresenham` back-end.
    Midpoint,
    /// Exactly the diamond-exit rule of the `diamond` back-end.
    Diamond,
    /// Vulkan's tolerance around the diamond-exit answer: every fragment
    /// within one pixel of it, as many fragments give or take one, one
    /// fragment per step along the major axis.
    Vulkan,
}

/// What a check requires of every case.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Property {
    /// Triangles: exactly the rules' fragments under this fill rule.
    Exact(FillRule),
    /// Triangles: no gaps, no double draws, nothing outside, whatever
    /// consistent tie rule is used.
    Watertight,
    /// Lines under a convention.
    Line(LineConvention),
}

impl fmt::Display for Property {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Property::Exact(rule) => write!(f, "exact under the {} rule", rule.name()),
            Property::Watertight => f.write_str("watertight"),
            Property::Line(LineConvention::Midpoint) => f.write_str("lines, midpoint rule"),
            Property::Line(LineConvention::Diamond) => f.write_str("lines, diamond exit rule"),
            Property::Line(LineConvention::Vulkan) => {
                f.write_str("lines, Vulkan's tolerance of the diamond exit rule")
            }
        }
    }
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
    /// What an exact rasterizer draws (under watertight: the top-left
    /// answer, one of those that pass).
    pub expected: Vec<Fragment>,
    /// Pixels that should have been drawn and were not.
    pub missing: Vec<Fragment>,
    /// Fragments that should not have been drawn (outside the target,
    /// listed twice, double draws, wrong pixels).
    pub extra: Vec<Fragment>,
    /// One sentence per problem found.
    pub problems: Vec<String>,
    /// A one-line explanation, where one can be given.
    pub diagnosis: Option<String>,
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
        diagnosis: None,
    };
    always(case, drawn, &mut finding);
    match property {
        Property::Exact(_) | Property::Line(LineConvention::Midpoint | LineConvention::Diamond) => {
            exact(drawn, &mut finding)
        }
        Property::Watertight => watertight(case, drawn, &mut finding),
        Property::Line(LineConvention::Vulkan) => vulkan(case, drawn, &mut finding),
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
            finding.problems.push(format!(
                "fragment ({}, {}) of primitive {} is outside the {}x{} target",
                f.x, f.y, f.id, case.width, case.height
            ));
            finding.extra.push(f);
        } else if f.id >= count {
            finding.problems.push(format!(
                "fragment ({}, {}) names primitive {}, but the input has {count}",
                f.x, f.y, f.id
            ));
            finding.extra.push(f);
        } else if !seen.insert(f) {
            finding.problems.push(format!(
                "pixel ({}, {}) is listed twice for primitive {}",
                f.x, f.y, f.id
            ));
            finding.extra.push(f);
        }
    }
}

/// The fragment set must equal the reference's.
fn exact(drawn: &[Fragment], finding: &mut Finding) {
    let want: BTreeSet<Fragment> = finding.expected.iter().copied().collect();
    let got: BTreeSet<Fragment> = drawn.iter().copied().collect();
    let missing: Vec<Fragment> = want.difference(&got).copied().collect();
    let extra: Vec<Fragment> = got.difference(&want).copied().collect();
    if !missing.is_empty() {
        finding.problems.push(format!(
            "{} fragment(s) missing, first ({}, {}) of primitive {}",
            missing.len(),
            missing[0].x,
            missing[0].y,
            missing[0].id
        ));
    }
    let already: BTreeSet<Fragment> = finding.extra.iter().copied().collect();
    let extra: Vec<Fragment> = extra.into_iter().filter(|f| !already.contains(f)).collect();
    if !extra.is_empty() {
        finding.problems.push(format!(
            "{} fragment(s) not in the answer, first ({}, {}) of primitive {}",
            extra.len(),
            extra[0].x,
            extra[0].y,
            extra[0].id
        ));
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

/// A direction reduced to lowest terms.
fn direction(dx: i64, dy: i64) -> (i64, i64) {
    let (mut a, mut b) = (dx.abs(), dy.abs());
    while b != 0 {
        (a, b) = (b, a % b);
    }
    let g = a.max(1);
    (dx / g, dy / g)
}

/// Rule-agnostic watertightness.
fn watertight(case: &Case, drawn: &[Fragment], finding: &mut Finding) {
    let snapped = case.snapped_triangles();
    let setups: Vec<TriangleSetup> = snapped
        .iter()
        .enumerate()
        .filter_map(|(i, v)| TriangleSetup::new(i as u32, *v, FillRule::TopLeft))
        .collect();
    let by_id: HashMap<u32, &TriangleSetup> = setups.iter().map(|t| (t.id, t)).collect();
    let (w, h) = (i64::from(case.width), i64::from(case.height));
    let mut at: BTreeMap<(i64, i64), Vec<u32>> = BTreeMap::new();
    for f in drawn {
        if (0..w).contains(&f.x) && (0..h).contains(&f.y) {
            at.entry((f.x, f.y)).or_default().push(f.id);
        }
    }
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
                    finding.problems.push(format!(
                        "triangle {id} draws pixel ({x}, {y}), whose centre it does not touch"
                    ));
                    finding.extra.push(Fragment { x, y, id });
                }
            }
            let c = cover(&setups, p);
            match (c, ids.len()) {
                (Cover::Inside, 0) => {
                    finding.problems.push(format!(
                        "gap: pixel ({x}, {y}) is inside the triangles and not drawn"
                    ));
                    let id = reference_at.get(&(x, y)).copied().unwrap_or(0);
                    finding.missing.push(Fragment { x, y, id });
                }
                (Cover::Inside | Cover::Boundary, n) if n >= 2 => {
                    finding.problems.push(format!(
                        "double draw: pixel ({x}, {y}) is drawn {n} times (by triangles {ids:?})"
                    ));
                    for &id in &ids[1..] {
                        finding.extra.push(Fragment { x, y, id });
                    }
                }
                _ => {}
            }
        }
    }
}

/// Vulkan's line tolerance against the diamond-exit answer.
fn vulkan(case: &Case, drawn: &[Fragment], finding: &mut Finding) {
    let snapped = case.snapped_lines();
    for (id, line) in snapped.iter().enumerate() {
        let id = id as u32;
        let want: Vec<&Fragment> = finding.expected.iter().filter(|f| f.id == id).collect();
        let got: Vec<&Fragment> = drawn.iter().filter(|f| f.id == id).collect();
        if want.len().abs_diff(got.len()) > 1 {
            finding.problems.push(format!(
                "line {id} has {} fragments; the diamond rule gives {} (at most one more or fewer)",
                got.len(),
                want.len()
            ));
        }
        for &&f in &got {
            if !want
                .iter()
                .any(|r| (r.x - f.x).abs() <= 1 && (r.y - f.y).abs() <= 1)
            {
                finding.problems.push(format!(
                    "line {id}: pixel ({}, {}) is more than one pixel from the diamond rule's pixels",
                    f.x, f.y
                ));
                finding.extra.push(f);
            }
        }
        let x_major =
            (line[1].x.raw() - line[0].x.raw()).abs() >= (line[1].y.raw() - line[0].y.raw()).abs();
        let mut steps = BTreeSet::new();
        for f in &got {
            if !steps.insert(if x_major { f.x } else { f.y }) {
                finding.problems.push(format!(
                    "line {id}: two fragments at {} {} (one per step along the major axis)",
                    if x_major { "column" } else { "row" },
                    if x_major { f.x } else { f.y }
                ));
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

/// A one-line explanation of the first problem pixel, where one can be
/// given: a double draw or a gap on a shared edge, a tie on one edge, a
/// fragment off the target.
fn diagnose(finding: &Finding) -> Option<String> {
    let case = &finding.case;
    if let Some(f) = finding.extra.iter().find(|f| {
        f.x < 0 || f.y < 0 || f.x >= i64::from(case.width) || f.y >= i64::from(case.height)
    }) {
        return Some(format!(
            "fragment ({}, {}) lies outside the {}x{} target: clip to the target (columns 0..{}, rows 0..{})",
            f.x, f.y, case.width, case.height, case.width, case.height
        ));
    }
    if case.triangles.is_empty() {
        return None;
    }
    let snapped = case.snapped_triangles();
    let pixel = finding.extra.first().or(finding.missing.first())?;
    let p = centre(pixel.x, pixel.y);
    let point = FixedPoint::from_raw(p.0, p.1).ok()?;
    let px = |v: FixedPoint| {
        let (x, y) = v.to_f64();
        format!("({x}, {y})")
    };
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
    let doubled = finding
        .extra
        .iter()
        .filter(|f| (f.x, f.y) == (pixel.x, pixel.y))
        .count()
        > 0
        && finding
            .drawn
            .iter()
            .filter(|f| (f.x, f.y) == (pixel.x, pixel.y))
            .count()
            >= 2;
    let missing = finding
        .missing
        .iter()
        .any(|f| (f.x, f.y) == (pixel.x, pixel.y));
    match on_edge.as_slice() {
        [(a, ta, ka), (b, tb, _), ..] if doubled || missing => {
            let (from, to) = (ta.vertices[(ka + 1) % 3], ta.vertices[(ka + 2) % 3]);
            let owner = if ta.covers(point) {
                a
            } else if tb.covers(point) {
                b
            } else {
                a
            };
            Some(format!(
                "{} at pixel ({}, {}) on the shared edge {}-{}: {}; under top-left only triangle {owner}, the one whose edge is a top or left edge there, does",
                if doubled { "double draw" } else { "gap" },
                pixel.x,
                pixel.y,
                px(from),
                px(to),
                if doubled {
                    format!("both triangles {a} and {b} own it")
                } else {
                    format!("neither triangle {a} nor {b} owns it")
                },
            ))
        }
        [(id, t, k), ..] => {
            let (from, to) = (t.vertices[(k + 1) % 3], t.vertices[(k + 2) % 3]);
            let rule = match finding.property {
                Property::Exact(rule) => rule,
                _ => FillRule::TopLeft,
            };
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
        [] => {
            let centre_px = (pixel.x as f64 + 0.5, pixel.y as f64 + 0.5);
            // Signed distance from the centre to the line a-b, positive on
            // the side of the triangle's third vertex.
            let distance = |t: &[(f64, f64); 3], k: usize| {
                let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                let cross = |p: (f64, f64)| (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
                let len = (b.0 - a.0).hypot(b.1 - a.1);
                (len > 0.0).then(|| cross(centre_px) / len * cross(c).signum())
            };
            let id = pixel.id as usize;
            let snapped_area = snapped.get(id).map(|v| TriangleSetup::signed_area(*v));
            if snapped_area == Some(0) {
                return Some(format!(
                    "triangle {id} has zero area once snapped to 1/256 px: it covers no pixel, yet pixel ({}, {}) is drawn for it",
                    pixel.x, pixel.y
                ));
            }
            let t = case.triangles.get(id)?;
            let (k, d) = (0..3)
                .filter_map(|k| distance(t, k).map(|d| (k, d)))
                .min_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))?;
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let on_grid = t
                .iter()
                .all(|p| (p.0 * 256.0).fract() == 0.0 && (p.1 * 256.0).fract() == 0.0);
            if d.abs() < 1.0 / 256.0 && !on_grid {
                Some(format!(
                    "pixel ({}, {})'s centre is within 1/256 px of edge ({}, {})-({}, {}) of triangle {id} as given: snap the vertices to 1/256 px (ties to even) before testing",
                    pixel.x, pixel.y, a.0, a.1, b.0, b.1
                ))
            } else {
                let why = if d.abs() < 0.01 {
                    "floating point or coarse fixed point errs this close"
                } else {
                    "the edges drawn are not the edges given (vertices moved, rounded to whole pixels?)"
                };
                Some(format!(
                    "pixel ({}, {})'s centre is {:.5} px {} edge ({}, {})-({}, {}) of triangle {id}, its nearest edge: no tie rule decides it, the exact edge function does; {why}",
                    pixel.x,
                    pixel.y,
                    d.abs(),
                    if d > 0.0 { "inside" } else { "outside" },
                    a.0, a.1, b.0, b.1
                ))
            }
        }
    }
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
        let _ = writeln!(out, "# property: {}", self.property);
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

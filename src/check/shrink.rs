//! Shrinking a failing case to a small counterexample.
//!
//! Greedy, as property-testing shrinkers are: try a smaller or simpler
//! variant of the case, keep it if it still fails **the same way** (the
//! same property and [`FailureKind`]: a double draw stays a double draw,
//! never turns into a gap), start again from it;
//! stop when no variant fails or the budget of subject runs is spent. The
//! variants, in order:
//!
//! 1. drop half or a quarter of the primitives, then one primitive (for
//!    polygons then a hole, then a vertex of a ring of more than 3);
//! 2. cut the target to the failing pixel alone (moving the input by
//!    whole pixels), or by half its width or height, or one pixel, and move
//!    the whole input toward the origin by whole pixels;
//! 3. move a point toward the pixel grid (to a whole, half or quarter
//!    pixel);
//! 4. move a point halfway toward the next point of its primitive.
//!
//! Points are moved wherever they occur, so triangles that share a vertex
//! keep sharing it. Under the watertight and crack-free properties a
//! variant is used only if the reference answer is still watertight on it
//! (no fold-over made two triangles overlap), so the counterexample is
//! never the input's fault. The shrunk finding records the first problem
//! of the case as generated ([`Finding::original_problem`]).

use super::case::{Case, Point};
use super::judge::{judge, FailureKind, Finding, Property};
use super::{reference, Subject, SubjectError};
use crate::raster::fixed::GUARD_BAND;

/// Shrinks the case of `first`, a failure of `subject` already judged,
/// within `runs` more runs of the subject; returns what is wrong with the
/// smallest case found that fails the same way and that `keep` accepts
/// (the cause found still explains it). `progress` is told how many runs
/// have been spent.
pub fn shrink(
    first: Finding,
    subject: &mut dyn Subject,
    runs: u32,
    keep: &dyn Fn(&Finding) -> bool,
    progress: &mut dyn FnMut(u32),
) -> Finding {
    let property = first.property;
    let kind: FailureKind = first.kind();
    let original = first.problems.first().cloned();
    let mut budget = runs;
    let mut fails = |c: &Case, budget: &mut u32| -> Option<Finding> {
        if *budget == 0 || !valid(property, c) {
            return None;
        }
        if matches!(property, Property::Line(c) if c.whole_pixels())
            && c.points().any(|p| p.0.fract() != 0.0 || p.1.fract() != 0.0)
        {
            // Pixel indices are whole numbers.
            return None;
        }
        *budget -= 1;
        progress(runs - *budget);
        let drawn = subject.draw(c).ok()?;
        let mut f = judge(property, c, &drawn)?;
        (f.lead_with(kind) && keep(&f)).then_some(f)
    };
    let mut best = first;
    'improve: while budget > 0 {
        let focus = best
            .extra
            .iter()
            .chain(&best.missing)
            .next()
            .map(|f| (f.x, f.y));
        for candidate in variants(&best.case, focus) {
            if let Some(f) = fails(&candidate, &mut budget) {
                best = f;
                continue 'improve;
            }
            if budget == 0 {
                break;
            }
        }
        break;
    }
    best.original_problem = original;
    best
}

/// Shrinks a case on which the subject breaks (fails to run, or prints
/// malformed output) to a smaller one on which it still breaks the same
/// way.
pub fn shrink_broken(case: &Case, subject: &mut dyn Subject, runs: u32) -> Case {
    let Err(first) = subject.draw(case) else {
        return case.clone();
    };
    let same = |e: &SubjectError| std::mem::discriminant(e) == std::mem::discriminant(&first);
    let mut best = case.clone();
    let mut budget = runs;
    'improve: while budget > 0 {
        for candidate in variants(&best, None) {
            if budget == 0 {
                break 'improve;
            }
            budget -= 1;
            if subject.draw(&candidate).as_ref().err().is_some_and(same) {
                best = candidate;
                continue 'improve;
            }
        }
        break;
    }
    best
}

/// Whether a variant is a fair input for the property.
fn valid(property: Property, case: &Case) -> bool {
    !property.needs_mesh()
        || judge(
            Property::Watertight,
            case,
            &reference(Property::Watertight, case),
        )
        .is_none()
}

/// The variants of a case, simplest first; `focus` is a pixel where the
/// case fails, which the target may be cut down to.
fn variants(case: &Case, focus: Option<(i64, i64)>) -> Vec<Case> {
    let mut out = Vec::new();
    // Halves and quarters first: a long input loses most of itself in a
    // few runs.
    for parts in [2, 4] {
        for k in 0..parts {
            let keep = |n: usize, i: usize| n < 2 || i * parts / n != k;
            let mut c = case.clone();
            let n = c.triangles.len();
            c.triangles = c
                .triangles
                .into_iter()
                .enumerate()
                .filter(|&(i, _)| keep(n, i))
                .map(|(_, t)| t)
                .collect();
            let n = c.lines.len();
            c.lines = c
                .lines
                .into_iter()
                .enumerate()
                .filter(|&(i, _)| keep(n, i))
                .map(|(_, l)| l)
                .collect();
            let n = c.polygons.len();
            c.polygons = c
                .polygons
                .into_iter()
                .enumerate()
                .filter(|&(i, _)| keep(n, i))
                .map(|(_, p)| p)
                .collect();
            if c.len() < case.len() && !c.is_empty() {
                out.push(c);
            }
        }
    }
    for i in 0..case.triangles.len() {
        let mut c = case.clone();
        c.triangles.remove(i);
        out.push(c);
    }
    for i in 0..case.lines.len() {
        let mut c = case.clone();
        c.lines.remove(i);
        out.push(c);
    }
    for i in 0..case.polygons.len() {
        let mut c = case.clone();
        c.polygons.remove(i);
        out.push(c);
    }
    out.extend(super::polygons::variants(case));
    if let Some((x, y)) = focus.filter(|&(x, y)| {
        (0..i64::from(case.width)).contains(&x) && (0..i64::from(case.height)).contains(&y)
    }) {
        // The failing pixel alone, moved to (0, 0) by whole pixels.
        if case.width > 1 || case.height > 1 {
            let moved = map_points(case, |p| (p.0 - x as f64, p.1 - y as f64));
            out.push(Case {
                width: 1,
                height: 1,
                ..moved
            });
        }
    }
    for (w, h) in [
        (case.width / 2, case.height),
        (case.width, case.height / 2),
        (case.width - 1, case.height),
        (case.width, case.height - 1),
    ] {
        if w >= 1 && h >= 1 {
            out.push(Case {
                width: w,
                height: h,
                ..case.clone()
            });
        }
    }
    let (min_x, min_y) = case
        .points()
        .fold((f64::MAX, f64::MAX), |m, p| (m.0.min(p.0), m.1.min(p.1)));
    for (dx, dy) in [
        (min_x.floor(), 0.0),
        (0.0, min_y.floor()),
        (1.0, 0.0),
        (0.0, 1.0),
    ] {
        if (dx > 0.0 || dy > 0.0) && dx.is_finite() && dy.is_finite() {
            out.push(map_points(case, |p| (p.0 - dx, p.1 - dy)));
        }
    }
    let mut distinct: Vec<Point> = case.points().collect();
    distinct.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    distinct.dedup();
    for &p in &distinct {
        for step in [1.0, 0.5, 0.25] {
            let q = ((p.0 / step).round() * step, (p.1 / step).round() * step);
            if q != p {
                out.push(map_points(case, |r| if r == p { q } else { r }));
            }
        }
    }
    let primitives: Vec<Vec<Point>> = case
        .triangles
        .iter()
        .map(|t| t.to_vec())
        .chain(case.lines.iter().map(|l| l.to_vec()))
        .chain(case.polygons.iter().flatten().cloned())
        .collect();
    for prim in primitives {
        for k in 0..prim.len() {
            let (p, next) = (prim[k], prim[(k + 1) % prim.len()]);
            let q = (
                ((p.0 + next.0) / 2.0 * 256.0).round() / 256.0,
                ((p.1 + next.1) / 2.0 * 256.0).round() / 256.0,
            );
            if q != p {
                out.push(map_points(case, |r| if r == p { q } else { r }));
            }
        }
    }
    let limit = (GUARD_BAND - 1) as f64;
    out.retain(|c| !c.is_empty() && c.points().all(|p| p.0.abs() < limit && p.1.abs() < limit));
    out
}

fn map_points(case: &Case, f: impl Fn(Point) -> Point) -> Case {
    case.map_points(f)
}

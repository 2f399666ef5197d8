//! Whether a cause explains what a subject drew: the reference draws the
//! case under the cause's changes, the fragments the cause strips (off
//! the target, listed twice) are set aside, and every difference left
//! must be none, or meet the cause's condition (a short bounding box,
//! within a hair of an edge, ...). Where it holds, what the cause showed
//! is put in words: the evidence of a diagnosis.

use super::{lines, polygons, triangles, Cause, Role, Winding};
use super::{FAR_OFF_TARGET, NEAR_AN_EDGE};
use crate::check::case::Case;
use crate::check::property::{LineConvention, Property};
use crate::check::Fragment;
use crate::raster::edge::FillRule;
use std::collections::{BTreeMap, BTreeSet};

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
pub(super) fn explains(
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
    let has_model = causes.iter().any(|c| c.role() == Role::Model);
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
        Property::Line(_) | Property::Polygon(_) => vec![None],
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
        } else if let Property::Polygon(rule) = property {
            let mut model = polygons::Model::default();
            for c in causes.iter().filter(|c| c.role() == Role::Model) {
                if !model.add(c) {
                    return None;
                }
            }
            vec![model.fragments(case, rule)]
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
                // With a model, a case the model explains alone needs no
                // condition (the inclusive rule, evaluated in floating
                // point, draws most cases as the inclusive rule does).
                Some(_) if has_model && extra.is_empty() && missing.is_empty() => true,
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
        // A condition beside a model that left no difference says nothing.
        if c.role() == Role::Condition && differing == 0 {
            continue;
        }
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

/// What the changes among `causes` draw on `case` (the reference's answer
/// with them), or `None` when they hold no change or conflict.
pub(crate) fn predict(causes: &[Cause], property: Property, case: &Case) -> Option<Vec<Fragment>> {
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
        Property::Polygon(rule) => {
            let mut model = polygons::Model::default();
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

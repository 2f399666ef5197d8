//! Lines: one fragment per step of the major axis, and Vulkan's
//! tolerance around the diamond-exit answer.

use super::{FailureKind, Finding};
use crate::check::case::Case;
use crate::check::Fragment;
use std::collections::{BTreeMap, BTreeSet};

/// Whether a line runs along x (`|dx| >= |dy|`).
pub(super) fn x_major(line: &[(f64, f64); 2]) -> bool {
    (line[1].0 - line[0].0).abs() >= (line[1].1 - line[0].1).abs()
}

/// Lines: one fragment per step along the major axis.
pub(super) fn one_per_step(case: &Case, drawn: &[Fragment], finding: &mut Finding) {
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
pub(super) fn vulkan(case: &Case, drawn: &[Fragment], finding: &mut Finding) {
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

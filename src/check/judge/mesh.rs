//! Watertight and crack-free, judged without a tie rule (the module docs
//! of [`judge`](super) say how).

use super::{centre, FailureKind, Finding};
use crate::check::case::Case;
use crate::check::Fragment;
use crate::raster::edge::{FillRule, TriangleSetup};
use crate::raster::fixed::FixedPoint;
use std::collections::{BTreeMap, HashMap};

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
        .map(|(_, &id)| Fragment::at(x, y, id))
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
pub(super) fn watertight(case: &Case, drawn: &[Fragment], finding: &mut Finding) {
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
                    let f = Fragment::at(x, y, id);
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
                    let f = Fragment::at(x, y, id);
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
pub(super) fn crack_free(case: &Case, drawn: &[Fragment], finding: &mut Finding) {
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
                let f = Fragment::at(x, y, id);
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

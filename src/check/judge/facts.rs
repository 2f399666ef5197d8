//! The facts of a failure's first problem, in one line: what is said
//! when no cause of the catalogue explains it (a fragment off the
//! target, a double draw or a gap on a shared edge, a tie on one edge, a
//! centre off every edge with its distance, a line's pixel in one step).

use super::lines::x_major;
use super::{centre, num, px, FailureKind, Finding, LineConvention, Property};
use crate::check::pixel_index;
use crate::check::snapping::Snapping;
use crate::check::Fragment;
use crate::raster::edge::{FillRule, TriangleSetup};
use crate::raster::fixed::FixedPoint;

/// A one-line explanation of the first problem, where one can be given:
/// a fragment off the target, a double draw or a gap on a shared edge, a
/// tie on one edge, a centre off every edge (with its true distance to the
/// triangle), a line's pixel in one step of its major axis.
pub(super) fn diagnose(finding: &Finding) -> Option<String> {
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
    // A multisampled case's problems name their samples themselves; the
    // facts below are about pixel centres.
    if case.triangles.is_empty() || case.samples.is_some() {
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
        let snapped = match finding.case.snapping {
            Snapping::AsGiven => "zero area".to_string(),
            s => format!("zero area once snapped to {s} px"),
        };
        return Some(format!(
            "triangle {id} has {snapped}: it covers no pixel, yet pixel ({}, {}) is drawn for it",
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
    let snapping = finding.case.snapping;
    let on_grid = t.iter().all(|&p| snapping.apply(p) == p);
    if distance < snapping.step() && !on_grid {
        let k = if outside {
            violated[0]
        } else {
            sides.iter().min_by(|a, b| a.1.total_cmp(&b.1))?.0
        };
        return Some(format!(
            "pixel ({}, {})'s centre is within {snapping} px of edge {} of triangle {id} as given: snap the vertices to {snapping} px (ties to even) before testing",
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
        LineConvention::DiamondNudged => {
            "the pixels whose diamond the segment exits, both ends moved by (e, e^2) with y up"
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
                LineConvention::DiamondNudged => "by moving both ends by (e, e^2), y up",
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

//! The line clipping traces: Cohen-Sutherland's outcodes pass by pass and
//! Liang-Barsky's boundaries one by one, then the walk of what they keep,
//! restarted at the entry column, beside the naive walk of the rounded
//! clipped segment.

use super::line::{frame_axes, frame_note, LineEnds};
use super::AREA_UNIT;
use crate::error::Result;
use crate::raster::edge::PixelRect;
use crate::raster::fixed::{FixedPoint, SUBPIXEL_SCALE};
use crate::raster::fragment::FragmentList;
use crate::raster::line::bresenham::Bresenham;
use crate::raster::line::clip::cohen_sutherland::{self, Decision};
use crate::raster::line::clip::liang_barsky::{self, BOUNDARIES};
use crate::raster::line::clip::{
    draw_clipped, walk_rect, ClipRestart, ClipWindow, ClipWork, Clipped, Clipper, ExactPoint, Param,
};
use crate::raster::line::{LineOptions, LineRasterizer, LineSetup, LineWalk, OctantFrame};
use crate::teaching::trace_table::{Column, Trace, TraceRow};

fn point_text(p: ExactPoint) -> String {
    let (x, y) = p.to_pixels();
    format!("({x:.3}, {y:.3})")
}

fn param_text(t: Param) -> String {
    format!("{}/{} = {:.4}", t.num, t.den, t.to_f64())
}

fn px(units: i64) -> String {
    format!("{}", units as f64 / SUBPIXEL_SCALE as f64)
}

/// Clipping a line to a `width` x `height` viewport by `clipper`, step
/// by step, then `backend`'s walk of the part kept: the entry and exit
/// columns in the segment's own frame, the row (and, for the midpoint
/// walk, the decision variable) it restarts with, and the pixels the
/// naive walk of the rounded clipped segment would move.
pub fn trace_clip(
    clipper: Clipper,
    backend: &dyn LineRasterizer,
    ends: &LineEnds,
    width: u32,
    height: u32,
) -> Result<Trace> {
    let viewport = PixelRect::of_target(width, height);
    let window = ClipWindow::around(viewport);
    let line = LineSetup {
        id: 0,
        from: ends.from,
        to: ends.to,
    };
    let mut out = Trace::saying(format!(
        "{clipper} clipping {} to the {width} x {height} viewport",
        ends.describe()
    ));
    out.header.push(format!(
        "window: x in [{}, {}], y in [{}, {}] px (y down): the viewport's edges moved out by {} px, \
         as a line that far outside can still choose a pixel of the edge",
        px(window.x0),
        px(window.x1),
        px(window.y0),
        px(window.y1),
        ClipWindow::MARGIN
    ));
    let mut work = ClipWork::default();
    let kept = match clipper {
        Clipper::CohenSutherland => cohen_sutherland_rows(&line, window, &mut work, &mut out),
        Clipper::LiangBarsky => liang_barsky_rows(&line, window, &mut work, &mut out),
    };
    out.footer.push(match clipper {
        Clipper::CohenSutherland => format!(
            "work: {} outcodes, {} intersections computed",
            work.outcodes, work.intersections
        ),
        Clipper::LiangBarsky => format!(
            "work: {} boundary tests, {} ratios q/p computed, the points computed once from t0 and t1",
            work.boundary_tests, work.intersections
        ),
    });
    let Some(kept) = kept else {
        out.footer
            .push("rejected: no part of the segment is inside, nothing is walked".to_string());
        return Ok(out);
    };
    let [entry, exit] = kept.points(&line);
    out.footer.push(format!(
        "kept: t in [{}, {}], from {} to {}",
        param_text(kept.t0),
        param_text(kept.t1),
        point_text(entry),
        point_text(exit)
    ));
    walk_lines(backend, &line, &kept, viewport, &mut out);
    Ok(out)
}

fn cohen_sutherland_rows(
    line: &LineSetup,
    window: ClipWindow,
    work: &mut ClipWork,
    out: &mut Trace,
) -> Option<Clipped> {
    out.header
        .push("outcodes TBRL: top (y above the top edge), bottom, right, left".to_string());
    out.columns = vec![
        Column::right("pass", 4, 0),
        Column::right("P0 TBRL", 7, 2),
        Column::right("P1 TBRL", 7, 2),
        Column::left("decision", 0, 2),
    ];
    let mut rows = Vec::new();
    let kept = cohen_sutherland::clip(line.from, line.to, window, work, |step| rows.push(step));
    for (n, step) in rows.into_iter().enumerate() {
        let decision = match step.decision {
            Decision::Accept => {
                "accept: both codes 0000, the segment between them is inside".into()
            }
            Decision::Reject => format!(
                "reject: {} & {} = {:04b}, both beyond one edge",
                step.codes[0],
                step.codes[1],
                step.codes[0].0 & step.codes[1].0
            ),
            Decision::Move { end, edge, t, code } => format!(
                "P{end} is outside: move it to the {} edge, t = {}, P{end} = {}, code {code}",
                edge.name(),
                param_text(t),
                point_text(t.point(line.from, line.to))
            ),
        };
        out.rows.push(TraceRow::new(vec![
            (n + 1).to_string(),
            step.codes[0].to_string(),
            step.codes[1].to_string(),
            decision,
        ]));
    }
    kept
}

fn liang_barsky_rows(
    line: &LineSetup,
    window: ClipWindow,
    work: &mut ClipWork,
    out: &mut Trace,
) -> Option<Clipped> {
    out.header.push(
        "P(t) = P0 + t (P1 - P0); inside when p_k t <= q_k for k = 1..4; p < 0 enters (t0 = max), p > 0 leaves (t1 = min)"
            .to_string(),
    );
    out.columns = vec![
        Column::right("k", 1, 0),
        Column::left("edge", 6, 2),
        Column::right("p", 12, 1),
        Column::right("q", 12, 1),
        Column::right("r = q/p", 9, 1),
        Column::right("t0", 7, 1),
        Column::right("t1", 7, 1),
        Column::left("verdict", 0, 2),
    ];
    let mut rows = Vec::new();
    let kept = liang_barsky::clip(line.from, line.to, window, work, |step| rows.push(step));
    for step in rows {
        let verdict = match (step.r, step.p < 0) {
            (None, _) if step.rejects => "parallel and outside: reject",
            (None, _) => "parallel and inside: no change",
            _ if step.rejects => "t0 > t1: reject",
            (Some(_), true) => "p < 0, enters: t0 = max(t0, r)",
            (Some(_), false) => "p > 0, leaves: t1 = min(t1, r)",
        };
        out.rows.push(TraceRow::new(vec![
            step.k.to_string(),
            BOUNDARIES[step.k - 1].to_string(),
            px(step.p),
            px(step.q),
            step.r
                .map_or("-".to_string(), |r| format!("{:.4}", r.to_f64())),
            format!("{:.4}", step.t0.to_f64()),
            format!("{:.4}", step.t1.to_f64()),
            verdict.to_string(),
        ]));
    }
    out.footer
        .push("p and q in pixels (the back-end keeps them in 1/256 px; r is exact)".to_string());
    kept
}

/// The walk of the part kept, in the whole segment's frame, and the
/// naive walk's difference.
fn walk_lines(
    backend: &dyn LineRasterizer,
    line: &LineSetup,
    kept: &Clipped,
    viewport: PixelRect,
    out: &mut Trace,
) {
    let frame = OctantFrame::new(line.from, line.to);
    let (u, v) = frame_axes(&frame);
    out.footer.push(format!("walk: {}", frame_note(&frame)));
    let rect = walk_rect(line, kept, viewport);
    let ((lo, hi), _) = frame.ranges_within(rect);
    let (first, last) = (frame.i0.max(lo), frame.i1.min(hi));
    if rect.is_empty() || first > last {
        out.footer
            .push("the part kept chooses no on-screen pixel: nothing is walked".to_string());
    } else {
        out.footer.push(format!(
            "the whole segment's columns are {u} = {}..{}; the clipped walk keeps its frame and walks {u} = {first}..{last} only",
            frame.i0, frame.i1
        ));
        let restart = match backend.descriptor().walk {
            LineWalk::AntiAliased => format!(
                "its two rows below and above the line's exact {v} at the column's centre, weighted as the whole walk weighs them"
            ),
            LineWalk::DiamondExit | LineWalk::DiamondExitNudged => {
                "its candidates around the line, each tested against the whole segment's ends, not the clipped ones".to_string()
            }
            _ => format!(
                "row {v} = {}, the row nearest the line at the column's centre, as the whole walk has it",
                frame.nearest_row(first)
            ),
        };
        out.footer.push(format!(
            "entry column {u} = {first}: restarted with {restart}"
        ));
        if backend.descriptor().walk == LineWalk::Midpoint {
            let at = |i: i64| Bresenham::steps_within(&frame, i, i)[0];
            let (restart, start) = (at(first), at(frame.i0));
            out.footer.push(format!(
                "decision variable restarted there: d = f({u} + 1, {v} + 1/2) = {:.3} px² (the whole walk starts at {u} = {} with d = {:.3})",
                restart.d as f64 / AREA_UNIT,
                frame.i0,
                start.d as f64 / AREA_UNIT
            ));
        }
    }
    let draw = |restart| {
        let mut list = FragmentList::default();
        draw_clipped(
            backend,
            Clipper::LiangBarsky,
            restart,
            std::slice::from_ref(line),
            &LineOptions::DEFAULT,
            viewport,
            &mut list,
        );
        list.lines
            .iter()
            .map(|f| (f.x, f.y, f.coverage.to_bits()))
            .collect::<Vec<_>>()
    };
    let kept_pixels = draw(ClipRestart::KeepDecision);
    out.footer.push(format!(
        "{}: {} fragments on screen, the whole segment's",
        backend.name(),
        kept_pixels.len()
    ));
    let mut work = ClipWork::default();
    let own = Clipper::LiangBarsky.clip(line, ClipWindow::of_viewport(viewport), &mut work);
    for (restart, round, how) in [
        (
            ClipRestart::RoundEndpoints,
            ExactPoint::rounded as fn(ExactPoint) -> FixedPoint,
            "rounded to the 1/256 px grid",
        ),
        (
            ClipRestart::RoundToPixelCentres,
            ExactPoint::pixel_centre,
            "moved to their pixels' centres",
        ),
    ] {
        let naive = draw(restart);
        let moved = kept_pixels.iter().filter(|p| !naive.contains(p)).count()
            + naive.iter().filter(|p| !kept_pixels.contains(p)).count();
        let ends = own.map(|c| {
            let [a, b] = c.points(line);
            [
                if c.t0 == Param::ZERO {
                    line.from
                } else {
                    round(a)
                },
                if c.t1 == Param::ONE {
                    line.to
                } else {
                    round(b)
                },
            ]
        });
        out.footer.push(match ends {
            Some([a, b]) => format!(
                "naive ({restart}): clipped at the viewport's own edges, {how}, ({}, {}) -> ({}, {}), walked afresh: {} fragments, {moved} drawn by one walk and not the other",
                a.x.to_f64(),
                a.y.to_f64(),
                b.x.to_f64(),
                b.y.to_f64(),
                naive.len()
            ),
            None => format!(
                "naive ({restart}): nothing inside the viewport's own edges, nothing drawn: {moved} fragments lost"
            ),
        });
    }
}

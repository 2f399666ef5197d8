//! A counterexample as a self-contained HTML page: the pixel grid with
//! the primitives drawn over it, each cell coloured by what the checked
//! rasterizer did against the expected answer.

use super::judge::Finding;
use crate::teaching::grid_picture::escape;
use std::collections::BTreeSet;
use std::fmt::Write;

/// Pixels per grid cell in the page.
const CELL: f64 = 40.0;
/// The most cells drawn on a side (the shrunk target is usually small).
const MAX_SIDE: i64 = 64;
/// Cells shown around the target, so the primitives near a one-pixel
/// counterexample can be seen.
const MARGIN: i64 = 3;

/// Colours: correct fragment, extra fragment, missing fragment.
const CORRECT: &str = "#86c98a";
const EXTRA: &str = "#e0524d";
const MISSING: &str = "#f2b233";

impl Finding {
    /// The grid picture alone, as SVG: the target and a margin of three
    /// cells (grey) around it, pixel centres, the primitives as given
    /// (snapped), and each cell coloured green (drawn and expected), red
    /// (drawn and not expected, or drawn twice) or orange (expected and
    /// missing).
    pub fn to_svg(&self) -> String {
        let w = i64::from(self.case.width).min(MAX_SIDE);
        let h = i64::from(self.case.height).min(MAX_SIDE);
        let extra: BTreeSet<(i64, i64)> = self.extra.iter().map(|f| (f.x, f.y)).collect();
        let missing: BTreeSet<(i64, i64)> = self.missing.iter().map(|f| (f.x, f.y)).collect();
        let drawn: BTreeSet<(i64, i64)> = self.drawn.iter().map(|f| (f.x, f.y)).collect();
        // The view: the target and a margin around it, the margin grey.
        let m = MARGIN as f64 * CELL;
        let (pw, ph) = (w as f64 * CELL, h as f64 * CELL);
        let (vw, vh) = (pw + 2.0 * m, ph + 2.0 * m);
        let mut svg = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{vw}\" height=\"{vh}\" viewBox=\"{0} {0} {vw} {vh}\">\n<rect x=\"{0}\" y=\"{0}\" width=\"{vw}\" height=\"{vh}\" fill=\"#e8e8e8\"/>\n<rect width=\"{pw}\" height=\"{ph}\" fill=\"white\"/>\n",
            -m
        );
        for y in 0..h {
            for x in 0..w {
                let fill = if extra.contains(&(x, y)) {
                    EXTRA
                } else if missing.contains(&(x, y)) {
                    MISSING
                } else if drawn.contains(&(x, y)) {
                    CORRECT
                } else {
                    continue;
                };
                let _ = writeln!(
                    svg,
                    "<rect class=\"cell\" data-x=\"{x}\" data-y=\"{y}\" x=\"{}\" y=\"{}\" width=\"{CELL}\" height=\"{CELL}\" fill=\"{fill}\"/>",
                    x as f64 * CELL,
                    y as f64 * CELL
                );
            }
        }
        for k in -MARGIN..=w + MARGIN {
            let _ = writeln!(
                svg,
                "<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke=\"#ccc\"/>",
                k as f64 * CELL,
                -m,
                ph + m
            );
        }
        for k in -MARGIN..=h + MARGIN {
            let _ = writeln!(
                svg,
                "<line x1=\"{1}\" y1=\"{0}\" x2=\"{2}\" y2=\"{0}\" stroke=\"#ccc\"/>",
                k as f64 * CELL,
                -m,
                pw + m
            );
        }
        let _ = writeln!(
            svg,
            "<rect width=\"{pw}\" height=\"{ph}\" fill=\"none\" stroke=\"#333\" stroke-width=\"2\"/>"
        );
        for y in -MARGIN..h + MARGIN {
            for x in -MARGIN..w + MARGIN {
                let _ = writeln!(
                    svg,
                    "<circle cx=\"{}\" cy=\"{}\" r=\"1.5\" fill=\"#555\"/>",
                    (x as f64 + 0.5) * CELL,
                    (y as f64 + 0.5) * CELL
                );
            }
        }
        let to_px = |p: crate::raster::fixed::FixedPoint| {
            let (x, y) = p.to_f64();
            format!("{:.2},{:.2}", x * CELL, y * CELL)
        };
        for t in self.case.snapped_triangles() {
            let _ = writeln!(
                svg,
                "<polygon points=\"{} {} {}\" fill=\"none\" stroke=\"#1d4ed8\" stroke-width=\"1.5\"/>",
                to_px(t[0]),
                to_px(t[1]),
                to_px(t[2])
            );
        }
        // Every vertex and end point, so a triangle of zero area shows.
        let ends = self.case.snapped_triangles().into_iter().flatten();
        for p in ends.chain(self.case.snapped_lines().into_iter().flatten()) {
            let (x, y) = p.to_f64();
            let _ = writeln!(
                svg,
                "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"3.5\" fill=\"#1d4ed8\"/>",
                x * CELL,
                y * CELL
            );
        }
        for l in self.case.snapped_lines() {
            let (a, b) = (to_px(l[0]), to_px(l[1]));
            let (a, b) = (
                a.split_once(',').unwrap_or_default(),
                b.split_once(',').unwrap_or_default(),
            );
            let _ = writeln!(
                svg,
                "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#1d4ed8\" stroke-width=\"1.5\"/>",
                a.0, a.1, b.0, b.1
            );
        }
        svg.push_str("</svg>\n");
        svg
    }

    /// Where the case came from and how it failed before shrinking, as
    /// HTML paragraphs.
    fn provenance_html(&self) -> String {
        let mut out = String::new();
        if let Some(p) = &self.provenance {
            let _ = write!(
                out,
                "<p id=\"provenance\">Command: <code>{}</code><br>Seed {}, case {} (family {}).</p>",
                escape(&p.command),
                p.seed,
                p.case_index,
                escape(&p.family)
            );
        }
        if let Some(o) = &self.original_problem {
            let _ = write!(
                out,
                "<p id=\"original\">The case as generated: {}</p>",
                escape(o)
            );
        }
        out
    }

    /// The page: a legend, the problems, the diagnosis, the grid picture
    /// ([`Finding::to_svg`]) and the counterexample file.
    pub fn to_html(&self) -> String {
        let svg = self.to_svg();
        let problems: String = self
            .problems
            .iter()
            .take(20)
            .map(|p| format!("<li>{}</li>", escape(p)))
            .collect();
        let diagnosis = self
            .diagnosis
            .as_deref()
            .map(|d| format!("<p id=\"diagnosis\"><b>Diagnosis:</b> {}</p>", escape(d)))
            .unwrap_or_default();
        format!(
            r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>rasterlab check: counterexample</title>
<style>body{{font-family:sans-serif;margin:2em;max-width:80em}} .key span{{display:inline-block;width:1em;height:1em;margin:0 .3em 0 1em;vertical-align:middle}} pre{{background:#f4f4f4;padding:1em;white-space:pre-wrap}}</style>
</head><body>
<h1>Counterexample: {property}</h1>
{provenance}
<p>Target {w0}x{h0}, {n} primitive(s). {drawn} fragment(s) drawn, {expected} expected. Failure kind: <b>{kind}</b>.</p>
<p class="key"><span style="background:{CORRECT}"></span>drawn and expected <span style="background:{EXTRA}"></span>drawn, not expected (or twice) <span style="background:{MISSING}"></span>expected, missing</p>
<ul id="problems">{problems}</ul>
{diagnosis}
{svg}
<h2>The input (counterexample.txt)</h2>
<pre>{text}</pre>
</body></html>
"#,
            property = escape(&self.property.to_string()),
            kind = self.kind(),
            provenance = self.provenance_html(),
            w0 = self.case.width,
            h0 = self.case.height,
            n = self.case.len(),
            drawn = self.drawn.len(),
            expected = self.expected.len(),
            text = escape(&self.counterexample_text()),
        )
    }
}

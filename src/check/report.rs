//! A counterexample as a picture and a self-contained HTML page: the pixel
//! grid with the primitives drawn over it, each cell coloured by what the
//! checked rasterizer did against the expected answer.
//!
//! The picture follows the course's grid drawings: one cell per pixel,
//! its centre marked, pixel indices along both axes, and the triangles as
//! given (snapped to the 1/256 px grid), each in its own colour and line
//! pattern and labelled `t0`, `t1`, ..., its vertices `v0`-`v2`. A few cells of
//! margin around the target show the primitives just outside it; a
//! primitive reaching beyond the view (the huge and overflow families
//! have vertices thousands of pixels away) is clipped to it, and its
//! vertices are listed in the legend. Colours are the palette's
//! ([`crate::teaching::palette`]): correct, extra, missing, off the
//! target, pixel centres, and the triangles' colours and line patterns.

use super::case::Origin;
use super::judge::{with_samples, Finding, Property};
use crate::markup::Markup;
use crate::teaching::palette::{colour_hex, triangle_colour, triangle_mark, Legend, Role};
use std::collections::BTreeSet;

/// The most cells drawn on a side of the target (the shrunk target is
/// usually small).
const MAX_SIDE: i64 = 64;
/// Cells shown around the target, so the primitives near a one-pixel
/// counterexample can be seen.
const MARGIN: i64 = 3;
/// The picture's grid, at most, in SVG pixels on its longer side.
const GRID_SIZE: f64 = 720.0;

/// A point in pixels (screen coordinates).
type P = (f64, f64);

/// The visible rectangle, in pixels: `[x0, x1] x [y0, y1]`.
#[derive(Copy, Clone, Debug)]
struct View {
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
}

impl View {
    fn contains(self, (x, y): P) -> bool {
        (self.x0..=self.x1).contains(&x) && (self.y0..=self.y1).contains(&y)
    }

    fn clamp(self, (x, y): P) -> P {
        (x.clamp(self.x0, self.x1), y.clamp(self.y0, self.y1))
    }

    /// `polygon` clipped to the view (Sutherland and Hodgman: against
    /// each side's half-plane in turn).
    fn clip(self, polygon: &[P]) -> Vec<P> {
        // (axis, bound, keep the side >= bound)
        let sides = [
            (0, self.x0, true),
            (0, self.x1, false),
            (1, self.y0, true),
            (1, self.y1, false),
        ];
        let mut out = polygon.to_vec();
        for (axis, bound, above) in sides {
            let coord = |p: P| if axis == 0 { p.0 } else { p.1 };
            let inside = |p: P| {
                if above {
                    coord(p) >= bound
                } else {
                    coord(p) <= bound
                }
            };
            let input = std::mem::take(&mut out);
            for (i, &b) in input.iter().enumerate() {
                let a = input[(i + input.len() - 1) % input.len()];
                let cross = |a: P, b: P| {
                    let t = (bound - coord(a)) / (coord(b) - coord(a));
                    (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
                };
                match (inside(a), inside(b)) {
                    (true, true) => out.push(b),
                    (true, false) => out.push(cross(a, b)),
                    (false, true) => {
                        out.push(cross(a, b));
                        out.push(b);
                    }
                    (false, false) => {}
                }
            }
        }
        out
    }

    /// The segment `a`-`b` clipped to the view (Liang and Barsky), or
    /// `None` when none of it is seen.
    fn clip_segment(self, a: P, b: P) -> Option<(P, P)> {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for (p, q) in [
            (-dx, a.0 - self.x0),
            (dx, self.x1 - a.0),
            (-dy, a.1 - self.y0),
            (dy, self.y1 - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else if p < 0.0 {
                t0 = t0.max(q / p);
            } else {
                t1 = t1.min(q / p);
            }
        }
        (t0 <= t1).then_some((
            (a.0 + t0 * dx, a.1 + t0 * dy),
            (a.0 + t1 * dx, a.1 + t1 * dy),
        ))
    }
}

/// The mean of `points` (`None` for none).
fn centroid(points: &[P]) -> Option<P> {
    let n = points.len() as f64;
    (!points.is_empty()).then(|| {
        points
            .iter()
            .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n))
    })
}

/// A coordinate as the input writes it: up to 1/256 px, no trailing zeros.
fn number(v: f64) -> String {
    let text = format!("{v:.8}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".into()
    } else {
        text.into()
    }
}

/// One primitive of the picture: its name, its vertices in pixels.
struct Primitive {
    name: String,
    points: Vec<P>,
}

impl Finding {
    /// The primitives, as drawn: triangles `t0`, `t1`, ... (snapped),
    /// then segments `l0`, `l1`, ... (snapped; under the pixel-index
    /// convention an end names a pixel and is drawn at its centre), then
    /// each polygon's rings, `p0`, `p0 hole 1`, ... (snapped).
    fn primitives(&self) -> Vec<Primitive> {
        let centre = if matches!(self.property, Property::Line(c) if c.whole_pixels()) {
            0.5
        } else {
            0.0
        };
        let triangles = self
            .case
            .snapped_triangles()
            .into_iter()
            .enumerate()
            .map(|(i, t)| Primitive {
                name: format!("t{i}"),
                points: t.iter().map(|p| p.to_f64()).collect(),
            });
        let lines = self
            .case
            .snapped_lines()
            .into_iter()
            .enumerate()
            .map(|(i, l)| Primitive {
                name: format!("l{i}"),
                points: l
                    .iter()
                    .map(|p| {
                        let (x, y) = p.to_f64();
                        (x + centre, y + centre)
                    })
                    .collect(),
            });
        let rings = self
            .case
            .snapped_polygons()
            .into_iter()
            .enumerate()
            .flat_map(|(i, rings)| {
                rings
                    .into_iter()
                    .enumerate()
                    .map(move |(k, ring)| Primitive {
                        name: if k == 0 {
                            format!("p{i}")
                        } else {
                            format!("p{i} hole {k}")
                        },
                        points: ring.iter().map(|p| p.to_f64()).collect(),
                    })
            });
        triangles.chain(lines).chain(rings).collect()
    }

    /// The picture's legend: the cell colours, then a swatch per
    /// primitive with its vertices.
    fn legend(&self, primitives: &[Primitive]) -> Legend {
        // The vertices as the program is given them: y up from the
        // bottom edge under `--origin bottom-left`.
        let seen = |y: f64| match self.origin {
            Origin::TopLeft => y,
            Origin::BottomLeft => f64::from(self.case.height) - y,
        };
        let labels: Vec<String> = primitives
            .iter()
            .map(|p| {
                let vertices: Vec<String> = p
                    .points
                    .iter()
                    .enumerate()
                    .map(|(k, &(x, y))| format!("v{k} ({}, {})", number(x), number(seen(y))))
                    .collect();
                format!("{}: {}", p.name, vertices.join(", "))
            })
            .collect();
        Legend::new(&[
            Role::Correct,
            Role::Extra,
            Role::Missing,
            Role::OffTarget,
            Role::PixelCentre,
        ])
        .with_triangles(&labels)
    }

    /// The picture, as SVG: a caption, the target and a margin of three
    /// cells around it, pixel indices on both axes, pixel centres, each
    /// cell coloured correct (drawn and expected), extra (drawn and not
    /// expected, or drawn twice) or missing (expected, not drawn), the
    /// primitives clipped to the view with their labels, and the legend.
    pub fn to_svg(&self) -> String {
        let w = i64::from(self.case.width).min(MAX_SIDE);
        let h = i64::from(self.case.height).min(MAX_SIDE);
        let extra: BTreeSet<(i64, i64)> = self.extra.iter().map(|f| (f.x, f.y)).collect();
        let missing: BTreeSet<(i64, i64)> = self.missing.iter().map(|f| (f.x, f.y)).collect();
        let drawn: BTreeSet<(i64, i64)> = self.drawn.iter().map(|f| (f.x, f.y)).collect();
        let view = View {
            x0: -MARGIN as f64,
            y0: -MARGIN as f64,
            x1: (w + MARGIN) as f64,
            y1: (h + MARGIN) as f64,
        };
        let (columns, rows) = (w + 2 * MARGIN, h + 2 * MARGIN);
        let s = (GRID_SIZE / columns.max(rows) as f64)
            .clamp(12.0, 40.0)
            .floor();
        let (gw, gh) = (columns as f64 * s, rows as f64 * s);
        // Room for the row numbers left, the column numbers above.
        let digits = [-MARGIN, w + MARGIN - 1, h + MARGIN - 1]
            .map(|v| v.to_string().len())
            .into_iter()
            .max()
            .unwrap_or(1) as f64;
        let left = 10.0 + 7.0 * digits;
        let caption = format!(
            "Counterexample: {} ({}){}",
            with_samples(self.property.to_string(), self.case.samples),
            self.kind(),
            match self.origin {
                Origin::TopLeft => "",
                Origin::BottomLeft => ", y up: rows and vertices as the program counts them",
            }
        );
        let top = 26.0 + 18.0;
        let primitives = self.primitives();
        let legend = self.legend(&primitives);
        // Wide enough for the longest swatch (a triangle's vertices), as
        // the legend measures text: about 0.56 em a character.
        let longest = legend
            .entries
            .iter()
            .map(|e| 32.0 + e.label.chars().count() as f64 * 13.0 * 0.56)
            .fold(0.0, f64::max);
        let legend_width = (left + gw).max(420.0).max(longest + 8.0) - 8.0;
        let (legend, legend_height) = legend.to_svg(4.0, top + gh + 10.0, legend_width);
        let width = (left + gw + 8.0)
            .max(legend_width + 8.0)
            .max(caption.chars().count() as f64 * 8.4 + 12.0);
        let height = top + gh + 12.0 + legend_height;
        let mut m = Markup::new();
        m.open_svg(width, height, None).newline();
        m.element("title", &[], &caption).newline();
        m.empty(
            "path",
            &[
                ("d", &format_args!("M0 0H{width}V{height}H0Z")),
                ("fill", &"white"),
            ],
        )
        .newline();
        m.element(
            "text",
            &[
                ("class", &"caption"),
                ("x", &4),
                ("y", &18),
                ("font-size", &15),
            ],
            &caption,
        )
        .newline();
        // Pixel indices: every one while they fit, else every 2nd, 5th, ...
        let step = [1i64, 2, 5, 10, 20]
            .into_iter()
            .find(|&k| k as f64 * s >= 7.0 * digits + 4.0)
            .unwrap_or(20);
        m.open(
            "g",
            &[("class", &"axes"), ("font-size", &11), ("fill", &"#444")],
        );
        let origin = (left + MARGIN as f64 * s, top + MARGIN as f64 * s);
        for x in (-MARGIN..w + MARGIN).filter(|x| x.rem_euclid(step) == 0) {
            m.element(
                "text",
                &[
                    ("class", &"column"),
                    ("x", &(origin.0 + (x as f64 + 0.5) * s)),
                    ("y", &(top - 5.0)),
                    ("text-anchor", &"middle"),
                ],
                &x.to_string(),
            );
        }
        for y in (-MARGIN..h + MARGIN).filter(|y| y.rem_euclid(step) == 0) {
            m.element(
                "text",
                &[
                    ("class", &"row"),
                    ("x", &(left - 4.0)),
                    ("y", &(origin.1 + (y as f64 + 0.5) * s + 4.0)),
                    ("text-anchor", &"end"),
                ],
                &self.program_row(y).to_string(),
            );
        }
        m.close("g").newline();
        m.open(
            "g",
            &[
                ("class", &"grid"),
                (
                    "transform",
                    &format_args!("translate({} {})", origin.0, origin.1),
                ),
            ],
        )
        .newline();
        m.empty(
            "rect",
            &[
                ("x", &(view.x0 * s)),
                ("y", &(view.y0 * s)),
                ("width", &gw),
                ("height", &gh),
                ("fill", &Role::OffTarget.hex()),
            ],
        )
        .newline();
        m.empty(
            "rect",
            &[
                ("width", &(w as f64 * s)),
                ("height", &(h as f64 * s)),
                ("fill", &Role::Untested.hex()),
            ],
        )
        .newline();
        for y in -MARGIN..h + MARGIN {
            for x in -MARGIN..w + MARGIN {
                let role = if extra.contains(&(x, y)) {
                    Role::Extra
                } else if missing.contains(&(x, y)) {
                    Role::Missing
                } else if drawn.contains(&(x, y)) {
                    Role::Correct
                } else {
                    continue;
                };
                m.empty(
                    "rect",
                    &[
                        ("class", &"cell"),
                        ("data-x", &x),
                        ("data-y", &y),
                        ("data-role", &role.key()),
                        ("x", &(x as f64 * s)),
                        ("y", &(y as f64 * s)),
                        ("width", &s),
                        ("height", &s),
                        ("fill", &role.hex()),
                    ],
                )
                .newline();
            }
        }
        for k in -MARGIN..=w + MARGIN {
            let x = k as f64 * s;
            m.empty(
                "line",
                &[
                    ("x1", &x),
                    ("y1", &(view.y0 * s)),
                    ("x2", &x),
                    ("y2", &(view.y1 * s)),
                    ("stroke", &"#9a9a9a"),
                ],
            )
            .newline();
        }
        for k in -MARGIN..=h + MARGIN {
            let y = k as f64 * s;
            m.empty(
                "line",
                &[
                    ("x1", &(view.x0 * s)),
                    ("y1", &y),
                    ("x2", &(view.x1 * s)),
                    ("y2", &y),
                    ("stroke", &"#9a9a9a"),
                ],
            )
            .newline();
        }
        m.empty(
            "rect",
            &[
                ("class", &"target"),
                ("width", &(w as f64 * s)),
                ("height", &(h as f64 * s)),
                ("fill", &"none"),
                ("stroke", &"#444"),
                ("stroke-width", &2),
            ],
        )
        .newline();
        let centre_colour = Role::PixelCentre.hex();
        for y in -MARGIN..h + MARGIN {
            for x in -MARGIN..w + MARGIN {
                m.empty(
                    "circle",
                    &[
                        ("cx", &((x as f64 + 0.5) * s)),
                        ("cy", &((y as f64 + 0.5) * s)),
                        ("r", &1.8),
                        ("fill", &centre_colour),
                    ],
                )
                .newline();
            }
        }
        let to_svg = |(x, y): P| format!("{:.2},{:.2}", x * s, y * s);
        let mut labels = Markup::new();
        // The labels placed so far: centre and half width.
        let mut placed: Vec<(f64, f64, f64)> = Vec::new();
        let mut label = |out: &mut Markup, (x, y): P, text: &str, colour: &str, class: &str| {
            // Kept inside the view (bold DejaVu Sans at 14 px: about 9 px
            // a character), on a white halo.
            let half = text.chars().count() as f64 * 4.5 + 2.0;
            let (lo, hi) = (view.x0 * s + half, view.x1 * s - half);
            let x = if lo <= hi {
                x.clamp(lo, hi)
            } else {
                (lo + hi) / 2.0
            };
            let (top, bottom) = (view.y0 * s + 14.0, view.y1 * s - 4.0);
            let mut y = y.clamp(top, bottom.max(top));
            // A small view clamps several labels to one place: move each
            // one line down (up, at the bottom) until it overlaps none.
            let overlaps = |y: f64, placed: &[(f64, f64, f64)]| {
                placed
                    .iter()
                    .any(|&(px, py, ph)| (px - x).abs() < ph + half && (py - y).abs() < 16.0)
            };
            let step = if y + 16.0 <= bottom { 16.0 } else { -16.0 };
            for _ in 0..placed.len() {
                if !overlaps(y, &placed) {
                    break;
                }
                y += step;
            }
            placed.push((x, y, half));
            out.halo_label(class, (x, y), colour, text).newline();
        };
        for (i, p) in primitives.iter().enumerate() {
            let colour = colour_hex(triangle_colour(i));
            let dash = triangle_mark(i).dasharray();
            // The edges clipped one by one (the view's border is no edge).
            let n = p.points.len();
            let edges: Vec<(P, P)> = (0..if n >= 3 { n } else { 1 })
                .filter_map(|k| view.clip_segment(p.points[k], p.points[(k + 1) % n]))
                .collect();
            if !edges.is_empty() {
                let d: String = edges
                    .iter()
                    .map(|&(a, b)| format!("M{} L{} ", to_svg(a), to_svg(b)))
                    .collect();
                m.empty(
                    "path",
                    &[
                        ("class", &"primitive"),
                        ("data-id", &i),
                        ("d", &d.trim_end()),
                        ("fill", &"none"),
                        ("stroke", &colour),
                        ("stroke-width", &2.5),
                        // Round caps would close a pattern's gaps.
                        ("stroke-linecap", &dash.map_or("round", |_| "butt")),
                        ("stroke-dasharray", &dash.unwrap_or("none")),
                    ],
                )
                .newline();
            }
            let seen = if n >= 3 {
                view.clip(&p.points)
            } else {
                edges.iter().flat_map(|&(a, b)| [a, b]).collect()
            };
            // The name at the middle of what is seen; each vertex's away
            // from it, so the labels of triangles sharing a vertex part.
            let middle = centroid(&seen)
                .unwrap_or_else(|| view.clamp(centroid(&p.points).unwrap_or_default()));
            label(
                &mut labels,
                (middle.0 * s, middle.1 * s + 5.0),
                &p.name,
                &colour,
                "primitive-label",
            );
            // A vertex off the view is named where the way to it from the
            // middle leaves the view; vertices far off in one direction
            // share one label.
            let mut off: Vec<(P, Vec<String>)> = Vec::new();
            for (k, &v) in p.points.iter().enumerate() {
                if !view.contains(v) {
                    let at = view.clip_segment(middle, v).map_or(middle, |(_, b)| b);
                    match off
                        .iter_mut()
                        .find(|(q, _)| (q.0 - at.0).hypot(q.1 - at.1) * s < 24.0)
                    {
                        Some((_, names)) => names.push(format!("v{k}")),
                        None => off.push((at, vec![format!("v{k}")])),
                    }
                    continue;
                }
                m.empty(
                    "circle",
                    &[
                        ("class", &"vertex"),
                        ("cx", &format_args!("{:.2}", v.0 * s)),
                        ("cy", &format_args!("{:.2}", v.1 * s)),
                        ("r", &4),
                        ("fill", &colour),
                    ],
                )
                .newline();
                let (dx, dy) = (v.0 - middle.0, v.1 - middle.1);
                let len = dx.hypot(dy).max(1e-9);
                label(
                    &mut labels,
                    (v.0 * s + dx / len * 14.0, v.1 * s + dy / len * 14.0 + 5.0),
                    &format!("v{k}"),
                    &colour,
                    "vertex-label",
                );
            }
            for (at, names) in off {
                // Beside the edge that leads there, not over it.
                let (dx, dy) = (at.0 - middle.0, at.1 - middle.1);
                let len = dx.hypot(dy).max(1e-9);
                let (px, py) = if dx.abs() > 1e-9 {
                    (-dy / len * dx.signum(), dx.abs() / len)
                } else {
                    (1.0, 0.0)
                };
                label(
                    &mut labels,
                    (at.0 * s + px * 16.0, at.1 * s + py * 16.0 + 5.0),
                    &format!("{} (off view)", names.join(", ")),
                    &colour,
                    "vertex-label",
                );
            }
        }
        m.raw(&labels.finish());
        m.close("g").newline();
        m.raw(&legend);
        m.close("svg").newline();
        m.finish()
    }

    /// Where the case came from and how it failed before shrinking, as
    /// HTML paragraphs.
    fn provenance_html(&self, m: &mut Markup) {
        if let Some(p) = &self.provenance {
            m.open("p", &[("id", &"provenance")]).text("Command: ");
            m.element("code", &[], &p.command).empty("br", &[]);
            m.text(&format!(
                "Seed {}, case {} (family {}).",
                p.seed, p.case_index, p.family
            ))
            .close("p");
        }
        if let Some(o) = &self.original_problem {
            m.open("p", &[("id", &"original")])
                .text("The case as generated: ")
                .text(o)
                .close("p");
        }
    }

    /// The page: the problems, the cause (or the diagnosis), the picture
    /// ([`Finding::to_svg`], its legend in it) and the counterexample
    /// file.
    pub fn to_html(&self) -> String {
        let mut m = Markup::new();
        m.raw("<!DOCTYPE html>\n");
        m.open("html", &[("lang", &"en")]).open("head", &[]);
        m.empty("meta", &[("charset", &"utf-8")]);
        m.element("title", &[], "rasterlab check: counterexample")
            .newline();
        m.element(
            "style",
            &[],
            "body{font-family:sans-serif;margin:2em;max-width:80em} pre{background:#f4f4f4;padding:1em;white-space:pre-wrap}",
        )
        .newline();
        m.close("head").open("body", &[]).newline();
        m.element(
            "h1",
            &[],
            &format!(
                "Counterexample: {}",
                with_samples(self.property.to_string(), self.case.samples)
            ),
        )
        .newline();
        self.provenance_html(&mut m);
        m.newline();
        let expected = match self.property {
            Property::Exact(_) | Property::Line(_) | Property::Polygon(_) => {
                format!("{} expected", self.expected.len())
            }
            // Any consistent tie rule passes: there is no one answer.
            Property::Watertight | Property::CrackFree => {
                "no single answer expected (any consistent tie rule passes)".to_string()
            }
        };
        m.open("p", &[]).text(&format!(
            "Target {}x{}, {} primitive(s). {} fragment(s) drawn, {expected}. Failure kind: ",
            self.case.width,
            self.case.height,
            self.case.len(),
            self.drawn.len(),
        ));
        m.element("b", &[], &self.kind().to_string())
            .text(".")
            .close("p")
            .newline();
        m.open("ul", &[("id", &"problems")]);
        for p in self.problems.iter().take(20) {
            m.element("li", &[], p);
        }
        m.close("ul").newline();
        if let Some(note) = self.coordinates_note() {
            m.element("p", &[("id", &"coordinates")], &format!("Under --origin bottom-left {note}; the picture numbers the rows as the program does."))
                .newline();
        }
        if let Some(d) = self.diagnosis.as_deref() {
            m.open("p", &[("id", &"diagnosis")])
                .element("b", &[], "Diagnosis:")
                .text(" ")
                .text(d)
                .close("p")
                .newline();
        }
        if let Some(c) = &self.cause {
            let also = if c.also_fits.is_empty() {
                "none".to_string()
            } else {
                c.also_fits
                    .iter()
                    .map(|f| f.join(" + "))
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            m.open("table", &[("id", &"cause")]);
            m.open("tr", &[])
                .element("th", &[], "cause")
                .open("td", &[]);
            m.element("code", &[], &c.causes.join(" + "))
                .text(&format!(": {}", c.description))
                .close("td")
                .close("tr");
            for (head, value) in [
                ("evidence", c.evidence.clone()),
                (
                    "confirmed on",
                    format!(
                        "{} of {} failing case(s) as generated",
                        c.confirmed_on, c.failing_cases
                    ),
                ),
                ("also fits", also),
            ] {
                m.open("tr", &[])
                    .element("th", &[], head)
                    .element("td", &[], &value)
                    .close("tr");
            }
            m.close("table").newline();
        }
        m.raw(&self.to_svg());
        m.element("h2", &[], "The input (counterexample.txt)")
            .newline();
        m.element("pre", &[], &self.counterexample_text()).newline();
        m.close("body").close("html").newline();
        m.finish()
    }
}
